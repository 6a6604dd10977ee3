use super::*;

#[test]
fn a_posture_within_the_tolerance_of_the_last_rendered_reuses_its_frame() {
    let q = |v: f64| vec![0.5 + v, -0.2, 0.0];
    let qpos = vec![q(0.0), q(0.6e-3), q(1.2e-3), q(1.5e-3), q(0.2), q(0.2)];
    // 0.6e-3 from sample 0: reused; 1.2e-3 from sample 0 (not from sample 1): rendered,
    // so small steps cannot drift; 0.3e-3 from sample 2: reused; 0.2 rad: rendered
    assert_eq!(
        frame_sources(&qpos, 1),
        vec![(0, 0), (1, 0), (2, 2), (3, 2), (4, 4), (5, 4)]
    );
    // every second sample: sample 2 is compared with sample 0, 1.2e-3 away
    assert_eq!(frame_sources(&qpos, 2), vec![(0, 0), (2, 2), (4, 4)]);
    let qpos = vec![q(0.0), q(2.0), q(0.5e-3)];
    assert_eq!(frame_sources(&qpos, 2), vec![(0, 0), (2, 0)]);
    // a single joint beyond the tolerance is enough to render
    let qpos = vec![vec![0.0, 0.0], vec![0.0, 2.0 * STILL_RAD]];
    assert_eq!(frame_sources(&qpos, 1), vec![(0, 0), (1, 1)]);
}
