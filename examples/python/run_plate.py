#!/usr/bin/python3
"""A TLSPH fracture run driven from Python (Debian's python3-lammps).

A 2D glass plate (plane strain, unit thickness), 40 mm by 20 mm, with a
10 mm centre crack along y = 0 (pair_style tlsph/damage precrack), flies
freely: no boundary conditions, the initial velocity is a rigid drift in x
plus a stretch in y,

    v = (vdrift, vstretch * y / (H/2)),

so that the crack faces open, the crack tips see a stress concentration and
the cracks run out from them.  Nothing acts on the plate from outside, so its
momentum must stay what it was (M vdrift, 0): the script checks that on the
velocities it pulls out of LAMMPS.

What it shows:
  1. create a LAMMPS instance and load the package: tlsph.register(lmp) for
     Debian's LAMMPS (no PLUGIN package), or 'plugin load' where the LAMMPS
     has PLUGIN (doc/Howto_load.rst);
  2. build the plate with lmp.command() / lmp.commands_string();
  3. run in chunks (lmp.command("run N")) and pull per-particle data into numpy
     between them: lmp.numpy.extract_atom() for id, x, x0 (the reference
     position of atom_style peri), v, rmass; lmp.numpy.extract_compute() for the
     per-atom arrays of compute tlsph/stress/atom and tlsph/damage/atom;
     lmp.get_thermo() and extract_compute() for global values;
  4. plot with matplotlib: the plate coloured by sigma_yy and by the damage, and
     the time history (energies, broken bonds) -> OUT/plate.png;
  5. write_dump the final state and save the extracted arrays (OUT/plate.npz)
     so that they can be compared (unittest/output/check_run_plate.py).

Run (from anywhere; -h for the options):
    /usr/bin/python3 examples/python/run_plate.py --out /tmp/plate
It prints one line per chunk and at the end
    momentum drift |P(t) - P(0)| / (M vdrift) = ...
"""

import argparse
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))


