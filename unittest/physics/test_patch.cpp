/* ----------------------------------------------------------------------
   Corrected gradient (tlsph_particle.h: make_bond, correction,
   deformation_gradient): the patch test, for both gradient orders. An
   affine field x = F0 X + c must give F = F0 on every particle, boundary
   and corner particles included; with ORDER 2 a quadratic field must give
   its exact F on every particle whose correction reached order 2.
------------------------------------------------------------------------- */

#include "physics_system.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

using tlsph_test::ORDERS;
using tlsph_test::System;

namespace {

// general non-symmetric matrices with det > 0
const double F0_3D[9] = {1.10, 0.25, -0.08,    //
                         -0.12, 0.92, 0.31,    //
                         0.05, -0.20, 1.05};
const double F0_2D[9] = {1.20, 0.30, 0.0,    //
                         -0.10, 0.90, 0.0,    //
                         0.0, 0.0, 1.0};
const double C_SHIFT[3] = {0.137, -0.052, 0.011};

// max over particles of max_k |F_i,k - F0_k|
double worst_F_error(const System &s, const double *F0)
{
  double worst = 0.0;
  for (int i = 0; i < s.size(); i++)
    worst = std::max(worst, tlsph_test::max_abs_diff9(&s.F[9 * i], F0));
  return worst;
}

int count_layer(const System &s, int l)
{
  int c = 0;
  for (int i = 0; i < s.size(); i++) c += (s.layer[i] == l);
  return c;
}

}    // namespace

TEST(PatchTest, NonSymmetricF0HasPositiveDet)
{
  EXPECT_GT(TLSPH::mat_det(F0_3D), 0.0);
  EXPECT_GT(TLSPH::mat_det(F0_2D), 0.0);
  // and they are really non-symmetric, so F vs F^T would be caught
  EXPECT_GT(std::fabs(F0_3D[1] - F0_3D[3]), 0.1);
  EXPECT_GT(std::fabs(F0_2D[1] - F0_2D[3]), 0.1);
}

/* Every particle of the lattice, corners included, gets a well-conditioned
   correction: ORDER 1 everywhere; ORDER 2 everywhere as well (a surface
   particle would be allowed to fall back to the W-weighted linear
   correction, order 1, never to none; none does). The counts are printed
   and pinned (they are a property of the lattice and of
   MAX_CONDITION_QUADRATIC). */
TEST(PatchTest, AllLatticeParticlesWellConditioned)
{
  for (int order : ORDERS)
    for (int dim : {2, 3}) {
      System s = (dim == 2) ? System::lattice(2, 10, 10, 1, 1e-3, 1.33, order)
                            : System::lattice(3, 8, 8, 8, 1e-3, 1.33, order);
      s.build_bonds();
      s.correct();
      int fallback = 0;
      for (int i = 0; i < s.size(); i++) {
        if (order == 1) {
          EXPECT_EQ(s.achieved[i], 1) << "particle " << i;
        } else {
          EXPECT_GE(s.achieved[i], 1) << "particle " << i;
          if (s.achieved[i] != 2) {
            fallback++;
            EXPECT_EQ(s.layer[i], 0) << "particle " << i << " fell back to order "
                                     << s.achieved[i] << " off the surface";
          }
        }
      }
      // measured: no particle falls back on these lattices, corners included
      // (their quadratic moment matrices have condition numbers of ~1e2, far
      // below MAX_CONDITION_QUADRATIC)
      if (order == 2) {
        EXPECT_EQ(s.count_achieved(2), s.size()) << "dim " << dim;
      }
      std::printf("[ info ] dim %d, order %d requested, %d particles: %d reach order 2, %d order "
                  "1, %d order 0\n",
                  dim, order, s.size(), s.count_achieved(2), s.count_achieved(1),
                  s.count_achieved(0));
      // a corner sees a quarter (2D) or an octant (3D) of the support: offsets
      // in {0,1,2}^dim except 0 and those with two 2s (|X| = sqrt(8) dx > 2h)
      const int corner = s.index(0, 0, 0);
      EXPECT_EQ(s.bonds[corner].size(), dim == 2 ? 7u : 19u);
      // an interior particle has the full support: 20 (2D), 80 (3D) partners
      const int mid = (dim == 2) ? s.index(5, 5) : s.index(4, 4, 4);
      EXPECT_EQ(s.bonds[mid].size(), dim == 2 ? 20u : 80u);
    }
}

