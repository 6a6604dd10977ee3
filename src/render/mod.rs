//! Off-screen rendering of a MuJoCo model with OSMesa (no display needed): frames as
//! [`image::RgbImage`], PNG files, animated GIF clips and PNG contact sheets.
//!
//! - [`Renderer`]: an owned OSMesa context with MuJoCo's scene and GPU context;
//! - [`Clip`]: frames collected during a simulation, written as a GIF and a contact sheet;
//! - [`project`]: where a point of the world appears in a camera's frame.
//!
//! ```
//! use cosco_hsom::mujoco::{Data, Model};
//! use cosco_hsom::render::{RenderOptions, Renderer};
//! let model = Model::from_xml_str(
//!     r#"<mujoco><worldbody><light pos="0 0 3"/><geom type="plane" size="1 1 0.1"/>
//!        <body pos="0 0 0.2"><freejoint/><geom type="box" size="0.1 0.1 0.1" rgba="1 0 0 1"/>
//!        </body></worldbody></mujoco>"#,
//! )?;
//! let mut data = Data::new(&model)?;
//! data.forward()?;
//! let mut renderer = Renderer::new(&model, RenderOptions { width: 160, height: 120, ..Default::default() })?;
//! let frame = renderer.render(&data)?;
//! assert_eq!(frame.dimensions(), (160, 120));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod animation;
mod clip;
mod error;
mod font;
mod offscreen;
mod project;

pub use clip::{contact_sheet, Clip};
pub use error::{RenderError, Result};
pub use offscreen::{save_png, RenderOptions, Renderer};
pub use project::project;
