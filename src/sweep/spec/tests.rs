use super::*;

fn spec(text: &str) -> Result<SweepSpec, SweepError> {
    // relative config names resolve against the crate root
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("test.toml");
    SweepSpec::parse(text, &path)
}

#[test]
fn grid_runs_in_axis_order_seed_fastest() {
    let text = r#"
        [axes]
        gesture = ["wave", "salute"]
        seed = "3-4"
        method = ["cosco-hsom", "gmr"]
        "#;
    let s = spec(text).unwrap();
    let runs = s.runs();
    let got: Vec<(&str, &str, u64)> = runs
        .iter()
        .map(|r| (r.axes.method.name(), r.axes.gesture.as_str(), r.axes.seed))
        .collect();
    let want = [
        ("cosco-hsom", "wave", 3),
        ("cosco-hsom", "wave", 4),
        ("cosco-hsom", "salute", 3),
        ("cosco-hsom", "salute", 4),
        ("gmr", "wave", 3),
        ("gmr", "wave", 4),
        ("gmr", "salute", 3),
        ("gmr", "salute", 4),
    ];
    assert_eq!(got, want);
    assert_eq!(
        runs[0].id,
        "0000-wave-s3-nao-gestures-n0.001-c4-hconfig-in-sample-cosco-hsom"
    );
    assert!(runs.iter().enumerate().all(|(i, r)| r.index == i));
    // the same spec gives the same grid
    assert_eq!(spec(text).unwrap().runs(), runs);
}

#[test]
fn height_override_builds_the_truncated_configuration() {
    let s = spec("[axes]\nheight = [\"config\", 1]\n").unwrap();
    let runs = s.runs();
    assert_eq!(runs.len(), 2);
    assert_eq!(s.config_of(&runs[1].axes).unwrap().params().height, 1);
    assert!(s.config_of(&runs[0].axes).unwrap().params().height > 1);
}

#[test]
fn identity_changes_with_an_axis_and_not_with_comments_or_the_name() {
    let a = spec("[axes]\nseed = [1, 2]\n").unwrap();
    let b = spec("# a comment\n[sweep]\nname = \"b\"\n[axes]\nseed = \"1-2\"\n").unwrap();
    let c = spec("[axes]\nseed = [1, 3]\n").unwrap();
    assert_eq!(a.hash(), b.hash());
    assert_ne!(a.hash(), c.hash());
}

#[test]
fn bad_specs_name_the_axis_and_what_is_allowed() {
    for (text, needles) in [
        ("[axes]\ncolour = [\"red\"]\n", vec!["colour", "gesture"]),
        ("[axes]\nseed = []\n", vec!["`seed` is empty"]),
        (
            "[axes]\ngesture = [\"dance\"]\n",
            vec!["'dance'", "reading-watch"],
        ),
        (
            "[axes]\nconfig = [\"nope.xml\"]\n",
            vec!["'nope.xml'", "cannot read"],
        ),
        ("[axes]\nmethod = [\"both\", \"gmr\"]\n", vec!["`both`"]),
        (
            "[axes]\nmethod = [\"svm\"]\n",
            vec!["'svm'", "cosco-hsom, gmr, both, promp, dmp"],
        ),
        (
            "[axes]\nevaluation = [\"k-fold\"]\n",
            vec!["'k-fold'", "leave-one-out"],
        ),
        ("[axes]\nnoise = [-1.0]\n", vec!["`noise`", "-1"]),
        ("[axes]\ncount = [0]\n", vec!["`count`", "1 to 100"]),
        ("[axes]\nseed = [1, 1]\n", vec!["twice"]),
        ("[axes]\nheight = [99]\n", vec!["height 99", "levels"]),
        ("[axes]\nheight = [\"tall\"]\n", vec!["'tall'", "config"]),
        (
            "[axes]\ncount = [1]\nevaluation = [\"leave-one-out\"]\n",
            vec!["at least 2"],
        ),
        (
            "[sweep]\ntransition = \"cubic\"\n[axes]\n",
            vec!["transition", "cubic"],
        ),
        ("[sweep]\nthreads = 4\n[axes]\n", vec!["threads"]),
        ("[axes\n", vec!["TOML parse error"]),
        (
            "[axes]\nrobot = [\"biped\"]\n",
            vec!["axis `robot`", "`biped`", "left-arm, upper-body"],
        ),
        (
            "[axes]\nrobot = [\"upper-body\"]\ngesture = [\"wave\"]\n",
            vec![
                "axis `gesture`",
                "'wave'",
                "upper-body",
                "wave-right, clap, welcome",
            ],
        ),
        (
            "[axes]\nrobot = [\"left-arm\", \"upper-body\"]\ngesture = [\"clap\"]\n",
            vec![
                "axis `gesture`",
                "'clap'",
                "of the left-arm",
                "reading-watch, wave",
            ],
        ),
        (
            "[axes]\nrobot = [\"upper-body\"]\nconfig = [\"configs/nao-gestures.xml\"]\n",
            vec!["`config`", "`robot`", "stateLength 6", "upper-body 14"],
        ),
        (
            "[axes]\nrobot = [\"left-arm\", \"upper-body\"]\n\
             config = [\"configs/nao-gestures.xml\"]\n",
            vec![
                "no configuration for the upper-body's 14 joints",
                "nao-upper-body.xml",
            ],
        ),
        (
            "[sweep]\nmodel = \"models/nao_left_arm.xml\"\n[axes]\n\
             robot = [\"left-arm\", \"upper-body\"]\ngesture = [\"salute\"]\n",
            vec!["[sweep] model", "one robot's"],
        ),
    ] {
        let e = spec(text).unwrap_err().to_string();
        assert!(e.contains("test.toml"), "{text}: {e}");
        for n in needles {
            assert!(e.contains(n), "{text}: '{n}' not in: {e}");
        }
    }
}

