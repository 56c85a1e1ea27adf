//! The glTF light options (inverse-square attenuation with and without range, the smooth spot
//! cone, with distinct and with equal cones) on the GPU against the CPU reference: the image
//! with the parity thresholds of parity.rs, the probe's f_att and S term by term, and the
//! specialised shader against the full one.

use glint_core::FlatScene;
use glint_core::probe_pixel;
use glint_io::parse_scene;
use glint_types::layout::{NO_HIT, feature};

use super::support::{compare_and_keep, cpu, gpu_or_skip, gpu_render, log_errors, within_parity, write_failure_images};

/// A floor, two spheres and a mirror lit by glTF-style lights beside OpenGL-style ones.
const SCENE: &str = r#"
[render]
max_depth = 5

[camera]
position = [0.0, 3.5, -7.0]
look_at = [0.0, 0.5, 0.0]
fov_y = 50.0

[world]
ambient = 0.02

[materials.floor]
ka = 0.5
kd = 0.7
checker = { kd = 0.35, size = 1.0 }

[materials.plastic]
ka = 0.3
kd = [0.8, 0.3, 0.2]
ks = 0.5
shininess = 60.0

[materials.mirror]
kd = 0.05
ks = 0.2
kr = 0.8

# inverse square with glTF's range window
[[lights]]
type = "point"
position = [-2.5, 3.0, -1.0]
diffuse = 12.0
ambient = 0.5
attenuation = { model = "inverse_square", range = 9.0 }

# plain inverse square
[[lights]]
type = "point"
position = [2.5, 2.5, 1.0]
diffuse = [6.0, 5.0, 4.0]
attenuation = { model = "inverse_square" }

# glTF spot: smooth cone, windowed inverse square
[[lights]]
type = "spot"
position = [0.0, 5.0, 0.5]
direction = [0.0, -1.0, -0.1]
diffuse = [20.0, 20.0, 30.0]
falloff = "smooth"
inner_cone = 12.0
outer_cone = 28.0
attenuation = { model = "inverse_square", range = 12.0 }

# smooth spot with equal cones (a hard cone), polynomial attenuation
[[lights]]
type = "spot"
position = [3.0, 4.0, -2.0]
direction = [-2.0, -4.0, 3.0]
diffuse = [0.8, 1.0, 0.6]
falloff = "smooth"
inner_cone = 15.0
outer_cone = 15.0
attenuation = { c = 1.0, q = 0.02 }

# OpenGL spot beside them
[[lights]]
type = "spot"
position = [-3.0, 4.0, 2.0]
direction = [3.0, -4.0, -1.0]
diffuse = 0.7
exponent = 8.0
cutoff = 25.0

[[objects]]
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "floor"

[[objects]]
type = "sphere"
center = [-1.2, 0.8, 0.0]
radius = 0.8
material = "plastic"

[[objects]]
type = "sphere"
center = [1.2, 0.8, 0.5]
radius = 0.8
material = "mirror"
"#;

fn flat(spp: u32) -> FlatScene {
    let (desc, warnings) = parse_scene(SCENE, std::path::Path::new("gltf-lights.toml")).expect("scene parses");
    assert!(warnings.is_empty(), "{warnings:?}");
    let mut s = desc.render.clone();
    (s.width, s.height, s.spp) = (160, 120, spp);
    FlatScene::build(&desc, &s)
}

#[test]
fn gltf_lights_match_the_cpu_reference() {
    let tracer = gpu_or_skip!();
    for spp in [1, 4] {
        let flat = flat(spp);
        let both = feature::INVERSE_SQUARE | feature::SMOOTH_SPOT | feature::ATTENUATION;
        assert_eq!(flat.header.features & both, both, "the scene must use every attenuation model");
        let c = cpu(&flat);
        let g = gpu_render(tracer, &flat, true);
        let name = format!("gltf-lights-spp{spp}");
        let (e, base) = compare_and_keep("parity", &name, &c, &g);
        log_errors(&name, &e, g.status);
        let ok = within_parity(&e, g.status);
        if !ok {
            write_failure_images(&base, &c, &g);
        }
        assert!(ok, "{name}: GPU/CPU parity failed (images in target/tmp/gpu-tests/parity)");
        let full = gpu_render(tracer, &flat, false);
        assert_eq!(full.image.pixels, g.image.pixels, "{name}: the specialised shader differs from the full one");
    }
}

#[test]
fn gpu_probe_reports_gltf_f_att_and_s_as_the_cpu_does() {
    let tracer = gpu_or_skip!();
    let flat = flat(1);
    // A grid over the image: floor under every light, both spheres, beyond the first range.
    let pixels = (0..6).flat_map(|j| (0..8).map(move |i| (10 + 20 * i, 10 + 20 * j)));
    let (mut ramp, mut windowed) = (0, 0);
    for (x, y) in pixels {
        let c = probe_pixel(&flat, x, y, 0).expect("valid tags");
        let (g, status) = tracer.probe_pixel(&flat, x, y).expect("GPU probe");
        assert_eq!(status, 0, "({x}, {y}): status {status}");
        assert_eq!(c.object_id, g.object_id, "({x}, {y}): first hit differs");
        if c.object_id == NO_HIT {
            continue;
        }
        assert_eq!(c.lights.len(), g.lights.len());
        for (j, (cl, gl)) in c.lights.iter().zip(&g.lights).enumerate() {
            let what = format!("({x}, {y}) light {j}");
            assert!(
                (cl.f_att - gl.f_att).abs() <= 1e-5 * cl.f_att.max(1.0),
                "{what}: f_att {} vs {}",
                cl.f_att,
                gl.f_att
            );
            assert!((cl.spot - gl.spot).abs() <= 1e-5, "{what}: S {} vs {}", cl.spot, gl.spot);
            let close =
                (cl.contribution - gl.contribution).abs().cmple(1e-4 * cl.contribution.abs().max(glam::DVec3::ONE));
            assert!(close.all(), "{what}: {cl:?} vs {gl:?}");
        }
        // The pixels must exercise the smooth ramp and the range window, not only their ends.
        ramp += usize::from(c.lights[2].spot > 0.0 && c.lights[2].spot < 1.0);
        let d = (glam::DVec3::from_array([-2.5, 3.0, -1.0]) - c.point).length();
        windowed += usize::from(c.lights[0].f_att > 0.0 && d > 1.0 && c.lights[0].f_att < 0.99 / (d * d));
    }
    assert!(ramp >= 1 && windowed >= 3, "only {ramp} probes on the smooth ramp and {windowed} in the range window");
}
