//! A synthetic demonstrator: turns a [`Gesture`] into the continuous joint trajectory a
//! person guiding the arm would produce, with a person's variability.
//!
//! The trajectory is a superposition of per-joint minimum-jerk blends (one per `Move`,
//! starting at a slightly different moment for each joint, as a hand guiding an arm never
//! moves all joints at once), faded oscillations, and a smooth low-frequency wobble that is
//! present only while the person moves the arm. Idle time before and after varies widely
//! (the paper's footnote 3), overall speed by about +-20 %, key poses by a few degrees.

use crate::curve::minimum_jerk_at;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

use super::library::{Gesture, Pose, Segment};

/// How much one demonstration differs from the next. All angles in degrees for readability.
#[derive(Debug, Clone, PartialEq)]
pub struct Variation {
    /// Idle time before the movement starts, uniform in this range (s).
    pub idle_before: (f64, f64),
    /// Idle time after the movement ends, uniform in this range (s).
    pub idle_after: (f64, f64),
    /// Relative speed spread: the speed factor is uniform in `1 +- speed` (0.2 = +-20 %).
    pub speed: f64,
    /// Standard deviation of each key pose's joint angles (degrees).
    pub amplitude_deg: f64,
    /// Amplitude of the smooth wobble while moving (degrees).
    pub wobble_deg: f64,
    /// Largest per-joint delay of a movement's start (s).
    pub stagger: f64,
}

impl Default for Variation {
    fn default() -> Self {
        Variation {
            idle_before: (0.4, 2.4),
            idle_after: (0.4, 2.0),
            speed: 0.2,
            amplitude_deg: 3.0,
            wobble_deg: 1.0,
            stagger: 0.06,
        }
    }
}

impl Variation {
    /// No variability at all: the nominal gesture with fixed 1 s idle times.
    pub fn none() -> Self {
        Variation {
            idle_before: (1.0, 1.0),
            idle_after: (1.0, 1.0),
            speed: 0.0,
            amplitude_deg: 0.0,
            wobble_deg: 0.0,
            stagger: 0.0,
        }
    }

    /// Check every field: ranges ordered and non-negative, speed below 0.9, finite values.
    pub fn check(&self) -> Result<(), String> {
        for (name, (lo, hi)) in [
            ("idle_before", self.idle_before),
            ("idle_after", self.idle_after),
        ] {
            if !(lo.is_finite() && hi.is_finite() && lo >= 0.0 && hi >= lo) {
                return Err(format!(
                    "variation {name} = ({lo}, {hi}): need 0 <= low <= high"
                ));
            }
        }
        if !(self.speed.is_finite() && (0.0..0.9).contains(&self.speed)) {
            return Err(format!(
                "variation speed = {}: allowed 0 <= speed < 0.9",
                self.speed
            ));
        }
        for (name, v) in [
            ("amplitude_deg", self.amplitude_deg),
            ("wobble_deg", self.wobble_deg),
            ("stagger", self.stagger),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(format!("variation {name} = {v}: need a finite value >= 0"));
            }
        }
        Ok(())
    }
}

/// A time-continuous demonstrator trajectory, evaluated on demand.
#[derive(Debug, Clone)]
pub struct HumanTrajectory {
    initial: Pose,
    moves: Vec<Blend>,
    oscillations: Vec<Oscillation>,
    wobble: Vec<[(f64, f64, f64); 3]>,
    motion_start: f64,
    motion_end: f64,
    total: f64,
    limits: Vec<(f64, f64)>,
}

#[derive(Debug, Clone)]
struct Blend {
    start: Vec<f64>,
    duration: f64,
    delta: Pose,
}

#[derive(Debug, Clone)]
struct Oscillation {
    joints: Vec<(usize, f64)>,
    start: f64,
    amplitude: f64,
    period: f64,
    cycles: f64,
}

fn smoothstep(s: f64) -> f64 {
    let s = s.clamp(0.0, 1.0);
    s * s * (3.0 - 2.0 * s)
}

