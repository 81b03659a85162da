#!/usr/bin/python3
"""tools/dump2vtk.py against the dumps it converts (ctest output.dump2vtk).

Runs the fracture decks briefly through lmp_tlsph --
  * examples/kalthoff-2d at dx = 1.67 mm (7,200 particles), 3 us, full-field
    dump every 1 us (columns id type x y z ux uy vx vy phi phi' sxx syy sxy)
    and the damage dump every 0.5 us (id x y phi phi'; after step 0 only the
    damaged particles),
  * examples/kalthoff-3d at dx = 5 mm, 3 layers (2,400 particles), 3 us, full
    field every 1 us (ux uy uz, vx vy vz, the six stresses),
-- plus a synthetic dump written here (unsorted, no ITEM: TIME, no z column,
an empty frame), converts each with dump2vtk.py, reads the .vtu files back
with meshio (an empty frame: its XML) and the .pvd as XML, and checks with a
dump reader of its own:
  * one .vtu per frame (per selected frame with --every/--tmin/--tmax), the
    number of points of each, the .pvd's times = ITEM: TIME (else the step)
    and files, in order;
  * the positions and every column equal to the dump's number (parsed as a
    double: the printed precision exactly), matched by id, in the field the
    tool documents: velocity, displacement (3-vectors), stress (3x3, from
    LAMMPS's xx yy zz xy xz yz), damage, damage_smoothed, id, type; the
    components a 2D dump lacks are 0; no other field;
  * a file that is not a dump, and a malformed one, exit 2 with a message and
    write no .pvd.

    check_dump2vtk.py --lmp LMP --examples DIR --tool DUMP2VTK --workdir DIR
Prints PASSED or FAILED (ctest matches PASSED) and exits 0 / 1.
"""

import argparse
import os
import subprocess
import sys
import xml.etree.ElementTree as ET

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples"))
from checks import run_lammps, verdict  # noqa: E402

# where dump2vtk.py documents each column to go: name -> (field, flat component
# indices within the field; None = a scalar field)
VOIGT9 = {1: (0,), 2: (4,), 3: (8,), 4: (1, 3), 5: (2, 6), 6: (5, 7)}


def expected_place(col):
    if col in ("x", "y", "z"):
        return "points", ("xyz".index(col),)
    if col in ("vx", "vy", "vz"):
        return "velocity", ("xyz".index(col[1]),)
    if col in ("id", "type"):
        return col, None
    if col.startswith("c_ufull["):
        return "displacement", (int(col[8:-1]) - 1,)
    if col.startswith("c_sfull["):
        return "stress", VOIGT9[int(col[8:-1])]
    if col == "c_dmg[1]":
        return "damage", None
    if col == "c_dmg[2]":
        return "damage_smoothed", None
    raise KeyError(col)


FIELD_SIZE = {"points": 3, "velocity": 3, "displacement": 3, "stress": 9}


def read_dump(path):
    """frames of a text dump: dicts time (None if absent), step, names, rows (strings)"""
    frames = []
    with open(path) as f:
        lines = f.read().splitlines()
    k = 0
    while k < len(lines):
        time = None
        if lines[k] == "ITEM: TIME":
            time = float(lines[k + 1])
            k += 2
        assert lines[k] == "ITEM: TIMESTEP", (path, k, lines[k])
        step = int(lines[k + 1])
        assert lines[k + 2] == "ITEM: NUMBER OF ATOMS"
        n = int(lines[k + 3])
        assert lines[k + 4].startswith("ITEM: BOX BOUNDS")
        names = lines[k + 8].split()[2:]
        rows = [ln.split() for ln in lines[k + 9:k + 9 + n]]
        frames.append(dict(time=time, step=step, names=names, rows=rows))
        k += 9 + n
    return frames


def convert(tool, dump, outdir, prefix, *opts):
    p = subprocess.run([sys.executable, tool, dump, "-o", outdir, "-p", prefix, *opts],
                       capture_output=True, text=True)
    return p


