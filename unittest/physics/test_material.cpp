/* ----------------------------------------------------------------------
   Constitutive law (tlsph_material.h), stress_tensors and pack_row
   (tlsph_particle.h)
------------------------------------------------------------------------- */

#include "physics_system.h"

#include <gtest/gtest.h>

#include <random>

namespace {

TLSPH::IsotropicSVK steel(int plane_stress)
{
  return TLSPH::IsotropicSVK{TLSPH::lame_lambda(tlsph_test::STEEL_E, tlsph_test::STEEL_NU),
                             TLSPH::lame_mu(tlsph_test::STEEL_E, tlsph_test::STEEL_NU),
                             plane_stress};
}

double double_dot(const double *A, const double *B)
{
  double s = 0.0;
  for (int k = 0; k < 9; k++) s += A[k] * B[k];
  return s;
}

void random_sym(std::mt19937 &rng, double amp, int dim, double *E)
{
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  TLSPH::mat_zero(E);
  for (int a = 0; a < dim; a++)
    for (int b = a; b < dim; b++) E[3 * a + b] = E[3 * b + a] = amp * U(rng);
}

}    // namespace

// textbook values for steel, E = 210 GPa, nu = 0.3
TEST(Material, LameConstantsSteel)
{
  EXPECT_NEAR(TLSPH::lame_lambda(210e9, 0.3), 121.153846153846e9, 1e-3);
  EXPECT_NEAR(TLSPH::lame_mu(210e9, 0.3), 80.7692307692308e9, 1e-3);
}

// the inverse relations E = mu (3 lambda + 2 mu) / (lambda + mu),
// nu = lambda / (2 (lambda + mu)), K = E / (3 (1 - 2 nu)) = lambda + 2 mu / 3
TEST(Material, LameConstantsInverseRelations)
{
  for (double E : {1e6, 32e9, 190e9, 210e9})
    for (double nu : {-0.3, 0.0, 0.2, 0.3, 0.33, 0.45, 0.499}) {
      const double l = TLSPH::lame_lambda(E, nu), m = TLSPH::lame_mu(E, nu);
      EXPECT_NEAR(m * (3 * l + 2 * m) / (l + m), E, 1e-12 * E) << E << " " << nu;
      if (nu != 0.0) EXPECT_NEAR(l / (2 * (l + m)), nu, 1e-12) << E << " " << nu;
      else EXPECT_EQ(l, 0.0);
      EXPECT_NEAR(l + 2 * m / 3, E / (3 * (1 - 2 * nu)), 1e-12 * E / (1 - 2 * nu));
    }
}

// c0 = sqrt((K + 4 mu / 3) / rho), about 6 km/s for steel
TEST(Material, WaveSpeed)
{
  const double E = 210e9, nu = 0.3, rho = 7850.0;
  const double K = E / (3 * (1 - 2 * nu)), G = E / (2 * (1 + nu));
  const double c = TLSPH::wave_speed(TLSPH::lame_lambda(E, nu), TLSPH::lame_mu(E, nu), rho);
  EXPECT_NEAR(c, std::sqrt((K + 4.0 * G / 3.0) / rho), 1e-9 * c);
  EXPECT_NEAR(c, 6001.0, 1.0);
}

/* Plane stress, uniaxial stress: E11 = eps, E22 = -nu eps gives S11 = E eps,
   S22 = S33 = 0 and E33 = -nu/(1 - nu) (E11 + E22). SVK is linear in E so
   this holds for any eps. */
