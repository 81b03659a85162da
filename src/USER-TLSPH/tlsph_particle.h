/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: per-particle kernels of the TLSPH step (doc/pair_tlsph.rst)

   Called by pair_tlsph.cpp (CPU loop), by the unit tests with plain arrays,
   and meant for Kokkos functors: particle data are read through small
   accessor objects (`rows(j)` returns a pointer to row j), so the same code
   serves LAMMPS's double** arrays, std::vector storage or Kokkos views.

   Corrected gradient, in one form for both orders (doc: "Corrected
   gradient"):  g_ij = V_j w_ij Q_i p(X_ij / h),
     Q_i = first DIM rows of  M_i^-1 / h,   M_i = sum_j V_j w_ij p p^T,
   with, for ORDER 1 (the thesis), p(s) = s and w = -W'(r)/r, which is
   exactly A_i^-1 grad_i W_ij; and for ORDER 2, p(s) = (s, quadratic
   monomials of s) and w = W(r) (moving least squares), which reproduces
   the gradient of every quadratic field, also at free surfaces.
   F_i = I + sum_j (u_j - u_i) (x) g_ij, and the variationally consistent
   force is f_i = V_i P_i sum_j g_ij - sum_j V_j P_j g_ji.
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
  double g[3];    // corrected gradient g_ij (includes V_j)
  double c;       // V_i w_ij: weight of the reverse gradient g_ji = c Q_j p(-X_ij/h)
  double wv;      // V_j (-W'(r)/r): V_j grad_i W_ij = wv X_ij (uncorrected, viscosity)
  double whg;     // V_j W_ij / |X_ij|^2 (hourglass weight)
  int j;          // index of the partner in the particle arrays
  int k;          // slot of the bond in the owner's bond row
};

/* Bond accessors. The step reads a particle's bonds through one of these,
   so that one copy of the math serves two layouts:
     BondRecords  the full record above (set-up, corrections, unit tests);
     LeanBonds    the step's layout (PairTLSPH): per bond only the partner
                  index, g_ij and the two kernel weights of the viscous and
                  hourglass terms, each in its own array (structure of
                  arrays, CSR over the particles: one Kokkos view each).
                  X_ij is not stored: it is X0_j - X0_i from the reference
                  positions X0 of the particles (made consistent with the
                  periodic images by the caller); the reverse weight
                  c = V_i w_ij, read only without Newton's third law, is
                  recomputed from |X_ij|.
   Interface: partner(m), grad(m) (DIM values), ref(m, X) (DIM values),
   wv(m), whg(m), reverse_weight(m). */
struct BondRecords {
  const Bond *b;
  TLSPH_INLINE int partner(int m) const { return b[m].j; }
  TLSPH_INLINE const double *grad(int m) const { return b[m].g; }
  template <int DIM> TLSPH_INLINE void ref(int m, double *X) const
  {
    for (int d = 0; d < DIM; d++) X[d] = b[m].X[d];
  }
  TLSPH_INLINE double wv(int m) const { return b[m].wv; }
  TLSPH_INLINE double whg(int m) const { return b[m].whg; }
  TLSPH_INLINE double reverse_weight(int m) const { return b[m].c; }
};

// the lean layout's per-bond arrays (counts: 1, DIM, 2 and 1 per bond)
struct LeanArrays {
  int *j;        // partner index in the particle arrays
  double *g;     // corrected gradient g_ij (DIM per bond)
  double *w;     // wv, whg (2 per bond; see Bond)
  int *k;        // slot of the bond in the owner's row of the bond fix
};

template <int DIM, class Rows> struct LeanBonds {
  const int *j;
  const double *g;
  const double *w;
  Rows X0;                    // reference positions, X0(j) = X0_j
  const double *X0i;          // X0_i
  // for reverse_weight() only (gather form of the stress term)
  CubicSpline kernel;
  double Vi;
  int order;
  // bond m of this particle is record m * stride of j, g, w: 1 for rows (a
  // particle's bonds one after another), C for the sliced layout of the /kk
  // styles on a GPU (the bonds of C consecutive particles interleaved slot by
  // slot, so that the C threads of a warp read adjacent records)
  int stride = 1;
  TLSPH_INLINE long slot(int m) const { return (long) m * stride; }
  TLSPH_INLINE int partner(int m) const { return j[slot(m)]; }
  TLSPH_INLINE const double *grad(int m) const { return g + DIM * slot(m); }
  template <int D> TLSPH_INLINE void ref(int m, double *X) const
  {
    const double *xj = X0(j[slot(m)]);
    for (int d = 0; d < D; d++) X[d] = xj[d] - X0i[d];
  }
  TLSPH_INLINE double wv(int m) const { return w[2 * slot(m)]; }
  TLSPH_INLINE double whg(int m) const { return w[2 * slot(m) + 1]; }
  TLSPH_INLINE double reverse_weight(int m) const
  {
    double X[3] = {0.0, 0.0, 0.0};
    ref<DIM>(m, X);
    const double r = std::sqrt(dot3(X, X));
    return Vi * (order == 1 ? -kernel.derivative(r) / r : kernel.value(r));
  }
};

/* Accessors of particle data for the kernels below, usable on a device:
   rows j of a contiguous per-atom block (memory->create's double** arrays,
   Kokkos LayoutRight views), the type of particle j, and the virial tally. */
struct StridedRows {
  const double *base;
  int stride;
  TLSPH_INLINE const double *operator()(int j) const { return base + (long) stride * j; }
};
/* The same rows stored column by column (value k of row j at base[k stride
   + j]): the /kk force kernel's packed rows on a GPU, where the threads of a
   warp read value k of their partners j, nearby indices, from nearby
   addresses instead of one row each (TLSPH_KK_PK_COLUMNS). A row is read by
   index only. */
