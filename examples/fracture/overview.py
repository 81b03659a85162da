#!/usr/bin/env python3
"""The final damage of the main job's two runs side by side, one PNG.

    overview.py BRANCHING_PREFIX KALTHOFF_PREFIX -o overview.png

Reads PREFIX.dump (the fracture decks' damage dump: every particle at step 0,
later frames the damaged ones) and PREFIX.crack.json (tools/crack_measure.py,
written by the examples' summarise.py) and draws, for each run, the plate at
its reference positions in light grey and every particle with damage phi > 0
of the last frame coloured by phi, with the measured numbers in the title.
"""
import argparse
import json
import math
import os
import sys

import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, '..', '..', 'tools'))
import crack_measure as cm  # noqa: E402


def last_frames(dump):
    first = last = None
    for fr in cm.read_dump(dump):
        if first is None:
            first = fr
        last = fr
    return first, last


def panel(ax, prefix, title):
    f0, fl = last_frames(prefix + '.dump')
    X0 = np.stack([f0.col('x'), f0.col('y')], axis=1) * 1e3
    ids0 = f0.ids
    phicol = [c for c in f0.columns if c.startswith('c_') and c.endswith('[1]')][0]
    phi = np.zeros(len(ids0))
    pos = {int(i): k for k, i in enumerate(ids0)}
    for i, p in zip(fl.ids, fl.col(phicol)):
        k = pos.get(int(i))
        if k is not None:
            phi[k] = p
    ext = X0.max(axis=0) - X0.min(axis=0)
    dxe = math.sqrt(ext[0] * ext[1] / max(len(X0) - 1, 1))
    w_in = ax.get_position().width * ax.figure.get_figwidth()
    s = max(0.2, (dxe * w_in * 72.0 / (ext[0] * 1.06)) ** 2)
    from matplotlib.patches import Rectangle
    lo, hi = X0.min(axis=0) - dxe / 2, X0.max(axis=0) + dxe / 2
    ax.add_patch(Rectangle(lo, *(hi - lo), facecolor='0.9', edgecolor='0.5', lw=0.6))
    m = np.flatnonzero(phi > 0)
    m = m[np.argsort(phi[m])]
    sc = ax.scatter(X0[m, 0], X0[m, 1], c=phi[m], s=s, cmap='jet', vmin=0, vmax=1,
                    marker='s', linewidths=0)
    ax.set_aspect('equal')
    ax.set_xlabel('x [mm]')
    ax.set_ylabel('y [mm]')
    t = fl.time * 1e6 if fl.time is not None else float('nan')
    ax.set_title(f'{title}\n(damage at t = {t:.0f} us, reference positions)', fontsize=9)
    return sc


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('branching')
    ap.add_argument('kalthoff')
    ap.add_argument('-o', '--out', default='overview.png')
    a = ap.parse_args()
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(13.0, 4.4), gridspec_kw=dict(width_ratios=[2.5, 0.75]),
                                 constrained_layout=True)

    def crack(prefix):
        try:
            return json.load(open(prefix + '.crack.json'))
        except (OSError, ValueError):
            return {}
    cb = crack(a.branching).get('cracks', {}).get('crack', {})
    bt = cb.get('branching_time')
    t1 = 'Dynamic crack branching, glass plate, 1 MPa'
    if bt is not None:
        t1 += f': branches at {bt * 1e6:.1f} us'
    panel(a1, a.branching, t1)
    ck = crack(a.kalthoff).get('cracks', {})
    angs = [c.get('angle_deg') for c in ck.values() if c.get('angle_deg') is not None]
    t2 = 'Kalthoff-Winkler, 16.5 m/s impact'
    if angs:
        t2 += ': cracks at ' + ' / '.join(f'{abs(v):.1f}' for v in angs) + ' deg'
    sc = panel(a2, a.kalthoff, t2)
    fig.colorbar(sc, ax=[a1, a2], shrink=0.8, label='damage phi')
    fig.savefig(a.out, dpi=110)
    print('wrote', a.out)


if __name__ == '__main__':
    main()
