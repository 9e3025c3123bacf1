//! Marching a three-direction point over one period's samples until its loop closes
//! (the AFT's time part for [`super::Hb3`] and the FE balance), coupled or as two
//! points: without coupled slip each tangential direction is its own point, (u₁, 0, h)
//! and (0, u₂, h), sharing the overclosure h (docs/contact3d.md).

use crate::capi::{self, CapiError, Contact3, POINT3D_STATE_LEN};
use crate::mhb::aft::{AftError, CLOSE_TOL, MAX_PERIODS};
use crate::mhb::aitken::Aitken;

/// One closed period of a point: forces (t₁, t₂, N) per sample, the energy dissipated
/// over the period, the periods marched and the point's state at the period's end.
#[derive(Debug, Clone)]
pub struct Period3 {
    pub force: [Vec<f64>; 3],
    pub dissipated: f64,
    pub periods: usize,
    /// State at the period's end: where the march of a nearby path may start
    /// ([`march3_from`]).
    pub state: [f64; POINT3D_STATE_LEN],
}

/// Marches `c` over the periodic samples `disp` = (u₁, u₂, h) from a virgin state until
/// two consecutive periods' forces agree to [`CLOSE_TOL`] of the force scale. A cell that
/// slips on a short arc of a path that is not a circle forgets its sideways position
/// slowly (geometrically, docs/contact3d.md §4), each cell at a rate of its own: the
/// sliders' positions (state slots 5 …, the header's layout) are extrapolated slot by
/// slot (Aitken's Δ², [`Aitken::per_slot`]).
pub fn march3(c: &Contact3, disp: &[[f64; 3]]) -> Result<Period3, AftError> {
    march3_from(c, disp, &[0.0; POINT3D_STATE_LEN])
}

/// [`march3`] from the state `start` instead of a virgin point. The forward-difference
/// columns of a Jacobian start from their base path's closed state ([`Period3::state`]):
/// a path 1e-7 away closes within a few periods there, where from a virgin point it
/// repeats the whole transient (the per-point cost of the coupled balance's Jacobian).
pub fn march3_from(
    c: &Contact3,
    disp: &[[f64; 3]],
    start: &[f64; POINT3D_STATE_LEN],
) -> Result<Period3, AftError> {
    let aitken = Aitken::per_slot(SLIDER_SLOTS..POINT3D_STATE_LEN);
    march_with(c, disp, start, aitken)
}

/// [`march3_from`] with the given extrapolation.
fn march_with(
    c: &Contact3,
    disp: &[[f64; 3]],
    start: &[f64; POINT3D_STATE_LEN],
    mut aitken: Aitken,
) -> Result<Period3, AftError> {
    let n = disp.len();
    let mut state = *start;
    let mut next = [0.0; POINT3D_STATE_LEN];
    let mut cur = Period3 {
        force: [vec![0.0; n], vec![0.0; n], vec![0.0; n]],
        dissipated: 0.0,
        periods: 0,
        state: *start,
    };
    let mut prev = cur.force.clone();
    for p in 1..=MAX_PERIODS {
        let mut diss = 0.0;
        for (k, d) in disp.iter().enumerate() {
            let s = capi::point3d_step(c, &state, *d, &mut next)?;
            state = next;
            for a in 0..3 {
                cur.force[a][k] = s.force[a];
            }
            diss += s.dissipated;
        }
        cur.dissipated = diss;
        cur.periods = p;
        let mut scale = f64::MIN_POSITIVE;
        let mut diff = 0.0f64;
        for a in 0..3 {
            for k in 0..n {
                scale = scale.max(cur.force[a][k].abs());
                diff = diff.max((cur.force[a][k] - prev[a][k]).abs());
            }
        }
        prev.clone_from(&cur.force);
        if aitken.starting() {
            aitken.first(&state);
            continue;
        }
        if diff <= CLOSE_TOL * scale {
            cur.state = state;
            return Ok(cur);
        }
        if let Some(x) = aitken.after(&state, diff) {
            match <[f64; POINT3D_STATE_LEN]>::try_from(x.as_slice()) {
                Ok(x) if capi::point3d_step(c, &x, disp[0], &mut next).is_ok() => state = x,
                _ => aitken.rejected(&state),
            }
        }
    }
    Err(AftError::NotClosed {
        periods: MAX_PERIODS,
    })
}

/// First slot of the sliders' positions in a three-direction point's state (the
/// header's layout: cell count, u₁, u₂, h, energy, then two slots per cell).
const SLIDER_SLOTS: usize = 5;

/// The states of one point: the coupled point in the first slot, or the two tangential
/// directions' points (second slot unused when coupled).
pub type States = [[f64; POINT3D_STATE_LEN]; 2];

/// Virgin states.
pub const VIRGIN: States = [[0.0; POINT3D_STATE_LEN]; 2];

