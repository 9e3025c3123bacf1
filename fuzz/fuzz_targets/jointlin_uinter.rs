//! jointlin_uinter as Abaqus calls it, on a real store with an open increment: a sequence
//! of calls on one contact point (STATEV carried over, so the hysteresis history grows)
//! with arbitrary NDIR, NPROPS, NSTATV (arrays allocated to exactly those sizes), PROPS,
//! initial STATEV, RDISP/DRDISP (huge, tiny, alternating), FREQR, AREA, KINC, LINPER,
//! plus reports to the store and LOP 2/3 at the end. Properties: never
//! JOINTLIN_ERR_PANIC; on JOINTLIN_OK every output finite; on an error no output changed.

#![cfg_attr(not(feature = "replay"), no_main)]

#[path = "../src/common.rs"]
mod common;

use arbitrary::{Arbitrary, Unstructured};
use common::*;
use jointlin::ffi::store::*;
use jointlin::ffi::uexternaldb::jointlin_uexternaldb;
use jointlin::ffi::uinter::*;

#[derive(Debug, Arbitrary)]
struct Input {
    ndir: u8,
    nprops: u8,
    nstatv: u8,
    /// PROPS 1..=NPROPS: a code/value from the valid table, or anything.
    props: Vec<Prop>,
    statev: Vec<(u8, F)>,
    area: Near,
    name_len: u8,
    initial_amplitude: Near,
    calls: Vec<Call>,
}

#[derive(Debug, Clone, Copy, Arbitrary)]
enum Prop {
    Valid,
    Code(u8),
    Value(F),
}

#[derive(Debug, Arbitrary)]
struct Call {
    linper: u8,
    /// Overclosure relative to 1e-4, slips relative to δ* ≈ 1e-4 for the default props.
    h: Near,
    slip: [Near; 2],
    alternate: bool,
    stress1: Near,
    freqr: Near,
    kinc: i8,
    node: i8,
    coords: [Near; 3],
    mcrd: u8,
    report: Option<[Near; 2]>,
    null_report: bool,
}

/// A valid PROPS table (Mindlin, thesis rule, μ 0.3, k_T0 1282.7, linear normal 1e4).
const VALID: [f64; 12] = [
    0.0, 0.0, 0.3, 1282.7, 0.0, 1e4, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
];

