//! `jointlin mhb --backbones`: cost of backbones of the 3-DOF Jenkins chain
//! ([`super::mhb_chain::jenkins_chain`]): 100 modal amplitudes from a tenth of the first
//! slip onset to 300 times it, first order and EPMC at H = 1, 3, 7, as a Markdown table;
//! with scenes, the first-order backbone of FE scenes and their reduction ([`fe_row`]).

use std::time::Instant;

use crate::backbone::{epmc, fe, first_order, log_space};
use crate::capi;
use crate::mhb::default_samples;
use crate::model::Job;

use super::mhb_chain::jenkins_chain;

/// The table (wall times measured on this machine, one thread).
pub fn table() -> String {
    let sys = jenkins_chain(0.0);
    let mut s = String::from(
        "3-DOF Jenkins chain (`bench::mhb_chain::jenkins_chain`), mode 1, 100 modal amplitudes \
         q from 0.1 to 300 q_s (q_s: first slip onset):\n\n\
         | method | wall time [s] | amplitudes reached | C-API calls (linearize; point_step) |\n\
         |---|---:|---:|---:|\n",
    );
    let qs = first_order::stuck_mode(&sys, 1)
        .and_then(|m| first_order::stick_limit(&sys, &m.shape))
        .unwrap_or(1.0);
    let q = log_space(0.1 * qs, 300.0 * qs, 100);
    let t = Instant::now();
    let calls = capi::counts().linearize;
    let reached = first_order::backbone(&sys, 1, &q).map_or(0, |p| p.len());
    s += &format!(
        "| first order | {:.3e} | {reached} | {} |\n",
        t.elapsed().as_secs_f64(),
        capi::counts().linearize - calls
    );
    for h in [1usize, 3, 7] {
        let t = Instant::now();
        let steps = capi::point_steps();
        let reached = epmc::trace(&sys, 1, h, default_samples(h), &q).map_or(0, |t| t.points.len());
        s += &format!(
            "| EPMC H = {h} (N = {}) | {:.3e} | {reached} | {} |\n",
            default_samples(h),
            t.elapsed().as_secs_f64(),
            capi::point_steps() - steps
        );
    }
    s
}

/// Cost of the first-order backbone of an FE scene's mode 1 (`backbone::fe`): the
/// static step and reduction, then 100 modal amplitudes over the default range
/// ([`first_order::slip_range`]); one Markdown row.
pub fn fe_row(job: impl Into<Job>) -> Result<String, String> {
    let job: Job = job.into();
    let t = Instant::now();
    let p = job.build().map_err(|e| e.to_string())?;
    let r = fe::reduce(&p, &job.settings.effects, 1)?;
    let t_reduce = t.elapsed().as_secs_f64();
    let sys = &r.lumped.system;
    let (from, to) = first_order::slip_range(sys, 1).map_err(|e| e.to_string())?;
    let q = log_space(from, to, 100);
    let t = Instant::now();
    let calls = capi::counts().linearize;
    let reached = first_order::backbone(sys, 1, &q).map_or(0, |p| p.len());
    let t_backbone = t.elapsed().as_secs_f64();
    Ok(format!(
        "| {} | {} | {} | {} | {} | {:.3e} | {:.3e} | {reached} | {} |\n",
        job.file(),
        p.sys.dofs.n_free(),
        sys.elements.len(),
        r.modes,
        sys.n(),
        t_reduce,
        t_backbone,
        capi::counts().linearize - calls
    ))
}

/// The FE table's header.
pub const FE_HEADER: &str = "FE scenes, mode 1, first order, 100 modal amplitudes over the \
    default range (a tenth of the first slip onset to 30 times the last); reduction: \
    static step, Craig–Bampton onto the contact directions (`backbone::fe`):\n\n\
    | scene | free DOFs | joints | interior modes | reduced DOFs | reduction [s] | \
    backbone [s] | amplitudes reached | C-API calls (linearize) |\n\
    |---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
