//! Render postures of the Nao upper body (`models/nao_upper_body.xml`) off-screen, one PNG per
//! keyframe, from one of the model's cameras: a look at the model and at the view a clip of
//! both arms would have. With `--apexes FILE`, one sheet instead: a demonstration of every
//! upper-body gesture (recorded from the simulated encoders, seed `--seed`) at its apex, where
//! its signature is at its extreme (`experiment::signature::apex`; docs/METRICS.md, "Gesture
//! signatures"), each labelled with its signature's measure. With `--pointing FILE`, a sheet
//! of the pointing gestures aimed at targets (`cosco reproduce --point-at --look-at`): each a
//! held-out reproduction executed on the simulated upper body, at the middle of its held part,
//! with the direction from the shoulder to the target (red) and from the top camera to it
//! (blue) drawn in, and the executed angles in the label.
//!
//! ```sh
//! cargo run --example upper_body_frames -- --out /tmp/upper --camera front StandInit ArmsOpen
//! cargo run --release --example upper_body_frames -- --width 360 --apexes docs/figures/upper-body-apexes.png
//! cargo run --release --example upper_body_frames -- --width 480 --pointing docs/figures/pointing.png
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
    /// The demonstrations' seed (with --apexes and --pointing).
    #[arg(long, default_value_t = 41)]
    seed: u64,
    /// Instead: the pointing gestures aimed at three targets, on one sheet (PNG).
    #[arg(long)]
    pointing: Option<PathBuf>,
}

/// The upper body's model with each ray `(from, to, rgba)` drawn (a thin capsule that touches
/// nothing), a sphere at `dot`, and the camera `front_right` (`front_left` mirrored).
fn with_rays(xml: &str, rays: &[([f64; 3], [f64; 3], &str)], dot: [f64; 3]) -> String {
    let mut geoms = String::new();
    for (a, b, rgba) in rays {
        geoms += &format!(
            r#"<geom type="capsule" fromto="{} {} {} {} {} {}" size="0.003" rgba="{rgba}" contype="0" conaffinity="0"/>"#,
            a[0], a[1], a[2], b[0], b[1], b[2]
        );
    }
    geoms += &format!(
        r#"<geom type="sphere" pos="{} {} {}" size="0.012" rgba="0.9 0.15 0.1 1" contype="0" conaffinity="0"/>"#,
        dot[0], dot[1], dot[2]
    );
    geoms += r#"<camera name="front_right" pos="0.8 -0.62 0.36" xyaxes="0.6126 0.7904 0 -0.2177 0.1687 0.9613" fovy="45"/>"#;
    xml.replacen("</worldbody>", &format!("{geoms}</worldbody>"), 1)
}

/// The pointing gestures aimed at three targets within view (held out: learned from three
/// demonstrations of `seed`, reproduced from a fourth's first posture, aimed with
/// `--point-at` and `--look-at` at the target, executed), each at the middle of its held part,
/// on a sheet of three columns written to `path`.
fn pointing(path: &std::path::Path, options: RenderOptions, seed: u64) -> Result<()> {
    use cosco_hsom::aim::{self, Aim};
    use cosco_hsom::condition::Conditions;
    use cosco_hsom::experiment::demonstrate::{record_demonstrations, DemoSettings};
    use cosco_hsom::gesture::Gesture;
    use cosco_hsom::robot::Robot;
    use cosco_hsom::sim::{execute_postures, NaoArm};
    let robot = Robot::UpperBody;
    let xml = std::fs::read_to_string(robot.model_path())?;
    let arm = NaoArm::<14>::load_shipped(robot)?;
    let cfg = cosco_hsom::config::load_config(std::path::Path::new("configs/nao-upper-body.xml"))?;
    // each in view of the camera (`front_left` mirrored: from the robot's right, in front)
    let shots = [
        ("point-left", [0.5, 0.45, 0.2], "front_right"),
        ("point-right", [0.55, -0.5, 0.3], "front_right"),
        ("point-right", [0.4, -0.55, 0.6], "front_right"),
    ];
    let mut frames = Vec::new();
    for (name, target, camera) in shots {
        let g = Gesture::by_name(robot, name).context("a pointing gesture")?;
        let demos: Vec<_> =
            record_demonstrations(&arm, &g, 4, seed, &DemoSettings::default(), |_| {})?
                .iter()
                .map(|r| r.to_demonstration(g.name))
                .collect();
        let model = cfg.fit(&demos[..3])?;
        let initial = &demos[3].rows[0];
        let plain = model.reproduce(initial)?.postures;
        let want = Aim {
            point_at: Some(target),
            look_at: Some(target),
        };
        let (c, solved) = aim::aim_conditions(robot, &plain, &Conditions::default(), &want)?;
        let rows = model
            .reproduce_conditioned(initial, &c, Some(&robot.ranges()))?
            .postures;
        let executed = execute_postures(&arm, &rows, 40.0)?.qpos;
        let k = ((solved.span.0 + solved.span.1) / 2).min(executed.len() - 1);
        let q = &executed[k];
        let hand = solved.arm.context("a pointing arm")?;
        let pointed = aim::pointing_errors(robot, hand, std::slice::from_ref(q), target)[0];
        let looked = aim::gaze_errors(std::slice::from_ref(q), target)[0];
        let (eye, _) = aim::camera(&q[..2]);
        let rays = [
            (hand.shoulder(), target, "0.9 0.15 0.1 0.9"),
            (eye, target, "0.15 0.35 0.9 0.9"),
        ];
        let marked = cosco_hsom::mujoco::Model::from_xml_str(&with_rays(&xml, &rays, target))?;
        let shown = NaoArm::<14>::from_model(robot, marked)?;
        let view = RenderOptions {
            camera: Some(camera.into()),
            ..options.clone()
        };
        let mut renderer = Renderer::new(shown.model(), view)?;
        let mut sim = shown.sim()?;
        sim.set_posture_clamped(q)?;
        sim.forward()?;
        let label = format!("{name}  arm {pointed:.1} deg  camera {looked:.1} deg");
        println!("{label}");
        frames.push((Some(label), renderer.render(sim.data())?));
    }
    let refs: Vec<(Option<String>, &image::RgbImage)> =
        frames.iter().map(|(l, f)| (l.clone(), f)).collect();
    let sheet = cosco_hsom::render::contact_sheet(&refs, 3)?;
    cosco_hsom::render::save_png(&sheet, path)?;
    println!("{}", path.display());
    Ok(())
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
    if let Some(path) = &args.pointing {
        return pointing(path, options, args.seed);
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
