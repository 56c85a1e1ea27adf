//! The path-traced image split by the kind of light its paths bring back (`PathKind`): what
//! Whitted's model leaves out, by kind. Each kind's image is a render that leaves out the
//! others (`SceneHeader::omit_kinds`, read by both tracers); with the same seed every kind's
//! render traces the same paths, so the four add up to the whole image.

use glam::DVec3;
use glint_types::PathKind;

use crate::cpu::emitter::Emitters;
use crate::cpu::path::{path_bounce, start_path};
use crate::cpu::{RayCounts, TraceContext};
use crate::flat::FlatScene;

/// `scene` rendering the light of `kind` alone.
pub fn kind_alone(scene: &FlatScene, kind: PathKind) -> FlatScene {
    let mut s = scene.clone();
    s.header.omit_kinds = kind.alone();
    s
}

/// A pixel's path-traced radiance by bounce (the row: where the light was added, 0 at the
/// first hit) and by kind (the column, in `PathKind::ALL` order): the mean over `spp` samples.
#[derive(Clone, Debug, PartialEq)]
pub struct PathProbe {
    pub by_bounce: Vec<[DVec3; 4]>,
    pub spp: u32,
}

impl PathProbe {
    /// Each kind's radiance over all bounces.
    pub fn by_kind(&self) -> [DVec3; 4] {
        let mut sum = [DVec3::ZERO; 4];
        for row in &self.by_bounce {
            for (s, v) in sum.iter_mut().zip(row) {
                *s += *v;
            }
        }
        sum
    }

    pub fn total(&self) -> DVec3 {
        self.by_kind().iter().sum()
    }
}

/// The path tracer's radiance at pixel (x, y) by bounce and kind, over its first `spp` samples
/// (the image's own paths): each kind's samples are traced with the others left out, and what
/// each bounce adds is recorded.
pub fn probe_paths(ctx: &TraceContext, x: u32, y: u32, spp: u32) -> PathProbe {
    let emitters = Emitters::of(ctx);
    let mut counts = RayCounts::default();
    let mut by_bounce: Vec<[DVec3; 4]> = Vec::new();
    let spp = spp.max(1);
    for (column, kind) in PathKind::ALL.into_iter().enumerate() {
        let alone = TraceContext { omit_kinds: kind.alone(), ..ctx.clone() };
        for sample in 0..spp {
            let mut path = start_path(&alone, x, y, sample, &mut counts);
            loop {
                let (depth, before) = (path.depth as usize, path.radiance);
                let goes_on = path_bounce(&alone, &emitters, &mut path, &mut counts);
                if by_bounce.len() <= depth {
                    by_bounce.resize(depth + 1, [DVec3::ZERO; 4]);
                }
                by_bounce[depth][column] += (path.radiance - before) / f64::from(spp);
                if !goes_on {
                    break;
                }
            }
        }
    }
    PathProbe { by_bounce, spp }
}
