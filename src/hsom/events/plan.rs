//! A reproduction: the levels climbed while they are confident, the highest one's plan
//! expanded to timed bottom events, re-planned on a surprise.

use std::collections::VecDeque;

use crate::config::ReproductionParams;

use super::curve::Timing;
use super::encode::{
    a_part, b_part, chunk_input, dist2, event_content, summary, DurationCode, Item, Step,
};
use super::levels::used;
use super::traces::{trace_bmus_at, trace_places, trace_postures_at, Decoder, TRACE_HEAD};
use super::END;
use crate::hsom::followers::most_frequent;
use crate::hsom::inputs::Layout;
use crate::hsom::model::EventsHsom;
use crate::hsom::reproduction::{Reproduction, StopReason};

impl EventsHsom {
    /// The events reproduction after `prefix`, bottom events already executed from the
    /// normalised posture `start` (none: a reproduction from `start`): they are pushed up the
    /// lists exactly as executed events are, so every level's context and completed entries
    /// are theirs, and the plan continues from there. The postures returned start at `from`
    /// (the prefix's last posture) and hold only the continuation's events.
    pub(in crate::hsom) fn plan_events(
        &self,
        start: &[f64],
        from: &[f64],
        prefix: &[(usize, f64)],
        r: &ReproductionParams,
    ) -> Reproduction {
        let (executed, stop) = self.plan_event_list(start, prefix, &[], r);
        self.timed_postures(
            start,
            from,
            &executed[prefix.len()..],
            stop,
            Timing::Planned,
        )
    }

