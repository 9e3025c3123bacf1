#!/usr/bin/env bash
# The whole test suite: formatting, lints, rustdoc, every Rust/C/Fortran test, the header check,
# the Python package's tests,
# sanitizer runs of the host programs and a short fuzz run.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
echo "== cargo fmt --check"
cargo fmt --all -- --check
echo "== cargo clippy -D warnings"
cargo clippy --workspace --all-targets --release -- -D warnings
echo "== rustdoc, warnings as errors"
# The harness and the Python crate are documented with their private items (their docs
# are for contributors); the library's public API last, so target/doc/jointlin is it.
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --lib --release --document-private-items
RUSTDOCFLAGS="-D warnings" cargo doc -p jointlin --no-deps --lib --release
echo "== cargo build (workspace, release)"
# The host-program tests load target/release/libjointlin.so and run target/release/jointlin:
# built first, so that a target directory kept from an earlier build never hands them a
# stale copy.
cargo build --workspace --release
echo "== cargo test (workspace, release)"
# Tests that need a missing external tool fail on CI and leave a note here elsewhere
# (tests/tools/mod.rs).
rm -rf target/tmp/skipped
cargo test --workspace --release
skipped=0
if [ -d target/tmp/skipped ]; then
    skipped=$(find target/tmp/skipped -type f | wc -l)
fi
echo "== Python package: wheel, fresh virtual environment, pytest"
bash scripts/python-tests.sh
echo "== documentation site: mdBook build, every link and anchor checked"
bash scripts/book.sh
echo "== README blocks regenerated and compared (those that take under a minute; timings left out)"
# The long ones: harness/tests/readme_blocks.rs (ignored tests).
bash scripts/readme-tables.sh --check seed_cases deck_keywords python_study accuracy_table \
    deck_stack tradeoff_block tradeoff_mass_on_plane backbone_plot backbone_chain_h7 \
    backbone_braced backbone_fe
# The sanitizer and fuzz runs need a nightly toolchain (ASan-instrumented library,
# libFuzzer): installed here, never silently replaced by a weaker run.
if ! cargo +nightly --version >/dev/null 2>&1; then
    if command -v rustup >/dev/null; then
        echo "== installing the nightly Rust toolchain (for ASan and libFuzzer)"
        rustup toolchain install nightly --profile minimal
    else
        echo "the sanitizer and fuzz runs need a nightly Rust toolchain: install rustup" >&2
        echo "(https://rustup.rs), then run:  rustup toolchain install nightly --profile minimal" >&2
        exit 1
    fi
fi
echo "== robustness: sanitizers, threaded valgrind, short fuzz run"
bash scripts/robustness.sh asan
bash scripts/robustness.sh valgrind
bash scripts/robustness.sh fuzz-ci 15
# Last, so that it is the summary a reader sees: tests that skipped for a missing tool
# (always 0 on CI, where a missing tool fails its test).
echo "tests skipped for a missing tool: $skipped"
if [ "$skipped" -gt 0 ]; then
    for f in target/tmp/skipped/*; do echo "  $(basename "$f"): $(cat "$f")"; done
fi
