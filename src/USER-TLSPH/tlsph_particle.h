/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: per-particle kernels of the TLSPH step (doc/pair_tlsph.rst)

   Called by pair_tlsph.cpp (CPU loop), by the unit tests with plain arrays,
   and meant for Kokkos functors: particle data are read through small
   accessor objects (`rows(j)` returns a pointer to row j), so the same code
   serves LAMMPS's double** arrays, std::vector storage or Kokkos views.
------------------------------------------------------------------------- */

#ifndef TLSPH_PARTICLE_H
#define TLSPH_PARTICLE_H

#include "tlsph_kernel.h"
#include "tlsph_material.h"
#include "tlsph_pair_terms.h"

namespace TLSPH {

// geometric data of one intact bond i -> j (reference configuration)
struct Bond {
  double X[3];    // X_j - X_i
  double w[3];    // V_j grad_i W_ij
  double whg;     // V_j W_ij / |X_ij|^2 (hourglass weight)
  int j;          // index of the partner in the particle arrays
  int k;          // slot of the bond in the owner's bond row
};

// fill the reference data of a bond from X_ij and the partner's volume
TLSPH_INLINE void make_bond(const CubicSpline &kernel, const double *Xij, double Vj, int j, int k,
                            Bond &b)
{
  b.X[0] = Xij[0];
  b.X[1] = Xij[1];
  b.X[2] = Xij[2];
  const double r = std::sqrt(dot3(Xij, Xij));
  double g[3];
  kernel.gradient(Xij, r, g);
  b.w[0] = Vj * g[0];
  b.w[1] = Vj * g[1];
  b.w[2] = Vj * g[2];
  b.whg = Vj * kernel.value(r) / (r * r);
  b.j = j;
  b.k = k;
}

// a correction matrix whose condition number exceeds this is treated as
// singular: the particle has too few partners to define a gradient
constexpr double MAX_CONDITION = 1.0e6;

/* Correction matrix A_i = sum_j w_ij (x) X_ij, so that
   F = I + sum_j (u_j - u_i) (x) A_i^-1 w_ij is exact for affine motion.
   Writes A_i^-1 (zero when A is ill-conditioned: the particle then carries
   no stress of its own but still feels its partners') and s_i = sum_j w_ij.
   Returns false for the ill-conditioned case. */
TLSPH_INLINE bool correction(const Bond *b, int nb, int dim, double *Ainv, double *sumw)
{
  double A[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  sumw[0] = sumw[1] = sumw[2] = 0.0;
  for (int m = 0; m < nb; m++) {
    add_outer(A, b[m].w, b[m].X);
    sumw[0] += b[m].w[0];
    sumw[1] += b[m].w[1];
    sumw[2] += b[m].w[2];
  }
  if (dim == 2) {
    A[2] = A[5] = A[6] = A[7] = 0.0;
    A[8] = 1.0;
  }
  double Ai[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  const double det = mat_inverse(A, Ai);
  const bool ok = nb >= dim && det > 0.0 && mat_norm(A) * mat_norm(Ai) < MAX_CONDITION;
  if (ok) mat_copy(Ai, Ainv);
  else mat_zero(Ainv);
  return ok;
}

/* F_i = I + (sum_j (u_j - u_i) (x) w_ij) A_i^-T, with u = x - X and the
   reference bond vector X_ij taken from the bond. x(j) returns x_j. */
template <int DIM, class Rows>
TLSPH_INLINE void deformation_gradient(const Rows &x, int i, const Bond *b, int nb,
                                       const double *Ainv, double *F)
{
  double G[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  const double *xi = x(i);
  for (int m = 0; m < nb; m++) {
    const double *xj = x(b[m].j);
    double du[3];
    for (int d = 0; d < DIM; d++) du[d] = (xj[d] - xi[d]) - b[m].X[d];
    for (int r = 0; r < DIM; r++)
      for (int c = 0; c < DIM; c++) G[3 * r + c] += du[r] * b[m].w[c];
  }
  double GA[9];
  mat_mult(G, Ainv, GA);    // G A^-T
  mat_identity(F);
  for (int r = 0; r < DIM; r++)
    for (int c = 0; c < DIM; c++) F[3 * r + c] += GA[3 * r + c];
}

/* From F: strain energy density (returned), T = P A^-1 with P = F S, and,
   if H is not null, H = J F^-T A^-1 (viscosity mapping). In 2D plane
   stress F33 is set from E33. *J receives det(F). */
TLSPH_INLINE double stress_tensors(const IsotropicSVK &law, int dim, double *F, const double *Ainv,
                                   double *T, double *H, double *J)
{
  double E[9], S[9], P[9];
  green_lagrange(F, E);
  const double psi = law.stress(E, S);
  if (dim == 2 && law.plane_stress) F[8] = std::sqrt(1.0 + 2.0 * E[8]);
  *J = mat_det(F);
  mat_mul(F, S, P);
  mat_mul(P, Ainv, T);
  if (H) {
    double Finv[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}, FinvT[9];
    mat_inverse(F, Finv);
    mat_transpose(Finv, FinvT);
    mat_mul(FinvT, Ainv, H);
    for (int k = 0; k < 9; k++) H[k] *= *J;
  }
  return psi;
}

// material numbers the force pass needs, per particle type
struct PairMaterial {
  double c0, rho, E;
};

struct NoBondVisitor {
  TLSPH_INLINE void operator()(int, const double *, const double *) const {}
};

/* Force on particle i (added to fs: stress, fv: viscous, fh: hourglass):
     f_i = V_i sum_j [ (T_i + T_j) w_ij - q_ij (H_i + H_j) w_ij / 2 ] + f_i^HG
   Accessors x, v, T, F, H return rows; type(j) the particle type; mat[type]
   the material numbers. visit(j, xij, fij) is called with the total bond
   force on i when VISIT is set (virial tallies). */
template <int DIM, int HG, int VISC, int VISIT, class Rows, class Types, class Visitor>
TLSPH_INLINE void particle_force(int i, double Vi, const Bond *b, int nb, const double *sumw,
                                 const Rows &x, const Rows &v, const Rows &T, const Rows &F,
                                 const Rows &H, const Types &type, const PairMaterial *mat,
                                 double h, double alpha, double beta, double gamma,
                                 double *fs, double *fv, double *fh, const Visitor &visit)
{
  const double *Ti = T(i);
  const double *xi = x(i);
  const int ti = type(i);
  double acc[3] = {0, 0, 0};
  mat_vec(Ti, sumw, acc);
  for (int m = 0; m < nb; m++) {
    const int j = b[m].j;
    const double *w = b[m].w;
    const double *Tj = T(j);
    double fb[3] = {0.0, 0.0, 0.0};
    for (int r = 0; r < DIM; r++) {
      double s = 0.0;
      for (int c = 0; c < DIM; c++) s += Tj[3 * r + c] * w[c];
      acc[r] += s;
      if (VISIT) {
        double si = 0.0;
        for (int c = 0; c < DIM; c++) si += Ti[3 * r + c] * w[c];
        fb[r] = Vi * (s + si);
      }
    }
    const double *xj = x(j);
    double xij[3] = {0.0, 0.0, 0.0};
    for (int d = 0; d < DIM; d++) xij[d] = xj[d] - xi[d];
    if (VISC) {
      const double *vi = v(i), *vj = v(j);
      double dvX = 0.0, X2 = 0.0;
      for (int d = 0; d < DIM; d++) {
        dvX += (vj[d] - vi[d]) * b[m].X[d];
        X2 += b[m].X[d] * b[m].X[d];
      }
      if (dvX < 0.0) {
        const int tj = type(j);
        const double c = 0.5 * (mat[ti].c0 + mat[tj].c0);
        const double rho = 0.5 * (mat[ti].rho + mat[tj].rho);
        const double q = viscous_pressure(dvX, X2, h, alpha, beta, c, rho);
        const double *Hi = H(i), *Hj = H(j);
        for (int r = 0; r < DIM; r++) {
          double s = 0.0;
          for (int c2 = 0; c2 < DIM; c2++) s += (Hi[3 * r + c2] + Hj[3 * r + c2]) * w[c2];
          const double fr = -0.5 * q * Vi * s;
          fv[r] += fr;
          if (VISIT) fb[r] += fr;
        }
      }
    }
    if (HG) {
      const double Ebar = 0.5 * (mat[ti].E + mat[type(j)].E);
      const double coeff = 0.5 * gamma * Ebar * Vi * b[m].whg;
      double fhb[3];
      hourglass_force(F(i), F(j), b[m].X, xij, coeff, fhb);
      for (int d = 0; d < DIM; d++) {
        fh[d] += fhb[d];
        if (VISIT) fb[d] += fhb[d];
      }
    }
    if (VISIT) visit(j, xij, fb);
  }
  for (int d = 0; d < DIM; d++) fs[d] += Vi * acc[d];
}

}    // namespace TLSPH

#endif
