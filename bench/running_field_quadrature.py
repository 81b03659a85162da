#!/usr/bin/env python3
"""An independent check of tlsph_crack.h's running_ratio_factors (ctest
physics.CrackTip.RunningRatioFactors quotes its numbers at 0.6 c_R).

Freund's steady running-crack field is built here another way than in the
header: the coefficients a, b of F'' = a z_d^-1/2, G'' = b z_s^-1/2 are
solved numerically from traction-free faces and K = 1 (not taken from the
closed forms), and the interaction integral with Williams's static field (the
same potentials at v -> 0) is summed by the midpoint rule over 4000 angles
(not Gauss-Legendre). Printed per v / c_R: the static-auxiliary factors f_I,
f_II and their ratio, the faces' jump ratio (a_s / a_d) and the dynamic J of
mode I against Freund's A_I. Plane strain, mu = rho = 1 (c_s = 1).

    python3 bench/running_field_quadrature.py [nu]      (default 0.3)
Needs numpy.
"""
import sys
import numpy as np


def field(v, nu, mode):
    cd = np.sqrt(2 * (1 - nu) / (1 - 2 * nu))
    ad, as_ = np.sqrt(1 - v * v / cd ** 2), np.sqrt(1 - v * v)
    lam = cd ** 2 - 2.0

    def at(a, b, x1, x2):
        F = a / np.sqrt(x1 + 1j * ad * x2)
        G = b / np.sqrt(x1 + 1j * as_ * x2)
        H = np.array([[F.real + as_ * G.real, -ad * F.imag - as_ ** 2 * G.imag],
                      [-ad * F.imag - G.imag, -ad ** 2 * F.real - as_ * G.real]])
        tr = H[0, 0] + H[1, 1]
        S = np.array([[lam * tr + 2 * H[0, 0], H[0, 1] + H[1, 0]],
                      [H[0, 1] + H[1, 0], lam * tr + 2 * H[1, 1]]])
        F1, G1 = 2 * a * np.sqrt(x1 + 1j * ad * x2), 2 * b * np.sqrt(x1 + 1j * as_ * x2)
        u = np.array([F1.real + as_ * G1.real, -ad * F1.imag - G1.imag])
        return H, S, u

    def conds(p):
        a, b = p[0] + 1j * p[1], p[2] + 1j * p[3]
        _, Sf, _ = at(a, b, -1.0, 1e-14)
        _, Sa, _ = at(a, b, 1.0, 0.0)
        return np.array([Sf[1, 1], Sf[0, 1], Sa[1, 1], Sa[0, 1]])

    M = np.array([conds(e) for e in np.eye(4)]).T
    rhs = np.zeros(4)
    rhs[2 + mode] = 1 / np.sqrt(2 * np.pi)
    p = np.linalg.solve(M, rhs)
    a, b = p[0] + 1j * p[1], p[2] + 1j * p[3]
    return lambda x1, x2: at(a, b, x1, x2)


def interaction(act, aux, v=0.0, n=4000, kinetic=False):
    s = 0.0
    for t in -np.pi + (np.arange(n) + 0.5) * 2 * np.pi / n:
        nv = np.array([np.cos(t), np.sin(t)])
        H, S, _ = act(*nv)
        Ha, Sa, _ = aux(*nv)
        w = np.sum(Sa * H) + (v * v * (H[:, 0] @ Ha[:, 0]) if kinetic else 0.0)
        s += w * nv[0] - (S * Ha[:, 0][:, None]).sum(axis=0) @ nv - (Sa * H[:, 0][:, None]).sum(axis=0) @ nv
    return s * 2 * np.pi / n


def main():
    nu = float(sys.argv[1]) if len(sys.argv) > 1 else 0.3
    cd = np.sqrt(2 * (1 - nu) / (1 - 2 * nu))
    D = lambda v: 4 * np.sqrt(1 - v * v / cd ** 2) * np.sqrt(1 - v * v) - (2 - v * v) ** 2  # noqa: E731
    lo, hi = 0.5, 0.999    # Rayleigh speed by bisection (D < 0 below it, > 0 above, in this sign)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if D(mid) * D(lo) > 0 else (lo, mid)
    cR = 0.5 * (lo + hi)
    Ep2 = 1.0 / (1 - nu)    # E' / 2 with mu = 1 (plane strain)
    stat = [field(1e-4, nu, m) for m in (0, 1)]
    print(f"nu = {nu}, c_R = {cR:.6f} c_s")
    print(" v/c_R    f_I     f_II   f_II/f_I  faces a_s/a_d  J_dyn E'/K^2  A_I")
    for f in (0.2, 0.4, 0.5, 0.6, 0.7, 0.8):
        v = f * cR
        run = [field(v, nu, m) for m in (0, 1)]
        fI, fII = Ep2 * interaction(run[0], stat[0]), Ep2 * interaction(run[1], stat[1])
        jump = []
        for m, c in ((0, 1), (1, 0)):
            up, dn = run[m](-1.0, 1e-12)[2], run[m](-1.0, -1e-12)[2]
            us, ds = stat[m](-1.0, 1e-12)[2], stat[m](-1.0, -1e-12)[2]
            jump.append((up[c] - dn[c]) / (us[c] - ds[c]))
        ad, as_ = np.sqrt(1 - v * v / cd ** 2), np.sqrt(1 - v * v)
        AI = v * v * ad / ((1 - nu) * (4 * ad * as_ - (1 + as_ ** 2) ** 2))
        jd = Ep2 * interaction(run[0], run[0], v, kinetic=True)    # the field with itself: 2 J
        print(f" {f:4.2f}  {fI:7.4f}  {fII:7.4f}  {fII / fI:7.4f}  {jump[1] / jump[0]:9.4f}"
              f"  {jd:12.4f}  {AI:7.4f}")


if __name__ == "__main__":
    main()
