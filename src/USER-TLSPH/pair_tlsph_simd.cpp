/* ----------------------------------------------------------------------
   USER-TLSPH: the SIMD step of pair_style tlsph (tlsph_ell.h): the
   sliced-ELLPACK bond layout, built after every bond-cache build, and the
   drivers of its two bond loops, compiled for AVX-512, for AVX2 + FMA and
   for the build's own baseline (portable); the one to run is chosen at
   init from the CPU (pair_style ... simd auto) or by the user.
------------------------------------------------------------------------- */

// the vector types of tlsph_ell_vec.h pass by value only between functions
// that are always inlined (a function taking one out of line would be
// compiled for the baseline and called from AVX code with another ABI);
// GCC's note on that ABI (-Wpsabi) is about calls that do not exist then
#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

#include "pair_tlsph.h"

#include "atom.h"
#include "atom_vec.h"
#include "domain.h"
#include "comm.h"
#include "error.h"
#include "fix_tlsph_bonds.h"
#include "force.h"
#include "memory.h"
#include "pair_tlsph_step.h"
#include "tlsph_ell_vec.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>
#include <map>
#include <string>
#include <utility>
#include <vector>

using namespace LAMMPS_NS;

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(__CUDACC__)
#define TLSPH_ELL_X86 1
#define TLSPH_ATTR_AVX2 __attribute__((target("avx2,fma,tune=haswell")))
#define TLSPH_ATTR_AVX512 \
  __attribute__((target("avx512f,avx512vl,avx512dq,avx2,fma,tune=skylake-avx512,prefer-vector-width=512")))
#else
#define TLSPH_ELL_X86 0
#endif

namespace {
/* Bond values of a stencil chunk's lanes (and of two chunks) that agree to
   this fraction of the quantity's largest magnitude in the chunk are one
   pattern. On a lattice they differ only by the round-off of each
   particle's gradient-correction solve (its sums taken in another order:
   measured up to 1e-13 on the bench blocks), so sharing one particle's
   values changes the step by round-off. */
constexpr double ELL_SHARE_TOL = 1.0e-13;
/* A chunk's slots are the union of its particles' partner offsets; it takes
   no further particle once that union would exceed this factor times the
   largest bond count among them (the lanes' zero-weight slots are work
   without use; a particle left alone runs in a vector of one lane). */
constexpr double ELL_UNION_SLACK = 1.25;
/* A chunk is compared with at most this many earlier ones of the same
   offsets (the first found: on a lattice the few kinds of neighbourhood),
   so that a particle set whose chunks share offsets but not values does not
   make build_ell quadratic in the chunks. */
constexpr size_t ELL_SHARE_CANDIDATES = 16;
using TLSPH::EllArrays;
using TLSPH::EllParticles;
using DeformFn = void (*)(const EllArrays &, const EllParticles &, double *, TLSPH::EllStress *,
                          TLSPH::EllScreen *);
using ForceFn = void (*)(const EllArrays &, const EllParticles &);

#if TLSPH_ELL_VEC
// a chunk's n lanes in vectors of 8, 4, 2 and 1 lanes (the widest first,
// at most the instruction set's width)
#define TLSPH_ELL_PIECES8(n, CALL)                                                           \
  {                                                                                          \
    int h = 0;                                                                               \
    for (; h + 8 <= (n); h += 8) CALL(8);                                                    \
    if (h + 4 <= (n)) { CALL(4); h += 4; }                                                   \
    if (h + 2 <= (n)) { CALL(2); h += 2; }                                                   \
    if (h < (n)) CALL(1);                                                                    \
  }
#define TLSPH_ELL_PIECES4(n, CALL)                                                           \
  {                                                                                          \
    int h = 0;                                                                               \
    for (; h + 4 <= (n); h += 4) CALL(4);                                                    \
    if (h + 2 <= (n)) { CALL(2); h += 2; }                                                   \
    if (h < (n)) CALL(1);                                                                    \
  }
#define TLSPH_ELL_PIECES2(n, CALL)                                                           \
  {                                                                                          \
    int h = 0;                                                                               \
    for (; h + 2 <= (n); h += 2) CALL(2);                                                    \
    if (h < (n)) CALL(1);                                                                    \
  }

// every chunk, in order, its lanes in PIECES of vector widths, each piece a CALL
// chunk c's lanes in PIECES of vector widths, each piece a CALL
#define TLSPH_ELL_CHUNK(c, PIECES, CALL)                                                     \
  {                                                                                          \
    const int first = e.first[c], n = e.n[c];                                                \
    if (e.kind[c] == EllArrays::PATTERN) {                                                   \
      const auto sl = TLSPH::pattern_slots<DIM>(e, c);                                       \
      PIECES(n, CALL)                                                                        \
    } else {                                                                                 \
      const auto sl = TLSPH::lane_slots<DIM>(e, c);                                          \
      PIECES(n, CALL)                                                                        \
    }                                                                                        \
  }
// every chunk, in order
#define TLSPH_ELL_CHUNKS(PIECES, CALL)                                                       \
  for (int c = 0; c < e.nchunk; c++) TLSPH_ELL_CHUNK(c, PIECES, CALL)
// the drivers (one copy per instruction set)
#define TLSPH_ELL_DRIVERS(NS, ATTR, PIECES)                                                  \
  namespace NS {                                                                             \
  template <int DIM, int ORDER, int SCREEN>                                                  \
  ATTR void deformation(const EllArrays &e, const EllParticles &p, double *F,               \
                        TLSPH::EllStress *st, TLSPH::EllScreen *scr)                         \
  {                                                                                          \
    if (!SCREEN || !scr->need) {                                                             \
      TLSPH_ELL_CHUNKS(PIECES, ELL_D)                                                        \
      return;                                                                                \
    }                                                                                        \
    /* the screen where need says so, the plain pass elsewhere */                           \
    for (int c = 0; c < e.nchunk; c++) {                                                     \
      if (scr->need[c]) {                                                                    \
        double cw = -1.0e300;                                                                \
        TLSPH_ELL_CHUNK(c, PIECES, ELL_DW)                                                   \
        if (scr->worst) scr->worst[c] = cw;                                                  \
      } else                                                                                 \
        TLSPH_ELL_CHUNK(c, PIECES, ELL_D0)                                                   \
    }                                                                                        \
  }                                                                                          \
  template <int DIM, int ORDER, int HG, int VISC, int MULTI>                                 \
  ATTR void forces(const EllArrays &e, const EllParticles &p)                               \
  {                                                                                          \
    TLSPH_ELL_CHUNKS(PIECES, ELL_F)                                                          \
  }                                                                                          \
  }
#define ELL_D(w) TLSPH::ell_deformation_stencil<DIM, ORDER, SCREEN, w>(sl, first, h, p, F, st, scr)
#define ELL_D0(w) TLSPH::ell_deformation_stencil<DIM, ORDER, 0, w>(sl, first, h, p, F, st, scr)
#define ELL_DW(w)                                                                            \
  {                                                                                          \
    ELL_D(w);                                                                                \
    cw = scr->piece > cw ? scr->piece : cw;                                                  \
  }
#define ELL_F(w) TLSPH::ell_force_stencil<DIM, ORDER, HG, VISC, MULTI, w>(sl, first, h, p)

TLSPH_ELL_DRIVERS(ell_portable, , TLSPH_ELL_PIECES2)
#if TLSPH_ELL_X86
TLSPH_ELL_DRIVERS(ell_avx2, TLSPH_ATTR_AVX2, TLSPH_ELL_PIECES4)
TLSPH_ELL_DRIVERS(ell_avx512, TLSPH_ATTR_AVX512, TLSPH_ELL_PIECES8)
#endif

template <int DIM, int ORDER, int SCREEN> DeformFn pick_deformation_screen(int isa)
{
#if TLSPH_ELL_X86
  if (isa == PairTLSPH::SIMD_AVX512) return ell_avx512::deformation<DIM, ORDER, SCREEN>;
  if (isa == PairTLSPH::SIMD_AVX2) return ell_avx2::deformation<DIM, ORDER, SCREEN>;
#endif
  (void) isa;
  return ell_portable::deformation<DIM, ORDER, SCREEN>;
}

// screen: 0 none, 1 the upper stretch limit, 2 both limits
template <int DIM, int ORDER> DeformFn pick_deformation(int isa, int screen)
{
  if (screen == 2) return pick_deformation_screen<DIM, ORDER, 2>(isa);
  if (screen == 1) return pick_deformation_screen<DIM, ORDER, 1>(isa);
  return pick_deformation_screen<DIM, ORDER, 0>(isa);
}

template <int DIM, int ORDER, int HG, int VISC, int MULTI> ForceFn pick_forces(int isa)
{
#if TLSPH_ELL_X86
  if (isa == PairTLSPH::SIMD_AVX512) return ell_avx512::forces<DIM, ORDER, HG, VISC, MULTI>;
  if (isa == PairTLSPH::SIMD_AVX2) return ell_avx2::forces<DIM, ORDER, HG, VISC, MULTI>;
#endif
  (void) isa;
  return ell_portable::forces<DIM, ORDER, HG, VISC, MULTI>;
}

template <int DIM, int ORDER, int HG, int VISC>
ForceFn pick_forces_multi(int isa, int multi)
{
  return multi ? pick_forces<DIM, ORDER, HG, VISC, 1>(isa)
               : pick_forces<DIM, ORDER, HG, VISC, 0>(isa);
}

template <int DIM, int ORDER, int HG>
ForceFn pick_forces_visc(int isa, int visc, int multi)
{
  return visc ? pick_forces_multi<DIM, ORDER, HG, 1>(isa, multi)
              : pick_forces_multi<DIM, ORDER, HG, 0>(isa, multi);
}

template <int DIM, int ORDER> ForceFn pick_forces_hg(int isa, int hg, int visc, int multi)
{
  if (hg == 1) return pick_forces_visc<DIM, ORDER, 1>(isa, visc, multi);
  if (hg == 2) return pick_forces_visc<DIM, ORDER, 2>(isa, visc, multi);
  return pick_forces_visc<DIM, ORDER, 0>(isa, visc, multi);
}
#endif    // TLSPH_ELL_VEC
}    // namespace