struct ColumnRows {
  const double *base;
  long stride;
  struct Row {
    const double *p;
    long s;
    TLSPH_INLINE double operator[](int k) const { return p[k * s]; }
  };
  TLSPH_INLINE Row operator()(int j) const { return Row{base + j, stride}; }
};
struct TypeArray {
  const int *t;
  TLSPH_INLINE int operator()(int j) const { return t[j]; }
};
// every bond is visited from both ends: half of r_ij (x) f_ij each time
struct VirialTally {
  double *virial;
  TLSPH_INLINE void operator()(int, const double *xij, const double *f) const
  {
    virial[0] -= 0.5 * xij[0] * f[0];
    virial[1] -= 0.5 * xij[1] * f[1];
    virial[2] -= 0.5 * xij[2] * f[2];
    virial[3] -= 0.5 * xij[0] * f[1];
    virial[4] -= 0.5 * xij[0] * f[2];
    virial[5] -= 0.5 * xij[1] * f[2];
  }
};

/* A particle's bond segment in the lean layout (arrays j, g (DIM per bond),
   w (2 per bond), k), intact bonds first, the first nlead of them leading
   their pair (pair_tlsph.h): drop_bond() moves bond m behind the intact ones
   (where a policy may keep it for the correction) and keeps the leading
   bonds first; the bond moved into slot m is the next to examine. Used by
   tlsph/damage on the CPU, in the tlsph/damage/kk kernel and in the host
   replay of the kernel's breaks, so that all three leave the same order. */
template <int DIM>
TLSPH_INLINE void swap_bond(int *j, double *g, double *w, int *k, int a, int b, int S = 1)
{
  a *= S, b *= S;    // records a S and b S (LeanBonds::stride)
  const int tj = j[a], tk = k[a];
  j[a] = j[b], j[b] = tj;
  k[a] = k[b], k[b] = tk;
  for (int d = 0; d < DIM; d++) {
    const double t = g[DIM * a + d];
    g[DIM * a + d] = g[DIM * b + d], g[DIM * b + d] = t;
  }
  for (int d = 0; d < 2; d++) {
    const double t = w[2 * a + d];
    w[2 * a + d] = w[2 * b + d], w[2 * b + d] = t;
  }
}

template <int DIM>
TLSPH_INLINE void drop_bond(int *j, double *g, double *w, int *k, int m, int &nlead, int &n,
                           int S = 1)
{
  if (m < nlead) {
    swap_bond<DIM>(j, g, w, k, m, nlead - 1, S);
    swap_bond<DIM>(j, g, w, k, nlead - 1, n - 1, S);
    nlead--;
  } else {
    swap_bond<DIM>(j, g, w, k, m, n - 1, S);
  }
  n--;
}

/* The stretch criterion of tlsph/damage for bond i-j, from the current and
   reference positions: writes du = (x_j - x_i) - (X_j - X_i) (DIM values,
   what F needs) and returns true when the stretch s = (r - r0)/r0 reaches
   s_c (ABS: |s| >= s_c). s >= s_c <=> r^2 >= r0^2 (1 + s_c)^2 (and, with
   the absolute criterion, s <= -s_c <=> r^2 <= r0^2 (1 - s_c)^2): a cheap
   filter without square roots against lim_up = (1 + s_c)^2 (1 - 1e-10) and
   lim_down = (1 - s_c)^2 (1 + 1e-10); only bonds within round-off of the
   limit or beyond it are decided with the stretch itself. s_c: the smaller
   critical stretch of the two particles' materials. (CPU pass and Kokkos
   kernel of tlsph/damage.) */
template <int DIM, int ABS>
TLSPH_INLINE bool bond_breaks(const double *xi, const double *xj, const double *x0i,
                              const double *x0j, double lim_up, double lim_down, double s_c,
                              double *du)
{
  double r2 = 0.0, r02 = 0.0;
  for (int d = 0; d < DIM; d++) {
    const double dx = xj[d] - xi[d];
    const double X = x0j[d] - x0i[d];
    du[d] = dx - X;
    r2 += dx * dx;
    r02 += X * X;
  }
  bool suspect = r2 >= r02 * lim_up;
  if (ABS) suspect = suspect || r2 <= r02 * lim_down;
  if (!suspect) return false;
  const double r0 = std::sqrt(r02);
  double st = (std::sqrt(r2) - r0) / r0;
  if (ABS) st = std::fabs(st);
  return st >= s_c;
}

// the polynomial basis of the corrected gradient
template <int DIM, int ORDER> struct Basis {
  static constexpr int size = (ORDER == 1) ? DIM : (DIM == 2 ? 5 : 9);
  template <class T> TLSPH_FORCE_INLINE static void eval(const T *s, T *p)
  {
    for (int d = 0; d < DIM; d++) p[d] = s[d];
    if (ORDER == 2) {
      if (DIM == 2) {
        p[2] = s[0] * s[0];
        p[3] = s[0] * s[1];
        p[4] = s[1] * s[1];
      } else {
        p[3] = s[0] * s[0];
        p[4] = s[1] * s[1];
        p[5] = s[2] * s[2];
        p[6] = s[0] * s[1];
        p[7] = s[0] * s[2];
        p[8] = s[1] * s[2];
      }
    }
  }
};

// largest size of a Q row block (DIM x basis size)
constexpr int QMAX = 27;

// fill the reference data of a bond from X_ij and the two volumes
// (g and c are completed by correction()). kernel_scale converts a volume
// into the measure the kernel is normalised over: 1 in 3D, 1/thickness in
// 2D (the kernel is normalised per area), so that the viscous and hourglass
// terms scale with the thickness exactly like the stress term.
TLSPH_INLINE void make_bond(const CubicSpline &kernel, const double *Xij, double Vi, double Vj,
                            int j, int k, Bond &b, double kernel_scale = 1.0)
{
  b.X[0] = Xij[0];
  b.X[1] = Xij[1];
  b.X[2] = Xij[2];
  const double r = std::sqrt(dot3(Xij, Xij));
  const double W = kernel.value(r);
  const double dW = kernel.derivative(r);
  b.g[0] = b.g[1] = b.g[2] = 0.0;
  b.c = Vi;    // times w_ij, set by correction()
  b.wv = -Vj * kernel_scale * dW / r;
  b.whg = Vj * kernel_scale * W / (r * r);
  b.j = j;
  b.k = k;
}

// condition numbers above these mean: too few partners to define a gradient
constexpr double MAX_CONDITION_LINEAR = 1.0e6;
constexpr double MAX_CONDITION_QUADRATIC = 1.0e9;

