//! CPU twin of `shaders/texture.wgsl`: texture coordinates at a hit and the texel math of both
//! tracers — the UV transform, the wrap modes, nearest and bilinear filtering — in f64 from the
//! same stored f32 texels the GPU reads.
//!
//! A coordinate is first folded into its wrap mode's base period in floating point ([0, 1)
//! repeat, [0, 2) mirrored, [0, 1] clamp), so that the texel indices derived from it stay within
//! [−1, 2n + 1] whatever the coordinate; the indices are then wrapped as integers.

use glam::{DVec2, DVec3};

use super::{TraceContext, v3};
use crate::flat::FlatScene;
use glint_scene::{Filter, Wrap};
use glint_types::layout::{GpuTexture, GpuTriangle, MESH_HAS_UVS, UV_ACROSS_X, UV_ACROSS_Y, UV_ACROSS_Z, UV_MESH};

/// The axis planar coordinates are taken across: the geometric normal's dominant one.
pub fn planar_axis(ng: DVec3) -> u32 {
    let a = ng.abs();
    if a.x >= a.y && a.x >= a.z {
        UV_ACROSS_X
    } else if a.y >= a.z {
        UV_ACROSS_Y
    } else {
        UV_ACROSS_Z
    }
}

/// Planar texture coordinates at `p`, relative to the frame's origin (whose own coordinates
/// are in the texture's `planar_u`/`planar_v`): the two coordinates across the dominant axis
/// of the geometric normal (y and z for x, x and z for y, x and y for z), so that a floor at
/// y = 0 does not flicker with the sign of rounding errors in y. One scene unit is one unit of
/// UV.
pub fn planar_uv(p: DVec3, ng: DVec3) -> DVec2 {
    let a = ng.abs();
    if a.x >= a.y && a.x >= a.z {
        DVec2::new(p.y, p.z)
    } else if a.y >= a.z {
        DVec2::new(p.x, p.z)
    } else {
        DVec2::new(p.x, p.y)
    }
}

/// Where a triangle's texture coordinates come from: its mesh's UVs, or planar ones.
pub fn triangle_uv_origin(scene: &FlatScene, tri: &GpuTriangle, ng: DVec3) -> u32 {
    if scene.meshes[tri.mesh as usize].flags & MESH_HAS_UVS == 0 {
        return planar_axis(ng);
    }
    UV_MESH
}

/// Texture coordinates of a triangle hit: the vertices' interpolated with the barycentrics the
/// shading normal is interpolated with, or planar ones for a mesh without them.
pub fn triangle_uv(scene: &FlatScene, tri: &GpuTriangle, bu: f64, bv: f64, p: DVec3, ng: DVec3) -> DVec2 {
    if scene.meshes[tri.mesh as usize].flags & MESH_HAS_UVS == 0 {
        return planar_uv(p, ng);
    }
    let [a, b, c] = [tri.va, tri.vb, tri.vc].map(|i| {
        let uv = scene.uvs[i as usize];
        DVec2::new(f64::from(uv[0]), f64::from(uv[1]))
    });
    (1.0 - bu - bv) * a + bu * b + bv * c
}

/// The transformed coordinates of the coordinates' origin: the transform's offset for a mesh's
/// UVs, the frame origin's for planar ones.
pub fn uv_origin_of(tex: &GpuTexture, origin: u32) -> DVec2 {
    let (u, v) = if origin == UV_ACROSS_X {
        (tex.planar_u[0], tex.planar_v[0])
    } else if origin == UV_ACROSS_Y {
        (tex.planar_u[1], tex.planar_v[1])
    } else if origin == UV_ACROSS_Z {
        (tex.planar_u[2], tex.planar_v[2])
    } else {
        (tex.transform_u[2], tex.transform_v[2])
    };
    DVec2::new(f64::from(u), f64::from(v))
}

/// The texture's UV transform (KHR_texture_transform's T · R · S, stored as two rows), about
/// the coordinates' origin.
pub fn transform_uv(tex: &GpuTexture, uv: DVec2, origin: u32) -> DVec2 {
    let o = uv_origin_of(tex, origin);
    let row = |r: [f32; 4], o: f64| f64::from(r[0]) * uv.x + f64::from(r[1]) * uv.y + o;
    DVec2::new(row(tex.transform_u, o.x), row(tex.transform_v, o.y))
}

/// A coordinate folded into its wrap mode's base period: [0, 1) (repeat), [0, 2) (mirrored
/// repeat, whose period is two copies) or [0, 1] (clamp to edge). A small negative u folds to
/// just below the period, which rounding would make the period itself, the first texel's edge
/// instead of the last texel: in f32 for |u| < 2^-25, half a 1e9 checker seen near the origin.
pub fn wrap_period(u: f64, mode: Wrap) -> f64 {
    match mode {
        Wrap::Repeat => (u - u.floor()).min(1.0 - f64::EPSILON / 2.0),
        Wrap::MirroredRepeat => (u - 2.0 * (u * 0.5).floor()).min(2.0 - f64::EPSILON),
        Wrap::ClampToEdge => u.clamp(0.0, 1.0),
    }
}

