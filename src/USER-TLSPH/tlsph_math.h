/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: Total Lagrangian SPH for solid mechanics (LAMMPS plugin)

   Small fixed-size tensor algebra used by the physics headers.
   Tensors are row-major double[9] (T[3*r+c]), vectors double[3].
   Nothing here includes LAMMPS, allocates, or does I/O, so every function
   can be called from a unit test or (with Kokkos) from device code.
------------------------------------------------------------------------- */

#ifndef TLSPH_MATH_H
#define TLSPH_MATH_H

#include <cmath>

#if defined(TLSPH_KOKKOS)
// the /kk styles: host and device functions (whatever was included before)
#include <Kokkos_Macros.hpp>
#define TLSPH_INLINE KOKKOS_INLINE_FUNCTION
#define TLSPH_FORCE_INLINE KOKKOS_FORCEINLINE_FUNCTION
#else
#define TLSPH_INLINE inline
// per-particle kernels of the step that GCC would otherwise call out of line
#if defined(__GNUC__)
#define TLSPH_FORCE_INLINE inline __attribute__((always_inline))
#else
#define TLSPH_FORCE_INLINE inline
#endif
#endif

namespace TLSPH {

TLSPH_INLINE void mat_identity(double *A)
{
  A[0] = 1.0; A[1] = 0.0; A[2] = 0.0;
  A[3] = 0.0; A[4] = 1.0; A[5] = 0.0;
  A[6] = 0.0; A[7] = 0.0; A[8] = 1.0;
}

TLSPH_INLINE void mat_zero(double *A)
{
  for (int k = 0; k < 9; ++k) A[k] = 0.0;
}

TLSPH_INLINE void mat_copy(const double *A, double *B)
{
  for (int k = 0; k < 9; ++k) B[k] = A[k];
}

// C = A B
// (mat_mul, mat_tmul, mat_det: templates on the scalar type, so that the
// SIMD step, tlsph_ell_vec.h, runs the same code on vectors)
template <class T> TLSPH_FORCE_INLINE void mat_mul(const T *A, const T *B, T *C)
{
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      C[3 * r + c] = A[3 * r] * B[c] + A[3 * r + 1] * B[3 + c] + A[3 * r + 2] * B[6 + c];
}

// C = A^T B
template <class T> TLSPH_FORCE_INLINE void mat_tmul(const T *A, const T *B, T *C)
{
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      C[3 * r + c] = A[r] * B[c] + A[3 + r] * B[3 + c] + A[6 + r] * B[6 + c];
}

// C = A B^T
TLSPH_INLINE void mat_mult(const double *A, const double *B, double *C)
{
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      C[3 * r + c] = A[3 * r] * B[3 * c] + A[3 * r + 1] * B[3 * c + 1] + A[3 * r + 2] * B[3 * c + 2];
}

TLSPH_INLINE void mat_transpose(const double *A, double *B)
{
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) B[3 * c + r] = A[3 * r + c];
}

// y = A x
TLSPH_INLINE void mat_vec(const double *A, const double *x, double *y)
{
  y[0] = A[0] * x[0] + A[1] * x[1] + A[2] * x[2];
  y[1] = A[3] * x[0] + A[4] * x[1] + A[5] * x[2];
  y[2] = A[6] * x[0] + A[7] * x[1] + A[8] * x[2];
}

template <class T> TLSPH_FORCE_INLINE T mat_det(const T *A)
{
  return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
      A[2] * (A[3] * A[7] - A[4] * A[6]);
}

TLSPH_INLINE double mat_trace(const double *A)
{
  return A[0] + A[4] + A[8];
}

// Frobenius norm
TLSPH_INLINE double mat_norm(const double *A)
{
  double s = 0.0;
  for (int k = 0; k < 9; ++k) s += A[k] * A[k];
  return std::sqrt(s);
}

// B = A^{-1}; returns det(A). B is left untouched when det(A) == 0.
/* B = A^-1 from the cofactors, without a test of det(A) (returned): a
   template on the scalar type (the SIMD step runs it on vectors, where a
   lane with det = 0 stops the run) */
template <class T> TLSPH_FORCE_INLINE T mat_inverse_unchecked(const T *A, T *B)
{
  const T c00 = A[4] * A[8] - A[5] * A[7];
  const T c01 = A[5] * A[6] - A[3] * A[8];
  const T c02 = A[3] * A[7] - A[4] * A[6];
  const T det = A[0] * c00 + A[1] * c01 + A[2] * c02;
  const T s = 1.0 / det;
  B[0] = c00 * s;
  B[1] = (A[2] * A[7] - A[1] * A[8]) * s;
  B[2] = (A[1] * A[5] - A[2] * A[4]) * s;
  B[3] = c01 * s;
  B[4] = (A[0] * A[8] - A[2] * A[6]) * s;
  B[5] = (A[2] * A[3] - A[0] * A[5]) * s;
  B[6] = c02 * s;
  B[7] = (A[1] * A[6] - A[0] * A[7]) * s;
  B[8] = (A[0] * A[4] - A[1] * A[3]) * s;
  return det;
}

// B = A^-1; returns det(A), and leaves B as it was when det(A) = 0
TLSPH_INLINE double mat_inverse(const double *A, double *B)
{
  const double det = A[0] * (A[4] * A[8] - A[5] * A[7]) + A[1] * (A[5] * A[6] - A[3] * A[8]) +
      A[2] * (A[3] * A[7] - A[4] * A[6]);
  if (det == 0.0) return det;
  return mat_inverse_unchecked(A, B);
}

TLSPH_INLINE double dot3(const double *a, const double *b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// A += a (x) b, i.e. A_kl += a_k b_l
TLSPH_INLINE void add_outer(double *A, const double *a, const double *b)
{
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) A[3 * r + c] += a[r] * b[c];
}

/* In-place Gauss-Jordan inversion of a small dense n x n matrix (n <= 9),
   row-major, with partial pivoting. M is destroyed; Minv receives the
   inverse. Returns false if a pivot vanishes. */
TLSPH_INLINE bool invert_small(int n, double *M, double *Minv)
{
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) Minv[n * r + c] = (r == c) ? 1.0 : 0.0;
  for (int col = 0; col < n; ++col) {
    int piv = col;
    double best = std::fabs(M[n * col + col]);
    for (int r = col + 1; r < n; ++r)
      if (std::fabs(M[n * r + col]) > best) best = std::fabs(M[n * r + col]), piv = r;
    if (best == 0.0) return false;
    if (piv != col)
      for (int c = 0; c < n; ++c) {
        double t = M[n * col + c];
        M[n * col + c] = M[n * piv + c];
        M[n * piv + c] = t;
        t = Minv[n * col + c];
        Minv[n * col + c] = Minv[n * piv + c];
        Minv[n * piv + c] = t;
      }
    const double s = 1.0 / M[n * col + col];
    for (int c = 0; c < n; ++c) {
      M[n * col + c] *= s;
      Minv[n * col + c] *= s;
    }
    for (int r = 0; r < n; ++r) {
      if (r == col) continue;
      const double f = M[n * r + col];
      if (f == 0.0) continue;
      for (int c = 0; c < n; ++c) {
        M[n * r + c] -= f * M[n * col + c];
        Minv[n * r + c] -= f * Minv[n * col + c];
      }
    }
  }
  return true;
}

}    // namespace TLSPH

#endif
