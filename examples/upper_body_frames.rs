//! Render postures of the Nao upper body (`models/nao_upper_body.xml`) off-screen, one PNG per
//! keyframe, from one of the model's cameras: a look at the model and at the view a clip of
//! both arms would have. With `--apexes FILE`, one sheet instead: a demonstration of every
//! upper-body gesture (recorded from the simulated encoders, seed `--seed`) at its apex, where
//! its signature is at its extreme (`experiment::signature::apex`; docs/METRICS.md, "Gesture
//! signatures"), each labelled with its signature's measure.
//!
//! ```sh
//! cargo run --example upper_body_frames -- --out /tmp/upper --camera front StandInit ArmsOpen
//! cargo run --release --example upper_body_frames -- --width 360 --apexes docs/figures/upper-body-apexes.png
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
    /// Instead: every upper-body gesture's demonstration at its apex, on one sheet (PNG).
    #[arg(long)]
    apexes: Option<PathBuf>,
    /// The demonstrations' seed (with --apexes).
    #[arg(long, default_value_t = 41)]
    seed: u64,
}

/// Every upper-body gesture's first demonstration of `seed` at its apex, labelled, on a sheet
/// of four columns written to `path`.
fn apexes(path: &std::path::Path, options: RenderOptions, seed: u64) -> Result<()> {
    use cosco_hsom::experiment::demonstrate::{record_demonstrations, DemoSettings};
    use cosco_hsom::experiment::signature::{apex, signature};
    use cosco_hsom::gesture::Gesture;
    use cosco_hsom::robot::Robot;
    use cosco_hsom::sim::NaoArm;
    let arm = NaoArm::<14>::load_shipped(Robot::UpperBody)?;
    let mut renderer = Renderer::new(arm.model(), options)?;
    let mut sim = arm.sim()?;
    let mut frames = Vec::new();
    for g in Gesture::every(Robot::UpperBody) {
        let rec =
            record_demonstrations(&arm, &g, 1, seed, &DemoSettings::default(), |_| {})?.remove(0);
        let k = apex(&arm, g.name, &rec.qpos)?.context("an empty demonstration")?;
        let s = signature(&arm, g.name, &rec.qpos)?.context("a gesture without a signature")?;
        sim.set_posture_clamped(&rec.qpos[k])?;
        let label = format!("{}  t {:.1} s  {:.2}", g.name, rec.time[k], s.measured);
        frames.push((Some(label), renderer.render(sim.data())?));
        println!(
            "{}: {} {:.3} ({})",
            g.name,
            s.rule,
            s.measured,
            if s.holds { "holds" } else { "misses" }
        );
    }
    let refs: Vec<(Option<String>, &image::RgbImage)> =
        frames.iter().map(|(l, f)| (l.clone(), f)).collect();
    let sheet = cosco_hsom::render::contact_sheet(&refs, 4)?;
    cosco_hsom::render::save_png(&sheet, path)?;
    println!("{}", path.display());
    Ok(())
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
    if let Some(path) = &args.apexes {
        return apexes(path, options, args.seed);
    }
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
