/* ----------------------------------------------------------------------
   USER-TLSPH: orthotropic plies through LAMMPS (ctest: lammps.Orthotropic*)

   Patch tests of laminates (two atom types at different ply angles, and an
   isotropic type beside a ply) under a homogeneous deformation: F is exact
   at every particle, and compute tlsph/stress/atom and the pair energy
   equal the analytic orthotropic St. Venant-Kirchhoff values of each
   particle's own ply, in 3D, 2D plane strain and 2D plane stress. The
   analytic values are computed here by another route than the package
   (6x6 Gauss-Jordan inverse of the compliance, 4th-order tensor rotation).
   Also: the material numbers the step uses (wave speed, hourglass modulus),
   the file form with NAME@ANGLE, restart round trips (tlsph and
   tlsph/damage) and tlsph/damage with a ply.
   TLSPH_TEST_VERBOSE=1 shows LAMMPS's screen output.
------------------------------------------------------------------------- */

#include "atom.h"
#include "compute.h"
#include "force.h"
#include "lammps.h"
#include "library.h"
#include "modify.h"
#include "pair_tlsph.h"
#include "pair_tlsph_damage.h"
#include "update.h"

#include "lammps_driver.h"
#include "tlsph_material.h"

#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

using LAMMPS_NS::LAMMPS;
using LAMMPS_NS::PairTLSPH;
using tlsph_test::run_script;

namespace {

const double PI = 3.14159265358979323846;

LAMMPS *open_lammps()
{
  return tlsph_test::open_lammps("test_tlsph_orthotropic");
}

PairTLSPH *tlsph_pair(LAMMPS *lmp)
{
  return dynamic_cast<PairTLSPH *>(lmp->force->pair);
}

/* ---------------------------------------------------------------------- */
// the analytic law, by an independent route

struct Ply {
  bool orthotropic;
  double k[9];    // E1 E2 E3 G12 G13 G23 nu12 nu13 nu23, or E nu (isotropic)
  double rho, theta;
};

const Ply CARBON_EPOXY{true, {121e9, 8.6e9, 8.6e9, 4.7e9, 4.7e9, 3.1e9, 0.27, 0.27, 0.4}, 1490, 0};
const Ply STEEL{false, {210e9, 0.3}, 7800, 0};

Ply at(Ply p, double theta)
{
  p.theta = theta;
  return p;
}

// C_ijkl (3x3x3x3, flat) of a ply in global axes
std::vector<double> stiffness_tensor(const Ply &p)
{
  std::vector<double> T(81, 0.0);
  auto id = [](int i, int j, int k, int l) {
    return 27 * i + 9 * j + 3 * k + l;
  };
  if (!p.orthotropic) {
    const double E = p.k[0], nu = p.k[1];
    const double lam = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        for (int k = 0; k < 3; k++)
          for (int l = 0; l < 3; l++)
            T[id(i, j, k, l)] =
                lam * (i == j) * (k == l) + mu * ((i == k) * (j == l) + (i == l) * (j == k));
    return T;
  }
  // compliance, engineering shear, order 11 22 33 23 13 12; inverted by Gauss-Jordan
  const double *k = p.k;
  double S[36] = {0}, Sc[36], C[36];
  S[0] = 1 / k[0];
  S[7] = 1 / k[1];
  S[14] = 1 / k[2];
  S[1] = S[6] = -k[6] / k[0];
  S[2] = S[12] = -k[7] / k[0];
  S[8] = S[13] = -k[8] / k[1];
  S[21] = 1 / k[5];
  S[28] = 1 / k[4];
  S[35] = 1 / k[3];
  std::copy(S, S + 36, Sc);
  EXPECT_TRUE(TLSPH::invert_small(6, Sc, C));
  const int v[9] = {0, 5, 4, 5, 1, 3, 4, 3, 2};
  std::vector<double> L(81);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) L[id(i, j, a, b)] = C[6 * v[3 * i + j] + v[3 * a + b]];
  const double t = p.theta * PI / 180.0;
  const double R[9] = {std::cos(t), -std::sin(t), 0, std::sin(t), std::cos(t), 0, 0, 0, 1};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      for (int kk = 0; kk < 3; kk++)
        for (int l = 0; l < 3; l++) {
          double acc = 0.0;
          for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++)
              for (int c = 0; c < 3; c++)
                for (int d = 0; d < 3; d++)
                  acc += R[3 * i + a] * R[3 * j + b] * R[3 * kk + c] * R[3 * l + d] *
                      L[id(a, b, c, d)];
          T[id(i, j, kk, l)] = acc;
        }
  return T;
}

