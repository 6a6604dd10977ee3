fn main() {
    println!("cosco: not yet wired");
}
