/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: constitutive laws (doc/pair_tlsph.rst, "Material law")

   Isotropic St. Venant-Kirchhoff:  E = (F^T F - I)/2,
   S = lambda tr(E) I + 2 mu E,  P = F S.
   2D plane strain uses the 3D Lame constants with E33 = 0 (the thesis's
   choice); plane stress eliminates E33 from S33 = 0.
------------------------------------------------------------------------- */

#ifndef TLSPH_MATERIAL_H
#define TLSPH_MATERIAL_H

#include "tlsph_math.h"

namespace TLSPH {

TLSPH_INLINE double lame_lambda(double E, double nu)
{
  return E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
}

TLSPH_INLINE double lame_mu(double E, double nu)
{
  return E / (2.0 * (1.0 + nu));
}

// longitudinal (P-wave) speed c0 = sqrt((K + 4 mu/3)/rho) = sqrt((lambda + 2 mu)/rho)
TLSPH_INLINE double wave_speed(double lambda, double mu, double rho)
{
  return std::sqrt((lambda + 2.0 * mu) / rho);
}

// Green-Lagrange strain E = (F^T F - I)/2
TLSPH_INLINE void green_lagrange(const double *F, double *E)
{
  mat_tmul(F, F, E);
  E[0] -= 1.0;
  E[4] -= 1.0;
  E[8] -= 1.0;
  for (int k = 0; k < 9; ++k) E[k] *= 0.5;
}

struct IsotropicSVK {
  double lambda;
  double mu;
  int plane_stress;    // 1: 2D plane stress (S33 = 0), 0: 3D or 2D plane strain

  // Second Piola-Kirchhoff stress S from Green-Lagrange strain E (E33 is
  // overwritten with the plane-stress value when plane_stress is set).
  // Returns the strain energy density psi(E).
  TLSPH_INLINE double stress(double *E, double *S) const
  {
    if (plane_stress) E[8] = -lambda * (E[0] + E[4]) / (lambda + 2.0 * mu);
    const double tr = E[0] + E[4] + E[8];
    for (int k = 0; k < 9; ++k) S[k] = 2.0 * mu * E[k];
    S[0] += lambda * tr;
    S[4] += lambda * tr;
    S[8] += lambda * tr;
    if (plane_stress) S[8] = 0.0;
    double EE = 0.0;
    for (int k = 0; k < 9; ++k) EE += E[k] * E[k];
    return 0.5 * lambda * tr * tr + mu * EE;
  }
};

}    // namespace TLSPH

#endif
