//! The ray sets of the acceleration-structure benchmark (`glint bench rays`, the criterion
//! bench `rays`, the GPU ray-cast test) and the comparison of two tracers' hits on them.
//!
//! Rays are stored in f32, as the GPU reads them; the CPU widens those exact values (as it does
//! the scene), so both tracers cast bit-identical rays. They are in the scene's stored
//! coordinates (relative to `SceneHeader::frame`), which for the bench scenes, built around the
//! world origin, are world space.

use crate::cpu::FAR;
use crate::cpu::raycast::{HitRecord, RayRecord};

/// Width and height of both ray sets: one 720p frame.
pub const RAYS_WIDTH: u32 = 1280;
pub const RAYS_HEIGHT: u32 = 720;

/// The eye of the primary rays (the bumpy scene's camera position).
pub const PRIMARY_EYE: [f64; 3] = [0.0, 0.3, 3.0];
/// Half the height of the image plane at distance 1 (a vertical field of view of 2·atan 0.6).
pub const PRIMARY_HALF_HEIGHT: f64 = 0.6;

/// The box incoherent rays start in: [−2, 2] × [−1, 2] × [−2, 2].
pub const INCOHERENT_MIN: [f64; 3] = [-2.0, -1.0, -2.0];
pub const INCOHERENT_MAX: [f64; 3] = [2.0, 2.0, 2.0];
/// The fixed seed of the incoherent rays.
pub const INCOHERENT_SEED: u64 = 0x5eed_91a7_2026_1201;

/// Which ray set.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RaySet {
    /// A 1280×720 pinhole camera at `PRIMARY_EYE` looking along −z: coherent rays.
    Primary,
    /// 1280×720 rays from uniform points of the `INCOHERENT_*` box in uniform directions.
    Incoherent,
}

impl RaySet {
    pub const ALL: [Self; 2] = [Self::Primary, Self::Incoherent];

    pub fn name(self) -> &'static str {
        match self {
            Self::Primary => "primary",
            Self::Incoherent => "incoherent",
        }
    }

    /// The rays of this set, `RAYS_WIDTH`·`RAYS_HEIGHT` of them.
    pub fn rays(self) -> Vec<RayRecord> {
        match self {
            Self::Primary => primary_rays(RAYS_WIDTH, RAYS_HEIGHT),
            Self::Incoherent => incoherent_rays((RAYS_WIDTH * RAYS_HEIGHT) as usize, INCOHERENT_SEED),
        }
    }
}

fn record(origin: [f64; 3], dir: [f64; 3]) -> RayRecord {
    let len = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
    let d = dir.map(|c| (c / len) as f32);
    RayRecord {
        origin_t_min: [origin[0] as f32, origin[1] as f32, origin[2] as f32, 0.0],
        dir_t_max: [d[0], d[1], d[2], FAR as f32],
    }
}

/// A `width`×`height` pinhole camera at `PRIMARY_EYE` looking along −z: the image plane at
/// distance 1 with half-height 0.6 and the image's aspect, one ray through each pixel centre,
/// row by row from the top left.
pub fn primary_rays(width: u32, height: u32) -> Vec<RayRecord> {
    let half_h = PRIMARY_HALF_HEIGHT;
    let half_w = half_h * f64::from(width) / f64::from(height);
    let mut rays = Vec::with_capacity((width * height) as usize);
    for y in 0..height {
        let v = half_h * (1.0 - 2.0 * (f64::from(y) + 0.5) / f64::from(height));
        for x in 0..width {
            let u = half_w * (2.0 * (f64::from(x) + 0.5) / f64::from(width) - 1.0);
            rays.push(record(PRIMARY_EYE, [u, v, -1.0]));
        }
    }
    rays
}

/// splitmix64 (Steele, Lea & Flood, "Fast splittable pseudorandom number generators", OOPSLA
/// 2014; the constants of Vigna's reference code): small, fast, and the same sequence on every
/// platform.
#[derive(Clone, Debug)]
pub struct SplitMix64(pub u64);

impl SplitMix64 {
    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1): the top 53 bits.
    pub fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// `count` rays with origins uniform in the `INCOHERENT_*` box and directions uniform on the
/// sphere (z uniform in [−1, 1], azimuth uniform: Archimedes), from splitmix64 at `seed`.
pub fn incoherent_rays(count: usize, seed: u64) -> Vec<RayRecord> {
    let mut rng = SplitMix64(seed);
    (0..count)
        .map(|_| {
            let origin: [f64; 3] =
                std::array::from_fn(|k| INCOHERENT_MIN[k] + (INCOHERENT_MAX[k] - INCOHERENT_MIN[k]) * rng.next_f64());
            let z = 1.0 - 2.0 * rng.next_f64();
            let phi = 2.0 * std::f64::consts::PI * rng.next_f64();
            let s = (1.0 - z * z).max(0.0).sqrt();
            record(origin, [s * phi.cos(), s * phi.sin(), z])
        })
        .collect()
}

