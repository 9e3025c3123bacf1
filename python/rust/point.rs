//! The library's time-domain points as stateful Python objects: `Point` (one tangential
//! direction, `jointlin_point_step`, thesis §2.3.3) and `Point3d` (two tangential
//! directions and the normal one, `jointlin_point3d_step`). Each keeps its C-API state
//! array; a failed step leaves the state at the last accepted step.

use jointlin::ffi::error::JOINTLIN_OK;
use jointlin::ffi::linearize::jointlin_contact;
use jointlin::ffi::point::{jointlin_point_step, jointlin_step, JOINTLIN_POINT_STATE_LEN};
use jointlin::ffi::point3d::{
    jointlin_contact3d, jointlin_point3d_step, jointlin_step3d, JOINTLIN_POINT3D_STATE_LEN,
};
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{call_error, last_error, status_error};

/// One tangential direction of a contact point, stepped in slip (length).
#[pyclass(module = "jointlin._native")]
pub struct Point {
    contact: jointlin_contact,
    state: [f64; JOINTLIN_POINT_STATE_LEN],
}

impl Point {
    /// One C-API step from the held state; the state advances only on success.
    fn advance(&mut self, slip: f64) -> Result<jointlin_step, i32> {
        let mut next = [0.0; JOINTLIN_POINT_STATE_LEN];
        let mut out = jointlin_step::default();
        // SAFETY: the state arrays hold JOINTLIN_POINT_STATE_LEN doubles; all live.
        let s = unsafe {
            jointlin_point_step(
                &self.contact,
                self.state.as_ptr(),
                slip,
                next.as_mut_ptr(),
                &mut out,
            )
        };
        if s != JOINTLIN_OK {
            return Err(s);
        }
        self.state = next;
        Ok(out)
    }
}

#[pymethods]
impl Point {
    /// A virgin point at slip 0 of the contact (law, rule codes, μ, F_N in force, k_T0 in
    /// force/length); an invalid contact raises at once.
    #[new]
    fn new(
        py: Python<'_>,
        law: i32,
        rule: i32,
        mu: f64,
        normal_force: f64,
        k_t0: f64,
    ) -> PyResult<Self> {
        let mut p = Point {
            contact: jointlin_contact {
                law,
                rule,
                mu,
                normal_force,
                k_t0,
            },
            state: [0.0; JOINTLIN_POINT_STATE_LEN],
        };
        p.advance(0.0).map_err(|s| call_error(py, s))?;
        p.state = [0.0; JOINTLIN_POINT_STATE_LEN];
        Ok(p)
    }

    /// Moves to the slip `slip` (length): (force, tangent, dissipated energy).
    fn step(&mut self, py: Python<'_>, slip: f64) -> PyResult<(f64, f64, f64)> {
        let r = self.advance(slip).map_err(|s| call_error(py, s))?;
        Ok((r.force, r.tangent, r.dissipated))
    }

    /// Steps through `slips` in order: dict of arrays force, tangent, dissipated. A
    /// failing sample raises naming its index; the state is then the last good sample's.
    fn run<'py>(
        &mut self,
        py: Python<'py>,
        slips: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let x = slips.as_slice()?;
        let n = x.len();
        let (cols, failure) = py.detach(|| {
            let mut cols = [vec![0.0; n], vec![0.0; n], vec![0.0; n]];
            for (i, &u) in x.iter().enumerate() {
                match self.advance(u) {
                    Ok(r) => {
                        cols[0][i] = r.force;
                        cols[1][i] = r.tangent;
                        cols[2][i] = r.dissipated;
                    }
                    Err(s) => return (cols, Some((i, s, last_error()))),
                }
            }
            (cols, None)
        });
        if let Some((i, s, detail)) = failure {
            return Err(status_error(py, s, &format!("sample {i}: {detail}")));
        }
        let d = PyDict::new(py);
        for (name, col) in ["force", "tangent", "dissipated"].into_iter().zip(cols) {
            d.set_item(name, col.into_pyarray(py))?;
        }
        Ok(d)
    }

    /// The C-API state (JOINTLIN_POINT_STATE_LEN doubles), a copy.
    #[getter]
    fn state<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.state.to_vec().into_pyarray(py)
    }

    /// Back to the virgin state at slip 0.
    fn reset(&mut self) {
        self.state = [0.0; JOINTLIN_POINT_STATE_LEN];
    }
}

/// A contact point in three directions, stepped in (u1, u2, h): tangential relative
/// displacements and the overclosure (length; penetration positive).
#[pyclass(module = "jointlin._native")]
pub struct Point3d {
    contact: jointlin_contact3d,
    state: Box<[f64; JOINTLIN_POINT3D_STATE_LEN]>,
}