/// One step of a point from `from` to `disp` = (u₁, u₂, h), coupled or as two points
/// sharing h: the forces (F₁, F₂, N) and the energy dissipated in the step; the new
/// states go to `to`.
pub fn step(
    c: &Contact3,
    coupled: bool,
    from: &States,
    disp: [f64; 3],
    to: &mut States,
) -> Result<([f64; 3], f64), CapiError> {
    if coupled {
        let s = capi::point3d_step(c, &from[0], disp, &mut to[0])?;
        return Ok((s.force, s.dissipated));
    }
    let a = capi::point3d_step(c, &from[0], [disp[0], 0.0, disp[2]], &mut to[0])?;
    let b = capi::point3d_step(c, &from[1], [0.0, disp[1], disp[2]], &mut to[1])?;
    Ok((
        [a.force[0], b.force[1], a.force[2]],
        a.dissipated + b.dissipated,
    ))
}

/// One closed period of a point, coupled or as two points: forces (F₁, F₂, N) per
/// sample, the energy dissipated over the period (force·length), the periods marched
/// (the longer of the two) and the states at the period's end.
#[derive(Debug, Clone)]
pub struct Marched {
    pub force: [Vec<f64>; 3],
    pub dissipated: f64,
    pub periods: usize,
    pub states: States,
}

