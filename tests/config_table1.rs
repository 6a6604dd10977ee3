//! The XML configuration: Table I, round trip, and one test per bad input.

use std::path::Path;

use cosco_hsom::config::{
    load_config, parse_config, Algorithm, ConfigError, HsomParams, ListUpdate, Reflex,
    ReproductionMode, Timing,
};
use cosco_hsom::som::Topology;

fn table1_text() -> String {
    std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/configs/successor-table.xml"),
    )
    .unwrap()
}

#[test]
fn recommended_configuration_uses_the_events_extension() {
    let c = load_config(&Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/nao-gestures.xml"))
        .unwrap();
    assert_eq!(c.params().algorithm, Algorithm::Events);
    let again = parse_config(&c.to_xml(), "again.xml").unwrap();
    assert_eq!(c.params(), again.params());
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
    assert_invalid(
        parse_config(&levels, "bad.xml").unwrap_err(),
        "memoryMode",
        "levels",
    );
}

#[test]
fn unknown_algorithm_is_refused() {
    let t = table1_text().replacen(
        "<seed>1</seed>",
        "<seed>1</seed><algorithm>magic</algorithm>",
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
        (p.height, p.memory, p.update_period, p.training_steps),
        (6, 4, 2, 5000)
    );
    assert_eq!((p.state_length, p.action_length), (6, 6));
    let expect = [(16, 0.1), (10, 0.2), (8, 0.3), (6, 0.5), (2, 0.6), (1, 0.8)];
    for (l, &(n, a)) in p.levels.iter().zip(&expect) {
        assert_eq!((l.rows, l.cols), (n, n));
        assert_eq!(l.learning_factor.initial, a);
        assert_eq!(l.topology, Topology::Orthogonal);
    }
    // the file is the paper taken literally: the built-in Table I with the paper's own
    // output (the node's action half, open loop) and nothing beyond the paper switched on
    let mut b = HsomParams::table1();
    b.reproduction.continuity = 0.0;
    b.reproduction.closed_loop = false;
    assert_eq!(p, b.check("x").unwrap().params());
    assert_eq!(p.algorithm, Algorithm::Paper);
    assert_eq!(p.list_update, ListUpdate::EveryStep);
    assert_eq!(p.reproduction.mode, ReproductionMode::Literal);
    assert_eq!(p.reproduction.reflex, Reflex::Bmu);
    assert_eq!(p.reproduction.timing, Timing::Step);
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
            assert_eq!(*line, 8);
            assert!(*column > 1);
        }
        other => panic!("{other:?}"),
    }
    assert!(e.to_string().starts_with("bad.xml:8:"), "{e}");
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
fn invalid_missing_memory() {
    let e = err(&replace("<memory>4</memory>", ""));
    assert!(
        matches!(&e, ConfigError::Missing { field, .. } if field == "memory"),
        "{e:?}"
    );
    assert!(e.to_string().contains("bad.xml") && e.to_string().contains("memory"));
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

#[test]
fn new_options_parse_and_bad_values_are_named() {
    let t = table1_text();
    for (from, to, field) in [
        ("<changeRatio>0.6<", "<changeRatio>0<", "changeRatio"),
        ("<changeRatio>0.6<", "<changeRatio>1.5<", "changeRatio"),
        ("<actionHorizon>10<", "<actionHorizon>0<", "actionHorizon"),
        (
            "<listUpdate>onChange<",
            "<listUpdate>sometimes<",
            "listUpdate",
        ),
        ("<timing>speed<", "<timing>fast<", "reproduction/timing"),
        ("<reflex>successor<", "<reflex>jump<", "reproduction/reflex"),
        (
            "<minAccuracy>0.2<",
            "<minAccuracy>2<",
            "reproduction/minAccuracy",
        ),
        (
            "<loopWindow>24<",
            "<loopWindow>0<",
            "reproduction/loopWindow",
        ),
    ] {
        assert!(t.contains(from), "{from}");
        match err(&t.replacen(from, to, 1)) {
            ConfigError::Invalid { field: f, .. } => assert_eq!(f, field),
            e => panic!("{to}: {e}"),
        }
    }
    // every word is accepted, case-insensitively
    for (from, to) in [
        ("<listUpdate>onChange<", "<listUpdate>EVERYSTEP<"),
        ("<timing>speed<", "<timing>dwell<"),
        ("<timing>speed<", "<timing>step<"),
        ("<reflex>successor<", "<reflex>bmu<"),
    ] {
        let c = parse_config(&t.replacen(from, to, 1), "ok.xml").unwrap();
        let again = parse_config(&c.to_xml(), "again.xml").unwrap();
        assert_eq!(c.params(), again.params());
    }
}

#[test]
fn consensus_weighing_parses_round_trips_and_names_bad_values() {
    let t = std::fs::read_to_string("configs/nao-gestures.xml").unwrap();
    let default = parse_config(&t, "nao-gestures.xml").unwrap();
    assert_eq!(
        default.params().consensus,
        cosco_hsom::config::Consensus::Start
    );
    let with = |word: &str| {
        t.replacen(
            "<normalisation>global</normalisation>",
            &format!("<normalisation>global</normalisation><consensus>{word}</consensus>"),
            1,
        )
    };
    for (word, expected) in [
        ("local", cosco_hsom::config::Consensus::Local),
        ("LOCAL", cosco_hsom::config::Consensus::Local),
        ("all", cosco_hsom::config::Consensus::All),
        ("Start", cosco_hsom::config::Consensus::Start),
    ] {
        let c = parse_config(&with(word), "ok.xml").unwrap();
        assert_eq!(c.params().consensus, expected);
        let again = parse_config(&c.to_xml(), "again.xml").unwrap();
        assert_eq!(c.params(), again.params());
    }
    match err(&with("nearest")) {
        ConfigError::Invalid { field, reason, .. } => {
            assert_eq!(field, "consensus");
            assert!(reason.contains("all, local, start"), "{reason}");
        }
        e => panic!("{e}"),
    }
}

#[test]
fn alignment_parses_round_trips_and_names_bad_values() {
    use cosco_hsom::config::Alignment;
    let t = std::fs::read_to_string("tests/configs/decoded-plan.xml").unwrap();
    // not written there: the default
    assert!(!t.contains("<alignment>"));
    let default = parse_config(&t, "decoded-plan.xml").unwrap();
    assert_eq!(default.params().alignment, Alignment::Stepped);
    let with = |word: &str| {
        t.replacen(
            "<normalisation>global</normalisation>",
            &format!("<normalisation>global</normalisation><alignment>{word}</alignment>"),
            1,
        )
    };
    for (word, expected) in [
        ("smooth", Alignment::Smooth),
        ("Smooth", Alignment::Smooth),
        ("STEPPED", Alignment::Stepped),
    ] {
        let c = parse_config(&with(word), "ok.xml").unwrap();
        assert_eq!(c.params().alignment, expected);
        let again = parse_config(&c.to_xml(), "again.xml").unwrap();
        assert_eq!(c.params(), again.params());
    }
    match err(&with("linear")) {
        ConfigError::Invalid {
            field,
            value,
            reason,
            ..
        } => {
            assert_eq!((field.as_str(), value.as_str()), ("alignment", "linear"));
            assert!(reason.contains("stepped, smooth"), "{reason}");
        }
        e => panic!("{e}"),
    }
}

#[test]
fn plan_parses_round_trips_and_names_bad_values() {
    use cosco_hsom::config::Plan;
    let t = std::fs::read_to_string("tests/configs/decoded-plan.xml").unwrap();
    let default = parse_config(&t, "decoded-plan.xml").unwrap();
    assert_eq!(default.params().plan, Plan::Decoded);
    // not written there: the default
    let bare = t.replacen("<plan>decoded</plan>", "", 1);
    assert_eq!(
        parse_config(&bare, "bare.xml").unwrap().params().plan,
        Plan::Decoded
    );
    for (word, expected) in [
        ("traced", Plan::Traced),
        ("Traced", Plan::Traced),
        ("DECODED", Plan::Decoded),
    ] {
        let written = format!("<plan>{word}</plan>");
        let c = parse_config(&t.replacen("<plan>decoded</plan>", &written, 1), "ok.xml").unwrap();
        assert_eq!(c.params().plan, expected);
        let again = parse_config(&c.to_xml(), "again.xml").unwrap();
        assert_eq!(c.params(), again.params());
    }
    match err(&t.replacen("<plan>decoded</plan>", "<plan>replayed</plan>", 1)) {
        ConfigError::Invalid { field, reason, .. } => {
            assert_eq!(field, "plan");
            assert!(reason.contains("traced, decoded"), "{reason}");
        }
        e => panic!("{e}"),
    }
}

/// tests/configs/traced-finer-events.xml, measured beside the recommended configuration in
/// docs/CONFIG.md (`changeRatio`, `knots`), is that configuration with exactly `changeRatio`
/// and `knots` changed: the comparison it documents stays one of two settings.
#[test]
fn the_finer_events_configuration_is_the_recommended_one_with_two_settings_changed() {
    use cosco_hsom::config::{Alignment, Knots, Plan};
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let rec = load_config(&root.join("configs/nao-gestures.xml"))
        .unwrap()
        .into_params();
    let fine = load_config(&root.join("tests/configs/traced-finer-events.xml"))
        .unwrap()
        .into_params();
    assert_eq!(
        (rec.plan, rec.change_ratio, rec.alignment, rec.knots),
        (Plan::Traced, 0.6, Alignment::Smooth, Knots::Halves)
    );
    assert_eq!(
        (fine.plan, fine.change_ratio, fine.alignment, fine.knots),
        (Plan::Traced, 0.8, Alignment::Smooth, Knots::Event)
    );
    let mut same = fine.clone();
    same.change_ratio = rec.change_ratio;
    same.knots = rec.knots;
    assert_eq!(same, rec);
}

/// tests/configs/decoded-plan.xml, the recommended configuration up to the nineteenth
/// session, is today's with exactly `plan`, `alignment` and `knots` at their defaults: its
/// bottom events, and so recognition, are the recommended configuration's.
#[test]
fn the_decoded_plan_configuration_is_the_recommended_one_with_three_settings_changed() {
    use cosco_hsom::config::{Alignment, Knots, Plan};
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let rec = load_config(&root.join("configs/nao-gestures.xml"))
        .unwrap()
        .into_params();
    let decoded = load_config(&root.join("tests/configs/decoded-plan.xml"))
        .unwrap()
        .into_params();
    assert_eq!(
        (rec.plan, rec.alignment, rec.knots),
        (Plan::Traced, Alignment::Smooth, Knots::Halves)
    );
    assert_eq!(
        (decoded.plan, decoded.alignment, decoded.knots),
        (Plan::Decoded, Alignment::Stepped, Knots::Event)
    );
    assert_eq!(decoded.change_ratio, rec.change_ratio);
    let mut same = decoded.clone();
    same.plan = rec.plan;
    same.alignment = rec.alignment;
    same.knots = rec.knots;
    assert_eq!(same, rec);
}

#[test]
fn knots_parse_round_trip_and_name_bad_values() {
    use cosco_hsom::config::Knots;
    let t = std::fs::read_to_string("tests/configs/decoded-plan.xml").unwrap();
    // not written there: the default
    assert!(!t.contains("<knots>"));
    assert_eq!(
        parse_config(&t, "decoded-plan.xml").unwrap().params().knots,
        Knots::Event
    );
    let with = |word: &str| {
        t.replacen(
            "<normalisation>global</normalisation>",
            &format!("<normalisation>global</normalisation><knots>{word}</knots>"),
            1,
        )
    };
    for (word, expected) in [
        ("halves", Knots::Halves),
        ("Halves", Knots::Halves),
        ("EVENT", Knots::Event),
    ] {
        let c = parse_config(&with(word), "ok.xml").unwrap();
        assert_eq!(c.params().knots, expected);
        assert_eq!(word.parse::<Knots>().unwrap(), expected);
        let again = parse_config(&c.to_xml(), "again.xml").unwrap();
        assert_eq!(c.params(), again.params());
    }
    assert!("thirds"
        .parse::<Knots>()
        .unwrap_err()
        .contains("event, halves"));
    match err(&with("thirds")) {
        ConfigError::Invalid {
            field,
            value,
            reason,
            ..
        } => {
            assert_eq!((field.as_str(), value.as_str()), ("knots", "thirds"));
            assert!(reason.contains("event, halves"), "{reason}");
        }
        e => panic!("{e}"),
    }
}
