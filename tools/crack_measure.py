#!/usr/bin/env python3
"""crack_measure: crack geometry from LAMMPS dumps of pair_style tlsph/damage.

Measures, without looking at pictures, what a dynamic-fracture benchmark is
judged on: the crack tip(s), crack length and tip speed against time, the
initiation time, the propagation angle, branching (number of branches, branch
point, branching time) and whether the crack or its branches reach a boundary.
Needs numpy only (matplotlib for the plots).

Input
-----
``dump custom N file id x y [z] c_dmg[1] ...`` with ``dump_modify sort id``
(unsorted dumps are sorted here).  ``dump_modify time yes`` puts the simulated
time in the dump (needed with a variable time step, fix tlsph/dt); without it
pass ``--dt`` (time = step * dt) or times are given in steps.  Reference
positions: columns x0 y0 if present, else the positions of the first frame.
The damage column is chosen with ``--phi-col`` (default: the first column whose
name starts with ``c_`` and ends with ``[1]``, i.e. the damage phi of
compute tlsph/damage/atom).

Definitions (2D, x-y plane; all in the reference configuration; lengths and
times in dump units)
-----------------------------------------------------------------------------
* dx: particle spacing, the median nearest-neighbour distance (or ``--dx``).
* cracked particle: phi >= threshold (``--threshold``, 0.3), except the
  particles excluded by ``--exclude-initial``: *cracked* (default) those with
  phi >= threshold in the first frame (the flanks of a pre-crack, whose cut
  bonds count as broken), *damaged* those with phi > 0 there, *none*.
* frames after the first may hold only some particles (``dump_modify thresh``,
  e.g. only damaged ones): the missing ones have phi = 0.  The first frame
  must hold every particle.
* clusters: connected components of the cracked particles, two particles being
  linked when their reference distance is <= link * dx (``--link``, 1.5).
* crack of a seed: the union of the clusters with a particle within
  seed_radius * dx (``--seed-radius``, 2.5) of the seed point (a pre-crack or
  notch tip).  Cracked particles in no seed's crack are "other" damage.
* path distance: shortest path from the seed through the crack's links (the
  links weighted with their reference length; the particles near the seed
  start at their straight distance to it).  The tip is the crack's particle
  farthest along this path (``--tip projection``: farthest along the main
  direction); the crack length is the straight (chord) distance
  from the seed to the tip (``--length path`` uses the path distance, which
  over-counts lattice zig-zag by up to ~8 %).
* tip speed: least-squares slope of the running maximum of the crack length
  over a centred time window (``--window``, default 4 median frame spacings).
  The tip advances by whole particle spacings, so the window must span several
  spacings' worth of growth for a smooth curve.
* initiation: the first frame whose crack length is >= init_length * dx
  (``--init-length``, 3).
* angle: total-least-squares line through the crack's particles whose
  straight distance from the seed lies in [r1, r2] (``--angle-range``,
  default 5 dx .. 1e30), oriented away from the seed; its angle to the
  reference direction (``--ref-dir`` degrees, default 0 = +x), as a signed
  value in (-180, 180] and as the unsigned angle between the two directions.
* branching: the crack is cut into slices of width dx perpendicular to the
  seed's main direction (given, or 'auto' = the fitted direction of the whole
  crack); in each slice the particles' transverse coordinates are split into
  groups wherever the gap exceeds ``--gap`` dx (3).  n(s) is the number of
  groups at distance s along the main direction.  The crack has m branches if
  n(s) >= m over a run of slices at least ``--branch-min-length`` dx long
  (10); the branch point is where the first such run with m >= 2 starts.
  Shorter runs of n(s) >= 2, and runs above the persistent branch count, are
  counted as short side branches (runs that reach the crack's far end are not:
  they may still be growing).  The branches themselves are the connected
  components of the crack beyond the branch point; each has its own tip,
  angle and boundary contact.  Branching is *detected* in the first frame from
  which every later frame has >= 2 branches; the *branching time* is the first
  frame in which the crack had reached (along the main direction) the branch
  point found in that detection frame.  The largest transverse extent of the
  crack within one slice (``width_max``) shows a widening band or branching
  attempts that did not separate.
* boundaries: xmin, xmax, ymin, ymax of the reference bounding box; a crack
  or branch reaches one when one of its particles is within ``--edge-tol`` dx
  (1.0) of it (edges the crack touched in the first frame are not reported).
* regions (``--region NAME xlo xhi ylo yhi``): maximum phi, maximum rise of
  phi since the first frame, number of cracked particles and of newly damaged
  particles (phi > 0, undamaged in the first frame) inside, per frame (e.g.
  under an impactor).

Command line
------------
::

  crack_measure.py DUMP --seed tip 0.05 0.02 0 --rayleigh 2125 \\
      --target-edge xmax --out out/crack  [--plot out/speed.png] \\
      [--montage out/montage.png --montage-times 10e-6,20e-6,30e-6]
  crack_measure.py --selftest

``--seed NAME X Y DIR`` may be repeated (DIR in degrees, or 'auto').  Writes
OUT.json (everything), OUT.csv (time series, one row per frame and seed) and
OUT.txt (summary, also printed).

Module use
----------
::

  import crack_measure as cm
  res = cm.analyse(cm.read_dump('dump.crack'), seeds=[cm.Seed('tip', 0.05, 0.02, 0.0)])
  print(cm.summary_text(res))
"""

import argparse
import csv
import heapq
import json
import math
import os
import sys
import tempfile

import numpy as np

__all__ = ['Frame', 'Seed', 'read_dump', 'analyse', 'summary_text', 'write_outputs',
           'plot_speed', 'montage', 'symmetry', 'selftest']


# --------------------------------------------------------------------------- input

class Frame:
    """One dump frame: step, time (None if the dump has none), column names, data
    (rows sorted by id), box bounds."""
    __slots__ = ('step', 'time', 'columns', 'data', 'box')

    def __init__(self, step, time, columns, data, box):
        self.step, self.time, self.columns, self.data, self.box = step, time, columns, data, box

    def col(self, name):
        return self.data[:, self.columns.index(name)]

    @property
    def ids(self):
        return self.data[:, self.columns.index('id')].astype(np.int64)


