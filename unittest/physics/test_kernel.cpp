/* ----------------------------------------------------------------------
   Cubic-spline kernel (tlsph_kernel.h): normalisation, lattice sum,
   gradient against finite differences, compact support, continuity.
------------------------------------------------------------------------- */

#include "physics_system.h"
#include "tlsph_kernel.h"

#include <gtest/gtest.h>

#include <cmath>

using TLSPH::CubicSpline;

namespace {

const double PI = 3.14159265358979323846;

// 5-point Gauss-Legendre on [a, b]: exact for polynomials up to degree 9
double gauss5(double a, double b, const CubicSpline &k, int dim)
{
  static const double node[5] = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                 0.5384693101056831, 0.9061798459386640};
  static const double weight[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                   0.4786286704993665, 0.2369268850561891};
  const double m = 0.5 * (a + b), hw = 0.5 * (b - a);
  double s = 0.0;
  for (int q = 0; q < 5; q++) {
    const double r = m + hw * node[q];
    // measure of the sphere of radius r: 2 pi r (2D), 4 pi r^2 (3D)
    const double shell = (dim == 2) ? 2.0 * PI * r : 4.0 * PI * r * r;
    s += weight[q] * shell * k.value(r);
  }
  return hw * s;
}

// integral of W over its support; W is a polynomial on [0,h] and on [h,2h],
// so Gauss-Legendre on each piece is exact up to round-off
double kernel_integral(const CubicSpline &k, int dim)
{
  return gauss5(0.0, k.h, k, dim) + gauss5(k.h, 2.0 * k.h, k, dim);
}

}    // namespace

TEST(Kernel, NormalisationIntegral2D)
{
  for (double h : {1.0, 1.33e-3, 0.37}) {
    const CubicSpline k(h, 2);
    EXPECT_NEAR(kernel_integral(k, 2), 1.0, 1e-13) << "h = " << h;
  }
}

TEST(Kernel, NormalisationIntegral3D)
{
  for (double h : {1.0, 1.33e-3, 0.37}) {
    const CubicSpline k(h, 3);
    EXPECT_NEAR(kernel_integral(k, 3), 1.0, 1e-13) << "h = " << h;
  }
}

// An independent check of the quadrature itself: a fine composite midpoint
// rule over the 2D square [-2h, 2h]^2, no use of radial symmetry.
TEST(Kernel, NormalisationCartesian2D)
{
  const double h = 0.5;
  const CubicSpline k(h, 2);
  const int n = 1600;
  const double L = 4.0 * h, d = L / n;
  double s = 0.0;
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) {
      const double x = -2.0 * h + (i + 0.5) * d, y = -2.0 * h + (j + 0.5) * d;
      s += k.value(std::sqrt(x * x + y * y)) * d * d;
    }
  EXPECT_NEAR(s, 1.0, 1e-5);
}

/* Lattice sum sum_j V_j W_ij for an interior particle of a regular lattice,
   h = 1.33 dx. This is a midpoint-rule quadrature of W with ~2.7 points per
   support radius; W has jumps in its second derivative at q = 1 and q = 2 so
   the sum is not exact: it comes out 1.0005 (2D) and 0.9973 (3D). The
   tolerance, 1%, bounds that quadrature error, not round-off. */
TEST(Kernel, LatticeSum)
{
  const double dx = 1.0e-3;
  for (int dim : {2, 3}) {
    const CubicSpline k(1.33 * dx, dim);
    const double V = (dim == 2) ? dx * dx : dx * dx * dx;
    double s = 0.0;
    const int zr = (dim == 2) ? 0 : 4;
    for (int a = -4; a <= 4; a++)
      for (int b = -4; b <= 4; b++)
        for (int c = -zr; c <= zr; c++) s += V * k.value(dx * std::sqrt(a * a + b * b + c * c));
    EXPECT_NEAR(s, 1.0, 1e-2) << "dim " << dim;
    // it is a quadrature, not an identity: the sum is not 1 to round-off
    EXPECT_GT(std::fabs(s - 1.0), 1e-5) << "dim " << dim;
  }
}

// dW/dr against a central difference of value(), in both branches
TEST(Kernel, DerivativeIsFiniteDifferenceOfValue)
{
  for (int dim : {2, 3}) {
    const double h = 1.33e-3;
    const CubicSpline k(h, dim);
    const double eps = 1e-6 * h;
    for (double q : {0.05, 0.3, 0.7, 0.95, 1.05, 1.4, 1.8, 1.97}) {
      const double r = q * h;
      const double fd = (k.value(r + eps) - k.value(r - eps)) / (2.0 * eps);
      const double scale = k.norm / h;    // |dW/dr| is of this order
      EXPECT_NEAR(k.derivative(r), fd, 1e-8 * scale) << "dim " << dim << " q " << q;
    }
  }
}

