//! Raw declarations of the `umfpack_zl_*` (complex) and `umfpack_dl_*` (real) functions
//! the wrapper uses, from
//! `/usr/include/suitesparse/umfpack.h` (SuiteSparse_long is `long` on LP64 Linux,
//! `__int64` on Win64: 64 bits either way). Only [`super`] calls them.

use std::ffi::c_void;

pub const UMFPACK_CONTROL: usize = 20;
pub const UMFPACK_INFO: usize = 90;
/// Control index of the ordering strategy, and its symmetric value.
pub const UMFPACK_STRATEGY: usize = 5;
pub const UMFPACK_STRATEGY_SYMMETRIC: f64 = 3.0;
/// Info index of the strategy the symbolic analysis used.
pub const UMFPACK_STRATEGY_USED: usize = 18;
/// Control index of the fill-reducing ordering, and its value "try AMD, METIS and
/// nested dissection, keep the one with the least fill".
pub const UMFPACK_ORDERING: usize = 10;
pub const UMFPACK_ORDERING_BEST: f64 = 4.0;
/// Info index of the estimated reciprocal condition number.
pub const UMFPACK_RCOND: usize = 67;
/// Solve A x = b.
pub const UMFPACK_A: i64 = 0;
/// Solve Aᴴ x = b (the conjugate transpose; Aᵀ for a real matrix).
pub const UMFPACK_AT: i64 = 1;
/// Control index: maximum iterative-refinement steps per solve (default 2).
pub const UMFPACK_IRSTEP: usize = 7;

// Linked by build.rs (cargo:rustc-link-lib=umfpack).
extern "C" {
    pub fn umfpack_zl_defaults(control: *mut f64);
    pub fn umfpack_zl_symbolic(
        n_row: i64,
        n_col: i64,
        ap: *const i64,
        ai: *const i64,
        ax: *const f64,
        az: *const f64,
        symbolic: *mut *mut c_void,
        control: *const f64,
        info: *mut f64,
    ) -> i64;
    pub fn umfpack_zl_numeric(
        ap: *const i64,
        ai: *const i64,
        ax: *const f64,
        az: *const f64,
        symbolic: *mut c_void,
        numeric: *mut *mut c_void,
        control: *const f64,
        info: *mut f64,
    ) -> i64;
    #[allow(clippy::too_many_arguments)]
    pub fn umfpack_zl_solve(
        sys: i64,
        ap: *const i64,
        ai: *const i64,
        ax: *const f64,
        az: *const f64,
        xx: *mut f64,
        xz: *mut f64,
        bx: *const f64,
        bz: *const f64,
        numeric: *mut c_void,
        control: *const f64,
        info: *mut f64,
    ) -> i64;
    pub fn umfpack_zl_free_symbolic(symbolic: *mut *mut c_void);
    pub fn umfpack_zl_free_numeric(numeric: *mut *mut c_void);
    pub fn umfpack_dl_symbolic(
        n_row: i64,
        n_col: i64,
        ap: *const i64,
        ai: *const i64,
        ax: *const f64,
        symbolic: *mut *mut c_void,
        control: *const f64,
        info: *mut f64,
    ) -> i64;
    pub fn umfpack_dl_numeric(
        ap: *const i64,
        ai: *const i64,
        ax: *const f64,
        symbolic: *mut c_void,
        numeric: *mut *mut c_void,
        control: *const f64,
        info: *mut f64,
    ) -> i64;
    #[allow(clippy::too_many_arguments)]
    pub fn umfpack_dl_solve(
        sys: i64,
        ap: *const i64,
        ai: *const i64,
        ax: *const f64,
        xx: *mut f64,
        bx: *const f64,
        numeric: *mut c_void,
        control: *const f64,
        info: *mut f64,
    ) -> i64;
    pub fn umfpack_dl_free_symbolic(symbolic: *mut *mut c_void);
    pub fn umfpack_dl_free_numeric(numeric: *mut *mut c_void);
}
