//! The SOM kernel against this CPU's limits and against MiniSom (issue 13).
//!
//! ```sh
//! benches/minisom.sh                          # sets up MiniSom in a venv, then runs this
//! cargo bench --bench som_kernel              # without MiniSom
//! cargo bench --bench som_kernel -- --plot docs/figures/som-step-vs-size.png
//! ```
//!
//! Prints, in one run: a roofline estimate for the best-matching-unit scan (flops and bytes per
//! node, with this CPU's L1 read bandwidth and add throughput measured here), the scan and the
//! training step of a 16x16 map on 12-D input (blocked kernels, and the node-major loops they
//! replaced, kept here as the reference), the step against map size (8x8 to 64x64), Table I
//! trained for 5,000 steps on 3 demonstrations, and, when `MINISOM_PYTHON` names a Python
//! with MiniSom, MiniSom's training step on the same map and data and the ratio.
//! Timings are medians of repeated batches (`Instant`), in ns per operation.

mod common;

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;

use common::gestures;
use cosco_hsom::som::reference::NodeMajorMap;
use cosco_hsom::som::{Neighbourhood, Reach, SelfOrganizingMap, Topology};
use cosco_hsom::stats::upper_median;
use cosco_hsom::table::Table;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Median over `batches` of the mean time per call of `f` (ns), `per_batch` calls a batch.
fn time_ns(batches: usize, per_batch: usize, mut f: impl FnMut()) -> f64 {
    for _ in 0..per_batch {
        f();
    }
    let mut v: Vec<f64> = (0..batches)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..per_batch {
                f();
            }
            t.elapsed().as_nanos() as f64 / per_batch as f64
        })
        .collect();
    upper_median(&mut v).unwrap_or(f64::NAN)
}

/// Roofline probes, run under `pulp`'s dispatch like the kernels: L1 read bandwidth
/// (bytes/ns, 8-lane sums over 24 KiB) and the scan's arithmetic alone (weights/ns: one
/// subtraction, multiplication and addition each, from registers).
fn probes() -> (f64, f64, &'static str) {
    struct Sum<'a>(&'a [[f64; 8]]);
    impl pulp::WithSimd for Sum<'_> {
        type Output = f64;
        #[inline(always)]
        fn with_simd<S: pulp::Simd>(self, _: S) -> f64 {
            let mut acc = [[0.0f64; 8]; 4];
            for c in self.0.chunks_exact(4) {
                for (a, v) in acc.iter_mut().zip(c) {
                    for l in 0..8 {
                        a[l] += v[l];
                    }
                }
            }
            acc.iter().flatten().sum()
        }
    }
    /// The scan's operations per weight, t = w - x, acc += t t, on 8 independent vector
    /// accumulators held in registers (no memory traffic): the compute roof.
    struct Mix(f64, usize);
    impl pulp::WithSimd for Mix {
        type Output = f64;
        #[inline(always)]
        fn with_simd<S: pulp::Simd>(self, simd: S) -> f64 {
            // x moves every iteration so that nothing can be hoisted out of the loop (one
            // extra addition per 8 x 8 weights)
            let mut x = simd.splat_f64s(self.0);
            let eps = simd.splat_f64s(self.0 * 1e-3);
            let mut w = [simd.splat_f64s(0.0); 8];
            for (j, v) in w.iter_mut().enumerate() {
                *v = simd.splat_f64s(j as f64 * 1e-3);
            }
            let mut acc = [simd.splat_f64s(0.0); 8];
            for _ in 0..self.1 {
                x = simd.add_f64s(x, eps);
                for (a, &v) in acc.iter_mut().zip(&w) {
                    let t = simd.sub_f64s(v, x);
                    *a = simd.add_f64s(*a, simd.mul_f64s(t, t));
                }
            }
            let mut s = 0.0;
            for a in acc {
                s += simd.reduce_sum_f64s(a);
            }
            s
        }
    }
    let arch = pulp::Arch::new();
    let name = match arch {
        pulp::Arch::V4(_) => "AVX-512 (pulp x86-v4)",
        pulp::Arch::V3(_) => "AVX2+FMA (pulp x86-v3)",
        _ => "x86-64 baseline (SSE2)",
    };
    // 24 KiB: the 16x16x12 map's weights, resident in L1
    let buf = vec![[1.0f64; 8]; 384];
    let t = time_ns(31, 2000, || {
        black_box(arch.dispatch(Sum(black_box(&buf))));
    });
    let bw = (384 * 64) as f64 / t;
    let iters = 10_000;
    let lanes = match arch {
        pulp::Arch::V4(_) => 8,
        pulp::Arch::V3(_) => 4,
        _ => 1,
    };
    let t = time_ns(31, 20, || {
        black_box(arch.dispatch(Mix(black_box(1e-9), iters)));
    });
    let weights_per_ns = (iters * 8 * lanes) as f64 / t;
    (bw, weights_per_ns, name)
}

