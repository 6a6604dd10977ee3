//! Confusion matrices: one panel per classifier, rows the true label, columns the answer
//! (the labels, then any extra answer such as `unknown`), each cell shaded by the fraction of
//! its row and labelled with its count.

use std::path::Path;

use plotters::prelude::*;
use plotters::style::RGBColor;

use super::figure::{draw_error, grid_png, label_at, Area, PlotError};

/// One panel: a classifier's counts.
#[derive(Debug, Clone)]
pub struct ConfusionPanel {
    /// Panel title (the classifier, its accuracy).
    pub title: String,
    /// True labels, one per row of `counts`.
    pub rows: Vec<String>,
    /// Answers, one per column of `counts` (the labels, then e.g. `unknown`).
    pub columns: Vec<String>,
    /// `counts[r][c]`: queries of label `rows[r]` answered `columns[c]`.
    pub counts: Vec<Vec<usize>>,
}

/// Draw `panels` side by side with a figure title and write the PNG atomically to `path`.
pub fn confusion_png(path: &Path, title: &str, panels: &[ConfusionPanel]) -> Result<(), PlotError> {
    for p in panels {
        if p.rows.is_empty()
            || p.columns.is_empty()
            || p.counts.len() != p.rows.len()
            || p.counts.iter().any(|r| r.len() != p.columns.len())
        {
            return Err(PlotError::Empty {
                path: path.to_path_buf(),
                panel: p.title.clone(),
            });
        }
    }
    let cols = panels.len().max(1);
    grid_png(path, title, panels.len(), cols, (520, 470), |i, area| {
        draw_panel(path, &panels[i], area)
    })
}

fn draw_panel(path: &Path, panel: &ConfusionPanel, area: &Area<'_>) -> Result<(), PlotError> {
    let draw_err = draw_error(path, &panel.title);
    let (nr, nc) = (panel.rows.len(), panel.columns.len());
    let columns = panel.columns.clone();
    let rows = panel.rows.clone();
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, ("sans-serif", 17))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(100)
        .build_cartesian_2d(0.0..nc as f64, 0.0..nr as f64)
        .map_err(|e| draw_err(&e))?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_labels(2 * nc + 1)
        .y_labels(2 * nr + 1)
        // labels at the cells' centres, row 0 at the top
        .x_label_formatter(&|x| label_at(*x - 0.5, &columns))
        .y_label_formatter(&|y| label_at(nr as f64 - *y - 0.5, &rows))
        .x_desc("answer")
        .y_desc("gesture shown")
        .label_style(("sans-serif", 12))
        .axis_desc_style(("sans-serif", 13))
        .draw()
        .map_err(|e| draw_err(&e))?;
    for (r, row) in panel.counts.iter().enumerate() {
        let total: usize = row.iter().sum();
        for (c, &n) in row.iter().enumerate() {
            let frac = if total > 0 {
                n as f64 / total as f64
            } else {
                0.0
            };
            // white (none) to a dark blue (every query of the row)
            let shade = |full: u8| (255.0 - frac * (255.0 - full as f64)).round() as u8;
            let fill = RGBColor(shade(31), shade(80), shade(160));
            let y0 = (nr - 1 - r) as f64;
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(c as f64, y0), (c as f64 + 1.0, y0 + 1.0)],
                    fill.filled(),
                )))
                .map_err(|e| draw_err(&e))?;
            let ink = if frac > 0.5 { WHITE } else { BLACK };
            chart
                .draw_series(std::iter::once(Text::new(
                    n.to_string(),
                    (c as f64 + 0.45, y0 + 0.55),
                    ("sans-serif", 18).into_font().color(&ink),
                )))
                .map_err(|e| draw_err(&e))?;
        }
    }
    Ok(())
}
