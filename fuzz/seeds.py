#!/usr/bin/env python3
"""Seed corpus of the parser fuzzer (doc/fuzz.md): writes one file per seed
into DIR. A seed is byte 0 (the set-up, see fuzz_parser.cpp) and text:
line 1 the pair_style arguments, then inline pair_coeff argument lists, or
(file form) the material names and the material file.

    seeds.py DIR
"""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MATFILE = open(os.path.join(ROOT, "potentials", "tlsph_materials.tlsph")).read()

# byte 0
D3, DAMAGE, FILE, RUN, NEWTON_OFF, REISSUE = 1, 2, 16, 32, 64, 128
T2, T3 = 4, 12

ISO = "E 210e9 nu 0.3 rho 7800"
ORTHO = ("E1 120e9 E2 8e9 E3 8e9 G12 4e9 G13 4e9 G23 3e9 nu12 0.3 nu13 0.3 nu23 0.4 "
         "rho 1500")
CE = ("E1 121e9 E2 8.6e9 E3 8.6e9 G12 4.7e9 G13 4.7e9 G23 3.1e9 nu12 0.27 nu13 0.27 "
      "nu23 0.4 rho 1490")

SEEDS = [
    # ---- inline, pair_style tlsph (examples/cantilever-*, laminate-*)
    ("iso_2d", RUN, "h 0.0015 alpha 1.0 beta 0 gamma 1.0\n* * " + ISO),
    ("iso_2d_stress", RUN, "h 0.0015 alpha 1.0 plane stress thickness 0.002\n1 1 " + ISO),
    ("iso_3d_linear", D3 | RUN, "h 0.0015 gradient linear cutfactor 1.2\n* * " + ISO),
    ("iso_3d_quadratic", D3 | NEWTON_OFF, "h 0.0015 gradient quadratic\n* * " + ISO),
    ("two_types", T2 | RUN, "h 0.0015\n1 1 " + ISO + "\n2 2 E 70e9 nu 0.33 rho 2700"),
    ("three_types_ortho", D3 | T3 | RUN,
     "h 0.0015\n1 1 " + ISO + "\n2 2 " + ORTHO + " theta 45\n3 3 " + ORTHO + " theta -30"),
    ("ortho_3d", D3 | RUN, "h 0.0015\n* * " + CE + " theta 90"),
    ("ortho_2d_reissue", REISSUE, "h 0.0015 plane stress\n* * " + ORTHO + " theta 30"),
    ("sc_on_tlsph", 0, "h 0.0015\n* * " + ISO + " sc 0.01"),
    # ---- inline, pair_style tlsph/damage (examples/kalthoff-*, crack-branching)
    ("damage_gc_2d", DAMAGE | RUN,
     "h 0.00133 alpha 1.0 alpha_d 1.0 beta 0.0 gamma 1.0 precrack -0.001 0.0015 0.002 0.0015\n"
     "1 1 E 190e9 nu 0.3 rho 8000 Gc 22.13e3"),
    ("damage_sc_2d", DAMAGE | RUN | NEWTON_OFF,
     "h 0.0015 criterion absolute correction rebuild\n* * E 32e9 nu 0.2 rho 2450 sc 0.001"),
    ("damage_3d_precrack", DAMAGE | D3 | RUN,
     "h 0.0015 precrack 0 0 0.0015 0.003 0 0.0015 0 0.003 0.0015\n* * " + ISO + " sc 0.0005"),
    ("damage_ortho_sc", DAMAGE | D3 | T2,
     "h 0.0015 gradient quadratic\n1 1 " + ORTHO + " sc 0.01\n2 2 " + ISO + " Gc 3"),
    ("damage_reissue", DAMAGE | REISSUE | RUN, "h 0.0015 plane strain\n* * " + ISO + " Gc 100"),
    # ---- the material file (potentials/tlsph_materials.tlsph)
    ("file_steel", FILE | RUN, "h 0.0015\nsteel\n" + MATFILE),
    ("file_two", FILE | T2, "h 0.0015\nsteel glass\n" + MATFILE),
    ("file_plies_3d", FILE | D3 | T2 | RUN, "h 0.0015\ncarbon_epoxy@0 carbon_epoxy@90\n" + MATFILE),
    ("file_plies_2d", FILE | T3 | REISSUE,
     "h 0.0015 plane stress\ncarbon_epoxy@0 carbon_epoxy@45 carbon_epoxy@-45\n" + MATFILE),
    ("file_null", FILE | T2, "h 0.0015\nsteel NULL\n" + MATFILE),
    ("file_damage", FILE | DAMAGE | T3 | RUN,
     "h 0.0015\nmaraging_steel glass maraging_steel\n" + MATFILE),
    ("file_small", FILE, "h 0.0015\nm\n# comment\nm E 1 nu 0 rho 1\n"),
    ("file_units", FILE, "h 0.0015\nm\n# DATE: 2024-01-01 UNITS: metal\nm E 1 nu 0 rho 1\n"),
    ("file_duplicate", FILE, "h 0.0015\nm\nm E 1 nu 0 rho 1\nm E 2 nu 0.1 rho 2\n"),
    ("file_tabs_cr", FILE, "h 0.0015\nm\nm\tE 2e9\r\n"),
    # ---- accepted values far from the usual ones (units other than si, or
    # mistakes): the derived constants must stay finite or be refused
    ("far_h_large", RUN, "h 1e100 cutfactor 2\n* * " + ISO),
    ("far_h_small", D3 | RUN, "h 1e-100\n* * " + ISO),
    ("far_moduli", RUN, "h 0.0015\n* * E 1e200 nu 0.45 rho 1e-100"),
    ("far_ortho", D3, "h 0.0015\n* * E1 1e100 E2 1e99 E3 1e99 G12 1e98 G13 1e98 G23 1e98 "
     "nu12 0.3 nu13 0.3 nu23 0.4 rho 1e-50 theta 30"),
    ("far_damage", DAMAGE | RUN, "h 1e-50 alpha_d 1e100\n* * E 1e-100 nu 0.3 rho 1e100 Gc 1e-140"),
    # found by the fuzzer (doc/fuzz.md): G12 ~1e86 E1 gave E_hg = 0 at 45 degrees
    ("found_ply_G12_huge", FILE | T3 | REISSUE,
     "h 0.0015 plane stress\ncarbon_epoxy@0 carbon_epoxy@45 carbon_epoxy@-45\n"
     + MATFILE.replace("G12 4.7e9", "G12 4e97")),
    # ---- malformed (unittest/lammps/bad_input.py)
    ("bad_h", 0, "h 1e\n* * " + ISO),
    ("bad_overflow", 0, "h 0.0015\n* * E 1e999 nu 0.3 rho 7800"),
    ("bad_nu", 0, "h 0.0015\n* * E 210e9 nu 0.5 rho 7800"),
    ("bad_odd", 0, "h 0.0015\n* * E 210e9 nu 0.3 rho"),
    ("bad_mixed", D3, "h 0.0015\n* * " + ORTHO + " E 210e9"),
    ("bad_nu12", D3, "h 0.0015\n* * " + ORTHO.replace("nu12 0.3", "nu12 5")),
    ("bad_angle", FILE | D3, "h 0.0015\ncarbon_epoxy@abc\n" + MATFILE),
    ("bad_precrack", DAMAGE, "h 0.0015 precrack 0 0 1\n* * " + ISO + " sc 0.01"),
    ("bad_range", T2, "h 0.0015\n3 3 " + ISO),
    ("bad_types", T2, "h 0.0015\n1 2 " + ISO),
]


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for name, cfg, text in SEEDS:
        with open(os.path.join(out, name), "wb") as f:
            f.write(bytes([cfg]) + text.encode())
    print(f"{len(SEEDS)} seeds in {out}")


if __name__ == "__main__":
    main()
