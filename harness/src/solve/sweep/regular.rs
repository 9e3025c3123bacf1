//! Whether a frequency's dynamic stiffness is regular: UMFPACK's pivot ratio screens,
//! the reciprocal 1-norm condition estimated from the factors decides, and one solve's
//! bound confirms (docs/robustness.md, "Singular frequencies").

use super::{Setup, SweepError, C64};
use crate::solve::umfpack::{Numeric, UmfpackError};

/// The threshold of one solve's bound ([`Setup::rcond_bound`]): below it the frequency
/// is singular (the response to this load has no correct digit).
pub const SINGULAR_RCOND: f64 = 1e-14;

/// A frequency whose dynamic stiffness has an estimated reciprocal 1-norm condition
/// number of its row-equilibrated form (`Numeric::rcond1_row_equilibrated_estimate`,
/// Hager–Higham as LAPACK's zgecon) below the machine epsilon is singular to working
/// precision, LAPACK's criterion (xGESVX's INFO = N + 1), as is UMFPACK's status 1 (an
/// exactly zero pivot): no response is computed there, the sweep goes on. The estimate
/// is computed where UMFPACK's pivot ratio min|Uᵢᵢ|/max|Uᵢᵢ| falls below
/// [`PIVOT_RATIO_SCREEN`]. Measured: the undamped open joint of
/// scenes/hard/open-resonance.toml at its first eigenfrequency 1.8e-18, 1e-10 below it
/// 4.4e-17, 1e-6 below 5.1e-13 (its response right to 1e-4); the damped bolted lap of
/// examples/deck/ 1.1e-15 at its resonance peak, where a solve's backward error is 1e-16
/// and the response is right.
pub const SINGULAR_RCOND_ESTIMATE: f64 = f64::EPSILON;

/// A pivot ratio at or above this is regular without the condition estimate (a few
/// solves). The pivot ratio is no condition number: it falls with the length of a long,
/// well-conditioned structure (a damped steel column of 101 439 DOFs, 6 % below its
/// first mode: below 1e-14 with UMFPACK's unsymmetric strategy, which called every
/// frequency singular when the pivot ratio alone decided), and it is 1.5e-9 on the
/// healthy joint of scenes/hard/stiffness-ratio.toml (k_T0·L/(E·A) = 1e6); singular
/// frequencies have shown 1e-13 and less (open-resonance.toml).
pub const PIVOT_RATIO_SCREEN: f64 = 1e-8;

impl Setup<'_> {
    /// Factorizes `self.s` (filled by [`Setup::fill`]) for frequency `f` (1/time): `None`
    /// when it is singular ([`Setup::factor_regular`]).
    pub fn factor(&self, f: f64) -> Result<Option<Numeric<'_>>, SweepError> {
        self.factor_regular()
            .map_err(|source| SweepError::Umfpack { freq: f, source })
    }

    /// Factorizes `self.s`: `None` when it is singular (UMFPACK status 1, or a pivot ratio
    /// below [`PIVOT_RATIO_SCREEN`] confirmed by a reciprocal condition estimate below
    /// [`SINGULAR_RCOND_ESTIMATE`]).
    pub fn factor_regular(&self) -> Result<Option<Numeric<'_>>, UmfpackError> {
        match self.symbolic()?.factor(&self.s) {
            Ok(num) if num.rcond() >= PIVOT_RATIO_SCREEN => Ok(Some(num)),
            Ok(num) => match num.rcond1_row_equilibrated_estimate() {
                Ok(r) if r >= SINGULAR_RCOND_ESTIMATE => Ok(Some(num)),
                Ok(_) | Err(UmfpackError::NonFinite) => Ok(None),
                Err(source) => Err(source),
            },
            Err(UmfpackError::Singular { .. }) => Ok(None),
            Err(source) => Err(source),
        }
    }

    /// An upper bound of the reciprocal 2-norm condition number of `self.s` from one
    /// solve x = S⁻¹ f: ‖S⁻¹‖₂ ≥ ‖x‖₂/‖f‖₂ and ‖S‖₂ ≥ c, the largest column 2-norm, so
    /// rcond₂ ≤ ‖f‖₂/(c‖x‖₂). Below [`SINGULAR_RCOND`] the frequency is singular for
    /// this load. It catches a near-zero eigenvalue that no single pivot shows: the
    /// undamped stuck joint of three-beams-coarse at its `jointlin modes` frequency
    /// 1174.498 Hz had a pivot ratio above 1e-14 and a response of 1.38e6 mm (bound
    /// 1e-15 from that solve).
    pub fn rcond_bound(&self, f: &[C64], x: &[C64]) -> f64 {
        let p = &self.s.pattern;
        let c = (0..p.n)
            .map(|j| {
                let k = p.col_ptr[j] as usize..p.col_ptr[j + 1] as usize;
                self.s.values[k].iter().map(|v| v.norm_sqr()).sum::<f64>()
            })
            .fold(0.0f64, f64::max)
            .sqrt();
        let norm = |v: &[C64]| v.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt();
        let (nf, nx) = (norm(f), norm(x));
        if nx == 0.0 {
            return 1.0;
        }
        nf / (c * nx)
    }
}
