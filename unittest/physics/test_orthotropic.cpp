/* ----------------------------------------------------------------------
   Orthotropic St. Venant-Kirchhoff (tlsph_material.h): local stiffness,
   rotation to global axes, stress, energy, 2D modes, objectivity, wave
   speed and hourglass modulus. The reference values are computed here by
   independent routes (closed-form inverse, 4th-order tensor rotation).
------------------------------------------------------------------------- */

#include "physics_system.h"

#include <gtest/gtest.h>

#include <random>

namespace {

const double PI = 3.14159265358979323846;

// thesis Table 3.6, carbon-fibre reinforced epoxy
const TLSPH::OrthotropicConstants CARBON_EPOXY{121e9, 8.6e9, 8.6e9, 4.7e9, 4.7e9,
                                               3.1e9, 0.27,  0.27,  0.4};
const double CARBON_RHO = 1490.0;

// a ply with nine different constants (no accidental symmetry)
const TLSPH::OrthotropicConstants GENERIC{70e9, 20e9, 9e9, 6e9, 4e9, 3e9, 0.31, 0.22, 0.45};

// Voigt index of the tensor pair (i, j), order 11 22 33 23 13 12
int voigt(int i, int j)
{
  static const int v[9] = {0, 5, 4, 5, 1, 3, 4, 3, 2};
  return v[3 * i + j];
}

// C_ijkl from a Voigt stiffness with engineering shear strains
double tensor(const double *C, int i, int j, int k, int l)
{
  return C[6 * voigt(i, j) + voigt(k, l)];
}

// C'_ijkl = R_ia R_jb R_kc R_ld C_abcd, returned in Voigt form
void rotate_tensor(const double *C, const double *R, double *Cr)
{
  for (int I = 0; I < 6; I++)
    for (int J = 0; J < 6; J++) {
      const int i = TLSPH::VOIGT_I[I], j = TLSPH::VOIGT_J[I];
      const int k = TLSPH::VOIGT_I[J], l = TLSPH::VOIGT_J[J];
      double acc = 0.0;
      for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
          for (int c = 0; c < 3; c++)
            for (int d = 0; d < 3; d++)
              acc +=
                  R[3 * i + a] * R[3 * j + b] * R[3 * k + c] * R[3 * l + d] * tensor(C, a, b, c, d);
      Cr[6 * I + J] = acc;
    }
}

// S_ij = C_ijkl E_kl, the 4th-order tensor route
void tensor_stress(const double *C, const double *E, double *S)
{
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double acc = 0.0;
      for (int k = 0; k < 3; k++)
        for (int l = 0; l < 3; l++) acc += tensor(C, i, j, k, l) * E[3 * k + l];
      S[3 * i + j] = acc;
    }
}

double max_abs(const double *A, int n)
{
  double m = 0.0;
  for (int k = 0; k < n; k++) m = std::max(m, std::fabs(A[k]));
  return m;
}

double max_diff(const double *A, const double *B, int n)
{
  double m = 0.0;
  for (int k = 0; k < n; k++) m = std::max(m, std::fabs(A[k] - B[k]));
  return m;
}

// a rotation from an axis and an angle (Rodrigues), independent of rotation_z
void axis_angle(const double *axis, double angle, double *R)
{
  const double n = std::sqrt(TLSPH::dot3(axis, axis));
  const double u[3] = {axis[0] / n, axis[1] / n, axis[2] / n};
  const double c = std::cos(angle), s = std::sin(angle);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) R[3 * i + j] = (i == j ? c : 0.0) + (1.0 - c) * u[i] * u[j];
  R[1] -= s * u[2];
  R[2] += s * u[1];
  R[3] += s * u[2];
  R[5] -= s * u[0];
  R[6] -= s * u[1];
  R[7] += s * u[0];
}

TLSPH::OrthotropicSVK ply(const TLSPH::OrthotropicConstants &k, double theta_deg, int ps = 0)
{
  TLSPH::OrthotropicSVK law;
  EXPECT_TRUE(TLSPH::make_orthotropic(k, theta_deg, ps, law));
  return law;
}

void local_stiffness(const TLSPH::OrthotropicConstants &k, double *C)
{
  EXPECT_TRUE(TLSPH::orthotropic_stiffness_local(k, C));
}

void random_sym(std::mt19937 &rng, double amp, int dim, double *E)
{
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  TLSPH::mat_zero(E);
  for (int a = 0; a < dim; a++)
    for (int b = a; b < dim; b++) E[3 * a + b] = E[3 * b + a] = amp * U(rng);
}

}    // namespace

