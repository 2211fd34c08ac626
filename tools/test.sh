#!/usr/bin/env bash
# Every test: the Rust workspace (cargo test), then the Python package built from this
# repository into a virtual environment and its pytest suite (mech-py/tests).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --workspace
tools/python_tests.sh
