//! What the controller records: encoder readings and hand positions at a fixed rate.

use serde::{Deserialize, Serialize};

use crate::demos::Demonstration;

/// Joint encoders (with the optional sensor noise), commanded targets and the `l_wrist` /
/// `l_gripper` positions (torso frame, noise-free), sampled at `rate_hz`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Recording {
    /// Joint names, the columns of `qpos` and `target`.
    pub joint_names: Vec<String>,
    /// Sampling rate, Hz.
    pub rate_hz: f64,
    /// Sample times, s, from the start of the motion: `k / rate_hz`.
    pub time: Vec<f64>,
    /// Encoder readings, one row per sample (rad; LHand open fraction).
    pub qpos: Vec<Vec<f64>>,
    /// Commanded posture at each sample time (the planned trajectory, without feed-forward terms).
    pub target: Vec<Vec<f64>>,
    /// `l_wrist` site position at each sample, m.
    pub wrist: Vec<[f64; 3]>,
    /// `l_gripper` site position at each sample, m.
    pub gripper: Vec<[f64; 3]>,
    /// Every contact between two parts of the robot during the motion (none on a model without
    /// collision shapes, such as the left arm's).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub contacts: Vec<Touch>,
}

/// Two parts of the robot in contact over an interval of the motion.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Touch {
    /// The two bodies (MuJoCo's names: `torso`, `LForeArm`, `r_wrist`, ...).
    pub parts: [String; 2],
    /// When the contact began, s from the start of the motion.
    pub start_s: f64,
    /// When it was last seen, s.
    pub end_s: f64,
    /// The deepest penetration, m (>= 0).
    pub depth_m: f64,
}

impl Touch {
    /// One line for people: "0.52-0.61 s: LForeArm and torso, 1.8 mm deep" (or "touching",
    /// [`contact_depth`](crate::trajectory::contact_depth)).
    pub fn describe(&self) -> String {
        format!(
            "{:.2}-{:.2} s: {} and {}, {}",
            self.start_s,
            self.end_s,
            self.parts[0],
            self.parts[1],
            crate::trajectory::contact_depth(self.depth_m)
        )
    }
}

impl Touch {
    /// The two limbs in contact, sorted ([`limb`]).
    pub fn limbs(&self) -> [String; 2] {
        let mut l = self.parts.clone().map(|p| limb(&p).to_string());
        l.sort();
        l
    }
}

/// The limb a body of the shipped models belongs to: a hand's palm (`l_wrist`, `r_wrist`) and
/// its fingers (`LHand_fingers`, `RHand_fingers`) are one hand, `left hand` or `right hand`;
/// every other body is its own limb.
pub fn limb(body: &str) -> &str {
    match body {
        "l_wrist" | "LHand_fingers" => "left hand",
        "r_wrist" | "RHand_fingers" => "right hand",
        b => b,
    }
}

/// A gesture's own contacts: the pairs of limbs in contact ([`Touch::limbs`]) in every one of
/// `executions` (each the contacts of one demonstration, executed); none when there is none,
/// or when one execution made none.
pub fn own_contacts(executions: &[Vec<Touch>]) -> Vec<[String; 2]> {
    let Some((first, rest)) = executions.split_first() else {
        return Vec::new();
    };
    let mut own: Vec<[String; 2]> = first.iter().map(Touch::limbs).collect();
    own.sort();
    own.dedup();
    own.retain(|pair| rest.iter().all(|e| e.iter().any(|t| &t.limbs() == pair)));
    own
}

/// Gathers the contacts seen at each physics step into [`Touch`] intervals: two parts touch
/// when their shapes meet or penetrate (a contact within the pair's margin, still apart, is
/// none); a pair seen again within `gap_s` of its last sighting extends its interval.
#[derive(Debug, Default)]
pub(crate) struct Touches {
    open: Vec<Touch>,
}

impl Touches {
    pub(crate) fn see(&mut self, t: f64, gap_s: f64, contacts: &[crate::mujoco::Contact]) {
        for c in contacts.iter().filter(|c| c.dist <= 0.0) {
            let name = |i: usize| {
                c.body_name[i]
                    .clone()
                    .unwrap_or_else(|| format!("body {}", c.body[i]))
            };
            let mut parts = [name(0), name(1)];
            parts.sort();
            let depth = (-c.dist).max(0.0);
            let open = self
                .open
                .iter_mut()
                .find(|o| o.parts == parts && t - o.end_s <= gap_s);
            match open {
                Some(o) => {
                    o.end_s = t;
                    o.depth_m = o.depth_m.max(depth);
                }
                None => self.open.push(Touch {
                    parts,
                    start_s: t,
                    end_s: t,
                    depth_m: depth,
                }),
            }
        }
    }

    pub(crate) fn into_vec(self) -> Vec<Touch> {
        self.open
    }
}

impl Recording {
    pub(crate) fn new(rate_hz: f64, robot: crate::robot::Robot) -> Recording {
        Recording {
            joint_names: robot.joint_names().iter().map(|s| s.to_string()).collect(),
            rate_hz,
            time: Vec::new(),
            qpos: Vec::new(),
            target: Vec::new(),
            wrist: Vec::new(),
            gripper: Vec::new(),
            contacts: Vec::new(),
        }
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.time.len()
    }

    /// True when nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.time.is_empty()
    }

    /// One joint's encoder series, by index in `joint_names`.
    pub fn joint(&self, index: usize) -> Option<Vec<f64>> {
        (index < self.joint_names.len()).then(|| self.qpos.iter().map(|r| r[index]).collect())
    }

    /// Append a recording that went on from where this one ended (the state one tick after
    /// this one's last sample is `later`'s first): `later`'s times are shifted by this one's
    /// length. The rates and joints must agree.
    pub fn append(&mut self, later: Recording) -> super::Result<()> {
        if later.rate_hz != self.rate_hz || later.joint_names != self.joint_names {
            return Err(super::SimError::InvalidTrajectory(format!(
                "appending a recording at {} Hz of {:?} to one at {} Hz of {:?}",
                later.rate_hz, later.joint_names, self.rate_hz, self.joint_names
            )));
        }
        let offset = self.len() as f64 / self.rate_hz;
        self.time.extend(later.time.iter().map(|t| t + offset));
        self.qpos.extend(later.qpos);
        self.target.extend(later.target);
        self.wrist.extend(later.wrist);
        self.gripper.extend(later.gripper);
        self.contacts
            .extend(later.contacts.into_iter().map(|c| Touch {
                start_s: c.start_s + offset,
                end_s: c.end_s + offset,
                ..c
            }));
        Ok(())
    }

    /// The encoder series as a [`Demonstration`] (columns: joint names, with times).
    pub fn to_demonstration(&self, source: impl Into<String>) -> Demonstration {
        Demonstration {
            source: source.into(),
            columns: self.joint_names.clone(),
            time: Some(self.time.clone()),
            rows: self.qpos.clone(),
        }
    }
}
