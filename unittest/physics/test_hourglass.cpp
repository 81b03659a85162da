/* ----------------------------------------------------------------------
   Hourglass control (tlsph_pair_terms.h: hourglass_force, and through
   particle_force): zero for homogeneous deformation, restoring for the
   checkerboard zero-energy mode (both gradient orders), antisymmetric.
------------------------------------------------------------------------- */

#include "physics_system.h"

#include <gtest/gtest.h>

#include <random>

using tlsph_test::ORDERS;
using tlsph_test::System;

namespace {

// the doc's definition, written out independently of hourglass_force:
// eps_ij = F_i X_ij - x_ij, eps_ji = F_j X_ji - x_ji, delta = eps . x / |x|
// with the bond vector of each end; force on i along x_ij:
// f_i = -coeff (delta_ij + delta_ji) x_ij / |x_ij|
void reference_hourglass(const double *Fi, const double *Fj, const double *Xij,
                         const double *xij, double coeff, double *f)
{
  double Xji[3] = {-Xij[0], -Xij[1], -Xij[2]}, xji[3] = {-xij[0], -xij[1], -xij[2]};
  double a[3], b[3];
  TLSPH::mat_vec(Fi, Xij, a);
  TLSPH::mat_vec(Fj, Xji, b);
  double eij[3], eji[3];
  for (int d = 0; d < 3; d++) {
    eij[d] = a[d] - xij[d];
    eji[d] = b[d] - xji[d];
  }
  const double r = tlsph_test::norm3(xij);
  const double dij = TLSPH::dot3(eij, xij) / r;
  const double dji = TLSPH::dot3(eji, xji) / r;
  for (int d = 0; d < 3; d++) f[d] = -coeff * (dij + dji) * xij[d] / r;
}

void random_F(std::mt19937 &rng, double *F)
{
  std::uniform_real_distribution<double> U(-0.3, 0.3);
  do {
    for (int k = 0; k < 9; k++) F[k] = (k % 4 == 0 ? 1.0 : 0.0) + U(rng);
  } while (TLSPH::mat_det(F) < 0.2);
}

}    // namespace

TEST(Hourglass, MatchesDocFormula)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int n = 0; n < 100; n++) {
    double Fi[9], Fj[9], X[3], x[3];
    random_F(rng, Fi);
    random_F(rng, Fj);
    for (int d = 0; d < 3; d++) {
      X[d] = 1e-3 * U(rng);
      x[d] = X[d] + 3e-4 * U(rng);
    }
    const double coeff = 1e5 * (1.0 + U(rng));
    double f[3], g[3];
    TLSPH::hourglass_force(Fi, Fj, X, x, coeff, f);
    reference_hourglass(Fi, Fj, X, x, coeff, g);
    const double scale = coeff * tlsph_test::norm3(X);
    for (int d = 0; d < 3; d++) EXPECT_NEAR(f[d], g[d], 1e-13 * scale);
  }
}

// F_i = F_j = F and x_ij = F X_ij (x from x = F X + c): exactly zero force
TEST(Hourglass, ZeroForHomogeneousDeformation)
{
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const double axis[3] = {0.3, -1.0, 0.4};
  for (int n = 0; n < 200; n++) {
    double F[9], R[9], FR[9];
    random_F(rng, F);
    tlsph_test::rotation(axis, 3.0 * U(rng), R);
    TLSPH::mat_mul(R, F, FR);    // large rotations as well
    double Xi[3], Xj[3], c[3];
    for (int d = 0; d < 3; d++) {
      Xi[d] = 1e-2 * U(rng);
      Xj[d] = Xi[d] + 2e-3 * U(rng);
      c[d] = 0.1 * U(rng);
    }
    double xi[3], xj[3];
    TLSPH::mat_vec(FR, Xi, xi);
    TLSPH::mat_vec(FR, Xj, xj);
    const double X[3] = {Xj[0] - Xi[0], Xj[1] - Xi[1], Xj[2] - Xi[2]};
    const double x[3] = {xj[0] + c[0] - xi[0] - c[0], xj[1] + c[1] - xi[1] - c[1],
                         xj[2] + c[2] - xi[2] - c[2]};
    const double coeff = 3e6;
    double f[3];
    TLSPH::hourglass_force(FR, FR, X, x, coeff, f);
    // round-off only: relative to the force of a unit error, coeff |X|
    EXPECT_LT(tlsph_test::norm3(f), 1e-12 * coeff * tlsph_test::norm3(X)) << "sample " << n;
    // a 1% bond-length error on the same pair is well above that
    const double x2[3] = {1.01 * x[0], 1.01 * x[1], 1.01 * x[2]};
    TLSPH::hourglass_force(FR, FR, X, x2, coeff, f);
    EXPECT_GT(tlsph_test::norm3(f), 1e-3 * coeff * tlsph_test::norm3(X));
  }
}