/* ---------------------------------------------------------------------- */

const char *PairTLSPH::simd_name(int isa)
{
  switch (isa) {
    case SIMD_NO: return "no";
    case SIMD_PORTABLE: return "portable";
    case SIMD_AVX2: return "avx2";
    case SIMD_AVX512: return "avx512";
    default: return "auto";
  }
}

int PairTLSPH::simd_value(const char *word)
{
  for (int isa : {SIMD_AUTO, SIMD_NO, SIMD_PORTABLE, SIMD_AVX2, SIMD_AVX512})
    if (strcmp(word, simd_name(isa)) == 0) return isa;
  return SIMD_INVALID;
}

// what this CPU can run of the compiled instruction sets
bool PairTLSPH::simd_supported(int isa)
{
  if (isa == SIMD_NO) return true;
#if !TLSPH_ELL_VEC
  return false;    // a compiler without GCC's vector extension (or CUDA): the scalar step
#endif
  if (isa == SIMD_PORTABLE) return true;
#if TLSPH_ELL_X86
  __builtin_cpu_init();
  if (isa == SIMD_AVX2) return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  if (isa == SIMD_AVX512)
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
        __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx2") &&
        __builtin_cpu_supports("fma");
#endif
  return false;
}

/* the instruction set of the step (init_style): the user's choice, checked
   against the CPU, or for 'auto' the widest this CPU runs; SIMD_NO for the
   styles that do not have the SIMD step (simd_capable) */
void PairTLSPH::select_simd()
{
  simd_isa = SIMD_NO;
  if (simd_request == SIMD_NO) return;
  if (!simd_capable()) {
    if (simd_request != SIMD_AUTO)
      error->all(FLERR, "pair_style {}: simd {} is not available for this style (only "
                        "pair_style tlsph and tlsph/damage have the SIMD step; allowed here: simd auto, "
                        "simd no)",
                 force->pair_style, simd_name(simd_request));
    return;
  }
  if (simd_request == SIMD_AUTO) {
    simd_isa = simd_supported(SIMD_AVX512) ? SIMD_AVX512
        : simd_supported(SIMD_AVX2)        ? SIMD_AVX2
        : simd_supported(SIMD_PORTABLE)    ? SIMD_PORTABLE
                                           : SIMD_NO;
    return;
  }
  if (!simd_supported(simd_request))
    error->all(FLERR, "pair_style tlsph: simd {}: this CPU (or this build) does not support it "
                      "(allowed: simd auto, no, portable{}{})", simd_name(simd_request),
               simd_supported(SIMD_AVX2) ? ", avx2" : "", simd_supported(SIMD_AVX512) ? ", avx512" : "");
  simd_isa = simd_request;
}

/* The SIMD step's data after every build of the bond cache (tlsph_ell.h):
   the step's particle order (local, then ghost particles, each sorted by
   their reference position x0c along the axes of sort_axes, ties by index), x0c as
   columns, every particle's bonds sorted by partner in that order, the
   sliced-ELLPACK layout with the reverse weights c_ij = V_i w_ij as the
   scalar gather form computes them (LeanBonds::reverse_weight), and which
   chunks are stencil chunks. */