struct Analytic {
  double sigma[9];    // Cauchy stress
  double psi;         // strain energy density
};

/* sigma = F S F^T / J with S = C : E, E = (F^T F - I)/2; plane stress: E33
   such that S33 = 0 and F33 = sqrt(1 + 2 E33) */
Analytic analytic(const Ply &p, const double *F0, int dim, bool plane_stress)
{
  const std::vector<double> T = stiffness_tensor(p);
  auto C = [&](int i, int j, int k, int l) {
    return T[27 * i + 9 * j + 3 * k + l];
  };
  double F[9];
  std::copy(F0, F0 + 9, F);
  double E[9];
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double acc = 0.0;
      for (int k = 0; k < 3; k++) acc += F[3 * k + i] * F[3 * k + j];
      E[3 * i + j] = 0.5 * (acc - (i == j));
    }
  if (dim == 2 && plane_stress) {
    double rest = 0.0;
    for (int k = 0; k < 3; k++)
      for (int l = 0; l < 3; l++)
        if (!(k == 2 && l == 2)) rest += C(2, 2, k, l) * E[3 * k + l];
    E[8] = -rest / C(2, 2, 2, 2);
    F[8] = std::sqrt(1.0 + 2.0 * E[8]);
  }
  double S[9];
  Analytic out;
  out.psi = 0.0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double acc = 0.0;
      for (int k = 0; k < 3; k++)
        for (int l = 0; l < 3; l++) acc += C(i, j, k, l) * E[3 * k + l];
      S[3 * i + j] = acc;
    }
  if (dim == 2 && plane_stress) S[8] = 0.0;
  for (int k = 0; k < 9; k++) out.psi += 0.5 * S[k] * E[k];
  const double J = F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) +
      F[2] * (F[3] * F[7] - F[4] * F[6]);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double acc = 0.0;
      for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++) acc += F[3 * i + a] * S[3 * a + b] * F[3 * j + b];
      out.sigma[3 * i + j] = acc / J;
    }
  return out;
}

// pair_coeff words of a ply (inline form)
std::string coeff(int type, const Ply &p)
{
  char buf[400];
  if (p.orthotropic)
    snprintf(buf, sizeof(buf),
             "pair_coeff %d %d E1 %.17g E2 %.17g E3 %.17g G12 %.17g G13 %.17g G23 %.17g nu12 "
             "%.17g nu13 %.17g nu23 %.17g rho %.17g theta %.17g\n",
             type, type, p.k[0], p.k[1], p.k[2], p.k[3], p.k[4], p.k[5], p.k[6], p.k[7], p.k[8],
             p.rho, p.theta);
  else
    snprintf(buf, sizeof(buf), "pair_coeff %d %d E %.17g nu %.17g rho %.17g\n", type, type, p.k[0],
             p.k[1], p.rho);
  return buf;
}

/* ---------------------------------------------------------------------- */
// a two-type block: type 2 above the middle (z in 3D, y in 2D: the ply
// angle always turns about z)

std::string block_script(int dim, const std::string &plane, int ntypes_extra = 0)
{
  std::string s = "units si\natom_style peri\natom_modify map array\n";
  if (dim == 3) {
    s += R"(dimension 3
boundary s s s
lattice sc 0.001
region box block 0 7 0 6 0 7
)";
    s += "create_box " + std::to_string(2 + ntypes_extra) + " box\n";
    s += R"(create_atoms 1 box
region top block INF INF INF INF 3.5 INF units lattice
set region top type 2
set group all volume 1e-9
)";
  } else {
    s += R"(dimension 2
boundary s s p
lattice sq 0.001
region box block 0 9 0 8 -0.5 0.5
)";
    s += "create_box " + std::to_string(2 + ntypes_extra) + " box\n";
    s += R"(create_atoms 1 box
region top block INF INF 3.5 INF INF INF units lattice
set region top type 2
set group all volume 1e-6
)";
  }
  s += "pair_style tlsph h 0.00133 alpha 1.0 gamma 1.0";
  if (dim == 2) s += " plane " + plane;
  s += "\n";
  return s;
}

// masses rho V per type
std::string masses(int dim, const Ply &p1, const Ply &p2)
{
  const double V = (dim == 3) ? 1e-9 : 1e-6;
  char buf[200];
  snprintf(buf, sizeof(buf), "set type 1 mass %.17g\nset type 2 mass %.17g\n", p1.rho * V,
           p2.rho * V);
  return buf;
}

