#!/usr/bin/env bash
# Installs the Debian packages jointlin needs (as root), or prints the exact command to run.
# Sourced by scripts/main-job.sh and scripts/test.sh.
set -euo pipefail
JOINTLIN_DEBS=(gcc g++ make gfortran pkg-config libsuitesparse-dev libarpack2-dev libopenblas0-pthread valgrind
  openmpi-bin libopenmpi-dev calculix-ccx gmsh python3 python3-venv)
missing=()
for pkg in "${JOINTLIN_DEBS[@]}"; do
  dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
done
if [ ${#missing[@]} -gt 0 ]; then
  cmd="apt-get update && DEBIAN_FRONTEND=noninteractive apt-get install -y ${missing[*]}"
  if [ "$(id -u)" -eq 0 ]; then
    echo "== installing: ${missing[*]}"
    bash -c "$cmd"
  else
    echo "jointlin needs Debian packages that are missing: ${missing[*]}" >&2
    echo "Run as root:  sudo bash -c '$cmd'" >&2
    exit 1
  fi
fi
command -v cargo >/dev/null || { echo "cargo not found: install Rust (https://rustup.rs) first" >&2; exit 1; }
