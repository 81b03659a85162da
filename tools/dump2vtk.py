#!/usr/bin/python3
"""dump2vtk: LAMMPS text dumps (dump custom / dump atom) to VTK for ParaView.

Writes one VTK XML unstructured grid (.vtu) per frame -- the particles as
points with one vertex cell each, every other column of the dump as point
data -- and a ParaView collection file (.pvd) that lists the frames with
their times, so that ParaView opens the whole dump as one time series.
The .vtu files are written by meshio (Debian: python3-meshio), binary,
zlib-compressed, every value in double precision (the dump's numbers exactly).

  /usr/bin/python3 tools/dump2vtk.py kalthoff-2d.full.dump
      -> kalthoff-2d.full.pvd, kalthoff-2d.full_0000.vtu, ..._0001.vtu, ...
  paraview kalthoff-2d.full.pvd

Input
-----
Text dumps of dump custom or dump atom, 2D or 3D, one or many frames
(several files are read one after the other, e.g. those of a dump file name
with '*'), gzip-compressed or not.  Every frame is converted on its own: a
frame may hold any subset of the particles (dump_modify thresh, e.g. the
damage dumps of the fracture decks, which after step 0 hold only the damaged
particles), in any order; the points of a frame are sorted by id when the dump
has an id column (--keep-order: as in the file).  The header items ITEM: UNITS
and ITEM: TIME (dump_modify units/time yes) are optional.  An incomplete last
frame (a dump still being written) is skipped with a warning.

Points: the columns x y z, else xu yu zu, else xs ys zs or xsu ysu zsu
(scaled: mapped through the frame's box, triclinic included).  A missing z
(2D dumps without a z column) is 0.

Point data (names as ParaView shows them):
  id, type, and any other single column      under its dump name (c_pe, mass, ...)
  vx vy vz          -> velocity (3-vector)      fx fy fz -> force
  ix iy iz          -> image                    mux muy muz -> dipole
  omegax.. angmomx.. tqx..  -> angular_velocity, angular_momentum, torque
  xu yu zu (when the points come from x y z)  -> unwrapped_position
  Bracketed columns c_ID[1] c_ID[2] ... (and f_ID[k]) of one compute or fix
  are grouped by the compute's style:
    displace/atom          [1-3] displacement (3-vector), [4] displacement_magnitude
    tlsph/stress/atom      [1-6] stress   (3x3 symmetric tensor, 9 components,
    tlsph/strain/atom      [1-6] strain    row by row, from LAMMPS's column
                                           order xx yy zz xy xz yz)
    tlsph/defgrad/atom     [1-9] defgrad (3x3, row by row), [10] detF
    tlsph/damage/atom      [1] damage, [2] damage_smoothed, [3] bonds_intact,
                           [4] bonds_initial
  Components missing from the dump are written as 0: the z components of
  2D vectors, and in 2D the stress's zz, xz, yz when the dump holds only
  c_ID[1] c_ID[2] c_ID[4] (xx yy xy; in plane strain sigma_zz is not 0, dump
  c_ID[3] for it).  A note on stderr says so.  The compute IDs of the
  package's decks and pages are known: dmg (tlsph/damage/atom), sfull
  (tlsph/stress/atom), ufull (displace/atom).  Other IDs: give the style with
  --compute ID=STYLE or let the tool read the 'compute' commands of the
  input script or log with --log FILE; a generic layout also works:
    --compute ID=vector[:NAME]     [1-3] a 3-vector
    --compute ID=symtensor[:NAME]  [1-6] xx yy zz xy xz yz -> 3x3
    --compute ID=tensor[:NAME]     [1-9] row by row -> 3x3
    --compute ID=scalars           each column on its own (under its dump name)
  Bracketed columns of an unknown compute or fix stay single columns under
  their dump names (c_ID[1], ...).

Frame times (the pvd's timestep): ITEM: TIME when the dump has it, else the
step (--time step: always the step).  --tmin/--tmax select frames by that
time, --every N keeps every N-th of the frames in the range (the first one
included).

Output: OUTDIR/PREFIX.pvd and OUTDIR/PREFIX_NNNN.vtu, NNNN = the frame's
index in the input (0, 1, ...; frames left out by --every or the time range
keep their numbers free).  Defaults: OUTDIR = the folder of the (first)
dump, PREFIX = its file name without a trailing .gz and .dump/.txt/.lammpstrj.

Exit status 0, or 2 with a message for an input that is not a LAMMPS text
dump (or a malformed one, with the file and line).
"""