/* Reproducing conditions of the corrected gradient, checked with an
   independent loop over the bonds (without deformation_gradient):
   - both orders: sum_j X_ij (x) g_ij = I on every particle (linear
     completeness; for ORDER 1 the old sum_j V_j X_ij (x) gradt W_ij = I);
   - ORDER 2, particles that reached order 2: sum_j (X_ij)_a (X_ij)_b g_ij = 0
     for all a, b (quadratic completeness), measured in units of h;
   - ORDER 1 is the thesis's correction: g_ij = A_i^-1 V_j grad_i W_ij with
     A_i = sum_j V_j grad_i W_ij (x) X_ij, built here from kernel.gradient()
     and mat_inverse(), and Q_i = h A_i^-1 (the basis is p(X/h), so
     Q = M^-1 / h with M = A / h^2: Q is A^-1 scaled by h, not A^-1 itself);
     and its quadratic moments do not vanish at the surface (so the ORDER 2
     check can fail). */
TEST(PatchTest, CorrectedGradientReproducesIdentity)
{
  for (int order : ORDERS)
    for (int dim : {2, 3}) {
      System s = (dim == 2) ? System::lattice(2, 10, 10, 1, 1e-3, 1.33, order)
                            : System::lattice(3, 7, 7, 7, 1e-3, 1.33, order);
      s.build_bonds();
      s.correct();
      double I[9];
      TLSPH::mat_identity(I);
      // A is dimensionless (~ I), Q / h too, g_ij is O(1/dx)
      double worst = 0.0, worst_quad = 0.0, worst_thesis = 0.0, worst_Q = 0.0;
      int nquad = 0;
      for (int i = 0; i < s.size(); i++) {
        double M[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
        if (dim == 2) M[8] = 1.0;
        for (const auto &b : s.bonds[i])
          for (int r = 0; r < dim; r++)
            for (int c = 0; c < dim; c++) M[3 * r + c] += b.X[r] * b.g[c];
        worst = std::max(worst, tlsph_test::max_abs_diff9(M, I));

        // quadratic moments sum_j (X_a X_b / h) g_ij, dimensionless
        double q = 0.0;
        for (int a = 0; a < dim; a++)
          for (int bb = a; bb < dim; bb++)
            for (int r = 0; r < dim; r++) {
              double m = 0.0;
              for (const auto &b : s.bonds[i]) m += b.X[a] * b.X[bb] / s.h * b.g[r];
              q = std::max(q, std::fabs(m));
            }
        if (order == 2 && s.achieved[i] == 2) {
          worst_quad = std::max(worst_quad, q);
          nquad++;
        }
        if (order == 1) {
          worst_quad = std::max(worst_quad, q);
          // the thesis: A = sum_j V_j grad W (x) X, gradt W = A^-1 grad W
          double A[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}, Ai[9];
          for (const auto &b : s.bonds[i]) {
            double gw[3];
            s.kernel.gradient(b.X, tlsph_test::norm3(b.X), gw);
            for (int r = 0; r < 3; r++)
              for (int c = 0; c < 3; c++) A[3 * r + c] += s.V[b.j] * gw[r] * b.X[c];
          }
          if (dim == 2) A[2] = A[5] = A[6] = A[7] = 0.0, A[8] = 1.0;
          ASSERT_NE(TLSPH::mat_inverse(A, Ai), 0.0);
          const double *Qi = &s.Q[TLSPH::QMAX * i];
          for (int r = 0; r < dim; r++)
            for (int c = 0; c < dim; c++)
              worst_Q = std::max(worst_Q, std::fabs(Qi[dim * r + c] / s.h - Ai[3 * r + c]));
          for (const auto &b : s.bonds[i]) {
            double gw[3], gt[3];
            s.kernel.gradient(b.X, tlsph_test::norm3(b.X), gw);
            for (int d = 0; d < 3; d++) gw[d] *= s.V[b.j];
            TLSPH::mat_vec(Ai, gw, gt);
            for (int d = 0; d < dim; d++)
              worst_thesis = std::max(worst_thesis, std::fabs(b.g[d] - gt[d]) * s.dx);
          }
        }
      }
      EXPECT_LT(worst, 1e-12) << "order " << order << " dim " << dim;
      std::printf("[ info ] order %d dim %d: |sum X (x) g - I| = %.2e, max |sum X_a X_b g / h| "
                  "= %.2e\n", order, dim, worst, worst_quad);
      if (order == 2) {
        ASSERT_GT(nquad, 0);
        EXPECT_LT(worst_quad, 1e-12) << "dim " << dim;
      } else {
        // gradient differences are O(1/dx): relative to that, round-off only
        EXPECT_LT(worst_thesis, 1e-12) << "dim " << dim;
        EXPECT_LT(worst_Q, 1e-12) << "dim " << dim;
        EXPECT_GT(worst_quad, 1e-2) << "dim " << dim;
      }
    }
}

// x = X: F = I everywhere
TEST(PatchTest, IdentityMotionGivesIdentityF)
{
  for (int order : ORDERS)
    for (int dim : {2, 3}) {
      System s = (dim == 2) ? System::lattice(2, 10, 10, 1, 1e-3, 1.33, order)
                            : System::lattice(3, 7, 7, 7, 1e-3, 1.33, order);
      s.build_bonds();
      s.correct();
      s.deform();
      double I[9];
      TLSPH::mat_identity(I);
      EXPECT_LT(worst_F_error(s, I), 1e-14) << "order " << order << " dim " << dim;
      // pure translation x = X + c as well
      s.affine(I, C_SHIFT);
      s.deform();
      EXPECT_LT(worst_F_error(s, I), 1e-12) << "order " << order << " dim " << dim;
    }
}

TEST(PatchTest, AffineField3DExactOnEveryParticle)
{
  for (int order : ORDERS) {
    System s = System::lattice(3, 8, 8, 8, 1e-3, 1.33, order);
    s.build_bonds();
    s.correct();
    s.affine(F0_3D, C_SHIFT);
    s.deform();
    ASSERT_GT(count_layer(s, 0), 0);
    for (int i = 0; i < s.size(); i++)
      EXPECT_LT(tlsph_test::max_abs_diff9(&s.F[9 * i], F0_3D), 1e-12)
          << "order " << order << " particle " << i << " (layer " << s.layer[i] << ", order "
          << s.achieved[i] << ")";
    // the transposed gradient would be far off: the test can tell F from F^T
    double F0T[9];
    TLSPH::mat_transpose(F0_3D, F0T);
    EXPECT_GT(worst_F_error(s, F0T), 0.1);
  }
}

TEST(PatchTest, AffineField2DExactOnEveryParticle)
{
  for (int order : ORDERS) {
    System s = System::lattice(2, 12, 9, 1, 1e-3, 1.33, order);
    s.build_bonds();
    s.correct();
    s.affine(F0_2D, C_SHIFT);
    s.deform();
    for (int i = 0; i < s.size(); i++)
      EXPECT_LT(tlsph_test::max_abs_diff9(&s.F[9 * i], F0_2D), 1e-12)
          << "order " << order << " particle " << i << " (layer " << s.layer[i] << ", order "
          << s.achieved[i] << ")";
    double F0T[9];
    TLSPH::mat_transpose(F0_2D, F0T);
    EXPECT_GT(worst_F_error(s, F0T), 0.1);
  }
}

namespace {
// a randomly perturbed reference configuration with non-uniform volumes
System irregular(int dim, int order, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  System s = (dim == 2) ? System::lattice(2, 10, 10, 1, 1e-3, 1.33, order)
                        : System::lattice(3, 7, 7, 7, 1e-3, 1.33, order);
  for (int i = 0; i < s.size(); i++) {
    for (int d = 0; d < dim; d++) s.X[3 * i + d] += 0.2 * s.dx * U(rng);
    s.V[i] *= 1.0 + 0.3 * U(rng);
  }
  s.x = s.X;
  s.build_bonds();
  s.correct();
  return s;
}
}    // namespace

/* The correction does not rely on the lattice: on a randomly perturbed
   reference configuration with non-uniform volumes the affine field is still
   reproduced exactly (first-order completeness of the corrected gradient),
   by both orders; with ORDER 2 a particle may fall back to order 1 (which
   still reproduces affine fields), never to 0. */
TEST(PatchTest, AffineFieldExactOnIrregularParticles)
{
  for (int order : ORDERS)
    for (int dim : {2, 3}) {
      System s = irregular(dim, order, 12345u);
      const double *F0 = (dim == 2) ? F0_2D : F0_3D;
      s.affine(F0, C_SHIFT);
      s.deform();
      for (int i = 0; i < s.size(); i++) {
        ASSERT_GE(s.achieved[i], 1) << "order " << order << " particle " << i;
        if (order == 1) {
          ASSERT_EQ(s.achieved[i], 1) << "particle " << i;
        }
        EXPECT_LT(tlsph_test::max_abs_diff9(&s.F[9 * i], F0), 1e-11)
            << "order " << order << " dim " << dim << " particle " << i;
      }
      std::printf("[ info ] irregular, dim %d, order %d requested, %d particles: %d reach order "
                  "2, %d order 1\n", dim, order, s.size(), s.count_achieved(2),
                  s.count_achieved(1));
    }
}

/* Too few partners (a particle that lost its bonds): the documented fallback
   is Q = 0, so g = 0, sum g = 0 and F = I, no NaN; correction() returns the
   order achieved. A quadratic correction with too few partners for its
   basis falls back to the linear one. */
TEST(PatchTest, IllConditionedParticleFallsBack)
{
  const TLSPH::CubicSpline k3(1.33e-3, 3), k2(1.33e-3, 2);
  const double X1[3] = {1e-3, 0.0, 0.0}, X2[3] = {0.0, 1e-3, 0.0};
  const double vj[2] = {1e-9, 1e-9};
  TLSPH::Bond b[2];
  // correction() completes g and c in place: fresh bonds for every call
  auto fresh = [&](const TLSPH::CubicSpline &k) {
    TLSPH::make_bond(k, X1, 1e-9, vj[0], 1, 0, b[0]);
    TLSPH::make_bond(k, X2, 1e-9, vj[1], 2, 1, b[1]);
  };
  auto all_zero = [](const double *a, int n) {
    for (int m = 0; m < n; m++)
      if (a[m] != 0.0) return false;
    return true;
  };
  double Q[TLSPH::QMAX], sumg[3];

  // 3D with two in-plane bonds: rank 2, for both orders
  fresh(k3);
  EXPECT_EQ((TLSPH::correction<3, 1>(b, 2, vj, k3, Q, sumg)), 0);
  EXPECT_TRUE(all_zero(Q, 9));
  EXPECT_TRUE(all_zero(sumg, 3));
  EXPECT_TRUE(all_zero(b[0].g, 3) && all_zero(b[1].g, 3));
  fresh(k3);
  for (double &q : Q) q = 1.0;
  EXPECT_EQ((TLSPH::correction<3, 2>(b, 2, vj, k3, Q, sumg)), 0);
  EXPECT_TRUE(all_zero(Q, 27));
  EXPECT_TRUE(all_zero(sumg, 3));
  // 2D with one bond: rank 1
  fresh(k2);
  EXPECT_EQ((TLSPH::correction<2, 1>(b, 1, vj, k2, Q, sumg)), 0);
  fresh(k2);
  EXPECT_EQ((TLSPH::correction<2, 2>(b, 1, vj, k2, Q, sumg)), 0);
  // no bond at all
  EXPECT_EQ((TLSPH::correction<2, 1>(b, 0, vj, k2, Q, sumg)), 0);
  EXPECT_TRUE(all_zero(sumg, 3));
  EXPECT_EQ((TLSPH::correction<3, 2>(b, 0, vj, k3, Q, sumg)), 0);
  EXPECT_TRUE(all_zero(sumg, 3));
  // 2D with the two bonds: fine for ORDER 1; ORDER 2 has 5 basis functions
  // and only 2 partners: it falls back to the linear correction
  fresh(k2);
  EXPECT_EQ((TLSPH::correction<2, 1>(b, 2, vj, k2, Q, sumg)), 1);
  fresh(k2);
  EXPECT_EQ((TLSPH::correction<2, 2>(b, 2, vj, k2, Q, sumg)), 1);
  // the fallback has zero quadratic columns and reproduces X (x) g = I
  for (int r = 0; r < 2; r++)
    for (int c = 2; c < 5; c++) EXPECT_EQ(Q[5 * r + c], 0.0);
  for (int r = 0; r < 2; r++)
    for (int c = 0; c < 2; c++)
      EXPECT_NEAR(b[0].X[r] * b[0].g[c] + b[1].X[r] * b[1].g[c], r == c ? 1.0 : 0.0, 1e-14);

  // F from an ill-conditioned particle is I and finite whatever the motion
  const double xs[9] = {0, 0, 0, 1.7e-3, 0.2e-3, 0, -0.1e-3, 0.8e-3, 0};
  const tlsph_test::Rows xr{xs, 3};
  double I[9], F[9];
  TLSPH::mat_identity(I);
  fresh(k3);
  TLSPH::correction<3, 1>(b, 2, vj, k3, Q, sumg);
  TLSPH::deformation_gradient<3>(xr, 0, b, 2, F);
  EXPECT_EQ(tlsph_test::max_abs_diff9(F, I), 0.0);
  fresh(k3);
  TLSPH::correction<3, 2>(b, 2, vj, k3, Q, sumg);
  TLSPH::deformation_gradient<3>(xr, 0, b, 2, F);
  EXPECT_EQ(tlsph_test::max_abs_diff9(F, I), 0.0);
  // while the well-conditioned 2D particle does see the motion (checked below)
  fresh(k2);
  TLSPH::correction<2, 2>(b, 2, vj, k2, Q, sumg);
  TLSPH::deformation_gradient<2>(xr, 0, b, 2, F);
  EXPECT_GT(tlsph_test::max_abs_diff9(F, I), 0.1);

  // a strip (2D) or slab (3D) two particles thick: on its particles
  // y^2 = dx y, the quadratic moment matrix is singular and every particle
  // falls back to order 1, which still reproduces affine fields exactly
  for (int dim : {2, 3}) {
    System s = (dim == 2) ? System::lattice(2, 8, 2, 1, 1e-3, 1.33, 2)
                          : System::lattice(3, 5, 2, 5, 1e-3, 1.33, 2);
    s.build_bonds();
    s.correct();
    EXPECT_EQ(s.count_achieved(1), s.size()) << "dim " << dim;
    const double F0[9] = {1.20, 0.30, -0.05, -0.10, 0.90, 0.08, 0.04, -0.02, 1.1};
    double F0d[9];
    TLSPH::mat_copy(F0, F0d);
    if (dim == 2) F0d[2] = F0d[5] = F0d[6] = F0d[7] = 0.0, F0d[8] = 1.0;
    s.affine(F0d, C_SHIFT);
    s.deform();
    for (int i = 0; i < s.size(); i++)
      EXPECT_LT(tlsph_test::max_abs_diff9(&s.F[9 * i], F0d), 1e-12) << "dim " << dim << " " << i;
  }
}

/* ----------------------------------------------------------------------
   Quadratic patch test: x = X + u(X) with u_r = sum_ab B^r_ab X_a X_b,
   exact F_rc = delta_rc + sum_b (B^r_cb + B^r_bc) X_b.
   - ORDER 2: exact on every particle that reached order 2, corners
     included when they did (on the lattice and on perturbed particles);
   - ORDER 1: exact where the support is point-symmetric (lattice layer >= 2,
     where sum_j X_a X_b g_ij vanishes by symmetry), but not at the surface.
   The number of ORDER 2 particles that fell back to order 1 is printed.
------------------------------------------------------------------------- */

namespace {

struct Quadratic {
  double B[3][3][3];    // B[r][a][b]

  Quadratic(int dim, unsigned seed)
  {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    for (auto &Br : B)
      for (auto &Bra : Br)
        for (double &v : Bra) v = 0.0;
    // 10 / m: u up to ~1e-3 m and grad u up to ~0.3 on a 1 cm lattice
    for (int r = 0; r < dim; r++)
      for (int a = 0; a < dim; a++)
        for (int b = 0; b < dim; b++) B[r][a][b] = 10.0 * U(rng);
  }
  void apply(System &s) const
  {
    for (int i = 0; i < s.size(); i++) {
      const double *X = s.Xr(i);
      for (int r = 0; r < 3; r++) {
        double u = 0.0;
        for (int a = 0; a < 3; a++)
          for (int b = 0; b < 3; b++) u += B[r][a][b] * X[a] * X[b];
        s.x[3 * i + r] = X[r] + u;
      }
    }
  }
  void exact_F(const double *X, double *F) const
  {
    TLSPH::mat_identity(F);
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++)
        for (int b = 0; b < 3; b++) F[3 * r + c] += (B[r][c][b] + B[r][b][c]) * X[b];
  }
};

}    // namespace

