//! Bad input never crashes, hangs or is silently "fixed" (the classes of bad input answered in
//! the library; docs/RELIABILITY.md): an MJCF model whose time step the controller cannot run,
//! a model lacking an actuator, a configuration whose root is not `<hsom>`, demonstrations
//! too short for the action horizon or too large to train on, and model files whose
//! statistics would size the reproduction without bound.

use crate::hsom_common;

use cosco_hsom::config::{parse_config, ConfigError, HsomParams};
use cosco_hsom::hsom::{Hsom, HsomError, PersistError};
#[cfg(feature = "sim")]
use cosco_hsom::sim::{NaoArm, SimError};
#[cfg(feature = "sim")]
use predicates::prelude::*;

#[cfg(feature = "sim")]
const ARM: &str = include_str!("../../models/nao_left_arm.xml");

#[test]
#[cfg(feature = "sim")] // needs the simulated arm
fn mjcf_time_steps_the_controller_cannot_run_are_refused_before_simulating() {
    for bad in ["0", "-0.002", "0.05", "1e-7"] {
        let xml = ARM.replacen("timestep=\"0.002\"", &format!("timestep=\"{bad}\""), 1);
        assert_ne!(xml, ARM, "the shipped model sets timestep=\"0.002\"");
        match NaoArm::from_xml_str(&xml) {
            Err(SimError::BadOption { name, value, .. }) => {
                assert_eq!(name, "option/@timestep");
                assert_eq!(value, bad.parse::<f64>().unwrap());
            }
            // MuJoCo itself may refuse a non-positive step: an error either way, never a hang
            Err(SimError::Mujoco(_)) if bad.starts_with('-') || bad == "0" => {}
            other => panic!("timestep {bad}: {other:?}"),
        }
    }
    // the shipped step loads
    assert!(NaoArm::from_xml_str(ARM).is_ok());
}

#[test]
#[cfg(feature = "sim")] // needs the simulated arm
fn a_model_without_one_of_the_arms_actuators_names_it() {
    let start = ARM.find("<general name=\"LElbowYaw\"").unwrap();
    let end = start + ARM[start..].find("/>").unwrap() + 2;
    let xml = format!("{}{}", &ARM[..start], &ARM[end..]);
    let e = NaoArm::from_xml_str(&xml).unwrap_err();
    assert!(
        matches!(&e, SimError::Missing { kind: "actuator", name } if name == "LElbowYaw"),
        "{e}"
    );
    assert!(e.to_string().contains("LElbowYaw"), "{e}");
}

#[test]
fn a_configuration_whose_root_is_not_hsom_is_refused_with_its_line() {
    let good = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/configs/nao-gestures.xml"
    ))
    .unwrap();
    assert!(parse_config(&good, "good.xml").is_ok());
    let bad = good
        .replace("<hsom version=\"1\">", "<mujoco version=\"1\">")
        .replace("</hsom>", "</mujoco>");
    let e = parse_config(&bad, "bad.xml").unwrap_err();
    assert!(matches!(e, ConfigError::Malformed { .. }), "{e}");
    let m = e.to_string();
    assert!(
        m.contains("bad.xml") && m.contains("<mujoco>") && m.contains("<hsom>"),
        "{m}"
    );
}

/// Table I for 2 variables; with a `horizon` above 1 the events algorithm (which reads it) on
/// Table I's levels.
fn config(horizon: usize, normalisation: &str) -> cosco_hsom::config::HsomConfig {
    let mut p = HsomParams::table1();
    p.state_length = 2;
    p.action_length = 2;
    if horizon > 1 {
        p.algorithm =
            cosco_hsom::config::AlgorithmParams::Events(cosco_hsom::config::EventsParams {
                change_ratio: 1.0,
                action_horizon: horizon,
            });
    }
    p.normalisation = match normalisation {
        "none" => cosco_hsom::config::Normalisation::None,
        _ => cosco_hsom::config::Normalisation::Global,
    };
    p.check("test").unwrap()
}

fn line(n: usize, scale: f64) -> Vec<Vec<f64>> {
    (0..n)
        .map(|i| {
            let f = i as f64 / n as f64;
            vec![scale * (2.0 * f - 1.0), -scale * f]
        })
        .collect()
}

