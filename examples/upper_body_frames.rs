//! Render postures of the Nao upper body (`models/nao_upper_body.xml`) off-screen, one PNG per
//! keyframe, from one of the model's cameras: a look at the model and at the view a clip of
//! both arms would have.
//!
//! ```sh
//! cargo run --example upper_body_frames -- --out /tmp/upper --camera front StandInit ArmsOpen
//! ```

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::Parser;

use cosco_hsom::mujoco::{Data, Model};
use cosco_hsom::render::{RenderOptions, Renderer};

/// One PNG per keyframe of the upper-body model.
#[derive(Parser, Debug)]
struct Args {
    /// Directory the PNGs are written into (created if missing), one `<camera>_<keyframe>.png` each.
    #[arg(long, default_value = "/tmp/upper_body_frames")]
    out: PathBuf,
    /// The model's camera to render from.
    #[arg(long, default_value = "front")]
    camera: String,
    /// Image width in pixels (the height is 3/4 of it).
    #[arg(long, default_value_t = 480)]
    width: usize,
    /// The MJCF model.
    #[arg(long, default_value = concat!(env!("CARGO_MANIFEST_DIR"), "/models/nao_upper_body.xml"))]
    model: PathBuf,
    /// Keyframe names (default: every keyframe of the model).
    keys: Vec<String>,
}

fn main() -> Result<()> {
    let args = Args::parse();
    let model = Model::from_xml_path(&args.model)?;
    let keys: Vec<usize> = if args.keys.is_empty() {
        (0..model.nkey()).collect()
    } else {
        let mut ids = Vec::new();
        for name in &args.keys {
            match model.key_id(name) {
                Some(id) => ids.push(id),
                None => bail!("{}: no keyframe named {name:?}", args.model.display()),
            }
        }
        ids
    };
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    let options = RenderOptions {
        width: args.width,
        height: args.width * 3 / 4,
        shadows: true,
        multisample: true,
        camera: Some(args.camera.clone()),
    };
    let mut renderer = Renderer::new(&model, options)?;
    let mut data = Data::new(&model)?;
    for key in keys {
        data.reset_to_key(key);
        data.forward()?;
        let name = model.key_name(key).unwrap_or_else(|| format!("key{key}"));
        let path = args.out.join(format!("{}_{name}.png", args.camera));
        renderer.render_to_png(&data, &path)?;
        println!("{}", path.display());
    }
    Ok(())
}