    /// The events of [`EventsHsom::plan_events`]: the prefix's, then the planned ones, each (node,
    /// duration in samples, level that planned it), and why the plan ended. The first
    /// planned events are `executed` where given (what was executed of an earlier plan: its
    /// nodes, for the durations observed): each is pushed up the lists in the plan's place,
    /// and where it surprises the levels the rest of the plan is made anew, as for any
    /// executed event.
    pub(super) fn plan_event_list(
        &self,
        start: &[f64],
        prefix: &[(usize, f64)],
        observed: &[(usize, f64)],
        r: &ReproductionParams,
    ) -> (Vec<Step<usize>>, StopReason) {
        let cfg = &self.config;
        let p = cfg.params();
        let max_len = r.max_length;
        let lay = Layout::of(cfg);
        let s = lay.s;
        let h = p.height;
        let code = DurationCode::from_dwell(&self.dwell);
        let mean_events = self.demo_runs[1].max(1.0);
        let cap = ((self.demo_len[2] * r.length_factor).ceil() as usize).clamp(2, max_len.max(2));
        let used_levels: Vec<Vec<usize>> = (0..h).map(|l| used(self, l)).collect();
        let top = r.max_level.unwrap_or(h - 1).min(h - 1);
        // the initial event: the bottom node nearest to the initial posture (state half)
        let (n_init, _) = self.maps[0].bmu_range(start, 0..s);
        let init_content = event_content(&self.maps[0], n_init, 0.0, code);
        let mut lists = Lists::new(h, a_part(lay, &init_content));
        let mut plan: VecDeque<Step<u32>> = VecDeque::new();
        // the training demonstration the last traced plan came from
        let mut follow: Option<u32> = None;
        let mut executed: Vec<Step<usize>> = Vec::new();
        let mut x = vec![0.0; lay.dim()];
        let mut mask = vec![true; lay.dim()];
        let mut total = 0.0;
        let mut stop = StopReason::LearnedLength;
        let mut first = prefix.is_empty();
        for &(node, dur) in prefix {
            executed.push((node, dur, 0, None));
            total += dur;
            lists.push_event(self, lay, code, mean_events, node, dur);
        }
        'run: loop {
            if plan.is_empty() {
                lists.expected.iter_mut().for_each(|e| e.clear());
                // climb while the match lies within what the level saw in training
                let mut matched: Vec<usize> = vec![0; h];
                let mut level = 0;
                for (l, slot) in matched.iter_mut().enumerate().take(top + 1).skip(1) {
                    let known = lists.input(lay, l, mean_events, &mut x, &mut mask);
                    let (b, d2) = self.maps[l].bmu_masked(&x, &mask);
                    // level 1 always predicts (the lowest level with a sequence and a
                    // context); higher levels only while they are not confused
                    if l > 1
                        && (!self.level_trusted(l)
                            || (d2 / known as f64).sqrt()
                                > self.part.threshold[l] * (1.0 + 1e-9) + 1e-12)
                    {
                        break;
                    }
                    *slot = b;
                    level = l;
                }
                if level == 0 {
                    // confused everywhere: the bottom's lookup table (its reflex)
                    let last = executed.last().map_or(n_init, |e| e.0);
                    let next = if first {
                        n_init as u32
                    } else {
                        most_frequent(&self.part.followers[0], self.maps[0].len(), last as u32)
                    };
                    if next == u32::MAX || next == END {
                        stop = StopReason::EndEvent;
                        break 'run;
                    }
                    plan.push_back((next, self.dwell[next as usize].max(1.0), 0, None));
                } else {
                    let done: Vec<usize> = lists.chunk.iter().map(|c| c.len()).collect();
                    let here: Vec<f64> = match executed.last() {
                        Some(e) => self.maps[0].weights(e.0)[..s].to_vec(),
                        None => start[..s].to_vec(),
                    };
                    let ctx = Planner {
                        lay,
                        code,
                        matched: &matched,
                        done: &done,
                        used: &used_levels,
                        by: level,
                        executed: executed.len(),
                        here: &here,
                        index: &lists.index,
                    };
                    // the chunk in progress at the top level used is its own match
                    let mut tail = lists.tail.clone();
                    // where the plan is in the gesture: its top node's exemplar position
                    // (none for a node no training chunk chose)
                    let pos = if self.exemplar(level, matched[level], 0) == u32::MAX {
                        f64::NAN
                    } else {
                        self.part.exemplar_phase[level][matched[level]]
                    };
                    let traced =
                        self.traced_plan(&ctx, level, &mut follow, &mut plan, &mut lists.expected);
                    if !traced {
                        self.expand(
                            &ctx,
                            level,
                            matched[level],
                            done[level],
                            true,
                            pos,
                            &mut plan,
                            &mut lists.expected,
                            &mut tail,
                        );
                    }
                }
            }
            let planned = plan.pop_front();
            let (node, dur, by, at) = match (observed.get(executed.len() - prefix.len()), planned) {
                // an observed event keeps the planned one's place only where it is that event
                (Some(&(n, d)), planned) => match planned {
                    Some((m, _, by, at)) => (n as u32, d, by, at.filter(|_| m == n as u32)),
                    None => (n as u32, d, 0, None),
                },
                (None, Some(e)) => e,
                (None, None) => break,
            };
            first = false;
            if node == END {
                stop = StopReason::EndEvent;
                break;
            }
            let node = node as usize;
            // never past the cap, whatever a (loaded, untrusted) duration says
            let dur = dur.min(cap as f64 - total).max(1.0);
            executed.push((node, dur, by, at));
            total += dur;
            if total >= cap as f64 {
                stop = StopReason::LearnedLength;
                break;
            }
            // push the executed event up the lists, as in training; re-plan on surprise
            let surprise = lists.push_event(self, lay, code, mean_events, node, dur);
            if surprise {
                plan.clear();
            }
        }
        (executed, stop)
    }

    /// The plan of the demonstrated stretch node `matched[level]` stands for, from where the
    /// reproduction is in its chunk (docs/ALGORITHM.md, section 3.6): of the
    /// training chunks the node keeps ([`Traces`]) at the reproduction's place in the gesture
    /// (the same chunk index), the one whose bottom event before it was nearest where the
    /// reproduction is (`ctx.here`: the last executed event's node, or the start; for a
    /// demonstration's first chunk its first event; ties to the one nearest the node's
    /// weights): the chunk that goes on from the event just executed. Its bottom events go to
    /// `plan` (at their nodes' learned durations), and the entries of every level below it
    /// completes to `expected` (the chunk's; the partial match for a chunk already begun).
    /// False where the node keeps no such chunk: the plan is then decoded.
    fn traced_plan(
        &self,
        ctx: &Planner<'_>,
        level: usize,
        follow: &mut Option<u32>,
        plan: &mut VecDeque<Step<u32>>,
        expected: &mut [VecDeque<u32>],
    ) -> bool {
        let Some(chunks) = self
            .part
            .traces
            .as_ref()
            .and_then(|t| t.levels.get(level))
            .filter(|w| !w.is_empty())
        else {
            return false;
        };
        let (k, s, pw) = (ctx.lay.k, ctx.lay.s, trace_places(self.config.params()));
        let n0 = self.maps[0].len();
        let postures = trace_postures_at(k, level);
        let span = k.pow(level as u32);
        let n = ctx.matched[level];
        // bottom events the reproduction has completed in its current chunk of this level
        let off: usize = (1..=level).map(|m| ctx.done[m] * k.pow(m as u32 - 1)).sum();
        let index = ctx.index[level];
        let followed = *follow;
        // the demonstration followed goes on; otherwise the node matched, otherwise any;
        // nearest first, then nearest the node's weights (the first of equals)
        let best = chunks
            .iter()
            .filter(|c| {
                let slot = &c.words;
                slot[0] as usize == index
                    && off < span
                    && slot[TRACE_HEAD + off] != u32::MAX
                    && (slot[1] as usize) < n0
            })
            .map(|c| {
                let slot = &c.words[..];
                let d = dist2(&self.maps[0].weights(slot[1] as usize)[..s], ctx.here);
                (slot, Some(slot[2]) != followed, c.node as usize != n, d)
            })
            .min_by(|a, b| a.1.cmp(&b.1).then(a.2.cmp(&b.2)).then(a.3.total_cmp(&b.3)));
        let Some((slot, ..)) = best else {
            *follow = None;
            return false;
        };
        *follow = Some(slot[2]);
        let mut end = off;
        for &e in &slot[TRACE_HEAD + off..TRACE_HEAD + span] {
            if e == u32::MAX || (e != END && e as usize >= n0) {
                break;
            }
            end += 1;
            if e == END {
                plan.push_back((END, 0.0, ctx.by, None));
                break;
            }
            // where this event of that demonstration lies in the consensus (none stored:
            // where its node is placed)
            let at = &slot[postures + (end - 1) * pw..postures + end * pw];
            let at =
                (at[0] != u32::MAX).then(|| at.iter().map(|&v| f32::from_bits(v) as f64).collect());
            plan.push_back((e, self.dwell[e as usize].max(1.0), ctx.by, at));
        }
        let mut at = trace_bmus_at(k, level, pw);
        for (m, exp) in expected.iter_mut().enumerate().take(level).skip(1) {
            let count = k.pow((level - m) as u32);
            let sm = k.pow(m as u32);
            let mut q = off / sm;
            while (q + 1) * sm <= end {
                let e = if q == off / sm && off % sm != 0 {
                    ctx.matched[m] as u32
                } else {
                    slot[at + q]
                };
                if e == u32::MAX {
                    break;
                }
                exp.push_back(e);
                q += 1;
            }
            at += count;
        }
        true
    }

    /// Expand the prediction of node `n` of `level` from slot `from` into timed bottom
    /// events (`plan`), and the entries of every level it expects (`expected`). With
    /// `in_progress`, the slot `from` is the chunk being executed below: it is the lower
    /// level's own match (`matched`), expanded from what that chunk has completed (`done`).
    #[allow(clippy::too_many_arguments)]
    fn expand(
        &self,
        ctx: &Planner<'_>,
        level: usize,
        n: usize,
        from: usize,
        in_progress: bool,
        pos: f64,
        plan: &mut VecDeque<Step<u32>>,
        expected: &mut [VecDeque<u32>],
        tail: &mut [u32],
    ) -> bool {
        let lay = ctx.lay;
        let w = self.maps[level].weights(n);
        let mean_events = self.demo_runs[1].max(1.0);
        for j in from..lay.k {
            let c = &w[lay.slot_range(j)];
            let slot_pos = pos + (j * lay.k.pow(level as u32 - 1)) as f64 / mean_events;
            let below = level - 1;
            // above level 1, the slot being executed below is that level's own match
            let resumed = in_progress && j == from && level > 1;
            let m = if resumed {
                ctx.matched[below] as u32
            } else {
                // level 1 decodes by position too
                let (before, at) = match level {
                    1 => ((ctx.executed + plan.len()) as f64, slot_pos),
                    _ => (0.0, f64::NAN),
                };
                let hint = self.exemplar(level, n, j);
                let used = &ctx.used[below];
                ctx.decoder(self)
                    .decode(level, c, used, tail[below], before, at, hint)
            };
            tail[below] = m;
            if m == END {
                plan.push_back((END, 0.0, ctx.by, None));
                return true;
            }
            if level == 1 {
                plan.push_back((m, self.dwell[m as usize].max(1.0), ctx.by, None));
                continue;
            }
            expected[below].push_back(m);
            let sub_from = if resumed { ctx.done[below] } else { 0 };
            let m = m as usize;
            if self.expand(
                ctx, below, m, sub_from, resumed, slot_pos, plan, expected, tail,
            ) {
                return true;
            }
        }
        false
    }
}

