#!/usr/bin/env python3
"""Summary of a 3D Kalthoff-Winkler run: both cracks measured by
tools/crack_measure.py on the mid-thickness particle layer and on the
through-thickness projection, next to the thesis's, the literature's and the
experiment's numbers (examples/common/acceptance.py).

  summarise.py PREFIX [--label L] [--window S] [--threshold PHI]

Reads PREFIX.dump (3D: id x y z phi phi'; first frame every particle, later
frames the damaged ones) and PREFIX.log.  tools/crack_measure.py works in the
x-y plane, so the 3D dump is first reduced to two 2D dumps:

  PREFIX.mid.dump   the particle layer nearest the mid-thickness plane (the
                    middle one of an odd number of layers; of an even number,
                    the one just below the mid-plane), its own phi
  PREFIX.proj.dump  one particle per (x, y) column of the lattice, with the
                    largest phi (and phi') of the column's layers: a column
                    counts as cracked as soon as any layer is

The crack measured on the mid layer is the main result (the thesis's figures
show the x-y plane); the projection shows how far ahead of it the crack is on
any layer.  Every layer is also measured on its own (initiation, angle, final
tip) to show the crack front through the thickness.

Writes PREFIX.crack.{json,csv,txt} (mid layer), PREFIX.proj.crack.{json,csv,txt},
PREFIX.speed.png (tip speeds, Rayleigh speed 2803 m/s drawn), PREFIX.montage.png
(mid layer) and prints the summary table.
"""
import argparse
import math
import os
import sys

import numpy as np

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, '..', '..', 'tools'))
sys.path.insert(0, os.path.join(here, '..', 'common'))
import crack_measure as cm  # noqa: E402
import acceptance as A  # noqa: E402  (../common: the acceptance bands, the thesis's numbers)
from run_info import git_rev, log_info, us  # noqa: E402  (../common)

RAYLEIGH = A.RAYLEIGH_STEEL.value   # m/s, plane strain / 3D (doc/references.rst)


