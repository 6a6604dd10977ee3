//! Each upper-body gesture's signature: the one measurable thing that makes it the gesture its
//! name says (the clap's hands meet, the shrug's palms face up, ...), measured on postures
//! through the shipped model's kinematics (docs/METRICS.md, "Gesture signatures").

use serde::Serialize;

use crate::dtw::euclidean;
use crate::sim::{NaoArm, SimError};

/// A gesture's signature measured on one trajectory.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Signature {
    /// The gesture.
    pub gesture: String,
    /// The rule, for people.
    pub rule: &'static str,
    /// What was measured, in the rule's unit.
    pub measured: f64,
    /// Whether the rule holds.
    pub holds: bool,
}

/// The clap: the gripper sites come within this distance, m ...
pub const CLAP_MEET_M: f64 = 0.04;
/// ... and part beyond this distance between two meetings, m.
pub const CLAP_PART_M: f64 = 0.07;

/// The rule of each upper-body gesture: (gesture, rule, the threshold, whether the measure
/// must reach at least it (true) or at most it).
const RULES: [(&str, &str, f64, bool); 10] = [
    ("clap", "times the gripper sites come within 4 cm (parting beyond 7 cm between)", 2.0, true),
    ("shrug", "both palms' angle from facing up at the apex, degrees", 30.0, false),
    ("welcome", "the gripper sites' largest distance, m", 0.48, true),
    ("wave-right", "the right elbow's swings (RElbowRoll reversals of 0.2 rad or more)", 4.0, true),
    ("nod", "the head's nods (HeadPitch reversals of 0.15 rad or more)", 4.0, true),
    ("shake-head", "the head's turns (HeadYaw reversals of 0.4 rad or more)", 3.0, true),
    ("reading-watch", "the top camera's angle to the left wrist (the watch) at its closest with the head turned left 0.2 rad or more, degrees", 45.0, false),
    ("salute", "the right gripper's distance to the top camera at its closest, m", 0.10, false),
    ("point-left", "the left arm held outstretched ahead (LElbowRoll within 0.3 rad of straight, the gripper 0.15 m or more ahead of the torso) for the longest stretch, s", 0.5, true),
    ("point-right", "the right arm held outstretched ahead (RElbowRoll within 0.3 rad of straight, the gripper 0.15 m or more ahead of the torso) for the longest stretch, s", 0.5, true),
];

/// The rows a second of the trajectories a signature measures (the encoders' 40 Hz).
const RATE_HZ: f64 = 40.0;

/// The longest stretch (s) that `arm` is held outstretched ahead in `rows` (upper-body
/// postures): its ElbowRoll within 0.3 rad of straight, its gripper 0.15 m or more ahead.
fn outstretched(rows: &[Vec<f64>], arm: crate::aim::Arm) -> f64 {
    let at = arm
        .offset(crate::robot::Robot::UpperBody)
        .expect("the upper body has both arms");
    let ahead: Vec<f64> = (rows.iter())
        .map(|r| {
            let straight = r[at + 3].abs() <= 0.3;
            let forward = arm.gripper(&r[at..at + 5])[0] >= 0.15;
            if straight && forward {
                0.0
            } else {
                1.0
            }
        })
        .collect();
    crate::aim::longest_within(&ahead, 0.5) as f64 / RATE_HZ
}

/// The signature of `gesture` (an upper-body gesture's name) measured on `rows` (upper-body
/// postures, NAOqi order, clamped into the joint ranges); `None` for a gesture without one.
pub fn signature(
    arm: &NaoArm<14>,
    gesture: &str,
    rows: &[Vec<f64>],
) -> Result<Option<Signature>, SimError> {
    let Some(&(_, rule, threshold, at_least)) = RULES.iter().find(|r| r.0 == gesture) else {
        return Ok(None);
    };
    let measured = match gesture {
        "wave-right" => reversals(rows, 11, 0.2) as f64,
        "nod" => reversals(rows, 1, 0.15) as f64,
        "shake-head" => reversals(rows, 0, 0.4) as f64,
        "point-left" => outstretched(rows, crate::aim::Arm::Left),
        "point-right" => outstretched(rows, crate::aim::Arm::Right),
        _ => kinematic(arm, gesture, rows)?,
    };
    let holds = match at_least {
        true => measured >= threshold,
        false => measured <= threshold,
    };
    Ok(Some(Signature {
        gesture: gesture.to_string(),
        rule,
        measured,
        holds,
    }))
}

/// How many times column `j` of `rows` turns back after moving at least `min` since its last
/// turn (the first excursion from the start counts from the first row).
pub fn reversals(rows: &[Vec<f64>], j: usize, min: f64) -> usize {
    let (mut count, mut extreme, mut direction) = (0, None::<f64>, 0.0_f64);
    let Some(first) = rows.first() else {
        return 0;
    };
    let mut anchor = first[j];
    for r in rows {
        let v = r[j];
        let e = extreme.unwrap_or(anchor);
        if direction == 0.0 {
            if (v - anchor).abs() >= min {
                direction = (v - anchor).signum();
                extreme = Some(v);
            }
        } else if (v - e) * direction > 0.0 {
            extreme = Some(v);
        } else if (e - v) * direction >= min {
            count += 1;
            direction = -direction;
            anchor = e;
            extreme = Some(v);
        }
    }
    count
}

/// The measures that need the model's kinematics.
fn kinematic(arm: &NaoArm<14>, gesture: &str, rows: &[Vec<f64>]) -> Result<f64, SimError> {
    let frames = frames(arm, rows)?;
    if gesture == "clap" {
        return Ok(meetings(frames.iter().map(Frame::grippers_apart)) as f64);
    }
    Ok(extreme(gesture, &frames).map_or(f64::NAN, |(_, v)| v))
}