/* The local stiffness is the inverse of the compliance: C S = I, and it
   matches the textbook closed form C11 = E1 (1 - nu23 nu32) / Delta, ... */
TEST(Orthotropic, StiffnessInvertsCompliance)
{
  for (const auto &k : {CARBON_EPOXY, GENERIC}) {
    double C[36], S[36];
    local_stiffness(k, C);
    TLSPH::orthotropic_compliance(k, S);
    for (int I = 0; I < 6; I++)
      for (int J = 0; J < 6; J++) {
        double acc = 0.0;
        for (int K = 0; K < 6; K++) acc += C[6 * I + K] * S[6 * K + J];
        EXPECT_NEAR(acc, I == J ? 1.0 : 0.0, 1e-13) << I << J;
        EXPECT_EQ(C[6 * I + J], C[6 * J + I]);
      }
    const double nu21 = k.nu12 * k.E2 / k.E1, nu31 = k.nu13 * k.E3 / k.E1;
    const double nu32 = k.nu23 * k.E3 / k.E2;
    const double D = TLSPH::orthotropic_delta(k);
    const double ref[6] = {k.E1 * (1 - k.nu23 * nu32) / D,    k.E1 * (nu21 + nu31 * k.nu23) / D,
                           k.E1 * (nu31 + nu21 * nu32) / D,   k.E2 * (1 - k.nu13 * nu31) / D,
                           k.E2 * (nu32 + k.nu12 * nu31) / D, k.E3 * (1 - k.nu12 * nu21) / D};
    const double got[6] = {C[0], C[1], C[2], C[7], C[8], C[14]};
    for (int n = 0; n < 6; n++) EXPECT_NEAR(got[n], ref[n], 1e-12 * k.E1) << n;
    EXPECT_EQ(C[21], k.G23);
    EXPECT_EQ(C[28], k.G13);
    EXPECT_EQ(C[35], k.G12);
  }
  // carbon/epoxy: the numbers of the doc page (GPa)
  double C[36];
  local_stiffness(CARBON_EPOXY, C);
  EXPECT_NEAR(C[0] / 1e9, 123.1265, 1e-4);
  EXPECT_NEAR(C[1] / 1e9, 3.93801, 1e-5);
  EXPECT_NEAR(C[7] / 1e9, 10.36405, 1e-5);
  EXPECT_NEAR(C[8] / 1e9, 4.22119, 1e-5);
}

/* The Voigt rotation equals the rotation of the 4th-order tensor, for ply
   angles about z and for general 3D rotations (rotate_stiffness is general). */
TEST(Orthotropic, RotationEqualsTensorRotation)
{
  for (const auto &k : {CARBON_EPOXY, GENERIC}) {
    double Cl[36];
    local_stiffness(k, Cl);
    const double scale = max_abs(Cl, 36);
    for (double theta : {0.0, 30.0, 45.0, 90.0, -60.0, 137.0}) {
      const TLSPH::OrthotropicSVK law = ply(k, theta);
      // R: columns are the material axes in global coordinates, fibre at +theta from x
      const double t = theta * PI / 180.0, z[3] = {0, 0, 1};
      double R[9], Cr[36];
      axis_angle(z, t, R);
      EXPECT_NEAR(R[0], std::cos(t), 1e-15);
      EXPECT_NEAR(R[3], std::sin(t), 1e-15);
      rotate_tensor(Cl, R, Cr);
      EXPECT_LT(max_diff(law.C, Cr, 36), 1e-12 * scale) << "theta " << theta;
      // a rotation about z keeps z a symmetry plane (monoclinic): the zeros
      // that the plane-stress condensation relies on
      for (int I : {0, 1, 2, 5})
        for (int J : {3, 4}) {
          EXPECT_LT(std::fabs(law.C[6 * I + J]), 1e-12 * scale) << theta << " C" << I << J;
          EXPECT_LT(std::fabs(law.C[6 * J + I]), 1e-12 * scale) << theta << " C" << J << I;
        }
    }
    // general rotations
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    for (int n = 0; n < 10; n++) {
      const double axis[3] = {U(rng), U(rng), U(rng)};
      double R[9], C1[36], C2[36];
      axis_angle(axis, PI * U(rng), R);
      TLSPH::rotate_stiffness(Cl, R, C1);
      rotate_tensor(Cl, R, C2);
      EXPECT_LT(max_diff(C1, C2, 36), 1e-12 * scale);
    }
  }
  // 90 degrees: exact swap of the in-plane axes (no round-off from cos(pi/2))
  const TLSPH::OrthotropicSVK l90 = ply(GENERIC, 90.0);
  double Cl[36];
  local_stiffness(GENERIC, Cl);
  EXPECT_EQ(l90.C[0], Cl[7]);
  EXPECT_EQ(l90.C[7], Cl[0]);
  EXPECT_EQ(l90.C[5], 0.0);
  EXPECT_EQ(l90.C[11], 0.0);
}

