//! PNG plots: panels of time series (the paper's Figs. 3 and 4), 2-D paths (the wrist path),
//! and the GMM/GMR figure (Fig. 5: Gaussians as ellipses, the regression mean, a +-2 sigma
//! envelope, the training points), and box plots (the merged tables of a sweep).
//!
//! Drawing goes to an in-memory RGB buffer that is encoded to PNG and written atomically, so
//! a failed plot never leaves a half-written file. Text uses the DejaVu Sans font shipped in
//! `assets/` (no fontconfig needed on the machine).

mod boxplot;
mod caption;
mod confusion;
mod figure;
mod legend;

pub use boxplot::{boxplots_png, BoxPanel};
pub use caption::{caption, mark};
pub use confusion::{confusion_png, ConfusionPanel};
pub use figure::{panels_png, Band, Ellipse, Panel, PlotError, Scatter, Series, Tube};

use plotters::style::RGBColor;

/// Colours for demonstrations (a qualitative palette that stays readable next to black).
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
];

/// Black, for the reproduction (as in the paper's Fig. 4).
pub const BLACK: RGBColor = RGBColor(0, 0, 0);

/// The colour of the `i`-th demonstration.
pub fn demo_color(i: usize) -> RGBColor {
    PALETTE[i % PALETTE.len()]
}
