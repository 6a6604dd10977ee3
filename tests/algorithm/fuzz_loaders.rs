//! Fuzzing on stable Rust (proptest) of every loader of untrusted files but the MJCF one
//! (tests/fuzz_mjcf.rs): the XML configuration parser, the demonstration CSV reader, both
//! CoSCo-HSOM model readers (binary and plain text) and the GMM/GMR model reader. Each gets
//! arbitrary bytes and structured mutations of a valid file (bytes flipped, inserted, removed,
//! the file cut, numbers replaced by extreme ones). None may panic (a panic fails the case),
//! and none may make a single allocation larger than the input allows (a counting allocator
//! records the largest allocation while the loader runs). A hang would stop the run.
//!
//! `PROPTEST_CASES` sets the number of cases per target (CI: the default below); the long
//! campaign and its results: docs/RELIABILITY.md.

use crate::hsom_common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::path::Path;

use proptest::prelude::*;

use cosco_hsom::config::parse_config;
use cosco_hsom::demos::parse_csv;
use cosco_hsom::hsom::Hsom;

/// Tracks, per thread, the largest single allocation since the last reset.
struct Counting;

thread_local! {
    static LARGEST: Cell<usize> = const { Cell::new(0) };
}

// Safety: every call is forwarded to the system allocator unchanged; the thread-local cell is
// const-initialised and never allocates.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LARGEST.with(|c| c.set(c.get().max(layout.size())));
        // Safety: the caller's contract is System's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // Safety: as above.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        LARGEST.with(|c| c.set(c.get().max(new_size)));
        // Safety: as above.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOC: Counting = Counting;

/// Run `f` and return the largest single allocation it made.
fn largest_allocation<T>(f: impl FnOnce() -> T) -> (T, usize) {
    LARGEST.with(|c| c.set(0));
    let out = f();
    (out, LARGEST.with(|c| c.get()))
}

/// What a loader may allocate at most at once for `n` bytes of input: a bounded multiple of
/// the input (parsed numbers are 8 bytes per character at worst), plus a fixed allowance.
fn allowance(n: usize) -> usize {
    64 * n + (4 << 20)
}

const CONFIG: &str = include_str!("../../configs/nao-gestures.xml");
const TABLE1: &str = include_str!("../../configs/table1.xml");

fn small_model() -> Hsom {
    small_model_of(cosco_hsom::config::Algorithm::Paper)
}

/// The same with the events extension: it stores its postures (`knots`).
fn small_events_model() -> Hsom {
    let m = small_model_of(cosco_hsom::config::Algorithm::Events);
    assert!(m.to_text().contains("\"knots\":["));
    m
}

fn small_model_of(algorithm: cosco_hsom::config::Algorithm) -> Hsom {
    use cosco_hsom::config::{Algorithm, AlgorithmParams, EventsParams};
    let mut p = cosco_hsom::config::HsomParams::table1();
    if algorithm == Algorithm::Events {
        p.algorithm = AlgorithmParams::Events(EventsParams {
            change_ratio: 1.0,
            action_horizon: 1,
        });
    }
    p.state_length = 2;
    p.action_length = 2;
    p.height = 3;
    p.levels.truncate(3);
    for l in &mut p.levels {
        l.rows = l.rows.min(4);
        l.cols = l.cols.min(4);
    }
    p.training_steps = 300;
    let cfg = p.check("fuzz").unwrap();
    let series: Vec<Vec<Vec<f64>>> = (0..2)
        .map(|k| {
            (0..20 + k)
                .map(|i| {
                    let t = i as f64 / 10.0;
                    vec![t.sin(), t.cos()]
                })
                .collect()
        })
        .collect();
    cfg.fit(&cosco_hsom::demos::Demonstration::from_series(&series))
        .unwrap()
}

fn csv_file() -> Vec<u8> {
    let mut s = String::from("time,a,b\n");
    for i in 0..30 {
        s.push_str(&format!(
            "{},{},{}\n",
            i as f64 / 40.0,
            (i as f64).sin(),
            i as f64
        ));
    }
    s.into_bytes()
}

