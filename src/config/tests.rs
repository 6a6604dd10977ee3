//! The XML configuration: Table I, round trip, and one test per bad input.

use std::path::Path;

use crate::config::{
    load_config, parse_config, Algorithm, ConfigError, HsomParams, IdDecoding, MemoryMode, StopRule,
};
use crate::som::Topology;

fn table1_text() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/table1.xml"))
        .unwrap()
}

fn recommended_text() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/nao-gestures.xml"))
        .unwrap()
}

#[test]
fn recommended_configuration_uses_the_events_extension() {
    let c = load_config(&Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/nao-gestures.xml"))
        .unwrap();
    assert_eq!(c.params().kind(), Algorithm::Events);
    assert_eq!(c.params(), &HsomParams::recommended());
    let again = parse_config(&c.to_xml(), "again.xml").unwrap();
    assert_eq!(c.params(), again.params());
}

/// The recommended file names at most 10 top-level settings and 7 per level, and every one
/// of them is read by its algorithm (a setting it does not read would be refused).
#[test]
fn the_recommended_file_is_small() {
    let t = recommended_text();
    let top = t
        .lines()
        .filter(|l| l.starts_with("  <") && !l.starts_with("  </") && !l.contains("<levels>"))
        .count();
    assert!(top <= 10, "{top} top-level settings");
    let most = t
        .split("<level ")
        .skip(1)
        .map(|l| l.split("</level>").next().unwrap().matches("</").count())
        .max()
        .unwrap();
    assert!(most <= 7, "{most} settings in a level");
}

/// An omitted setting takes the recommended configuration's value (`algorithm` events), or
/// Table I's under `algorithm = paper`: an empty configuration is the recommended one.
#[test]
fn omitted_settings_take_the_defaults_of_their_algorithm() {
    let c = parse_config("<hsom/>", "empty.xml").unwrap();
    assert_eq!(c.params(), &HsomParams::recommended());
    let c = parse_config("<hsom><algorithm>paper</algorithm></hsom>", "paper.xml").unwrap();
    assert_eq!(c.params(), &HsomParams::table1());
    let c = parse_config(
        "<hsom><seed>7</seed><changeRatio>0.8</changeRatio></hsom>",
        "x",
    )
    .unwrap();
    assert_eq!(c.params().seed, 7);
    assert_eq!(c.params().change_ratio(), 0.8);
    assert_eq!(c.params().action_horizon(), 10);
}

#[test]
fn events_configurations_are_checked_with_their_own_input_sizes() {
    let rec = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/nao-gestures.xml"),
    )
    .unwrap();
    // 64 slots of 2 x 4096 values on a 32x32 level: far beyond the weight limit for events,
    // although the paper's ID lists (2 x memory values) would fit
    let big = rec
        .replacen("<memory>4</memory>", "<memory>64</memory>", 1)
        .replacen(
            "<stateLength>6</stateLength>",
            "<stateLength>4096</stateLength>",
            1,
        )
        .replacen(
            "<actionLength>6</actionLength>",
            "<actionLength>4096</actionLength>",
            1,
        )
        .replacen(
            "<rows>8</rows>\n      <cols>8</cols>",
            "<rows>32</rows>\n      <cols>32</cols>",
            1,
        );
    let e = parse_config(&big, "bad.xml").unwrap_err();
    assert!(e.to_string().contains("100 million weights"), "{e}");
    let levels = rec.replacen(
        "<algorithm>events</algorithm>",
        "<algorithm>events</algorithm><memoryMode>levels</memoryMode>",
        1,
    );
    assert_not_read(
        parse_config(&levels, "bad.xml").unwrap_err(),
        "memoryMode",
        "paper",
    );
}

#[test]
fn unknown_algorithm_is_refused() {
    let t = table1_text().replacen(
        "<algorithm>paper</algorithm>",
        "<algorithm>magic</algorithm>",
        1,
    );
    let e = parse_config(&t, "bad.xml").unwrap_err();
    assert!(e.to_string().contains("algorithm"), "{e}");
    assert!(e.to_string().contains("paper, events"), "{e}");
}

