// Twin of crates/glint-core/src/cpu/shade.rs: the local model of the seed,
// I_local = E_m + I_a·k_a + Σ_j f_att,j·S_j·[ I_a,j·k_a + V_j·( I_d,j·k_d·max(N·L,0) + I_s,j·k_s·spec_j ) ]
#define_import_path glint::shade

#import glint::scene_data::{NO_CONE_VERSIN, ProbeLight, MAX_PROBE_LIGHTS, GpuLight, GpuMaterial, LIGHT_CASTS_SHADOWS, LIGHT_DIRECTIONAL, LIGHT_SPOT, SPECULAR_BLINN, SPECULAR_PHONG, SPECULAR_COOK_TORRANCE, FRESNEL_SCHLICK, NO_TEXTURE, ATTENUATION_POLYNOMIAL, ATTENUATION_INVERSE_SQUARE, SPOT_FALLOFF_SMOOTH}
#import glint::bindings::{header, materials, lights}
#import glint::ray::{Ray, ray_counts, probe, probe_active}
#import glint::ray::FAR
#import glint::intersect::all_zero
#ifdef BVH
#import glint::bvh::shadow_transmittance
#else
#import glint::intersect::shadow_transmittance
#endif
#import glint::offset::{spawn_ray, shadow_t_max, leaving_surface}
#ifdef TEXTURES
#import glint::texture::sample_texture
#endif

const MIN_LIGHT_DISTANCE: f32 = 1e-20;
const MIN_HALF_LENGTH: f32 = 1e-12;
const MIN_ATTENUATION_DENOMINATOR: f32 = 1e-6;
const MIN_GRAZING_COS: f32 = 1e-6;

// Geometry at a hit (twin of trace.rs's Surface, which lives here so shading can use it).
struct Surface {
    p: vec3<f32>,
    p_surface: vec3<f32>,
    ng: vec3<f32>,
    ns: vec3<f32>,
    uv: vec2<f32>,
    // UV_MESH, or the axis planar coordinates are taken across (relative to the frame).
    uv_origin: u32,
    // The interpolated vertex colour (white without vertex colours).
    colour: vec3<f32>,
    material: u32,
    object_id: u32,
    prim: u32,
    index: u32,
}

// x^0 = 1 (also for x = 0) and 0 for x ≤ 0 otherwise: WGSL's pow is undefined there.
fn safe_pow(x: f32, n: f32) -> f32 {
    if n == 0.0 {
        return 1.0;
    }
    if x <= 0.0 {
        return 0.0;
    }
    return pow(x, n);
}

fn attenuation_factor(att: vec4<f32>, d: f32) -> f32 {
    return 1.0 / (att.x + att.y * d + att.z * d * d);
}

// glTF's range window over 1/d² (range 0: none); d² bounded below as the polynomial's
// denominator is, so f_att ≤ 1e6.
fn inverse_square_factor(range: f32, d: f32) -> f32 {
    var window = 1.0;
    if range > 0.0 {
        if d >= range {
            window = 0.0;
        } else {
            let x = d / range;
            let x2 = x * x;
            window = 1.0 - x2 * x2;
        }
    }
    return window / max(d * d, MIN_ATTENUATION_DENOMINATOR);
}

// 1 − cos θ without its cancellation near θ = 0: sin²θ/(1 + cos θ) below 90°.
fn spot_versin(stored_axis: vec3<f32>, l: vec3<f32>) -> f32 {
    let axis = normalize(stored_axis);
    let cos_angle = dot(axis, -l);
    if cos_angle > 0.0 {
        let s = cross(axis, l);
        return dot(s, s) / (1.0 + cos_angle);
    }
    return 1.0 - cos_angle;
}

// glTF's cone: S = t², t from the outer to the inner cone, on versines; a step when they coincide.
fn smooth_spot_factor(light: GpuLight, l: vec3<f32>) -> f32 {
    let v = spot_versin(light.direction.xyz, l);
    if v > light.spot_versin_cutoff {
        return 0.0;
    }
    if v <= light.spot_versin_inner {
        return 1.0;
    }
    let t = (light.spot_versin_cutoff - v) / (light.spot_versin_cutoff - light.spot_versin_inner);
    return t * t;
}

