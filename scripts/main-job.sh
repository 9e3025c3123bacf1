#!/usr/bin/env bash
# The main job: the thesis's three-beam study (§4.3) through the harness, writing tables
# (CSV, JSON) and SVG plots to out/three-beams.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
cargo run --release -p jointlin-harness --bin jointlin -- run scenes/three-beams.toml --out out/three-beams
echo "== results in out/three-beams"
