//! jointlin_uexternaldb and the store calls in arbitrary order: LOP -1..=7, LRESTART,
//! KSTEP, KINC, NaN times, registration, estimates, reports (any amplitude), next action,
//! re-run lists with any capacity, pass stats, point status, restore, with a restart file
//! in a temporary directory that the input may also truncate or corrupt before a LOP 4.
//! Properties: never JOINTLIN_ERR_PANIC; estimates finite and > 0 on JOINTLIN_OK; the
//! re-run list never written past its capacity.

#![cfg_attr(not(feature = "replay"), no_main)]

#[path = "../src/common.rs"]
mod common;

use arbitrary::{Arbitrary, Unstructured};
use common::*;
use jointlin::ffi::store::*;
use jointlin::ffi::store_model::jointlin_store_set_model;
use jointlin::ffi::uexternaldb::jointlin_uexternaldb;
use std::path::PathBuf;
use std::sync::OnceLock;

#[derive(Debug, Arbitrary)]
struct Input {
    scheme: u8,
    numbering: u8,
    max_passes: u8,
    sweep_step: u8,
    rtol: Near,
    ops: Vec<Op>,
}

#[derive(Debug, Arbitrary)]
enum Op {
    Db {
        lop: i8,
        lrestart: i8,
        kstep: u8,
        kinc: i8,
        bad_time: bool,
    },
    Register {
        point: u8,
    },
    Estimate {
        point: u8,
        kinc: i8,
    },
    Report {
        point: u8,
        kinc: i8,
        amp: [Near; 2],
    },
    /// Estimate then report a contraction a* = c + s·a (what a host would do).
    Host {
        point: u8,
        kinc: i8,
        c: u8,
        s: i8,
    },
    Next,
    Rerun {
        cap: u8,
    },
    Stats {
        pass: i8,
    },
    Status {
        point: u8,
        kinc: i8,
    },
    Count,
    Restore,
    /// Truncates the restart file at `at` (fraction of 256) and/or flips a byte.
    Corrupt {
        at: u8,
        flip: Option<(u16, u8)>,
    },
    /// Sets the model fingerprint (none for 0), then saved files and restores check it;
    /// `utf8` puts a two-byte character into the file at `at` (fraction of 256).
    Model {
        id: u8,
        utf8: Option<u8>,
    },
}

