#!/usr/bin/env python3
"""Every measured figure of the README and docs/, printed by one command.

    python3 tools/report.py list               # the figures: name, command, where they are shown
    python3 tools/report.py NAME [NAME ...]    # measure, print each figure's block
    python3 tools/report.py NAME --write       # ... and put the block into README.md / docs/*.md
    python3 tools/report.py all --write        # every figure (about 1.5 h, the fuzzer's long run included)

A figure is shown in a document between two markers, and nowhere else:

    <!-- report NAME -->
    ...the table this command printed...
    <sub>Printed by `python3 tools/report.py NAME` (...the underlying command...) on the code
    of COMMIT (tree FNV-1a HASH of PATHS), MACHINE, DATE.</sub>
    <!-- /report NAME -->

`--write` replaces the text between the markers of NAME in every document that holds them.
The test `docs_figures` (root `suite` binary) reads the blocks back: every block names a
figure of this script; every measured-looking number of README.md and docs/*.md (a ratio
`1.2×`, a time `40 ns`, a rate `/s`) stands inside a block; and a block of the README whose
code has changed since it was measured (the FNV-1a hash of the files under PATHS, computed
the same way in Rust) fails, with the command that measures it again.

Measurements are made on this machine, as it is: run nothing else at the same time. The
machine is read from `lscpu` and `nproc`.
"""

import argparse
import datetime
import json
import os
import re
import subprocess
import tempfile
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DOCS = [ROOT / "README.md"] + sorted((ROOT / "docs").glob("*.md"))

# The code every figure depends on.
CORE = ["mech-core/src", "mech-macros/src", "src"]
# The code a generated struct is made of: the macro, the facade, and the layers of mech-core
# its expansion calls or that decide what it emits (not `dynamics`, not `runtime`, which
# only the run-time mechanism and the integrators use: mech-core/tests/imports.rs keeps the
# layers below them from importing them).
GENERATED = ["mech-macros/src", "src"] + ["mech-core/src/" + p for p in (
    "lib.rs", "private.rs", "error.rs", "kernel", "elements", "model", "front", "plan", "checks",
    "solvers")]


# ---------------------------------------------------------------------------------------
# the code hash, the commit, the machine


def code_hash(paths):
    """FNV-1a 64 over every file under `paths` (sorted by its path relative to the
    repository, '/'-separated): path bytes, NUL, content bytes, NUL. The Rust test
    `docs_figures` computes the same."""
    # Files git ignores (an insta `.snap.new` left by a failed run, say) are not code and
    # are not in a clean clone, where `docs_figures` recomputes the hash: left out.
    ignored = set(subprocess.run(
        ["git", "ls-files", "--others", "--ignored", "--exclude-standard", "--", *paths],
        cwd=ROOT, capture_output=True, text=True, check=True).stdout.split("\n"))
    files = []
    for p in paths:
        full = ROOT / p
        if full.is_file():
            files.append(p)
        else:
            for f in full.rglob("*"):
                if f.is_file():
                    files.append(f.relative_to(ROOT).as_posix())
    files = [f for f in files if f not in ignored]
    h = 0xCBF29CE484222325
    for rel in sorted(set(files)):
        for byte in rel.encode() + b"\0" + (ROOT / rel).read_bytes() + b"\0":
            h ^= byte
            h = (h * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return f"{h:016x}"


def commit(paths):
    """HEAD, marked when the measured `paths` differ from it (the documents that --write
    rewrites are not among them)."""
    out = subprocess.run(["git", "rev-parse", "--short=7", "HEAD"], cwd=ROOT,
                         capture_output=True, text=True).stdout.strip()
    dirty = subprocess.run(["git", "status", "--porcelain", "--"] + list(paths), cwd=ROOT,
                           capture_output=True, text=True).stdout.strip()
    return out + ("+uncommitted changes" if dirty else "")


def machine():
    model = "unknown processor"
    try:
        for line in subprocess.run(["lscpu"], capture_output=True, text=True).stdout.splitlines():
            if line.startswith("Model name:"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{model}, {os.cpu_count()} cores"


# ---------------------------------------------------------------------------------------
# running things


def sh(cmd, env=None, **kw):
    """Run `cmd` (a list) in the repository; its stdout; stderr passes through."""
    print("$ " + " ".join(cmd), file=sys.stderr)
    full_env = dict(os.environ, **(env or {}))
    r = subprocess.run(cmd, cwd=ROOT, env=full_env, stdout=subprocess.PIPE, text=True, **kw)
    if r.returncode:
        sys.exit(f"`{' '.join(cmd)}` failed with status {r.returncode}")
    return r.stdout


def target_dir():
    return Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))


