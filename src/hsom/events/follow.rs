//! Following one demonstration: re-encoding it, following the nearest one, continuing a
//! prefix, resuming.

use crate::demos::Demonstration;

use super::consensus::{aligned_samples, MAX_ALIGNED};
use super::curve::Timing;
use super::encode::{bottom_events, dist2, observed_durations, Step};
use crate::hsom::errors::HsomError;
use crate::hsom::inputs::{check_series, demo_series, Series};
use crate::hsom::model::{EventsHsom, Model, Part};
use crate::hsom::reproduction::{Reproduction, StopReason};

impl<A: Part> Model<A> {
    /// [`check_series`] with this model's stateLength and actionHorizon.
    pub(crate) fn check_demos(&self, series: &[Series<'_>]) -> Result<(), HsomError> {
        let p = self.config.params();
        check_series(series, p.state_length, p.action_horizon())
    }

    /// The demonstration through the bottom level's own code and back: its events (the
    /// bottom node of each run of samples and the run's length, as in training) turned into
    /// postures exactly as a reproduction's planned events are. No upper level is involved,
    /// so this is the ceiling of what the hierarchy can reproduce of that demonstration:
    /// whatever is lost here (a swing's amplitude, a short hold) the levels above cannot
    /// bring back. `predicted_by` is 0 throughout.
    pub(crate) fn reencode(&self, demo: &Demonstration) -> Result<Reproduction, HsomError> {
        self.check_demos(&demo_series(std::slice::from_ref(demo)))?;
        let norm: Vec<Vec<f64>> = demo.rows.iter().map(|r| self.normalise(r)).collect();
        let executed: Vec<Step<usize>> = bottom_events(self, &norm)
            .into_iter()
            .map(|(n, d)| (n, d, 0, None))
            .collect();
        Ok(self.timed_postures(
            &norm[0],
            &norm[0],
            &executed,
            StopReason::EndEvent,
            Timing::Kept,
        ))
    }

    /// The *nearest-sequence* baseline (docs/ALGORITHM.md, section 3.6): of the
    /// demonstrations `demos` (a model's training demonstrations), the one whose first
    /// posture is nearest `initial` (in the model's normalised units), its bottom events
    /// executed from `initial` exactly as a reproduction's planned events are: each event's
    /// node at the posture where the model places it, for the node's learned mean duration
    /// (its own length where the node has none). No level above the bottom is involved:
    /// this is a reproduction whose plan is one whole demonstrated sequence of bottom nodes,
    /// the one that starts nearest, where the levels' plan is built chunk by chunk.
    /// `predicted_by` is 0 throughout.
    pub(crate) fn follow_nearest(
        &self,
        demos: &[Demonstration],
        initial: &[f64],
    ) -> Result<Reproduction, HsomError> {
        self.check_demos(&demo_series(demos))?;
        self.check_initial(initial)?;
        let y0 = self.normalise(initial);
        let nearest = demos
            .iter()
            .map(|d| dist2(&self.normalise(&d.rows[0]), &y0))
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(i, _)| i)
            .ok_or(HsomError::NoDemonstrations)?;
        let all: Vec<Vec<Vec<f64>>> = demos.iter().map(|d| self.normalise_rows(&d.rows)).collect();
        let executed = self.followed(&all, nearest, None);
        Ok(self.timed_postures(&y0, &y0, &executed, StopReason::EndEvent, Timing::Planned))
    }

    /// The bottom events of `norm[d]` (normalised demonstrations) that begin after sample
    /// `after` (all of them for `None`), as planned ones, as a reproduction whose plan follows
    /// that demonstration executes them: each for its node's learned mean duration (its own
    /// length where the node has none); with `plan = traced`, each at that event's place in
    /// the consensus of `norm` ([`Model::event_offsets`]), as a traced plan places it.
    pub(super) fn followed(
        &self,
        norm: &[Vec<Vec<f64>>],
        d: usize,
        after: Option<f64>,
    ) -> Vec<Step<usize>> {
        let own = self
            .part
            .events()
            .is_some_and(|e| e.traces.is_some())
            .then(|| self.event_offsets(norm, &aligned_samples(norm, MAX_ALIGNED)));
        let mut begun = 0.0;
        bottom_events(self, &norm[d])
            .into_iter()
            .enumerate()
            .filter(|&(_, (_, len))| {
                let keep = after.map_or(true, |a| begun > a);
                begun += len;
                keep
            })
            .map(|(i, (n, len))| {
                let learned = self.dwell.get(n).copied().unwrap_or(0.0);
                let at = own.as_ref().map(|o| o[d][i].1.clone());
                (n, if learned > 0.0 { learned } else { len }, 0, at)
            })
            .collect()
    }

    /// The normalised rows of `prefix` (the first samples of a gesture, in the data's units;
    /// `source` names it in errors), once checked as a demonstration is.
    pub(super) fn normalised_prefix(
        &self,
        source: &'static str,
        prefix: &[Vec<f64>],
    ) -> Result<Vec<Vec<f64>>, HsomError> {
        self.check_demos(&[Series {
            source,
            rows: prefix,
        }])?;
        Ok(self.normalise_rows(prefix))
    }

