//! Conditions on a reproduction besides its initial posture: a goal (its last posture) and
//! via-points (a posture and the phase, 0..1 of the reproduction's duration, at which it is
//! passed); bending a trajectory onto the conditions (docs/ALGORITHM.md, "Conditioning");
//! the confidence band about a reproduction.
//!
//! A trajectory of `n` rows is at phase `p` at the fractional row `p (n - 1)`, read by linear
//! interpolation between the two rows about it ([`at_phase`]): that is how a conditioned
//! reproduction's rows are checked, so that is the reading [`bend`] makes exact.

use nalgebra::{DMatrix, DVector};

use crate::curve::{at_phase, minimum_jerk_at, split_phase, split_row, MINIMUM_JERK_PEAK};

mod band;
#[cfg(test)]
mod tests;

pub use band::{spread_band, ConfidenceBand};

/// A posture to pass at a phase of the reproduction.
#[derive(Debug, Clone, PartialEq)]
pub struct ViaPoint {
    /// 0 (the start) to 1 (the end).
    pub phase: f64,
    /// One value per variable.
    pub posture: Vec<f64>,
}

/// A reproduction's goal and via-points (none of either: the reproduction as the model makes
/// it).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Conditions {
    /// The last posture.
    pub goal: Option<Vec<f64>>,
    /// Postures to pass, in any order.
    pub via: Vec<ViaPoint>,
}

/// A condition that cannot be met; each names the condition, the value and what is allowed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ConditionError {
    /// A posture of the wrong width.
    #[error("{what} has {found} values; the model has {expected} variables ({columns})")]
    Width {
        /// `the goal` or `the via-point at phase P`.
        what: String,
        /// Values given.
        found: usize,
        /// Variables of the model.
        expected: usize,
        /// Their names, comma-separated.
        columns: String,
    },
    /// A value that is not a finite number.
    #[error("{what}: {column} is {value}; need a finite number")]
    NonFinite {
        /// The condition.
        what: String,
        /// The variable.
        column: String,
        /// The value.
        value: f64,
    },
    /// A phase outside [0, 1].
    #[error("a via-point's phase is {0}; allowed 0 to 1 (0 the start, 1 the end)")]
    Phase(f64),
    /// Two conditions at one phase with different postures (the goal is at phase 1, the
    /// initial posture at phase 0).
    #[error("{first} and {second} are both at phase {phase} with different postures")]
    Conflict {
        /// The phase.
        phase: f64,
        /// One condition.
        first: String,
        /// The other.
        second: String,
    },
    /// A value outside its variable's range.
    #[error("{what}: {column} = {value} is outside its range [{lower}, {upper}]")]
    Range {
        /// The condition.
        what: String,
        /// The variable (a joint).
        column: String,
        /// The value.
        value: f64,
        /// The range's lower end.
        lower: f64,
        /// Its upper end.
        upper: f64,
    },
    /// A reproduction too short to be bent onto a condition between its rows.
    #[error("the reproduction has {rows} rows: too few to pass the condition at phase {phase} (it reads {found:?}, the condition is {wanted:?})")]
    Unmet {
        /// Rows of the reproduction.
        rows: usize,
        /// The condition's phase.
        phase: f64,
        /// What the bent reproduction reads there.
        found: Vec<f64>,
        /// The condition's posture.
        wanted: Vec<f64>,
    },
}

/// A posture as a command line gives it (`--initial`, `--goal`): `V1,V2,...`, each value a
/// finite number. Its [`FromStr`](std::str::FromStr) is the one reading of posture text; clap
/// names the flag and the text beside what it says is wrong.
#[derive(Debug, Clone, PartialEq)]
pub struct PostureArg(pub Vec<f64>);

impl std::str::FromStr for PostureArg {
    type Err = String;

    /// The values, or which one is not a finite number.
    fn from_str(text: &str) -> Result<Self, String> {
        text.split(',')
            .enumerate()
            .map(|(i, v)| match v.trim().parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(x),
                _ => Err(format!(
                    "value {} is '{}': need a finite number",
                    i + 1,
                    v.trim()
                )),
            })
            .collect::<Result<_, _>>()
            .map(PostureArg)
    }
}

