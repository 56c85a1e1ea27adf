// Twin of crates/glint-core/src/cpu/sample.rs: the warps the path tracer draws directions and
// points with, each beside its density (per unit solid angle, on the whole sphere). Directions
// are in a local frame whose z is the lobe's axis.
#define_import_path glint::sample

const PI: f32 = 3.14159265358979;
const FRAC_1_PI: f32 = 0.318309886183791;
const FRAC_PI_4: f32 = 0.785398163397448;

// Duff et al., JCGT 2017; −0 counts as + (the CPU's sign test is the same).
fn frame_x(n: vec3<f32>) -> vec3<f32> {
    let sign = select(-1.0, 1.0, n.z >= 0.0);
    let a = -1.0 / (sign + n.z);
    let b = n.x * n.y * a;
    return vec3<f32>(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
}

fn frame_y(n: vec3<f32>) -> vec3<f32> {
    return cross(n, frame_x(n));
}

fn to_world(n: vec3<f32>, local: vec3<f32>) -> vec3<f32> {
    return frame_x(n) * local.x + frame_y(n) * local.y + n * local.z;
}

fn spherical_direction(sin_theta: f32, cos_theta: f32, phi: f32) -> vec3<f32> {
    return vec3<f32>(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta);
}

// Shirley and Chiu's concentric map of the square onto the disk.
fn concentric_disk(u: vec2<f32>) -> vec2<f32> {
    let a = 2.0 * u - vec2<f32>(1.0);
    if a.x == 0.0 && a.y == 0.0 {
        return vec2<f32>(0.0);
    }
    if abs(a.x) > abs(a.y) {
        let phi = FRAC_PI_4 * (a.y / a.x);
        return a.x * vec2<f32>(cos(phi), sin(phi));
    }
    let phi = 2.0 * FRAC_PI_4 - FRAC_PI_4 * (a.x / a.y);
    return a.y * vec2<f32>(cos(phi), sin(phi));
}

fn cosine_hemisphere(u: vec2<f32>) -> vec3<f32> {
    let d = concentric_disk(u);
    let z = sqrt(max(1.0 - dot(d, d), 0.0));
    return vec3<f32>(d.x, d.y, z);
}

fn cosine_hemisphere_pdf(cos_theta: f32) -> f32 {
    return max(cos_theta, 0.0) * FRAC_1_PI;
}

fn power_cosine(u: vec2<f32>, exponent: f32) -> vec3<f32> {
    let cos_theta = pow(1.0 - u.x, 1.0 / (exponent + 1.0));
    let sin_theta = sqrt(max(1.0 - cos_theta * cos_theta, 0.0));
    return spherical_direction(sin_theta, cos_theta, 2.0 * PI * u.y);
}

fn power_cosine_pdf(cos_theta: f32, exponent: f32) -> f32 {
    if cos_theta <= 0.0 {
        return 0.0;
    }
    return (exponent + 1.0) * 0.5 * FRAC_1_PI * pow(cos_theta, exponent);
}

fn beckmann_normal(u: vec2<f32>, m: f32) -> vec3<f32> {
    let tan2 = -m * m * log(1.0 - u.x);
    let cos_theta = 1.0 / sqrt(1.0 + tan2);
    let sin_theta = sqrt(max(1.0 - cos_theta * cos_theta, 0.0));
    return spherical_direction(sin_theta, cos_theta, 2.0 * PI * u.y);
}

fn beckmann_normal_pdf(cos_theta: f32, m: f32) -> f32 {
    if cos_theta <= 0.0 {
        return 0.0;
    }
    let cos2 = cos_theta * cos_theta;
    let tan2 = max(1.0 - cos2, 0.0) / cos2;
    return exp(-tan2 / (m * m)) * FRAC_1_PI / (m * m * cos2 * cos_theta);
}

fn reflect_about(v: vec3<f32>, h: vec3<f32>) -> vec3<f32> {
    return 2.0 * dot(v, h) * h - v;
}

fn reflected_pdf(half_pdf: f32, v_dot_h: f32) -> f32 {
    if v_dot_h == 0.0 {
        return 0.0;
    }
    return half_pdf / (4.0 * abs(v_dot_h));
}

fn cone_versin(sin2_max: f32) -> f32 {
    return sin2_max / (1.0 + sqrt(max(1.0 - sin2_max, 0.0)));
}

fn uniform_cone(u: vec2<f32>, versin_max: f32) -> vec3<f32> {
    let versin = u.x * versin_max;
    let cos_theta = 1.0 - versin;
    let sin_theta = sqrt(max(versin * (2.0 - versin), 0.0));
    return spherical_direction(sin_theta, cos_theta, 2.0 * PI * u.y);
}

fn uniform_cone_pdf(versin_max: f32) -> f32 {
    return 1.0 / (2.0 * PI * versin_max);
}

fn uniform_sphere(u: vec2<f32>) -> vec3<f32> {
    let z = 1.0 - 2.0 * u.x;
    return spherical_direction(sqrt(max(1.0 - z * z, 0.0)), z, 2.0 * PI * u.y);
}

fn uniform_sphere_pdf() -> f32 {
    return 0.25 * FRAC_1_PI;
}

// Heitz 2019's low-distortion map: barycentrics of b and c, uniform in area.
fn uniform_triangle(u: vec2<f32>) -> vec2<f32> {
    if u.y > u.x {
        let b0 = 0.5 * u.x;
        return vec2<f32>(b0, u.y - b0);
    }
    let b1 = 0.5 * u.y;
    return vec2<f32>(u.x - b1, b1);
}

fn area_to_solid_angle(pdf_area: f32, distance: f32, cos_at_light: f32) -> f32 {
    if cos_at_light == 0.0 {
        return 0.0;
    }
    return pdf_area * distance * distance / abs(cos_at_light);
}

// The largest density whose square the power heuristic forms: f32's square overflows at 1.8e19,
// which a small emitter's density reaches from far away, and ∞/∞ is NaN.
const MAX_SQUARED_PDF: f32 = 1e18;

// Veach's power heuristic, β = 2; beyond MAX_SQUARED_PDF from the ratio of the densities.
fn power_heuristic(pdf: f32, other: f32) -> f32 {
    if max(pdf, other) > MAX_SQUARED_PDF {
        let r = min(pdf, other) / max(pdf, other);
        let r2 = r * r;
        return select(r2 / (1.0 + r2), 1.0 / (1.0 + r2), pdf >= other);
    }
    let a = pdf * pdf;
    let b = other * other;
    return select(a / (a + b), 0.0, a + b == 0.0);
}
