//! What a reproduction returns, whichever algorithm made it.

/// Why a reproduction ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopReason {
    /// `maxLength` postures were produced.
    MaxLength,
    /// A bottom node on which training demonstrations ended was reached.
    EndNode,
    /// The posture stopped changing for `stationarySteps` steps.
    Stationary,
    /// `lengthFactor` times the longest demonstration was reached.
    LearnedLength,
    /// The hierarchy predicted the end of the gesture (`algorithm = events`).
    EndEvent,
}

/// A reproduced gesture: postures (in the data's units) with their step index.
#[derive(Debug, Clone, PartialEq)]
pub struct Reproduction {
    /// Step index of each posture (0 = the initial posture).
    pub steps: Vec<usize>,
    /// One posture per step, `stateLength` values each.
    pub postures: Vec<Vec<f64>>,
    /// Level whose prediction produced each posture (0 = the bottom level's reflex; the
    /// initial posture counts as 0).
    pub predicted_by: Vec<usize>,
    /// Why it ended.
    pub stop: StopReason,
}

impl Reproduction {
    /// Keep the first `n` steps (at least one: the initial posture).
    pub(crate) fn truncate(&mut self, n: usize) {
        let n = n.max(1);
        self.postures.truncate(n);
        self.steps.truncate(n);
        self.predicted_by.truncate(n);
    }
}
