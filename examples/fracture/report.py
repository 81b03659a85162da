#!/usr/bin/env python3
"""The main job's numbers: extracted from a `make run`, as a table, into README.

    report.py extract BRANCHING_PREFIX KALTHOFF_PREFIX -o results.json
    report.py table results.json            the markdown table (stdout)
    report.py write README.md results.json  the table between README's markers
    report.py check README.md results.json  exit 1 if README's table differs

`extract` reads each run's crack measurement (PREFIX.crack.json, written by
the examples' summarise.py with tools/crack_measure.py) and its LAMMPS log
(PREFIX.log) and keeps the few numbers the README shows, the model's
pair_style line, the particles, steps and times, and the commit the run was
made from (examples/common/run_info.git_rev, which says '-dirty' for a
modified tree). The acceptance bands and the thesis's numbers come from
examples/common/acceptance.py. README's table lies between the lines
<!-- make-run:begin --> and <!-- make-run:end -->; ctest
examples.fracture.readme fails when it is not what `table` makes of the
committed examples/fracture/results.json.
"""
import json
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, '..', 'common'))
import acceptance as A  # noqa: E402
from run_info import git_rev, log_info  # noqa: E402

BEGIN = '<!-- make-run:begin -->'
END = '<!-- make-run:end -->'


def _run(prefix):
    c = json.load(open(prefix + '.crack.json'))
    info = log_info(prefix + '.log')
    return c, {k: info.get(k) for k in ('pair_style', 'filter', 'atoms', 'steps', 'loop_s',
                                        'wall_s', 'procs', 'error')}


def _code(prefix):
    """the commit the run's summary names (summarise.py's 'code:' line, written
    when the run was measured), or None"""
    d, n = os.path.split(prefix)
    try:
        for line in open(os.path.join(d, f'summary-{n}.txt')):
            if line.startswith('code: '):
                return line[6:].split(', binary')[0].strip()
    except OSError:
        pass
    return None


def extract(bprefix, kprefix):
    bc, binfo = _run(bprefix)
    kc, kinfo = _run(kprefix)
    b = bc['cracks']['crack']
    br = dict(binfo, initiation_time=b['initiation_time'], branching_time=b['branching_time'],
              branches_final=b['branches_final'], branches_max=b['branches_max_persistent'],
              side_branches_max=b['side_branches_max'], speed_max=b['speed_max'],
              both_at_edge_time=b.get('two_branches_at_target_time'),
              branch_angles=[round(x['angle_deg'], 1) for x in b['branches_at_end']],
              other_cracked_max=max(bc['other_cracked']), tend=bc['time'][-1])
    up, lo = kc['cracks']['upper'], kc['cracks']['lower']
    reg = kc.get('regions', {})
    kw = dict(kinfo, angle_upper=up['angle_deg'], angle_lower=lo['angle_deg'],
              initiation_time=up['initiation_time'], speed_max=max(up['speed_max'], lo['speed_max']),
              edge_time=up['target_reached_time'], side_branches_max=max(up['side_branches_max'],
                                                                       lo['side_branches_max']),
              mirror_angle_diff=(kc.get('symmetry') or {}).get('angle_diff_deg'),
              impactor_cracked_max=(reg.get('under_impactor') or {}).get('n_cracked_max'),
              tend=kc['time'][-1])
    return dict(code=_code(bprefix) or git_rev(), branching=br, kalthoff=kw)


def _us(v):
    return 'n/a' if v is None else f'{v * 1e6:.1f} us'


def _band_us(r):
    lo, hi = r.value
    return f'{lo * 1e6:g}-{hi * 1e6:g} us'


def _yes(ok):
    return 'yes' if ok else '**no**'


