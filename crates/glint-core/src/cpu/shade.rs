//! CPU twin of `shaders/shade.wgsl`: the local Phong/Blinn model of the seed (spec_j one of
//! Blinn's, Phong's or Cook & Torrance's lobes),
//!
//! I_local = E_m + I_a·k_a + Σ_j f_att,j·S_j·[ I_a,j·k_a + V_j·( I_d,j·k_d·max(N·L,0) + I_s,j·k_s·spec_j ) ]

use glam::{DVec2, DVec3};

use super::FAR;
use super::intersect::{Prim, all_zero};
use super::offset::{leaving_surface, shadow_t_max, spawn_ray};
use super::texture::sample_texture;
use super::walk::shadow_transmittance;
use super::{Ray, RayCounts, TraceContext, v3};
pub use glint_scene::MIN_ATTENUATION_DENOMINATOR;
use glint_scene::{AttenuationModel, Fresnel, LightKind, SpecularModel, SpotFalloff};
use glint_types::layout::NO_CONE_VERSIN;
use glint_types::layout::{GpuLight, GpuMaterial, LIGHT_CASTS_SHADOWS, NO_TEXTURE, feature};
use glint_types::{LightTags, MaterialTags};

/// Geometry at a hit: point, unit geometric and shading normals as stored (not yet turned
/// towards the ray), material and object.
#[derive(Clone, Copy, Debug)]
pub struct Surface {
    /// o + t·d, where shading happens.
    pub p: DVec3,
    /// The hit point recomputed from the surface itself (robust epsilon mode only, else p):
    /// its error does not grow with the distance the ray travelled, as o + t·d's does.
    pub p_surface: DVec3,
    pub ng: DVec3,
    pub ns: DVec3,
    /// Texture coordinates (zero when the scene has no textures).
    pub uv: DVec2,
    /// `UV_MESH`, or the axis planar coordinates are taken across (relative to the frame).
    pub uv_origin: u32,
    /// The interpolated vertex colour (white without vertex colours).
    pub colour: DVec3,
    pub material: u32,
    pub object_id: u32,
    /// The primitive hit (`skip_convex` does not test it again from here).
    pub prim: Prim,
    pub index: u32,
}

/// A light closer than this to the shaded point gives no direct term (its direction is
/// undefined); it still gives its ambient term.
pub const MIN_LIGHT_DISTANCE: f64 = 1e-20;

/// Below this |L + V| the half vector is undefined (L = −V) and the Blinn lobe takes its value
/// at H·N = 0: 0, or 1 for n = 0 (x^0 = 1, as everywhere else).
pub const MIN_HALF_LENGTH: f64 = 1e-12;

/// x^n with the conventions the model needs and `pow` does not guarantee on the GPU:
/// x^0 = 1 (also for x = 0), and 0 for x ≤ 0 otherwise.
pub fn safe_pow(x: f64, n: f64) -> f64 {
    if n == 0.0 {
        1.0
    } else if x <= 0.0 {
        0.0
    } else {
        x.powf(n)
    }
}

/// f_att = 1 / (c + l·d + q·d²).
pub fn attenuation_factor(att: [f32; 4], d: f64) -> f64 {
    1.0 / (f64::from(att[0]) + f64::from(att[1]) * d + f64::from(att[2]) * d * d)
}

/// The inverse-square model: f_att = w / max(d², MIN_ATTENUATION_DENOMINATOR) with the range
/// window w = clamp(1 − (d/range)⁴, 0, 1) that KHR_lights_punctual recommends (not squared, as
/// in the glTF text and Khronos' sample renderer), w = 1 for range 0 (none). The window is
/// written as its two cases (0 from d = range on, 1 − x⁴ with x < 1 before), which is the
/// clamp without one. The bound on d² caps f_att at 1e6, as validation caps the polynomial's.
pub fn inverse_square_factor(range: f32, d: f64) -> f64 {
    let range = f64::from(range);
    let mut window = 1.0;
    if range > 0.0 {
        if d >= range {
            window = 0.0;
        } else {
            let x = d / range;
            let x2 = x * x;
            window = 1.0 - x2 * x2;
        }
    }
    window / (d * d).max(MIN_ATTENUATION_DENOMINATOR)
}

