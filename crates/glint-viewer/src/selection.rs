//! What the user selected: the object picked in the view, the material and the light shown in
//! their panels, and the object's outline.

use std::borrow::Cow;

use crate::outline::{Segment, outline};

/// Where an outline's first hits come from: the GPU's image, the CPU's, or each pixel's centre
/// traced on the CPU (a jittered render's first hits, a path's first sample, fall anywhere in
/// the pixel, and their outline was ragged).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Hits {
    Gpu,
    Cpu,
    Centres,
}

#[derive(Debug, Default)]
pub struct Selection {
    pub object: Option<usize>,
    pub material: Option<String>,
    /// Index into the scene's lights.
    pub light: usize,
    /// The selected object's outline and what it was traced from: (revision, object, hits).
    /// Kept between frames: finding it reads every pixel's first hit.
    outline: Option<(u64, usize, Hits, Vec<Segment>)>,
}

impl Selection {
    /// The outline of the selected object, from the first hits `source` names as of revision
    /// `revision` (the document's for an image; for centres, the last that could move one),
    /// which `hits` gives (the image's width and its hits) when the outline must be found
    /// again; empty with nothing selected or no hits of the revision.
    pub fn outline<'a>(
        &mut self,
        revision: u64,
        source: Option<Hits>,
        hits: impl FnOnce(Hits) -> Option<(u32, Cow<'a, [u32]>)>,
    ) -> &[Segment] {
        let (Some(object), Some(source)) = (self.object, source) else { return &[] };
        let fresh = self.outline.as_ref().is_some_and(|o| (o.0, o.1, o.2) == (revision, object, source));
        if !fresh {
            // Object ids in the images are scene order: the id is the object's index.
            let segments = hits(source).map_or_else(Vec::new, |(w, hits)| outline(w, &hits, object as u32));
            self.outline = Some((revision, object, source, segments));
        }
        self.outline.as_ref().map_or(&[], |o| &o.3)
    }
}
