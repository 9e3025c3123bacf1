#!/usr/bin/env bash
# Regenerates the Abaqus example jobs of examples/abaqus/ from their scenes with
# `jointlin export` (harness/tests/export_roundtrip.rs checks that the committed files
# are what this writes): each job directory gets its deck, sweep.frq and jointlin.cfg.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p jointlin-harness
J=target/release/jointlin
$J export scenes/block-on-plane.toml --inp examples/abaqus/block-on-plane/block.inp
$J export scenes/three-beams-coarse.toml --inp examples/abaqus/three-beams/three-beams.inp