// Cutoff 180 (versine 2) means no cone and S = 1, as OpenGL.
fn spot_factor(light: GpuLight, l: vec3<f32>) -> f32 {
    if light.spot_versin_cutoff >= NO_CONE_VERSIN {
        return 1.0;
    }
    if spot_versin(light.direction.xyz, l) > light.spot_versin_cutoff {
        return 0.0;
    }
    return safe_pow(max(dot(light.direction.xyz, -l), 0.0), light.spot_exponent);
}

struct LightSample {
    l: vec3<f32>,
    dist: f32,
    f_att: f32,
    spot: f32,
}

fn light_sample(light: GpuLight, p: vec3<f32>) -> LightSample {
    if light.kind == LIGHT_DIRECTIONAL {
        return LightSample(-light.direction.xyz, FAR, 1.0, 1.0);
    }
    let to_light = light.position.xyz - p;
    let dist = length(to_light);
    var l = vec3<f32>(0.0);
    if dist >= MIN_LIGHT_DISTANCE {
        l = to_light / dist;
    }
    var f_att = 1.0;
#ifdef ATTENUATION
    if light.attenuation_model == ATTENUATION_POLYNOMIAL {
        f_att = attenuation_factor(light.attenuation, dist);
    }
#endif
#ifdef INVERSE_SQUARE
    if light.attenuation_model == ATTENUATION_INVERSE_SQUARE {
        f_att = inverse_square_factor(light.range, dist);
    }
#endif
    var spot = 1.0;
#ifdef SPOT_LIGHTS
    if light.kind == LIGHT_SPOT {
#ifdef SMOOTH_SPOT
        if light.spot_falloff == SPOT_FALLOFF_SMOOTH {
            spot = smooth_spot_factor(light, l);
        } else {
            spot = spot_factor(light, l);
        }
#else
        spot = spot_factor(light, l);
#endif
    }
#endif
    return LightSample(l, dist, f_att, spot);
}

#ifdef COOK_TORRANCE
// Beckmann's D without its 1/π (it cancels the seed's π); sin²α = |N × H|² keeps its digits
// near α = 0, where 1 − cos²α would lose them in f32.
fn beckmann_distribution(m: f32, cos_alpha: f32, sin2_alpha: f32) -> f32 {
    let m2 = m * m;
    let cos2 = cos_alpha * cos_alpha;
    return exp(-sin2_alpha / (cos2 * m2)) / (m2 * cos2 * cos2);
}

// The unpolarised dielectric Fresnel reflectance; 1 where g² ≤ 0 (total internal reflection).
fn fresnel_exact(eta: f32, c: f32) -> f32 {
    let g2 = eta * eta + c * c - 1.0;
    if g2 <= 0.0 {
        return 1.0;
    }
    let g = sqrt(g2);
    let a = (g - c) / (g + c);
    let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    return 0.5 * a * a * (1.0 + b * b);
}

fn fresnel_schlick(eta: f32, c: f32) -> f32 {
    let r = (eta - 1.0) / (eta + 1.0);
    let f0 = r * r;
    let k = 1.0 - c;
    let k2 = k * k;
    return f0 + (1.0 - f0) * k2 * k2 * k;
}

// F·D·G / (N·V): π·(N·L) times Cook & Torrance's R_s; 0 at grazing N·V, N·H, V·H.
fn cook_torrance_term(mat: GpuMaterial, n: vec3<f32>, l: vec3<f32>, v: vec3<f32>, n_dot_l: f32) -> f32 {
    let n_dot_v = dot(n, v);
    if n_dot_v < MIN_GRAZING_COS {
        return 0.0;
    }
    let hv = normalize(l) + v;
    let len = length(hv);
    if len < MIN_HALF_LENGTH {
        return 0.0;
    }
    let h = hv / len;
    let n_dot_h = dot(n, h);
    let v_dot_h = dot(v, h);
    if n_dot_h < MIN_GRAZING_COS || v_dot_h < MIN_GRAZING_COS {
        return 0.0;
    }
    let nxh = cross(n, h);
    let d = beckmann_distribution(mat.roughness, n_dot_h, dot(nxh, nxh));
    var f: f32;
    if mat.fresnel == FRESNEL_SCHLICK {
        f = fresnel_schlick(mat.ior, v_dot_h);
    } else {
        f = fresnel_exact(mat.ior, v_dot_h);
    }
    let g = min(min(2.0 * n_dot_h * n_dot_v / v_dot_h, 2.0 * n_dot_h * n_dot_l / v_dot_h), 1.0);
    return f * d * g / n_dot_v;
}
#endif

