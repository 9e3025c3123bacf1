//! The contact points in the time domain: every point's force and tangent from UINTER
//! (LINPER = 0) for a trial relative displacement, evaluated from the committed state; the
//! trial becomes the committed state only by [`Contacts::commit`] (once per accepted
//! step). Nothing of the contact law lives here.
//!
//! Per point, with δ = Qᵀ(u_upper − u_lower) = (δ_n, δ_t₁, δ_t₂) (local): RDISP = Sδ,
//! S = diag(−1, 1, 1) (overclosure h = −δ_n); the local force on the upper side is
//! q = S·STRESS·area and its tangent dq/dδ = S·DDSDDR·S·area (as in the static step).
//! The energy dissipated by a point is STATEV(5) (accumulated SFD, per area) × area.
//!
//! With `[effects] coupled_slip` or `normal_load_variation` the points are the library's
//! three-direction point instead ([`super::contact_points3d`]), the balance's model.

use nalgebra::Matrix3;

use super::contact_points3d::Points3;
use crate::capi::{self, CapiError, NPROPS, NSTATV};
use crate::model::Problem;
use crate::solve::contact::interface_props;
use crate::solve::static_step::{overclosure, uinter_point, StaticState};
use crate::solve::sweep::harmonic_fe_point3d::PointModel;

/// KSTEP of the time-domain step (the static preload step is 1).
pub const KSTEP: i32 = 2;

fn s_flip(v: [f64; 3]) -> [f64; 3] {
    [-v[0], v[1], v[2]]
}

/// All contact points of a problem, committed and trial states.
#[derive(Debug, Clone)]
pub struct Contacts<'a> {
    p: &'a Problem,
    props: Vec<[f64; NPROPS]>,
    /// Committed local relative displacement, force (× area) and STATEV per point.
    pub delta: Vec<[f64; 3]>,
    pub force: Vec<[f64; 3]>,
    statev: Vec<[f64; NSTATV]>,
    trial_delta: Vec<[f64; 3]>,
    trial_force: Vec<[f64; 3]>,
    trial_statev: Vec<[f64; NSTATV]>,
    kinc: i32,
    /// UINTER calls made.
    pub calls: u64,
    /// The three-direction points, when the point model is not the thesis's.
    points3: Option<Points3>,
}

impl<'a> Contacts<'a> {
    /// The points in the state the static step left them in, at displacement `stat.u`.
    pub fn new(p: &'a Problem, stat: &StaticState) -> Result<Self, CapiError> {
        Contacts::with_model(p, stat, PointModel::default())
    }

    /// [`Contacts::new`] with the point model `model` (the thesis's: UINTER; else the
    /// three-direction point, starting virgin at the static state).
    pub fn with_model(
        p: &'a Problem,
        stat: &StaticState,
        model: PointModel,
    ) -> Result<Self, CapiError> {
        let props = p.interfaces.iter().map(interface_props).collect();
        let n = p.contacts.len();
        let mut c = Contacts {
            p,
            props,
            delta: vec![[0.0; 3]; n],
            force: vec![[0.0; 3]; n],
            statev: stat.statev.clone(),
            trial_delta: vec![[0.0; 3]; n],
            trial_force: vec![[0.0; 3]; n],
            trial_statev: stat.statev.clone(),
            kinc: 0,
            calls: 0,
            points3: None,
        };
        let d = c.local(&stat.u);
        c.delta.clone_from(&d);
        if !model.is_thesis() {
            c.points3 = Some(Points3::new(p, stat, d.clone(), model));
        }
        c.evaluate(&d, None)?;
        c.commit();
        Ok(c)
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.delta.len()
    }

    pub fn is_empty(&self) -> bool {
        self.delta.is_empty()
    }

    /// Local relative displacements of every point for free-DOF displacements `u`.
    pub fn local(&self, u: &[f64]) -> Vec<[f64; 3]> {
        self.p
            .contacts
            .iter()
            .map(|c| std::array::from_fn(|k| c.relative(k, u)))
            .collect()
    }

    /// Evaluates every point at `delta` from its committed state (a trial); writes the
    /// local tangents (× area) when asked. The trial force is [`Self::trial_force`].
    pub fn evaluate(
        &mut self,
        delta: &[[f64; 3]],
        mut tangents: Option<&mut [Matrix3<f64>]>,
    ) -> Result<(), CapiError> {
        if let Some(p3) = self.points3.as_mut() {
            for (i, d) in delta.iter().enumerate() {
                let (q, t) = p3.evaluate(i, *d)?;
                self.trial_force[i] = q;
                self.trial_delta[i] = *d;
                if let Some(ts) = tangents.as_deref_mut() {
                    ts[i] = t;
                }
            }
            return Ok(());
        }
        let s = Matrix3::from_diagonal(&nalgebra::Vector3::new(-1.0, 1.0, 1.0));
        for (i, c) in self.p.contacts.iter().enumerate() {
            let pt = uinter_point(self.p, c, &self.props[c.interface]);
            let mut sv = self.statev[i];
            let rdisp = overclosure(self.p, c, delta[i]);
            let old = overclosure(self.p, c, self.delta[i]);
            let drdisp = std::array::from_fn(|k| rdisp[k] - old[k]);
            let out = capi::uinter_general(&pt, &mut sv, rdisp, drdisp, KSTEP, self.kinc + 1)?;
            self.calls += 1;
            let f = s_flip(out.stress);
            self.trial_force[i] = f.map(|v| v * c.area);
            self.trial_delta[i] = delta[i];
            self.trial_statev[i] = sv;
            if let Some(t) = tangents.as_deref_mut() {
                let d = Matrix3::from_fn(|r, k| out.ddsddr[r][k]);
                t[i] = s * d * s * c.area;
            }
        }
        Ok(())
    }

    /// Local forces (× area) of the last trial.
    pub fn trial_force(&self) -> &[[f64; 3]] {
        &self.trial_force
    }

    /// Accepts the last trial as the committed state.
    pub fn commit(&mut self) {
        self.delta.clone_from(&self.trial_delta);
        self.force.clone_from(&self.trial_force);
        self.statev.clone_from(&self.trial_statev);
        if let Some(p3) = self.points3.as_mut() {
            p3.commit();
        }
        self.kinc += 1;
    }

    /// Energy dissipated so far by each point (committed; force·length).
    pub fn dissipated(&self) -> Vec<f64> {
        if let Some(p3) = &self.points3 {
            return p3.dissipated().to_vec();
        }
        self.p
            .contacts
            .iter()
            .zip(&self.statev)
            .map(|(c, sv)| sv[4] * c.area)
            .collect()
    }

    /// r += Bᵀ q: the internal forces of local point forces `q` on the free DOFs.
    pub fn add_internal(&self, q: &[[f64; 3]], r: &mut [f64]) {
        for (c, f) in self.p.contacts.iter().zip(q) {
            for k in 0..3 {
                for &(i, w) in &c.rows[k] {
                    r[i] += w * f[k];
                }
            }
        }
    }
}
