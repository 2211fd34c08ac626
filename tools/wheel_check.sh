#!/usr/bin/env bash
# The PyPI release, checked as a user gets it (docs/release.md): build the abi3 wheel of
# `mech-dynamics` (module `mech`) with maturin, install it into a FRESH virtual environment,
# and run the pytest suite (mech-py/tests) there with a PATH that holds no cargo and no rustc,
# so that the tests can only pass on what the wheel carries.
#
#     bash tools/wheel_check.sh          # tools/python_tests.sh runs this, and so does
#                                        # tests/python_package.rs (cargo test --workspace)
#
# Needs python3 (>= 3.8) with venv and pip, and pip's access to PyPI for maturin, numpy,
# pytest, dask and pandas. The wheel is left in target/wheels/ for `twine upload` / `maturin
# upload`. Only pytest's output goes to stdout (tests/python_package.rs reads its summary);
# this script's own lines go to stderr.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
START=$(date +%s)
say() { echo "wheel_check: $*" >&2; }

# 1. The build environment (kept between runs): maturin.
BUILD=$ROOT/target/py-venv
python3 -m venv "$BUILD"
"$BUILD/bin/python" -m pip install --quiet --upgrade pip >&2
"$BUILD/bin/python" -m pip install --quiet "maturin>=1.5,<2" >&2

# 2. The wheel.
OUT=$ROOT/target/wheels
mkdir -p "$OUT"
rm -f "$OUT"/mech-*.whl "$OUT"/mech_dynamics-*.whl
"$BUILD/bin/maturin" build --release --quiet -m mech-py/Cargo.toml -o "$OUT" >&2
shopt -s nullglob
WHEELS=("$OUT"/mech_dynamics-0.1.0-*.whl)
[ ${#WHEELS[@]} -eq 1 ] || { say "expected one mech_dynamics wheel in $OUT, found: ${WHEELS[*]:-none}"; exit 1; }
WHEEL=${WHEELS[0]}
case "$(basename "$WHEEL")" in
    *-cp38-abi3-*) ;;
    *) say "$(basename "$WHEEL") is not an abi3 wheel for CPython >= 3.8"; exit 1 ;;
esac
"$BUILD/bin/python" - "$WHEEL" >&2 <<'EOF'
import sys, zipfile
w = zipfile.ZipFile(sys.argv[1])
names = w.namelist()
meta = w.read(next(n for n in names if n.endswith(".dist-info/METADATA"))).decode()
assert "\nName: mech-dynamics\n" in meta, meta[:300]
assert "mech/__init__.py" in names and "mech/py.typed" in names, names
assert any(n.startswith("mech/_mech") and n.endswith(".so") for n in names), names
print(f"wheel_check: {sys.argv[1].rsplit('/', 1)[-1]}: {len(names)} files, "
      f"{sum(i.file_size for i in w.infolist()) // 1024} KiB unpacked")
EOF

# 3. A fresh environment with nothing but the wheel and the test suite's needs.
VENV=$ROOT/target/wheel-venv
rm -rf "$VENV"
python3 -m venv "$VENV"
"$VENV/bin/python" -m pip install --quiet --upgrade pip >&2
"$VENV/bin/python" -m pip install --quiet "$WHEEL" pytest "dask[distributed]" pandas >&2

# 4. The tests, with no Rust toolchain on PATH.
CLEAN=$VENV/bin
IFS=: read -r -a DIRS <<<"$PATH"
for d in "${DIRS[@]}"; do
    [ -n "$d" ] && [ ! -e "$d/cargo" ] && [ ! -e "$d/rustc" ] && [ ! -e "$d/rustup" ] && CLEAN=$CLEAN:$d
done
cd "$ROOT/target"   # not mech-py/: `import mech` must find the installed wheel, not the sources
env -u CARGO -u RUSTC -u RUSTUP_TOOLCHAIN PATH="$CLEAN" bash -c '
    set -euo pipefail
    if command -v cargo >/dev/null || command -v rustc >/dev/null; then
        echo "wheel_check: cargo or rustc is on the test PATH: $(command -v cargo rustc)" >&2; exit 1
    fi
    echo "wheel_check: command -v cargo fails here: no cargo and no rustc on PATH" >&2
    python -c "import mech, sys; f = mech.__file__; assert f.startswith(sys.prefix), f; print(\"wheel_check: import mech ->\", f, file=sys.stderr)"
    python -m pytest -q -p no:cacheprovider ../mech-py/tests
'
say "OK in $(( $(date +%s) - START )) s: $(basename "$WHEEL")"
