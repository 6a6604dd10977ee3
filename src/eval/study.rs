//! A held-out study as `cosco heldout` and the Python package run it: leave-one-out as the
//! demonstrations were recorded and, when asked, the same folds conditioned on each held-out
//! demonstration's end (and middle) beside it.

use std::collections::BTreeMap;

use serde::Serialize;

use crate::config::HsomConfig;
use crate::table::Table;

use super::executor::Executor;
use super::fold::Conditioning;
use super::loo::{leave_one_out, Gestures, LooError, LooSettings};
use super::report::{json_text, markdown};
use super::results::{summary, GestureLoo, MethodSummary};
use super::two_arms::GestureLags;

/// Leave-one-out, and the conditioned folds beside it.
#[derive(Debug, Clone, PartialEq)]
pub struct Study {
    /// Every fold from the initial posture alone.
    pub unconditioned: Vec<GestureLoo>,
    /// The same folds conditioned as the settings say (`None` when they say nothing).
    pub conditioned: Option<(Conditioning, Vec<GestureLoo>)>,
    /// The same folds with a far goal, per `K` asked for ([`super::far_target`]).
    pub far: Vec<(f64, Vec<GestureLoo>)>,
    /// The same folds taught in two sittings (`None` unless the settings ask for it).
    pub sittings: Option<Vec<GestureLoo>>,
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
        sittings: false,
        ..*settings
    };
    let sittings = match settings.sittings {
        false => None,
        true => {
            let s = LooSettings {
                sittings: true,
                in_sample: false,
                keep_learned: false,
                ..plain
            };
            Some(leave_one_out(
                config,
                gestures.clone(),
                &s,
                executor,
                progress,
            )?)
        }
    };
    let far = far
        .iter()
        .map(|&k| {
            let s = LooSettings {
                far: Some(k),
                keep_learned: false,
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
                sittings: false,
                keep_learned: false,
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
        sittings,
    })
}

/// A part of a held-out study computed from its folds besides the tables (the simulator's
/// contacts, `experiment::upper_body`): Markdown appended to the tables, JSON under `key`.
#[derive(Debug, Clone, PartialEq)]
pub struct Section {
    /// The key of the JSON document it goes under.
    pub key: &'static str,
    /// Its Markdown.
    pub markdown: String,
    /// Its JSON.
    pub json: serde_json::Value,
}

/// What computes a [`Section`] from the unconditioned folds (`None`: nothing for this data;
/// the reason as a line when it fails).
pub type Extra<'a> = &'a (dyn Fn(&[GestureLoo]) -> Result<Option<Section>, String> + Sync);

/// The JSON document of a held-out study (`cosco heldout --json`): the configuration's name,
/// the [`summary`] and every gesture's folds; on the upper body, the two arms' lags; the
/// conditioned, far-goal and two-sittings folds when run; and the sections computed besides
/// ([`Section`]) under their keys. Written by [`json_text`]: keys in alphabetical order at
/// every level.
#[derive(Debug, Serialize)]
pub struct StudyDocument<'a> {
    config: &'a str,
    summary: Vec<MethodSummary>,
    gestures: &'a [GestureLoo],
    #[serde(skip_serializing_if = "Vec::is_empty")]
    two_arms: Vec<GestureLags>,
    #[serde(skip_serializing_if = "Option::is_none")]
    conditioned: Option<Folds<'a>>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    far: Vec<Folds<'a>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    sittings: Option<Folds<'a>>,
    #[serde(flatten)]
    sections: BTreeMap<&'static str, &'a serde_json::Value>,
}

/// A run of the study's folds besides the unconditioned one: its summary, its folds and what
/// sets it apart (the condition, the far goal's `K`, or the ratios to the folds taught at once).
#[derive(Debug, Serialize)]
struct Folds<'a> {
    #[serde(skip_serializing_if = "Option::is_none")]
    condition: Option<&'static str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    k: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    against_at_once: Option<Vec<SittingsRatio>>,
    summary: Vec<MethodSummary>,
    gestures: &'a [GestureLoo],
}

impl<'a> Folds<'a> {
    fn of(study: &'a [GestureLoo]) -> Self {
        Folds {
            condition: None,
            k: None,
            against_at_once: None,
            summary: summary(study),
            gestures: study,
        }
    }
}