/// 1 − cos θ, θ the angle between the spot axis and −L, without forming 1 − cos θ: for a small
/// cone cos θ ≈ 1 and the difference would keep only ulp(1)/(1 − cos θ) of its digits (4e-4 at
/// 1° in f32). Below 90° it is sin²θ / (1 + cos θ), sin²θ = |axis × L|² (the vectors' lengths
/// enter as relative errors only); past 90° 1 − cos θ has no cancellation. The stored axis is
/// unit only to f32's 6e-8, which would enter v relatively: it is normalised first.
pub fn spot_versin(axis: DVec3, l: DVec3) -> f64 {
    let axis = axis.normalize();
    let cos_angle = axis.dot(-l);
    if cos_angle > 0.0 { axis.cross(l).length_squared() / (1.0 + cos_angle) } else { 1.0 - cos_angle }
}

/// S = max(L_N·(−L), 0)^s inside the cone, 0 outside; 1 everywhere for cutoff 180 (stored as
/// versine 2), as OpenGL, so that such a spot equals a point light. The cone is tested on
/// versines (`spot_versin`), both formed without cancellation.
pub fn spot_factor(light: &GpuLight, l: DVec3) -> f64 {
    if light.spot_versin_cutoff >= NO_CONE_VERSIN {
        return 1.0;
    }
    let axis = v3(light.direction);
    if spot_versin(axis, l) > f64::from(light.spot_versin_cutoff) {
        return 0.0;
    }
    safe_pow(axis.dot(-l).max(0.0), f64::from(light.spot_exponent))
}

/// The smooth (glTF) cone: S = t², t = saturate((cos θ − cos outer) / (cos inner − cos outer)),
/// cos θ = L_N·(−L), the KHR_lights_punctual reference — formed on versines, (v_outer − v) /
/// (v_outer − v_inner), the same ratio without the cancellation of cosines near 1. Written as
/// its three cases, so that it never divides by zero: 0 outside the outer cone, 1 inside the
/// inner one (both closed), the ramp between. With inner = outer it is the step the ramp tends
/// to: 1 inside the closed cone, 0 outside.
pub fn smooth_spot_factor(light: &GpuLight, l: DVec3) -> f64 {
    let v = spot_versin(v3(light.direction), l);
    let v_outer = f64::from(light.spot_versin_cutoff);
    let v_inner = f64::from(light.spot_versin_inner);
    if v > v_outer {
        return 0.0;
    }
    if v <= v_inner {
        return 1.0;
    }
    let t = (v_outer - v) / (v_outer - v_inner);
    t * t
}

/// Direction and distance to a light from `p`, with its attenuation and spot factors.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// Unit vector from p towards the light.
    pub l: DVec3,
    pub dist: f64,
    pub f_att: f64,
    pub spot: f64,
}

pub fn light_sample(ctx: &TraceContext, light: &GpuLight, tags: LightTags, p: DVec3) -> LightSample {
    let is_spot = match tags.kind {
        LightKind::Directional => return LightSample { l: -v3(light.direction), dist: FAR, f_att: 1.0, spot: 1.0 },
        LightKind::Point => false,
        LightKind::Spot => true,
    };
    let to_light = v3(light.position) - p;
    let dist = to_light.length();
    let l = if dist >= MIN_LIGHT_DISTANCE { to_light / dist } else { DVec3::ZERO };
    let f_att = match tags.attenuation {
        AttenuationModel::Polynomial if ctx.has(feature::ATTENUATION) => attenuation_factor(light.attenuation, dist),
        AttenuationModel::InverseSquare if ctx.has(feature::INVERSE_SQUARE) => inverse_square_factor(light.range, dist),
        AttenuationModel::Polynomial | AttenuationModel::InverseSquare => 1.0,
    };
    let spot = if ctx.has(feature::SPOT_LIGHTS) && is_spot {
        match tags.falloff {
            SpotFalloff::Smooth if ctx.has(feature::SMOOTH_SPOT) => smooth_spot_factor(light, l),
            SpotFalloff::Smooth | SpotFalloff::Power => spot_factor(light, l),
        }
    } else {
        1.0
    };
    LightSample { l, dist, f_att, spot }
}

