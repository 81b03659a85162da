/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: pair terms of the momentum equation (doc/pair_tlsph.rst)

   All functions take the bond from particle i to partner j, with
   Xij = X_j - X_i (reference) and xij = x_j - x_i (current).
------------------------------------------------------------------------- */

#ifndef TLSPH_PAIR_TERMS_H
#define TLSPH_PAIR_TERMS_H

#include "tlsph_math.h"

namespace TLSPH {

/* Hourglass control (Ganzenmueller 2015).  Error vectors
   eps_ij = F_i Xij - xij, eps_ji = F_j Xji - xji, their projections on the
   current bond delta = eps . xhat, and the force on i
     f_i = -coeff (delta_ij + delta_ji) xij/|xij|,
   coeff = gamma Ebar V_i V_j W_ij / (2 |Xij|^2).
   It vanishes for every homogeneous deformation (F_i = F_j = F, xij = F Xij)
   and is restoring for gamma > 0.  The force on j is -f_i. */
TLSPH_INLINE void hourglass_force(const double *Fi, const double *Fj, const double *Xij,
                                  const double *xij, double coeff, double *fi)
{
  double a[3], b[3];
  mat_vec(Fi, Xij, a);
  mat_vec(Fj, Xij, b);
  const double r2 = dot3(xij, xij);
  if (r2 <= 0.0) {
    fi[0] = fi[1] = fi[2] = 0.0;
    return;
  }
  // (delta_ij + delta_ji) = ((F_i + F_j) Xij - 2 xij) . xij / |xij|
  double e[3] = {a[0] + b[0] - 2.0 * xij[0], a[1] + b[1] - 2.0 * xij[1],
                 a[2] + b[2] - 2.0 * xij[2]};
  // f_i = -coeff * (e.xij/|xij|) * xij/|xij| = -coeff * (e.xij) xij / r2
  const double s = -coeff * dot3(e, xij) / r2;
  fi[0] = s * xij[0];
  fi[1] = s * xij[1];
  fi[2] = s * xij[2];
}

/* Monaghan artificial viscosity (thesis Eq. 2.17-2.18) returned as a
   pressure q_ij = rho (-alpha c mu_ij + beta mu_ij^2) >= 0, with
   mu_ij = h dvX / (r2 + 0.01 h^2) when the pair approaches (dvX < 0), else 0.
   dvX = (v_j - v_i).d and r2 = |d|^2 for the separation d; particle_force()
   uses the current separation x_ij (objective), the thesis the reference X_ij. */
TLSPH_INLINE double viscous_pressure(double dvX, double X2, double h, double alpha, double beta,
                                     double c, double rho)
{
  if (dvX >= 0.0) return 0.0;
  const double mu = h * dvX / (X2 + 0.01 * h * h);
  return rho * (-alpha * c * mu + beta * mu * mu);
}

/* Critical bond stretch from the fracture energy (thesis Eq. 2.28, horizon
   delta; K = lambda + 2 mu/3 is the bulk modulus). */
TLSPH_INLINE double critical_stretch(double G_c, double mu, double K, double delta, int dim)
{
  const double pi = 3.14159265358979323846;
  if (dim == 3) return std::sqrt(G_c / ((3.0 * mu + 0.31640625 * (K - 5.0 * mu / 3.0)) * delta));
  return std::sqrt(G_c / ((6.0 * mu / pi + 16.0 / (9.0 * pi * pi) * (K - 2.0 * mu)) * delta));
}

/* Viscosity coefficient of a particle from its smoothed damage phi'
   (pair tlsph/damage): thesis Eq. 2.35, alpha_d wherever phi' > 0 (step);
   'damping linear': alpha + (alpha_d - alpha) min(phi', 1). */
TLSPH_INLINE double damaged_alpha(double phis, double alpha, double alpha_d, int linear)
{
  if (linear) return alpha + (alpha_d - alpha) * (phis < 1.0 ? phis : 1.0);
  return (phis > 0.0) ? alpha_d : alpha;
}

}    // namespace TLSPH

#endif
