use std::path::{Path, PathBuf};
use std::sync::Once;

use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::RGBColor;

use crate::fsutil::write_atomic;

static FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");
static REGISTER: Once = Once::new();

/// Errors while drawing or writing a plot.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PlotError {
    /// Nothing to draw: every series of a panel was empty.
    #[error("plot {path}: panel '{panel}' has no finite data to draw")]
    Empty {
        /// The file that was to be written.
        path: PathBuf,
        /// The panel's title.
        panel: String,
    },
    /// A figure needs at least one panel.
    #[error("plot {path}: no panels to draw")]
    NoPanels {
        /// The file that was to be written.
        path: PathBuf,
    },
    /// The drawing library failed.
    #[error("plot {path}: drawing failed: {message}")]
    Draw {
        /// The file that was to be written.
        path: PathBuf,
        /// What the drawing backend said.
        message: String,
    },
    /// Encoding or writing the PNG failed.
    #[error("plot {path}: cannot write the PNG: {source}")]
    Write {
        /// The file that was to be written.
        path: PathBuf,
        /// The I/O or encoding error.
        source: std::io::Error,
    },
}

/// A line through `(x, y)` points.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend entry; `None` keeps it out of the legend.
    pub label: Option<String>,
    /// Line colour.
    pub color: RGBColor,
    /// Line width in pixels.
    pub width: u32,
    /// The points, in drawing order. Non-finite points are skipped.
    pub points: Vec<(f64, f64)>,
}

impl Series {
    /// A labelled line of width 2.
    pub fn new(label: impl Into<String>, color: RGBColor, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: Some(label.into()),
            color,
            width: 2,
            points,
        }
    }
}

/// A shaded envelope between `lower` and `upper` at each `x`.
#[derive(Debug, Clone)]
pub struct Band {
    /// Legend entry.
    pub label: Option<String>,
    /// Fill colour (drawn translucent).
    pub color: RGBColor,
    /// `(x, lower, upper)` triples, ordered by `x`.
    pub points: Vec<(f64, f64, f64)>,
}

/// A region in the plane made of axis-aligned boxes (a band about a path in the plane: per
/// sample, the box of its lower and upper ends), filled in one pale colour.
#[derive(Debug, Clone)]
pub struct Tube {
    /// Legend entry.
    pub label: Option<String>,
    /// Colour (drawn pale and opaque, so that overlapping boxes look as one).
    pub color: RGBColor,
    /// `((x lower, y lower), (x upper, y upper))` per box.
    pub boxes: Vec<((f64, f64), (f64, f64))>,
}

/// A filled ellipse: a 2-D Gaussian's `n_sigma` contour.
#[derive(Debug, Clone)]
pub struct Ellipse {
    /// Centre.
    pub mean: (f64, f64),
    /// Covariance `[[sxx, sxy], [sxy, syy]]`.
    pub cov: [[f64; 2]; 2],
    /// How many standard deviations the contour is at.
    pub n_sigma: f64,
    /// Fill colour (drawn translucent).
    pub color: RGBColor,
}

/// A cloud of small dots.
#[derive(Debug, Clone)]
pub struct Scatter {
    /// Legend entry.
    pub label: Option<String>,
    /// Dot colour.
    pub color: RGBColor,
    /// Dot radius in pixels.
    pub size: u32,
    /// The dots.
    pub points: Vec<(f64, f64)>,
}

/// One chart of a figure.
#[derive(Debug, Clone, Default)]
pub struct Panel {
    /// Caption above the chart.
    pub title: String,
    /// X axis label.
    pub x_label: String,
    /// Y axis label.
    pub y_label: String,
    /// Regions of boxes, drawn first.
    pub tubes: Vec<Tube>,
    /// Envelopes, drawn after the regions.
    pub bands: Vec<Band>,
    /// Ellipses, drawn after the envelopes.
    pub ellipses: Vec<Ellipse>,
    /// Dots, drawn after the ellipses.
    pub scatter: Vec<Scatter>,
    /// Lines, drawn last (on top).
    pub series: Vec<Series>,
    /// Keep one unit in x equal to one unit in y (for paths in space).
    pub equal_aspect: bool,
}