impl Point3d {
    /// One C-API step from the held state; the state advances only on success.
    fn advance(&mut self, disp: [f64; 3]) -> Result<jointlin_step3d, i32> {
        let mut next = [0.0; JOINTLIN_POINT3D_STATE_LEN];
        let mut out = jointlin_step3d::default();
        // SAFETY: the state arrays hold JOINTLIN_POINT3D_STATE_LEN doubles, disp 3; all live.
        let s = unsafe {
            jointlin_point3d_step(
                &self.contact,
                self.state.as_ptr(),
                disp.as_ptr(),
                next.as_mut_ptr(),
                &mut out,
            )
        };
        if s != JOINTLIN_OK {
            return Err(s);
        }
        *self.state = next;
        Ok(out)
    }
}

#[pymethods]
impl Point3d {
    /// A virgin point at (0, 0, 0) of the contact: law code and cells (0 = default), μ,
    /// k_T0 (force/length), the normal law code, its stiffness (k_N in force/length, or E*
    /// in force/length² for Hertz) and r* (length, Hertz only). An invalid contact raises.
    #[new]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        law: i32,
        cells: i32,
        mu: f64,
        k_t0: f64,
        normal_law: i32,
        normal_stiffness: f64,
        r_star: f64,
    ) -> PyResult<Self> {
        let mut p = Point3d {
            contact: jointlin_contact3d {
                law,
                cells,
                mu,
                k_t0,
                normal_law,
                normal_stiffness,
                r_star,
            },
            state: Box::new([0.0; JOINTLIN_POINT3D_STATE_LEN]),
        };
        p.advance([0.0; 3]).map_err(|s| call_error(py, s))?;
        *p.state = [0.0; JOINTLIN_POINT3D_STATE_LEN];
        Ok(p)
    }

    /// Moves to (u1, u2, h): (force (t1, t2, N), stiffness (9, row-major d force /
    /// d (u1, u2, h)), dissipated energy, regime code).
    fn step(
        &mut self,
        py: Python<'_>,
        u1: f64,
        u2: f64,
        h: f64,
    ) -> PyResult<([f64; 3], [f64; 9], f64, i32)> {
        let r = self.advance([u1, u2, h]).map_err(|s| call_error(py, s))?;
        Ok((r.force, r.stiffness, r.dissipated, r.regime))
    }

    /// Steps through the rows of `history` (flat, 3 per sample): dict of flat arrays force
    /// (3 per sample), stiffness (9 per sample), dissipated, regime. A failing sample
    /// raises naming its index; the state is then the last good sample's.
    fn run<'py>(
        &mut self,
        py: Python<'py>,
        history: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let x = history.as_slice()?;
        if x.len() % 3 != 0 {
            return Err(PyValueError::new_err(
                "history must hold 3 values per sample",
            ));
        }
        let n = x.len() / 3;
        let (force, stiffness, dissipated, regime, failure) = py.detach(|| {
            let (mut f, mut k) = (vec![0.0; 3 * n], vec![0.0; 9 * n]);
            let (mut e, mut g) = (vec![0.0; n], vec![0i32; n]);
            for i in 0..n {
                match self.advance([x[3 * i], x[3 * i + 1], x[3 * i + 2]]) {
                    Ok(r) => {
                        f[3 * i..3 * i + 3].copy_from_slice(&r.force);
                        k[9 * i..9 * i + 9].copy_from_slice(&r.stiffness);
                        e[i] = r.dissipated;
                        g[i] = r.regime;
                    }
                    Err(s) => return (f, k, e, g, Some((i, s, last_error()))),
                }
            }
            (f, k, e, g, None)
        });
        if let Some((i, s, detail)) = failure {
            return Err(status_error(py, s, &format!("sample {i}: {detail}")));
        }
        let d = PyDict::new(py);
        d.set_item("force", force.into_pyarray(py))?;
        d.set_item("stiffness", stiffness.into_pyarray(py))?;
        d.set_item("dissipated", dissipated.into_pyarray(py))?;
        d.set_item("regime", regime.into_pyarray(py))?;
        Ok(d)
    }

    /// The C-API state (JOINTLIN_POINT3D_STATE_LEN doubles), a copy.
    #[getter]
    fn state<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.state.to_vec().into_pyarray(py)
    }

    /// Back to the virgin state at (0, 0, 0).
    fn reset(&mut self) {
        *self.state = [0.0; JOINTLIN_POINT3D_STATE_LEN];
    }
}
