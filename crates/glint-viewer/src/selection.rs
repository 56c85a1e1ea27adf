//! What the user selected: the object picked in the view, the material and the light shown in
//! their panels.

use glint_core::HdrImage;

use crate::outline::{Segment, outline};

#[derive(Debug, Default)]
pub struct Selection {
    pub object: Option<usize>,
    pub material: Option<String>,
    /// Index into the scene's lights.
    pub light: usize,
    /// The selected object's outline and what it was traced from: (revision, object, from the
    /// GPU image). Kept between frames: finding it reads every pixel of the image.
    outline: Option<(u64, usize, bool, Vec<Segment>)>,
}

impl Selection {
    /// The outline of the selected object in `image` (the first hits of `revision`, from the
    /// GPU image or the CPU one); empty with nothing selected or no image of the revision.
    pub fn outline(&mut self, revision: u64, image: Option<(&HdrImage, bool)>) -> &[Segment] {
        let (Some(object), Some((image, from_gpu))) = (self.object, image) else { return &[] };
        let fresh = self.outline.as_ref().is_some_and(|o| (o.0, o.1, o.2) == (revision, object, from_gpu));
        if !fresh {
            // Object ids in the images are scene order: the id is the object's index.
            self.outline = Some((revision, object, from_gpu, outline(image, object as u32)));
        }
        self.outline.as_ref().map_or(&[], |o| &o.3)
    }
}