import argparse
import gzip
import os
import re
import sys
import xml.etree.ElementTree as ET

import numpy as np

# ------------------------------------------------------------------ layout

# per-atom vector attributes of dump custom: (x, y, z keywords) -> field name
ATTR_VECTORS = [
    (("vx", "vy", "vz"), "velocity"),
    (("fx", "fy", "fz"), "force"),
    (("ix", "iy", "iz"), "image"),
    (("mux", "muy", "muz"), "dipole"),
    (("omegax", "omegay", "omegaz"), "angular_velocity"),
    (("angmomx", "angmomy", "angmomz"), "angular_momentum"),
    (("tqx", "tqy", "tqz"), "torque"),
]
POSITIONS = [("x", "y", "z"), ("xu", "yu", "zu"), ("xs", "ys", "zs"), ("xsu", "ysu", "zsu")]
INT_COLUMNS = {"id", "type", "mol", "proc", "procp1", "ix", "iy", "iz"}

# compute styles -> list of (kind, name, indices); kind: vector (3 indices),
# symtensor (6 indices xx yy zz xy xz yz), tensor (9 indices row by row),
# scalar (1 index)
STYLES = {
    "displace/atom": [("vector", "displacement", (1, 2, 3)),
                      ("scalar", "displacement_magnitude", (4,))],
    "tlsph/stress/atom": [("symtensor", "stress", (1, 2, 3, 4, 5, 6))],
    "tlsph/strain/atom": [("symtensor", "strain", (1, 2, 3, 4, 5, 6))],
    "tlsph/defgrad/atom": [("tensor", "defgrad", tuple(range(1, 10))),
                           ("scalar", "detF", (10,))],
    "tlsph/damage/atom": [("scalar", "damage", (1,)), ("scalar", "damage_smoothed", (2,)),
                          ("scalar", "bonds_intact", (3,)), ("scalar", "bonds_initial", (4,))],
}
GENERIC = {"vector": (1, 2, 3), "symtensor": (1, 2, 3, 4, 5, 6),
           "tensor": tuple(range(1, 10))}
# the compute IDs of the package's decks (examples/*/in.*) and doc pages
DEFAULT_COMPUTES = {"dmg": "tlsph/damage/atom", "sfull": "tlsph/stress/atom",
                    "ufull": "displace/atom"}
# Voigt position (LAMMPS order xx yy zz xy xz yz, 1-based) -> 3x3 entries
VOIGT = {1: [(0, 0)], 2: [(1, 1)], 3: [(2, 2)], 4: [(0, 1), (1, 0)],
         5: [(0, 2), (2, 0)], 6: [(1, 2), (2, 1)]}
BRACKET = re.compile(r"^([cf])_([^\[\]]+)\[(\d+)\]$")


class DumpError(Exception):
    """the input is not a (well-formed) LAMMPS text dump"""


def note(msg):
    print(f"dump2vtk: {msg}", file=sys.stderr)


def layout_for(style_spec):
    """style or generic kind ('vector:name') -> list of (kind, name, indices); None = scalars"""
    kind, _, name = style_spec.partition(":")
    if kind in STYLES:
        lay = STYLES[kind]
        if name and len(lay) == 1:
            lay = [(lay[0][0], name, lay[0][2])]
        return lay
    if kind in GENERIC:
        return [(kind, name, GENERIC[kind])]
    if kind == "scalars":
        return None
    raise ValueError(f"unknown compute style or kind '{kind}' (known: "
                     + ", ".join(sorted(STYLES) + sorted(GENERIC) + ["scalars"]) + ")")