def criterion_medians():
    """{full_id: median (ns, or the value itself for a ratio)} of every criterion result."""
    out = {}
    for bench in (target_dir() / "criterion").glob("**/new/benchmark.json"):
        try:
            meta = json.loads(bench.read_text())
            est = json.loads((bench.parent / "estimates.json").read_text())
        except (OSError, ValueError):
            continue
        out[meta["full_id"]] = est["median"]["point_estimate"]
    return out


def ns(v):
    return "—" if v is None else (f"{v:.0f}" if v >= 100 else f"{v:.1f}")


# ---------------------------------------------------------------------------------------
# the figures


FLOOR_MACHINES = ("four_bar|slider_crank|quick_return|scotch_yoke|inverted_slider_crank|geared_slider_crank"
                  "|roller_cam|crank_rod_wheel|block_scotch_yoke|slotted_crank_ram|planetary"
                  "|rack_pinion")


def floor():
    sh(["cargo", "bench", "--bench", "floor", "--", f"^({FLOOR_MACHINES})/|^ratio/({FLOOR_MACHINES})/"])
    return sh([sys.executable, "tools/floor_ratios.py"]).strip()


FLOOR_CMD = (f"`cargo bench --bench floor -- '^({FLOOR_MACHINES})/|^ratio/({FLOOR_MACHINES})/'`, "
             "tabulated by `tools/floor_ratios.py`")

FLOOR_OPS = ["pose", "kinematics", "kinematics+kinetostatics", "kinematics+driver_action", "reduced",
             "acceleration"]


def runtime_floor():
    """The run-time mechanism against the generated struct on every operation of the floor's
    machines, interleaved (`runtime_ratio/<machine>/<op>`, benches/floor/runtime.rs)."""
    sh(["cargo", "bench", "--bench", "floor", "--", "^runtime_ratio/", "--warm-up-time", "1",
        "--measurement-time", "2"])
    med = criterion_medians()
    rows = ["| machine | " + " | ".join(f"`{o}`" for o in FLOOR_OPS) + " |",
            "|---|" + "---:|" * len(FLOOR_OPS)]
    for m in FLOOR_MACHINES.split("|"):
        vals = [med.get(f"runtime_ratio/{m}/{o}") for o in FLOOR_OPS]
        if all(v is None for v in vals):
            sys.exit(f"no result for runtime_ratio/{m}")
        rows.append(f"| {m.replace('_', ' ')} | " + " | ".join("—" if v is None else f"{v:.2f}×" for v in vals) + " |")
    return "\n".join(rows)


RUNTIME_FLOOR_CMD = ("`cargo bench --bench floor -- '^runtime_ratio/' --warm-up-time 1 --measurement-time 2`, "
                     "the interleaved ratio run-time / generated (medians)")

BATCH_OPS = ["four_bar/points", "four_bar/reduced", "four_bar/acceleration", "slider_crank/acceleration"]
BATCH_SIZE = 1024  # benches/floor.rs, BATCH