/// The sample of `rows` that shows `gesture` (an upper-body gesture's name) best: where its
/// signature's measure is at its extreme (the clap: the hands closest; the wave and the head
/// gestures: the swinging joint farthest from its first value); `None` for no rows.
pub fn apex(arm: &NaoArm<14>, gesture: &str, rows: &[Vec<f64>]) -> Result<Option<usize>, SimError> {
    let frames = frames(arm, rows)?;
    Ok(match gesture {
        "clap" => extreme("clap", &frames).map(|(i, _)| i),
        "shrug" | "welcome" | "reading-watch" | "salute" => {
            extreme(gesture, &frames).map(|(i, _)| i)
        }
        "point-left" | "point-right" if !rows.is_empty() => {
            // the middle of the held part
            let at = if gesture == "point-left" { 2 } else { 8 };
            let (a, b) = crate::aim::held_span(rows, at..at + 4);
            Some((a + b) / 2)
        }
        _ => {
            // the joint that swings: its value farthest from the first
            let j = match gesture {
                "nod" => 1,
                "shake-head" => 0,
                _ => 11,
            };
            (0..rows.len()).max_by(|&a, &b| {
                let far = |k: usize| (rows[k][j] - rows[0][j]).abs();
                far(a).total_cmp(&far(b))
            })
        }
    })
}

/// The sample where a kinematic measure is at its extreme, and its value.
fn extreme(gesture: &str, frames: &[Frame]) -> Option<(usize, f64)> {
    let (f, max): (&dyn Fn(&Frame) -> f64, bool) = match gesture {
        "clap" => (&Frame::grippers_apart, false),
        "shrug" => (&|f: &Frame| f.palms[0].max(f.palms[1]), false),
        "welcome" => (&Frame::grippers_apart, true),
        "reading-watch" => (
            &|f: &Frame| f.watch.map_or(180.0, |w| angle_to(&f.camera, &w)),
            false,
        ),
        _ => (&|f: &Frame| euclidean(&f.camera.0, &f.grippers[1]), false),
    };
    let values = frames.iter().map(f).enumerate();
    match max {
        true => values.max_by(|a, b| a.1.total_cmp(&b.1)),
        false => values.min_by(|a, b| a.1.total_cmp(&b.1)),
    }
}

/// Each posture of `rows` through the model's kinematics.
fn frames(arm: &NaoArm<14>, rows: &[Vec<f64>]) -> Result<Vec<Frame>, SimError> {
    let model = arm.model();
    let site = |name: &str| {
        model
            .site_id(name)
            .ok_or_else(|| SimError::InvalidTrajectory(format!("the model has no site {name}")))
    };
    let (l, r, lw, rw, cam) = (
        site("l_gripper")?,
        site("r_gripper")?,
        site("l_wrist")?,
        site("r_wrist")?,
        site("camera_top")?,
    );
    let mut sim = arm.sim()?;
    let mut frames = Vec::with_capacity(rows.len());
    for q in rows {
        sim.set_posture_clamped(q)?;
        sim.forward()?;
        let d = sim.data();
        frames.push(Frame {
            grippers: [d.site_xpos(l), d.site_xpos(r)],
            palms: [palm_up_deg(&d.site_xmat(lw)), palm_up_deg(&d.site_xmat(rw))],
            camera: (d.site_xpos(cam), d.site_xmat(cam)),
            watch: (q[0] >= 0.2).then(|| d.site_xpos(lw)),
        });
    }
    Ok(frames)
}

/// One posture's positions and angles.
struct Frame {
    grippers: [[f64; 3]; 2],
    palms: [f64; 2],
    camera: ([f64; 3], [f64; 9]),
    /// The left wrist, when the head is turned left by 0.2 rad or more.
    watch: Option<[f64; 3]>,
}

impl Frame {
    fn grippers_apart(&self) -> f64 {
        euclidean(&self.grippers[0], &self.grippers[1])
    }
}

/// How many times a distance comes within [`CLAP_MEET_M`], parting beyond [`CLAP_PART_M`]
/// between two meetings.
fn meetings(distances: impl Iterator<Item = f64>) -> usize {
    let (mut count, mut apart) = (0, true);
    for d in distances {
        if apart && d < CLAP_MEET_M {
            count += 1;
            apart = false;
        } else if d > CLAP_PART_M {
            apart = true;
        }
    }
    count
}

/// The angle between a hand's palm normal and straight up, degrees: the palm faces the hand
/// frame's -z (`xmat` row-major, its columns the frame's axes in the torso frame).
fn palm_up_deg(xmat: &[f64; 9]) -> f64 {
    (-xmat[8]).clamp(-1.0, 1.0).acos().to_degrees()
}

/// The angle between the camera's view (its frame's x-axis) and the direction to `target`,
/// degrees.
fn angle_to(camera: &([f64; 3], [f64; 9]), target: &[f64; 3]) -> f64 {
    let (p, m) = camera;
    let to: Vec<f64> = (0..3).map(|i| target[i] - p[i]).collect();
    let n = to.iter().map(|v| v * v).sum::<f64>().sqrt();
    if n == 0.0 {
        return 0.0;
    }
    let cos = (m[0] * to[0] + m[3] * to[1] + m[6] * to[2]) / n;
    cos.clamp(-1.0, 1.0).acos().to_degrees()
}

#[cfg(test)]
mod tests;
