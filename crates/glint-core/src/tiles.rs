//! An image split into a fixed grid of blocks for renders spread over many machines
//! (`glint render --tile I/N`, `glint merge`): every pixel's value depends on its own
//! coordinates only (Whitted's tree and the paths' random numbers alike), so a block rendered
//! alone holds the same bits as the same pixels of the whole image.

/// A rectangle of pixels of an image.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PixelRect {
    pub x0: u32,
    pub y0: u32,
    pub width: u32,
    pub height: u32,
}

impl PixelRect {
    /// The whole of a `width`×`height` image.
    pub fn full(width: u32, height: u32) -> Self {
        Self { x0: 0, y0: 0, width, height }
    }

    pub fn pixel_count(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// Whether it has a pixel and lies inside a `width`×`height` image (what both tracers check
    /// before rendering a region).
    pub fn within(&self, width: u32, height: u32) -> bool {
        self.pixel_count() > 0
            && u64::from(self.x0) + u64::from(self.width) <= u64::from(width)
            && u64::from(self.y0) + u64::from(self.height) <= u64::from(height)
    }
}

impl std::fmt::Display for PixelRect {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}x{} at ({}, {})", self.width, self.height, self.x0, self.y0)
    }
}

/// `count` blocks of a `width`×`height` image in `cols` columns and `rows` rows, row by row;
/// the last column and row take what is left.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TileGrid {
    pub cols: u32,
    pub rows: u32,
    pub width: u32,
    pub height: u32,
}

/// Why an image cannot be split as asked.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum TileGridError {
    #[error("a grid needs at least one tile")]
    NoTiles,
    #[error(
        "{count} tiles fit no grid of a {width}x{height} image: the tiles are columns × rows, with at most {} and \
         {} (a pixel each){}",
        counted(*width, "column"),
        counted(*height, "row"),
        nearest_text(*nearest)
    )]
    NoGrid { count: u32, width: u32, height: u32, nearest: (Option<u32>, Option<u32>) },
    #[error("tile {index} of {count}: tiles are numbered 0 to {last}")]
    OutOfRange { index: u32, count: u32, last: u32 },
}

impl TileGrid {
    /// The grid of `count` blocks whose shape is closest to square pixels: `cols` the divisor
    /// of `count` nearest √(count · width / height), so that a prime count gives bands.
    pub fn new(count: u32, width: u32, height: u32) -> Result<Self, TileGridError> {
        if count == 0 {
            return Err(TileGridError::NoTiles);
        }
        let cols = grid_columns(count, width, height).ok_or_else(|| TileGridError::NoGrid {
            count,
            width,
            height,
            nearest: nearest_counts(count, width, height),
        })?;
        Ok(Self { cols, rows: count / cols, width, height })
    }

    pub fn count(&self) -> u32 {
        self.cols * self.rows
    }

    /// Block `index` (row by row from the top left). Blocks are ⌈width / cols⌉ wide and
    /// ⌈height / rows⌉ high; a last column or row that the split leaves empty is not possible
    /// (`new` keeps cols ≤ width and rows ≤ height, and the blocks are split evenly).
    pub fn rect(&self, index: u32) -> Result<PixelRect, TileGridError> {
        let count = self.count();
        if index >= count {
            return Err(TileGridError::OutOfRange { index, count, last: count - 1 });
        }
        let (col, row) = (index % self.cols, index / self.cols);
        // Even splits: column c spans [c·W/cols, (c+1)·W/cols), so every block has a pixel.
        let edge = |i: u32, n: u32, size: u32| (u64::from(i) * u64::from(size) / u64::from(n)) as u32;
        let (x0, x1) = (edge(col, self.cols, self.width), edge(col + 1, self.cols, self.width));
        let (y0, y1) = (edge(row, self.rows, self.height), edge(row + 1, self.rows, self.height));
        Ok(PixelRect { x0, y0, width: x1 - x0, height: y1 - y0 })
    }

    /// "COLSxROWS", as tile files record it.
    pub fn describe(&self) -> String {
        format!("{}x{}", self.cols, self.rows)
    }
}

/// The divisors of `n`, ascending (found up to √n: a count of 4e9 takes 65,536 steps, not 4e9).
fn divisors(n: u32) -> Vec<u32> {
    let mut out = Vec::new();
    let mut i = 1u32;
    while u64::from(i) * u64::from(i) <= u64::from(n) {
        if n.is_multiple_of(i) {
            out.push(i);
            if i != n / i {
                out.push(n / i);
            }
        }
        i += 1;
    }
    out.sort_unstable();
    out
}

/// The columns of the grid of `count` tiles over `width`×`height`: the divisor of `count`
/// nearest √(count·width/height) (the smaller of two as near) among those that leave every
/// tile a pixel (at most `width` columns and `height` rows); `None` where no divisor does.
fn grid_columns(count: u32, width: u32, height: u32) -> Option<u32> {
    let ideal = (f64::from(count) * f64::from(width) / f64::from(height.max(1))).sqrt();
    let fits = |cols: u32| cols <= width && count / cols <= height;
    divisors(count)
        .into_iter()
        .filter(|c| fits(*c))
        .min_by(|a, b| (f64::from(*a) - ideal).abs().total_cmp(&(f64::from(*b) - ideal).abs()))
}