/// N·V, N·H and V·H below this give no Cook–Torrance lobe. Its limit at grazing angles is
/// finite (G/(N·V) → 2(N·H)/(V·H)), but f32 would divide by numbers near 0 there; the band
/// cut off is a millionth of a radian wide, and for N·H below it D is 0 in f32 and f64 alike.
pub const MIN_GRAZING_COS: f64 = 1e-6;

/// The Beckmann distribution of Cook & Torrance (1982), without the 1/π that normalises it
/// (docs/scene-format.md: that π cancels the seed's): D = exp(−tan²α/m²) / (m²·cos⁴α), α the angle
/// between N and H, given as cos α and sin²α = |N × H|² (which keeps its digits near α = 0,
/// where 1 − cos²α would lose them in f32).
pub fn beckmann_distribution(m: f64, cos_alpha: f64, sin2_alpha: f64) -> f64 {
    let m2 = m * m;
    let cos2 = cos_alpha * cos_alpha;
    (-sin2_alpha / (cos2 * m2)).exp() / (m2 * cos2 * cos2)
}

/// The unpolarised dielectric Fresnel reflectance at c = V·H for the relative index η (Cook &
/// Torrance's form): F = ½ (g−c)²/(g+c)² · [1 + (c(g+c)−1)²/(c(g−c)+1)²], g = √(η² + c² − 1),
/// and 1 where η² + c² − 1 ≤ 0 (total internal reflection, for η < 1; the formula's own value
/// at 0). With g > 0 and c > 0 neither denominator is 0.
pub fn fresnel_exact(eta: f64, c: f64) -> f64 {
    let g2 = eta * eta + c * c - 1.0;
    if g2 <= 0.0 {
        return 1.0;
    }
    let g = g2.sqrt();
    let a = (g - c) / (g + c);
    let b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    0.5 * a * a * (1.0 + b * b)
}

/// Schlick's approximation of `fresnel_exact`: F0 + (1 − F0)(1 − c)⁵, F0 = ((η − 1)/(η + 1))².
pub fn fresnel_schlick(eta: f64, c: f64) -> f64 {
    let r = (eta - 1.0) / (eta + 1.0);
    let f0 = r * r;
    let k = 1.0 - c;
    let k2 = k * k;
    f0 + (1.0 - f0) * k2 * k2 * k
}

/// The Cook–Torrance lobe in the seed's place of (N·H)^n: spec = F·D·G / (N·V), which is π·(N·L)
/// times the paper's R_s = F·D·G / (π (N·L)(N·V)) (docs/scene-format.md), with the V-groove term
/// G = min(1, 2(N·H)(N·V)/(V·H), 2(N·H)(N·L)/(V·H)). 0 where N·V, N·H or V·H is below
/// `MIN_GRAZING_COS`, or where the half vector is undefined.
pub fn cook_torrance_term(mat: &GpuMaterial, fresnel: Fresnel, n: DVec3, l: DVec3, v: DVec3, n_dot_l: f64) -> f64 {
    let n_dot_v = n.dot(v);
    if n_dot_v < MIN_GRAZING_COS {
        return 0.0;
    }
    let h = l.normalize() + v;
    let len = h.length();
    if len < MIN_HALF_LENGTH {
        return 0.0;
    }
    let h = h / len;
    let n_dot_h = n.dot(h);
    let v_dot_h = v.dot(h);
    if n_dot_h < MIN_GRAZING_COS || v_dot_h < MIN_GRAZING_COS {
        return 0.0;
    }
    let d = beckmann_distribution(f64::from(mat.roughness), n_dot_h, n.cross(h).length_squared());
    let eta = f64::from(mat.ior);
    let f = match fresnel {
        Fresnel::Exact => fresnel_exact(eta, v_dot_h),
        Fresnel::Schlick => fresnel_schlick(eta, v_dot_h),
    };
    let g = (2.0 * n_dot_h * n_dot_v / v_dot_h).min(2.0 * n_dot_h * n_dot_l / v_dot_h).min(1.0);
    f * d * g / n_dot_v
}