def load_package(lmp, build):
    """the package into the instance: 'plugin load' if this LAMMPS has PLUGIN,
    else tlsph.register() (Debian's LAMMPS). Returns how."""
    plugin = os.path.join(build, "tlsphplugin.so")
    if "PLUGIN" in lmp.installed_packages:
        lmp.command(f"plugin load {plugin}")
        return "plugin load " + plugin
    sys.path.insert(0, build)                       # build/tlsph.py
    sys.path.insert(1, os.path.join(ROOT, "python"))  # python/tlsph.py (finds ../build)
    import tlsph
    tlsph.register(lmp, plugin if os.path.isfile(plugin) else None)
    return "tlsph.register (" + tlsph.__file__ + ")"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 epilog=__doc__.split("\n\n", 1)[1],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default="plate-out", help="output folder (default plate-out)")
    ap.add_argument("--build", default=os.environ.get("TLSPH_BUILD", os.path.join(ROOT, "build")),
                    help="folder of tlsphplugin.so and tlsph.py (default: build/ of the "
                    "source tree, or $TLSPH_BUILD)")
    ap.add_argument("--name", default="",
                    help="LAMMPS library to load: liblammps_NAME.so (lammps(name=NAME); e.g. "
                    "'plugin' for the PLUGIN-enabled LAMMPS of scripts/build-lammps-plugin.sh, "
                    "its lib/ on LD_LIBRARY_PATH); default: Debian's liblammps.so")
    ap.add_argument("--dx", type=float, default=0.5e-3, help="particle spacing [m] (0.5 mm)")
    ap.add_argument("--tend", type=float, default=12e-6, help="simulated time [s] (12 us)")
    ap.add_argument("--chunks", type=int, default=12, help="runs between which the data are "
                    "pulled into numpy (12)")
    ap.add_argument("--vstretch", type=float, default=6.0,
                    help="stretch velocity of the top and bottom edges [m/s] (6)")
    ap.add_argument("--vdrift", type=float, default=2.0, help="rigid drift in x [m/s] (2)")
    a = ap.parse_args()

    from lammps import lammps, LMP_STYLE_ATOM, LMP_STYLE_GLOBAL, LMP_TYPE_ARRAY, LMP_TYPE_VECTOR
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    os.makedirs(a.out, exist_ok=True)
    out = os.path.abspath(a.out)
    # -screen none: LAMMPS's own output goes to the log only
    lmp = lammps(name=a.name, cmdargs=["-log", os.path.join(out, "log.lammps"),
                                       "-screen", "none"])
    how = load_package(lmp, a.build)
    print(f"LAMMPS {lmp.version()}, package loaded by {how}")

    # ---- the plate -------------------------------------------------------------
    W, H, c = 0.040, 0.020, 0.010       # plate width, height, crack length [m]
    dx = a.dx
    matfile = os.path.join(ROOT, "potentials", "tlsph_materials.tlsph")
    lmp.commands_string(f"""
        units        si
        dimension    2
        boundary     s s p
        atom_style   peri
        atom_modify  map array
        lattice      sq {dx} origin 0.5 0.5 0.0
        region       plate block {-W / 2} {W / 2} {-H / 2} {H / 2} {-dx / 2} {dx / 2} units box
        create_box   1 plate
        create_atoms 1 region plate
        set          type 1 volume {dx * dx}
        set          type 1 mass {dx * dx * 2450}
        pair_style   tlsph/damage h {1.33 * dx} alpha 0.09 alpha_d 3.1 beta 0 gamma 0 &
                     criterion tip branch yoffe precrack {-c / 2} 0.0 {c / 2} 0.0
        pair_coeff   * * {matfile} glass
        variable     vy atom {a.vstretch}*y/{H / 2}
        velocity     all set {a.vdrift} v_vy 0.0 units box
        fix          nve all nve
        fix          dt all tlsph/dt 0.3
        compute      s all tlsph/stress/atom
        compute      d all tlsph/damage/atom
        compute      e all tlsph/energy
        compute      nb all reduce sum c_d[3] c_d[4]
        variable     broken equal (c_nb[2]-c_nb[1])/2
        thermo_style custom step time dt c_e[1] c_e[4] v_broken
        thermo       50
        run          0
    """)
    natoms = lmp.get_natoms()
    print(f"{natoms} particles, dx = {dx * 1e3:g} mm, glass (E 32 GPa, Gc 3 J/m^2)")

    def pull():
        """the per-particle state, sorted by id, as numpy copies"""
        ids = lmp.numpy.extract_atom("id")
        order = np.argsort(ids)
        s = lmp.numpy.extract_compute("s", LMP_STYLE_ATOM, LMP_TYPE_ARRAY)
        d = lmp.numpy.extract_compute("d", LMP_STYLE_ATOM, LMP_TYPE_ARRAY)
        st = dict(id=ids[order].copy(),
                  x=lmp.numpy.extract_atom("x")[order].copy(),
                  x0=lmp.numpy.extract_atom("x0")[order].copy(),
                  v=lmp.numpy.extract_atom("v")[order].copy(),
                  m=lmp.numpy.extract_atom("rmass")[order].copy(),
                  stress=s[order].copy(), damage=d[order].copy())
        st["time"] = lmp.get_thermo("time")
        st["step"] = int(lmp.get_thermo("step"))
        return st

    st0 = pull()
    M = st0["m"].sum()
    P0 = (st0["m"][:, None] * st0["v"]).sum(axis=0)
    hist = []

    def record(st):
        e = lmp.numpy.extract_compute("e", LMP_STYLE_GLOBAL, LMP_TYPE_VECTOR)
        P = (st["m"][:, None] * st["v"]).sum(axis=0)
        hist.append(dict(t=st["time"], strain=e[0], kinetic=e[3],
                         broken=lmp.extract_variable("broken"),
                         dmax=st["damage"][:, 0].max(), P=P))

    record(st0)
    # ---- run in chunks: the time step is chosen by fix tlsph/dt, so the number of
    # steps per chunk comes from the current step size
    dt = lmp.get_thermo("dt")
    nchunk = max(1, int(round(a.tend / a.chunks / dt)))
    for _ in range(a.chunks):
        lmp.command(f"run {nchunk} post no")
        st = pull()
        record(st)
        h = hist[-1]
        print(f"t = {h['t'] * 1e6:6.2f} us  step {st['step']:5d}  strain energy "
              f"{h['strain']:.4g} J  kinetic {h['kinetic']:.4g} J  broken bonds "
              f"{h['broken']:.0f}  max damage {h['dmax']:.3f}")

    # ---- the final state: a dump of LAMMPS's own, and the arrays as numpy saw them
    lmp.command(f"write_dump all custom {os.path.join(out, 'plate.final.dump')} id x y vx vy "
                "c_s[1] c_s[2] c_s[4] c_d[1] modify format float %.17g")
    np.savez(os.path.join(out, "plate.npz"), **{k: v for k, v in st.items()})

    P = np.array([h["P"] for h in hist])
    drift = np.abs(P - P0).max() / (M * abs(a.vdrift))
    cracked = st["damage"][:, 0] > 0.3          # the crack's flanks
    xc = st["x0"][cracked, 0]
    print(f"cracked particles (damage > 0.3): {cracked.sum()}, crack from x = "
          f"{xc.min() * 1e3:.1f} to {xc.max() * 1e3:.1f} mm (reference positions; "
          f"pre-crack {-c / 2 * 1e3:g} to {c / 2 * 1e3:g} mm)")
    print(f"momentum drift |P(t) - P(0)| / (M vdrift) = {drift:.3e}")

    # ---- plots -------------------------------------------------------------------
    t = np.array([h["t"] for h in hist]) * 1e6
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.2), gridspec_kw=dict(width_ratios=[1.3, 1.3, 1]))
    ms = 4.0e4 * dx     # marker size for ~600 px wide panels
    x = st["x"] * 1e3
    sc = ax[0].scatter(x[:, 0], x[:, 1], c=st["stress"][:, 1] / 1e6, s=ms, cmap="coolwarm",
                       marker="s", linewidths=0)
    fig.colorbar(sc, ax=ax[0], label=r"$\sigma_{yy}$ [MPa]")
    sc = ax[1].scatter(x[:, 0], x[:, 1], c=st["damage"][:, 0], s=ms, cmap="inferno_r",
                       vmin=0, vmax=1, marker="s", linewidths=0)
    fig.colorbar(sc, ax=ax[1], label="damage")
    for k, title in ((0, "stress"), (1, "damage")):
        ax[k].set_aspect("equal")
        ax[k].set_xlabel("x [mm]")
        ax[k].set_ylabel("y [mm]")
        ax[k].set_title(f"{title} at t = {t[-1]:.1f} us")
    ax[2].plot(t, [h["strain"] for h in hist], label="strain energy")
    ax[2].plot(t, [h["kinetic"] for h in hist], label="kinetic energy")
    ax[2].set_xlabel("t [us]")
    ax[2].set_ylabel("energy [J]")
    ax2 = ax[2].twinx()
    ax2.plot(t, [h["broken"] for h in hist], "k--", label="broken bonds")
    ax2.set_ylabel("broken bonds")
    ax[2].legend(loc="upper left", fontsize=8)
    ax2.legend(loc="lower right", fontsize=8)
    ax[2].set_title("history")
    fig.tight_layout()
    png = os.path.join(out, "plate.png")
    fig.savefig(png, dpi=80)
    print(f"wrote {png}")
    lmp.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
