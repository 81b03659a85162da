"""Cantilever under a tip dead load of fixed direction: exact elastica and
linear beam theory (Euler-Bernoulli, Timoshenko shear term).

Elastica (inextensible, unshearable, M = E'I kappa), clamped at s = 0, load P
perpendicular to the undeformed axis at the tip s = L. With theta the slope
angle and arc length s in units of L:

    theta'' = -alpha cos(theta),  theta(0) = 0,  theta'(1) = 0,
    alpha = P L^2 / (E' I).

Two independent evaluations:
  * shooting: RK integration of the ODE and root-finding on theta'(0);
  * quadrature of the first integral theta'^2 = 2 alpha (sin theta_0 - sin theta)
    (the elliptic-integral solution of Bisshopp & Drucker 1945), with
    theta_0 the tip angle fixed by the arc-length condition.

Run `python3 elastica.py` for the self-test against the reference table
(doc/references.rst, "Large-deflection cantilever") and a small table.
"""

import math
import warnings

from scipy.integrate import IntegrationWarning, quad, solve_ivp
from scipy.optimize import brentq

# doc/references.rst, Bisshopp & Drucker: alpha -> (tip angle deg, v/L, u/L)
REFERENCE = {1.0: (26.434, 0.30172, 0.05643), 10.0: (81.949, 0.81061, 0.55500)}


def _shoot(alpha, k, dense=False):
    """Integrate theta'' = -alpha cos theta from s = 0 with theta'(0) = k.
    State: theta, theta', x, y (x, y in units of L)."""

    def rhs(s, z):
        th, dth = z[0], z[1]
        return [dth, -alpha * math.cos(th), math.cos(th), math.sin(th)]

    return solve_ivp(rhs, (0.0, 1.0), [0.0, k, 0.0, 0.0], method="DOP853", rtol=1e-12,
                     atol=1e-14, dense_output=dense)


def elastica_shooting(alpha):
    """(tip angle [rad], v/L, u/L) by shooting; v: deflection along the load,
    u: retreat of the tip towards the clamp."""
    if alpha == 0.0:
        return 0.0, 0.0, 0.0
    # theta'(0) = curvature at the clamp = alpha * (horizontal lever arm) <= alpha
    f = lambda k: _shoot(alpha, k).y[1, -1]
    k = brentq(f, 1e-12 * alpha, alpha * (1.0 + 1e-9), xtol=1e-15, rtol=1e-15, maxiter=200)
    sol = _shoot(alpha, k)
    th, _, x, y = sol.y[:, -1]
    return th, y, 1.0 - x


def _first_integral(alpha, th0, weight):
    """integral_0^th0 weight(theta) dtheta / sqrt(2 alpha (sin th0 - sin theta)),
    with theta = th0 (1 - v^2) to remove the inverse-square-root end point."""

    def integrand(v):
        th = th0 * (1.0 - v * v)
        # sin th0 - sin th = 2 cos((th0 + th)/2) sin(th0 v^2 / 2), divided by v^2
        if v == 0.0:
            d_over_v2 = th0 * math.cos(th0)
        else:
            d_over_v2 = 2.0 * math.cos(0.5 * (th0 + th)) * math.sin(0.5 * th0 * v * v) / (v * v)
        return 2.0 * th0 * weight(th) / math.sqrt(2.0 * alpha * d_over_v2)

    with warnings.catch_warnings():
        # near th0 = pi/2 (the far end of the root bracket) the integral diverges
        # logarithmically and quad warns; the root itself is far from there
        warnings.simplefilter("ignore", IntegrationWarning)
        return quad(integrand, 0.0, 1.0, epsabs=1e-12, epsrel=1e-11, limit=200)[0]


def elastica_quadrature(alpha):
    """(tip angle [rad], v/L, u/L) from the first integral (elliptic form)."""
    if alpha == 0.0:
        return 0.0, 0.0, 0.0
    length = lambda th0: _first_integral(alpha, th0, lambda th: 1.0) - 1.0
    th0 = brentq(length, 1e-9, 0.5 * math.pi - 1e-9, xtol=1e-15, rtol=1e-15, maxiter=200)
    v = _first_integral(alpha, th0, math.sin)
    x = _first_integral(alpha, th0, math.cos)
    return th0, v, 1.0 - x


