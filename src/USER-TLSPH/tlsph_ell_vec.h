/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: the stencil chunks of the SIMD step with explicit vectors
   (tlsph_ell.h). Only for pair_tlsph_simd.cpp, which compiles them per
   instruction set: the vector type is passed by value only between inlined
   functions, so the ABI note of GCC about it (-Wpsabi) does not apply.
------------------------------------------------------------------------- */

#ifndef TLSPH_ELL_VEC_H
#define TLSPH_ELL_VEC_H

#include "tlsph_ell.h"

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace TLSPH {

// the per-particle stress lanes (below; declared for every compiler, since
// pair_tlsph_simd.cpp names the type in its dispatch table)
struct EllStress;

#if defined(__GNUC__) && !defined(__CUDACC__)
#define TLSPH_ELL_VEC 1
/* Stencil chunks with explicit vectors: GCC's vector extension, C doubles
   (one AVX-512 register, two AVX2 ones, or scalar code on the portable
   build), so that every quantity of a slot is one contiguous load; the
   pair terms are the same templates as the scalar path's, with T = EllVecOf<W>::type.
   (The vectoriser, left to itself, mixes gathers into these loops.) */
template <int W> struct EllVecOf {
  typedef double type __attribute__((vector_size(W * sizeof(double))));
};

template <class V> TLSPH_FORCE_INLINE V ell_load(const double *p)
{
  V v;
  __builtin_memcpy(&v, p, sizeof(v));
  return v;
}

template <class V> TLSPH_FORCE_INLINE V ell_splat(double a)
{
  return V{} + a;
}

/* Prefetches. A chunk's passes touch about a hundred columns (its own
   particles' and, in every slot, its partners'), far more streams than
   the hardware prefetcher follows, so that lines come on demand. Each
   chunk therefore asks for the lines a later chunk will need:
   ELL_PREFETCH particles on (two chunks of 8), the columns of its own
   particles there and, at the leading edge of the partner window (the
   partners of its last slot, first read by this chunk), those of the
   partners there. A prefetch changes no result. */
constexpr long ELL_PREFETCH = 16;
template <int RW> TLSPH_FORCE_INLINE void ell_prefetch(const double *base, int ncol, long ns, long at)
{
  for (int q = 0; q < ncol; q++) __builtin_prefetch(base + q * ns + at, RW, 3);
}

/* The slots of a stencil chunk: its blocks (values per lane) or its
   pattern (one value for all lanes). j0(m): partner of lane 0 in slot m;
   val<V>(m, k, h): the k-th value of slot m (EllShape) for the lanes h..
   (as many as V holds). */
template <int DIM> struct LaneSlots {
  const int *j;       // at the chunk's first block
  const double *v;
  int n;
  long i0;            // the chunk's first particle (j holds offsets from it)
  TLSPH_FORCE_INLINE long j0(int m) const { return i0 + j[(long) ELL_C * m]; }
  template <class V> TLSPH_FORCE_INLINE V val(int m, int k, int h) const
  {
    return ell_load<V>(v + (long) EllShape<DIM>::NV * ELL_C * m + ELL_C * k + h);
  }
};
template <int DIM> struct PatternSlots {
  const int *off;     // at the pattern's first slot
  const double *v;
  int n;
  long i0;
  TLSPH_FORCE_INLINE long j0(int m) const { return i0 + off[m]; }
  template <class V> TLSPH_FORCE_INLINE V val(int m, int k, int) const
  {
    return ell_splat<V>(v[EllShape<DIM>::NV * m + k]);
  }
};

template <int DIM> TLSPH_FORCE_INLINE LaneSlots<DIM> lane_slots(const EllArrays &e, int c)
{
  const long b0 = e.start[c];
  return LaneSlots<DIM>{e.j + ELL_C * b0, e.v + (long) EllShape<DIM>::NV * ELL_C * b0,
                        e.width[c], (long) e.first[c]};
}
template <int DIM> TLSPH_FORCE_INLINE PatternSlots<DIM> pattern_slots(const EllArrays &e, int c)
{
  const int q = e.pat[c], m0 = e.pat_start[q];
  return PatternSlots<DIM>{e.pat_off + m0, e.pat_v + (long) EllShape<DIM>::NV * m0,
                           e.pat_start[q + 1] - m0, (long) e.first[c]};
}

/* pass (1), the bond part: F_i = I + sum_j (u_j - u_i) (x) g_ij
   (deformation_gradient_bonds) for lanes h .. h + W - 1 of the chunk whose
   first particle is `first`, its slots from sl; F: 9 per atom, by LAMMPS
   index */
/* The per-particle part of pass (1) on W lanes, for one isotropic material
   without the conservative hourglass form (particle_stress_row with
   IsotropicSVK: stress_tensors, then pack_row with R): from F - I (Fa,
   DIM x DIM) the stress P, psi, J, K = J F^-T, the packed row (into the
   columns) and V_i P_i s_i. A lane with J <= 0 or a psi that
   is not finite is recorded in st.bad (the caller stops the run). Outputs
   by LAMMPS index. */
struct EllStress {
  IsotropicSVK law;
  int need_K;
  const double *Q;          // correction_size() per atom
  int qs;
  const double *sumg;       // 3 per atom
  double alpha;             // alpha_i where alpha_atom is null
  const double *alpha_atom; // per-particle alpha_i by LAMMPS index (tlsph/damage), or null
  double *F, *P, *psi, *ehg, *fown;    // 9, 9, 1, 1, 3 per atom
  double *pks;              // the packed rows' columns (EllParticles::pks; the SIMD
                            // step keeps them there only, not in the rows pk)
  int bad;                  // first lane that failed (LAMMPS index), else -1
  double badJ;
  /* 2D, crack nucleation (tlsph/damage's strength): where nuc_hit is not
     null, nuc_hit[i] = 1 for each particle whose largest in-plane principal
     Cauchy stress may reach nuc_s (a margin of 1e-9 of the stresses' size
     beyond round-off: PairTLSPH::principal_screen_xy tests these exactly),
     else 0 */
  double nuc_s;
  unsigned char *nuc_hit;
};

template <int DIM, int ORDER, int W, class V>
TLSPH_FORCE_INLINE void ell_stress_lanes(const V *Fa, long i0, const EllParticles &p,
                                         EllStress &st)
{
  using L = Packed<DIM, ORDER>;
  constexpr int NB = L::NB;
  // the packed rows this pass writes and the Q it reads, a later chunk's
  ell_prefetch<1>(st.pks, L::size, p.ns, i0 + ELL_PREFETCH);
  ell_prefetch<0>(p.qcol, DIM * NB, p.ns, i0 + ELL_PREFETCH);
  V Fm[9], E[9], S[9], P[9], K[9];
  for (int r = 0; r < 3; r++)
    for (int k = 0; k < 3; k++)
      Fm[3 * r + k] = (r < DIM && k < DIM) ? (r == k ? 1.0 : 0.0) + Fa[DIM * r + k]
                                           : ell_splat<V>(r == k ? 1.0 : 0.0);
  green_lagrange(Fm, E);
  const V psi = st.law.template stress<V>(E, S);
  if (DIM == 2 && st.law.plane_stress)
    for (int l = 0; l < W; l++) Fm[8][l] = std::sqrt(1.0 + 2.0 * E[8][l]);
  const V J = mat_det(Fm);
  mat_mul(Fm, S, P);
  if (st.need_K) {
    // K = J F^-T (a lane with det = 0 stops the run below)
    V Fi[9];
    mat_inverse_unchecked(Fm, Fi);
    for (int r = 0; r < 3; r++)
      for (int c = 0; c < 3; c++) K[3 * r + c] = J * Fi[3 * c + r];
  } else {
    for (int k = 0; k < 9; k++) K[k] = V{};
  }
  // the volume, Q and s of the lanes' particles (columns)
  const long ns = p.ns;
  const V Vi = ell_load<V>(p.vcol + i0);
  V row[L::size], fo[DIM];
  for (int r = 0; r < DIM; r++) {
    for (int c = 0; c < NB; c++) {
      V acc = V{};
      for (int k = 0; k < DIM; k++) acc += P[3 * r + k] * ell_load<V>(p.qcol + (NB * k + c) * ns + i0);
      row[L::R + NB * r + c] = Vi * acc;
    }
    for (int c = 0; c < DIM; c++) {
      row[L::F + DIM * r + c] = Fm[3 * r + c];
      row[L::K + DIM * r + c] = K[3 * r + c];
    }
  }
  row[L::A] = ell_splat<V>(st.alpha);
  if (st.alpha_atom)
    for (int l = 0; l < W; l++) row[L::A][l] = st.alpha_atom[p.perm[i0 + l]];
  for (int r = 0; r < DIM; r++) {
    fo[r] = V{};
    for (int c = 0; c < DIM; c++) fo[r] += Vi * P[3 * r + c] * ell_load<V>(p.scol + c * ns + i0);
  }
  for (int q = 0; q < L::size; q++) __builtin_memcpy(st.pks + q * ns + i0, &row[q], sizeof(V));
  for (int r = 0; r < DIM; r++) __builtin_memcpy(p.fcol + r * ns + i0, &fo[r], sizeof(V));
  // J sigma = P F^T, in-plane (in 2D, P and F couple no in-plane component to z)
  V mean{}, d{}, xy{};
  if (DIM == 2 && st.nuc_hit) {
    const V xx = P[0] * Fm[0] + P[1] * Fm[1], yy = P[3] * Fm[3] + P[4] * Fm[4];
    xy = P[0] * Fm[3] + P[1] * Fm[4];
    mean = 0.5 * (xx + yy);
    d = 0.5 * (xx - yy);
  }
  for (int l = 0; l < W; l++) {
    const long i = p.perm[i0 + l];
    if (DIM == 2 && st.nuc_hit) {
      const double r = std::sqrt(d[l] * d[l] + xy[l] * xy[l]), sJ = st.nuc_s * J[l];
      st.nuc_hit[i] = mean[l] + r - sJ + 1.0e-9 * (std::fabs(mean[l]) + r + std::fabs(sJ)) >= 0.0;
    }
    for (int k = 0; k < 9; k++) st.F[9 * i + k] = Fm[k][l], st.P[9 * i + k] = P[k][l];
    st.psi[i] = psi[l];
    st.ehg[i] = 0.0;
    for (int r = 0; r < 3; r++) st.fown[3 * i + r] = r < DIM ? fo[r][l] : 0.0;
    if ((!(J[l] > 0.0) || !std::isfinite(psi[l])) && st.bad < 0) st.bad = (int) i, st.badJ = J[l];
  }
}

template <int DIM, int ORDER, int SCREEN, int W, class Slots>
TLSPH_FORCE_INLINE void ell_deformation_stencil(const Slots &sl, int first, int h,
                                                const EllParticles &p, double *F,
                                                EllStress *st, EllScreen *scr)
{
  using V = typename EllVecOf<W>::type;
  const long ns = p.ns, i0 = (long) first + h;
  V xi[DIM], x0i[DIM], Fa[DIM * DIM];
  for (int d = 0; d < DIM; d++) xi[d] = ell_load<V>(p.xs + d * ns + i0), x0i[d] = ell_load<V>(p.x0s + d * ns + i0);
  for (int k = 0; k < DIM * DIM; k++) Fa[k] = V{};
  // SCREEN 1: the largest r^2 - up r0^2 of the lane's bonds; 2: or down r0^2 - r^2
  V worst = ell_splat<V>(-1.0);
  // a later chunk's x and x0, and those at the partners' leading edge
  ell_prefetch<0>(p.xs, DIM, ns, i0 + ELL_PREFETCH);
  ell_prefetch<0>(p.x0s, DIM, ns, i0 + ELL_PREFETCH);
  if (sl.n > 0) {
    const long je = sl.j0(sl.n - 1) + h + ELL_PREFETCH;
    ell_prefetch<0>(p.xs, DIM, ns, je);
    ell_prefetch<0>(p.x0s, DIM, ns, je);
  }
  for (int m = 0; m < sl.n; m++) {
    const long j0 = sl.j0(m) + h;
    V dx[DIM], X[DIM], du[DIM], g[DIM];
    for (int d = 0; d < DIM; d++) {
      dx[d] = ell_load<V>(p.xs + d * ns + j0) - xi[d];
      X[d] = ell_load<V>(p.x0s + d * ns + j0) - x0i[d];
      du[d] = dx[d] - X[d];
    }
    for (int k = 0; k < DIM; k++) g[k] = sl.template val<V>(m, k, h);
    for (int r = 0; r < DIM; r++)
      for (int k = 0; k < DIM; k++) Fa[DIM * r + k] += du[r] * g[k];
    if (SCREEN) {
      V r2 = V{}, r02 = V{};
      for (int d = 0; d < DIM; d++) r2 += dx[d] * dx[d], r02 += X[d] * X[d];
      V q = r2 - scr->up * r02;
      if (SCREEN == 2) {
        const V q2 = scr->down * r02 - r2;
        q = q > q2 ? q : q2;
      }
      // padded and broken slots (zero weights) are no bonds (EllScreen)
      const V cm = sl.template val<V>(m, EllShape<DIM>::CREV, h);
      q = (cm != V{}) || (r02 < scr->reach2) ? q : ell_splat<V>(-1.0);
      worst = worst > q ? worst : q;
    }
  }
  if (SCREEN) {
    double pw = -1.0e300;
    for (int l = 0; l < W; l++) {
      if (worst[l] >= 0.0) scr->list[scr->n++] = p.perm[i0 + l];
      pw = worst[l] > pw ? worst[l] : pw;
    }
    scr->piece = pw;
  }
  if (st) {
    ell_stress_lanes<DIM, ORDER, W>(Fa, i0, p, *st);
    return;
  }
  for (int l = 0; l < W; l++) {
    double *Fi = F + 9 * (long) p.perm[i0 + l];
    for (int r = 0; r < 3; r++)
      for (int k = 0; k < 3; k++)
        Fi[3 * r + k] = (r < DIM && k < DIM) ? (r == k ? 1.0 : 0.0) + Fa[DIM * r + k][l]
                                             : (r == k ? 1.0 : 0.0);
  }
}

/* pass (3) for lanes h .. h + W - 1 of a chunk. The stress term is
   gathered: - sum_j c_ij R_j p(-X_ij/h) over every bond, plus fown. The
   viscous and (HG 1, 2) hourglass pair forces are antisymmetric
   (f_ji = -f_ij), so each bond's is computed once, by the particle that
   comes first in the step's order (the partner offset of the slot is
   positive; locals come before ghosts, so a bond to an earlier particle is
   a bond to a local particle, whose chunk computed it): the lanes add it,
   and the partners' accumulators (EllParticles::pcol, zeroed before the
   pass) subtract it, a contiguous vector per slot. A partner's accumulator
   is complete when its own lanes come: the chunks run in the step's order
   and only later particles receive. A ghost partner's entry is not read:
   its owner computes its end of the bond. The sums of a particle's pair
   forces are then taken in another order than from both ends (round-off).
   Adds to f and sets the tallies f_hg (HG 1) and f_visc. MULTI 0: one
   material (its averages are the values themselves). */
template <int DIM, int ORDER, int HG, int VISC, int MULTI, int W, class Slots>
TLSPH_FORCE_INLINE void ell_force_stencil(const Slots &sl, int first, int h,
                                          const EllParticles &p)
{
  using V = typename EllVecOf<W>::type;
  using S = EllShape<DIM>;
  using L = Packed<DIM, ORDER>;
  constexpr int NB = L::NB;
  constexpr int C = W;
  const double inv_h = 1.0 / p.h;
  const double eps2 = 0.01 * p.h * p.h;
  const long ns = p.ns, i0 = (long) first + h;
  const double *xs = p.xs, *vs = p.vs, *x0s = p.x0s, *pks = p.pks;
  double *pv_col = p.pcol, *ph_col = p.pcol + DIM * ns;

  // a later chunk's own columns, and those at the partners' leading edge
  {
    const long io = i0 + ELL_PREFETCH;
    ell_prefetch<0>(xs, DIM, ns, io);
    ell_prefetch<0>(vs, DIM, ns, io);
    ell_prefetch<0>(x0s, DIM, ns, io);
    ell_prefetch<0>(p.fcol, DIM, ns, io);
    ell_prefetch<0>(pks, L::R, ns, io);
    ell_prefetch<1>(pv_col, 2 * DIM, ns, io);
    ell_prefetch<0>(p.vcol, 1, ns, io);
    if (sl.n > 0) {
      const long je = sl.j0(sl.n - 1) + h + ELL_PREFETCH;
      ell_prefetch<0>(xs, DIM, ns, je);
      ell_prefetch<0>(vs, DIM, ns, je);
      ell_prefetch<0>(x0s, DIM, ns, je);
      ell_prefetch<0>(pks, L::size, ns, je);
      ell_prefetch<1>(pv_col, 2 * DIM, ns, je);
    }
  }
  V x0i[DIM], as[DIM];
  for (int d = 0; d < DIM; d++) x0i[d] = ell_load<V>(x0s + d * ns + i0), as[d] = V{};
  // the stress term, every bond
  for (int m = 0; m < sl.n; m++) {
    const long j0 = sl.j0(m) + h;
    V s3[3] = {V{}, V{}, V{}}, pb[NB];
    for (int d = 0; d < DIM; d++) s3[d] = (x0i[d] - ell_load<V>(x0s + d * ns + j0)) * inv_h;
    Basis<DIM, ORDER>::eval(s3, pb);
    const V cm = sl.template val<V>(m, S::CREV, h);
    for (int r = 0; r < DIM; r++) {
      V acc = V{};
      for (int k = 0; k < NB; k++) acc += ell_load<V>(pks + (L::R + NB * r + k) * ns + j0) * pb[k];
      as[r] -= cm * acc;
    }
  }

  // the pair forces, once per bond (the slots of later partners)
  V av[DIM], ah[DIM];
  for (int d = 0; d < DIM; d++) av[d] = ah[d] = V{};
  if (HG || VISC) {
    V xi[DIM], vi[DIM], Fi[DIM * DIM], Ki[DIM * DIM];
    for (int d = 0; d < DIM; d++) {
      xi[d] = ell_load<V>(xs + d * ns + i0);
      vi[d] = ell_load<V>(vs + d * ns + i0);
    }
    for (int k = 0; k < DIM * DIM; k++) {
      Fi[k] = ell_load<V>(pks + (L::F + k) * ns + i0);
      Ki[k] = ell_load<V>(pks + (L::K + k) * ns + i0);
    }
    const V ai = ell_load<V>(pks + L::A * ns + i0);
    double tc[C], tr[C], tE[C];
    for (int l = 0; l < C; l++) {
      const int il = p.perm[i0 + l];
      const PairMaterial &mi = p.pm[p.type[MULTI ? il : p.perm[first]]];
      tc[l] = mi.c0, tr[l] = mi.rho, tE[l] = mi.E;
    }
    const V Vi = ell_load<V>(p.vcol + i0), c0i = ell_load<V>(tc), rhoi = ell_load<V>(tr),
            Ei = ell_load<V>(tE);
    for (int m = 0; m < sl.n; m++) {
      if (sl.j0(m) < first) continue;    // an earlier partner computed this bond
      const long j0 = sl.j0(m) + h;
      V X[DIM], xij[DIM], r2 = V{};
      for (int d = 0; d < DIM; d++) {
        X[d] = ell_load<V>(x0s + d * ns + j0) - x0i[d];
        xij[d] = ell_load<V>(xs + d * ns + j0) - xi[d];
        r2 += xij[d] * xij[d];
      }
      const V r2s = r2 > V{} ? r2 : ell_splat<V>(1.0);
      const V inv_both = 1.0 / (r2s * (r2s + eps2));
      V c0j = c0i, rhoj = rhoi, Ej = Ei;
      if (MULTI) {
        for (int l = 0; l < C; l++) {
          const PairMaterial &mj = p.pm[p.type[p.perm[j0 + l]]];
          tc[l] = mj.c0, tr[l] = mj.rho, tE[l] = mj.E;
        }
        c0j = ell_load<V>(tc), rhoj = ell_load<V>(tr), Ej = ell_load<V>(tE);
      }
      if (VISC) {
        V vj[DIM];
        for (int d = 0; d < DIM; d++) vj[d] = ell_load<V>(vs + d * ns + j0);
        const V sv = viscous_coefficient<DIM>(
            vi, vj, xij, r2, inv_both, p.h, p.beta, 0.5 * (ai + ell_load<V>(pks + L::A * ns + j0)),
            V(0.5 * (c0i + c0j)), V(0.5 * (rhoi + rhoj)), V(Vi * sl.template val<V>(m, S::WV, h)));
        for (int r = 0; r < DIM; r++) {
          V acc = V{};
          for (int k = 0; k < DIM; k++)
            acc += (Ki[DIM * r + k] + ell_load<V>(pks + (L::K + DIM * r + k) * ns + j0)) * X[k];
          const V pv = sv * acc;
          av[r] += pv;
          double *q = pv_col + r * ns + j0;
          const V qj = ell_load<V>(q) - pv;
          __builtin_memcpy(q, &qj, sizeof(V));
        }
      }
      if (HG) {
        V Fj[DIM * DIM], ph[DIM];
        for (int k = 0; k < DIM * DIM; k++) Fj[k] = ell_load<V>(pks + (L::F + k) * ns + j0);
        hourglass_pair<DIM, HG, false>(Fi, Fj, X, xij, r2, eps2, inv_both,
                                       V(p.gamma * 0.5 * (Ei + Ej)),
                                       V(Vi * sl.template val<V>(m, S::WHG, h)), ph);
        for (int d = 0; d < DIM; d++) {
          ah[d] += ph[d];
          double *q = ph_col + d * ns + j0;
          const V qj = ell_load<V>(q) - ph[d];
          __builtin_memcpy(q, &qj, sizeof(V));
        }
      }
    }
  }

  // what the earlier partners left in the accumulators
  for (int d = 0; d < DIM; d++) {
    if (VISC) av[d] += ell_load<V>(pv_col + d * ns + i0);
    if (HG) ah[d] += ell_load<V>(ph_col + d * ns + i0);
  }
  for (int l = 0; l < C; l++) {
    const long i = p.perm[i0 + l];
    for (int r = 0; r < DIM; r++) {
      const double fs = p.fcol[r * ns + i0 + l] + as[r][l];
      p.f[3 * i + r] += fs + av[r][l] + ah[r][l];
      if (HG != 2 && p.f_hg) p.f_hg[3 * i + r] = ah[r][l];
      p.f_visc[3 * i + r] = av[r][l];
    }
    for (int r = DIM; r < 3; r++) {
      if (HG != 2 && p.f_hg) p.f_hg[3 * i + r] = 0.0;
      p.f_visc[3 * i + r] = 0.0;
    }
  }
}
#else
#define TLSPH_ELL_VEC 0
#endif

}    // namespace TLSPH

#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#endif
