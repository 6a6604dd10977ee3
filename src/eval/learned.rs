//! What a method learned on a fold: fitted once ([`Learned::fit`], each method's parameters
//! built here alone), it gives the plan a fold executes ([`Learned::plan`]) and the stepper the
//! loop runs ([`Learned::stepper`]) under the same conditions. The fold keeps it
//! ([`Fold::learned`](super::Fold::learned)), so the loop study does not learn again.

use std::fmt;
use std::sync::Arc;
use std::time::Instant;

use crate::condition::{meet, Conditions, ConfidenceBand};
use crate::dba::Dba;
use crate::demos::Demonstration;
use crate::dmp::{Dmp, DmpSettings, DmpStepper};
use crate::dtw::euclidean;
use crate::gmr::{plan_at, BicScore, ComponentChoice, GmrModel, GmrParams, GmrPlan, TrainingSet};
use crate::hsom::{Hsom, HsomStepper, NearestStepper, Reproduction};
use crate::promp::{Promp, PrompSettings, PrompStepper};
use crate::robot::arm_ranges;
use crate::stepper::Stepper;

use super::method::{peak_speed, Method};

/// What a method learned from a fold's training demonstrations.
#[derive(Debug)]
pub enum Learned {
    /// The hierarchy, the nearest sequence (the hierarchy's model) and height 1: the model.
    Hsom(Arc<Hsom>),
    /// GMM/GMR, its pre-processed training data and the BIC of each component count tried.
    Gmr {
        /// The model.
        model: GmrModel,
        /// The pre-processed training data.
        training: TrainingSet,
        /// BIC of every component count tried.
        bic: Vec<BicScore>,
    },
    /// ProMP's distribution of weights.
    Promp(Promp),
    /// The DMP.
    Dmp(Dmp),
    /// The DTW mean.
    Dba(Dba),
    /// The replay: nothing learned, the training demonstrations as recorded.
    Replay,
}

/// What a method learned, kept for the reports that show it.
#[derive(Debug, Clone)]
pub enum Fitted {
    /// The hierarchy and its reproduction (how each posture was produced, why it stopped).
    Hierarchy {
        /// The model.
        model: Box<Hsom>,
        /// Its reproduction.
        reproduction: Reproduction,
    },
    /// GMM/GMR, its pre-processed training data, the BIC of each component count tried and
    /// the plan it executed (lead-in, then GMR's mean).
    GmmGmr {
        /// The model.
        model: Box<GmrModel>,
        /// The pre-processed training data.
        training: Box<TrainingSet>,
        /// BIC of every component count tried.
        bic: Vec<BicScore>,
        /// The plan.
        plan: GmrPlan,
    },
}

/// What a method planned: the postures, the seconds it took, what it learned for the reports
/// that show it, and its band.
pub struct Planned {
    /// The postures.
    pub postures: Vec<Vec<f64>>,
    /// Time to produce them, seconds.
    pub reproduce_s: f64,
    /// The hierarchy's model and reproduction, GMM/GMR's model and plan.
    pub fitted: Option<Fitted>,
    /// The central 95 % band about the postures, for the methods that give one.
    pub band: Option<ConfidenceBand>,
}

impl Planned {
    /// The plan retimed to last `duration_s` seconds at its `period`, its path kept (the band
    /// with it; [`crate::export::limits::at_duration`]: refused when `names` are a robot's
    /// joints that cannot move that fast).
    pub(super) fn at_duration(
        self,
        names: &[String],
        period: f64,
        duration_s: f64,
    ) -> Result<Planned, String> {
        let rate = 1.0 / period;
        let postures = crate::export::limits::at_duration(names, &self.postures, rate, duration_s)
            .map_err(msg)?;
        let n = postures.len();
        let band = (self.band).map(|b| ConfidenceBand {
            lo: crate::curve::resample_linear(&b.lo, n),
            hi: crate::curve::resample_linear(&b.hi, n),
        });
        Ok(Planned {
            postures,
            band,
            ..self
        })
    }
}