TEST(Hourglass, PairAntisymmetry)
{
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int n = 0; n < 100; n++) {
    double Fi[9], Fj[9], X[3], x[3];
    random_F(rng, Fi);
    random_F(rng, Fj);
    for (int d = 0; d < 3; d++) {
      X[d] = 1e-3 * U(rng);
      x[d] = X[d] + 4e-4 * U(rng);
    }
    const double mX[3] = {-X[0], -X[1], -X[2]}, mx[3] = {-x[0], -x[1], -x[2]};
    double fi[3], fj[3];
    TLSPH::hourglass_force(Fi, Fj, X, x, 7e5, fi);
    TLSPH::hourglass_force(Fj, Fi, mX, mx, 7e5, fj);
    const double scale = 7e5 * tlsph_test::norm3(X);
    for (int d = 0; d < 3; d++) EXPECT_NEAR(fi[d], -fj[d], 1e-14 * scale);
    // a central force: parallel to x_ij
    double cr[3] = {fi[1] * x[2] - fi[2] * x[1], fi[2] * x[0] - fi[0] * x[2],
                    fi[0] * x[1] - fi[1] * x[0]};
    EXPECT_LT(tlsph_test::norm3(cr), 1e-14 * scale * tlsph_test::norm3(x));
  }
}

// restoring sign on a single stretched / compressed bond: if |x_ij| exceeds
// |F X_ij|, i is pulled towards j (f_i . x_ij > 0) for gamma > 0
TEST(Hourglass, RestoringOnSingleBond)
{
  double I[9];
  TLSPH::mat_identity(I);
  const double X[3] = {1e-3, 0.5e-3, 0.0};
  const double longer[3] = {1.1e-3, 0.55e-3, 0.0}, shorter[3] = {0.9e-3, 0.45e-3, 0.0};
  double f[3];
  TLSPH::hourglass_force(I, I, X, longer, 1e6, f);
  EXPECT_GT(TLSPH::dot3(f, longer), 0.0);
  TLSPH::hourglass_force(I, I, X, shorter, 1e6, f);
  EXPECT_LT(TLSPH::dot3(f, shorter), 0.0);
  // negative gamma flips it
  TLSPH::hourglass_force(I, I, X, longer, -1e6, f);
  EXPECT_LT(TLSPH::dot3(f, longer), 0.0);
}

/* Checkerboard (zero-energy) mode on a 2D lattice: u_i = s_i e y with
   s_i = (-1)^(ix+iy), F from the corrected gradient, both orders. In the
   interior the mode is invisible to F (F = I, no stress: the bulk g_ij is
   odd in X_ij for both orders, the mode even); the hourglass force must
   oppose the displacement of every particle and dissipate the mode. */