/* theta = 0 with E1 = E2 = E3 = E, G = E / (2 (1 + nu)), nu_ij = nu is the
   isotropic law (also at any other angle): S, psi, the plane-stress E33 */
TEST(Orthotropic, IsotropicLimit)
{
  const double E = tlsph_test::STEEL_E, nu = tlsph_test::STEEL_NU, G = E / (2 * (1 + nu));
  const TLSPH::OrthotropicConstants k{E, E, E, G, G, G, nu, nu, nu};
  std::mt19937 rng(3);
  for (int ps : {0, 1})
    for (int dim : {2, 3}) {
      if (ps && dim == 3) continue;
      const TLSPH::IsotropicSVK iso{TLSPH::lame_lambda(E, nu), TLSPH::lame_mu(E, nu), ps};
      for (double theta : {0.0, 33.0}) {
        const TLSPH::OrthotropicSVK law = ply(k, theta, ps);
        for (int n = 0; n < 20; n++) {
          double E1[9], E2[9], S1[9], S2[9];
          random_sym(rng, 1e-2, dim, E1);
          TLSPH::mat_copy(E1, E2);
          const double psi1 = iso.stress(E1, S1), psi2 = law.stress(E2, S2);
          const double Ss = max_abs(S1, 9);
          EXPECT_LT(max_diff(S1, S2, 9), 1e-12 * Ss) << "ps " << ps << " dim " << dim;
          EXPECT_NEAR(psi2, psi1, 1e-12 * std::fabs(psi1));
          EXPECT_NEAR(E2[8], E1[8], 1e-12 * max_abs(E1, 9));
        }
      }
    }
  // wave speed and hourglass modulus reduce to the isotropic ones
  const TLSPH::OrthotropicSVK law = ply(k, 0.0);
  const double c_iso = TLSPH::wave_speed(TLSPH::lame_lambda(E, nu), TLSPH::lame_mu(E, nu), 7800);
  EXPECT_NEAR(std::sqrt(TLSPH::max_acoustic_modulus(law.C) / 7800), c_iso, 1e-12 * c_iso);
  EXPECT_NEAR(TLSPH::voigt_young_modulus(law.C), E, 1e-12 * E);
}

/* Uniaxial strain along the fibre: S11 = C11 E11, S22 = C12 E11,
   S33 = C13 E11 (local constants); at theta = 90 the fibre is y; at 45 the
   stress has the same form in the rotated axes. */
