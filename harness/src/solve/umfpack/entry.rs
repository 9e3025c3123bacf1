//! The matrix entry types UMFPACK factors: `f64` through the real `umfpack_dl_*`
//! functions, `Complex<f64>` through the complex `umfpack_zl_*` ones (packed: the z
//! pointers NULL, values as (re, im) pairs, num-complex's `#[repr(C)]` layout). A real
//! matrix factored as real costs about a quarter of the flops of the same matrix as
//! complex.

use std::ffi::c_void;
use std::ptr;

use nalgebra::Complex;

use super::ffi;

/// An entry type with its UMFPACK functions. Sealed: only `f64` and `Complex<f64>`.
pub trait Entry: Copy + Default + Send + Sync + private::Sealed + 'static {
    /// The names of the symbolic, numeric and solve functions, for messages.
    const CALLS: Calls;
    /// Both parts finite.
    fn finite(&self) -> bool;
    /// umfpack_*_symbolic on the pattern alone (values NULL).
    ///
    /// # Safety
    /// `ap` has n+1 and `ai` `ap[n]` entries; `control` UMFPACK_CONTROL, `info`
    /// UMFPACK_INFO doubles.
    unsafe fn symbolic(
        n: i64,
        ap: *const i64,
        ai: *const i64,
        out: *mut *mut c_void,
        control: *const f64,
        info: *mut f64,
    ) -> i64;
    /// umfpack_*_numeric.
    ///
    /// # Safety
    /// As [`Entry::symbolic`]; `ax` holds `ap[n]` entries; `symbolic` from this family.
    unsafe fn numeric(
        ap: *const i64,
        ai: *const i64,
        ax: *const Self,
        symbolic: *mut c_void,
        out: *mut *mut c_void,
        control: *const f64,
        info: *mut f64,
    ) -> i64;
    /// umfpack_*_solve of the system `sys` (`ffi::UMFPACK_A`: A x = b,
    /// `ffi::UMFPACK_AT`: Aᴴ x = b).
    ///
    /// # Safety
    /// As [`Entry::numeric`]; `x` and `b` hold n entries; `numeric` from this family.
    #[allow(clippy::too_many_arguments)]
    unsafe fn solve(
        sys: i64,
        ap: *const i64,
        ai: *const i64,
        ax: *const Self,
        x: *mut Self,
        b: *const Self,
        numeric: *mut c_void,
        control: *const f64,
        info: *mut f64,
    ) -> i64;
    /// # Safety
    /// `p` points to a Symbolic object of this family (freed once).
    unsafe fn free_symbolic(p: *mut *mut c_void);
    /// # Safety
    /// `p` points to a Numeric object of this family (freed once).
    unsafe fn free_numeric(p: *mut *mut c_void);
}

/// Function names of one UMFPACK family.
pub struct Calls {
    pub symbolic: &'static str,
    pub numeric: &'static str,
    pub solve: &'static str,
}

mod private {
    pub trait Sealed {}
    impl Sealed for f64 {}
    impl Sealed for nalgebra::Complex<f64> {}
}

impl Entry for f64 {
    const CALLS: Calls = Calls {
        symbolic: "umfpack_dl_symbolic",
        numeric: "umfpack_dl_numeric",
        solve: "umfpack_dl_solve",
    };
    fn finite(&self) -> bool {
        self.is_finite()
    }
    unsafe fn symbolic(
        n: i64,
        ap: *const i64,
        ai: *const i64,
        out: *mut *mut c_void,
        control: *const f64,
        info: *mut f64,
    ) -> i64 {
        ffi::umfpack_dl_symbolic(n, n, ap, ai, ptr::null(), out, control, info)
    }
    unsafe fn numeric(
        ap: *const i64,
        ai: *const i64,
        ax: *const Self,
        symbolic: *mut c_void,
        out: *mut *mut c_void,
        control: *const f64,
        info: *mut f64,
    ) -> i64 {
        ffi::umfpack_dl_numeric(ap, ai, ax, symbolic, out, control, info)
    }
    unsafe fn solve(
        sys: i64,
        ap: *const i64,
        ai: *const i64,
        ax: *const Self,
        x: *mut Self,
        b: *const Self,
        numeric: *mut c_void,
        control: *const f64,
        info: *mut f64,
    ) -> i64 {
        ffi::umfpack_dl_solve(sys, ap, ai, ax, x, b, numeric, control, info)
    }
    unsafe fn free_symbolic(p: *mut *mut c_void) {
        ffi::umfpack_dl_free_symbolic(p)
    }
    unsafe fn free_numeric(p: *mut *mut c_void) {
        ffi::umfpack_dl_free_numeric(p)
    }
}

impl Entry for Complex<f64> {
    const CALLS: Calls = Calls {
        symbolic: "umfpack_zl_symbolic",
        numeric: "umfpack_zl_numeric",
        solve: "umfpack_zl_solve",
    };
    fn finite(&self) -> bool {
        self.re.is_finite() && self.im.is_finite()
    }
    unsafe fn symbolic(
        n: i64,
        ap: *const i64,
        ai: *const i64,
        out: *mut *mut c_void,
        control: *const f64,
        info: *mut f64,
    ) -> i64 {
        ffi::umfpack_zl_symbolic(n, n, ap, ai, ptr::null(), ptr::null(), out, control, info)
    }
    unsafe fn numeric(
        ap: *const i64,
        ai: *const i64,
        ax: *const Self,
        symbolic: *mut c_void,
        out: *mut *mut c_void,
        control: *const f64,
        info: *mut f64,
    ) -> i64 {
        ffi::umfpack_zl_numeric(
            ap,
            ai,
            ax as *const f64,
            ptr::null(),
            symbolic,
            out,
            control,
            info,
        )
    }
    unsafe fn solve(
        sys: i64,
        ap: *const i64,
        ai: *const i64,
        ax: *const Self,
        x: *mut Self,
        b: *const Self,
        numeric: *mut c_void,
        control: *const f64,
        info: *mut f64,
    ) -> i64 {
        ffi::umfpack_zl_solve(
            sys,
            ap,
            ai,
            ax as *const f64,
            ptr::null(),
            x as *mut f64,
            ptr::null_mut(),
            b as *const f64,
            ptr::null(),
            numeric,
            control,
            info,
        )
    }
    unsafe fn free_symbolic(p: *mut *mut c_void) {
        ffi::umfpack_zl_free_symbolic(p)
    }
    unsafe fn free_numeric(p: *mut *mut c_void) {
        ffi::umfpack_zl_free_numeric(p)
    }
}
