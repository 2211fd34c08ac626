#!/usr/bin/env bash
# The crates.io release, checked without publishing (docs/release.md).
#
# The committed manifests keep the package names `mech`, `mech-core`, `mech-macros` and
# `mech-cli` (the workspace and its users depend on them by those names), but `mech` and
# `mech-core` are taken on crates.io by an unrelated project. This script copies the
# repository (tracked and untracked, not ignored, files) into a temporary folder, gives the
# four packages their published names there
#
#     mech -> mech-dynamics             mech-core   -> mech-dynamics-core
#     mech-macros -> mech-dynamics-macros   mech-cli -> mech-dynamics-cli
#
# with `[lib] name` kept (`mech`, `mech_core`, `mech_macros`, `mech_cli`) and every path
# dependency written `mech-core = { package = "mech-dynamics-core", path = ..., version = ... }`
# so that no `use mech::...` changes, copies the root license texts into each package,
# runs `cargo publish --workspace --dry-run` (every package packaged and built from its
# .crate, the unpublished ones resolved against each other), and checks what each .crate
# holds: the license texts, the README, the sources, and no tests, benches, examples or
# data.
#
#     bash tools/release_check.sh            # the check (CI runs it)
#     bash tools/release_check.sh --publish  # the real release: publishes, in order (needs a token)
#
# Needs cargo >= 1.90 (workspace publish of interdependent unpublished crates) and python3.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
MODE=${1:---dry-run}
case "$MODE" in --dry-run | --publish) ;; *) echo "usage: $0 [--dry-run|--publish]" >&2; exit 2 ;; esac
START=$(date +%s)

TARGET=${CARGO_TARGET_DIR:-$ROOT/target}
WORK=$TARGET/release-check
SRC=$WORK/src
rm -rf "$SRC"
mkdir -p "$SRC"

for f in LICENSE-MIT LICENSE-APACHE; do
    [ -s "$f" ] || { echo "release_check: $f is missing at the repository root: every package must ship the license texts" >&2; exit 1; }
done

# 1. The copy: what git tracks plus new files not ignored (so a check before a commit sees them).
git ls-files -z --cached --others --exclude-standard |
    while IFS= read -r -d '' f; do [ -e "$f" ] && printf '%s\0' "$f"; done |
    tar --null -T - -cf - | tar -xf - -C "$SRC"

for d in mech-core mech-macros mech-cli; do cp LICENSE-MIT LICENSE-APACHE "$SRC/$d/"; done

# 2. The published names.
python3 - "$SRC" <<'EOF'
import re, sys, pathlib
src = pathlib.Path(sys.argv[1])
NEW = {"mech": "mech-dynamics", "mech-core": "mech-dynamics-core",
       "mech-macros": "mech-dynamics-macros", "mech-cli": "mech-dynamics-cli"}
LIB = {"mech": "mech", "mech-core": "mech_core", "mech-macros": "mech_macros", "mech-cli": "mech_cli"}
DIRS = {"mech": ".", "mech-core": "mech-core", "mech-macros": "mech-macros", "mech-cli": "mech-cli"}

def sub1(pattern, repl, text, what, flags=re.M):
    out, n = re.subn(pattern, repl, text, count=1, flags=flags)
    if n != 1:
        sys.exit(f"release_check: cannot rewrite {what}")
    return out

for old, d in DIRS.items():
    path = src / d / "Cargo.toml"
    text = path.read_text()
    # [package] name
    text = sub1(r'(\[package\][^\[]*?^name\s*=\s*)"%s"' % re.escape(old),
                r'\1"%s"' % NEW[old], text, f"{path}: [package] name", re.M | re.S)
    # [lib] name: the crate a user writes against keeps its name.
    if re.search(r"^\[lib\]\s*$", text, re.M):
        if re.search(r"\[lib\][^\[]*?^name\s*=", text, re.M | re.S):
            sys.exit(f"release_check: {path} already names its [lib]")
        text = sub1(r"^\[lib\]\s*$", '[lib]\nname = "%s"' % LIB[old], text, f"{path}: [lib]")
    else:
        text = text.rstrip("\n") + '\n\n[lib]\nname = "%s"\npath = "src/lib.rs"\n' % LIB[old]
    if d == ".":
        # The root's [profile.*] tables tune this repository's own builds (tests at opt-level 1,
        # dependencies at 2); crates.io users never see them (only a workspace root's profiles
        # count), and verifying the facade with them built mech-core at opt-level 2 again.
        tables = re.split(r"(?m)^(?=\[)", text)
        text = "".join(t for t in tables if not t.startswith("[profile"))
    path.write_text(text)

# Every dependency on a renamed package, in every manifest of the copy (fuzz, mech-py too).
dep = re.compile(r'^(%s)(\s*=\s*\{)(?![^}]*\bpackage\s*=)([^}]*\bpath\s*=)' %
                 "|".join(map(re.escape, sorted(NEW, key=len, reverse=True))), re.M)
for path in sorted(src.glob("**/Cargo.toml")):
    if "target" in path.relative_to(src).parts:
        continue
    text = path.read_text()
    text = dep.sub(lambda m: f'{m[1]}{m[2]} package = "{NEW[m[1]]}",{m[3]}', text)
    path.write_text(text)
    try:
        import tomllib
        tomllib.loads(text)
    except ImportError:
        pass
