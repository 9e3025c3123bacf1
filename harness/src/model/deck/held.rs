//! Whether a deck's model is held: every connected part (elements sharing nodes, joined
//! by ties and contact pairs) must have its six rigid-body motions u = t + θ × x
//! stopped by its zero boundary conditions, else the static and dynamic stiffness is
//! singular. A part with fewer than six independent constraints is named with the
//! number of rigid-body modes it keeps, before any factorization.

use nalgebra::{Matrix6, Vector3, Vector6};

use crate::fe::mesh::Model;

/// Relative size of the smallest eigenvalue of Rᵀ R (R: the rigid motions at the held
/// DOFs, positions scaled to the part's size) that still counts as a constraint.
const RANK_TOLERANCE: f64 = 1e-10;

/// A part that is not held: its rigid-body modes and some of its nodes (indices).
#[derive(Debug, Clone, PartialEq)]
pub struct Loose {
    pub modes: usize,
    pub nodes: Vec<usize>,
}

/// The parts of `model` (its elements and tied node pairs, joined further by the node
/// groups `couplings`: ties and contact points) that keep rigid-body modes.
pub fn loose_parts(model: &Model, couplings: &[Vec<usize>]) -> Vec<Loose> {
    let n = model.nodes.len();
    let mut parent: Vec<usize> = (0..n).collect();
    let find = |p: &mut Vec<usize>, mut i: usize| {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    };
    let join = |p: &mut Vec<usize>, a: usize, b: usize| {
        let (ra, rb) = (find(p, a), find(p, b));
        if ra != rb {
            p[ra] = rb;
        }
    };
    let mut used = vec![false; n];
    for e in &model.elements {
        for w in e.nodes.windows(2) {
            join(&mut parent, w[0], w[1]);
        }
        for &i in &e.nodes {
            used[i] = true;
        }
    }
    for group in couplings {
        for w in group.windows(2) {
            join(&mut parent, w[0], w[1]);
        }
    }
    for &[a, b] in &model.ties {
        join(&mut parent, a, b);
    }
    // Per part: its nodes, then Rᵀ R over its held DOFs.
    let mut parts: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
    for i in (0..n).filter(|&i| used[i]) {
        let r = find(&mut parent, i);
        parts.entry(r).or_default().push(i);
    }
    let mut out = Vec::new();
    for nodes in parts.into_values() {
        let modes = rigid_modes(model, &nodes);
        if modes > 0 {
            out.push(Loose { modes, nodes });
        }
    }
    out
}

/// The rigid-body modes of the part with `nodes` that its held DOFs leave free.
fn rigid_modes(model: &Model, nodes: &[usize]) -> usize {
    // Positions about the part's centre, scaled to its size, so that the translation
    // and rotation columns of R weigh alike.
    let x: Vec<Vector3<f64>> = nodes
        .iter()
        .map(|&i| Vector3::from(model.nodes[i]))
        .collect();
    let centre = x.iter().sum::<Vector3<f64>>() / x.len() as f64;
    let size = x
        .iter()
        .map(|p| (p - centre).norm())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let mut rtr = Matrix6::<f64>::zeros();
    let mut rows = 0usize;
    for (&i, p) in nodes.iter().zip(&x) {
        let q = (p - centre) / size;
        for c in 0..3 {
            if !model.fixed[3 * i + c] {
                continue;
            }
            // Component c of t + θ × q: t_c + (θ × q)_c.
            let mut e = Vector3::zeros();
            e[c] = 1.0;
            let rot = q.cross(&e); // (θ × q)·e = θ·(q × e)
            let row = Vector6::new(e[0], e[1], e[2], rot[0], rot[1], rot[2]);
            rtr += row * row.transpose();
            rows += 1;
        }
    }
    if rows == 0 {
        return 6;
    }
    let eig = rtr.symmetric_eigenvalues();
    let largest = eig.iter().fold(0.0f64, |a, &b| a.max(b));
    eig.iter()
        .filter(|&&l| l <= RANK_TOLERANCE * largest.max(1.0))
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fe::elements::box_mesh::box_mesh;
    use crate::fe::elements::ElementKind;
    use crate::fe::mesh::{Element, Material};

    fn bar() -> Model {
        let m = box_mesh(ElementKind::C3D8, [4.0, 1.0, 1.0], [4, 1, 1], 0.0, 0);
        let mut model = Model::new(vec![Material::new(1.0, 0.3, 1.0).unwrap()]);
        model.nodes = m.nodes.clone();
        model.elements = m
            .elements
            .iter()
            .map(|e| Element {
                kind: ElementKind::C3D8,
                nodes: e.clone(),
                material: 0,
            })
            .collect();
        model.fixed = vec![false; model.n_dofs()];
        model
    }

    #[test]
    fn rigid_modes_count_what_the_boundary_leaves_free() {
        let mut m = bar();
        assert_eq!(loose_parts(&m, &[])[0].modes, 6, "free");
        // One node pinned in x, y, z: the three rotations about it stay.
        m.fixed[0..3].fill(true);
        assert_eq!(loose_parts(&m, &[])[0].modes, 3);
        // The whole x = 0 face clamped: held.
        for (i, p) in m.nodes.clone().iter().enumerate() {
            if p[0] == 0.0 {
                m.fixed[3 * i..3 * i + 3].fill(true);
            }
        }
        assert!(loose_parts(&m, &[]).is_empty());
        // Only z held on the x = 0 face: x, y translations, the rotation about z and
        // the rotation about the face's y axis.
        for (i, p) in m.nodes.clone().iter().enumerate() {
            if p[0] == 0.0 {
                m.fixed[3 * i..3 * i + 2].fill(false);
            }
        }
        assert_eq!(loose_parts(&m, &[])[0].modes, 4);
        // Two bars, the second joined to the first's free end by a coupling: one part.
        let mut two = m.clone();
        for (i, p) in m.nodes.iter().enumerate() {
            if p[0] == 0.0 {
                two.fixed[3 * i..3 * i + 3].fill(true);
            }
        }
        let off = two.nodes.len();
        two.nodes
            .extend(m.nodes.iter().map(|p| [p[0] + 4.0, p[1], p[2]]));
        two.elements.extend(m.elements.iter().map(|e| Element {
            kind: e.kind,
            nodes: e.nodes.iter().map(|n| n + off).collect(),
            material: 0,
        }));
        two.fixed.extend(vec![false; 3 * off]);
        assert_eq!(
            loose_parts(&two, &[]).len(),
            1,
            "the second bar alone is free"
        );
        assert_eq!(loose_parts(&two, &[]).first().map(|l| l.modes), Some(6));
        let ends: Vec<Vec<usize>> = (0..off)
            .filter(|&i| m.nodes[i][0] == 4.0)
            .map(|i| {
                let j = (0..off)
                    .find(|&j| {
                        m.nodes[j][0] == 0.0
                            && m.nodes[j][1] == m.nodes[i][1]
                            && m.nodes[j][2] == m.nodes[i][2]
                    })
                    .unwrap();
                vec![i, j + off]
            })
            .collect();
        assert!(loose_parts(&two, &ends).is_empty());
    }
}
