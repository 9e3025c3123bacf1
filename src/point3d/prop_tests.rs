//! Random contacts and random paths (with separation, reversals, tiny and large normal
//! loads): every step succeeds with finite outputs, the tangential force stays inside the
//! circle μN, nothing dissipates negatively, and the state survives its stored form.

use super::*;
use crate::law::hertz::Hertz;
use proptest::prelude::*;

fn contact_strategy() -> impl Strategy<Value = Contact3d> {
    (
        prop_oneof![Just(0usize), 1usize..=MAX_CELLS],
        0.0f64..1.0,
        -3.0f64..6.0,
        any::<bool>(),
        -2.0f64..8.0,
    )
        .prop_map(|(cells, mu, log_k, hertz, log_n)| Contact3d {
            tangential: if cells == 0 {
                Tangential3d::Jenkins
            } else {
                Tangential3d::MindlinMasing { cells }
            },
            mu,
            k_t0: 10f64.powf(log_k),
            normal: if hertz {
                NormalLaw::Hertz {
                    hertz: Hertz::new(5.0, 10f64.powf(log_n)).unwrap(),
                    area: 1.0,
                }
            } else {
                NormalLaw::Linear {
                    stiffness_per_area: 10f64.powf(log_n),
                }
            },
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn random_paths_keep_the_force_inside_the_circle(
        c in contact_strategy(),
        path in prop::collection::vec((-1e-2f64..1e-2, -1e-2f64..1e-2, -1e-3f64..1e-3), 1..40),
    ) {
        let mut st = State3d::default();
        let cells = c.cell_count();
        for (u1, u2, h) in path {
            let (next, r) = c.step(&st, [u1, u2, h]).unwrap();
            let n = r.force[2];
            let t = r.force[0].hypot(r.force[1]);
            prop_assert!(n >= 0.0 && n.is_finite());
            prop_assert!(t <= c.mu * n * (1.0 + 1e-12) + 1e-300, "{t} > {}", c.mu * n);
            prop_assert!(r.dissipated >= 0.0 && r.dissipated.is_finite());
            prop_assert!(r.stiffness.iter().flatten().all(|v| v.is_finite()));
            prop_assert_eq!(r.regime == Regime::Open, c.mu * n == 0.0);
            prop_assert!(next.dissipated >= st.dissipated);
            let mut buf = [0.0; STATE3D_LEN];
            next.write(cells, &mut buf);
            prop_assert_eq!(State3d::read(&buf, cells).unwrap(), next);
            st = next;
        }
    }
}
