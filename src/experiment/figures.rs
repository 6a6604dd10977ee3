//! The main job's pictures: the paper's Fig. 4 (`joints.png`) and the wrist path (`wrist.png`;
//! on the upper body the right wrist's beside it).

use std::path::Path;

use plotters::style::RGBColor;

use crate::condition::ConfidenceBand;
use crate::demos::Demonstration;
use crate::plot::{demo_color, panels_png, Band, Panel, PlotError, Series};
use crate::sim::{site_path, NaoArm, Recording, RIGHT_WRIST_SITE};

use super::ExperimentError;

/// Something to draw as a line: a legend label, a colour, a line width and its data (a
/// [`Curve`]'s sample times and rows, a [`Path3`]'s positions).
#[derive(Debug, Clone)]
pub struct Trace<D> {
    /// Legend entry.
    pub label: String,
    /// Line colour.
    pub color: RGBColor,
    /// Line width in pixels.
    pub width: u32,
    /// What is drawn.
    pub data: D,
}

/// A trajectory: sample times (seconds) and one row per sample.
pub type Curve<'a> = Trace<(&'a [f64], &'a [Vec<f64>])>;

/// A wrist path: positions in metres, torso frame.
pub type Path3<'a> = Trace<&'a [[f64; 3]]>;

impl<D> Trace<D> {
    /// The `i`-th demonstration, in the palette's `i`-th colour.
    pub fn demo(i: usize, data: D) -> Self {
        Trace {
            label: format!("demonstration {}", i + 1),
            color: demo_color(i),
            width: 2,
            data,
        }
    }

    /// A reproduction, drawn thicker.
    pub fn reproduction(label: impl Into<String>, color: RGBColor, data: D) -> Self {
        Trace {
            label: label.into(),
            color,
            width: 3,
            data,
        }
    }

    /// Its line through `points`.
    fn series(&self, points: Vec<(f64, f64)>) -> Series {
        Series {
            label: Some(self.label.clone()),
            color: self.color,
            width: self.width,
            points,
        }
    }
}

/// An executed reproduction, drawn thicker: its trajectory (sample times, encoder rows) and
/// its wrist path.
pub fn reproduction<'a>(
    label: &str,
    color: RGBColor,
    rec: &'a Recording,
) -> (Curve<'a>, Path3<'a>) {
    let curve = Curve::reproduction(label, color, (&rec.time[..], &rec.qpos[..]));
    (curve, Path3::reproduction(label, color, &rec.wrist[..]))
}

/// The demonstrations' curves (their own times; none without a time column), each in its
/// palette colour.
pub fn demo_curves(demos: &[Demonstration]) -> Vec<Curve<'_>> {
    (demos.iter().enumerate())
        .map(|(i, d)| Curve::demo(i, (d.time.as_deref().unwrap_or(&[]), &d.rows[..])))
        .collect()
}

/// A confidence band to draw under the curves: its legend label, colour, the seconds between
/// its rows, and the band.
pub type BandTrace<'a> = Trace<(f64, &'a ConfidenceBand)>;

/// One panel per named joint (`columns[k]` names column `k` of the rows, its axis
/// [`axis_label`](crate::robot::axis_label)), every curve in each over `band` when given, time
/// in seconds: the paper's Fig. 4 when the columns are the four arm joints.
pub fn joint_panels_png(
    path: &Path,
    title: &str,
    columns: &[(usize, &str)],
    curves: &[Curve<'_>],
    band: Option<&BandTrace<'_>>,
) -> Result<(), PlotError> {
    let panels: Vec<Panel> = columns
        .iter()
        .map(|&(k, name)| {
            let mut p = Panel::new(name, "time (s)", crate::robot::axis_label(name));
            if let Some(b) = band {
                let (period, rows) = b.data;
                p.bands.push(Band {
                    label: Some(b.label.clone()),
                    color: b.color,
                    points: (rows.lo.iter().zip(&rows.hi).enumerate())
                        .filter_map(|(i, (lo, hi))| {
                            Some((i as f64 * period, *lo.get(k)?, *hi.get(k)?))
                        })
                        .collect(),
                });
            }
            for c in curves {
                let (time, rows) = c.data;
                let points = time.iter().zip(rows);
                let points = points.filter_map(|(t, r)| r.get(k).map(|v| (*t, *v)));
                p.series.push(c.series(points.collect()));
            }
            p
        })
        .collect();
    panels_png(path, title, &panels, 2, (620, 380))
}

/// The demonstrations' wrist paths, each in its palette colour.
pub fn demo_paths(wrists: &[Vec<[f64; 3]>]) -> Vec<Path3<'_>> {
    (wrists.iter().enumerate())
        .map(|(i, w)| Path3::demo(i, &w[..]))
        .collect()
}

/// The wrist paths seen from the front (y-z plane: as a viewer facing the robot sees it, the
/// robot's left on the right of the picture) and from the side (x-z plane), in millimetres,
/// with equal axis scales.
pub fn wrist_png(path: &Path, title: &str, paths: &[Path3<'_>]) -> Result<(), PlotError> {
    let view = |title: &str, x_label: &str, x: usize| {
        let mut panel = Panel::new(title, x_label, "z: up (mm)");
        panel.equal_aspect = true;
        for p in paths {
            let points = p.data.iter().map(|q| (q[x] * 1000.0, q[2] * 1000.0));
            panel.series.push(p.series(points.collect()));
        }
        panel
    };
    let front = view(
        "front view (seen from ahead of the robot)",
        "y: robot's left (mm)",
        1,
    );
    let side = view(
        "side view (seen from the robot's left)",
        "x: forward (mm)",
        0,
    );
    panels_png(path, title, &[front, side], 2, (620, 520))
}

/// The right wrist's (`r_wrist`) paths, from `arm`'s kinematics at the encoder rows, of the
/// demonstrations (each in its palette colour) and of each `(label, colour, recording)`
/// reproduction (drawn thicker), as [`wrist_png`] draws them into `path`.
pub fn right_wrist_png<'a, const N: usize>(
    arm: &NaoArm<N>,
    demos: &[Demonstration],
    reproductions: impl IntoIterator<Item = (&'a str, RGBColor, &'a Recording)>,
    path: &Path,
    title: &str,
) -> Result<(), ExperimentError> {
    let demo_wrists = demos
        .iter()
        .map(|d| site_path(arm, RIGHT_WRIST_SITE, &d.rows))
        .collect::<Result<Vec<_>, _>>()?;
    let reps = reproductions
        .into_iter()
        .map(|(label, color, rec)| Ok((label, color, site_path(arm, RIGHT_WRIST_SITE, &rec.qpos)?)))
        .collect::<Result<Vec<_>, ExperimentError>>()?;
    let mut paths = demo_paths(&demo_wrists);
    paths.extend(
        reps.iter()
            .map(|(label, color, w)| Path3::reproduction(*label, *color, &w[..])),
    );
    Ok(wrist_png(path, title, &paths)?)
}