def instructions(bench_bin, name, simd="1", required=True):
    """Instructions per call of the criterion function `name` (callgrind; the recipe of the
    header of benches/floor.rs). `simd="0"` sets MECH_SIMD=0: the lanes' baseline path (two
    128-bit registers per lane value) instead of the 256-bit one chosen at run time. A
    function timed otherwise than by `Bencher::iter` (a setup per batch) is an error, or
    None when not `required`."""
    out = Path(tempfile.mkdtemp()) / "cg.out"
    subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", bench_bin,
                    "--bench", "--profile-time", "1", f"^{re.escape(name)}$"],
                   cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True,
                   env=dict(os.environ, MECH_SIMD=simd))
    ann = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--tree=caller", str(out)],
                         stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, check=True).stdout
    n = k = None
    for line in ann.splitlines():
        if re.search(r"\* .*Bencher<M>::iter", line):
            n = float(line.split()[0].replace(",", ""))
        m = re.search(r"< .*Bencher<M>::iter \(([\d,]+)x\)", line)
        if m:
            k = float(m.group(1).replace(",", ""))
    if not n or not k:
        if not required:
            return None
        sys.exit(f"callgrind found no timing loop for {name}")
    return n / k


def floor_bench_bin():
    """The path of the floor's criterion binary, built (release) if needed."""
    exe = sh(["cargo", "bench", "--bench", "floor", "--no-run", "--message-format", "json"])
    return next(json.loads(l)["executable"] for l in exe.splitlines()
                if '"executable":"' in l and json.loads(l).get("target", {}).get("name") == "floor")


def floor_instructions():
    """Instructions per call (callgrind) of every floor operation timed by `Bencher::iter`:
    generated, hand-written and their ratio, and the run-time mechanism's with its ratio to
    the generated struct. Stable where the timings are noisy; a dash where callgrind finds
    no `Bencher::iter` loop."""
    bench_bin = floor_bench_bin()
    rows = ["| operation | generated | hand | generated / hand | run-time | run-time / generated |",
            "|---|---:|---:|---:|---:|---:|"]
    for m in FLOOR_MACHINES.split("|"):
        for op in FLOOR_OPS:
            g = instructions(bench_bin, f"{m}/{op}/generated", required=False)
            if g is None:
                continue
            h = instructions(bench_bin, f"{m}/{op}/hand", required=False)
            r = instructions(bench_bin, f"runtime/{m}/{op}/runtime", required=False)
            g2 = instructions(bench_bin, f"runtime/{m}/{op}/generated", required=False)
            cells = [f"{g:.0f}", "—" if h is None else f"{h:.0f}", "—" if h is None else f"{g / h:.2f}×",
                     "—" if r is None else f"{r:.0f}", "—" if r is None or g2 is None else f"{r / g2:.2f}×"]
            rows.append(f"| `{m}/{op}` | " + " | ".join(cells) + " |")
    return "\n".join(rows)


def batch():
    sh(["cargo", "bench", "--bench", "floor", "--", "--warm-up-time", "1", "--measurement-time", "3",
        "^batch/|^ratio/batch/"])
    med = criterion_medians()
    bench_bin = floor_bench_bin()
    rows = ["| operation | batched (ns per configuration) | hand-written (ns per configuration) "
            "| interleaved ratio | batched (instructions per configuration) "
            "| batched, `MECH_SIMD=0` (instructions per configuration) | hand-written (instructions per configuration) |",
            "|---|---:|---:|---:|---:|---:|---:|"]
    for op in BATCH_OPS:
        g, h, r = (med.get(f"batch/{op}/generated"), med.get(f"batch/{op}/hand"),
                   med.get(f"ratio/batch/{op}"))
        if g is None or h is None or r is None:
            sys.exit(f"no result for batch/{op}")
        ig = instructions(bench_bin, f"batch/{op}/generated") / BATCH_SIZE
        i0 = instructions(bench_bin, f"batch/{op}/generated", simd="0") / BATCH_SIZE
        ih = instructions(bench_bin, f"batch/{op}/hand") / BATCH_SIZE
        rows.append(f"| `{op}` | {g / BATCH_SIZE:.1f} | {h / BATCH_SIZE:.1f} | {r:.2f}× | {ig:.0f} | {i0:.0f} | {ih:.0f} |")
    return "\n".join(rows)


