//! The error type of the rendering layer.

use crate::mujoco::MjError;
use std::path::PathBuf;
use thiserror::Error;

/// Everything that can go wrong when rendering or writing images.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum RenderError {
    /// The requested size is larger than the model's off-screen buffer.
    #[error(
        "render size {width}x{height} exceeds the model's off-screen buffer {max_width}x{max_height}; \
         raise it in the MJCF with <visual><global offwidth=\"{width}\" offheight=\"{height}\"/></visual>"
    )]
    TooLarge {
        /// Requested width.
        width: usize,
        /// Requested height.
        height: usize,
        /// The model's `offwidth`.
        max_width: usize,
        /// The model's `offheight`.
        max_height: usize,
    },
    /// A width or height of zero.
    #[error("render size {width}x{height} is empty: width and height must be at least 1")]
    EmptySize {
        /// Requested width.
        width: usize,
        /// Requested height.
        height: usize,
    },
    /// The camera named in the options is not in the model.
    #[error("no camera named {name:?} in the model (cameras: {available}); use None for the free camera")]
    CameraNotFound {
        /// The name asked for.
        name: String,
        /// The model's camera names, comma-separated.
        available: String,
    },
    /// OSMesa or MuJoCo's OpenGL context could not be created or used.
    #[error("off-screen OpenGL context: {0}")]
    Context(String),
    /// The state handed to `render` belongs to another model than the renderer's.
    #[error("the Data passed to render() belongs to another Model than the Renderer's")]
    WrongModel,
    /// A MuJoCo error (raised while building the scene or context).
    #[error(transparent)]
    MuJoCo(#[from] MjError),
    /// A clip or contact sheet without frames.
    #[error("{0}: no frames were collected")]
    NoFrames(&'static str),
    /// Frames of different sizes in one clip.
    #[error("frame {index} is {got:?}, the clip's frames are {expected:?}")]
    FrameSize {
        /// Index of the offending frame.
        index: usize,
        /// Its size.
        got: (u32, u32),
        /// The size of the first frame.
        expected: (u32, u32),
    },
    /// Invalid settings of a clip or contact sheet.
    #[error("invalid {field}: {value} ({why})")]
    Invalid {
        /// The setting.
        field: &'static str,
        /// Its value.
        value: String,
        /// What is expected.
        why: &'static str,
    },
    /// Encoding an image failed.
    #[error("cannot encode {what}: {source}")]
    Encode {
        /// PNG, GIF...
        what: &'static str,
        /// The encoder's error.
        source: image::ImageError,
    },
    /// Encoding a GIF failed.
    #[error("cannot encode GIF: {0}")]
    Gif(#[from] gif::EncodingError),
    /// Writing a file failed.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
}

/// Result of the rendering layer.
pub type Result<T> = std::result::Result<T, RenderError>;