def table(res):
    b, k = res['branching'], res['kalthoff']
    lo, hi = A.KW_ANGLE_BAND.value
    rows = [
        ('Crack branching, glass, 1 MPa, dx = 0.333 mm', '', '', '', ''),
        ('initiation', _us(b['initiation_time']), f"~{A.THESIS_BR_INITIATION.value * 1e6:g} us",
         f"< {A.BR_INITIATION_BEFORE.value * 1e6:g} us",
         _yes(b['initiation_time'] is not None and b['initiation_time'] < A.BR_INITIATION_BEFORE.value)),
        ('branching (two persistent branches)', _us(b['branching_time']),
         f"~{A.THESIS_BR_BRANCHING.value * 1e6:g} us", _band_us(A.BR_WINDOW),
         _yes(A.in_band(b['branching_time'], A.BR_WINDOW))),
        ('main branches at the end / side branches',
         f"{b['branches_final']} / {b['side_branches_max']}", '2 / 0', '2 / 0',
         _yes(b['branches_final'] == A.BR_MAIN_BRANCHES.value and b['branches_max'] == 2
              and b['side_branches_max'] == 0 and b['other_cracked_max'] == 0)),
        ('both branches at the right edge', _us(b['both_at_edge_time']),
         f"{A.THESIS_BR_EDGE.value * 1e6:g} us", 'yes', _yes(b['both_at_edge_time'] is not None)),
        ('peak tip speed', f"{b['speed_max']:.0f} m/s", '-',
         f"<= {A.RAYLEIGH_GLASS.value:.0f} m/s (Rayleigh)",
         _yes(b['speed_max'] <= A.RAYLEIGH_GLASS.value)),
        ('Kalthoff-Winkler 2D, 16.5 m/s, dx = 1 mm', '', '', '', ''),
        ('crack angle to the impact (upper / lower)',
         f"{k['angle_upper']:.3f} / {k['angle_lower']:.3f} deg",
         f"{A.THESIS_KW_ANGLE.value:g} deg (experiment ~{A.EXP_KW_ANGLE.value:g})",
         f"{lo:g}-{hi:g} deg",
         _yes(A.in_band(k['angle_upper'], A.KW_ANGLE_BAND) and A.in_band(k['angle_lower'], A.KW_ANGLE_BAND))),
        ('initiation', _us(k['initiation_time']), f"{A.THESIS_KW_INITIATION.value * 1e6:g} us", '-', '-'),
        ('side edges reached', _us(k['edge_time']), f"{A.THESIS_KW_EDGE.value * 1e6:g} us", '-', '-'),
        ('peak tip speed', f"{k['speed_max']:.0f} m/s", f"{A.THESIS_KW_SPEED.value:.0f} m/s",
         f"< {A.RAYLEIGH_STEEL.value:.0f} m/s (Rayleigh)", _yes(k['speed_max'] < A.RAYLEIGH_STEEL.value)),
        ('cracking under the impactor / side branches',
         f"{k['impactor_cracked_max']} / {k['side_branches_max']}", 'none', 'none',
         _yes(k['impactor_cracked_max'] == 0 and k['side_branches_max'] == 0)),
    ]
    out = ['| quantity | measured | thesis | acceptance | met |', '|---|---|---|---|---|']
    for r in rows:
        if not r[1]:
            out.append(f'| **{r[0]}** | | | | |')
        else:
            out.append('| ' + ' | '.join(r) + ' |')
    out.append('')
    out.append(f"Made by `make run` from commit {res['code']}: {b['atoms']} and {k['atoms']} particles, "
               f"{b['steps']} and {k['steps']} steps, loop times {b['loop_s']:.0f} s and "
               f"{k['loop_s']:.0f} s on one MPI rank of a shared 2-core machine "
               f"(examples/fracture/results.json; regenerate with examples/fracture/report.py).")
    return '\n'.join(out)


def _block(text):
    i, j = text.find(BEGIN), text.find(END)
    if i < 0 or j < i:
        return None, None, None
    return text[:i + len(BEGIN)], text[i + len(BEGIN):j], text[j:]


def main(argv):
    if len(argv) >= 1 and argv[0] == 'extract':
        out = 'results.json'
        args = argv[1:]
        if '-o' in args:
            k = args.index('-o')
            out = args[k + 1]
            args = args[:k] + args[k + 2:]
        if len(args) != 2:
            print(__doc__)
            return 2
        res = extract(*args)
        with open(out, 'w') as f:
            json.dump(res, f, indent=1, sort_keys=True)
            f.write('\n')
        print('wrote', out)
        return 0
    if len(argv) == 2 and argv[0] == 'table':
        print(table(json.load(open(argv[1]))))
        return 0
    if len(argv) == 3 and argv[0] in ('write', 'check'):
        text = open(argv[1]).read()
        head, old, tail = _block(text)
        if head is None:
            print(f'FAILED: {argv[1]} has no {BEGIN} ... {END} block')
            return 1
        new = '\n' + table(json.load(open(argv[2]))) + '\n'
        if argv[0] == 'write':
            open(argv[1], 'w').write(head + new + tail)
            print('wrote the make-run table into', argv[1])
            return 0
        if old != new:
            print(f'FAILED: the make-run table in {argv[1]} is not what report.py makes of {argv[2]}'
                  ' (run: examples/fracture/report.py write README.md examples/fracture/results.json)')
            return 1
        res = json.load(open(argv[2]))
        if 'modified' in res['code'] or 'dirty' in res['code']:
            print(f"FAILED: {argv[2]} was made from modified code ({res['code']})")
            return 1
        print(f'PASSED: README make-run table matches {argv[2]} (commit {res["code"]})')
        return 0
    print(__doc__)
    return 2


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
