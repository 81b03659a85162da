/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: the SIMD step of pair_style tlsph (doc/pair_tlsph.rst,
   "SIMD"): the bond cache in a sliced-ELLPACK layout and the two bond
   loops of the step over chunks of C particles, one particle per SIMD lane.

   Layout. Local particles are taken in chunks of C = ELL_C consecutive
   indices (the last chunk padded). A chunk c has w_c slot blocks, w_c the
   largest bond count of its particles; block b (start[c] <= b < start[c+1])
   holds slot m = b - start[c] of the C particles of the chunk:
     j[C b + l]                 partner of particle c C + l in slot m
     v[NV C b + C k + l]        k = 0..DIM-1: corrected gradient g_ij (k-th
                                component); DIM: wv, DIM + 1: whg (the
                                viscous and hourglass weights, TLSPH::Bond);
                                DIM + 2: the reverse weight c_ij = V_i w_ij
   so that a slot of the C lanes is one vector load per quantity. A padded
   slot (its particle has fewer bonds, or there is no particle) points at
   the lane's own particle with all weights zero: it adds exactly zero (its
   separation is zero, which the pair terms below treat as no pair).

   Force pass: the gather form (each particle sums its whole force from its
   own bonds, reading the partners' packed rows with R = V P Q; no scatter,
   no reverse communication; the form of newton_pair off and of the Kokkos
   kernels), in the same operations and order as particle_force_bonds
   (tlsph_particle.h) with SCATTER off, whose pair-term functions it calls:
   one copy of the math. The lane loops are written for the compiler's
   vectoriser (pair_tlsph_simd.cpp compiles them for AVX-512, AVX2 + FMA and
   the portable baseline and picks one at run time). With FMA the results
   differ from the scalar path by round-off only.
------------------------------------------------------------------------- */

#ifndef TLSPH_ELL_H
#define TLSPH_ELL_H

#include "tlsph_particle.h"

