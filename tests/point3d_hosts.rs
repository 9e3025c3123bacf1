//! The three-direction point through the C API from a C program (gcc, include/jointlin.h)
//! and a Fortran program (gfortran, fortran-shim/jointlin.f90), both linked against the
//! libjointlin.so of this cargo build: an elliptic path with a normal load that varies and
//! opens the contact for part of each cycle, then the describing function on a circle and,
//! tabulated, for two complex amplitudes;
//! every printed number against the Rust core to 1e-12 relative.

mod hosts_common;

use std::f64::consts::PI;
use std::process::Command;

use hosts_common::{lib_dir, root, run_ok, scratch};
use jointlin::iterate::Complex64;
use jointlin::law::hertz::NormalLaw;
use jointlin::point3d::describing::{describe, Method};
use jointlin::point3d::phasors::describe_phasors;
use jointlin::point3d::{Contact3d, State3d, Tangential3d};

const STEPS: usize = 240;

fn path(j: usize) -> [f64; 3] {
    let th = 2.0 * PI * j as f64 / 80.0;
    [
        3e-3 * th.cos(),
        2e-3 * th.sin(),
        1e-3 * (1.0 + 1.2 * (0.5 * th).cos()),
    ]
}

const C_SRC: &str = r#"#include <math.h>
#include <stdio.h>
#include "jointlin.h"
int main(void) {
  jointlin_contact3d c = {JOINTLIN_LAW_MINDLIN, 8, 0.5, 1000.0, JOINTLIN_NORMAL_LINEAR, 2000.0, 0.0};
  static double state[JOINTLIN_POINT3D_STATE_LEN];
  jointlin_step3d out;
  for (int j = 1; j <= 240; ++j) {
    double th = 2.0 * M_PI * j / 80.0;
    double d[3] = {3e-3 * cos(th), 2e-3 * sin(th), 1e-3 * (1.0 + 1.2 * cos(0.5 * th))};
    if (jointlin_point3d_step(&c, state, d, state, &out) != JOINTLIN_OK) return 1;
    printf("%.17g %.17g %.17g %.17g %d\n", out.force[0], out.force[1], out.force[2], out.dissipated, out.regime);
  }
  jointlin_linearization3d l;
  if (jointlin_linearize3d(&c, 2.0, 2e-3, 2e-3, 100.0, &l) != JOINTLIN_OK) return 2;
  printf("%.17g %.17g %.17g %.17g %.17g %d\n", l.k_star[0], l.k_star[1], l.d_star[0], l.d_star[1], l.energy_per_cycle, l.regime);
  double u[4] = {2e-3, 5e-4, -1e-3, 1.5e-3};
  jointlin_linearization3d_matrix m;
  if (jointlin_linearize3d_phasors(&c, 2.0, u, 100.0, JOINTLIN_DESCRIBE_TABULATED, &m) != JOINTLIN_OK) return 3;
  for (int k = 0; k < 4; ++k) printf("%.17g ", m.k_star[k]);
  for (int k = 0; k < 4; ++k) printf("%.17g ", m.d_star[k]);
  printf("%.17g %d\n", m.energy_per_cycle, m.regime);
  return 0;
}
"#;

const F_SRC: &str = r#"program point3d
  use, intrinsic :: iso_c_binding, only: c_double, c_int32_t
  use jointlin
  implicit none
  type(jointlin_contact3d) :: c
  type(jointlin_step3d) :: out
  type(jointlin_linearization3d) :: l
  type(jointlin_linearization3d_matrix) :: m
  real(c_double) :: state(JOINTLIN_POINT3D_STATE_LEN), d(3), th, u(4)
  real(c_double), parameter :: pi = 4.0_c_double * atan(1.0_c_double)
  integer :: j
  c = jointlin_contact3d(JOINTLIN_LAW_MINDLIN, 8, 0.5_c_double, 1000.0_c_double, &
       JOINTLIN_NORMAL_LINEAR, 2000.0_c_double, 0.0_c_double)
  state = 0.0_c_double
  do j = 1, 240
     th = 2.0_c_double * pi * j / 80.0_c_double
     d = [3e-3_c_double * cos(th), 2e-3_c_double * sin(th), &
          1e-3_c_double * (1.0_c_double + 1.2_c_double * cos(0.5_c_double * th))]
     if (jointlin_point3d_step(c, state, d, state, out) /= JOINTLIN_OK) error stop 1
     write (*, '(4(es25.17e3,1x),i0)') out%force, out%dissipated, out%regime
  end do
  if (jointlin_linearize3d(c, 2.0_c_double, 2e-3_c_double, 2e-3_c_double, 100.0_c_double, l) &
       /= JOINTLIN_OK) error stop 2
  write (*, '(5(es25.17e3,1x),i0)') l%k_star, l%d_star, l%energy_per_cycle, l%regime
  u = [2e-3_c_double, 5e-4_c_double, -1e-3_c_double, 1.5e-3_c_double]
  if (jointlin_linearize3d_phasors(c, 2.0_c_double, u, 100.0_c_double, &
       JOINTLIN_DESCRIBE_TABULATED, m) /= JOINTLIN_OK) error stop 3
  write (*, '(9(es25.17e3,1x),i0)') m%k_star, m%d_star, m%energy_per_cycle, m%regime
