//! Links SuiteSparse UMFPACK (Debian: `libsuitesparse-dev`), whose `umfpack_zl_*`
//! functions `src/solve/umfpack/ffi.rs` declares itself (UMFPACK pulls in AMD, CHOLMOD
//! and BLAS through its own shared-library dependencies), and ARPACK-NG (Debian:
//! `libarpack2-dev`), whose `dsaupd_c`/`dseupd_c` `src/solve/arpack/ffi.rs` declares;
//! compiles `src/solve/cholmod/shim.c` against CHOLMOD's header (the `cc` crate: the
//! compiler and flags cargo's target asks for) and links CHOLMOD.
fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rustc-link-lib=umfpack");
    println!("cargo:rustc-link-lib=arpack");
    println!("cargo:rerun-if-changed=src/solve/cholmod/shim.c");
    cc::Build::new()
        .file("src/solve/cholmod/shim.c")
        .include("/usr/include/suitesparse")
        .warnings(true)
        .compile("jointlin_cholmod_shim");
    println!("cargo:rustc-link-lib=cholmod");
}