fn run(data: &[u8]) {
    let Ok(input) = Input::arbitrary(&mut Unstructured::new(data)) else {
        return;
    };
    let ndir = match input.ndir % 8 {
        0..=2 => 3,
        3 | 4 => 2,
        5 => 1,
        6 => 0,
        _ => 4,
    };
    let nprops = 5 + i32::from(input.nprops % 12); // 5..=16
    let nstatv = 55 + i32::from(input.nstatv % 8); // 55..=62
    let mut props = vec![0.0; nprops as usize];
    for (i, p) in props.iter_mut().enumerate() {
        let valid = VALID.get(i).copied().unwrap_or(99.0);
        *p = match input.props.get(i).copied().unwrap_or(Prop::Valid) {
            Prop::Valid => valid,
            Prop::Code(c) => f64::from(c % 4),
            Prop::Value(f) => f.get(),
        };
    }
    // Simpson with a huge interval count is valid but slow: cap the work per call.
    if nprops >= 12 && props[10] == 1.0 && props[11] > f64::from(1 << 14) {
        return;
    }
    let mut statev = vec![0.0; nstatv as usize];
    for &(i, f) in &input.statev {
        if let Some(s) = statev.get_mut(usize::from(i)) {
            *s = f.get();
        }
    }
    let area = input.area.around(1.0);
    let mut name = b"CP-FUZZ".to_vec();
    name.resize(usize::from(input.name_len) * 2, b' ');

    let mut cfg = unsafe { std::mem::zeroed::<jointlin_store_config>() };
    assert_eq!(unsafe { jointlin_store_config_default(&mut cfg) }, 0);
    cfg.initial_amplitude = input.initial_amplitude.around(1e-4);
    let mut store = std::ptr::null_mut();
    if unsafe { jointlin_store_new(&cfg, &mut store) } != 0 {
        cfg.initial_amplitude = 1e-4;
        assert_eq!(unsafe { jointlin_store_new(&cfg, &mut store) }, 0);
    }
    let time = [0.0, 0.0];
    let db = |lop: i32, kinc: i32| unsafe {
        jointlin_uexternaldb(store, lop, 1, time.as_ptr(), 0.0, 1, kinc)
    };
    assert_eq!(db(0, 0), 0);
    assert_eq!(db(1, 1), 0);

    let n = usize::try_from(ndir).unwrap_or(0).clamp(1, 3);
    let mut rdisp = vec![0.0; n];
    let mut lopenclose = -1i32;
    for (k, call) in input.calls.iter().take(48).enumerate() {
        let sign = if call.alternate && k % 2 == 1 {
            -1.0
        } else {
            1.0
        };
        let mut new = vec![call.h.around(1e-4)];
        new.extend(call.slip.iter().map(|s| sign * s.around(1e-4)));
        new.truncate(n);
        let drdisp: Vec<f64> = new.iter().zip(&rdisp).map(|(a, b)| a - b).collect();
        let mut stress = vec![0.0; n];
        stress[0] = call.stress1.around(2.0);
        let mut ddsddr = vec![0.0; n * n];
        let mut dviscous = vec![0.0; n * n];
        let mut dstructural = vec![0.0; n * n];
        let mut sfd = 0.0;
        let mut pnewdt = 1.0;
        let mcrd = match call.mcrd % 5 {
            0 => 0,
            4 => 4,
            m => i32::from(m),
        };
        let coords: Vec<f64> = call
            .coords
            .iter()
            .take(mcrd.clamp(1, 3) as usize)
            .map(|c| c.around(1.0))
            .collect();
        let mut report = jointlin_uinter_report::default();
        let linper = match call.linper % 6 {
            0..=2 => 0,
            3 | 4 => 1,
            _ => 2,
        };
        let kinc = if call.kinc.unsigned_abs() < 100 {
            1
        } else {
            i32::from(call.kinc)
        };
        let before = (
            stress.clone(),
            ddsddr.clone(),
            dviscous.clone(),
            dstructural.clone(),
            statev.clone(),
            sfd,
            lopenclose,
        );
        let status = unsafe {
            jointlin_uinter(
                store,
                stress.as_mut_ptr(),
                ddsddr.as_mut_ptr(),
                dviscous.as_mut_ptr(),
                dstructural.as_mut_ptr(),
                statev.as_mut_ptr(),
                &mut sfd,
                &mut pnewdt,
                new.as_ptr(),
                drdisp.as_ptr(),
                time.as_ptr(),
                0.01,
                call.freqr.around(100.0),
                name.as_ptr().cast(),
                name.len(),
                props.as_ptr(),
                coords.as_ptr(),
                area,
                i32::from(call.node),
                ndir,
                nstatv,
                nprops,
                mcrd,
                1,
                kinc,
                linper,
                &mut lopenclose,
                if call.null_report {
                    std::ptr::null_mut()
                } else {
                    &mut report
                },
            )
        };
        assert_status("jointlin_uinter", status);
        if status == 0 {
            assert_finite("STRESS", &stress);
            assert_finite("DDSDDR", &ddsddr);
            assert_finite("DVISCOUS", &dviscous);
            assert_finite("DSTRUCTURAL", &dstructural);
            // STATEV(1:57) are the library's; entries past 57 are the host's (left as given).
            assert_finite("STATEV", &statev[..57]);
            assert_finite("SFD", &[sfd]);
            assert!(sfd >= 0.0, "SFD {sfd}");
            let r = &report;
            let mut v = vec![r.pressure, r.energy_per_cycle, r.dissipated_power];
            v.extend(
                r.amplitude
                    .iter()
                    .chain(&r.k_star)
                    .chain(&r.d_star)
                    .chain(&r.eta),
            );
            assert_finite("report", &v);
            rdisp = new;
            if linper == 1 && report.point > 0 {
                if let Some(a) = call.report {
                    let amp = [a[0].around(1e-4), a[1].around(1e-4)];
                    let s = unsafe { jointlin_store_report(store, report.point, 1, amp.as_ptr()) };
                    assert_status("jointlin_store_report", s);
                }
            }
        } else {
            let after = (
                stress,
                ddsddr,
                dviscous,
                dstructural,
                statev.clone(),
                sfd,
                lopenclose,
            );
            // Bitwise (NaN-safe) comparison: nothing may be written on an error.
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert!(
                bits(&before.0) == bits(&after.0)
                    && bits(&before.1) == bits(&after.1)
                    && bits(&before.2) == bits(&after.2)
                    && bits(&before.3) == bits(&after.3)
                    && bits(&before.4) == bits(&after.4)
                    && before.5.to_bits() == after.5.to_bits()
                    && before.6 == after.6,
                "outputs written on error {status}"
            );
        }
    }
    assert_status("LOP 2", db(2, 1));
    assert_status("LOP 3", db(3, 0));
    unsafe { jointlin_store_free(store) };
}

#[cfg(not(feature = "replay"))]
libfuzzer_sys::fuzz_target!(|data: &[u8]| run(data));

#[cfg(feature = "replay")]
fn main() {
    replay_main(run);
}
