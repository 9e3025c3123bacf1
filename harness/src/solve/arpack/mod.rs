//! Shift-invert Lanczos for K φ = λ M φ through ARPACK (ARPACK-NG's `dsaupd`/`dseupd`,
//! the implicitly restarted Lanczos method CalculiX's `*FREQUENCY` uses), driven by
//! reverse communication: ARPACK asks for products, the caller's closures give them.
//!
//! Mode 3 (shift-invert, `bmat = "G"`): ARPACK runs Lanczos on OP = (K − σM)⁻¹ M in the
//! M inner product and returns the eigenvalues θ of OP of largest magnitude as
//! λ = σ + 1/θ — the λ nearest σ — with M-orthonormal vectors. M may be semidefinite
//! (massless DOFs map to θ = 0, never among the wanted ones).
//!
//! ARPACK keeps state in Fortran SAVE variables: it is not reentrant, so every run holds
//! one process-wide lock ([`ARPACK_LOCK`]) from the first `dsaupd` to the last `dseupd`.

use std::ffi::c_int;
use std::sync::Mutex;

use thiserror::Error;

mod ffi;

/// Serializes ARPACK runs (see the module doc).
static ARPACK_LOCK: Mutex<()> = Mutex::new(());

/// Errors of [`shift_invert`]; `E` is the error of the caller's solve.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum LanczosError<E: std::error::Error + 'static> {
    #[error(transparent)]
    Solve(E),
    #[error(
        "the Lanczos iteration converged {converged} of {wanted} eigenpairs in {restarts} restarts"
    )]
    NotConverged {
        converged: usize,
        wanted: usize,
        restarts: usize,
    },
    #[error("ARPACK {call} returned info = {info} ({meaning})")]
    Arpack {
        call: &'static str,
        info: i32,
        meaning: &'static str,
    },
    #[error("{n} DOFs is beyond ARPACK's 32-bit index range")]
    TooLarge { n: usize },
}

/// What [`shift_invert`] found.
#[derive(Debug, Clone)]
pub struct Lanczos {
    /// The `nev` eigenvalues λ nearest σ, ascending, (rad/time)².
    pub eigenvalues: Vec<f64>,
    /// Their vectors, M-orthonormal, length n each.
    pub vectors: Vec<Vec<f64>>,
    /// Implicit restarts ARPACK used.
    pub restarts: usize,
    /// Products with OP = (K − σM)⁻¹ M, i.e. solves with the factorization.
    pub solves: usize,
}

/// The meaning of a negative or special `info` of dsaupd/dseupd (ARPACK's dsaupd.f).
fn info_meaning(info: i32) -> &'static str {
    match info {
        1 => "maximum number of restarts taken",
        3 => "no shifts could be applied: the Krylov space is too small",
        -1 => "n not positive",
        -2 => "nev not positive",
        -3 => "ncv not in nev < ncv <= n",
        -4 => "maximum iterations not positive",
        -7 => "workspace too small",
        -8 => "tridiagonal eigenvalue computation failed",
        -9 => "starting vector is zero",
        -14 => "dsaupd found no converged Ritz value",
        -9999 => "no Lanczos factorization could be built",
        _ => "see ARPACK's dsaupd.f",
    }
}

/// Lanczos basis size for `nev` wanted pairs of an n-DOF problem: ARPACK's advice of at
/// least 2·nev, and 20 more than nev for few modes (fewer restarts), at most n.
pub fn basis_size(nev: usize, n: usize) -> usize {
    (2 * nev + 1).max(nev + 20).min(n)
}

/// The `nev` eigenpairs of K φ = λ M φ nearest `sigma` (0 < nev < n).
///
/// `solve(b, x)` sets x = (K − σM)⁻¹ b; `mass(x, y)` sets y = M x. `tol` is ARPACK's
/// relative accuracy of the Ritz values of OP (0: machine precision); `start` (length
/// n, not zero) is the first Lanczos vector, so results are deterministic.
pub fn shift_invert<E: std::error::Error + 'static>(
    nev: usize,
    sigma: f64,
    tol: f64,
    max_restarts: usize,
    start: &[f64],
    mut solve: impl FnMut(&[f64], &mut [f64]) -> Result<(), E>,
    mut mass: impl FnMut(&[f64], &mut [f64]),
) -> Result<Lanczos, LanczosError<E>> {
    let n = start.len();
    let mut w = Workspace::new(nev, start, max_restarts).ok_or(LanczosError::TooLarge { n })?;
    let mut ido: c_int = 0;
    let mut info: c_int = 1; // resid holds the start vector
    let mut solves = 0;
    let mut scratch = vec![0.0; n];

    let _guard = ARPACK_LOCK.lock().unwrap_or_else(|e| e.into_inner());
    loop {
        w.saupd(&mut ido, tol, &mut info);
        // ipntr holds 1-based offsets into workd of the operands ARPACK asks about.
        let at = |k: usize| (w.ipntr[k] - 1) as usize;
        let workd = &mut w.workd;
        match ido {
            -1 => {
                // y = OP x = (K − σM)⁻¹ M x.
                let (x, y) = (at(0), at(1));
                mass(&workd[x..x + n], &mut scratch);
                solve(&scratch, &mut workd[y..y + n]).map_err(LanczosError::Solve)?;
                solves += 1;
            }
            1 => {
                // y = (K − σM)⁻¹ (M x), M x given.
                let (bx, y) = (at(2), at(1));
                scratch.copy_from_slice(&workd[bx..bx + n]);
                solve(&scratch, &mut workd[y..y + n]).map_err(LanczosError::Solve)?;
                solves += 1;
            }
            2 => {
                let (x, y) = (at(0), at(1));
                scratch.copy_from_slice(&workd[x..x + n]);
                mass(&scratch, &mut workd[y..y + n]);
            }
            _ => break,
        }
    }
    let restarts = w.iparam[2].max(0) as usize;
    let converged = w.iparam[4].max(0) as usize;
    match info {
        0 => {}
        1 => {
            return Err(LanczosError::NotConverged {
                converged,
                wanted: nev,
                restarts,
            })
        }
        _ => {
            return Err(LanczosError::Arpack {
                call: "dsaupd",
                info,
                meaning: info_meaning(info),
            })
        }
    }
    let (d, z) = w.eupd(sigma, tol)?;
    let mut order: Vec<usize> = (0..nev).collect();
    order.sort_by(|&a, &b| d[a].total_cmp(&d[b]));
    Ok(Lanczos {
        eigenvalues: order.iter().map(|&i| d[i]).collect(),
        vectors: order
            .iter()
            .map(|&i| z[i * n..(i + 1) * n].to_vec())
            .collect(),
        restarts,
        solves,
    })
}

