fn main() {
    println!("jointlin harness: under construction");
}
