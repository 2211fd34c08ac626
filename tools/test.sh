#!/usr/bin/env bash
# Every test: the Rust workspace (cargo test), then the Python package built from this
# repository into a virtual environment and its pytest suite (mech-py/tests), then a
# one-minute fuzzing run of the run-time loader and the solvers (fuzz/).
set -euo pipefail
cd "$(dirname "$0")/.."
cargo test --workspace
tools/python_tests.sh
# A minute of mutated mechanisms through the run-time loader and every solver
# (README, "Hostile input"; `--cases 1000000` for the long run).
cargo run --release --quiet -p mech-fuzz -- --seconds 60
