// Twin of crates/glint-core/src/cpu/bsdf.rs: the seed's glossy terms as BRDFs for the path
// tracer, each with the routine that samples its lobe and that routine's density. Local
// directions (z along the shading normal), both away from the surface; per unit k.
#define_import_path glint::bsdf

#import glint::sample::{FRAC_1_PI, cosine_hemisphere, cosine_hemisphere_pdf, power_cosine, power_cosine_pdf, reflect_about, reflected_pdf, to_world}
#import glint::shade::safe_pow
#ifdef SPECULAR
#import glint::scene_data::{GpuMaterial, SPECULAR_PHONG, SPECULAR_COOK_TORRANCE}
#endif
#ifdef COOK_TORRANCE
#import glint::scene_data::FRESNEL_SCHLICK
#import glint::sample::{beckmann_normal, beckmann_normal_pdf}
#import glint::shade::{beckmann_distribution, fresnel_exact, fresnel_schlick}
#endif

// The half vector of wo and wi, as (h, 1), or (0, 0) where they are opposite.
fn half_vector(wo: vec3<f32>, wi: vec3<f32>) -> vec4<f32> {
    let h = wo + wi;
    let len = length(h);
    if len > 1e-12 {
        return vec4<f32>(h / len, 1.0);
    }
    return vec4<f32>(0.0);
}

fn lambert_brdf(wo: vec3<f32>, wi: vec3<f32>) -> f32 {
    return select(FRAC_1_PI, 0.0, wo.z <= 0.0 || wi.z <= 0.0);
}

// 1/(2π ∫₀¹ ((1 + c)/2)^(n/2) c dc): albedo 1 at normal incidence (the CPU twin derives it).
fn blinn_normalisation(exponent: f32) -> f32 {
    let k = 0.5 * exponent;
    let integral = 4.0 * (1.0 - exp2(-(k + 2.0))) / (k + 2.0) - 2.0 * (1.0 - exp2(-(k + 1.0))) / (k + 1.0);
    return 0.5 * FRAC_1_PI / integral;
}

fn blinn_brdf(wo: vec3<f32>, wi: vec3<f32>, exponent: f32) -> f32 {
    let h = half_vector(wo, wi);
    if wo.z <= 0.0 || wi.z <= 0.0 || h.w == 0.0 {
        return 0.0;
    }
    return blinn_normalisation(exponent) * safe_pow(h.z, exponent);
}

fn phong_brdf(wo: vec3<f32>, wi: vec3<f32>, exponent: f32) -> f32 {
    if wo.z <= 0.0 || wi.z <= 0.0 {
        return 0.0;
    }
    let r = reflect_about(wi, vec3<f32>(0.0, 0.0, 1.0));
    return (exponent + 2.0) * 0.5 * FRAC_1_PI * safe_pow(dot(r, wo), exponent);
}

// n = 0: C(0) = 1/π, Lambert's lobe, drawn as Lambert's (uniform half vectors spread the weights).
fn sample_blinn(wo: vec3<f32>, u: vec2<f32>, exponent: f32) -> vec3<f32> {
    if exponent == 0.0 {
        return cosine_hemisphere(u);
    }
    return reflect_about(wo, power_cosine(u, exponent));
}

fn blinn_pdf(wo: vec3<f32>, wi: vec3<f32>, exponent: f32) -> f32 {
    if exponent == 0.0 {
        return cosine_hemisphere_pdf(wi.z);
    }
    let h = half_vector(wo, wi);
    if h.w == 0.0 {
        return 0.0;
    }
    return reflected_pdf(power_cosine_pdf(h.z, exponent), dot(wo, h.xyz));
}

// n = 0: (R·wo)⁰ = 1 above the surface, Lambert's lobe, drawn as Lambert's (a cone about R
// misses R·wi < 0).
fn sample_phong(wo: vec3<f32>, u: vec2<f32>, exponent: f32) -> vec3<f32> {
    if exponent == 0.0 {
        return cosine_hemisphere(u);
    }
    return to_world(reflect_about(wo, vec3<f32>(0.0, 0.0, 1.0)), power_cosine(u, exponent));
}