impl HumanTrajectory {
    /// Draw one demonstration of `gesture` with `variation` from `rng`. Perturbed key poses
    /// are kept 0.02 rad inside the gesture's robot's joint ranges, and every posture within them.
    pub fn sample(
        gesture: &Gesture,
        variation: &Variation,
        rng: &mut ChaCha8Rng,
    ) -> Result<HumanTrajectory, String> {
        variation.check()?;
        let limits = gesture.robot.ranges();
        let n = limits.len();
        let uniform = |rng: &mut ChaCha8Rng, (lo, hi): (f64, f64)| {
            if hi > lo {
                rng.gen_range(lo..hi)
            } else {
                lo
            }
        };
        let idle_before = uniform(rng, variation.idle_before);
        let idle_after = uniform(rng, variation.idle_after);
        let speed = 1.0 + uniform(rng, (-variation.speed, variation.speed));
        let amp =
            Normal::new(0.0, variation.amplitude_deg.to_radians()).map_err(|e| e.to_string())?;

        let mut t = idle_before;
        let mut pose = gesture.initial.clone();
        let mut moves = Vec::new();
        let mut oscillations = Vec::new();
        for seg in &gesture.segments {
            // Each segment's duration varies a little around the overall speed too.
            let jitter = 1.0 + uniform(rng, (-0.05, 0.05)) * (variation.speed > 0.0) as u8 as f64;
            match seg {
                Segment::Move { to, duration, .. } | Segment::Aim { to, duration, .. } => {
                    let d = duration / speed * jitter;
                    let mut target = to.clone();
                    if let Segment::Aim { spread, .. } = seg {
                        for &(j, deg) in spread {
                            let aim =
                                Normal::new(0.0, deg.to_radians()).map_err(|e| e.to_string())?;
                            target[j] += aim.sample(rng);
                        }
                    }
                    if !matches!(seg, Segment::Move { perturb: false, .. }) {
                        for (j, v) in target.iter_mut().enumerate() {
                            let (lo, hi) = limits[j];
                            *v = (*v + amp.sample(rng)).clamp(lo + 0.02, hi - 0.02);
                        }
                    }
                    moves.push(Blend {
                        start: (0..n)
                            .map(|_| t + uniform(rng, (0.0, variation.stagger)))
                            .collect(),
                        duration: d,
                        delta: target.iter().zip(&pose).map(|(a, b)| a - b).collect(),
                    });
                    pose = target;
                    t += d;
                }
                Segment::Hold { duration } => t += duration / speed * jitter,
                Segment::Oscillate {
                    joints,
                    amplitude,
                    period,
                    cycles,
                } => {
                    let p = period / speed * jitter;
                    let a = amplitude
                        * (1.0
                            + uniform(rng, (-0.15, 0.15))
                                * (variation.amplitude_deg > 0.0) as u8 as f64);
                    oscillations.push(Oscillation {
                        joints: joints.clone(),
                        start: t,
                        amplitude: a,
                        period: p,
                        cycles: *cycles,
                    });
                    t += p * cycles;
                }
            }
        }
        let motion_end = t + variation.stagger;
        let wobble = (0..n)
            .map(|_| {
                std::array::from_fn(|_| {
                    let freq = uniform(rng, (0.2, 0.9));
                    let phase = uniform(rng, (0.0, std::f64::consts::TAU));
                    let amplitude = variation.wobble_deg.to_radians() / 3.0_f64.sqrt();
                    (amplitude, freq, phase)
                })
            })
            .collect();
        Ok(HumanTrajectory {
            initial: gesture.initial.clone(),
            moves,
            oscillations,
            wobble,
            motion_start: idle_before,
            motion_end,
            total: motion_end + idle_after,
            limits,
        })
    }

    /// Total length in seconds, idle times included.
    pub fn duration(&self) -> f64 {
        self.total
    }

    /// When the person starts and stops moving the arm (s).
    pub fn motion_interval(&self) -> (f64, f64) {
        (self.motion_start, self.motion_end)
    }

    /// The posture at time `t` (s), inside the joint limits.
    pub fn at(&self, t: f64) -> Pose {
        let mut q = self.initial.clone();
        for m in &self.moves {
            for ((v, d), s) in q.iter_mut().zip(&m.delta).zip(&m.start) {
                *v += d * minimum_jerk_at((t - s) / m.duration);
            }
        }
        for o in &self.oscillations {
            let span = o.period * o.cycles;
            let local = t - o.start;
            if (0.0..=span).contains(&local) {
                let fade = o.period / 4.0;
                let env = smoothstep(local / fade) * smoothstep((span - local) / fade);
                let v = o.amplitude * env * (std::f64::consts::TAU * local / o.period).sin();
                for &(j, w) in &o.joints {
                    q[j] += w * v;
                }
            }
        }
        // The wobble lives only while the arm is guided: faded in and out over 0.3 s.
        let env =
            smoothstep((t - self.motion_start) / 0.3) * smoothstep((self.motion_end - t) / 0.3);
        if env > 0.0 {
            for (j, comps) in self.wobble.iter().enumerate() {
                let w: f64 = comps
                    .iter()
                    .map(|&(a, f, ph)| a * ((std::f64::consts::TAU * f * t + ph).sin()))
                    .sum();
                q[j] += env * w;
            }
        }
        for (j, v) in q.iter_mut().enumerate() {
            let (lo, hi) = self.limits[j];
            *v = v.clamp(lo, hi);
        }
        q
    }

    /// The posture sampled every `dt` seconds from 0 to the end, inclusive.
    pub fn sampled(&self, dt: f64) -> Vec<(f64, Pose)> {
        let n = (self.total / dt).floor() as usize;
        (0..=n)
            .map(|i| {
                let t = i as f64 * dt;
                (t, self.at(t))
            })
            .collect()
    }
}

#[cfg(test)]
mod tests;