impl Panel {
    /// An empty panel with a title and axis labels.
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
    ) -> Self {
        Panel {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            ..Panel::default()
        }
    }

    /// The data range over everything drawn, padded by 5 %, or `None` when nothing is finite.
    fn bounds(&self) -> Option<((f64, f64), (f64, f64))> {
        let mut xs = (f64::INFINITY, f64::NEG_INFINITY);
        let mut ys = (f64::INFINITY, f64::NEG_INFINITY);
        let mut add = |x: f64, y: f64| {
            if x.is_finite() && y.is_finite() {
                xs = (xs.0.min(x), xs.1.max(x));
                ys = (ys.0.min(y), ys.1.max(y));
            }
        };
        let lines = self.series.iter().map(|s| &s.points);
        for points in lines.chain(self.scatter.iter().map(|s| &s.points)) {
            points.iter().for_each(|&(x, y)| add(x, y));
        }
        for t in &self.tubes {
            for &((x0, y0), (x1, y1)) in &t.boxes {
                add(x0, y0);
                add(x1, y1);
            }
        }
        for b in &self.bands {
            for &(x, lo, hi) in &b.points {
                add(x, lo);
                add(x, hi);
            }
        }
        for e in &self.ellipses {
            for (x, y) in ellipse_outline(e, 16) {
                add(x, y);
            }
        }
        if !xs.0.is_finite() {
            return None;
        }
        let pad = |(lo, hi): (f64, f64)| {
            let span = hi - lo;
            let p = if span > 0.0 {
                0.05 * span
            } else {
                0.5_f64.max(lo.abs() * 0.05)
            };
            (lo - p, hi + p)
        };
        Some((pad(xs), pad(ys)))
    }
}

fn ellipse_outline(e: &Ellipse, n: usize) -> Vec<(f64, f64)> {
    // Eigen-decomposition of the symmetric 2x2 covariance, in closed form.
    let [[a, b], [_, d]] = e.cov;
    let tr = a + d;
    let det = a * d - b * b;
    let disc = ((tr * tr / 4.0) - det).max(0.0).sqrt();
    let l1 = (tr / 2.0 + disc).max(0.0);
    let l2 = (tr / 2.0 - disc).max(0.0);
    let angle = if b.abs() > 1e-300 {
        (l1 - a).atan2(b)
    } else if a >= d {
        0.0
    } else {
        std::f64::consts::FRAC_PI_2
    };
    let (r1, r2) = (e.n_sigma * l1.sqrt(), e.n_sigma * l2.sqrt());
    (0..n)
        .map(|i| {
            let t = i as f64 / n as f64 * std::f64::consts::TAU;
            let (u, v) = (r1 * t.cos(), r2 * t.sin());
            (
                e.mean.0 + u * angle.cos() - v * angle.sin(),
                e.mean.1 + u * angle.sin() + v * angle.cos(),
            )
        })
        .collect()
}

pub(crate) fn register_font() {
    REGISTER.call_once(|| {
        // The shipped font is a valid TTF; if a future replacement were not, text would be
        // missing but plots would still be drawn, so the error is deliberately not fatal.
        let _ = plotters::style::register_font("sans-serif", FontStyle::Normal, FONT);
    });
}

/// Draw `panels` on a grid of `cols` columns, each panel `panel_size` pixels, with a figure
/// title on top and one legend for the figure in a strip below the panels (every labelled
/// line, envelope and cloud once), and write the PNG atomically to `path`.
pub fn panels_png(
    path: &Path,
    title: &str,
    panels: &[Panel],
    cols: usize,
    panel_size: (u32, u32),
) -> Result<(), PlotError> {
    use super::legend::{entries, Mark};
    let entries = entries(panels.iter().flat_map(|p| {
        let tubes = p.tubes.iter().map(|t| (Mark::Fill, t.color, &t.label));
        let bands = p.bands.iter().map(|b| (Mark::Fill, b.color, &b.label));
        let dots = p.scatter.iter().map(|s| (Mark::Dot, s.color, &s.label));
        let lines = p
            .series
            .iter()
            .map(|s| (Mark::Line(s.width), s.color, &s.label));
        tubes.chain(bands).chain(dots).chain(lines)
    }));
    let width = panel_size.0 * cols.clamp(1, panels.len().max(1)) as u32;
    let footer = super::legend::height(&entries, width);
    let draw_err = |e: &dyn std::fmt::Display| PlotError::Draw {
        path: path.to_path_buf(),
        message: format!("legend: {e}"),
    };
    framed_png(
        path,
        title,
        (panels.len(), cols, panel_size),
        footer,
        |area| super::legend::draw(area, &entries).map_err(|e| draw_err(&e)),
        |i, area| draw_panel(path, &panels[i], area),
    )
}