TEST(Orthotropic, UniaxialStrainAlongFibre)
{
  double Cl[36];
  local_stiffness(GENERIC, Cl);
  const double eps = 1e-3;
  {
    const TLSPH::OrthotropicSVK law = ply(GENERIC, 0.0);
    double E[9] = {eps, 0, 0, 0, 0, 0, 0, 0, 0}, S[9];
    const double psi = law.stress(E, S);
    EXPECT_NEAR(S[0], Cl[0] * eps, 1e-14 * Cl[0]);
    EXPECT_NEAR(S[4], Cl[1] * eps, 1e-14 * Cl[0]);
    EXPECT_NEAR(S[8], Cl[2] * eps, 1e-14 * Cl[0]);
    EXPECT_EQ(S[1], 0.0);
    EXPECT_EQ(S[2], 0.0);
    EXPECT_EQ(S[5], 0.0);
    EXPECT_NEAR(psi, 0.5 * Cl[0] * eps * eps, 1e-14 * Cl[0] * eps * eps);
  }
  {
    const TLSPH::OrthotropicSVK law = ply(GENERIC, 90.0);
    double E[9] = {0, 0, 0, 0, eps, 0, 0, 0, 0}, S[9];
    law.stress(E, S);
    EXPECT_NEAR(S[4], Cl[0] * eps, 1e-14 * Cl[0]);    // along y: the fibre
    EXPECT_NEAR(S[0], Cl[1] * eps, 1e-14 * Cl[0]);    // x: transverse direction 2
    EXPECT_NEAR(S[8], Cl[2] * eps, 1e-14 * Cl[0]);
    EXPECT_EQ(S[1], 0.0);
    // shear in the xy plane is G12 whatever the in-plane angle is 0 or 90
    double Es[9] = {0, eps, 0, eps, 0, 0, 0, 0, 0};
    law.stress(Es, S);
    EXPECT_NEAR(S[1], 2.0 * GENERIC.G12 * eps, 1e-14 * Cl[0]);
  }
  for (double theta : {45.0, -60.0, 137.0}) {
    // E = eps n (x) n with n the fibre direction (cos, sin, 0):
    // S = eps (C11 n(x)n + C12 t(x)t + C13 e3(x)e3), t = (-sin, cos, 0)
    const TLSPH::OrthotropicSVK law = ply(GENERIC, theta);
    const double c = std::cos(theta * PI / 180.0), s = std::sin(theta * PI / 180.0);
    const double n[3] = {c, s, 0}, t[3] = {-s, c, 0}, e3[3] = {0, 0, 1};
    double E[9], S[9], Sr[9];
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        E[3 * i + j] = eps * n[i] * n[j];
        Sr[3 * i + j] = eps * (Cl[0] * n[i] * n[j] + Cl[1] * t[i] * t[j] + Cl[2] * e3[i] * e3[j]);
      }
    law.stress(E, S);
    EXPECT_LT(max_diff(S, Sr, 9), 1e-12 * Cl[0] * eps) << "theta " << theta;
  }
}

/* S = C : E through the Voigt code equals the 4th-order contraction with the
   rotated tensor; psi = S : E / 2 = d psi / d E checked by central differences */
TEST(Orthotropic, StressAndEnergy)
{
  std::mt19937 rng(11);
  double Cl[36];
  local_stiffness(GENERIC, Cl);
  for (double theta : {0.0, 30.0, -60.0, 137.0}) {
    const TLSPH::OrthotropicSVK law = ply(GENERIC, theta);
    double R[9], Cr[36];
    const double z[3] = {0, 0, 1};
    axis_angle(z, theta * PI / 180.0, R);
    rotate_tensor(Cl, R, Cr);
    for (int n = 0; n < 10; n++) {
      double E[9], S[9], Sr[9];
      random_sym(rng, 1e-2, 3, E);
      const double psi = law.stress(E, S);
      tensor_stress(Cr, E, Sr);
      EXPECT_LT(max_diff(S, Sr, 9), 1e-12 * max_abs(Sr, 9));
      double SE = 0.0;
      for (int k = 0; k < 9; k++) SE += S[k] * E[k];
      EXPECT_NEAR(psi, 0.5 * SE, 1e-12 * psi);
      EXPECT_GT(psi, 0.0);
      const double dE = 1e-7;
      for (int a = 0; a < 3; a++)
        for (int b = a; b < 3; b++) {
          double Ep[9], Em[9], Sd[9];
          TLSPH::mat_copy(E, Ep);
          TLSPH::mat_copy(E, Em);
          Ep[3 * a + b] += dE;
          Em[3 * a + b] -= dE;
          if (a != b) {
            Ep[3 * b + a] += dE;
            Em[3 * b + a] -= dE;
          }
          const double dpsi = (law.stress(Ep, Sd) - law.stress(Em, Sd)) / (2 * dE);
          const double expect = (a == b) ? S[3 * a + b] : 2.0 * S[3 * a + b];
          EXPECT_NEAR(dpsi, expect, 1e-6 * GENERIC.E1 * 1e-2) << theta << " E" << a << b;
        }
    }
  }
}

/* 2D: plane strain keeps E33 = 0 (S33 != 0); plane stress gives S33 = 0 with
   E33 = -(C31 E11 + C32 E22 + 2 C36 E12) / C33, and psi of the condensed law
   is still S : E / 2 = d psi / d E. At theta = 0, in-plane uniaxial stress
   E22 = -nu12 E11 gives S11 = E1 E11, S22 = 0, E33 = -nu13 E11. */
