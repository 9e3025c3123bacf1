//! Gives the C library (the cdylib `libjointlin.so`) its ELF SONAME,
//! `libjointlin.so.<MAJOR>`, MAJOR being `JOINTLIN_ABI_VERSION_MAJOR` of `src/ffi/mod.rs`
//! (read from there, so the SONAME and the ABI version cannot drift apart). A host linked
//! with `-ljointlin` records that name, not the bare `libjointlin.so`, and keeps loading
//! every library of the same ABI major. `make install` lays out the usual links
//! (`libjointlin.so` → `libjointlin.so.MAJOR` → `libjointlin.so.VERSION`); in cargo's own
//! output directory the Makefiles and tests add the `libjointlin.so.MAJOR` link.
use std::env;
use std::fs;

fn abi_major(source: &str) -> u32 {
    source
        .lines()
        .find_map(|l| {
            l.trim()
                .strip_prefix("pub const JOINTLIN_ABI_VERSION_MAJOR: u32 = ")?
                .strip_suffix(';')?
                .parse()
                .ok()
        })
        .expect("src/ffi/mod.rs defines `pub const JOINTLIN_ABI_VERSION_MAJOR: u32 = N;`")
}

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rerun-if-changed=src/ffi/mod.rs");
    let source = fs::read_to_string("src/ffi/mod.rs").expect("read src/ffi/mod.rs");
    let major = abi_major(&source);
    // ELF targets only (Apple's linker uses -install_name, Windows has no SONAME).
    let family = env::var("CARGO_CFG_TARGET_FAMILY").unwrap_or_default();
    let os = env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    if family.split(',').any(|f| f == "unix") && !matches!(os.as_str(), "macos" | "ios") {
        println!("cargo:rustc-cdylib-link-arg=-Wl,-soname,libjointlin.so.{major}");
    }
}