TEST(Material, PlaneStressUniaxialStress)
{
  const TLSPH::IsotropicSVK law = steel(1);
  const double Ey = tlsph_test::STEEL_E, nu = tlsph_test::STEEL_NU;
  for (double eps : {1e-6, 1e-3, 0.05}) {
    double E[9] = {eps, 0, 0, 0, -nu * eps, 0, 0, 0, 0}, S[9];
    law.stress(E, S);
    EXPECT_NEAR(S[0], Ey * eps, 1e-12 * Ey * eps);
    EXPECT_NEAR(S[4], 0.0, 1e-12 * Ey * eps);
    EXPECT_EQ(S[8], 0.0);
    EXPECT_NEAR(E[8], -nu * eps, 1e-14 * eps);    // -nu/(1-nu) (E11 + E22)
  }
  // a general in-plane strain: S33 = 0 and E33 from the textbook relation
  std::mt19937 rng(1);
  for (int n = 0; n < 20; n++) {
    double E[9], S[9];
    random_sym(rng, 1e-2, 2, E);
    const double E33 = -nu / (1 - nu) * (E[0] + E[4]);
    law.stress(E, S);
    EXPECT_EQ(S[8], 0.0);
    EXPECT_NEAR(E[8], E33, 1e-14);
    // plane-stress Hooke: S11 = E/(1-nu^2) (E11 + nu E22), S12 = E/(1+nu) E12
    EXPECT_NEAR(S[0], Ey / (1 - nu * nu) * (E[0] + nu * E[4]), 1e-12 * Ey * 1e-2);
    EXPECT_NEAR(S[1], Ey / (1 + nu) * E[1], 1e-12 * Ey * 1e-2);
  }
}

/* Through stress_tensors with F: plane stress, F = diag(1 + eps, 1 - nu eps):
   P11 = E eps at small strain, F33 = 1 - nu eps from S33 = 0, P33 = 0. */
TEST(Material, PlaneStressThroughF)
{
  const TLSPH::IsotropicSVK law = steel(1);
  const double Ey = tlsph_test::STEEL_E, nu = tlsph_test::STEEL_NU, eps = 1e-6;
  double F[9] = {1 + eps, 0, 0, 0, 1 - nu * eps, 0, 0, 0, 1}, P[9], K[9], J;
  TLSPH::stress_tensors(law, 2, F, P, K, &J);
  EXPECT_NEAR(P[0], Ey * eps, 1e-5 * Ey * eps);    // O(eps) from the large-strain terms
  EXPECT_NEAR(P[4], 0.0, 1e-5 * Ey * eps);
  EXPECT_EQ(P[8], 0.0);
  EXPECT_NEAR(F[8], 1 - nu * eps, 1e-11);
  EXPECT_NEAR(J, F[0] * F[4] * F[8], 1e-15);
  // K = J F^-T sees the plane-stress F33 as well: K33 = F11 F22
  EXPECT_NEAR(K[8], F[0] * F[4], 1e-15);
}

/* Plane strain (the 2D default, 3D Lame constants) and 3D, uniaxial strain
   F = diag(1 + eps, 1, 1): S11 = (lambda + 2 mu) E11, S22 = S33 = lambda E11
   (exact in E), P11 = (lambda + 2 mu) eps at small strain. */
TEST(Material, PlaneStrainUniaxialStrain)
{
  const TLSPH::IsotropicSVK law = steel(0);
  const double M = law.lambda + 2 * law.mu;
  for (int dim : {2, 3}) {
    const double eps = 1e-6;
    double F[9] = {1 + eps, 0, 0, 0, 1, 0, 0, 0, 1}, P[9], K[9], J;
    double E[9], S[9];
    TLSPH::green_lagrange(F, E);
    law.stress(E, S);
    EXPECT_NEAR(S[0], M * E[0], 1e-12 * M * eps);
    EXPECT_NEAR(S[4], law.lambda * E[0], 1e-12 * M * eps);
    EXPECT_NEAR(S[8], law.lambda * E[0], 1e-12 * M * eps);
    TLSPH::stress_tensors(law, dim, F, P, K, &J);
    EXPECT_NEAR(P[0], M * eps, 1e-5 * M * eps) << "dim " << dim;
    EXPECT_EQ(F[8], 1.0);    // plane strain keeps F33 = 1
    // textbook: M = E (1 - nu) / ((1 + nu)(1 - 2 nu))
    const double Ey = tlsph_test::STEEL_E, nu = tlsph_test::STEEL_NU;
    EXPECT_NEAR(M, Ey * (1 - nu) / ((1 + nu) * (1 - 2 * nu)), 1e-12 * M);
  }
}

/* psi = 1/2 S : E (SVK is quadratic in E), and S = d psi / d E by central
   differences, in 3D, plane strain and plane stress. */
