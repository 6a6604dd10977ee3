//! A held-out study as `cosco heldout` and the Python package run it: leave-one-out as the
//! demonstrations were recorded and, when asked, the same folds conditioned on each held-out
//! demonstration's end (and middle) beside it.

use crate::config::HsomConfig;

use super::executor::Executor;
use super::fold::Conditioning;
use super::loo::{leave_one_out, Gestures, LooError, LooSettings};
use super::report::{json_value, markdown};
use super::results::{summary, GestureLoo};

/// Leave-one-out, and the conditioned folds beside it.
#[derive(Debug, Clone, PartialEq)]
pub struct Study {
    /// Every fold from the initial posture alone.
    pub unconditioned: Vec<GestureLoo>,
    /// The same folds conditioned as the settings say (`None` when they say nothing).
    pub conditioned: Option<(Conditioning, Vec<GestureLoo>)>,
    /// The same folds with a far goal, per `K` asked for ([`super::far_target`]).
    pub far: Vec<(f64, Vec<GestureLoo>)>,
}

/// [`leave_one_out`] of `gestures` from the initial posture alone and, when
/// `settings.conditioning` asks for it, again conditioned, and again with a far goal for each
/// of `far` (`progress(done, total)` after each fold of each).
pub fn study<E: Executor>(
    config: &HsomConfig,
    gestures: Gestures,
    settings: &LooSettings,
    far: &[f64],
    executor: &E,
    progress: Option<&(dyn Fn(usize, usize) + Sync)>,
) -> Result<Study, LooError> {
    let plain = LooSettings {
        conditioning: Conditioning::Unconditioned,
        far: None,
        ..*settings
    };
    let far = far
        .iter()
        .map(|&k| {
            let s = LooSettings {
                far: Some(k),
                ..plain
            };
            Ok((
                k,
                leave_one_out(config, gestures.clone(), &s, executor, progress)?,
            ))
        })
        .collect::<Result<Vec<_>, LooError>>()?;
    let conditioned = match settings.conditioning {
        Conditioning::Unconditioned => None,
        c => {
            let s = LooSettings {
                far: None,
                ..*settings
            };
            Some((
                c,
                leave_one_out(config, gestures.clone(), &s, executor, progress)?,
            ))
        }
    };
    Ok(Study {
        unconditioned: leave_one_out(config, gestures, &plain, executor, progress)?,
        conditioned,
        far,
    })
}

impl Study {
    /// The JSON document of `cosco heldout --json`: the configuration's name, the summary and
    /// every gesture's folds; with conditioning, the same under `conditioned` with its
    /// `condition` (`end` or `end+mid`).
    pub fn json(&self, config: &HsomConfig) -> String {
        let mut doc = json_value(config, &self.unconditioned);
        if let (Some((c, study)), Some(map)) = (&self.conditioned, doc.as_object_mut()) {
            map.insert(
                "conditioned".into(),
                serde_json::json!({
                    "condition": c.name(),
                    "summary": summary(study),
                    "gestures": study,
                }),
            );
        }
        if let (false, Some(map)) = (self.far.is_empty(), doc.as_object_mut()) {
            let far: Vec<serde_json::Value> = (self.far.iter())
                .map(|(k, study)| {
                    serde_json::json!({ "k": k, "summary": summary(study), "gestures": study })
                })
                .collect();
            map.insert("far".into(), far.into());
        }
        // cannot fail: plain numbers (non-finite ones become null), strings and enums
        serde_json::to_string_pretty(&doc).unwrap_or_default()
    }

    /// The Markdown tables: unconditioned, then conditioned.
    pub fn markdown(&self) -> String {
        let mut out = markdown(&self.unconditioned);
        if let Some((c, study)) = &self.conditioned {
            let what = match c {
                Conditioning::EndMid => {
                    "last posture (the goal) and its posture at phase 0.5 \
                                         (a via-point)"
                }
                _ => "last posture (the goal)",
            };
            out.push_str(&format!(
                "\n## Conditioned on each held-out demonstration's {what}\n\nThe same folds, \
                 each reproduction also conditioned on the held-out demonstration's {what}. \
                 GMM/GMR cannot be conditioned; the DMP takes the goal only; the replay is as \
                 recorded.\n\n"
            ));
            out.push_str(&markdown(study));
        }
        for (k, study) in &self.far {
            out.push_str(&format!(
                "\n## Far goals: {k} x the end spread\n\nThe same folds, each goal moved {k} times \
                 the training demonstrations' end spread away from their mean end (toward the \
                 held-out demonstration's end), every reproduction conditioned on it; scored \
                 against the held-out demonstration shifted by the same offset, fading in as a \
                 minimum-jerk profile of its phase (docs/METRICS.md, \"Far goals\").\n\n"
            ));
            out.push_str(&markdown(study));
        }
        out
    }
}
