//! The outline of the selected object over the images: the edges between the pixels whose
//! first hit is the object and the others (another object, the background, the image's edge).

/// One straight edge of the outline, in pixel-corner coordinates (origin top-left, x right).
pub type Segment = [(u32, u32); 2];

/// The outline of the pixels whose first hit is `object`, of an image `width` wide whose first
/// hits are `hits`, row by row. Runs of unit edges along a row or column are merged into one
/// segment, so a straight side costs one line to draw.
pub fn outline(width: u32, hits: &[u32], object: u32) -> Vec<Segment> {
    let w = i64::from(width.max(1));
    let h = hits.len() as i64 / w;
    let inside = |x: i64, y: i64| (0..w).contains(&x) && (0..h).contains(&y) && hits[(y * w + x) as usize] == object;
    let mut out = Vec::new();
    // Horizontal edges: on line y, between rows y − 1 and y.
    for y in 0..=h {
        runs(w, |x| inside(x, y - 1) != inside(x, y), |x0, x1| out.push([(x0, y as u32), (x1, y as u32)]));
    }
    // Vertical edges: on line x, between columns x − 1 and x.
    for x in 0..=w {
        runs(h, |y| inside(x - 1, y) != inside(x, y), |y0, y1| out.push([(x as u32, y0), (x as u32, y1)]));
    }
    out
}

/// Calls `emit(start, end)` for each maximal run of `0..n` where `edge` holds.
fn runs(n: i64, edge: impl Fn(i64) -> bool, mut emit: impl FnMut(u32, u32)) {
    let mut start = None;
    for i in 0..=n {
        match (i < n && edge(i), start) {
            (true, None) => start = Some(i),
            (false, Some(s)) => {
                emit(s as u32, i as u32);
                start = None;
            }
            _ => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glint_types::layout::NO_HIT;

    #[test]
    fn a_block_is_outlined_by_its_four_sides() {
        let n = NO_HIT;
        #[rustfmt::skip]
        let hits = [
            n, n, n, n,
            n, 7, 7, n,
            n, 7, 7, n,
        ];
        let mut segments = outline(4, &hits, 7);
        segments.sort_unstable();
        assert_eq!(segments, vec![[(1, 1), (1, 3)], [(1, 1), (3, 1)], [(1, 3), (3, 3)], [(3, 1), (3, 3)]]);
        assert!(outline(4, &hits, 3).is_empty(), "an object not in the image has no outline");
    }
}
