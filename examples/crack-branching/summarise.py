#!/usr/bin/env python3
"""Summary of a crack-branching run: the crack measured by tools/crack_measure.py
next to the thesis's numbers and the acceptance criteria of the benchmark
(both from examples/common/acceptance.py; the branching window 25-45 us is that
of issues 12 and 26).

  summarise.py PREFIX [--window S] [--threshold PHI] [--dx DX]

--dx DX (the run's particle spacing, m): the measurement lengths that the tool
counts in spacings (initiation length 3, branch gap 3, branch persistence 10)
are scaled so that they stay the physical lengths they are at the deck's
dx = 0.333 mm (1, 1 and 3.33 mm); for runs at other spacings.  Without it the
tool's defaults (in units of the spacing it measures from the dump) apply.

Reads PREFIX.dump and PREFIX.log; writes PREFIX.crack.{json,csv,txt} (the tool's
output), PREFIX.speed.png (tip speed, Rayleigh speed drawn), PREFIX.montage.png
(damage field at 10, 20, ... us) and prints the summary table.
"""
import argparse
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

RAYLEIGH = A.RAYLEIGH_GLASS.value      # m/s, plane strain (doc/references.rst)
DX_DECK = 0.1 / 300    # m, the deck's spacing


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('prefix')
    ap.add_argument('--window', type=float, default=3e-6)
    ap.add_argument('--threshold', type=float, default=0.3)
    ap.add_argument('--label', default='')
    ap.add_argument('--dx', type=float, default=None)
    a = ap.parse_args()
    p = a.prefix
    info = log_info(p + '.log')
    lengths = {}
    if a.dx:
        k = DX_DECK / a.dx
        lengths = dict(dx=a.dx, init_length=cm.DEFAULTS['init_length'] * k,
                       gap=cm.DEFAULTS['gap'] * k,
                       branch_min_length=cm.DEFAULTS['branch_min_length'] * k)
    res = cm.analyse(cm.read_dump(p + '.dump'), [cm.Seed('crack', 0.05, 0.02, 0.0)],
                     target_edges={'crack': 'xmax'}, threshold=a.threshold, window=a.window,
                     tip='projection',
                     regions={'top_row': (-1, 1, 0.0395, 1), 'bottom_row': (-1, 1, -1, 0.0005)},
                     **lengths)
    cm.write_outputs(res, p + '.crack')
    cm.plot_speed(res, p + '.speed.png', rayleigh=RAYLEIGH,
                  title=f'crack branching {a.label}'.strip())
    tend = res['time'][-1]
    times = [t * 1e-6 for t in range(10, int(tend * 1e6) + 1, 10)]
    cm.montage(p + '.dump', p + '.montage.png', times=times, ncols=2, vmax=1.0,
               title=f'damage phi, crack branching {a.label}'.strip())
    c = res['cracks']['crack']
    ini, br, vmax = c['initiation_time'], c['branching_time'], c['speed_max']
    nfin, side = c['branches_final'], c['side_branches_max']
    other = max(res['other_cracked'])
    edge2 = c.get('two_branches_at_target_time')
    nat = c.get('branches_at_target_final', 0)
    rows = []

    def row(q, meas, thesis, crit, ok):
        rows.append((q, meas, thesis, crit, '-' if ok is None else ('yes' if ok else 'NO')))

    t0, t1 = A.BR_WINDOW.value
    row('crack initiation', us(ini), f'~{A.us(A.THESIS_BR_INITIATION.value)}',
        f'< {A.us(A.BR_INITIATION_BEFORE.value)}',
        ini is not None and ini < A.BR_INITIATION_BEFORE.value)
    row('branching time (persistent 2 branches)', us(br) + (f' (detected {us(c["branching_detected_time"])})'
                                                             if br is not None else ''),
        f'~{A.us(A.THESIS_BR_BRANCHING.value)}', f'{t0 * 1e6:g} .. {t1 * 1e6:g} us',
        A.in_band(br, A.BR_WINDOW))
    nb = A.BR_MAIN_BRANCHES.value
    row('main branches at the end', f'{nfin} (max {c["branches_max_persistent"]})', str(nb), str(nb),
        nfin == nb and c['branches_max_persistent'] == nb)
    row('max tip speed', 'n/a' if vmax is None else f'{vmax:.0f} m/s at {us(c["speed_max_time"])}',
        '< Rayleigh', f'<= {RAYLEIGH:.0f} m/s', vmax is not None and vmax <= RAYLEIGH)
    row('spurious branches / damage off the crack',
        f'{side} short side branches, {other} cracked particles off the crack',
        'none', 'none', side == 0 and other == 0 and c['branches_max_persistent'] <= nb)
    row('both branches reach the right edge',
        (f'yes, at {us(edge2)}' if edge2 is not None else
         f'no: {nat} branch(es) there; the crack (one tip) reached it at {us(c["target_reached_time"])}'
         if c['target_reached_time'] is not None else
         f'no ({nat} branch(es) at x = 100 mm; crack tip at x = '
         f'{c["tip_final"][0] * 1e3:.1f} mm at {us(tend)})' if c['tip_final'] else 'no'),
        A.us(A.THESIS_BR_EDGE.value), 'yes', edge2 is not None)
    lines = []
    lines.append(f'crack branching {a.label}: {p}')
    lines.append(f'code: {git_rev()}, binary md5 '
                 + (open(p + '.binary').read().split()[0][:12] if os.path.exists(p + '.binary') else '?'))
    lines.append(f"pair_style tlsph/damage {info.get('pair_style', '?')}")
    lines.append(f"velocity filter {info.get('filter', '?')}, s_c = {info.get('sc', float('nan')):.4g}")
    lines.append(f"particles {info.get('atoms', res['n_particles'])}, steps {info.get('steps')}, "
                 f"simulated {tend * 1e6:.1f} us, loop time {info.get('loop_s', float('nan')):.0f} s, "
                 f"wall time {info.get('wall_s', '?')} s on {info.get('procs', 1)} MPI rank(s) "
                 f"(shared machine)")
    if 'error' in info:
        lines.append(f"LAMMPS STOPPED: {info['error']}")
    if lengths:
        lines.append(f"lengths at dx = {a.dx * 1e3:.4g} mm: initiation {lengths['init_length']:.3g} dx, "
                     f"branch gap {lengths['gap']:.3g} dx, persistence {lengths['branch_min_length']:.3g} dx "
                     f"(= 1, 1, 3.33 mm)")
    lines.append(f"crack_measure: phi >= {a.threshold}, speed window {a.window * 1e6:g} us, "
                 f"dump every {(res['time'][2] - res['time'][1]) * 1e6:.2f} us")
    lines.append('')
    w = [max(len(r[i]) for r in rows + [('quantity', 'measured', 'thesis', 'acceptance', 'met')])
         for i in range(5)]
    hdr = ('quantity', 'measured', 'thesis', 'acceptance', 'met')
    lines.append('  '.join(h.ljust(w[i]) for i, h in enumerate(hdr)))
    lines.append('  '.join('-' * w[i] for i in range(5)))
    for r in rows:
        lines.append('  '.join(v.ljust(w[i]) for i, v in enumerate(r)))
    lines.append('')
    lines.append(f"final crack tip {c['tip_final']}, length {c['length_final'] * 1e3:.1f} mm from the "
                 f"pre-crack tip; branches at the end: "
                 + ('; '.join(f"tip {b['tip']}, angle {b['angle_deg']:.0f} deg, edges {b['edges']}"
                              for b in c['branches_at_end']) or 'none'))
    mean_v = None
    if ini is not None and c['tip_final'] is not None and tend > ini:
        mean_v = c['length_final'] / (tend - ini)
        lines.append(f'mean tip speed from initiation to the end: {mean_v:.0f} m/s')
    if 'energy_excess_max' in info:
        es, wf = info['energy_final']
        lines.append(f"energy balance (thermo, every 1 us): strain + hourglass + viscous + kinetic energy at "
                     f"the end {es:.4g} J/m vs traction work {wf:.4g} J/m; largest excess (E - W)/max W = "
                     f"{info['energy_excess_max']:+.3f} at {info['energy_excess_time'] * 1e6:.1f} us "
                     f"(must stay <= ~0: broken bonds only lose energy), first above +0.1 at "
                     f"{us(info['energy_onset_time'])}")
    if 'first_break_time' in info:
        lines.append(f"first bond broken (other than the pre-crack's): between "
                     f"{info['first_break_prev_time'] * 1e6:.1f} and {info['first_break_time'] * 1e6:.1f} us "
                     f"(thermo output)")
    lines.append('')
    lines.append('tool summary:')
    lines.append(open(p + '.crack.txt').read().rstrip())
    txt = '\n'.join(lines)
    print(txt)
    return txt


if __name__ == '__main__':
    main()
