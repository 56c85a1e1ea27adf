//! Linear HDR images and their output (PNG with metadata, EXR), written atomically.

use glam::DVec3;
use rayon::prelude::*;

use glint_types::layout::NO_HIT;

/// A linear-radiance image with the first-hit object of every pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct HdrImage {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<DVec3>,
    /// Object id of the first hit of each pixel's first sample, `NO_HIT` for background.
    pub first_hit: Vec<u32>,
}

impl HdrImage {
    pub fn new(width: u32, height: u32) -> Self {
        let n = width as usize * height as usize;
        Self { width, height, pixels: vec![DVec3::ZERO; n], first_hit: vec![NO_HIT; n] }
    }

    pub fn get(&self, x: u32, y: u32) -> DVec3 {
        self.pixels[(y * self.width + x) as usize]
    }

    /// Whether every channel of every pixel is a finite number.
    /// The mean over every pixel and channel.
    pub fn mean(&self) -> f64 {
        self.pixels.iter().map(|p| p.element_sum()).sum::<f64>() / (3 * self.pixels.len().max(1)) as f64
    }

    pub fn all_finite(&self) -> bool {
        self.pixels.iter().all(|p| p.is_finite())
    }

    /// The pixels an image file cannot hold as the numbers they are: NaN, infinite, or finite
    /// in f64 but beyond f32's range (an EXR stores those as +inf, a PNG as white). `None` when
    /// every pixel is representable.
    pub fn unrepresentable(&self) -> Option<Unrepresentable> {
        let bad = |p: &DVec3| !p.to_array().iter().all(|&v| (v as f32).is_finite());
        // In parallel chunks: a whole image is read for the usual answer, none (rayon's
        // per-pixel `position_first` cost 20 ns a pixel, a tenth of a 720p `glint render`).
        const CHUNK: usize = 4096;
        let chunk = self.pixels.par_chunks(CHUNK).position_first(|c| c.iter().any(bad))?;
        let first = chunk * CHUNK + self.pixels[chunk * CHUNK..].iter().position(bad)?;
        let count = self.pixels.iter().filter(|p| bad(p)).count();
        let largest = self.pixels.iter().filter(|p| bad(p)).map(|p| p.abs().max_element()).fold(0.0, f64::max);
        let nan = self.pixels.iter().filter(|p| p.is_nan()).count();
        let width = self.width.max(1) as usize;
        Some(Unrepresentable { count, first: ((first % width) as u32, (first / width) as u32), largest, nan })
    }

    /// The pixels of `r`, an image of its size.
    pub fn cropped(&self, r: crate::tiles::PixelRect) -> Self {
        let mut out = Self::new(r.width, r.height);
        for row in 0..r.height as usize {
            let src = (r.y0 as usize + row) * self.width as usize + r.x0 as usize;
            let dst = row * r.width as usize;
            out.pixels[dst..dst + r.width as usize].copy_from_slice(&self.pixels[src..src + r.width as usize]);
            out.first_hit[dst..dst + r.width as usize].copy_from_slice(&self.first_hit[src..src + r.width as usize]);
        }
        out
    }

    /// The image as a file stores it: each channel rounded to f32, as the GPU computes and an
    /// EXR holds it. What a comparison with the GPU, and its "black = identical", reads: two
    /// images whose files are bit-identical compare as identical.
    pub fn as_stored(&self) -> Self {
        let mut out = self.clone();
        out.pixels.par_iter_mut().for_each(|p| *p = p.as_vec3().as_dvec3());
        out
    }

    /// 8-bit sRGB, clamped to [0, 1] first, of each channel's f32 value (as an EXR stores it,
    /// so that a PNG made from EXR tiles, `glint merge`, is the same bytes as one rendered
    /// whole). In parallel chunks: even without a `powf` per channel (`linear_to_srgb8`), a 720p
    /// image is millions of channels.
    pub fn to_srgb8(&self) -> Vec<u8> {
        const CHUNK: usize = 4096;
        let mut out = vec![0; self.pixels.len() * 3];
        out.par_chunks_mut(3 * CHUNK).zip(self.pixels.par_chunks(CHUNK)).for_each(|(bytes, pixels)| {
            for (b, p) in bytes.chunks_exact_mut(3).zip(pixels) {
                b.copy_from_slice(&srgb8_as_stored(*p));
            }
        });
        out
    }
}

/// What `HdrImage::unrepresentable` found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Unrepresentable {
    pub count: usize,
    /// (x, y) of the first such pixel in row order.
    pub first: (u32, u32),
    /// The largest magnitude among them (NaN compares as nothing, so a NaN image says 0).
    pub largest: f64,
    /// How many of them have a NaN channel: no overflow makes those alone.
    pub nan: usize,
}

