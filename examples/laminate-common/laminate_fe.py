"""Finite-element reference for the two-ply carbon/epoxy laminate benchmarks
(thesis section 3.3): writes CalculiX decks, runs ccx, reads the nodal
displacements back, and samples the quadratic (20-node serendipity) FE field
at arbitrary points.

Model: 3D solid, structured mesh of straight-edged (box) 20-node hexahedra
(C3D20R by default), orthotropic ply in engineering constants with one
*ORIENTATION per ply (local axis 1 = fibre, at angle theta about +z from the
global x axis, local 3 = global z). The load is a dead load (fixed direction,
-z), given as the consistent nodal forces of a uniform traction on the loaded
element faces; the geometrically nonlinear run (*STEP, NLGEOM) is the St.
Venant-Kirchhoff total-Lagrangian model, i.e. the same continuum as the TLSPH
model; a linear run is made on the same mesh for the CLT comparison.

Geometry, numbering and sampling are shared by the writer, the reader and
laminate_reference.py (the sampler used by the TLSPH comparisons):

* the mesh is the tensor product of three 1D grids xg, yg, zg (element
  boundaries); element (ex, ey, ez) is the box [xg[ex], xg[ex+1]] x ...
* nodes live on the "doubled" grid (2nx+1, 2ny+1, 2nz+1) (boundaries and
  element mid-points); a doubled-grid point (I, J, K) is a node iff at most one
  of I, J, K is odd (serendipity: no face or body centre nodes). Node ids are
  1-based in C order of (I, J, K) over those points, and the stored nodal arrays
  use the same order, so no connectivity is stored.

    python3 laminate_fe.py --help
"""

import gzip
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.dirname(HERE)

# ------------------------------------------------------------------ material
PLY = dict(E1=121e9, E2=8.6e9, E3=8.6e9, nu12=0.27, nu13=0.27, nu23=0.4,
           G12=4.7e9, G13=4.7e9, G23=3.1e9, rho=1490.0)

# ------------------------------------------------------------------ cases
# plies: (z_bottom, z_top, theta_deg), bottom first
CASES = {
    "beam_0_90": dict(kind="beam", L=0.1, b=0.01, h=0.01,
                      plies=[(0.0, 0.005, 0.0), (0.005, 0.01, 90.0)],
                      P=500.0, patch=((0.004, 0.006), (0.004, 0.006)),
                      folder="laminate-beam"),
    "beam_0_45": dict(kind="beam", L=0.1, b=0.01, h=0.01,
                      plies=[(0.0, 0.005, 0.0), (0.005, 0.01, 45.0)],
                      P=500.0, patch=((0.004, 0.006), (0.004, 0.006)),
                      folder="laminate-beam"),
    "plate_0_90": dict(kind="plate", a=0.1, h=0.004,
                       plies=[(0.0, 0.002, 0.0), (0.002, 0.004, 90.0)],
                       q=1.0e6, folder="laminate-plate"),
}

# meshes, coarse to fine: target element sizes (m). Beam: hx along x, hyz in
# y and z (the y/z grids always contain the load-patch edges 4 and 6 mm and
# the ply interface 5 mm). Plate: n in-plane elements per side, nzp elements
# per ply.
MESHES = {
    # beam: x grid as (end, element size) segments; y/z element size outside
    # (h_out) and inside (h_in) the load-patch range [4, 6] mm
    "beam": {"coarse": dict(x=[(0.1, 4e-3)], h_out=2e-3, h_in=2e-3),
             "medium": dict(x=[(0.1, 2e-3)], h_out=1e-3, h_in=1e-3),
             "fine": dict(x=[(0.01, 1e-3), (0.09, 2e-3), (0.1, 0.5e-3)], h_out=1e-3, h_in=0.5e-3)},
    "plate": {"coarse": dict(n=20, nzp=2),
              "medium": dict(n=40, nzp=2),
              "fine": dict(n=50, nzp=3)},
}
# the mesh whose nodal solution is stored as the reference
STORED_MESH = {"beam": "fine", "plate": "fine"}


def reference_dir(case):
    return os.path.join(EXAMPLES, CASES[case]["folder"], "reference")


# ------------------------------------------------------------------ grids
def _axis(breaks, h):
    """1D grid through the break points; h: one element size, or one per segment"""
    hs = h if isinstance(h, (list, tuple)) else [h] * (len(breaks) - 1)
    pts = [breaks[0]]
    for a, b, hh in zip(breaks[:-1], breaks[1:], hs):
        n = max(1, int(math.ceil((b - a) / hh - 1e-9)))
        pts.extend(a + (b - a) * np.arange(1, n + 1) / n)
    out = np.array(pts, dtype=float)
    out[-1] = breaks[-1]
    return out


def make_grid(case, mesh):
    c = CASES[case]
    m = MESHES[c["kind"]][mesh]
    zb = sorted({z for p in c["plies"] for z in p[:2]})
    if c["kind"] == "beam":
        (y0, y1), (z0, z1) = c["patch"]
        xb = [0.0] + [e for e, _ in m["x"]]
        xg = _axis(xb, [hh for _, hh in m["x"]])
        yb = sorted({0.0, y0, y1, c["b"]})
        zbk = sorted(set(zb) | {z0, z1})
        hy = [m["h_in"] if (a >= y0 - 1e-12 and b <= y1 + 1e-12) else m["h_out"]
              for a, b in zip(yb[:-1], yb[1:])]
        hz = [m["h_in"] if (a >= z0 - 1e-12 and b <= z1 + 1e-12) else m["h_out"]
              for a, b in zip(zbk[:-1], zbk[1:])]
        yg = _axis(yb, hy)
        zg = _axis(zbk, hz)
    else:
        xg = np.linspace(0.0, c["a"], m["n"] + 1)
        yg = xg.copy()
        zg = np.concatenate([np.linspace(p[0], p[1], m["nzp"] + 1)[:-1] for p in c["plies"]]
                            + [[c["h"]]])
    return xg, yg, zg


