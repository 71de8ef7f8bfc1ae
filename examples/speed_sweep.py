"""A speed sweep on this machine's cores: the bridge of study 4 crossed at 21 speeds, the
midspan's lowest deflection against speed, as `rollbeam sweep --set disk.omega0=…` does.

    python examples/speed_sweep.py [figure.png]
"""

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import rollbeam

here = Path(__file__).resolve().parent
figure = sys.argv[1] if len(sys.argv) > 1 else "speed_sweep.png"

scene = rollbeam.Scene.from_yaml(here.parent / "studies" / "bridge-d44.yaml")
radius = 0.4  # m, the scene's disk.radius: the speed is -omega0 * radius
omega0 = np.linspace(-10.0, -110.0, 21)
table = rollbeam.sweep(scene, {"disk.omega0": omega0}, rtol=1e-4)

speed = -table["disk.omega0"] * radius
plt.plot(speed, -table["mid.w_min"] * 1e3, marker="o")
plt.xlabel("disk speed (m/s)")
plt.ylabel("largest midspan deflection (mm)")
plt.title(f"{scene.name}: {table.rows} runs, {int(np.sum(table['status'] != 'ok'))} failed")
plt.savefig(figure, dpi=100)
peak = int(np.nanargmin(table["mid.w_min"]))
print(f"{scene.name}: deepest midspan deflection {table['mid.w_min'][peak]:.6e} m at {speed[peak]:.1f} m/s; wrote {figure}")
