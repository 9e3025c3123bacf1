#!/usr/bin/env bash
# The Python package: a wheel built from python/ (maturin, PyO3), installed into a fresh
# virtual environment with its test dependencies, then its tests by pytest. pytest exits
# with 5 when it collects no tests: that, like any failure, fails this script.
# Needs target/release/libjointlin.so and target/release/jointlin (the tests compare
# with the C API and the program): scripts/test.sh builds them first.
set -euo pipefail
cd "$(dirname "$0")/.."
venv=target/python-venv
rm -rf "$venv" target/wheels
python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --upgrade pip
"$venv/bin/python" -m pip wheel --quiet --no-deps ./python -w target/wheels
wheel=$(ls target/wheels/jointlin-*.whl)
echo "built $wheel"
"$venv/bin/python" -m pip install --quiet "$wheel[test]"
# From outside the source tree, so `import jointlin` is the installed package.
(cd python/tests && ../../"$venv"/bin/python -c "import jointlin; print('import jointlin:', jointlin.__file__)")
JOINTLIN_REPO="$PWD" "$venv/bin/python" -m pytest -q -p no:cacheprovider --rootdir python python/tests "$@"