/// The fraction of rays that hit something.
pub fn hit_fraction(hits: &[HitRecord]) -> f64 {
    if hits.is_empty() {
        return 0.0;
    }
    hits.iter().filter(|h| h.is_hit()).count() as f64 / hits.len() as f64
}

/// How two tracers' hits on the same rays compare.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HitAgreement {
    pub rays: usize,
    /// Rays whose hit primitive (kind and index, or the miss) differs.
    pub differing: usize,
    /// Largest |t_a − t_b| / t_b over the rays that hit the same primitive.
    pub max_t_rel: f64,
}

impl HitAgreement {
    pub fn differing_fraction(&self) -> f64 {
        if self.rays == 0 { 0.0 } else { self.differing as f64 / self.rays as f64 }
    }
}

/// Compares hits `a` with the reference `b`, ray by ray (the shorter length counts; a length
/// mismatch counts every missing ray as differing).
pub fn compare_hits(a: &[HitRecord], b: &[HitRecord]) -> HitAgreement {
    let rays = a.len().max(b.len());
    let mut out = HitAgreement { rays, differing: rays - a.len().min(b.len()), max_t_rel: 0.0 };
    for (x, y) in a.iter().zip(b) {
        if (x.prim, x.index) != (y.prim, y.index) || x.is_hit() != y.is_hit() {
            out.differing += 1;
        } else if x.is_hit() {
            let rel = (f64::from(x.t) - f64::from(y.t)).abs() / f64::from(y.t).abs().max(f64::MIN_POSITIVE);
            out.max_t_rel = out.max_t_rel.max(rel);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splitmix64_matches_the_reference_sequence() {
        // Vigna's splitmix64.c from seed 0: the first three outputs.
        let mut r = SplitMix64(0);
        assert_eq!(r.next_u64(), 0xe220_a839_7b1d_cdaf);
        assert_eq!(r.next_u64(), 0x6e78_9e6a_a1b9_65f4);
        assert_eq!(r.next_u64(), 0x06c4_5d18_8009_454f);
    }

    #[test]
    fn primary_rays_go_through_pixel_centres() {
        let rays = primary_rays(RAYS_WIDTH, RAYS_HEIGHT);
        assert_eq!(rays.len(), 1280 * 720);
        let o = rays[0].origin_t_min;
        assert_eq!([o[0], o[1], o[2]], [0.0, 0.3, 3.0]);
        // The top-left pixel centre: u = −(16/9)·0.6·(1 − 1/1280), v = 0.6·(1 − 1/720).
        let (u, v) = (-(16.0 / 9.0) * 0.6 * (1.0 - 1.0 / 1280.0), 0.6 * (1.0 - 1.0 / 720.0));
        let len = (u * u + v * v + 1.0f64).sqrt();
        let d = rays[0].dir_t_max;
        assert!((f64::from(d[0]) - u / len).abs() < 1e-7 && (f64::from(d[1]) - v / len).abs() < 1e-7);
        assert!((f64::from(d[2]) + 1.0 / len).abs() < 1e-7);
        // Symmetric about the axis: the bottom-right ray mirrors the top-left one.
        let last = rays[rays.len() - 1].dir_t_max;
        assert_eq!([last[0], last[1], last[2]], [-d[0], -d[1], d[2]]);
    }

    #[test]
    fn incoherent_rays_are_deterministic_in_the_box_and_unit() {
        let a = incoherent_rays(10_000, INCOHERENT_SEED);
        assert_eq!(a, incoherent_rays(10_000, INCOHERENT_SEED));
        assert_ne!(a, incoherent_rays(10_000, INCOHERENT_SEED + 1));
        let mut mean_dir = [0.0f64; 3];
        for r in &a {
            for k in 0..3 {
                let o = f64::from(r.origin_t_min[k]);
                assert!((INCOHERENT_MIN[k]..=INCOHERENT_MAX[k]).contains(&o), "{r:?}");
                mean_dir[k] += f64::from(r.dir_t_max[k]) / a.len() as f64;
            }
            let d = r.dir_t_max;
            let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            assert!((len - 1.0).abs() < 1e-6, "{r:?}");
        }
        // Uniform on the sphere: the mean direction is near 0 (σ ≈ 0.58/√10000 per axis).
        assert!(mean_dir.iter().all(|m| m.abs() < 0.03), "{mean_dir:?}");
    }

    #[test]
    fn comparison_counts_different_primitives_and_measures_t() {
        let hit = |prim, index, t| HitRecord { prim, index, t, pad: 0 };
        let a = [hit(3, 7, 2.0), hit(3, 8, 1.0), hit(0, 0, 0.0), hit(1, 0, 4.0)];
        let b = [hit(3, 7, 2.0001), hit(3, 9, 1.0), hit(0, 0, 0.0), hit(0, 0, 0.0)];
        let c = compare_hits(&a, &b);
        assert_eq!((c.rays, c.differing), (4, 2));
        assert!((c.max_t_rel - 0.0001 / 2.0001).abs() < 1e-6, "{c:?}");
        assert_eq!(hit_fraction(&a), 0.75);
        assert_eq!(compare_hits(&a[..3], &b).differing, 2);
    }
}