def computes_from_log(path):
    """ID -> style of every 'compute ID group style ...' command in an input script or log"""
    found = {}
    with open(path, errors="replace") as f:
        for line in f:
            w = line.split("#", 1)[0].split()
            if len(w) >= 4 and w[0] == "compute":
                found[w[1]] = w[3]
    return found


class Plan:
    """how the columns of a dump (one ATOMS header) become points and point data"""

    def __init__(self, names, computes):
        self.names = names
        col = {n: k for k, n in enumerate(names)}
        used = set()
        self.points = None      # (kind, [col or None]*3); kind: plain | scaled
        for trip in POSITIONS:
            if trip[0] in col and trip[1] in col:
                self.points = ("scaled" if trip[0].startswith("xs") else "plain",
                               [col.get(c) for c in trip])
                used.update(c for c in trip if c in col)
                break
        if self.points is None:
            raise DumpError("the dump has no positions (columns x y [z], xu yu [zu], "
                            "xs ys [zs] or xsu ysu [zsu]); its columns: " + " ".join(names))
        self.fields = []        # (name, kind, spec, is_int); kind: scalar | vector | ...tensor
        self.notes = []
        for n in ("id", "type"):
            if n in col:
                self.fields.append((n, "scalar", col[n], True))
                used.add(n)
        for trip, fname in ATTR_VECTORS + [(("xu", "yu", "zu"), "unwrapped_position")]:
            if any(c in col and c not in used for c in trip):
                idx = [col.get(c) for c in trip]
                self.fields.append((fname, "vector", idx, trip[0] in INT_COLUMNS))
                used.update(c for c in trip if c in col)
                self._missing(fname, [c for c, i in zip(trip, idx) if i is None])
        # bracketed columns, grouped by compute / fix ID
        groups = {}
        for n in names:
            m = BRACKET.match(n)
            if m and n not in used:
                groups.setdefault((m.group(1), m.group(2)), {})[int(m.group(3))] = col[n]
        for (cf, cid), cols in groups.items():
            spec = computes.get(cid) if cf == "c" else computes.get("f_" + cid)
            if spec is None:
                key = cid if cf == "c" else "f_" + cid
                self.notes.append(f"{cf}_{cid}[...]: style unknown, single columns under "
                                  f"their dump names (--compute {key}=STYLE or --log)")
                continue
            try:
                lay = layout_for(spec)
            except ValueError:      # a style read from a log that has no layout here
                self.notes.append(f"{cf}_{cid}[...]: compute style {spec} has no layout "
                                  "here, single columns under their dump names")
                continue
            if lay is None:
                continue
            for kind, fname, idxs in lay:
                fname = fname or cid
                present = [i for i in idxs if i in cols]
                if not present:
                    continue
                missing = [i for i in idxs if i not in cols]
                if kind == "scalar":
                    self.fields.append((fname, "scalar", cols[idxs[0]], False))
                elif kind == "vector":
                    self.fields.append((fname, "vector", [cols.get(i) for i in idxs], False))
                else:
                    self.fields.append((fname, kind, {i: cols[i] for i in present}, False))
                if missing:
                    self._missing(fname, [f"{cf}_{cid}[{i}]" for i in missing])
                used.update(names[cols[i]] for i in present)
        for n in names:
            if n not in used:
                self.fields.append((n, "scalar", col[n], n in INT_COLUMNS))
        seen = set()
        for f in self.fields:
            if f[0] in seen:
                raise DumpError(f"two fields would be named '{f[0]}' (columns: {' '.join(names)})")
            seen.add(f[0])

    def _missing(self, fname, cols):
        if cols:
            self.notes.append(f"{fname}: {' '.join(cols)} not in the dump, written as 0")

    def describe(self):
        out = []
        kind, idx = self.points
        out.append("points <- " + " ".join(self.names[i] if i is not None else "0" for i in idx)
                   + (" (scaled, through the box)" if kind == "scaled" else ""))
        for fname, kind, spec, _ in self.fields:
            if kind == "scalar":
                src = self.names[spec]
            elif kind == "vector":
                src = " ".join(self.names[i] if i is not None else "0" for i in spec)
            else:
                src = " ".join(self.names[i] for i in spec.values())
            shape = {"scalar": "", "vector": " (3-vector)", "symtensor": " (3x3 tensor)",
                     "tensor": " (3x3 tensor)"}[kind]
            out.append(f"{fname}{shape} <- {src}")
        return out

    def arrays(self, data, box):
        """(points (n,3), {name: array}) of one frame's data (n, ncol)"""
        n = data.shape[0]
        kind, idx = self.points
        pts = np.zeros((n, 3))
        for d, i in enumerate(idx):
            if i is not None:
                pts[:, d] = data[:, i]
        if kind == "scaled":
            pts = box.unscale(pts, [i is not None for i in idx])
        pdata = {}
        for fname, fkind, spec, is_int in self.fields:
            if fkind == "scalar":
                a = data[:, spec]
            elif fkind == "vector":
                a = np.zeros((n, 3))
                for d, i in enumerate(spec):
                    if i is not None:
                        a[:, d] = data[:, i]
            elif fkind == "symtensor":
                t = np.zeros((n, 3, 3))
                for v, i in spec.items():
                    for r, c in VOIGT[v]:
                        t[:, r, c] = data[:, i]
                a = t.reshape(n, 9)
            else:   # tensor, row by row
                a = np.zeros((n, 9))
                for v, i in spec.items():
                    a[:, v - 1] = data[:, i]
            pdata[fname] = a.astype(np.int64) if is_int else np.ascontiguousarray(a)
        return pts, pdata


