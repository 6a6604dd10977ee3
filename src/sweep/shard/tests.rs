use super::*;

#[test]
fn shards_partition_the_grid_exactly_once() {
    for count in 1..=5 {
        let shards: Vec<Shard> = (0..count)
            .map(|i| Shard::new(i, count, "test").unwrap())
            .collect();
        for index in 0..23 {
            let owners = shards.iter().filter(|s| s.contains(index)).count();
            assert_eq!(owners, 1, "run {index} with {count} shards");
        }
    }
}

#[test]
fn parse_and_range_errors() {
    assert_eq!(Shard::parse("1/3").unwrap(), Shard { index: 1, count: 3 });
    let e = Shard::parse("2/2").unwrap_err().to_string();
    assert!(e.contains("out of range") && e.contains("0 to 1"), "{e}");
    assert!(Shard::parse("0/0")
        .unwrap_err()
        .to_string()
        .contains("at least 1"));
    assert!(Shard::parse("a/2").unwrap_err().to_string().contains("I/N"));
    assert!(Shard::parse("1").unwrap_err().to_string().contains("I/N"));
}

#[test]
fn slurm_variables_choose_the_shard() {
    let env = |pairs: &'static [(&'static str, &'static str)]| {
        move |k: &str| {
            pairs
                .iter()
                .find(|(n, _)| *n == k)
                .map(|(_, v)| v.to_string())
        }
    };
    assert_eq!(Shard::from_slurm(env(&[])).unwrap(), None);
    assert_eq!(
        Shard::from_slurm(env(&[
            ("SLURM_ARRAY_TASK_ID", "3"),
            ("SLURM_ARRAY_TASK_COUNT", "4")
        ]))
        .unwrap(),
        Some(Shard { index: 3, count: 4 })
    );
    assert_eq!(
        Shard::from_slurm(env(&[
            ("SLURM_ARRAY_TASK_ID", "4"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_COUNT", "4")
        ]))
        .unwrap(),
        Some(Shard { index: 3, count: 4 })
    );
    let e = Shard::from_slurm(env(&[
        ("SLURM_ARRAY_TASK_ID", "4"),
        ("SLURM_ARRAY_TASK_COUNT", "4"),
    ]))
    .unwrap_err()
    .to_string();
    assert!(e.contains("out of range"), "{e}");
}
