//! Filming a recorded trajectory: each frame puts the simulated arm (or upper body) in a
//! recorded posture and renders it off-screen from the model's camera.

use crate::mujoco::Data;
use crate::render::{Clip, RenderOptions, Renderer};
use crate::sim::{NaoArm, Recording};
use image::RgbImage;

use super::ExperimentError;

/// The view `simulate` films its clips with: 480x360, shadows, the model's `front` camera.
pub fn clip_options() -> RenderOptions {
    RenderOptions {
        width: 480,
        height: 360,
        shadows: true,
        multisample: false,
        camera: Some("front".into()),
    }
}

/// A posture within this many radians (LHand: open fraction) of the last one rendered, in every
/// joint, shows the same picture: at the `front` camera's scale (about 1.4 mm a pixel at
/// 480x360, a hand about 0.22 m from the shoulder) no part of the arm moves more than about
/// half a pixel, so the clip reuses that frame rather than rendering it again (most of a
/// reproduction's start and end, where the arm holds).
pub const STILL_RAD: f64 = 1e-3;

/// Render every `stride`-th sample of `recording` (the arm placed at the recorded encoder
/// values) into a [`Clip`] whose GIF plays in real time. A sample whose posture is within
/// [`STILL_RAD`] of the last rendered one repeats its frame (see [`frame_sources`]).
pub fn film<const N: usize>(
    arm: &NaoArm<N>,
    recording: &Recording,
    options: &RenderOptions,
    stride: usize,
    on_frame: impl FnMut(usize, usize),
) -> Result<Clip, ExperimentError> {
    film_marked(arm, recording, options, stride, |_, _, _| {}, on_frame)
}

/// [`film`], each frame then marked by `mark(sample, data, frame)`: the sample it is taken at,
/// MuJoCo's state of the posture it shows (to place a mark: [`crate::render::project`]) and
/// the frame to draw on.
pub fn film_marked<const N: usize>(
    arm: &NaoArm<N>,
    recording: &Recording,
    options: &RenderOptions,
    stride: usize,
    mut mark: impl FnMut(usize, &Data<'_>, &mut RgbImage),
    mut on_frame: impl FnMut(usize, usize),
) -> Result<Clip, ExperimentError> {
    if stride == 0 {
        return Err(ExperimentError::Invalid(
            "frame stride is 0: need at least 1".into(),
        ));
    }
    if recording.is_empty() {
        return Err(ExperimentError::Invalid(
            "nothing to film: the recording is empty".into(),
        ));
    }
    let delay_ms = ((1000.0 * stride as f64 / recording.rate_hz).round() as u32).max(10);
    let mut clip = Clip::new(delay_ms)?;
    let mut renderer = Renderer::new(arm.model(), options.clone())?;
    let mut sim = arm.sim()?;
    let sources = frame_sources(&recording.qpos, stride);
    let mut shown: Option<(usize, RgbImage)> = None;
    for (n, &(i, source)) in sources.iter().enumerate() {
        let frame = match shown.take() {
            Some((s, frame)) if s == source => frame,
            _ => {
                sim.set_posture_clamped(&recording.qpos[source])?;
                renderer.render(sim.data())?
            }
        };
        let mut marked = frame.clone();
        mark(i, sim.data(), &mut marked);
        clip.push(recording.time[i], marked)?;
        shown = Some((source, frame));
        on_frame(n + 1, sources.len());
    }
    Ok(clip)
}

/// The frames of a clip of every `stride`-th sample of `qpos`: for each, the sample it is taken
/// at and the sample whose rendering it shows, the last one rendered when no joint has moved
/// more than [`STILL_RAD`] from it, itself otherwise.
pub fn frame_sources(qpos: &[Vec<f64>], stride: usize) -> Vec<(usize, usize)> {
    let mut rendered: Option<usize> = None;
    (0..qpos.len())
        .step_by(stride.max(1))
        .map(|i| {
            let still = rendered.is_some_and(|r| {
                qpos[r].len() == qpos[i].len()
                    && qpos[r]
                        .iter()
                        .zip(&qpos[i])
                        .all(|(a, b)| (a - b).abs() <= STILL_RAD)
            });
            if !still {
                rendered = Some(i);
            }
            (i, rendered.unwrap_or(i))
        })
        .collect()
}

#[cfg(test)]
mod tests;
