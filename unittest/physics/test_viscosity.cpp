/* ----------------------------------------------------------------------
   Artificial viscosity (tlsph_pair_terms.h: viscous_pressure, and the
   viscous term of particle_force: -V_i sum_j q_ij (K_i + K_j) V_j grad_i W_ij / 2
   with the uncorrected kernel gradient, K = J F^-T and q_ij from the
   approach rate along the current separation x_ij).
------------------------------------------------------------------------- */

#include "physics_system.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

using tlsph_test::ORDERS;
using tlsph_test::System;

namespace {

// Monaghan's q from the doc, computed from the particle vectors:
// mu = h (v_i - v_j).(X_i - X_j) / (|X_ij|^2 + 0.01 h^2) when negative,
// q = rho (-alpha c mu + beta mu^2)
double reference_q(const double *vi, const double *vj, const double *Xi, const double *Xj,
                   double h, double alpha, double beta, double c, double rho)
{
  double dv_dX = 0.0, X2 = 0.0;
  for (int d = 0; d < 3; d++) {
    dv_dX += (vi[d] - vj[d]) * (Xi[d] - Xj[d]);
    X2 += (Xi[d] - Xj[d]) * (Xi[d] - Xj[d]);
  }
  if (!(dv_dX < 0.0)) return 0.0;
  const double mu = h * dv_dX / (X2 + 0.01 * h * h);
  return rho * (-alpha * c * mu + beta * mu * mu);
}

double dvX_of(const double *vi, const double *vj, const double *Xi, const double *Xj)
{
  // the argument the header expects: (v_j - v_i) . X_ij, X_ij = X_j - X_i
  double s = 0.0;
  for (int d = 0; d < 3; d++) s += (vj[d] - vi[d]) * (Xj[d] - Xi[d]);
  return s;
}

}    // namespace

TEST(Viscosity, ZeroWhenSeparatingOrSliding)
{
  const double h = 1.33e-3, c = 6000.0, rho = 7850.0;
  const double Xi[3] = {0, 0, 0}, Xj[3] = {1e-3, 0.4e-3, 0};
  // separating: v_j - v_i along X_ij
  const double vi[3] = {-1.0, -0.4, 0.0}, vj[3] = {2.0, 0.8, 0.0};
  EXPECT_GT(dvX_of(vi, vj, Xi, Xj), 0.0);
  EXPECT_EQ(TLSPH::viscous_pressure(dvX_of(vi, vj, Xi, Xj), 1.16e-6, h, 1.0, 1.0, c, rho), 0.0);
  // sliding past each other (relative velocity normal to X_ij)
  const double vs[3] = {-0.4, 1.0, 0.0}, z[3] = {0, 0, 0};
  EXPECT_EQ(TLSPH::viscous_pressure(dvX_of(z, vs, Xi, Xj), 1.16e-6, h, 1.0, 1.0, c, rho), 0.0);
}

TEST(Viscosity, ApproachingMatchesFormula)
{
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const double h = 1.33e-3, c = 6000.0, rho = 7850.0;
  int napproach = 0;
  for (int n = 0; n < 200; n++) {
    double Xi[3], Xj[3], vi[3], vj[3];
    for (int d = 0; d < 3; d++) {
      Xi[d] = 1e-3 * U(rng);
      Xj[d] = Xi[d] + 2e-3 * U(rng);
      vi[d] = 50.0 * U(rng);
      vj[d] = 50.0 * U(rng);
    }
    double X2 = 0.0;
    for (int d = 0; d < 3; d++) X2 += (Xj[d] - Xi[d]) * (Xj[d] - Xi[d]);
    for (double alpha : {0.0, 1.0, 2.5})
      for (double beta : {0.0, 1.0}) {
        const double q = TLSPH::viscous_pressure(dvX_of(vi, vj, Xi, Xj), X2, h, alpha, beta, c,
                                                 rho);
        const double qr = reference_q(vi, vj, Xi, Xj, h, alpha, beta, c, rho);
        EXPECT_NEAR(q, qr, 1e-13 * std::fabs(qr));
        EXPECT_GE(q, 0.0);
        if (qr > 0.0 && alpha == 1.0 && beta == 1.0) napproach++;
      }
  }
  EXPECT_GT(napproach, 50);    // both branches were exercised

  // one worked value: head-on approach at 10 m/s over |X| = dx = 1 mm
  // mu = 1.33e-3 * (-10 * 1e-3) / (1e-6 + 0.01 * 1.33e-3^2) = -13.068826
  // q = rho (alpha c |mu| + beta mu^2) = 7850 (6000 * 13.068826 + 2 * 13.068826^2)
  //   = 6.18223e8 Pa for alpha = 1, beta = 2
  const double q = TLSPH::viscous_pressure(-10.0e-3, 1e-6, h, 1.0, 2.0, c, rho);
  EXPECT_NEAR(q, 6.18223e8, 1e3);
}

/* Particle level, F = I: a rigid translation feels no viscosity (exactly),
   a separating (expanding) flow none either, a converging flow is slowed
   down (negative power) and the viscous forces still cancel in sum. The
   viscous term uses the uncorrected kernel gradient: with the same F it is
   the same for both gradient orders. */