namespace detail {
// w_ij of the given order for a bond (reconstructed from the stored weights)
TLSPH_INLINE double bond_weight(const Bond &b, const CubicSpline &kernel, int order)
{
  const double r = std::sqrt(dot3(b.X, b.X));
  return order == 1 ? -kernel.derivative(r) / r : kernel.value(r);
}

template <int DIM, int ORDER>
TLSPH_INLINE bool solve_correction(const Bond *b, int nb, const double *Vj,
                                   const CubicSpline &kernel, double *Q)
{
  constexpr int NB = Basis<DIM, ORDER>::size;
  double M[NB * NB], Mi[NB * NB], Mc[NB * NB];
  for (int k = 0; k < NB * NB; k++) M[k] = 0.0;
  const double inv_h = 1.0 / kernel.h;
  for (int m = 0; m < nb; m++) {
    double s[3] = {b[m].X[0] * inv_h, b[m].X[1] * inv_h, b[m].X[2] * inv_h}, p[NB];
    Basis<DIM, ORDER>::eval(s, p);
    const double w = Vj[m] * bond_weight(b[m], kernel, ORDER);
    for (int r = 0; r < NB; r++)
      for (int c = 0; c < NB; c++) M[NB * r + c] += w * p[r] * p[c];
  }
  for (int k = 0; k < NB * NB; k++) Mc[k] = M[k];
  if (nb < NB || !invert_small(NB, Mc, Mi)) return false;
  double nM = 0.0, nMi = 0.0;
  for (int k = 0; k < NB * NB; k++) nM += M[k] * M[k], nMi += Mi[k] * Mi[k];
  const double cond = std::sqrt(nM * nMi);
  if (!(cond < (ORDER == 1 ? MAX_CONDITION_LINEAR : MAX_CONDITION_QUADRATIC))) return false;
  for (int r = 0; r < DIM; r++)
    for (int c = 0; c < NB; c++) Q[NB * r + c] = Mi[NB * r + c] * inv_h;
  return true;
}
}    // namespace detail

template <int DIM, int ORDER>
TLSPH_INLINE void apply_correction(Bond *b, int nb, const double *Vj, const CubicSpline &kernel,
                                   const double *Q, double *sumg);

/* Corrected gradients of particle i (see the header comment). Vj[m] is the
   volume of the partner of bond m. Writes Q_i (DIM x Basis::size, row-major)
   and s_i = sum_j g_ij, completes g and c of every bond. A quadratic
   correction that is ill-conditioned (corner particles) falls back to the
   W-weighted linear one in the same layout; if that also fails Q = 0: the
   particle carries no stress of its own (F = I) but still feels its
   partners'. Returns 2, 1 or 0: the order actually achieved. */
template <int DIM, int ORDER>
TLSPH_INLINE int correction(Bond *b, int nb, const double *Vj, const CubicSpline &kernel,
                            double *Q, double *sumg)
{
  constexpr int NB = Basis<DIM, ORDER>::size;
  for (int k = 0; k < DIM * NB; k++) Q[k] = 0.0;
  int achieved = 0;
  int weight_order = ORDER;
  if (detail::solve_correction<DIM, ORDER>(b, nb, Vj, kernel, Q)) achieved = ORDER;
  else if (ORDER == 2) {
    // linear W-weighted fallback in the quadratic layout: zero quadratic columns
    constexpr int NL = DIM;
    double QL[DIM * DIM];
    // same weights as the quadratic basis (w = W), linear basis
    double M[NL * NL], Mc[NL * NL], Mi[NL * NL];
    for (int k = 0; k < NL * NL; k++) M[k] = 0.0;
    const double inv_h = 1.0 / kernel.h;
    for (int m = 0; m < nb; m++) {
      const double w = Vj[m] * detail::bond_weight(b[m], kernel, 2);
      for (int r = 0; r < NL; r++)
        for (int c = 0; c < NL; c++) M[NL * r + c] += w * b[m].X[r] * b[m].X[c] * inv_h * inv_h;
    }
    for (int k = 0; k < NL * NL; k++) Mc[k] = M[k];
    if (nb >= DIM && invert_small(NL, Mc, Mi)) {
      double nM = 0.0, nMi = 0.0;
      for (int k = 0; k < NL * NL; k++) nM += M[k] * M[k], nMi += Mi[k] * Mi[k];
      if (std::sqrt(nM * nMi) < MAX_CONDITION_LINEAR) {
        for (int k = 0; k < NL * NL; k++) QL[k] = Mi[k] * inv_h;
        for (int r = 0; r < DIM; r++)
          for (int c = 0; c < DIM; c++) Q[NB * r + c] = QL[NL * r + c];
        achieved = 1;
      }
    }
  }
  apply_correction<DIM, ORDER>(b, nb, Vj, kernel, Q, sumg);
  (void) weight_order;
  return achieved;
}

/* Corrected gradients g_ij = V_j w_ij Q p(X_ij/h) of the bonds b[0..nb) for a
   given correction Q (from correction(), or frozen at setup), s = sum g_ij,
   and the reverse weights c = V_i w_ij (make_bond stored V_i in c). */
template <int DIM, int ORDER>
TLSPH_INLINE void apply_correction(Bond *b, int nb, const double *Vj, const CubicSpline &kernel,
                                   const double *Q, double *sumg)
{
  constexpr int NB = Basis<DIM, ORDER>::size;
  sumg[0] = sumg[1] = sumg[2] = 0.0;
  const double inv_h = 1.0 / kernel.h;
  for (int m = 0; m < nb; m++) {
    const double w = detail::bond_weight(b[m], kernel, ORDER);
    double s[3] = {b[m].X[0] * inv_h, b[m].X[1] * inv_h, b[m].X[2] * inv_h}, p[NB];
    Basis<DIM, ORDER>::eval(s, p);
    for (int r = 0; r < 3; r++) b[m].g[r] = 0.0;
    for (int r = 0; r < DIM; r++) {
      double acc = 0.0;
      for (int c = 0; c < NB; c++) acc += Q[NB * r + c] * p[c];
      b[m].g[r] = Vj[m] * w * acc;
      sumg[r] += b[m].g[r];
    }
    b[m].c *= w;    // make_bond stored V_i
  }
}