TEST(Hourglass, CheckerboardModeIsRestoring)
{
  for (int order : ORDERS) {
    System s = System::lattice(2, 12, 12, 1, 1e-3, 1.33, order);
    s.build_bonds();
    s.correct();
    const double e = 0.01 * s.dx;
    std::vector<double> u(3 * s.size(), 0.0);
    for (int iy = 0; iy < s.n[1]; iy++)
      for (int ix = 0; ix < s.n[0]; ix++) {
        const int i = s.index(ix, iy);
        u[3 * i + 1] = ((ix + iy) % 2 ? -1.0 : 1.0) * e;
      }
    for (int k = 0; k < 3 * s.size(); k++) s.x[k] = s.X[k] + u[k];
    s.v = u;    // velocity along the mode: the power is that of the mode
    s.deform();

    // the zero-energy mode: F = I away from the boundary (support complete)
    double I[9];
    TLSPH::mat_identity(I);
    for (int i = 0; i < s.size(); i++) {
      if (s.layer[i] >= 2) {
        ASSERT_LT(tlsph_test::max_abs_diff9(&s.F[9 * i], I), 1e-12) << "order " << order << " " << i;
      }
    }

    for (double gamma : {1.0, 5.0}) {
      s.forces<1, 0>(0.0, 0.0, gamma);
      // the stress does not resist the mode deep inside
      const double scale = tlsph_test::STEEL_E * s.V[0] / s.dx * (e / s.dx);
      for (int i = 0; i < s.size(); i++) {
        if (s.layer[i] >= 4) {
          EXPECT_LT(tlsph_test::norm3(&s.fs[3 * i]), 1e-10 * scale)
              << "order " << order << " stress at " << i;
        }
      }

      double power = 0.0, fhmax = 0.0;
      int n_not_restoring = 0;
      for (int i = 0; i < s.size(); i++) {
        const double fu = TLSPH::dot3(&s.fh[3 * i], &u[3 * i]);
        fhmax = std::max(fhmax, tlsph_test::norm3(&s.fh[3 * i]));
        if (!(fu < 0.0)) {
          n_not_restoring++;
          ADD_FAILURE() << "order " << order << " gamma " << gamma << ": particle " << i
                        << " (layer " << s.layer[i] << ") f_hg . u = " << fu;
        }
        power += TLSPH::dot3(&s.fh[3 * i], &s.v[3 * i]);
      }
      EXPECT_EQ(n_not_restoring, 0);
      EXPECT_LT(power, 0.0);
      EXPECT_GT(fhmax, 0.0);
      // the hourglass forces of the pairs cancel (antisymmetry at system level)
      double sum[3] = {0, 0, 0}, mag = 0.0;
      for (int i = 0; i < s.size(); i++) {
        for (int d = 0; d < 3; d++) sum[d] += s.fh[3 * i + d];
        mag += tlsph_test::norm3(&s.fh[3 * i]);
      }
      EXPECT_LT(tlsph_test::norm3(sum), 1e-13 * mag);
    }

    // linear in gamma
    s.forces<1, 0>(0.0, 0.0, 1.0);
    const std::vector<double> f1 = s.fh;
    s.forces<1, 0>(0.0, 0.0, 5.0);
    double fmax = 0.0;
    for (int k = 0; k < 3 * s.size(); k++) fmax = std::max(fmax, std::fabs(s.fh[k]));
    // round-off of the per-particle sums: relative to the largest force
    for (int k = 0; k < 3 * s.size(); k++) EXPECT_NEAR(s.fh[k], 5.0 * f1[k], 1e-12 * fmax);
  }
}

// hourglass term of particle_force on a lattice in homogeneous deformation:
// zero on every particle, boundary included (unlike the stress term), both orders
TEST(Hourglass, LatticeHomogeneousZero)
{
  for (int order : ORDERS)
    for (int dim : {2, 3}) {
      System s = (dim == 2) ? System::lattice(2, 9, 9, 1, 1e-3, 1.33, order)
                            : System::lattice(3, 6, 6, 6, 1e-3, 1.33, order);
      s.build_bonds();
      s.correct();
      const double F3[9] = {1.10, 0.25, -0.08, -0.12, 0.92, 0.31, 0.05, -0.20, 1.05};
      const double F2[9] = {1.20, 0.30, 0.0, -0.10, 0.90, 0.0, 0.0, 0.0, 1.0};
      const double c[3] = {0.01, 0.02, 0.03};
      s.affine(dim == 2 ? F2 : F3, c);
      s.deform();
      s.forces<1, 0>(0.0, 0.0, 10.0);
      const double scale = 10.0 * tlsph_test::STEEL_E * s.V[0] / s.dx;
      for (int i = 0; i < s.size(); i++)
        EXPECT_LT(tlsph_test::norm3(&s.fh[3 * i]), 1e-12 * scale)
            << "order " << order << " dim " << dim << " " << i;
      // the stress term is not zero on the boundary: the hourglass check is
      // not vacuous (same lattice, same F)
      double fsmax = 0.0;
      for (int i = 0; i < s.size(); i++) fsmax = std::max(fsmax, tlsph_test::norm3(&s.fs[3 * i]));
      EXPECT_GT(fsmax, 1e-3 * scale / 10.0) << "order " << order << " dim " << dim;
    }
}