#[test]
fn the_left_arm_robot_axis_is_the_spec_without_it() {
    let without = spec("[axes]\ngesture = [\"wave\"]\nseed = [3]\n").unwrap();
    let with = spec("[axes]\nrobot = [\"left-arm\"]\ngesture = [\"wave\"]\nseed = [3]\n").unwrap();
    assert_eq!(with.hash(), without.hash());
    assert_eq!(with.runs(), without.runs());
    let json = serde_json::to_string(&with.runs()[0].axes).unwrap();
    assert!(!json.contains("robot"), "{json}");
    // the upper body is another sweep, its robot in the ids and the run files
    let ub = spec("[axes]\nrobot = [\"upper-body\"]\ngesture = [\"salute\"]\n").unwrap();
    let la = spec("[axes]\ngesture = [\"salute\"]\n").unwrap();
    assert_ne!(ub.hash(), la.hash());
    let run = &ub.runs()[0];
    assert_eq!(
        run.id,
        "0000-upper-body-salute-s1-nao-upper-body-n0.001-c4-hconfig-in-sample-both"
    );
    let json = serde_json::to_string(&run.axes).unwrap();
    assert!(json.contains(r#""robot":"upper-body""#), "{json}");
    let back: AxisValues = serde_json::from_str(&json).unwrap();
    assert_eq!(&back, &run.axes);
}

#[test]
fn each_robot_gets_its_own_default_gesture_and_configuration() {
    let ub = spec("[axes]\nrobot = [\"upper-body\"]\n").unwrap();
    let runs = ub.runs();
    assert_eq!(runs.len(), 1);
    assert_eq!(runs[0].axes.gesture, "wave-right");
    assert_eq!(runs[0].axes.config, UPPER_BODY_CONFIG);
    assert_eq!(
        ub.config_of(&runs[0].axes).unwrap().params().state_length,
        14
    );
    // both robots: the gesture both have, each robot with its configuration only
    let both = spec("[axes]\nrobot = [\"left-arm\", \"upper-body\"]\nseed = [1, 2]\n").unwrap();
    let runs = both.runs();
    let got: Vec<(Robot, &str, usize)> = runs
        .iter()
        .map(|r| {
            let width = both.config_of(&r.axes).unwrap().params().state_length;
            (r.axes.robot, r.axes.gesture.as_str(), width)
        })
        .collect();
    assert_eq!(
        got,
        [
            (Robot::LeftArm, "reading-watch", 6),
            (Robot::LeftArm, "reading-watch", 6),
            (Robot::UpperBody, "reading-watch", 14),
            (Robot::UpperBody, "reading-watch", 14),
        ]
    );
    // a config axis of both widths: still a robot with its own width only
    let text = "[axes]\nrobot = [\"left-arm\", \"upper-body\"]\ngesture = [\"salute\"]\n\
                config = [\"configs/nao-gestures.xml\", \"configs/nao-upper-body.xml\", \
                \"configs/table1.xml\"]\n";
    let runs = spec(text).unwrap().runs();
    let got: Vec<(Robot, &str)> = runs
        .iter()
        .map(|r| (r.axes.robot, r.axes.config.as_str()))
        .collect();
    assert_eq!(
        got,
        [
            (Robot::LeftArm, "configs/nao-gestures.xml"),
            (Robot::LeftArm, "configs/table1.xml"),
            (Robot::UpperBody, "configs/nao-upper-body.xml"),
        ]
    );
}