/// A side x side map on 12-D input and 64 inputs, from seed 1 (the map of benches/hsom.rs).
fn map_and_data(side: usize) -> (SelfOrganizingMap, Vec<Vec<f64>>) {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let map = SelfOrganizingMap::new_random(
        side,
        side,
        12,
        Topology::Orthogonal,
        &[0.0; 12],
        &[1.0; 12],
        &mut rng,
    );
    let xs = (0..64)
        .map(|_| (0..12).map(|_| rng.gen()).collect())
        .collect();
    (map, xs)
}

/// Scan and step (cut, exact) of a side x side map, ns per call.
fn scan_and_step(side: usize, radius: f64) -> (f64, f64, f64) {
    let (mut map, xs) = map_and_data(side);
    let mut i = 0;
    let scan = time_ns(31, 20_000 / side, || {
        i = (i + 1) % xs.len();
        black_box(map.bmu(black_box(&xs[i])));
    });
    let mut step = |reach: Reach, map: &mut SelfOrganizingMap| {
        time_ns(31, 20_000 / side, || {
            i = (i + 1) % xs.len();
            let (b, _) = map.bmu(&xs[i]);
            map.update_reach(&xs[i], None, b, 0.1, radius, Neighbourhood::Gaussian, reach);
        })
    };
    let cut = step(Reach::Cut { h_min: 1e-4 }, &mut map.clone());
    let exact = step(Reach::Exact, &mut map);
    (scan, cut, exact)
}

fn minisom(python: &Path, dir: &Path, steps_per_batch: usize) -> anyhow::Result<(f64, f64)> {
    let (map, xs) = map_and_data(16);
    let csv = |rows: &mut dyn Iterator<Item = Vec<f64>>| -> String {
        rows.map(|r| {
            r.iter()
                .map(|v| format!("{v:e}"))
                .collect::<Vec<_>>()
                .join(",")
        })
        .collect::<Vec<_>>()
        .join("\n")
    };
    std::fs::create_dir_all(dir)?;
    let w = map.all_weights();
    std::fs::write(
        dir.join("weights.csv"),
        csv(&mut w.chunks(12).map(|c| c.to_vec())),
    )?;
    std::fs::write(dir.join("inputs.csv"), csv(&mut xs.iter().cloned()))?;
    // MiniSom has no cut: the reference for the check is the exact update
    let mut exact = map.clone();
    for x in xs.iter().cycle().take(200) {
        let (b, _) = exact.bmu(x);
        exact.update_reach(x, None, b, 0.1, 2.0, Neighbourhood::Gaussian, Reach::Exact);
    }
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/minisom_step.py");
    let out = std::process::Command::new(python)
        .arg(script)
        .arg(dir)
        .arg(steps_per_batch.to_string())
        .output()?;
    anyhow::ensure!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout)?;
    let mut us = f64::NAN;
    for line in text.lines() {
        if let Some(v) = line.strip_prefix("step_us ") {
            us = v.trim().parse()?;
        }
    }
    let theirs: Vec<f64> = std::fs::read_to_string(dir.join("after200.csv"))?
        .split([',', '\n'])
        .filter(|s| !s.trim().is_empty())
        .map(|s| s.trim().parse())
        .collect::<Result<_, _>>()?;
    let ours = exact.all_weights();
    anyhow::ensure!(
        theirs.len() == ours.len(),
        "MiniSom weights of another size"
    );
    let diff = ours
        .iter()
        .zip(&theirs)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    Ok((us * 1000.0, diff))
}

