#!/usr/bin/env python3
# %% [markdown]
# # A tour of the cueplan Python package
#
# A plain script in Jupyter's "percent" format: each `# %%` starts a cell, so Jupyter
# (with jupytext), VS Code or Spyder open it as a notebook, and `python3` runs it whole
# (ctest does: python_tour_test, matplotlib's Agg backend). It plots a planned shot, a
# spin map, and a batch of problems as a pandas DataFrame (a list of dicts without pandas).
#
#     pip install --no-build-isolation .      # or PYTHONPATH=build/python
#     python3 examples/python_tour.py --out-dir tour
#
# %%
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")  # pictures to files; drop this line in a notebook
import matplotlib.pyplot as plt
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
try:
    import cueplan
except ImportError:  # a checkout built with CMake, not installed
    sys.path.insert(0, os.path.join(ROOT, "build", "python"))
    import cueplan

parser = argparse.ArgumentParser(description="A tour of the cueplan Python package")
parser.add_argument("--out-dir", default="tour", help="where the pictures go (tour/)")
parser.add_argument("--problems", default=os.path.join(ROOT, "problems"), help="the shipped problems")
args, _ = parser.parse_known_args()
os.makedirs(args.out_dir, exist_ok=True)
print("cueplan", cueplan.__version__)

# %% [markdown]
# ## A problem, with every default resolved
# %%
problem = cueplan.Problem(os.path.join(args.problems, "pots", "straight_pot_corner.yaml"))
print(problem.describe())
print("table", problem.table.length, "x", problem.table.width, "m;", len(problem.table.pockets), "pockets;",
      "pot", problem.pot)

# %% [markdown]
# ## Solve it and plot the shot
# The evaluation budget, not the clock, ends the search, so the answer is reproducible.
# %%
plan = cueplan.solve(problem, method="exact", max_evaluations=400, samples=50, seed=2, max_time=120)
print(plan, "-", plan.best["stroke_words"])
print("P(pot) =", plan.success["pot"]["p"], " P(both) =", plan.success["both"]["p"])
shot = plan.shot
ax = shot.plot()
fig_shot = os.path.join(args.out_dir, "shot.png")
ax.figure.savefig(fig_shot, dpi=100)
plt.close(ax.figure)
t, x, y = shot.trajectory(0.01)
print(f"trajectory: {len(t)} instants over {t[-1]:.2f} s for {x.shape[1]} balls; "
      f"{len(shot.events)} events; the pot made: {shot.verdict['pot_made']}")
assert shot.verdict["pot_made"], shot.verdict

# %% [markdown]
# ## What spin lands here? The spin map at the planned speed and aim
# %%
position = cueplan.Problem(os.path.join(args.problems, "one_rail_position.yaml"))
spins = cueplan.spin_map(position, 1.002, -60.36, grid=21, method="exact")
ax = spins.plot()
fig_spin = os.path.join(args.out_dir, "spin_map.png")
ax.figure.savefig(fig_spin, dpi=100)
plt.close(ax.figure)
print(f"spin map: {spins.landing} of {len(spins.cells['lands'])} spins land")

# %% [markdown]
# ## Cushion rebounds over a numpy grid (the batch path: SIMD lanes, all cores)
# %%
angle = np.linspace(5, 175, 171)
topspin = np.array([-1.0, 0.0, 1.0, 2.0])[:, None]
r = cueplan.rebound(1.5, angle[None, :], topspin)
fig, ax = plt.subplots(figsize=(6, 4))
for k, row in zip(topspin[:, 0], r["rebound_angle_deg"]):
    ax.plot(angle, row, label=f"k_T = {k:g}")
ax.plot(angle, angle, "k:", lw=0.8, label="mirror")
ax.set_xlabel("incidence alpha (deg)")
ax.set_ylabel("rebound angle (deg)")
ax.legend()
fig_rebound = os.path.join(args.out_dir, "rebound.png")
fig.savefig(fig_rebound, dpi=100)
plt.close(fig)

# %% [markdown]
# ## A batch of problems as a DataFrame
# %%
pots = sorted(os.path.join(args.problems, "pots", f) for f in os.listdir(os.path.join(args.problems, "pots"))
              if f.endswith(".yaml"))[:4]
records = cueplan.solve_many(pots, threads=2, method="exact", max_evaluations=300, samples=20, max_time=120)
try:
    import pandas as pd

    table = pd.DataFrame(records)[["name", "status", "speed", "aim_deg", "success", "p_pot"]]
    print(table.to_string(index=False))
except ImportError:  # pandas is optional: the records are plain dicts
    for rec in records:
        print(rec["name"], rec["status"], round(rec["speed"], 3), round(rec["aim_deg"], 2), rec["success"])
assert len(records) == len(pots)
print("pictures:", fig_shot, fig_spin, fig_rebound)