/* The bond math of particle i at a bond cache build (PairTLSPH::build_bond_cache
   on the host, PairTLSPHKokkosT::build_bond_cache_device on a Kokkos device):
   from its partners j[0..nall) (slots k[0..nall), record m at m S; the nb intact bonds first,
   then broken ones that only enter the correction) and the reference
   positions x0c(j) (consistent with the periodic images), the records
   b[0..nall) and partner volumes Vj[0..nall) (scratch), the correction Q,
   s = sum of g over the intact bonds, and the step's lean data: g (DIM per
   bond) and the weights w (wv, whg per bond). frozen: a correction to apply
   instead of computing one (nullptr: compute it). Returns the order achieved
   (ORDER when frozen). */
template <int DIM, int ORDER, class X0>
TLSPH_INLINE int particle_bonds(int i, const int *j, const int *k, int nall, int nb, const X0 &x0c,
                                const double *vfrac, const CubicSpline &kernel,
                                double kernel_scale, const double *frozen, Bond *b, double *Vj,
                                double *Q, double *sumg, double *g, double *w, int S = 1)
{
  const double *xi = x0c(i);
  for (int m = 0; m < nall; m++) {
    const int jm = j[(long) m * S], km = k[(long) m * S];
    const double *xj = x0c(jm);
    const double X[3] = {xj[0] - xi[0], xj[1] - xi[1], DIM == 2 ? 0.0 : xj[2] - xi[2]};
    make_bond(kernel, X, vfrac[i], vfrac[jm], jm, km, b[m], kernel_scale);
    Vj[m] = vfrac[jm];
  }
  int achieved = ORDER;
  if (frozen) {
    for (int q = 0; q < DIM * Basis<DIM, ORDER>::size; q++) Q[q] = frozen[q];
    apply_correction<DIM, ORDER>(b, nall, Vj, kernel, Q, sumg);
  } else {
    achieved = correction<DIM, ORDER>(b, nall, Vj, kernel, Q, sumg);
  }
  if (nall > nb) {
    // broken bonds entered the correction only: sum_j g_ij runs over intact ones
    sumg[0] = sumg[1] = sumg[2] = 0.0;
    for (int m = 0; m < nb; m++)
      for (int d = 0; d < 3; d++) sumg[d] += b[m].g[d];
  }
  for (int m = 0; m < nall; m++) {
    const long r = (long) m * S;
    for (int d = 0; d < DIM; d++) g[DIM * r + d] = b[m].g[d];
    w[2 * r] = b[m].wv;
    w[2 * r + 1] = b[m].whg;
  }
  return achieved;
}

/* F_i = I + sum_j (u_j - u_i) (x) g_ij, with u = x - X and the reference
   bond vector X_ij taken from the bond. x(j) returns x_j. */
template <int DIM, class Rows, class Bonds>
TLSPH_INLINE void deformation_gradient_bonds(const Rows &x, int i, const Bonds &b, int nb,
                                             double *F)
{
  const double *xi = x(i);
  double Fa[DIM * DIM];    // in registers: F may alias nothing the loop reads, but
  for (int k = 0; k < DIM * DIM; k++) Fa[k] = 0.0;    // the compiler cannot know it
  for (int m = 0; m < nb; m++) {
    const double *xj = x(b.partner(m));
    const double *g = b.grad(m);
    double X[DIM], du[DIM];
    b.template ref<DIM>(m, X);
    for (int d = 0; d < DIM; d++) du[d] = (xj[d] - xi[d]) - X[d];
    for (int r = 0; r < DIM; r++)
      for (int c = 0; c < DIM; c++) Fa[DIM * r + c] += du[r] * g[c];
  }
  mat_identity(F);
  for (int r = 0; r < DIM; r++)
    for (int c = 0; c < DIM; c++) F[3 * r + c] += Fa[DIM * r + c];
}

/* The velocity gradient L_i = dv/dX = sum_j (v_j - v_i) (x) g_ij (the rate
   of F), 3 x 3 row-major, zero beyond DIM. v(j) returns v_j. */
template <int DIM, class Rows, class Bonds>
TLSPH_INLINE void velocity_gradient_bonds(const Rows &v, int i, const Bonds &b, int nb, double *L)
{
  const double *vi = v(i);
  for (int k = 0; k < 9; k++) L[k] = 0.0;
  for (int m = 0; m < nb; m++) {
    const double *vj = v(b.partner(m));
    const double *g = b.grad(m);
    for (int r = 0; r < DIM; r++)
      for (int c = 0; c < DIM; c++) L[3 * r + c] += (vj[r] - vi[r]) * g[c];
  }
}

template <int DIM, class Rows>
TLSPH_INLINE void deformation_gradient(const Rows &x, int i, const Bond *b, int nb, double *F)
{
  deformation_gradient_bonds<DIM>(x, i, BondRecords{b}, nb, F);
}

/* From F: strain energy density (returned), the first Piola-Kirchhoff
   stress P = F S, and, if K is not null, K = J F^-T (viscosity mapping).
   In 2D plane stress F33 is set from E33. *J receives det(F). Law is
   IsotropicSVK or OrthotropicSVK (tlsph_material.h): the type is fixed at
   compile time, so the isotropic loop carries no test for the other law. */
template <class Law>
TLSPH_FORCE_INLINE double stress_tensors(const Law &law, int dim, double *F, double *P, double *K,
                                   double *J)
{
  double E[9], S[9];
  green_lagrange(F, E);
  const double psi = law.stress(E, S);
  if (dim == 2 && law.plane_stress) F[8] = std::sqrt(1.0 + 2.0 * E[8]);
  *J = mat_det(F);
  mat_mul(F, S, P);
  if (K) {
    double Finv[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    mat_inverse(F, Finv);
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++) K[3 * r + c] = *J * Finv[3 * c + r];
  }
  return psi;
}

/* The per-particle row the force pass reads for every partner (and that
   ghosts receive), blocks back to back, row-major:
     F (DIM x DIM),  K = J F^-T (DIM x DIM),  the particle's viscosity
     coefficient alpha_i (tlsph/damage raises it on damaged particles; the
     pair term uses (alpha_i + alpha_j)/2), and last
     R = V P Q  (DIM x Basis::size), read only by the gather form of the
     stress term (newton off): with Newton's third law the rows end before
     R (`compact`), which saves computing R, reading Q and moving R.
   2D: 4 + 4 + 1 + 4 (linear) or + 10 (quadratic); 3D: 9 + 9 + 1 + 9 or + 27. */
