"""A first run from Python: the paper's five-block wall with variable friction under a ground
motion made in numpy (a 400 gal, 1 Hz sine that dies away), its history as numpy arrays, and
the same wall under El Centro 1940 read from its file.

    python docs/python/first_run.py          # from the repository's root
"""

from pathlib import Path

import numpy as np

import pirqa

ROOT = Path(__file__).resolve().parents[2]

wall = pirqa.Wall.from_file(ROOT / "walls/five-block-variable.ron")
dt_s = 0.01
t_s = np.arange(0.0, 20.0 + dt_s / 2, dt_s)
accel_gal = 400.0 * np.sin(2 * np.pi * 1.0 * t_s) * np.exp(-0.05 * t_s)
motion = pirqa.Motion.from_array(accel_gal, dt_s=dt_s, units="gal", name="decaying sine")

result = pirqa.run(wall, motion, output_dt_s=0.01)
for block in result.summary["blocks"]:
    print(f"{block['name']}: max |u| = {block['max_abs_displacement_m']:.4f} m")
energy = result.summary["energy"]
print(f"energy balance residual {energy['residual_j']:.3e} J of {energy['input_j']:.1f} J input")

h = result.history
top = h.blocks.index("B4")
print(f"history: {len(h.time_s)} rows x {len(h.blocks)} blocks; B4 ends at "
      f"{h.displacement_m[-1, top]:.4f} m")

el_centro = pirqa.Motion.from_file(
    ROOT / "records/elcentro1940_IELC180_peer_dt0p01_g.AT2", pga="1500gal"
)
collapse = pirqa.run(wall, el_centro).summary["collapse"]
print(f"El Centro at 1500 gal: {collapse}")