end program point3d
"#;

fn expected() -> Vec<Vec<f64>> {
    let c = Contact3d {
        tangential: Tangential3d::MindlinMasing { cells: 8 },
        mu: 0.5,
        k_t0: 1000.0,
        normal: NormalLaw::Linear {
            stiffness_per_area: 2000.0,
        },
    };
    let mut st = State3d::default();
    let mut rows = Vec::new();
    for j in 1..=STEPS {
        let (next, r) = c.step(&st, path(j)).unwrap();
        st = next;
        let mut row = r.force.to_vec();
        row.extend([r.dissipated, r.regime as i32 as f64]);
        rows.push(row);
    }
    let d = describe(&c, 2.0, [2e-3, 2e-3], 100.0).unwrap();
    rows.push(vec![
        d.k_star[0],
        d.k_star[1],
        d.d_star[0],
        d.d_star[1],
        d.energy_per_cycle,
        d.regime as i32 as f64,
    ]);
    let u = [Complex64::new(2e-3, 5e-4), Complex64::new(-1e-3, 1.5e-3)];
    let m = describe_phasors(&c, 2.0, u, 100.0, Method::Tabulated).unwrap();
    let mut row: Vec<f64> = m
        .k_star
        .iter()
        .chain(&m.d_star)
        .flatten()
        .copied()
        .collect();
    row.extend([m.energy_per_cycle, m.regime as i32 as f64]);
    rows.push(row);
    rows
}

fn check(host: &str, stdout: &[u8], want: &[Vec<f64>]) {
    let text = String::from_utf8_lossy(stdout);
    let got: Vec<Vec<f64>> = text
        .lines()
        .map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(got.len(), want.len(), "{host}: {text}");
    // The path separates for part of each cycle: some rows are open, some slide.
    assert!(want.iter().any(|r| r[2] == 0.0) && want.iter().any(|r| r[2] > 0.0));
    for (i, (g, w)) in got.iter().zip(want).enumerate() {
        assert_eq!(g.len(), w.len());
        let scale = w.iter().map(|v| v.abs()).fold(0.0, f64::max);
        for (a, b) in g.iter().zip(w) {
            assert!(
                (a - b).abs() <= 1e-12 * scale,
                "{host} row {i}: {g:?} vs {w:?}"
            );
        }
    }
}

#[test]
fn c_and_fortran_hosts_step_and_describe_like_the_core() {
    let dir = scratch("point3d");
    let lib = lib_dir();
    let link = [
        format!("-L{}", lib.display()),
        "-ljointlin".to_string(),
        format!("-Wl,-rpath,{}", lib.display()),
    ];
    std::fs::write(dir.join("point3d.c"), C_SRC).unwrap();
    std::fs::write(dir.join("point3d.f90"), F_SRC).unwrap();
    run_ok(
        Command::new("gcc")
            .args(["-std=c99", "-D_DEFAULT_SOURCE", "-Wall", "-Werror"])
            .arg(format!("-I{}", root().join("include").display()))
            .args(["-o", "point3d_c", "point3d.c"])
            .args(&link)
            .arg("-lm")
            .current_dir(&dir),
    );
    run_ok(
        Command::new("gfortran")
            .args(["-Wall", "-c"])
            .arg(root().join("fortran-shim/jointlin.f90"))
            .current_dir(&dir),
    );
    run_ok(
        Command::new("gfortran")
            .args(["-Wall", "-o", "point3d_f", "point3d.f90"])
            .args(&link)
            .current_dir(&dir),
    );
    let want = expected();
    check(
        "C",
        &run_ok(&mut Command::new(dir.join("point3d_c"))).stdout,
        &want,
    );
    check(
        "Fortran",
        &run_ok(&mut Command::new(dir.join("point3d_f"))).stdout,
        &want,
    );
}
