use super::*;

fn contact(law: TangentialLaw, rule: Rule) -> Contact {
    Contact {
        law,
        rule,
        mu: 0.3,
        normal_force: 2.0,
        k_t0: 1282.7,
    }
}

#[test]
fn explore_errors() {
    for rule in [Rule::Thesis, Rule::Masing] {
        let c = contact(TangentialLaw::Mindlin, rule);
        let ds = 0.9 / 1282.7;
        for n in [4, 6, 8, 10, 12, 16, 24] {
            let mut worst: f64 = 0.0;
            let mut at = 0.0;
            for i in 0..=400 {
                let r = 10f64.powf(-12.0 + 18.0 * i as f64 / 400.0);
                let rs = [
                    r,
                    5.0 / 6.0 * (1.0 + 1e-9),
                    5.0 / 6.0 * (1.0 - 1e-9),
                    1.0 + 1e-9,
                    1.0 - 1e-9,
                    5.0 / 6.0,
                    1.0,
                ];
                for r in rs {
                    let a = r * ds;
                    let reference = linearize(&c, a, 1.0, Method::Graded { points: 64 }).unwrap();
                    let got = linearize(&c, a, 1.0, Method::Graded { points: n }).unwrap();
                    let err = ((got.k_star - reference.k_star) / reference.k_star).abs();
                    if err > worst {
                        worst = err;
                        at = r;
                    }
                }
            }
            eprintln!("{rule:?} n={n} worst {worst:e} at A/δ*={at:e}");
        }
    }
}
