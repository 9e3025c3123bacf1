//! The contact points' hysteresis loops of an FE harmonic-balance solution: every
//! balanced direction's relative displacement rebuilt from its harmonics at the
//! balance's N samples and marched through the library's point until its loop closes
//! (the AFT's own march: one-direction points by `jointlin_point_step`, three-direction
//! points by `jointlin_point3d_step`), in force form (stress × tributary area). The loop
//! the balance describes, to set beside the time domain's (loops_time.csv).

use super::harmonic_fe::FeBalance;
use super::harmonic_fe_point3d::loop_samples;
use crate::mhb::aft::march;
use crate::mhb::loops::LoopSample;
use crate::mhb::{Law, MhbError};

/// The loops of one frequency's solution.
#[derive(Debug, Clone)]
pub struct BalanceLoops {
    /// Frequency (1/time).
    pub freq: f64,
    /// Per sample of the period (t_k = kT/N, k = 1..N), per contact point of the problem:
    /// (u₁, u₂, h) and (F₁, F₂, N); zeros at points outside the balance (open).
    pub samples: Vec<Vec<LoopSample>>,
    /// The contact points in the balance (closed after the preload).
    pub points: Vec<usize>,
    /// The overclosure h follows the balance (`normal_load_variation`); otherwise the
    /// normal is held at its static force and h is not part of the solution.
    pub overclosure: bool,
}

impl FeBalance<'_, '_> {
    /// The loops of the solution `r` (direction-major coefficients) at `freq`.
    pub fn loops(&mut self, r: &[f64], freq: f64) -> Result<BalanceLoops, MhbError> {
        let (n, nc) = (self.tr.n, self.tr.ncoef());
        let contacts = self.setup.problem.contacts.len();
        let mut samples = vec![vec![LoopSample::default(); contacts]; n];
        let mut delta = vec![0.0; n];
        for gi in 0..self.groups.len() {
            let g = self.groups[gi];
            let dc = &r[g.first * nc..(g.first + g.len) * nc];
            let d = self.dirs[g.first];
            let i = self.setup.active[d.point];
            if let Some(p3) = &g.point3 {
                for (k, s) in loop_samples(&mut self.tr, p3, dc)?.into_iter().enumerate() {
                    samples[k][i] = s;
                }
                continue;
            }
            // One tangential direction of a thesis-model point at its static pressure.
            let (t, a) = (self.tang[d.point], self.area[d.point]);
            self.tr.synthesize(dc, &mut delta);
            let period = march(&Law::Point(t), &delta)?;
            for (k, s) in samples.iter_mut().enumerate() {
                s[i].displacement[d.comp - 1] = delta[k];
                s[i].force[d.comp - 1] = a * period.force[k];
                s[i].force[2] = a * t.normal;
            }
        }
        Ok(BalanceLoops {
            freq,
            samples,
            points: self.setup.active.clone(),
            overclosure: self.setup.point_model.normal_load_variation,
        })
    }
}