void PairTLSPH::build_ell()
{
  constexpr int C = TLSPH::ELL_C;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int nv = dim + 3;

  // the order
  if (nall > ell_nperm) {
    ell_nperm = nall + nall / 32 + C;
    memory->destroy(ell_perm);
    memory->destroy(ell_inv);
    memory->destroy(ell_chunk_of);
    memory->create(ell_perm, ell_nperm, "tlsph:ell_perm");
    memory->create(ell_inv, ell_nperm, "tlsph:ell_inv");
    memory->create(ell_chunk_of, ell_nperm, "tlsph:ell_chunk_of");
    // columns: x, v, x0c (dim each) and the packed rows
    memory->destroy(ell_soa);
    memory->create(ell_soa, (bigint) ell_nperm * ell_ncolumns(), "tlsph:ell_soa");
  }
  const double *x0 = x0c[0];
  int ax[3];
  sort_axes(ax);
  const auto before = [&](int a, int b) {
    for (int q = 0; q < dim; q++) {
      const int d = ax[q];
      if (x0[3 * a + d] != x0[3 * b + d]) return x0[3 * a + d] < x0[3 * b + d];
    }
    return a < b;
  };
  for (int i = 0; i < nall; i++) ell_perm[i] = i;
  std::sort(ell_perm, ell_perm + nlocal, before);
  std::sort(ell_perm + nlocal, ell_perm + nall, before);
  for (int k = 0; k < nall; k++) ell_inv[ell_perm[k]] = k;
  const int ns = ell_nperm;
  double *x0s = ell_soa + (bigint) 2 * dim * ns;
  for (int k = 0; k < nall; k++)
    for (int d = 0; d < dim; d++) x0s[(bigint) d * ns + k] = x0[3 * ell_perm[k] + d];
  // the per-particle constants of the stress lanes (local particles): Q, s, V
  {
    const EllParticles cp = ell_particles();
    const int qsz = correction_size();
    double *qc = const_cast<double *>(cp.qcol), *sc = const_cast<double *>(cp.scol),
           *vc = const_cast<double *>(cp.vcol);
    for (int k = 0; k < nlocal; k++) {
      const int i = ell_perm[k];
      const double *Qi = Q ? Q[i] : q_build.data() + (size_t) qsz * i;
      for (int q = 0; q < qsz; q++) qc[(bigint) q * ns + k] = Qi[q];
      for (int d = 0; d < dim; d++) sc[(bigint) d * ns + k] = sumg[i][d];
      vc[k] = atom->vfrac[i];
    }
    std::vector<double>().swap(q_build);    // Q lives in its columns now (rows_kept false)
  }

  // every local particle's bonds sorted by partner in the step's order:
  // (partner, bond) pairs, bo_start per particle
  std::vector<int> bo_start(nlocal + 1, 0);
  std::vector<std::pair<int, int>> bo;
  for (int ii = 0; ii < nlocal; ii++) {
    const int i = ell_perm[ii], s = bond_start[i], n = nbond[i];
    for (int m = 0; m < n; m++) bo.emplace_back(ell_inv[lean.j[s + m]], m);
    std::sort(bo.begin() + bo_start[ii], bo.end());
    bo_start[ii + 1] = (int) bo.size();
  }
  /* chunks: up to C consecutive particles; their slots are the union of
     their partner offsets (partner index minus own index), a lane without
     a bond of that offset reads a partner that is none of its own, with
     zero weights (it adds exactly zero); a particle joins while the union
     stays within ELL_UNION_SLACK of the largest bond count of the chunk and
     every lane's partner index is a particle of the columns */
  const auto offsets = [&](int ii) {
    std::vector<int> o(bo_start[ii + 1] - bo_start[ii]);
    for (size_t m = 0; m < o.size(); m++) o[m] = bo[bo_start[ii] + m].first - ii;
    return o;
  };
  std::vector<int> cfirst, cn, cslot_start(1, 0), cslot;
  for (int ii = 0; ii < nlocal;) {
    std::vector<int> uni = offsets(ii), cand;
    size_t wmax = uni.size();
    int n = 1;
    while (n < C && ii + n < nlocal) {
      const std::vector<int> o = offsets(ii + n);
      cand.clear();
      std::set_union(uni.begin(), uni.end(), o.begin(), o.end(), std::back_inserter(cand));
      const size_t w = std::max(wmax, o.size());
      if ((double) cand.size() > ELL_UNION_SLACK * (double) w) break;
      if (!cand.empty() && (ii + cand.front() < 0 || ii + n + cand.back() >= nall)) break;
      uni.swap(cand);
      wmax = w;
      n++;
    }
    cfirst.push_back(ii);
    cn.push_back(n);
    cslot.insert(cslot.end(), uni.begin(), uni.end());
    cslot_start.push_back((int) cslot.size());
    ii += n;
  }
  const int nchunk = (int) cfirst.size();
  if (nchunk + 1 > ell_nstart) {
    ell_nstart = nchunk + 1 + nchunk / 8 + 8;
    for (int **a : {&ell.start, &ell.width, &ell.first, &ell.n, &ell.kind, &ell.pat, &ell.shared}) {
      memory->destroy(*a);
      memory->create(*a, ell_nstart, "tlsph:ell_chunks");
    }
  }
  ell.nchunk = nchunk;
  std::copy(cfirst.begin(), cfirst.end(), ell.first);
  std::copy(cn.begin(), cn.end(), ell.n);
  for (int c = 0; c < nchunk; c++)
    for (int l = 0; l < cn[c]; l++) ell_chunk_of[cfirst[c] + l] = c;

  // chunk c's blocks into sj (C per slot) and sv (nv C per slot); its width
  std::vector<int> sj;
  std::vector<double> sv;
  const auto fill = [&](int c) {
    const int first = ell.first[c];
    const int *off = cslot.data() + cslot_start[c];
    const int w = cslot_start[c + 1] - cslot_start[c];
    sj.assign((size_t) C * w, 0);
    sv.assign((size_t) nv * C * w, 0.0);
    for (int l = 0; l < ell.n[c]; l++) {
      const int ii = first + l, i = ell_perm[ii];
      const int b0 = bo_start[ii], nb = bo_start[ii + 1] - b0;
      const double *gi, *wi;
      bond_values(i, gi, wi);
      int q = 0;    // the lane's next own bond (sorted like the offsets)
      for (int m = 0; m < w; m++) {
        sj[(size_t) C * m + l] = l + off[m];    // relative to the chunk's first particle
        if (q < nb && bo[b0 + q].first - ii == off[m]) {
          ell_put_bond(sv.data() + (size_t) nv * C * m, l, i, bo[b0 + q].second, gi, wi);
          q++;
        }
      }
    }
    return w;
  };
  /* whether nsets sets of slot values (set 0 the reference; value(s, m, k)
     is quantity k of slot m in set s) agree: the largest difference to set
     0, relative to the largest magnitude of that quantity in all sets (the
     gradient's components together), within ELL_SHARE_TOL */
  const auto agree = [&](int w, int nsets, auto value) {
    double scale[TLSPH::EllShape<3>::NV] = {0, 0, 0, 0, 0, 0};
    for (int m = 0; m < w; m++)
      for (int k = 0; k < nv; k++)
        for (int q = 0; q < nsets; q++) {
          double &sc = scale[k < dim ? 0 : k];
          sc = std::max(sc, std::fabs(value(q, m, k)));
        }
    for (int m = 0; m < w; m++)
      for (int k = 0; k < nv; k++)
        for (int q = 1; q < nsets; q++) {
          const double a = value(q, m, k), b = value(0, m, k);
          if (a != b && std::fabs(a - b) > ELL_SHARE_TOL * scale[k < dim ? 0 : k]) return false;
        }
    return true;
  };
  // pass 1: kinds and patterns (a chunk whose lanes agree within the
  // tolerance, matched against the patterns with the same offsets)
  std::map<std::string, std::vector<int>> patterns;
  int npat = 0;
  std::vector<int> pat_off;
  std::vector<double> pat_v;
  std::vector<int> pat_start(1, 0);
  bigint nblock = 0;
  for (int c = 0; c < nchunk; c++) {
    const int w = fill(c);
    ell.pat[c] = -1;
    ell.kind[c] = EllArrays::STENCIL;
    const auto lane = [&](int l, int m, int k) { return sv[(size_t) nv * C * m + C * k + l]; };
    if (ell.n[c] < 2 || !agree(w, ell.n[c], lane)) {
      nblock += w;
      continue;
    }
    ell.kind[c] = EllArrays::PATTERN;
    std::vector<int> off(w);
    std::vector<double> val((size_t) nv * w);
    for (int m = 0; m < w; m++) {
      off[m] = sj[(size_t) C * m];
      for (int k = 0; k < nv; k++) val[(size_t) nv * m + k] = sv[(size_t) nv * C * m + C * k];
    }
    const std::string key(reinterpret_cast<const char *>(off.data()), sizeof(int) * off.size());
    auto &cands = patterns[key];
    int found = -1;
    for (int q : cands) {
      const double *pv = pat_v.data() + (size_t) nv * pat_start[q];
      const auto set = [&](int which, int m, int k) {
        return which == 0 ? pv[(size_t) nv * m + k] : val[(size_t) nv * m + k];
      };
      if (agree(w, 2, set)) {
        found = q;
        break;
      }
    }
    if (found < 0) {
      found = npat++;
      if (cands.size() < ELL_SHARE_CANDIDATES) cands.push_back(found);
      pat_off.insert(pat_off.end(), off.begin(), off.end());
      pat_v.insert(pat_v.end(), val.begin(), val.end());
      pat_start.push_back((int) pat_off.size());
    }
    ell.pat[c] = found;
  }
  ell.npat = npat;
  memory->destroy(ell.pat_start);
  memory->destroy(ell.pat_off);
  memory->destroy(ell.pat_v);
  memory->create(ell.pat_start, ell.npat + 1, "tlsph:ell_pat_start");
  memory->create(ell.pat_off, std::max<size_t>(pat_off.size(), 1), "tlsph:ell_pat_off");
  memory->create(ell.pat_v, std::max<size_t>(pat_v.size(), 1), "tlsph:ell_pat_v");
  std::copy(pat_start.begin(), pat_start.end(), ell.pat_start);
  std::copy(pat_off.begin(), pat_off.end(), ell.pat_off);
  std::copy(pat_v.begin(), pat_v.end(), ell.pat_v);
  /* pass 2: the blocks of the chunks that are not patterns; a chunk whose
     lanes, offsets and values lane by lane, are those of an earlier chunk
     within the tolerance (a translated copy: the same end of another row)
     reads that chunk's blocks */
  std::map<std::string, std::vector<int>> owners;
  int b = 0;
  bigint nshared = 0;
  for (int c = 0; c < nchunk; c++) {
    int w = 0;
    ell.start[c] = b;
    ell.shared[c] = 0;
    if (ell.kind[c] != EllArrays::PATTERN) {
      w = fill(c);
      std::string key(reinterpret_cast<const char *>(&ell.n[c]), sizeof(int));
      for (int m = 0; m < w; m++) key.append(reinterpret_cast<const char *>(&sj[(size_t) C * m]), sizeof(int));
      auto &cands = owners[key];
      int found = -1;
      for (int o : cands) {
        // lane by lane: "slot" s = C m + l of the two chunks
        const double *ov = ell.v + (bigint) nv * C * ell.start[o];
        const auto lanes = [&](int which, int s, int k) {
          const size_t at = (size_t) nv * C * (s / C) + (size_t) C * k + s % C;
          return which == 0 ? ov[at] : sv[at];
        };
        if (agree(C * w, 2, lanes)) {
          found = o;
          break;
        }
      }
      if (found >= 0) {
        ell.start[c] = ell.start[found];
        ell.shared[c] = ell.shared[found] = 1;
        ell.width[c] = w;
        nshared += ell.n[c];
        continue;
      }
      if (cands.size() < ELL_SHARE_CANDIDATES) cands.push_back(c);
      if (b + w > ell_nblock_max) {
        // at most the blocks of every stencil chunk (pass 1's count)
        ell_nblock_max = std::max<bigint>(b + w, std::min<bigint>(nblock, 2 * (bigint) b + w + 16));
        memory->grow(ell.j, ell_nblock_max * C, "tlsph:ell_j");
        memory->grow(ell.v, ell_nblock_max * C * nv, "tlsph:ell_v");
      }
      std::copy(sj.begin(), sj.end(), ell.j + (bigint) C * b);
      std::copy(sv.begin(), sv.end(), ell.v + (bigint) nv * C * b);
    }
    ell.width[c] = w;
    b += w;
  }
  ell_nblock = b;
  ell_version = cache_version;
  ell_builds++;
  ell_dirty.clear();    // the layout is the bond cache's as it is now
  if (report_simd) {
    // once per run: how the particles were laid out (rank sums)
    report_simd = 0;
    bigint mine[7] = {0, 0, 0, 0, ell.npat, nblock, nshared}, all[7];
    for (int c = 0; c < nchunk; c++) {
      mine[ell.kind[c] == EllArrays::PATTERN ? 1 : 0] += ell.n[c];
      if (ell.n[c] == 1) mine[2]++;
      mine[3]++;
    }
    MPI_Allreduce(mine, all, 7, MPI_LMP_BIGINT, MPI_SUM, world);
    if (comm->me == 0)
      utils::logmesg(lmp, "pair tlsph: SIMD step ({}, up to {} lanes): {} particles in {} chunks; "
                          "{} read their bonds from {} shared pattern(s), {} their own ({} of "
                          "them alone in a chunk; {} from the blocks of a translated copy)\n",
                     simd_name(simd_isa), C, all[0] + all[1], all[3], all[1], all[4], all[0],
                     all[2], all[6]);
  }
}

