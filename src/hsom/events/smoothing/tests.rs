use super::{JerkFactor, BEFORE};

/// The solve of one column on its own, its recurrences not interleaved: what
/// [`JerkFactor::solve_columns`] must give bit for bit.
fn alone(f: &JerkFactor, c: &[f64], slope: f64) -> Vec<f64> {
    let (a, l) = (&f.a, &f.l);
    // the samples before the curve and its first one, its last one and the samples at
    // rest after it: known values
    let known = BEFORE + 1;
    let last = c[c.len() - 1];
    let full: Vec<f64> = (0..BEFORE)
        .map(|k| c[0] - (BEFORE - k) as f64 * slope)
        .chain(c.iter().copied())
        .chain(std::iter::repeat(last).take(BEFORE))
        .collect();
    let n = full.len();
    // the unknowns are x_known..n - known; their right-hand side without the known
    // values' terms (the normal matrix is symmetric: entry (i, i + k) is a[i + k][k])
    let m = n - 2 * known;
    let mut b: Vec<f64> = full[known..n - known].to_vec();
    for (u, bu) in b.iter_mut().enumerate() {
        let i = u + known;
        for k in 1..=3usize {
            if i - k < known {
                *bu -= a[i][k] * full[i - k];
            }
            if i + k >= n - known {
                *bu -= a[i + k][k] * full[i + k];
            }
        }
    }
    // L y = b, then Lᵀ x = y
    let mut y = vec![0.0; m];
    for i in 0..m {
        let mut sum = b[i];
        for k in 1..=3.min(i) {
            sum -= l[i][k] * y[i - k];
        }
        y[i] = sum / l[i][0];
    }
    let mut x = vec![0.0; m];
    for i in (0..m).rev() {
        let mut sum = y[i];
        for k in 1..=3usize {
            if i + k < m {
                sum -= l[i + k][k] * x[i + k];
            }
        }
        x[i] = sum / l[i][0];
    }
    std::iter::once(c[0])
        .chain(x)
        .chain(std::iter::once(last))
        .collect()
}

#[test]
fn columns_solved_together_are_each_solved_alone_bit_for_bit() {
    let len = 157;
    let cols: Vec<Vec<f64>> = (0..6)
        .map(|d| {
            (0..len)
                .map(|i| {
                    ((i * (d + 3)) as f64 * 0.037).sin() * (1.0 + d as f64) + 0.01 * (i % 7) as f64
                })
                .collect()
        })
        .collect();
    let slopes = [0.0, 0.02, -0.013, 0.5, 0.0, -1e-3];
    for lambda in [1.0, 30.0, 1000.0] {
        let f = JerkFactor::new(len, lambda);
        let together = f.solve_columns(&cols, &slopes);
        assert_eq!(together.len(), 6);
        for (d, t) in together.iter().enumerate() {
            let alone = alone(&f, &cols[d], slopes[d]);
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(t), bits(&alone), "column {d}, weight {lambda}");
        }
        // a column without a slope is left out
        assert_eq!(f.solve_columns(&cols, &slopes[..2]).len(), 2);
    }
}
