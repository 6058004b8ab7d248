#!/usr/bin/env python3
"""Skin1's diffusion profile r R(r) under every model of the registry against the exact one (matplotlib).

    python3 examples/plot_skin_models.py [OUT.png]       (default: skin1-models.png)

One call per model evaluates all radii of all channels (numpy in, numpy out).
"""
import sys

import matplotlib

matplotlib.use("Agg")  # files only: runs without a display (CI)
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import bssrdf  # noqa: E402

out = sys.argv[1] if len(sys.argv) > 1 else "skin1-models.png"
skin = bssrdf.materials.get("Skin1").medium
r = np.geomspace(1e-3, 20, 400)  # mm
exact = bssrdf.Model("exact").R(skin, r)

fig, axes = plt.subplots(1, 3, figsize=(15, 4.5), sharey=True)
for info in bssrdf.models():
    if info.name == "exact":
        continue
    model = bssrdf.Model(info.name)
    R = model.R(skin, r)
    for c, ax in enumerate(axes):
        ax.loglog(r, r * R[c], lw=1, label="%s (%.0f ns)" % (info.name, info.cost_ns))
for c, ax in enumerate(axes):
    ax.loglog(r, r * exact[c], "k", lw=2.5, label="exact")
    ax.set_title("Skin1, channel %s" % skin.channels[c])
    ax.set_xlabel("r (mm)")
    ax.set_ylim(1e-5, 1)
axes[0].set_ylabel("r R(r) (1/mm)")
axes[2].legend(fontsize=7)
fig.tight_layout()
fig.savefig(out, dpi=100)

# The numbers behind the picture: each model's worst relative L2 of r R(r) against exact.
for info in bssrdf.models():
    R = bssrdf.Model(info.name).R(skin, r)
    l2 = np.sqrt(((r * (R - exact)) ** 2).sum(axis=1) / ((r * exact) ** 2).sum(axis=1)).max()
    print("%-18s r R(r) relative L2 against exact (worst channel): %6.2f %%" % (info.name, 100 * l2))
print("wrote", out)
