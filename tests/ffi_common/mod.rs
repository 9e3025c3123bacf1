//! Shared helpers of the tests/ffi_*.rs integration tests: one UINTER call's arguments,
//! owned by Rust, passed to `jointlin_uinter` exactly as a Fortran host would.

#![allow(dead_code)]

use jointlin::ffi::error::jointlin_last_error;
use jointlin::ffi::store::*;
use jointlin::ffi::uinter::*;

/// Block of Appendix C in per-area form (area 1): μ = 0.3, k_T0 = 1282.7, linear normal law
/// with k_N = 1e4 (so h = 2e-4 gives p ≈ 2, μp ≈ 0.6).
pub fn block_props() -> Vec<f64> {
    vec![0.0, 0.0, 0.3, 1282.7, 0.0, 1e4, 0.0]
}

#[derive(Clone)]
pub struct Uinter {
    pub stress: [f64; 3],
    pub ddsddr: [f64; 9],
    pub dviscous: [f64; 9],
    pub dstructural: [f64; 9],
    pub statev: Vec<f64>,
    pub sfd: f64,
    pub pnewdt: f64,
    pub rdisp: [f64; 3],
    pub drdisp: [f64; 3],
    pub time: [f64; 2],
    pub dtime: f64,
    pub freqr: f64,
    pub ciname: Vec<u8>,
    pub props: Vec<f64>,
    pub coords: [f64; 3],
    pub area: f64,
    pub node: i32,
    pub ndir: i32,
    pub mcrd: i32,
    pub kstep: i32,
    pub kinc: i32,
    pub linper: i32,
    pub lopenclose: i32,
    pub report: jointlin_uinter_report,
}

impl Uinter {
    pub fn new(props: Vec<f64>, ndir: i32) -> Self {
        let mut name = b"CP-BLOCK".to_vec();
        name.resize(80, b' '); // Fortran CHARACTER*80, blank padded
        Self {
            stress: [0.0; 3],
            ddsddr: [0.0; 9],
            dviscous: [0.0; 9],
            dstructural: [0.0; 9],
            statev: vec![0.0; 60],
            sfd: 0.0,
            pnewdt: 1.0,
            rdisp: [0.0; 3],
            drdisp: [0.0; 3],
            time: [0.0, 0.0],
            dtime: 0.1,
            freqr: 1.0,
            ciname: name,
            props,
            coords: [0.0, 0.0, 0.0],
            area: 1.0,
            node: 0,
            ndir,
            mcrd: 3,
            kstep: 1,
            kinc: 1,
            linper: 0,
            lopenclose: -1,
            report: jointlin_uinter_report::default(),
        }
    }

    /// Calls jointlin_uinter with every argument from `self`.
    pub fn call(&mut self, store: *const jointlin_store) -> i32 {
        unsafe {
            jointlin_uinter(
                store,
                self.stress.as_mut_ptr(),
                self.ddsddr.as_mut_ptr(),
                self.dviscous.as_mut_ptr(),
                self.dstructural.as_mut_ptr(),
                self.statev.as_mut_ptr(),
                &mut self.sfd,
                &mut self.pnewdt,
                self.rdisp.as_ptr(),
                self.drdisp.as_ptr(),
                self.time.as_ptr(),
                self.dtime,
                self.freqr,
                self.ciname.as_ptr().cast(),
                self.ciname.len(),
                self.props.as_ptr(),
                self.coords.as_ptr(),
                self.area,
                self.node,
                self.ndir,
                self.statev.len() as i32,
                self.props.len() as i32,
                self.mcrd,
                self.kstep,
                self.kinc,
                self.linper,
                &mut self.lopenclose,
                &mut self.report,
            )
        }
    }

    /// Moves the slips to `rdisp` (increments from the current values) and calls LINPER = 0.
    pub fn step_to(&mut self, rdisp: [f64; 3]) -> i32 {
        for ((d, new), old) in self.drdisp.iter_mut().zip(rdisp).zip(self.rdisp) {
            *d = new - old;
        }
        self.rdisp = rdisp;
        self.linper = 0;
        self.call(std::ptr::null())
    }

    /// Every output value, to check that nothing is NaN or that nothing changed.
    pub fn outputs(&self) -> Vec<f64> {
        let mut v: Vec<f64> = self
            .stress
            .iter()
            .chain(&self.ddsddr)
            .chain(&self.dviscous)
            .chain(&self.dstructural)
            .chain(&self.statev)
            .copied()
            .collect();
        v.extend([self.sfd, self.pnewdt, self.lopenclose as f64]);
        let r = &self.report;
        v.extend([
            r.point as f64,
            r.pressure,
            r.energy_per_cycle,
            r.dissipated_power,
        ]);
        v.extend(
            r.k_star
                .iter()
                .chain(&r.d_star)
                .chain(&r.eta)
                .chain(&r.amplitude),
        );
        v
    }
}

/// A store with the given initial amplitude, relative tolerance and KINC numbering.
pub fn new_store(initial: f64, rtol: f64, numbering: i32) -> *mut jointlin_store {
    let mut cfg = std::mem::MaybeUninit::<jointlin_store_config>::uninit();
    unsafe {
        assert_eq!(jointlin_store_config_default(cfg.as_mut_ptr()), 0);
        let mut cfg = cfg.assume_init();
        cfg.initial_amplitude = initial;
        cfg.rtol = rtol;
        cfg.kinc_numbering = numbering;
        let mut store = std::ptr::null_mut();
        assert_eq!(jointlin_store_new(&cfg, &mut store), 0);
        store
    }
}

/// The store's next action and pass number.
pub fn next_action(store: *const jointlin_store) -> (i32, i32) {
    let (mut action, mut pass) = (-1, -1);
    assert_eq!(
        unsafe { jointlin_store_next_action(store, &mut action, &mut pass) },
        0
    );
    (action, pass)
}

/// The increments listed for the next action.
pub fn increments(store: *const jointlin_store) -> Vec<i32> {
    let mut buf = [0i32; 64];
    let mut n = 0usize;
    assert_eq!(
        unsafe { jointlin_store_rerun_increments(store, buf.as_mut_ptr(), buf.len(), &mut n) },
        0
    );
    buf[..n].to_vec()
}

/// jointlin_uexternaldb with a dummy time.
pub fn uexternaldb(
    store: *const jointlin_store,
    lop: i32,
    lrestart: i32,
    kstep: i32,
    kinc: i32,
) -> i32 {
    let time = [0.0, 0.0];
    unsafe {
        jointlin::ffi::uexternaldb::jointlin_uexternaldb(
            store,
            lop,
            lrestart,
            time.as_ptr(),
            0.0,
            kstep,
            kinc,
        )
    }
}

/// The calling thread's last error message (jointlin_last_error).
pub fn last_error() -> String {
    let mut buf = [0 as std::ffi::c_char; 256];
    unsafe { jointlin_last_error(buf.as_mut_ptr(), buf.len()) };
    unsafe { std::ffi::CStr::from_ptr(buf.as_ptr()) }
        .to_string_lossy()
        .into_owned()
}