def reduce_dump(path, out_mid, out_proj):
    """Write the 2D mid-layer and through-thickness-maximum dumps of a 3D dump.
    Returns dict(dx, nz, layer_z, mid_layer, n_particles, per_layer_frames)."""
    frames = cm.read_dump(path)
    f0 = next(frames)
    ids0 = f0.ids
    X = np.stack([f0.col('x'), f0.col('y'), f0.col('z')], axis=1)
    zs = np.unique(np.round(X[:, 2], 9))
    nz = len(zs)
    dx = float(np.median(np.diff(zs))) if nz > 1 else math.sqrt(0.1 * 0.2 / len(X))
    layer = np.rint((X[:, 2] - zs[0]) / dx).astype(int)
    mid = nz // 2 if nz % 2 else nz // 2 - 1
    ix = np.rint((X[:, 0] - X[:, 0].min()) / dx).astype(int)
    iy = np.rint((X[:, 1] - X[:, 1].min()) / dx).astype(int)
    ny = iy.max() + 1
    colkey = ix * ny + iy
    cols, col_of = np.unique(colkey, return_inverse=True)
    ncol = len(cols)
    # column positions: those of the column's particles (all layers share x, y)
    cx = np.zeros(ncol); cy = np.zeros(ncol)
    cx[col_of] = X[:, 0]; cy[col_of] = X[:, 1]
    in_mid = np.flatnonzero(layer == mid)
    mid_ids = ids0[in_mid]
    phicol = [c for c in f0.columns if c.startswith('c_') and c.endswith('[1]')][0]
    phi2col = [c for c in f0.columns if c.startswith('c_') and c.endswith('[2]')]
    phi2col = phi2col[0] if phi2col else phicol
    layers_xy = [np.flatnonzero(layer == k) for k in range(nz)]

    def head(f, fr, n):
        if fr.time is not None:
            f.write(f'ITEM: TIME\n{fr.time:.10g}\n')
        f.write(f'ITEM: TIMESTEP\n{fr.step}\nITEM: NUMBER OF ATOMS\n{n}\n')
        f.write('ITEM: BOX BOUNDS ss ss pp\n')
        f.write(f'{fr.box[0][0]:.7g} {fr.box[0][1]:.7g}\n{fr.box[1][0]:.7g} {fr.box[1][1]:.7g}\n'
                '-0.5 0.5\n')
        f.write('ITEM: ATOMS id x y c_dmg[1] c_dmg[2]\n')

    per_layer = [[] for _ in range(nz)]   # per frame: (time, step, rows) of damaged particles
    with open(out_mid, 'w') as fm, open(out_proj, 'w') as fp:
        for k, fr in enumerate(_chain(f0, frames)):
            pos = np.searchsorted(ids0, fr.ids)
            phi = np.zeros(len(ids0)); phi2 = np.zeros(len(ids0))
            phi[pos] = fr.col(phicol); phi2[pos] = fr.col(phi2col)
            # mid layer (first frame: every particle of it)
            sel = in_mid if k == 0 else in_mid[phi[in_mid] > 0]
            head(fm, fr, len(sel))
            fm.write(''.join(f'{ids0[i]} {X[i, 0]:.7g} {X[i, 1]:.7g} {phi[i]:.6g} {phi2[i]:.6g}\n'
                             for i in sel))
            # through-thickness maximum per column
            pc = np.zeros(ncol); pc2 = np.zeros(ncol)
            np.maximum.at(pc, col_of, phi); np.maximum.at(pc2, col_of, phi2)
            selc = np.arange(ncol) if k == 0 else np.flatnonzero(pc > 0)
            head(fp, fr, len(selc))
            fp.write(''.join(f'{c + 1} {cx[c]:.7g} {cy[c]:.7g} {pc[c]:.6g} {pc2[c]:.6g}\n'
                             for c in selc))
            for L in range(nz):
                li = layers_xy[L] if k == 0 else layers_xy[L][phi[layers_xy[L]] > 0]
                per_layer[L].append((fr.time, fr.step, li, phi[li].copy()))
    return dict(dx=dx, nz=nz, layer_z=zs.tolist(), mid_layer=mid, n_particles=len(ids0),
                ncol=ncol, X=X, ids0=ids0, per_layer=per_layer, mid_ids=mid_ids)


def _chain(first, rest):
    yield first
    yield from rest


def layer_frames(red, L):
    """crack_measure Frames of layer L (2D: id x y phi)."""
    X, ids0 = red['X'], red['ids0']
    for t, step, idx, phi in red['per_layer'][L]:
        data = np.column_stack([ids0[idx].astype(float), X[idx, 0], X[idx, 1], phi])
        yield cm.Frame(step, t, ['id', 'x', 'y', 'c_dmg[1]'], data, None)


