#!/usr/bin/env python3
"""A data file of a rectangular plate whose square-lattice particles are moved
by random offsets (in.crack-branching or in.kalthoff-2d -var data FILE):

    jitter.py AMPLITUDE SEED FILE [--dx DX] [--box X0 X1 Y0 Y1] [--rho RHO]
              [--mirror-y]

Each particle of the lattice (centres (X0 + (i+0.5) dx, Y0 + (j+0.5) dx) of
the box, by default the 100 x 40 mm crack-branching plate) moves by independent
uniform offsets in [-A, A] dx in x and y; volume dx^2 x 1 m, mass rho V (the
decks set the masses again). A measures how much a crack depends on the
lattice directions. --mirror-y (a box symmetric about y = 0) draws the offsets
of the upper half only and mirrors them onto the lower half, so that a problem
symmetric about y = 0 (Kalthoff-Winkler) stays exactly symmetric."""
import argparse

import numpy as np


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("amplitude", type=float, help="largest offset per coordinate, in dx (< 0.5)")
    ap.add_argument("seed", type=int)
    ap.add_argument("file")
    ap.add_argument("--dx", type=float, default=0.000333333333333)
    ap.add_argument("--box", type=float, nargs=4, default=[0.0, 0.1, 0.0, 0.04],
                    metavar=("X0", "X1", "Y0", "Y1"))
    ap.add_argument("--rho", type=float, default=2450.0, help="density (default: the glass)")
    ap.add_argument("--mirror-y", action="store_true")
    a = ap.parse_args()
    if not 0.0 <= a.amplitude < 0.5:
        ap.error("amplitude must be in [0, 0.5) dx")
    x0, x1, y0, y1 = a.box
    nx, ny = round((x1 - x0) / a.dx), round((y1 - y0) / a.dx)
    if a.mirror_y and (abs(y0 + y1) > 1e-12 or ny % 2):
        ap.error("--mirror-y needs a box symmetric about y = 0 with an even number of rows")
    rng = np.random.default_rng(a.seed)
    i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    ox = a.amplitude * rng.uniform(-1, 1, i.shape)
    oy = a.amplitude * rng.uniform(-1, 1, i.shape)
    if a.mirror_y:
        # row j mirrors row ny-1-j
        ox[:, :ny // 2] = ox[:, ny - 1:ny // 2 - 1:-1]
        oy[:, :ny // 2] = -oy[:, ny - 1:ny // 2 - 1:-1]
    x = x0 + (i.ravel() + 0.5 + ox.ravel()) * a.dx
    y = y0 + (j.ravel() + 0.5 + oy.ravel()) * a.dx
    V = a.dx * a.dx * 1.0
    with open(a.file, "w") as f:
        f.write(f"plate {x1 - x0} x {y1 - y0} m, square lattice dx = {a.dx} m jittered by "
                f"+-{a.amplitude} dx (seed {a.seed}{', mirrored about y = 0' if a.mirror_y else ''})"
                f"\n\n{x.size} atoms\n1 atom types\n\n"
                f"{x0} {x1} xlo xhi\n{y0} {y1} ylo yhi\n-0.5 0.5 zlo zhi\n\nAtoms # peri\n\n")
        for k, (xa, ya) in enumerate(zip(x, y)):
            # atom_style peri: id type volume mass x y z (the deck sets the mass)
            f.write(f"{k + 1} 1 {V:.12g} {a.rho * V:.12g} {xa:.12g} {ya:.12g} 0\n")


if __name__ == "__main__":
    main()
