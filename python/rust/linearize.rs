//! Vectorized linearizations: one C-API call per element of equally long flat arrays
//! (the Python half broadcasts), with the GIL released over the loop. A failed element
//! gets its status and NaN fields (no value, marked); the loop goes on.

use jointlin::ffi::error::JOINTLIN_OK;
use jointlin::ffi::linearize::{
    jointlin_contact, jointlin_linearization, jointlin_linearize, jointlin_method,
};
use jointlin::ffi::point3d::{
    jointlin_contact3d, jointlin_linearization3d, jointlin_linearize3d, JOINTLIN_NORMAL_LINEAR,
};
use jointlin::ffi::screw::jointlin_screw_preload;
use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::last_error;

/// The first failing element: its flat index, status and the library's detail.
type FirstFailure = Option<(usize, i32, String)>;

/// Equally long slices of the inputs, or a ValueError naming the lengths.
fn slices<'a, const N: usize>(
    arrays: [&'a PyReadonlyArray1<'_, f64>; N],
) -> PyResult<[&'a [f64]; N]> {
    let mut out = [&[][..]; N];
    for (o, a) in out.iter_mut().zip(arrays) {
        *o = a.as_slice()?;
    }
    if out.iter().any(|s| s.len() != out[0].len()) {
        let lens: Vec<usize> = out.iter().map(|s| s.len()).collect();
        return Err(PyValueError::new_err(format!(
            "inputs of unequal lengths {lens:?}"
        )));
    }
    Ok(out)
}

/// Records the first failure of a loop.
fn note_failure(first: &mut FirstFailure, i: usize, status: i32) {
    if first.is_none() {
        *first = Some((i, status, last_error()));
    }
}

/// The results of a loop over elements: K value columns (NaN where the call failed), the
/// regime (-1 where it failed), the status and the first failure.
struct Columns<const K: usize> {
    values: [Vec<f64>; K],
    regime: Vec<i32>,
    status: Vec<i32>,
    first: FirstFailure,
}

impl<const K: usize> Columns<K> {
    /// `call(i)` for each of `n` elements: its values and regime, or its status.
    fn collect(n: usize, call: impl Fn(usize) -> Result<([f64; K], i32), i32>) -> Self {
        let mut c = Columns {
            values: std::array::from_fn(|_| vec![f64::NAN; n]),
            regime: vec![-1; n],
            status: vec![JOINTLIN_OK; n],
            first: None,
        };
        for i in 0..n {
            match call(i) {
                Ok((values, regime)) => {
                    for (col, v) in c.values.iter_mut().zip(values) {
                        col[i] = v;
                    }
                    c.regime[i] = regime;
                }
                Err(s) => {
                    c.status[i] = s;
                    note_failure(&mut c.first, i, s);
                }
            }
        }
        c
    }

    /// The columns as a dict: `names` for the values, then regime, status and
    /// first_failure.
    fn into_dict<'py>(self, py: Python<'py>, names: [&str; K]) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (name, col) in names.into_iter().zip(self.values) {
            d.set_item(name, col.into_pyarray(py))?;
        }
        d.set_item("regime", self.regime.into_pyarray(py))?;
        d.set_item("status", self.status.into_pyarray(py))?;
        d.set_item("first_failure", self.first)?;
        Ok(d)
    }
}

