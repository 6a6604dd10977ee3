//! The methods an evaluation compares on the same folds.

use serde::Serialize;

use crate::demos::Demonstration;
use crate::gmr::ComponentChoice;
use crate::stats::median;

/// The components the GMM/GMR baseline chooses among (lowest BIC): 1..=16, wider than the
/// library's default 1..=8 (on the four gestures BIC still fell at 8 components; a wave needs
/// about two per oscillation).
pub const GMR_COMPONENTS: ComponentChoice = ComponentChoice::Bic { min: 1, max: 16 };

/// A method of an evaluation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// The configuration as given ([`Hsom::reproduce`]).
    Hierarchy,
    /// The same trained model's bottom code following the bottom events of the training
    /// demonstration whose first sample is nearest, no level above
    /// ([`Hsom::follow_nearest`]): the simpler thing the hierarchy has to beat.
    NearestSequence,
    /// The configuration with its bottom level alone ([`HsomConfig::at_height`]).
    Height1,
    /// The paper's baseline: GMM/GMR ([`GMR_COMPONENTS`]), a minimum-jerk lead-in from the
    /// initial posture to GMR's first point at the executor's speed
    /// ([`Executor::gmr_lead_in_speed`]), then GMR's mean every sample period.
    GmmGmr,
    /// The second baseline: ProMP ([`crate::promp`], default [`PrompSettings`]) conditioned on
    /// the initial posture, its conditioned mean at every sample period for the training
    /// demonstrations' mean duration; it starts at the initial posture, so no lead-in.
    ///
    /// [`PrompSettings`]: crate::promp::PrompSettings
    #[serde(rename = "promp")]
    ProMP,
    /// The third baseline: the discrete DMP ([`crate::dmp`], default [`DmpSettings`]) from
    /// rest at the initial posture to the training demonstrations' mean end (or the given
    /// goal), for their mean duration.
    ///
    /// [`DmpSettings`]: crate::dmp::DmpSettings
    Dmp,
    /// The DTW mean of the training demonstrations ([`crate::dba`]): DBA initialised at their
    /// medoid, keeping its length, joined from the initial posture; the sequence nearest all
    /// of them under alignment, what a reproduction scored by DTW has to beat.
    Dba,
    /// The training demonstration whose first sample is nearest, as recorded (no model).
    Replay,
}

impl Method {
    /// Every method, in the order of the tables.
    pub const ALL: [Method; 8] = [
        Method::Hierarchy,
        Method::NearestSequence,
        Method::Height1,
        Method::GmmGmr,
        Method::ProMP,
        Method::Dmp,
        Method::Dba,
        Method::Replay,
    ];

    /// The name in tables.
    pub fn name(self) -> &'static str {
        match self {
            Method::Hierarchy => "hierarchy",
            Method::NearestSequence => "nearest sequence",
            Method::Height1 => "height 1",
            Method::GmmGmr => "GMM/GMR",
            Method::ProMP => "ProMP",
            Method::Dmp => "DMP",
            Method::Dba => "DBA",
            Method::Replay => "replay (no model)",
        }
    }
}

/// The peak speed of demonstrations sampled every `period` seconds, units per second: the
/// median over the demonstrations of their largest speed on any variable, each speed a
/// difference over 4 samples (so a single noisy sample does not make it; over all of a
/// demonstration shorter than 5 samples; 0 for one sample). The kinematic executor's GMM/GMR
/// lead-in moves at most this fast.
pub fn peak_speed(demos: &[Demonstration], period: f64) -> f64 {
    let per_demo = demos.iter().map(|d| {
        // over 4 samples, or all of a shorter demonstration
        let span = d.rows.len().saturating_sub(1).min(4);
        if span == 0 {
            return 0.0;
        }
        d.rows
            .windows(span + 1)
            .flat_map(|w| w[span].iter().zip(&w[0]).map(|(b, a)| (b - a).abs()))
            .fold(0.0, f64::max)
            / (span as f64 * period)
    });
    median(per_demo).unwrap_or(0.0)
}
