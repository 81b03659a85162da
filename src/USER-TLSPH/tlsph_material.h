/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: constitutive laws (doc/pair_tlsph.rst, "Material law")

   Isotropic St. Venant-Kirchhoff:  E = (F^T F - I)/2,
   S = lambda tr(E) I + 2 mu E,  P = F S.
   2D plane strain uses the 3D Lame constants with E33 = 0 (the thesis's
   choice); plane stress eliminates E33 from S33 = 0.

   Orthotropic St. Venant-Kirchhoff (a laminate ply, doc: "Orthotropic
   materials"): the same E and P = F S, with S = C(theta) : E, where C is
   the exact inverse of the orthotropic compliance in the material axes
   (1 = fibre), rotated by the ply angle theta about the global z axis.
   Voigt order 11 22 33 23 13 12, engineering shear strains (2 E_ij).
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
template <class T> TLSPH_FORCE_INLINE void green_lagrange(const T *F, T *E)
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
  // (a template on the scalar type: the SIMD step runs it on vectors)
  template <class T> TLSPH_FORCE_INLINE T stress(T *E, T *S) const
  {
    if (plane_stress) E[8] = -lambda * (E[0] + E[4]) / (lambda + 2.0 * mu);
    const T tr = E[0] + E[4] + E[8];
    for (int k = 0; k < 9; ++k) S[k] = 2.0 * mu * E[k];
    S[0] += lambda * tr;
    S[4] += lambda * tr;
    S[8] += lambda * tr;
    if (plane_stress) S[8] = T{};
    T EE = T{};
    for (int k = 0; k < 9; ++k) EE += E[k] * E[k];
    return 0.5 * lambda * tr * tr + mu * EE;
  }
};

/* ----------------------------------------------------------------------
   Orthotropic materials
------------------------------------------------------------------------- */

// Voigt index pairs: I -> (VOIGT_I[I], VOIGT_J[I]), order 11 22 33 23 13 12
constexpr int VOIGT_I[6] = {0, 1, 2, 1, 0, 0};
constexpr int VOIGT_J[6] = {0, 1, 2, 2, 2, 1};

// engineering constants in the material axes (1 = fibre, 3 = laminate normal);
// nu_ij = -eps_j / eps_i under uniaxial stress along i, so nu_ji = nu_ij E_j / E_i
struct OrthotropicConstants {
  double E1, E2, E3, G12, G13, G23, nu12, nu13, nu23;
};

/* 1 - nu12 nu21 - nu23 nu32 - nu31 nu13 - 2 nu21 nu32 nu13 (thesis Eq. 2.44):
   E1 E2 E3 times the determinant of the normal block of the compliance. With
   positive moduli and |nu_ij| < sqrt(E_i/E_j) the compliance is positive
   definite exactly when this is > 0. */
TLSPH_INLINE double orthotropic_delta(const OrthotropicConstants &k)
{
  const double nu21 = k.nu12 * k.E2 / k.E1, nu31 = k.nu13 * k.E3 / k.E1;
  const double nu32 = k.nu23 * k.E3 / k.E2;
  return 1.0 - k.nu12 * nu21 - k.nu23 * nu32 - nu31 * k.nu13 - 2.0 * nu21 * nu32 * k.nu13;
}

// 6x6 compliance in the material axes, row-major (e = S s, engineering shear)
TLSPH_INLINE void orthotropic_compliance(const OrthotropicConstants &k, double *S)
{
  for (int a = 0; a < 36; a++) S[a] = 0.0;
  S[0] = 1.0 / k.E1;
  S[7] = 1.0 / k.E2;
  S[14] = 1.0 / k.E3;
  S[1] = S[6] = -k.nu12 / k.E1;
  S[2] = S[12] = -k.nu13 / k.E1;
  S[8] = S[13] = -k.nu23 / k.E2;
  S[21] = 1.0 / k.G23;
  S[28] = 1.0 / k.G13;
  S[35] = 1.0 / k.G12;
}

/* Stiffness in the material axes: the inverse of the compliance, computed
   from it (the normal 3x3 block inverted, the shear terms G_ij) rather than
   from closed-form Q_ij, which the thesis prints with slips (Eq. 2.43).
   Returns false if the normal block is singular. */
TLSPH_INLINE bool orthotropic_stiffness_local(const OrthotropicConstants &k, double *C)
{
  double S[36], Sn[9], Cn[9];
  orthotropic_compliance(k, S);
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) Sn[3 * a + b] = S[6 * a + b];
  const double det = mat_inverse(Sn, Cn);
  if (!(det != 0.0) || !std::isfinite(det)) return false;
  for (int a = 0; a < 36; a++) C[a] = 0.0;
  for (int a = 0; a < 3; a++)
    for (int b = 0; b < 3; b++) C[6 * a + b] = 0.5 * (Cn[3 * a + b] + Cn[3 * b + a]);
  C[21] = k.G23;
  C[28] = k.G13;
  C[35] = k.G12;
  return true;
}