fn plot(path: &Path, rows: &[(usize, f64, f64, f64)]) -> anyhow::Result<()> {
    use cosco_hsom::plot::{panels_png, Panel, Series, PALETTE};
    let line =
        |label: &str, color: usize, per_node: bool, f: fn(&(usize, f64, f64, f64)) -> f64| {
            let points = rows
                .iter()
                .map(|r| {
                    let n = (r.0 * r.0) as f64;
                    (n, if per_node { f(r) / n } else { f(r) / 1000.0 })
                })
                .collect();
            Series::new(label, PALETTE[color], points)
        };
    let mut per_call = Panel::new(
        "time per call (radius 2)",
        "nodes (8x8, 16x16, 32x32, 64x64)",
        "us",
    );
    let mut per_node = Panel::new(
        "time per node",
        "nodes (8x8, 16x16, 32x32, 64x64)",
        "ns / node",
    );
    for (panel, pn) in [(&mut per_call, false), (&mut per_node, true)] {
        panel.series = vec![
            line("BMU scan", 0, pn, |r| r.1),
            line("training step, cut h < 1e-4 (default)", 3, pn, |r| r.2),
            line("training step, exact (every node)", 2, pn, |r| r.3),
        ];
    }
    panels_png(
        path,
        "SOM kernel: 12-D input, AVX-512 through pulp (benches/som_kernel.rs)",
        &[per_call, per_node],
        2,
        (560, 420),
    )?;
    Ok(())
}