print("release_check: published names applied:", ", ".join(f"{k} -> {v}" for k, v in NEW.items()))
EOF

cd "$SRC"
# The target folder of the repository: dependencies that `cargo test` built with the same
# settings are not built again when the packages are verified.
export CARGO_TARGET_DIR=$TARGET
rm -rf "$CARGO_TARGET_DIR/package"
PKGS=(mech-dynamics-core mech-dynamics-macros mech-dynamics mech-dynamics-cli)

# 3. What each package will hold (`cargo package --list`), checked before anything is built.
for p in "${PKGS[@]}"; do
    cargo package --list --allow-dirty -p "$p" >"$WORK/$p.list" 2>"$WORK/$p.list.err" ||
        { cat "$WORK/$p.list.err" >&2; exit 1; }
    echo "== $p: $(wc -l <"$WORK/$p.list") files"
    sed 's/^/   /' "$WORK/$p.list"
    for need in Cargo.toml Cargo.toml.orig README.md LICENSE-MIT LICENSE-APACHE; do
        grep -qx "$need" "$WORK/$p.list" || { echo "release_check: $p lacks $need" >&2; exit 1; }
    done
    grep -Eq '^src/(lib|main)\.rs$' "$WORK/$p.list" || { echo "release_check: $p has no src/lib.rs" >&2; exit 1; }
    if grep -Ev '^(Cargo\.toml(\.orig)?|Cargo\.lock|README\.md|LICENSE-MIT|LICENSE-APACHE|\.cargo_vcs_info\.json|src/.*\.rs|src/serve/page\.(html|js))$' "$WORK/$p.list"; then
        echo "release_check: $p would publish the files above, which it does not need" >&2
        exit 1
    fi
done

# 4. The dry run: every package packaged, then built from its .crate alone.
# Cargo unpacks the .crate files of its temporary local registry under
# $CARGO_HOME/registry/src/-<hash of the registry's path>/ and does not unpack a version it
# finds there again: a second run from the same folder would verify against the sources of
# the first (a stale mech-dynamics-core 0.1.0 failed CI this way). Those unpacked copies of our
# own unpublished packages are removed first; nothing from crates.io is touched.
CARGO_HOME_DIR=${CARGO_HOME:-$HOME/.cargo}
for d in "$CARGO_HOME_DIR"/registry/src/-*/mech-dynamics*-0.1.0; do
    [ -d "$d" ] && rm -rf "$d"
done
# For the same reason (a registry crate's version is trusted to name its contents) the builds
# of those packages left in the target folder by an earlier run are forgotten: their
# fingerprints are removed, so each is compiled again from this run's .crate.
rm -rf "$CARGO_TARGET_DIR"/*/.fingerprint/mech-dynamics-*
if [ "$MODE" = --publish ]; then
    cargo publish --workspace --exclude mech-fuzz --allow-dirty
else
    cargo publish --workspace --exclude mech-fuzz --dry-run --allow-dirty
fi

# 5. The .crate files: names, library names, dependencies as crates.io will see them.
python3 - "$CARGO_TARGET_DIR/package" "${PKGS[@]}" <<'EOF'
import sys, tarfile, tomllib, pathlib
pkgdir, pkgs = pathlib.Path(sys.argv[1]), sys.argv[2:]
LIB = {"mech-dynamics": "mech", "mech-dynamics-core": "mech_core",
       "mech-dynamics-macros": "mech_macros", "mech-dynamics-cli": "mech_cli"}
for p in pkgs:
    found = sorted(pkgdir.glob(f"**/{p}-0.1.0.crate"))  # package/ or package/tmp-crate/
    assert found, f"no {p}-0.1.0.crate under {pkgdir}"
    crate = found[0]
    with tarfile.open(crate) as t:
        names = t.getnames()
        man = tomllib.loads(t.extractfile(f"{p}-0.1.0/Cargo.toml").read().decode())
        for lic in ("LICENSE-MIT", "LICENSE-APACHE"):
            body = t.extractfile(f"{p}-0.1.0/{lic}").read().decode()
            assert ("MIT License" in body or "Permission is hereby granted" in body) if lic == "LICENSE-MIT" \
                else "Apache License" in body, f"{p}: {lic} is not the license text"
    pk = man["package"]
    assert pk["name"] == p and pk["license"] == "MIT OR Apache-2.0", pk
    for key in ("description", "repository", "documentation", "readme", "keywords", "categories"):
        assert pk.get(key), f"{p}: no {key}"
    assert len(pk["keywords"]) <= 5, pk["keywords"]
    assert man["lib"]["name"] == LIB[p], man.get("lib")
    for kind in ("dependencies", "build-dependencies"):
        for name, d in man.get(kind, {}).items():
            if isinstance(d, dict) and d.get("package", "").startswith("mech-dynamics"):
                assert "path" not in d and d.get("version"), (p, name, d)
    bins = [b["name"] for b in man.get("bin", [])]
    print(f"release_check: {crate.name}: {len(names)} files, {crate.stat().st_size // 1024} KiB, "
          f"lib {man['lib']['name']}" + (f", bin {', '.join(bins)}" if bins else "") +
          ", deps " + ", ".join(sorted(f"{n}={d['package']}" if isinstance(d, dict) and 'package' in d else n
                                      for n, d in man.get("dependencies", {}).items())))
assert man  # at least one package read
EOF

echo "release_check: passed in $(( $(date +%s) - START )) s (${MODE#--})"