template <int DIM, int ORDER> struct Packed {
  static constexpr int NB = Basis<DIM, ORDER>::size;
  static constexpr int F = 0;
  static constexpr int K = DIM * DIM;
  static constexpr int A = 2 * DIM * DIM;
  static constexpr int R = A + 1;
  static constexpr int compact = R;
  static constexpr int size = R + DIM * NB;
};

/* Fill particle i's packed row and its own force term V_i P_i s_i; the R
   block only if with_R (the gather form needs it, see Packed). */
template <int DIM, int ORDER>
TLSPH_INLINE void pack_row(double Vi, const double *P, const double *Q, const double *F,
                           const double *K, double alpha_i, const double *sumg, double *row,
                           double *fown, bool with_R = true)
{
  using L = Packed<DIM, ORDER>;
  constexpr int NB = L::NB;
  for (int r = 0; r < DIM; r++) {
    if (with_R) {
      for (int c = 0; c < NB; c++) {
        double acc = 0.0;
        for (int k = 0; k < DIM; k++) acc += P[3 * r + k] * Q[NB * k + c];
        row[L::R + NB * r + c] = Vi * acc;
      }
    }
    for (int c = 0; c < DIM; c++) {
      row[L::F + DIM * r + c] = F[3 * r + c];
      row[L::K + DIM * r + c] = K ? K[3 * r + c] : 0.0;
    }
  }
  row[L::A] = alpha_i;
  for (int r = 0; r < 3; r++) fown[r] = 0.0;
  for (int r = 0; r < DIM; r++)
    for (int c = 0; c < DIM; c++) fown[r] += Vi * P[3 * r + c] * sumg[c];
}

// material numbers the force pass needs, per particle type
struct PairMaterial {
  double c0, rho, E;
};

struct NoBondVisitor {
  TLSPH_INLINE void operator()(int, const double *, const double *) const {}
};

struct NoScatter {
  TLSPH_INLINE void operator()(int, const double *) const {}
};

/* The viscous and hourglass forces of a bond are pair forces: the force on
   j is minus the force on i (both coefficients below are symmetric in i and
   j, and X_ji = -X_ij, x_ji = -x_ij).
   Viscous: the force on i is sv (K_i + K_j) X_ij, with
     sv = -q_ij V_i V_j (-W'(r)/r) / 2 = -0.5 q_ij Vi wv,
   q_ij from the approach rate (v_j - v_i).x_ij, measured along the current
   separation x_ij, not the reference X_ij of the thesis: identical for small
   deformation, and zero for a rigid rotation (objective). Branch-free:
   q = 0 for separating pairs (a data-dependent branch is mispredicted half
   the time). inv_both = 1 / (r2 (r2 + 0.01 h^2)): one division serves both
   denominators, 1/r2 (hourglass) and 1/(r2 + 0.01 h^2) (viscosity). */
template <int DIM, class T>
TLSPH_FORCE_INLINE T viscous_coefficient(const T *vi, const T *vj, const T *xij, T r2, T inv_both,
                                         double h, double beta, T alpha, T c, T rho, T Vi_wv)
{
  T dvX = T{};
  for (int d = 0; d < DIM; d++) dvX += (vj[d] - vi[d]) * xij[d];
  // (a select on every lane of a SIMD type T, tlsph_ell.h)
  const T mu = h * (dvX < T{} ? dvX : T{}) * r2 * inv_both;
  const T q = rho * mu * (beta * mu - alpha * c);
  return -0.5 * q * Vi_wv;
}

/* current separation x_ij = x_j - x_i, r2 = |x_ij|^2 and
   inv_both = 1 / (r2 (r2 + eps2)), eps2 = 0.01 h^2 */
template <int DIM>
TLSPH_FORCE_INLINE void pair_separation(const double *xi, const double *xj, double eps2, double *xij,
                                  double &r2, double &inv_both)
{
  r2 = 0.0;
  for (int d = 0; d < DIM; d++) {
    xij[d] = xj[d] - xi[d];
    r2 += xij[d] * xij[d];
  }
  inv_both = 1.0 / (r2 * (r2 + eps2));
}

/* Hourglass: the force on i is sh x_ij, with
   (delta_ij + delta_ji) |x_ij| = ((F_i + F_j) X_ij - 2 x_ij) . x_ij (see
   hourglass_force()); Fi, Fj are DIM x DIM blocks. Zero when r2 = 0 (the
   unguarded form, for a SIMD type T, has no branch: the SIMD step passes a
   finite inv_both for r2 = 0, where its result is zero). */
template <int DIM, class T>
TLSPH_FORCE_INLINE T hourglass_coefficient_unguarded(const T *Fi, const T *Fj, const T *X,
                                                     const T *xij, T r2, double eps2, T inv_both,
                                                     T gamma_Ebar, T Vi_whg)
{
  T ex = T{};
  for (int r = 0; r < DIM; r++) {
    T e = -2.0 * xij[r];
    for (int c2 = 0; c2 < DIM; c2++) e += (Fi[DIM * r + c2] + Fj[DIM * r + c2]) * X[c2];
    ex += e * xij[r];
  }
  return -0.5 * gamma_Ebar * Vi_whg * ex * (r2 + eps2) * inv_both;
}

template <int DIM>
TLSPH_FORCE_INLINE double hourglass_coefficient(const double *Fi, const double *Fj, const double *X,
                                                const double *xij, double r2, double eps2,
                                                double inv_both, double gamma_Ebar, double Vi_whg)
{
  if (!(r2 > 0.0)) return 0.0;
  return hourglass_coefficient_unguarded<DIM>(Fi, Fj, X, xij, r2, eps2, inv_both, gamma_Ebar,
                                              Vi_whg);
}