// the values of bond mm of local particle i into lane l of the slot block vb (tlsph_ell.h)
void PairTLSPH::ell_put_bond(double *vb, int l, int i, int mm, const double *g,
                             const double *w) const
{
  constexpr int C = TLSPH::ELL_C;
  for (int k = 0; k < dim; k++) vb[C * k + l] = g[dim * mm + k];
  vb[C * dim + l] = w[2 * mm];
  vb[C * (dim + 1) + l] = w[2 * mm + 1];
  vb[C * (dim + 2) + l] = (dim == 2) ? bond_view<2>(i, g, w).reverse_weight(mm)
                                     : bond_view<3>(i, g, w).reverse_weight(mm);
}

/* lean.g and lean.w are dropped (bond_values_kept false) where nothing
   but the SIMD layout needs them every step: the SIMD step with its stress
   on the lanes (one isotropic law, not the conservative hourglass form:
   simd_deformation's 'lanes'), so that no pass of a step reads them; the
   virial's gather pass, build_ell and, in tlsph/damage, the particles that
   lose bonds (pass (1) again, their lanes re-filled) compute them again
   per particle (bond_values) */
bool PairTLSPH::keeps_bond_values() const
{
#if TLSPH_ELL_VEC
  return simd_isa == SIMD_NO || !stress_lanes_possible();
#else
  return true;
#endif
}