#[test]
fn demonstrations_shorter_than_the_action_horizon_are_refused() {
    let e = config(10, "global")
        .fit(&cosco_hsom::demos::Demonstration::from_series(&[
            line(3, 1.0),
            line(40, 1.0),
        ]))
        .unwrap_err();
    assert!(
        matches!(
            e,
            HsomError::TooShort {
                rows: 3,
                needed: 11,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("series #0"), "{e}");
    // long enough: trains
    assert!(config(10, "global")
        .fit(&cosco_hsom::demos::Demonstration::from_series(&[
            line(11, 1.0),
            line(40, 1.0)
        ]))
        .is_ok());
}

#[test]
fn data_too_large_to_train_on_is_refused_instead_of_saving_an_unloadable_model() {
    // 1e200 raw (normalisation none) and +-1e308 (the range overflows: no normalisation)
    for (scale, norm) in [(1e200, "none"), (1e308, "global")] {
        let e = config(1, norm)
            .fit(&cosco_hsom::demos::Demonstration::from_series(&[
                line(40, scale),
                line(40, scale),
            ]))
            .unwrap_err();
        assert!(matches!(e, HsomError::OutOfScale { .. }), "{scale}: {e}");
        assert!(e.to_string().contains("series #"), "{e}");
    }
    // large but representable: trains, saves and loads
    let m = config(1, "none")
        .fit(&cosco_hsom::demos::Demonstration::from_series(&[
            line(40, 1e6),
            line(40, 1e6),
        ]))
        .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("m.bin");
    m.save(&p).unwrap();
    assert!(Hsom::load(&p).is_ok());
}

#[test]
fn model_statistics_that_would_size_the_reproduction_without_bound_are_refused() {
    let m = config(1, "global")
        .fit(&cosco_hsom::demos::Demonstration::from_series(&[
            line(40, 1.0),
            line(50, 1.0),
        ]))
        .unwrap();
    let text = m.to_text();
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("m.txt");
    // a node held longer than the longest demonstration
    let bad = hsom_common::edit_model_text(&text, |m| m["dwell"][0] = 1e300.into());
    std::fs::write(&p, bad).unwrap();
    let e = Hsom::load(&p).unwrap_err();
    assert!(matches!(e, PersistError::Corrupted { .. }), "{e}");
    assert!(
        e.to_string()
            .contains("longer than the longest demonstration"),
        "{e}"
    );
    // the model as trained loads (saving refuses what loading would: src/hsom/persist.rs)
    std::fs::write(&p, &text).unwrap();
    assert_eq!(Hsom::load(&p).unwrap().to_text(), text);
}

/// A model file of a small trained model, resealed (the checksum recomputed) after `edit`.
fn resealed(edit: impl FnOnce(&mut serde_json::Value)) -> (tempfile::TempDir, std::path::PathBuf) {
    let m = config(1, "global")
        .fit(&cosco_hsom::demos::Demonstration::from_series(&[
            line(40, 1.0),
            line(50, 1.0),
        ]))
        .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("m.txt");
    std::fs::write(&p, hsom_common::edit_model_text(&m.to_text(), edit)).unwrap();
    (dir, p)
}

#[test]
fn weights_beyond_what_training_makes_are_refused_naming_the_level_and_the_bound() {
    let (_dir, p) = resealed(|m| {
        for map in m["maps"].as_array_mut().unwrap() {
            for w in map["weights"].as_array_mut().unwrap() {
                *w = 1e300.into();
            }
        }
    });
    let e = Hsom::load(&p).unwrap_err();
    assert!(matches!(e, PersistError::Corrupted { .. }), "{e}");
    let e = e.to_string();
    assert!(
        e.contains("m.txt") && e.contains("weights of level 0") && e.contains("1e100"),
        "{e}"
    );
}

#[test]
fn a_scale_training_cannot_make_is_refused_naming_the_normalisation() {
    let (_dir, p) = resealed(|m| {
        for s in m["scale"].as_array_mut().unwrap() {
            *s = 1e-300.into();
        }
    });
    let e = Hsom::load(&p).unwrap_err().to_string();
    assert!(
        e.contains("m.txt") && e.contains("scale 1e-300") && e.contains("normalisation global"),
        "{e}"
    );
    // normalisation none keeps offset 0 and scale 1
    let m = config(1, "none")
        .fit(&cosco_hsom::demos::Demonstration::from_series(&[
            line(40, 1.0),
            line(50, 1.0),
        ]))
        .unwrap();
    let bad = hsom_common::edit_model_text(&m.to_text(), |m| m["scale"][1] = 2.0.into());
    std::fs::write(&p, bad).unwrap();
    let e = Hsom::load(&p).unwrap_err().to_string();
    assert!(e.contains("offset 0 and scale 1"), "{e}");
}

#[test]
fn a_model_file_without_its_kind_line_is_refused_quoting_a_short_prefix() {
    let (_dir, p) = resealed(|_| {});
    let text = std::fs::read_to_string(&p).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let without = [&lines[..2], &lines[3..]].concat().join("\n") + "\n";
    std::fs::write(&p, hsom_common::with_checksum(&without)).unwrap();
    let e = Hsom::load(&p).unwrap_err().to_string();
    assert!(e.contains("m.txt") && e.contains("kind line"), "{e}");
    assert!(e.len() < 300, "{} characters: {e}", e.len());
}

#[test]
fn what_the_binary_form_cannot_decode_is_said_in_words() {
    let m = config(1, "global")
        .fit(&cosco_hsom::demos::Demonstration::from_series(&[
            line(40, 1.0),
            line(50, 1.0),
        ]))
        .unwrap();
    let mut b = m.to_bytes();
    // the embedded configuration made unreadable (same length), the file resealed
    let at = b.windows(6).position(|w| w == b"<rows>").unwrap();
    b[at + 6] = b'x';
    let n = b.len() - 8;
    let sum = b[..n].iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &x| {
        (h ^ x as u64).wrapping_mul(0x0100_0000_01b3)
    });
    b[n..].copy_from_slice(&sum.to_le_bytes());
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("m.bin");
    std::fs::write(&p, &b).unwrap();
    let e = Hsom::load(&p).unwrap_err().to_string();
    assert!(e.contains("m.bin") && e.contains("rows"), "{e}");
    assert!(!e.contains("OtherString") && !e.contains("Error("), "{e}");
}

const NAO: &str = include_str!("../../configs/nao-gestures.xml");

#[test]
fn a_missing_level_is_named_by_its_index() {
    // height 4 with level 1 left out
    let start = NAO.find("<level index=\"1\">").unwrap();
    let end = start + NAO[start..].find("</level>").unwrap() + "</level>".len();
    let bad = format!("{}{}", &NAO[..start], &NAO[end..]);
    let e = parse_config(&bad, "bad.xml").unwrap_err();
    assert!(
        matches!(
            e,
            ConfigError::MissingLevel {
                index: 1,
                height: 4,
                listed: 3,
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().contains("<level index=\"1\">"), "{e}");
}

/// A level index the hierarchy does not have is named, with the indices it has (not reported
/// as the first index left without a level).
#[test]
fn a_stray_level_index_is_named_with_the_allowed_ones() {
    let lone = "<hsom><levels><level index=\"9\"><rows>2</rows><cols>2</cols>\
                <topology>orthogonal</topology><learningFactor>0.5</learningFactor></level>\
                </levels></hsom>";
    for bad in [
        lone.to_string(),
        NAO.replacen("<level index=\"3\">", "<level index=\"9\">", 1),
    ] {
        let e = parse_config(&bad, "bad.xml").unwrap_err();
        assert!(
            matches!(&e, ConfigError::Invalid { field, value, .. }
                if field == "levels/level[0]/@index" && value == "9"),
            "{e:?}"
        );
        let m = e.to_string();
        assert!(m.contains("bad.xml") && m.contains("from 0 to 3"), "{m}");
    }
}

#[test]
fn mixed_content_names_the_element_and_its_line() {
    let bad = NAO.replace("<seed>1</seed>", "<seed>1 <b>2</b></seed>");
    let e = parse_config(&bad, "bad.xml").unwrap_err();
    let line = NAO[..NAO.find("<seed>").unwrap()].matches('\n').count() + 1;
    match &e {
        ConfigError::Malformed {
            line: l, message, ..
        } => {
            assert_eq!(*l, line, "{e}");
            assert!(message.contains("<seed>"), "{e}");
        }
        other => panic!("{other}"),
    }
}

#[test]
fn demonstrations_sampled_at_different_rates_are_refused() {
    use cosco_hsom::demos::{parse_csv, validate_set, DemoError};
    let csv = |period: f64| {
        let mut s = String::from("time,a\n");
        for i in 0..20 {
            s.push_str(&format!("{},{}\n", i as f64 * period, i));
        }
        parse_csv(&format!("d{period}.csv"), s.as_bytes()).unwrap()
    };
    assert!(validate_set(&[csv(0.025), csv(0.025)], None).is_ok());
    let e = validate_set(&[csv(0.025), csv(0.01)], None).unwrap_err();
    assert!(matches!(e, DemoError::RateMismatch { .. }), "{e}");
    assert!(
        e.to_string().contains("d0.01.csv") && e.to_string().contains("d0.025.csv"),
        "{e}"
    );
    // one with a time column, one without
    let plain = parse_csv("plain.csv", b"a\n1\n2\n3\n").unwrap();
    let e = validate_set(&[csv(0.025), plain], None).unwrap_err();
    assert!(matches!(e, DemoError::RateMismatch { .. }), "{e}");
}

#[test]
#[cfg(feature = "sim")] // needs the simulated arm
fn evaluating_a_one_row_or_impossible_reproduction_is_refused() {
    use cosco_hsom::metrics::MetricsParams;
    use cosco_hsom::sim::evaluate;
    use cosco_hsom::sim::JOINT_NAMES;
    let arm = NaoArm::load_default().unwrap();
    let demo = cosco_hsom::demos::Demonstration {
        source: "demo.csv".into(),
        columns: JOINT_NAMES.iter().map(|s| s.to_string()).collect(),
        time: None,
        rows: (0..40)
            .map(|i| {
                let t = i as f64 / 40.0;
                vec![1.4 - t, 0.3, -1.39, -1.01, 0.0, 0.25]
            })
            .collect(),
    };
    let params = MetricsParams::default();
    let one = vec![demo.rows[0].clone()];
    let e = evaluate(Some(&arm), std::slice::from_ref(&demo), &one, &params).unwrap_err();
    assert!(e.to_string().contains("1 sample"), "{e}");
    let mut far = demo.rows.clone();
    far[5][3] = 10.0;
    let e = evaluate(Some(&arm), std::slice::from_ref(&demo), &far, &params).unwrap_err();
    assert!(
        e.to_string().contains("LElbowRoll") && e.to_string().contains("sample 5"),
        "{e}"
    );
    // a little beyond a limit (encoder noise, a soft joint limit) is scored
    let mut hair = demo.rows.clone();
    hair[5][3] = -0.0349066 + 0.1;
    assert!(evaluate(Some(&arm), std::slice::from_ref(&demo), &hair, &params).is_ok());
}

/// `simulate --demos`: a demonstration far outside a joint's range is refused, naming the file,
/// sample and joint; values a little outside are clamped before execution with a warning on
/// stderr (and counted in report.md), and `--strict` turns the warning into an error.
#[test]
#[cfg(feature = "sim")] // needs the simulated arm
fn simulate_refuses_far_out_demonstrations_and_warns_on_clamping() {
    use assert_cmd::Command;
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    Command::cargo_bin("cosco")
        .unwrap()
        .args(["demos", "--gesture", "wave", "--count", "3", "--out"])
        .arg(d.join("demos"))
        .assert()
        .success();
    // LElbowRoll (column 4 after time) of every sample set to `v`
    let rewrite = |to: &std::path::Path, v: &str| {
        std::fs::create_dir_all(to).unwrap();
        for k in 1..=3 {
            let name = format!("demo_{k:02}.csv");
            let text = std::fs::read_to_string(d.join("demos").join(&name)).unwrap();
            let out: Vec<String> = text
                .lines()
                .enumerate()
                .map(|(i, l)| {
                    if i == 0 {
                        return l.to_string();
                    }
                    let mut f: Vec<&str> = l.split(',').collect();
                    f[4] = v;
                    f.join(",")
                })
                .collect();
            std::fs::write(to.join(&name), out.join("\n") + "\n").unwrap();
        }
    };
    let simulate = |demos: &std::path::Path, strict: bool| {
        let mut c = Command::cargo_bin("simulate").unwrap();
        c.args(["--no-render", "--no-variants", "--no-heldout", "--demos"])
            .arg(demos)
            .arg("--out")
            .arg(d.join("out"));
        if strict {
            c.arg("--strict");
        }
        c.assert()
    };
    rewrite(&d.join("far"), "3.5");
    simulate(&d.join("far"), false).failure().stderr(
        predicates::str::contains("demo_01.csv")
            .and(predicates::str::contains("LElbowRoll"))
            .and(predicates::str::contains("sample")),
    );
    // 0.1 rad: 0.135 above LElbowRoll's maximum, within the 0.25 rad tolerance
    rewrite(&d.join("near"), "0.1");
    simulate(&d.join("near"), false)
        .success()
        .stderr(predicates::str::contains(
            "warning: posture values outside the joint ranges",
        ));
    simulate(&d.join("near"), true)
        .failure()
        .stderr(predicates::str::contains("--strict"));
}

/// Every `memory` object of a model's JSON (one gesture's, or each gesture's) with `field` set
/// to `value`.
fn set_memory(m: &mut serde_json::Value, field: &str, value: u64) {
    match m {
        serde_json::Value::Object(o) => {
            for (k, v) in o.iter_mut() {
                match (k.as_str(), v.get(field).is_some()) {
                    ("memory", true) => v[field] = value.into(),
                    _ => set_memory(v, field, value),
                }
            }
        }
        serde_json::Value::Array(a) => a.iter_mut().for_each(|v| set_memory(v, field, value)),
        _ => {}
    }
}

/// The model of [`resealed`] with `memory.<field>` set to `value`, and beside it two
/// demonstrations of its columns to teach it more (`more/`).
fn counted(field: &str, value: u64) -> (tempfile::TempDir, std::path::PathBuf) {
    let (dir, p) = resealed(|m| set_memory(m, field, value));
    let columns = config(1, "global")
        .fit(&cosco_hsom::demos::Demonstration::from_series(&[
            line(40, 1.0),
            line(50, 1.0),
        ]))
        .unwrap()
        .columns()
        .join(",");
    let more = dir.path().join("more");
    std::fs::create_dir_all(&more).unwrap();
    for (k, n) in [42, 47].into_iter().enumerate() {
        let rows: Vec<String> = (line(n, 1.0).iter())
            .map(|r| format!("{},{}", r[0], r[1]))
            .collect();
        let text = format!("{columns}\n{}\n", rows.join("\n"));
        std::fs::write(more.join(format!("d{k}.csv")), text).unwrap();
    }
    (dir, p)
}

/// `cosco inspect MODEL` (`teach` false) or `cosco train --from MODEL --demos more/ --out
/// taught.txt` beside it (`teach` true).
fn cosco_on(model: &std::path::Path, teach: bool) -> assert_cmd::assert::Assert {
    let mut c = assert_cmd::Command::cargo_bin("cosco").unwrap();
    match teach {
        false => c.arg("inspect").arg(model),
        true => (c.args(["train", "--from"]).arg(model))
            .arg("--demos")
            .arg(model.with_file_name("more"))
            .arg("--out")
            .arg(model.with_file_name("taught.txt")),
    };
    c.assert()
}

/// `run` failed with every one of `says` (the model's file, the field, what is allowed), no
/// panic, the output neither blamed nor written.
fn refused(run: assert_cmd::assert::Assert, model: &std::path::Path, says: &[&str]) {
    let stderr = String::from_utf8_lossy(&run.failure().get_output().stderr).to_string();
    for s in says {
        assert!(stderr.contains(s), "{s:?} not in: {stderr}");
    }
    assert!(
        !stderr.contains("panicked") && !stderr.contains("taught.txt"),
        "{stderr}"
    );
    assert!(!model.with_file_name("taught.txt").exists());
}

#[test]
fn a_model_counting_more_sittings_than_demonstrations_is_refused_naming_the_file() {
    // learned from 2 demonstrations: at most 2 sittings, the training and 1 update
    for updates in [2, 3, u64::from(u32::MAX)] {
        let (_dir, p) = counted("updates", updates);
        let says = [
            "m.txt",
            &format!("updates (sittings after the first) is {updates} with learned 2"),
            "at most learned - 1 = 1",
        ];
        refused(cosco_on(&p, false), &p, &says);
        refused(cosco_on(&p, true), &p, &says);
    }
    // negative control: the most sittings 2 demonstrations make load, and are said
    let (_dir, p) = counted("updates", 1);
    cosco_on(&p, false)
        .success()
        .stdout(predicates::str::contains(
            "learned from 2 demonstrations in 2 sittings",
        ));
}

#[test]
fn an_absurd_count_of_demonstrations_learned_is_refused_naming_the_input_model() {
    use cosco_hsom::hsom::MAX_LEARNED;
    for learned in [u64::from(u32::MAX), MAX_LEARNED + 1, u64::MAX] {
        let (_dir, p) = counted("learned", learned);
        let says = [
            "m.txt",
            &format!("learned (demonstrations learned from) is {learned}: 1 to 1000000000"),
        ];
        refused(cosco_on(&p, false), &p, &says);
        refused(cosco_on(&p, true), &p, &says);
    }
    // the bound loads; an update that would count past it is refused naming the model taught
    let (_dir, p) = counted("learned", MAX_LEARNED);
    cosco_on(&p, false)
        .success()
        .stdout(predicates::str::contains(
            "learned from 1000000000 demonstrations",
        ));
    let says = "m.txt: the model learned from 1000000000 demonstrations (learned); 2 more would \
                pass 1000000000, the most a model counts";
    refused(cosco_on(&p, true), &p, &[says]);
    // negative control: an update that reaches the bound is taught
    let (_dir, p) = counted("learned", MAX_LEARNED - 2);
    cosco_on(&p, true).success();
    let taught = Hsom::load(&p.with_file_name("taught.txt")).unwrap();
    assert_eq!(taught.learned(), (MAX_LEARNED, 4, 1));
}
