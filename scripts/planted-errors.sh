#!/usr/bin/env bash
# Shows that eight tests against external references can fail: each expected value is
# moved by about twice the test's tolerance in a copy of the test, the test is run and
# must fail, and the file is restored (also on Ctrl-C). Exits 1 if a planted test
# passes. References: an independent closed-form eigenvalue (2-DOF Jenkins chain),
# the converged quadrature reference of k*, CalculiX's eigenfrequencies, the thesis's
# block amplitude, the RK4 time domain of a three-direction joint, the independent
# Duffing integration, the unit cell's closed-form describing function, the RK4 time
# domain of the three-direction point's balance (docs/accuracy.md, "Where each claim is
# tested", marks these rows).
set -euo pipefail
cd "$(dirname "$0")/.."
planted=""
restore() { [ -z "$planted" ] || git checkout -q -- "$planted"; }
trap restore EXIT INT TERM
plant() { # FILE OLD NEW -- CARGO_TEST_ARGS…
  local file=$1 old=$2 new=$3
  shift 4
  [ -z "$(git status --porcelain -- "$file")" ] || { echo "$file has local changes" >&2; exit 2; }
  python3 - "$file" "$old" "$new" <<'PY'
import sys
f, old, new = sys.argv[1:4]
s = open(f).read()
assert s.count(old) == 1, f"{f}: the planted line is not there once"
open(f, "w").write(s.replace(old, new))
PY
  planted=$file
  if out=$(cargo test --release -q "$@" 2>&1); then
    echo "PASSED despite the planted error: $file" >&2
    exit 1
  fi
  restore
  planted=""
  # Failed at an assertion, not at the build.
  echo "$out" | grep -q "panicked at" || { echo "$out" >&2; echo "the planted test did not run" >&2; exit 1; }
  echo "$out" | grep -A1 "panicked at" | head -2
}
echo "== independent closed form: 2-DOF Jenkins chain backbone, frequency +2e-8 (tolerance 1e-8)"
plant harness/src/backbone/tests.rs "refs.push((lam.norm(), -lam.re / lam.norm()));" \
  "refs.push((lam.norm() * (1.0 + 2e-8), -lam.re / lam.norm()));" -- -p jointlin-harness --lib two_dof_chain_against
echo "== converged quadrature: k* +1e-10 (tolerance 5e-11)"
plant src/linearize/tests.rs "let err = ((got.k_star - reference.k_star) / reference.k_star).abs();" \
  "let err = ((got.k_star - reference.k_star * (1.0 + 1e-10)) / reference.k_star).abs();" -- -p jointlin --lib default_matches_the_converged_reference
echo "== CalculiX: C3D8/C3D20 frequencies +2e-6 (tolerance 1e-6)"
plant harness/tests/elements_ccx.rs "map(|(a, b)| a / b - 1.0)" "map(|(a, b)| a / (b * (1.0 + 2e-6)) - 1.0)" \
  -- -p jointlin-harness --test elements_ccx same_formulation
echo "== thesis: the block's linearized amplitude +2 % (tolerance 1 %)"
plant tests/seed_cases.rs "deviation_percent(r.block_linearized, THESIS_BLOCK_LINEARIZED)" \
  "deviation_percent(r.block_linearized, THESIS_BLOCK_LINEARIZED * 1.02)" -- --test seed_cases block_linearized
echo "== time domain: RK4 amplitude of the three-direction joint +2 % (tolerance 1 %)"
plant harness/tests/lumped_joints3d.rs "rel(hb.x[0].norm(), td.amplitude[0])," \
  "rel(hb.x[0].norm(), td.amplitude[0] * 1.02)," -- -p jointlin-harness --test lumped_joints3d normal_load_variation
echo "== independent integration: Duffing's steady maximum 0.395574 +2e-6 (tolerance 1e-6)"
plant tests/seed_cases.rs "(r.duffing_rk_amplitude - INDEPENDENT_DUFFING_RK).abs() <= 1e-6" \
  "(r.duffing_rk_amplitude - (INDEPENDENT_DUFFING_RK + 2e-6)).abs() <= 1e-6" -- --test seed_cases duffing_rk4_maximum
echo "== closed form: the unit cell's describing function c1 +2e-9 (tolerance 1e-9)"
plant src/point3d/tests.rs "(l.c1 - exact.c1).abs() < 1e-9" "(l.c1 - exact.c1 - 2e-9).abs() < 1e-9" \
  -- -p jointlin --lib describing_function_of_a_unit_cell
echo "== time domain: the three-direction point's H = 7 amplitudes +2 % (tolerance 1 %)"
plant harness/tests/contact3d_lumped.rs "*v = (hb.amplitude(&sol.u, k) - td.amplitude[k]).abs()" \
  "*v = (hb.amplitude(&sol.u, k) - td.amplitude[k] * 1.02).abs()" -- -p jointlin-harness --test contact3d_lumped oblique_force
echo "all eight planted errors were caught"