/// ARPACK's arrays for one run, of the lengths dsaupd.f documents for n, nev and ncv
/// (resid n, v n·ncv with ldv = n, iparam/ipntr 11, workd 3n, workl ncv(ncv + 8)).
struct Workspace {
    n: c_int,
    nev: c_int,
    ncv: c_int,
    lworkl: c_int,
    resid: Vec<f64>,
    v: Vec<f64>,
    workd: Vec<f64>,
    workl: Vec<f64>,
    iparam: [c_int; 11],
    ipntr: [c_int; 11],
}

impl Workspace {
    /// The arrays for `nev` pairs from the first Lanczos vector `start`, exact shifts,
    /// shift-invert of the generalized problem; None beyond 32-bit indices.
    fn new(nev: usize, start: &[f64], max_restarts: usize) -> Option<Self> {
        let n = start.len();
        let ncv = basis_size(nev, n);
        let lworkl = ncv * (ncv + 8);
        let int = |v: usize| c_int::try_from(v).ok();
        let mut iparam = [0 as c_int; 11];
        iparam[0] = 1; // exact shifts
        iparam[2] = int(max_restarts.max(1))?;
        iparam[6] = 3; // shift-invert, generalized
        Some(Workspace {
            n: int(n)?,
            nev: int(nev)?,
            ncv: int(ncv)?,
            lworkl: int(lworkl)?,
            resid: start.to_vec(),
            v: vec![0.0; n * ncv],
            workd: vec![0.0; 3 * n],
            workl: vec![0.0; lworkl],
            iparam,
            ipntr: [0; 11],
        })
    }

    /// One reverse-communication call of dsaupd.
    fn saupd(&mut self, ido: &mut c_int, tol: f64, info: &mut c_int) {
        // SAFETY: every array has the length dsaupd.f documents ([`Workspace`]); strings
        // are NUL-terminated; the caller holds ARPACK_LOCK for the whole run.
        unsafe {
            ffi::dsaupd_c(
                ido,
                BMAT.as_ptr(),
                self.n,
                WHICH.as_ptr(),
                self.nev,
                tol,
                self.resid.as_mut_ptr(),
                self.ncv,
                self.v.as_mut_ptr(),
                self.n,
                self.iparam.as_mut_ptr(),
                self.ipntr.as_mut_ptr(),
                self.workd.as_mut_ptr(),
                self.workl.as_mut_ptr(),
                self.lworkl,
                info,
            )
        };
    }

    /// dseupd after a converged dsaupd: the nev eigenvalues λ (unsorted) and their
    /// vectors, n values each, one after the other.
    fn eupd<E: std::error::Error + 'static>(
        &mut self,
        sigma: f64,
        tol: f64,
    ) -> Result<(Vec<f64>, Vec<f64>), LanczosError<E>> {
        let (n, nev) = (self.n as usize, self.nev as usize);
        let select = vec![0 as c_int; self.ncv as usize];
        let mut d = vec![0.0; nev];
        let mut z = vec![0.0; n * nev];
        let mut info: c_int = 0;
        // SAFETY: as in saupd; select has ncv entries, d nev, z n·nev with ldz = n.
        unsafe {
            ffi::dseupd_c(
                1,
                c"A".as_ptr(),
                select.as_ptr(),
                d.as_mut_ptr(),
                z.as_mut_ptr(),
                self.n,
                sigma,
                BMAT.as_ptr(),
                self.n,
                WHICH.as_ptr(),
                self.nev,
                tol,
                self.resid.as_mut_ptr(),
                self.ncv,
                self.v.as_mut_ptr(),
                self.n,
                self.iparam.as_mut_ptr(),
                self.ipntr.as_mut_ptr(),
                self.workd.as_mut_ptr(),
                self.workl.as_mut_ptr(),
                self.lworkl,
                &mut info,
            )
        };
        if info != 0 {
            return Err(LanczosError::Arpack {
                call: "dseupd",
                info,
                meaning: info_meaning(info),
            });
        }
        Ok((d, z))
    }
}

/// ARPACK's problem kind (generalized: B = M) and which Ritz values (largest magnitude
/// of OP, i.e. λ nearest σ).
const BMAT: &std::ffi::CStr = c"G";
const WHICH: &std::ffi::CStr = c"LM";
