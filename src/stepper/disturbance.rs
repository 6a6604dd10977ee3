//! What disturbs an arm while a stepper drives it: held, moved and held, a link pushed, or the
//! goal moved; at a phase of the reproduction's duration (`cosco heldout --disturb hold:P:D`)
//! or at seconds (`simulate --hold T:S`); moved by an absolute amount per variable or `k`
//! times the demonstrations' diagonal. One type and one parser for every flag; each
//! [`super::Plant`] places it on its ticks.
//!
//! ```
//! use cosco_hsom::stepper::{Clock, Disturbance};
//! let d = Disturbance::parse("hold", "0.4:0.25", Clock::Phase).unwrap();
//! assert_eq!(d.describe(), "held from phase 0.4 for 0.25 of the duration");
//! let d = Disturbance::parse("push", "5.0:LForeArm:0,0,-8:0.2", Clock::Seconds).unwrap();
//! assert_eq!(d.describe(), "LForeArm pushed with (0, 0, -8) N at 5.00 s for 0.20 s");
//! assert!(d.acts_at(5.1) && !d.acts_at(5.2));
//! ```

use serde::ser::{Serialize, SerializeMap, Serializer};

/// What a disturbance's start and length count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Clock {
    /// Shares of the reproduction's duration (the start a phase, 0 to 1).
    Phase,
    /// Seconds from the start.
    Seconds,
}

/// How far a move or a goal's move goes.
#[derive(Debug, Clone, PartialEq)]
pub enum Amount {
    /// One value per variable: the displacement, or the new goal.
    Absolute(Vec<f64>),
    /// `k` times the demonstrations' diagonal (`k` times each variable's extent), a goal from
    /// the undisturbed run's end.
    Diagonal(f64),
}

/// What it does to the arm.
#[derive(Debug, Clone, PartialEq)]
pub enum Kind {
    /// A hand holds every joint where it was when grabbed.
    Hold,
    /// The hand holds the arm displaced by the amount from where it was.
    Move(Amount),
    /// The force (N, the torso's frame) pushes the link `body` (the model's body name) at its
    /// centre of mass: only a simulated arm can be pushed.
    Push {
        /// The link.
        body: String,
        /// The force, N.
        force: [f64; 3],
    },
    /// The stepper's goal moves ([`super::Stepper::set_goal`]) to the amount.
    Goal(Amount),
}

/// A disturbance: from `at` for `lasts` (a goal's move: at `at`), counted by `clock`.
#[derive(Debug, Clone, PartialEq)]
pub struct Disturbance {
    /// What `at` and `lasts` count.
    pub clock: Clock,
    /// When it starts: a phase 0 to 1, or seconds.
    pub at: f64,
    /// How long it has the arm: a share of the duration, or seconds (0 for a goal's move).
    pub lasts: f64,
    /// What it does.
    pub kind: Kind,
}

/// A number of a flag's value, finite and >= 0, or the reason naming `flag` and `text`.
fn number(flag: &str, text: &str, field: &str) -> Result<f64, String> {
    match field.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && v >= 0.0 => Ok(v),
        _ => Err(format!(
            "{flag} {text:?}: `{field}` is not a finite number >= 0"
        )),
    }
}

/// Comma-separated finite numbers, or the reason naming `flag` and `text`.
fn numbers(flag: &str, text: &str, field: &str) -> Result<Vec<f64>, String> {
    (field.split(','))
        .map(|v| match v.trim().parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(format!("{flag} {text:?}: `{v}` is not a finite number")),
        })
        .collect()
}

impl Disturbance {
    /// A hold from phase `at` for `share` of the duration.
    pub fn hold(at: f64, share: f64) -> Disturbance {
        let kind = Kind::Hold;
        Disturbance {
            clock: Clock::Phase,
            at,
            lasts: share,
            kind,
        }
    }

    /// A move by `by` (one value per variable) at phase `at`, held for `share`.
    pub fn moved(at: f64, by: Vec<f64>, share: f64) -> Disturbance {
        let kind = Kind::Move(Amount::Absolute(by));
        Disturbance {
            clock: Clock::Phase,
            at,
            lasts: share,
            kind,
        }
    }

    /// The goal moved to `goal` at phase `at`.
    pub fn goal(at: f64, goal: Vec<f64>) -> Disturbance {
        let kind = Kind::Goal(Amount::Absolute(goal));
        Disturbance {
            clock: Clock::Phase,
            at,
            lasts: 0.0,
            kind,
        }
    }

