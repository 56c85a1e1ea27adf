//! The presenter (shaders/present.wgsl) turns linear radiance into the sRGB bytes the CPU's
//! `linear_to_srgb8` writes into PNGs: the viewer draws the GPU image from these bytes.

use glint_core::image::linear_to_srgb8;
use glint_gpu::Presenter;
use wgpu::util::DeviceExt as _;

use super::support::gpu_or_skip;

#[test]
fn presented_pixels_are_the_cpus_srgb_bytes() {
    let tracer = gpu_or_skip!();
    let ctx = tracer.context();
    let (width, height) = (64u32, 48u32);
    // Every value from below 0 to above 1, dense around sRGB's linear segment.
    let n = (width * height) as usize;
    let value = |i: usize, c: usize| {
        let t = (3 * i + c) as f32 / (3 * n) as f32;
        if i.is_multiple_of(4) { t * 0.01 } else { t * 1.3 - 0.1 }
    };
    // And the values no render should make, which must still show as the CPU shows them:
    // NaN black (WGSL leaves clamp of a NaN to the implementation), infinities clamped.
    let odd = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, -f32::NAN];
    let value = |i: usize, c: usize| if i < odd.len() { odd[(i + c) % odd.len()] } else { value(i, c) };
    let radiance: Vec<[f32; 4]> = (0..n).map(|i| [value(i, 0), value(i, 1), value(i, 2), 1.0]).collect();
    let buffer = ctx.device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
        label: Some("radiance"),
        contents: bytemuck::cast_slice(&radiance),
        usage: wgpu::BufferUsages::STORAGE,
    });
    let presenter = Presenter::new(ctx, width, height);
    let pending = presenter.present(ctx, &buffer);
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    let rgba = loop {
        if let Some(r) = pending.poll(ctx) {
            break r.expect("the pixels are read back");
        }
        assert!(std::time::Instant::now() < deadline, "the presented pixels never arrived");
        std::thread::yield_now();
    };
    assert_eq!(rgba.len(), n * 4);
    let mut off = Vec::new();
    for (i, px) in radiance.iter().enumerate() {
        for c in 0..3 {
            let (want, got) = (linear_to_srgb8(f64::from(px[c])), rgba[4 * i + c]);
            if want.abs_diff(got) > 0 {
                off.push((px[c], want, got));
            }
        }
        assert_eq!(rgba[4 * i + 3], 255, "alpha");
    }
    // f32 pow against the CPU's exact table: a value within rounding of a code's edge may
    // land on its neighbour, never further.
    assert!(off.iter().all(|(v, w, g)| v.is_finite() && w.abs_diff(*g) == 1), "{off:?}");
    assert!(off.len() * 1000 <= 3 * n, "{} of {} channels differ from the CPU's byte: {off:?}", off.len(), 3 * n);
    eprintln!("{} of {} channels one code off the CPU's", off.len(), 3 * n);
}