impl std::str::FromStr for ViaPoint {
    type Err = String;

    /// `PHASE:V1,V2,...` (`--via`): the phase, then the posture as [`PostureArg`] reads it;
    /// or what is wrong and what is allowed.
    fn from_str(text: &str) -> Result<Self, String> {
        let (phase, posture) = text
            .split_once(':')
            .ok_or("need PHASE:V1,V2,... (the phase 0 to 1, then the posture)")?;
        let phase = phase
            .trim()
            .parse::<f64>()
            .ok()
            .filter(|p| p.is_finite())
            .ok_or("the phase before ':' must be a number from 0 to 1")?;
        Ok(ViaPoint {
            phase,
            posture: posture.parse::<PostureArg>()?.0,
        })
    }
}

/// `posture` (named `what` in errors) is one finite value per variable of `columns`, each
/// within its range when `ranges` are given.
pub fn check_posture(
    what: &str,
    posture: &[f64],
    columns: &[String],
    ranges: Option<&[(f64, f64)]>,
) -> Result<(), ConditionError> {
    if posture.len() != columns.len() {
        return Err(ConditionError::Width {
            what: what.to_string(),
            found: posture.len(),
            expected: columns.len(),
            columns: columns.join(", "),
        });
    }
    for (j, &value) in posture.iter().enumerate() {
        if !value.is_finite() {
            return Err(ConditionError::NonFinite {
                what: what.to_string(),
                column: columns[j].clone(),
                value,
            });
        }
        if let Some(&(lower, upper)) = ranges.and_then(|r| r.get(j)) {
            if !(lower..=upper).contains(&value) {
                return Err(ConditionError::Range {
                    what: what.to_string(),
                    column: columns[j].clone(),
                    value,
                    lower,
                    upper,
                });
            }
        }
    }
    Ok(())
}

impl Conditions {
    /// No goal and no via-point.
    pub fn is_empty(&self) -> bool {
        self.goal.is_none() && self.via.is_empty()
    }

    /// Every condition checked against the model's `columns`, their `ranges` (when known:
    /// the arm's joints) and the `initial` posture: widths, finite values, phases in [0, 1],
    /// no two different postures at one phase.
    pub fn check(
        &self,
        columns: &[String],
        ranges: Option<&[(f64, f64)]>,
        initial: &[f64],
    ) -> Result<(), ConditionError> {
        let mut named: Vec<(f64, String, &[f64])> =
            vec![(0.0, "the initial posture".into(), initial)];
        if let Some(g) = &self.goal {
            named.push((1.0, "the goal".into(), g));
        }
        for v in &self.via {
            if !(0.0..=1.0).contains(&v.phase) {
                return Err(ConditionError::Phase(v.phase));
            }
            named.push((
                v.phase,
                format!("the via-point at phase {}", v.phase),
                &v.posture,
            ));
        }
        for (_, what, p) in &named[1..] {
            check_posture(what, p, columns, ranges)?;
        }
        for (i, (pa, a, va)) in named.iter().enumerate() {
            for (pb, b, vb) in &named[i + 1..] {
                if pa == pb && va != vb {
                    return Err(ConditionError::Conflict {
                        phase: *pa,
                        first: a.clone(),
                        second: b.clone(),
                    });
                }
            }
        }
        Ok(())
    }

    /// The phases where a reproduction is pinned after its start ([`Conditions::points`]').
    pub fn phases(&self) -> Vec<f64> {
        self.points().into_iter().map(|(p, _)| p).collect()
    }

    /// The postures to meet after the start, by phase (the goal at phase 1; one of several
    /// equal conditions at a phase; a via-point at phase 0 is the start's).
    pub fn points(&self) -> Vec<(f64, Vec<f64>)> {
        let mut p: Vec<(f64, Vec<f64>)> = self
            .via
            .iter()
            .filter(|v| v.phase > 0.0)
            .map(|v| (v.phase, v.posture.clone()))
            .chain(self.goal.iter().map(|g| (1.0, g.clone())))
            .collect();
        p.sort_by(|a, b| a.0.total_cmp(&b.0));
        p.dedup_by(|a, b| a.0 == b.0);
        p
    }
}

