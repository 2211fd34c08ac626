"""The Dask recipe of docs/scale-out.md on a LocalCluster of 2 workers (10⁴ variants),
against the same sample computed serially; the mechanism pickles to the workers."""

import pathlib
import sys

import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "examples"))
import tolerance_study as ts  # noqa: E402

distributed = pytest.importorskip("dask.distributed")


def test_dask_local_cluster_matches_serial(tmp_path):
    total, parts = 10_000, 4
    serial = ts.run_serial(total, parts)
    with distributed.Client(distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, env={"MECH_NUM_THREADS": "1"})) as client:
        got = ts.run_dask(total, parts, out_dir=str(tmp_path), client=client)
    assert got == serial
    files = sorted(tmp_path.glob("part-*.csv"))
    assert len(files) == parts
    assert sum(len(f.read_text().splitlines()) - 1 for f in files) == total
    # The statistics are physical: the nominal peak torque and transmission angle.
    nominal_peak, nominal_mu = ts.study({"points.A": [[0.04, 0.06928203230275509]]})
    assert abs(serial["peak_torque_mean"] - nominal_peak[0]) < 5 * serial["peak_torque_std"]
    assert 0 < serial["min_angle_mean"] < 1.6 and serial["failed"] == 0