/// A drawing area of one panel of a figure.
pub(crate) type Area<'a> = DrawingArea<BitMapBackend<'a>, plotters::coord::Shift>;

/// The frame shared by every figure: `n` panels on a grid of `cols` columns, each
/// `panel_size` pixels, drawn by `draw(i, area)`, a title on top, encoded to PNG and written
/// atomically to `path`.
pub(crate) fn grid_png(
    path: &Path,
    title: &str,
    n: usize,
    cols: usize,
    panel_size: (u32, u32),
    draw: impl Fn(usize, &Area<'_>) -> Result<(), PlotError>,
) -> Result<(), PlotError> {
    framed_png(path, title, (n, cols, panel_size), 0, |_| Ok(()), draw)
}

/// Pixels a figure's title leaves free, both ends together.
const TITLE_MARGIN: u32 = 16;

/// [`grid_png`] with a strip `footer_h` pixels high below the panels, drawn by `footer`.
fn framed_png(
    path: &Path,
    title: &str,
    (n, cols, panel_size): (usize, usize, (u32, u32)),
    footer_h: u32,
    footer: impl Fn(&Area<'_>) -> Result<(), PlotError>,
    draw: impl Fn(usize, &Area<'_>) -> Result<(), PlotError>,
) -> Result<(), PlotError> {
    if n == 0 {
        return Err(PlotError::NoPanels {
            path: path.to_path_buf(),
        });
    }
    register_font();
    let cols = cols.clamp(1, n);
    let rows = n.div_ceil(cols);
    let title_h = 40u32;
    let (w, h) = (
        panel_size.0 * cols as u32,
        panel_size.1 * rows as u32 + title_h + footer_h,
    );
    let mut buf = vec![255u8; (w * h * 3) as usize];
    let draw_err = |e: &dyn std::fmt::Display| PlotError::Draw {
        path: path.to_path_buf(),
        message: e.to_string(),
    };
    {
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| draw_err(&e))?;
        let (top, rest) = root.split_vertically(title_h);
        // 24 px, smaller when the title is wider than the figure (one narrow panel)
        let wide = (top.estimate_text_size(title, &("sans-serif", 24).into_text_style(&top)))
            .map_err(|e| draw_err(&e))?
            .0;
        let size = match wide + TITLE_MARGIN > w {
            true => 24.0 * f64::from(w.saturating_sub(TITLE_MARGIN)) / f64::from(wide),
            false => 24.0,
        };
        top.titled(title, ("sans-serif", size))
            .map_err(|e| draw_err(&e))?;
        let (body, bottom) = rest.split_vertically(panel_size.1 * rows as u32);
        footer(&bottom)?;
        let areas = body.split_evenly((rows, cols));
        for (i, area) in areas.iter().enumerate().take(n) {
            draw(i, area)?;
        }
        root.present().map_err(|e| draw_err(&e))?;
    }
    let img = image::RgbImage::from_raw(w, h, buf)
        .ok_or_else(|| draw_err(&"pixel buffer has the wrong size"))?;
    let mut png = Vec::new();
    img.write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .map_err(|e| PlotError::Write {
            path: path.to_path_buf(),
            source: std::io::Error::other(e),
        })?;
    write_atomic(path, &png).map_err(|source| PlotError::Write {
        path: path.to_path_buf(),
        source,
    })
}

/// How a failure to draw panel `panel` of the figure at `path` is reported.
pub(crate) fn draw_error<'a>(
    path: &'a Path,
    panel: &'a str,
) -> impl Fn(&dyn std::fmt::Display) -> PlotError + 'a {
    move |e| PlotError::Draw {
        path: path.to_path_buf(),
        message: format!("panel '{panel}': {e}"),
    }
}

/// The label of index `v` when `v` is a whole number, empty elsewhere (axis labels of
/// categories).
pub(crate) fn label_at(v: f64, labels: &[String]) -> String {
    let i = v.round();
    if (v - i).abs() < 1e-6 && i >= 0.0 {
        labels.get(i as usize).cloned().unwrap_or_default()
    } else {
        String::new()
    }
}