def read_dump(path, every=1, tmin=None, tmax=None, columns=None):
    """Yield the Frames of a LAMMPS text dump (dump custom / atom style).

    every: keep every n-th frame; tmin/tmax: keep frames with time (or step if the
    dump has no time) in the range (the first frame is always kept: it holds the
    reference configuration); columns: keep only these columns (plus id)."""
    with open(path) as f:
        k = -1
        while True:
            line = f.readline()
            if not line:
                return
            time = None
            if line.strip() == 'ITEM: TIME':
                time = float(f.readline())
                line = f.readline()
            if not line.startswith('ITEM: TIMESTEP'):
                raise ValueError(f'{path}: expected ITEM: TIMESTEP, got {line!r}')
            step = int(f.readline())
            if not f.readline().startswith('ITEM: NUMBER OF ATOMS'):
                raise ValueError(f'{path}: expected ITEM: NUMBER OF ATOMS')
            n = int(f.readline())
            bline = f.readline()
            ndim_box = 3
            box = np.array([[float(v) for v in f.readline().split()[:2]] for _ in range(ndim_box)])
            if 'xy' in bline:   # triclinic: keep the bounds, ignore the tilt
                pass
            head = f.readline().split()
            if head[:2] != ['ITEM:', 'ATOMS']:
                raise ValueError(f'{path}: expected ITEM: ATOMS')
            names = head[2:]
            k += 1
            tval = time if time is not None else step
            keep = k == 0 or ((k % every == 0) and (tmin is None or tval >= tmin)
                              and (tmax is None or tval <= tmax))
            if not keep:
                for _ in range(n):
                    f.readline()
                continue
            block = ''.join(f.readline() for _ in range(n))
            data = np.array(block.split(), dtype=float).reshape(n, len(names))
            if columns is not None:
                sel = [names.index('id')] + [names.index(c) for c in columns if c != 'id']
                data = data[:, sel]
                names = ['id'] + [c for c in columns if c != 'id']
            ids = data[:, names.index('id')]
            if np.any(np.diff(ids) < 0):
                data = data[np.argsort(ids, kind='stable')]
            yield Frame(step, time, names, data, box)


# --------------------------------------------------------------------------- geometry helpers

def _full_column(fr, name, ids0):
    """Column of a frame on the particles of the first frame (ids0, sorted); a frame
    may hold a subset of them (dump_modify thresh): the others get 0."""
    v = fr.col(name)
    ids = fr.ids
    if len(ids) == len(ids0) and np.array_equal(ids, ids0):
        return v
    pos = np.searchsorted(ids0, ids)
    pos = np.clip(pos, 0, len(ids0) - 1)
    if np.any(ids0[pos] != ids):
        raise ValueError(f'step {fr.step}: particle ids not in the first frame '
                         '(the first frame must hold every particle)')
    full = np.zeros(len(ids0))
    full[pos] = v
    return full


def _pairs_within(P, r):
    """All pairs (i<j) of rows of P (n x d) closer than r, by cell hashing."""
    n, d = P.shape
    if n < 2:
        return np.zeros((0, 2), dtype=np.int64), np.zeros(0)
    c = np.floor((P - P.min(axis=0)) / r).astype(np.int64)
    dims = c.max(axis=0) + 3
    c += 1
    mult = np.cumprod(np.concatenate([[1], dims[:-1]]))
    key = c @ mult
    order = np.argsort(key, kind='stable')
    skey = key[order]
    offsets = np.array(np.meshgrid(*[[-1, 0, 1]] * d, indexing='ij')).reshape(d, -1).T
    I, J = [], []
    for off in offsets:
        nk = key + off @ mult
        lo = np.searchsorted(skey, nk, 'left')
        hi = np.searchsorted(skey, nk, 'right')
        cnt = hi - lo
        if cnt.sum() == 0:
            continue
        ii = np.repeat(np.arange(n), cnt)
        start = np.repeat(lo, cnt)
        within = np.arange(cnt.sum()) - np.repeat(np.cumsum(cnt) - cnt, cnt)
        jj = order[start + within]
        m = ii < jj
        I.append(ii[m]); J.append(jj[m])
    I = np.concatenate(I); J = np.concatenate(J)
    dist = np.linalg.norm(P[I] - P[J], axis=1)
    m = dist <= r
    return np.stack([I[m], J[m]], axis=1), dist[m]


def _components(n, pairs):
    """Connected-component labels 0..k-1 of n nodes with edges pairs (union-find)."""
    parent = list(range(n))

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for a, b in pairs:
        ra, rb = find(int(a)), find(int(b))
        if ra != rb:
            parent[max(ra, rb)] = min(ra, rb)
    roots = np.array([find(a) for a in range(n)], dtype=np.int64)
    _, lab = np.unique(roots, return_inverse=True)
    return lab


def _dijkstra(n, pairs, w, src, src_d):
    """Shortest path distances from several sources with initial distances."""
    adj = [[] for _ in range(n)]
    for (a, b), ww in zip(pairs, w):
        adj[a].append((b, ww)); adj[b].append((a, ww))
    dist = np.full(n, np.inf)
    h = []
    for s, d0 in zip(src, src_d):
        if d0 < dist[s]:
            dist[s] = d0
            heapq.heappush(h, (d0, s))
    while h:
        d, a = heapq.heappop(h)
        if d > dist[a]:
            continue
        for b, ww in adj[a]:
            nd = d + ww
            if nd < dist[b]:
                dist[b] = nd
                heapq.heappush(h, (nd, b))
    return dist


def fit_direction(P, origin):
    """Unit direction of the total-least-squares line through points P (k x d),
    oriented away from origin; None if fewer than 2 distinct points."""
    if len(P) < 2:
        return None
    c = P.mean(axis=0)
    _, s, vt = np.linalg.svd(P - c, full_matrices=False)
    if s[0] <= 0:
        return None
    u = vt[0]
    if np.dot(c - origin, u) < 0:
        u = -u
    return u


def angle_deg(u, ref):
    """Signed angle from ref to u in the x-y plane (deg, (-180,180]) and the
    unsigned angle between them (deg, [0,180])."""
    a = math.degrees(math.atan2(ref[0] * u[1] - ref[1] * u[0], ref[0] * u[0] + ref[1] * u[1]))
    return a, abs(a)


def _unit(deg):
    return np.array([math.cos(math.radians(deg)), math.sin(math.radians(deg))])


def _runs(mask):
    """(start, end) index pairs (end exclusive) of the True runs of a bool array."""
    m = np.concatenate([[False], np.asarray(mask, bool), [False]])
    d = np.diff(m.astype(int))
    return list(zip(np.flatnonzero(d == 1), np.flatnonzero(d == -1)))


def smoothed_rate(t, y, window):
    """Least-squares slope of y(t) over the frames with |t - t_k| <= window/2."""
    t = np.asarray(t, float); y = np.asarray(y, float)
    r = np.full(len(t), np.nan)
    for k in range(len(t)):
        m = np.abs(t - t[k]) <= 0.5 * window * (1 + 1e-9)
        if m.sum() >= 2:
            tt = t[m] - t[m].mean()
            den = np.dot(tt, tt)
            if den > 0:
                r[k] = np.dot(tt, y[m] - y[m].mean()) / den
    return r


# --------------------------------------------------------------------------- analysis

