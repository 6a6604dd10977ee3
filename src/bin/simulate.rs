fn main() {
    println!("simulate: not yet wired");
}
