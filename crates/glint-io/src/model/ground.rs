//! Where the ground under an opened model goes (`--ground`), so that it is never coplanar
//! with the model's own faces: two coplanar surfaces z-fight, and each tracer picks its own
//! winner pixel by pixel.

use std::str::FromStr;

use glint_scene::{FieldIssue, MeshDesc, storage_origin_of_box};
use glint_types::layout::f32_spacing;

/// Whether an opened model stands on a grey ground plane.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Ground {
    /// A ground unless the model has its own floor (upward faces at its lowest y covering at
    /// least `FLOOR_COVER` of its footprint).
    #[default]
    Auto,
    On,
    Off,
}

impl Ground {
    pub const ALL: [Self; 3] = [Self::Auto, Self::On, Self::Off];

    pub fn name(self) -> &'static str {
        match self {
            Self::Auto => "auto",
            Self::On => "on",
            Self::Off => "off",
        }
    }
}

impl FromStr for Ground {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Self::ALL.into_iter().find(|g| g.name() == s.trim()).ok_or_else(|| {
            let names: Vec<_> = Self::ALL.iter().map(|g| g.name()).collect();
            format!("'{s}' is not a ground mode: use one of {}", names.join(", "))
        })
    }
}

/// The gap between the model's lowest point and the ground, as a fraction of the model's
/// bounding-box diagonal: above f32 rounding and the tracers' ε (a model's is 1e-6 of its size
/// at most), below what a pixel shows. At 1e-3 a model filling a 120-pixel frame stood 0.12
/// pixel above the ground, and one pixel centre in eight along its base saw the shadowed
/// ground through the gap: a dotted line under every flat-bottomed model.
pub const GROUND_GAP: f64 = 1e-5;

/// The least gap in f32 spacings at the model's stored magnitude (relative to the scene's
/// storage origin, `glint_scene::storage_origin`): a model that spans far more than its
/// details would otherwise round its base and the ground to the same f32.
const MIN_GAP_ULPS: f64 = 64.0;

/// The least gap in f64 spacings at the model's world coordinates: the ground is a plane
/// written there, and so is every placed vertex. A model 1e-6 wide at 5e5 had a gap of 1.7e-11,
/// below f64's step there (5.8e-11): the ground rounded onto its base and was warned of as
/// z-fighting with it, a plane the user never wrote (a tester). Few: at 9e8 f64's step is 1.2e-7,
/// and a model 1e-6 wide there stands that many steps above the ground.
const MIN_GAP_F64_ULPS: f64 = 4.0;

/// The share of the footprint that upward faces at the lowest y must cover to be a floor.
pub const FLOOR_COVER: f64 = 0.5;

