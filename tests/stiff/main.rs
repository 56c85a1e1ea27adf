//! The stiff-and-extreme-cases suite (issue 5): twenty-eight small generated scenes, each rendered on
//! the CPU f64 reference and on the WGSL tracer, with the expected behaviour stated in a comment
//! and checked automatically. Every read-back image is scanned for NaN and infinities (there
//! must be none: `gpu::render_both` fails otherwise and leaves the images in target/tmp/stiff).
//!
//! Without a GPU adapter the suite fails with a clear message; `GLINT_SKIP_GPU=1` runs the CPU
//! half only. The teaching tables (acne per epsilon strategy, rays per pixel against depth, …)
//! go to stderr: `cargo test --test stiff -- --nocapture`. What each case shows and the
//! measured tolerances are in docs/numerics.md.

/// Report lines, printed in one piece when the test ends (the tests run in parallel: printed
/// line by line, their tables would interleave). `say!(out, …)` is `writeln!`, `say!(out; …)`
/// is `write!`.
macro_rules! say {
    ($out:ident) => {
        say!($out, "")
    };
    ($out:ident, $($arg:tt)*) => {{
        use std::fmt::Write as _;
        writeln!($out, $($arg)*).expect("writing to a String");
    }};
    ($out:ident; $($arg:tt)*) => {{
        use std::fmt::Write as _;
        write!($out, $($arg)*).expect("writing to a String");
    }};
}

mod case01_far_sphere;
mod case02_grazing_light;
mod case03_cube_contact;
mod case04_coplanar_triangles;
mod case05_watertight_mesh;
mod case06_degenerate_triangles;
mod case07_parallel_rays;
mod case08_camera_inside_sphere;
mod case09_light_opposite_viewer;
mod case10_shininess;
mod case11_light_on_surface;
mod case12_spot_cutoff;
mod case13_index_of_refraction;
mod case14_energy_gain;
mod case15_recursion_depth;
mod case16_invalid_data;
mod case17_translation_and_scale;
mod case18_huge_sphere;
mod case19_coplanar_overlap;
mod case20_translated_textures;
mod case21_map_coordinates;
mod case22_telephoto;
mod case23_far_light;
mod case24_far_eye_over_a_plane;
mod case25_large_triangle_through_an_axis;
mod case26_far_object_out_of_sight;
mod case27_huge_triangle_near_the_eye;
mod case28_orthographic;
mod generated;
mod plot;

use glint_test_support::{gpu, reference, render, scene};

/// Translations of case 20 (textures far from the origin).
const TRANSLATED_TEXTURES: [f64; 5] = [1e2, 1e3, 1e4, 1e5, 1e6];

/// Axis vectors for camera ups and normals.
const Y: [f64; 3] = [0.0, 1.0, 0.0];
const Z: [f64; 3] = [0.0, 0.0, 1.0];

/// |a − b| / |b| (0 when both are 0).
fn rel_err(a: f64, b: f64) -> f64 {
    if a == b { 0.0 } else { (a - b).abs() / b.abs() }
}