// a general (non-symmetric) homogeneous deformation, x = F X: stretch, shear
// and a finite rotation, strains of a few percent
void deformation(int dim, double *F)
{
  const double G[9] = {0.021, -0.013, 0.008, 0.017, -0.011, 0.006, -0.009, 0.012, 0.015};
  for (int k = 0; k < 9; k++) F[k] = (k % 4 == 0) + G[k];
  if (dim == 2) F[2] = F[5] = F[6] = F[7] = 0.0, F[8] = 1.0;
  // plus a rotation by 0.3 rad about z (objectivity through the whole chain)
  const double c = std::cos(0.3), s = std::sin(0.3);
  const double R[9] = {c, -s, 0, s, c, 0, 0, 0, 1};
  double RF[9];
  TLSPH::mat_mul(R, F, RF);
  std::copy(RF, RF + 9, F);
}

// x = F X; displace_atoms moves one component after the other, so the
// variables read the positions frozen before the move (fix store/state)
std::string displace(int dim, const double *F)
{
  char buf[800];
  const char *X = "f_X0[1]", *Y = "f_X0[2]", *Z = "f_X0[3]";
  if (dim == 3)
    snprintf(buf, sizeof(buf),
             "fix X0 all store/state 0 x y z\n"
             "variable ux atom %.17g*%s+%.17g*%s+%.17g*%s\n"
             "variable uy atom %.17g*%s+%.17g*%s+%.17g*%s\n"
             "variable uz atom %.17g*%s+%.17g*%s+%.17g*%s\n"
             "displace_atoms all move v_ux v_uy v_uz units box\nunfix X0\n",
             F[0] - 1, X, F[1], Y, F[2], Z, F[3], X, F[4] - 1, Y, F[5], Z, F[6], X, F[7], Y,
             F[8] - 1, Z);
  else
    snprintf(buf, sizeof(buf),
             "fix X0 all store/state 0 x y\n"
             "variable ux atom %.17g*%s+%.17g*%s\nvariable uy atom %.17g*%s+%.17g*%s\n"
             "displace_atoms all move v_ux v_uy 0 units box\nunfix X0\n",
             F[0] - 1, X, F[1], Y, F[3], X, F[4] - 1, Y);
  return buf;
}

LAMMPS_NS::Compute *find_compute(LAMMPS *lmp, const char *id)
{
  const int ic = lmp->modify->find_compute(id);
  EXPECT_GE(ic, 0);
  return lmp->modify->compute[ic];
}

struct PatchResult {
  double dF, dsigma, dpsi;    // max relative errors
  double contrast;            // how different the two types' stresses are (relative)
  int n[3];                   // particles per type
};

/* A homogeneous deformation of a block of two types with the laws p1, p2
   (inline coefficients, or the words of `coeffs` if not empty) */
PatchResult patch(int dim, const std::string &plane, const Ply &p1, const Ply &p2,
                  const std::string &coeffs = "")
{
  LAMMPS *lmp = open_lammps();
  double F[9];
  deformation(dim, F);
  std::string s = block_script(dim, plane) + masses(dim, p1, p2);
  s += coeffs.empty() ? coeff(1, p1) + coeff(2, p2) : coeffs;
  // partners found in the reference state (run 0), then the deformation
  s += R"(compute s all tlsph/stress/atom
compute d all tlsph/defgrad/atom
fix 1 all nve
thermo_style custom step pe
run 0
)";
  s += displace(dim, F) + "run 0\n";
  run_script(lmp, s);
  const bool ps = (plane == "stress");
  const Analytic a[3] = {Analytic{}, analytic(p1, F, dim, ps), analytic(p2, F, dim, ps)};
  LAMMPS_NS::Compute *cs = find_compute(lmp, "s"), *cd = find_compute(lmp, "d");
  cs->compute_peratom();
  cd->compute_peratom();
  const int nlocal = lmp->atom->nlocal;
  const int *type = lmp->atom->type;
  const double *vfrac = lmp->atom->vfrac;
  PatchResult r{0, 0, 0, 0, {0, 0, 0}};
  double smax = 0.0, energy = 0.0;
  for (int t = 1; t <= 2; t++)
    for (int k = 0; k < 9; k++) smax = std::max(smax, std::fabs(a[t].sigma[k]));
  const int vo[6] = {0, 4, 8, 1, 2, 5};    // xx yy zz xy xz yz
  for (int i = 0; i < nlocal; i++) {
    const int t = type[i];
    r.n[t]++;
    const double *d = cd->array_atom[i];

    for (int k = 0; k < 9; k++) {
      // 2D: F33 = 1 stored (plane stress: the thickness stretch is in sigma only)
      const double ref = (dim == 2 && k == 8) ? d[8] : F[k];
      r.dF = std::max(r.dF, std::fabs(d[k] - ref));
    }
    const double *s = cs->array_atom[i];
    for (int c = 0; c < 6; c++)
      r.dsigma = std::max(r.dsigma, std::fabs(s[c] - a[t].sigma[vo[c]]) / smax);
    energy += vfrac[i] * a[t].psi;
  }
  const double pe = lammps_get_thermo(lmp, "pe");
  r.dpsi = std::fabs(pe - energy) / energy;
  for (int k = 0; k < 9; k++)
    r.contrast = std::max(r.contrast, std::fabs(a[1].sigma[k] - a[2].sigma[k]) / smax);
  printf("patch %dD %s: %d + %d particles, max |dF| %.3g, max |dsigma|/|sigma| %.3g, energy %.3g "
         "rel, stress contrast of the types %.3g\n",
         dim, dim == 2 ? plane.c_str() : "", r.n[1], r.n[2], r.dF, r.dsigma, r.dpsi, r.contrast);
  delete lmp;
  return r;
}

