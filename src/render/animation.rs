//! Animated GIF encoding for clips filmed from a fixed camera, where most of the picture (sky,
//! floor, the still parts of the robot) stays the same from frame to frame:
//!
//! - one palette for the whole clip, learned once with NeuQuant from a few evenly spaced
//!   frames (not one per frame: the same colour keeps its index, so unchanged pixels stay
//!   unchanged after quantisation and nothing flickers);
//! - frame deltas: every frame after the first stores only the pixels whose palette index
//!   changes, cropped to their bounding box, the rest transparent over the previous frame
//!   (disposal "keep"). A frame where nothing changes is a single transparent pixel that keeps
//!   the frame's time on screen.
//!
//! Decoded, each frame shows exactly the first frame's pixels quantised to the clip's palette,
//! updated where they change.

use super::{RenderError, Result};
use color_quant::NeuQuant;
use image::RgbImage;
use std::borrow::Cow;
use std::collections::HashMap;

/// Colours of the clip's palette; index 255 of the 256 is the transparent one.
const COLOURS: usize = 255;
/// The palette index that leaves the previous frame's pixel showing.
const TRANSPARENT: u8 = 255;
/// Frames the palette is learned from, evenly spaced from the first to the last.
const PALETTE_FRAMES: usize = 8;
/// NeuQuant's sampling factor: 1 learns from every pixel, 30 from one in 30 (the fastest);
/// 10 is the `image` crate's default trade-off between quality and time, used as long as it
/// leaves at least [`MIN_SAMPLES`] pixels to learn from.
const SAMPLE_FACTOR: usize = 10;
/// Pixels NeuQuant learns from at least (all of them in a smaller clip).
const MIN_SAMPLES: usize = 100_000;

/// Encode `frames` (all the same size, checked by the caller) as a GIF that loops forever,
/// each frame shown for `delay_ms` milliseconds (rounded to GIF's hundredths of a second).
pub(super) fn encode(frames: &[&RgbImage], delay_ms: u32) -> Result<Vec<u8>> {
    let Some(first) = frames.first() else {
        return Err(RenderError::NoFrames("GIF"));
    };
    let (width, height) = first.dimensions();
    let size = |v: u32| {
        u16::try_from(v).map_err(|_| RenderError::Invalid {
            field: "GIF frame size",
            value: format!("{width}x{height}"),
            why: "GIF allows at most 65535 pixels a side",
        })
    };
    let (w16, h16) = (size(width)?, size(height)?);
    let delay = u16::try_from(delay_ms.div_ceil(10).max(1)).map_err(|_| RenderError::Invalid {
        field: "GIF frame delay",
        value: format!("{delay_ms} ms"),
        why: "GIF allows at most 655350 ms",
    })?;

    let mut quantiser = Quantiser::learn(frames);
    let mut palette = quantiser.palette();
    palette.extend_from_slice(&[0, 0, 0]); // the transparent entry: never shown
    let mut encoder = gif::Encoder::new(Vec::new(), w16, h16, &palette)?;
    encoder.set_repeat(gif::Repeat::Infinite)?;

    let (w, h) = (width as usize, height as usize);
    // The palette indices on screen after the frames so far.
    let mut canvas = vec![TRANSPARENT; w * h];
    let mut delta = vec![TRANSPARENT; w * h];
    let mut previous: Option<&RgbImage> = None;
    for frame in frames {
        delta.fill(TRANSPARENT);
        let mut bounds = Bounds::default();
        let now = frame.as_raw();
        let before = previous.map(|p| p.as_raw());
        for i in 0..w * h {
            let rgb = [now[3 * i], now[3 * i + 1], now[3 * i + 2]];
            // the same colour has the same index: already on the canvas
            if before.is_some_and(|b| b[3 * i..3 * i + 3] == rgb) {
                continue;
            }
            let index = quantiser.index(rgb);
            if canvas[i] != index {
                canvas[i] = index;
                delta[i] = index;
                bounds.add(i % w, i / w);
            }
        }
        let gif_frame = match bounds.rect() {
            Some((left, top, fw, fh)) => gif::Frame {
                left: left as u16,
                top: top as u16,
                width: fw as u16,
                height: fh as u16,
                buffer: Cow::Owned(crop(&delta, w, (left, top, fw, fh))),
                ..delta_frame(delay)
            },
            None => gif::Frame {
                width: 1,
                height: 1,
                buffer: Cow::Borrowed(&[TRANSPARENT]),
                ..delta_frame(delay)
            },
        };
        encoder.write_frame(&gif_frame)?;
        previous = Some(frame);
    }
    Ok(encoder.into_inner()?)
}