BATCH_CMD = ("`cargo bench --bench floor -- '^batch/|^ratio/batch/'`, medians over 1 024 configurations "
             "per call on one thread, and callgrind's instruction counts of the same functions, "
             "on the 256-bit lanes the processor's AVX2 selects and with `MECH_SIMD=0` on the "
             "128-bit baseline)")

MACHINES = [("four_bar", "four-bar"), ("slider_crank", "slider-crank"),
            ("watt2", "Watt II six-bar"), ("five_bar", "five-bar (2 DOF)")]


def runtime():
    sh(["cargo", "bench", "--bench", "generated_vs_generic", "--", r"kinematics\+kinetostatics",
        "--warm-up-time", "1", "--measurement-time", "3"])
    med = criterion_medians()
    rows = ["| mechanism | generated (ns) | run-time, caller buffers (ns) | run-time / generated "
            "| dense oracle (ns) | oracle / generated |", "|---|---:|---:|---:|---:|---:|"]
    for key, name in MACHINES:
        g = med.get(f"{key}/kinematics+kinetostatics/generated")
        r = med.get(f"{key}/kinematics+kinetostatics/runtime_buffers")
        o = med.get(f"{key}/kinematics+kinetostatics/generic")
        if g is None:
            sys.exit(f"no result for {key}/kinematics+kinetostatics/generated")
        rows.append(f"| {name} | {ns(g)} | {ns(r)} | {r / g:.2f}× | {ns(o)} | {o / g:.0f}× |")
    return "\n".join(rows)


RUNTIME_CMD = ("`cargo bench --bench generated_vs_generic -- 'kinematics\\+kinetostatics' "
               "--warm-up-time 1 --measurement-time 3`, medians, `kinematics + kinetostatics` per call")


def elements():
    sh(["cargo", "bench", "--bench", "machine_elements"])
    med = criterion_medians()
    ops = ["kinematics+kinetostatics", "acceleration"]
    variants = sorted({k.split("/")[1] for k in med if k.startswith("slider_crank/")
                       and len(k.split("/")) == 3 and k.split("/")[2] in ops})
    rows = ["| slider-crank | " + " | ".join(f"`{o}` (ns)" for o in ops) + " |",
            "|---|" + "---:|" * len(ops)]
    for v in variants:
        rows.append(f"| {v} | " + " | ".join(ns(med.get(f"slider_crank/{v}/{o}")) for o in ops) + " |")
    return "\n".join(rows)


def accuracy():
    return sh(["cargo", "run", "--release", "--example", "accuracy_report"]).strip()


def dynamics():
    sh(["cargo", "bench", "--bench", "dynamics"])
    med = criterion_medians()
    rows = ["| benchmark | median |", "|---|---:|"]
    for k in sorted(med):
        if k.startswith("slider_crank/acceleration") or k.startswith("slider_crank/integrate"):
            if "/" in k[len("slider_crank/"):]:
                continue
            v = med[k]
            rows.append(f"| `{k}` | " + (f"{v:.0f} ns" if v < 1e4 else f"{v / 1e6:.3f} ms") + " |")
    return "\n".join(rows)


def engine_output():
    out = sh(["cargo", "run", "--release", "--example", "engine"])
    return [l for l in out.splitlines() if not l.startswith("done in ")]


def engine():
    return "```text\n" + "\n".join(engine_output()).strip() + "\n```"


def engine_flywheel():
    lines = engine_output()
    a = next(i for i, l in enumerate(lines) if "balanced by a constant" in l)
    b = next(i for i, l in enumerate(lines) if "without a flywheel" in l)
    return "```text\n" + "\n".join(lines[a:b + 1]) + "\n```"


def work_precision():
    out = sh(["cargo", "run", "--release", "--example", "work_precision"])
    return "\n".join(l for l in out.splitlines() if l.startswith("|") or l.startswith("Slider")).strip()


