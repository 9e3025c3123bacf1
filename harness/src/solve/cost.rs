//! What a sweep will cost, forecast before it runs: one factorization and one solve of
//! the model's dynamic stiffness S(ω) = K + K_c − ω²M + iωD (contacts closed and stuck:
//! k_N, k_T0 per area × area) timed on this machine, times the counts the scene's mode
//! needs per frequency. A forecast, not a promise: the static step, the library calls
//! and the contact iteration's own work come on top, and a loaded machine is slower.

use std::time::Instant;

use nalgebra::{Matrix3, Vector3};

use crate::fe::pair_blocks::to_global;
use crate::model::Problem;
use crate::settings::Mode;
use crate::solve::sweep::fast::CONDENSE_MAX;
use crate::solve::sweep::C64;
use crate::solve::umfpack::{Symbolic, UmfpackError};

/// One factorization and one solve of S(ω), measured (seconds).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measured {
    pub analysis: f64,
    pub factorization: f64,
    pub solve: f64,
}

/// Factorizations and solves of a sweep as a range (fewest, most), and the seconds they
/// take at the measured rates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Forecast {
    pub factorizations: [f64; 2],
    pub solves: [f64; 2],
    pub seconds: [f64; 2],
}

/// Thesis mode's passes: at least the first and the final one; at most the scene's
/// `max_passes`.
const THESIS_MIN_PASSES: f64 = 2.0;
/// Fast mode's FGMRES solves per frequency beyond the condensation limit (three-beams:
/// 2.4 on average; the knife near resonance: up to about 40).
const FGMRES_SOLVES: [f64; 2] = [1.0, 40.0];

/// Times the symbolic analysis, one factorization of S at `omega` (rad/time) and one
/// solve with the excitation.
pub fn measure(p: &Problem, omega: f64) -> Result<Measured, UmfpackError> {
    let t = Instant::now();
    let symbolic = Symbolic::symmetric_best(p.sys.pattern.clone())?;
    let analysis = t.elapsed().as_secs_f64();
    let mut base = p.sys.k.values.clone();
    for c in &p.contacts {
        let itf = &p.interfaces[c.interface];
        // A stuck closed joint; the normal stiffness of the constant law where the
        // scene has one, else k_T0 (only the pattern's fill and pivots matter here).
        let kn = itf
            .contact
            .normal_stiffness_per_area
            .unwrap_or(itf.contact.k_t0_per_area);
        let kt = itf.contact.k_t0_per_area;
        let local = Matrix3::from_diagonal(&Vector3::new(kn, kt, kt)) * c.area;
        p.sys
            .pairs
            .add(&mut base, c.pair, &to_global(&c.frame, &local));
    }
    let mut s = p.sys.complex_zeros();
    let w2 = omega * omega;
    for (k, v) in s.values.iter_mut().enumerate() {
        let d = p.damping.as_ref().map_or(0.0, |d| d.values[k]);
        let h = p.structural.as_ref().map_or(0.0, |h| h.values[k]);
        *v = C64::new(base[k] - w2 * p.sys.m.values[k], omega * d + h);
    }
    let t = Instant::now();
    let num = symbolic.factor(&s)?;
    let factorization = t.elapsed().as_secs_f64();
    let mut x = vec![C64::new(0.0, 0.0); p.sys.dofs.n_free()];
    let t = Instant::now();
    num.solve_into(&p.excitation, &mut x)?;
    Ok(Measured {
        analysis,
        factorization,
        solve: t.elapsed().as_secs_f64(),
    })
}

/// The counts of a sweep of `frequencies` in `mode` with `points` closed contact points
/// (all of them, as an upper bound), `harmonics` H and thesis mode's `max_passes`;
/// doubled by `reference` (the sweep without contact damping that the FRF plot draws).
pub fn forecast(
    m: &Measured,
    frequencies: usize,
    mode: Mode,
    points: usize,
    harmonics: usize,
    max_passes: usize,
    reference: bool,
) -> Forecast {
    let nf = frequencies as f64;
    let dirs = 2.0 * points as f64;
    let per_frequency_solves = if points == 0 {
        [1.0, 1.0]
    } else if 2 * points <= CONDENSE_MAX {
        [dirs + 1.0, dirs + 1.0]
    } else {
        FGMRES_SOLVES.map(|s| s + 1.0)
    };
    let (mut fac, mut sol) = match mode {
        Mode::Fast => ([nf, 2.0 * nf], per_frequency_solves.map(|s| s * nf)),
        Mode::Thesis => {
            let passes = [
                THESIS_MIN_PASSES,
                (max_passes as f64).max(THESIS_MIN_PASSES),
            ];
            (passes.map(|k| k * nf), passes.map(|k| k * nf))
        }
        Mode::HarmonicBalance => {
            // Per harmonic: the condensation (m solves) and the a-posteriori check.
            let h = harmonics.max(1) as f64 + 1.0;
            let f = 2.0 * h * nf;
            let s = h * nf * (dirs + 2.0);
            ([f, f], [s, s])
        }
    };
    if reference {
        fac = fac.map(|v| 2.0 * v);
        sol = sol.map(|v| 2.0 * v);
    }
    let seconds = [0, 1].map(|i| m.analysis + fac[i] * m.factorization + sol[i] * m.solve);
    Forecast {
        factorizations: fac,
        solves: sol,
        seconds,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const M: Measured = Measured {
        analysis: 0.5,
        factorization: 2.0,
        solve: 0.1,
    };

    #[test]
    fn the_counts_follow_the_mode() {
        // Fast, 4 points (8 directions ≤ CONDENSE_MAX): one factorization and 9 solves
        // per frequency, up to a refactorization each.
        let f = forecast(&M, 10, Mode::Fast, 4, 1, 50, false);
        assert_eq!(f.factorizations, [10.0, 20.0]);
        assert_eq!(f.solves, [90.0, 90.0]);
        assert_eq!(f.seconds, [0.5 + 20.0 + 9.0, 0.5 + 40.0 + 9.0]);
        // Thesis: 2 … max_passes passes of every frequency; the reference sweep doubles.
        let f = forecast(&M, 10, Mode::Thesis, 100, 1, 30, true);
        assert_eq!(f.factorizations, [40.0, 600.0]);
        // Harmonic balance H = 3: 4 harmonics, twice each (balance and check).
        let f = forecast(&M, 10, Mode::HarmonicBalance, 4, 3, 50, false);
        assert_eq!(f.factorizations, [80.0, 80.0]);
        assert_eq!(f.solves, [400.0, 400.0]);
    }
}
