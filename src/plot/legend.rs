//! One legend for a whole figure of panels, in a strip below them, so that no legend covers a
//! curve: every labelled line, envelope and cloud of dots of any panel once, in the order met.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::RGBColor;

/// How an entry's sample is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Mark {
    /// A line of this width.
    Line(u32),
    /// A translucent fill.
    Fill,
    /// A dot.
    Dot,
}

/// One entry: its mark, colour and label.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Entry {
    mark: Mark,
    color: RGBColor,
    label: String,
}

/// Height of one row of entries, pixels.
const ROW_H: u32 = 24;
/// Width of an entry's sample, pixels.
const SAMPLE_W: i32 = 24;

/// `(mark, colour, label)` of everything labelled, each label once (its first appearance).
pub(crate) fn entries<'a>(
    labelled: impl IntoIterator<Item = (Mark, RGBColor, &'a Option<String>)>,
) -> Vec<Entry> {
    let mut out: Vec<Entry> = Vec::new();
    for (mark, color, label) in labelled {
        if let Some(l) = label {
            if !out.iter().any(|e| &e.label == l) {
                out.push(Entry {
                    mark,
                    color,
                    label: l.clone(),
                });
            }
        }
    }
    out
}

/// The width an entry takes, pixels (its sample, a gap, its text at about 7.5 px a character).
fn entry_w(e: &Entry) -> i32 {
    SAMPLE_W + 8 + (e.label.chars().count() as f64 * 7.5).ceil() as i32 + 24
}

/// Where each entry goes in a strip `width` pixels wide: `(x, row)`, rows wrapping.
fn layout(entries: &[Entry], width: u32) -> Vec<(i32, u32)> {
    let (mut x, mut row) = (16, 0);
    entries
        .iter()
        .map(|e| {
            let w = entry_w(e);
            if x > 16 && x + w > width as i32 {
                (x, row) = (16, row + 1);
            }
            let at = (x, row);
            x += w;
            at
        })
        .collect()
}

/// The strip's height for `entries` in a figure `width` pixels wide (0 without entries).
pub(crate) fn height(entries: &[Entry], width: u32) -> u32 {
    match layout(entries, width).last() {
        Some(&(_, rows)) => (rows + 1) * ROW_H + 12,
        None => 0,
    }
}

/// Draw `entries` in `area` (a strip below the panels); the drawing library's complaint on
/// failure.
pub(crate) fn draw(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    entries: &[Entry],
) -> Result<(), String> {
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let (width, _) = area.dim_in_pixel();
    for (e, (x, row)) in entries.iter().zip(layout(entries, width)) {
        let y = 6 + (row * ROW_H + ROW_H / 2) as i32;
        let c = e.color;
        match e.mark {
            Mark::Line(w) => area.draw(&PathElement::new(
                vec![(x, y), (x + SAMPLE_W, y)],
                c.stroke_width(w),
            )),
            Mark::Fill => area.draw(&Rectangle::new(
                [(x, y - 6), (x + SAMPLE_W, y + 6)],
                c.mix(0.25).filled(),
            )),
            Mark::Dot => area.draw(&Circle::new((x + SAMPLE_W / 2, y), 3, c.filled())),
        }
        .map_err(|er| err(&er))?;
        area.draw(&Text::new(
            e.label.as_str(),
            (x + SAMPLE_W + 8, y - 8),
            ("sans-serif", 14).into_font(),
        ))
        .map_err(|er| err(&er))?;
    }
    Ok(())
}
