#!/usr/bin/env bash
# What one `mechanism!` costs at build time (docs/macro_cost.md).
#
# Builds a throwaway library crate outside the repository, with mech as its only
# dependency, in four versions that differ only by the mechanisms they declare:
#   none      : `use mech::prelude::*;` and a small function
#   four_bar  : + the crank-rocker four-bar (a crank and one RRR dyad)
#   watt2     : + the Watt II six-bar instead (a crank and two RRR dyads)
#   both      : + both
# Each version is built N times (alternating), debug with incremental off and release;
# the CPU time (user + sys of cargo and rustc) is reported as the median, and the lines of
# LLVM IR of the crate (debug, --emit=llvm-ir) once.
#
# usage: tools/macro_cost.sh [N=5]      (writes under /tmp/macro_cost; MECH_ROOT=... to
# measure another checkout of mech, MACRO_COST_DIR=... for another scratch folder)
set -euo pipefail
N=${1:-5}
ROOT=${MECH_ROOT:-$(cd "$(dirname "$0")/.." && pwd)}
W=${MACRO_COST_DIR:-/tmp/macro_cost}
rm -rf "$W" && mkdir -p "$W/src" "$W/variants"
cat > "$W/Cargo.toml" <<TOML
[package]
name = "macro_cost"
version = "0.1.0"
edition = "2021"
[dependencies]
mech = { path = "$ROOT" }
[workspace]
TOML
# The mechanisms, cut from tests/common/mechanisms.rs.
extract() { # name -> the mechanism! { ... } block declaring `pub struct name`
  python3 - "$ROOT/tests/common/mechanisms.rs" "$1" <<'PY'
import sys, re
src = open(sys.argv[1]).read(); name = sys.argv[2]
for m in re.finditer(r'mechanism! \{', src):
    depth, i = 0, m.end() - 1
    while True:
        depth += {'{': 1, '}': -1}.get(src[i], 0); i += 1
        if depth == 0: break
    block = src[m.start():i]
    if re.search(r'pub struct %s \{' % name, block): print(block); break
PY
}
head='use mech::prelude::*;
pub fn answer() -> f64 { 42.0 }'
printf '%s\n' "$head" > "$W/variants/none.rs"
printf '%s\n%s\n' "$head" "$(extract FourBar)" > "$W/variants/four_bar.rs"
printf '%s\n%s\n' "$head" "$(extract Watt2)" > "$W/variants/watt2.rs"
printf '%s\n%s\n%s\n' "$head" "$(extract FourBar)" "$(extract Watt2)" > "$W/variants/both.rs"
cd "$W"
cp variants/none.rs src/lib.rs
cargo build -q && cargo build -q --release
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
declare -A T
for profile in debug release; do
  flag=""; [ "$profile" = release ] && flag="--release"
  for i in $(seq "$N"); do
    for v in none four_bar watt2 both; do
      cp "variants/$v.rs" src/lib.rs
      cargo build -q $flag -p mech >/dev/null 2>&1 || true
      t=$( { CARGO_INCREMENTAL=0 /usr/bin/time -f "%U %S" cargo build -q $flag 2>&1 >/dev/null; } | tail -1 | awk '{print $1 + $2}')
      T[$profile.$v]="${T[$profile.$v]:-} $t"
    done
  done
done
echo "| variant | debug CPU s | release CPU s | debug extra | release extra | LLVM IR lines (debug) |"
echo "|---|---:|---:|---:|---:|---:|"
d0=$(echo ${T[debug.none]} | tr ' ' '\n' | median); r0=$(echo ${T[release.none]} | tr ' ' '\n' | median)
for v in none four_bar watt2 both; do
  d=$(echo ${T[debug.$v]} | tr ' ' '\n' | median); r=$(echo ${T[release.$v]} | tr ' ' '\n' | median)
  cp "variants/$v.rs" src/lib.rs
  rm -f target/debug/deps/macro_cost-*.ll
  cargo rustc -q --lib -- --emit=llvm-ir >/dev/null 2>&1
  ir=$(cat target/debug/deps/macro_cost-*.ll 2>/dev/null | wc -l)
  printf "| %s | %.2f | %.2f | %+.2f | %+.2f | %s |\n" "$v" "$d" "$r" "$(echo "$d - $d0" | bc -l)" "$(echo "$r - $r0" | bc -l)" "$ir"
done
