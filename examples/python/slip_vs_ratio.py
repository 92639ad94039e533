# %% [markdown]
# # Slip against the tension ratio, and the stick/slip field, from Python
#
# The thick body of the paper's section 3 (a semi-elliptical prism `a = b = 2`, `E = 1e3`,
# `nu = 1/4`, `mu = 1/2`, grid 250 x 41) is pulled with a growing tension ratio
# `tau_max / tau0`. The fraction of the contact surface that slips (the paper's Slip) grows
# until the whole contact slides; at `tau_max = 2` part of it still sticks.
#
# Run (a notebook-style script: `# %%` cells open in Jupyter/VS Code as a notebook):
#
#     pip install ./crates/python matplotlib      # or: cd crates/python && maturin develop
#     python examples/python/slip_vs_ratio.py [OUT_DIR]
#
# Look at `OUT_DIR/slip_vs_ratio.png` (compare with `docs/figures/slip-ratio.svg`) and
# `OUT_DIR/stick_slip_field.png` (v^2 over the curved body, the contact state beneath).

# %%
import sys
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only; drop this line in a notebook
import matplotlib.pyplot as plt
import numpy as np

import capstan

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/python")
out.mkdir(parents=True, exist_ok=True)
scene = capstan.Scene()  # the paper's defaults; e.g. capstan.Scene.from_toml("examples/scenes/contact_default.toml")
print(scene)

# %% Slip against the tension ratio: one bulk factorisation serves every point
ratios = np.linspace(1.0, 3.3, 24)
t = time.perf_counter()
sweep = capstan.sweep(scene, "loads.tau_max", ratios)
print(f"{len(ratios)} points in {time.perf_counter() - t:.1f} s")
points = [p for p in sweep.points if p.converged]
x = np.array([p.tension_ratio for p in points])
slip = np.array([p.slip_fraction for p in points])

fig, ax = plt.subplots(figsize=(6, 4))
ax.plot(x, slip, "o-")
ax.set_xlabel("tension ratio tau_max / tau0")
ax.set_ylabel("Slip (mean of -1/0/+1 node states)")
ax.set_title("Slip against the tension ratio (paper section 3)")
ax.grid(True, alpha=0.3)
fig.tight_layout()
fig.savefig(out / "slip_vs_ratio.png", dpi=120)

# %% The stick/slip field at tau_max = 2, with the Newton residuals as they fall
residuals = []
result = capstan.contact(scene, callback=lambda p: residuals.append(p["residual"]))
print(f"Slip {result.slip_fraction:.4f}, stick {result.stick_interval}, "
      f"{result.newton_iterations} Newton iterations, last residual {residuals[-1]:.2e}")

points3 = result.fields["points"]          # (n2, n3, 3): the body in E^3
v2 = result.fields["displacement_contravariant"][:, :, 1]  # v^2 (rad)
c = result.contact                          # the contact surface, x3 = 0

fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 7), height_ratios=[3, 1])
mesh = top.pcolormesh(points3[:, :, 1], points3[:, :, 2], v2, shading="gouraud", cmap="coolwarm")
fig.colorbar(mesh, ax=top, label="v^2 (rad)")
top.set_aspect("equal")
top.set_xlabel("y")
top.set_ylabel("z")
top.set_title("Azimuthal displacement on the curved body")
bottom.step(c.x2, c.state, where="mid")
bottom.set_yticks([-1, 0, 1], ["slip -", "stick", "slip +"])
bottom.set_xlabel("x2 = theta (rad)")
bottom.set_title("Contact state")
fig.tight_layout()
fig.savefig(out / "stick_slip_field.png", dpi=120)
print("wrote", out / "slip_vs_ratio.png", "and", out / "stick_slip_field.png")
