"""Run a scene and plot a probe: the midspan deflection of the thesis' bridge (study 4, D44)
as the disk crosses it, with the disk's normal force beside it.

    python examples/run_and_plot.py [scene.yaml] [figure.png]
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import rollbeam

here = Path(__file__).resolve().parent
scene_file = sys.argv[1] if len(sys.argv) > 1 else here.parent / "studies" / "bridge-d44.yaml"
figure = sys.argv[2] if len(sys.argv) > 2 else "run_and_plot.png"

scene = rollbeam.Scene.from_yaml(scene_file)
result = rollbeam.run(scene)
h = result.history

fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(7, 5))
top.plot(result.t, h["mid.w"] * 1e3)
top.set_ylabel("midspan w (mm)")
bottom.plot(result.t, h["disk.rn"] / 1e3)
bottom.set_ylabel("normal force R_n (kN)")
bottom.set_xlabel("t (s)")
fig.suptitle(f"{scene.name}: {result.stopped} at t = {result.summary['stopped']['t']:.3f} s")
fig.savefig(figure, dpi=100)
print(f"{scene.name}: lowest midspan w {h['mid.w'].min():.6e} m; wrote {figure}")
