//! Craig–Bampton reduction of a symmetric pair (K, M): the boundary DOFs kept as they
//! are, the interior represented by its static constraint modes Ψ = −K_II⁻¹ K_IB and
//! the lowest `modes` fixed-interface normal modes Φ (K_II φ = ω² M_II φ, mass
//! normalized: Φᵀ M_II Φ = I). With T = [I 0; Ψ Φ], K_r = Tᵀ K T and M_r = Tᵀ M T
//! (Craig & Bampton, AIAA J. 6 (1968) 1313; Craig & Kurdila, *Fundamentals of
//! Structural Dynamics*, 2006, §17.5). The reduced rows are the boundary DOFs in the
//! order given, then the modal coordinates (mass × length² … units of √mass·length).
//!
//! Dense: for the small models a test or an example reduces (a few hundred DOFs).

use nalgebra::DMatrix;

/// A reduced pair and the fixed-interface frequencies it keeps.
#[derive(Debug, Clone)]
pub struct Reduced {
    pub k: DMatrix<f64>,
    pub m: DMatrix<f64>,
    /// ω² of the kept fixed-interface modes (1/time²), ascending.
    pub interior_eigenvalues: Vec<f64>,
}

/// Reduces (K, M) onto the rows `boundary` and `modes` fixed-interface modes.
pub fn reduce(
    k: &DMatrix<f64>,
    m: &DMatrix<f64>,
    boundary: &[usize],
    modes: usize,
) -> Result<Reduced, String> {
    let n = k.nrows();
    if boundary.iter().any(|&b| b >= n) {
        return Err(format!("a boundary row is outside 0..{n}"));
    }
    let interior: Vec<usize> = (0..n).filter(|r| !boundary.contains(r)).collect();
    let (nb, ni) = (boundary.len(), interior.len());
    if modes > ni {
        return Err(format!("{modes} modes asked, the interior has {ni} DOFs"));
    }
    let sub = |a: &DMatrix<f64>, r: &[usize], c: &[usize]| {
        DMatrix::from_fn(r.len(), c.len(), |i, j| a[(r[i], c[j])])
    };
    let kii = sub(k, &interior, &interior);
    let kib = sub(k, &interior, boundary);
    let mii = sub(m, &interior, &interior);
    let chol_k = kii
        .clone()
        .cholesky()
        .ok_or("K_II is not positive definite: the boundary must hold the body")?;
    let psi = -chol_k.solve(&kib);
    // K_II φ = λ M_II φ with M_II = L Lᵀ: (L⁻¹ K_II L⁻ᵀ) y = λ y, φ = L⁻ᵀ y.
    let l = mii.cholesky().ok_or("M_II is not positive definite")?.l();
    let linv = l.clone().try_inverse().ok_or("M_II is singular")?;
    let a = &linv * &kii * linv.transpose();
    let a = (&a + a.transpose()) * 0.5;
    let eig = a.symmetric_eigen();
    let mut order: Vec<usize> = (0..ni).collect();
    order.sort_by(|&x, &y| eig.eigenvalues[x].total_cmp(&eig.eigenvalues[y]));
    let mut phi = DMatrix::<f64>::zeros(ni, modes);
    for (c, &o) in order.iter().take(modes).enumerate() {
        phi.set_column(c, &(linv.transpose() * eig.eigenvectors.column(o)));
    }
    // T in the original row order.
    let mut t = DMatrix::<f64>::zeros(n, nb + modes);
    for (c, &b) in boundary.iter().enumerate() {
        t[(b, c)] = 1.0;
    }
    for (i, &r) in interior.iter().enumerate() {
        for c in 0..nb {
            t[(r, c)] = psi[(i, c)];
        }
        for c in 0..modes {
            t[(r, nb + c)] = phi[(i, c)];
        }
    }
    let sym = |a: DMatrix<f64>| (&a + a.transpose()) * 0.5;
    Ok(Reduced {
        k: sym(t.transpose() * k * &t),
        m: sym(t.transpose() * m * &t),
        interior_eigenvalues: order
            .iter()
            .take(modes)
            .map(|&o| eig.eigenvalues[o])
            .collect(),
    })
}
