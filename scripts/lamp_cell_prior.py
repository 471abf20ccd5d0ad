#!/usr/bin/env python3
"""The best room-blind answer to the lamp-cell loss (train --emitter-cell-weight).

For each scene folder of a training set (scene.json and cameras.json, as `synth` writes them),
t is the distribution over level 0's 8 x 8 x 8 cells that the loss asks for: 1/M on the cell of
each of the scene's M emitting primitives (lamps and window panes). Level 0 is the cube of side
s0 = 2 min(far, 20) m centred on the reference camera (docs/conventions.md), so a cell is s0/8
wide. Prints the mean Kullback-Leibler divergence KL(t || m) in nats, m being the distribution
of the other scenes' lamp cells (leave one out, mixed with a thousandth of uniform so that no
cell is impossible), and the same for a uniform m. A head that reads the room must score below
the first to have learnt anything about where this room's lamps are.

Usage: python3 scripts/lamp_cell_prior.py DATA_DIR
"""
import json
import math
import os
import sys

CELLS_PER_SIDE = 8
CELLS = CELLS_PER_SIDE ** 3
UNIFORM_SHARE = 1e-3


def lamp_cells(folder):
    """t of one scene as {cell index: share}, or None if the folder has no lamps or files."""
    try:
        with open(os.path.join(folder, "scene.json")) as f:
            scene = json.load(f)
        with open(os.path.join(folder, "cameras.json")) as f:
            far = float(json.load(f)["far"])
    except (OSError, ValueError, KeyError) as e:
        print(f"lamp_cell_prior: skipping {folder}: {e}", file=sys.stderr)
        return None
    lamps = [p["centre"] for p in scene.get("primitives", []) if p.get("emission", "none") != "none"]
    if not lamps:
        return None
    side = 2.0 * min(far, 20.0)
    cell = side / CELLS_PER_SIDE
    t = {}
    for centre in lamps:
        i = [min(CELLS_PER_SIDE - 1, max(0, math.floor((centre[a] + side / 2) / cell))) for a in range(3)]
        index = (i[2] * CELLS_PER_SIDE + i[1]) * CELLS_PER_SIDE + i[0]  # z, y, x as the cubes
        t[index] = t.get(index, 0.0) + 1.0 / len(lamps)
    return t


def main():
    if len(sys.argv) != 2 or not os.path.isdir(sys.argv[1]):
        sys.exit("usage: lamp_cell_prior.py DATA_DIR (a folder of synth scene folders)")
    root = sys.argv[1]
    scenes = [lamp_cells(os.path.join(root, d)) for d in sorted(os.listdir(root))
              if os.path.isdir(os.path.join(root, d))]
    scenes = [t for t in scenes if t]
    if len(scenes) < 2:
        sys.exit(f"lamp_cell_prior: {root} has {len(scenes)} scenes with lamps; at least 2 needed")
    total = [0.0] * CELLS
    for t in scenes:
        for c, share in t.items():
            total[c] += share
    n = len(scenes)
    marginal_kl, uniform_kl = 0.0, 0.0
    for t in scenes:
        for c, share in t.items():
            others = (total[c] - share) / (n - 1)
            m = (1 - UNIFORM_SHARE) * others + UNIFORM_SHARE / CELLS
            marginal_kl += share * math.log(share / m) / n
            uniform_kl += share * math.log(share * CELLS) / n
    print(f"scenes with lamps: {n}; cells that hold one: {sum(1 for v in total if v > 0)} of {CELLS}")
    print(f"mean KL(t || training marginal, leave one out): {marginal_kl:.3f} nats")
    print(f"mean KL(t || uniform): {uniform_kl:.3f} nats")


if __name__ == "__main__":
    main()