// GUARD: the scalar form with its test of r2 (double only); else unguarded
template <int DIM, bool GUARD> struct hourglass_coefficient_select {
  TLSPH_FORCE_INLINE static double get(const double *Fi, const double *Fj, const double *X,
                                       const double *xij, double r2, double eps2,
                                       double inv_both, double gamma_Ebar, double Vi_whg)
  {
    return hourglass_coefficient<DIM>(Fi, Fj, X, xij, r2, eps2, inv_both, gamma_Ebar, Vi_whg);
  }
};
template <int DIM> struct hourglass_coefficient_select<DIM, false> {
  template <class T>
  TLSPH_FORCE_INLINE static T get(const T *Fi, const T *Fj, const T *X, const T *xij, T r2,
                                  double eps2, T inv_both, T gamma_Ebar, T Vi_whg)
  {
    return hourglass_coefficient_unguarded<DIM>(Fi, Fj, X, xij, r2, eps2, inv_both, gamma_Ebar,
                                                Vi_whg);
  }
};

/* Conservative hourglass control (pair_style ... hourglass conservative,
   doc/pair_tlsph.rst): the gradient of the energy
     E_hg = 1/4 sum_i sum_j c_ij |e_ij|^2,   e_ij = F_i X_ij - x_ij,
     c_ij = gamma Ebar V_i V_j W_ij / |X_ij|^2   (symmetric in i and j),
   which vanishes for every homogeneous deformation. With F_i linear in the
   positions (F_i = I + sum_m (u_m - u_i) (x) g_im) the force is
     f_k = -dE_hg/dx_k = (1/2) H_k s_k - sum_i (1/2) H_i g_ik
                         - (1/2) sum_j c_kj ((F_k + F_j) X_kj - 2 x_kj),
     H_i = sum_j c_ij e_ij (x) X_ij,
   i.e. (1/2) H_i adds to V_i P_i in the stress term, and each bond carries a
   pair force: the thesis's pair force without its projection on x_ij.
   hourglass_moment() returns sum_j c_ij |e_ij|^2 (= 4 x the particle's share
   of E_hg) and writes H_i (DIM x DIM, row-major); coeff(m) is c_ij of bond m.
   e_ij = (F_i - I) X_ij - (u_j - u_i): no cancellation of x_ij against F X_ij
   for small strains. */
template <int DIM, class Rows, class Bonds, class Coeff>
TLSPH_INLINE double hourglass_moment(const Rows &x, int i, const Bonds &b, int nb,
                                     const double *F, const Coeff &coeff, double *H)
{
  const double *xi = x(i);
  double G[DIM * DIM];
  for (int r = 0; r < DIM; r++)
    for (int c = 0; c < DIM; c++) G[DIM * r + c] = F[3 * r + c] - (r == c ? 1.0 : 0.0);
  for (int k = 0; k < DIM * DIM; k++) H[k] = 0.0;
  double ee = 0.0;
  for (int m = 0; m < nb; m++) {
    const double *xj = x(b.partner(m));
    double X[DIM];
    b.template ref<DIM>(m, X);
    const double c = coeff(m);
    for (int r = 0; r < DIM; r++) {
      double e = -((xj[r] - xi[r]) - X[r]);
      for (int k = 0; k < DIM; k++) e += G[DIM * r + k] * X[k];
      ee += c * e * e;
      for (int k = 0; k < DIM; k++) H[DIM * r + k] += c * e * X[k];
    }
  }
  return ee;
}

/* the pair force of the conservative form on i from bond ij:
   f = coeff ((F_i + F_j) X_ij - 2 x_ij), coeff = -c_ij / 2 (Fi, Fj: DIM x DIM) */
template <int DIM, class T>
TLSPH_FORCE_INLINE void hourglass_pair_conservative(const T *Fi, const T *Fj, const T *X,
                                                    const T *xij, T coeff, T *f)
{
  for (int r = 0; r < DIM; r++) {
    T e = -2.0 * xij[r];
    for (int c = 0; c < DIM; c++) e += (Fi[DIM * r + c] + Fj[DIM * r + c]) * X[c];
    f[r] = coeff * e;
  }
}

/* the hourglass pair force on i from bond ij, HG 1: the thesis's (projected
   on x_ij), HG 2: the conservative form's; gamma_Ebar Vi_whg = c_ij */
template <int DIM, int HG, bool GUARD = true, class T>
TLSPH_FORCE_INLINE void hourglass_pair(const T *Fi, const T *Fj, const T *X, const T *xij, T r2,
                                       double eps2, T inv_both, T gamma_Ebar, T Vi_whg, T *f)
{
  if (HG == 2) {
    hourglass_pair_conservative<DIM>(Fi, Fj, X, xij, T(-0.5 * gamma_Ebar * Vi_whg), f);
  } else {
    const T sh = hourglass_coefficient_select<DIM, GUARD>::get(Fi, Fj, X, xij, r2, eps2, inv_both,
                                                                gamma_Ebar, Vi_whg);
    for (int d = 0; d < DIM; d++) f[d] = sh * xij[d];
  }
}

/* c_ij of bond m of particle i for the conservative hourglass form:
   gamma (E_i + E_j) / 2 V_i V_j W_ij / |X_ij|^2 (V_j W / |X|^2 is whg) */
template <class Bonds, class Types> struct HourglassWeights {
  const PairMaterial *pm;
  Types type;
  const Bonds &b;
  double gamma, gEi, Vi;
  TLSPH_INLINE HourglassWeights(const PairMaterial *pm_, Types type_, const Bonds &b_,
                                double gamma_, int i, double Vi_) :
      pm(pm_), type(type_), b(b_), gamma(gamma_), gEi(0.5 * gamma_ * pm_[type_(i)].E), Vi(Vi_)
  {
  }
  TLSPH_INLINE double operator()(int m) const
  {
    return (gEi + 0.5 * gamma * pm[type(b.partner(m))].E) * Vi * b.whg(m);
  }
};

/* The per-particle part of pass (1) once F_i is known (both pair styles, CPU
   loop and Kokkos kernel): stress P_i from the law (IsotropicSVK or
   OrthotropicSVK; F may get F33 in 2D plane stress), with the conservative
   hourglass form (conservative = true) plus H_i / (2 V_i) and its energy
   share *ehg = E_hg,i (else *ehg = 0), then the packed row and V_i P_i s_i.
   coeff(m) = c_ij of bond m (hourglass_moment). Returns psi_i and *J = det F;
   when J <= 0 or psi is not finite it returns at once (the caller stops the
   run, naming the particle). */