# The commit before `mech sweep` went through the batch runner (`Columns::rows_many`): the
# "before" of the sweep figure.
SWEEP_BEFORE = "3e1cc59"


def build_cli_at(commit):
    """The release `mech` binary of `commit`, built in a worktree of its own under target/."""
    tree = target_dir() / f"sweep-before-{commit}"
    if not tree.exists():
        sh(["git", "worktree", "add", "--detach", str(tree), commit])
    env = {"CARGO_TARGET_DIR": str(target_dir() / "sweep-before-target")}
    print(f"$ (in {tree}) cargo build --release -p mech-cli", file=sys.stderr)
    subprocess.run(["cargo", "build", "--release", "-p", "mech-cli"], cwd=tree,
                   env=dict(os.environ, **env), check=True, stdout=subprocess.DEVNULL)
    return str(target_dir() / "sweep-before-target" / "release" / "mech")


def sweep():
    sh(["cargo", "build", "--release", "-p", "mech-cli"])
    after = str(target_dir() / "release" / "mech")
    before = build_cli_at(SWEEP_BEFORE)
    rows = [f"| `--level` | configurations | before ({SWEEP_BEFORE}), configurations/s "
            "| after, configurations/s | after / before |", "|---|---:|---:|---:|---:|"]
    for level in ["pose", "kinematics", "forces"]:
        best = {before: float("inf"), after: float("inf")}
        for _ in range(3):  # interleaved: before, after, before, after, ...
            for exe in (before, after):
                cmd = [exe, "sweep", "examples/mech/watt_ii.mech", "--from", "0", "--to", "360deg",
                       "--steps", "999999", "--level", level, "--format", "csv"]
                t0 = time.perf_counter()
                subprocess.run(cmd, cwd=ROOT, stdout=subprocess.DEVNULL, check=True)
                best[exe] = min(best[exe], time.perf_counter() - t0)
        rb, ra = 1e6 / best[before], 1e6 / best[after]
        rows.append(f"| {level} | 1 000 000 | {rb:,.0f} | {ra:,.0f} | {ra / rb:.2f}× |".replace(",", " "))
    return "\n".join(rows)


SWEEP_CMD = ("`mech sweep examples/mech/watt_ii.mech --from 0 --to 360deg --steps 999999 "
             "--level L --format csv > /dev/null`, best of 3 interleaved, the release builds of "
             f"{SWEEP_BEFORE} (before) and of this commit (after)")


def pyslvs():
    return sh([sys.executable, "tools/python_vs_pyslvs.py", "--table"]).strip()


def montecarlo():
    code = "\n".join([
        "import sys, time",
        "sys.path.insert(0, 'mech-py/examples')",
        "import tolerance_study as ts",
        "ts.run_serial(1000, 1)  # warm up",
        "times = []",
        "for _ in range(3):",
        "    t0 = time.perf_counter()",
        "    ts.run_serial(10000, 1)",
        "    times.append(time.perf_counter() - t0)",
        "print(min(times))",
    ])
    env = {"OPENBLAS_NUM_THREADS": "1"}
    seconds = float(sh([sys.executable, "-c", code], env=env).strip())
    import_threads = sh([sys.executable, "-c", "import mech; print(mech.num_threads())"], env=env).strip()
    rate = f"{7.2e5 / seconds:,.0f}".replace(",", " ")
    return ("| configurations | threads | wall time (s, best of 3) | configurations/s |\n|---:|---:|---:|---:|\n"
            f"| 720 000 | {import_threads} | {seconds:.2f} | {rate} |")


def fuzz():
    out = sh(["cargo", "run", "--release", "-p", "mech-fuzz", "--", "--cases", "1000000"])
    return out.strip().splitlines()[-1]


def macro_cost():
    return sh(["bash", "tools/macro_cost.sh", "3"]).strip()


SYNTH_CASES = [
    # (file, what, seed, extra arguments)
    ("tests/data/synthesis/kunjur18.csv", "18-point closed path (Kunjur & Krishnamurty 1997), four-bar",
     1, []),
    ("tests/data/synthesis/kunjur18.csv", "the same path, Stephenson III six-bar, 10⁶ evaluations",
     4, ["--topology", "six-bar", "--evaluations", "1000000"]),
]


