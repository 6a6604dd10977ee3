//! The main job's pictures: the paper's Fig. 4 (`joints.png`) and the wrist path (`wrist.png`).

use std::path::Path;

use plotters::style::RGBColor;

use crate::plot::{demo_color, panels_png, Panel, PlotError, Series, BLACK};

/// A trajectory to draw: a legend label, a colour, sample times and rows.
#[derive(Debug, Clone)]
pub struct Curve<'a> {
    /// Legend entry.
    pub label: String,
    /// Line colour.
    pub color: RGBColor,
    /// Line width in pixels.
    pub width: u32,
    /// Sample times, seconds.
    pub time: &'a [f64],
    /// One row per sample.
    pub rows: &'a [Vec<f64>],
}

impl<'a> Curve<'a> {
    /// The `i`-th demonstration, in the palette's `i`-th colour.
    pub fn demo(i: usize, time: &'a [f64], rows: &'a [Vec<f64>]) -> Self {
        Curve {
            label: format!("demonstration {}", i + 1),
            color: demo_color(i),
            width: 2,
            time,
            rows,
        }
    }

    /// A reproduction in black, drawn thicker.
    pub fn reproduction(label: impl Into<String>, time: &'a [f64], rows: &'a [Vec<f64>]) -> Self {
        Curve {
            label: label.into(),
            color: BLACK,
            width: 3,
            time,
            rows,
        }
    }
}

/// One panel per named column (`columns[k]` names column `k` of the rows), every curve in
/// each, time in seconds: the paper's Fig. 4 when the columns are the four arm joints.
pub fn joint_panels_png(
    path: &Path,
    title: &str,
    columns: &[(usize, &str)],
    curves: &[Curve<'_>],
    unit: &str,
) -> Result<(), PlotError> {
    let panels: Vec<Panel> = columns
        .iter()
        .map(|&(k, name)| {
            let mut p = Panel::new(name, "time (s)", format!("{name} ({unit})"));
            for c in curves {
                p.series.push(Series {
                    label: Some(c.label.clone()),
                    color: c.color,
                    width: c.width,
                    points: c
                        .time
                        .iter()
                        .zip(c.rows)
                        .filter_map(|(t, r)| r.get(k).map(|v| (*t, *v)))
                        .collect(),
                });
            }
            p
        })
        .collect();
    panels_png(path, title, &panels, 2, (620, 380))
}

/// A wrist path to draw (positions in metres, torso frame).
#[derive(Debug, Clone)]
pub struct Path3<'a> {
    /// Legend entry.
    pub label: String,
    /// Line colour.
    pub color: RGBColor,
    /// Line width in pixels.
    pub width: u32,
    /// Positions, m.
    pub points: &'a [[f64; 3]],
}

impl<'a> Path3<'a> {
    /// The `i`-th demonstration's path, in the palette's `i`-th colour.
    pub fn demo(i: usize, points: &'a [[f64; 3]]) -> Self {
        Path3 {
            label: format!("demonstration {}", i + 1),
            color: demo_color(i),
            width: 2,
            points,
        }
    }

    /// A reproduction's path, drawn thicker.
    pub fn reproduction(label: impl Into<String>, color: RGBColor, points: &'a [[f64; 3]]) -> Self {
        Path3 {
            label: label.into(),
            color,
            width: 3,
            points,
        }
    }
}

/// The demonstrations' wrist paths, each in its palette colour.
pub fn demo_paths(wrists: &[Vec<[f64; 3]>]) -> Vec<Path3<'_>> {
    wrists
        .iter()
        .enumerate()
        .map(|(i, w)| Path3::demo(i, w))
        .collect()
}

/// The wrist paths seen from the front (y-z plane: as a viewer facing the robot sees it, the
/// robot's left on the right of the picture) and from the side (x-z plane), in millimetres,
/// with equal axis scales.
pub fn wrist_png(path: &Path, title: &str, paths: &[Path3<'_>]) -> Result<(), PlotError> {
    let mm = |v: f64| v * 1000.0;
    let mut front = Panel::new(
        "front view (seen from ahead of the robot)",
        "y: robot's left (mm)",
        "z: up (mm)",
    );
    let mut side = Panel::new(
        "side view (seen from the robot's left)",
        "x: forward (mm)",
        "z: up (mm)",
    );
    front.equal_aspect = true;
    side.equal_aspect = true;
    for p in paths {
        front.series.push(Series {
            label: Some(p.label.clone()),
            color: p.color,
            width: p.width,
            points: p.points.iter().map(|q| (mm(q[1]), mm(q[2]))).collect(),
        });
        side.series.push(Series {
            label: Some(p.label.clone()),
            color: p.color,
            width: p.width,
            points: p.points.iter().map(|q| (mm(q[0]), mm(q[2]))).collect(),
        });
    }
    panels_png(path, title, &[front, side], 2, (620, 520))
}