    /// The value `text` of a flag of `kind` (`hold`, `move`, `push`, `goal`) counted by
    /// `clock`: `AT:LASTS` (hold), `AT:LASTS:K` (move by `K` x the diagonal) or
    /// `AT:LASTS:V1,...` (move by these), `AT:BODY:FX,FY,FZ:LASTS` (push), `AT:K` or
    /// `AT:V1,...` (goal); a phase is at most 1, every time and `K` finite and >= 0. A
    /// single number is `K`, more an absolute amount on the seconds clock (`simulate`).
    pub fn parse(kind: &str, text: &str, clock: Clock) -> Result<Disturbance, String> {
        let flag = match (clock, kind) {
            (Clock::Phase, "goal") => "--goal-moves".to_string(),
            (Clock::Phase, _) => "--disturb".to_string(),
            (Clock::Seconds, "goal") => "--goal-at".to_string(),
            (Clock::Seconds, k) => format!("--{k}"),
        };
        let (t, u) = match clock {
            Clock::Phase => ("P", "D"),
            Clock::Seconds => ("T", "S"),
        };
        let usage = match kind {
            "hold" => format!("{t}:{u}"),
            "move" if clock == Clock::Phase => format!("{t}:{u}:K"),
            "move" => format!("{t}:{u}:V1,..."),
            "push" => format!("{t}:BODY:FX,FY,FZ:{u}"),
            "goal" if clock == Clock::Phase => format!("{t}:K"),
            "goal" => format!("{t}:V1,... (one value per joint)"),
            _ => {
                return Err(format!(
                    "{flag} {kind}:{text}: needs hold:P:D (held from phase P for D of the \
                     duration), move:P:D:K (moved K x the diagonal at phase P, held for D) or \
                     push:P:BODY:FX,FY,FZ:D (the simulated arm's link BODY pushed)"
                ))
            }
        };
        let fields: Vec<&str> = text.split(':').collect();
        let n = usage.split(':').count();
        if fields.len() != n || (kind == "push" && fields[1].trim().is_empty()) {
            return Err(format!("{flag} {text:?}: needs {usage}"));
        }
        let at = number(&flag, text, fields[0])?;
        if clock == Clock::Phase && at > 1.0 {
            return Err(format!(
                "{flag} {text:?}: the phase {at} is past 1 (0 is the start, 1 the end)"
            ));
        }
        let amount = |field: &str| match clock {
            Clock::Phase => number(&flag, text, field).map(Amount::Diagonal),
            Clock::Seconds => numbers(&flag, text, field).map(Amount::Absolute),
        };
        let (lasts, kind) = match kind {
            "hold" => (number(&flag, text, fields[1])?, Kind::Hold),
            "move" => (
                number(&flag, text, fields[1])?,
                Kind::Move(amount(fields[2])?),
            ),
            "push" => {
                let force = numbers(&flag, text, fields[2])?;
                let force = (force.try_into())
                    .map_err(|_| format!("{flag} {text:?}: needs {usage} (three forces)"))?;
                let body = fields[1].trim().to_string();
                (number(&flag, text, fields[3])?, Kind::Push { body, force })
            }
            _ => (0.0, Kind::Goal(amount(fields[1])?)),
        };
        Ok(Disturbance {
            clock,
            at,
            lasts,
            kind,
        })
    }

    /// `cosco heldout --disturb`'s value: `hold:P:D`, `move:P:D:K` or `push:P:BODY:FX,FY,FZ:D`.
    pub fn disturb(text: &str) -> Result<Disturbance, String> {
        let (kind, rest) = text.split_once(':').unwrap_or((text, ""));
        Disturbance::parse(kind, rest, Clock::Phase)
    }

    /// `cosco heldout --disturb`'s value for the kinematic loop: `hold:P:D` or `move:P:D:K`;
    /// a push is refused, naming where pushes run.
    pub fn kinematic(text: &str) -> Result<Disturbance, String> {
        let d = Disturbance::disturb(text)?;
        match d.kind {
            Kind::Push { .. } => Err(format!(
                "--disturb {text:?}: the kinematic loop of `cosco heldout` cannot push a link (the \
                 arm goes where it is commanded); pushes run on the simulated arm: `simulate \
                 --loop closed --push T:BODY:FX,FY,FZ:S` or `cargo run --example heldout -- \
                 --push P:BODY:FX,FY,FZ:D`"
            )),
            _ => Ok(d),
        }
    }

    /// `--goal-moves P:K`.
    pub fn goal_moves(text: &str) -> Result<Disturbance, String> {
        Disturbance::parse("goal", text, Clock::Phase)
    }

    /// When it ends: `at + lasts` (a goal's move: `at`).
    pub fn until(&self) -> f64 {
        self.at + self.lasts
    }

    /// Whether it has the arm (holds, moves or pushes it) at `t` (on its clock).
    pub fn acts_at(&self, t: f64) -> bool {
        !matches!(self.kind, Kind::Goal(_)) && t >= self.at && t < self.until()
    }

    /// The same with its amounts absolute, for demonstrations spanning `extent` per variable
    /// and the undisturbed run's end `end`: a move by `k` x the diagonal is `k` x `extent`, a
    /// goal moved by it is `end` plus that.
    pub fn absolute(&self, extent: &[f64], end: &[f64]) -> Disturbance {
        let along = |k: f64| extent.iter().map(|e| k * e).collect::<Vec<f64>>();
        let kind = match &self.kind {
            Kind::Move(Amount::Diagonal(k)) => Kind::Move(Amount::Absolute(along(*k))),
            Kind::Goal(Amount::Diagonal(k)) => Kind::Goal(Amount::Absolute(
                end.iter().zip(along(*k)).map(|(e, d)| e + d).collect(),
            )),
            other => other.clone(),
        };
        Disturbance {
            kind,
            ..self.clone()
        }
    }