void expect_patch(const PatchResult &r)
{
  EXPECT_GT(r.n[1], 30);
  EXPECT_GT(r.n[2], 30);
  EXPECT_LT(r.dF, 1e-12);
  EXPECT_LT(r.dsigma, 1e-10);
  EXPECT_LT(r.dpsi, 1e-10);
  // the test means something only if the two laws differ
  EXPECT_GT(r.contrast, 0.1);
}

}    // namespace

/* ---------------------------------------------------------------------- */

TEST(OrthotropicPatch, cross_ply_0_90_3d)
{
  expect_patch(patch(3, "", at(CARBON_EPOXY, 0), at(CARBON_EPOXY, 90)));
}

TEST(OrthotropicPatch, angle_ply_0_45_3d)
{
  expect_patch(patch(3, "", at(CARBON_EPOXY, 0), at(CARBON_EPOXY, 45)));
}

// the file form with NAME@ANGLE gives the same plies as the inline form
TEST(OrthotropicPatch, file_form_0_45_3d)
{
  expect_patch(patch(3, "", at(CARBON_EPOXY, 0), at(CARBON_EPOXY, 45),
                     "pair_coeff * * tlsph_materials.tlsph carbon_epoxy carbon_epoxy@45\n"));
}

// an isotropic type and a ply in one body, each with its own law
TEST(OrthotropicPatch, steel_and_ply_3d)
{
  expect_patch(patch(3, "", STEEL, at(CARBON_EPOXY, -30)));
}

TEST(OrthotropicPatch, angle_ply_2d_plane_strain)
{
  expect_patch(patch(2, "strain", at(CARBON_EPOXY, 0), at(CARBON_EPOXY, 45)));
}

TEST(OrthotropicPatch, angle_ply_2d_plane_stress)
{
  expect_patch(patch(2, "stress", at(CARBON_EPOXY, 137), STEEL));
}

/* ---------------------------------------------------------------------- */

/* the numbers the step reads: c0 (time step, viscosity) = the fastest wave
   of the ply (along the fibre for carbon/epoxy, whatever theta), the
   hourglass modulus = Voigt-average E (28.18 GPa); an isotropic type keeps
   sqrt((lambda + 2 mu)/rho) and E */
