//! What the user selected: the object picked in the view, the material and the light shown in
//! their panels.

#[derive(Debug, Default)]
pub struct Selection {
    pub object: Option<usize>,
    pub material: Option<String>,
    /// Index into the scene's lights.
    pub light: usize,
}
