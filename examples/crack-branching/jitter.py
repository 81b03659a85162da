#!/usr/bin/env python3
"""A data file of the crack-branching plate with the particles of the square
lattice moved by random offsets (for in.crack-branching -var data FILE):

    jitter.py AMPLITUDE SEED FILE [--dx DX]

Each particle of the deck's lattice (centres ((i+0.5) dx, (j+0.5) dx) of the
100 x 40 mm plate) moves by independent uniform offsets in [-A, A] dx in x and
y; volume dx^2 x 1 m and the glass density as in the deck (which sets the
masses again). A measures how much the crack depends on the lattice
directions."""
import argparse

import numpy as np


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("amplitude", type=float, help="largest offset per coordinate, in dx (< 0.5)")
    ap.add_argument("seed", type=int)
    ap.add_argument("file")
    ap.add_argument("--dx", type=float, default=0.000333333333333)
    a = ap.parse_args()
    if not 0.0 <= a.amplitude < 0.5:
        ap.error("amplitude must be in [0, 0.5) dx")
    Lx, Ly, rho = 0.1, 0.04, 2450.0
    nx, ny = round(Lx / a.dx), round(Ly / a.dx)
    rng = np.random.default_rng(a.seed)
    i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    x = (i.ravel() + 0.5) * a.dx + a.amplitude * a.dx * rng.uniform(-1, 1, i.size)
    y = (j.ravel() + 0.5) * a.dx + a.amplitude * a.dx * rng.uniform(-1, 1, i.size)
    V = a.dx * a.dx * 1.0
    with open(a.file, "w") as f:
        f.write(f"crack-branching plate, square lattice dx = {a.dx} m jittered by "
                f"+-{a.amplitude} dx (seed {a.seed})\n\n{x.size} atoms\n1 atom types\n\n"
                f"0 {Lx} xlo xhi\n0 {Ly} ylo yhi\n-0.5 0.5 zlo zhi\n\nAtoms # peri\n\n")
        for k, (xa, ya) in enumerate(zip(x, y)):
            # atom_style peri: id type volume mass x y z (the deck sets the mass)
            f.write(f"{k + 1} 1 {V:.12g} {rho * V:.12g} {xa:.12g} {ya:.12g} 0\n")


if __name__ == "__main__":
    main()