# ------------------------------------------------------------------ reading

class Box:
    def __init__(self, lo, hi, tilt):
        self.lo, self.hi, self.tilt = lo, hi, tilt     # bounds as written, xy xz yz

    def unscale(self, s, present):
        """scaled (fractional) coordinates -> positions (LAMMPS's triclinic box conversion)"""
        xy, xz, yz = self.tilt
        lo, hi = self.lo.copy(), self.hi.copy()
        if any(self.tilt):       # the bounds written are those of the bounding box
            lo[0] -= min(0.0, xy, xz, xy + xz)
            hi[0] -= max(0.0, xy, xz, xy + xz)
            lo[1] -= min(0.0, yz)
            hi[1] -= max(0.0, yz)
        L = hi - lo
        s = s.copy()
        for d in range(3):
            if not present[d]:
                s[:, d] = 0.0
        x = np.empty_like(s)
        x[:, 0] = lo[0] + L[0] * s[:, 0] + xy * s[:, 1] + xz * s[:, 2]
        x[:, 1] = lo[1] + L[1] * s[:, 1] + yz * s[:, 2]
        x[:, 2] = lo[2] + L[2] * s[:, 2]
        for d in range(3):
            if not present[d]:
                x[:, d] = 0.0
        return x


class Frame:
    __slots__ = ("index", "step", "time", "names", "data", "box", "path", "line")


class LineReader:
    def __init__(self, path):
        self.path = path
        with open(path, "rb") as f:
            magic = f.read(2)
        if magic == b"\x1f\x8b":
            self.f = gzip.open(path, "rt", errors="strict")
        else:
            self.f = open(path, "rt", errors="strict")
        self.lineno = 0

    def where(self):
        return f"{self.path}:{self.lineno}"

    def readline(self):
        try:
            line = self.f.readline()
        except UnicodeDecodeError:
            raise DumpError(f"{self.path}:{self.lineno + 1}: not a text file (a binary dump? "
                            "convert it with LAMMPS's tools/binary2txt first)") from None
        if line:
            self.lineno += 1
        return line

    def close(self):
        self.f.close()


def _expect_number(r, conv, what):
    line = r.readline()
    try:
        return conv(line.split()[0])
    except (ValueError, IndexError):
        raise DumpError(f"{r.where()}: expected {what}, found {line.strip()!r}") from None


