//! Box plots: for each category (a gesture) one box per series (a method), side by side.
//! A box spans the first to the third quartile with a line at the median; whiskers reach the
//! farthest values within 1.5 interquartile ranges of the box; values beyond are dots.
//! Quartiles interpolate linearly between order statistics ([`quantile`]).

use std::path::Path;

use plotters::prelude::*;
use plotters::style::RGBColor;

use super::figure::{draw_error, draw_legend, grid_png, label_at, tick_label, Area, PlotError};
use crate::stats::quantile;

/// One panel of box plots.
#[derive(Debug, Clone)]
pub struct BoxPanel {
    /// Panel title.
    pub title: String,
    /// Label of the value axis.
    pub y_label: String,
    /// Groups along the x axis.
    pub categories: Vec<String>,
    /// Series (legend name, colour): one box per category and series.
    pub series: Vec<(String, RGBColor)>,
    /// `values[category][series]`: the values of one box (non-finite values are left out).
    pub values: Vec<Vec<Vec<f64>>>,
}

/// Five numbers of a box: whisker ends, quartiles, median; and the outliers.
struct Boxed {
    low: f64,
    q1: f64,
    median: f64,
    q3: f64,
    high: f64,
    outliers: Vec<f64>,
}

fn boxed(values: &[f64]) -> Option<Boxed> {
    let mut v: Vec<f64> = values.iter().copied().filter(|x| x.is_finite()).collect();
    v.sort_by(f64::total_cmp);
    let (q1, median, q3) = (quantile(&v, 0.25)?, quantile(&v, 0.5)?, quantile(&v, 0.75)?);
    let reach = 1.5 * (q3 - q1);
    let inside = |x: &&f64| **x >= q1 - reach && **x <= q3 + reach;
    let low = v.iter().find(inside).copied().unwrap_or(q1);
    let high = v.iter().rev().find(inside).copied().unwrap_or(q3);
    let outliers = v.iter().copied().filter(|x| !inside(&x)).collect();
    Some(Boxed {
        low,
        q1,
        median,
        q3,
        high,
        outliers,
    })
}

/// Draw `panels` of box plots on a grid of `cols` columns, each `panel_size` pixels, with a
/// figure title, and write the PNG atomically to `path`.
pub fn boxplots_png(
    path: &Path,
    title: &str,
    panels: &[BoxPanel],
    cols: usize,
    panel_size: (u32, u32),
) -> Result<(), PlotError> {
    grid_png(path, title, panels.len(), cols, panel_size, |i, area| {
        draw_boxes(path, &panels[i], area)
    })
}

fn draw_boxes(path: &Path, panel: &BoxPanel, area: &Area<'_>) -> Result<(), PlotError> {
    let draw_err = draw_error(path, &panel.title);
    let finite = || {
        panel
            .values
            .iter()
            .flatten()
            .flatten()
            .copied()
            .filter(|v| v.is_finite())
    };
    let (lo, hi) = finite().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
        (l.min(v), h.max(v))
    });
    if !(lo.is_finite() && hi.is_finite()) {
        return Err(PlotError::Empty {
            path: path.to_path_buf(),
            panel: panel.title.clone(),
        });
    }
    let pad = if hi > lo {
        (hi - lo) * 0.08
    } else {
        lo.abs().max(1.0) * 0.1
    };
    let n_cat = panel.categories.len().max(1);
    let n_ser = panel.series.len().max(1);
    let categories = panel.categories.clone();
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(-0.5..(n_cat as f64 - 0.5), (lo - pad)..(hi + pad))
        .map_err(|e| draw_err(&e))?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_labels(n_cat * 2 + 1)
        .x_label_formatter(&|x| label_at(*x, &categories))
        .y_label_formatter(&|y| tick_label(*y))
        .y_desc(panel.y_label.as_str())
        .max_light_lines(1)
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 14))
        .light_line_style(RGBColor(240, 240, 240))
        .draw()
        .map_err(|e| draw_err(&e))?;
    // boxes of one category share 0.8 of the unit slot
    let slot = 0.8 / n_ser as f64;
    let half = slot * 0.35;
    for (s, (name, color)) in panel.series.iter().enumerate() {
        let color = *color;
        let mut shapes: Vec<DynElement<'static, BitMapBackend<'_>, (f64, f64)>> = Vec::new();
        for (c, per_series) in panel.values.iter().enumerate() {
            let Some(b) = per_series.get(s).and_then(|v| boxed(v)) else {
                continue;
            };
            let x = c as f64 - 0.4 + slot * (s as f64 + 0.5);
            let (rect, median) = ([(x - half, b.q1), (x + half, b.q3)], b.median);
            shapes.extend([
                Rectangle::new(rect, color.mix(0.3).filled()).into_dyn(),
                Rectangle::new(rect, color.stroke_width(2)).into_dyn(),
                PathElement::new(
                    vec![(x - half, median), (x + half, median)],
                    color.stroke_width(3),
                )
                .into_dyn(),
            ]);
            for (from, to) in [(b.q3, b.high), (b.q1, b.low)] {
                let cap = vec![(x - half / 2.0, to), (x + half / 2.0, to)];
                shapes.extend([
                    PathElement::new(vec![(x, from), (x, to)], color.stroke_width(1)).into_dyn(),
                    PathElement::new(cap, color.stroke_width(1)).into_dyn(),
                ]);
            }
            for o in b.outliers {
                shapes.push(Circle::new((x, o), 3, color.filled()).into_dyn());
            }
        }
        chart
            .draw_series(shapes)
            .map_err(|e| draw_err(&e))?
            .label(name.as_str())
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 20, y + 5)], color.filled()));
    }
    draw_legend(&mut chart, &draw_err)
}

#[cfg(test)]
mod tests;