/// The specular lobe: max(N·H, 0)^n (Blinn), max(R·V, 0)^n (Phong) or Cook–Torrance's
/// F·D·G/(N·V); 0 where N·L ≤ 0.
pub fn specular_term(
    ctx: &TraceContext,
    mat: &GpuMaterial,
    tags: MaterialTags,
    n: DVec3,
    l: DVec3,
    v: DVec3,
    n_dot_l: f64,
) -> f64 {
    let shininess = f64::from(mat.shininess);
    match tags.specular {
        SpecularModel::Phong if ctx.has(feature::PHONG) => {
            let r = 2.0 * n_dot_l * n - l;
            return safe_pow(r.dot(v).max(0.0), shininess);
        }
        SpecularModel::CookTorrance if ctx.has(feature::COOK_TORRANCE) => {
            return cook_torrance_term(mat, tags.fresnel, n, l, v, n_dot_l);
        }
        SpecularModel::Phong | SpecularModel::CookTorrance | SpecularModel::Blinn => {}
    }
    // L normalised here: a directional light's L is its stored f32 direction, unit only to
    // ~3e-8, and where L ≈ −V that length error, not the direction, would set H's direction.
    let h = l.normalize() + v;
    let len = h.length();
    if len < MIN_HALF_LENGTH {
        return safe_pow(0.0, shininess);
    }
    safe_pow((n.dot(h) / len).max(0.0), shininess)
}

/// The lobe `specular_term` evaluates for a material of `tags`.
pub fn lobe_model(ctx: &TraceContext, tags: MaterialTags) -> SpecularModel {
    match tags.specular {
        SpecularModel::Phong if ctx.has(feature::PHONG) => SpecularModel::Phong,
        SpecularModel::CookTorrance if ctx.has(feature::COOK_TORRANCE) => SpecularModel::CookTorrance,
        SpecularModel::Phong | SpecularModel::CookTorrance | SpecularModel::Blinn => SpecularModel::Blinn,
    }
}

/// The cosine the lobe of `model` is of: R·V (Phong), else N·H with the unit half vector (0
/// where H is undefined, as in `specular_term`).
pub fn lobe_cosine(model: SpecularModel, n: DVec3, l: DVec3, v: DVec3, n_dot_l: f64) -> f64 {
    match model {
        SpecularModel::Phong => return (2.0 * n_dot_l * n - l).dot(v),
        SpecularModel::CookTorrance | SpecularModel::Blinn => {}
    }
    let h = l.normalize() + v;
    let len = h.length();
    if len < MIN_HALF_LENGTH {
        return 0.0;
    }
    n.dot(h) / len
}

/// The angles behind `light`'s terms at `s` (`LightAngles`); all 0 where the light gives no
/// direct term (f_att·S = 0, as `light_term` stops there, or the light closer than
/// `MIN_LIGHT_DISTANCE`, whose direction is undefined).
pub fn light_angles(
    ctx: &TraceContext,
    light: &GpuLight,
    tags: LightTags,
    mat: &GpuMaterial,
    s: &Surface,
    n: DVec3,
    v: DVec3,
) -> LightAngles {
    let ls = light_sample(ctx, light, tags, s.p);
    let material_tags = ctx.material_tags[s.material as usize];
    let lobe_model = lobe_model(ctx, material_tags);
    // No direct term, or a light on the point itself (L is 0 there: H would be NaN).
    if ls.f_att * ls.spot == 0.0 || ls.l == DVec3::ZERO {
        return LightAngles { lobe_model, ..LightAngles::default() };
    }
    let n_dot_l = n.dot(ls.l);
    let lobe = if n_dot_l > 0.0 && ctx.has(feature::SPECULAR) {
        specular_term(ctx, mat, material_tags, n, ls.l, v, n_dot_l)
    } else {
        0.0
    };
    LightAngles { n_dot_l, lobe_cosine: lobe_cosine(lobe_model, n, ls.l, v, n_dot_l), lobe, lobe_model }
}

/// The colours of the model at a hit, after the material's textures.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MaterialColours {
    pub ka: DVec3,
    pub kd: DVec3,
    pub emission: DVec3,
}

