//! `jointlin loss --calibrate`: contact parameters fitted to reference points. Each
//! parameter (`k_t0_per_area`, `mu`) is scaled by one factor on every interface; the
//! factors solve ln P_i(factors) = ln P_ref,i at as many reference points as
//! parameters (the scene's `[loss_study] calibration`, by default k_T0 on the first
//! point). Newton in the ln factors with a forward-difference Jacobian to start and
//! Broyden's update after each step (one loss evaluation per step at each point); a
//! step into parameters where the model does not converge is halved.

use nalgebra::{DMatrix, DVector};

use super::{power_at, LossError};
use crate::model::Job;
use crate::settings::CalibratedParameter;

/// Most Newton–Broyden steps (the knife's k_T0 alone took 6 secant steps to 0.2 %).
const STEPS: usize = 16;
/// The calibration stops when every |ln(P/P_ref)| is below this (0.2 %).
const TOL: f64 = 2e-3;
/// Forward-difference step in ln factor for the first Jacobian (5 %).
const FD_STEP: f64 = 0.05;
/// Largest change of an ln factor per step (a factor of e²).
const MAX_STEP: f64 = 2.0;
/// Halvings of a step whose model does not converge.
const HALVINGS: usize = 4;
/// Largest factor (either way) on a parameter: beyond it the fit is not a calibration
/// of the scene's values but a different model; steps are shortened to stay inside,
/// and the fit stops where one would have to leave.
const MAX_FACTOR: f64 = 20.0;

/// A converged calibration: each parameter's factor and the power (reported unit)
/// reached at each calibration point.
#[derive(Debug, Clone)]
pub struct Calibration {
    pub factors: Vec<(CalibratedParameter, f64)>,
    pub powers: Vec<f64>,
}

/// The job (or scene) with each parameter scaled by its factor on every interface.
pub fn scaled(job: impl Into<Job>, factors: &[(CalibratedParameter, f64)]) -> Job {
    let (mut k_t0, mut mu) = (1.0, 1.0);
    for &(p, f) in factors {
        match p {
            CalibratedParameter::KT0 => k_t0 *= f,
            CalibratedParameter::Mu => mu *= f,
        }
    }
    job.into().with_interfaces_scaled(k_t0, mu)
}

/// Fits the study's calibration; `progress` gets one line per evaluation.
pub fn calibrate(job: impl Into<Job>, progress: &dyn Fn(&str)) -> Result<Calibration, LossError> {
    let job: &Job = &job.into();
    let st = job.settings.loss_study.as_ref().ok_or(LossError::NoStudy)?;
    let (params, points) = match &st.calibration {
        Some(c) => (c.parameters.clone(), c.points.clone()),
        None => (vec![CalibratedParameter::KT0], vec![0]),
    };
    let refs = points
        .iter()
        .map(|&k| st.reference.get(k).cloned())
        .collect::<Option<Vec<_>>>()
        .ok_or_else(|| LossError::Spec("calibration needs its reference points".into()))?;
    let n = params.len();
    let factors = |x: &DVector<f64>| -> Vec<(CalibratedParameter, f64)> {
        params
            .iter()
            .zip(x.iter())
            .map(|(&p, v)| (p, v.exp()))
            .collect()
    };
    // ln(P/P_ref) at each point and the powers, for ln factors x.
    let eval = |x: &DVector<f64>| -> Result<(DVector<f64>, Vec<f64>), LossError> {
        let sc = scaled(job, &factors(x));
        let mut powers = Vec::with_capacity(n);
        for r in &refs {
            let (s, _) = power_at(&sc, r.torque, r.amplitude)?;
            powers.push(s.power * st.power_factor);
        }
        let line: Vec<String> = factors(x)
            .iter()
            .map(|(p, f)| format!("{} × {f:.5}", p.key()))
            .chain(
                refs.iter()
                    .zip(&powers)
                    .map(|(r, p)| format!("P({}) = {p:.4} {}", r.torque, st.power_unit)),
            )
            .collect();
        progress(&line.join(", "));
        let err =
            DVector::from_iterator(n, powers.iter().zip(&refs).map(|(p, r)| (p / r.power).ln()));
        Ok((err, powers))
    };
    let mut x = DVector::zeros(n);
    let (mut err, mut powers) = eval(&x)?;
    // Forward-difference Jacobian d ln P / d ln factor.
    let mut jac = DMatrix::zeros(n, n);
    if err.amax() >= TOL {
        for j in 0..n {
            let mut xj = x.clone();
            xj[j] += FD_STEP;
            let (ej, _) = eval(&xj)?;
            jac.set_column(j, &((ej - &err) / FD_STEP));
        }
    }
    for _ in 0..STEPS {
        if err.amax() < TOL {
            return Ok(Calibration {
                factors: factors(&x),
                powers,
            });
        }
        let Some(step) = jac.clone().lu().solve(&(-&err)) else {
            return Err(LossError::Spec(format!(
                "the calibration's parameters act alike at its points (singular d ln P / d ln factor = {jac}): fit fewer parameters or points that tell them apart"
            )));
        };
        // A step whose model does not converge (a contact iteration at some trial
        // parameters) is halved, at most HALVINGS times.
        let mut step = step.map(|v| v.clamp(-MAX_STEP, MAX_STEP));
        // Shortened to stay within MAX_FACTOR; a step that cannot (a factor already at
        // the bound and pushed further out) ends the fit.
        let bound = MAX_FACTOR.ln();
        let room = (0..n)
            .filter(|&j| (x[j] + step[j]).abs() > bound)
            .map(|j| ((bound * step[j].signum() - x[j]) / step[j], j))
            .min_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((fraction, j)) = room {
            if fraction < 1e-6 {
                return Err(LossError::Spec(format!(
                    "the calibration would scale {} beyond a factor {MAX_FACTOR} of the scene's value (d ln P / d ln factor = {jac}): no fit within that range; fit fewer parameters or points that tell them apart",
                    params[j].key()
                )));
            }
            step *= fraction;
        }
        let mut tried = 0;
        let (x_new, e_new, p_new) = loop {
            let x_new = &x + &step;
            match eval(&x_new) {
                Ok((e, p)) => break (x_new, e, p),
                Err(e) if tried == HALVINGS => return Err(e),
                Err(e) => {
                    progress(&format!("  not solved ({e}): half the step"));
                    step *= 0.5;
                    tried += 1;
                }
            }
        };
        // Broyden: J += (Δe − J s) sᵀ / (sᵀ s).
        let ds = &e_new - &err - &jac * &step;
        jac += ds * step.transpose() / step.norm_squared();
        (x, err, powers) = (x_new, e_new, p_new);
    }
    Err(LossError::Calibration(STEPS))
}
