//! A model file's bytes by part (`Hsom::file_parts`), the table of docs/BENCHMARKS.md
//! ("Model size"): `COSCO_MODEL=out/model.bin cargo test --release --test model_size --
//! --ignored --nocapture` prints it for `simulate`'s model.

use std::path::Path;

use cosco_hsom::hsom::Hsom;

/// The breakdown of the model in `COSCO_MODEL` as a Markdown table, checked to add up to the
/// file's length.
#[test]
#[ignore = "prints the table for a model file named by COSCO_MODEL"]
fn print_the_model_file_by_part() {
    let path = std::env::var("COSCO_MODEL").expect("COSCO_MODEL=path/to/model.bin");
    let bytes = std::fs::read(&path).unwrap();
    let model = Hsom::load(Path::new(&path)).unwrap();
    let parts = model.file_parts();
    let total: usize = parts.iter().map(|p| p.bytes).sum();
    assert_eq!(total, bytes.len());
    let weights: usize = model.maps().iter().map(|m| m.all_weights().len()).sum();
    println!("{path}: {} bytes, {weights} weights\n", bytes.len());
    println!("| part | bytes |\n|---|---|");
    for p in &parts {
        println!("| {} | {} |", p.part, p.bytes);
    }
    println!("| **total** | {total} |");
    println!(
        "\ntraced chunks' ceiling (every node with all its chunks): {} bytes",
        model.traced_ceiling()
    );
}
