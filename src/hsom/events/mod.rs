//! The events extension (`algorithm = events`, docs/ALGORITHM.md, section
//! 3): activity lists of events (a bottom node and how long it was held), levels whose
//! nodes tile `memory` consecutive entries of the level below, lists encoded by content, a
//! learned begin and end, and a reproduction that climbs while the levels' matches lie within
//! what they saw in training, expands the highest confident level's prediction down to timed
//! bottom events, and re-plans when what was executed is not what the plan expected.
//!
//! Layout of a level-l input (l >= 1), all in the bottom level's normalised units:
//! `[context | slot 0 | ... | slot memory-1]`, context = `[previous posture (S), begin, phase]`,
//! slot = `[a (S), b (S), duration, end]`. At level 1 a slot is a bottom event: a and b are
//! its node's state and action halves, duration its encoded length in samples. Higher up a
//! slot summarises a node of the level below: a = its first posture, b = its last, duration
//! the encoded sum of its slots' durations, end the largest of their end flags.
//!
//! Where to look:
//! - [`encode`]: the bottom level's events and the slots, chunks and summaries every level
//!   above encodes them as;
//! - [`levels`]: training the levels above the bottom, level by level;
//! - [`traces`]: the training chunks a node keeps so that a traced plan replays them, and
//!   the decoder of a node's content;
//! - [`plan`]: a reproduction: climbing the levels, the highest confident level's plan
//!   expanded to timed bottom events, re-planning on a surprise;
//! - [`consensus`] and [`start`]: where each bottom event is placed (the demonstrations'
//!   consensus, weighed by their starts);
//! - [`curve`]: the executed curve through the placed, timed events, and [`smoothing`]: it
//!   made as smooth as the demonstrations;
//! - [`follow`]: following the nearest demonstration, re-encoding one, continuing a prefix.

mod consensus;
mod curve;
mod encode;
mod follow;
mod levels;
mod plan;
mod smoothing;
mod start;
mod traces;

#[cfg(test)]
mod tests;

pub(super) use encode::{
    a_part, b_part, bottom_events, chunk_input, chunks, summary, DurationCode, Item,
};
pub(super) use levels::used;
pub(super) use traces::{trace_places, trace_width, trace_words, TRACED_CHUNKS};

pub(crate) use super::followers::END;
pub(crate) use consensus::smooth_warp;
pub(crate) use curve::as_smooth_as;
pub(crate) use start::start_fade;