def doubled(g):
    d = np.empty(2 * len(g) - 1)
    d[0::2] = g
    d[1::2] = 0.5 * (g[:-1] + g[1:])
    return d


def node_mask(shape):
    """shape = (2nx+1, 2ny+1, 2nz+1); True where the doubled-grid point is a node"""
    I, J, K = np.meshgrid(*[np.arange(s) % 2 for s in shape], indexing="ij")
    return (I + J + K) <= 1


# 20-node hexahedron (CalculiX/Abaqus order): local coordinates of the nodes
LOCAL = np.array([
    [-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
    [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1],
    [0, -1, -1], [1, 0, -1], [0, 1, -1], [-1, 0, -1],
    [0, -1, 1], [1, 0, 1], [0, 1, 1], [-1, 0, 1],
    [-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], dtype=int)


def shape20(xi):
    """serendipity shape functions, xi: (n, 3) local coordinates -> (n, 20)"""
    xi = np.asarray(xi, dtype=float)
    x, y, z = xi[:, 0:1], xi[:, 1:2], xi[:, 2:3]
    a, b, c = LOCAL[:, 0][None, :], LOCAL[:, 1][None, :], LOCAL[:, 2][None, :]
    fx = np.where(a == 0, 1 - x * x, 1 + a * x)
    fy = np.where(b == 0, 1 - y * y, 1 + b * y)
    fz = np.where(c == 0, 1 - z * z, 1 + c * z)
    corner = (a != 0) & (b != 0) & (c != 0)
    N = fx * fy * fz
    N = np.where(corner, 0.125 * N * (a * x + b * y + c * z - 2), 0.25 * N)
    return N


class Mesh:
    """structured 20-node hexahedral mesh on the grid xg x yg x zg"""

    def __init__(self, xg, yg, zg):
        self.g = [np.asarray(xg, float), np.asarray(yg, float), np.asarray(zg, float)]
        self.ne = tuple(len(g) - 1 for g in self.g)
        self.dshape = tuple(2 * n + 1 for n in self.ne)
        self.mask = node_mask(self.dshape)
        self.ids = np.zeros(self.dshape, dtype=np.int64)
        self.ids[self.mask] = np.arange(1, self.mask.sum() + 1)
        self.nnode = int(self.mask.sum())
        self.dg = [doubled(g) for g in self.g]

    def coords(self):
        X, Y, Z = np.meshgrid(*self.dg, indexing="ij")
        return np.stack([X[self.mask], Y[self.mask], Z[self.mask]], axis=1)

    def element_nodes(self, ex, ey, ez):
        """(n, 20) node ids of elements with indices ex, ey, ez (arrays)"""
        ex, ey, ez = (np.asarray(v)[:, None] for v in (ex, ey, ez))
        I = 2 * ex + 1 + LOCAL[None, :, 0]
        J = 2 * ey + 1 + LOCAL[None, :, 1]
        K = 2 * ez + 1 + LOCAL[None, :, 2]
        return self.ids[I, J, K]

    def all_elements(self):
        ex, ey, ez = np.meshgrid(*[np.arange(n) for n in self.ne], indexing="ij")
        return ex.ravel(), ey.ravel(), ez.ravel()

    def nodes_where(self, axis, value):
        """ids of the nodes on the plane coordinate[axis] == value"""
        d = self.dg[axis]
        i = int(np.argmin(np.abs(d - value)))
        assert abs(d[i] - value) < 1e-12, (axis, value)
        sl = [slice(None)] * 3
        sl[axis] = i
        ids = self.ids[tuple(sl)]
        return ids[ids > 0]


class Field:
    """a nodal displacement solution on a Mesh, evaluable anywhere inside"""

    def __init__(self, mesh, U):
        self.mesh = mesh
        U = np.asarray(U, dtype=float)
        assert U.shape == (mesh.nnode, 3), (U.shape, mesh.nnode)
        self.U = U
        self.full = np.full(mesh.dshape + (3,), np.nan)
        self.full[mesh.mask] = U

    def locate(self, points, tol=1e-9):
        p = np.atleast_2d(np.asarray(points, dtype=float))
        idx, xi = [], []
        for d in range(3):
            g = self.mesh.g[d]
            span = g[-1] - g[0]
            if np.any(p[:, d] < g[0] - tol * span) or np.any(p[:, d] > g[-1] + tol * span):
                bad = p[(p[:, d] < g[0] - tol * span) | (p[:, d] > g[-1] + tol * span)][0]
                raise ValueError(f"point {bad} outside the body "
                                 f"(axis {d}: [{g[0]}, {g[-1]}])")
            e = np.clip(np.searchsorted(g, p[:, d], side="right") - 1, 0, len(g) - 2)
            idx.append(e)
            xi.append(2.0 * (p[:, d] - g[e]) / (g[e + 1] - g[e]) - 1.0)
        return idx, np.stack(xi, axis=1)

    def sample(self, points):
        (ex, ey, ez), xi = self.locate(points)
        N = shape20(xi)
        I = 2 * ex[:, None] + 1 + LOCAL[None, :, 0]
        J = 2 * ey[:, None] + 1 + LOCAL[None, :, 1]
        K = 2 * ez[:, None] + 1 + LOCAL[None, :, 2]
        Ue = self.full[I, J, K]  # (n, 20, 3)
        return np.einsum("na,nac->nc", N, Ue)


# ------------------------------------------------------------------ loads
GAUSS3 = (np.array([-math.sqrt(0.6), 0.0, math.sqrt(0.6)]), np.array([5.0, 8.0, 5.0]) / 9.0)


def face_points(ga, gb, a_range=None, b_range=None):
    """3x3 Gauss points and weights on the cells of the 2D grid ga x gb
    (restricted to [a_range] x [b_range]); returns (pa, pb, w)"""
    xg, wg = GAUSS3
    pa, pb, w = [], [], []
    for i in range(len(ga) - 1):
        a0, a1 = ga[i], ga[i + 1]
        if a_range and (a0 < a_range[0] - 1e-12 or a1 > a_range[1] + 1e-12):
            continue
        for j in range(len(gb) - 1):
            b0, b1 = gb[j], gb[j + 1]
            if b_range and (b0 < b_range[0] - 1e-12 or b1 > b_range[1] + 1e-12):
                continue
            A, B = np.meshgrid(0.5 * (a0 + a1) + 0.5 * (a1 - a0) * xg,
                               0.5 * (b0 + b1) + 0.5 * (b1 - b0) * xg, indexing="ij")
            W = np.outer(wg, wg) * 0.25 * (a1 - a0) * (b1 - b0)
            pa.append(A.ravel()), pb.append(B.ravel()), w.append(W.ravel())
    return np.concatenate(pa), np.concatenate(pb), np.concatenate(w)


def face_loads(mesh, axis, value, traction, a_range=None, b_range=None):
    """consistent nodal forces {node: (fx, fy, fz)} of a uniform traction on the
    element faces of the plane coordinate[axis] == value (in-plane ranges
    optional). For a rectangular 8-node face this is -1/12 of the face force
    at each corner and +1/3 at each mid-side node."""
    t = np.asarray(traction, float)
    ax = [d for d in range(3) if d != axis]
    ga, gb = mesh.g[ax[0]], mesh.g[ax[1]]
    forces = {}
    for i in range(len(ga) - 1):
        if a_range and (ga[i] < a_range[0] - 1e-12 or ga[i + 1] > a_range[1] + 1e-12):
            continue
        for j in range(len(gb) - 1):
            if b_range and (gb[j] < b_range[0] - 1e-12 or gb[j + 1] > b_range[1] + 1e-12):
                continue
            area = (ga[i + 1] - ga[i]) * (gb[j + 1] - gb[j])
            dI = int(np.argmin(np.abs(mesh.dg[axis] - value)))
            for la in (-1, 0, 1):
                for lb in (-1, 0, 1):
                    if la == 0 and lb == 0:
                        continue
                    w = 1.0 / 3.0 if (la == 0 or lb == 0) else -1.0 / 12.0
                    idx = [0, 0, 0]
                    idx[axis] = dI
                    idx[ax[0]] = 2 * i + 1 + la
                    idx[ax[1]] = 2 * j + 1 + lb
                    n = int(mesh.ids[tuple(idx)])
                    forces[n] = forces.get(n, 0.0) + w * area * t
    return forces


# ------------------------------------------------------------------ decks
def orientation_axes(theta_deg):
    th = math.radians(theta_deg)
    c, s = math.cos(th), math.sin(th)
    c, s = round(c, 15), round(s, 15)
    return (c, s, 0.0), (-s, c, 0.0)


def _id_lines(ids, per=16):
    ids = list(ids)
    return "\n".join(", ".join(str(int(v)) for v in ids[k:k + per]) for k in range(0, len(ids), per))


def build_model(case, mesh_name):
    c = CASES[case]
    mesh = Mesh(*make_grid(case, mesh_name))
    if c["kind"] == "beam":
        fixed = mesh.nodes_where(0, 0.0)
        (y0, y1), (z0, z1) = c["patch"]
        area = (y1 - y0) * (z1 - z0)
        loads = face_loads(mesh, 0, c["L"], (0.0, 0.0, -c["P"] / area), (y0, y1), (z0, z1))
    else:
        a = c["a"]
        fixed = np.unique(np.concatenate([mesh.nodes_where(0, 0.0), mesh.nodes_where(0, a),
                                          mesh.nodes_where(1, 0.0), mesh.nodes_where(1, a)]))
        loads = face_loads(mesh, 2, c["h"], (0.0, 0.0, -c["q"]))
    return mesh, np.asarray(fixed), loads


def write_deck(path, case, mesh_name, nlgeom, eltype="C3D20R"):
    c = CASES[case]
    mesh, fixed, loads = build_model(case, mesh_name)
    fixed_set = set(int(v) for v in fixed)
    X = mesh.coords()
    ex, ey, ez = mesh.all_elements()
    conn = mesh.element_nodes(ex, ey, ez)
    zc = 0.5 * (mesh.g[2][ez] + mesh.g[2][ez + 1])
    out = []
    w = out.append
    w(f"** laminate_fe.py: case {case}, mesh {mesh_name} "
      f"({mesh.ne[0]}x{mesh.ne[1]}x{mesh.ne[2]} {eltype}, {mesh.nnode} nodes), "
      f"{'NLGEOM' if nlgeom else 'linear'}")
    w("** units: m, N, Pa. Generated file: edit laminate_fe.py instead.")
    w("*NODE, NSET=NALL")
    w("\n".join(f"{i + 1}, {x:.15g}, {y:.15g}, {z:.15g}" for i, (x, y, z) in enumerate(X)))
    for k, (zb, zt, th) in enumerate(c["plies"]):
        sel = np.nonzero((zc > zb) & (zc < zt))[0]
        w(f"*ELEMENT, TYPE={eltype}, ELSET=PLY{k + 1}")
        lines = []
        for e in sel:
            n = conn[e]
            lines.append(f"{e + 1}, " + ", ".join(str(int(v)) for v in n[:15]) + ",\n"
                         + ", ".join(str(int(v)) for v in n[15:]))
        w("\n".join(lines))
    w("*NSET, NSET=NFIX")
    w(_id_lines(sorted(fixed_set)))
    w("*MATERIAL, NAME=CFRP")
    w("*ELASTIC, TYPE=ENGINEERING CONSTANTS")
    p = PLY
    w(f"{p['E1']:.6g}, {p['E2']:.6g}, {p['E3']:.6g}, {p['nu12']}, {p['nu13']}, {p['nu23']}, "
      f"{p['G12']:.6g}, {p['G13']:.6g}")
    w(f"{p['G23']:.6g}, 0.")
    w("*DENSITY")
    w(f"{p['rho']}")
    for k, (zb, zt, th) in enumerate(c["plies"]):
        (a1, a2, a3), (b1, b2, b3) = orientation_axes(th)
        w(f"** ply {k + 1}: z in [{zb}, {zt}], fibre (local 1) at {th} deg about +z from x")
        w(f"*ORIENTATION, NAME=OR{k + 1}, SYSTEM=RECTANGULAR")
        w(f"{a1:.15g}, {a2:.15g}, {a3:.15g}, {b1:.15g}, {b2:.15g}, {b3:.15g}")
        w(f"*SOLID SECTION, ELSET=PLY{k + 1}, MATERIAL=CFRP, ORIENTATION=OR{k + 1}")
    w("*BOUNDARY")
    w("NFIX, 1, 3, 0.")
    if nlgeom:
        w("*STEP, NLGEOM, INC=1000")
        w("*STATIC")
        w("1.0, 1.0, 1e-4, 1.0")
        w("*CONTROLS, PARAMETERS=FIELD")
        w("1e-7, 1e-7, , , 1e-7")
    else:
        w("*STEP")
        w("*STATIC")
    w("*CLOAD")
    lines = []
    for n in sorted(loads):
        if n in fixed_set:
            continue  # absorbed by the clamp
        f = loads[n]
        for d in range(3):
            if f[d] != 0.0:
                lines.append(f"{n}, {d + 1}, {f[d]:.15g}")
    w("\n".join(lines))
    w("*NODE PRINT, NSET=NALL, FREQUENCY=1000")
    w("U")
    w("*NODE PRINT, NSET=NFIX, TOTALS=ONLY")
    w("RF")
    w("*END STEP")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")
    total = np.sum([loads[n] for n in loads if n not in fixed_set], axis=0)
    return mesh, total


# ------------------------------------------------------------------ ccx
def ccx_version():
    exe = shutil.which("ccx")
    if not exe:
        return None
    r = subprocess.run([exe, "-v"], capture_output=True, text=True)
    m = re.search(r"Version\s+(\S+)", r.stdout + r.stderr)
    return m.group(1) if m else (r.stdout + r.stderr).strip()


def run_ccx(workdir, job, threads=1):
    exe = shutil.which("ccx")
    if not exe:
        raise RuntimeError("CalculiX 'ccx' not found on PATH: install the Debian package "
                           "calculix-ccx (scripts/setup.sh does)")
    env = dict(os.environ)
    for k in ("OMP_NUM_THREADS", "CCX_NPROC_STIFFNESS", "CCX_NPROC_EQUATION_SOLVER",
              "NUMBER_OF_CPUS", "CCX_NPROC_RESULTS"):
        env[k] = str(threads)
    t0 = time.time()
    r = subprocess.run([exe, "-i", job], cwd=workdir, env=env, capture_output=True, text=True)
    wall = time.time() - t0
    with open(os.path.join(workdir, job + ".log"), "w") as f:
        f.write(r.stdout)
        f.write(r.stderr)
    if r.returncode != 0 or "Job finished" not in r.stdout:
        tail = "\n".join((r.stdout + r.stderr).splitlines()[-30:])
        raise RuntimeError(f"ccx failed on {job} (rc {r.returncode}):\n{tail}")
    iters = len(re.findall(r"^\s*iteration\s+\d+", r.stdout, flags=re.M))
    incs = len(re.findall(r"^\s*increment\s+\d+\s+attempt", r.stdout, flags=re.M))
    return wall, incs, iters


def read_dat(path, nnode):
    """last displacement block for set NALL and last total force of NFIX"""
    with open(path) as f:
        text = f.read()
    blocks = [m.start() for m in re.finditer(r"displacements \(vx,vy,vz\) for set NALL", text)]
    if not blocks:
        raise RuntimeError(f"no displacement output in {path}")
    lines = text[blocks[-1]:].splitlines()[1:]
    U = np.full((nnode, 3), np.nan)
    seen = 0
    for ln in lines:
        s = ln.split()
        if not s:
            if seen:
                break
            continue
        if len(s) != 4:
            break
        U[int(s[0]) - 1] = [float(v) for v in s[1:]]
        seen += 1
    if seen != nnode or np.isnan(U).any():
        raise RuntimeError(f"{path}: read {seen} of {nnode} nodal displacements")
    rf = None
    m = list(re.finditer(r"total force \(fx,fy,fz\) for set NFIX[^\n]*\n\s*\n?\s*([-+0-9.Ee ]+)", text))
    if m:
        rf = [float(v) for v in m[-1].group(1).split()[:3]]
    return U, rf


def solve(case, mesh_name, nlgeom, workdir, eltype="C3D20R", threads=1, keep_deck_to=None):
    os.makedirs(workdir, exist_ok=True)
    job = f"{case}_{mesh_name}_{'nlgeom' if nlgeom else 'linear'}_{eltype}"
    inp = os.path.join(workdir, job + ".inp")
    mesh, total = write_deck(inp, case, mesh_name, nlgeom, eltype)
    for ext in (".dat", ".frd", ".sta", ".cvg"):
        if os.path.exists(os.path.join(workdir, job + ext)):
            os.remove(os.path.join(workdir, job + ext))
    wall, incs, iters = run_ccx(workdir, job, threads)
    U, rf = read_dat(os.path.join(workdir, job + ".dat"), mesh.nnode)
    if keep_deck_to:
        os.makedirs(keep_deck_to, exist_ok=True)
        with open(inp, "rb") as fi, open(os.path.join(keep_deck_to, job + ".inp.gz"), "wb") as fo, \
                gzip.GzipFile(filename="", mode="wb", fileobj=fo, compresslevel=9, mtime=0) as gz:
            shutil.copyfileobj(fi, gz)
    return dict(case=case, mesh=mesh_name, nlgeom=nlgeom, eltype=eltype, job=job,
                ne=list(mesh.ne), nnode=mesh.nnode, wall_s=round(wall, 2), increments=incs,
                iterations=iters, applied_load=[float(v) for v in total], reaction=rf,
                field=Field(mesh, U))


# ------------------------------------------------------------------ stations
DX = 1.0e-3  # TLSPH particle spacing of the benchmarks


def lattice(n, dx=DX):
    return (np.arange(n) + 0.5) * dx


def stations(case, field):
    """the key quantities of a case from a Field (floats, metres)"""
    c = CASES[case]
    s = {}
    if c["kind"] == "beam":
        L, b, h = c["L"], c["b"], c["h"]
        u = field.sample([[L, b / 2, h / 2], [L, b / 2, h], [L, b / 2, 0.0],
                          [L, 0.0, h / 2], [L, b, h / 2]])
        s["u3_tip_centre"] = u[0, 2]
        s["u1_tip_top_centre"] = u[1, 0]
        s["u1_tip_bottom_centre"] = u[2, 0]
        s["u2_tip_centre"] = u[0, 1]
        s["u1_tip_centre"] = u[0, 0]
        s["twist_rad"] = math.atan2(u[4, 2] - u[3, 2], b + u[4, 1] - u[3, 1])
        py, pz, w = face_points(field.mesh.g[1], field.mesh.g[2])
        uu = field.sample(np.stack([np.full_like(py, L), py, pz], axis=1))
        s["u3_tip_face_mean"] = float(np.sum(w * uu[:, 2]) / np.sum(w))
        s["u1_tip_face_mean"] = float(np.sum(w * uu[:, 0]) / np.sum(w))
    else:
        a, h = c["a"], c["h"]
        g = np.linspace(0.0, a, 401)  # 0.25 mm sampling of the top surface
        X, Y = np.meshgrid(g, g, indexing="ij")
        u = field.sample(np.stack([X.ravel(), Y.ravel(), np.full(X.size, h)], axis=1))
        s["u3_top_min"] = u[:, 2].min()
        s["u1_top_max"], s["u1_top_min"] = u[:, 0].max(), u[:, 0].min()
        s["u2_top_max"], s["u2_top_min"] = u[:, 1].max(), u[:, 1].min()
        uA = field.sample([[0.075, 0.075, h]])[0]
        s["u1_A_top"], s["u2_A_top"], s["u3_A_top"] = uA
        uc = field.sample([[a / 2, a / 2, h / 2], [a / 2, a / 2, h]])
        s["u3_centre_mid"], s["u3_centre_top"] = uc[0, 2], uc[1, 2]
    return {k: float(v) for k, v in s.items()}


def plate_extrema(field, a, h):
    """max/min of u1, u2, u3 on the bottom (z = 0) and top (z = h) surfaces
    (0.25 mm sampling) and on the bottom and top particle layers (dx = 1 mm)"""
    out = {}
    g = np.linspace(0.0, a, 401)
    X, Y = np.meshgrid(g, g, indexing="ij")
    xs = lattice(int(round(a / DX)))
    XL, YL = np.meshgrid(xs, xs, indexing="ij")
    zl = lattice(int(round(h / DX)))
    for name, (PX, PY, z) in (("surface_bottom", (X, Y, 0.0)), ("surface_top", (X, Y, h)),
                              ("layer_bottom", (XL, YL, zl[0])), ("layer_top", (XL, YL, zl[-1]))):
        u = field.sample(np.stack([PX.ravel(), PY.ravel(), np.full(PX.size, z)], axis=1))
        out[name] = dict(z=float(z), **{f"u{c + 1}_{m}": float(getattr(u[:, c], m)())
                                        for c in range(3) for m in ("max", "min")})
    return out


def lattice_stations(case, field):
    """the same quantities sampled where the TLSPH particles (dx = 1 mm) sit"""
    c = CASES[case]
    out = {}
    if c["kind"] == "beam":
        L, b, h = c["L"], c["b"], c["h"]
        xs = L - DX / 2
        ys, zs = lattice(int(round(b / DX))), lattice(int(round(h / DX)))
        Y, Z = np.meshgrid(ys, zs, indexing="ij")
        u = field.sample(np.stack([np.full(Y.size, xs), Y.ravel(), Z.ravel()], axis=1))
        u = u.reshape(len(ys), len(zs), 3)
        jc = [len(ys) // 2 - 1, len(ys) // 2]
        kc = [len(zs) // 2 - 1, len(zs) // 2]
        out["x_layer"] = xs
        out["u3_central4_mean"] = float(u[np.ix_(jc, kc)][..., 2].mean())
        out["u3_layer_mean"] = float(u[..., 2].mean())
        out["u1_layer_mean"] = float(u[..., 0].mean())
        out["u2_central4_mean"] = float(u[np.ix_(jc, kc)][..., 1].mean())
        out["z"] = [float(v) for v in zs]
        # the two central particle columns y = 4.5 and 5.5 mm, and their mean
        for j in jc:
            out[f"column_y{ys[j] * 1e3:.1f}mm"] = {
                "u1": [float(v) for v in u[j, :, 0]],
                "u2": [float(v) for v in u[j, :, 1]],
                "u3": [float(v) for v in u[j, :, 2]]}
        out["column_mean_u1"] = [float(v) for v in u[jc, :, 0].mean(axis=0)]
        out["column_mean_u3"] = [float(v) for v in u[jc, :, 2].mean(axis=0)]
        out["u1_top_particles_mean"] = float(u[jc, -1, 0].mean())
        out["u1_bottom_particles_mean"] = float(u[jc, 0, 0].mean())
    else:
        a, h = c["a"], c["h"]
        xs = lattice(int(round(a / DX)))
        zs = lattice(int(round(h / DX)))
        zt = zs[-1]
        X, Y = np.meshgrid(xs, xs, indexing="ij")
        u = field.sample(np.stack([X.ravel(), Y.ravel(), np.full(X.size, zt)], axis=1))
        out["z_layer"] = float(zt)
        out["u3_top_layer_min"] = float(u[:, 2].min())
        out["u1_top_layer_max"], out["u1_top_layer_min"] = float(u[:, 0].max()), float(u[:, 0].min())
        out["u2_top_layer_max"], out["u2_top_layer_min"] = float(u[:, 1].max()), float(u[:, 1].min())
        nb = np.array([[x, y] for x in (0.0745, 0.0755) for y in (0.0745, 0.0755)])
        out["z"] = [float(v) for v in zs]
        for name, z in (("A_top_layer", zt),):
            uu = field.sample(np.column_stack([nb, np.full(4, z)]))
            ue = field.sample([[0.075, 0.075, z]])[0]
            out[name] = {"neighbours_xy": nb.tolist(),
                         "neighbours_u": uu.tolist(),
                         "neighbours_mean": uu.mean(axis=0).tolist(),
                         "exact_0.075": ue.tolist()}
        prof_e = field.sample(np.column_stack([np.full(len(zs), 0.075), np.full(len(zs), 0.075), zs]))
        prof_n = np.mean([field.sample(np.column_stack([np.full(len(zs), x), np.full(len(zs), y), zs]))
                          for x, y in nb], axis=0)
        out["A_profile_exact_0.075"] = {"u1": prof_e[:, 0].tolist(), "u2": prof_e[:, 1].tolist(),
                                        "u3": prof_e[:, 2].tolist()}
        out["A_profile_neighbours_mean"] = {"u1": prof_n[:, 0].tolist(), "u2": prof_n[:, 1].tolist(),
                                            "u3": prof_n[:, 2].tolist()}
    return out


# ------------------------------------------------------------------ CLT
def qbar(theta_deg):
    p = PLY
    nu21 = p["nu12"] * p["E2"] / p["E1"]
    d = 1 - p["nu12"] * nu21
    Q11, Q22, Q12, Q66 = p["E1"] / d, p["E2"] / d, p["nu12"] * p["E2"] / d, p["G12"]
    Q = np.array([[Q11, Q12, 0], [Q12, Q22, 0], [0, 0, Q66]])
    t = math.radians(theta_deg)
    c, s = math.cos(t), math.sin(t)
    T = np.array([[c * c, s * s, 2 * c * s], [s * s, c * c, -2 * c * s], [-c * s, c * s, c * c - s * s]])
    R = np.diag([1, 1, 2.0])
    return np.linalg.inv(T) @ Q @ R @ T @ np.linalg.inv(R)


def abd(plies):
    zs = [p[0] for p in plies] + [plies[-1][1]]
    zm = 0.5 * (zs[0] + zs[-1])
    A, B, D = np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((3, 3))
    for zb, zt, th in plies:
        Qb = qbar(th)
        z0, z1 = zb - zm, zt - zm
        A += Qb * (z1 - z0)
        B += Qb * (z1 ** 2 - z0 ** 2) / 2
        D += Qb * (z1 ** 3 - z0 ** 3) / 3
    return np.block([[A, B], [B, D]])


def clt_beam(case):
    """narrow-beam CLT: D* = 1/d11 (all other resultants zero) and the bound with
    the twist curvature kappa_xy restrained (Mxy free to react)"""
    c = CASES[case]
    M = abd(c["plies"])
    inv = np.linalg.inv(M)
    Dfree = 1.0 / inv[3, 3]
    keep = [0, 1, 2, 3, 4]  # kappa_xy = 0: drop its row and column
    Dtw = 1.0 / np.linalg.inv(M[np.ix_(keep, keep)])[3, 3]
    L, b, P = c["L"], c["b"], c["P"]
    # Timoshenko shear estimate: kappa = 5/6 on the thickness-averaged G_xz
    p = PLY
    gxz = []
    for zb, zt, th in c["plies"]:
        t = math.radians(th)
        gxz.append((zt - zb) / (math.cos(t) ** 2 / p["G13"] + math.sin(t) ** 2 / p["G23"]))
    Gxz = sum(gxz) / c["h"]
    ws = P * L / (5.0 / 6.0 * Gxz * b * c["h"])
    return dict(Dstar_free=Dfree, Dstar_twist_restrained=Dtw,
                w_clt_free=P * L ** 3 / (3 * Dfree * b),
                w_clt_twist_restrained=P * L ** 3 / (3 * Dtw * b),
                Gxz_mean=Gxz, w_shear_timoshenko=ws)


# ------------------------------------------------------------------ driver
def _rel(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


def run_case(case, workdir, threads, meshes=None, verbose=True, store=True, eltype_check=True):
    c = CASES[case]
    kind = c["kind"]
    meshes = meshes or list(MESHES[kind])
    stored = STORED_MESH[kind] if STORED_MESH[kind] in meshes else meshes[-1]
    refdir = reference_dir(case)
    res = dict(case=case, definition={k: v for k, v in c.items() if k != "folder"},
               runs=[], convergence={}, eltype_check={})
    fields = {}
    for mname in meshes:
        for nl in (True, False):
            r = solve(case, mname, nl, workdir, "C3D20R", threads,
                      keep_deck_to=refdir if (store and (mname == "coarse" or (mname == stored and nl)))
                      else None)
            f = r.pop("field")
            fields[(mname, nl, "C3D20R")] = f
            r["stations"] = stations(case, f)
            res["runs"].append(r)
            if verbose:
                print(f"{case} {mname:6s} {'nlgeom' if nl else 'linear'}: "
                      f"{r['ne']} {r['nnode']} nodes, {r['wall_s']} s, "
                      f"{r['increments']} inc {r['iterations']} it, reaction {r['reaction']}",
                      file=sys.stderr)
    if eltype_check:
        mname = "medium"
        r = solve(case, mname, True, workdir, "C3D20", threads)
        f = r.pop("field")
        r["stations"] = stations(case, f)
        res["runs"].append(r)
        ref = next(x for x in res["runs"] if x["mesh"] == mname and x["nlgeom"] and x["eltype"] == "C3D20R")
        res["eltype_check"] = {k: dict(C3D20R=ref["stations"][k], C3D20=v,
                                       rel_diff=_rel(v, ref["stations"][k]))
                               for k, v in r["stations"].items()}
        if verbose:
            print(f"{case} C3D20 vs C3D20R ({mname}, nlgeom): max rel diff "
                  f"{max(d['rel_diff'] for d in res['eltype_check'].values()):.2e}", file=sys.stderr)
    # convergence: each mesh against the finest, nlgeom and linear
    for nl in (True, False):
        key = "nlgeom" if nl else "linear"
        rows = [x for x in res["runs"] if x["nlgeom"] == nl and x["eltype"] == "C3D20R"]
        fin = rows[-1]["stations"]
        res["convergence"][key] = {
            x["mesh"]: {k: dict(value=v, rel_to_finest=_rel(v, fin[k])) for k, v in x["stations"].items()}
            for x in rows}
    ref_nl = fields[(stored, True, "C3D20R")]
    ref_li = fields[(stored, False, "C3D20R")]
    res["stored_mesh"] = stored
    derived(case, res, ref_nl, ref_li)
    if store:
        save_field(os.path.join(refdir, f"{case}.npz"), case, stored, U_nlgeom=ref_nl)
        save_field(os.path.join(refdir, f"{case}_linear.npz"), case, stored, U_linear=ref_li)
        save_field(os.path.join(refdir, f"{case}_coarse.npz"), case, "coarse",
                   U_nlgeom=fields[("coarse", True, "C3D20R")],
                   U_linear=fields[("coarse", False, "C3D20R")])
        res["files"] = {k: f"{case}{s}.npz" for k, s in
                        (("nlgeom", ""), ("linear", "_linear"), ("coarse", "_coarse"))}
    return res


def derived(case, res, ref_nl, ref_li):
    """the quantities computed from the stored fields (no ccx): stations, lattice
    samples, extrema, CLT check"""
    c = CASES[case]
    res["stations_nlgeom"] = stations(case, ref_nl)
    res["stations_linear"] = stations(case, ref_li)
    res["lattice_nlgeom"] = lattice_stations(case, ref_nl)
    res["lattice_linear"] = lattice_stations(case, ref_li)
    if c["kind"] == "plate":
        res["extrema_nlgeom"] = plate_extrema(ref_nl, c["a"], c["h"])
        res["extrema_linear"] = plate_extrema(ref_li, c["a"], c["h"])
    if c["kind"] == "beam":
        cl = clt_beam(case)
        w_fe = -res["stations_linear"]["u3_tip_centre"]
        cl.update(w_fe_linear_tip_centre=w_fe,
                  w_fe_linear_tip_face_mean=-res["stations_linear"]["u3_tip_face_mean"],
                  fe_over_clt_free=w_fe / cl["w_clt_free"],
                  fe_over_clt_twist_restrained=w_fe / cl["w_clt_twist_restrained"],
                  fe_over_clt_free_plus_shear=w_fe / (cl["w_clt_free"] + cl["w_shear_timoshenko"]))
        res["clt"] = cl
    else:
        p = PLY
        coef = lambda w: 100 * w * p["E2"] * c["h"] ** 3 / (c["q"] * c["a"] ** 4)  # noqa: E731
        wm = -res["stations_linear"]["u3_centre_mid"]
        res["clt"] = dict(coefficient_clt=0.5416, w_clt=0.5416 * c["q"] * c["a"] ** 4 / (100 * p["E2"] * c["h"] ** 3),
                          w_fe_linear_centre_mid=wm, coefficient_fe_mid=coef(wm),
                          coefficient_fe_top=coef(-res["stations_linear"]["u3_centre_top"]),
                          fe_over_clt=coef(wm) / 0.5416,
                          w_fe_nlgeom_centre_mid=-res["stations_nlgeom"]["u3_centre_mid"])


def refresh(cases):
    """recompute the derived quantities of summary.json from the stored npz files"""
    import laminate_report
    for case in cases:
        d = reference_dir(case)
        path = os.path.join(d, "summary.json")
        with open(path) as f:
            doc = json.load(f)
        res = doc["cases"][case]
        derived(case, res, load_field(os.path.join(d, f"{case}.npz"), "nlgeom"),
                load_field(os.path.join(d, f"{case}_linear.npz"), "linear"))
        with open(path, "w") as f:
            json.dump(doc, f, indent=1)
        laminate_report.write_markdown(CASES[case]["folder"], doc)


def save_field(path, case, mesh_name, **fields):
    """grid + nodal displacements (float64, node order of Mesh) as compressed npz"""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    m = next(iter(fields.values())).mesh
    np.savez_compressed(path, case=np.array(case), mesh=np.array(mesh_name),
                        eltype=np.array("C3D20R"), ccx_version=np.array(str(ccx_version())),
                        xg=m.g[0], yg=m.g[1], zg=m.g[2],
                        **{k: f.U for k, f in fields.items()})


def load_field(path, analysis="nlgeom"):
    with np.load(path) as d:
        mesh = Mesh(d["xg"], d["yg"], d["zg"])
        return Field(mesh, d["U_" + analysis])


# extra meshes of the refinement study (linear runs only, printed, not stored):
# they separate the through-thickness from the in-plane refinement
STUDY = {
    "beam": {"medium_yz05": dict(x=[(0.1, 2e-3)], h_out=0.5e-3, h_in=0.5e-3),
             "medium_x1": dict(x=[(0.1, 1e-3)], h_out=1e-3, h_in=1e-3)},
    "plate": {"20x20x6": dict(n=20, nzp=3), "20x20x12": dict(n=20, nzp=6),
              "30x30x4": dict(n=30, nzp=2), "50x50x4": dict(n=50, nzp=2),
              "40x40x6": dict(n=40, nzp=3)},
}


def run_study(cases, workdir, threads):
    for case in cases:
        kind = CASES[case]["kind"]
        MESHES[kind].update(STUDY[kind])
        keys = ["u3_tip_centre", "u3_tip_face_mean", "u1_tip_top_centre", "u1_tip_bottom_centre"] \
            if kind == "beam" else ["u3_centre_mid", "u3_top_min", "u1_top_max", "u2_top_max",
                                    "u1_A_top", "u2_A_top", "u3_A_top"]
        print(f"| {case} linear | nodes | ccx s | " + " | ".join(keys) + " |")
        print("|---|---|---|" + "---|" * len(keys))
        for m in list(MESHES[kind]):
            r = solve(case, m, False, workdir, "C3D20R", threads)
            s = stations(case, r["field"])
            print(f"| {m} {'x'.join(map(str, r['ne']))} | {r['nnode']} | {r['wall_s']:.1f} | "
                  + " | ".join(f"{s[k]:.6e}" for k in keys) + " |", flush=True)


def shear_check(cases, workdir, threads, factor=100.0):
    """linear runs with G13 and G23 multiplied by factor (transverse shear made
    stiff): how much of the FE-CLT difference is transverse shear"""
    saved = dict(PLY)
    try:
        PLY["G13"] *= factor
        PLY["G23"] *= factor
        for case in cases:
            c = CASES[case]
            mesh = "medium" if c["kind"] == "beam" else "coarse"
            r = solve(case, mesh, False, workdir, "C3D20R", threads)
            s = stations(case, r["field"])
            if c["kind"] == "beam":
                cl = clt_beam(case)
                print(f"{case} ({mesh}, linear, G13 G23 x{factor:g}): u3 tip centre {s['u3_tip_centre']:.6e}, "
                      f"tip-face mean {s['u3_tip_face_mean']:.6e}; / CLT free "
                      f"{-s['u3_tip_face_mean'] / cl['w_clt_free']:.4f}, / CLT twist-restrained "
                      f"{-s['u3_tip_face_mean'] / cl['w_clt_twist_restrained']:.4f} (tip-face mean)")
            else:
                w = -s["u3_centre_mid"]
                coef = 100 * w * saved["E2"] * c["h"] ** 3 / (c["q"] * c["a"] ** 4)
                print(f"{case} ({mesh}, linear, G13 G23 x{factor:g}): centre w {w:.6e}, "
                      f"100 w E2 h^3/(q a^4) = {coef:.4f} (CLT 0.5416, ratio {coef / 0.5416:.4f})")
    finally:
        PLY.update(saved)


def main(argv=None):
    import argparse
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--case", action="append", choices=list(CASES),
                    help="case(s) to run (default: all)")
    ap.add_argument("--workdir", default=os.path.join(os.environ.get("TMPDIR", "/tmp"), "laminate_fe"),
                    help="where the decks are written and ccx runs")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--mesh", action="append", help="restrict to these meshes (no storing)")
    ap.add_argument("--no-store", action="store_true", help="do not write the reference files")
    ap.add_argument("--report-only", action="store_true",
                    help="rewrite reference/README.md from reference/summary.json (no ccx)")
    ap.add_argument("--refresh", action="store_true",
                    help="recompute the stations, lattice samples, extrema and CLT check of "
                         "summary.json from the stored npz files and rewrite README.md (no ccx)")
    ap.add_argument("--study", action="store_true",
                    help="linear runs on the extra meshes of STUDY (printed, nothing stored)")
    ap.add_argument("--shear-check", action="store_true",
                    help="linear runs with the transverse shear moduli x100 (printed)")
    ap.add_argument("--write-decks", metavar="DIR",
                    help="only write the decks of every mesh and analysis into DIR (no ccx)")
    args = ap.parse_args(argv)
    cases = args.case or list(CASES)
    if args.write_decks:
        os.makedirs(args.write_decks, exist_ok=True)
        for case in cases:
            for m in MESHES[CASES[case]["kind"]]:
                for nl in (True, False):
                    job = f"{case}_{m}_{'nlgeom' if nl else 'linear'}_C3D20R"
                    write_deck(os.path.join(args.write_decks, job + ".inp"), case, m, nl)
                    print(os.path.join(args.write_decks, job + ".inp"))
        return
    if args.refresh:
        refresh(cases)
        return
    if args.report_only:
        import laminate_report
        laminate_report.rewrite_from_json(cases)
        return
    if args.shear_check:
        shear_check(cases, args.workdir, args.threads)
        return
    if args.study:
        run_study(cases, args.workdir, args.threads)
        return
    store = not args.no_store and not args.mesh
    allres = {}
    for case in cases:
        allres[case] = run_case(case, args.workdir, args.threads, meshes=args.mesh, store=store,
                                eltype_check=not args.mesh)
    if store:
        import laminate_report
        laminate_report.write_summaries(allres, "python3 examples/laminate-common/laminate_fe.py")
    else:
        print(json.dumps({k: v["convergence"] for k, v in allres.items()}, indent=1))


if __name__ == "__main__":
    main()