/// The error and its causes on one line.
pub(super) fn msg(e: impl std::error::Error + 'static) -> String {
    crate::errors::error_line(&e)
}

/// What `f` returns, and the seconds it took.
pub(super) fn timed<T>(f: impl FnOnce() -> T) -> (T, f64) {
    let t = Instant::now();
    let r = f();
    (r, t.elapsed().as_secs_f64())
}

/// The hierarchy's model of a fold for `method` (the hierarchy, the nearest sequence or height
/// 1), and the seconds it took to learn.
pub type HsomOf<'a> = dyn FnMut(Method) -> Result<(Arc<Hsom>, f64), String> + 'a;

impl Learned {
    /// `method` learned from `train` (demonstrations `period` seconds a sample; GMM/GMR choosing
    /// its components as `components` says), the hierarchy's model from `hsom`; with the
    /// seconds it took to learn.
    pub fn fit(
        method: Method,
        train: &[Demonstration],
        period: f64,
        components: ComponentChoice,
        hsom: &mut HsomOf<'_>,
    ) -> Result<(Learned, f64), String> {
        match method {
            Method::Hierarchy | Method::NearestSequence | Method::Height1 => {
                hsom(method).map(|(m, s)| (Learned::Hsom(m), s))
            }
            Method::GmmGmr => {
                let (fitted, s) = timed(|| {
                    let p = GmrParams::new().components(components);
                    p.sample_period(period).check()?.fit_with_details(train)
                });
                let (model, training, bic) = fitted.map_err(msg)?;
                let gmr = Learned::Gmr {
                    model,
                    training,
                    bic,
                };
                Ok((gmr, s))
            }
            Method::ProMP => {
                let (m, s) = timed(|| PrompSettings::default().fit(train));
                Ok((Learned::Promp(m.map_err(msg)?), s))
            }
            Method::Dmp => {
                let (m, s) = timed(|| DmpSettings::default().fit(train));
                Ok((Learned::Dmp(m.map_err(msg)?), s))
            }
            Method::Dba => {
                let (m, s) = timed(|| Dba::fit(train));
                Ok((Learned::Dba(m.map_err(msg)?), s))
            }
            Method::Replay => Ok((Learned::Replay, 0.0)),
        }
    }

