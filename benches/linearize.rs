//! Per-call cost of the linearization: the default method and each quadrature option on
//! the block of Appendix C (thesis rule) at microslip (A = 0.5δ*) and sliding (A = 2δ*).
//! The error-vs-cost table is `cargo run --release --example accuracy_table`.

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

criterion_group!(benches, options, c_api);
criterion_main!(benches);