TEST(OrthotropicMaterial, wave_speed_and_hourglass_modulus)
{
  LAMMPS *lmp = open_lammps();
  run_script(lmp,
             block_script(3, "", 1) + masses(3, CARBON_EPOXY, CARBON_EPOXY) +
                 coeff(1, at(CARBON_EPOXY, 0)) + coeff(2, at(CARBON_EPOXY, 45)) + coeff(3, STEEL));
  PairTLSPH *pair = tlsph_pair(lmp);
  ASSERT_NE(pair, nullptr);
  // C11 of carbon/epoxy from the closed form
  const Ply &p = CARBON_EPOXY;
  const double E1 = p.k[0], E2 = p.k[1], E3 = p.k[2], n12 = p.k[6], n13 = p.k[7], n23 = p.k[8];
  const double n32 = n23 * E3 / E2, n21 = n12 * E2 / E1, n31 = n13 * E3 / E1;
  const double D = 1 - n12 * n21 - n23 * n32 - n31 * n13 - 2 * n21 * n32 * n13;
  const double C11 = E1 * (1 - n23 * n32) / D;
  const double c_fibre = std::sqrt(C11 / p.rho);
  for (int t : {1, 2}) {
    const PairTLSPH::Material &m = pair->material(t);
    EXPECT_EQ(m.orthotropic, 1);
    EXPECT_NEAR(m.c0, c_fibre, 1e-9 * c_fibre);
    EXPECT_NEAR(m.E_hg / 1e9, 28.1758, 1e-4);
  }
  EXPECT_EQ(pair->material(2).theta, 45.0);
  const PairTLSPH::Material &s = pair->material(3);
  EXPECT_EQ(s.orthotropic, 0);
  EXPECT_EQ(s.E_hg, 210e9);
  EXPECT_NEAR(s.c0, 6020.18, 0.01);
  EXPECT_NEAR(pair->max_wave_speed(), c_fibre, 1e-9 * c_fibre);
  delete lmp;
}

/* the hourglass modulus (Voigt average) does not depend on theta, also for
   constants of very different magnitudes: with G12 ~1e86 E1 it cancelled in
   the rotated stiffness to E_hg = 0 at 45 degrees (found by the parser
   fuzzer, doc/fuzz.md; now taken in the material axes) */
TEST(OrthotropicMaterial, hourglass_modulus_independent_of_theta)
{
  LAMMPS *lmp = open_lammps();
  Ply stiff = CARBON_EPOXY;
  stiff.k[3] = 4e97;    // G12
  run_script(lmp, block_script(3, "") + masses(3, stiff, stiff) + coeff(1, at(stiff, 0)) +
                      coeff(2, at(stiff, 45)));
  PairTLSPH *pair = tlsph_pair(lmp);
  ASSERT_NE(pair, nullptr);
  const double E0 = pair->material(1).E_hg;
  EXPECT_TRUE(std::isfinite(E0) && E0 > 0.0) << E0;
  EXPECT_NEAR(pair->material(2).E_hg, E0, 1e-12 * E0);
  delete lmp;
}

/* ---------------------------------------------------------------------- */
// restart: run 40 == run 20 + write_restart + read_restart (new instance) +
// run 20, bitwise (no viscosity), and the materials come back identical

namespace {

std::string restart_setup(int dim, const std::string &style, const std::string &plane)
{
  std::string s = block_script(dim, plane);
  // block_script writes 'pair_style tlsph ... alpha 1.0': no viscosity here
  s = s.substr(0, s.find("pair_style"));
  s += "pair_style " + style + " h 0.00133 alpha 0 gamma 1.0";
  if (dim == 2) s += " plane " + plane;
  s += "\n" + masses(dim, CARBON_EPOXY, CARBON_EPOXY);
  // one ply inline with its theta, the other from the file with an angle suffix
  std::string c1 = coeff(1, at(CARBON_EPOXY, 30)), c2 = coeff(2, at(CARBON_EPOXY, -60));
  if (style == "tlsph/damage") {
    // the file's carbon_epoxy has no fracture value: inline, with s_c
    c1.insert(c1.size() - 1, " sc 0.02");
    c2.insert(c2.size() - 1, " sc 0.05");
    s += c2;
  } else
    s += "pair_coeff * * tlsph_materials.tlsph NULL carbon_epoxy@-60\n";
  s += c1;
  s += dim == 3 ? "variable vx atom 20.0*sin(y/2.0e-3)\nvariable vy atom 15.0*sin(z/2.0e-3)\n"
                  "variable vz atom 10.0*sin(x/3.0e-3)\nvelocity all set v_vx v_vy v_vz units box\n"
                : "variable vx atom 20.0*sin(y/2.0e-3)\nvariable vy atom 15.0*sin(x/2.0e-3)\n"
                  "velocity all set v_vx v_vy 0 units box\n";
  return s;
}

// atom sorting off: a restart sorts the atoms at its setup, and with newton
// on the scattered stress forces are then summed in another order (round-off
// differences, also for isotropic materials)
const char *restart_common = R"(atom_modify sort 0 0.0
neighbor 0.0002 bin
neigh_modify every 1 delay 0 check yes
fix 1 all nve
fix dt all tlsph/dt 0.3
thermo 20
)";

using ById = std::map<long, std::vector<double>>;