// one isotropic law for every type and not the conservative hourglass form:
// pass (1) of the SIMD step can compute the stress on the lanes
bool PairTLSPH::stress_lanes_possible() const
{
  if (any_orthotropic || (hg_form == 2 && gamma != 0.0)) return false;
  for (int t = 2; t <= atom->ntypes; t++)
    if (mat[t].lambda != mat[1].lambda || mat[t].mu != mat[1].mu) return false;
  return true;
}

/* Lane l of chunk c from the bond cache as it is now (tlsph/damage, after
   bonds of its particle broke): every slot zero, then the values of each
   intact bond in the slot of its partner offset, as build_ell fills them;
   a broken bond's slot then adds exactly zero, like a padded one. */
void PairTLSPH::ell_fill_lane(int c, int l)
{
  constexpr int C = TLSPH::ELL_C;
  const int nv = dim + 3;
  const int k = ell.first[c] + l, i = ell_perm[k], w = ell.width[c];
  const int *jb = ell.j + (bigint) C * ell.start[c];
  double *vb = ell.v + (bigint) nv * C * ell.start[c];
  for (int m = 0; m < w; m++)
    for (int q = 0; q < nv; q++) vb[(bigint) nv * C * m + C * q + l] = 0.0;
  // the particle's Q and s (the stress lanes read them): 'rebuild' corrected
  // it again from the bonds left, 'setup' took the broken bonds out of s
  {
    const EllParticles cp = ell_particles();
    const int ns = ell_nperm, qsz = correction_size();
    double *qc = const_cast<double *>(cp.qcol), *sc = const_cast<double *>(cp.scol);
    for (int q = 0; q < qsz; q++) qc[(bigint) q * ns + k] = Q[i][q];
    for (int d = 0; d < dim; d++) sc[(bigint) d * ns + k] = sumg[i][d];
  }
  const int s = bond_start[i];
  const double *gi, *wi;
  bond_values(i, gi, wi);
  for (int mm = 0; mm < nbond[i]; mm++) {
    // the slots are sorted by partner offset (lane 0's partner minus first)
    const int off = ell_inv[lean.j[s + mm]] - k;
    int lo = 0, hi = w;
    while (lo < hi) {
      const int mid = (lo + hi) / 2;
      if (jb[(bigint) C * mid] < off) lo = mid + 1;
      else hi = mid;
    }
    if (lo == w || jb[(bigint) C * lo] != off)
      error->one(FLERR, "pair {}: internal error: a bond of atom {} has no slot in the SIMD "
                        "step's layout", force->pair_style, atom->tag[i]);
    ell_put_bond(vb + (bigint) nv * C * lo, l, i, mm, gi, wi);
  }
}

/* The layout after the bonds of local particles changed since build_ell
   (ell_dirty: tlsph/damage's breaks and cuts): each such particle's lane
   re-filled; a pattern chunk first gets blocks of its own, behind the
   others, with its pattern's slots (its other lanes filled from their own
   bonds, as build_ell fills a stencil chunk), and a chunk whose blocks
   other chunks read too a copy of them. */
void PairTLSPH::ell_apply_dirty()
{
  constexpr int C = TLSPH::ELL_C;
  const int nv = dim + 3;
  for (int i : ell_dirty) {
    const int k = ell_inv[i], c = ell_chunk_of[k];
    if (ell.kind[c] == EllArrays::PATTERN) {
      const int q = ell.pat[c], m0 = ell.pat_start[q], w = ell.pat_start[q + 1] - m0;
      if (ell_nblock + w > ell_nblock_max) {
        ell_nblock_max = ell_nblock + w + ell_nblock / 8 + 16;
        memory->grow(ell.j, ell_nblock_max * C, "tlsph:ell_j");
        memory->grow(ell.v, ell_nblock_max * C * nv, "tlsph:ell_v");
      }
      int *jb = ell.j + (bigint) C * ell_nblock;
      for (int m = 0; m < w; m++)
        for (int l = 0; l < C; l++) jb[(bigint) C * m + l] = l + ell.pat_off[m0 + m];
      ell.kind[c] = EllArrays::STENCIL;
      ell.start[c] = (int) ell_nblock;
      ell.width[c] = w;
      ell_nblock += w;
      for (int l = 0; l < ell.n[c]; l++) ell_fill_lane(c, l);
      ell_nrelaid++;
    } else if (ell.shared[c]) {
      // blocks that other chunks read too: a copy of its own behind the others
      const int w = ell.width[c];
      if (ell_nblock + w > ell_nblock_max) {
        ell_nblock_max = ell_nblock + w + ell_nblock / 8 + 16;
        memory->grow(ell.j, ell_nblock_max * C, "tlsph:ell_j");
        memory->grow(ell.v, ell_nblock_max * C * nv, "tlsph:ell_v");
      }
      std::copy(ell.j + (bigint) C * ell.start[c], ell.j + (bigint) C * (ell.start[c] + w),
                ell.j + (bigint) C * ell_nblock);
      std::copy(ell.v + (bigint) nv * C * ell.start[c], ell.v + (bigint) nv * C * (ell.start[c] + w),
                ell.v + (bigint) nv * C * ell_nblock);
      ell.start[c] = (int) ell_nblock;
      ell.shared[c] = 0;
      ell_nblock += w;
      ell_fill_lane(c, k - ell.first[c]);
      ell_nunshared++;
    } else {
      ell_fill_lane(c, k - ell.first[c]);
    }
    ell_nrefill++;
  }
  ell_dirty.clear();
}