/// k_a, k_d and E_m at surface `s`: a diffuse texture's colour and the vertex colour multiply
/// k_a and k_d (POV-Ray's pigment, OpenGL's ambient-and-diffuse colour material, glTF's
/// COLOR_0 times its base colour), an emission texture's multiplies E_m.
pub fn material_colours(ctx: &TraceContext, mat: &GpuMaterial, s: &Surface) -> MaterialColours {
    let mut c = MaterialColours { ka: v3(mat.ka), kd: v3(mat.kd), emission: v3(mat.emission) };
    let (uv, uv_origin) = (s.uv, s.uv_origin);
    if ctx.has(feature::VERTEX_COLOURS) {
        c.ka *= s.colour;
        c.kd *= s.colour;
    }
    if ctx.has(feature::TEXTURES) {
        if mat.diffuse_texture != NO_TEXTURE {
            let t = sample_texture(ctx, mat.diffuse_texture, uv, uv_origin);
            c.ka *= t;
            c.kd *= t;
        }
        if mat.emission_texture != NO_TEXTURE {
            c.emission *= sample_texture(ctx, mat.emission_texture, uv, uv_origin);
        }
    }
    c
}

/// Visibility V_j of a light from the hit: 1 unobstructed, 0 behind an opaque occluder, the
/// product of crossed k_t behind transmissive ones.
pub fn light_visibility(
    ctx: &TraceContext,
    light: &GpuLight,
    kind: LightKind,
    s: &Surface,
    ng: DVec3,
    ls: &LightSample,
    counts: &mut RayCounts,
) -> DVec3 {
    let n_side = if ng.dot(ls.l) >= 0.0 { ng } else { -ng };
    let sp = spawn_ray(ctx, s.p, s.p_surface, n_side, ls.l, leaving_surface(s.prim, s.index, s.ng, n_side));
    let (origin, t_min) = (sp.origin, sp.t_min);
    let (dir, t_max) = match kind {
        LightKind::Directional => (ls.l, FAR),
        LightKind::Point | LightKind::Spot => {
            let to_light = v3(light.position) - origin;
            let dist = to_light.length();
            if dist < MIN_LIGHT_DISTANCE {
                return DVec3::ONE;
            }
            (to_light / dist, shadow_t_max(ctx, dist))
        }
    };
    if t_max <= t_min {
        return DVec3::ONE;
    }
    counts.shadow += 1;
    shadow_transmittance(ctx, &Ray { origin, dir }, t_min, t_max, &sp.leaving)
}

/// One light's share at the probed hit, with every factor of the model kept apart.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LightTerm {
    pub f_att: f64,
    pub spot: f64,
    /// V_j per channel (filtered shadows).
    pub visibility: DVec3,
    /// I_a,j·k_a.
    pub ambient: DVec3,
    /// I_d,j·k_d·max(N·L, 0).
    pub diffuse: DVec3,
    /// I_s,j·k_s·spec_j.
    pub specular: DVec3,
    /// f_att·S·[ambient + V·(diffuse + specular)], what the light adds.
    pub contribution: DVec3,
    /// Whether a shadow ray was traced to the light (V was not simply taken as 1 or left 0).
    pub shadow_ray: bool,
    /// The angles behind the diffuse and specular terms (`light_angles`).
    pub angles: LightAngles,
}

/// The cosines behind one light's terms at a hit, for the pixel probe: N·L before it is
/// clamped at 0 (why a light behind the surface adds no diffuse), the cosine the specular lobe
/// is of and the lobe spec_j itself, which the model takes as 0 where N·L ≤ 0.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LightAngles {
    pub n_dot_l: f64,
    /// R·V for Phong's lobe, N·H with the unit half vector for Blinn's and Cook–Torrance's.
    pub lobe_cosine: f64,
    pub lobe: f64,
    /// The lobe evaluated (the material's, as `specular_term` dispatches it).
    pub lobe_model: SpecularModel,
}