// grad_i W(|X_j - X_i|) for the bond Xij = X_j - X_i against a central
// difference with respect to X_i, componentwise, in 3D and 2D
TEST(Kernel, GradientIsFiniteDifferenceWrtXi)
{
  const double h = 1.33e-3;
  const double Xj[3] = {0.4e-3, -0.2e-3, 0.3e-3};
  const double Xi_list[4][3] = {{0.0, 0.0, 0.0},
                                {-0.6e-3, 0.5e-3, 0.1e-3},
                                {1.5e-3, 0.2e-3, -0.9e-3},
                                {0.9e-3, -1.7e-3, 0.5e-3}};
  for (int dim : {2, 3}) {
    const CubicSpline k(h, dim);
    for (const auto &Xi0 : Xi_list) {
      double Xij[3] = {Xj[0] - Xi0[0], Xj[1] - Xi0[1], dim == 2 ? 0.0 : Xj[2] - Xi0[2]};
      const double r = tlsph_test::norm3(Xij);
      ASSERT_LT(r, 2.0 * h);
      double g[3];
      k.gradient(Xij, r, g);
      const double eps = 1e-7 * h;
      for (int d = 0; d < dim; d++) {
        double Xp[3] = {Xi0[0], Xi0[1], Xi0[2]}, Xm[3] = {Xi0[0], Xi0[1], Xi0[2]};
        Xp[d] += eps;
        Xm[d] -= eps;
        auto dist = [&](const double *Xi) {
          const double a = Xj[0] - Xi[0], b = Xj[1] - Xi[1], c = dim == 2 ? 0.0 : Xj[2] - Xi[2];
          return std::sqrt(a * a + b * b + c * c);
        };
        const double fd = (k.value(dist(Xp)) - k.value(dist(Xm))) / (2.0 * eps);
        EXPECT_NEAR(g[d], fd, 1e-7 * k.norm / h) << "dim " << dim << " component " << d;
      }
      // points from i towards j: g . Xij > 0
      EXPECT_GT(TLSPH::dot3(g, Xij), 0.0);
    }
  }
}

TEST(Kernel, CompactSupport)
{
  for (int dim : {2, 3}) {
    const double h = 1.33e-3;
    const CubicSpline k(h, dim);
    EXPECT_DOUBLE_EQ(k.support(), 2.0 * h);
    for (double q : {2.0, 2.0 + 1e-12, 2.1, 3.0, 10.0}) {
      EXPECT_EQ(k.value(q * h), 0.0) << "q " << q;
      EXPECT_EQ(k.derivative(q * h), 0.0) << "q " << q;
      const double X[3] = {q * h, 0.0, 0.0};
      double g[3] = {1, 1, 1};
      k.gradient(X, q * h, g);
      EXPECT_EQ(g[0], 0.0);
      EXPECT_EQ(g[1], 0.0);
      EXPECT_EQ(g[2], 0.0);
    }
    // positive everywhere inside the support
    for (double q : {0.0, 0.5, 1.0, 1.5, 1.999})
      EXPECT_GT(k.value(q * h), 0.0) << "q " << q;
    // closed form at a few points: W(0) = 2/3 a_d, W(h) = 1/6 a_d, W(1.5h) = a_d/48
    EXPECT_NEAR(k.value(0.0), 2.0 / 3.0 * k.norm, 1e-15 * k.norm);
    EXPECT_NEAR(k.value(h), 1.0 / 6.0 * k.norm, 1e-15 * k.norm);
    EXPECT_NEAR(k.value(1.5 * h), k.norm / 48.0, 1e-15 * k.norm);
  }
  // normalisation constants of Eq. 2.7
  const double h = 0.7;
  EXPECT_NEAR(CubicSpline(h, 2).norm, 15.0 / (7.0 * PI * h * h), 1e-15);
  EXPECT_NEAR(CubicSpline(h, 3).norm, 3.0 / (2.0 * PI * h * h * h), 1e-15);
}

// value and dW/dr continuous at q = 1 and q = 2 (left and right limits)
TEST(Kernel, ContinuityAtBranchPoints)
{
  for (int dim : {2, 3}) {
    const double h = 1.33e-3;
    const CubicSpline k(h, dim);
    const double t = 1e-10;
    for (double q : {1.0, 2.0}) {
      const double lo = q * h * (1.0 - t), hi = q * h * (1.0 + t);
      EXPECT_NEAR(k.value(lo), k.value(hi), 1e-8 * k.norm) << "W at q=" << q;
      EXPECT_NEAR(k.derivative(lo), k.derivative(hi), 1e-8 * k.norm / h) << "dW/dr at q=" << q;
    }
    // second derivative continuous at q = 1 as well (cubic spline is C2)
    const double e = 1e-4 * h;
    auto d2 = [&](double r) { return (k.derivative(r + e) - k.derivative(r - e)) / (2 * e); };
    EXPECT_NEAR(d2(h - 2 * e), d2(h + 2 * e), 1e-3 * k.norm / (h * h));
  }
}