class Seed:
    """A crack's starting point (x, y) and main growth direction (degrees from +x,
    or None = 'auto': the direction fitted to the whole crack)."""

    def __init__(self, name, x, y, direction=None):
        self.name, self.x, self.y = name, float(x), float(y)
        self.direction = None if direction in (None, 'auto') else float(direction)

    def as_dict(self):
        return {'name': self.name, 'x': self.x, 'y': self.y,
                'direction_deg': self.direction if self.direction is not None else 'auto'}


DEFAULTS = dict(threshold=0.3, link=1.5, seed_radius=2.5, init_length=3.0, gap=3.0,
                branch_min_length=10.0, edge_tol=1.0, ref_dir=0.0, angle_range=(5.0, 1e30),
                length='chord', window=None, min_branch_particles=5,
                exclude_initial='cracked', tip='path')


def _frame_crack(X, idx, seed, o, dx, edges):
    """Geometry of one seed's crack in one frame.  X: reference positions (2D) of the
    cracked particles idx; returns a dict."""
    sp = np.array([seed.x, seed.y])
    out = dict(n=int(len(idx)), tip=None, length_chord=0.0, length_path=0.0,
               branches=1, branch_s=None, side_branches=0, n_profile=None,
               branch_list=[], edges=[], dir_fit=None)
    if len(idx) == 0:
        return out
    P = X[idx]
    pairs, w = _pairs_within(P, o['link'] * dx * (1 + 1e-9))
    r0 = np.linalg.norm(P - sp, axis=1)
    near = np.flatnonzero(r0 <= o['seed_radius'] * dx)
    dpath = _dijkstra(len(P), pairs, w, near, r0[near])
    ok = np.isfinite(dpath)
    P, idx, r0, dpath = P[ok], idx[ok], r0[ok], dpath[ok]
    # reindex the pairs to the kept particles
    newi = np.cumsum(ok) - 1
    pm = ok[pairs[:, 0]] & ok[pairs[:, 1]] if len(pairs) else np.zeros(0, bool)
    pairs = newi[pairs[pm]] if len(pairs) else pairs
    out['n'] = int(len(idx))
    if len(idx) == 0:
        return out
    # main direction
    if seed.direction is not None:
        d = _unit(seed.direction)
    else:
        d = fit_direction(P, sp)
        if d is None:
            d = _unit(o['ref_dir'])
    out['dir_main'] = [float(d[0]), float(d[1])]
    # tip: farthest along the path (or along the main direction)
    kt = int(np.argmax(dpath if o['tip'] == 'path' else (P - sp) @ d))
    out['tip'] = [float(P[kt, 0]), float(P[kt, 1])]
    out['tip_id_index'] = int(idx[kt])
    out['length_chord'] = float(r0[kt])
    out['length_path'] = float(dpath[kt])
    out['edges'] = [e for e, (ax, val) in edges.items()
                    if np.any(np.abs(P[:, ax] - val) <= o['edge_tol'] * dx)]
    uf = fit_direction(P[(r0 >= o['angle_range'][0] * dx) & (r0 <= o['angle_range'][1])], sp)
    if uf is not None:
        out['dir_fit'] = [float(uf[0]), float(uf[1])]
    # branching profile
    nrm = np.array([-d[1], d[0]])
    s = (P - sp) @ d
    p = (P - sp) @ nrm
    k = np.floor(s / dx).astype(int)
    kmin = min(k.min(), 0)
    nb = k.max() - kmin + 1
    prof = np.zeros(nb, dtype=int)
    wmax, wpos = 0.0, None
    for kk in np.unique(k):
        pp = np.sort(p[k == kk])
        prof[kk - kmin] = 1 + int(np.sum(np.diff(pp) > o['gap'] * dx))
        if pp[-1] - pp[0] > wmax:
            wmax, wpos = float(pp[-1] - pp[0]), float((kk + 0.5) * dx)
    # largest transverse extent of the crack in one slice (a widening crack band,
    # micro-branching, or the spread of separated branches) and where it is
    out['width_max'] = wmax
    out['width_max_s'] = wpos
    out['s_max'] = float(s.max())
    out['n_profile'] = {'s0': float(kmin * dx), 'ds': float(dx), 'n': prof.tolist()}
    minrun = max(1, int(round(o['branch_min_length'])))
    branches, s_b = 1, None
    for m in range(2, prof.max() + 1 if len(prof) else 2):
        runs = [r for r in _runs(prof >= m) if r[1] - r[0] >= minrun]
        if not runs:
            break
        branches = m
        if m == 2:
            s_b = (runs[0][0] + kmin) * dx
    out['branches'] = branches
    out['branch_s'] = s_b
    # short runs that do not reach the crack's far end (those may still be growing)
    side = [r for r in _runs(prof >= 2) if r[1] - r[0] < minrun and r[1] < nb]
    side += [r for r in _runs(prof >= branches + 1) if r[1] < nb] if branches >= 2 else []
    out['side_branches'] = len(side)
    # the branches: components of the crack beyond the branch point
    if s_b is not None:
        beyond = np.flatnonzero(s >= s_b + dx)
        if len(beyond):
            mp = np.zeros(len(P), bool); mp[beyond] = True
            sub = np.full(len(P), -1); sub[beyond] = np.arange(len(beyond))
            bp = pairs[mp[pairs[:, 0]] & mp[pairs[:, 1]]] if len(pairs) else pairs
            lab = _components(len(beyond), sub[bp] if len(bp) else [])
            blist = []
            for c in range(lab.max() + 1):
                memb = beyond[lab == c]
                ext = s[memb].max() - s[memb].min()
                if len(memb) < o['min_branch_particles'] or ext < o['branch_min_length'] * dx * 0.999:
                    continue
                kb = memb[np.argmax(dpath[memb])]
                ub = fit_direction(P[memb], sp)
                blist.append(dict(
                    n=int(len(memb)), tip=[float(P[kb, 0]), float(P[kb, 1])],
                    length_chord=float(r0[kb]), side=float(np.mean(p[memb])),
                    dir_fit=None if ub is None else [float(ub[0]), float(ub[1])],
                    edges=[e for e, (ax, val) in edges.items()
                           if np.any(np.abs(P[memb, ax] - val) <= o['edge_tol'] * dx)]))
            blist.sort(key=lambda b: b['side'])
            out['branch_list'] = blist
    return out


