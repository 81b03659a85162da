#!/usr/bin/env python3
"""Bad input, systematically (ctest lammps.bad_input): every keyword and
numeric argument of every USER-TLSPH style, missing, malformed, out of range,
conflicting, in the wrong dimension or with the wrong atom style, and bad
potential files. Each case is a small deck run by lmp_tlsph; it must stop
with a LAMMPS ERROR line whose text matches the case's pattern (which names
the command and the keyword or value at fault), exit non-zero, within the
time limit (no hang) and without a crash (signal) or NaN. A pattern that
starts with WARNING marks an input that is accepted but unused: the run
must finish normally and print that warning.

    bad_input.py --lmp build/lmp_tlsph --workdir DIR [--list] [-k SUBSTRING]

Prints one line per case and PASSED / FAILED (ctest matches PASSED). The
single-deck error tests (unittest/lammps/errors, unittest/damage/errors)
keep their own cases; this table covers the argument grammar as a whole.
"""
import argparse
import os
import re
import subprocess
import sys

# ---------------------------------------------------------------- decks
HEAD = {
    2: ("units si\ndimension 2\nboundary s s p\natom_style {atom_style}\natom_modify map array\n"
        "lattice sq 0.001\nregion box block 0 6 0 4 -0.5 0.5\ncreate_box 2 box\n"
        "create_atoms 1 box\nset type 1 volume 1e-6\nset type 1 mass 7.8e-3\n"),
    3: ("units si\ndimension 3\nboundary s s s\natom_style {atom_style}\natom_modify map array\n"
        "lattice sc 0.001\nregion box block 0 5 0 4 0 4\ncreate_box 2 box\n"
        "create_atoms 1 box\nset type 1 volume 1e-9\nset type 1 mass 7.8e-6\n"),
}
PAIR = "pair_style tlsph h 0.00133 alpha 1.0 gamma 1.0\n"
DPAIR = "pair_style tlsph/damage h 0.00133 alpha 1.0 gamma 1.0\n"
COEFF = "pair_coeff * * E 210e9 nu 0.3 rho 7800\n"
DCOEFF = "pair_coeff * * E 210e9 nu 0.3 rho 7800 sc 0.01\n"
TAIL = "fix 1 all nve\ntimestep 1e-8\nrun 0\n"
ORTHO = "E1 120e9 E2 8e9 E3 8e9 G12 4e9 G13 4e9 G23 3e9 nu12 0.3 nu13 0.3 nu23 0.4 rho 1500"

GOOD_FILE = "steel E 210e9 nu 0.3 rho 7800\nply E1 120e9 E2 8e9 E3 8e9 G12 4e9 G13 4e9 G23 3e9 " \
            "nu12 0.3 nu13 0.3 nu23 0.4 rho 1500\n"


def deck(body, dim=2, atom_style="peri", pair=PAIR, coeff=COEFF, tail=TAIL):
    """a deck: head, pair_style, pair_coeff, body, tail (None drops a part)"""
    parts = [HEAD[dim].format(atom_style=atom_style), pair or "", coeff or "", body, tail or ""]
    return "".join(parts)


def ps(args, dim=2):
    """a pair_style tlsph line with these arguments"""
    return deck("", dim=dim, pair=f"pair_style tlsph {args}\n")


def pds(args, dim=2, coeff=DCOEFF):
    return deck("", dim=dim, pair=f"pair_style tlsph/damage {args}\n", coeff=coeff)


def pc(args, dim=2, pair=PAIR):
    return deck("", dim=dim, pair=pair, coeff=f"pair_coeff {args}\n")


def fx(line, pair=PAIR, coeff=COEFF, dim=2):
    return deck(line + "\n", dim=dim, pair=pair, coeff=coeff)


def pv(volume, mass, dim=2, pair=PAIR, coeff=COEFF):
    """a deck whose particles get this volume and mass ('set' lines; None: not set,
    atom_style peri's default 1)"""
    v0, m0 = ("1e-6", "7.8e-3") if dim == 2 else ("1e-9", "7.8e-6")
    head = HEAD[dim].format(atom_style="peri")
    head = head.replace(f"set type 1 volume {v0}\n", "" if volume is None else f"set type 1 volume {volume}\n")
    head = head.replace(f"set type 1 mass {m0}\n", "" if mass is None else f"set type 1 mass {mass}\n")
    return head + pair + coeff + TAIL


def loner(pair):
    """the 2D block in a box twice as long, plus one particle 4 spacings away from
    it (alone on purpose, e.g. a projectile)"""
    head = HEAD[2].format(atom_style="peri").replace(
        "region box block 0 6 0 4 -0.5 0.5\ncreate_box 2 box\ncreate_atoms 1 box\n",
        "region box block 0 12 0 4 -0.5 0.5\ncreate_box 2 box\nregion body block 0 6 0 4 -0.5 0.5\n"
        "create_atoms 1 region body\ncreate_atoms 1 single 10 2 0\n")
    return head + pair + COEFF + TAIL