fn main() -> anyhow::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let plot_path = args
        .iter()
        .position(|a| a == "--plot")
        .and_then(|i| args.get(i + 1))
        .map(PathBuf::from);

    let (bw, per_ns, isa) = probes();
    // per node of the 12-D scan: 12 weights of 8 bytes read; 12 subtractions, 12
    // multiplications, 12 additions (no fused multiply-add: the plain summation order is kept
    // bit for bit)
    let (bytes, flops) = (96.0, 36.0);
    let roof = (bytes / bw).max(12.0 / per_ns);
    println!("instruction set in use: {isa}");
    println!(
        "L1 read bandwidth (measured): {bw:.0} bytes/ns; the scan's arithmetic alone (measured): \
         {per_ns:.1} weights/ns = {:.1} Gflop/s",
        per_ns * 3.0
    );
    println!(
        "roofline per node (12-D): {bytes} bytes, {flops} flops: max(memory {:.3}, compute {:.3}) \
         = {roof:.3} ns/node, {:.0} ns for 256 nodes",
        bytes / bw,
        12.0 / per_ns,
        roof * 256.0
    );

    let (map, xs) = map_and_data(16);
    let mut old = NodeMajorMap::of(&map);
    let mut i = 0;
    let old_scan = time_ns(31, 2000, || {
        i = (i + 1) % xs.len();
        black_box(old.bmu(black_box(&xs[i])));
    });
    let old_step = time_ns(31, 2000, || {
        i = (i + 1) % xs.len();
        let (b, _) = old.bmu(&xs[i]);
        old.update(&xs[i], None, b, 0.1, 2.0, Neighbourhood::Gaussian, 1e-4);
    });
    let (scan, cut, exact) = scan_and_step(16, 2.0);
    let three_sigma = {
        let (mut map, xs) = map_and_data(16);
        let mut i = 0;
        let reach = Reach::Cut {
            h_min: (-4.5f64).exp(),
        };
        time_ns(31, 2000, || {
            i = (i + 1) % xs.len();
            let (b, _) = map.bmu(&xs[i]);
            map.update_reach(&xs[i], None, b, 0.1, 2.0, Neighbourhood::Gaussian, reach);
        })
    };
    println!("\n16x16 map, 12-D input, radius 2 (ns per call):");
    let mut table = Table::new([
        "kernel",
        "BMU scan",
        "training step",
        "step / scan",
        "scan / roofline",
    ]);
    let roofline = |scan: f64| format!("{:.1}", scan / (roof * 256.0));
    for (name, s, step, per_roof) in [
        (
            "node-major loops (before)",
            old_scan,
            old_step,
            roofline(old_scan),
        ),
        ("blocked, cut h < 1e-4 (default)", scan, cut, roofline(scan)),
        (
            "blocked, cut at 3 radii (h < exp(-4.5) = 0.011)",
            scan,
            three_sigma,
            String::new(),
        ),
        ("blocked, exact (every node)", scan, exact, String::new()),
    ] {
        table.row([
            name.to_string(),
            format!("{s:.0}"),
            format!("{step:.0}"),
            format!("{:.2}", step / s),
            per_roof,
        ]);
    }
    print!("{table}");

    println!("\n16x16 step against the learning radius (cut h < 1e-4; ns per call):");
    print!(
        "{}",
        Table::new([
            "radius",
            "nodes within the cut (4.29 r)",
            "step",
            "step / scan"
        ])
    );
    for r in [0.5, 1.0, 2.0, 4.0] {
        let (s, c, _) = scan_and_step(16, r);
        let reach = (r * (2.0 * 1e4f64.ln()).sqrt()).min(16.0);
        print!(
            "{}",
            Table::line([
                r.to_string(),
                format!(
                    "about {:.0}",
                    (std::f64::consts::PI * reach * reach).min(256.0)
                ),
                format!("{c:.0}"),
                format!("{:.2}", c / s),
            ])
        );
    }

    println!("\nstep against map size (radius 2; ns per call):");
    print!(
        "{}",
        Table::new([
            "map",
            "BMU scan",
            "ns/node",
            "step, cut",
            "step / scan",
            "step, exact",
        ])
    );
    let mut rows = Vec::new();
    for side in [8, 16, 32, 64] {
        let (s, c, e) = scan_and_step(side, 2.0);
        print!(
            "{}",
            Table::line([
                format!("{side}x{side}"),
                format!("{s:.0}"),
                format!("{:.2}", s / (side * side) as f64),
                format!("{c:.0}"),
                format!("{:.2}", c / s),
                format!("{e:.0}"),
            ])
        );
        rows.push((side, s, c, e));
    }
    if let Some(p) = &plot_path {
        plot(p, &rows)?;
        println!("plot: {}", p.display());
    }

    let demos = gestures(3, 300);
    let cfg = cosco_hsom::config::load_config(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/table1.xml"),
    )?;
    let fit = time_ns(11, 3, || {
        black_box(cfg.fit(&demos).unwrap());
    });
    println!(
        "\nTable I (configs/table1.xml: 6 levels, 16x16 bottom), 5,000 steps on 3 demonstrations x 300 samples: {:.2} ms",
        fit / 1e6
    );

    if let Some(py) = std::env::var_os("MINISOM_PYTHON") {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/minisom");
        let (theirs, diff) = minisom(Path::new(&py), &dir, 2000)?;
        println!("\nMiniSom, same 16x16 map and 64 inputs, winner + update (sigma 2, learning rate 0.1):");
        let mut table = Table::new(["", "training step (ns)"]);
        table.row(["MiniSom".to_string(), format!("{theirs:.0}")]);
        table.row(["cosco-hsom, cut (default)".to_string(), format!("{cut:.0}")]);
        table.row(["cosco-hsom, exact".to_string(), format!("{exact:.0}")]);
        print!("{table}");
        println!(
            "ratio MiniSom / cosco-hsom: {:.0}x (cut), {:.0}x (exact)",
            theirs / cut,
            theirs / exact
        );
        println!("largest weight difference to MiniSom after the same 200 exact steps: {diff:.1e}");
    }
    Ok(())
}