fn specular_term(mat: GpuMaterial, n: vec3<f32>, l: vec3<f32>, v: vec3<f32>, n_dot_l: f32) -> f32 {
#ifdef PHONG
    if mat.specular_model == SPECULAR_PHONG {
        let r = 2.0 * n_dot_l * n - l;
        return safe_pow(max(dot(r, v), 0.0), mat.shininess);
    }
#endif
#ifdef COOK_TORRANCE
    if mat.specular_model == SPECULAR_COOK_TORRANCE {
        return cook_torrance_term(mat, n, l, v, n_dot_l);
    }
#endif
#ifdef BLINN
    // L normalised as on the CPU (there a directional light's f32 direction is unit only to ~3e-8).
    let h = normalize(l) + v;
    let len = length(h);
    if len < MIN_HALF_LENGTH {
        return safe_pow(0.0, mat.shininess);
    }
    return safe_pow(max(dot(n, h) / len, 0.0), mat.shininess);
#else
    return 0.0;
#endif
}

// The lobe specular_term evaluates for `mat`.
fn lobe_model(mat: GpuMaterial) -> u32 {
#ifdef PHONG
    if mat.specular_model == SPECULAR_PHONG {
        return SPECULAR_PHONG;
    }
#endif
#ifdef COOK_TORRANCE
    if mat.specular_model == SPECULAR_COOK_TORRANCE {
        return SPECULAR_COOK_TORRANCE;
    }
#endif
    return SPECULAR_BLINN;
}

// The cosine the lobe of `model` is of: R·V (Phong), else N·H with the unit half vector.
fn lobe_cosine(model: u32, n: vec3<f32>, l: vec3<f32>, v: vec3<f32>, n_dot_l: f32) -> f32 {
    if model == SPECULAR_PHONG {
        return dot(2.0 * n_dot_l * n - l, v);
    }
    let h = normalize(l) + v;
    let len = length(h);
    if len < MIN_HALF_LENGTH {
        return 0.0;
    }
    return dot(n, h) / len;
}

// The cosines behind one light's terms, for the probe (cpu::shade::LightAngles).
struct LightAngles {
    n_dot_l: f32,
    lobe_cosine: f32,
    lobe: f32,
    lobe_model: u32,
}

fn light_angles(light: GpuLight, mat: GpuMaterial, s: Surface, n: vec3<f32>, v: vec3<f32>) -> LightAngles {
    let ls = light_sample(light, s.p);
    let model = lobe_model(mat);
    // No direct term, or a light on the point itself (L is 0 there: H would be NaN).
    if ls.f_att * ls.spot == 0.0 || all(ls.l == vec3<f32>(0.0)) {
        return LightAngles(0.0, 0.0, 0.0, model);
    }
    let n_dot_l = dot(n, ls.l);
    var lobe = 0.0;
#ifdef SPECULAR
    if n_dot_l > 0.0 {
        lobe = specular_term(mat, n, ls.l, v, n_dot_l);
    }
#endif
    return LightAngles(n_dot_l, lobe_cosine(model, n, ls.l, v, n_dot_l), lobe, model);
}

// The colours of the model at a hit, after the material's textures.
struct MaterialColours {
    ka: vec3<f32>,
    kd: vec3<f32>,
    emission: vec3<f32>,
}

// A diffuse texture's colour and the vertex colour multiply k_a and k_d, an emission
// texture's E_m.
fn material_colours(mat: GpuMaterial, s: Surface) -> MaterialColours {
    var c = MaterialColours(mat.ka.xyz, mat.kd.xyz, mat.emission.xyz);
    let uv = s.uv;
    let uv_origin = s.uv_origin;
#ifdef VERTEX_COLOURS
    c.ka *= s.colour;
    c.kd *= s.colour;
#endif
#ifdef TEXTURES
    if mat.diffuse_texture != NO_TEXTURE {
        let t = sample_texture(mat.diffuse_texture, uv, uv_origin);
        c.ka *= t;
        c.kd *= t;
    }
    if mat.emission_texture != NO_TEXTURE {
        c.emission *= sample_texture(mat.emission_texture, uv, uv_origin);
    }
#endif
    return c;
}