def elastica(alpha):
    """Tip of the elastica: dict with angle_deg, v (deflection/L), u (retreat/L)."""
    th, v, u = elastica_shooting(alpha)
    return {"angle_deg": math.degrees(th), "v": v, "u": u}


def elastica_at_particle(alpha, L, s):
    """Deflection of the elastica at arc length s <= L when the load acts at s
    (the part beyond is unloaded): v/L, u/L of the cantilever of length s
    with alpha' = alpha (s/L)^2, returned normalised by L."""
    e = elastica(alpha * (s / L) ** 2)
    return {"angle_deg": e["angle_deg"], "v": e["v"] * s / L, "u": e["u"] * s / L}


def cowper_shear_coefficient(nu):
    """Cowper (1966) shear coefficient of a rectangular section."""
    return 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu)


def linear_beam(alpha, H, L, E_bend, G, kshear=5.0 / 6.0):
    """Linear theory, tip deflection / L: Euler-Bernoulli alpha/3 and the
    Timoshenko shear term P L / (k G A) = alpha E' H^2 / (12 k G L^2)
    (rectangular section, depth H)."""
    eb = alpha / 3.0
    shear = alpha * E_bend * H * H / (12.0 * kshear * G * L * L)
    return {"euler_bernoulli": eb, "shear": shear, "timoshenko": eb + shear}


def self_test(verbose=True):
    ok = True
    for alpha, (ang, v, u) in REFERENCE.items():
        t1, v1, u1 = elastica_shooting(alpha)
        t2, v2, u2 = elastica_quadrature(alpha)
        for name, got, want, tol in (("tip angle deg", math.degrees(t1), ang, 1e-3),
                                     ("v/L", v1, v, 1e-5), ("u/L", u1, u, 1e-5)):
            good = abs(got - want) <= tol
            ok &= good
            if verbose:
                print(f"alpha {alpha:5g}  {name:13s} shooting {got:.7f}  reference {want}  "
                      f"{'ok' if good else 'FAIL'}")
        d = max(abs(t1 - t2), abs(v1 - v2), abs(u1 - u2))
        ok &= d < 1e-8
        if verbose:
            print(f"alpha {alpha:5g}  shooting vs quadrature max difference {d:.2e} "
                  f"{'ok' if d < 1e-8 else 'FAIL'}")
    # small load: v -> alpha/3 (linear theory)
    a = 1e-3
    e = elastica(a)
    good = abs(e["v"] / (a / 3.0) - 1.0) < 1e-5
    ok &= good
    if verbose:
        print(f"alpha {a:g}  v/(alpha/3) = {e['v'] / (a / 3):.8f}  {'ok' if good else 'FAIL'}")
    return ok


if __name__ == "__main__":
    import sys

    good = self_test()
    E, nu = 210e9, 0.3
    G = E / (2 * (1 + nu))
    print("\nthesis cantilever, P = 17.5 kN, L = 100 mm, H = 10 mm")
    for name, Eb, t in (("2D plane strain", E / (1 - nu * nu), 1e-3), ("2D plane stress", E, 1e-3),
                        ("3D 10x10 mm", E, 10e-3)):
        I = t * 0.01 ** 3 / 12
        alpha = 17500 * 0.1 ** 2 / (Eb * I)
        e = elastica(alpha)
        lin = linear_beam(alpha, 0.01, 0.1, Eb, G)
        print(f"{name:16s} alpha {alpha:8.5f}  tip angle {e['angle_deg']:7.3f} deg  "
              f"v/L {e['v']:.5f}  u/L {e['u']:.5f}  linear EB {lin['euler_bernoulli']:.5f} "
              f"+shear {lin['timoshenko']:.5f}")
    sys.exit(0 if good else 1)