def one_row():
    """a single row of particles in 2D: every partner on one line"""
    head = HEAD[2].format(atom_style="peri").replace("boundary s s p", "boundary s f p").replace(
        "create_atoms 1 box\n", "region row block 0 6 1.9 2.1 -0.5 0.5\ncreate_atoms 1 region row\n")
    return head + PAIR + COEFF + TAIL


H = "h 0.00133"
# (name, deck text, files {name: text}, pattern the ERROR line must match)
CASES = [
    # ------------------------------------------------ pair_style tlsph: every keyword
    ("ps_no_args", ps(""), {}, r"pair_style tlsph: keyword 'h' .*is required"),
    ("ps_h_missing_value", ps("h"), {}, r"pair_style tlsph: keyword 'h' needs a value"),
    ("ps_h_word", ps("h abc"), {}, r"pair_style tlsph: h needs a number, got 'abc'"),
    ("ps_h_half_exponent", ps("h 1e"), {}, r"pair_style tlsph: h needs a number, got '1e'"),
    ("ps_h_two_signs", ps("h +-1"), {}, r"pair_style tlsph: h needs a number, got '\+-1'"),
    ("ps_h_two_points", ps("h 1.2.3"), {}, r"pair_style tlsph: h needs a number, got '1.2.3'"),
    ("ps_h_overflow", ps("h 1e999"), {}, r"pair_style tlsph: h = '1e999' is out of the range"),
    ("ps_h_zero", ps("h 0"), {}, r"pair_style tlsph: h must be > 0"),
    ("ps_h_negative", ps("h -0.001"), {}, r"pair_style tlsph: h must be > 0"),
    ("ps_h_not_given", ps("alpha 1.0"), {}, r"pair_style tlsph: keyword 'h' .*is required"),
    ("ps_alpha_word", ps(f"{H} alpha x"), {}, r"pair_style tlsph: alpha needs a number, got 'x'"),
    ("ps_alpha_negative", ps(f"{H} alpha -1"), {}, r"pair_style tlsph: alpha must be >= 0"),
    ("ps_alpha_missing", ps(f"{H} alpha"), {}, r"pair_style tlsph: keyword 'alpha' needs a value"),
    ("ps_beta_word", ps(f"{H} beta x"), {}, r"pair_style tlsph: beta needs a number"),
    ("ps_beta_negative", ps(f"{H} beta -1"), {}, r"pair_style tlsph: beta must be >= 0"),
    ("ps_gamma_word", ps(f"{H} gamma x"), {}, r"pair_style tlsph: gamma needs a number"),
    ("ps_gamma_negative", ps(f"{H} gamma -1"), {}, r"pair_style tlsph: gamma must be >= 0"),
    ("ps_hourglass_word", ps(f"{H} hourglass projected"), {},
     r"pair_style tlsph: hourglass must be 'thesis' or 'conservative', got 'projected'"),
    ("ps_plane_bad", ps(f"{H} plane foo"), {}, r"pair_style tlsph: plane must be 'strain' or 'stress', got 'foo'"),
    ("ps_plane_in_3d", ps(f"{H} plane strain", dim=3), {},
     r"pair_style tlsph: keyword 'plane' is only allowed with dimension 2"),
    ("ps_thickness_zero", ps(f"{H} thickness 0"), {}, r"pair_style tlsph: thickness must be > 0"),
    ("ps_thickness_word", ps(f"{H} thickness t"), {}, r"pair_style tlsph: thickness needs a number"),
    ("ps_thickness_in_3d", ps(f"{H} thickness 0.001", dim=3), {},
     r"pair_style tlsph: keyword 'thickness' is only allowed with dimension 2"),
    ("ps_gradient_bad", ps(f"{H} gradient cubic"), {},
     r"pair_style tlsph: gradient must be 'linear' or 'quadratic', got 'cubic'"),
    ("ps_gradient_missing", ps(f"{H} gradient"), {}, r"pair_style tlsph: keyword 'gradient' needs a value"),
    ("ps_cutfactor_small", ps(f"{H} cutfactor 0.5"), {}, r"pair_style tlsph: cutfactor must be >= 1"),
    ("ps_cutfactor_word", ps(f"{H} cutfactor big"), {}, r"pair_style tlsph: cutfactor needs a number"),
    ("ps_unknown", ps(f"{H} foo 1"), {}, r"pair_style tlsph: unknown keyword 'foo' \(allowed: h, alpha"),
    ("ps_simd_word", ps(f"{H} simd fast"), {},
     r"pair_style tlsph: simd must be 'auto', 'no', 'portable', 'avx2' or 'avx512', got 'fast'"),
    ("ps_simd_missing", ps(f"{H} simd"), {}, r"pair_style tlsph: keyword 'simd' needs a value"),
    # values the kernel or LAMMPS's squared cutoff cannot be computed with
    # (found by the parser fuzzer, doc/fuzz.md)
    ("ps_h_kernel_underflow", ps("h 1e-200"), {}, r"pair_style tlsph: h = 1e-200 with cutfactor 1.1 is out of the range a 2D kernel can be computed in"),
    ("ps_h_kernel_overflow_3d", ps("h 1e120", dim=3), {}, r"pair_style tlsph: h = 1e\+120 with cutfactor 1.1 is out of the range a 3D kernel"),
    ("ps_cutoff_overflow", ps(f"{H} cutfactor 1e308"), {}, r"pair_style tlsph: h = 0.00133 with cutfactor 1e\+308 is out of the range"),
    ("ps_check_partners_word", ps(f"{H} check_partners maybe"), {},
     r"pair_style tlsph: check_partners must be 'yes' or 'no', got 'maybe'"),
    ("ps_check_partners_missing", ps(f"{H} check_partners"), {},
     r"pair_style tlsph: keyword 'check_partners' needs a value"),
    ("ps_check_volume_word", ps(f"{H} check_volume off"), {},
     r"pair_style tlsph: check_volume must be 'yes' or 'no', got 'off'"),
    # ------------------------------------------------ h against the particle spacing
    # (every particle needs DIM partners within 2h, not on one line / in one plane)
    ("ps_h_below_spacing", ps("h 0.0001"), {},
     r"pair_style tlsph: particle 1 has 0 reference partners \(h = 0.0001, kernel support 2h = "
     r"0.0002; particle spacing dx = 0.001 from its volume, h = 0.1 dx\): a corrected gradient "
     r"needs at least 2 partners within 2h, not all on one line .*35 of 35 particles have too "
     r"few: h must be larger than the particle spacing \(h = 1.33 dx is the usual value: h "
     r"0.00133 for this spacing\).*add 'check_partners no' to pair_style"),
    ("ps_h_below_spacing_3d", ps("h 0.0004", dim=3), {},
     r"pair_style tlsph: particle 1 has 0 reference partners \(h = 0.0004, kernel support 2h = "
     r"0.0008; particle spacing dx = 0.001 from its volume, h = 0.4 dx\): a corrected gradient "
     r"needs at least 3 partners within 2h, not all in one plane \(9 for the quadratic"),
    ("pd_h_below_spacing", pds("h 0.0004"), {},
     r"pair_style tlsph: particle 1 has 0 reference partners \(h = 0.0004.*h must be larger than "
     r"the particle spacing"),
    ("ps_one_row", one_row(), {},
     r"pair_style tlsph: particle 1 has 2 reference partners, all on one line \(h = 0.00133, "
     r"kernel support 2h = 0.00266; nearest partner 0.001 away, h = 1.33 dx\).*7 of 7 particles "
     r"have too few: h is not smaller than the spacing, but a body one particle thick has no "
     r"gradient across it"),
    ("ps_isolated", loner(PAIR), {},
     r"pair_style tlsph: particle 36 has 0 reference partners .*1 of 36 particles have too few: "
     r"h is not smaller than the spacing: the particle lies apart from the others .*'check_partners no'"),
    # the override: the lone particle is meant; the run goes on, with a warning
    ("ps_isolated_override", loner(f"pair_style tlsph {H} check_partners no\n"), {},
     r"WARNING: pair_style tlsph: particle 36 has 0 reference partners .*they carry no stress of "
     r"their own \(check_partners no\)"),
    # ------------------------------------------------ volumes and masses against h and rho
    ("pv_volume_default", pv(None, "7.8e-3"), {},
     r"pair tlsph: particle 1 \(type 1\) has mass 0.0078 and volume 1: mass/volume = 0.0078, but "
     r"its material has rho = 7800 \(100% off\): set the volume .*'set type 1 volume <dx\^2 in 2D.*"
     r"'set type 1 mass <7800\*volume>'.*volume 1 is atom_style peri's default.*'check_volume no'"),
    ("pv_volume_default_3d", pv(None, "7.8e-6", dim=3), {},
     r"pair tlsph: particle 1 \(type 1\) has mass 7.8e-06 and volume 1: .*'set type 1 volume "
     r"<dx\^3 in 3D>'"),
    ("pv_mass_and_volume_default", pv(None, None), {},
     r"pair tlsph: particle 1 \(type 1\) has mass 1 and volume 1: mass/volume = 1, but its "
     r"material has rho = 7800"),
    ("pv_mass_tenfold", pv("1e-6", "7.8e-2"), {},
     r"pair tlsph: particle 1 \(type 1\) has mass 0.078 and volume 1e-06: mass/volume = 78000, "
     r"but its material has rho = 7800 \(900% off\)"),
    ("pv_mass_tenfold_override", pv("1e-6", "7.8e-2", pair=f"pair_style tlsph {H} check_volume no\n"), {},
     r"WARNING: pair tlsph: mass/volume differs from rho: particle 1 \(type 1\) has mass 0.078"),
    ("pv_mass_rounded", pv("1e-6", "7.81e-3"), {},
     r"WARNING: pair tlsph: mass/volume differs from rho: .*\(0.128% off\)"),
    # mass = rho*volume, but the volume in other units (mm^2 read as m^2)
    ("pv_volume_units", pv("1e-3", "7.8"), {},
     r"pair tlsph: the particle volumes do not match the kernel normalisation: sum_j V_j W_ij = "
     r"1001 at particle \d+ \(volume 0.001, h = 0.00133\), about 1 expected \(0.5 to 2 "
     r"accepted\) \(its nearest partner is 0.001 away: on a lattice of that spacing its volume "
     r"would be 1e-06\).*'set type N volume <dx\^2 in 2D.*'check_volume no'"),
    ("pv_volume_units_override", pv("1e-3", "7.8", pair=f"pair_style tlsph {H} check_volume no\n"), {},
     r"WARNING: pair tlsph: the particle volumes do not match the kernel normalisation: sum_j V_j "
     r"W_ij = 1001 "),
    # 2D volumes that contain a 1 mm thickness, without the 'thickness' keyword
    ("pv_thickness_missing", pv("1e-9", "7.8e-6"), {},
     r"pair tlsph: the particle volumes do not match the kernel normalisation: sum_j V_j W_ij = "
     r"0.001\d* .*dx\^2 t with pair_style ... thickness t \(t = 1 now\)"),
    # ------------------------------------------------ wrong atom style / set-up
    ("atom_style_atomic", HEAD[2].format(atom_style="atomic").split("set type")[0] + "mass * 7.8e-3\n"
     + PAIR + COEFF + TAIL, {}, r"pair tlsph requires atom_style peri"),
    ("type_without_material", pc("1 1 E 210e9 nu 0.3 rho 7800"), {},
     r"pair tlsph: atom type 2 has no material"),
    # ------------------------------------------------ pair_coeff, inline isotropic
    ("pc_E_word", pc("* * E abc nu 0.3 rho 7800"), {}, r"E needs a number, got 'abc'"),
    ("pc_E_negative", pc("* * E -1 nu 0.3 rho 7800"), {}, r"E must be > 0"),
    ("pc_E_missing", pc("* * nu 0.3 rho 7800"), {}, r"missing material value 'E'"),
    ("pc_nu_missing", pc("* * E 210e9 rho 7800"), {}, r"missing material value 'nu'"),
    ("pc_rho_missing", pc("* * E 210e9 nu 0.3"), {}, r"missing material value 'rho'"),
    ("pc_nu_half", pc("* * E 210e9 nu 0.5 rho 7800"), {}, r"nu must satisfy -1 < nu < 0.5, got 0.5"),
    ("pc_nu_below_minus_one", pc("* * E 210e9 nu -1.5 rho 7800"), {}, r"nu must satisfy -1 < nu < 0.5"),
    ("pc_rho_zero", pc("* * E 210e9 nu 0.3 rho 0"), {}, r"rho must be > 0"),
    ("pc_odd_count", pc("* * E 210e9 nu 0.3 rho"), {}, r"keyword/value pairs"),
    ("pc_unknown_key", pc("* * E 210e9 nu 0.3 rho 7800 G 80e9"), {},
     r"unknown material keyword 'G'"),
    ("pc_no_values", pc("* *"), {}, r"pair_coeff tlsph: expected 'I J E value nu value rho value'"),
    ("pc_bad_type_range", pc("3 3 E 210e9 nu 0.3 rho 7800"), {}, r"Numeric index 3 is out of bounds \(1-2\)"),
    # derived constants out of the range of a double (found by the parser fuzzer)
    ("pc_lambda_overflow", pc("* * E 1e308 nu 0.49 rho 7800"), {},
     r"pair_coeff 1 1: the material values are out of the range this style can compute with: they give a wave speed c0 = inf.*lambda = inf"),
    ("pc_wave_speed_overflow", pc("* * E 1e300 nu 0.3 rho 1e-300"), {},
     r"pair_coeff 1 1: the material values are out of the range .*c0 = inf"),
    # accepted (material files serve both styles), but said to be unused
    ("pc_sc_on_tlsph", pc("* * E 210e9 nu 0.3 rho 7800 sc 0.01"), {},
     r"WARNING: pair_coeff 1 1: 'sc' is a fracture value of pair_style tlsph/damage; pair_style tlsph ignores it"),
    # ------------------------------------------------ pair_coeff, orthotropic ply
    ("ortho_missing_E3", pc("* * " + ORTHO.replace("E3 8e9 ", ""), dim=3), {}, r"missing orthotropic material value.*'E3'"),
    ("ortho_G12_word", pc("* * " + ORTHO.replace("G12 4e9", "G12 four"), dim=3), {}, r"G12 needs a number, got 'four'"),
    ("ortho_negative", pc("* * " + ORTHO.replace("E2 8e9", "E2 -8e9"), dim=3), {}, r"pair_coeff 1 1: E2 must be > 0"),
    ("ortho_theta_word", pc("* * " + ORTHO + " theta ninety", dim=3), {}, r"theta needs a number, got 'ninety'"),
    ("ortho_mixed_iso", pc("* * " + ORTHO + " E 210e9", dim=3), {}, r"isotropic and orthotropic material keywords cannot be mixed"),
    ("ortho_nu12_big", pc("* * " + ORTHO.replace("nu12 0.3", "nu12 5"), dim=3), {}, r"nu12 = 5 is out of range: \|nu12\| must be < sqrt\(E1/E2\)"),
    ("ortho_wave_speed_overflow", pc("* * " + ORTHO.replace("rho 1500", "rho 1e-300"), dim=3), {},
     r"pair_coeff 1 1: the material values are out of the range .*c0 = inf"),
    # ------------------------------------------------ potential (material) files
    ("file_not_found", pc("* * nosuch.tlsph steel steel"), {}, r"cannot open tlsph material potential file nosuch\.tlsph"),
    ("file_name_not_found", pc("* * mat.tlsph steel iron"), {"mat.tlsph": GOOD_FILE}, r"material 'iron' \(atom type 2\) not found in file 'mat\.tlsph'"),
    ("file_too_few_names", pc("* * mat.tlsph steel"), {"mat.tlsph": GOOD_FILE}, r"file 'mat\.tlsph' needs one material name per atom type \(2\), got 1"),
    ("file_value_word", pc("* * bad.tlsph steel steel"), {"bad.tlsph": "steel E x nu 0.3 rho 7800\n"},
     r"E needs a number, got 'x'"),
    ("file_odd_count", pc("* * bad.tlsph steel steel"), {"bad.tlsph": "steel E 210e9 nu 0.3 rho\n"},
     r"keyword/value pairs"),
    ("file_unknown_key", pc("* * bad.tlsph steel steel"), {"bad.tlsph": "steel E 210e9 nu 0.3 rho 7800 K 1\n"},
     r"unknown material keyword 'K'"),
    ("file_missing_rho", pc("* * bad.tlsph steel steel"), {"bad.tlsph": "steel E 210e9 nu 0.3\n"},
     r"missing material value 'rho'"),
    ("file_angle_word", pc("* * mat.tlsph ply@abc ply@0", dim=3), {"mat.tlsph": GOOD_FILE}, r"'ply@abc' \(atom type 1\): the ply angle after '@' must be a number"),
    ("file_angle_on_isotropic", pc("* * mat.tlsph steel@30 steel"), {"mat.tlsph": GOOD_FILE}, r"'steel@30' \(atom type 1\): a ply angle '@30' needs an orthotropic material"),
    ("file_empty", pc("* * empty.tlsph steel steel"), {"empty.tlsph": "# nothing\n"}, r"material 'steel' \(atom type 1\) not found in file 'empty\.tlsph'"),
    # ------------------------------------------------ pair_style tlsph/damage
    ("pd_alpha_d_word", pds(f"{H} alpha_d x"), {}, r"pair_style tlsph/damage: alpha_d needs a number"),
    ("pd_simd_word", pds(f"{H} simd fast"), {},
     r"simd must be 'auto', 'no', 'portable', 'avx2' or 'avx512', got 'fast'"),
    ("pd_alpha_d_negative", pds(f"{H} alpha_d -1"), {}, r"pair_style tlsph/damage: alpha_d must be >= 0"),
    ("pd_alpha_d_missing", pds(f"{H} alpha_d"), {}, r"pair_style tlsph/damage: alpha_d needs a value"),
    ("pd_criterion_bad", pds(f"{H} criterion shear"), {}, r"criterion must be 'tension', 'absolute' or 'tip', got 'shear'"),
    ("pd_correction_bad", pds(f"{H} correction never"), {}, r"correction must be 'rebuild' or 'setup', got 'never'"),
    ("pd_tipseg_negative", pds(f"{H} criterion tip tipseg -1"), {}, r"tipseg must be >= 0"),
    ("pd_kfit_bad", pds(f"{H} criterion tip kfit best"), {}, r"pair_style tlsph/damage: kfit must be 'tip', 'offset', 'j' or 'interaction', got 'best'"),
    ("pd_kfit_without_tip", pds(f"{H} kfit offset"), {}, r"branch, tipdir, tipseg, kfit, kratio, jinertia, jring and tipparam are settings of 'criterion tip'"),
    ("pd_jring_order", pds(f"{H} criterion tip kfit j jring 4 2"), {}, r"jring must be two radii in h with 0 <= r1 < r2, got 4 2"),
    ("pd_jring_short", pds(f"{H} criterion tip jring 2"), {}, r"jring needs two values \(the J domain's inner and outer radius in h\)"),
    ("pd_tipparam_name", pds(f"{H} criterion tip tipparam radius 2"), {}, r"tipparam name must be sample, disc, hoopr, window or split, got 'radius'"),
    ("pd_tipparam_negative", pds(f"{H} criterion tip tipparam disc -1"), {}, r"tipparam disc must be > 0 and < 100 \(in h, or in segments for split\), got -1"),
    ("pd_tipparam_window", pds(f"{H} criterion tip tipparam window 90"), {}, r"tipparam window must be a whole number of degrees in \[1, 80\], got 90"),
    ("pd_tipparam_short", pds(f"{H} criterion tip tipparam split"), {}, r"tipparam needs a name and a value \(names: sample, disc, hoopr, window, split\)"),
    ("pd_jring_word", pds(f"{H} criterion tip jring 2 far"), {}, r"pair_style tlsph/damage: jring needs a number, got 'far'"),
    ("pd_branch_word", pds(f"{H} criterion tip branch wide"), {}, r"pair_style tlsph/damage: branch must be 'yoffe', 'yoffe/step', 'tstress', 'tstress/dynamic' or an angle in \[0, 90\) degrees, got wide"),
    ("pd_branch_tstress_missing", pds(f"{H} criterion tip kfit interaction branch tstress"), {}, r"branch tstress needs the distance r_c \(a length > 0\)"),
    ("pd_branch_tstress_negative", pds(f"{H} criterion tip kfit interaction branch tstress -1e-3"), {}, r"branch tstress needs the distance r_c > 0, got -1e-3"),
    ("pd_branch_tstress_kfit", pds(f"{H} criterion tip kfit offset branch tstress 1e-3"), {},
     r"branch tstress takes the T-stress from an interaction integral over J's ring: it needs kfit j or kfit interaction"),
    ("pd_branch_tstressdyn_missing", pds(f"{H} criterion tip kfit interaction branch tstress/dynamic"), {},
     r"branch tstress/dynamic needs the distance r_c \(a length > 0\)"),
    ("pd_branch_tstressdyn_zero", pds(f"{H} criterion tip kfit interaction branch tstress/dynamic 0"), {},
     r"branch tstress/dynamic needs the distance r_c > 0, got 0"),
    ("pd_branch_tstressdyn_kfit", pds(f"{H} criterion tip kfit tip branch tstress/dynamic 1e-3"), {},
     r"branch tstress/dynamic takes the T-stress from an interaction integral over J's ring: it needs kfit j or kfit interaction"),
    ("pd_kratio_missing", pds(f"{H} criterion tip kfit j kratio"), {}, r"kratio needs a value"),
    ("pd_kratio_bad", pds(f"{H} criterion tip kfit j kratio dynamic"), {}, r"kratio must be 'static' or 'running', got 'dynamic'"),
    ("pd_kratio_kfit", pds(f"{H} criterion tip kratio running"), {},
     r"kratio running corrects the mode ratio of tips whose K takes its size from the J-integral: it needs kfit j or kfit interaction"),
    ("pd_kratio_without_tip", pds(f"{H} kratio running"), {}, r"branch, tipdir, tipseg, kfit, kratio, jinertia, jring and tipparam are settings of 'criterion tip'"),
    ("pd_tipdir_missing", pds(f"{H} criterion tip tipdir"), {}, r"tipdir needs a value"),
    ("pd_tipdir_bad", pds(f"{H} criterion tip tipdir left"), {}, r"tipdir must be 'faces', 'hoop' or 'segment', got 'left'"),
    ("pd_tipdir_segment_kfit", pds(f"{H} criterion tip tipdir segment"), {},
     r"tipdir segment takes the T-stress from an interaction integral over J's ring: it needs kfit j or kfit interaction"),
    ("pd_tip_3d_not_through", pds(f"{H} criterion tip precrack 0.002 0.002 0.002 0.004 0.002 0.002 0.002 0.004 0.002", dim=3,
                                  coeff="pair_coeff * * E 210e9 nu 0.3 rho 7800 Gc 1000\n"), {},
     r"'criterion tip' in 3D needs pre-cracks through the thickness"),
    ("pd_precrack_short_2d", pds(f"{H} precrack 0 0 1"), {}, r"precrack needs 4 numbers in 2D"),
    ("pd_precrack_word_2d", pds(f"{H} precrack 0 0 1 x"), {}, r"precrack needs 4 numbers in 2D"),
    ("pd_precrack_short_3d", pds(f"{H} precrack 0 0 0 1 1 1", dim=3), {}, r"precrack needs 9 numbers in 3D"),
    ("pd_h_word", pds("h abc"), {}, r"pair_style tlsph: h needs a number, got 'abc'"),
    ("pd_unknown", pds(f"{H} foo 1"), {}, r"unknown keyword 'foo'"),
    ("pd_sc_negative", pds(H, coeff="pair_coeff * * E 210e9 nu 0.3 rho 7800 sc -0.01\n"), {}, r"sc must be > 0"),
    ("pd_sc_word", pds(H, coeff="pair_coeff * * E 210e9 nu 0.3 rho 7800 sc small\n"), {}, r"sc needs a number, got 'small'"),
    ("pd_Gc_zero", pds(H, coeff="pair_coeff * * E 210e9 nu 0.3 rho 7800 Gc 0\n"), {}, r"Gc must be > 0"),
    ("pd_no_fracture_value", pds(H, coeff=COEFF), {}, r"pair tlsph/damage needs a fracture value for every material: Gc .* or sc"),
    ("pd_sc_from_Gc_overflow", pds(H, coeff="pair_coeff * * E 1e-100 nu 0.3 rho 7800 Gc 1e300\n"), {},
     r"pair tlsph/damage: type 1: the critical stretch from Gc = 1e\+300 .* is inf: it must be finite and > 0"),
    ("pd_sc_from_Gc_underflow", pds(H, coeff="pair_coeff * * E 1e100 nu 0.3 rho 7800 Gc 1e-300\n"), {},
     r"pair tlsph/damage: type 1: the critical stretch from Gc = 1e-300 .* is 0: it must be finite and > 0"),
    # ------------------------------------------------ fix tlsph/dt
    ("dt_missing_C", fx("fix dt all tlsph/dt"), {}, r"fix tlsph/dt: expected 'fix ID group tlsph/dt C"),
    ("dt_C_word", fx("fix dt all tlsph/dt fast"), {}, r"fix tlsph/dt: C needs a number, got 'fast'"),
    ("dt_C_zero", fx("fix dt all tlsph/dt 0"), {}, r"fix tlsph/dt: Courant number C must satisfy 0 < C <= 1"),
    ("dt_C_two", fx("fix dt all tlsph/dt 2"), {}, r"fix tlsph/dt: Courant number C must satisfy 0 < C <= 1"),
    ("dt_every_zero", fx("fix dt all tlsph/dt 0.3 every 0"), {}, r"fix tlsph/dt: every must be > 0"),
    ("dt_every_float", fx("fix dt all tlsph/dt 0.3 every 1.5"), {}, r"fix tlsph/dt: every needs an integer, got '1.5'"),
    ("dt_every_missing", fx("fix dt all tlsph/dt 0.3 every"), {}, r"fix tlsph/dt: keyword 'every' needs a value"),
    ("dt_unknown", fx("fix dt all tlsph/dt 0.3 often 2"), {}, r"fix tlsph/dt: unknown keyword 'often'"),
    ("dt_without_pair", deck("fix dt all tlsph/dt 0.3\n", pair=None, coeff=None), {}, r"fix tlsph/dt requires pair_style tlsph or tlsph/damage"),
    # ------------------------------------------------ fix tlsph/relax
    ("relax_args", fx("fix r all tlsph/relax 1"), {}, r"fix tlsph/relax takes no arguments"),
    # ------------------------------------------------ fix tlsph/velocity/filter
    ("filter_count", fx("fix vf all tlsph/velocity/filter 0.5", pair=DPAIR, coeff=DCOEFF), {},
     r"fix tlsph/velocity/filter: expected 'fix ID group tlsph/velocity/filter phi_c eps'"),
    ("filter_phi_word", fx("fix vf all tlsph/velocity/filter high 0.1", pair=DPAIR, coeff=DCOEFF), {},
     r"fix tlsph/velocity/filter: phi_c needs a number, got 'high'"),
    ("filter_phi_big", fx("fix vf all tlsph/velocity/filter 1.5 0.1", pair=DPAIR, coeff=DCOEFF), {},
     r"phi_c \(damage threshold\) must be in \[0,1\]"),
    ("filter_eps_zero", fx("fix vf all tlsph/velocity/filter 0.5 0", pair=DPAIR, coeff=DCOEFF), {},
     r"eps \(smoothing factor\) must be in \(0,1\]"),
    ("filter_eps_word", fx("fix vf all tlsph/velocity/filter 0.5 e", pair=DPAIR, coeff=DCOEFF), {},
     r"fix tlsph/velocity/filter: eps needs a number, got 'e'"),
    ("filter_without_damage", fx("fix vf all tlsph/velocity/filter 0.5 0.1"), {}, r"fix tlsph/velocity/filter requires pair_style tlsph/damage"),
    # ------------------------------------------------ computes
    ("energy_args", fx("compute e all tlsph/energy 1"), {}, r"compute tlsph/energy takes no arguments"),
    ("damage_atom_args", fx("compute d all tlsph/damage/atom x", pair=DPAIR, coeff=DCOEFF), {},
     r"compute tlsph/damage/atom takes no arguments"),
    ("damage_atom_without_damage", fx("compute d all tlsph/damage/atom\nvariable m equal c_d[1][1]"), {},
     r"compute tlsph/damage/atom requires pair_style tlsph/damage"),
    ("crack_tips_args", fx("compute t all tlsph/crack/tips 1", pair=DPAIR, coeff=DCOEFF), {},
     r"compute tlsph/crack/tips takes no arguments"),
    ("crack_tips_without_tip", fx("compute t all tlsph/crack/tips", pair=DPAIR, coeff=DCOEFF), {},
     r"compute tlsph/crack/tips requires pair_style tlsph/damage with 'criterion tip'"),
    ("stress_args", fx("compute s all tlsph/stress/atom 2"), {}, r"compute tlsph/stress/atom takes no arguments"),
    ("strain_args", fx("compute s all tlsph/strain/atom x"), {}, r"compute tlsph/strain/atom takes no arguments"),
    ("defgrad_args", fx("compute s all tlsph/defgrad/atom x"), {}, r"compute tlsph/defgrad/atom takes no arguments"),
    ("stress_without_pair", deck("compute s all tlsph/stress/atom\n", pair=None, coeff=None), {},
     r"compute tlsph/stress/atom requires pair_style tlsph or tlsph/damage"),
]