/// The largest change of a reproduction's pace [`meet`] makes when it re-times it: the pace
/// stays between 0.5 and 1.5 times its own.
pub const MAX_PACE_CHANGE: f64 = 0.5;

/// `rows` conditioned on `points` (phase, posture; phases in (0, 1], ascending): first
/// re-timed so that each via-point's phase falls where the trajectory passes nearest its
/// posture ([`retime`]), then bent onto the points exactly ([`bend`]). The first row, the
/// start, stays; the number of rows stays.
///
/// With `ranges` (per variable, its lowest and highest value), each variable is bent where
/// its range cannot be left: on `ln((y - lo) / (hi - y))`, the range widened to hold the
/// re-timed rows and the points as they are. The bend then never takes a value further out
/// than the reproduction or the conditions already are: near a limit it compresses instead
/// of overshooting. The points are still met exactly as [`at_phase`] reads them (a few
/// corrections of the bent variable's targets, since reading between two rows does not
/// commute with the map).
///
/// An error when a point is not met within 1e-9 of the largest value (a reproduction of too
/// few rows to pass a point between two of them).
pub fn meet(
    rows: &[Vec<f64>],
    points: &[(f64, Vec<f64>)],
    ranges: Option<&[(f64, f64)]>,
) -> Result<Vec<Vec<f64>>, ConditionError> {
    let timed = retime(rows, points);
    let scale = timed
        .iter()
        .flatten()
        .chain(points.iter().flat_map(|(_, p)| p))
        .fold(1.0f64, |m, v| m.max(v.abs()));
    let misses = |out: &[Vec<f64>]| -> Vec<Vec<f64>> {
        points
            .iter()
            .map(|(phase, wanted)| {
                let found = at_phase(out, *phase);
                wanted.iter().zip(&found).map(|(w, f)| w - f).collect()
            })
            .collect()
    };
    let out = match ranges.filter(|r| r.len() == timed.first().map_or(0, Vec::len)) {
        None => {
            let mut out = timed;
            bend(&mut out, points);
            out
        }
        Some(ranges) => {
            let maps: Vec<Limits> = (0..ranges.len())
                .map(|d| {
                    let values = (timed.iter().map(|r| r[d])).chain(points.iter().map(|p| p.1[d]));
                    Limits::around(ranges[d], values)
                })
                .collect();
            let to_u = |rows: &[Vec<f64>]| -> Vec<Vec<f64>> {
                (rows.iter())
                    .map(|r| r.iter().zip(&maps).map(|(y, m)| m.to_u(*y)).collect())
                    .collect()
            };
            let base = to_u(&timed);
            let mut targets: Vec<(f64, Vec<f64>)> = (points.iter())
                .map(|(p, y)| (*p, y.iter().zip(&maps).map(|(y, m)| m.to_u(*y)).collect()))
                .collect();
            let mut out = timed.clone();
            for _ in 0..50 {
                let mut u = base.clone();
                bend(&mut u, &targets);
                out = (u.iter())
                    .map(|r| r.iter().zip(&maps).map(|(u, m)| m.to_y(*u)).collect())
                    .collect();
                let miss = misses(&out);
                if miss.iter().flatten().all(|m| m.abs() <= 1e-12 * scale) {
                    break;
                }
                // move each target by how far the reading misses, in the bent variable
                for ((_, wanted), t) in points.iter().zip(&mut targets) {
                    let found = at_phase(&out, t.0);
                    for (d, m) in maps.iter().enumerate() {
                        t.1[d] += m.to_u(wanted[d]) - m.to_u(found[d]);
                    }
                }
            }
            out
        }
    };
    for ((phase, wanted), miss) in points.iter().zip(misses(&out)) {
        let worst = miss.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if out.is_empty() || worst.is_nan() || worst > 1e-9 * scale {
            return Err(ConditionError::Unmet {
                rows: out.len(),
                phase: *phase,
                found: at_phase(&out, *phase),
                wanted: wanted.clone(),
            });
        }
    }
    Ok(out)
}