/// A structured mutation of `base`: each op is (kind, position, byte).
fn mutate(base: &[u8], ops: &[(u8, usize, u8)]) -> Vec<u8> {
    let mut v = base.to_vec();
    for &(kind, pos, byte) in ops {
        let at = if v.is_empty() { 0 } else { pos % v.len() };
        match kind % 6 {
            0 if !v.is_empty() => v[at] ^= byte | 1,
            1 => v.insert(at, byte),
            2 if !v.is_empty() => {
                v.remove(at);
            }
            3 => v.truncate(at),
            4 => {
                // a digit run replaced by an extreme number
                let extreme: &[&[u8]] =
                    &[b"1e308", b"-1e308", b"NaN", b"inf", b"99999999999", b"-0"];
                let e = extreme[byte as usize % extreme.len()];
                let end = (at + 3).min(v.len());
                v.splice(at..end, e.iter().copied());
            }
            _ => {
                // a line duplicated (repeated sections, counts off by one)
                let start = v[..at]
                    .iter()
                    .rposition(|&b| b == b'\n')
                    .map_or(0, |i| i + 1);
                let end = v[at..]
                    .iter()
                    .position(|&b| b == b'\n')
                    .map_or(v.len(), |i| at + i + 1);
                let line = v[start..end].to_vec();
                v.splice(end..end, line);
            }
        }
    }
    v
}

fn ops() -> impl Strategy<Value = Vec<(u8, usize, u8)>> {
    prop::collection::vec((any::<u8>(), any::<usize>(), any::<u8>()), 1..8)
}

fn input(base: Vec<u8>) -> impl Strategy<Value = Vec<u8>> {
    prop_oneof![
        prop::collection::vec(any::<u8>(), 0..512),
        ops().prop_map(move |o| mutate(&base, &o)),
    ]
}

proptest! {
    #![proptest_config(hsom_common::fuzz_config(64))]

    #[test]
    fn config_parser(bytes in prop_oneof![input(CONFIG.as_bytes().to_vec()), input(TABLE1.as_bytes().to_vec())]) {
        let text = String::from_utf8_lossy(&bytes);
        let (_, big) = largest_allocation(|| parse_config(&text, "fuzz.xml"));
        prop_assert!(big <= allowance(bytes.len()), "{big} bytes allocated for {} of input", bytes.len());
    }

    #[test]
    fn csv_reader(bytes in input(csv_file())) {
        let (_, big) = largest_allocation(|| parse_csv("fuzz.csv", &bytes));
        prop_assert!(big <= allowance(bytes.len()), "{big} bytes allocated for {} of input", bytes.len());
    }

    #[test]
    fn model_binary_reader(bytes in prop_oneof![input(small_model().to_bytes()), input(small_events_model().to_bytes())]) {
        let (_, big) = largest_allocation(|| Hsom::from_bytes(&bytes, Path::new("fuzz.bin")));
        prop_assert!(big <= allowance(bytes.len()), "{big} bytes allocated for {} of input", bytes.len());
    }

    #[test]
    fn model_text_reader(bytes in prop_oneof![input(small_model().to_text().into_bytes()), input(small_events_model().to_text().into_bytes())], fix_checksum in any::<bool>()) {
        let text = String::from_utf8_lossy(&bytes).into_owned();
        // half the cases with a valid checksum, so that the mutation reaches the values
        let text = if fix_checksum { hsom_common::with_checksum(&text) } else { text };
        let (_, big) = largest_allocation(|| Hsom::from_text(&text, Path::new("fuzz.txt")));
        prop_assert!(big <= allowance(text.len()), "{big} bytes allocated for {} of input", text.len());
    }

    #[test]
    fn gmr_model_reader(bytes in input(gmr_file())) {
        let text = String::from_utf8_lossy(&bytes);
        let (_, big) = largest_allocation(|| cosco_hsom::gmr::model_from_str("fuzz.txt", &text));
        prop_assert!(big <= allowance(bytes.len()), "{big} bytes allocated for {} of input", bytes.len());
    }
}

fn gmr_file() -> Vec<u8> {
    use cosco_hsom::gmr::{model_to_string, ComponentChoice, GmrModel, GmrParams};
    let pts: Vec<Vec<f64>> = (0..60)
        .map(|i| {
            let t = 3.0 * i as f64 / 59.0;
            vec![t, (t * 2.0).sin(), (t * 3.0).cos() + 0.01 * (i % 7) as f64]
        })
        .collect();
    let (gmm, _) = GmrParams::new()
        .components(ComponentChoice::Fixed(2))
        .check()
        .unwrap()
        .fit_gmm(&pts)
        .unwrap();
    let model = GmrModel::new(vec!["a".into(), "b".into()], 3.0, gmm).unwrap();
    model_to_string(&model).unwrap().into_bytes()
}

/// The counter sees allocations (the negative control of the allocation checks above).
#[test]
fn the_allocation_counter_sees_a_large_allocation() {
    let (v, big) = largest_allocation(|| vec![1u8; 8 << 20]);
    assert_eq!(v.len(), 8 << 20);
    assert!(big >= 8 << 20 && big > allowance(16), "{big}");
}
