#!/usr/bin/env bash
# The Python package's pytest suite (mech-py/tests), as tests/python_package.rs runs it:
# tools/wheel_check.sh builds the wheel (maturin, in a virtual environment under target/),
# installs it into a fresh virtual environment and runs pytest there with no cargo or rustc
# on PATH. Needs python3 (>= 3.8) with venv and pip.
set -euo pipefail
exec bash "$(dirname "$0")/wheel_check.sh" "$@"
