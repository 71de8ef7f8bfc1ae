"""The same speed sweep on a Dask cluster: here a local one with two workers; on a real
cluster, pass that cluster's Client instead. Each case is rollbeam.sweep_case, a pure
function of (scene, values), so Dask ships the scene and gets a record back.

    python examples/dask_sweep.py
"""

from pathlib import Path

import numpy as np
from dask.distributed import Client, LocalCluster

import rollbeam


def main():
    here = Path(__file__).resolve().parent
    scene = rollbeam.Scene.from_yaml(here.parent / "studies" / "bridge-d44.yaml")
    omega0 = np.linspace(-10.0, -110.0, 11)
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with Client(cluster) as client:
            table = rollbeam.sweep(
                scene, {"disk.omega0": omega0}, executor=client.get_executor(), rtol=1e-4
            )
    local = rollbeam.sweep(scene, {"disk.omega0": omega0}, rtol=1e-4)
    same = all(
        np.array_equal(table[c], local[c], equal_nan=table[c].dtype.kind == "f")
        for c in table
        if c != "wall_s"
    )
    print(f"{scene.name}: {table.rows} cases on Dask; same table as the local sweep: {same}")
    if not same:
        raise SystemExit(1)


if __name__ == "__main__":
    main()
