#!/usr/bin/env python3
"""The sampling constants of the tips' K, scanned on the relaxed fields of
bench/kcheck.sh (its dumps: reference and final positions): for each dump,
the two tips' samples as PairTLSPHDamage::grow_tips takes them (kernel means
(1 - d^2/rho^2)^2 over the disc of radius rho about each sample point, one
per face, at r = r0 + 0.5 h k, k = 0..3, behind the tip), with the sample
start r0 and the disc radius rho each varied by a factor of two around the
model's values (1.5 h, 1.5 h), and both fits (tlsph_crack.h: kfit tip, kfit
offset, re-implemented here). Prints a Markdown table of K / reference.
Plain Python: python3 kcheck_scan.py OUTDIR DX... (dumps OUTDIR/d0-MODE-DX.txt,
OUTDIR/d1-MODE-DX.txt)."""
import math
import sys

A_HALF, W, LOAD, E, NU = 0.005, 0.08, 1.0e6, 32e9, 0.2
EP = E / (1 - NU * NU)
lam = A_HALF / (W / 2)
F = (1 - 0.025 * lam ** 2 + 0.06 * lam ** 4) * math.sqrt(1 / math.cos(math.pi * lam / 2))
K0 = LOAD * math.sqrt(math.pi * A_HALF) * F


def load(p):
    L = open(p).read().splitlines()
    k = next(i for i, l in enumerate(L) if l.startswith("ITEM: ATOMS"))
    return {int(l.split()[0]): [float(v) for v in l.split()[1:3]] for l in L[k + 1:] if l.strip()}


def fit_tip(r, j):
    n = len(r)
    y = [v / math.sqrt(x) for v, x in zip(j, r)]
    sr, sr2, sy, sry = sum(r), sum(x * x for x in r), sum(y), sum(x * v for x, v in zip(r, y))
    c1 = (sr2 * sy - sr * sry) / (n * sr2 - sr * sr)
    return EP / 8 * math.sqrt(2 * math.pi) * c1


def fit_offset(r, j):
    # j^2 = A r + B + C r^2 (normal equations)
    rows = [[1.0, x, x * x] for x in r]
    y = [v * v for v in j]
    M = [[sum(a[p] * a[q] for a in rows) for q in range(3)] for p in range(3)]
    b = [sum(a[p] * v for a, v in zip(rows, y)) for p in range(3)]
    for i in range(3):
        for k in range(i + 1, 3):
            f = M[k][i] / M[i][i]
            for c in range(i, 3):
                M[k][c] -= f * M[i][c]
            b[k] -= f * b[i]
    x = [0.0] * 3
    for i in reversed(range(3)):
        x[i] = (b[i] - sum(M[i][c] * x[c] for c in range(i + 1, 3))) / M[i][i]
    A = x[1]
    return EP * math.sqrt(math.pi * A / 32) * (1 if sum(j) > 0 else -1) if A > 0 else 0.0


def tip_k(pts, mode, h, r0, rho, fit):
    ks = []
    for sgn in (1, -1):    # the tips at (+a, 0) (path +x) and (-a, 0) (path -x)
        tx = float(sgn)
        rr, jj = [], []
        for k in range(4):
            r = r0 + 0.5 * h * k
            qx = sgn * (A_HALF - r)
            s = {1: [0.0, 0.0, 0.0], -1: [0.0, 0.0, 0.0]}
            for (X, Y, ux, uy) in pts:
                d2 = (X - qx) ** 2 + Y * Y
                if d2 >= rho * rho:
                    continue
                dn = tx * Y    # n = t rotated by +90 deg
                if dn == 0.0:
                    continue
                w = (1 - d2 / rho ** 2) ** 2
                S = s[1 if dn > 0 else -1]
                S[0] += w
                S[1] += w * ux
                S[2] += w * uy
            if s[1][0] <= 0 or s[-1][0] <= 0:
                continue
            dux = s[1][1] / s[1][0] - s[-1][1] / s[-1][0]
            duy = s[1][2] / s[1][0] - s[-1][2] / s[-1][0]
            jn, jt = tx * duy, tx * dux
            rr.append(r)
            jj.append(jn if mode == "I" else jt)
        ks.append(abs(fit(rr, jj)))
    return 0.5 * (ks[0] + ks[1])


out, dxs = sys.argv[1], sys.argv[2:]
print("| mode | dx [mm] | fit | sample start r0 / h | disc radius / h | K / reference |")
print("|---|---:|---|---:|---:|---:|")
for mode in ("I", "II"):
    for dx in dxs:
        try:
            d0, d1 = load("%s/d0-%s-%s.txt" % (out, mode, dx)), load("%s/d1-%s-%s.txt" % (out, mode, dx))
        except OSError:
            continue
        pts = [(d0[i][0], d0[i][1], d1[i][0] - d0[i][0], d1[i][1] - d0[i][1]) for i in d0]
        h = 1.33 * float(dx)
        for fname, fit in (("tip", fit_tip), ("offset", fit_offset)):
            for r0 in (0.75, 1.5, 3.0):
                for rho in (0.75, 1.5, 3.0):
                    k = tip_k(pts, mode, h, r0 * h, rho * h, fit)
                    mark = " (the model's)" if (r0, rho) == (1.5, 1.5) else ""
                    print("| %s | %.3f | %s | %.2f | %.2f%s | %.4f |" % (mode, 1e3 * float(dx), fname, r0, rho, mark, k / K0))