TEST(PatchTest, QuadraticFieldExactWithOrder2)
{
  for (int dim : {2, 3})
    for (bool perturbed : {false, true})
      for (int order : ORDERS) {
        System s = perturbed ? irregular(dim, order, 777u)
                 : (dim == 2) ? System::lattice(2, 10, 10, 1, 1e-3, 1.33, order)
                              : System::lattice(3, 7, 7, 7, 1e-3, 1.33, order);
        if (!perturbed) {
          s.build_bonds();
          s.correct();
        }
        const Quadratic q(dim, 4242u + dim);
        q.apply(s);
        s.deform();
        double worst2 = 0.0, worst_fallback = 0.0, worst_sym = 0.0, worst_surface = 0.0;
        int corners2 = 0, ncorner = 0;
        for (int i = 0; i < s.size(); i++) {
          double Fex[9];
          q.exact_F(s.Xr(i), Fex);
          const double e = tlsph_test::max_abs_diff9(&s.F[9 * i], Fex);
          // a lattice corner: layer 0 in every direction
          bool corner = !perturbed;
          for (int d = 0; d < dim && corner; d++) {
            const int id = static_cast<int>(std::lround(s.X[3 * i + d] / s.dx));
            corner = (id == 0 || id == s.n[d] - 1);
          }
          ncorner += corner;
          if (order == 2) {
            if (s.achieved[i] == 2) {
              worst2 = std::max(worst2, e);
              corners2 += corner;
              EXPECT_LT(e, 1e-11) << "dim " << dim << (perturbed ? " perturbed" : " lattice")
                                  << " particle " << i << " (layer " << s.layer[i] << ")";
            } else {
              worst_fallback = std::max(worst_fallback, e);
            }
          } else {
            if (!perturbed && s.layer[i] >= 2) {
              worst_sym = std::max(worst_sym, e);
              EXPECT_LT(e, 1e-11) << "dim " << dim << " order 1, particle " << i << " (layer "
                                  << s.layer[i] << ")";
            }
            if (s.layer[i] == 0) worst_surface = std::max(worst_surface, e);
          }
        }
        if (order == 2) {
          ASSERT_GT(s.count_achieved(2), 0);
          EXPECT_EQ(s.count_achieved(0), 0);
          std::printf("[ info ] quadratic field, dim %d %s, order 2: %d of %d particles at "
                      "order 2 (corners: %d of %d), %d fell back to order 1; worst F error "
                      "%.2e at order 2",
                      dim, perturbed ? "perturbed" : "lattice", s.count_achieved(2), s.size(),
                      corners2, ncorner, s.count_achieved(1), worst2);
          if (s.count_achieved(1) > 0) std::printf(", %.2e at the fallbacks", worst_fallback);
          std::printf("\n");
        } else {
          // the linear correction misses the quadratic field at the surface
          EXPECT_GT(worst_surface, 1e-3) << "dim " << dim;
          if (perturbed)
            std::printf("[ info ] quadratic field, dim %d perturbed, order 1: worst F error "
                        "%.2e on the surface\n", dim, worst_surface);
          else
            std::printf("[ info ] quadratic field, dim %d lattice, order 1: worst F error %.2e "
                        "on layers >= 2, %.2e on the surface\n", dim, worst_sym, worst_surface);
        }
      }
}
