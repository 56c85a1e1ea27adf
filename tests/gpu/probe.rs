//! The pixel probe on both tracers: each breakdown sums to its pixel's radiance, and the GPU's
//! terms match the CPU's term by term (f32 against f64).

use glint_core::cpu::shade::{Breakdown, LightTerm};
use glint_core::probe_pixel;
use glint_types::SpecularModel;
use glint_types::layout::NO_HIT;

use glint_test_support::scene::SceneText;

use super::support::{builtin, gpu_or_skip};

/// |a − b| ≤ tol·max(1, |a|), per channel.
fn close(a: glam::DVec3, b: glam::DVec3, tol: f64) -> bool {
    (a - b).abs().cmple(tol * a.abs().max(glam::DVec3::ONE)).all()
}

fn check_sum(b: &Breakdown, what: &str) {
    if b.object_id == NO_HIT {
        return;
    }
    assert!(
        close(b.total, b.sum_of_terms(), 1e-5),
        "{what}: terms sum to {} but the pixel is {}",
        b.sum_of_terms(),
        b.total
    );
}

/// The cosines behind a light's terms: the same lobe, N·L and the lobe's cosine to f32's
/// rounding of unit vectors, the lobe to that rounding times its exponent (d(c^n)/c^n = n·dc/c:
/// n = 10000 in highlights).
fn check_angles(c: &LightTerm, g: &LightTerm, what: &str) {
    let (c, g) = (&c.angles, &g.angles);
    assert_eq!(c.lobe_model, g.lobe_model, "{what}: lobe");
    assert!((c.n_dot_l - g.n_dot_l).abs() <= 1e-5, "{what}: N·L {} vs {}", c.n_dot_l, g.n_dot_l);
    assert!((c.lobe_cosine - g.lobe_cosine).abs() <= 1e-5, "{what}: cosine {} vs {}", c.lobe_cosine, g.lobe_cosine);
    assert!((c.lobe - g.lobe).abs() <= 2e-3 * c.lobe.max(1e-3), "{what}: lobe {} vs {}", c.lobe, g.lobe);
}

/// Blinn's, Phong's and Cook–Torrance's lobes side by side under a point light: the GPU probe
/// shows the same cosines and lobes as the CPU's, and names the lobe each sphere has.
#[test]
fn gpu_probe_shows_each_lobes_cosines_as_the_cpu() {
    let tracer = gpu_or_skip!();
    let lobes = [
        ("blinn", "specular_model = \"blinn\"", SpecularModel::Blinn),
        ("phong", "specular_model = \"phong\"", SpecularModel::Phong),
        ("ct", "specular_model = \"cook_torrance\"\nroughness = 0.3", SpecularModel::CookTorrance),
    ];
    let mut scene = SceneText::new(96, 32, "max_depth = 0", [0.0, 0.0, -6.0], [0.0; 3], [0.0, 1.0, 0.0], 40.0)
        .light("point", "position = [1.5, 2.0, -4.0]\ndiffuse = [1, 1, 1]\nspecular = [1, 1, 1]");
    for (i, (name, lobe, _)) in lobes.iter().enumerate() {
        scene = scene
            .material(name, &format!("kd = [0.5, 0.5, 0.5]\nks = [0.5, 0.5, 0.5]\nshininess = 20\n{lobe}"))
            .sphere([2.2 * (i as f64 - 1.0), 0.0, 0.0], 1.0, name);
    }
    let flat = scene.flat();
    let mut lit = 0;
    for (i, (name, _, model)) in lobes.iter().enumerate() {
        // Across each sphere's face (centred 16 pixels apart, about 7 wide; +x is on the left,
        // the camera looking along +z), through its highlight and past it.
        for x in [-5, -2, 0, 2, 5].map(|x| (48 - 16 * (i as i32 - 1) + x) as u32) {
            for y in [12, 14, 16, 19] {
                let cpu = probe_pixel(&flat, x, y, 0).expect("valid tags");
                let (gpu, status) = tracer.probe_pixel(&flat, x, y).expect("GPU probe");
                let what = format!("{name} ({x}, {y})");
                assert_eq!(status, 0, "{what}: status {status}");
                if cpu.object_id == NO_HIT {
                    continue;
                }
                assert_eq!(cpu.lights[0].angles.lobe_model, *model, "{what}: the CPU's lobe");
                check_angles(&cpu.lights[0], &gpu.lights[0], &what);
                lit += usize::from(cpu.lights[0].angles.lobe > 0.05);
            }
        }
    }
    assert!(lit >= 6, "only {lit} probes in a highlight");
}