/* The axes of the SIMD step's order, slowest first (ax[0 .. dim-1]): z, y,
   x (x the fastest: a lattice's rows along x become runs of consecutive
   indices), except that the axis across which this rank has the most ghost
   partners (a cut between ranks or a periodic boundary) goes first. The
   ghosts come after the local particles in the step's order; with their axis
   the slowest, the ghost slab lies beyond the first or the last local rows,
   and a particle's offsets to its ghost partners are the same along its row
   (translated chunks keep sharing their blocks). With the cut across the
   fastest axis instead, every row ends at the ghosts, its offsets to them
   change from row to row, and the rows' ends are chunks of their own. From
   the decomposition only (the processor grid, the periodic axes, the
   sub-domain), so that sort_particles and build_ell agree. */
void PairTLSPH::sort_axes(int *ax) const
{
  int best = -1;
  double wbest = 0.0;
  if (comm->layout != Comm::LAYOUT_TILED) {
    for (int d = dim - 1; d >= 0; d--) {    // (a tie keeps the default order)
      const int sides = (domain->periodicity[d] || comm->myloc[d] > 0 ? 1 : 0) +
          (domain->periodicity[d] || comm->myloc[d] < comm->procgrid[d] - 1 ? 1 : 0);
      double w = sides;    // the ghost slabs' cross-section
      for (int e = 0; e < dim; e++)
        if (e != d) w *= domain->subhi[e] - domain->sublo[e];
      if (w > wbest) {
        wbest = w;
        best = d;
      }
    }
  }
  int q = 0;
  if (best >= 0) ax[q++] = best;
  for (int d = dim - 1; d >= 0; d--)
    if (d != best) ax[q++] = d;
}

/* The local particles in the SIMD step's order: sorted by their reference
   position in the image of their current one (x0c of set_reference_images)
   along the axes of sort_axes, ties by tag: the rows of a lattice become
   runs of consecutive indices. Called before every exchange (the bond fix's
   pre_exchange); moves the atoms as LAMMPS's Atom::sort does (AtomVec::copy,
   which carries the fixes' per-atom data, the bonds included). */
void PairTLSPH::sort_particles()
{
  if (simd_isa == SIMD_NO) return;
  const int nlocal = atom->nlocal;
  if (nlocal < 2) return;
  double **x = atom->x, **x0 = atom->x0;
  tagint *tag = atom->tag;
  const bool periodic = domain->xperiodic || domain->yperiodic || domain->zperiodic;
  std::vector<double> key(3 * (size_t) nlocal);
  for (int i = 0; i < nlocal; i++) {
    double u[3] = {x[i][0] - x0[i][0], x[i][1] - x0[i][1], x[i][2] - x0[i][2]};
    double um[3] = {u[0], u[1], u[2]};
    if (periodic) domain->minimum_image(um[0], um[1], um[2]);
    for (int d = 0; d < 3; d++) key[3 * i + d] = (um[d] == u[d]) ? x0[i][d] : x0[i][d] + (u[d] - um[d]);
  }
  std::vector<int> permute(nlocal);
  for (int i = 0; i < nlocal; i++) permute[i] = i;
  int ax[3];
  sort_axes(ax);
  std::sort(permute.begin(), permute.end(), [&](int a, int b) {
    for (int q = 0; q < dim; q++) {
      const int d = ax[q];
      if (key[3 * a + d] != key[3 * b + d]) return key[3 * a + d] < key[3 * b + d];
    }
    return tag[a] < tag[b];
  });
  // permute[I] = J: the I-th atom of the new order is the J-th of the old
  bool sorted = true;
  for (int i = 0; i < nlocal && sorted; i++) sorted = permute[i] == i;
  if (sorted) return;
  // the spare slot of the cycles: behind the ghosts, which are still there
  // (Atom::sort runs after the exchange, with none: it uses slot nlocal;
  // here that would overwrite a ghost, whose tag the exchange's map_clear
  // then could not find, leaving a stale entry in the atom map)
  const int spare = nlocal + atom->nghost;
  if (spare >= atom->nmax) atom->avec->grow(spare + 1);
  std::vector<int> current(nlocal);
  for (int i = 0; i < nlocal; i++) current[i] = i;
  AtomVec *avec = atom->avec;
  for (int i = 0; i < nlocal; i++) {
    if (current[i] == permute[i]) continue;
    avec->copy(i, spare, 0);
    int empty = i;
    while (permute[empty] != i) {
      avec->copy(permute[empty], empty, 0);
      empty = current[empty] = permute[empty];
    }
    avec->copy(spare, empty, 0);
    current[empty] = permute[empty];
  }
}

/* the columns of x and v (every step) and of the packed rows of particles
   k0 <= k < k1 of the step's order */
void PairTLSPH::ell_columns_xv()
{
  const int nall = atom->nlocal + atom->nghost;
  const int ns = ell_nperm;
  double *xs = ell_soa, *vs = ell_soa + (bigint) dim * ns;
  double **x = atom->x, **v = atom->v;
  for (int k = 0; k < nall; k++) {
    const int i = ell_perm[k];
    for (int d = 0; d < dim; d++) {
      xs[(bigint) d * ns + k] = x[i][d];
      vs[(bigint) d * ns + k] = v[i][d];
    }
  }
}

// columns of ell_soa: x, v, x0c (dim each), the packed rows, Q, s (dim), V, fown (dim),
// the pair-force accumulators of pass (3) (2 dim)
int PairTLSPH::ell_ncolumns() const
{
  return 3 * dim + packed_size() + correction_size() + dim + 1 + dim + 2 * dim;
}