def _frame_ends(r, line, item, step, what=""):
    """True when the file ends where a frame's `item` line should be (the last
    frame is incomplete: a note, and the caller stops); a DumpError when another
    line stands there; False when the line is `item`"""
    if line.startswith(item):
        return False
    if not line:
        note(f"{r.where()}: the last frame (step {step}) is incomplete: skipped")
        return True
    raise DumpError(f"{r.where()}: expected '{item}'{what}, found {line.strip()[:60]!r}")


def read_frames(paths, select):
    """yield the Frames of the dumps; select(index, step, time) -> parse this frame?
    (frames not selected are skipped without parsing their atom lines)"""
    index = -1
    for path in paths:
        r = LineReader(path)
        first = True
        try:
            while True:
                line = r.readline()
                if not line:
                    break
                if not line.strip():
                    continue
                time = None
                start = r.lineno
                while line.rstrip() in ("ITEM: UNITS", "ITEM: TIME"):
                    if line.startswith("ITEM: UNITS"):
                        r.readline()
                    else:
                        time = _expect_number(r, float, "the time after ITEM: TIME")
                    line = r.readline()
                if not line.startswith("ITEM: TIMESTEP"):
                    if first:
                        raise DumpError(
                            f"{r.where()}: not a LAMMPS text dump: a dump starts with "
                            f"'ITEM: TIMESTEP' (after ITEM: UNITS / ITEM: TIME), found "
                            f"{line.strip()[:60]!r}")
                    raise DumpError(f"{r.where()}: expected 'ITEM: TIMESTEP' (a new frame), "
                                    f"found {line.strip()[:60]!r}")
                first = False
                step = _expect_number(r, int, "the step after ITEM: TIMESTEP")
                line = r.readline()
                if line.startswith("ITEM: NUMBER OF ENTRIES"):
                    raise DumpError(f"{r.where()}: a 'dump local' file; dump2vtk converts "
                                    "per-atom dumps (dump custom, dump atom)")
                if _frame_ends(r, line, "ITEM: NUMBER OF ATOMS", step):
                    break
                natoms = _expect_number(r, int, "the number of atoms")
                line = r.readline()
                if _frame_ends(r, line, "ITEM: BOX BOUNDS", step):
                    break
                triclinic = "xy" in line.split()
                lo, hi, tilt = np.zeros(3), np.zeros(3), [0.0, 0.0, 0.0]
                blines = [r.readline() for _ in range(3)]
                if not blines[-1]:
                    note(f"{r.where()}: the last frame (step {step}) is incomplete: skipped")
                    break
                for d, bl in enumerate(blines):
                    try:
                        w = [float(v) for v in bl.split()]
                        lo[d], hi[d] = w[0], w[1]
                        if triclinic:
                            tilt[d] = w[2]
                    except (ValueError, IndexError):
                        raise DumpError(f"{r.path}:{r.lineno - 2 + d}: expected box bounds, "
                                        f"found {bl.strip()!r}") from None
                head = r.readline()
                if _frame_ends(r, head, "ITEM: ATOMS", step, " and the column names"):
                    break
                names = head.split()[2:]
                if not names:
                    raise DumpError(f"{r.where()}: 'ITEM: ATOMS' names no columns")
                body_line = r.lineno + 1
                lines = [r.readline() for _ in range(natoms)]
                if natoms and not lines[-1]:
                    note(f"{r.where()}: the last frame (step {step}) is incomplete: skipped")
                    break
                index += 1
                keep = select(index, step, time)
                if not keep:
                    continue
                fr = Frame()
                fr.index, fr.step, fr.time, fr.names = index, step, time, names
                fr.box = Box(lo, hi, tilt)
                fr.path, fr.line = path, start
                fr.data = _parse_atoms(lines, names, path, body_line)
                yield fr
        finally:
            r.close()
        if first:
            raise DumpError(f"{path}: empty: not a LAMMPS dump")


