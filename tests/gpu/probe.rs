//! The pixel probe on both tracers: each breakdown sums to its pixel's radiance, and the GPU's
//! terms match the CPU's term by term (f32 against f64).

use glint_core::cpu::shade::Breakdown;
use glint_core::probe_pixel;
use glint_types::layout::NO_HIT;

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