TEST(Viscosity, LatticeFlows)
{
  for (int dim : {2, 3}) {
    std::vector<double> fv_order1;
    for (int order : ORDERS) {
      System s = (dim == 2) ? System::lattice(2, 9, 8, 1, 1e-3, 1.33, order)
                            : System::lattice(3, 6, 5, 6, 1e-3, 1.33, order);
      s.build_bonds();
      s.correct();
      s.deform();
      const double xc[3] = {4e-3, 3.5e-3, dim == 2 ? 0.0 : 2.5e-3};
      // translation
      for (int i = 0; i < s.size(); i++)
        for (int d = 0; d < dim; d++) s.v[3 * i + d] = (d + 1) * 7.0;
      s.forces<0, 1>(1.0, 1.0, 0.0);
      for (int k = 0; k < 3 * s.size(); k++) EXPECT_EQ(s.fv[k], 0.0);
      // expansion v = k (X - xc)
      for (int i = 0; i < s.size(); i++)
        for (int d = 0; d < dim; d++) s.v[3 * i + d] = 1e4 * (s.X[3 * i + d] - xc[d]);
      s.forces<0, 1>(1.0, 1.0, 0.0);
      for (int k = 0; k < 3 * s.size(); k++) EXPECT_EQ(s.fv[k], 0.0);
      // compression v = -k (X - xc)
      for (int k = 0; k < 3 * s.size(); k++) s.v[k] = -s.v[k];
      s.forces<0, 1>(1.0, 1.0, 0.0);
      double power = 0.0, mag = 0.0, sum[3] = {0, 0, 0};
      for (int i = 0; i < s.size(); i++) {
        power += TLSPH::dot3(&s.fv[3 * i], &s.v[3 * i]);
        mag += tlsph_test::norm3(&s.fv[3 * i]);
        for (int d = 0; d < 3; d++) sum[d] += s.fv[3 * i + d];
      }
      EXPECT_GT(mag, 0.0);
      EXPECT_LT(power, 0.0) << "order " << order << " dim " << dim;
      EXPECT_LT(tlsph_test::norm3(sum), 1e-13 * mag);
      // the particle at the corner X = 0 moves towards the centre; the
      // viscosity pushes it back out (against its velocity)
      const int corner = s.index(0, 0, 0);
      EXPECT_LT(TLSPH::dot3(&s.fv[3 * corner], &s.v[3 * corner]), 0.0);
      // independent of the gradient order (F = I exactly for both)
      if (order == 1) fv_order1 = s.fv;
      else {
        ASSERT_EQ(fv_order1.size(), s.fv.size());
        for (int k = 0; k < 3 * s.size(); k++)
          EXPECT_NEAR(s.fv[k], fv_order1[k], 1e-14 * mag / s.size()) << "dim " << dim << " " << k;
      }
    }
  }
}

/* A body rigidly rotated by theta that spins at omega feels no viscosity:
   particle_force measures the approach rate along the current separation,
   (v_j - v_i).x_ij = 0 for a rigid motion (objective). With the reference
   separations of the thesis it would be -omega sin(theta) |X_ij|^2 != 0 and
   the viscosity would act on the rigid motion at theta = 35 degrees. Both
   angles, both gradient orders; the measured force is printed. */
TEST(Viscosity, RigidSpinMeasurement)
{
  const double omega = 1.0e3;    // rad/s
  for (int order : ORDERS)
    for (double theta_deg : {0.0, 35.0}) {
      System s = System::lattice(2, 10, 10, 1, 1e-3, 1.33, order);
      s.build_bonds();
      s.correct();
      const double th = theta_deg * 3.14159265358979323846 / 180.0;
      const double R[9] = {std::cos(th), -std::sin(th), 0, std::sin(th), std::cos(th), 0, 0, 0, 1};
      const double c[3] = {0, 0, 0};
      s.affine(R, c);
      const double xc[2] = {4.5e-3 * (std::cos(th) - std::sin(th)),
                            4.5e-3 * (std::sin(th) + std::cos(th))};
      for (int i = 0; i < s.size(); i++) {
        s.v[3 * i] = -omega * (s.x[3 * i + 1] - xc[1]);
        s.v[3 * i + 1] = omega * (s.x[3 * i] - xc[0]);
      }
      s.deform();
      s.forces<0, 1>(1.0, 0.0, 0.0);
      double power = 0.0, fmax = 0.0;
      for (int i = 0; i < s.size(); i++) {
        power += TLSPH::dot3(&s.fv[3 * i], &s.v[3 * i]);
        fmax = std::max(fmax, tlsph_test::norm3(&s.fv[3 * i]));
      }
      // force scale of the same speed in a head-on approach: rho c (omega dx) V / dx
      const double fscale = s.mats[0].rho * s.mats[0].c0 * omega * s.dx * s.V[0] / s.dx;
      std::printf("[ info ] order %d, rigid spin omega = %g rad/s at theta = %g deg: max "
                  "|f_visc| = %.3e N/m (%.2e of rho c |dv| V/dx), power = %.3e W/m\n",
                  order, omega, theta_deg, fmax, fmax / fscale, power);
      EXPECT_LT(fmax, 1e-10 * fscale) << "order " << order << " theta " << theta_deg;
    }
}