fn phong_pdf(wo: vec3<f32>, wi: vec3<f32>, exponent: f32) -> f32 {
    if exponent == 0.0 {
        return cosine_hemisphere_pdf(wi.z);
    }
    return power_cosine_pdf(dot(reflect_about(wo, vec3<f32>(0.0, 0.0, 1.0)), wi), exponent);
}

#ifdef COOK_TORRANCE
fn cook_torrance_brdf(wo: vec3<f32>, wi: vec3<f32>, m: f32, eta: f32, fresnel: u32) -> f32 {
    let h = half_vector(wo, wi);
    if wo.z <= 0.0 || wi.z <= 0.0 || h.w == 0.0 {
        return 0.0;
    }
    let o_dot_h = dot(wo, h.xyz);
    if h.z <= 0.0 || o_dot_h <= 0.0 {
        return 0.0;
    }
    let d = beckmann_distribution(m, h.z, h.x * h.x + h.y * h.y);
    var f: f32;
    if fresnel == FRESNEL_SCHLICK {
        f = fresnel_schlick(eta, o_dot_h);
    } else {
        f = fresnel_exact(eta, o_dot_h);
    }
    let g = min(min(2.0 * h.z * wo.z / o_dot_h, 2.0 * h.z * wi.z / o_dot_h), 1.0);
    return f * d * g * 0.25 * FRAC_1_PI / (wi.z * wo.z);
}

fn sample_cook_torrance(wo: vec3<f32>, u: vec2<f32>, m: f32) -> vec3<f32> {
    return reflect_about(wo, beckmann_normal(u, m));
}

fn cook_torrance_pdf(wo: vec3<f32>, wi: vec3<f32>, m: f32) -> f32 {
    let h = half_vector(wo, wi);
    if h.w == 0.0 {
        return 0.0;
    }
    return reflected_pdf(beckmann_normal_pdf(h.z, m), dot(wo, h.xyz));
}
#endif

#ifdef SPECULAR
// The glossy lobe's BRDF per unit k_s, for the material's specular model.
fn glossy_brdf(mat: GpuMaterial, wo: vec3<f32>, wi: vec3<f32>) -> f32 {
#ifdef PHONG
    if mat.specular_model == SPECULAR_PHONG {
        return phong_brdf(wo, wi, mat.shininess);
    }
#endif
#ifdef COOK_TORRANCE
    if mat.specular_model == SPECULAR_COOK_TORRANCE {
        return cook_torrance_brdf(wo, wi, mat.roughness, mat.ior, mat.fresnel);
    }
#endif
#ifdef BLINN
    return blinn_brdf(wo, wi, mat.shininess);
#else
    return 0.0;
#endif
}

fn sample_glossy(mat: GpuMaterial, wo: vec3<f32>, u: vec2<f32>) -> vec3<f32> {
#ifdef PHONG
    if mat.specular_model == SPECULAR_PHONG {
        return sample_phong(wo, u, mat.shininess);
    }
#endif
#ifdef COOK_TORRANCE
    if mat.specular_model == SPECULAR_COOK_TORRANCE {
        return sample_cook_torrance(wo, u, mat.roughness);
    }
#endif
#ifdef BLINN
    return sample_blinn(wo, u, mat.shininess);
#else
    return vec3<f32>(0.0);
#endif
}

fn glossy_pdf(mat: GpuMaterial, wo: vec3<f32>, wi: vec3<f32>) -> f32 {
#ifdef PHONG
    if mat.specular_model == SPECULAR_PHONG {
        return phong_pdf(wo, wi, mat.shininess);
    }
#endif
#ifdef COOK_TORRANCE
    if mat.specular_model == SPECULAR_COOK_TORRANCE {
        return cook_torrance_pdf(wo, wi, mat.roughness);
    }
#endif
#ifdef BLINN
    return blinn_pdf(wo, wi, mat.shininess);
#else
    return 0.0;
#endif
}
#endif
