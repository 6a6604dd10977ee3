//! Continuing a prefix, held out ([`continuation_folds`]): the hierarchy and the nearest
//! sequence are shown the first part of a held-out demonstration (as demonstrated, held
//! still or pushed back along its path: [`Disturbance`]) and continue it on the simulated
//! arm.

use std::time::Instant;

use cosco_hsom::config::HsomConfig;
use cosco_hsom::demos::Demonstration;
use cosco_hsom::eval::{
    diagonal, fold_scores, loo_map, Executor, FoldScores, Method, MethodRun, Pool, Split,
};
use cosco_hsom::experiment::heldout::check_demos;
use cosco_hsom::experiment::{ArmExecutor, ExperimentError};
use cosco_hsom::sim::{NaoArm, Transition};

/// What happens to the arm at the end of a shown prefix, before the continuation takes over
/// ([`continuation_folds`]): nothing, held still for a number of samples, or pushed back
/// along its own path by a number of samples (so the prefix ends at an earlier posture of
/// the gesture).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Disturbance {
    /// The prefix as demonstrated.
    None,
    /// The last posture held for this many more samples.
    Hold(usize),
    /// The prefix's last samples retraced backwards, this many.
    Rewind(usize),
}

impl Disturbance {
    /// Parse `none`, `hold:N` or `rewind:N` (N samples, at least 1).
    pub fn parse(text: &str) -> Result<Disturbance, ExperimentError> {
        let bad = || {
            ExperimentError::Invalid(format!(
                "disturbance '{text}': allowed none, hold:N or rewind:N (N samples, at least 1)"
            ))
        };
        if text == "none" {
            return Ok(Disturbance::None);
        }
        let (kind, n) = text.split_once(':').ok_or_else(bad)?;
        let n: usize = n.parse().map_err(|_| bad())?;
        if n == 0 {
            return Err(bad());
        }
        match kind {
            "hold" => Ok(Disturbance::Hold(n)),
            "rewind" => Ok(Disturbance::Rewind(n)),
            _ => Err(bad()),
        }
    }

    /// `prefix` as the encoders read it after the disturbance (a rewind is at most the
    /// prefix's length less one; an empty prefix stays empty).
    pub fn apply(self, prefix: &[Vec<f64>]) -> Vec<Vec<f64>> {
        let mut rows = prefix.to_vec();
        if prefix.is_empty() {
            return rows;
        }
        match self {
            Disturbance::None => {}
            Disturbance::Hold(n) => {
                let last = rows[rows.len() - 1].clone();
                rows.extend(std::iter::repeat(last).take(n));
            }
            Disturbance::Rewind(n) => {
                let n = n.min(prefix.len() - 1);
                rows.extend(
                    prefix[prefix.len() - 1 - n..prefix.len() - 1]
                        .iter()
                        .rev()
                        .cloned(),
                );
            }
        }
        rows
    }
}

/// Continuing a prefix, held out: on fold `i` CoSCo-HSOM learns from every demonstration but
/// `demos[i]` (with `config`), is shown the first `fraction` of `demos[i]`'s samples (at
/// least `actionHorizon + 1`, at most all but one) and continues it
/// ([`Hsom::continue_events`](cosco_hsom::hsom::Hsom::continue_events): the prefix pushed up the
/// lists, the levels plan the rest), and the nearest-sequence baseline continues it from the
/// same model ([`Hsom::follow_nearest_from`](cosco_hsom::hsom::Hsom::follow_nearest_from): the
/// training demonstration along which the prefix runs closest, after the prefix's end).
/// With a `disturbance` the prefix is what the encoders read after it (held still, or
/// pushed back along its path), and both continue from there. The prefix followed by each
/// continuation is executed with `transition` and scored against `demos[i]` alone (the
/// prefix is the same for both, so the difference is the continuation's). Returns (the
/// hierarchy's folds, the baseline's).
pub fn continuation_folds(
    arm: &NaoArm,
    config: &HsomConfig,
    demos: &[Demonstration],
    fraction: f64,
    disturbance: Disturbance,
    transition: Transition,
) -> Result<(Vec<FoldScores>, Vec<FoldScores>), ExperimentError> {
    check_demos(demos)?;
    if !(fraction > 0.0 && fraction < 1.0) {
        return Err(ExperimentError::Invalid(format!(
            "prefix fraction {fraction}: needs a number strictly between 0 and 1"
        )));
    }
    let needed = config.params().action_horizon() + 1;
    let executor = ArmExecutor { arm, transition };
    let pool = Pool::new(1).map_err(ExperimentError::Invalid)?;
    let fold = |split: Split| -> Result<_, ExperimentError> {
        let (train, targets) = split.of(demos);
        let held = &targets[0];
        let k = ((held.rows.len() as f64 * fraction).round() as usize)
            .max(needed)
            .min(held.rows.len() - 1);
        let prefix = &disturbance.apply(&held.rows[..k])[..];
        let t = Instant::now();
        let model = config.fit(&train)?;
        let train_s = t.elapsed().as_secs_f64();
        let score = |rep: cosco_hsom::hsom::Reproduction, reproduce_s: f64| {
            let postures: Vec<Vec<f64>> = prefix
                .iter()
                .chain(rep.postures.iter().skip(1))
                .cloned()
                .collect();
            let executed = executor
                .execute(Method::Hierarchy, &postures, targets)
                .map_err(ExperimentError::Invalid)?;
            let run = MethodRun {
                postures,
                executed,
                train_s,
                reproduce_s,
                fitted: None,
                conditions: Default::default(),
                band: None,
                learned: None,
                aimed: None,
            };
            fold_scores(&run, &executor, &train, held, diagonal(demos))
                .map_err(ExperimentError::Invalid)
        };
        let t = Instant::now();
        let rep = model.continue_events(prefix)?;
        let hsom = score(rep, t.elapsed().as_secs_f64())?;
        let t = Instant::now();
        let rep = model.follow_nearest_from(&train, prefix)?;
        let sequence = score(rep, t.elapsed().as_secs_f64())?;
        Ok((hsom, sequence))
    };
    (loo_map(&[demos], false, &pool, None, |_, split| fold(split)).into_iter())
        .flat_map(|(held_out, _)| held_out)
        .collect::<Result<Vec<_>, ExperimentError>>()
        .map(|v| v.into_iter().unzip())
}