/// The radiance of a camera ray split into the terms of the model at its first hit.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Breakdown {
    /// Object id of the first hit, `NO_HIT` for background.
    pub object_id: u32,
    pub material: u32,
    pub t: f64,
    pub point: DVec3,
    /// Shading normal turned towards the viewer.
    pub normal: DVec3,
    /// E_m.
    pub emission: DVec3,
    /// I_a·k_a.
    pub ambient: DVec3,
    /// k_a and k_d at the hit, after the texture and the vertex colour (the material's own without them).
    pub ka: DVec3,
    pub kd: DVec3,
    /// Every light's terms, in light order.
    pub lights: Vec<LightTerm>,
    /// k_r·I_r (including the k_t share under total internal reflection).
    pub reflected: DVec3,
    /// k_t·I_t.
    pub transmitted: DVec3,
    /// The pixel radiance: the sum of all the above (or the background).
    pub total: DVec3,
}

impl Breakdown {
    /// Sum of the listed terms, to check against `total`.
    pub fn sum_of_terms(&self) -> DVec3 {
        self.emission
            + self.ambient
            + self.lights.iter().map(|l| l.contribution).sum::<DVec3>()
            + self.reflected
            + self.transmitted
    }
}

/// One light's terms at a hit, each factor kept apart (the pixel probe shows them).
pub fn light_term(
    ctx: &TraceContext,
    light: &GpuLight,
    tags: LightTags,
    mat: &GpuMaterial,
    s: &Surface,
    n: DVec3,
    ng: DVec3,
    v: DVec3,
    c: &MaterialColours,
    counts: &mut RayCounts,
) -> LightTerm {
    let ls = light_sample(ctx, light, tags, s.p);
    let scale = ls.f_att * ls.spot;
    let mut term = LightTerm { f_att: ls.f_att, spot: ls.spot, ..LightTerm::default() };
    if scale == 0.0 {
        return term;
    }
    if ctx.has(feature::LIGHT_AMBIENT) {
        term.ambient = v3(light.ambient) * c.ka;
    }
    let n_dot_l = n.dot(ls.l);
    if n_dot_l > 0.0 {
        term.visibility = if ctx.has(feature::SHADOWS) && light.flags & LIGHT_CASTS_SHADOWS != 0 {
            light_visibility(ctx, light, tags.kind, s, ng, &ls, counts)
        } else {
            DVec3::ONE
        };
        if !all_zero(term.visibility) {
            term.diffuse = v3(light.diffuse) * c.kd * n_dot_l;
            if ctx.has(feature::SPECULAR) && !all_zero(v3(mat.ks)) {
                let tags = ctx.material_tags[s.material as usize];
                term.specular = v3(light.specular) * v3(mat.ks) * specular_term(ctx, mat, tags, n, ls.l, v, n_dot_l);
            }
        }
    }
    term.contribution = scale * (term.ambient + term.visibility * (term.diffuse + term.specular));
    term
}

/// The local model at a hit. `n` is the shading normal and `ng` the geometric normal, both
/// turned towards the incoming ray; `v` points back along it.
pub fn shade_local(
    ctx: &TraceContext,
    s: &Surface,
    n: DVec3,
    ng: DVec3,
    v: DVec3,
    counts: &mut RayCounts,
    mut probe: Option<&mut Breakdown>,
) -> DVec3 {
    let scene = ctx.scene;
    let mat = &scene.materials[s.material as usize];
    let c = material_colours(ctx, mat, s);
    let emission = if ctx.has(feature::EMISSION) { c.emission } else { DVec3::ZERO };
    let ambient = v3(scene.header.ambient) * c.ka;
    let mut sum = DVec3::ZERO;
    for (light, &tags) in scene.lights.iter().zip(&ctx.light_tags) {
        let shadow_rays = counts.shadow;
        let term = light_term(ctx, light, tags, mat, s, n, ng, v, &c, counts);
        sum += term.contribution;
        if let Some(b) = probe.as_deref_mut() {
            let angles = light_angles(ctx, light, tags, mat, s, n, v);
            b.lights.push(LightTerm { shadow_ray: counts.shadow != shadow_rays, angles, ..term });
        }
    }
    if let Some(b) = probe {
        b.emission = emission;
        b.ambient = ambient;
        b.ka = c.ka;
        b.kd = c.kd;
    }
    emission + ambient + sum
}
