#!/usr/bin/env python3
"""Summary of a 2D Kalthoff-Winkler run: both cracks measured by
tools/crack_measure.py, next to the thesis's and the experiment's numbers
(examples/common/acceptance.py).

  summarise.py PREFIX [--label L] [--window S] [--threshold PHI]

Reads PREFIX.dump and PREFIX.log; writes PREFIX.crack.{json,csv,txt},
PREFIX.speed.png (tip speeds, Rayleigh speed 2803 m/s drawn), PREFIX.montage.png
and prints the summary table.
"""
import argparse
import math
import os
import re
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, '..', '..', 'tools'))
sys.path.insert(0, os.path.join(here, '..', 'common'))
import crack_measure as cm  # noqa: E402
import acceptance as A  # noqa: E402  (../common: the acceptance bands, the thesis's numbers)
from run_info import git_rev, log_info, us  # noqa: E402  (../common)

RAYLEIGH = A.RAYLEIGH_STEEL.value   # m/s, plane strain (doc/references.rst)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('prefix')
    ap.add_argument('--label', default='')
    ap.add_argument('--window', type=float, default=4e-6)
    ap.add_argument('--threshold', type=float, default=0.3)
    ap.add_argument('--angle-near', type=float, default=0.02,
                    help='outer radius [m] of the fit for the initial kink angle')
    a = ap.parse_args()
    p = a.prefix
    info = log_info(p + '.log')
    seeds = [cm.Seed('upper', 0.05, 0.025, 'auto'), cm.Seed('lower', 0.05, -0.025, 'auto')]
    frames = list(cm.read_dump(p + '.dump'))
    dx = math.sqrt(0.1 * 0.2 / len(frames[0].data))
    # under the impactor: its strip less the notch flanks (which start damaged)
    regions = {'under_impactor': (-1.0, 5.01 * dx, -0.025 + 2.01 * dx, 0.025 - 2.01 * dx),
               'impacted_edge_strip': (-1.0, 10.01 * dx, -0.1, 0.1)}
    kw = dict(target_edges={'upper': 'any', 'lower': 'any'}, threshold=a.threshold,
              window=a.window, ref_dir=0.0, regions=regions)
    res = cm.analyse(frames, seeds, **kw)
    res['symmetry'] = cm.symmetry(res, 'upper', 'lower', axis='y', about=0.0)
    # initial kink angle: the fit over the first angle_near metres of each crack
    near = cm.analyse(frames, seeds, angle_range=(3.0, a.angle_near), **kw)
    for s in ('upper', 'lower'):
        res['cracks'][s]['angle_near_deg'] = near['cracks'][s]['angle_deg']
        res['cracks'][s]['angle_near_range'] = [3 * res['dx'], a.angle_near]
    cm.write_outputs(res, p + '.crack')
    cm.plot_speed(res, p + '.speed.png', rayleigh=RAYLEIGH,
                  title=f'Kalthoff-Winkler 2D {a.label}'.strip())
    tend = res['time'][-1]
    times = [t * 1e-6 for t in (20, 35, 50, 65, 80, 95, 110) if t * 1e-6 <= tend + 1e-6]
    cm.montage(p + '.dump', p + '.montage.png', times=times, ncols=4, panel_width=3.0,
               title=f'damage phi, Kalthoff-Winkler 2D {a.label}'.strip())
    U, L = res['cracks']['upper'], res['cracks']['lower']
    sym = res['symmetry']

    def f(v, fmt):
        return 'n/a' if v is None else format(v, fmt)

    def edge(c):
        if c['target_reached_time'] is None:
            tip = c['tip_final']
            return f"no (tip at {tip[0] * 1e3:.0f}, {tip[1] * 1e3:.0f} mm)" if tip else 'no crack'
        e = min(c['edge_reached_time'], key=c['edge_reached_time'].get)
        return f"{us(c['target_reached_time'])} ({e})"

    th = A.THESIS_KW_ANGLES.value
    exp = f'~{A.EXP_KW_ANGLE.value:g} deg'
    rows = [
        ('crack angle to the impact direction, whole crack', f(U['angle_deg'], '.1f') + ' deg',
         f(L['angle_deg'], '.1f') + ' deg', f'{th[1.0]:g} deg (1.67 mm: {th[1.67]:g})', exp),
        (f'initial kink angle (fit within {a.angle_near * 1e3:.0f} mm of the tip)',
         f(U['angle_near_deg'], '.1f') + ' deg', f(L['angle_near_deg'], '.1f') + ' deg', '-', exp),
        ('initiation time', us(U['initiation_time']), us(L['initiation_time']),
         f'{A.us(A.THESIS_KW_INITIATION.value)} (1.67 mm: {A.THESIS_KW_INITIATION_COARSE.value * 1e6:g})',
         '-'),
        ('time to reach a plate edge', edge(U), edge(L),
         f'{A.us(A.THESIS_KW_EDGE.value)} (1.67 mm: {A.THESIS_KW_EDGE_COARSE.value * 1e6:g}, far edge)',
         '-'),
        ('peak crack speed', f(U['speed_max'], '.0f') + ' m/s', f(L['speed_max'], '.0f') + ' m/s',
         f'{A.THESIS_KW_SPEED.value:.0f} m/s', f'< Rayleigh {RAYLEIGH:.0f} m/s'),
        ('branches / short side branches', f"{U['branches_max_persistent']} / {U['side_branches_max']}",
         f"{L['branches_max_persistent']} / {L['side_branches_max']}", '1 / 0', '1'),
        ('final crack length (chord from the notch tip)', f(U['length_final'] * 1e3, '.1f') + ' mm',
         f(L['length_final'] * 1e3, '.1f') + ' mm', '-', '-'),
    ]
    hdr = ('quantity', 'upper crack', 'lower crack', 'thesis (2D, dx = 1 mm)', 'experiment')
    w = [max(len(r[i]) for r in rows + [hdr]) for i in range(5)]
    out = [f'Kalthoff-Winkler 2D {a.label}: {p}',
           f'code: {git_rev()}, binary md5 '
           + (open(p + '.binary').read().split()[0][:12] if os.path.exists(p + '.binary') else '?'),
           f"pair_style tlsph/damage {info.get('pair_style', '?')}",
           f"velocity filter {info.get('filter', '?')}, s_c = {info.get('sc', float('nan')):.4g}, "
           f"dx = {res['dx'] * 1e3:.3g} mm",
           f"particles {info.get('atoms', res['n_particles'])}, steps {info.get('steps')}, "
           f"simulated {tend * 1e6:.1f} us, loop time {info.get('loop_s', float('nan')):.0f} s, "
           f"wall time {info.get('wall_s', '?')} s on {info.get('procs', 1)} MPI rank(s) (shared machine)",
           f"crack_measure: phi >= {a.threshold}, speed window {a.window * 1e6:g} us, "
           f"angle to +x (impact direction), fitted from 3 dx (initial) / 5 dx (whole) from the notch tip",
           *([f"LAMMPS STOPPED: {info['error']}"] if 'error' in info else []),
           '',
           '  '.join(h.ljust(w[i]) for i, h in enumerate(hdr)),
           '  '.join('-' * w[i] for i in range(5))]
    out += ['  '.join(v.ljust(w[i]) for i, v in enumerate(r)) for r in rows]
    out.append('')
    out.append('symmetry (lower crack mirrored about y = 0): initiation difference '
               f"{f(sym['initiation_time_diff'] and sym['initiation_time_diff'] * 1e6, '.2f')} us, angle difference "
               f"{f(sym['angle_diff_deg'], '.2f')} deg, final length difference "
               f"{f(sym['length_final_diff'] and sym['length_final_diff'] * 1e3, '.2f')} mm, largest tip distance "
               f"{f(sym['tip_mirror_distance_max'] * 1e3, '.2f')} mm")
    ri = res['regions']['under_impactor']
    re_ = res['regions']['impacted_edge_strip']
    out.append(f"under the impactor (x < 5 dx, |y| < 25 mm - 2 dx): max phi {max(ri['phi_max']):.3f}, "
               f"cracked (phi >= {a.threshold}) particles at most {ri['n_cracked_max']}, damaged "
               f"(phi > 0) at most {max(ri['n_damaged'])}")
    out.append(f"impacted-edge strip (x < 10 dx, all y): largest phi rise {re_['dphi_max_all']:.3f}, "
               f"newly damaged particles at most {max(re_['n_damaged'])}, cracked at most "
               f"{re_['n_cracked_max']}")
    out.append(f"cracked particles in neither crack (final / max): {res['other_cracked'][-1]} / "
               f"{max(res['other_cracked'])}")
    if 'energy_excess_max' in info:
        es, wf = info['energy_final']
        out.append(f"energy balance (thermo, every 2 us): strain + hourglass + viscous + kinetic energy (less the "
                   f"impactor's own, which fix move sets) at the "
                   f"end {es:.4g} J/m vs impactor work {wf:.4g} J/m; largest excess (E - W)/max W = "
                   f"{info['energy_excess_max']:+.3f} at {info['energy_excess_time'] * 1e6:.1f} us "
                   f"(must stay <= ~0: broken bonds only lose energy), first above +0.1 at "
                   f"{us(info['energy_onset_time'])}; kinetic energy max "
                   f"{info['ke_max'][0]:.4g} J/m at {info['ke_max'][1] * 1e6:.1f} us")
    if 'first_break_time' in info:
        out.append(f"first bond broken anywhere (other than the notch cuts): between "
                   f"{info['first_break_prev_time'] * 1e6:.1f} and {info['first_break_time'] * 1e6:.1f} us "
                   f"(thermo output)")
    out.append('')
    out.append('tool summary:')
    out.append(open(p + '.crack.txt').read().rstrip())
    txt = '\n'.join(out)
    print(txt)


if __name__ == '__main__':
    main()