def track(frames, seeds, dx, threshold=0.3, link=1.5, seed_radius=2.5, join=2.5):
    """Crack ownership from the growth history.  frames: 2D Frames (the first holds
    every particle).  A particle that becomes cracked (phi >= threshold, not cracked
    in the first frame) joins the crack of the cracked particles it is linked to
    (reference distance <= link dx), through chains of particles cracked in the same
    frame (breadth-first from the labelled ones, ties to the lower label); a new
    cluster linked to no crack starts the crack of a seed if it lies within
    seed_radius dx of it, joins the crack with a particle within join dx of it, or
    else starts a crack of its own (e.g. at the far edge).  Labels never change, so two cracks that meet stay
    two cracks.  Returns dict(X, ids0, phicol, labels (per frame), extra (the cracks not
    started at a seed), contacts ({(a, b): first time}))."""
    f0 = frames[0]
    ids0 = f0.ids
    X = np.stack([f0.col('x'), f0.col('y')], axis=1)
    phicol = [c for c in f0.columns if c.startswith('c_') and c.endswith('[1]')][0]
    excluded = f0.col(phicol) >= threshold
    ns = len(seeds)
    S = np.array([[sd.x, sd.y] for sd in seeds])
    label = np.full(len(X), -1)
    labels, extra, contacts = [], [], {}
    for fr in frames:
        t = fr.time
        phi = cm._full_column(fr, phicol, ids0)
        cracked = (phi >= threshold) & ~excluded
        cidx = np.flatnonzero(cracked)
        if len(cidx):
            pairs, _ = cm._pairs_within(X[cidx], link * dx * (1 + 1e-9))
            nb = [[] for _ in range(len(cidx))]
            for a, b in pairs:
                nb[a].append(b); nb[b].append(a)
            loc = label[cidx].copy()
            if np.any(loc < 0):
                # level by level from the labelled particles; a particle reached from two
                # cracks in the same level joins the lower label (the notch cracks before
                # the others, upper before lower): mirror-symmetric, independent of the
                # particle order
                front = np.flatnonzero(loc >= 0).tolist()
                while front:
                    cand = {}
                    for a in front:
                        for b in nb[a]:
                            if loc[b] < 0:
                                cand[b] = min(cand.get(b, loc[a]), loc[a])
                    for b, lab in cand.items():
                        loc[b] = lab
                    front = list(cand)
                un = np.flatnonzero(loc < 0)
                if len(un):
                    pos = -np.ones(len(cidx), int); pos[un] = np.arange(len(un))
                    sp = [(pos[a], pos[b]) for a, b in pairs if pos[a] >= 0 and pos[b] >= 0]
                    comp = cm._components(len(un), sp)
                    have = np.flatnonzero(label >= 0)
                    for c in range(comp.max() + 1):
                        memb = un[comp == c]
                        P = X[cidx[memb]]
                        d = np.min(np.linalg.norm(P[None, :, :] - S[:, None, :], axis=2), axis=1)
                        # a cluster near no crack but within join dx of a crack's particle
                        # (a tip that advanced past a particle) joins that crack
                        dj, lj = np.inf, -1
                        if len(have):
                            dd = np.linalg.norm(X[have][None, :, :] - P[:, None, :], axis=2)
                            k = np.unravel_index(np.argmin(dd), dd.shape)
                            dj, lj = dd[k], int(label[have[k[1]]])
                        if d.min() <= seed_radius * dx:
                            lab = int(np.argmin(d))
                        elif dj <= join * dx:
                            lab = lj
                        else:
                            lab = ns + len(extra)
                            extra.append(dict(label=lab, birth_time=t, birth_xy=P.mean(axis=0).tolist(),
                                              birth_n=int(len(memb))))
                        loc[memb] = lab
            label[cidx] = loc
            # first contact between two cracks: linked particles with different labels
            if len(pairs):
                la, lb = loc[pairs[:, 0]], loc[pairs[:, 1]]
                m = la != lb
                for a, b in set(zip(np.minimum(la[m], lb[m]).tolist(), np.maximum(la[m], lb[m]).tolist())):
                    contacts.setdefault((a, b), t)
        labels.append(label.copy())
    for e in extra:
        mine = labels[-1] == e['label']
        P = X[mine]
        e['n_final'] = int(mine.sum())
        e['extent_final'] = [P[:, 0].min(), P[:, 0].max(), P[:, 1].min(), P[:, 1].max()]
    return dict(X=X, ids0=ids0, phicol=phicol, labels=labels, extra=extra, contacts=contacts,
                frames=frames)


def crack_frames(tr, lab):
    """The frames with only crack lab's particles (the first frame unchanged)."""
    X, ids0, frames = tr['X'], tr['ids0'], tr['frames']
    out = [frames[0]]
    for fr, L in zip(frames[1:], tr['labels'][1:]):
        phi = cm._full_column(fr, tr['phicol'], ids0)
        idx = np.flatnonzero(L == lab)
        data = np.column_stack([ids0[idx].astype(float), X[idx, 0], X[idx, 1], phi[idx]])
        out.append(cm.Frame(fr.step, fr.time, ['id', 'x', 'y', tr['phicol']], data, fr.box))
    return out