#[test]
fn gpu_probe_matches_cpu_probe_term_by_term() {
    let tracer = gpu_or_skip!();
    // Pixels on the checker floor, the mirror and the glass sphere (TIR rim included), the
    // Cornell walls, spot-lit floor and the light bays.
    let cases = [
        ("whitted", [(20, 110), (55, 45), (100, 70), (112, 62), (80, 10)]),
        ("cornell", [(20, 60), (80, 20), (45, 95), (110, 95), (80, 110)]),
        ("spotlights", [(60, 70), (80, 65), (100, 60), (70, 90), (10, 10)]),
        ("highlights", [(25, 55), (60, 55), (95, 55), (130, 55), (80, 100)]),
        ("lights", [(35, 60), (80, 60), (125, 60), (80, 20), (10, 100)]),
    ];
    let (mut reflected, mut transmitted) = (0, 0);
    // At 4 spp both probe the same jittered first sample.
    for ((name, pixels), spp) in cases.iter().flat_map(|c| [(c, 1), (c, 4)]) {
        let flat = builtin(name, 160, 120, spp, 5);
        for &(x, y) in pixels {
            let cpu = probe_pixel(&flat, x, y, 0).expect("valid tags");
            let (gpu, status) = tracer.probe_pixel(&flat, x, y).expect("GPU probe");
            assert_eq!(status, 0, "{name} ({x}, {y}): status {status}");
            let what = format!("{name} ({x}, {y}) at {spp} spp");
            check_sum(&cpu, &format!("{what} CPU"));
            check_sum(&gpu, &format!("{what} GPU"));
            assert_eq!(cpu.object_id, gpu.object_id, "{what}: first hit differs");
            assert!(close(cpu.total, gpu.total, 1e-4), "{what}: total CPU {} GPU {}", cpu.total, gpu.total);
            if cpu.object_id == NO_HIT {
                continue;
            }
            reflected += usize::from(cpu.reflected.max_element() > 1e-3);
            transmitted += usize::from(cpu.transmitted.max_element() > 1e-3);
            assert_eq!(cpu.lights.len(), gpu.lights.len(), "{what}: light count");
            for (j, (c, g)) in cpu.lights.iter().zip(&gpu.lights).enumerate() {
                assert!(close(c.contribution, g.contribution, 1e-4), "{what} light {j}: {c:?} vs {g:?}");
                assert!((c.f_att - g.f_att).abs() <= 1e-5 * c.f_att.max(1.0), "{what}: f_att");
                assert!((c.spot - g.spot).abs() <= 1e-5, "{what}: spot {} vs {}", c.spot, g.spot);
                check_angles(c, g, &format!("{what} light {j}"));
            }
            for (term, c, g) in [
                ("k_a", cpu.ka, gpu.ka),
                ("k_d", cpu.kd, gpu.kd),
                ("emission", cpu.emission, gpu.emission),
                ("ambient", cpu.ambient, gpu.ambient),
                ("k_r·I_r", cpu.reflected, gpu.reflected),
                ("k_t·I_t", cpu.transmitted, gpu.transmitted),
            ] {
                assert!(close(c, g, 1e-4), "{what}: {term} CPU {c} GPU {g}");
            }
        }
    }
    // The chosen pixels must exercise the global terms, not only the local ones.
    assert!(reflected >= 3 && transmitted >= 2, "only {reflected} reflecting and {transmitted} transmitting probes");
}
