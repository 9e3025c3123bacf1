//! `jointlin mhb --backbones`: cost of backbones of the 3-DOF Jenkins chain
//! ([`super::mhb_chain::jenkins_chain`]): 100 modal amplitudes from a tenth of the first
//! slip onset to 300 times it, first order and EPMC at H = 1, 3, 7, as a Markdown table.

use std::time::Instant;

use crate::backbone::{epmc, first_order, log_space};
use crate::capi;
use crate::mhb::default_samples;

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
