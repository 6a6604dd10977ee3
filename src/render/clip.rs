//! [`Clip`]: frames collected during a simulation, written as an animated GIF and a PNG
//! contact sheet of key frames.

use super::{font, save_png, RenderError, Result};
use image::RgbImage;
use std::path::Path;

/// Frames of one simulation, with the simulation time of each.
#[derive(Debug, Clone)]
pub struct Clip {
    frames: Vec<(f64, RgbImage)>,
    delay_ms: u32,
}

impl Clip {
    /// An empty clip whose GIF shows each frame for `delay_ms` milliseconds (at least 10:
    /// GIF counts delays in hundredths of a second and viewers clamp shorter ones).
    pub fn new(delay_ms: u32) -> Result<Clip> {
        if delay_ms < 10 {
            return Err(RenderError::Invalid {
                field: "GIF frame delay",
                value: format!("{delay_ms} ms"),
                why: "must be at least 10 ms",
            });
        }
        Ok(Clip {
            frames: Vec::new(),
            delay_ms,
        })
    }

    /// Add a frame taken at simulation time `time` (seconds). All frames must have the size
    /// of the first.
    pub fn push(&mut self, time: f64, frame: RgbImage) -> Result<()> {
        if let Some((_, first)) = self.frames.first() {
            if first.dimensions() != frame.dimensions() {
                return Err(RenderError::FrameSize {
                    index: self.frames.len(),
                    got: frame.dimensions(),
                    expected: first.dimensions(),
                });
            }
        }
        self.frames.push((time, frame));
        Ok(())
    }

    /// Number of frames.
    pub fn len(&self) -> usize {
        self.frames.len()
    }

    /// Whether the clip has no frame.
    pub fn is_empty(&self) -> bool {
        self.frames.is_empty()
    }

    /// Frame delay of the GIF in milliseconds.
    pub fn delay_ms(&self) -> u32 {
        self.delay_ms
    }

    /// The frames and their times.
    pub fn frames(&self) -> impl Iterator<Item = (f64, &RgbImage)> {
        self.frames.iter().map(|(t, f)| (*t, f))
    }

    /// Encode the clip as an animated GIF (looping forever): one palette for the whole clip
    /// and frame deltas (see the `animation` module), so a still background costs nothing
    /// after the first frame.
    pub fn gif_bytes(&self) -> Result<Vec<u8>> {
        let frames: Vec<&RgbImage> = self.frames.iter().map(|(_, f)| f).collect();
        super::animation::encode(&frames, self.delay_ms)
    }

    /// Write the clip as an animated GIF at `path`, atomically.
    pub fn write_gif(&self, path: &Path) -> Result<()> {
        let bytes = self.gif_bytes()?;
        crate::fsutil::write_atomic(path, &bytes).map_err(|source| RenderError::Io {
            path: path.to_path_buf(),
            source,
        })
    }

    /// Indices of `n` frames evenly spaced from the first to the last.
    pub fn key_frames(&self, n: usize) -> Vec<usize> {
        let len = self.frames.len();
        if len == 0 || n == 0 {
            return Vec::new();
        }
        let n = n.min(len);
        if n == 1 {
            return vec![0];
        }
        (0..n)
            .map(|i| (i * (len - 1) + (n - 1) / 2) / (n - 1))
            .collect()
    }

    /// `n` key frames (see [`Clip::key_frames`]) that show every window of `windows` (from,
    /// to, in the frames' seconds): where no key frame falls inside a window, the one nearest
    /// its middle moves to the frame there.
    pub fn key_frames_within(&self, n: usize, windows: &[(f64, f64)]) -> Vec<usize> {
        let mut picked = self.key_frames(n);
        let time = |i: usize| self.frames[i].0;
        for &(from, to) in windows {
            let inside = |i: &usize| time(*i) >= from && time(*i) < to;
            let Some(middle) = (0..self.frames.len()).filter(inside).min_by(|a, b| {
                (time(*a) - (from + to) / 2.0)
                    .abs()
                    .total_cmp(&(time(*b) - (from + to) / 2.0).abs())
            }) else {
                continue;
            };
            if picked.iter().any(inside) {
                continue;
            }
            let nearest = (0..picked.len()).min_by(|a, b| {
                picked[*a]
                    .abs_diff(middle)
                    .cmp(&picked[*b].abs_diff(middle))
            });
            if let Some(k) = nearest {
                picked[k] = middle;
            }
        }
        picked.sort_unstable();
        picked.dedup();
        picked
    }

    /// A contact sheet of the frames `picked` (indices, e.g. [`Clip::key_frames`]) in a grid
    /// of `columns` columns, optionally labelled with their simulation time.
    pub fn contact_sheet(
        &self,
        picked: &[usize],
        columns: usize,
        labels: bool,
    ) -> Result<RgbImage> {
        if self.frames.is_empty() {
            return Err(RenderError::NoFrames("contact sheet"));
        }
        let picked: Vec<(Option<String>, &RgbImage)> = (picked.iter())
            .filter_map(|&i| self.frames.get(i))
            .map(|(t, f)| (labels.then(|| format!("t={t:.2}s")), f))
            .collect();
        contact_sheet(&picked, columns)
    }

    /// Write the contact sheet (see [`Clip::contact_sheet`]) as a PNG at `path`, atomically.
    pub fn write_contact_sheet(
        &self,
        path: &Path,
        picked: &[usize],
        columns: usize,
        labels: bool,
    ) -> Result<()> {
        let sheet = self.contact_sheet(picked, columns, labels)?;
        save_png(&sheet, path)
    }
}

/// Lay `frames` (all the same size) out in a grid of `columns` columns with a 4-pixel white
/// gutter, each with an optional label in its top-left corner.
pub fn contact_sheet(frames: &[(Option<String>, &RgbImage)], columns: usize) -> Result<RgbImage> {
    const GUTTER: u32 = 4;
    if columns == 0 {
        return Err(RenderError::Invalid {
            field: "contact sheet columns",
            value: "0".into(),
            why: "must be at least 1",
        });
    }
    let Some((_, first)) = frames.first() else {
        return Err(RenderError::NoFrames("contact sheet"));
    };
    let (w, h) = first.dimensions();
    for (index, (_, f)) in frames.iter().enumerate() {
        if f.dimensions() != (w, h) {
            return Err(RenderError::FrameSize {
                index,
                got: f.dimensions(),
                expected: (w, h),
            });
        }
    }
    let cols = columns.min(frames.len()) as u32;
    let rows = frames.len().div_ceil(columns) as u32;
    let mut sheet = RgbImage::from_pixel(
        cols * w + (cols + 1) * GUTTER,
        rows * h + (rows + 1) * GUTTER,
        image::Rgb([255, 255, 255]),
    );
    let scale = (h / 120).max(1);
    for (i, (label, frame)) in frames.iter().enumerate() {
        let (c, r) = (i as u32 % cols, i as u32 / cols);
        let (x, y) = (GUTTER + c * (w + GUTTER), GUTTER + r * (h + GUTTER));
        image::imageops::replace(&mut sheet, *frame, x as i64, y as i64);
        if let Some(text) = label {
            font::draw_label(&mut sheet, x + 2, y + 2, scale, text);
        }
    }
    Ok(sheet)
}

#[cfg(test)]
mod tests;
