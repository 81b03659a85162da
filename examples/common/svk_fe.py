"""Finite-element reference for the cantilever: the same St. Venant-Kirchhoff
continuum as pair tlsph, solved with an independent method.

Total-Lagrangian finite elements, tensor-product quadratic Lagrange elements
(Q9 in 2D, Q27 in 3D) with full Gauss quadrature (3 points per direction),
Newton-Raphson with load stepping (dead load). Material: isotropic SVK,
S = lambda tr(E) I + 2 mu E; 2D plane strain uses the 3D Lame constants, 2D
plane stress the reduced lambda* = 2 lambda mu / (lambda + 2 mu), exactly as
tlsph_material.h. Geometry: beam [0, L] x [0, H] (x [0, B] in 3D), every node
on the face x = 0 fixed (clamp), total load P in -y as a uniform traction on
the end face x = L.

The elastica is the beam-theory limit of this problem (inextensible axis,
plane sections, linear moment-curvature); this solver says what the SVK
continuum itself does, so the TLSPH error can be split into discretisation
error (TLSPH against this) and model difference (this against the elastica).

    python3 svk_fe.py --dim 2 --plane stress --P 17500 --nx 80 --ny 8
"""

import argparse
import itertools
import json
import sys
import time

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla


def _shape_1d(xi):
    """quadratic Lagrange on [-1, 1], nodes -1, 0, 1: values and derivatives"""
    N = np.array([0.5 * xi * (xi - 1.0), 1.0 - xi * xi, 0.5 * xi * (xi + 1.0)])
    dN = np.array([xi - 0.5, -2.0 * xi, xi + 0.5])
    return N, dN