ById per_atom(LAMMPS *lmp, const char *name)
{
  const int nlocal = lmp->atom->nlocal;
  auto tag = (int *) lammps_extract_atom(lmp, "id");
  auto v = (double **) lammps_extract_atom(lmp, name);
  ById out;
  for (int i = 0; i < nlocal; i++) out[tag[i]] = {v[i][0], v[i][1], v[i][2]};
  return out;
}

double max_diff(const ById &a, const ById &b)
{
  EXPECT_EQ(a.size(), b.size());
  double m = 0.0;
  for (const auto &kv : a) {
    auto it = b.find(kv.first);
    if (it == b.end()) return 1e300;
    for (int d = 0; d < 3; d++) m = std::max(m, std::fabs(kv.second[d] - it->second[d]));
  }
  return m;
}

void expect_same_material(const PairTLSPH::Material &a, const PairTLSPH::Material &b, int t)
{
  EXPECT_EQ(a.orthotropic, b.orthotropic) << "type " << t;
  EXPECT_EQ(a.rho, b.rho) << "type " << t;
  EXPECT_EQ(a.theta, b.theta) << "type " << t;
  EXPECT_EQ(a.c0, b.c0) << "type " << t;
  EXPECT_EQ(a.E_hg, b.E_hg) << "type " << t;
  EXPECT_EQ(std::memcmp(&a.ortho, &b.ortho, sizeof(a.ortho)), 0) << "type " << t;
  for (int k = 0; k < 36; k++) EXPECT_EQ(a.ortho_law.C[k], b.ortho_law.C[k]) << "type " << t;
  EXPECT_EQ(a.ortho_law.plane_stress, b.ortho_law.plane_stress) << "type " << t;
}

void check_restart(int dim, const std::string &style, const std::string &plane,
                   const std::string &file)
{
  const std::string setup = restart_setup(dim, style, plane);
  LAMMPS *a = open_lammps();
  run_script(a, setup + restart_common + "run 40\n");
  const ById xa = per_atom(a, "x"), va = per_atom(a, "v");
  delete a;

  LAMMPS *b = open_lammps();
  run_script(b, setup + restart_common + "run 20\n");
  PairTLSPH *pb = tlsph_pair(b);
  ASSERT_NE(pb, nullptr);
  std::vector<PairTLSPH::Material> mb = {pb->material(1), pb->material(2)};
  EXPECT_EQ(mb[0].theta, 30.0);
  EXPECT_EQ(mb[1].theta, -60.0);
  EXPECT_EQ(mb[0].ortho_law.plane_stress, plane == "stress" ? 1 : 0);
  run_script(b, "write_restart " + file + "\n");
  delete b;

  LAMMPS *c = open_lammps();
  run_script(c, "read_restart " + file + "\n");
  PairTLSPH *pc = tlsph_pair(c);
  ASSERT_NE(pc, nullptr);
  for (int t = 1; t <= 2; t++) expect_same_material(pc->material(t), mb[t - 1], t);
  if (style == "tlsph/damage") {
    auto *d = dynamic_cast<LAMMPS_NS::PairTLSPHDamage *>(pc);
    ASSERT_NE(d, nullptr);
    run_script(c, std::string(restart_common) + "run 0\n");
    EXPECT_EQ(d->critical_stretch_of(1), 0.02);
    EXPECT_EQ(d->critical_stretch_of(2), 0.05);
  }
  run_script(c, std::string(restart_common) + "run 20\n");
  EXPECT_EQ(c->update->ntimestep, 40);
  const ById xc = per_atom(c, "x"), vc = per_atom(c, "v");
  delete c;
  remove(file.c_str());
  EXPECT_EQ(max_diff(xa, xc), 0.0);
  EXPECT_EQ(max_diff(va, vc), 0.0);
  // the plies really deformed (the comparison is not trivial)
  double vmax = 0.0;
  for (const auto &kv : va) vmax = std::max(vmax, std::fabs(kv.second[0]));
  EXPECT_GT(vmax, 1.0);
}

}    // namespace

TEST(OrthotropicRestart, plies_3d)
{
  check_restart(3, "tlsph", "", "tlsph_ortho_3d.rst");
}

TEST(OrthotropicRestart, plies_2d_plane_stress)
{
  check_restart(2, "tlsph", "stress", "tlsph_ortho_2d.rst");
}

TEST(OrthotropicRestart, damage_plies_3d)
{
  check_restart(3, "tlsph/damage", "", "tlsph_ortho_damage_3d.rst");
}

/* ---------------------------------------------------------------------- */

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  const int rc = RUN_ALL_TESTS();
  MPI_Finalize();
  return rc;
}