/// The reproduction's short-term memory, as in training: per level l >= 1 the entries of
/// level l-1 completed in its current chunk, the chunk's context and index; per level its
/// last completed entry; and the entries the current plan expects each level to complete.
#[derive(Debug, Clone)]
pub(super) struct Lists {
    pub(super) chunk: Vec<Vec<Item>>,
    pub(super) prev: Vec<Vec<f64>>,
    pub(super) index: Vec<usize>,
    /// Last completed entry per level (`u32::MAX`: the begin).
    pub(super) tail: Vec<u32>,
    pub(super) expected: Vec<VecDeque<u32>>,
}

impl Lists {
    pub(super) fn new(height: usize, start: &[f64]) -> Self {
        Lists {
            chunk: vec![Vec::new(); height],
            prev: vec![start.to_vec(); height],
            index: vec![0; height],
            tail: vec![u32::MAX; height],
            expected: vec![VecDeque::new(); height],
        }
    }

    /// The input of level `l`'s current chunk (completed slots known); the known count.
    pub(super) fn input(
        &self,
        lay: Layout,
        l: usize,
        mean_events: f64,
        x: &mut [f64],
        mask: &mut [bool],
    ) -> usize {
        let refs: Vec<&[f64]> = self.chunk[l].iter().map(|i| i.content.as_slice()).collect();
        let phase = (self.index[l] * lay.k.pow(l as u32)) as f64 / mean_events;
        chunk_input(
            lay,
            &self.prev[l],
            self.index[l] == 0,
            phase,
            &refs,
            x,
            mask,
        )
    }