    /// The nearest-sequence baseline for a prefix: of `demos`, the one along which `prefix`
    /// runs closest (open-end DTW in the model's normalised units, per prefix sample), its
    /// bottom events after the sample where the prefix ends along it, executed from the
    /// prefix's last posture as [`Hsom::follow_nearest`] executes them. The postures start
    /// at the prefix's last posture and hold only the continuation.
    pub(crate) fn follow_nearest_from(
        &self,
        demos: &[Demonstration],
        prefix: &[Vec<f64>],
    ) -> Result<Reproduction, HsomError> {
        self.check_demos(&demo_series(demos))?;
        let norm = self.normalised_prefix("prefix", prefix)?;
        let all: Vec<Vec<Vec<f64>>> = demos.iter().map(|d| self.normalise_rows(&d.rows)).collect();
        let (d, end, _) = all
            .iter()
            .enumerate()
            .map(|(d, rows)| {
                let (end, cost) = crate::dtw::open_end_cost(&norm, rows);
                (d, end, cost)
            })
            .min_by(|a, b| a.2.total_cmp(&b.2))
            .ok_or(HsomError::NoDemonstrations)?;
        // the events the prefix has reached (begun at or before its end) are skipped, as
        // `continue_events` takes the prefix's last event as done
        let executed = self.followed(&all, d, Some(end as f64));
        Ok(self.timed_postures(
            &norm[0],
            &norm[norm.len() - 1],
            &executed,
            StopReason::EndEvent,
            Timing::Planned,
        ))
    }
}

impl EventsHsom {
    /// Continue a gesture from its first samples (`prefix`, in the data's units; at least
    /// `actionHorizon + 1` of them) with the events extension's own machinery: the prefix's
    /// bottom events are pushed up the lists exactly as executed events are (each level's
    /// context, phase and completed entries become the prefix's), and the levels plan the rest
    /// from there (docs/ALGORITHM.md, section 3.10). The postures start at the
    /// prefix's last posture and hold only the continuation.
    pub(crate) fn continue_events(&self, prefix: &[Vec<f64>]) -> Result<Reproduction, HsomError> {
        let p = self.config.params();
        let norm = self.normalised_prefix("prefix", prefix)?;
        let events = bottom_events(self, &norm);
        let last = &norm[norm.len() - 1];
        let r = &p.reproduction;
        let mut rep = self.plan_events(&norm[0], last, &events, r);
        rep.truncate(r.max_length);
        Ok(rep)
    }

    /// Resume this model's own reproduction from `initial` after part of it was executed:
    /// `reading` is what the encoders read meanwhile (in the data's units, from `initial`; at
    /// least `actionHorizon + 1` samples), possibly disturbed (held still, slowed, pushed).
    /// The closed loop on the plan's own events (docs/ALGORITHM.md, section
    /// 3.10): the reproduction is planned again from `initial` (it is deterministic), the
    /// reading is aligned with its postures by DTW (open end, the model's normalised units),
    /// so each planned event begun by the reading's end has an observed duration (the reading
    /// samples aligned with it); the plan is then made again with those events executed for
    /// those durations, each pushed up the lists, and where one surprises the levels (a chunk
    /// completed otherwise than expected) the rest is planned anew; the event in progress goes
    /// on for what is left of it. Read back without a disturbance this is the plan itself.
    /// The events are the plan's own, not the reading encoded again: a reproduction's reading
    /// encodes into more bottom events than were planned, and the lists' phase counts events.
    /// The postures start at the reading's last posture and hold only the continuation.
    pub(crate) fn resume(
        &self,
        initial: &[f64],
        reading: &[Vec<f64>],
    ) -> Result<Reproduction, HsomError> {
        let p = self.config.params();
        self.check_initial(initial)?;
        let norm = self.normalised_prefix("reading", reading)?;
        let y0 = self.normalise(initial);
        let r = &p.reproduction;
        let (events, stop) = self.plan_event_list(&y0, &[], &[], r);
        let plan = self.normalise_rows(
            &self
                .timed_postures(&y0, &y0, &events, stop, Timing::Planned)
                .postures,
        );
        // the alignment keeps a cell per (reading, plan) sample pair: bounded as the
        // consensus's alignments are
        let most = MAX_ALIGNED * MAX_ALIGNED / plan.len().max(1);
        if norm.len() > most {
            return Err(HsomError::ReadingTooLong {
                rows: norm.len(),
                most,
                plan: plan.len(),
            });
        }
        let (executed, left) = observed_durations(&norm, &plan, &events);
        let from = &norm[norm.len() - 1];
        if executed.is_empty() {
            return Ok(self.plan_events(&y0, from, &[], r));
        }
        // the events begun are executed as observed (the one in progress as it will have
        // lasted), and the plan is made again from there; the one in progress goes on first
        let (all, stop) = self.plan_event_list(&y0, &[], &executed, r);
        // the continuation is the whole plan's curve (the events executed as observed, then
        // the rest), from where the reading is along it: it starts at the reading's last
        // posture, moving as the encoders read, and goes on through the plan's knots after
        // that time (each turning point kept as in the whole plan)
        let timed = self.retimed(self.timed_knots(&y0, &y0, &all, stop));
        let now = executed.iter().map(|e| e.1).sum::<f64>() - left;
        let rest = timed.from(now, from);
        let v0: Vec<f64> = from
            .iter()
            .zip(&norm[norm.len() - 2])
            .map(|(a, b)| a - b)
            .collect();
        let samples = rest.total.floor() as usize + 1;
        let mut rep = self.curve(&rest, &v0, samples, stop);
        rep.truncate(r.max_length);
        Ok(rep)
    }
}
