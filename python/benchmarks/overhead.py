"""What the Python package costs beside the command line (issue 19's performance table in
REPORT.md, "Performance"). Not a test: timings depend on the machine.

    python python/benchmarks/overhead.py [--cases 1000]

1. One run: `rollbeam run` as a process (median of 7), the process start-up alone
   (`rollbeam --version`), and `rollbeam.run` in this process (median of 7, arrays included).
2. A sweep of N cases of the parabola study: built in (threads over every core) against a
   local Dask cluster of two worker processes (`client.get_executor()`), same machine, same
   run; the overhead per case is the difference over N.
"""

import argparse
import os
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

import rollbeam

ROOT = Path(__file__).resolve().parents[2]
BIN = Path(os.environ.get("ROLLBEAM_BIN", ROOT / "target" / "release" / "rollbeam"))


def median_time(f, repeat=7):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--cases", type=int, default=1000)
    args = parser.parse_args()
    out = tempfile.mkdtemp()
    start = median_time(lambda: subprocess.run([BIN, "--version"], capture_output=True, check=True))
    print(f"process start-up (rollbeam --version): {start * 1e3:.1f} ms")
    print("| study | `rollbeam run` (process) | minus start-up | `rollbeam.run` | ratio |")
    print("|---|---|---|---|---|")
    for study in ["parabola-p1.yaml", "bridge-d44.yaml"]:
        path = ROOT / "studies" / study
        cli = median_time(
            lambda: subprocess.run([BIN, "run", path, "--out", out], capture_output=True, check=True)
        )
        scene = rollbeam.Scene.from_yaml(path)
        py = median_time(lambda: rollbeam.run(scene))
        print(
            f"| {study[:-5]} | {cli * 1e3:.0f} ms | {(cli - start) * 1e3:.0f} ms | {py * 1e3:.0f} ms "
            f"| {py / (cli - start):.2f} |"
        )
    scene = rollbeam.Scene.from_yaml(ROOT / "studies" / "parabola-p1.yaml")
    omega0 = np.linspace(-1.0, -3.0, args.cases)
    t = time.perf_counter()
    local = rollbeam.sweep(scene, {"disk.omega0": omega0})
    built_in = time.perf_counter() - t
    from dask.distributed import Client, LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            rollbeam.sweep(scene, {"disk.omega0": omega0[:4]}, executor=client.get_executor())
            t = time.perf_counter()
            on_dask = rollbeam.sweep(scene, {"disk.omega0": omega0}, executor=client.get_executor())
            dask_s = time.perf_counter() - t
    run_s = float(np.sum(local["wall_s"]))
    print(
        f"{args.cases} cases of parabola-p1: built in {built_in:.2f} s, Dask (2 workers) {dask_s:.2f} s; "
        f"the runs themselves {run_s:.2f} s of one core; overhead per case on Dask "
        f"{(dask_s - built_in) / args.cases * 1e3:.2f} ms; tables equal (but wall_s): "
        f"{all(np.array_equal(local[c], on_dask[c], equal_nan=local[c].dtype.kind == 'f') for c in local if c != 'wall_s')}"
    )


if __name__ == "__main__":
    main()