fn restart_path() -> &'static PathBuf {
    static P: OnceLock<PathBuf> = OnceLock::new();
    P.get_or_init(|| {
        let d = std::env::temp_dir().join(format!("jointlin-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        d.join("store.restart")
    })
}

fn kinc_of(k: i8) -> i32 {
    if k.unsigned_abs() < 120 {
        i32::from(k.rem_euclid(6))
    } else {
        i32::from(k) * 1000
    }
}

fn run(data: &[u8]) {
    let Ok(input) = Input::arbitrary(&mut Unstructured::new(data)) else {
        return;
    };
    let path = restart_path();
    let _ = std::fs::remove_file(path);
    let bytes = path.as_os_str().as_encoded_bytes();
    let mut cfg = unsafe { std::mem::zeroed::<jointlin_store_config>() };
    assert_eq!(unsafe { jointlin_store_config_default(&mut cfg) }, 0);
    cfg.initial_amplitude = 1e-3;
    cfg.scheme = i32::from(input.scheme % 3);
    cfg.kinc_numbering = i32::from(input.numbering % 2);
    cfg.max_passes = 1 + i32::from(input.max_passes % 6);
    cfg.sweep_step = i32::from(input.sweep_step % 3);
    let rtol = input.rtol.around(1e-3);
    if (0.0..1.0).contains(&rtol) {
        cfg.rtol = rtol;
    }
    cfg.restart_path = bytes.as_ptr().cast();
    cfg.restart_path_len = bytes.len();
    let mut store = std::ptr::null_mut();
    assert_eq!(unsafe { jointlin_store_new(&cfg, &mut store) }, 0);
    let mut ids: Vec<i64> = Vec::new();
    let id_of = |ids: &[i64], p: u8| -> i64 {
        match p {
            250..=255 => i64::from(p) - 253, // -3..=2: unknown or raw ids
            _ if ids.is_empty() => 1,
            _ => ids[usize::from(p) % ids.len()],
        }
    };
    for op in input.ops.iter().take(200) {
        match *op {
            Op::Db {
                lop,
                lrestart,
                kstep,
                kinc,
                bad_time,
            } => {
                let time = if bad_time {
                    [f64::NAN, 0.0]
                } else {
                    [0.0, 1.0]
                };
                let s = unsafe {
                    jointlin_uexternaldb(
                        store,
                        i32::from(lop % 9),
                        i32::from(lrestart % 4),
                        time.as_ptr(),
                        0.1,
                        i32::from(kstep % 4),
                        kinc_of(kinc),
                    )
                };
                assert_status("jointlin_uexternaldb", s);
            }
            Op::Register { point } => {
                let name = b"FUZZ-SURF   ";
                let coords = [f64::from(point % 16), -0.0, 1.0];
                let mut id = -1;
                let s = unsafe {
                    jointlin_store_register_point(
                        store,
                        name.as_ptr().cast(),
                        name.len(),
                        0,
                        coords.as_ptr(),
                        3,
                        &mut id,
                    )
                };
                assert_status("register", s);
                if s == 0 {
                    assert!(id >= 1);
                    ids.push(id);
                }
            }
            Op::Estimate { point, kinc } => {
                let mut amp = [-1.0; 2];
                let s = unsafe {
                    jointlin_store_estimate(
                        store,
                        id_of(&ids, point),
                        kinc_of(kinc),
                        amp.as_mut_ptr(),
                    )
                };
                assert_status("estimate", s);
                if s == 0 {
                    assert!(
                        amp.iter().all(|a| a.is_finite() && *a > 0.0),
                        "estimate {amp:?}"
                    );
                }
            }
            Op::Report { point, kinc, amp } => {
                let a = [amp[0].around(1e-3), amp[1].around(1e-3)];
                let s = unsafe {
                    jointlin_store_report(store, id_of(&ids, point), kinc_of(kinc), a.as_ptr())
                };
                assert_status("report", s);
            }
            Op::Host { point, kinc, c, s } => {
                let (id, k) = (id_of(&ids, point), kinc_of(kinc));
                let mut amp = [-1.0; 2];
                if unsafe { jointlin_store_estimate(store, id, k, amp.as_mut_ptr()) } == 0 {
                    assert!(
                        amp.iter().all(|a| a.is_finite() && *a > 0.0),
                        "estimate {amp:?}"
                    );
                    let slope = f64::from(s) / 64.0;
                    let c = 1e-3 * (1.0 + f64::from(c) / 32.0);
                    let out = amp.map(|a| (c + slope * a).abs());
                    let st = unsafe { jointlin_store_report(store, id, k, out.as_ptr()) };
                    assert_status("report", st);
                }
            }
            Op::Next => {
                let (mut a, mut p) = (-1, -1);
                let s = unsafe { jointlin_store_next_action(store, &mut a, &mut p) };
                assert_status("next_action", s);
                if s == 0 {
                    assert!((0..=5).contains(&a) && p >= 0, "action {a} pass {p}");
                }
            }
            Op::Rerun { cap } => {
                let cap = usize::from(cap % 12);
                let mut buf = vec![-77i32; cap + 4];
                let mut count = 0usize;
                let s = unsafe {
                    jointlin_store_rerun_increments(
                        store,
                        if cap == 0 {
                            std::ptr::null_mut()
                        } else {
                            buf.as_mut_ptr()
                        },
                        cap,
                        &mut count,
                    )
                };
                assert_status("rerun_increments", s);
                assert!(buf[cap..].iter().all(|&x| x == -77), "written past cap");
                if s == 0 {
                    assert!(count <= cap);
                    assert!(buf[..count].windows(2).all(|w| w[0] < w[1]), "{buf:?}");
                }
            }
            Op::Stats { pass } => {
                let mut st = jointlin_pass_stats::default();
                let s = unsafe { jointlin_store_pass_stats(store, i32::from(pass), &mut st) };
                assert_status("pass_stats", s);
            }
            Op::Status { point, kinc } => {
                let mut st = jointlin_point_status::default();
                let s = unsafe {
                    jointlin_store_point_status(store, id_of(&ids, point), kinc_of(kinc), &mut st)
                };
                assert_status("point_status", s);
                if s == 0 {
                    assert_finite(
                        "status",
                        &[
                            st.estimate[0],
                            st.estimate[1],
                            st.computed[0],
                            st.computed[1],
                        ],
                    );
                }
            }
            Op::Count => {
                let mut n = -1;
                assert_eq!(unsafe { jointlin_store_point_count(store, &mut n) }, 0);
                assert!(n >= 0);
            }
            Op::Restore => {
                let s = unsafe { jointlin_store_restore(store) };
                assert_status("restore", s);
            }
            Op::Corrupt { at, flip } => {
                if let Ok(mut text) = std::fs::read(path) {
                    let cut = text.len() * usize::from(at) / 255;
                    text.truncate(cut.max(1));
                    if let Some((i, b)) = flip {
                        let i = usize::from(i) % text.len();
                        text[i] = b;
                    }
                    std::fs::write(path, text).unwrap();
                }
            }
            Op::Model { id, utf8 } => {
                let fp = [id];
                let len = usize::from(id != 0);
                let s = unsafe { jointlin_store_set_model(store, fp.as_ptr().cast(), len) };
                assert_eq!(s, 0, "set_model");
                if let (Some(at), Ok(text)) = (utf8, std::fs::read(path)) {
                    let cut = text.len() * usize::from(at) / 255;
                    let mut t = text[..cut].to_vec();
                    t.extend_from_slice("é".as_bytes());
                    t.extend_from_slice(&text[cut..]);
                    std::fs::write(path, t).unwrap();
                }
            }
        }
    }
    unsafe { jointlin_store_free(store) };
}

#[cfg(not(feature = "replay"))]
libfuzzer_sys::fuzz_target!(|data: &[u8]| run(data));

#[cfg(feature = "replay")]
fn main() {
    replay_main(run);
}