TLSPH::EllParticles PairTLSPH::ell_particles()
{
  const int ns = ell_nperm;
  EllParticles p;
  p.ns = ns;
  p.xs = ell_soa;
  p.vs = ell_soa + (bigint) dim * ns;
  p.x0s = ell_soa + (bigint) 2 * dim * ns;
  p.pks = ell_soa + (bigint) 3 * dim * ns;
  const int np = packed_size();
  p.qcol = p.pks + (bigint) np * ns;
  p.scol = p.qcol + (bigint) correction_size() * ns;
  p.vcol = p.scol + (bigint) dim * ns;
  p.fcol = const_cast<double *>(p.vcol) + ns;
  p.pcol = p.fcol + (bigint) dim * ns;
  p.perm = ell_perm;
  p.type = atom->type;
  p.pm = pairmat.data();
  p.f = atom->f[0];
  p.f_hg = bonds->f_hg[0];
  p.f_visc = bonds->f_visc[0];
  p.nlocal = atom->nlocal;
  p.h = h;
  p.beta = beta;
  p.gamma = gamma;
  return p;
}

/* pass (1) of the SIMD step: F by chunks, then the per-particle stress
   (as compute_deformation) and the packed rows as columns; for one
   isotropic material without the conservative hourglass form the stress
   too on the lanes (ell_stress_lanes), else particle by particle */
template <int DIM, int ORDER, int LAWS> void PairTLSPH::simd_deformation()
{
  const int nlocal = atom->nlocal;
  ell_columns_xv();
  // bonds a tip cut before this pass (tlsph/damage's update_bonds)
  if (!ell_dirty.empty()) ell_apply_dirty();
  const bool need_K = viscosity_active();
  const int ns = ell_nperm, np = packed_size();
  double *pks = ell_soa + (bigint) 3 * DIM * ns;
  bool lanes = !LAWS && stress_lanes_possible() && (!alpha_atom || alpha_after_deformation());
  // tlsph/damage: the stretch screen (simd_screen), the flagged particles to simd_breaks
  TLSPH::EllScreen scr{0.0, -1.0, 0.0, nullptr, 0};
  const int screen = simd_screen(scr.up, scr.down, scr.reach2) ? (scr.down > 0.0 ? 2 : 1) : 0;
  if (screen) {
    if ((int) ell_flagged.size() < nlocal) ell_flagged.resize(nlocal);
    scr.list = ell_flagged.data();
    simd_screen_select(scr);
  }
#if TLSPH_ELL_VEC
  if (nlocal > 0) {
    TLSPH::EllStress st;
    if (lanes) {
      st.law = TLSPH::IsotropicSVK{mat[1].lambda, mat[1].mu, DIM == 2 ? plane_stress : 0};
      st.need_K = need_K ? 1 : 0;
      st.Q = Q ? Q[0] : nullptr;    // (the lanes read the columns)
      st.qs = correction_size();
      st.sumg = sumg[0];
      st.alpha = alpha;
      st.alpha_atom = alpha_atom;
      st.F = F[0];
      st.P = P[0];
      st.psi = psi;
      st.ehg = ehg;
      st.fown = fown[0];
      st.pks = pks;
      st.bad = -1;
      st.badJ = 0.0;
      st.nuc_s = nuc_screen_s;
      st.nuc_hit = nullptr;
      if (DIM == 2 && nuc_screen_s > 0.0) {
        if ((int) nuc_hit.size() < atom->nmax) nuc_hit.resize(atom->nmax);
        st.nuc_hit = nuc_hit.data();
      }
    }
    pick_deformation<DIM, ORDER>(simd_isa, screen)(ell, ell_particles(), F[0], lanes ? &st : nullptr,
                                                   screen ? &scr : nullptr);
    nuc_hit_step = (lanes && st.nuc_hit) ? update->ntimestep : -1;
    // the flagged particles: the exact test, and F and the stress of what is left
    if (scr.n) simd_breaks(scr.list, scr.n);
    if (lanes) {
      // a flagged particle's stress came again from simd_breaks, which checked it
      if (st.bad >= 0 && std::find(scr.list, scr.list + scr.n, st.bad) == scr.list + scr.n)
        unstable_particle(st.bad, st.badJ);
      return;
    }
  }
#else
  lanes = false;
  (void) screen;
#endif
  nuc_hit_step = -1;
  double *fcol = ell_particles().fcol;
  for (int k = 0; k < nlocal; k++) {
    const int i = ell_perm[k];
    particle_stress<DIM, ORDER, LAWS>(i, need_K);
    const double *row = pk[i];
    for (int q = 0; q < np; q++) pks[(bigint) q * ns + k] = row[q];
    for (int d = 0; d < DIM; d++) fcol[(bigint) d * ns + k] = fown[i][d];
  }
}

/* Which chunks the stretch screen must visit this step. A bond of reference
   length r0 <= R and length r (r <= sqrt(up) r0 while it holds) has
   up r0^2 - r^2 = (sqrt(up) r0 - r)(sqrt(up) r0 + r) <= (sqrt(up) r0 - r) 2 sqrt(up) R,
   so its room to the limit is at least (up r0^2 - r^2) / (2 sqrt(up) R)
   (the same for the lower limit, r - sqrt(down) r0); and since the full
   screen its length changed by at most 2 d, d the largest displacement of
   any particle (local or ghost) since then, less a shift common to all. A
   chunk whose largest r^2 - up r0^2 at the full screen (ell_cworst) leaves
   more room than that cannot have a bond at a limit now, and keeps the
   plain pass. A full screen (every chunk, margins and positions recorded)
   runs after every build_ell and whenever more than an eighth of the
   chunks need one. (Test: damage.SimdStep.same_bonds_break_as_scalar_slow_skipping;
   a bound ten times too small breaks it.) */
