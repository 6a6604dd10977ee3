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
}

/// [`leave_one_out`] of `gestures` from the initial posture alone and, when
/// `settings.conditioning` asks for it, again conditioned (`progress(done, total)` after each
/// fold of each).
pub fn study<E: Executor>(
    config: &HsomConfig,
    gestures: Gestures,
    settings: &LooSettings,
    executor: &E,
    progress: Option<&(dyn Fn(usize, usize) + Sync)>,
) -> Result<Study, LooError> {
    let plain = LooSettings {
        conditioning: Conditioning::Unconditioned,
        ..*settings
    };
    let conditioned = match settings.conditioning {
        Conditioning::Unconditioned => None,
        c => Some((
            c,
            leave_one_out(config, gestures.clone(), settings, executor, progress)?,
        )),
    };
    Ok(Study {
        unconditioned: leave_one_out(config, gestures, &plain, executor, progress)?,
        conditioned,
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
        // cannot fail: plain numbers (non-finite ones become null), strings and enums
        serde_json::to_string_pretty(&doc).unwrap_or_default()
    }

    /// The Markdown tables: unconditioned, then conditioned.
    pub fn markdown(&self) -> String {
        let mut out = markdown(&self.unconditioned);
        if let Some((c, study)) = &self.conditioned {
            let what = match c {
                Conditioning::EndMid => "last posture (the goal) and its posture at phase 0.5 \
                                         (a via-point)",
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
        out
    }
}