/// A variable's range as [`meet`] bends it: `u = ln((y - lo) / (hi - y))`, the range widened
/// to hold what the variable already holds, and by a hair more so that a value at a limit
/// maps to a finite `u`.
#[derive(Debug, Clone, Copy)]
struct Limits {
    lo: f64,
    hi: f64,
}

impl Limits {
    /// `range` widened to hold `values`, then by 1e-9 of its width on each side.
    fn around(range: (f64, f64), values: impl Iterator<Item = f64>) -> Limits {
        let (lo, hi) = values.fold(range, |(l, h), v| (l.min(v), h.max(v)));
        let pad = 1e-9 * (hi - lo).max(f64::MIN_POSITIVE);
        Limits {
            lo: lo - pad,
            hi: hi + pad,
        }
    }

    fn to_u(self, y: f64) -> f64 {
        ((y - self.lo) / (self.hi - y)).ln()
    }

    fn to_y(self, u: f64) -> f64 {
        self.lo + (self.hi - self.lo) / (1.0 + (-u).exp())
    }
}

/// `rows` re-timed so that at each via-point's phase `p` (a point before the end) the
/// trajectory is where it passes nearest the point's posture (Euclidean, in the data's
/// units), within the shift of phase that keeps the pace between `1 -`
/// [`MAX_PACE_CHANGE`] and `1 +` it: the phase `s` of the result reads `rows` at
/// `s + Δ(s)`, `Δ` 0 at the start and the end and the chosen shift at each via-point,
/// joined by minimum-jerk blends (whose steepest slope is 1.875 times the mean), read
/// between two rows. The number of rows stays.
pub fn retime(rows: &[Vec<f64>], points: &[(f64, Vec<f64>)]) -> Vec<Vec<f64>> {
    let n = rows.len();
    let via: Vec<&(f64, Vec<f64>)> = points
        .iter()
        .filter(|(p, _)| *p > 0.0 && *p < 1.0)
        .collect();
    if n < 3 || via.is_empty() {
        return rows.to_vec();
    }
    // nearest in the data's own units, as DTW scores a reproduction: scaling each variable
    // by its own range would let one that hardly moves decide where the others pass
    let dist =
        |r: &[f64], q: &[f64]| -> f64 { r.iter().zip(q).map(|(a, b)| (a - b).powi(2)).sum() };
    // the slope of Δ between two knots is at most 1.875 |Δd| / Δp
    let slope = MAX_PACE_CHANGE / MINIMUM_JERK_PEAK;
    let last = (n - 1) as f64;
    // knots (phase, shift): the start, each via-point, the end
    let mut knots: Vec<(f64, f64)> = vec![(0.0, 0.0)];
    for (k, (p, posture)) in via.iter().enumerate() {
        let (prev_p, prev_d) = *knots.last().expect("the start");
        let next_p = via.get(k + 1).map_or(1.0, |(q, _)| *q);
        let lo = (prev_d - slope * (p - prev_p)).max(-slope * (next_p - p));
        let hi = (prev_d + slope * (p - prev_p)).min(slope * (next_p - p));
        let first = ((p + lo) * last).ceil().max(0.0) as usize;
        let end = (((p + hi) * last).floor() as usize).min(n - 1);
        let best = (first..=end.max(first))
            .min_by(|&a, &b| dist(&rows[a], posture).total_cmp(&dist(&rows[b], posture)))
            .unwrap_or(first);
        let d = (best as f64 / last - p).clamp(lo.min(hi), hi.max(lo));
        knots.push((*p, d));
    }
    knots.push((1.0, 0.0));
    let shift = |s: f64| -> f64 {
        let k = knots
            .iter()
            .rposition(|(p, _)| *p <= s)
            .unwrap_or(0)
            .min(knots.len() - 2);
        let ((a, da), (b, db)) = (knots[k], knots[k + 1]);
        da + (db - da) * minimum_jerk_at((s - a) / (b - a))
    };
    (0..n)
        .map(|i| {
            let s = i as f64 / last;
            at_phase(rows, (s + shift(s)).clamp(0.0, 1.0))
        })
        .collect()
}

