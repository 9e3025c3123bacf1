//! Per-call cost of the linearization: the default method and each quadrature option on
//! the block of Appendix C (thesis rule) at microslip (A = 0.5δ*) and sliding (A = 2δ*).
//! The error-vs-cost table is `cargo run --release --example accuracy_table`. Also the
//! coupled element's describing function for two complex amplitudes (docs/contact3d.md
//! §4), integrated and tabulated, on a 32- and a 128-cell Mindlin–Masing point.

use criterion::{black_box, criterion_group, criterion_main, BenchmarkId, Criterion};
use jointlin::hysteresis::Rule;
use jointlin::law::TangentialLaw;
use jointlin::linearize::{linearize, Contact, Method};

fn block() -> Contact {
    Contact {
        law: TangentialLaw::Mindlin,
        rule: Rule::Thesis,
        mu: 0.3,
        normal_force: 2.0,
        k_t0: 1282.7,
    }
}

fn options(c: &mut Criterion) {
    let contact = block();
    let delta_star = 1.5 * 0.6 / 1282.7;
    let methods = [
        ("default", Method::default()),
        ("gauss64", Method::Gauss { points: 64 }),
        ("simpson256", Method::Simpson { intervals: 256 }),
        ("simpson4096", Method::Simpson { intervals: 4096 }),
    ];
    let mut group = c.benchmark_group("linearize");
    for (ratio_name, ratio) in [("microslip", 0.5), ("sliding", 2.0)] {
        for (name, method) in methods {
            group.bench_with_input(BenchmarkId::new(name, ratio_name), &ratio, |b, &r| {
                b.iter(|| {
                    linearize(black_box(&contact), black_box(r * delta_star), 1.3, method).unwrap()
                })
            });
        }
    }
    group.finish();
}

/// The C entry point a host calls: `jointlin_linearize` with the default method (NULL),
/// including the panic boundary and input checks.
fn c_api(c: &mut Criterion) {
    use jointlin::ffi::linearize::{jointlin_contact, jointlin_linearization};
    let contact = jointlin_contact {
        law: 0,
        rule: 0,
        mu: 0.3,
        normal_force: 2.0,
        k_t0: 1282.7,
    };
    let delta_star = 1.5 * 0.6 / 1282.7;
    let mut out = jointlin_linearization::default();
    c.bench_function("jointlin_linearize/default/microslip", |b| {
        b.iter(|| {
            // SAFETY: valid pointers to live locals; NULL method selects the default.
            let status = unsafe {
                jointlin::ffi::linearize::jointlin_linearize(
                    &contact,
                    black_box(0.5 * delta_star),
                    1.3,
                    std::ptr::null(),
                    &mut out,
                )
            };
            assert_eq!(status, 0);
            black_box(out.k_star)
        })
    });
}

/// `describe_phasors` on an ellipse of semi-axes (1, 0.4) δ* turned by 0.5 rad: the
/// integrated cells (the reference) against the table.
fn coupled(c: &mut Criterion) {
    use jointlin::iterate::Complex64;
    use jointlin::law::hertz::NormalLaw;
    use jointlin::point3d::describing::Method as Cells;
    use jointlin::point3d::phasors::describe_phasors;
    use jointlin::point3d::{Contact3d, Tangential3d};
    let delta_star = 1.5 * 0.6 / 1282.7;
    let (s, co) = 0.5f64.sin_cos();
    let (a1, a2) = (delta_star, 0.4 * delta_star);
    let u = [
        Complex64::new(a1 * co, a2 * s),
        Complex64::new(a1 * s, -a2 * co),
    ];
    let mut group = c.benchmark_group("linearize3d_phasors");
    group.sample_size(10);
    for cells in [32, 128] {
        let contact = Contact3d {
            tangential: Tangential3d::MindlinMasing { cells },
            mu: 0.3,
            k_t0: 1282.7,
            normal: NormalLaw::Linear {
                stiffness_per_area: 1e5,
            },
        };
        for (name, method) in [
            ("integrated", Cells::Integrated),
            ("tabulated", Cells::Tabulated),
        ] {
            group.bench_with_input(BenchmarkId::new(name, cells), &u, |b, u| {
                b.iter(|| describe_phasors(&contact, 2.0, black_box(*u), 1.3, method).unwrap())
            });
        }
    }
    group.finish();
}

criterion_group!(benches, options, c_api, coupled);
criterion_main!(benches);