/* Voigt stiffness in rotated axes: C' = M C M^T, with M the stress
   transformation (Bond) matrix of the rotation R (R_ia: global component i
   of material axis a), s' = M s. Equivalent to C'_ijkl = R_ia R_jb R_kc R_ld
   C_abcd with engineering shear strains; the unit test checks it against
   that tensor rotation. */
TLSPH_INLINE void rotate_stiffness(const double *C, const double *R, double *Cr)
{
  double M[36], MC[36];
  for (int I = 0; I < 6; I++) {
    const int i = VOIGT_I[I], j = VOIGT_J[I];
    for (int J = 0; J < 6; J++) {
      const int a = VOIGT_I[J], b = VOIGT_J[J];
      M[6 * I + J] = (a == b) ? R[3 * i + a] * R[3 * j + a]
                              : R[3 * i + a] * R[3 * j + b] + R[3 * i + b] * R[3 * j + a];
    }
  }
  for (int I = 0; I < 6; I++)
    for (int J = 0; J < 6; J++) {
      double acc = 0.0;
      for (int K = 0; K < 6; K++) acc += M[6 * I + K] * C[6 * K + J];
      MC[6 * I + J] = acc;
    }
  for (int I = 0; I < 6; I++)
    for (int J = 0; J < 6; J++) {
      double acc = 0.0;
      for (int K = 0; K < 6; K++) acc += MC[6 * I + K] * M[6 * J + K];
      Cr[6 * I + J] = acc;
    }
  // exactly symmetric, as the strain energy needs
  for (int I = 0; I < 6; I++)
    for (int J = I + 1; J < 6; J++)
      Cr[6 * I + J] = Cr[6 * J + I] = 0.5 * (Cr[6 * I + J] + Cr[6 * J + I]);
}

/* rotation by theta (radians) about the global z axis: material axis 1 (the
   fibre) points along (cos theta, sin theta, 0) */
TLSPH_INLINE void rotation_z(double theta, double *R)
{
  const double c = std::cos(theta), s = std::sin(theta);
  R[0] = c;
  R[1] = -s;
  R[2] = 0.0;
  R[3] = s;
  R[4] = c;
  R[5] = 0.0;
  R[6] = 0.0;
  R[7] = 0.0;
  R[8] = 1.0;
}

/* Largest eigenvalue of the acoustic tensor A_ik(n) = C_ijkl n_j n_l over
   all directions n: rho c^2 of the fastest plane wave (quasi-longitudinal).
   Invariant under rotations of C. A 25 x 96 grid of the half sphere (the
   coordinate axes included), then ten refinements around the best
   direction (to an angle of 1e-7 rad); isotropic: exactly lambda + 2 mu. */
namespace detail {
TLSPH_INLINE double acoustic_max(const double *C, double a, double b)
{
  const double n[3] = {std::sin(a) * std::cos(b), std::sin(a) * std::sin(b), std::cos(a)};
  // Voigt index of the pair (i, j)
  const int v[9] = {0, 5, 4, 5, 1, 3, 4, 3, 2};
  double A[9];
  for (int i = 0; i < 3; i++)
    for (int k = 0; k < 3; k++) {
      double acc = 0.0;
      for (int j = 0; j < 3; j++)
        for (int l = 0; l < 3; l++) acc += C[6 * v[3 * i + j] + v[3 * k + l]] * n[j] * n[l];
      A[3 * i + k] = acc;
    }
  // largest eigenvalue of a symmetric 3x3 (trigonometric form)
  const double p1 = A[1] * A[1] + A[2] * A[2] + A[5] * A[5];
  const double q = (A[0] + A[4] + A[8]) / 3.0;
  const double p2 =
      (A[0] - q) * (A[0] - q) + (A[4] - q) * (A[4] - q) + (A[8] - q) * (A[8] - q) + 2.0 * p1;
  const double p = std::sqrt(p2 / 6.0);
  if (!(p > 1.0e-14 * std::fabs(q))) return q;
  double B[9];
  for (int k = 0; k < 9; k++) B[k] = A[k] / p;
  B[0] -= q / p;
  B[4] -= q / p;
  B[8] -= q / p;
  double r = 0.5 * mat_det(B);
  r = r < -1.0 ? -1.0 : (r > 1.0 ? 1.0 : r);
  return q + 2.0 * p * std::cos(std::acos(r) / 3.0);
}
}    // namespace detail