/// A texel index in [−1, 2n + 1] wrapped into [0, n) (OpenGL's and glTF's wrap rules).
pub fn wrap_texel(i: i32, n: i32, mode: Wrap) -> i32 {
    match mode {
        Wrap::Repeat => ((i % n) + n) % n,
        Wrap::MirroredRepeat => {
            let j = ((i % (2 * n)) + 2 * n) % (2 * n);
            if j >= n { 2 * n - 1 - j } else { j }
        }
        Wrap::ClampToEdge => i.clamp(0, n - 1),
    }
}

/// The colour (rgb) of texel (x, y), both in range, widened exactly.
pub fn fetch_texel(scene: &FlatScene, tex: &GpuTexture, x: i32, y: i32) -> DVec3 {
    v3(scene.texels[(tex.offset + y as u32 * tex.width + x as u32) as usize])
}

/// The colour of texture `index` at `uv`: transformed, wrapped, then the nearest texel or the
/// bilinear blend of the four around the coordinate (texel centres at half-integers).
pub fn sample_texture(ctx: &TraceContext, index: u32, uv: DVec2, origin: u32) -> DVec3 {
    let scene = ctx.scene;
    let tex = &scene.textures[index as usize];
    let ([wrap_s, wrap_t], filter) = ctx.texture_modes[index as usize];
    let st = transform_uv(tex, uv, origin);
    let (w, h) = (tex.width as i32, tex.height as i32);
    let x = wrap_period(st.x, wrap_s) * f64::from(tex.width);
    let y = wrap_period(st.y, wrap_t) * f64::from(tex.height);
    match filter {
        Filter::Nearest => {
            let (i, j) = (wrap_texel(x.floor() as i32, w, wrap_s), wrap_texel(y.floor() as i32, h, wrap_t));
            fetch_texel(scene, tex, i, j)
        }
        Filter::Bilinear => {
            let (x, y) = (x - 0.5, y - 0.5);
            let (x0, y0) = (x.floor(), y.floor());
            let (fx, fy) = (x - x0, y - y0);
            let (i0, j0) = (x0 as i32, y0 as i32);
            let (i0, i1) = (wrap_texel(i0, w, wrap_s), wrap_texel(i0 + 1, w, wrap_s));
            let (j0, j1) = (wrap_texel(j0, h, wrap_t), wrap_texel(j0 + 1, h, wrap_t));
            let top = fetch_texel(scene, tex, i0, j0) * (1.0 - fx) + fetch_texel(scene, tex, i1, j0) * fx;
            let bottom = fetch_texel(scene, tex, i0, j1) * (1.0 - fx) + fetch_texel(scene, tex, i1, j1) * fx;
            top * (1.0 - fy) + bottom * fy
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glint_types::layout::{FILTER_BILINEAR, FILTER_NEAREST, WRAP_CLAMP_TO_EDGE, WRAP_MIRRORED_REPEAT, WRAP_REPEAT};

    #[test]
    fn wrap_texel_folds_indices_as_opengl() {
        let n = 4;
        let fold = |mode| (-1..=9).map(|i| wrap_texel(i, n, mode)).collect::<Vec<_>>();
        assert_eq!(fold(Wrap::Repeat), [3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1]);
        assert_eq!(fold(Wrap::ClampToEdge), [0, 0, 1, 2, 3, 3, 3, 3, 3, 3, 3]);
        // Mirrored: 0 1 2 3 | 3 2 1 0 | 0 1 …, and −1 mirrors to 0.
        assert_eq!(fold(Wrap::MirroredRepeat), [0, 0, 1, 2, 3, 3, 2, 1, 0, 0, 1]);
    }

    #[test]
    fn wrap_period_keeps_coordinates_in_the_base_period() {
        assert_eq!(wrap_period(2.25, Wrap::Repeat), 0.25);
        assert_eq!(wrap_period(-0.25, Wrap::Repeat), 0.75);
        assert_eq!(wrap_period(-0.25, Wrap::MirroredRepeat), 1.75);
        assert_eq!(wrap_period(3.5, Wrap::MirroredRepeat), 1.5);
        assert_eq!(wrap_period(-3.0, Wrap::ClampToEdge), 0.0);
        assert_eq!(wrap_period(1.5, Wrap::ClampToEdge), 1.0);
        // Below the period, not rounded onto it: the last texel's, as u = −1e-20 is.
        assert!(wrap_period(-1e-20, Wrap::Repeat) < 1.0);
        assert!(wrap_period(-1e-20, Wrap::MirroredRepeat) < 2.0);
    }

    /// A 4×2 texture of distinct texels: red = x / 4, green = y / 2 (exact in f32), blue 1.
    fn scene_with(wrap: u32, filter: u32, transform_u: [f32; 4]) -> FlatScene {
        let (desc, _) = glint_io::builtin("bumpy").expect("built-in").load(Some(4)).expect("loads");
        let mut s = FlatScene::build(&desc, &desc.render);
        s.texels = (0..2).flat_map(|y| (0..4).map(move |x| [x as f32 / 4.0, y as f32 / 2.0, 1.0, 1.0])).collect();
        s.textures = vec![GpuTexture {
            offset: 0,
            width: 4,
            height: 2,
            wrap_s: wrap,
            wrap_t: wrap,
            filter_mode: filter,
            pad_a: 0,
            pad_b: 0,
            transform_u,
            transform_v: [0.0, 1.0, 0.0, 0.0],
            planar_u: [transform_u[2]; 4],
            planar_v: [0.0; 4],
        }];
        s
    }

    fn sample(scene: &FlatScene, u: f64, v: f64) -> DVec3 {
        let ctx = TraceContext::new(scene).expect("tags decode");
        sample_texture(&ctx, 0, DVec2::new(u, v), UV_MESH)
    }

    const IDENTITY_U: [f32; 4] = [1.0, 0.0, 0.0, 0.0];

    #[test]
    fn nearest_picks_the_texel_the_coordinate_falls_in() {
        let s = scene_with(WRAP_REPEAT, FILTER_NEAREST, IDENTITY_U);
        // u = 0.6 → x = 2.4 → texel 2; v = 0.7 → y = 1.4 → row 1.
        assert_eq!(sample(&s, 0.6, 0.7), DVec3::new(0.5, 0.5, 1.0));
        // Repeat: u = 1.6 is u = 0.6; v = −0.3 is 0.7.
        assert_eq!(sample(&s, 1.6, -0.3), DVec3::new(0.5, 0.5, 1.0));
        let clamp = scene_with(WRAP_CLAMP_TO_EDGE, FILTER_NEAREST, IDENTITY_U);
        assert_eq!(sample(&clamp, 7.0, -2.0), DVec3::new(0.75, 0.0, 1.0));
        let mirror = scene_with(WRAP_MIRRORED_REPEAT, FILTER_NEAREST, IDENTITY_U);
        // u = 1.1 mirrors to 0.9 → texel 3; u = 1.9 → 0.1 → texel 0.
        assert_eq!(sample(&mirror, 1.1, 0.2).x, 0.75);
        assert_eq!(sample(&mirror, 1.9, 0.2).x, 0.0);
    }

    #[test]
    fn bilinear_blends_the_four_texels_around_the_coordinate() {
        let s = scene_with(WRAP_REPEAT, FILTER_BILINEAR, IDENTITY_U);
        // x = 0.5 · 4 − 0.5 = 1.5: halfway between texels 1 and 2 (red 0.25, 0.5);
        // y = 0.5 · 2 − 0.5 = 0.5: halfway between rows 0 and 1 (green 0, 0.5).
        let c = sample(&s, 0.5, 0.5);
        assert_eq!((c.x, c.y, c.z), (0.375, 0.25, 1.0));
        // At a texel centre the texel itself.
        assert_eq!(sample(&s, 0.375, 0.25), DVec3::new(0.25, 0.0, 1.0));
        // Repeat: u = 0 lies between the last texel (0.75) and the first (0): x = −0.5.
        assert_eq!(sample(&s, 0.0, 0.25).x, 0.375);
        // Clamp: the edge texel alone.
        let clamp = scene_with(WRAP_CLAMP_TO_EDGE, FILTER_BILINEAR, IDENTITY_U);
        assert_eq!(sample(&clamp, 0.0, 0.25).x, 0.0);
        // Mirrored: texel 0 mirrored onto itself.
        let mirror = scene_with(WRAP_MIRRORED_REPEAT, FILTER_BILINEAR, IDENTITY_U);
        assert_eq!(sample(&mirror, 0.0, 0.25).x, 0.0);
        // A quarter of the way from texel 1's centre to texel 2's: 0.25 + 0.25 · 0.25.
        assert_eq!(sample(&s, 0.4375, 0.25).x, 0.3125);
    }

    #[test]
    fn the_transform_applies_before_wrapping() {
        // u' = 2u + 0.25: u = 0.2 → 0.65 → x = 2.6 → texel 2.
        let s = scene_with(WRAP_REPEAT, FILTER_NEAREST, [2.0, 0.0, 0.25, 0.0]);
        assert_eq!(sample(&s, 0.2, 0.1).x, 0.5);
    }

    #[test]
    fn planar_coordinates_follow_the_dominant_axis() {
        let p = DVec3::new(1.0, 2.0, 3.0);
        assert_eq!(planar_uv(p, DVec3::new(0.9, 0.1, 0.1)), DVec2::new(2.0, 3.0));
        assert_eq!(planar_uv(p, DVec3::new(0.1, -0.9, 0.1)), DVec2::new(1.0, 3.0));
        assert_eq!(planar_uv(p, DVec3::new(0.1, 0.1, 0.9)), DVec2::new(1.0, 2.0));
    }
}
