//! Filming a recorded trajectory: each frame puts the simulated arm in a recorded posture and
//! renders it off-screen from the model's camera.

use crate::render::{Clip, RenderOptions, Renderer};
use crate::sim::{NaoArm, Recording};

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

/// Render every `stride`-th sample of `recording` (the arm placed at the recorded encoder
/// values) into a [`Clip`] whose GIF plays in real time.
pub fn film(
    arm: &NaoArm,
    recording: &Recording,
    options: &RenderOptions,
    stride: usize,
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
    let picked: Vec<usize> = (0..recording.len()).step_by(stride).collect();
    for (n, &i) in picked.iter().enumerate() {
        sim.set_posture_clamped(&recording.qpos[i])?;
        clip.push(recording.time[i], renderer.render(sim.data())?)?;
        on_frame(n + 1, picked.len());
    }
    Ok(clip)
}
