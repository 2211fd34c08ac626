"""Monte Carlo tolerance study of a crank-rocker four-bar, serially, on Dask, or on Ray.

Every variant moves the pins A, B and the ground pivot O4 by independent normal errors
(sigma = 0.1 mm in x and y: toleranced lengths), is solved over a full turn of the crank
at constant speed, and reports the peak driver torque and the minimum transmission angle
(the acute angle between the coupler and the rocker). The batch of a partition is one
call of `mech.sweep` (Rust, rayon, GIL released); a variant that does not assemble is
masked, never an exception.

    python tolerance_study.py serial 10000
    python tolerance_study.py dask 1000000 out/      # partitions as CSV files in out/
    python tolerance_study.py ray 1000000 out/
"""

import math
import os
import sys

import numpy as np

import mech

FOUR_BAR = """
/// Crank-rocker four-bar: crank 80 mm, coupler 260 mm, rocker 190 mm, frame 300 mm.
pub struct FourBar {
    consts { crank: 80 mm, coupler: 260 mm, rocker: 190 mm },
    gravity: (0.0, -9.81),
    ground { O2: (0.0, 0.0), O4: (300 mm, 40 mm) },
    link crank { points { O2, A: O2 + polar(crank, 60 deg) }, mass: 650 g, inertia: 5.2e-4 kg_m2, cg: along(25 mm) },
    link coupler { points { A, B: circle_circle(A, coupler, O4, rocker, left) }, mass: 1.45 kg, inertia: 0.0112 kg_m2, cg: along(130 mm) },
    link rocker { points { O4, B }, mass: 0.95 kg, inertia: 0.0036 kg_m2, cg: along(95 mm) },
    joints {
        O2: revolute(ground, crank),
        A: revolute(crank, coupler),
        B: revolute(coupler, rocker),
        O4: revolute(ground, rocker),
    },
    input: O2,
    loads { resist: torque on rocker },
}
"""

SIGMA = 1e-4          # m, pin position tolerance (one standard deviation, each axis)
SPEED = 2 * math.pi * 5   # rad/s, 300 rpm
STEPS = 72            # crank positions per turn
RESIST = -6.5         # N·m on the rocker


def mechanism():
    """The nominal four-bar."""
    return mech.Mechanism.from_dsl(FOUR_BAR)


def variants(n, seed):
    """n toleranced drawings (dict of parameter -> (n, 2) arrays), reproducible by seed."""
    m = mechanism()
    nominal = m.pose(m_input_at_drawing(m))
    rng = np.random.default_rng(seed)
    return {
        "points.%s" % p: np.array([nominal["%s.x" % p], nominal["%s.y" % p]]) + rng.normal(0.0, SIGMA, size=(n, 2))
        for p in ("A", "B", "O4")
    }


def m_input_at_drawing(m):
    """The crank angle of the drawing (60°)."""
    return math.radians(60.0)


def study(params, m=None):
    """Peak |driver torque| (N·m) and minimum transmission angle (rad) of each variant,
    NaN where a variant does not assemble over the whole turn."""
    m = m or mechanism()
    q = np.linspace(0.0, 2 * math.pi, STEPS, endpoint=False)
    out = mech.sweep(m, params, q, qd=SPEED, loads={"resist": RESIST}, parts=["positions", "virtual_power"])
    ok = out["ok"].all(axis=1)
    peak = np.nanmax(np.abs(out["virtual_power"]), axis=1)
    ab = np.stack([out["B.x"] - out["A.x"], out["B.y"] - out["A.y"]], axis=-1)
    ob = np.stack([out["B.x"] - out["O4.x"], out["B.y"] - out["O4.y"]], axis=-1)
    cos = np.abs(np.sum(ab * ob, axis=-1)) / (np.linalg.norm(ab, axis=-1) * np.linalg.norm(ob, axis=-1))
    mu = np.nanmin(np.arccos(np.clip(cos, 0.0, 1.0)), axis=1)
    peak[~ok] = np.nan
    mu[~ok] = np.nan
    return peak, mu


def partition(seed, n):
    """One partition: n variants from `seed`, as columns."""
    peak, mu = study(variants(n, seed))
    return {"seed": np.full(n, seed), "peak_torque": peak, "min_transmission_angle": mu}


def frame(seed, n, out_dir=None):
    """One partition as a pandas DataFrame, written as `out_dir/part-<seed>.csv` when
    `out_dir` is given (by the worker that computed it)."""
    import pandas as pd

    df = pd.DataFrame(partition(seed, n))
    if out_dir:
        df.to_csv(os.path.join(out_dir, "part-%05d.csv" % seed), index=False)
    return df


def summary(peak, mu):
    """Mean and standard deviation of both, and the 0.1 % quantile of the angle."""
    return {
        "peak_torque_mean": float(np.nanmean(peak)),
        "peak_torque_std": float(np.nanstd(peak)),
        "min_angle_mean": float(np.nanmean(mu)),
        "min_angle_q001": float(np.nanquantile(mu, 0.001)),
        "failed": int(np.isnan(peak).sum()),
    }


def run_dask(total, parts, out_dir=None, client=None):
    """The study on a Dask cluster (a LocalCluster when `client` is None): one task per
    partition, each written as CSV in `out_dir` when given; returns the summary."""
    import dask
    import pandas as pd
    from dask.distributed import Client, LocalCluster

    own = client is None
    if own:
        client = Client(LocalCluster(n_workers=2, threads_per_worker=1, env={"MECH_NUM_THREADS": "1"}))
    try:
        n = total // parts
        frames = [dask.delayed(frame)(seed, n, out_dir) for seed in range(parts)]
        df = pd.concat(dask.compute(*frames))
        return summary(df["peak_torque"].to_numpy(), df["min_transmission_angle"].to_numpy())
    finally:
        if own:
            client.close()


def run_ray(total, parts, out_dir=None):
    """The same on Ray: one remote task per partition."""
    import pandas as pd
    import ray

    ray.init(ignore_reinit_error=True, runtime_env={"env_vars": {"MECH_NUM_THREADS": "1"}})
    task = ray.remote(frame)
    n = total // parts
    df = pd.concat(ray.get([task.remote(seed, n, out_dir) for seed in range(parts)]))
    return summary(df["peak_torque"].to_numpy(), df["min_transmission_angle"].to_numpy())


def run_serial(total, parts):
    """The same sample in one process, partition by partition."""
    cols = [partition(seed, total // parts) for seed in range(parts)]
    return summary(np.concatenate([c["peak_torque"] for c in cols]), np.concatenate([c["min_transmission_angle"] for c in cols]))


if __name__ == "__main__":
    how, total = sys.argv[1], int(sys.argv[2])
    out = sys.argv[3] if len(sys.argv) > 3 else None
    if out:
        os.makedirs(out, exist_ok=True)
    parts = max(1, total // 10000)
    result = {"serial": run_serial, "dask": lambda t, p: run_dask(t, p, out), "ray": lambda t, p: run_ray(t, p, out)}[how](total, parts)
    print(result)