    /// Push an executed bottom event up the lists exactly as in training: every chunk it
    /// completes is matched by its level and pushed one level up. True when a completed
    /// chunk's node is not the one the plan expected there (a surprise).
    pub(super) fn push_event(
        &mut self,
        model: &EventsHsom,
        lay: Layout,
        code: DurationCode,
        mean_events: f64,
        node: usize,
        dur: f64,
    ) -> bool {
        let mut x = vec![0.0; lay.dim()];
        let mut mask = vec![true; lay.dim()];
        self.tail[0] = node as u32;
        let mut item = Item {
            node: node as u32,
            content: event_content(&model.maps[0], node, dur, code),
        };
        let mut surprise = false;
        for l in 1..self.chunk.len() {
            self.chunk[l].push(item);
            if self.chunk[l].len() < lay.k {
                break;
            }
            self.input(lay, l, mean_events, &mut x, &mut mask);
            let (b, _) = model.maps[l].bmu(&x);
            self.prev[l] = b_part(lay, &self.chunk[l][lay.k - 1].content).to_vec();
            self.chunk[l].clear();
            self.index[l] += 1;
            self.tail[l] = b as u32;
            if let Some(e) = self.expected[l].pop_front() {
                surprise |= e != b as u32;
            }
            item = Item {
                node: b as u32,
                content: summary(lay, &model.maps[l].weights(b), code),
            };
        }
        surprise
    }
}

impl Planner<'_> {
    pub(super) fn decoder<'m>(&self, model: &'m EventsHsom) -> Decoder<'m> {
        Decoder {
            model,
            lay: self.lay,
            code: self.code,
        }
    }
}

/// What a plan is made from.
struct Planner<'a> {
    pub(super) lay: Layout,
    pub(super) code: DurationCode,
    /// Per level, the partial match of its current chunk.
    pub(super) matched: &'a [usize],
    /// Per level, the entries its current chunk has completed.
    pub(super) done: &'a [usize],
    /// Per level, its used nodes.
    pub(super) used: &'a [Vec<usize>],
    /// The level the plan comes from.
    pub(super) by: usize,
    /// Bottom events executed before the plan.
    pub(super) executed: usize,
    /// Where the reproduction is: the last executed event's node's posture (the start
    /// posture before any).
    pub(super) here: &'a [f64],
    /// Per level, the index of its current chunk.
    pub(super) index: &'a [usize],
}
