/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: the SIMD step of pair_style tlsph (doc/pair_tlsph.rst,
   "SIMD"): the bond cache in a sliced-ELLPACK layout and the two bond
   loops of the step over chunks of up to C particles, one per SIMD lane.

   Order and chunks. The step keeps its particle data as columns in its own
   order (EllParticles): local particles sorted by reference position, then
   the ghosts, sorted the same way (PairTLSPH::sort_axes: the axis across
   which the rank has its ghosts first), so that a row of a lattice is a run of
   consecutive indices. A chunk is a run of up to C consecutive local
   particles whose bonds have the same partner offsets (partner index minus
   own index, slot by slot, bonds sorted by partner): in slot m, lane l
   reads partner j0(m) + l, so that every quantity of a slot is one
   contiguous vector load (no gathers). A particle whose neighbourhood no
   neighbour shares is a chunk of one.
   Layout: chunk c (lanes first[c] .. first[c] + n[c] - 1, w_c = width[c]
   slots) has blocks start[c] <= b < start[c] + w_c, block b holding slot
   m = b - start[c] (in chunk order, except the chunks that tlsph/damage
   re-lays behind the others when a bond of theirs breaks):
     j[C b]                     partner of lane 0 minus first[c] (the
                                slot's offset; lane l's partner is
                                first[c] + l + j[C b])
     v[NV C b + C k + l]        k = 0..DIM-1: corrected gradient g_ij (k-th
                                component); DIM: wv, DIM + 1: whg (the
                                viscous and hourglass weights, TLSPH::Bond);
                                DIM + 2: the reverse weight c_ij = V_i w_ij
   A chunk whose values are also the same in every lane (a lattice
   interior: translated copies of one neighbourhood) keeps no blocks: it
   reads a pattern shared by all such chunks. Chunks whose offsets and
   values, lane by lane, are those of another chunk (the ends of a
   lattice's rows: translated copies of one row end) read that chunk's
   blocks (shared[c] = 1 for all of them: tlsph/damage gives such a chunk
   blocks of its own before it changes a lane).

   Force pass: the stress term in the gather form (each particle sums it
   from its own bonds, reading the partners' packed rows with R = V P Q),
   the viscous and hourglass pair forces once per bond, by the particle
   that comes first in the step's order, which subtracts them from its
   partner's accumulator (a contiguous vector per slot; a ghost partner's
   end is computed by its owner, so there is no reverse communication);
   the pair terms are the templates of particle_force_bonds
   (tlsph_particle.h) called with a vector type (tlsph_ell_vec.h): one
   copy of the math. pair_tlsph_simd.cpp compiles the kernels for
   AVX-512, AVX2 + FMA and the portable baseline and picks one at run
   time. With FMA and the bonds summed by partner the results differ from
   the scalar path by round-off.
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
  int *first = nullptr;    // per chunk: its first particle (the step's order)
  int *n = nullptr;        // per chunk: its particles (1 .. C)
  int *start = nullptr;    // per chunk: its first slot block
  int *width = nullptr;    // per chunk: its slots (blocks; a PATTERN chunk: its pattern's)
  int *j = nullptr;        // C per block (lane 0's partner first)
  double *v = nullptr;     // NV C per block
  int *kind = nullptr;     // per chunk: STENCIL (its blocks) or PATTERN
  int *shared = nullptr;   // per chunk: 1 if other chunks read its blocks too
  // patterns: slot m of pattern q (pat_start[q] <= m < pat_start[q + 1])
  // has partners i0 + pat_off[m] + l and the NV values pat_v[NV m ..]
  int *pat = nullptr;      // per chunk: its pattern (PATTERN chunks)
  int npat = 0;
  int *pat_start = nullptr;
  int *pat_off = nullptr;
  double *pat_v = nullptr;
  enum { STENCIL = 0, PATTERN = 1 };
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
  const double *qcol;    // correction Q (DIM x basis size columns), local particles
  const double *scol;    // s_i = sum_j g_ij (DIM columns)
  const double *vcol;    // V_i
  double *fcol;          // V_i P_i s_i (DIM columns), written by pass (1)
  double *pcol;          // pass (3): the viscous, then the hourglass pair forces
                         // that earlier partners left (DIM columns each)
  const int *perm;       // SIMD order -> LAMMPS index
  const int *type;       // by LAMMPS index, as the rest below
  const PairMaterial *pm;
  double *f;             // 3 per atom
  double *f_hg, *f_visc; // 3 per atom (the bond fix's tallies); f_hg may be null
  int nlocal;
  double h, beta, gamma;
};

/* The stretch screen of tlsph/damage in pass (1) of the SIMD step: a lane
   whose bond has r^2 >= up r0^2 or, with down > 0, r^2 <= down r0^2 is
   appended to list (its LAMMPS index; the caller sizes list for every local
   particle). A slot is taken for a bond when its reverse weight is not zero
   (padded and broken slots have zero weights) or, when the bond family
   reaches beyond the kernel support (whose bonds there have zero weights
   too), when r0^2 < reach2 (0: no such bonds); a padded or broken slot
   taken so only costs the exact test of its particle. A step may screen
   only the chunks that PairTLSPH::simd_deformation cannot prove safe
   (need), and record the margins of those it screens (worst). */
struct EllScreen {
  double up, down, reach2;
  int *list;
  int n;
  // which chunks to screen (null: all), and (non-null) the largest
  // r^2 - up r0^2 (or down r0^2 - r^2) of each screened chunk's bonds
  const char *need = nullptr;
  double *worst = nullptr;
  double piece = 0.0;    // set by a screened piece: the largest of its lanes
};

}    // namespace TLSPH

#endif
