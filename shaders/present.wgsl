// Twin of crates/glint-core/src/image.rs (linear_to_srgb8): turns the tracer's linear output
// buffer into 8-bit sRGB pixels for display, on the GPU, so that a quarter of the bytes go to
// the host (the viewer draws them; its window renders on another device than the tracer).
@group(0) @binding(0) var<storage, read> radiance: array<vec4<f32>>;
@group(0) @binding(1) var<storage, read_write> pixels: array<u32>;
@group(0) @binding(2) var<uniform> size: vec4<u32>;

// The sRGB transfer function (IEC 61966-2-1) of a clamped linear value, as a value in [0, 1]
// that pack4x8unorm rounds to the same byte as the CPU's linear_to_srgb8.
fn linear_to_srgb8(v: f32) -> f32 {
    // WGSL leaves clamp of a NaN to the implementation; the CPU's clamp_linear makes it 0.
    let c = select(clamp(v, 0.0, 1.0), 0.0, v != v);
    if c <= 0.0031308 {
        return 12.92 * c;
    }
    return 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}

@compute @workgroup_size(8, 8, 1)
fn main(@builtin(global_invocation_id) gid: vec3<u32>) {
    if gid.x >= size.x || gid.y >= size.y {
        return;
    }
    let i = gid.y * size.x + gid.x;
    let p = radiance[i].xyz;
    let srgb = vec3<f32>(linear_to_srgb8(p.x), linear_to_srgb8(p.y), linear_to_srgb8(p.z));
    // Bytes R, G, B, A in memory order (little-endian packing of x, y, z, w).
    pixels[i] = pack4x8unorm(vec4<f32>(srgb, 1.0));
}
