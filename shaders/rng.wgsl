// Twin of crates/glint-core/src/cpu/rng.rs: counter-based hash RNG.
#define_import_path glint::rng

// PCG hash (Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 2020).
fn pcg_hash(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

fn sample_hash(pixel: u32, sample_index: u32, dim: u32, seed: u32) -> u32 {
    return pcg_hash(pixel ^ pcg_hash(sample_index ^ pcg_hash(dim ^ pcg_hash(seed))));
}

// 24 bits in [0, 1): exact in f32, the same values as the f64 twin.
fn hash_to_unit(h: u32) -> f32 {
    return f32(h >> 8u) * (1.0 / 16777216.0);
}