/// `jointlin_linearize` per element: law and rule codes, μ, F_N (force), k_T0
/// (force/length), A (length), ω (rad/time), the quadrature (kind, points; 0 = default).
/// Returns a dict of arrays k_star, d_star, eta, energy_per_cycle, peak_force,
/// slip_limit, amplitude_ratio (float), regime, status (int32) and `first_failure`
/// (None or (index, status, detail)).
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub fn linearize<'py>(
    py: Python<'py>,
    law: i32,
    rule: i32,
    mu: PyReadonlyArray1<'py, f64>,
    normal_force: PyReadonlyArray1<'py, f64>,
    k_t0: PyReadonlyArray1<'py, f64>,
    amplitude: PyReadonlyArray1<'py, f64>,
    omega: PyReadonlyArray1<'py, f64>,
    method: i32,
    points: i32,
) -> PyResult<Bound<'py, PyDict>> {
    let [mu, fnorm, kt, amp, om] = slices([&mu, &normal_force, &k_t0, &amplitude, &omega])?;
    let n = mu.len();
    let method = jointlin_method {
        kind: method,
        points,
    };
    let columns = py.detach(|| {
        Columns::collect(n, |i| {
            let c = jointlin_contact {
                law,
                rule,
                mu: mu[i],
                normal_force: fnorm[i],
                k_t0: kt[i],
            };
            let mut l = jointlin_linearization::default();
            // SAFETY: all pointers are to live locals.
            match unsafe { jointlin_linearize(&c, amp[i], om[i], &method, &mut l) } {
                JOINTLIN_OK => Ok((
                    [
                        l.k_star,
                        l.d_star,
                        l.eta,
                        l.energy_per_cycle,
                        l.peak_force,
                        l.slip_limit,
                        l.amplitude_ratio,
                    ],
                    l.regime,
                )),
                s => Err(s),
            }
        })
    });
    columns.into_dict(
        py,
        [
            "k_star",
            "d_star",
            "eta",
            "energy_per_cycle",
            "peak_force",
            "slip_limit",
            "amplitude_ratio",
        ],
    )
}

/// `jointlin_linearize3d` per element for one contact (law code, cells, μ, k_T0): F_N
/// (force), the path's semi-axes A1, A2 (length) and ω (rad/time). Returns a dict of
/// arrays k_star_1, k_star_2, d_star_1, d_star_2, energy_per_cycle, regime, status and
/// `first_failure`.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub fn linearize3d<'py>(
    py: Python<'py>,
    law: i32,
    cells: i32,
    mu: f64,
    k_t0: f64,
    normal_force: PyReadonlyArray1<'py, f64>,
    amplitude_1: PyReadonlyArray1<'py, f64>,
    amplitude_2: PyReadonlyArray1<'py, f64>,
    omega: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let [fnorm, a1, a2, om] = slices([&normal_force, &amplitude_1, &amplitude_2, &omega])?;
    let n = fnorm.len();
    // The describing function does not use the normal law (the normal force is given).
    let c = jointlin_contact3d {
        law,
        cells,
        mu,
        k_t0,
        normal_law: JOINTLIN_NORMAL_LINEAR,
        normal_stiffness: 1.0,
        r_star: 1.0,
    };
    let columns = py.detach(|| {
        Columns::collect(n, |i| {
            let mut l = jointlin_linearization3d::default();
            // SAFETY: all pointers are to live locals.
            match unsafe { jointlin_linearize3d(&c, fnorm[i], a1[i], a2[i], om[i], &mut l) } {
                JOINTLIN_OK => Ok((
                    [
                        l.k_star[0],
                        l.k_star[1],
                        l.d_star[0],
                        l.d_star[1],
                        l.energy_per_cycle,
                    ],
                    l.regime,
                )),
                s => Err(s),
            }
        })
    });
    columns.into_dict(
        py,
        [
            "k_star_1",
            "k_star_2",
            "d_star_1",
            "d_star_2",
            "energy_per_cycle",
        ],
    )
}

/// `jointlin_screw_preload` per element: torque (force·length), pitch, flank diameter
/// d2, head diameter d_km (length), thread and head friction. Returns a dict of arrays
/// preload (force), regime (0: none applies), status and `first_failure`.
#[pyfunction]
pub fn screw_preload<'py>(
    py: Python<'py>,
    torque: PyReadonlyArray1<'py, f64>,
    pitch: PyReadonlyArray1<'py, f64>,
    d2: PyReadonlyArray1<'py, f64>,
    mu_thread: PyReadonlyArray1<'py, f64>,
    mu_head: PyReadonlyArray1<'py, f64>,
    d_km: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let [t, p, d2, mt, mh, dk] = slices([&torque, &pitch, &d2, &mu_thread, &mu_head, &d_km])?;
    let n = t.len();
    let columns = Columns::collect(n, |i| {
        let mut f = 0.0;
        // SAFETY: `f` is a live local.
        match unsafe { jointlin_screw_preload(t[i], p[i], d2[i], mt[i], mh[i], dk[i], &mut f) } {
            JOINTLIN_OK => Ok(([f], 0)),
            s => Err(s),
        }
    });
    columns.into_dict(py, ["preload"])
}