TEST(Material, StrainEnergyDensity)
{
  std::mt19937 rng(42);
  for (int ps : {0, 1})
    for (int dim : {2, 3}) {
      if (ps && dim == 3) continue;
      const TLSPH::IsotropicSVK law = steel(ps);
      for (int n = 0; n < 20; n++) {
        double E[9], S[9];
        random_sym(rng, 1e-3, dim, E);
        double Ec[9];
        TLSPH::mat_copy(E, Ec);
        const double psi = law.stress(Ec, S);
        EXPECT_NEAR(psi, 0.5 * double_dot(S, Ec), 1e-12 * std::fabs(psi));
        EXPECT_GT(psi, 0.0);
        const double dE = 1e-7;
        for (int a = 0; a < dim; a++)
          for (int b = a; b < dim; b++) {
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
            EXPECT_NEAR(dpsi, expect, 1e-6 * tlsph_test::STEEL_E * 1e-3)
                << "ps " << ps << " dim " << dim << " E" << a << b;
          }
      }
    }
}

/* stress_tensors: P = F S and K = J F^-T against independent products, for
   a general F; without K (null) the same P and psi. */
TEST(Material, StressTensorsProducts)
{
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const TLSPH::IsotropicSVK law = steel(0);
  for (int n = 0; n < 20; n++) {
    double F[9];
    do {
      for (int k = 0; k < 9; k++) F[k] = (k % 4 == 0) + 0.2 * U(rng);
    } while (TLSPH::mat_det(F) < 0.5);
    double Fc[9], P[9], K[9], J;
    TLSPH::mat_copy(F, Fc);
    const double psi = TLSPH::stress_tensors(law, 3, Fc, P, K, &J);
    EXPECT_EQ(tlsph_test::max_abs_diff9(F, Fc), 0.0);    // 3D: F unchanged
    double E[9], S[9], Pr[9];
    TLSPH::green_lagrange(F, E);
    const double psi_ref = law.stress(E, S);
    EXPECT_NEAR(psi, psi_ref, 1e-14 * std::fabs(psi_ref));
    // P = F S with explicit loops
    for (int a = 0; a < 3; a++)
      for (int b = 0; b < 3; b++) {
        Pr[3 * a + b] = 0.0;
        for (int k = 0; k < 3; k++) Pr[3 * a + b] += F[3 * a + k] * S[3 * k + b];
      }
    const double Ps = TLSPH::mat_norm(Pr);
    EXPECT_LT(tlsph_test::max_abs_diff9(P, Pr), 1e-13 * Ps);
    // F^T K = J I (K = J F^-T, not J F^-1: F is not symmetric)
    double FtK[9], JI[9], FK[9];
    TLSPH::mat_tmul(F, K, FtK);
    TLSPH::mat_identity(JI);
    for (int k = 0; k < 9; k++) JI[k] *= J;
    EXPECT_LT(tlsph_test::max_abs_diff9(FtK, JI), 1e-12 * TLSPH::mat_norm(JI));
    TLSPH::mat_mul(F, K, FK);
    EXPECT_GT(tlsph_test::max_abs_diff9(FK, JI), 1e-3 * J);
    EXPECT_NEAR(J, TLSPH::mat_det(F), 1e-15);
    // K is optional
    double P2[9], J2;
    TLSPH::mat_copy(F, Fc);
    EXPECT_EQ(TLSPH::stress_tensors(law, 3, Fc, P2, nullptr, &J2), psi);
    EXPECT_EQ(tlsph_test::max_abs_diff9(P, P2), 0.0);
    EXPECT_EQ(J2, J);
  }
}

/* pack_row: F and K blocks (DIM x DIM), alpha, R = V P Q (DIM x Basis size)
   and fown = V P sum_j g_ij, against explicit products, for both orders in
   2D and 3D, with a general P, Q, F, K; K null gives a zero K block; the
   compact row (with_R false, newton on) is the same up to R and ends there. */