def _parse_atoms(lines, names, path, body_line):
    ncol = len(names)
    tokens = "".join(lines).split()
    if len(tokens) != ncol * len(lines):
        for k, ln in enumerate(lines):
            if len(ln.split()) != ncol:
                raise DumpError(f"{path}:{body_line + k}: {len(ln.split())} values on an atom "
                                f"line, the ATOMS header names {ncol} columns")
    try:
        return np.array(tokens, dtype=float).reshape(len(lines), ncol)
    except ValueError:
        pass
    # a non-numeric column (e.g. 'element'): NaN there, dropped by the caller's plan
    s = np.array(tokens, dtype=object).reshape(len(lines), ncol)
    out = np.empty((len(lines), ncol))
    for j in range(ncol):
        try:
            out[:, j] = s[:, j].astype(float)
        except ValueError:
            out[:, j] = np.nan
            names[j] = "#" + names[j]     # marks a text column
    return out


# ------------------------------------------------------------------ writing

def write_pvd(path, entries):
    """entries: [(time, vtu file name relative to the pvd)]"""
    root = ET.Element("VTKFile", type="Collection", version="0.1",
                      byte_order="LittleEndian" if sys.byteorder == "little" else "BigEndian")
    coll = ET.SubElement(root, "Collection")
    for t, fname in entries:
        ET.SubElement(coll, "DataSet", timestep=repr(float(t)), group="", part="0",
                      file=fname)
    ET.indent(root)
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        ET.ElementTree(root).write(f, encoding="utf-8", xml_declaration=True)
        f.write(b"\n")
    os.replace(tmp, path)


def default_prefix(path):
    name = os.path.basename(path)
    if name.endswith(".gz"):
        name = name[:-3]
    for ext in (".dump", ".txt", ".lammpstrj"):
        if name.endswith(ext) and len(name) > len(ext):
            return name[: -len(ext)]
    return name