/// [`march3_from`], coupled or as two points sharing h, from `start`.
pub fn march_point(
    c: &Contact3,
    coupled: bool,
    disp: &[[f64; 3]],
    start: &States,
) -> Result<Marched, AftError> {
    if coupled {
        let p = march3_from(c, disp, &start[0])?;
        return Ok(Marched {
            force: p.force,
            dissipated: p.dissipated,
            periods: p.periods,
            states: [p.state, start[1]],
        });
    }
    let only = |keep: usize| -> Vec<[f64; 3]> {
        disp.iter()
            .map(|d| {
                let mut x = *d;
                x[1 - keep] = 0.0;
                x
            })
            .collect()
    };
    let a = march3_from(c, &only(0), &start[0])?;
    let b = march3_from(c, &only(1), &start[1])?;
    let [fa, _, na] = a.force;
    let [_, fb, _] = b.force;
    Ok(Marched {
        force: [fa, fb, na],
        dissipated: a.dissipated + b.dissipated,
        periods: a.periods.max(b.periods),
        states: [a.state, b.state],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::names::LawName;

    /// Plain marching (no extrapolation) of `periods` periods: the forces of the last.
    fn plain(c: &Contact3, disp: &[[f64; 3]], periods: usize) -> [Vec<f64>; 3] {
        let n = disp.len();
        let mut state = [0.0; POINT3D_STATE_LEN];
        let mut next = [0.0; POINT3D_STATE_LEN];
        let mut f = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
        for _ in 0..periods {
            for (k, d) in disp.iter().enumerate() {
                let s = capi::point3d_step(c, &state, *d, &mut next).unwrap();
                state = next;
                (0..3).for_each(|a| f[a][k] = s.force[a]);
            }
        }
        f
    }

    /// `n` samples of the ellipse (a cos ωt, b sin ωt) at overclosure 1.
    fn ellipse(a: f64, b: f64, n: usize) -> Vec<[f64; 3]> {
        (0..n)
            .map(|k| {
                let t = 2.0 * std::f64::consts::PI * k as f64 / n as f64;
                [a * t.cos(), b * t.sin(), 1.0]
            })
            .collect()
    }

    /// Largest difference of two periods' forces.
    fn largest_difference(f: &[Vec<f64>; 3], g: &[Vec<f64>; 3]) -> f64 {
        (0..3)
            .flat_map(|i| f[i].iter().zip(&g[i]).map(|(x, y)| (x - y).abs()))
            .fold(0.0f64, f64::max)
    }

    #[test]
    fn a_slowly_closing_coupled_loop_is_extrapolated_to_the_same_loop() {
        // Jenkins (x = μN/k_T0 = 1) on ellipses just beyond the stick circle: the slider
        // forgets its sideways position slowly. Plain marching needs 313 periods for
        // A = (1.01, 0.05) (more than MAX_PERIODS) and 160 for (1.02, 0.5); the
        // extrapolated march closes in 5 and 8 and lands on the loop that 3000 plain
        // periods reach.
        let c = Contact3 {
            law: LawName::Jenkins,
            cells: 0,
            mu: 1.0,
            k_t0: 1.0,
            k_n: 1.0,
        };
        let n = 256;
        for (a, b) in [(1.01, 0.05), (1.02, 0.5)] {
            let disp = ellipse(a, b, n);
            let fast = march3(&c, &disp).unwrap();
            let slow = plain(&c, &disp, 3000);
            let diff = largest_difference(&fast.force, &slow);
            eprintln!(
                "A = ({a}, {b}): closed in {} periods, {diff:.1e} μN from 3000 plain periods",
                fast.periods
            );
            assert!(
                fast.periods <= 20 && diff < 1e-9,
                "{} {diff:e}",
                fast.periods
            );
        }
    }
    #[test]
    fn a_mindlin_point_whose_cells_forget_at_their_own_rates_is_extrapolated_per_cell() {
        // Mindlin cells (δ* = 1.5 μN/k_T0 = 1.5) on nearly straight ellipses near δ*:
        // each cell that slips on a short arc forgets its sideways position at a rate set
        // by its own limit, so one ratio for all cells (that of the force differences)
        // jumps them poorly (17 and 53 periods); each slider's own ratio closes the loop
        // in 8 and 6, on the loop 3000 plain periods reach. (On the knife's
        // coupled-slip harmonic balance, H = 3, one ratio left loops unclosed after 200
        // periods.)
        let c = Contact3 {
            law: LawName::Mindlin,
            cells: 0,
            mu: 1.0,
            k_t0: 1.0,
            k_n: 1.0,
        };
        let n = 256;
        for (a, b) in [(1.0, 0.02), (1.6, 0.01)] {
            let disp = ellipse(a, b, n);
            let fast = march3(&c, &disp).unwrap();
            let virgin = [0.0; POINT3D_STATE_LEN];
            let one_ratio = march_with(
                &c,
                &disp,
                &virgin,
                Aitken::new(SLIDER_SLOTS..POINT3D_STATE_LEN),
            )
            .map_or(MAX_PERIODS, |p| p.periods);
            let slow = plain(&c, &disp, 3000);
            let diff = largest_difference(&fast.force, &slow);
            eprintln!(
                "A = ({a}, {b}): closed in {} periods ({one_ratio} with one ratio), {diff:.1e} μN from 3000 plain periods",
                fast.periods
            );
            assert!(
                fast.periods <= 10 && 2 * fast.periods <= one_ratio && diff < 1e-9,
                "{} {one_ratio} {diff:e}",
                fast.periods
            );
        }
    }

    #[test]
    fn a_nearby_path_marched_from_the_closed_state_gives_the_same_difference_quotient() {
        // A Jacobian column: the path moved by ε = 1e-7 (relative) in one coefficient,
        // marched from the base path's closed state instead of a virgin point, gives the
        // same difference quotient (to 1e-3 of its largest entry: both closed to
        // CLOSE_TOL, divided by ε) in no more periods: 5 instead of 8 for a Jenkins and a
        // Mindlin point on slowly closing ellipses; 3 as from virgin for a Mindlin point
        // whose normal load varies and lifts off for part of the cycle (h = 1 + 1.2 cos ωt:
        // the lift-off clears its memory every period).
        let point = |law| Contact3 {
            law,
            cells: 0,
            mu: 1.0,
            k_t0: 1.0,
            k_n: 1.0,
        };
        let n = 256;
        let lift = |mut d: Vec<[f64; 3]>| {
            for (k, x) in d.iter_mut().enumerate() {
                x[2] = 1.0 + 1.2 * (2.0 * std::f64::consts::PI * k as f64 / n as f64).cos();
            }
            d
        };
        let cases = [
            (point(LawName::Jenkins), ellipse(1.02, 0.5, n)),
            (point(LawName::Mindlin), ellipse(1.0, 0.02, n)),
            (point(LawName::Mindlin), lift(ellipse(0.8, 0.6, n))),
        ];
        let (mut warm_periods, mut cold_periods) = (0, 0);
        for (c, disp) in cases {
            let base = march3(&c, &disp).unwrap();
            let eps = 1e-7;
            let near: Vec<[f64; 3]> = disp
                .iter()
                .map(|d| [d[0] * (1.0 + eps), d[1], d[2]])
                .collect();
            let warm = march3_from(&c, &near, &base.state).unwrap();
            let cold = march3(&c, &near).unwrap();
            let quotient = |f: &[Vec<f64>; 3]| -> [Vec<f64>; 3] {
                std::array::from_fn(|a| {
                    f[a].iter()
                        .zip(&base.force[a])
                        .map(|(x, y)| (x - y) / eps)
                        .collect()
                })
            };
            let (qw, qc) = (quotient(&warm.force), quotient(&cold.force));
            let largest = largest_difference(&qc, &std::array::from_fn(|_| vec![0.0; n]));
            let diff = largest_difference(&qw, &qc);
            eprintln!(
                "{:?}: {} periods from the closed state, {} from virgin; quotients differ by {:.1e} of {largest:.2}",
                c.law, warm.periods, cold.periods, diff / largest
            );
            assert!(
                largest > 0.1 && diff <= 1e-3 * largest && warm.periods <= cold.periods,
                "{} {} {diff:e} {largest:e}",
                warm.periods,
                cold.periods
            );
            warm_periods += warm.periods;
            cold_periods += cold.periods;
        }
        assert!(warm_periods < cold_periods);
    }
}