void PairTLSPH::simd_screen_select(TLSPH::EllScreen &scr)
{
  const int DIM = dim;
  const int ns = ell_nperm, nall = atom->nlocal + atom->nghost, nc = ell.nchunk;
  const double *xs = ell_soa;    // DIM columns of x (ell_columns_xv)
  const double R = std::max(2.0 * h, std::sqrt(scr.reach2)) * (1.0 + 1.0e-6);
  const double den = 2.0 * std::sqrt(scr.up) * R;
  bool full = ell_screen_of != ell_builds || (int) ell_cworst.size() < nc;
  if (!full) {
    // d: the displacements u since the full screen less any common shift c
    // (a bond's length changes by at most |u_i - u_j| <= 2 max |u - c|),
    // c the middle of their range: |u - c| <= |half the range|
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int d = 0; d < DIM; d++) {
      const double *a = xs + (bigint) d * ns, *b = ell_xref.data() + (bigint) d * ns;
      for (int k = 0; k < nall; k++) {
        const double u = a[k] - b[k];
        lo[d] = u < lo[d] ? u : lo[d];
        hi[d] = u > hi[d] ? u : hi[d];
      }
    }
    double d2 = 0.0;
    for (int d = 0; d < DIM && nall > 0; d++) d2 += 0.25 * (hi[d] - lo[d]) * (hi[d] - lo[d]);
    // the room a chunk needs, with a margin for the round-off of its margins
    const double need_room = 2.0 * std::sqrt(d2) * (1.0 + 1.0e-6) + 1.0e-6 * R;
    int n = 0;
    ell_need.resize(nc);
    for (int c = 0; c < nc; c++) {
      ell_need[c] = -ell_cworst[c] / den <= need_room;
      n += ell_need[c];
    }
    if (8 * n > nc) full = true;
    else {
      scr.need = ell_need.data();
      scr.worst = nullptr;
      ell_nscreened += n;
      ell_nskipped += nc - n;
    }
  }
  if (full) {
    ell_screen_of = ell_builds;
    ell_cworst.assign(nc, 1.0);    // not screened: no room (the driver overwrites)
    ell_need.assign(nc, 1);
    scr.need = ell_need.data();
    scr.worst = ell_cworst.data();
    ell_xref.assign(xs, xs + (bigint) DIM * ns);
    ell_nscreened += nc;
  }
}

// the columns of local particle i from its rows (the packed row, V_i P_i s_i)
void PairTLSPH::ell_row_to_columns(int i)
{
  const int k = ell_inv[i], ns = ell_nperm, np = packed_size();
  const EllParticles cp = ell_particles();
  double *pks = const_cast<double *>(cp.pks);
  for (int q = 0; q < np; q++) pks[(bigint) q * ns + k] = pk[i][q];
  for (int d = 0; d < dim; d++) cp.fcol[(bigint) d * ns + k] = fown[i][d];
}

/* after after_deformation (tlsph/damage: the bonds of this step are
   decided, alpha_i is in the rows): the lanes of the particles whose bonds
   broke, and the column of alpha_i */
void PairTLSPH::simd_after_deformation()
{
  if (!ell_dirty.empty()) ell_apply_dirty();
  if (!alpha_after_deformation() || !alpha_changed) return;
  const int nlocal = atom->nlocal, ns = ell_nperm, ia = 2 * dim * dim;    // TLSPH::Packed::A
  double *acol = const_cast<double *>(ell_particles().pks) + (bigint) ia * ns;
  for (int k = 0; k < nlocal; k++) acol[k] = pk[ell_perm[k]][ia];
}

void PairTLSPH::simd_deformation_pass()
{
  const int laws = any_orthotropic ? 1 : 0;
  if (dim == 2) {
    if (order == 1) laws ? simd_deformation<2, 1, 1>() : simd_deformation<2, 1, 0>();
    else laws ? simd_deformation<2, 2, 1>() : simd_deformation<2, 2, 0>();
  } else {
    if (order == 1) laws ? simd_deformation<3, 1, 1>() : simd_deformation<3, 1, 0>();
    else laws ? simd_deformation<3, 2, 1>() : simd_deformation<3, 2, 0>();
  }
}

// pass (3) of the SIMD step (gather form); hg: 0 none, 1 thesis, 2 conservative
void PairTLSPH::simd_forces(int hg, int visc)
{
  const int nlocal = atom->nlocal;
  double **f_hg = bonds->f_hg;
  if (hg == 2)
    for (int i = 0; i < nlocal; i++) f_hg[i][0] = f_hg[i][1] = f_hg[i][2] = 0.0;
  // (the ghosts' packed rows: the forward communication wrote the columns)
  if (nlocal == 0) return;
  // one material (every type's force-pass numbers equal): no per-pair lookup
  int multi = 0;
  for (int t = 2; t <= atom->ntypes; t++)
    if (std::memcmp(&pairmat[t], &pairmat[1], sizeof(TLSPH::PairMaterial)) != 0) multi = 1;
#if TLSPH_ELL_VEC
  {
    // the accumulators the kernel reads (viscous: the first dim columns,
    // hourglass: the next dim), locals and ghosts (a ghost partner receives too)
    double *pcol = ell_particles().pcol;
    const bigint n = std::min(nlocal + atom->nghost + TLSPH::ELL_C, ell_nperm);
    for (int q = 0; q < 2 * dim; q++)
      if (q < dim ? visc : hg) std::fill_n(pcol + (bigint) q * ell_nperm, n, 0.0);
  }
  ForceFn fn;
  if (dim == 2) fn = (order == 1) ? pick_forces_hg<2, 1>(simd_isa, hg, visc, multi)
                                  : pick_forces_hg<2, 2>(simd_isa, hg, visc, multi);
  else fn = (order == 1) ? pick_forces_hg<3, 1>(simd_isa, hg, visc, multi)
                         : pick_forces_hg<3, 2>(simd_isa, hg, visc, multi);
  fn(ell, ell_particles());
#else
  (void) visc;
  (void) multi;
#endif
}

/* the virial of the SIMD step: the scalar gather form's tally (its forces
   and the bond fix's tallies computed into the arrays and then restored) */
void PairTLSPH::simd_virial(int hg, int visc)
{
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  double **f = atom->f, **f_hg = bonds->f_hg, **f_visc = bonds->f_visc;
  std::vector<double> keep(3 * ((size_t) nall + 2 * (size_t) nlocal));
  double *kf = keep.data(), *kh = kf + 3 * (size_t) nall, *kv = kh + 3 * (size_t) nlocal;
  if (nall) std::copy(f[0], f[0] + 3 * (size_t) nall, kf);
  if (nlocal) {
    std::copy(f_hg[0], f_hg[0] + 3 * (size_t) nlocal, kh);
    std::copy(f_visc[0], f_visc[0] + 3 * (size_t) nlocal, kv);
  }
  if (dim == 2) {
    if (order == 1) dispatch_forces<2, 1>(hg, visc, 1, 0);
    else dispatch_forces<2, 2>(hg, visc, 1, 0);
  } else {
    if (order == 1) dispatch_forces<3, 1>(hg, visc, 1, 0);
    else dispatch_forces<3, 2>(hg, visc, 1, 0);
  }
  if (nall) std::copy(kf, kf + 3 * (size_t) nall, f[0]);
  if (nlocal) {
    std::copy(kh, kh + 3 * (size_t) nlocal, f_hg[0]);
    std::copy(kv, kv + 3 * (size_t) nlocal, f_visc[0]);
  }
}
