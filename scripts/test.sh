#!/usr/bin/env bash
# The whole test suite: formatting, lints, every Rust/C/Fortran test, the header check.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
echo "== cargo fmt --check"
cargo fmt --all -- --check
echo "== cargo clippy -D warnings"
cargo clippy --workspace --all-targets --release -- -D warnings
echo "== cargo test (workspace, release)"
cargo test --workspace --release
