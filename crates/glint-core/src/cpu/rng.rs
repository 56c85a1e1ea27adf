//! CPU twin of `shaders/rng.wgsl`: a counter-based hash RNG, so that the GPU reproduces every
//! sample of the CPU exactly (same integers, same floats: 24-bit values are exact in f32).

/// PCG hash (Jarzynski & Olano, "Hash Functions for GPU Rendering", JCGT 2020).
pub fn pcg_hash(v: u32) -> u32 {
    let state = v.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    let word = ((state >> ((state >> 28) + 4)) ^ state).wrapping_mul(277_803_737);
    (word >> 22) ^ word
}

/// The random integer for one dimension of one sample of one pixel.
pub fn sample_hash(pixel: u32, sample: u32, dim: u32, seed: u32) -> u32 {
    pcg_hash(pixel ^ pcg_hash(sample ^ pcg_hash(dim ^ pcg_hash(seed))))
}

/// Maps a hash to [0, 1) with 24 bits, exactly representable in f32 and f64.
pub fn hash_to_unit(h: u32) -> f64 {
    f64::from(h >> 8) * (1.0 / 16_777_216.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pcg_hash_is_the_published_function() {
        // Golden values computed independently (Python, from the paper's listing): the hash
        // defines every jittered sample, so a change here changes every image.
        assert_eq!(pcg_hash(0), 129_708_002);
        assert_eq!(pcg_hash(1), 2_831_084_092);
        assert_eq!(pcg_hash(12_345), 4_099_845_390);
    }

    #[test]
    fn unit_values_are_in_range_and_spread() {
        let mut buckets = [0u32; 16];
        for i in 0..16_000 {
            let u = hash_to_unit(sample_hash(i, 0, 0, 7));
            assert!((0.0..1.0).contains(&u));
            buckets[(u * 16.0) as usize] += 1;
        }
        // 1000 expected per bucket; a broken hash lands far outside ±20 %.
        assert!(buckets.iter().all(|&b| (800..1200).contains(&b)), "{buckets:?}");
    }
}