namespace {
template <int DIM, int ORDER> void check_pack_row(std::mt19937 &rng)
{
  using L = TLSPH::Packed<DIM, ORDER>;
  constexpr int NB = TLSPH::Basis<DIM, ORDER>::size;
  static_assert(L::size == DIM * NB + 2 * DIM * DIM + 1 && L::A == 2 * DIM * DIM &&
                    L::R == L::A + 1 && L::compact == L::R,
                "layout");
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  double P[9], Fm[9], K[9], Q[TLSPH::QMAX], sumg[3];
  for (int k = 0; k < 9; k++) P[k] = 1e9 * U(rng), Fm[k] = U(rng), K[k] = U(rng);
  for (double &q : Q) q = 1e3 * U(rng);
  for (double &g : sumg) g = 1e3 * U(rng);
  const double V = 1e-9 * (1.5 + U(rng));
  std::vector<double> row(L::size + 1, -7.0);
  double fown[3];
  TLSPH::pack_row<DIM, ORDER>(V, P, Q, Fm, K, 0.7, sumg, row.data(), fown);
  EXPECT_EQ(row[L::A], 0.7);
  const double Rs = V * 1e9 * 1e3 * DIM;
  for (int r = 0; r < DIM; r++) {
    for (int c = 0; c < NB; c++) {
      double ref = 0.0;
      for (int k = 0; k < DIM; k++) ref += V * P[3 * r + k] * Q[NB * k + c];
      EXPECT_NEAR(row[L::R + NB * r + c], ref, 1e-14 * Rs) << DIM << ORDER << " R" << r << c;
    }
    for (int c = 0; c < DIM; c++) {
      EXPECT_EQ(row[L::F + DIM * r + c], Fm[3 * r + c]);
      EXPECT_EQ(row[L::K + DIM * r + c], K[3 * r + c]);
    }
    double ref = 0.0;
    for (int c = 0; c < DIM; c++) ref += V * P[3 * r + c] * sumg[c];
    EXPECT_NEAR(fown[r], ref, 1e-14 * Rs) << DIM << ORDER << " fown " << r;
  }
  for (int r = DIM; r < 3; r++) EXPECT_EQ(fown[r], 0.0);
  EXPECT_EQ(row[L::size], -7.0);    // nothing written past the row
  TLSPH::pack_row<DIM, ORDER>(V, P, Q, Fm, nullptr, 0.7, sumg, row.data(), fown);
  for (int k = 0; k < DIM * DIM; k++) EXPECT_EQ(row[L::K + k], 0.0);
  // compact: the same F, K, alpha and fown, nothing written from R on
  std::vector<double> crow(L::size + 1, -7.0);
  double cfown[3];
  TLSPH::pack_row<DIM, ORDER>(V, P, Q, Fm, K, 0.7, sumg, crow.data(), cfown, false);
  TLSPH::pack_row<DIM, ORDER>(V, P, Q, Fm, K, 0.7, sumg, row.data(), fown);
  for (int k = 0; k < L::compact; k++) EXPECT_EQ(crow[k], row[k]) << DIM << ORDER << " " << k;
  for (int k = L::compact; k <= L::size; k++) EXPECT_EQ(crow[k], -7.0) << DIM << ORDER << " " << k;
  for (int r = 0; r < 3; r++) EXPECT_EQ(cfown[r], fown[r]);
}
}    // namespace

TEST(Material, PackedRowProducts)
{
  std::mt19937 rng(21);
  // F + K (DIM x DIM each) + alpha + R (DIM x Basis size): 4 + 4 + 1 + 4 and
  // 4 + 4 + 1 + 10 in 2D, 9 + 9 + 1 + 9 and 9 + 9 + 1 + 27 in 3D
  EXPECT_EQ((TLSPH::Packed<2, 1>::size), 13);
  EXPECT_EQ((TLSPH::Packed<2, 2>::size), 19);
  EXPECT_EQ((TLSPH::Packed<3, 1>::size), 28);
  EXPECT_EQ((TLSPH::Packed<3, 2>::size), 46);
  for (int n = 0; n < 5; n++) {
    check_pack_row<2, 1>(rng);
    check_pack_row<2, 2>(rng);
    check_pack_row<3, 1>(rng);
    check_pack_row<3, 2>(rng);
  }
}
