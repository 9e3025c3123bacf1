//! The `jointlin` command-line host. Placeholder until the CLI is written; the FE
//! foundation lives in the library (`jointlin_harness`).

fn main() {
    println!(
        "jointlin harness {}: FE foundation only, no CLI yet",
        env!("CARGO_PKG_VERSION")
    );
}