/// A frame drawn over the previous one, transparent where it does not change it.
fn delta_frame(delay: u16) -> gif::Frame<'static> {
    gif::Frame {
        delay,
        dispose: gif::DisposalMethod::Keep,
        transparent: Some(TRANSPARENT),
        ..gif::Frame::default()
    }
}

/// The rows `top..top + height` and columns `left..left + width` of a `w`-wide index buffer.
fn crop(
    indices: &[u8],
    w: usize,
    (left, top, width, height): (usize, usize, usize, usize),
) -> Vec<u8> {
    indices
        .chunks_exact(w)
        .skip(top)
        .take(height)
        .flat_map(|row| &row[left..left + width])
        .copied()
        .collect()
}

/// NeuQuant's sampling factor for `pixels` pixels: [`SAMPLE_FACTOR`], lowered to keep at least
/// [`MIN_SAMPLES`] samples.
fn sample_factor(pixels: usize) -> i32 {
    (pixels / MIN_SAMPLES).clamp(1, SAMPLE_FACTOR) as i32
}

/// The smallest rectangle holding the pixels added.
#[derive(Debug, Default)]
struct Bounds(Option<(usize, usize, usize, usize)>);

impl Bounds {
    fn add(&mut self, x: usize, y: usize) {
        self.0 = Some(match self.0 {
            None => (x, y, x, y),
            Some((x0, y0, x1, y1)) => (x0.min(x), y0.min(y), x1.max(x), y1.max(y)),
        });
    }

    /// Left, top, width, height.
    fn rect(&self) -> Option<(usize, usize, usize, usize)> {
        self.0
            .map(|(x0, y0, x1, y1)| (x0, y0, x1 - x0 + 1, y1 - y0 + 1))
    }
}

/// The clip's palette and the index of each colour met, looked up once per colour.
struct Quantiser {
    quant: NeuQuant,
    known: HashMap<[u8; 3], u8>,
}

impl Quantiser {
    /// Learn the palette from up to [`PALETTE_FRAMES`] frames evenly spaced over `frames`.
    fn learn(frames: &[&RgbImage]) -> Quantiser {
        let n = frames.len().min(PALETTE_FRAMES);
        let mut rgba = Vec::new();
        for k in 0..n {
            let i = if n == 1 {
                0
            } else {
                k * (frames.len() - 1) / (n - 1)
            };
            for p in frames[i].as_raw().chunks_exact(3) {
                rgba.extend_from_slice(&[p[0], p[1], p[2], 255]);
            }
        }
        Quantiser {
            quant: NeuQuant::new(sample_factor(rgba.len() / 4), COLOURS, &rgba),
            known: HashMap::new(),
        }
    }

    /// The palette, `r, g, b` for each of the [`COLOURS`] indices.
    fn palette(&self) -> Vec<u8> {
        self.quant.color_map_rgb()
    }

    /// The palette index nearest to `rgb`.
    fn index(&mut self, rgb: [u8; 3]) -> u8 {
        let quant = &self.quant;
        *self.known.entry(rgb).or_insert_with(|| {
            // NeuQuant's indices are below COLOURS = 255, so they fit u8 and never hit TRANSPARENT
            quant.index_of(&[rgb[0], rgb[1], rgb[2], 255]) as u8
        })
    }
}

#[cfg(test)]
mod tests;