def analyse(frames, seeds, dx=None, dt=None, phi_col=None, regions=None, target_edges=None,
            **opts):
    """Measure the cracks.  frames: iterable of Frame (e.g. read_dump(path)); seeds: list
    of Seed; regions: {name: (xlo, xhi, ylo, yhi)}; target_edges: {seed name: edge name
    or 'any'}; opts: see DEFAULTS.  Returns a result dict (JSON-serialisable)."""
    o = dict(DEFAULTS)
    o.update({k: v for k, v in opts.items() if v is not None})
    regions = regions or {}
    target_edges = target_edges or {}
    X = phi_first = None
    rows = {s.name: [] for s in seeds}
    reg_rows = {r: [] for r in regions}
    other = []
    times, steps = [], []
    nframe = 0
    for fr in frames:
        if X is None:
            cols = fr.columns
            if phi_col is None:
                cand = [c for c in cols if c.startswith('c_') and c.endswith('[1]')]
                if not cand:
                    raise ValueError('no damage column (c_*[1]) in the dump: pass phi_col')
                phi_col = cand[0]
            if 'x0' in cols and 'y0' in cols:
                X = np.stack([fr.col('x0'), fr.col('y0')], axis=1)
            else:
                X = np.stack([fr.col('x'), fr.col('y')], axis=1)
            ids0 = fr.ids.copy()
            if dx is None:
                # nearest-neighbour distance: estimate a radius from the box first
                area = np.prod(X.max(axis=0) - X.min(axis=0))
                r = 2.0 * math.sqrt(area / max(len(X), 1))
                pr, dd = _pairs_within(X, r)
                nn = np.full(len(X), np.inf)
                np.minimum.at(nn, pr[:, 0], dd); np.minimum.at(nn, pr[:, 1], dd)
                dx = float(np.median(nn[np.isfinite(nn)]))
            lo, hi = X.min(axis=0), X.max(axis=0)
            edges = {'xmin': (0, lo[0]), 'xmax': (0, hi[0]), 'ymin': (1, lo[1]), 'ymax': (1, hi[1])}
            phi_first = fr.col(phi_col).copy()
            if o['exclude_initial'] == 'damaged':
                excluded = phi_first > 0
            elif o['exclude_initial'] == 'cracked':
                excluded = phi_first >= o['threshold']
            else:
                excluded = np.zeros(len(X), bool)
        phi = _full_column(fr, phi_col, ids0)
        t = fr.time if fr.time is not None else (fr.step * dt if dt is not None else float(fr.step))
        times.append(t); steps.append(fr.step)
        cracked = (phi >= o['threshold']) & ~excluded
        cidx = np.flatnonzero(cracked)
        # seed cracks: components of the cracked set touching each seed
        assigned = np.zeros(len(cidx), bool)
        if len(cidx):
            pairs, _ = _pairs_within(X[cidx], o['link'] * dx * (1 + 1e-9))
            lab = _components(len(cidx), pairs)
        for sd in seeds:
            if len(cidx):
                sp = np.array([sd.x, sd.y])
                near = np.linalg.norm(X[cidx] - sp, axis=1) <= o['seed_radius'] * dx
                labs = np.unique(lab[near])
                memb = np.isin(lab, labs) if len(labs) else np.zeros(len(cidx), bool)
                assigned |= memb
                sel = cidx[memb]
            else:
                sel = cidx
            g = _frame_crack(X, sel, sd, o, dx, edges)
            g.pop('tip_id_index', None)
            rows[sd.name].append(g)
        other.append(int(len(cidx) - assigned.sum()))
        for rn, (x0, x1, y0, y1) in regions.items():
            m = (X[:, 0] >= x0) & (X[:, 0] <= x1) & (X[:, 1] >= y0) & (X[:, 1] <= y1)
            reg_rows[rn].append(dict(phi_max=float(phi[m].max()) if m.any() else 0.0,
                                     dphi_max=float((phi[m] - phi_first[m]).max()) if m.any() else 0.0,
                                     n_cracked=int(np.sum(cracked & m)),
                                     n_damaged=int(np.sum((phi > 0) & m & ~(phi_first > 0)))))
        nframe += 1
    if nframe == 0:
        raise ValueError('no frames')
    times = np.array(times)
    res = dict(options={k: (list(v) if isinstance(v, tuple) else v) for k, v in o.items()},
               dx=dx, phi_col=phi_col, n_particles=int(len(X)), n_frames=nframe,
               time=times.tolist(), step=steps, other_cracked=other,
               box=dict(xmin=float(lo[0]), xmax=float(hi[0]), ymin=float(lo[1]), ymax=float(hi[1])),
               seeds=[s.as_dict() for s in seeds], cracks={}, regions={})
    window = o['window']
    if window is None:
        window = 4.0 * float(np.median(np.diff(times))) if nframe > 1 else 1.0
    res['options']['window'] = window
    ref = _unit(o['ref_dir'])
    for sd in seeds:
        R = rows[sd.name]
        lkey = 'length_path' if o['length'] == 'path' else 'length_chord'
        L = np.array([r[lkey] for r in R])
        Lmono = np.maximum.accumulate(L)
        speed = smoothed_rate(times, Lmono, window) if nframe > 1 else np.zeros(1)
        ini = np.flatnonzero(Lmono >= o['init_length'] * dx)
        nbr = np.array([r['branches'] for r in R])
        bt = None
        for k in range(nframe):
            if np.all(nbr[k:] >= 2):
                bt = k
                break
        cr = dict(seed=sd.as_dict(), length=Lmono.tolist(), length_raw=L.tolist(),
                  length_path=[r['length_path'] for r in R],
                  tip=[r['tip'] for r in R], speed=[None if not np.isfinite(v) else float(v)
                                                    for v in speed],
                  n_cracked=[r['n'] for r in R], branches=nbr.tolist(),
                  side_branches=[r['side_branches'] for r in R],
                  width_max=[r.get('width_max', 0.0) for r in R],
                  branch_s=[r['branch_s'] for r in R],
                  edges=[r['edges'] for r in R],
                  branch_list=[r['branch_list'] for r in R])
        cr['initiation_time'] = float(times[ini[0]]) if len(ini) else None
        fin = np.isfinite(speed)
        cr['speed_max'] = float(speed[fin].max()) if fin.any() else None
        cr['speed_max_time'] = float(times[fin][np.argmax(speed[fin])]) if fin.any() else None
        cr['length_final'] = float(Lmono[-1])
        cr['tip_final'] = R[-1]['tip']
        # angle (final frame)
        last = R[-1]
        if last['dir_fit'] is not None:
            a_s, a_u = angle_deg(last['dir_fit'], ref)
            cr['angle_signed_deg'], cr['angle_deg'] = a_s, a_u
            cr['direction_fit'] = last['dir_fit']
        else:
            cr['angle_signed_deg'] = cr['angle_deg'] = None
        cr['angle_vs_time'] = [None if r['dir_fit'] is None else angle_deg(r['dir_fit'], ref)[1]
                               for r in R]
        cr['n_profile_final'] = last['n_profile']
        # branching
        # detected: the first frame from which every frame has >= 2 persistent branches;
        # branching time: the first frame whose crack reached (along the main direction)
        # the branch point found in that detection frame
        cr['branching_detected_time'] = float(times[bt]) if bt is not None else None
        cr['branching_time'] = None
        if bt is not None:
            sb = R[bt]['branch_s']
            smax = np.array([r.get('s_max', -np.inf) for r in R])
            kb = np.flatnonzero(smax >= sb)
            cr['branching_time'] = float(times[kb[0]]) if len(kb) else float(times[bt])
            cr['branch_point_s_detected'] = sb
        first2 = np.flatnonzero(nbr >= 2)
        cr['first_two_branch_time'] = float(times[first2[0]]) if len(first2) else None
        cr['branches_final'] = int(nbr[-1])
        cr['branches_max_persistent'] = int(nbr.max())
        cr['branch_point_s'] = last['branch_s']
        cr['side_branches_max'] = int(max(r['side_branches'] for r in R))
        cr['width_max_final'] = last.get('width_max', 0.0)
        cr['width_max_final_s'] = last.get('width_max_s')
        cr['branches_at_end'] = [dict(tip=b['tip'], n=b['n'], edges=b['edges'],
                                      angle_deg=None if b['dir_fit'] is None
                                      else angle_deg(b['dir_fit'], ref)[0])
                                 for b in last['branch_list']]
        # boundaries
        tgt = target_edges.get(sd.name)
        first_edges = set(R[0]['edges'])
        reach = {}
        for k, r in enumerate(R):
            for e in r['edges']:
                if e not in first_edges and e not in reach:
                    reach[e] = float(times[k])
        cr['edge_reached_time'] = reach
        if tgt is not None:
            cr['target_edge'] = tgt
            if tgt == 'any':
                cr['target_reached_time'] = min(reach.values()) if reach else None
            else:
                cr['target_reached_time'] = reach.get(tgt)
                # branches touching the target edge
                nb_edge = [sum(tgt in b['edges'] for b in r['branch_list']) for r in R]
                cr['branches_at_target'] = nb_edge
                cr['branches_at_target_final'] = nb_edge[-1]
                t2 = [k for k, v in enumerate(nb_edge) if v >= 2]
                cr['two_branches_at_target_time'] = float(times[t2[0]]) if t2 else None
        res['cracks'][sd.name] = cr
    for rn, rr in reg_rows.items():
        res['regions'][rn] = dict(bounds=list(regions[rn]),
                                  phi_max=[r['phi_max'] for r in rr],
                                  dphi_max=[r['dphi_max'] for r in rr],
                                  dphi_max_all=max(r['dphi_max'] for r in rr),
                                  n_cracked=[r['n_cracked'] for r in rr],
                                  n_damaged=[r['n_damaged'] for r in rr],
                                  phi_max_final=rr[-1]['phi_max'],
                                  n_cracked_max=max(r['n_cracked'] for r in rr))
    return res