class Beam:
    def __init__(self, dim, L, H, B, n, E, nu, plane="strain"):
        self.dim = dim
        self.size = [L, H] + ([B] if dim == 3 else [])
        self.n = list(n)                       # elements per direction
        self.nn = [2 * k + 1 for k in self.n]  # nodes per direction
        self.nnodes = int(np.prod(self.nn))
        self.ndof = dim * self.nnodes
        lam = E * nu / ((1 + nu) * (1 - 2 * nu))
        mu = E / (2 * (1 + nu))
        if dim == 2 and plane == "stress":
            lam = 2 * lam * mu / (lam + 2 * mu)
        self.lam, self.mu = lam, mu
        self.h = [self.size[d] / self.n[d] for d in range(dim)]
        # node coordinates, node index = sum_d i_d * stride_d (x fastest)
        self.stride = [1] * dim
        for d in range(1, dim):
            self.stride[d] = self.stride[d - 1] * self.nn[d - 1]
        grids = np.meshgrid(*[np.linspace(0, self.size[d], self.nn[d]) for d in range(dim)],
                            indexing="ij")
        X = np.zeros((self.nnodes, dim))
        for idx in itertools.product(*[range(k) for k in self.nn]):
            X[self.node(idx)] = [grids[d][idx] for d in range(dim)]
        self.X = X
        # element connectivity (local node order: tensor product, x fastest)
        loc = list(itertools.product(*[range(3) for _ in range(dim)]))   # last index fastest
        loc = [tuple(reversed(t)) for t in itertools.product(*[range(3) for _ in range(dim)])]
        self.local = loc
        conn = []
        for e in itertools.product(*[range(k) for k in reversed(self.n)]):
            e = tuple(reversed(e))
            conn.append([self.node(tuple(2 * e[d] + l[d] for d in range(dim))) for l in loc])
        self.conn = np.array(conn)
        # Gauss points and reference shape-function gradients (same for every element)
        gp, gw = np.polynomial.legendre.leggauss(3)
        self.w = []
        dNdX = []
        for q in itertools.product(*[range(3) for _ in range(dim)]):
            wq = np.prod([gw[k] for k in q]) * np.prod([0.5 * hh for hh in self.h])
            vals = [_shape_1d(gp[k]) for k in q]
            g = np.zeros((len(loc), dim))
            for a, l in enumerate(loc):
                for d in range(dim):
                    term = 1.0
                    for dd in range(dim):
                        term *= (vals[dd][1][l[dd]] * 2.0 / self.h[dd]) if dd == d else vals[dd][0][l[dd]]
                    g[a, d] = term
            self.w.append(wq)
            dNdX.append(g)
        self.w = np.array(self.w)              # (nq,)
        self.dNdX = np.array(dNdX)             # (nq, nen, dim)
        # dof map per element: dof = dim * node + comp
        self.edofs = (self.conn[:, :, None] * dim + np.arange(dim)[None, None, :]).reshape(
            len(conn), -1)
        nen = len(loc) * dim
        self.rows = np.repeat(self.edofs, nen, axis=1).ravel()
        self.cols = np.tile(self.edofs, (1, nen)).ravel()

    def node(self, idx):
        return sum(i * s for i, s in zip(idx, self.stride))

    def face_nodes(self, d, side):
        """nodes on the face x_d = 0 (side 0) or x_d = size_d (side 1), with
        consistent integration weights (sum = face area)"""
        i_d = 0 if side == 0 else self.nn[d] - 1
        others = [k for k in range(self.dim) if k != d]
        nodes, weights = [], []
        w1 = {}
        for k in others:
            wk = np.zeros(self.nn[k])
            for e in range(self.n[k]):
                wk[2 * e:2 * e + 3] += np.array([1, 4, 1]) / 6.0 * self.h[k]
            w1[k] = wk
        for idx in itertools.product(*[range(self.nn[k]) for k in others]):
            full = [0] * self.dim
            full[d] = i_d
            for k, i in zip(others, idx):
                full[k] = i
            nodes.append(self.node(tuple(full)))
            weights.append(np.prod([w1[k][i] for k, i in zip(others, idx)]))
        return np.array(nodes), np.array(weights)

    def assemble(self, u, tangent=True):
        dim, lam, mu = self.dim, self.lam, self.mu
        ue = u[self.edofs].reshape(len(self.conn), -1, dim)        # (ne, nen, dim)
        I = np.eye(dim)
        fint = np.zeros((len(self.conn), ue.shape[1], dim))
        K = 0.0
        minJ = np.inf
        for q in range(len(self.w)):
            g = self.dNdX[q]                                          # (nen, dim)
            F = I[None] + np.einsum("eai,aJ->eiJ", ue, g)
            C = np.einsum("ekI,ekJ->eIJ", F, F)
            Eg = 0.5 * (C - I[None])
            tr = np.trace(Eg, axis1=1, axis2=2)
            S = lam * tr[:, None, None] * I[None] + 2 * mu * Eg
            P = np.einsum("eiK,eKJ->eiJ", F, S)
            minJ = min(minJ, np.linalg.det(F).min())
            fint += self.w[q] * np.einsum("eiJ,aJ->eai", P, g)
            if tangent:
                # A_iJkL = dP_iJ/dF_kL = delta_ik S_JL + lam F_iJ F_kL + mu F_iL F_kJ
                #          + mu (F F^T)_ik delta_JL     (SVK)
                b = np.einsum("eiM,ekM->eik", F, F)
                A = (np.einsum("ik,eJL->eiJkL", I, S)
                     + lam * np.einsum("eiJ,ekL->eiJkL", F, F)
                     + mu * np.einsum("eiL,ekJ->eiJkL", F, F)
                     + mu * np.einsum("eik,JL->eiJkL", b, I))
                Kq = np.einsum("aJ,eiJkL,bL->eaibk", g, A, g, optimize=True)
                K = K + self.w[q] * Kq
        fint_g = np.zeros(self.ndof)
        np.add.at(fint_g, self.edofs.ravel(), fint.reshape(-1))
        if not tangent:
            return fint_g, None, minJ
        ne = len(self.conn)
        nen = ue.shape[1] * dim
        Kg = sp.coo_matrix((K.reshape(ne, nen, nen).ravel(), (self.rows, self.cols)),
                           shape=(self.ndof, self.ndof)).tocsr()
        return fint_g, Kg, minJ


