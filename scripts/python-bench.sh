#!/usr/bin/env bash
# The cost of the Python package against the Rust loop (README, "Using jointlin from
# Python"): the Rust loop over the C entry, then the Python package on the same inputs.
# Prints Markdown.
set -euo pipefail
cd "$(dirname "$0")/.."
read -r _ ns _ sum < <(cargo run --release -q --example linearize_loop -- 1000000)
bash scripts/python.sh python/bench/linearize_cost.py "$ns" "$sum" 1000000
