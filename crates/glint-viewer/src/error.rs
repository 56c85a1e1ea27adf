//! Errors the viewer reports in its UI (never as a panic).

use std::path::PathBuf;

#[derive(Debug, thiserror::Error)]
pub enum ViewerError {
    #[error(transparent)]
    Scene(#[from] glint_io::SceneError),
    /// The I/O error is part of the message, not a `source()`: see `SceneError::Io`.
    #[error("{path}: cannot write the scene: {error}")]
    SaveScene { path: PathBuf, error: std::io::Error },
    #[error("cannot serialise the scene: {0}")]
    Serialise(String),
    #[error(transparent)]
    Image(#[from] glint_io::image_file::ImageWriteError),
    #[error("{}: an image is saved as .png (sRGB, the settings embedded) or .exr (linear); name it so", .0.display())]
    ImageFormat(PathBuf),
    #[error("nothing to save yet: {0}")]
    NotReady(&'static str),
    #[error(
        "no display: the viewer needs a window (DISPLAY or WAYLAND_DISPLAY is not set). \
         Render without a window with `glint render`"
    )]
    NoDisplay,
    #[error("cannot open the viewer window ({0}). Render without a window with `glint render`")]
    Window(String),
    #[error("{0}")]
    Automation(String),
}
