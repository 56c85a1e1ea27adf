//! The comparisons the viewer has made of the current scene, kept as points of error against
//! samples, depth and render time: the trade-off `glint report` tabulates, seen while editing.
//! Points belong to one scene: an edit of anything but the render settings starts over.

use glint_core::compare::ImageErrors;
use glint_scene::{RenderSettings, SceneDesc};

use crate::render_inputs::SceneInputs;

/// One finished comparison.
#[derive(Clone, Debug, PartialEq)]
pub struct ErrorPoint {
    pub revision: u64,
    pub settings: RenderSettings,
    pub errors: ImageErrors,
    /// GPU render time of the full image.
    pub gpu_ms: f64,
    /// CPU reference time.
    pub cpu_ms: f64,
}

/// What makes two revisions the same scene for the plot: everything the render reads but the
/// render settings (the objects are not edited in the viewer; a new document clears the
/// history), so that under paths an ambient edit keeps the points (`SceneInputs`).
type SceneKey = SceneInputs;

/// The plot's horizontal axis.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    Samples,
    Depth,
    GpuTime,
}

impl Axis {
    pub const ALL: [Self; 3] = [Self::Samples, Self::Depth, Self::GpuTime];

    pub fn label(self) -> &'static str {
        match self {
            Self::Samples => "samples per pixel",
            Self::Depth => "max depth",
            Self::GpuTime => "GPU time (ms)",
        }
    }

    pub fn value(self, p: &ErrorPoint) -> f64 {
        match self {
            Self::Samples => f64::from(p.settings.spp),
            Self::Depth => f64::from(p.settings.max_depth),
            Self::GpuTime => p.gpu_ms,
        }
    }

    /// Whether `p` differs from `current` only along this axis (for samples and depth: the
    /// other settings equal; against time every point of the scene counts).
    fn comparable(self, p: &RenderSettings, current: &RenderSettings) -> bool {
        match self {
            Self::Samples => RenderSettings { spp: current.spp, ..p.clone() } == *current,
            Self::Depth => RenderSettings { max_depth: current.max_depth, ..p.clone() } == *current,
            Self::GpuTime => true,
        }
    }
}

#[derive(Clone, Debug, Default)]
pub struct ErrorHistory {
    key: Option<SceneKey>,
    points: Vec<ErrorPoint>,
}

impl ErrorHistory {
    /// Adds a comparison of `desc` (once per revision); another scene starts a new history.
    pub fn record(&mut self, desc: &SceneDesc, point: ErrorPoint) {
        if self.points.iter().any(|p| p.revision == point.revision) {
            return;
        }
        let key = SceneKey::of(desc);
        if self.key.as_ref() != Some(&key) {
            self.points.clear();
            self.key = Some(key);
        }
        // One point per setting: the latest measurement of the same settings replaces it.
        self.points.retain(|p| p.settings != point.settings);
        self.points.push(point);
    }

    /// Forgets every point (a new document).
    pub fn clear(&mut self) {
        *self = Self::default();
    }

    /// The points to plot against `axis` for the `current` settings, sorted along it.
    pub fn along(&self, axis: Axis, current: &RenderSettings) -> Vec<&ErrorPoint> {
        let mut points: Vec<&ErrorPoint> =
            self.points.iter().filter(|p| axis.comparable(&p.settings, current)).collect();
        points.sort_by(|a, b| axis.value(a).total_cmp(&axis.value(b)));
        points
    }

    pub fn len(&self) -> usize {
        self.points.len()
    }

    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(revision: u64, spp: u32, depth: u32, rmse: f64) -> ErrorPoint {
        ErrorPoint {
            revision,
            settings: RenderSettings { spp, max_depth: depth, ..RenderSettings::default() },
            errors: ImageErrors { rmse, ..ImageErrors::default() },
            gpu_ms: f64::from(spp),
            cpu_ms: 1.0,
        }
    }

    #[test]
    fn points_of_one_scene_line_up_along_each_axis_and_another_scene_starts_over() {
        let (desc, _) = glint_io::builtin("whitted").expect("built-in").load(None).expect("loads");
        let mut h = ErrorHistory::default();
        for (rev, spp, depth) in [(1, 4, 5), (2, 1, 5), (3, 1, 2), (4, 16, 5)] {
            h.record(&desc, point(rev, spp, depth, 1.0 / f64::from(spp)));
        }
        h.record(&desc, point(4, 16, 5, 0.0));
        assert_eq!(h.len(), 4, "a revision is recorded once");
        let current = RenderSettings { spp: 1, max_depth: 5, ..RenderSettings::default() };
        let spp: Vec<u32> = h.along(Axis::Samples, &current).iter().map(|p| p.settings.spp).collect();
        assert_eq!(spp, [1, 4, 16], "depth 2 is another series");
        let depth: Vec<u32> = h.along(Axis::Depth, &current).iter().map(|p| p.settings.max_depth).collect();
        assert_eq!(depth, [2, 5]);
        assert_eq!(h.along(Axis::GpuTime, &current).len(), 4);
        // The same settings measured again replace the older point.
        h.record(&desc, point(5, 4, 5, 0.5));
        assert_eq!(h.len(), 4);
        let mut other = desc.clone();
        other.world.ambient = glint_scene::Rgb::splat(0.5);
        h.record(&other, point(6, 1, 5, 0.1));
        assert_eq!(h.len(), 1, "another scene starts a new history");
    }

    #[test]
    fn under_paths_the_ambient_terms_are_the_same_scene() {
        // The paths read no ambient term: after applying a fitted I_a the next point kept
        // nothing before it (a reviewer).
        let (mut desc, _) = glint_io::builtin("cornell-gi").expect("built-in").load(None).expect("loads");
        desc.render.integrator = glint_scene::Integrator::Path;
        let mut h = ErrorHistory::default();
        h.record(&desc, point(1, 1, 5, 1.0));
        desc.world.ambient = glint_scene::Rgb::splat(0.3);
        desc.materials.values_mut().for_each(|m| m.ka = glint_scene::Rgb::splat(0.7));
        h.record(&desc, point(2, 4, 5, 0.5));
        assert_eq!(h.len(), 2);
        desc.materials.values_mut().for_each(|m| m.kd = glint_scene::Rgb::splat(0.7));
        h.record(&desc, point(3, 16, 5, 0.25));
        assert_eq!(h.len(), 1, "a k_d edit is another scene");
    }
}