def synthesis():
    """`mech synth path` on each case of SYNTH_CASES (its seed and budget): E, the
    search's evaluations per second (its own report on standard error) on one thread and
    on every core, and the wall time on every core; best of 5 for the times, the runs
    interleaved (E is the same every run: one seed, one result)."""
    sh(["cargo", "build", "--release", "-p", "mech-cli"])
    exe = str(target_dir() / "release" / "mech")
    cores = os.cpu_count()
    rows = ["| path | targets | seed | E (m²) | evaluations | evaluations/s, 1 thread "
            f"| evaluations/s, {cores} threads | wall time, {cores} threads (s) |",
            "|---|---:|---:|---:|---:|---:|---:|---:|"]
    for file, what, seed, extra in SYNTH_CASES:
        n = sum(1 for l in (ROOT / file).read_text().splitlines()
                if l.strip() and not l.startswith("#")) - 1
        rate, wall, error = {1: 0.0, cores: 0.0}, float("inf"), None
        for _ in range(5):
            for threads in (1, cores):
                with tempfile.TemporaryDirectory() as tmp:
                    cmd = [exe, "synth", "path", file, "--seed", str(seed), "--format", "csv",
                           "-o", str(Path(tmp) / "out.mech")] + extra
                    t0 = time.perf_counter()
                    r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True,
                                       env=dict(os.environ, RAYON_NUM_THREADS=str(threads)))
                    t = time.perf_counter() - t0
                if r.returncode:
                    sys.exit(f"`{' '.join(cmd)}` failed: {r.stderr}")
                e = float(r.stdout.splitlines()[1].split(",")[0])
                if error is not None and e != error:
                    sys.exit(f"{file}: E changed between runs of one seed ({error} then {e})")
                error = e
                rate[threads] = max(rate[threads],
                                    float(re.search(r"([0-9.]+) evaluations/s", r.stderr).group(1)))
                evaluations = re.search(r"search: ([0-9]+) evaluations", r.stderr).group(1)
                if threads == cores:
                    wall = min(wall, t)
        thousands = lambda x: f"{x:,.0f}".replace(",", " ")  # noqa: E731
        rows.append(f"| {what} | {n} | {seed} | {error:.6e} | {evaluations} | {thousands(rate[1])} "
                    f"| {thousands(rate[cores])} | {wall:.2f} |")
    return "\n".join(rows)


def synthesis_rates():
    return sh([sys.executable, "tools/synthesis_vs_others.py", "--table"]).strip()


SYNTH_CMD = ("`mech synth path FILE --seed S` (200 000 evaluations unless the row says, μ ≥ 30°, "
             "ratio ≤ 10) with RAYON_NUM_THREADS=1 and on every core, best of 5 interleaved")


def triad():
    """A triad machine's pose against the Watt II dyad chain (issue 35: at most 3×), as the
    ratio of two medians and interleaved (`triad_ratio/<machine>`, the figure to read), and
    a run-time sweep with the triads' warm start against one call per configuration."""
    sh(["cargo", "bench", "--bench", "triad", "--", "--warm-up-time", "1", "--measurement-time", "3"])
    med = criterion_medians()
    watt = med.get("triad/pose/watt2")
    rows = ["| machine | `pose` (ns) | / Watt II (medians) | / Watt II (interleaved) "
            "| run-time sweep, warm (ns per configuration) "
            "| one call each (ns per configuration) | warm / one call |",
            "|---|---:|---:|---:|---:|---:|---:|"]
    for name in ["stephenson3", "stephenson2", "watt2"]:
        pose = med.get(f"triad/pose/{name}")
        inter = med.get(f"triad_ratio/{name}")
        if name != "watt2" and inter is None:
            sys.exit(f"no result for triad_ratio/{name}")
        warm, cold = med.get(f"triad_sweep/{name}/warm"), med.get(f"triad_sweep/{name}/cold")
        sweep = (f"{ns(warm / 64)} | {ns(cold / 64)} | {warm / cold:.2f}×" if warm and cold
                 else "— | — | —")
        ratio = f"{inter:.2f}×" if inter is not None else "1.00×"
        rows.append(f"| {name} | {ns(pose)} | {pose / watt:.2f}× | {ratio} | {sweep} |")
    return "\n".join(rows)