    /// Checked against the arm it runs on before any work: a moved goal and a move give one
    /// value per variable of `columns`, a goal within `ranges` (when known); a pushed link is
    /// one of `links` (when known); and it starts within a motion of `motion` (on its clock:
    /// seconds, or 1 for the phases).
    pub fn check(
        &self,
        columns: &[String],
        ranges: Option<&[(f64, f64)]>,
        links: Option<&[String]>,
        motion: f64,
    ) -> Result<(), String> {
        let what = self.describe();
        let unit = match self.clock {
            Clock::Phase => "of the duration".to_string(),
            Clock::Seconds => "s".to_string(),
        };
        if self.clock == Clock::Seconds && self.at >= motion {
            return Err(format!(
                "{what}: it starts after the motion, which lasts {motion:.2} {unit}; give a time \
                 within it"
            ));
        }
        match &self.kind {
            Kind::Goal(Amount::Absolute(goal)) => {
                crate::condition::check_posture("the goal", goal, columns, ranges)
                    .map_err(|e| format!("{what}: {e}"))
            }
            Kind::Move(Amount::Absolute(by)) => {
                crate::condition::check_posture("the displacement", by, columns, None)
                    .map_err(|e| format!("{what}: {e}"))
            }
            Kind::Push { force, .. } if force.iter().any(|f| !f.is_finite()) => {
                Err(format!("{what}: the force must be finite"))
            }
            Kind::Push { body, .. } => match links {
                Some(links) if !links.contains(body) => Err(format!(
                    "a push on `{body}`: the arm has no such link; allowed {}",
                    links.join(", ")
                )),
                _ => Ok(()),
            },
            _ => Ok(()),
        }
    }

    /// One line for people: `held from phase 0.4 for 0.25 of the duration`, `held at 1.00 s
    /// for 0.50 s`, `LForeArm pushed with (0, 0, -8) N at 1.00 s for 0.30 s`, `goal moved 0.1
    /// x the diagonal at phase 0.5`, `goal moved at 1.50 s`.
    pub fn describe(&self) -> String {
        let (at, lasts) = (self.at, self.lasts);
        match (self.clock, &self.kind) {
            (Clock::Phase, Kind::Hold) => {
                format!("held from phase {at} for {lasts} of the duration")
            }
            (Clock::Phase, Kind::Move(Amount::Diagonal(k))) => {
                format!("moved {k} x the diagonal at phase {at}, held for {lasts}")
            }
            (Clock::Phase, Kind::Move(_)) => format!("moved at phase {at}, held for {lasts}"),
            (Clock::Phase, Kind::Push { body, force }) => format!(
                "{body} pushed with ({}, {}, {}) N from phase {at} for {lasts}",
                force[0], force[1], force[2]
            ),
            (Clock::Phase, Kind::Goal(Amount::Diagonal(k))) => {
                format!("goal moved {k} x the diagonal at phase {at}")
            }
            (Clock::Phase, Kind::Goal(_)) => format!("goal moved at phase {at}"),
            (Clock::Seconds, Kind::Hold) => format!("held at {at:.2} s for {lasts:.2} s"),
            (Clock::Seconds, Kind::Move(_)) => {
                format!("moved at {at:.2} s and held for {lasts:.2} s")
            }
            (Clock::Seconds, Kind::Push { body, force }) => format!(
                "{body} pushed with ({}, {}, {}) N at {at:.2} s for {lasts:.2} s",
                force[0], force[1], force[2]
            ),
            (Clock::Seconds, Kind::Goal(_)) => format!("goal moved at {at:.2} s"),
        }
    }
}

/// As `{"kind": "hold", "at": 0.4, "share": 0.25}` (`move` adds `k`, `push` `body` and
/// `force`, `goal` has `at` and `k`); on the seconds clock `at_s` and `seconds`, and absolute
/// amounts as `by` or `goal`.
impl Serialize for Disturbance {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(None)?;
        let (name, amount) = match &self.kind {
            Kind::Hold => ("hold", None),
            Kind::Move(a) => ("move", Some(("by", a))),
            Kind::Push { .. } => ("push", None),
            Kind::Goal(a) => ("goal", Some(("goal", a))),
        };
        m.serialize_entry("kind", name)?;
        let (at, lasts) = match self.clock {
            Clock::Phase => ("at", "share"),
            Clock::Seconds => ("at_s", "seconds"),
        };
        m.serialize_entry(at, &self.at)?;
        if !matches!(self.kind, Kind::Goal(_)) {
            m.serialize_entry(lasts, &self.lasts)?;
        }
        match amount {
            Some((_, Amount::Diagonal(k))) => m.serialize_entry("k", k)?,
            Some((key, Amount::Absolute(v))) => m.serialize_entry(key, v)?,
            None => {}
        }
        if let Kind::Push { body, force } = &self.kind {
            m.serialize_entry("body", body)?;
            m.serialize_entry("force", force)?;
        }
        m.end()
    }
}