def symmetry(res, name_a, name_b, axis='y', about=0.0):
    """Compare two cracks that should be mirror images (mirror plane axis=about):
    differences of initiation time, angle, final length and the largest distance
    between tip a and the mirrored tip b over the frames."""
    a, b = res['cracks'][name_a], res['cracks'][name_b]
    ax = 1 if axis == 'y' else 0
    dmax = 0.0
    for ta, tb in zip(a['tip'], b['tip']):
        if ta is None or tb is None:
            if (ta is None) != (tb is None):
                dmax = max(dmax, float('nan'))
            continue
        m = list(tb); m[ax] = 2 * about - m[ax]
        dmax = max(dmax, math.hypot(ta[0] - m[0], ta[1] - m[1]))

    def diff(k):
        return None if a.get(k) is None or b.get(k) is None else a[k] - b[k]
    return dict(initiation_time_diff=diff('initiation_time'), angle_diff_deg=diff('angle_deg'),
                length_final_diff=diff('length_final'), speed_max_diff=diff('speed_max'),
                tip_mirror_distance_max=dmax)


# --------------------------------------------------------------------------- output

def _fmt(v, scale=1.0, unit='', nd=3):
    if v is None:
        return 'n/a'
    return f'{v * scale:.{nd}g}{unit}'


def summary_text(res, time_unit=1e-6, time_name='us'):
    L = []
    L.append(f"particles {res['n_particles']}, frames {res['n_frames']}, dx {res['dx']:.4g}, "
             f"t = {res['time'][0] / time_unit:.3g} .. {res['time'][-1] / time_unit:.3g} {time_name}, "
             f"threshold phi >= {res['options']['threshold']}")
    for name, c in res['cracks'].items():
        sd = c['seed']
        L.append(f"crack '{name}' (seed {sd['x']:.4g} {sd['y']:.4g}, direction {sd['direction_deg']}):")
        L.append(f"  initiation time       {_fmt(c['initiation_time'], 1 / time_unit, ' ' + time_name)}")
        L.append(f"  final length          {_fmt(c['length_final'], 1, '', 4)}  tip {c['tip_final']}")
        L.append(f"  max tip speed         {_fmt(c['speed_max'], 1, '', 4)} at "
                 f"{_fmt(c['speed_max_time'], 1 / time_unit, ' ' + time_name)}")
        L.append(f"  angle to ref. dir.    {_fmt(c['angle_deg'], 1, ' deg', 4)} "
                 f"(signed {_fmt(c['angle_signed_deg'], 1, ' deg', 4)})")
        L.append(f"  branches (final/max)  {c['branches_final']}/{c['branches_max_persistent']}, "
                 f"branching time {_fmt(c['branching_time'], 1 / time_unit, ' ' + time_name)} "
                 f"(persistent from {_fmt(c['branching_detected_time'], 1 / time_unit, ' ' + time_name)}), "
                 f"branch point s = {_fmt(c['branch_point_s'], 1, '', 4)}, "
                 f"short side branches (max per frame) {c['side_branches_max']}")
        if c.get('width_max_final_s') is not None:
            L.append(f"  widest crack band     {c['width_max_final'] / res['dx']:.1f} dx across, at "
                     f"s = {c['width_max_final_s']:.4g} from the seed (final frame)")
        for b in c['branches_at_end']:
            L.append(f"    branch: tip {b['tip']}, angle {_fmt(b['angle_deg'], 1, ' deg', 3)}, "
                     f"edges {b['edges']}")
        L.append("  edges reached         " + (', '.join(
            f"{e} at {_fmt(t, 1 / time_unit, ' ' + time_name)}" for e, t in c['edge_reached_time'].items())
            or 'none'))
        if 'target_edge' in c:
            L.append(f"  target edge {c['target_edge']}: reached at "
                     f"{_fmt(c['target_reached_time'], 1 / time_unit, ' ' + time_name)}"
                     + (f", branches touching it at the end: {c['branches_at_target_final']}, "
                        f"two branches there at {_fmt(c['two_branches_at_target_time'], 1 / time_unit, ' ' + time_name)}"
                        if 'branches_at_target' in c else ''))
    L.append(f"cracked particles in no seed's crack (final/max): {res['other_cracked'][-1]}/"
             f"{max(res['other_cracked'])}")
    for rn, r in res['regions'].items():
        L.append(f"region '{rn}' {r['bounds']}: max phi at the end {r['phi_max_final']:.3g}, "
                 f"largest phi rise since the first frame {r['dphi_max_all']:.3g}, "
                 f"cracked particles max {r['n_cracked_max']}")
    return '\n'.join(L)