template <int DIM, int ORDER, class Law, class Rows, class Bonds, class Coeff>
TLSPH_FORCE_INLINE double particle_stress_row(const Law &law, double *F, double *P, bool need_K,
                                              bool conservative, const Rows &x, int i,
                                              const Bonds &b, int nb, const Coeff &coeff,
                                              double Vi, const double *Q, double alpha_i,
                                              const double *sumg, bool with_R, double *row,
                                              double *fown, double *ehg, double *J)
{
  double K[9];
  const double psi = stress_tensors(law, DIM, F, P, need_K ? K : nullptr, J);
  *ehg = 0.0;
  if (!(*J > 0.0) || !std::isfinite(psi)) return psi;
  if (conservative) {
    double H[DIM * DIM];
    *ehg = 0.25 * hourglass_moment<DIM>(x, i, b, nb, F, coeff, H);
    const double s = 0.5 / Vi;
    for (int r = 0; r < DIM; r++)
      for (int c = 0; c < DIM; c++) P[3 * r + c] += s * H[DIM * r + c];
  }
  pack_row<DIM, ORDER>(Vi, P, Q, F, need_K ? K : nullptr, alpha_i, sumg, row, fown, with_R);
  return psi;
}

/* Pairs: with Newton's third law (SCATTER) the viscous and hourglass pair
   forces of a bond need computing once, not from both ends. The caller
   orders the bonds of i so that the first `nlead` lead: partner j is a
   ghost, or a local particle after i. particle_force_bonds then computes
   these terms for the leading bonds only, adds them to i and hands the
   opposite force of a local partner to pair(j, fv_ij, fh_ij) (f_j -= ...);
   a ghost partner gets nothing: its owner computes the same pair force from
   its side. NoPairs: every bond, from both ends. */
struct NoPairs {
  static constexpr bool enabled = false;
  int nlead = -1;
  int nlocal = 0;
  TLSPH_INLINE void operator()(int, const double *, const double *) const {}
};

/* Force on particle i from its bonds, added to fs (stress), fv (viscous)
   and fh (hourglass); fown = V_i P_i s_i must be added to fs separately.
     stress:   - sum_j V_j P_j g_ji  =  - sum_j R_j c_ij p(-X_ij/h)
     viscous:  - V_i sum_j q_ij (K_i + K_j) V_j grad_i W_ij / 2
     hourglass: HG 1 Ganzenmueller's pair force along x_ij (tlsph_pair_terms.h),
                HG 2 the pair part of the conservative form (its H_i part is
                in P_i and the packed rows, see hourglass_moment())
   (pair coefficients above). b: the bonds (BondRecords or LeanBonds).
   Accessors x, v return position/velocity rows, pk the packed rows, type(j)
   the particle type; mat[type] the material numbers. When VISIT is set,
   visit(j, xij, fij) receives twice the pair force of the bond that the
   tally halves (virial tallies; a pair force computed on both ranks counts
   once on each).
   SCATTER (Newton's third law for the stress term): instead of gathering
   - V_j P_j g_ji = - c_ij R_j p(-X_ij/h) from every partner, particle i hands
   its own bond force t_ij = V_i P_i g_ij to the partner, scatter(j, t) doing
   f_j -= t (ghost forces are then summed by LAMMPS's reverse communication):
   DIM^2 instead of DIM x Basis::size multiply-adds per bond, the same sum.
   With SCATTER, pairs (see NoPairs) may hand the viscous and hourglass
   forces on as well. Pi (the own stress) is needed with VISIT or SCATTER,
   otherwise it may be null. */
template <int DIM, int ORDER, int HG, int VISC, int VISIT, int SCATTER = 0, class Bonds,
          class Rows, class PkRows, class Types, class Visitor, class Scatter = NoScatter,
          class Pairs = NoPairs>