TEST(Orthotropic, PlaneStrainAndPlaneStress)
{
  std::mt19937 rng(17);
  for (double theta : {0.0, 45.0, 137.0}) {
    const TLSPH::OrthotropicSVK strain = ply(GENERIC, theta, 0), stress = ply(GENERIC, theta, 1);
    const double *C = strain.C;
    for (int n = 0; n < 10; n++) {
      double E[9], Es[9], S[9], Ss[9];
      random_sym(rng, 1e-2, 2, E);
      TLSPH::mat_copy(E, Es);
      strain.stress(E, S);
      EXPECT_EQ(E[8], 0.0);
      EXPECT_NEAR(S[8], C[12] * E[0] + C[13] * E[4] + 2 * C[17] * E[1], 1e-12 * max_abs(S, 9));
      EXPECT_EQ(S[2], 0.0);
      EXPECT_EQ(S[5], 0.0);
      const double psi = stress.stress(Es, Ss);
      EXPECT_EQ(Ss[8], 0.0);
      EXPECT_NEAR(Es[8], -(C[12] * E[0] + C[13] * E[4] + 2 * C[17] * E[1]) / C[14], 1e-16);
      // the full 3D law at the condensed strain has S33 = 0 too
      double S3[9];
      TLSPH::OrthotropicSVK full = strain;
      double E3[9];
      TLSPH::mat_copy(Es, E3);
      full.stress(E3, S3);
      EXPECT_LT(std::fabs(S3[8]), 1e-12 * max_abs(S3, 9));
      EXPECT_LT(max_diff(S3, Ss, 8), 1e-12 * max_abs(S3, 9));
      double SE = 0.0;
      for (int k = 0; k < 9; k++) SE += Ss[k] * Es[k];
      EXPECT_NEAR(psi, 0.5 * SE, 1e-12 * psi);
    }
  }
  const TLSPH::OrthotropicSVK law = ply(GENERIC, 0.0, 1);
  const double eps = 1e-3;
  double E[9] = {eps, 0, 0, 0, -GENERIC.nu12 * eps, 0, 0, 0, 0}, S[9];
  law.stress(E, S);
  EXPECT_NEAR(S[0], GENERIC.E1 * eps, 1e-12 * GENERIC.E1 * eps);
  EXPECT_NEAR(S[4], 0.0, 1e-12 * GENERIC.E1 * eps);
  EXPECT_NEAR(E[8], -GENERIC.nu13 * eps, 1e-14);
}

/* Objectivity: F = R F0 gives P = R P0, the same psi and S, and the Cauchy
   stress R sigma0 R^T, for general rotations and a finite prestrain. */
TEST(Orthotropic, Objectivity)
{
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (double theta : {0.0, 45.0, -60.0}) {
    const TLSPH::OrthotropicSVK law = ply(GENERIC, theta);
    for (int n = 0; n < 10; n++) {
      double F0[9];
      do {
        for (int k = 0; k < 9; k++) F0[k] = (k % 4 == 0) + 0.1 * U(rng);
      } while (TLSPH::mat_det(F0) < 0.5);
      const double axis[3] = {U(rng), U(rng), U(rng)};
      double R[9], F[9], P0[9], P[9], RP0[9], J0, J;
      axis_angle(axis, PI * U(rng), R);
      TLSPH::mat_mul(R, F0, F);
      double Fc0[9], Fc[9];
      TLSPH::mat_copy(F0, Fc0);
      TLSPH::mat_copy(F, Fc);
      const double psi0 = TLSPH::stress_tensors(law, 3, Fc0, P0, nullptr, &J0);
      const double psi = TLSPH::stress_tensors(law, 3, Fc, P, nullptr, &J);
      TLSPH::mat_mul(R, P0, RP0);
      const double Ps = max_abs(P0, 9);
      EXPECT_LT(max_diff(P, RP0, 9), 1e-12 * Ps) << "theta " << theta;
      EXPECT_NEAR(psi, psi0, 1e-12 * psi0);
      EXPECT_NEAR(J, J0, 1e-14);
      // sigma = P F^T / J
      double s0[9], s[9], Rs0[9], Rs0Rt[9];
      TLSPH::mat_mult(P0, F0, s0);
      TLSPH::mat_mult(P, F, s);
      TLSPH::mat_mul(R, s0, Rs0);
      TLSPH::mat_mult(Rs0, R, Rs0Rt);
      for (int k = 0; k < 9; k++) s0[k] /= J0, s[k] /= J, Rs0Rt[k] /= J0;
      EXPECT_LT(max_diff(s, Rs0Rt, 9), 1e-12 * max_abs(s0, 9));
    }
    // a rigid rotation alone: no stress
    double R[9], P[9], J;
    const double axis[3] = {0.3, -1.0, 0.5};
    axis_angle(axis, 1.1, R);
    const double psi = TLSPH::stress_tensors(law, 3, R, P, nullptr, &J);
    EXPECT_LT(std::fabs(psi), 1e-20 * GENERIC.E1);
    EXPECT_LT(max_abs(P, 9), 1e-15 * GENERIC.E1);
  }
}