#[test]
fn table1_file_reproduces_the_paper_table() {
    let c = load_config(&Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/table1.xml")).unwrap();
    let p = c.params();
    assert_eq!(
        (p.height, p.memory, p.update_period(), p.training_steps),
        (6, 4, 2, 5000)
    );
    assert_eq!((p.state_length, p.action_length), (6, 6));
    let expect = [(16, 0.1), (10, 0.2), (8, 0.3), (6, 0.5), (2, 0.6), (1, 0.8)];
    for (l, &(n, a)) in p.levels.iter().zip(&expect) {
        assert_eq!((l.rows, l.cols), (n, n));
        assert_eq!(l.learning_factor.initial, a);
        assert_eq!(l.topology, Topology::Orthogonal);
    }
    // the file is the paper taken literally: the built-in Table I
    assert_eq!(p, &HsomParams::table1());
    assert_eq!(p.kind(), Algorithm::Paper);
    let q = p.paper().unwrap();
    assert_eq!(
        (q.memory_mode, q.offset, q.id_decoding, q.stop),
        (MemoryMode::Lists, 3, IdDecoding::Round, StopRule::Learned)
    );
    assert_eq!((p.change_ratio(), p.action_horizon()), (1.0, 1));
}

#[test]
fn to_xml_round_trips() {
    let c = parse_config(&table1_text(), "table1.xml").unwrap();
    let again = parse_config(&c.to_xml(), "again.xml").unwrap();
    assert_eq!(c.params(), again.params());
}

fn err(text: &str) -> ConfigError {
    parse_config(text, "bad.xml").unwrap_err()
}

fn replace(from: &str, to: &str) -> String {
    let t = table1_text();
    assert!(t.contains(from), "{from}");
    t.replacen(from, to, 1)
}

fn assert_invalid(e: ConfigError, field: &str, value: &str) {
    let msg = e.to_string();
    match &e {
        ConfigError::Invalid {
            file,
            field: f,
            value: v,
            ..
        } => {
            assert_eq!(file, "bad.xml");
            assert_eq!(f, field, "{msg}");
            assert_eq!(v, value, "{msg}");
        }
        other => panic!("expected Invalid for {field}, got {other:?}"),
    }
    assert!(
        msg.contains("bad.xml") && msg.contains(field) && msg.contains(value),
        "{msg}"
    );
}

#[test]
fn invalid_malformed_xml_reports_line_and_column() {
    let e = err(&replace("<memory>4</memory>", "<memory>4</memroy>"));
    match &e {
        ConfigError::Malformed {
            file, line, column, ..
        } => {
            assert_eq!(file, "bad.xml");
            assert_eq!(*line, 10);
            assert!(*column > 1);
        }
        other => panic!("{other:?}"),
    }
    assert!(e.to_string().starts_with("bad.xml:10:"), "{e}");
    assert!(matches!(
        err("<hsom><memory>4</memory>"),
        ConfigError::Malformed { .. }
    ));
}

#[test]
fn invalid_unknown_element() {
    let e = err(&replace(
        "<memory>4</memory>",
        "<memory>4</memory><colour>red</colour>",
    ));
    assert!(matches!(e, ConfigError::Schema { .. }), "{e:?}");
    assert!(
        e.to_string().contains("colour") && e.to_string().contains("bad.xml"),
        "{e}"
    );
    let e = err(&replace(
        "<rows>16</rows>",
        "<rows>16</rows><depth>2</depth>",
    ));
    assert!(e.to_string().contains("depth"), "{e}");
}

#[test]
fn invalid_missing_level_rows() {
    let e = err(&replace("<rows>16</rows>", ""));
    assert!(
        matches!(&e, ConfigError::Missing { field, .. } if field == "levels/level[0]/rows"),
        "{e:?}"
    );
}

#[test]
fn invalid_memory_zero() {
    assert_invalid(
        err(&replace("<memory>4</memory>", "<memory>0</memory>")),
        "memory",
        "0",
    );
}

#[test]
fn invalid_memory_not_a_number() {
    assert_invalid(
        err(&replace("<memory>4</memory>", "<memory>four</memory>")),
        "memory",
        "four",
    );
}

#[test]
fn invalid_zero_size() {
    assert_invalid(
        err(&replace("<rows>16</rows>", "<rows>0</rows>")),
        "levels/level[0]/rows",
        "0",
    );
    assert_invalid(
        err(&replace("<cols>10</cols>", "<cols>0</cols>")),
        "levels/level[1]/cols",
        "0",
    );
}

#[test]
fn invalid_offset_greater_than_memory() {
    assert_invalid(
        err(&replace("<offset>3</offset>", "<offset>5</offset>")),
        "reproduction/offset",
        "5",
    );
}

#[test]
fn invalid_offset_zero() {
    assert_invalid(
        err(&replace("<offset>3</offset>", "<offset>0</offset>")),
        "reproduction/offset",
        "0",
    );
}

#[test]
fn invalid_learning_factor_above_one() {
    assert_invalid(
        err(&replace(
            "<learningFactor>0.8</learningFactor>",
            "<learningFactor>1.5</learningFactor>",
        )),
        "levels/level[5]/learningFactor",
        "1.5",
    );
}

#[test]
fn invalid_learning_factor_zero() {
    assert_invalid(
        err(&replace(
            "<learningFactor>0.1</learningFactor>",
            "<learningFactor>0</learningFactor>",
        )),
        "levels/level[0]/learningFactor",
        "0",
    );
}

#[test]
fn invalid_learning_radius_negative() {
    assert_invalid(
        err(&replace(
            "<learningRadius>8</learningRadius>",
            "<learningRadius>-1</learningRadius>",
        )),
        "levels/level[0]/learningRadius",
        "-1",
    );
}

#[test]
fn invalid_height_differs_from_level_count() {
    assert_invalid(
        err(&replace("<height>6</height>", "<height>5</height>")),
        "height",
        "5",
    );
}

#[test]
fn invalid_unknown_topology() {
    assert_invalid(
        err(&replace(
            "<topology>orthogonal</topology>",
            "<topology>toroidal</topology>",
        )),
        "levels/level[5]/topology",
        "toroidal",
    );
}

#[test]
fn invalid_update_period_zero() {
    assert_invalid(
        err(&replace(
            "<updatePeriod>2</updatePeriod>",
            "<updatePeriod>0</updatePeriod>",
        )),
        "updatePeriod",
        "0",
    );
}

#[test]
fn invalid_training_steps_zero() {
    assert_invalid(
        err(&replace(
            "<trainingSteps>5000</trainingSteps>",
            "<trainingSteps>0</trainingSteps>",
        )),
        "trainingSteps",
        "0",
    );
}

#[test]
fn invalid_action_length_differs_from_state_length() {
    assert_invalid(
        err(&replace(
            "<actionLength>6</actionLength>",
            "<actionLength>3</actionLength>",
        )),
        "actionLength",
        "3",
    );
}

#[test]
fn invalid_state_length_zero() {
    assert_invalid(
        err(&replace(
            "<stateLength>6</stateLength>",
            "<stateLength>0</stateLength>",
        )),
        "stateLength",
        "0",
    );
}

#[test]
fn invalid_duplicate_level_index() {
    assert_invalid(
        err(&replace("<level index=\"4\">", "<level index=\"5\">")),
        "levels/level[5]/@index",
        "5",
    );
}

#[test]
fn invalid_id_decoding() {
    assert_invalid(
        err(&replace(
            "<idDecoding>round</idDecoding>",
            "<idDecoding>ceil</idDecoding>",
        )),
        "reproduction/idDecoding",
        "ceil",
    );
}

#[test]
fn invalid_memory_mode() {
    assert_invalid(
        err(&replace(
            "<memoryMode>lists</memoryMode>",
            "<memoryMode>queue</memoryMode>",
        )),
        "memoryMode",
        "queue",
    );
}

#[test]
fn invalid_max_length_zero() {
    assert_invalid(
        err(&replace(
            "<maxLength>2000</maxLength>",
            "<maxLength>0</maxLength>",
        )),
        "reproduction/maxLength",
        "0",
    );
}

#[test]
fn invalid_seed() {
    assert_invalid(
        err(&replace("<seed>1</seed>", "<seed>-3</seed>")),
        "seed",
        "-3",
    );
}

#[test]
fn missing_file_is_an_io_error_naming_it() {
    let e = load_config(Path::new("/nonexistent/cfg.xml")).unwrap_err();
    assert!(matches!(e, ConfigError::Io { .. }));
    assert!(e.to_string().contains("/nonexistent/cfg.xml"));
}

#[test]
fn invalid_too_many_weights() {
    let t = replace("<rows>16</rows>", "<rows>1024</rows>").replacen(
        "<cols>16</cols>",
        "<cols>1024</cols>",
        1,
    );
    let t = t.replacen(
        "<memoryMode>lists</memoryMode>",
        "<memoryMode>levels</memoryMode>",
        1,
    );
    let e = err(&t);
    assert!(
        matches!(&e, ConfigError::Invalid { field, .. } if field == "levels"),
        "{e:?}"
    );
}

fn assert_not_read(e: ConfigError, field: &str, reads: &str) {
    let msg = e.to_string();
    match &e {
        ConfigError::NotRead {
            field: f, reads: r, ..
        } => {
            assert_eq!((f.as_str(), r.as_str()), (field, reads), "{msg}");
        }
        other => panic!("expected NotRead for {field}, got {other:?}"),
    }
    assert!(
        msg.contains("bad.xml") && msg.contains(field) && msg.contains(reads),
        "{msg}"
    );
}

#[test]
fn invalid_change_ratio_and_action_horizon() {
    let t = recommended_text();
    for (from, to, field, value) in [
        ("<changeRatio>0.6<", "<changeRatio>0<", "changeRatio", "0"),
        (
            "<changeRatio>0.6<",
            "<changeRatio>1.5<",
            "changeRatio",
            "1.5",
        ),
        (
            "<actionHorizon>10<",
            "<actionHorizon>0<",
            "actionHorizon",
            "0",
        ),
    ] {
        assert!(t.contains(from), "{from}");
        assert_invalid(err(&t.replacen(from, to, 1)), field, value);
    }
}

#[test]
fn invalid_max_level_above_the_height() {
    // never clamped: the top level is height - 1
    let t = replace(
        "<maxLength>2000</maxLength>",
        "<maxLength>2000</maxLength><maxLevel>6</maxLevel>",
    );
    assert_invalid(err(&t), "reproduction/maxLevel", "6");
    let t = replace(
        "<maxLength>2000</maxLength>",
        "<maxLength>2000</maxLength><maxLevel>5</maxLevel>",
    );
    let c = parse_config(&t, "ok.xml").unwrap();
    assert_eq!(c.params().reproduction.max_level, Some(5));
    // cut to a height that no longer has level 5: an error naming maxLevel, not a silent drop
    let e = c.at_height(3).unwrap_err();
    assert!(e.to_string().contains("reproduction/maxLevel"), "{e}");
    assert_eq!(c.at_height(6).unwrap().params(), c.params());
}

#[test]
fn invalid_length_factor() {
    assert_invalid(
        err(&replace(
            "<lengthFactor>1.5</lengthFactor>",
            "<lengthFactor>0</lengthFactor>",
        )),
        "reproduction/lengthFactor",
        "0",
    );
}

#[test]
fn invalid_stop() {
    assert_invalid(
        err(&replace("<stop>learned</stop>", "<stop>never</stop>")),
        "reproduction/stop",
        "never",
    );
}

/// Every retired setting is refused by name, saying what it is now, whatever its value.
#[test]
fn retired_settings_are_errors_naming_them() {
    let top = [
        ("plan", "traced", "follow a training demonstration"),
        ("alignment", "smooth", "stairs"),
        ("knots", "halves", "two knots"),
        ("consensus", "all", "starts"),
        ("partialTraining", "skip", "list below is full"),
        ("listUpdate", "onChange", "every step"),
    ];
    for (name, value, now) in top {
        for text in [recommended_text(), table1_text()] {
            let t = text.replacen(
                "<seed>1</seed>",
                &format!("<seed>1</seed><{name}>{value}</{name}>"),
                1,
            );
            let e = err(&t);
            assert!(
                matches!(&e, ConfigError::Retired { field, .. } if field == name),
                "{e:?}"
            );
            let m = e.to_string();
            assert!(
                m.contains("bad.xml") && m.contains(name) && m.contains("retired"),
                "{m}"
            );
            assert!(m.contains(now), "{m}");
        }
    }
    let reproduction = [
        ("mode", "literal"),
        ("unseenFallback", "true"),
        ("minLengthFraction", "0.6"),
        ("stationarySteps", "60"),
        ("stationaryTolerance", "1"),
        ("endTolerance", "0"),
        ("confusionThreshold", "0"),
        ("continuity", "0"),
        ("closedLoop", "false"),
        ("minAccuracy", "0"),
        ("reflex", "bmu"),
        ("timing", "step"),
        ("loopVisits", "0"),
        ("loopWindow", "24"),
        ("revisitSuccessors", "false"),
    ];
    for (name, value) in reproduction {
        let t = replace(
            "<maxLength>2000</maxLength>",
            &format!("<maxLength>2000</maxLength><{name}>{value}</{name}>"),
        );
        let field = format!("reproduction/{name}");
        let e = err(&t);
        assert!(
            matches!(&e, ConfigError::Retired { field: f, .. } if *f == field),
            "{e:?}"
        );
        assert!(e.to_string().contains("retired"), "{e}");
    }
}

/// A setting the chosen algorithm does not read is an error naming it and the algorithm that
/// reads it.
#[test]
fn settings_the_algorithm_does_not_read_are_errors() {
    let rec = recommended_text();
    for (add, field) in [
        ("<updatePeriod>4</updatePeriod>", "updatePeriod"),
        ("<memoryMode>lists</memoryMode>", "memoryMode"),
        (
            "<reproduction><offset>3</offset></reproduction>",
            "reproduction/offset",
        ),
        (
            "<reproduction><idDecoding>round</idDecoding></reproduction>",
            "reproduction/idDecoding",
        ),
        (
            "<reproduction><stop>learned</stop></reproduction>",
            "reproduction/stop",
        ),
    ] {
        let t = rec.replacen("</levels>", &format!("</levels>{add}"), 1);
        assert_not_read(err(&t), field, "paper");
    }
    for (add, field) in [
        ("<changeRatio>1</changeRatio>", "changeRatio"),
        ("<actionHorizon>1</actionHorizon>", "actionHorizon"),
    ] {
        let t = replace("<seed>1</seed>", &format!("<seed>1</seed>{add}"));
        assert_not_read(err(&t), field, "events");
    }
}

#[test]
fn to_xml_round_trips_the_recommended_configuration_and_levels_mode() {
    let c = parse_config(&recommended_text(), "rec.xml").unwrap();
    assert_eq!(parse_config(&c.to_xml(), "again.xml").unwrap(), c);
    let t = replace(
        "<memoryMode>lists</memoryMode>",
        "<memoryMode>LEVELS</memoryMode>",
    );
    let c = parse_config(&t, "levels.xml").unwrap();
    assert_eq!(c.params().memory_mode(), MemoryMode::Levels);
    assert_eq!(parse_config(&c.to_xml(), "again.xml").unwrap(), c);
}
