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
}

impl Recording {
    pub(crate) fn new(rate_hz: f64) -> Recording {
        Recording {
            joint_names: super::JOINT_NAMES.iter().map(|s| s.to_string()).collect(),
            rate_hz,
            time: Vec::new(),
            qpos: Vec::new(),
            target: Vec::new(),
            wrist: Vec::new(),
            gripper: Vec::new(),
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