def solve(dim=2, plane="strain", P=17500.0, L=0.1, H=0.01, B=0.001, n=(40, 4), E=210e9,
          nu=0.3, steps=10, tol=1e-11, verbose=False):
    """Static SVK solution. Returns a dict with the end-face mean displacement
    (tip_ux, tip_uy), the mean displacement of the section at x = L - s for
    s in 'sections', min det F at the Gauss points, Newton statistics."""
    t0 = time.time()
    beam = Beam(dim, L, H, B, n, E, nu, plane)
    fixed_nodes, _ = beam.face_nodes(0, 0)
    fixed = (fixed_nodes[:, None] * dim + np.arange(dim)[None]).ravel()
    free = np.setdiff1d(np.arange(beam.ndof), fixed)
    tip_nodes, tip_w = beam.face_nodes(0, 1)
    area = tip_w.sum()
    fext_unit = np.zeros(beam.ndof)
    # total -1 in y; in 2D per unit out-of-plane thickness: P / B
    fext_unit[tip_nodes * dim + 1] = -tip_w / area / (B if dim == 2 else 1.0)
    u = np.zeros(beam.ndof)
    lam_done, dlam = 0.0, 1.0 / steps
    iters = 0
    minJ = 1.0
    while lam_done < 1.0 - 1e-12:
        lam_try = min(1.0, lam_done + dlam)
        utry = u.copy()
        fext = lam_try * P * fext_unit
        ok = False
        for it in range(30):
            fint, K, minJ = beam.assemble(utry)
            r = fext[free] - fint[free]
            rn = np.linalg.norm(r) / (lam_try * P / (B if dim == 2 else 1.0))
            if verbose:
                print(f"  load {lam_try:.4f} it {it} |r|/P {rn:.3e} minJ {minJ:.4f}", file=sys.stderr)
            if not np.isfinite(rn) or rn > 1e6:
                break
            du = spla.spsolve(K[free][:, free].tocsc(), r)
            utry[free] += du
            iters += 1
            # round-off floor of the residual is ~1e-9 P: judge by the update
            if np.linalg.norm(du) <= tol * np.linalg.norm(utry[free]):
                ok = True
                break
        if ok:
            u, lam_done = utry, lam_try
            dlam = min(dlam * 1.5, 1.0 / steps * 2)
        else:
            dlam *= 0.5
            if dlam < 1e-4:
                return {"converged": False, "load_reached": lam_done * P, "minJ": minJ}
    U = u.reshape(-1, dim)
    out = {"converged": True, "dim": dim, "plane": plane if dim == 2 else None, "P": P,
           "n": list(n), "ndof": beam.ndof, "newton_iterations": iters, "minJ": float(minJ),
           "tip_ux": float(np.dot(tip_w, U[tip_nodes, 0]) / area),
           "tip_uy": float(np.dot(tip_w, U[tip_nodes, 1]) / area),
           "wall_s": time.time() - t0}
    # centre of the end face (node exists: odd node count per direction)
    centre = beam.node(tuple([beam.nn[0] - 1] + [(beam.nn[d] - 1) // 2 for d in range(1, dim)]))
    out["tip_centre_ux"], out["tip_centre_uy"] = float(U[centre, 0]), float(U[centre, 1])
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--dim", type=int, default=2)
    ap.add_argument("--plane", default="strain")
    ap.add_argument("--P", type=float, default=17500.0)
    ap.add_argument("--nx", type=int, default=40)
    ap.add_argument("--ny", type=int, default=4)
    ap.add_argument("--nz", type=int, default=4)
    ap.add_argument("--steps", type=int, default=10)
    ap.add_argument("-v", "--verbose", action="store_true")
    a = ap.parse_args()
    n = (a.nx, a.ny) if a.dim == 2 else (a.nx, a.ny, a.nz)
    B = 0.001 if a.dim == 2 else 0.01
    r = solve(a.dim, a.plane, a.P, B=B, n=n, steps=a.steps, verbose=a.verbose)
    print(json.dumps(r))


if __name__ == "__main__":
    main()