def measure(frames, seeds, dx, kw, angle_near=None):
    """crack_measure on every seed's own crack (growth-history ownership, see track),
    the regions and the untracked 'other' count from the plain analysis.  Returns a
    crack_measure result dict with 'tracking' added."""
    plain = cm.analyse(frames, seeds, **kw)
    tr = track(frames, seeds, dx, threshold=kw.get('threshold', 0.3))
    res = dict(plain)
    res['cracks'] = {}
    res['untracked_cracks'] = plain['cracks']
    kw1 = dict(kw); regions = kw1.pop('regions', None)  # noqa: F841
    tgt = kw1.pop('target_edges', {})
    for k, sd in enumerate(seeds):
        fr = crack_frames(tr, k)
        r = cm.analyse(fr, [sd], target_edges={sd.name: tgt.get(sd.name, 'any')}, **kw1)
        c = r['cracks'][sd.name]
        if angle_near is not None:
            rn = cm.analyse(fr, [sd], angle_range=(3.0, angle_near), **kw1)
            c['angle_near_deg'] = rn['cracks'][sd.name]['angle_deg']
            c['angle_near_range'] = [3 * dx, angle_near]
        res['cracks'][sd.name] = c
    names = [sd.name for sd in seeds] + [f"far{e['label'] - len(seeds) + 1}" for e in tr['extra']]
    res['tracking'] = dict(
        extra=[dict(e, name=names[e['label']]) for e in tr['extra']],
        contacts=[dict(a=names[a], b=names[b], time=t) for (a, b), t in sorted(tr['contacts'].items(),
                                                                            key=lambda kv: kv[1])])
    res['symmetry'] = cm.symmetry(res, 'upper', 'lower', axis='y', about=0.0)
    return res