    /// `method`'s plan from `initial` on `conditions` (learned from `train`, the nearest
    /// sequence following it; GMM/GMR's lead-in at `lead_in_speed`).
    pub fn plan(
        &self,
        method: Method,
        train: &[Demonstration],
        initial: &[f64],
        conditions: &Conditions,
        period: f64,
        lead_in_speed: f64,
    ) -> Result<Planned, String> {
        let (points, phases) = (conditions.points(), conditions.phases());
        match self {
            Learned::Hsom(m) => {
                let (rep, reproduce_s) = timed(|| match method {
                    Method::NearestSequence => m.follow_nearest(train, initial),
                    _ => m.reproduce(initial),
                });
                let mut rep = rep.map_err(msg)?;
                if !points.is_empty() {
                    let ranges = arm_ranges(m.columns());
                    rep.postures = meet(&rep.postures, &points, ranges.as_deref()).map_err(msg)?;
                }
                let band = m.band(&rep.postures, &phases);
                let fitted = (method == Method::Hierarchy).then(|| Fitted::Hierarchy {
                    model: Box::new((**m).clone()),
                    reproduction: rep.clone(),
                });
                Ok(Planned {
                    postures: rep.postures,
                    reproduce_s,
                    fitted,
                    band,
                })
            }
            Learned::Gmr {
                model,
                training,
                bic,
            } => {
                let (plan, reproduce_s) =
                    timed(|| plan_at(model, initial, 1.0 / period, lead_in_speed));
                let plan = plan.map_err(msg)?;
                let band = ConfidenceBand::around(&plan.postures, &plan.band_half_widths());
                Ok(Planned {
                    postures: plan.postures.clone(),
                    reproduce_s,
                    fitted: Some(Fitted::GmmGmr {
                        model: Box::new(model.clone()),
                        training: Box::new(training.clone()),
                        bic: bic.clone(),
                        plan,
                    }),
                    band: Some(band),
                })
            }
            Learned::Promp(m) => {
                let (p, reproduce_s) = timed(|| m.conditioned(initial, &points).map_err(msg));
                let (postures, band) = p?;
                Ok(Planned {
                    postures,
                    reproduce_s,
                    fitted: None,
                    band: Some(band),
                })
            }
            Learned::Dmp(m) => {
                let goal = conditions.goal.as_deref();
                let (p, reproduce_s) = timed(|| m.reproduce(initial, goal).map_err(msg));
                Ok(Planned {
                    postures: p?,
                    reproduce_s,
                    fitted: None,
                    band: None,
                })
            }
            Learned::Dba(m) => {
                let (p, reproduce_s) = timed(|| {
                    let postures = m.reproduce(initial);
                    match points.is_empty() {
                        true => Ok(postures),
                        false => meet(&postures, &points, None).map_err(msg),
                    }
                });
                Ok(Planned {
                    postures: p?,
                    reproduce_s,
                    fitted: None,
                    band: None,
                })
            }
            Learned::Replay => {
                let start = |d: &Demonstration| euclidean(&d.rows[0], initial);
                let nearest = train.iter().min_by(|a, b| start(a).total_cmp(&start(b)));
                Ok(Planned {
                    postures: nearest.ok_or("no training demonstration")?.rows.clone(),
                    reproduce_s: 0.0,
                    fitted: None,
                    band: None,
                })
            }
        }
    }

    /// `method`'s stepper from `initial` on `conditions` (learned from `train`, the nearest
    /// sequence following it; GMM/GMR's lead-in at the demonstrations' peak speed).
    pub fn stepper<'a>(
        &'a self,
        method: Method,
        train: &[Demonstration],
        initial: &[f64],
        conditions: &Conditions,
        period: f64,
    ) -> Result<Box<dyn Stepper + 'a>, String> {
        Ok(match (self, method) {
            (Learned::Hsom(m), Method::NearestSequence) => Box::new(
                NearestStepper::new(&**m, train.to_vec(), initial, conditions, None)
                    .map_err(msg)?,
            ),
            (Learned::Hsom(m), Method::Hierarchy) => {
                Box::new(HsomStepper::new(&**m, initial, conditions, None).map_err(msg)?)
            }
            (Learned::Promp(p), _) => {
                Box::new(PrompStepper::new(p, initial, conditions, None).map_err(msg)?)
            }
            (Learned::Dmp(d), _) => {
                Box::new(DmpStepper::new(d, initial, conditions, None).map_err(msg)?)
            }
            (Learned::Gmr { model, .. }, _) => {
                let speed = peak_speed(train, period);
                let s = crate::gmr::stepper(model, initial, 1.0 / period, speed, conditions);
                Box::new(s.map_err(msg)?)
            }
            _ => return Err(format!("{} does not step", method.name())),
        })
    }
}

/// What a fold's methods learned, kept for the loop study when asked
/// ([`FoldInput::keep`](super::FoldInput::keep)). Not serialised, and not compared: two folds
/// are equal by their results.
#[derive(Clone, Default)]
pub struct Kept(pub Vec<(Method, Arc<Learned>)>);

impl Kept {
    /// What `method` learned, when kept.
    pub fn get(&self, method: Method) -> Option<&Arc<Learned>> {
        self.0.iter().find(|(m, _)| *m == method).map(|(_, l)| l)
    }
}

impl PartialEq for Kept {
    fn eq(&self, _: &Kept) -> bool {
        true
    }
}

impl fmt::Debug for Kept {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_list()
            .entries(self.0.iter().map(|(m, _)| m.name()))
            .finish()
    }
}

#[cfg(test)]
mod tests;
