#!/usr/bin/env bash
# The whole test suite: formatting, lints, every Rust/C/Fortran test, the header check,
# sanitizer runs of the host programs and a short fuzz run.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
echo "== cargo fmt --check"
cargo fmt --all -- --check
echo "== cargo clippy -D warnings"
cargo clippy --workspace --all-targets --release -- -D warnings
echo "== cargo build (workspace, release)"
# The host-program tests load target/release/libjointlin.so and run target/release/jointlin:
# built first, so that a target directory kept from an earlier build never hands them a
# stale copy.
cargo build --workspace --release
echo "== cargo test (workspace, release)"
cargo test --workspace --release
echo "== robustness: sanitizers, threaded valgrind, short fuzz run"
bash scripts/robustness.sh asan
bash scripts/robustness.sh valgrind
bash scripts/robustness.sh fuzz-ci 15