def spatial():
    """The generated spatial struct against the run-time mechanism of the same declaration
    (the stack frame against the heap frame), and the RSSR's pose by its closed form, by
    Newton from the drawing and by the kernel alone (benches/spatial.rs)."""
    sh(["cargo", "bench", "--bench", "spatial", "--", "--warm-up-time", "1", "--measurement-time", "3"])
    med = criterion_medians()
    rows = ["| operation | generated (ns) | run-time (ns) | run-time / generated |",
            "|---|---:|---:|---:|"]
    for op, label in [("kinematics", "RSSR `kinematics` (closed-form positions)"),
                      ("kinetostatics", "RSSR `kinetostatics`"),
                      ("fourbar_kinematics", "four-bar in space `kinematics` (Newton)")]:
        g, r = med.get(f"spatial_generated/{op}_generated"), med.get(f"spatial_generated/{op}_runtime")
        rows.append(f"| {label} | {ns(g)} | {ns(r)} | {r / g:.2f}× |" if g and r
                    else f"| {label} | — | — | — |")
    rows += ["", "| the RSSR's `pose`, run-time, mean over a turn | ns |", "|---|---:|"]
    for key, label in [("closed", "closed form"), ("newton", "Newton continued from the drawing"),
                       ("kernel", "the kernel alone (`Rssr::points`)")]:
        rows.append(f"| {label} | {ns(med.get(f'spatial_rssr/{key}'))} |")
    return "\n".join(rows)


class Figure:
    def __init__(self, run, command, paths):
        self.run, self.command, self.paths = run, command, paths


