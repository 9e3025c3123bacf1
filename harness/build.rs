//! Links SuiteSparse UMFPACK (Debian: `libsuitesparse-dev`), whose `umfpack_zl_*`
//! functions `src/solve/umfpack/ffi.rs` declares itself. UMFPACK pulls in AMD, CHOLMOD
//! and BLAS through its own shared-library dependencies.
fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    println!("cargo:rustc-link-lib=umfpack");
}
