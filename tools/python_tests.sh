#!/usr/bin/env bash
# Build the Python package `mech` (mech-py, maturin) into a virtual environment under
# target/ and run its pytest suite. Needs python3 (>= 3.8) with venv and pip.
set -euo pipefail
cd "$(dirname "$0")/.."
VENV=target/py-venv
python3 -m venv "$VENV"
# shellcheck disable=SC1091
. "$VENV/bin/activate"
pip install --quiet --upgrade pip
pip install --quiet "maturin>=1.5,<2" "numpy>=1.21" pytest "dask[distributed]" pandas
maturin build --release --quiet -m mech-py/Cargo.toml -o target/wheels
pip install --quiet --force-reinstall --no-deps target/wheels/mech-*.whl
cd target && python -m pytest -q -p no:cacheprovider ../mech-py/tests