fn light_visibility(light: GpuLight, s: Surface, ng: vec3<f32>, ls: LightSample) -> vec3<f32> {
    let n_side = select(-ng, ng, dot(ng, ls.l) >= 0.0);
    let sp = spawn_ray(s.p, s.p_surface, n_side, ls.l, leaving_surface(s.prim, s.index, s.ng, n_side));
    var dir = ls.l;
    var t_max = FAR;
    if light.kind != LIGHT_DIRECTIONAL {
        let to_light = light.position.xyz - sp.origin;
        let dist = length(to_light);
        if dist < MIN_LIGHT_DISTANCE {
            return vec3<f32>(1.0);
        }
        dir = to_light / dist;
        t_max = shadow_t_max(dist);
    }
    if t_max <= sp.t_min {
        return vec3<f32>(1.0);
    }
    ray_counts.shadow += 1u;
    return shadow_transmittance(Ray(sp.origin, dir), sp.t_min, t_max, sp.leaving);
}

// One light's terms at a hit (the pixel probe reads them; shade_local sums them).
struct LightTerm {
    f_att: f32,
    spot: f32,
    visibility: vec3<f32>,
    ambient: vec3<f32>,
    diffuse: vec3<f32>,
    specular: vec3<f32>,
    contribution: vec3<f32>,
}

fn light_term(light: GpuLight, mat: GpuMaterial, s: Surface, n: vec3<f32>, ng: vec3<f32>, v: vec3<f32>, c: MaterialColours) -> LightTerm {
    let ls = light_sample(light, s.p);
    let scale = ls.f_att * ls.spot;
    var term = LightTerm(ls.f_att, ls.spot, vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0), vec3<f32>(0.0));
    if scale == 0.0 {
        return term;
    }
#ifdef LIGHT_AMBIENT
    term.ambient = light.ambient.xyz * c.ka;
#endif
    let n_dot_l = dot(n, ls.l);
    if n_dot_l > 0.0 {
        term.visibility = vec3<f32>(1.0);
#ifdef SHADOWS
        if (light.flags & LIGHT_CASTS_SHADOWS) != 0u {
            term.visibility = light_visibility(light, s, ng, ls);
        }
#endif
        if !all_zero(term.visibility) {
            term.diffuse = light.diffuse.xyz * c.kd * n_dot_l;
#ifdef SPECULAR
            if !all_zero(mat.ks.xyz) {
                term.specular = light.specular.xyz * mat.ks.xyz * specular_term(mat, n, ls.l, v, n_dot_l);
            }
#endif
        }
    }
    term.contribution = scale * (term.ambient + term.visibility * (term.diffuse + term.specular));
    return term;
}

fn shade_local(s: Surface, n: vec3<f32>, ng: vec3<f32>, v: vec3<f32>) -> vec3<f32> {
    let mat = materials[s.material];
    let c = material_colours(mat, s);
    var emission = vec3<f32>(0.0);
#ifdef EMISSION
    emission = c.emission;
#endif
    let ambient = header.ambient.xyz * c.ka;
    var sum = vec3<f32>(0.0);
    for (var j = 0u; j < header.light_count; j++) {
#ifdef PROBE
        let shadow_rays = ray_counts.shadow;
#endif
        let term = light_term(lights[j], mat, s, n, ng, v, c);
        sum += term.contribution;
#ifdef PROBE
        if probe_active && j < MAX_PROBE_LIGHTS {
            let a = light_angles(lights[j], mat, s, n, v);
            probe.lights[j] = ProbeLight(term.f_att, term.spot, u32(ray_counts.shadow != shadow_rays), a.n_dot_l, vec4<f32>(term.visibility, 0.0), vec4<f32>(term.ambient, 0.0), vec4<f32>(term.diffuse, 0.0), vec4<f32>(term.specular, 0.0), vec4<f32>(term.contribution, 0.0), a.lobe_cosine, a.lobe, a.lobe_model, 0.0);
        }
#endif
    }
#ifdef PROBE
    if probe_active {
        probe.light_count = min(header.light_count, MAX_PROBE_LIGHTS);
        probe.emission = vec4<f32>(emission, 0.0);
        probe.ambient = vec4<f32>(ambient, 0.0);
        probe.ka = vec4<f32>(c.ka, 0.0);
        probe.kd = vec4<f32>(c.kd, 0.0);
    }
#endif
    return emission + ambient + sum;
}
