//! The three-layer stack decks against CalculiX (validate::stack_deck): first bending
//! frequencies of `jointlin modes` on the same deck with `*TIE`, with `*CONTACT PAIR`
//! stuck (large μ, k_T0) and sliding (k_T0 → 0), against ccx's `*FREQUENCY` on the
//! `*TIE` deck and on one layer alone. Prints a Markdown table; `--write DIR` only
//! writes the decks.

use std::path::PathBuf;

use jointlin_harness::validate::deck_ccx::{comparison, write_decks};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let [flag, dir] = args.as_slice() {
        if flag == "--write" {
            match write_decks(&PathBuf::from(dir)) {
                Ok(files) => files.iter().for_each(|f| println!("{}", f.display())),
                Err(e) => {
                    eprintln!("error: {e}");
                    std::process::exit(1);
                }
            }
            return;
        }
    }
    let dir = std::env::temp_dir().join(format!("jointlin-deck-stack-{}", std::process::id()));
    let r = comparison(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    match r {
        Ok(c) => print!("{}", c.markdown()),
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}