def write_outputs(res, prefix):
    d = os.path.dirname(prefix)
    if d:
        os.makedirs(d, exist_ok=True)
    with open(prefix + '.json', 'w') as f:
        json.dump(res, f, indent=1, default=float)
    with open(prefix + '.csv', 'w', newline='') as f:
        w = csv.writer(f)
        w.writerow(['crack', 'step', 'time', 'length', 'length_raw', 'length_path', 'speed',
                    'tip_x', 'tip_y', 'n_cracked', 'branches', 'side_branches', 'width_max', 'angle_deg',
                    'edges', 'other_cracked'])
        for name, c in res['cracks'].items():
            for k, t in enumerate(res['time']):
                tip = c['tip'][k] or [None, None]
                w.writerow([name, res['step'][k], t, c['length'][k], c['length_raw'][k],
                            c['length_path'][k], c['speed'][k], tip[0], tip[1], c['n_cracked'][k],
                            c['branches'][k], c['side_branches'][k], c['width_max'][k],
                            c['angle_vs_time'][k],
                            ' '.join(c['edges'][k]), res['other_cracked'][k]])
    txt = summary_text(res)
    with open(prefix + '.txt', 'w') as f:
        f.write(txt + '\n')
    return txt


def plot_speed(res, png, rayleigh=None, title=None, time_unit=1e-6, extra=None):
    """Tip speed (and crack length) against time; a horizontal line at rayleigh.
    extra: optional list of (label, t_array_s, v_array) curves to overlay."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    t = np.array(res['time']) / time_unit
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(7, 6.5), sharex=True)
    for name, c in res['cracks'].items():
        v = np.array([np.nan if s is None else s for s in c['speed']])
        a1.plot(t, v, '-o', ms=2.5, label=f'{name}')
        a2.plot(t, np.array(c['length']) * 1e3, '-', label=name)
        if c['initiation_time'] is not None:
            a2.axvline(c['initiation_time'] / time_unit, color='0.6', ls=':', lw=0.8)
        if c.get('branching_time') is not None:
            a2.axvline(c['branching_time'] / time_unit, color='g', ls='--', lw=0.8)
    for lab, te, ve in (extra or []):
        a1.plot(np.asarray(te) / time_unit, ve, '--', label=lab)
    if rayleigh:
        a1.axhline(rayleigh, color='r', ls='--', label=f'Rayleigh speed {rayleigh:g} m/s')
    a1.set_ylabel('tip speed [m/s]')
    a1.set_ylim(bottom=0)
    a1.legend(fontsize=8)
    a1.grid(alpha=0.3)
    a2.set_ylabel('crack length from seed [mm]')
    a2.set_xlabel('time [us]')
    a2.grid(alpha=0.3)
    if title:
        a1.set_title(title)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)


def montage(dump, png, times=None, npanel=6, phi_col=None, vmax=1.0, deformed=False,
            ncols=2, time_unit=1e-6, dt=None, title=None, panel_width=5.0, dpi=110):
    """Damage field at several times (the nearest frames) in one PNG: the plate outline
    (bounding box of the first frame) and every particle with phi > 0, coloured by phi.
    times: list of times (dump time units) or None = npanel frames evenly spread."""
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    from matplotlib.patches import Rectangle
    frames = list(read_dump(dump))
    tt = np.array([f.time if f.time is not None else (f.step * dt if dt else f.step) for f in frames])
    if times is None:
        sel = np.unique(np.linspace(0, len(frames) - 1, npanel).round().astype(int))
    else:
        sel = [int(np.argmin(np.abs(tt - t))) for t in times]
    f0 = frames[0]
    ids0 = f0.ids
    if phi_col is None:
        phi_col = [c for c in f0.columns if c.startswith('c_') and c.endswith('[1]')][0]
    X0 = np.stack([f0.col('x'), f0.col('y')], axis=1)
    lo, hi = X0.min(axis=0), X0.max(axis=0)
    ext = hi - lo
    area = ext[0] * ext[1]
    dxe = math.sqrt(area / max(len(X0) - 1, 1)) if area > 0 else 1.0
    pad = 0.03 * ext.max()
    nrows = int(math.ceil(len(sel) / ncols))
    ph = panel_width * (ext[1] + 2 * pad) / (ext[0] + 2 * pad)
    fig, axs = plt.subplots(nrows, ncols, figsize=(panel_width * ncols + 1.2, (ph + 0.45) * nrows + 0.5),
                            squeeze=False, constrained_layout=True)
    # marker: one particle spacing wide (points^2)
    pts_per_len = panel_width * 72.0 / (ext[0] + 2 * pad) * 0.85
    ms = max(0.3, (dxe * pts_per_len) ** 2)
    sc = None
    for ax, k in zip(axs.flat, sel):
        fr = frames[k]
        phi = _full_column(fr, phi_col, ids0)
        if deformed and len(fr.data) == len(X0):
            P = np.stack([fr.col('x'), fr.col('y')], axis=1)
        else:
            P = X0
        ax.add_patch(Rectangle(lo * 1e3, *(ext * 1e3), facecolor='0.92', edgecolor='0.5', lw=0.6))
        m = np.flatnonzero(phi > 0)
        m = m[np.argsort(phi[m])]
        sc = ax.scatter(P[m, 0] * 1e3, P[m, 1] * 1e3, c=phi[m], s=ms, cmap='jet', vmin=0, vmax=vmax,
                        linewidths=0, marker='s')
        ax.set_xlim((lo[0] - pad) * 1e3, (hi[0] + pad) * 1e3)
        ax.set_ylim((lo[1] - pad) * 1e3, (hi[1] + pad) * 1e3)
        ax.set_aspect('equal')
        ax.set_title(f't = {tt[k] / time_unit:.1f} us (step {fr.step})', fontsize=9)
        ax.tick_params(labelsize=7)
    for ax in list(axs.flat)[len(sel):]:
        ax.axis('off')
    if sc is not None:
        fig.colorbar(sc, ax=axs, shrink=0.7, label='damage phi (positions in mm, reference)')
    if title:
        fig.suptitle(title)
    fig.savefig(png, dpi=dpi)
    plt.close(fig)


# --------------------------------------------------------------------------- self-test

def _write_dump(path, X, phis, times):
    with open(path, 'w') as f:
        for k, (phi, t) in enumerate(zip(phis, times)):
            f.write(f'ITEM: TIME\n{t:.10g}\nITEM: TIMESTEP\n{k * 100}\nITEM: NUMBER OF ATOMS\n{len(X)}\n')
            f.write('ITEM: BOX BOUNDS ss ss pp\n0 1\n0 1\n-0.5 0.5\n')
            f.write('ITEM: ATOMS id x y c_dmg[1] c_dmg[2]\n')
            for i in range(len(X)):
                f.write(f'{i + 1} {X[i, 0]:.8g} {X[i, 1]:.8g} {phi[i]:.4g} {phi[i]:.4g}\n')


def _synthetic(segments, X, dx, v, t0, times, width=1.0):
    """phi(t) for a crack made of segments [(start, end, t_start)], each growing from its
    start at speed v from its t_start; particles within width*dx of the grown part get
    phi 0.5 (closest) / 0.35 (next row)."""
    phis = []
    for t in times:
        phi = np.zeros(len(X))
        for a, b, ts in segments:
            a, b = np.asarray(a, float), np.asarray(b, float)
            Lseg = np.linalg.norm(b - a)
            grown = min(Lseg, max(0.0, v * (t - ts)))
            if grown <= 0:
                continue
            u = (b - a) / Lseg
            r = X - a
            s = r @ u
            d = np.abs(r @ np.array([-u[1], u[0]]))
            m = (s >= 0) & (s <= grown)
            phi = np.maximum(phi, np.where(m & (d <= 0.5 * dx * width + 1e-12), 0.5, 0.0))
            phi = np.maximum(phi, np.where(m & (d > 0.5 * dx * width + 1e-12) & (d <= 1.2 * dx), 0.35, 0.0))
        phis.append(phi)
    return phis


def selftest(verbose=True):
    """Synthetic straight, 60-degree and Y-shaped cracks through the file reader and the
    analysis; raises AssertionError on failure."""
    dx = 1e-3
    nx, ny = 100, 60
    gx, gy = np.meshgrid((np.arange(nx) + 0.5) * dx, (np.arange(ny) + 0.5) * dx, indexing='ij')
    X = np.stack([gx.ravel(), gy.ravel()], axis=1)
    v, t0 = 1000.0, 5e-6
    times = np.arange(0, 101) * 1e-6
    seed = np.array([0.02, 0.03])
    tmp = tempfile.mkdtemp(prefix='crack_measure_')
    ok = []

    def run(name, segments, sd, **kw):
        phis = _synthetic(segments, X, dx, v, t0, times)
        path = os.path.join(tmp, f'dump.{name}')
        _write_dump(path, X, phis, times)
        res = analyse(read_dump(path), [sd], **kw)
        if verbose:
            print(f'--- {name}')
            print(summary_text(res))
        return res

    def check(cond, msg):
        ok.append((cond, msg))
        if verbose:
            print(('  PASS ' if cond else '  FAIL ') + msg)

    # 1. straight crack along +x from the seed, 1000 m/s from t0 (the grid rows are
    # at y = 29.5 and 30.5 mm: both get phi 0.5)
    res = run('straight', [(seed, (0.0999, 0.03), t0)], Seed('s', *seed, 0.0),
              target_edges={'s': 'xmax'})
    c = res['cracks']['s']
    check(abs(c['initiation_time'] - (t0 + 3 * dx / v)) <= 1.01e-6,
          f"straight: initiation {c['initiation_time'] * 1e6:.2f} us (expect {(t0 + 3 * dx / v) * 1e6:.2f} +- 1)")
    vmid = np.nanmedian([s for s, t in zip(c['speed'], res['time']) if s is not None and 20e-6 < t < 60e-6])
    check(abs(vmid - v) / v < 0.03, f'straight: speed {vmid:.1f} m/s (expect {v})')
    check(abs(c['angle_deg']) < 1.0, f"straight: angle {c['angle_deg']:.2f} deg (expect 0)")
    check(c['branches_max_persistent'] == 1 and c['branching_time'] is None, 'straight: no branching')
    check(c['target_reached_time'] is not None and abs(c['target_reached_time'] - (t0 + 0.0795 / v)) <= 2e-6,
          f"straight: reaches xmax at {_fmt(c['target_reached_time'], 1e6)} us (expect ~{(t0 + 0.0795 / v) * 1e6:.1f})")
    # 1b. the same dump with the lengths given in other units of dx (as
    # examples/crack-branching/summarise.py --dx does): initiation at 6 dx
    res6 = analyse(read_dump(os.path.join(tmp, 'dump.straight')), [Seed('s', *seed, 0.0)],
                   init_length=6.0)
    t6 = res6['cracks']['s']['initiation_time']
    check(t6 is not None and abs(t6 - (t0 + 6 * dx / v)) <= 1.01e-6,
          f"straight, init_length 6: initiation {_fmt(t6, 1e6)} us (expect {(t0 + 6 * dx / v) * 1e6:.2f} +- 1)")
    # 2. 60-degree crack
    a = math.radians(60)
    end = seed + 0.0299 / math.sin(a) * np.array([math.cos(a), math.sin(a)])
    res = run('deg60', [(seed, end, t0)], Seed('s', *seed, 'auto'), target_edges={'s': 'any'})
    c = res['cracks']['s']
    check(abs(c['angle_deg'] - 60) < 1.5, f"60-degree: angle {c['angle_deg']:.2f} deg (expect 60)")
    vmid = np.nanmedian([s for s, t in zip(c['speed'], res['time']) if s is not None and 12e-6 < t < 30e-6])
    check(abs(vmid - v) / v < 0.06, f'60-degree: speed {vmid:.1f} m/s (expect {v})')
    check(c['branches_max_persistent'] == 1, '60-degree: no branching')
    check('ymax' in c['edge_reached_time'], f"60-degree: reaches ymax ({c['edge_reached_time']})")
    # 3. Y: stem along +x to x = 50 mm, branching at tb into +-30 degrees to the right edge
    bp = np.array([0.05, 0.03])
    tb = t0 + 0.03 / v
    ends = [bp + (0.0499 / math.cos(math.radians(30))) * np.array([math.cos(math.radians(s)), math.sin(math.radians(s))])
            for s in (30, -30)]
    res = run('Y', [(seed, bp, t0), (bp, ends[0], tb), (bp, ends[1], tb)], Seed('s', *seed, 0.0),
              target_edges={'s': 'xmax'})
    c = res['cracks']['s']
    check(c['branches_final'] == 2 and c['branches_max_persistent'] == 2,
          f"Y: {c['branches_final']} branches at the end (expect 2)")
    check(c['branching_time'] is not None and tb <= c['branching_time'] <= tb + 6e-6,
          f"Y: branching time {_fmt(c['branching_time'], 1e6)} us (expect {tb * 1e6:.0f} .. {tb * 1e6 + 6:.0f}: "
          "the crack reaches the branch point, where the branches are 3 dx apart)")
    check(c['branching_detected_time'] is not None and c['branching_detected_time'] <= tb + 20e-6,
          f"Y: persistent branches from {_fmt(c['branching_detected_time'], 1e6)} us (expect <= {tb * 1e6 + 20:.0f}: "
          "both branches 10 dx long beyond the branch point)")
    check(c['branch_point_s'] is not None and 0.03 <= c['branch_point_s'] <= 0.04,
          f"Y: branch point s = {_fmt(c['branch_point_s'], 1e3)} mm from the seed (expect 30 .. 40)")
    check(c['branches_at_target_final'] == 2, f"Y: branches at xmax {c['branches_at_target_final']} (expect 2)")
    angs = sorted(b['angle_deg'] for b in c['branches_at_end'])
    check(len(angs) == 2 and abs(angs[0] + 30) < 3 and abs(angs[1] - 30) < 3,
          f'Y: branch angles {["%.1f" % x for x in angs]} (expect -30, 30; fitted over each whole branch)')
    check(c['side_branches_max'] == 0, f"Y: side branches {c['side_branches_max']} (expect 0)")
    n_fail = sum(1 for cnd, _ in ok if not cnd)
    if verbose:
        print(f'selftest: {len(ok) - n_fail}/{len(ok)} checks passed')
    if n_fail:
        raise AssertionError(f'{n_fail} self-test checks failed')
    return True


# --------------------------------------------------------------------------- CLI

def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog='Definitions: see the module docstring (python3 -c '
                                        '"import crack_measure; help(crack_measure)").')
    ap.add_argument('dump', nargs='?', help='LAMMPS dump custom file (id x y c_dmg[1] ...)')
    ap.add_argument('--selftest', action='store_true', help='synthetic straight, 60-degree and Y cracks')
    ap.add_argument('--seed', nargs=4, action='append', metavar=('NAME', 'X', 'Y', 'DIR'),
                    help='crack seed point and main direction in degrees (or auto); repeatable')
    ap.add_argument('--threshold', type=float, help='cracked: phi >= this (0.3)')
    ap.add_argument('--dx', type=float, help='particle spacing (default: median nearest-neighbour distance)')
    ap.add_argument('--dt', type=float, help='time step, if the dump has no ITEM: TIME')
    ap.add_argument('--phi-col', help='damage column (default: first c_*[1])')
    ap.add_argument('--exclude-initial', choices=['cracked', 'damaged', 'none'],
                    help='particles left out: cracked (default) / damaged in the first frame, or none')
    ap.add_argument('--tip', choices=['path', 'projection'],
                    help='tip = farthest along the crack path (default) or along the main direction')
    ap.add_argument('--link', type=float, help='link distance of crack clusters, in dx (1.5)')
    ap.add_argument('--seed-radius', type=float, help='a crack belongs to a seed within this many dx (2.5)')
    ap.add_argument('--init-length', type=float, help='initiation: crack length >= this many dx (3)')
    ap.add_argument('--gap', type=float, help='branches are separated by a gap > this many dx (3)')
    ap.add_argument('--branch-min-length', type=float, help='a branch is at least this many dx long (10)')
    ap.add_argument('--edge-tol', type=float, help='reaching an edge: within this many dx (1)')
    ap.add_argument('--ref-dir', type=float, help='reference direction of the angle, degrees from +x (0)')
    ap.add_argument('--angle-range', type=float, nargs=2, metavar=('R1_DX', 'R2'),
                    help='R1 in units of dx, R2 in length units')
    ap.add_argument('--length', choices=['chord', 'path'], help='crack length: seed-tip chord (default) or path')
    ap.add_argument('--window', type=float, help='speed smoothing window (time units)')
    ap.add_argument('--target-edge', action='append', metavar='[NAME=]EDGE',
                    help='xmin|xmax|ymin|ymax|any, for every seed or NAME=EDGE')
    ap.add_argument('--region', nargs=5, action='append', metavar=('NAME', 'XLO', 'XHI', 'YLO', 'YHI'))
    ap.add_argument('--every', type=int, default=1, help='use every n-th frame')
    ap.add_argument('--tmax', type=float, help='ignore frames after this time')
    ap.add_argument('--out', help='prefix of OUT.json, OUT.csv, OUT.txt')
    ap.add_argument('--plot', help='tip speed PNG')
    ap.add_argument('--rayleigh', type=float, help='Rayleigh speed drawn on the speed plot')
    ap.add_argument('--title')
    ap.add_argument('--montage', help='damage montage PNG')
    ap.add_argument('--montage-times', help='comma-separated times (dump units)')
    ap.add_argument('--montage-cols', type=int, default=2)
    ap.add_argument('--symmetry', nargs=2, metavar=('A', 'B'),
                    help='compare crack A with crack B mirrored about y = 0')
    a = ap.parse_args(argv)
    if a.selftest:
        selftest()
        return 0
    if not a.dump or not a.seed:
        ap.error('a dump and at least one --seed are needed (or --selftest)')
    seeds = [Seed(n, x, y, d) for n, x, y, d in a.seed]
    tg = {}
    for t in a.target_edge or []:
        if '=' in t:
            n, e = t.split('=', 1)
            tg[n] = e
        else:
            for s in seeds:
                tg[s.name] = t
    regions = {r[0]: tuple(float(v) for v in r[1:]) for r in (a.region or [])}
    ar = tuple(a.angle_range) if a.angle_range else None
    res = analyse(read_dump(a.dump, every=a.every, tmax=a.tmax), seeds, dx=a.dx, dt=a.dt,
                  phi_col=a.phi_col, regions=regions, target_edges=tg,
                  threshold=a.threshold, exclude_initial=a.exclude_initial, tip=a.tip, link=a.link, seed_radius=a.seed_radius,
                  init_length=a.init_length, gap=a.gap, branch_min_length=a.branch_min_length,
                  edge_tol=a.edge_tol, ref_dir=a.ref_dir, angle_range=ar, length=a.length,
                  window=a.window)
    if a.symmetry:
        res['symmetry'] = symmetry(res, *a.symmetry)
    if a.out:
        txt = write_outputs(res, a.out)
    else:
        txt = summary_text(res)
    print(txt)
    if a.symmetry:
        print('symmetry:', json.dumps(res['symmetry']))
    if a.plot:
        plot_speed(res, a.plot, rayleigh=a.rayleigh, title=a.title)
    if a.montage:
        tm = [float(v) for v in a.montage_times.split(',')] if a.montage_times else None
        montage(a.dump, a.montage, times=tm, ncols=a.montage_cols, dt=a.dt, title=a.title)
    return 0


if __name__ == '__main__':
    sys.exit(main())
