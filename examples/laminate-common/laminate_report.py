"""Writes reference/summary.json and reference/README.md for the laminate
cases from the results of laminate_fe.run_case (called by laminate_fe.py)."""

import json
import os

import laminate_fe as F

LABELS = {
    "u3_tip_centre": "u3 tip-face centre (L, b/2, h/2)",
    "u3_tip_face_mean": "u3 mean over the tip face",
    "u1_tip_top_centre": "u1 tip top centre (L, b/2, h)",
    "u1_tip_bottom_centre": "u1 tip bottom centre (L, b/2, 0)",
    "u1_tip_centre": "u1 tip-face centre",
    "u2_tip_centre": "u2 tip-face centre",
    "u1_tip_face_mean": "u1 mean over the tip face",
    "twist_rad": "tip twist (rad), from u3 at y = 0 and b, z = h/2",
    "u3_top_min": "u3 min (= -max abs u3), top surface",
    "u1_top_max": "u1 max, top surface",
    "u1_top_min": "u1 min, top surface",
    "u2_top_max": "u2 max, top surface",
    "u2_top_min": "u2 min, top surface",
    "u1_A_top": "u1 at A = (0.075, 0.075, top)",
    "u2_A_top": "u2 at A",
    "u3_A_top": "u3 at A",
    "u3_centre_mid": "u3 plate centre, mid-thickness",
    "u3_centre_top": "u3 plate centre, top",
}
KEYS = {
    "beam": ["u3_tip_centre", "u3_tip_face_mean", "u1_tip_top_centre", "u1_tip_bottom_centre",
             "u2_tip_centre", "twist_rad"],
    "plate": ["u3_top_min", "u1_top_max", "u1_top_min", "u2_top_max", "u2_top_min",
              "u1_A_top", "u2_A_top", "u3_A_top", "u3_centre_mid"],
}


TINY = 1e-12  # |u| below this (m) is round-off of an exactly zero quantity ([0/90] u2, twist)


def _fmt(v):
    return "0 (round-off)" if abs(v) < TINY else f"{v:.6e}"


def _mesh_desc(case, mname):
    m = F.Mesh(*F.make_grid(case, mname))
    return f"{m.ne[0]}x{m.ne[1]}x{m.ne[2]}", m.nnode


