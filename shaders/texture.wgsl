// Twin of crates/glint-core/src/cpu/texture.rs: texture coordinates at a hit and the texel math
// of both tracers (UV transform, wrap modes, nearest and bilinear), in f32 from the texels the
// CPU widens to f64. A coordinate is folded into its wrap mode's base period first, so that
// the texel indices stay within [−1, 2n + 1]; the indices are then wrapped as integers.
#define_import_path glint::texture

#import glint::scene_data::{GpuTexture, GpuTriangle, MESH_HAS_UVS, WRAP_CLAMP_TO_EDGE, WRAP_MIRRORED_REPEAT, FILTER_NEAREST, UV_MESH, UV_ACROSS_X, UV_ACROSS_Y, UV_ACROSS_Z}
#import glint::bindings::{texels, textures, uvs, meshes}

#ifdef TEXTURES
// The axis planar coordinates are taken across: the geometric normal's dominant one.
fn planar_axis(ng: vec3<f32>) -> u32 {
    let a = abs(ng);
    if a.x >= a.y && a.x >= a.z {
        return UV_ACROSS_X;
    }
    if a.y >= a.z {
        return UV_ACROSS_Y;
    }
    return UV_ACROSS_Z;
}

// The two coordinates across the dominant axis of the geometric normal, of a point relative
// to the frame's origin (its own coordinates are in the texture's planar_u/v).
fn planar_uv(p: vec3<f32>, ng: vec3<f32>) -> vec2<f32> {
    let a = abs(ng);
    if a.x >= a.y && a.x >= a.z {
        return p.yz;
    }
    if a.y >= a.z {
        return p.xz;
    }
    return p.xy;
}

#ifdef TRIANGLES
// Where a triangle's texture coordinates come from: its mesh's UVs, or planar ones.
fn triangle_uv_origin(tri: GpuTriangle, ng: vec3<f32>) -> u32 {
    if (meshes[tri.mesh].flags & MESH_HAS_UVS) == 0u {
        return planar_axis(ng);
    }
    return UV_MESH;
}

// Interpolated with the barycentrics of the shading normal; planar without vertex UVs.
fn triangle_uv(tri: GpuTriangle, bu: f32, bv: f32, p: vec3<f32>, ng: vec3<f32>) -> vec2<f32> {
    if (meshes[tri.mesh].flags & MESH_HAS_UVS) == 0u {
        return planar_uv(p, ng);
    }
    return (1.0 - bu - bv) * uvs[tri.va] + bu * uvs[tri.vb] + bv * uvs[tri.vc];
}
#endif

// The transformed coordinates of the coordinates' origin: the transform's offset for a mesh's
// UVs, the frame origin's for planar ones.
fn uv_origin_of(tex: GpuTexture, origin: u32) -> vec2<f32> {
    if origin == UV_ACROSS_X {
        return vec2<f32>(tex.planar_u.x, tex.planar_v.x);
    }
    if origin == UV_ACROSS_Y {
        return vec2<f32>(tex.planar_u.y, tex.planar_v.y);
    }
    if origin == UV_ACROSS_Z {
        return vec2<f32>(tex.planar_u.z, tex.planar_v.z);
    }
    return vec2<f32>(tex.transform_u.z, tex.transform_v.z);
}

fn transform_uv(tex: GpuTexture, uv: vec2<f32>, origin: u32) -> vec2<f32> {
    let r = tex.transform_u;
    let s = tex.transform_v;
    let o = uv_origin_of(tex, origin);
    return vec2<f32>(r.x * uv.x + r.y * uv.y + o.x, s.x * uv.x + s.y * uv.y + o.y);
}

// [0, 1) for repeat, [0, 2) for mirrored repeat, [0, 1] for clamp to edge: a small negative u
// folds to just below the period, not onto it (the CPU twin says why).
fn wrap_period(u: f32, mode: u32) -> f32 {
    if mode == WRAP_MIRRORED_REPEAT {
        return min(u - 2.0 * floor(u * 0.5), 1.9999999);
    }
    if mode == WRAP_CLAMP_TO_EDGE {
        return clamp(u, 0.0, 1.0);
    }
    return min(u - floor(u), 0.99999994);
}

fn wrap_texel(i: i32, n: i32, mode: u32) -> i32 {
    if mode == WRAP_MIRRORED_REPEAT {
        let j = ((i % (2 * n)) + 2 * n) % (2 * n);
        return select(j, 2 * n - 1 - j, j >= n);
    }
    if mode == WRAP_CLAMP_TO_EDGE {
        return clamp(i, 0, n - 1);
    }
    return ((i % n) + n) % n;
}

fn fetch_texel(tex: GpuTexture, x: i32, y: i32) -> vec3<f32> {
    return texels[tex.offset + u32(y) * tex.width + u32(x)].xyz;
}

fn sample_texture(index: u32, uv: vec2<f32>, origin: u32) -> vec3<f32> {
    let tex = textures[index];
    let st = transform_uv(tex, uv, origin);
    let w = i32(tex.width);
    let h = i32(tex.height);
    let x = wrap_period(st.x, tex.wrap_s) * f32(tex.width);
    let y = wrap_period(st.y, tex.wrap_t) * f32(tex.height);
    if tex.filter_mode == FILTER_NEAREST {
        return fetch_texel(tex, wrap_texel(i32(floor(x)), w, tex.wrap_s), wrap_texel(i32(floor(y)), h, tex.wrap_t));
    }
    let xc = x - 0.5;
    let yc = y - 0.5;
    let x0 = floor(xc);
    let y0 = floor(yc);
    let fx = xc - x0;
    let fy = yc - y0;
    let i0 = wrap_texel(i32(x0), w, tex.wrap_s);
    let i1 = wrap_texel(i32(x0) + 1, w, tex.wrap_s);
    let j0 = wrap_texel(i32(y0), h, tex.wrap_t);
    let j1 = wrap_texel(i32(y0) + 1, h, tex.wrap_t);
    let top = fetch_texel(tex, i0, j0) * (1.0 - fx) + fetch_texel(tex, i1, j0) * fx;
    let bottom = fetch_texel(tex, i0, j1) * (1.0 - fx) + fetch_texel(tex, i1, j1) * fx;
    return top * (1.0 - fy) + bottom * fy;
}
#endif