impl Study {
    /// The study's [`StudyDocument`], with `sections` under their keys.
    pub fn document<'a>(
        &'a self,
        config: &'a HsomConfig,
        sections: &'a [Section],
    ) -> StudyDocument<'a> {
        StudyDocument {
            config: config.source(),
            summary: summary(&self.unconditioned),
            gestures: &self.unconditioned,
            two_arms: super::two_arms(&self.unconditioned),
            conditioned: (self.conditioned.as_ref()).map(|(c, study)| Folds {
                condition: Some(c.name()),
                ..Folds::of(study)
            }),
            far: (self.far.iter())
                .map(|(k, study)| Folds {
                    k: Some(*k),
                    ..Folds::of(study)
                })
                .collect(),
            sittings: self.sittings.as_deref().map(|study| Folds {
                against_at_once: Some(sittings_ratios(&self.unconditioned, study)),
                ..Folds::of(study)
            }),
            sections: sections.iter().map(|s| (s.key, &s.json)).collect(),
        }
    }

    /// The JSON document of `cosco heldout --json` without sections ([`Study::document`]).
    pub fn json(&self, config: &HsomConfig) -> String {
        json_text(&self.document(config, &[]))
    }

    /// The Markdown tables: unconditioned (on the upper body with the two arms' lags), then
    /// conditioned.
    pub fn markdown(&self) -> String {
        let mut out = markdown(&self.unconditioned);
        out.push_str(&super::two_arms::markdown(&super::two_arms(
            &self.unconditioned,
        )));
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
        if let Some(study) = &self.sittings {
            out.push_str(
                "\n## Taught in two sittings\n\nThe same folds, each hierarchy (and height 1) \
                 trained on the first half of its training demonstrations (rounded down) and \
                 updated with the rest, from the model and the new demonstrations alone \
                 (docs/ALGORITHM.md, section 10). GMM/GMR, ProMP, the DMP, the nearest sequence and \
                 the replay refit on what a model keeps of the first half and the rest.\n\n",
            );
            out.push_str(&sittings_table(&self.unconditioned, study));
            out.push('\n');
            out.push_str(&markdown(study));
        }
        out
    }
}

/// Per method: the median relative DTW taught at once and in two sittings, and their ratio
/// (in sittings over at once).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SittingsRatio {
    /// Which method.
    pub method: super::Method,
    /// Median relative DTW, held out, taught at once.
    pub at_once: Option<f64>,
    /// The same taught in two sittings.
    pub in_sittings: Option<f64>,
    /// `in_sittings / at_once`.
    pub ratio: Option<f64>,
    /// Held-out folds of the wave ("wave" in the gesture's name) whose reproduction in sittings
    /// keeps the held-out demonstration's swing count, and the wave's folds.
    pub wave_swings: (usize, usize),
}

/// [`SittingsRatio`] of every method in both studies.
pub fn sittings_ratios(at_once: &[GestureLoo], sittings: &[GestureLoo]) -> Vec<SittingsRatio> {
    let once = summary(at_once);
    summary(sittings)
        .into_iter()
        .map(|s| {
            let a = once
                .iter()
                .find(|o| o.method == s.method)
                .and_then(|o| o.relative_dtw);
            let folds = sittings
                .iter()
                .filter(|g| g.gesture.contains("wave"))
                .flat_map(|g| &g.held_out)
                .filter_map(|f| f.score(s.method));
            let (kept, n) = folds.fold((0, 0), |(k, n), sc| match sc.swings {
                Some([rep, demo]) => (k + usize::from(rep == demo), n + 1),
                None => (k, n),
            });
            SittingsRatio {
                method: s.method,
                at_once: a,
                in_sittings: s.relative_dtw,
                ratio: a.zip(s.relative_dtw).map(|(a, b)| b / a),
                wave_swings: (kept, n),
            }
        })
        .collect()
}

/// The Markdown table of [`sittings_ratios`].
fn sittings_table(at_once: &[GestureLoo], sittings: &[GestureLoo]) -> String {
    let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
    let mut table = Table::new([
        "method",
        "relative DTW at once",
        "in two sittings",
        "ratio",
        "wave: swings kept",
    ]);
    for r in sittings_ratios(at_once, sittings) {
        let (k, n) = r.wave_swings;
        table.row([
            r.method.name().to_string(),
            f(r.at_once),
            f(r.in_sittings),
            r.ratio.map_or("-".to_string(), |v| format!("{v:.3}")),
            if n == 0 {
                "-".to_string()
            } else {
                format!("{k}/{n}")
            },
        ]);
    }
    table.to_string()
}
