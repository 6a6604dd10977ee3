//! Where a point of the world appears in a frame rendered from one of the model's cameras
//! (a pinhole of the camera's vertical field of view), so that a frame can mark it.

use crate::mujoco::Data;

/// The pixel (`x` right, `y` down, from the top-left corner) at which `point` (world frame, m)
/// appears in a `width` x `height` frame rendered from `camera` (the model's camera id) in the
/// state `data` (after `forward`); `None` behind the camera or for a camera the model lacks.
pub fn project(
    data: &Data,
    camera: usize,
    point: [f64; 3],
    (width, height): (u32, u32),
) -> Option<(f64, f64)> {
    if camera >= data.model().ncam() {
        return None;
    }
    let (c, m) = (data.cam_xpos(camera), data.cam_xmat(camera));
    let d = [point[0] - c[0], point[1] - c[1], point[2] - c[2]];
    // the camera's axes are the columns of its orientation: right, up, backward
    let axis = |i: usize| d[0] * m[i] + d[1] * m[3 + i] + d[2] * m[6 + i];
    let (right, up, depth) = (axis(0), axis(1), -axis(2));
    if depth <= 1e-9 {
        return None;
    }
    let fovy = data.model().camera_fovy(camera).to_radians();
    let f = 0.5 * height as f64 / (0.5 * fovy).tan();
    Some((
        0.5 * width as f64 + f * right / depth,
        0.5 * height as f64 - f * up / depth,
    ))
}