def first_growth(res, name, dx, n=1.0):
    """First frame time with a crack length >= n dx (None if never)."""
    L = np.array(res['cracks'][name]['length'])
    k = np.flatnonzero(L >= n * dx * (1 - 1e-6))
    return float(res['time'][k[0]]) if len(k) else None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('prefix')
    ap.add_argument('--label', default='')
    ap.add_argument('--window', type=float, default=4e-6)
    ap.add_argument('--threshold', type=float, default=0.3)
    ap.add_argument('--angle-near', type=float, default=0.02,
                    help='outer radius [m] of the fit for the initial kink angle')
    ap.add_argument('--no-layers', action='store_true', help='skip the layer-by-layer measurement')
    a = ap.parse_args()
    p = a.prefix
    info = log_info(p + '.log')
    red = reduce_dump(p + '.dump', p + '.mid.dump', p + '.proj.dump')
    dx = red['dx']
    seeds = [cm.Seed('upper', 0.05, 0.025, 'auto'), cm.Seed('lower', 0.05, -0.025, 'auto')]
    # under the impactor: its strip less the notch flanks (which start damaged)
    regions = {'under_impactor': (-1.0, 5.01 * dx, -0.025 + 2.01 * dx, 0.025 - 2.01 * dx),
               'impacted_edge_strip': (-1.0, 10.01 * dx, -0.1, 0.1)}
    kw = dict(target_edges={'upper': 'any', 'lower': 'any'}, threshold=a.threshold,
              window=a.window, ref_dir=0.0, regions=regions, dx=dx)
    res = {}
    for view, dump in (('mid', p + '.mid.dump'), ('proj', p + '.proj.dump')):
        r = measure(list(cm.read_dump(dump)), seeds, dx, kw, angle_near=a.angle_near)
        r['reduction'] = dict(view=view, nz=red['nz'], layer_z=red['layer_z'], mid_layer=red['mid_layer'],
                              n_particles_3d=red['n_particles'])
        res[view] = r
    cm.write_outputs(res['mid'], p + '.crack')
    cm.write_outputs(res['proj'], p + '.proj.crack')
    # every layer on its own: the crack front through the thickness
    layers = []
    if not a.no_layers:
        for L in range(red['nz']):
            layers.append((L, red['layer_z'][L], measure(list(layer_frames(red, L)), seeds, dx, kw)))
    M, P = res['mid'], res['proj']
    extra = [(f'{s}, through-thickness max', np.array(P['time']),
              np.array([np.nan if v is None else v for v in P['cracks'][s]['speed']]))
             for s in ('upper', 'lower')]
    cm.plot_speed(M, p + '.speed.png', rayleigh=RAYLEIGH, extra=extra,
                  title=f'Kalthoff-Winkler 3D {a.label}: mid layer'.strip())
    tend = M['time'][-1]
    times = [t * 1e-6 for t in range(10, 101, 10) if t * 1e-6 <= tend + 1e-6]
    cm.montage(p + '.mid.dump', p + '.montage.png', times=times or None, npanel=5, ncols=5, panel_width=2.6,
               title=f'damage phi, mid-thickness layer, Kalthoff-Winkler 3D {a.label}'.strip())
    U, L_ = M['cracks']['upper'], M['cracks']['lower']
    PU, PL = P['cracks']['upper'], P['cracks']['lower']

    def f(v, fmt):
        return 'n/a' if v is None else format(v, fmt)

    def edge(c):
        if c['target_reached_time'] is None:
            tip = c['tip_final']
            return f"no (tip at {tip[0] * 1e3:.0f}, {tip[1] * 1e3:.0f} mm)" if tip else 'no crack'
        e = min(c['edge_reached_time'], key=c['edge_reached_time'].get)
        return f"{us(c['target_reached_time'])} ({e})"

    rows = [
        ('crack angle to the impact direction, whole crack',
         f(U['angle_deg'], '.1f') + ' deg', f(L_['angle_deg'], '.1f') + ' deg',
         f"{f(PU['angle_deg'], '.1f')} / {f(PL['angle_deg'], '.1f')} deg",
         A.THESIS_KW3D_ANGLE.value, f'~{A.EXP_KW_ANGLE.value:g} deg'),
        (f'initial kink angle (fit within {a.angle_near * 1e3:.0f} mm of the tip)',
         f(U['angle_near_deg'], '.1f') + ' deg', f(L_['angle_near_deg'], '.1f') + ' deg',
         f"{f(PU['angle_near_deg'], '.1f')} / {f(PL['angle_near_deg'], '.1f')} deg",
         f'{A.THESIS_KW3D_KINK.value:g} deg', f'~{A.EXP_KW_ANGLE.value:g} deg'),
        ('initiation time (crack >= 3 dx)', us(U['initiation_time']), us(L_['initiation_time']),
         f"{us(PU['initiation_time'])} / {us(PL['initiation_time'])}", A.us(A.THESIS_KW3D_INITIATION.value), '-'),
        ('first growth (crack >= 1 dx)', us(first_growth(M, 'upper', dx)), us(first_growth(M, 'lower', dx)),
         f"{us(first_growth(P, 'upper', dx))} / {us(first_growth(P, 'lower', dx))}", '-', '-'),
        ('time to reach a plate edge', edge(U), edge(L_), f"{edge(PU)} / {edge(PL)}",
         f'{A.us(A.THESIS_KW3D_EDGE.value)} (side edges)', '-'),
        ('peak crack speed', f(U['speed_max'], '.0f') + ' m/s', f(L_['speed_max'], '.0f') + ' m/s',
         f"{f(PU['speed_max'], '.0f')} / {f(PL['speed_max'], '.0f')} m/s",
         f'{A.THESIS_KW3D_SPEED.value:.0f} m/s', f'< Rayleigh {RAYLEIGH:.0f} m/s'),
        ('branches / short side branches', f"{U['branches_max_persistent']} / {U['side_branches_max']}",
         f"{L_['branches_max_persistent']} / {L_['side_branches_max']}",
         f"{PU['branches_max_persistent']} / {PU['side_branches_max']}, "
         f"{PL['branches_max_persistent']} / {PL['side_branches_max']}", '1 / 0', '1'),
        ('final crack length (chord from the notch tip)', f(U['length_final'] * 1e3, '.1f') + ' mm',
         f(L_['length_final'] * 1e3, '.1f') + ' mm',
         f"{f(PU['length_final'] * 1e3, '.1f')} / {f(PL['length_final'] * 1e3, '.1f')} mm", '-', '-'),
    ]
    hdr = ('quantity', 'upper, mid layer', 'lower, mid layer', 'upper / lower, projection',
           'thesis (3D, 30 m/s)', 'experiment')
    nc = len(hdr)
    w = [max(len(r[i]) for r in rows + [hdr]) for i in range(nc)]
    out = [f'Kalthoff-Winkler 3D {a.label}: {p}',
           f'code: {git_rev()}, binary md5 '
           + (open(p + '.binary').read().split()[0][:12] if os.path.exists(p + '.binary') else '?'),
           f"pair_style tlsph/damage {info.get('pair_style', '?')}",
           f"velocity filter {info.get('filter', '?')}, s_c = {info.get('sc', float('nan')):.4g}, "
           f"dx = {dx * 1e3:.4g} mm, {red['nz']} particle layers through the thickness "
           f"(z = {red['layer_z'][0] * 1e3:.3g} .. {red['layer_z'][-1] * 1e3:.3g} mm), mid layer = layer "
           f"{red['mid_layer'] + 1} (z = {red['layer_z'][red['mid_layer']] * 1e3:.3g} mm)",
           f"particles {info.get('atoms', red['n_particles'])}, steps {info.get('steps')}, "
           f"simulated {tend * 1e6:.1f} us, loop time {info.get('loop_s', float('nan')):.0f} s, "
           f"wall time {info.get('wall_s', '?')} s on {info.get('procs', 1)} MPI rank(s) (shared machine)",
           f"crack_measure: phi >= {a.threshold}, speed window {a.window * 1e6:g} us, "
           f"angle to +x (impact direction), fitted from 3 dx (initial) / 5 dx (whole) from the notch tip; "
           f"mid layer: that layer's phi; projection: the largest phi of each (x, y) column; each crack "
           f"is the particles that cracked next to it (growth history), so cracks that meet stay apart",
           *([f"LAMMPS STOPPED: {info['error']}"] if 'error' in info else []),
           '',
           '  '.join(h.ljust(w[i]) for i, h in enumerate(hdr)),
           '  '.join('-' * w[i] for i in range(nc))]
    out += ['  '.join(v.ljust(w[i]) for i, v in enumerate(r)) for r in rows]
    out.append('')
    for view in ('mid', 'proj'):
        sym = res[view]['symmetry']
        out.append(f'symmetry, {view} (lower crack mirrored about y = 0): initiation difference '
                   f"{f(sym['initiation_time_diff'] and sym['initiation_time_diff'] * 1e6, '.2f')} us, angle "
                   f"difference {f(sym['angle_diff_deg'], '.2f')} deg, final length difference "
                   f"{f(sym['length_final_diff'] and sym['length_final_diff'] * 1e3, '.2f')} mm, largest tip "
                   f"distance {f(sym['tip_mirror_distance_max'] * 1e3, '.2f')} mm")
    for view in ('mid', 'proj'):
        tk = res[view]['tracking']
        if not tk['extra']:
            out.append(f'other cracks, {view}: none (every cracked particle belongs to a notch crack)')
        for e in tk['extra']:
            ex = e['extent_final']
            out.append(f"other crack '{e['name']}', {view}: starts at {us(e['birth_time'])} at "
                       f"({e['birth_xy'][0] * 1e3:.1f}, {e['birth_xy'][1] * 1e3:.1f}) mm, at the end "
                       f"{e['n_final']} cracked particles in x {ex[0] * 1e3:.0f} .. {ex[1] * 1e3:.0f} mm, "
                       f"y {ex[2] * 1e3:.0f} .. {ex[3] * 1e3:.0f} mm")
        if tk['contacts']:
            out.append(f'cracks meet, {view}: ' + ', '.join(f"{c['a']}-{c['b']} at {us(c['time'])}"
                                                          for c in tk['contacts']))
    ri = P['regions']['under_impactor']
    re_ = P['regions']['impacted_edge_strip']
    out.append(f"under the impactor (x < 5 dx, |y| < 25 mm - 2 dx, any layer): max phi {max(ri['phi_max']):.3f}, "
               f"cracked (phi >= {a.threshold}) columns at most {ri['n_cracked_max']}, damaged "
               f"(phi > 0) at most {max(ri['n_damaged'])}")
    out.append(f"impacted-edge strip (x < 10 dx, all y, any layer): largest phi rise {re_['dphi_max_all']:.3f}, "
               f"newly damaged columns at most {max(re_['n_damaged'])}, cracked at most "
               f"{re_['n_cracked_max']}")
    if layers:
        out.append('')
        out.append('crack front through the thickness (each particle layer measured on its own; upper / lower):')
        out.append('  layer  z [mm]  initiation           angle (whole)        '
                   'peak speed [m/s]  edge reached          final tip [mm]')
        for L, z, r in layers:
            cu, cl = r['cracks']['upper'], r['cracks']['lower']
            tips = ' / '.join('-' if c['tip_final'] is None else
                              f"({c['tip_final'][0] * 1e3:.1f}, {c['tip_final'][1] * 1e3:.1f})" for c in (cu, cl))
            out.append(f"  {L + 1:5d}  {z * 1e3:6.2f}  {us(cu['initiation_time']):>8} / {us(cl['initiation_time']):<8}  "
                       f"{f(cu['angle_deg'], '5.1f')} / {f(cl['angle_deg'], '5.1f')} deg  "
                       f"{f(cu['speed_max'], '5.0f')} / {f(cl['speed_max'], '5.0f')}     "
                       f"{us(cu['target_reached_time']):>8} / {us(cl['target_reached_time']):<8}  {tips}"
                       + ('   (mid layer)' if L == red['mid_layer'] else ''))
    if 'energy_excess_max' in info:
        es, wf = info['energy_final']
        out.append('')
        out.append(f"energy balance (thermo, every 2 us): strain + hourglass + viscous + kinetic energy (less the "
                   f"impactor's own, which fix move sets) at the end {es:.4g} J vs impactor work {wf:.4g} J; largest excess (E - W)/max W = "
                   f"{info['energy_excess_max']:+.3f} at {info['energy_excess_time'] * 1e6:.1f} us "
                   f"(must stay <= ~0: broken bonds only lose energy), first above +0.1 at "
                   f"{us(info['energy_onset_time'])}; kinetic energy max "
                   f"{info['ke_max'][0]:.4g} J at {info['ke_max'][1] * 1e6:.1f} us")
    if 'first_break_time' in info:
        out.append(f"first bond broken anywhere (other than the notch cuts): between "
                   f"{info['first_break_prev_time'] * 1e6:.1f} and {info['first_break_time'] * 1e6:.1f} us "
                   f"(thermo output)")
    out.append('')
    out.append('tool summary, mid layer (cracks by growth history; regions and the untracked count '
               'from the plain analysis):')
    out.append(open(p + '.crack.txt').read().rstrip())
    out.append('')
    out.append('tool summary, through-thickness projection:')
    out.append(open(p + '.proj.crack.txt').read().rstrip())
    print('\n'.join(out))


if __name__ == '__main__':
    main()