namespace TLSPH {

constexpr int ELL_C = 8;    // lanes per chunk: 8 doubles = one AVX-512 vector, two AVX2

template <int DIM> struct EllShape {
  static constexpr int NV = DIM + 3;     // doubles per slot and lane
  static constexpr int WV = DIM;         // offsets of the weights in a slot block
  static constexpr int WHG = DIM + 1;
  static constexpr int CREV = DIM + 2;
};

// the layout (see above); the arrays are owned by the pair style
struct EllArrays {
  int nchunk = 0;
  int *start = nullptr;    // nchunk + 1 slot-block offsets
  int *j = nullptr;        // C per block (particle indices of the SIMD order, below)
  double *v = nullptr;     // NV C per block
  int *kind = nullptr;     // per chunk: GATHER, STENCIL or PATTERN (below)
  // patterns: the stencil chunks whose slots carry the same values in every
  // lane (a lattice interior: translated copies of one neighbourhood) keep
  // no blocks; slot m of pattern q (pat_start[q] <= m < pat_start[q + 1])
  // has partners i0 + pat_off[m] + l and the NV values pat_v[NV m ..]
  int *pat = nullptr;      // per chunk: its pattern (PATTERN chunks)
  int npat = 0;
  int *pat_start = nullptr;
  int *pat_off = nullptr;
  double *pat_v = nullptr;
  enum { GATHER = 0, STENCIL = 1, PATTERN = 2 };
};

/* Particle data of the SIMD step as structure of arrays, in the step's own
   order (PairTLSPH::build_ell): local particles first, sorted by their
   reference position (rows of a lattice become runs of consecutive
   indices), then the ghosts, sorted the same way. Column k of a quantity
   is base + k ns. In a lattice interior the partners of the C particles of
   a chunk are then, slot by slot, C consecutive indices (a "stencil"
   chunk): the lanes load them with one contiguous vector load instead of a
   gather; and where the chunk's bonds are the same in every lane, they are
   read from a pattern shared by all such chunks (EllArrays), so that the
   pass streams no bond data at all. perm maps the order to LAMMPS's
   particle index. */
struct EllParticles {
  int ns;                // column length (>= local + ghost particles)
  const double *xs;      // DIM columns: x
  const double *vs;      // DIM columns: v
  const double *x0s;     // DIM columns: x0c (PairTLSPH::x0c)
  const double *pks;     // packed rows as columns (TLSPH::Packed, with R)
  const int *perm;       // SIMD order -> LAMMPS index
  const double *vfrac;   // by LAMMPS index, as the rest below
  const double *fown;    // 3 per atom: V_i P_i s_i
  const int *type;
  const PairMaterial *pm;
  double *f;             // 3 per atom
  double *f_hg, *f_visc; // 3 per atom (the bond fix's tallies); f_hg may be null
  int nlocal;
  double h, beta, gamma;
};

/* pass (1), the bond part: F_i = I + sum_j (u_j - u_i) (x) g_ij for the
   particles of chunk c (deformation_gradient_bonds); F: 9 per atom, by
   LAMMPS index */
template <int DIM, int STENCIL>
TLSPH_FORCE_INLINE void ell_deformation_chunk(const EllArrays &e, int c, const EllParticles &p,
                                              double *F)
{
  using S = EllShape<DIM>;
  constexpr int C = ELL_C;
  const int ns = p.ns, nlocal = p.nlocal;
  const double *xs = p.xs, *x0s = p.x0s;
  double xi[DIM][C], x0i[DIM][C], Fa[DIM * DIM][C];
  for (int l = 0; l < C; l++) {
    const int i = c * C + l < nlocal ? c * C + l : nlocal - 1;
    for (int d = 0; d < DIM; d++) xi[d][l] = xs[d * ns + i], x0i[d][l] = x0s[d * ns + i];
    for (int k = 0; k < DIM * DIM; k++) Fa[k][l] = 0.0;
  }
  for (int b = e.start[c]; b < e.start[c + 1]; b++) {
    const int *jb = e.j + (long) C * b;
    const double *vb = e.v + (long) S::NV * C * b;
    // a stencil slot: lane l reads index j[0] + l (base pointers moved by
    // j[0], so that the compiler sees contiguous loads, not gathers)
    const long jbase = STENCIL ? jb[0] : 0;
    const double *xb = xs + jbase, *x0b = x0s + jbase;
#pragma GCC ivdep
#pragma GCC unroll 1
    for (int l = 0; l < C; l++) {
      const int j = STENCIL ? l : jb[l];
      double du[DIM];
      for (int d = 0; d < DIM; d++)
        du[d] = (xb[d * ns + j] - xi[d][l]) - (x0b[d * ns + j] - x0i[d][l]);
      for (int r = 0; r < DIM; r++)
        for (int k = 0; k < DIM; k++) Fa[DIM * r + k][l] += du[r] * vb[C * k + l];
    }
  }
  for (int l = 0; l < C && c * C + l < nlocal; l++) {
    // I + Fa, each entry written once (as mat_identity then +=, the same values)
    double *Fi = F + 9 * (long) p.perm[c * C + l];
    for (int r = 0; r < 3; r++)
      for (int k = 0; k < 3; k++)
        Fi[3 * r + k] = (r < DIM && k < DIM) ? (r == k ? 1.0 : 0.0) + Fa[DIM * r + k][l]
                                             : (r == k ? 1.0 : 0.0);
  }
}

/* pass (3), gather form, for the particles of chunk c: the stress term
   - sum_j c_ij R_j p(-X_ij/h), the viscous and (HG 1, 2) hourglass pair
   forces from this end, plus fown; adds to f and sets the tallies f_hg
   (HG 1) and f_visc. MULTI 0: one material (pm[type of the first
   particle] for every pair; its averages are the values themselves). */
template <int DIM, int ORDER, int HG, int VISC, int MULTI, int STENCIL>
TLSPH_FORCE_INLINE void ell_force_chunk(const EllArrays &e, int c, const EllParticles &p)
{
  using S = EllShape<DIM>;
  using L = Packed<DIM, ORDER>;
  constexpr int NB = L::NB;
  constexpr int C = ELL_C;
  const double inv_h = 1.0 / p.h;
  const double eps2 = 0.01 * p.h * p.h;
  const int nlocal = p.nlocal, ns = p.ns;
  const double *xs = p.xs, *vs = p.vs, *x0s = p.x0s, *pks = p.pks;

  double xi[DIM][C], vi[DIM][C], x0i[DIM][C], Fi[DIM * DIM][C], Ki[DIM * DIM][C], ai[C], Vi[C];
  double c0i[C], rhoi[C], Ei[C];
  double as[DIM][C], av[DIM][C], avi[DIM][C], ah[DIM][C];
  const PairMaterial m0 = p.pm[p.type[p.perm[c * C]]];
  for (int l = 0; l < C; l++) {
    const int i = c * C + l < nlocal ? c * C + l : nlocal - 1;
    for (int d = 0; d < DIM; d++) {
      xi[d][l] = xs[d * ns + i], vi[d][l] = vs[d * ns + i], x0i[d][l] = x0s[d * ns + i];
      as[d][l] = av[d][l] = avi[d][l] = ah[d][l] = 0.0;
    }
    for (int k = 0; k < DIM * DIM; k++)
      Fi[k][l] = pks[(L::F + k) * ns + i], Ki[k][l] = pks[(L::K + k) * ns + i];
    ai[l] = pks[L::A * ns + i];
    const int il = p.perm[i];
    Vi[l] = p.vfrac[il];
    const PairMaterial mi = MULTI ? p.pm[p.type[il]] : m0;
    c0i[l] = mi.c0, rhoi[l] = mi.rho, Ei[l] = mi.E;
  }

  for (int b = e.start[c]; b < e.start[c + 1]; b++) {
    const int *jb = e.j + (long) C * b;
    const double *vb = e.v + (long) S::NV * C * b;
    const long jbase = STENCIL ? jb[0] : 0;    // (see ell_deformation_chunk)
    const double *xb = xs + jbase, *vb_ = vs + jbase, *x0b = x0s + jbase, *pkb = pks + jbase;
#pragma GCC ivdep
#pragma GCC unroll 1
    for (int l = 0; l < C; l++) {
      const int j = STENCIL ? l : jb[l];
      double X[DIM];
      for (int d = 0; d < DIM; d++) X[d] = x0b[d * ns + j] - x0i[d][l];
      // stress term: - c_ij R_j p(-X_ij/h)
      {
        double s[3] = {0.0, 0.0, 0.0}, pb[NB];
        for (int d = 0; d < DIM; d++) s[d] = -X[d] * inv_h;
        Basis<DIM, ORDER>::eval(s, pb);
        const double cm = vb[C * S::CREV + l];
        for (int r = 0; r < DIM; r++) {
          double acc = 0.0;
          for (int k = 0; k < NB; k++) acc += pkb[(L::R + NB * r + k) * ns + j] * pb[k];
          as[r][l] -= cm * acc;
        }
      }
      if (!(HG || VISC)) continue;
      // pair_separation, with a padded slot (j = i, r2 = 0) made harmless
      // before the division (a division after a branch is not vectorised):
      // r2 = 0 makes both pair terms zero (the scalar path never sees it)
      double xij[3] = {0.0, 0.0, 0.0}, r2 = 0.0;
      for (int d = 0; d < DIM; d++) {
        xij[d] = xb[d * ns + j] - xi[d][l];
        r2 += xij[d] * xij[d];
      }
      const double r2s = r2 > 0.0 ? r2 : 1.0;
      const double inv_both = 1.0 / (r2s * (r2s + eps2));
      double c0j = c0i[l], rhoj = rhoi[l], Ej = Ei[l];
      if (MULTI) {
        const PairMaterial &mj = p.pm[p.type[p.perm[jbase + j]]];
        c0j = mj.c0, rhoj = mj.rho, Ej = mj.E;
      }
      if (VISC) {
        double vil[DIM], vj[DIM];
        for (int d = 0; d < DIM; d++) vil[d] = vi[d][l], vj[d] = vb_[d * ns + j];
        const double sv = viscous_coefficient<DIM>(
            vil, vj, xij, r2, inv_both, p.h, p.beta, 0.5 * (ai[l] + pkb[L::A * ns + j]),
            0.5 * (c0i[l] + c0j), 0.5 * (rhoi[l] + rhoj), Vi[l] * vb[C * S::WV + l]);
        for (int d = 0; d < DIM; d++) avi[d][l] += sv * X[d];
        for (int r = 0; r < DIM; r++) {
          double acc = 0.0;
          for (int k = 0; k < DIM; k++) acc += pkb[(L::K + DIM * r + k) * ns + j] * X[k];
          av[r][l] += sv * acc;
        }
      }
      if (HG) {
        double Fil[DIM * DIM], Fj[DIM * DIM], ph[DIM];
        for (int k = 0; k < DIM * DIM; k++) Fil[k] = Fi[k][l], Fj[k] = pkb[(L::F + k) * ns + j];
        hourglass_pair<DIM, HG, false>(Fil, Fj, X, xij, r2, eps2, inv_both,
                                       p.gamma * 0.5 * (Ei[l] + Ej),
                                       Vi[l] * vb[C * S::WHG + l], ph);
        for (int d = 0; d < DIM; d++) ah[d][l] += ph[d];
      }
    }
  }

  for (int l = 0; l < C && c * C + l < nlocal; l++) {
    const long i = p.perm[c * C + l];
    for (int r = 0; r < DIM; r++) {
      const double fs = p.fown[3 * i + r] + as[r][l];
      double fv = av[r][l];
      if (VISC)
        for (int k = 0; k < DIM; k++) fv += Ki[DIM * r + k][l] * avi[k][l];
      const double fh = ah[r][l];
      p.f[3 * i + r] += fs + fv + fh;
      if (HG != 2 && p.f_hg) p.f_hg[3 * i + r] = fh;
      p.f_visc[3 * i + r] = fv;
    }
    for (int r = DIM; r < 3; r++) {
      if (HG != 2 && p.f_hg) p.f_hg[3 * i + r] = 0.0;
      p.f_visc[3 * i + r] = 0.0;
    }
  }
}


}    // namespace TLSPH

#endif