/// How far from a count no grid takes `nearest_counts` looks for one that a grid does.
const NEAREST_SEARCH: u32 = 1000;

/// The nearest counts below and above `count` that some grid of `width`×`height` takes. Beyond
/// width·height pixels no count fits but width·height itself (a pixel a tile).
fn nearest_counts(count: u32, width: u32, height: u32) -> (Option<u32>, Option<u32>) {
    let pixels = u64::from(width) * u64::from(height);
    if u64::from(count) > pixels {
        return (u32::try_from(pixels).ok(), None);
    }
    let fits = |n: &u32| u64::from(*n) <= pixels && grid_columns(*n, width, height).is_some();
    let below = (count.saturating_sub(NEAREST_SEARCH).max(1)..count).rev().find(fits);
    let above = (count.saturating_add(1)..=count.saturating_add(NEAREST_SEARCH)).find(fits);
    (below, above)
}

/// "1 column", "97 columns".
fn counted(n: u32, noun: &str) -> String {
    if n == 1 { format!("1 {noun}") } else { format!("{n} {noun}s") }
}

fn nearest_text(nearest: (Option<u32>, Option<u32>)) -> String {
    match nearest {
        (Some(a), Some(b)) => format!("; the nearest counts that fit one are {a} and {b}"),
        (Some(n), None) | (None, Some(n)) => format!("; the nearest count that fits one is {n}"),
        (None, None) => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_blocks_cover_the_image_once_for_every_count() {
        for (w, h) in [(96, 72), (7, 3), (1920, 1080), (1, 1), (5, 200)] {
            for count in 1..=40 {
                // Counts no grid of this image takes are errors (tested below).
                let Ok(grid) = TileGrid::new(count, w, h) else { continue };
                assert_eq!(grid.count(), count);
                let mut covered = vec![0u8; (w * h) as usize];
                for i in 0..count {
                    let r = grid.rect(i).expect("in range");
                    assert!(r.width > 0 && r.height > 0, "{count} of {w}x{h}: tile {i} is empty");
                    for y in r.y0..r.y0 + r.height {
                        for x in r.x0..r.x0 + r.width {
                            covered[(y * w + x) as usize] += 1;
                        }
                    }
                }
                assert!(covered.iter().all(|&c| c == 1), "{count} of {w}x{h}: not a partition");
            }
        }
    }

    #[test]
    fn the_columns_are_those_a_search_over_every_divisor_gives() {
        // The grid a tile file records must not change: the √ enumeration picks what the plain
        // search over 1..=count picked.
        for (w, h) in [(96, 72), (7, 3), (1920, 1080), (5, 200), (97, 31)] {
            for count in 1..=300u32 {
                let ideal = (f64::from(count) * f64::from(w) / f64::from(h)).sqrt();
                let plain = (1..=count)
                    .filter(|c| count.is_multiple_of(*c) && *c <= w && count / *c <= h)
                    .min_by(|a, b| (f64::from(*a) - ideal).abs().total_cmp(&(f64::from(*b) - ideal).abs()));
                assert_eq!(grid_columns(count, w, h), plain, "{count} of {w}x{h}");
            }
        }
    }

    #[test]
    fn the_grid_is_near_square_and_bad_counts_are_errors() {
        assert_eq!(TileGrid::new(64, 7680, 4320).map(|g| g.describe()), Ok("8x8".to_string()));
        assert_eq!(TileGrid::new(4, 96, 72).map(|g| g.describe()), Ok("2x2".to_string()));
        assert_eq!(TileGrid::new(7, 96, 72).map(|g| g.describe()), Ok("1x7".to_string()));
        assert_eq!(TileGrid::new(0, 96, 72), Err(TileGridError::NoTiles));
        assert_eq!(
            TileGrid::new(13, 2, 2),
            Err(TileGridError::NoGrid { count: 13, width: 2, height: 2, nearest: (Some(4), None) })
        );
        // 101 is prime and above both sides of 97×31 (a user was told "use at most 3007").
        let error = TileGrid::new(101, 97, 31).expect_err("no grid");
        assert_eq!(
            error.to_string(),
            "101 tiles fit no grid of a 97x31 image: the tiles are columns × rows, with at most 97 columns and 31 \
             rows (a pixel each); the nearest counts that fit one are 100 and 102"
        );
        assert_eq!(
            TileGrid::new(4_000_000_000, 1920, 1080),
            Err(TileGridError::NoGrid {
                count: 4_000_000_000,
                width: 1920,
                height: 1080,
                nearest: (Some(2_073_600), None)
            }),
            "more tiles than pixels: a pixel a tile is the most"
        );
        let grid = TileGrid::new(4, 96, 72).unwrap();
        assert_eq!(grid.rect(4), Err(TileGridError::OutOfRange { index: 4, count: 4, last: 3 }));
        assert_eq!(grid.rect(3), Ok(PixelRect { x0: 48, y0: 36, width: 48, height: 36 }));
    }
}
