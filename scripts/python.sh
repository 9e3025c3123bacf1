#!/usr/bin/env bash
# Runs Python with the jointlin package installed: `bash scripts/python.sh SCRIPT ARGS…`.
# The environment is target/python-venv (built with the wheel and its test extras by
# scripts/python-tests.sh when missing).
set -euo pipefail
cd "$(dirname "$0")/.."
py=target/python-venv/bin/python
if ! { [ -x "$py" ] && "$py" -c "import jointlin, matplotlib" 2>/dev/null; }; then
  echo "== building the Python package into target/python-venv" >&2
  bash scripts/python-tests.sh -q >&2
fi
exec "$py" "$@"