TLSPH_INLINE double max_acoustic_modulus(const double *C)
{
  const double pi = 3.14159265358979323846;
  const int na = 24, nb = 96;
  double best = 0.0, ba = 0.0, bb = 0.0;
  for (int i = 0; i <= na; i++)
    for (int j = 0; j < nb; j++) {
      const double a = 0.5 * pi * i / na, b = 2.0 * pi * j / nb;
      const double m = detail::acoustic_max(C, a, b);
      if (m > best) best = m, ba = a, bb = b;
    }
  double da = 0.5 * pi / na, db = 2.0 * pi / nb;
  for (int level = 0; level < 10; level++) {
    const double a0 = ba, b0 = bb;
    for (int i = -4; i <= 4; i++)
      for (int j = -4; j <= 4; j++) {
        const double a = a0 + 0.25 * da * i, b = b0 + 0.25 * db * j;
        const double m = detail::acoustic_max(C, a, b);
        if (m > best) best = m, ba = a, bb = b;
      }
    da *= 0.25;
    db *= 0.25;
  }
  return best;
}

/* Voigt-average Young's modulus (rotation invariant; E itself for an
   isotropic C): K_V = (C11 + C22 + C33 + 2 (C12 + C13 + C23)) / 9,
   G_V = (C11 + C22 + C33 - (C12 + C13 + C23) + 3 (C44 + C55 + C66)) / 15,
   E_V = 9 K_V G_V / (3 K_V + G_V) */
TLSPH_INLINE double voigt_young_modulus(const double *C)
{
  const double d = C[0] + C[7] + C[14], o = C[1] + C[2] + C[8], s = C[21] + C[28] + C[35];
  const double K = (d + 2.0 * o) / 9.0, G = (d - o + 3.0 * s) / 15.0;
  return 9.0 * K * G / (3.0 * K + G);
}

struct OrthotropicSVK {
  double C[36];        // stiffness in global axes, Voigt 11 22 33 23 13 12, row-major
  int plane_stress;    // 1: 2D plane stress (S33 = 0), 0: 3D or 2D plane strain

  /* S = C : E with engineering shear strains (2 E_ij), psi = E : C : E / 2.
     2D plane stress: a rotation about z leaves C34 = C35 = 0 and the 2D E
     has E13 = E23 = 0, so S33 = 0 gives E33 = -(C31 E11 + C32 E22 +
     C36 2 E12) / C33 (written into E) and S13 = S23 = 0 hold already. */
  TLSPH_INLINE double stress(double *E, double *S) const
  {
    double e[6] = {E[0], E[4], E[8], 2.0 * E[5], 2.0 * E[2], 2.0 * E[1]};
    if (plane_stress) {
      e[2] = -(C[12] * e[0] + C[13] * e[1] + C[17] * e[5]) / C[14];
      E[8] = e[2];
    }
    double s[6];
    double psi2 = 0.0;
    for (int a = 0; a < 6; a++) {
      double acc = 0.0;
      for (int b = 0; b < 6; b++) acc += C[6 * a + b] * e[b];
      s[a] = acc;
      psi2 += acc * e[a];
    }
    if (plane_stress) s[2] = 0.0;
    S[0] = s[0];
    S[4] = s[1];
    S[8] = s[2];
    S[5] = S[7] = s[3];
    S[2] = S[6] = s[4];
    S[1] = S[3] = s[5];
    return 0.5 * psi2;
  }
};

/* rotation_z for an angle in degrees, with exact cosines and sines at the
   multiples of 90 degrees (a 90-degree ply then has C16 = C26 = 0 exactly) */
TLSPH_INLINE void rotation_z_degrees(double deg, double *R)
{
  double r = std::fmod(deg, 360.0);
  if (r < 0.0) r += 360.0;
  const double pi = 3.14159265358979323846;
  rotation_z(r * pi / 180.0, R);
  const double quarter = r / 90.0;
  if (quarter == std::floor(quarter)) {
    const int q = static_cast<int>(quarter) % 4;
    const double c = (q == 0) ? 1.0 : (q == 2 ? -1.0 : 0.0);
    const double s = (q == 1) ? 1.0 : (q == 3 ? -1.0 : 0.0);
    R[0] = c;
    R[1] = -s;
    R[3] = s;
    R[4] = c;
  }
}

/* The law of a ply: constants in material axes and the fibre angle theta
   (degrees, about +z from the global x axis). Returns false if the
   compliance cannot be inverted (the caller validates the constants). */
TLSPH_INLINE bool make_orthotropic(const OrthotropicConstants &k, double theta_deg,
                                   int plane_stress, OrthotropicSVK &law)
{
  double Cl[36], R[9];
  if (!orthotropic_stiffness_local(k, Cl)) return false;
  rotation_z_degrees(theta_deg, R);
  rotate_stiffness(Cl, R, law.C);
  law.plane_stress = plane_stress;
  return true;
}

}    // namespace TLSPH

#endif