/// The ground's height for a model with bounds `lo`..`hi` (`None`: no ground), and a note
/// saying why when `Auto` left it out.
pub fn ground_height(
    meshes: &[MeshDesc],
    lo: [f64; 3],
    hi: [f64; 3],
    mode: Ground,
) -> (Option<f64>, Option<FieldIssue>) {
    let diagonal = (0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
    // As both tracers store the model and the ground: relative to the scene's storage origin,
    // which the ground (a plane) does not move.
    let origin = storage_origin_of_box(lo, hi);
    let magnitude = (0..3).fold(0.0_f64, |m, k| m.max((lo[k] - origin[k]).abs()).max((hi[k] - origin[k]).abs()));
    let spacing = f32_spacing(magnitude);
    let world = lo.iter().chain(&hi).fold(0.0_f64, |m, c| m.max(c.abs()));
    let gap =
        (GROUND_GAP * diagonal).max(MIN_GAP_ULPS * spacing).max(MIN_GAP_F64_ULPS * glint_scene::f64_spacing(world));
    let below = lo[1] - gap;
    match mode {
        Ground::Off => (None, None),
        Ground::On => (Some(below), None),
        Ground::Auto => {
            let cover = floor_cover(meshes, lo, hi, 1e-6 * diagonal + 4.0 * spacing);
            if cover >= FLOOR_COVER {
                let note = FieldIssue {
                    field: "--ground".into(),
                    problem: format!(
                        "the model has its own floor (upward faces at its lowest y cover {:.0} % of its footprint): \
                         no ground added (`--ground on` adds one just below it)",
                        100.0 * cover.min(1.0)
                    ),
                };
                (None, Some(note))
            } else {
                (Some(below), None)
            }
        }
    }
}

/// The share of the model's x–z footprint covered by triangles that lie at its lowest y
/// (every corner within `tolerance`) and face up (counter-clockwise seen from above).
fn floor_cover(meshes: &[MeshDesc], lo: [f64; 3], hi: [f64; 3], tolerance: f64) -> f64 {
    let footprint = (hi[0] - lo[0]) * (hi[2] - lo[2]);
    if footprint.is_nan() || footprint <= 0.0 {
        return 0.0;
    }
    let mut area = 0.0;
    for mesh in meshes {
        for t in &mesh.triangles {
            let Some(p) = t.map(|i| mesh.vertices.get(i as usize).copied()).into_iter().collect::<Option<Vec<_>>>()
            else {
                continue;
            };
            if p.iter().any(|v| v[1] - lo[1] > tolerance) {
                continue;
            }
            // The y component of (b − a) × (c − a): twice the signed x–z area, positive for an
            // upward face.
            let (u, v) = ([p[1][0] - p[0][0], p[1][2] - p[0][2]], [p[2][0] - p[0][0], p[2][2] - p[0][2]]);
            let up = u[1] * v[0] - u[0] * v[1];
            if up > 0.0 {
                area += 0.5 * up;
            }
        }
    }
    area / footprint
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quad(y: f64, up: bool) -> MeshDesc {
        let vertices = vec![[0.0, y, 0.0], [1.0, y, 0.0], [1.0, y, 1.0], [0.0, y, 1.0]];
        let triangles = if up { vec![[0, 2, 1], [0, 3, 2]] } else { vec![[0, 1, 2], [0, 2, 3]] };
        MeshDesc::new(vertices, triangles, "m", "quad")
    }

    #[test]
    fn an_upward_quad_at_the_bottom_is_a_floor_and_a_downward_one_is_not() {
        let (lo, hi) = ([0.0, 0.0, 0.0], [1.0, 0.0, 1.0]);
        let (height, note) = ground_height(&[quad(0.0, true)], lo, hi, Ground::Auto);
        assert_eq!(height, None);
        assert!(note.is_some_and(|n| n.problem.contains("100 %")));
        let (height, note) = ground_height(&[quad(0.0, false)], lo, hi, Ground::Auto);
        assert!(height.is_some_and(|h| h < 0.0) && note.is_none(), "{height:?}");
    }

    #[test]
    fn the_ground_is_never_at_the_models_lowest_y_as_stored_and_keeps_its_gap_far_away() {
        // Stored relative to the storage origin, as both tracers store them; far from the world
        // origin the gap is the model's own (1e-5 of its diagonal), as at the origin.
        for base in [0.0, 1e4, 1e6, -3e7] {
            let (lo, hi) = ([0.0, base, 0.0], [1.0, base + 1.0, 1.0]);
            let (height, _) = ground_height(&[], lo, hi, Ground::On);
            let h = height.expect("on");
            let o = storage_origin_of_box(lo, hi)[1];
            assert!(((h - o) as f32) < ((base - o) as f32), "ground {h} rounds onto the base {base} in f32");
            assert!((base - h - GROUND_GAP * 3f64.sqrt()).abs() < 1e-6, "ground {h} under {base}");
        }
        // A model spanning 1e6 from the world origin (stored there): the gap is f32's.
        let (height, _) = ground_height(&[], [0.0, 1e6, 0.0], [1e6, 1e6 + 1.0, 1.0], Ground::On);
        let h = height.expect("on");
        assert!((h as f32) < (1e6f32) && 1e6 - h >= 64.0 * 0.0625, "ground {h}");
        assert_eq!(ground_height(&[quad(0.0, true)], [0.0; 3], [1.0, 0.0, 1.0], Ground::Off), (None, None));
        // A model 1e-6 wide at 5e5 (stored beside it): its own gap, 1.7e-11, is below f64's step
        // at 1e6 (1.2e-10), where the ground and the base are written; 4 of those steps.
        let (lo, hi) = ([1e6, 5e5 - 5e-7, -1e6], [1e6 + 1e-6, 5e5 + 5e-7, -1e6 + 1e-6]);
        let h = ground_height(&[], lo, hi, Ground::On).0.expect("on");
        assert_eq!(lo[1] - h, 4.0 * 2f64.powi(19 - 52), "ground {h} under {}", lo[1]);
    }

    #[test]
    fn ground_modes_parse_by_name_and_refuse_others() {
        for g in Ground::ALL {
            assert_eq!(g.name().parse::<Ground>(), Ok(g));
        }
        assert!("yes".parse::<Ground>().unwrap_err().contains("auto, on, off"));
    }
}
