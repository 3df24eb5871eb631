#!/usr/bin/env python3
"""Samples Table-Cube scenes (the paper's Figure 1) and plots, seen from above, where the cube
and the two trays landed on the table. Writes a PNG (matplotlib's Agg backend, no display).

Usage: plot_cube_positions.py [N_SCENES] [OUT.png]    (defaults: 2000, cube_positions.png)
"""

import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # before pyplot: render to files only
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402

import probrobscene as prs  # noqa: E402

EXAMPLES = pathlib.Path(__file__).resolve().parents[1]


def main() -> None:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 2000
    out = sys.argv[2] if len(sys.argv) > 2 else "cube_positions.png"
    scenario = prs.load(EXAMPLES / "table_cube.prs")
    scenes = scenario.sample_batch(n, seed=1)  # every core, without the GIL
    # The cube is anonymous in the paper's listing: it is the sixth object, "Cube#5".
    cube = prs.positions(scenes, "Cube#5")  # (n, 3) metres
    trays = [prs.positions(scenes, name) for name in ("tr_1", "tr_2")]

    table = scenes[0]["t"]
    width, length, _ = table.dimensions
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.add_patch(Rectangle((table.position[0] - width / 2, table.position[1] - length / 2),
                           width, length, fill=False, edgecolor="black", label="table"))
    for name, xyz in zip(("tray 1 centre", "tray 2 centre"), trays):
        ax.scatter(xyz[:, 0], xyz[:, 1], s=2, alpha=0.3, label=name)
    ax.scatter(cube[:, 0], cube[:, 1], s=2, color="blue", label="cube")
    ax.set(xlabel="x (m)", ylabel="y (m)", aspect="equal",
           title=f"Table-Cube: {n} scenes, seed 1")
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1), markerscale=4)
    fig.savefig(out, dpi=120, bbox_inches="tight")
    print(f"{out}: cube x in [{cube[:, 0].min():.3f}, {cube[:, 0].max():.3f}] m, "
          f"y in [{cube[:, 1].min():.3f}, {cube[:, 1].max():.3f}] m over {n} scenes")


if __name__ == "__main__":
    main()
