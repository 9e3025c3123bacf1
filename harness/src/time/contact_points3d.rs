//! The FE time domain with the library's three-direction point (docs/contact3d.md), when
//! the scene's `[effects]` switch `coupled_slip` or `normal_load_variation` on: the same
//! point model as the harmonic balance ([`crate::solve::sweep::harmonic_fe_point3d`]), so
//! a run integrates what the balance solves and can be its reference.
//!
//! Per point, from the static step's local relative displacement δ⁰ and overclosure h₀:
//! tangential displacements uⱼ = δ_tⱼ − δ⁰_tⱼ; with `normal_load_variation` the point
//! sees h = h₀ − (δ_n − δ⁰_n) (model.md §2: h = −δ_n − g₀), so N(t) follows the normal
//! law, may vanish (separation) and sets the slip limit μN(t); without it the point sees
//! h₀ (slip limit μN₀) and the normal force is the linear spring about the static state,
//! N = N₀ − k₀ (δ_n − δ⁰_n) with the static pressure N₀ and tangent k₀ = dp/dh, as in
//! the balance. With `coupled_slip` one point takes
//! both tangential directions under one circular limit; without it each direction is a
//! point of its own, (u₁, 0, h) and (0, u₂, h). Forces per area (the stress form) × the
//! point's area; the local force on the upper side is q = (−N, t₁, t₂)·A, as UINTER's
//! q = S·STRESS·A.

use nalgebra::Matrix3;

use crate::capi::{self, CapiError, POINT3D_STATE_LEN};
use crate::model::Problem;
use crate::solve::contact::{normal_stiffness, tangential};
use crate::solve::static_step::{overclosure, StaticState};
use crate::solve::sweep::harmonic_fe_point3d::{Point3, PointModel};

type State3 = [f64; POINT3D_STATE_LEN];

/// The points' three-direction models, committed and trial states.
#[derive(Debug, Clone)]
pub struct Points3 {
    points: Vec<Point3>,
    /// Static local relative displacement and pressure per point.
    delta0: Vec<[f64; 3]>,
    normal0: Vec<f64>,
    /// States per point: [coupled or t₁, t₂ (uncoupled only)].
    state: Vec<[State3; 2]>,
    trial: Vec<[State3; 2]>,
    /// Energy dissipated per point, committed and trial (force·length).
    energy: Vec<f64>,
    trial_energy: Vec<f64>,
}

impl Points3 {
    /// The points at the static state `stat`, whose local relative displacements are
    /// `delta0` (virgin hysteresis), for `model` (not the thesis's: then UINTER serves).
    /// The static step's tangential stresses are not carried, as in the balance.
    pub fn new(p: &Problem, stat: &StaticState, delta0: Vec<[f64; 3]>, model: PointModel) -> Self {
        let points: Vec<Point3> = p
            .contacts
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let itf = &p.interfaces[c.interface];
                let t = tangential(itf, stat.pressure[i]);
                let mut pt = Point3::new(
                    &t,
                    normal_stiffness(itf),
                    stat.normal_stiffness[i],
                    c.area,
                    model,
                );
                // h₀ = N₀/k_N as in the balance (the slip limit μN₀ for any normal law);
                // an open point keeps its static overclosure (≤ 0: the gap).
                if stat.pressure[i] <= 0.0 {
                    pt.h0 = overclosure(p, c, delta0[i])[0].min(0.0);
                }
                pt
            })
            .collect();
        let n = points.len();
        let virgin = [[0.0; POINT3D_STATE_LEN]; 2];
        Points3 {
            points,
            delta0,
            normal0: stat.pressure.clone(),
            state: vec![virgin; n],
            trial: vec![virgin; n],
            energy: vec![0.0; n],
            trial_energy: vec![0.0; n],
        }
    }

    /// Point `i` at local relative displacement `d` from its committed state: the local
    /// force q (× area) and its tangent ∂q/∂δ (× area); the trial state is kept.
    pub fn evaluate(
        &mut self,
        i: usize,
        d: [f64; 3],
    ) -> Result<([f64; 3], Matrix3<f64>), CapiError> {
        let pt = &self.points[i];
        let d0 = self.delta0[i];
        let (u1, u2) = (d[1] - d0[1], d[2] - d0[2]);
        let dn = d[0] - d0[0];
        let varies = pt.model.normal_load_variation;
        let h = if varies { pt.h0 - dn } else { pt.h0 };
        let mut out = [[0.0; POINT3D_STATE_LEN]; 2];
        // Rows (t₁, t₂, N) of the forces and of ∂/∂(u₁, u₂, h).
        let (force, stiff, dissipated) = if pt.model.coupled_slip {
            let s = capi::point3d_step(&pt.contact, &self.state[i][0], [u1, u2, h], &mut out[0])?;
            (s.force, s.stiffness, s.dissipated)
        } else {
            let a = capi::point3d_step(&pt.contact, &self.state[i][0], [u1, 0.0, h], &mut out[0])?;
            let b = capi::point3d_step(&pt.contact, &self.state[i][1], [0.0, u2, h], &mut out[1])?;
            let mut k = [0.0; 9];
            (k[0], k[2]) = (a.stiffness[0], a.stiffness[2]);
            (k[4], k[5]) = (b.stiffness[4], b.stiffness[5]);
            (k[6], k[8]) = (a.stiffness[6], a.stiffness[8]);
            (
                [a.force[0], b.force[1], a.force[2]],
                k,
                a.dissipated + b.dissipated,
            )
        };
        self.trial[i] = out;
        self.trial_energy[i] = self.energy[i] + pt.area * dissipated;
        // ∂h/∂δ_n = −1 when N varies; else N is the linear spring about the static state
        // (none for a point open at the static state, which the balance leaves out).
        let (normal, dn_du, dn_dh) = if varies {
            (force[2], [stiff[6], stiff[7]], stiff[8])
        } else if pt.h0 > 0.0 {
            (self.normal0[i] - pt.k_ref_n * dn, [0.0; 2], pt.k_ref_n)
        } else {
            (0.0, [0.0; 2], 0.0)
        };
        let a = pt.area;
        let q = [-normal * a, force[0] * a, force[1] * a];
        let dh = if varies { -1.0 } else { 0.0 };
        let t = Matrix3::new(
            dn_dh * a,
            -dn_du[0] * a,
            -dn_du[1] * a,
            stiff[2] * dh * a,
            stiff[0] * a,
            stiff[1] * a,
            stiff[5] * dh * a,
            stiff[3] * a,
            stiff[4] * a,
        );
        Ok((q, t))
    }

    /// Accepts every point's last trial.
    pub fn commit(&mut self) {
        self.state.clone_from(&self.trial);
        self.energy.clone_from(&self.trial_energy);
    }

    /// Energy dissipated so far by each point (committed; force·length).
    pub fn dissipated(&self) -> &[f64] {
        &self.energy
    }
}