impl Unrepresentable {
    /// Whether every such pixel is NaN: no value overflowed.
    pub fn all_nan(&self) -> bool {
        self.nan == self.count
    }
}

impl std::fmt::Display for Unrepresentable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (x, y) = self.first;
        let (pixels, are, have) = if self.count == 1 { ("pixel", "is", "has") } else { ("pixels", "are", "have") };
        if self.all_nan() {
            return write!(f, "{} {pixels} {are} NaN (first at pixel ({x}, {y}))", self.count);
        }
        let nan = if self.nan > 0 { format!("{} of them NaN; ", self.nan) } else { String::new() };
        write!(
            f,
            "{} {pixels} {have} radiance that is not a finite f32 number ({nan}largest {}, first at pixel ({x}, {y}))",
            self.count,
            glint_scene::format_number(self.largest)
        )
    }
}

/// The sRGB transfer function (IEC 61966-2-1) of a clamped linear value, rounded: the
/// definition, with a `powf` per value. `linear_to_srgb8` gives the same codes from a table.
fn linear_to_srgb8_by_powf(v: f64) -> u8 {
    let v = clamp_linear(v);
    let s = if v <= 0.003_130_8 { 12.92 * v } else { 1.055 * v.powf(1.0 / 2.4) - 0.055 };
    (s * 255.0 + 0.5) as u8
}

/// A linear value clamped to [0, 1], NaN to 0.
fn clamp_linear(v: f64) -> f64 {
    if v.is_nan() { 0.0 } else { v.clamp(0.0, 1.0) }
}

/// `linear_to_srgb8_by_powf`, as the number of codes whose least linear value is at most v:
/// a table look-up and a step or two instead of a `powf`, which was a sixth of a 720p `glint
/// render` (2.8 million channels). The same code for every input, since the definition never
/// decreases as v grows (tested around every threshold and over a dense sweep).
pub fn linear_to_srgb8(v: f64) -> u8 {
    let table = &*SRGB8_TABLE;
    let v = clamp_linear(v);
    // v · 2^12 is exact, so the bucket's start i / 2^12 is at most v: its code is a lower bound.
    let mut code = table.start[(v * SRGB8_BUCKETS as f64) as usize];
    while let Some(&t) = table.thresholds.get(usize::from(code))
        && t <= v
    {
        code += 1;
    }
    code
}

/// 8-bit sRGB of a pixel as a file stores it, each channel rounded to f32 first: what every
/// PNG, export and display of a CPU image shows, so that they agree code for code.
pub fn srgb8_as_stored(p: DVec3) -> [u8; 3] {
    p.to_array().map(|v| linear_f32_to_srgb8(v as f32))
}

/// `linear_to_srgb8` of a stored f32 channel.
pub fn linear_f32_to_srgb8(v: f32) -> u8 {
    linear_to_srgb8(f64::from(v))
}

/// Buckets of [0, 1] in `Srgb8Table::start`: at most two codes begin in one (the curve is
/// steepest at 0, 12.92 · 255 codes per unit).
const SRGB8_BUCKETS: usize = 1 << 12;

/// What `linear_to_srgb8` reads.
struct Srgb8Table {
    /// For code k in 1..=255, at index k − 1, the least linear value `linear_to_srgb8_by_powf`
    /// encodes as k or more.
    thresholds: [f64; 255],
    /// The code of i / `SRGB8_BUCKETS`, for i in 0..=SRGB8_BUCKETS.
    start: [u8; SRGB8_BUCKETS + 1],
}