/* The wave speed of the time step: the fastest plane wave over all
   directions, independent of theta; along the fibre for carbon/epoxy, along
   a diagonal for a cubic material with a large shear modulus. */
TEST(Orthotropic, WaveSpeed)
{
  double Cl[36];
  local_stiffness(CARBON_EPOXY, Cl);
  for (double theta : {0.0, 45.0, 90.0, 137.0}) {
    const TLSPH::OrthotropicSVK law = ply(CARBON_EPOXY, theta);
    const double c = std::sqrt(TLSPH::max_acoustic_modulus(law.C) / CARBON_RHO);
    EXPECT_NEAR(c, std::sqrt(Cl[0] / CARBON_RHO), 1e-9 * c) << theta;
  }
  EXPECT_NEAR(std::sqrt(Cl[0] / CARBON_RHO), 9090.39, 0.01);
  // cubic (copper-like, GPa): C11 168.4, C12 121.4, C44 75.4; the fastest
  // wave runs along [111] with rho c^2 = (C11 + 2 C12 + 4 C44) / 3 > C11
  const double C11 = 168.4e9, C12 = 121.4e9, C44 = 75.4e9;
  const double d = (C11 - C12) * (C11 + 2 * C12);
  const double S11 = (C11 + C12) / d, S12 = -C12 / d;
  const double E = 1.0 / S11, nu = -S12 / S11;
  const TLSPH::OrthotropicConstants cubic{E, E, E, C44, C44, C44, nu, nu, nu};
  const TLSPH::OrthotropicSVK law = ply(cubic, 0.0);
  EXPECT_NEAR(law.C[0], C11, 1e-6 * C11);
  const double m111 = (C11 + 2 * C12 + 4 * C44) / 3;
  EXPECT_GT(m111, C11 * 1.4);
  EXPECT_NEAR(TLSPH::max_acoustic_modulus(law.C), m111, 1e-7 * m111);
  // the result does not depend on a rotation of the material
  double R[9], Cr[36];
  const double axis[3] = {0.2, 0.7, -0.4};
  axis_angle(axis, 0.9, R);
  TLSPH::rotate_stiffness(law.C, R, Cr);
  EXPECT_NEAR(TLSPH::max_acoustic_modulus(Cr), m111, 1e-7 * m111);
}

/* The hourglass modulus: the Voigt-average Young's modulus, the same for
   every ply angle (28.18 GPa for carbon/epoxy) */
TEST(Orthotropic, HourglassModulus)
{
  const double E0 = TLSPH::voigt_young_modulus(ply(CARBON_EPOXY, 0.0).C);
  EXPECT_NEAR(E0 / 1e9, 28.1758, 1e-4);
  for (double theta : {30.0, 45.0, 90.0, -60.0})
    EXPECT_NEAR(TLSPH::voigt_young_modulus(ply(CARBON_EPOXY, theta).C), E0, 1e-12 * E0);
}

/* Positive definiteness: orthotropic_delta > 0 for the data sets, <= 0 for
   constants that pass every pairwise bound |nu_ij| < sqrt(E_i/E_j) */
TEST(Orthotropic, CompliancePositiveDefinite)
{
  EXPECT_NEAR(TLSPH::orthotropic_delta(CARBON_EPOXY), 0.825492297520661, 1e-14);
  EXPECT_GT(TLSPH::orthotropic_delta(GENERIC), 0.0);
  const TLSPH::OrthotropicConstants bad{1e9, 1e9, 1e9, 1e8, 1e8, 1e8, 0.6, 0.6, 0.6};
  EXPECT_LT(TLSPH::orthotropic_delta(bad), 0.0);
  // the isotropic value: (1 + nu)^2 (1 - 2 nu)
  const double nu = 0.3;
  const TLSPH::OrthotropicConstants iso{1e9, 1e9, 1e9, 1e8, 1e8, 1e8, nu, nu, nu};
  EXPECT_NEAR(TLSPH::orthotropic_delta(iso), (1 + nu) * (1 + nu) * (1 - 2 * nu), 1e-15);
}