def parse_args(argv):
    ap = argparse.ArgumentParser(
        prog="dump2vtk.py",
        description=__doc__.split("\n\n", 1)[0].split(": ", 1)[1],
        epilog=__doc__.split("\n\n", 1)[1],
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dump", nargs="+", help="LAMMPS text dump file(s), read in this order")
    ap.add_argument("-o", "--outdir", help="output folder (default: that of the first dump; "
                    "made if missing)")
    ap.add_argument("-p", "--prefix", help="output file name prefix (default: the dump's "
                    "file name without .dump)")
    ap.add_argument("--every", type=int, default=1, metavar="N",
                    help="keep every N-th frame of the time range (default 1: all)")
    ap.add_argument("--tmin", type=float, help="first time (or step) to convert")
    ap.add_argument("--tmax", type=float, help="last time (or step) to convert")
    ap.add_argument("--time", choices=("auto", "step"), default="auto",
                    help="frame times: ITEM: TIME if present, else the step (auto, default), "
                    "or always the step")
    ap.add_argument("--compute", action="append", default=[], metavar="ID=STYLE[:NAME]",
                    help="the style (or vector, symtensor, tensor, scalars) of compute ID "
                    "(f_ID=... for a fix); repeatable")
    ap.add_argument("--log", action="append", default=[], metavar="FILE",
                    help="read the compute styles from the 'compute' commands of this input "
                    "script or LAMMPS log; repeatable")
    ap.add_argument("--keep-order", action="store_true",
                    help="keep the file's particle order (default: sorted by id)")
    ap.add_argument("--info", action="store_true",
                    help="list the frames and the fields, write nothing")
    a = ap.parse_args(argv)
    if a.every < 1:
        ap.error("--every must be >= 1")
    return a, ap


def main(argv=None):
    a, ap = parse_args(argv)
    computes = dict(DEFAULT_COMPUTES)
    try:
        for path in a.log:
            computes.update(computes_from_log(path))
        for spec in a.compute:
            cid, eq, style = spec.partition("=")
            if not eq or not cid or not style:
                ap.error(f"--compute {spec}: expected ID=STYLE")
            layout_for(style)
            computes[cid] = style
    except (OSError, ValueError) as e:
        ap.error(str(e))
    for path in a.dump:
        if not os.path.isfile(path):
            ap.error(f"{path}: no such file")
    outdir = a.outdir or os.path.dirname(os.path.abspath(a.dump[0]))
    prefix = a.prefix or default_prefix(a.dump[0])
    if not a.info:
        os.makedirs(outdir, exist_ok=True)
    try:
        import meshio
    except ImportError:
        print("dump2vtk: error: needs meshio (Debian: apt-get install python3-meshio; "
              "run with /usr/bin/python3)", file=sys.stderr)
        return 2

    state = {"k": 0, "frames": 0}    # frames selected by the range, frames read

    def frame_time(step, time):
        return time if (time is not None and a.time == "auto") else step

    def select(index, step, time):
        state["frames"] += 1
        t = frame_time(step, time)
        if a.tmin is not None and t < a.tmin:
            return False
        if a.tmax is not None and t > a.tmax:
            return False
        k = state["k"]
        state["k"] += 1
        return k % a.every == 0

    plans = {}
    entries = []
    written = []
    width = 4
    try:
        for fr in read_frames(a.dump, select):
            key = tuple(fr.names)
            if key not in plans:
                keep = [j for j, n in enumerate(fr.names) if not n.startswith("#")]
                if len(keep) < len(fr.names):
                    note("text columns left out: "
                         + " ".join(n[1:] for n in fr.names if n.startswith("#")))
                plan = Plan([fr.names[j] for j in keep], computes)
                plans[key] = (keep if len(keep) < len(fr.names) else None, plan)
                for line in plan.notes:
                    note(line)
                if a.info:
                    for line in plan.describe():
                        print("  " + line)
            keep, plan = plans[key]
            data = fr.data if keep is None else fr.data[:, keep]
            names = plan.names
            if not a.keep_order and "id" in names:
                ids = data[:, names.index("id")]
                if np.any(np.diff(ids) < 0):
                    data = data[np.argsort(ids, kind="stable")]
            t = frame_time(fr.step, fr.time)
            if a.info:
                print(f"frame {fr.index}: step {fr.step}"
                      + (f" time {fr.time!r}" if fr.time is not None else "")
                      + f", {data.shape[0]} particles")
                continue
            pts, pdata = plan.arrays(data, fr.box)
            if fr.index >= 10 ** width:
                width = len(str(fr.index))
            fname = f"{prefix}_{fr.index:0{width}d}.vtu"
            # one vertex cell per particle; an empty frame (no particle selected by
            # dump_modify thresh) is written uncompressed (VTK needs its empty Cells
            # element; meshio's own reader cannot read empty meshes back)
            cells = [("vertex", np.arange(len(pts), dtype=np.int64)[:, None])]
            mesh = meshio.Mesh(pts, cells, point_data=pdata)
            meshio.write(os.path.join(outdir, fname), mesh, file_format="vtu",
                         compression="zlib" if len(pts) else None)
            entries.append((t, fname))
            written.append(fr.index)
    except DumpError as e:
        print(f"dump2vtk: error: {e}", file=sys.stderr)
        return 2
    except OSError as e:
        print(f"dump2vtk: error: {e}", file=sys.stderr)
        return 2
    if a.info:
        return 0
    if not entries and state["frames"] == 0:
        print("dump2vtk: error: no complete frame in the dump", file=sys.stderr)
        return 2
    if not entries:
        print("dump2vtk: error: no frame in the selection (check --tmin/--tmax: "
              + ("times" if a.time == "auto" else "steps") + ")", file=sys.stderr)
        return 2
    times = [t for t, _ in entries]
    if len(set(times)) != len(times):
        note("warning: some frames have the same time; ParaView shows one of them")
    pvd = os.path.join(outdir, prefix + ".pvd")
    write_pvd(pvd, entries)
    note(f"{len(entries)} frame(s) -> {pvd} (times {times[0]!r} .. {times[-1]!r})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