FIGURES = {
    "floor": Figure(floor, FLOOR_CMD, GENERATED + ["benches/floor.rs", "benches/floor"]),
    "floor_instructions": Figure(floor_instructions, "callgrind on `cargo bench --bench floor --no-run`'s binary "
                                 "(`--profile-time 1` per function, the recipe of `benches/floor.rs`'s header), "
                                 "instructions per call", GENERATED + ["mech-core/src/runtime", "benches/floor.rs",
                                                                      "benches/floor"]),
    "batch": Figure(batch, BATCH_CMD, GENERATED + ["benches/floor.rs", "benches/floor"]),
    "runtime_floor": Figure(runtime_floor, RUNTIME_FLOOR_CMD, GENERATED + ["mech-core/src/runtime", "benches/floor.rs",
                                                                          "benches/floor"]),
    "runtime": Figure(runtime, RUNTIME_CMD, CORE + ["mech-oracle/src", "benches/generated_vs_generic.rs"]),
    "triad": Figure(triad, "`cargo bench --bench triad -- --warm-up-time 1 --measurement-time 3`, medians "
                    "(a sweep: 64 crank angles over a turn; the interleaved ratio: `triad_ratio/<machine>`)",
                    GENERATED + ["mech-core/src/runtime", "benches/triad.rs", "tests/common/triads.rs"]),
    "spatial": Figure(spatial, "`cargo bench --bench spatial -- --warm-up-time 1 --measurement-time 3`, medians",
                      GENERATED + ["mech-core/src/spatial", "benches/spatial.rs"]),
    "elements": Figure(elements, "`cargo bench --bench machine_elements`, medians",
                       CORE + ["benches/machine_elements.rs"]),
    "accuracy": Figure(accuracy, "`cargo run --release --example accuracy_report`",
                       CORE + ["mech-oracle/src", "examples/accuracy_report.rs", "tests/data"]),
    "dynamics": Figure(dynamics, "`cargo bench --bench dynamics`, medians",
                       CORE + ["benches/dynamics.rs"]),
    "work_precision": Figure(work_precision, "`cargo run --release --example work_precision`",
                             CORE + ["examples/work_precision.rs"]),
    "engine": Figure(engine, "`cargo run --release --example engine`, all but its last line (the time it took)",
                     CORE + ["examples/engine.rs", "examples/common"]),
    "engine_flywheel": Figure(engine_flywheel, "`cargo run --release --example engine`, the flywheel's lines",
                              CORE + ["examples/engine.rs", "examples/common"]),
    "sweep": Figure(sweep, SWEEP_CMD, CORE + ["mech-cli/src", "examples/mech/watt_ii.mech"]),
    "pyslvs": Figure(pyslvs, "`python3 tools/python_vs_pyslvs.py --table` (needs `mech` and `pyslvs` installed)",
                     CORE + ["mech-py/src", "mech-py/python", "tools/python_vs_pyslvs.py"]),
    "montecarlo": Figure(montecarlo, "`run_serial(10000, 1)` of `mech-py/examples/tolerance_study.py`, best of 3 "
                         "(needs `mech` installed)", CORE + ["mech-py/src", "mech-py/examples/tolerance_study.py"]),
    "fuzz": Figure(fuzz, "`cargo run --release -p mech-fuzz -- --cases 1000000`",
                   CORE + ["fuzz/src"]),
    "macro_cost": Figure(macro_cost, "`tools/macro_cost.sh 3`", CORE + ["tools/macro_cost.sh"]),
    "synthesis": Figure(synthesis, SYNTH_CMD, CORE + ["mech-cli/src", "tests/data/synthesis"]),
    "synthesis_rates": Figure(synthesis_rates, "`python3 tools/synthesis_vs_others.py --table` (needs pyslvs and "
                              "pylinkage installed), one thread each",
                              CORE + ["mech-cli/src", "tests/data/synthesis", "tools/synthesis_vs_others.py"]),
}


# ---------------------------------------------------------------------------------------
# blocks


def block(name, body):
    f = FIGURES[name]
    today = datetime.date.today().isoformat()
    sub = (f"<sub>Printed by `python3 tools/report.py {name}` ({f.command}) on the code of "
           f"{commit(f.paths)} (tree FNV-1a {code_hash(f.paths)} of {', '.join(f.paths)}), "
           f"{machine()}, {today}.</sub>")
    return f"<!-- report {name} -->\n{body}\n\n{sub}\n<!-- /report {name} -->"


def pattern(name):
    return re.compile(r"<!-- report " + re.escape(name) + r" -->.*?<!-- /report " + re.escape(name) + r" -->",
                      re.S)


def write(name, text):
    hits = []
    for doc in DOCS:
        src = doc.read_text()
        new, n = pattern(name).subn(lambda _: text, src)
        if n:
            doc.write_text(new)
            hits.append(doc.relative_to(ROOT).as_posix())
    return hits


def shown_in(name):
    return [d.relative_to(ROOT).as_posix() for d in DOCS if pattern(name).search(d.read_text())]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("names", nargs="+", help="figure names, `all`, or `list`")
    ap.add_argument("--write", action="store_true", help="put each block into the documents that show it")
    args = ap.parse_args()
    if args.names == ["list"]:
        for name, f in FIGURES.items():
            print(f"{name:15} {f.command}\n{'':15} shown in: {', '.join(shown_in(name)) or '(nowhere)'}")
        return
    names = list(FIGURES) if args.names == ["all"] else args.names
    for n in names:
        if n not in FIGURES:
            sys.exit(f"unknown figure `{n}`; the figures: {', '.join(FIGURES)}")
    for n in names:
        text = block(n, FIGURES[n].run())
        print(text + "\n")
        if args.write:
            hits = write(n, text)
            print(f"(written into {', '.join(hits) or 'no document: add the markers first'})\n",
                  file=sys.stderr)


if __name__ == "__main__":
    main()
