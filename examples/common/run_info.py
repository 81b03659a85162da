"""Run information shared by the fracture examples' summary scripts: what the
LAMMPS log says about a run (loop and wall time, s_c, pair_style line) and
which commit produced it."""

import os
import re
import subprocess

# examples/common: '../../src' is the package source, as from an example folder
here = os.path.dirname(os.path.abspath(__file__))


def log_info(path):
    txt = open(path).read()
    info = {}
    m = re.findall(r'^Loop time of ([0-9.eE+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms', txt, re.M)
    if m:
        info['loop_s'] = float(m[-1][0]); info['procs'] = int(m[-1][1])
        info['steps'] = int(m[-1][2]); info['atoms'] = int(m[-1][3])
    m = re.search(r'^Total wall time: (\d+):(\d+):(\d+)', txt, re.M)
    if m:
        info['wall_s'] = int(m.group(1)) * 3600 + int(m.group(2)) * 60 + int(m.group(3))
    m = re.search(r'critical stretch s_c = ([0-9.eE+-]+)', txt)
    if m:
        info['sc'] = float(m.group(1))
    # LAMMPS echoes each input line, then again with the variables substituted
    m = [v for v in re.findall(r'^pair_style\s+tlsph/damage (.*)$', txt, re.M) if '$' not in v]
    if m:
        info['pair_style'] = ' '.join(m[-1].split())
    m = [v for v in re.findall(r'^\s*fix\s+filt\s+\S+\s+tlsph/velocity/filter\s+(\S+\s+\S+)', txt, re.M)
         if '$' not in v]
    if m:
        info['filter'] = m[-1]
    m = re.search(r'^ERROR.*$', txt, re.M)
    if m:
        info['error'] = m.group(0).strip()
        for k in ('loop_s', 'steps', 'wall_s'):   # those were of an earlier run (run 0)
            info.pop(k, None)
    # thermo block of the main run (the one with v_broken): columns by name
    lines = txt.splitlines()
    th = None
    for k, ln in enumerate(lines):
        cols = ln.split()
        if cols[:2] == ['Step', 'Time'] and 'v_broken' in cols:
            rows = []
            for row in lines[k + 1:]:
                v = row.split()
                if len(v) != len(cols):
                    break
                try:
                    rows.append([float(x) for x in v])
                except ValueError:
                    break
            if rows:
                th = {c: [r[i] for r in rows] for i, c in enumerate(cols)}
    info['thermo'] = th
    if th:
        info.setdefault('steps', int(th['Step'][-1]))
        # the first output time at which more bonds are broken than at step 0 (the
        # bonds cut by the pre-crack count as broken from the start)
        b = th['v_broken']
        for i in range(1, len(b)):
            if b[i] > b[0]:
                info['first_break_time'] = th['Time'][i]
                info['first_break_prev_time'] = th['Time'][i - 1]
                break
        if 'v_esum' in th and 'v_W' in th:
            wmax = max(abs(w) for w in th['v_W']) or 1.0
            ex = [(e - w) / wmax for e, w in zip(th['v_esum'], th['v_W'])]
            i = max(range(len(ex)), key=lambda j: ex[j])
            info['energy_excess_max'] = ex[i]
            info['energy_excess_time'] = th['Time'][i]
            info['energy_final'] = (th['v_esum'][-1], th['v_W'][-1])
            on = [j for j in range(len(ex)) if ex[j] > 0.1]
            info['energy_onset_time'] = th['Time'][on[0]] if on else None
            ke = th['c_e[4]']
            j = max(range(len(ke)), key=lambda q: ke[q])
            info['ke_max'] = (ke[j], th['Time'][j])
    return info


def git_rev():
    try:
        r = subprocess.run(['git', '-C', here, 'log', '-1', '--format=%h %ci'], capture_output=True,
                           text=True, timeout=10)
        d = subprocess.run(['git', '-C', here, 'status', '--short', '--', '../../src'],
                           capture_output=True, text=True, timeout=10)
        return r.stdout.strip() + (' (src modified)' if d.stdout.strip() else '')
    except Exception:
        return 'unknown'


def runs_code(folders):
    """The code the runs in these folders were made with: the 'code:' line
    (git_rev, through the summary scripts) of each summary-*.txt, counted,
    as 'CODE (N runs); ...'; 'unknown' when there is none."""
    codes = {}
    for d in folders:
        for f in sorted(os.listdir(d)) if os.path.isdir(d) else []:
            if f.startswith('summary-') and f.endswith('.txt'):
                for ln in open(os.path.join(d, f)):
                    if ln.startswith('code: '):
                        codes[ln[6:].strip()] = codes.get(ln[6:].strip(), 0) + 1
                        break
    return '; '.join(f'{k} ({n} runs)' for k, n in sorted(codes.items())) or 'unknown'


def us(v):
    return 'n/a' if v is None else f'{v * 1e6:.1f} us'