/// The text of a numeric axis tick: plotters' own rendering of an `f64` coordinate (at least
/// one decimal, at most five, no scientific notation), except that a value that rounds to zero
/// prints as `0.0`, never `-0.0`. Every numeric axis of every figure formats its ticks here.
pub(crate) fn tick_label(v: f64) -> String {
    let text = plotters::data::float::FloatPrettyPrinter {
        allow_scientific: false,
        min_decimal: 1,
        max_decimal: 5,
    }
    .print(v);
    match text.strip_prefix('-') {
        Some(magnitude) if magnitude.chars().all(|c| c == '0' || c == '.') => magnitude.to_string(),
        _ => text,
    }
}

fn draw_panel(path: &Path, panel: &Panel, area: &Area<'_>) -> Result<(), PlotError> {
    let draw_err = draw_error(path, &panel.title);
    let ((mut x0, mut x1), (mut y0, mut y1)) = panel.bounds().ok_or_else(|| PlotError::Empty {
        path: path.to_path_buf(),
        panel: panel.title.clone(),
    })?;
    if panel.equal_aspect {
        let (pw, ph) = area.dim_in_pixel();
        let (pw, ph) = ((pw as f64 - 80.0).max(1.0), (ph as f64 - 80.0).max(1.0));
        let scale = ((x1 - x0) / pw).max((y1 - y0) / ph);
        let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
        x0 = cx - scale * pw / 2.0;
        x1 = cx + scale * pw / 2.0;
        y0 = cy - scale * ph / 2.0;
        y1 = cy + scale * ph / 2.0;
    }
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| draw_err(&e))?;
    chart
        .configure_mesh()
        .x_desc(panel.x_label.as_str())
        .y_desc(panel.y_label.as_str())
        .x_label_formatter(&|x| tick_label(*x))
        .y_label_formatter(&|y| tick_label(*y))
        .label_style(("sans-serif", 13))
        .axis_desc_style(("sans-serif", 14))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(|e| draw_err(&e))?;
    for t in &panel.tubes {
        let pale = |c: u8| 255 - ((255 - c as u32) / 4) as u8;
        let fill = RGBColor(pale(t.color.0), pale(t.color.1), pale(t.color.2)).filled();
        chart
            .draw_series(
                t.boxes
                    .iter()
                    .filter(|((a, b), (c, d))| [a, b, c, d].iter().all(|v| v.is_finite()))
                    .map(|&(lo, hi)| Rectangle::new([lo, hi], fill)),
            )
            .map_err(|e| draw_err(&e))?;
    }
    for b in &panel.bands {
        let mut poly: Vec<(f64, f64)> = b.points.iter().map(|&(x, _, hi)| (x, hi)).collect();
        poly.extend(b.points.iter().rev().map(|&(x, lo, _)| (x, lo)));
        let style = b.color.mix(0.25).filled();
        chart
            .draw_series(std::iter::once(Polygon::new(poly, style)))
            .map_err(|e| draw_err(&e))?;
    }
    for e in &panel.ellipses {
        let outline = ellipse_outline(e, 64);
        chart
            .draw_series(std::iter::once(Polygon::new(
                outline.clone(),
                e.color.mix(0.35).filled(),
            )))
            .map_err(|er| draw_err(&er))?;
        let mut closed = outline;
        closed.push(closed[0]);
        chart
            .draw_series(std::iter::once(PathElement::new(
                closed,
                e.color.stroke_width(1),
            )))
            .map_err(|er| draw_err(&er))?;
    }
    for s in &panel.scatter {
        let c = s.color;
        let size = s.size;
        chart
            .draw_series(
                s.points
                    .iter()
                    .filter(|p| p.0.is_finite() && p.1.is_finite())
                    .map(move |&p| Circle::new(p, size, c.filled())),
            )
            .map_err(|e| draw_err(&e))?;
    }
    for s in &panel.series {
        let style = s.color.stroke_width(s.width);
        let pts: Vec<(f64, f64)> = s
            .points
            .iter()
            .copied()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
            .collect();
        chart
            .draw_series(LineSeries::new(pts, style))
            .map_err(|e| draw_err(&e))?;
    }
    Ok(())
}

/// The chart of a panel: f64 against f64.
pub(crate) type Chart<'a, 'b> =
    ChartContext<'a, BitMapBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// The legend box of every figure (upper right, translucent white).
pub(crate) fn draw_legend<'b>(
    chart: &mut Chart<'b, 'b>,
    draw_err: &dyn Fn(&dyn std::fmt::Display) -> PlotError,
) -> Result<(), PlotError> {
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(180, 180, 180))
        .label_font(("sans-serif", 13))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(|e| draw_err(&e))
}

#[cfg(test)]
mod tests;