/// `rows` bent onto `points` (phase, posture; phases in (0, 1], ascending) so that
/// [`at_phase`] reads each posture exactly; the first row, the start, stays.
///
/// Per variable, the offset the trajectory needs at each point is spread over the trajectory
/// by one blend per point: 1 at its point, 0 at the neighbouring points (and at the start),
/// rising and falling along a minimum-jerk profile of the variable's own progress (its
/// smoothed path length), so that the offset changes where the variable moves and hardly
/// where it holds: swings and holds keep their shape. After the last point that is not the
/// end, its offset fades out by the end. The offsets are solved together so that each point
/// is read exactly between its two rows.
pub fn bend(rows: &mut [Vec<f64>], points: &[(f64, Vec<f64>)]) {
    let n = rows.len();
    if n < 2 || points.is_empty() {
        return;
    }
    let last = (n - 1) as f64;
    // the knots in rows: the start, each point, and the end when no point is there
    let mut knots: Vec<f64> = std::iter::once(0.0)
        .chain(points.iter().map(|(p, _)| p * last))
        .collect();
    let open_end = *knots.last().expect("a point") < last;
    if open_end {
        knots.push(last);
    }
    for d in 0..rows[0].len() {
        let y: Vec<f64> = rows.iter().map(|r| r[d]).collect();
        let progress = progress(&y);
        let at = |x: f64| {
            let (i, f) = split_row(n, x);
            progress[i] + f * (progress[i + 1] - progress[i])
        };
        // blend k (k = 1..=points): rising over (knot k-1, knot k), falling over (k, k+1)
        let blend = |k: usize, x: f64| -> f64 {
            let (a, b) = (knots[k - 1], knots[k]);
            if x <= a {
                return 0.0;
            }
            if x <= b {
                return minimum_jerk_at((at(x) - at(a)) / (at(b) - at(a)).max(f64::MIN_POSITIVE));
            }
            match knots.get(k + 1) {
                Some(&c) if x < c => {
                    1.0 - minimum_jerk_at((at(x) - at(b)) / (at(c) - at(b)).max(f64::MIN_POSITIVE))
                }
                _ if k + 1 == knots.len() => 1.0,
                _ => 0.0,
            }
        };
        let read = |f: &dyn Fn(usize) -> f64, phase: f64| {
            let (i, a) = split_phase(n, phase);
            f(i) + a * (f((i + 1).min(n - 1)) - f(i))
        };
        let m = points.len();
        let a = DMatrix::from_fn(m, m, |j, k| read(&|i| blend(k + 1, i as f64), points[j].0));
        let r = DVector::from_fn(m, |j, _| points[j].1[d] - read(&|i| y[i], points[j].0));
        let Some(c) = a.lu().solve(&r) else {
            continue;
        };
        for (i, row) in rows.iter_mut().enumerate().skip(1) {
            row[d] += (0..m).map(|k| c[k] * blend(k + 1, i as f64)).sum::<f64>();
        }
    }
}

/// The smoothed path length of `y` at each row: the integral of sqrt(v² + ε²) with v the
/// central-difference velocity and ε half its mean magnitude: a hold still progresses, at
/// about half the pace of a swing, and the profile has no kink where v changes sign (a
/// smaller ε keeps holds flatter and makes the bend's jerk larger; src/condition/tests.rs).
fn progress(y: &[f64]) -> Vec<f64> {
    let n = y.len();
    let v: Vec<f64> = (0..n)
        .map(|i| {
            let (a, b) = (i.saturating_sub(1), (i + 1).min(n - 1));
            (y[b] - y[a]) / (b - a).max(1) as f64
        })
        .collect();
    let eps = (0.5 * v.iter().map(|x| x.abs()).sum::<f64>() / n as f64).max(1e-12);
    let speed: Vec<f64> = v.iter().map(|x| x.hypot(eps)).collect();
    let mut out = vec![0.0; n];
    for i in 1..n {
        out[i] = out[i - 1] + 0.5 * (speed[i - 1] + speed[i]);
    }
    out
}