TLSPH_FORCE_INLINE void particle_force_bonds(int i, double Vi, const Bonds &b, int nb,
                                             const Rows &x, const Rows &v, const PkRows &pk,
                                             const Types &type, const PairMaterial *mat, double h,
                                             double beta, double gamma, const double *Pi,
                                             double *fs, double *fv, double *fh,
                                             const Visitor &visit,
                                             const Scatter &scatter = Scatter(),
                                             const Pairs &pairs = Pairs())
{
  using L = Packed<DIM, ORDER>;
  constexpr int NB = L::NB;
  const double inv_h = 1.0 / h;
  const double eps2 = 0.01 * h * h;
  constexpr bool half = SCATTER && Pairs::enabled;
  // particle i's own blocks and material, held in registers for the bond loop
  // (local accumulators too: the outputs could alias the particle arrays)
  // (pk(j) is a row pointer, or a row of ColumnRows: values read by index only)
  const auto pi = pk(i);
  double Fi[DIM * DIM], Ki[DIM * DIM], xi[DIM], vi[DIM];
  for (int k = 0; k < DIM * DIM; k++) Fi[k] = pi[L::F + k], Ki[k] = pi[L::K + k];
  const double *xr = x(i), *vr = v(i);
  for (int d = 0; d < DIM; d++) xi[d] = xr[d], vi[d] = vr[d];
  const int ti = type(i);
  const PairMaterial mi = mat[ti];
  double as[DIM], av[DIM], avi[DIM], ah[DIM];
  for (int d = 0; d < DIM; d++) as[d] = av[d] = avi[d] = ah[d] = 0.0;

  // (a) the stress term of every bond; without pairs also the viscous and
  // hourglass terms (from this end)
  for (int m = 0; m < nb; m++) {
    const int j = b.partner(m);
    const double *gm = b.grad(m);
    const auto pj = pk(j);
    double fb[3] = {0.0, 0.0, 0.0};
    double X[DIM];
    if (!SCATTER || (!half && (HG || VISC))) b.template ref<DIM>(m, X);
    if (SCATTER) {
      double t[3] = {0.0, 0.0, 0.0};
      for (int r = 0; r < DIM; r++) {
        double own = 0.0;
        for (int c = 0; c < DIM; c++) own += Pi[3 * r + c] * gm[c];
        t[r] = Vi * own;
        // a pair force (+t on i, -t on j) counted once: twice for the halving tally
        if (VISIT) fb[r] = 2.0 * t[r];
      }
      scatter(j, t);
    } else {
      double s[3] = {0.0, 0.0, 0.0}, p[NB];
      for (int d = 0; d < DIM; d++) s[d] = -X[d] * inv_h;
      const double cm = b.reverse_weight(m);
      Basis<DIM, ORDER>::eval(s, p);
      for (int r = 0; r < DIM; r++) {
        double acc = 0.0;
        for (int c = 0; c < NB; c++) acc += pj[L::R + NB * r + c] * p[c];
        as[r] -= cm * acc;
        if (VISIT) {
          double own = 0.0;
          for (int c = 0; c < DIM; c++) own += Pi[3 * r + c] * gm[c];
          fb[r] = Vi * own - cm * acc;
        }
      }
    }
    if (half || !(HG || VISC)) {
      if (VISIT) {
        double xij[3] = {0.0, 0.0, 0.0};
        const double *xj = x(j);
        for (int d = 0; d < DIM; d++) xij[d] = xj[d] - xi[d];
        visit(j, xij, fb);
      }
      continue;
    }
    double xij[3] = {0.0, 0.0, 0.0}, r2, inv_both;
    pair_separation<DIM>(xi, x(j), eps2, xij, r2, inv_both);
    const PairMaterial &mj = mat[type(j)];
    if (VISC) {
      const double sv = viscous_coefficient<DIM>(
          vi, v(j), xij, r2, inv_both, h, beta, 0.5 * (pi[L::A] + pj[L::A]),
          0.5 * (mi.c0 + mj.c0), 0.5 * (mi.rho + mj.rho), Vi * b.wv(m));
      // (K_i + K_j) X_ij: the K_i part is applied once after the loop
      for (int d = 0; d < DIM; d++) avi[d] += sv * X[d];
      for (int r = 0; r < DIM; r++) {
        double acc = 0.0;
        for (int c2 = 0; c2 < DIM; c2++) acc += pj[L::K + DIM * r + c2] * X[c2];
        av[r] += sv * acc;
        if (VISIT) {
          double acci = 0.0;
          for (int c2 = 0; c2 < DIM; c2++) acci += Ki[DIM * r + c2] * X[c2];
          fb[r] += sv * (acc + acci);
        }
      }
    }
    if (HG) {
      double ph[DIM], Fj[DIM * DIM];
      for (int k = 0; k < DIM * DIM; k++) Fj[k] = pj[L::F + k];
      hourglass_pair<DIM, HG>(Fi, Fj, X, xij, r2, eps2, inv_both,
                              gamma * 0.5 * (mi.E + mj.E), Vi * b.whg(m), ph);
      for (int d = 0; d < DIM; d++) {
        ah[d] += ph[d];
        if (VISIT) fb[d] += ph[d];
      }
    }
    if (VISIT) visit(j, xij, fb);
  }

  // (b) pairs: the viscous and hourglass forces of the leading bonds, once
  if (half && (HG || VISC)) {
    for (int m = 0; m < pairs.nlead; m++) {
      const int j = b.partner(m);
      const auto pj = pk(j);
      double X[DIM];
      b.template ref<DIM>(m, X);
      double xij[3] = {0.0, 0.0, 0.0}, r2, inv_both;
      pair_separation<DIM>(xi, x(j), eps2, xij, r2, inv_both);
      const PairMaterial &mj = mat[type(j)];
      double pv[3] = {0.0, 0.0, 0.0}, ph[3] = {0.0, 0.0, 0.0};
      if (VISC) {
        const double sv = viscous_coefficient<DIM>(
            vi, v(j), xij, r2, inv_both, h, beta, 0.5 * (pi[L::A] + pj[L::A]),
            0.5 * (mi.c0 + mj.c0), 0.5 * (mi.rho + mj.rho), Vi * b.wv(m));
        for (int r = 0; r < DIM; r++) {
          double acc = 0.0;
          for (int c2 = 0; c2 < DIM; c2++) acc += (Ki[DIM * r + c2] + pj[L::K + DIM * r + c2]) * X[c2];
          pv[r] = sv * acc;
          av[r] += pv[r];
        }
      }
      if (HG) {
        double Fj[DIM * DIM];
        for (int k = 0; k < DIM * DIM; k++) Fj[k] = pj[L::F + k];
        hourglass_pair<DIM, HG>(Fi, Fj, X, xij, r2, eps2, inv_both,
                                gamma * 0.5 * (mi.E + mj.E), Vi * b.whg(m), ph);
        for (int d = 0; d < DIM; d++) ah[d] += ph[d];
      }
      const bool local = j < pairs.nlocal;
      if (local) pairs(j, pv, ph);
      if (VISIT) {
        // computed once for a local pair (twice for the halving tally), on
        // both ranks for a ghost partner (once each)
        const double k = local ? 2.0 : 1.0;
        double fb[3] = {0.0, 0.0, 0.0};
        for (int d = 0; d < DIM; d++) fb[d] = k * (pv[d] + ph[d]);
        visit(j, xij, fb);
      }
    }
  }
  for (int r = 0; r < DIM; r++) {
    fs[r] += as[r];
    fh[r] += ah[r];
    double acc = av[r];
    if (VISC && !half)
      for (int c = 0; c < DIM; c++) acc += Ki[DIM * r + c] * avi[c];
    fv[r] += acc;
  }
}

template <int DIM, int ORDER, int HG, int VISC, int VISIT, int SCATTER = 0, class Rows,
          class Types, class Visitor, class Scatter = NoScatter>
TLSPH_INLINE void particle_force(int i, double Vi, const Bond *b, int nb, const Rows &x,
                                 const Rows &v, const Rows &pk, const Types &type,
                                 const PairMaterial *mat, double h, double beta, double gamma,
                                 const double *Pi, double *fs, double *fv, double *fh,
                                 const Visitor &visit, const Scatter &scatter = Scatter())
{
  particle_force_bonds<DIM, ORDER, HG, VISC, VISIT, SCATTER>(
      i, Vi, BondRecords{b}, nb, x, v, pk, type, mat, h, beta, gamma, Pi, fs, fv, fh, visit,
      scatter);
}

}    // namespace TLSPH

#endif
