/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: cubic-spline kernel (doc/pair_tlsph.rst, Eq. K1)

   W(q) = a_d * { 2/3 - q^2 + q^3/2        0 <= q < 1
                { (2 - q)^3 / 6            1 <= q < 2
                { 0                        q >= 2,      q = r/h
   a_d = 15/(7 pi h^2) in 2D, 3/(2 pi h^3) in 3D; support radius 2h.
------------------------------------------------------------------------- */

#ifndef TLSPH_KERNEL_H
#define TLSPH_KERNEL_H

#include "tlsph_math.h"

namespace TLSPH {

struct CubicSpline {
  double h;       // smoothing length
  double norm;    // a_d
  double inv_h;

  CubicSpline() : h(0.0), norm(0.0), inv_h(0.0) {}
  CubicSpline(double h_, int dim) : h(h_), inv_h(1.0 / h_)
  {
    const double pi = 3.14159265358979323846;
    norm = (dim == 2) ? 15.0 / (7.0 * pi * h * h) : 3.0 / (2.0 * pi * h * h * h);
  }

  TLSPH_INLINE double support() const { return 2.0 * h; }

  TLSPH_INLINE double value(double r) const
  {
    const double q = r * inv_h;
    if (q < 1.0) return norm * (2.0 / 3.0 - q * q + 0.5 * q * q * q);
    if (q < 2.0) {
      const double t = 2.0 - q;
      return norm * t * t * t / 6.0;
    }
    return 0.0;
  }

  // dW/dr
  TLSPH_INLINE double derivative(double r) const
  {
    const double q = r * inv_h;
    if (q < 1.0) return norm * inv_h * (-2.0 * q + 1.5 * q * q);
    if (q < 2.0) {
      const double t = 2.0 - q;
      return -0.5 * norm * inv_h * t * t;
    }
    return 0.0;
  }

  // grad_i W(|X_i - X_j|) for the bond vector Xij = X_j - X_i, r = |Xij| > 0.
  // It points from i towards j (dW/dr < 0).
  TLSPH_INLINE void gradient(const double *Xij, double r, double *g) const
  {
    const double s = -derivative(r) / r;
    g[0] = s * Xij[0];
    g[1] = s * Xij[1];
    g[2] = s * Xij[2];
  }
};

}    // namespace TLSPH

#endif
