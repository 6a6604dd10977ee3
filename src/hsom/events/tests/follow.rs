//! Unit tests of the events extension: continuing a prefix (with the levels or the nearest
//! sequence) and resuming a reproduction.

use super::*;

/// Continued after a prefix, the nearest sequence goes on along the demonstration the
/// prefix ran along, from where it ended: half of "twice" (its first excursion) is
/// completed with the second, the prefix of "once" up to its far hold with the way back
/// only.
#[test]
fn the_nearest_sequence_continues_the_demonstration_the_prefix_ran_along() {
    let (demos, m) = once_and_twice();
    for d in &demos {
        let prefix = &d.rows[..d.rows.len() / 2];
        let r = m.follow_nearest_from(&demos, prefix).unwrap();
        assert_eq!(&r.postures[0], prefix.last().unwrap());
        let whole: Vec<Vec<f64>> = prefix
            .iter()
            .chain(r.postures.iter().skip(1))
            .cloned()
            .collect();
        assert_eq!(excursions(&whole), excursions(&d.rows), "{}", d.source);
    }
    let e = m
        .follow_nearest_from(&demos, &demos[0].rows[..1])
        .unwrap_err();
    assert!(e.to_string().contains("prefix"), "{e}");
}

/// Resuming its own reproduction: read back at any point of it (the reading is the
/// reproduction's first samples), the hierarchy goes on as planned, so reading and
/// continuation are the whole reproduction again (within 0.02, as long to a sample);
/// held still on the way out for 30 samples, it then goes on with the rest (out, hold,
/// back: one excursion, ending at home). Continuing the same readings as a new
/// demonstration's prefix (the reading encoded again by the bottom) does not give the
/// plan back (the control); a paper-algorithm model, a wrong initial posture and a
/// too-short reading are refused.
#[test]
fn resuming_its_own_reproduction_goes_on_as_planned() {
    let m = trained(3);
    let initial = gesture(30, 7)[0].clone();
    let whole = m.reproduce(&initial).unwrap().postures;
    let n = whole.len();
    let joined = |reading: &[Vec<f64>], rest: &[Vec<f64>]| -> Vec<Vec<f64>> {
        reading.iter().chain(rest.iter().skip(1)).cloned().collect()
    };
    let gap = |a: &[Vec<f64>], b: &[Vec<f64>]| {
        a.iter()
            .zip(b)
            .flat_map(|(x, y)| x.iter().zip(y).map(|(p, q)| (p - q).abs()))
            .fold(0.0, f64::max)
    };
    let mut control = Vec::new();
    for k in [n / 4, n / 2, 3 * n / 4] {
        let reading = &whole[..k];
        let rest = m.resume(&initial, reading).unwrap().postures;
        assert_eq!(&rest[0], reading.last().unwrap());
        let again = joined(reading, &rest);
        assert!(
            again.len().abs_diff(n) <= 1,
            "at {k}: {} of {n}",
            again.len()
        );
        assert!(
            gap(&again, &whole) < 0.02,
            "at {k}: {}",
            gap(&again, &whole)
        );
        let reencoded = joined(reading, &m.continue_events(reading).unwrap().postures);
        control.push(gap(&reencoded, &whole));
    }
    // the control: the reading encoded again does not give the plan back (0.08, 0.51 and
    // 0.08 measured)
    assert!(control.iter().any(|&g| g > 0.05), "{control:?}");
    // held still for 30 samples on the way out: then out, held, back, home
    let out = whole.iter().position(|p| p[0] > 0.5).unwrap();
    let mut reading = whole[..out].to_vec();
    reading.extend(std::iter::repeat(whole[out - 1].clone()).take(30));
    let after = joined(&reading, &m.resume(&initial, &reading).unwrap().postures);
    assert_eq!(excursions(&after), 1, "{after:?}");
    assert!(after.last().unwrap()[0].abs() < 0.15);
    assert!(
        after.len().abs_diff(n + 30) <= 10,
        "{} against {}",
        after.len(),
        n + 30
    );
    let e = m.resume(&[0.0], &reading).unwrap_err().to_string();
    assert!(e.contains("initial posture"), "{e}");
    let e = m.resume(&initial, &reading[..2]).unwrap_err().to_string();
    assert!(e.contains("reading") && e.contains("2 sample"), "{e}");
    let endless = vec![initial.clone(); MAX_ALIGNED * MAX_ALIGNED / n + 1];
    let e = m.resume(&initial, &endless).unwrap_err().to_string();
    assert!(
        e.contains("at most") && e.contains(&format!("plan of {n}")),
        "{e}"
    );
    let series: Vec<Vec<Vec<f64>>> = (0..3).map(|i| gesture(30 + 5 * i, i as u64)).collect();
    let mut p = HsomParams::table1();
    p.state_length = 2;
    p.action_length = 2;
    let paper = p
        .check("paper")
        .unwrap()
        .fit(&Demonstration::from_series(&series))
        .unwrap();
    let e = paper.resume(&initial, &reading).unwrap_err().to_string();
    assert!(e.contains("algorithm = events"), "{e}");
}

/// Continuing a prefix with the hierarchy: the prefix's events are pushed up the lists
/// and the levels plan the rest. Shown the way out and part of the far hold, the
/// reproduction holds, comes back and ends by itself, without going out again; an
/// untrained hierarchy does not. A paper-algorithm model and a too-short prefix are
/// refused with named errors.
#[test]
fn continuing_a_prefix_plans_the_rest_from_the_lists() {
    let prefix: Vec<Vec<f64>> = gesture(35, 9).into_iter().take(35 + 40 + 15).collect();
    let goes_home = |m: &EventsHsom| {
        let r = m.continue_events(&prefix).unwrap();
        let xs: Vec<f64> = r.postures.iter().map(|p| p[0]).collect();
        let back = xs.iter().position(|&x| x < 0.5);
        let out_again = back.is_some_and(|b| xs[b..].iter().any(|&x| x > 0.6));
        let held = xs.iter().take_while(|&&x| x > 0.9).count();
        (
            r.postures[0] == prefix[prefix.len() - 1]
                && r.stop == StopReason::EndEvent
                && xs.last().unwrap().abs() < 0.15
                && !out_again
                && (5..=45).contains(&held),
            format!("{xs:?}"),
        )
    };
    let (ok, xs) = goes_home(&trained(3));
    assert!(ok, "trained: {xs}");
    let series: Vec<Vec<Vec<f64>>> = (0..3).map(|i| gesture(30 + 5 * i, i as u64)).collect();
    let (ok, xs) = goes_home(&untrained(&series));
    assert!(!ok, "untrained: {xs}");
    let mut p = HsomParams::table1();
    p.state_length = 2;
    p.action_length = 2;
    let paper = p
        .check("paper")
        .unwrap()
        .fit(&Demonstration::from_series(&series))
        .unwrap();
    let e = paper.continue_events(&prefix).unwrap_err().to_string();
    assert!(e.contains("algorithm = events"), "{e}");
    let e = trained(3)
        .continue_events(&prefix[..2])
        .unwrap_err()
        .to_string();
    assert!(e.contains("prefix") && e.contains("2 sample"), "{e}");
}