def case_markdown(res):
    case = res["case"]
    kind = F.CASES[case]["kind"]
    keys = KEYS[kind]
    L = []
    w = L.append
    w(f"### {case}\n")
    d = res["definition"]
    w("Definition: " + ", ".join(f"{k} = {v}" for k, v in d.items() if k != "kind") + "\n")
    w("Runs (C3D20R unless stated; wall time of ccx on this machine, 2 threads):\n")
    w("| mesh | elements | nodes | analysis | element | increments / iterations | ccx wall (s) |")
    w("|---|---|---|---|---|---|---|")
    for r in res["runs"]:
        w(f"| {r['mesh']} | {'x'.join(map(str, r['ne']))} | {r['nnode']} | "
          f"{'NLGEOM' if r['nlgeom'] else 'linear'} | {r['eltype']} | "
          f"{r['increments']} / {r['iterations']} | {r['wall_s']:.1f} |")
    w("")
    for an in ("nlgeom", "linear"):
        conv = res["convergence"][an]
        meshes = list(conv)
        w(f"Mesh convergence, {an.upper() if an == 'nlgeom' else an} (value in m; in brackets the "
          f"relative difference to the {meshes[-1]} mesh):\n")
        w("| quantity | " + " | ".join(meshes) + " |")
        w("|---|" + "---|" * len(meshes))
        for k in keys:
            cells = []
            for m in meshes:
                v = conv[m][k]
                tiny = abs(conv[meshes[-1]][k]["value"]) < TINY
                cells.append(_fmt(v["value"]) + ("" if (m == meshes[-1] or tiny)
                                                 else f" ({v['rel_to_finest'] * 100:.3f} %)"))
            w(f"| {LABELS.get(k, k)} | " + " | ".join(cells) + " |")
        w("")
    if res.get("eltype_check"):
        w("C3D20 (full integration) against C3D20R (reduced), medium mesh, NLGEOM:\n")
        w("| quantity | C3D20R | C3D20 | rel. diff |")
        w("|---|---|---|---|")
        for k in keys:
            e = res["eltype_check"][k]
            rd = "-" if abs(e["C3D20R"]) < TINY else f"{e['rel_diff'] * 100:.3f} %"
            w(f"| {LABELS.get(k, k)} | {_fmt(e['C3D20R'])} | {_fmt(e['C3D20'])} | {rd} |")
        w("")
    cl = res["clt"]
    if kind == "beam":
        w("CLT check (linear run, stored mesh):\n")
        w(f"- CLT narrow beam D* = 1/d11 = {cl['Dstar_free']:.1f} N m per unit width "
          f"(= 18.87/22.16 x 5^3 of doc/references.rst): w = PL^3/(3 D* b) = {cl['w_clt_free'] * 1e3:.4f} mm")
        if abs(cl['Dstar_twist_restrained'] - cl['Dstar_free']) > 1e-9 * cl['Dstar_free']:
            w(f"- twist curvature restrained (kappa_xy = 0): D* = {cl['Dstar_twist_restrained']:.1f} N m, "
              f"w = {cl['w_clt_twist_restrained'] * 1e3:.4f} mm")
        w(f"- Timoshenko shear estimate P L/(5/6 G_xz b h), G_xz = {cl['Gxz_mean'] / 1e9:.3f} GPa "
          f"(thickness mean): {cl['w_shear_timoshenko'] * 1e3:.4f} mm")
        w(f"- FE linear tip-face centre: {cl['w_fe_linear_tip_centre'] * 1e3:.4f} mm "
          f"(tip-face mean {cl['w_fe_linear_tip_face_mean'] * 1e3:.4f} mm); "
          f"FE / CLT = {cl['fe_over_clt_free']:.4f}; FE / (CLT + shear) = {cl['fe_over_clt_free_plus_shear']:.4f}"
          + (f"; FE / CLT(twist restrained) = {cl['fe_over_clt_twist_restrained']:.4f}"
             if abs(cl['Dstar_twist_restrained'] - cl['Dstar_free']) > 1e-9 * cl['Dstar_free'] else ""))
        w("")
    else:
        w("CLT check (linear run, stored mesh):\n")
        w(f"- CLT (Ritz): 100 w E2 h^3/(q a^4) = 0.5416, w = {cl['w_clt'] * 1e3:.4f} mm")
        w(f"- FE linear centre, mid-thickness: w = {cl['w_fe_linear_centre_mid'] * 1e3:.4f} mm, "
          f"coefficient {cl['coefficient_fe_mid']:.4f} (top surface {cl['coefficient_fe_top']:.4f}); "
          f"FE / CLT = {cl['fe_over_clt']:.4f}")
        w(f"- FE NLGEOM centre, mid-thickness: w = {cl['w_fe_nlgeom_centre_mid'] * 1e3:.4f} mm")
        w("")
    w(f"Stations on the stored ({res['stored_mesh']}) mesh, exact surfaces:\n")
    w("| quantity | NLGEOM | linear |")
    w("|---|---|---|")
    for k in keys:
        w(f"| {LABELS.get(k, k)} | {_fmt(res['stations_nlgeom'][k])} | {_fmt(res['stations_linear'][k])} |")
    w("")
    lat, latl = res["lattice_nlgeom"], res["lattice_linear"]
    w("Sampled on the TLSPH particle lattice (dx = 1 mm, particles at (i+0.5) dx):\n")
    if kind == "beam":
        w(f"Tip particle layer x = {lat['x_layer']}; central particles y, z in {{4.5, 5.5}} mm.\n")
        w("| quantity | NLGEOM | linear |")
        w("|---|---|---|")
        for k, lab in (("u3_central4_mean", "u3 mean of the 4 central particles"),
                       ("u3_layer_mean", "u3 mean of the 100 tip-layer particles"),
                       ("u1_top_particles_mean", "u1 mean of the 2 central top particles (z = 9.5 mm)"),
                       ("u1_bottom_particles_mean", "u1 mean of the 2 central bottom particles (z = 0.5 mm)"),
                       ("u2_central4_mean", "u2 mean of the 4 central particles")):
            w(f"| {lab} | {_fmt(lat[k])} | {_fmt(latl[k])} |")
        w("")
        w("u1 and u3 through the thickness, mean of the particle columns y = 4.5 and 5.5 mm at "
          f"x = {lat['x_layer']} (NLGEOM):\n")
        w("| z (mm) | u1 | u3 |")
        w("|---|---|---|")
        for z, u1, u3 in zip(lat["z"], lat["column_mean_u1"], lat["column_mean_u3"]):
            w(f"| {z * 1e3:.1f} | {_fmt(u1)} | {_fmt(u3)} |")
        w("")
    else:
        w(f"Top particle layer z = {lat['z_layer']} (100 x 100 particles):\n")
        w("| quantity | NLGEOM | linear |")
        w("|---|---|---|")
        for k in ("u3_top_layer_min", "u1_top_layer_max", "u1_top_layer_min",
                  "u2_top_layer_max", "u2_top_layer_min"):
            w(f"| {k} | {_fmt(lat[k])} | {_fmt(latl[k])} |")
        for comp, i in (("u1", 0), ("u2", 1), ("u3", 2)):
            w(f"| {comp} at A, mean of the 4 particles (74.5/75.5, 74.5/75.5) | "
              f"{_fmt(lat['A_top_layer']['neighbours_mean'][i])} | {_fmt(latl['A_top_layer']['neighbours_mean'][i])} |")
            w(f"| {comp} at A interpolated at exactly (75, 75) | "
              f"{_fmt(lat['A_top_layer']['exact_0.075'][i])} | {_fmt(latl['A_top_layer']['exact_0.075'][i])} |")
        w("")
        if "extrema_nlgeom" in res:
            w("Extrema of u1, u2, u3 on the bottom and top surfaces and particle layers (NLGEOM; "
              "u1 peaks on the top surface, u2 on the bottom one):\n")
            w("| where | z (mm) | u1 max | u1 min | u2 max | u2 min | u3 min |")
            w("|---|---|---|---|---|---|---|")
            for name, e in res["extrema_nlgeom"].items():
                w(f"| {name} | {e['z'] * 1e3:.1f} | " + " | ".join(
                    _fmt(e[k]) for k in ("u1_max", "u1_min", "u2_max", "u2_min", "u3_min")) + " |")
            w("")
        w("Through-thickness profile at A (NLGEOM), exactly at x = y = 75 mm and as the mean of the "
          "4 neighbouring particle columns:\n")
        w("| z (mm) | u1 exact | u2 exact | u3 exact | u1 4-mean | u2 4-mean | u3 4-mean |")
        w("|---|---|---|---|---|---|---|")
        pe, pn = lat["A_profile_exact_0.075"], lat["A_profile_neighbours_mean"]
        for i, z in enumerate(lat["z"]):
            w(f"| {z * 1e3:.1f} | " + " | ".join(_fmt(p[c][i]) for p in (pe, pn) for c in ("u1", "u2", "u3")) + " |")
        w("")
    return "\n".join(L)