def read_pvd(path):
    root = ET.parse(path).getroot()
    if root.get("type") != "Collection":
        return None
    return [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")]


def compare(frames, outdir, prefix, selected, fails, label):
    """frames: the dump's; selected: their indices the conversion should hold"""
    import meshio

    pvd = read_pvd(os.path.join(outdir, prefix + ".pvd"))
    if pvd is None:
        fails.append(f"{label}: the .pvd is not a VTK Collection")
        return 0
    if len(pvd) != len(selected):
        fails.append(f"{label}: {len(pvd)} frames in the .pvd, {len(selected)} expected")
        return 0
    checked = 0
    for (t, fname), k in zip(pvd, selected):
        fr = frames[k]
        want_t = fr["time"] if fr["time"] is not None else float(fr["step"])
        if t != want_t:
            fails.append(f"{label}: frame {k}: pvd time {t!r}, the dump's {want_t!r}")
        path = os.path.join(outdir, fname)
        if not os.path.isfile(path):
            fails.append(f"{label}: frame {k}: {fname} missing")
            continue
        n = len(fr["rows"])
        if n == 0:     # meshio reads no empty mesh: the XML
            piece = ET.parse(path).getroot().find("./UnstructuredGrid/Piece")
            if piece is None or piece.get("NumberOfPoints") != "0":
                fails.append(f"{label}: frame {k}: empty frame not written with 0 points")
            checked += 1
            continue
        m = meshio.read(path)
        if m.points.shape != (n, 3):
            fails.append(f"{label}: frame {k}: {m.points.shape[0]} points, the dump has {n}")
            continue
        if len(m.cells) != 1 or m.cells[0].type != "vertex" or len(m.cells[0].data) != n:
            fails.append(f"{label}: frame {k}: not one vertex cell per particle")
        names = fr["names"]
        vals = np.array(fr["rows"], dtype=float)
        ids = vals[:, names.index("id")]
        if "id" not in m.point_data:
            fails.append(f"{label}: frame {k}: no id field")
            continue
        order = {int(i): r for r, i in enumerate(m.point_data["id"])}
        if sorted(order) != sorted(int(i) for i in ids):
            fails.append(f"{label}: frame {k}: the ids differ from the dump's")
            continue
        perm = np.array([order[int(i)] for i in ids])   # dump row -> vtu point
        data = {"points": m.points}
        data.update(m.point_data)
        expected_fields = {"id"}
        covered = {}
        for j, col in enumerate(names):
            field, comps = expected_place(col)
            if field not in data:
                fails.append(f"{label}: frame {k}: no field '{field}' for column {col}")
                continue
            arr = np.asarray(data[field])
            if field != "points":
                expected_fields.add(field)
            size = FIELD_SIZE.get(field, 1)
            arr2 = arr.reshape(len(arr), -1)
            if arr2.shape[1] != size:
                fails.append(f"{label}: frame {k}: field {field} has {arr2.shape[1]} "
                             f"components, {size} expected")
                continue
            for c in (comps or (0,)):
                got = arr2[perm, c]
                bad = np.flatnonzero(got != vals[:, j])
                if bad.size:
                    r = bad[0]
                    fails.append(f"{label}: frame {k}: {col} of id {int(ids[r])} is "
                                 f"{float(got[r])!r} in {field}[{c}], "
                                 f"the dump has {fr['rows'][r][j]}")
                covered.setdefault(field, set()).add(c)
        # what the dump does not have must be 0 (the z of 2D vectors, 2D stress)
        for field, cs in covered.items():
            arr2 = np.asarray(data[field]).reshape(n, -1)
            for c in set(range(arr2.shape[1])) - cs:
                if np.any(arr2[:, c] != 0.0):
                    fails.append(f"{label}: frame {k}: {field}[{c}] is not in the dump "
                                 "but not 0")
        extra = set(m.point_data) - expected_fields
        if extra:
            fails.append(f"{label}: frame {k}: unexpected fields {sorted(extra)}")
        checked += 1
    return checked


def synthetic(path):
    """a 2D dump without z and ITEM: TIME, rows in reverse id order, an empty frame"""
    rng = np.random.default_rng(7)
    frames = []
    with open(path, "w") as f:
        for step, n in ((0, 5), (10, 0), (20, 3)):
            f.write(f"ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ATOMS\n{n}\n"
                    "ITEM: BOX BOUNDS ss ss pp\n0 1\n0 1\n-0.5 0.5\n"
                    "ITEM: ATOMS id x y vx vy c_dmg[1]\n")
            for i in range(n, 0, -1):
                x, y, vx, vy = rng.uniform(-1, 1, 4)
                f.write(f"{i} {x:.7g} {y:.7g} {vx:.4g} {vy:.4g} {i / 10:g}\n")
            frames.append(step)
    return frames


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--lmp", required=True)
    ap.add_argument("--examples", required=True, help="examples/ of the source tree")
    ap.add_argument("--tool", required=True, help="tools/dump2vtk.py")
    ap.add_argument("--workdir", required=True)
    a = ap.parse_args()
    for k in ("lmp", "examples", "tool", "workdir"):
        setattr(a, k, os.path.abspath(getattr(a, k)))
    os.makedirs(a.workdir, exist_ok=True)
    wd = a.workdir
    mat = os.path.join(a.examples, "..", "potentials", "tlsph_materials.tlsph")
    k2, k3 = os.path.join(wd, "k2"), os.path.join(wd, "k3")
    for ext in (".full.dump", ".dump"):
        for p in (k2, k3):
            if os.path.exists(p + ext):
                os.remove(p + ext)
    runs = [
        [a.lmp, "-in", os.path.join(a.examples, "kalthoff-2d", "in.kalthoff-2d"),
         "-log", k2 + ".log", "-screen", "none", "-var", "out", k2,
         "-var", "dx", "0.00166666666666667", "-var", "tend", "3e-6", "-var", "tfull", "1e-6",
         "-var", "timg", "0", "-var", "matfile", mat],
        [a.lmp, "-in", os.path.join(a.examples, "kalthoff-3d", "in.kalthoff-3d"),
         "-log", k3 + ".log", "-screen", "none", "-var", "out", k3,
         "-var", "dx", "0.005", "-var", "thick", "0.015", "-var", "tend", "3e-6",
         "-var", "tfull", "1e-6", "-var", "timg", "0"],
    ]
    for cmd in runs:
        if not run_lammps(cmd, cwd=wd):
            return 1
    fails = []
    checks = []

    def case(label, dump, prefix, opts, select):
        frames = read_dump(dump)
        outdir = os.path.join(wd, "vtk-" + label)
        if os.path.isdir(outdir):
            for f in os.listdir(outdir):
                os.remove(os.path.join(outdir, f))
        p = convert(a.tool, dump, outdir, prefix, *opts)
        if p.returncode != 0:
            fails.append(f"{label}: dump2vtk exited {p.returncode}: {p.stderr.strip()[-500:]}")
            checks.append((f"{label}: converted", False))
            return
        sel = select(frames)
        nfail = len(fails)
        n = compare(frames, outdir, prefix, sel, fails, label)
        npts = sum(len(frames[k]["rows"]) for k in sel)
        checks.append((f"{label}: {n} of {len(sel)} frames ({npts} particle rows, "
                       f"{len(frames[0]['names'])} columns) read back equal to the dump",
                       len(fails) == nfail and n == len(sel) and len(sel) >= 2))

    every = lambda frames: list(range(len(frames)))  # noqa: E731
    case("2d-full", k2 + ".full.dump", "k2full", [], every)
    case("3d-full", k3 + ".full.dump", "k3full", [], every)
    case("2d-damage", k2 + ".dump", "k2dmg", [], every)

    # every 2nd frame of those with 0.9 us <= t <= 2.6 us of the damage dump
    def window(frames):
        inr = [k for k, fr in enumerate(frames) if 0.9e-6 <= fr["time"] <= 2.6e-6]
        return inr[::2]
    case("2d-damage-every2-window", k2 + ".dump", "k2win",
         ["--every", "2", "--tmin", "0.9e-6", "--tmax", "2.6e-6"], window)
    syn = os.path.join(wd, "synthetic.dump")
    synthetic(syn)
    case("synthetic", syn, "syn", [], every)

    # frame counts of the decks' dumps: what the test above relied on
    f2, f3, fd = (read_dump(p) for p in (k2 + ".full.dump", k3 + ".full.dump", k2 + ".dump"))
    checks.append((f"the dumps: 2D full {len(f2)} frames x {len(f2[0]['rows'])}, "
                   f"3D full {len(f3)} x {len(f3[0]['rows'])}, damage {len(fd)} frames "
                   f"({len(fd[0]['rows'])} then {len(fd[-1]['rows'])} particles)",
                   len(f2) >= 3 and len(f3) >= 3 and len(fd) >= 5
                   and 0 < len(fd[-1]["rows"]) < len(fd[0]["rows"])))

    # errors: not a dump (the log), a malformed dump (an atom line cut short)
    bad = os.path.join(wd, "bad.dump")
    with open(k2 + ".full.dump") as f:     # its first frame, atom line 3 cut short
        head = f.read().splitlines()[:11 + len(f2[0]["rows"])]
    head[13] = " ".join(head[13].split()[:-2])
    with open(bad, "w") as f:
        f.write("\n".join(head) + "\n")
    for label, path, msg in (("the log", k2 + ".log", "not a LAMMPS text dump"),
                             ("a malformed dump", bad, "values on an atom line")):
        out = os.path.join(wd, "vtk-error")
        p = convert(a.tool, path, out, "err")
        ok = (p.returncode == 2 and msg in p.stderr
              and not os.path.exists(os.path.join(out, "err.pvd")))
        checks.append((f"{label}: exit {p.returncode}, '{p.stderr.strip()[:90]}'", ok))
    # --help documents the options
    p = subprocess.run([sys.executable, a.tool, "--help"], capture_output=True, text=True)
    checks.append(("--help documents --outdir --prefix --every --tmin --tmax",
                   p.returncode == 0 and all(o in p.stdout for o in
                                             ("--outdir", "--prefix", "--every", "--tmin",
                                              "--tmax", ".pvd"))))

    for f in fails[:20]:
        print("  " + f)
    if len(fails) > 20:
        print(f"  ... {len(fails) - 20} more")
    return verdict(checks)


if __name__ == "__main__":
    sys.exit(main())