/// Found from the definition itself, by bisection over the bit patterns of [0, 1] (ordered as
/// the numbers are), so no threshold comes from a second formula.
static SRGB8_TABLE: std::sync::LazyLock<Srgb8Table> = std::sync::LazyLock::new(|| {
    let thresholds: [f64; 255] = std::array::from_fn(|i| {
        let code = i as u8 + 1;
        // Invariant: code(lo) < code ≤ code(hi); code(0) = 0 and code(1) = 255.
        let (mut lo, mut hi) = (0.0f64.to_bits(), 1.0f64.to_bits());
        while hi - lo > 1 {
            let mid = lo + (hi - lo) / 2;
            if linear_to_srgb8_by_powf(f64::from_bits(mid)) >= code {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        f64::from_bits(hi)
    });
    let start = std::array::from_fn(|i| {
        let v = i as f64 / SRGB8_BUCKETS as f64;
        thresholds.partition_point(|&t| t <= v) as u8
    });
    Srgb8Table { thresholds, start }
});

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_transfer_endpoints_and_midpoint() {
        assert_eq!(linear_to_srgb8(0.0), 0);
        assert_eq!(linear_to_srgb8(1.0), 255);
        assert_eq!(linear_to_srgb8(2.0), 255);
        assert_eq!(linear_to_srgb8(-1.0), 0);
        // 18 % grey is 118 in sRGB.
        assert_eq!(linear_to_srgb8(0.18), 118);
        assert_eq!(linear_to_srgb8(f64::NAN), 0);
        // IEC 61966-2-1's linear segment, s = 12.92·v, worked by hand (a mutation to 12.5 passed
        // every test but the golden hashes): 255·12.92·0.002 = 6.59 → 7; at its end 0.0031308,
        // 10.31 → 10; and the power segment at 0.5, 255·(1.055·0.5^(1/2.4) − 0.055) = 187.52 → 188.
        assert_eq!(linear_to_srgb8(0.002), 7);
        assert_eq!(linear_to_srgb8(0.003_130_8), 10);
        assert_eq!(linear_to_srgb8(0.5), 188);
    }

    /// The table gives the definition's code: for 20,000 values around every threshold (where
    /// a `powf` off by an ulp could round the other way) and a sweep of 2^22 + 1 values over
    /// [0, 1], with the clamped ends.
    #[test]
    fn the_srgb_table_gives_the_definitions_codes() {
        let check = |v: f64| assert_eq!(linear_to_srgb8(v), linear_to_srgb8_by_powf(v), "linear {v:e}");
        let thresholds = &SRGB8_TABLE.thresholds;
        for &t in thresholds {
            let bits = t.to_bits();
            for b in bits.saturating_sub(10_000)..bits + 10_000 {
                check(f64::from_bits(b));
            }
        }
        let steps = 1u32 << 22;
        for i in 0..=steps {
            check(f64::from(i) / f64::from(steps));
        }
        for v in [-0.0, -1e-300, 1.0 + f64::EPSILON, f64::INFINITY, f64::NEG_INFINITY, f64::MIN_POSITIVE] {
            check(v);
        }
        // The thresholds rise, and each is where its code begins.
        assert!(thresholds.windows(2).all(|w| w[0] < w[1]));
        for (k, &t) in (1..=255u8).zip(thresholds) {
            assert_eq!((linear_to_srgb8_by_powf(t), linear_to_srgb8_by_powf(t.next_down())), (k, k - 1));
        }
    }
}

/// What produced an image, for `render_metadata`.
#[derive(Clone, Debug)]
pub struct RenderInfo<'a> {
    pub scene: &'a str,
    pub backend: &'a str,
    pub device: &'a str,
    pub specialised: bool,
    pub time_ms: Option<f64>,
    pub rays: Option<u64>,
}

/// The render settings and provenance as PNG tEXt chunks (`glint:*` keys), the same for
/// `glint render` and the viewer's "Save image".
pub fn render_metadata(s: &glint_scene::RenderSettings, info: &RenderInfo) -> Vec<(String, String)> {
    let mut m: Vec<(String, String)> = [
        ("Software", format!("glint {}", env!("CARGO_PKG_VERSION"))),
        ("glint:scene", info.scene.to_string()),
        ("glint:size", format!("{}x{}", s.width, s.height)),
        ("glint:spp", s.spp.to_string()),
        ("glint:depth", s.max_depth.to_string()),
        ("glint:epsilon", s.epsilon.to_string()),
        ("glint:epsilon_mode", s.epsilon_mode.name().to_string()),
        ("glint:seed", s.seed.to_string()),
        ("glint:integrator", s.integrator.name().to_string()),
        ("glint:backend", info.backend.to_string()),
        ("glint:device", info.device.to_string()),
        ("glint:specialised", info.specialised.to_string()),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v))
    .collect();
    // Whitted's bailout; paths end by Russian roulette, and have no such setting to record.
    match s.integrator {
        glint_scene::Integrator::Whitted => m.push(("glint:bailout".into(), s.bailout.to_string())),
        glint_scene::Integrator::Path => {
            m.push(("glint:indirect".into(), if s.indirect { "on" } else { "off" }.into()))
        }
    }
    if let Some(t) = info.time_ms {
        m.push(("glint:time_ms".into(), format!("{t:.3}")));
    }
    if let Some(r) = info.rays {
        m.push(("glint:rays".into(), r.to_string()));
    }
    m
}