def run_case(lmp, workdir, name, text, files, timeout):
    d = os.path.join(workdir, name)
    os.makedirs(d, exist_ok=True)
    for fn, content in files.items():
        with open(os.path.join(d, fn), "w") as f:
            f.write(content)
    with open(os.path.join(d, "in.case"), "w") as f:
        f.write(text)
    try:
        p = subprocess.run([lmp, "-in", "in.case", "-log", "none", "-echo", "none"], cwd=d,
                           capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None, "timed out (hang?)"
    return p.returncode, p.stdout + p.stderr


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--lmp", required=True)
    ap.add_argument("--workdir", required=True)
    ap.add_argument("--timeout", type=float, default=60)
    ap.add_argument("--list", action="store_true")
    ap.add_argument("-k", default="")
    a = ap.parse_args()
    names = [c[0] for c in CASES]
    assert len(names) == len(set(names)), "duplicate case names"
    bad = []
    n = 0
    for name, text, files, pattern in CASES:
        if a.k not in name:
            continue
        n += 1
        rc, out = run_case(a.lmp, a.workdir, name, text, files, a.timeout)
        errs = [l for l in out.splitlines() if re.match(r"ERROR( on proc \d+)?: ", l)]
        first = errs[0] if errs else ""
        problems = []
        if rc is None:
            problems.append(out)
        elif pattern.startswith("WARNING"):
            # an accepted input that the style does not use: a warning, a normal run
            warns = [l for l in out.splitlines() if re.search(pattern, l)]
            first = warns[0] if warns else first
            if rc != 0 or errs:
                problems.append(f"exit code {rc}, {first}")
            if not warns:
                problems.append(f"no warning matching /{pattern}/")
        else:
            if rc == 0:
                problems.append("exit code 0")
            if rc < 0 or re.search(r"Segmentation|signal \d+|core dumped|terminate called", out):
                problems.append(f"crashed (exit {rc})")
            if not errs:
                problems.append("no ERROR line")
            elif not re.search(pattern, first):
                problems.append(f"message does not match /{pattern}/")
            if re.search(r"\bnan\b", out, re.I):
                problems.append("NaN in the output")
        status = "ok  " if not problems else "FAIL"
        print(f"{status} {name:32s} {first[:150]}")
        if problems:
            print("       " + "; ".join(problems))
            bad.append(name)
    if bad:
        print(f"FAILED: {len(bad)} of {n} cases: {' '.join(bad)}")
        return 1
    print(f"PASSED: {n} bad-input cases, each a clear error naming the problem")
    return 0


if __name__ == "__main__":
    sys.exit(main())