def write_summaries(allres, command):
    by_folder = {}
    for case, res in allres.items():
        by_folder.setdefault(F.CASES[case]["folder"], []).append(res)
    ver = F.ccx_version()
    for folder, results in by_folder.items():
        d = os.path.join(F.EXAMPLES, folder, "reference")
        os.makedirs(d, exist_ok=True)
        path = os.path.join(d, "summary.json")
        old = {}
        if os.path.exists(path):
            with open(path) as f:
                old = json.load(f).get("cases", {})
        for r in results:
            old[r["case"]] = r
        doc = dict(generator="examples/laminate-common/laminate_fe.py",
                   command=command, ccx_version=ver, ply=F.PLY,
                   meshes={k: F.MESHES[F.CASES[k]["kind"]] for k in old},
                   units="m, N, Pa; displacements in m",
                   note="load = dead load in -z (consistent nodal forces of a uniform traction); "
                        "NLGEOM = total-Lagrangian St. Venant-Kirchhoff",
                   cases=old)
        with open(path, "w") as f:
            json.dump(doc, f, indent=1)
        write_markdown(folder, doc)


def rewrite_from_json(cases):
    for folder in sorted({F.CASES[c]["folder"] for c in cases}):
        with open(os.path.join(F.EXAMPLES, folder, "reference", "summary.json")) as f:
            write_markdown(folder, json.load(f))


def write_markdown(folder, doc):
    d = os.path.join(F.EXAMPLES, folder, "reference")
    md = [f"# FE reference ({folder})\n",
          "Generated by `examples/laminate-common/laminate_fe.py` (CalculiX "
          f"{doc['ccx_version']}); do not edit, regenerate everything (about 30 min on 2 cores) with\n\n"
          f"    {doc['command']}\n",
          "Files:\n",
          "- `<case>.npz`: the stored (fine) mesh and its NLGEOM nodal displacements (float64);",
          "- `<case>_linear.npz`: the same mesh, linear run;",
          "- `<case>_coarse.npz`: the coarse mesh, both runs (ctest `fe.ccx_regenerate` recomputes it);",
          "- `*.inp.gz`: the CalculiX decks of the coarse runs and of the stored-mesh NLGEOM run "
          "(every other deck: `laminate_fe.py --write-decks DIR`);",
          "- `summary.json`: everything below, machine-readable.\n",
          "Evaluate the field at any material point with `examples/laminate-common/laminate_reference.py`: "
          "`sample(case, points, analysis='nlgeom')`. "
          "See examples/laminate-common/README.md for the model and the discussion.\n"]
    for case in sorted(doc["cases"]):
        md.append(case_markdown(doc["cases"][case]))
    with open(os.path.join(d, "README.md"), "w") as f:
        f.write("\n".join(md) + "\n")
