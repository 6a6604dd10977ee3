//! Follower tables: per entry of a level, its most frequent followers (the lookup baseline
//! every level must beat).

use std::collections::BTreeMap;

/// A node index that stands for the end of the gesture in item sequences and successors.
pub(crate) const END: u32 = u32::MAX - 1;

/// Followers kept per entry (fixed, so the model's size does not depend on the data).
pub(crate) const FOLLOWERS: usize = 4;

/// The row of the follower table for the entry `prev` (`u32::MAX` or [`END`]: the begin row,
/// `nodes`).
pub(super) fn follower_row(nodes: usize, prev: u32) -> usize {
    if prev == u32::MAX || prev == END {
        nodes
    } else {
        prev as usize
    }
}

/// The lookup table's prediction: the most frequent follower of `prev` in a follower table of
/// a level with `nodes` nodes (`u32::MAX`: none recorded).
pub(crate) fn most_frequent(table: &[u32], nodes: usize, prev: u32) -> u32 {
    table[follower_row(nodes, prev) * FOLLOWERS]
}

/// The fraction of the entries of `seqs` (each sequence starting after the begin) that the
/// lookup table of "next entry given the last one" of `table` predicts.
pub(crate) fn lookup_accuracy(table: &[u32], nodes: usize, seqs: &[Vec<u32>]) -> f64 {
    let (n, ok) = lookup_counts(table, nodes, seqs);
    fraction(ok, n)
}

/// `right / asked` (0 when nothing was asked): a prediction accuracy.
pub(crate) fn fraction(right: u32, asked: u32) -> f64 {
    if asked > 0 {
        right as f64 / asked as f64
    } else {
        0.0
    }
}

/// The entries of `seqs` the lookup table of `table` was asked for and how many it predicted
/// ([`lookup_accuracy`]).
pub(super) fn lookup_counts(table: &[u32], nodes: usize, seqs: &[Vec<u32>]) -> (u32, u32) {
    let (mut n, mut ok) = (0u32, 0u32);
    for sq in seqs {
        let mut prev = u32::MAX;
        for &x in sq {
            n += 1;
            ok += u32::from(most_frequent(table, nodes, prev) == x);
            prev = x;
        }
    }
    (n, ok)
}

/// at which that follower came after its row's entry in `seqs` (entries before it / `mean`,
/// the mean number of entries per sequence: the phase of a chunk's context, in its units);
/// 0 where the table holds none.
pub(crate) fn follower_positions(
    nodes: usize,
    seqs: &[Vec<u32>],
    table: &[u32],
    mean: f64,
) -> Vec<f64> {
    let mut sums: BTreeMap<(u32, u32), (f64, f64)> = BTreeMap::new();
    for sq in seqs {
        let mut prev = nodes as u32;
        for (i, &x) in sq.iter().enumerate() {
            let e = sums.entry((prev, x)).or_insert((0.0, 0.0));
            e.0 += i as f64 / mean.max(1.0);
            e.1 += 1.0;
            if x == END {
                break;
            }
            prev = x;
        }
    }
    table
        .iter()
        .enumerate()
        .map(|(k, &f)| {
            sums.get(&((k / FOLLOWERS) as u32, f))
                .map_or(0.0, |&(sum, count)| sum / count)
        })
        .collect()
}

/// The table of up to [`FOLLOWERS`] most frequent followers of every entry of a level (row
/// `nodes` is the begin of a demonstration; ties to the smaller index), from its entry
/// sequences. Its first column is the lookup table every level must beat.
pub(crate) fn followers_table(nodes: usize, seqs: &[Vec<u32>]) -> Vec<u32> {
    let mut counts: BTreeMap<(u32, u32), u32> = BTreeMap::new();
    for sq in seqs {
        let mut prev = nodes as u32;
        for &x in sq {
            *counts.entry((prev, x)).or_insert(0) += 1;
            if x == END {
                break;
            }
            prev = x;
        }
    }
    let mut rows: Vec<Vec<(u32, u32)>> = vec![Vec::new(); nodes + 1];
    for (&(a, b), &c) in &counts {
        rows[a as usize].push((c, b));
    }
    let mut t = vec![u32::MAX; (nodes + 1) * FOLLOWERS];
    for (i, r) in rows.iter_mut().enumerate() {
        r.sort_by(|x, y| y.0.cmp(&x.0).then(x.1.cmp(&y.1)));
        for (j, &(_, b)) in r.iter().take(FOLLOWERS).enumerate() {
            t[i * FOLLOWERS + j] = b;
        }
    }
    t
}
