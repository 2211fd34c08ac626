#!/usr/bin/env bash
# `mech serve`'s page in a real browser (headless Chromium driven by Playwright): installs
# what is missing, then runs tools/serve_check.py, which prints PASS/FAIL per check and a
# last line `serve_check: N passed, M failed`.
#
#     bash tools/serve_check.sh            # builds mech, checks; screenshots in target/serve-check/
#     bash tools/serve_check.sh --docs     # also writes docs/img/serve.png (the README's picture)
#
# mech-cli/tests/serve.rs runs this (so `cargo test --workspace` does), passing its own
# binary as MECH_BIN. Needs: Debian's `chromium` (apt-get install, as root, when missing),
# python3 with venv and pip, and pip's access to PyPI for `playwright` (its Python package
# only: it drives Debian's chromium, never downloads a browser of its own).
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
TARGET=${CARGO_TARGET_DIR:-$ROOT/target}
say() { echo "serve_check: $*" >&2; }

# 1. Chromium, Debian's package.
CHROME=$(command -v chromium || true)
if [ -z "$CHROME" ]; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
        say "installing Debian's chromium"
        apt-get update -qq >&2
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >&2
        CHROME=$(command -v chromium)
    else
        say "no chromium, and no root apt-get to install it: apt-get install -y chromium"
        exit 1
    fi
fi

# 2. Playwright in a virtual environment under the target directory (kept between runs).
VENV=$TARGET/serve-venv
if ! "$VENV/bin/python" -c "import playwright.sync_api" 2>/dev/null; then
    say "installing playwright into $VENV"
    python3 -m venv "$VENV"
    "$VENV/bin/python" -m pip install --quiet --upgrade pip >&2
    "$VENV/bin/python" -m pip install --quiet "playwright>=1.40,<2" >&2
fi

# 3. The mech binary: the caller's (MECH_BIN), or built here.
if [ -z "${MECH_BIN:-}" ]; then
    cargo build --quiet -p mech-cli --bin mech >&2
    MECH_BIN=$TARGET/debug/mech
fi

exec "$VENV/bin/python" tools/serve_check.py --mech "$MECH_BIN" --chromium "$CHROME" --out "$TARGET/serve-check" "$@"
