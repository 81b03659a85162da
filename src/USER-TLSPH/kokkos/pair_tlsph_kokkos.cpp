/* ----------------------------------------------------------------------
   USER-TLSPH: pair_style tlsph/kk (pair_tlsph_kokkos.h, doc/pair_tlsph_kokkos.rst)
------------------------------------------------------------------------- */

#ifndef TLSPH_KOKKOS
#define TLSPH_KOKKOS
#endif

#include "pair_tlsph_kokkos.h"

#include "atom_kokkos.h"
#include "atom_masks.h"
#include "atom_vec_peri_kokkos.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_tlsph_bonds.h"
#include "fix.h"
#include "force.h"
#include "modify.h"
#include "kokkos.h"
#include "neighbor_kokkos.h"
#include "memory.h"
#include "pair_tlsph_damage.h"
#include "pair_tlsph_step.h"
#include "update.h"
#include "utils.h"

#include <Kokkos_ScatterView.hpp>

#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <utility>
#include <type_traits>
#include <vector>

using namespace LAMMPS_NS;

using TLSPHKK::download;
using TLSPHKK::HostUnmanaged;
using TLSPHKK::upload;

/* ---------------------------------------------------------------------- */

template <class DeviceType, class Base>
PairTLSPHKokkosT<DeviceType, Base>::PairTLSPHKokkosT(LAMMPS *lmp) : Base(lmp)
{
  // a restart file of an older build, or an explicit /kk name without -k on
  if (lmp->kokkos == nullptr)
    error->all(FLERR, "pair_style tlsph/kk and tlsph/damage/kk need the KOKKOS package enabled "
                      "(-k on); without it use pair_style tlsph or tlsph/damage");
  kokkosable = 1;
  atomKK = (AtomKokkos *) atom;
  // (the device model of a host backend declares Device: tlsph_kk_copies.h)
  execution_space = TLSPHKK::execution_space_of<DeviceType>();
  datamask_read = X_MASK | V_MASK | F_MASK | TYPE_MASK | ENERGY_MASK | VIRIAL_MASK;
  datamask_modify = F_MASK | ENERGY_MASK | VIRIAL_MASK;
  kk_nmax = 0;
  host_current = 0;
  host_step = -1;
  uploaded_version = -1;
  work_device = false;
  forces_on_host = true;
  set_slice();
}

/* the chunk size C of the device's sliced bond layout (pair_tlsph_kokkos.h) */
template <class DeviceType, class Base>
void PairTLSPHKokkosT<DeviceType, Base>::set_slice()
{
  slice = (on_device() && !TLSPHKK::device_model()) ? 32 : 1;
  const char *pc = std::getenv("TLSPH_KK_PK_COLUMNS");
  if (pc && *pc) {
    if (std::string(pc) != "0" && std::string(pc) != "1")
      error->all(FLERR, "TLSPH_KK_PK_COLUMNS must be 0 or 1, not '{}'", pc);
    pk_columns = std::string(pc) == "1";
  }
  const char *e = std::getenv("TLSPH_KK_SLICE");
  if (e == nullptr || *e == '\0') return;
  char *end = nullptr;
  const long v = std::strtol(e, &end, 10);
  if (*end != '\0' || v < 1 || v > 1024)
    error->all(FLERR, "TLSPH_KK_SLICE must be a whole number from 1 to 1024 (the particles of a "
                      "chunk of the /kk bond layout; 1: rows), not '{}'", e);
  slice = (int) v;
}


/* ---------------------------------------------------------------------- */

template <class DeviceType, class Base>
void PairTLSPHKokkosT<DeviceType, Base>::init_style()
{
  Base::init_style();
  if (!dynamic_cast<AtomVecPeriKokkos *>(atom->avec))
    error->all(FLERR, "pair tlsph/kk requires atom_style peri/kk (run with -k on, or use "
                      "pair_style tlsph without /kk)");
  // as tlsph: newton_pair off, the gather form (the packed rows carry
  // R = V P Q, pair_tlsph.h; no atomics: the GPU's form), on: Newton's third
  // law, the partners' shares scattered through Kokkos ScatterViews (plain
  // stores on Serial, per-thread copies on OpenMP, atomics on a GPU); the
  // base class has set gather_rows and comm_forward accordingly
  kk_nmax = 0;    // row sizes may have changed: reallocate the device views
  // (the bond fix's per-step tally runs on the device, tally_work_device:
  // FixTLSPHBonds::init() then asks LAMMPS for no host copies)

  // restart files name the pair style by force->pair_style: give it the CPU
  // style's name (as newer LAMMPS versions do with every suffix), so that a
  // file written with -k on is read by pair_style tlsph, and by tlsph/kk with
  // -sf kk (atom_style peri/kk does the same for the atom style)
  if (force->pair == this && force->pair_style) {
    std::string name = force->pair_style;
    const auto kk = name.find("/kk");
    if (kk != std::string::npos) {
      delete[] force->pair_style;
      force->pair_style = utils::strdup(name.substr(0, kk));
    }
  }

  // On a device, a fix without a Kokkos variant that runs every step and
  // declares no atom data (datamask; many fixes of this LAMMPS version,
  // e.g. fix addforce) works on host copies that LAMMPS neither brings up
  // to date before it nor copies back after it: a force it adds is lost.
  // Warned once per fix (doc/kokkos-cuda.md, "Host-device copies").
  if (on_device() && comm->me == 0) {
    using namespace FixConst;
    const int per_step = INITIAL_INTEGRATE | POST_INTEGRATE | PRE_FORCE | PRE_REVERSE | POST_FORCE |
        FINAL_INTEGRATE | END_OF_STEP;
    for (int f = 0; f < this->modify->nfix; f++) {
      Fix *fix = this->modify->fix[f];
      if (fix->kokkosable || !(this->modify->fmask[f] & per_step) || fix == this->bonds) continue;
      if (fix->datamask_read == EMPTY_MASK && fix->datamask_modify == EMPTY_MASK)
        error->warning(FLERR, "pair {}/kk: fix {} ({}) has no Kokkos variant and declares no atom "
                              "data: on a GPU it reads and changes stale host copies every step "
                              "(a force it adds is lost); apply it with a Kokkos style or run on "
                              "a host backend", force->pair_style, fix->id, fix->style);
    }
  }

  // LAMMPS's neighbor check (neigh_modify check yes: every step) runs where
  // the perpetual neighbor lists live; with no list but the bond fix's
  // occasional host list that is the host, which copied x to the host every
  // step on a GPU (seen there by the atom ledger of kokkos.transfers). The
  // /kk pairs build no list of their own, so they ask NeighborKokkos to check
  // (and hold x at a build) on the device, as a Kokkos pair with a device
  // list would.
  if (on_device()) static_cast<NeighborKokkos *>(this->neighbor)->device_flag = 1;

  // materials, per type, to the device (pair_coeff cannot change them during a run)
  const int nt = atom->ntypes + 1;
  d_mat = Kokkos::View<Material *, DeviceType>("tlsph/kk:mat", nt);
  d_pm = Kokkos::View<TLSPH::PairMaterial *, DeviceType>("tlsph/kk:pairmat", nt);
  auto h_mat = Kokkos::create_mirror_view(d_mat);
  auto h_pm = Kokkos::create_mirror_view(d_pm);
  for (int t = 0; t < nt && t < (int) mat.size(); t++) h_mat(t) = mat[t];
  for (int t = 0; t < nt && t < (int) pairmat.size(); t++) h_pm(t) = pairmat[t];
  Kokkos::deep_copy(d_mat, h_mat);
  Kokkos::deep_copy(d_pm, h_pm);
}

/* per-particle device views for atom->nmax particles */
template <class DeviceType, class Base>
void PairTLSPHKokkosT<DeviceType, Base>::grow_device()
{
  if (atom->nmax <= kk_nmax) return;
  kk_nmax = atom->nmax;
  auto make = [&](dview &v, int per, const char *name) {
    v = dview(Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string(name)),
              (size_t) kk_nmax * per);
  };
  make(d_F, 9, "tlsph/kk:F");
  make(d_P, 9, "tlsph/kk:P");
  make(d_pk, packed_size(), "tlsph/kk:packed");
  make(d_fown, 3, "tlsph/kk:fown");
  make(d_psi, 1, "tlsph/kk:psi");
  make(d_ehg, 1, "tlsph/kk:ehg");
  make(d_fhg, 3, "tlsph/kk:f_hg");
  make(d_fvisc, 3, "tlsph/kk:f_visc");
}

/* a bond cache built on the host (PairTLSPH::build_bond_cache: the first
   build after the partner search, TLSPH_KK_HOST_CACHE=1) and the
   per-particle data it fixes until the next neighbor build, to the device */
template <class DeviceType, class Base>
void PairTLSPHKokkosT<DeviceType, Base>::upload_bond_cache()
{
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  const size_t nb = upload_rows(true);
  upload(d_Q, Q[0], (size_t) nlocal * correction_size(), "tlsph/kk:Q");
  upload(d_sumg, sumg[0], (size_t) nlocal * 3, "tlsph/kk:sumg");
  upload(d_x0c, x0c[0], (size_t) nall * 3, "tlsph/kk:x0c");
  uploaded_version = cache_version;
  after_cache_build(nb);
}

namespace {
/* The sliced layout (pair_tlsph_kokkos.h) of particles with nc[i] bonds
   each, in chunks of C: st[i] the record of i's bond 0, st[n] the records
   in all (returned) */
size_t slice_starts(const std::vector<int> &nc, int C, std::vector<int> &st)
{
  const int n = nc.size();
  st.assign(n + 1, 0);
  size_t total = 0;
  for (int c0 = 0; c0 < n; c0 += C) {
    int width = 0;
    for (int i = c0; i < MIN(n, c0 + C); i++) {
      width = MAX(width, nc[i]);
      st[i] = (int) total + (i - c0);
    }
    total += (size_t) C * width;
  }
  st[n] = (int) total;
  return total;
}

/* records of `per` values in the sliced layout -> rows: bond m of i from
   record st[i] + m C to row rs[i] + m */
template <class T>
void records_to_rows(const T *rec, int per, const std::vector<int> &st, const std::vector<int> &nc,
                     int C, const int *rs, T *rows)
{
  for (size_t i = 0; i < nc.size(); i++)
    for (int m = 0; m < nc[i]; m++)
      for (int d = 0; d < per; d++)
        rows[((size_t) rs[i] + m) * per + d] = rec[((size_t) st[i] + (size_t) m * C) * per + d];
}
}    // namespace

/* The host's rows of the bond cache (bond_start, nbond, nlead, lean: j, k
   and with_gw g, w) to the device in the sliced layout of `slice`
   particles per chunk (pair_tlsph_kokkos.h); returns the records in all.
   With slice 1 the rows go up as they are. */
template <class DeviceType, class Base>
size_t PairTLSPHKokkosT<DeviceType, Base>::upload_rows(bool with_gw)
{
  const int nlocal = atom->nlocal, C = slice;
  std::vector<int> st, nc(nlocal);
  for (int i = 0; i < nlocal; i++) nc[i] = bond_start[i + 1] - bond_start[i];
  const size_t total = slice_starts(nc, C, st);
  layout_records = (double) total;
  layout_bonds = (double) bond_start[nlocal];
  upload(d_start, st.data(), nlocal + 1, "tlsph/kk:bond_start");
  upload(d_ncache, nc.data(), nlocal, "tlsph/kk:ncache");
  upload(d_nbond, nbond, nlocal, "tlsph/kk:nbond");
  upload(d_nlead, nlead, nlocal, "tlsph/kk:nlead");
  // one array at a time through a host copy in the sliced order (the
  // records between rows: zero)
  auto put = [&](auto &view, const auto *rows, int per, const char *name) {
    using T = typename std::remove_const<typename std::remove_pointer<decltype(rows)>::type>::type;
    if (C == 1) {
      upload(view, rows, total * per, name);
      return;
    }
    std::vector<T> out(total * per, T(0));
    for (int i = 0; i < nlocal; i++)
      for (int m = 0; m < nc[i]; m++)
        for (int d = 0; d < per; d++)
          out[((size_t) st[i] + (size_t) m * C) * per + d] = rows[((size_t) bond_start[i] + m) * per + d];
    upload(view, out.data(), out.size(), name);
  };
  put(d_bj, lean.j, 1, "tlsph/kk:bond_j");
  put(d_bk, lean.k, 1, "tlsph/kk:bond_k");
  if (with_gw) {
    put(d_bg, lean.g, dim, "tlsph/kk:bond_g");
    put(d_bw, lean.w, 2, "tlsph/kk:bond_w");
  }
  return total;
}

/* the device's record of bond 0 of each particle (and the records in all,
   st[nlocal]) and its cached bonds: the sliced layout read back */
template <class DeviceType, class Base>
void PairTLSPHKokkosT<DeviceType, Base>::download_rows(std::vector<int> &st, std::vector<int> &nc)
{
  const int nlocal = atom->nlocal;
  st.resize(nlocal + 1);
  nc.resize(nlocal);
  download(st.data(), d_start, 0, nlocal + 1);
  download(nc.data(), d_ncache, 0, nlocal);
}

/* ----------------------------------------------------------------------
   The bond cache after a neighbor build, built on the device: the bond
   fix's partner rows (tags and states, 5 bytes per slot) and x0c (set on
   the host, where a neighbor build has brought x and x0) go up, the
   partners are resolved on the device (resolve_bonds_device: LAMMPS's map
   and images synced to the device), and the bond math runs there
   (TLSPH::particle_bonds, the same function as the host build: the
   records, the corrections, g, the weights, Q and sum g). Before, the whole
   cache went up: j, g, w, k (40-48 bytes per bond) and Q, sum g. Frozen
   corrections (tlsph/damage, policy setup) go up with the particles and
   come back when new ones were computed. Where the device resolution does
   not apply (device_resolve_ok) the host resolves (Base::resolve_bonds)
   and uploads indices and slots. The host build remains for the first
   build after the partner search (its checks name particles) and with
   TLSPH_KK_HOST_CACHE=1 (for comparisons). TLSPH_KK_CACHE_CHECK=1 builds
   both and compares them (check_device_cache). The host copy of the cache
   is then not kept (no host code of the /kk styles reads it; sync_host()
   brings the bond counts for the computes).
------------------------------------------------------------------------- */

namespace {
// Atom::map on a device: the array map (map_style array)
template <class View> struct MapLookup {
  View map;
  tagint max;
  KOKKOS_INLINE_FUNCTION int operator()(tagint t) const { return (t < 0 || t > max) ? -1 : map(t); }
};

bool env_flag(const char *name)
{
  const char *e = std::getenv(name);
  return e != nullptr && *e != '\0' && std::string(e) != "0";
}
}    // namespace

/* The partners resolved on the device (resolve_bonds_device), where it
   applies: an orthogonal box, LAMMPS's map as an array (atom_modify map
   array; the hash map of this version has no device lookup we use), and
   TLSPH_KK_HOST_RESOLVE unset (the host resolution, for comparisons). */
template <class DeviceType, class Base>
bool PairTLSPHKokkosT<DeviceType, Base>::device_resolve_ok() const
{
  return !this->domain->triclinic && atom->map_style == Atom::MAP_ARRAY &&
      !env_flag("TLSPH_KK_HOST_RESOLVE");
}

/* Base::resolve_bonds on the device: the bond fix's partner rows (tags and
   states, 5 bytes per slot) go up, LAMMPS's map and its list of images
   (sametag) are synced to the device, and per local particle a count
   kernel, a scan and a fill kernel give the partner indices and slots in
   the cache's order (the intact bonds that lead their pair, the other
   intact ones, then, for correction_from_all_partners, the broken ones
   still present), nlead, nbond and the row starts, as the host does; x0c is
   set on the host (it needs x and x0 there, which a neighbor build has
   brought) and goes up. A partner beyond the ghost cutoff or a bond vector
   no longer given by the minimum image sends the build back to the host
   resolution, whose error message names the particle. Returns the number
   of cached bonds. */
template <class DeviceType, class Base>
size_t PairTLSPHKokkosT<DeviceType, Base>::resolve_bonds_device()
{
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  if (this->peratom_rows_short()) this->grow_peratom();
  this->set_reference_images();
  upload(d_x0c, x0c[0], (size_t) nall * 3, "tlsph/kk:x0c");
  const int mp = MAX(1, this->bonds->maxpartner);
  upload(d_npartner, this->bonds->npartner, nlocal, "tlsph/kk:npartner");
  if (this->bonds->maxpartner > 0) {
    upload(d_ptag, this->bonds->partner[0], (size_t) nlocal * mp, "tlsph/kk:partner_tag");
    upload(d_pstate, this->bonds->state[0], (size_t) nlocal * mp, "tlsph/kk:partner_state");
  }
  atomKK->k_map_array.template sync<DeviceType>();
  atomKK->k_sametag.template sync<DeviceType>();
  atomKK->sync(execution_space, X_MASK);
  auto *avec = static_cast<AtomVecPeriKokkos *>(atom->avec);
  avec->k_x0.template sync<DeviceType>();
  TLSPHKK::reserve(d_start, (size_t) nlocal + 1, "tlsph/kk:bond_start");
  TLSPHKK::reserve(d_ncache, MAX(nlocal, 1), "tlsph/kk:ncache");
  TLSPHKK::reserve(d_nbond, nlocal, "tlsph/kk:nbond");
  TLSPHKK::reserve(d_nlead, nlocal, "tlsph/kk:nlead");

  const int *np = d_npartner.data();
  const unsigned char *st = d_pstate.data();
  const tagint *pt = d_ptag.data();
  const auto map = atomKK->k_map_array.template view<DeviceType>();
  const auto same = atomKK->k_sametag.template view<DeviceType>();
  const auto x = atomKK->k_x.template view<DeviceType>();
  const auto x0 = avec->k_x0.template view<DeviceType>();
  const double *x0cd = d_x0c.data();
  int *start = d_start.data(), *nbd = d_nbond.data(), *nld = d_nlead.data();
  int *ncache = d_ncache.data();
  const int C = slice;
  const bool all = this->correction_from_all_partners;
  const int INTACT = FixTLSPHBonds::INTACT, BROKEN = FixTLSPHBonds::BROKEN;
  const int twod = (dim == 2);
  // the partner's index, -1 when it is not on this rank (Atom::map)
  const MapLookup<decltype(map)> lookup{map, atom->map_tag_max};

  // (1) the row length of each particle; a missing intact partner is counted
  int missing = 0;
  Kokkos::parallel_reduce(
      "tlsph/kk:resolve_count", Kokkos::RangePolicy<DeviceType>(0, nlocal),
      KOKKOS_LAMBDA(const int i, int &miss) {
        int n = 0;
        for (int k = 0; k < np[i]; k++) {
          const int s = st[(size_t) mp * i + k];
          if (s == INTACT) {
            if (lookup(pt[(size_t) mp * i + k]) < 0) miss++;
            else n++;
          } else if (all && s == BROKEN && lookup(pt[(size_t) mp * i + k]) >= 0) {
            n++;
          }
        }
        ncache[i] = n;
      },
      missing);
  int nbtot = 0;
  if (missing == 0) {
    // (2) the layout: per chunk of C particles its width (longest row), an
    // exclusive scan of C x width gives each chunk's first record, the total
    // in base[nchunk]; particle i = c C + l starts at base_c + l
    const int nchunk = (nlocal + C - 1) / C;
    TLSPHKK::reserve(d_cbase, (size_t) nchunk + 1, "tlsph/kk:chunk_base");
    int *cbase = d_cbase.data();
    Kokkos::parallel_scan(
        "tlsph/kk:resolve_scan", Kokkos::RangePolicy<DeviceType>(0, nchunk + 1),
        KOKKOS_LAMBDA(const int c, int &upd, const bool final) {
          int width = 0;
          if (c < nchunk)
            for (int i = c * C; i < c * C + C && i < nlocal; i++) width = (ncache[i] > width) ? ncache[i] : width;
          if (final) cbase[c] = upd;
          upd += C * width;
        },
        nbtot);
    Kokkos::parallel_for(
        "tlsph/kk:resolve_starts", Kokkos::RangePolicy<DeviceType>(0, nlocal + 1),
        KOKKOS_LAMBDA(const int i) { start[i] = (i < nlocal) ? cbase[i / C] + i % C : cbase[nchunk]; });
    double cached = 0.0;
    Kokkos::parallel_reduce(
        "tlsph/kk:resolve_bonds", Kokkos::RangePolicy<DeviceType>(0, nlocal),
        KOKKOS_LAMBDA(const int i, double &sum) { sum += ncache[i]; }, cached);
    layout_records = (double) nbtot;
    layout_bonds = cached;
  }
  double image_error = 0.0;
  if (missing == 0) {
    TLSPHKK::reserve(d_bj, (size_t) nbtot, "tlsph/kk:bond_j");
    TLSPHKK::reserve(d_bk, (size_t) nbtot, "tlsph/kk:bond_k");
    int *bj = d_bj.data(), *bk = d_bk.data();
    const Domain *dom = this->domain;
    const int px = dom->xperiodic, py = dom->yperiodic, pz = dom->zperiodic;
    const double lx = dom->xprd, ly = dom->yprd, lz = dom->zprd;
    const double hx = dom->xprd_half, hy = dom->yprd_half, hz = dom->zprd_half;
    // (3) the rows, in the order of Base::resolve_bonds
    Kokkos::parallel_reduce(
        "tlsph/kk:resolve_fill", Kokkos::RangePolicy<DeviceType>(0, nlocal),
        KOKKOS_LAMBDA(const int i, double &emax) {
          const int s0 = start[i];
          int n = 0;
          for (int pass = 0; pass < 3; pass++) {
            if (pass == 2 && !all) break;
            for (int k = 0; k < np[i]; k++) {
              const int sk = st[(size_t) mp * i + k];
              if (pass < 2 && sk != INTACT) continue;
              if (pass == 2 && sk != BROKEN) continue;
              int j = lookup(pt[(size_t) mp * i + k]);
              if (j < 0) continue;    // (a broken partner that left the ghost shell)
              // Domain::closest_image
              {
                double d0 = x(i, 0) - x(j, 0), d1 = x(i, 1) - x(j, 1), d2 = x(i, 2) - x(j, 2);
                double rmin = d0 * d0 + d1 * d1 + d2 * d2;
                int jj = j, closest = j;
                while (same(jj) >= 0) {
                  jj = same(jj);
                  d0 = x(i, 0) - x(jj, 0);
                  d1 = x(i, 1) - x(jj, 1);
                  d2 = x(i, 2) - x(jj, 2);
                  const double r = d0 * d0 + d1 * d1 + d2 * d2;
                  if (r < rmin) rmin = r, closest = jj;
                }
                j = closest;
              }
              if (pass < 2 && (pass == 0) != (j >= nlocal || j > i)) continue;
              // the bond vector from x0c against the minimum image of x0 (Domain::minimum_image)
              double Xm[3] = {x0(j, 0) - x0(i, 0), x0(j, 1) - x0(i, 1), x0(j, 2) - x0(i, 2)};
              if (px) while (fabs(Xm[0]) > hx) Xm[0] += (Xm[0] < 0.0) ? lx : -lx;
              if (py) while (fabs(Xm[1]) > hy) Xm[1] += (Xm[1] < 0.0) ? ly : -ly;
              if (pz) while (fabs(Xm[2]) > hz) Xm[2] += (Xm[2] < 0.0) ? lz : -lz;
              double X[3] = {x0cd[3 * j] - x0cd[3 * i], x0cd[3 * j + 1] - x0cd[3 * i + 1],
                             x0cd[3 * j + 2] - x0cd[3 * i + 2]};
              if (twod) X[2] = Xm[2] = 0.0;
              const double e = sqrt(((X[0] - Xm[0]) * (X[0] - Xm[0]) + (X[1] - Xm[1]) * (X[1] - Xm[1]) +
                                     (X[2] - Xm[2]) * (X[2] - Xm[2])) /
                                    (Xm[0] * Xm[0] + Xm[1] * Xm[1] + Xm[2] * Xm[2]));
              if (!(e <= emax)) emax = e;
              bj[s0 + (long) n * C] = j;
              bk[s0 + (long) n * C] = k;
              n++;
            }
            if (pass == 0) nld[i] = n;
            if (pass == 1) nbd[i] = n;
          }
        },
        Kokkos::Max<double>(image_error));
  }
  if (missing > 0 || !(image_error <= 1.0e-8)) {
    // the host resolution names the particle (error->one), as without the device
    double shepard_max;
    int shepard_i;
    this->resolve_bonds(false, shepard_max, shepard_i);
    error->one(FLERR, "pair tlsph/kk: the device's partner resolution found {} missing partners "
                      "or an image error of {:.3g} that the host's did not", missing, image_error);
  }
  return (size_t) nbtot;
}

template <class DeviceType, class Base>
void PairTLSPHKokkosT<DeviceType, Base>::build_bond_cache()
{
  if (this->bonds->check_pending || env_flag("TLSPH_KK_HOST_CACHE")) {
    Base::build_bond_cache();    // uploaded whole by upload_bond_cache()
    host_builds++;
    return;
  }
  const double t0 = MPI_Wtime();
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  size_t nb;
  if (device_resolve_ok()) {
    nb = resolve_bonds_device();
    device_resolves++;
  } else {
    double shepard_max;
    int shepard_i;
    this->resolve_bonds(false, shepard_max, shepard_i);    // (no check: no Shepard sums)
    nb = upload_rows(false);
    upload(d_x0c, x0c[0], (size_t) nall * 3, "tlsph/kk:x0c");
  }
  const double t1 = MPI_Wtime();
  const int qs = correction_size();
  TLSPHKK::reserve(d_bg, nb * dim, "tlsph/kk:bond_g");
  TLSPHKK::reserve(d_bw, nb * 2, "tlsph/kk:bond_w");
  TLSPHKK::reserve(d_Q, (size_t) nlocal * qs, "tlsph/kk:Q");
  TLSPHKK::reserve(d_sumg, (size_t) nlocal * 3, "tlsph/kk:sumg");
  const bool has_frozen = this->correction_from_all_partners && this->bonds->nfrozen;
  const int nq = has_frozen ? this->bonds->nfrozen : 0;
  if (has_frozen) upload(d_frozen, this->bonds->frozen[0], (size_t) nlocal * (1 + nq), "tlsph/kk:frozen");
  static_cast<AtomVecPeriKokkos *>(atom->avec)->k_vfrac.template sync<DeviceType>();
  Kokkos::fence();
  const double t2 = MPI_Wtime();

  // the particles in chunks, so that the records of a chunk's bonds fit a
  // scratch view (about 512 MB on a GPU, 16 MB on a host backend)
  // (the longest row: at most the bond fix's maxpartner)
  const int maxn = MAX(1, this->bonds->maxpartner);
  const size_t per = (size_t) maxn * (sizeof(TLSPH::Bond) + sizeof(double));
  const size_t budget = (execution_space == Device && !TLSPHKK::device_model()) ? (512u << 20) : (16u << 20);
  const int chunk = (int) MAX((size_t) 1, MIN((size_t) MAX(nlocal, 1), budget / per));
  if (d_scratch.extent(0) < (size_t) chunk * maxn) {
    d_scratch = Kokkos::View<TLSPH::Bond *, DeviceType>(
        Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("tlsph/kk:bond_scratch")),
        (size_t) chunk * maxn);
    d_vjs = dview(Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string("tlsph/kk:vj_scratch")),
                  (size_t) chunk * maxn);
  }
  const double kscale = (dim == 2) ? 1.0 / this->thickness : 1.0;
  long long counts[2] = {0, 0};    // degraded, new frozen corrections
  for (int first = 0; first < nlocal; first += chunk) {
    const int last = MIN(nlocal, first + chunk);
    long long c;
    if (dim == 2)
      c = (order == 1) ? bond_math_chunk<2, 1>(first, last, maxn, nq, has_frozen, kscale)
                       : bond_math_chunk<2, 2>(first, last, maxn, nq, has_frozen, kscale);
    else
      c = (order == 1) ? bond_math_chunk<3, 1>(first, last, maxn, nq, has_frozen, kscale)
                       : bond_math_chunk<3, 2>(first, last, maxn, nq, has_frozen, kscale);
    counts[0] += c & 0xffffffffLL;    // (bond_math_chunk: degraded + 2^32 new frozen)
    counts[1] += c >> 32;
  }
  this->ndegraded = (int) counts[0];
  if (has_frozen && counts[1] > 0)
    download(this->bonds->frozen[0], d_frozen, 0, (size_t) nlocal * (1 + nq));
  Kokkos::fence();
  build_time[0] += t1 - t0;
  build_time[1] += t2 - t1;
  build_time[2] += MPI_Wtime() - t2;
  this->cache_version++;
  uploaded_version = this->cache_version;
  after_cache_build(nb);
  device_builds++;
  if (env_flag("TLSPH_KK_CACHE_CHECK")) check_device_cache();
}

// returns the particles of [first, last) whose correction fell back to a
// lower order plus 2^32 times those whose frozen correction was made now
template <class DeviceType, class Base>
template <int DIM, int ORDER>
long long PairTLSPHKokkosT<DeviceType, Base>::bond_math_chunk(int first, int last, int maxn, int nq,
                                                        bool has_frozen, double kscale)
{
  const int *start = d_start.data(), *nbd = d_nbond.data(), *bj = d_bj.data(), *bk = d_bk.data();
  const int *ncache = d_ncache.data();
  const int C = slice;
  const TLSPH::StridedRows x0{d_x0c.data(), 3};
  const double *vfrac =
      static_cast<AtomVecPeriKokkos *>(atom->avec)->k_vfrac.template view<DeviceType>().data();
  double *bg = d_bg.data(), *bw = d_bw.data(), *Q = d_Q.data(), *sumg = d_sumg.data();
  double *frozen = has_frozen ? d_frozen.data() : nullptr;
  TLSPH::Bond *scratch = d_scratch.data();
  double *vjs = d_vjs.data();
  const TLSPH::CubicSpline kern = kernel;
  const int qs = correction_size();
  long long count = 0;
  Kokkos::parallel_reduce(
      "tlsph/kk:bond_math", Kokkos::RangePolicy<DeviceType>(first, last),
      KOKKOS_LAMBDA(const int i, long long &acc) {
        const int s = start[i], nall = ncache[i];
        double *fz = frozen ? frozen + (size_t) i * (1 + nq) : nullptr;
        const double *fq = (fz && fz[0] == 1.0) ? fz + 1 : nullptr;
        const int a = TLSPH::particle_bonds<DIM, ORDER>(
            i, bj + s, bk + s, nall, nbd[i], x0, vfrac, kern, kscale, fq,
            scratch + (size_t) (i - first) * maxn, vjs + (size_t) (i - first) * maxn, Q + qs * i,
            sumg + 3 * i, bg + (size_t) DIM * s, bw + 2 * (size_t) s, C);
        if (fq) return;
        if (a < ORDER) acc += 1;
        if (fz) {
          for (int q = 0; q < nq; q++) fz[1 + q] = Q[qs * i + q];
          fz[0] = 1.0;
          acc += 1LL << 32;
        }
      },
      count);
  return count;
}

/* TLSPH_KK_CACHE_CHECK=1: the host build of the same cache, compared with
   the device-built one value by value (j, k by construction; g, w, Q, sum g
   within 1e-12 relative to each array's largest value, or the value of
   TLSPH_KK_CACHE_CHECK when it is below 1: bitwise on a host backend, FMA
   round-off on a GPU); a difference stops the run. The host
   build is then the current one (re-uploaded, as without the device build). */
template <class DeviceType, class Base>
void PairTLSPHKokkosT<DeviceType, Base>::check_device_cache()
{
  const int nlocal = atom->nlocal, C = slice;
  std::vector<int> st, nc;    // the device's layout: record of bond 0, bonds cached
  download_rows(st, nc);
  const size_t nrec = st[nlocal];    // records in all
  std::vector<double> gs(nrec * dim), ws(nrec * 2), q((size_t) nlocal * correction_size()), sg((size_t) nlocal * 3);
  std::vector<int> bjs(nrec), bks(nrec), nbd(nlocal), nld(nlocal);
  download(bjs.data(), d_bj, 0, nrec);
  download(bks.data(), d_bk, 0, nrec);
  download(nbd.data(), d_nbond, 0, nlocal);
  download(nld.data(), d_nlead, 0, nlocal);
  download(gs.data(), d_bg, 0, gs.size());
  download(ws.data(), d_bw, 0, ws.size());
  download(q.data(), d_Q, 0, q.size());
  // the layout itself must be the documented one; then the device's cache
  // as rows (the host build's layout)
  std::vector<int> expect;
  slice_starts(nc, C, expect);
  const bool layout = (expect == st);
  std::vector<int> rs(nlocal + 1, 0);
  for (int i = 0; i < nlocal; i++) rs[i + 1] = rs[i] + nc[i];
  const size_t nb = rs[nlocal];
  std::vector<double> g(nb * dim), w(nb * 2);
  std::vector<int> bj(nb), bk(nb);
  records_to_rows(bjs.data(), 1, st, nc, C, rs.data(), bj.data());
  records_to_rows(bks.data(), 1, st, nc, C, rs.data(), bk.data());
  records_to_rows(gs.data(), dim, st, nc, C, rs.data(), g.data());
  records_to_rows(ws.data(), 2, st, nc, C, rs.data(), w.data());
  download(sg.data(), d_sumg, 0, sg.size());
  const bool has_frozen = this->correction_from_all_partners && this->bonds->nfrozen;
  std::vector<double> fz;
  if (has_frozen) fz.assign(this->bonds->frozen[0], this->bonds->frozen[0] + (size_t) nlocal * (1 + this->bonds->nfrozen));
  Base::build_bond_cache();
  double worst = 0.0;
  auto cmp = [&](const std::vector<double> &a, const double *b) {
    double scale = 0.0, diff = 0.0;
    for (size_t k = 0; k < a.size(); k++) {
      scale = MAX(scale, fabs(b[k]));
      diff = MAX(diff, fabs(a[k] - b[k]));
      if (!std::isfinite(a[k]) || !std::isfinite(b[k])) diff = INFINITY;
    }
    worst = MAX(worst, scale > 0.0 ? diff / scale : diff);
  };
  // the partners: equal, index by index (the host build's resolve_bonds)
  bool same = layout && (size_t) bond_start[nlocal] == nb;
  for (size_t m = 0; same && m < nb; m++) same = bj[m] == lean.j[m] && bk[m] == lean.k[m];
  for (int i = 0; same && i < nlocal; i++)
    same = rs[i] == bond_start[i] && nbd[i] == nbond[i] && nld[i] == nlead[i];
  if (!same) worst = INFINITY;
  cmp(g, lean.g);
  cmp(w, lean.w);
  cmp(q, Q[0]);
  cmp(sg, sumg[0]);
  if (has_frozen) cmp(fz, this->bonds->frozen[0]);
  double all;
  MPI_Allreduce(&worst, &all, 1, MPI_DOUBLE, MPI_MAX, this->world);
  cache_check_worst = MAX(cache_check_worst, all);
  // TLSPH_KK_CACHE_CHECK=1: 1e-12; a value below 1 is the tolerance itself
  const double tol = std::atof(std::getenv("TLSPH_KK_CACHE_CHECK"));
  if (!(all <= ((tol > 0.0 && tol < 1.0) ? tol : 1.0e-12)))
    error->all(FLERR, "pair tlsph/kk: the device-built bond cache differs from the host build by "
                      "{:.3g} (relative) at step {}", all, update->ntimestep);
}

template <class DeviceType, class Base>
typename PairTLSPHKokkosT<DeviceType, Base>::DeviceCache
PairTLSPHKokkosT<DeviceType, Base>::device_cache() const
{
  const auto *avec = static_cast<AtomVecPeriKokkos *>(atom->avec);
  return DeviceCache{d_start.data(),
                     d_bj.data(),
                     d_bg.data(),
                     d_bw.data(),
                     d_x0c.data(),
                     avec->k_vfrac.template view<DeviceType>().data(),
                     kernel,
                     order,
                     slice};
}

/* pass (1) of tlsph/kk: the deformation kernel for the dimension, gradient
   order and laws of the scene */
template <class DeviceType, class Base>
int PairTLSPHKokkosT<DeviceType, Base>::deformation_step()
{
  if (dim == 2) {
    if (order == 1) return any_orthotropic ? deformation_kernel<2, 1, 1>() : deformation_kernel<2, 1, 0>();
    return any_orthotropic ? deformation_kernel<2, 2, 1>() : deformation_kernel<2, 2, 0>();
  }
  if (order == 1) return any_orthotropic ? deformation_kernel<3, 1, 1>() : deformation_kernel<3, 1, 0>();
  return any_orthotropic ? deformation_kernel<3, 2, 1>() : deformation_kernel<3, 2, 0>();
}

/* ----------------------------------------------------------------------
   pass (1): F, stress and the packed row of every local particle; returns
   the first particle with det F <= 0 or a non-finite energy, or -1
------------------------------------------------------------------------- */

template <class DeviceType, class Base>
template <int DIM, int ORDER, int LAWS>
int PairTLSPHKokkosT<DeviceType, Base>::deformation_kernel()
{
  using TLSPH::StridedRows;
  const int nlocal = atom->nlocal;
  const StridedRows x{atomKK->k_x.template view<DeviceType>().data(), 3};
  const TLSPH::TypeArray type{atomKK->k_type.template view<DeviceType>().data()};
  const DeviceCache dc = device_cache();
  const int *nb = d_nbond.data();
  const double *Q = d_Q.data(), *sumg = d_sumg.data();
  double *F = d_F.data(), *P = d_P.data(), *pk = d_pk.data(), *fown = d_fown.data();
  double *psi = d_psi.data(), *ehg = d_ehg.data();
  const Material *mt = d_mat.data();
  const TLSPH::PairMaterial *pm = d_pm.data();
  const int qs = correction_size(), ps = packed_size(), pstress = plane_stress;
  const bool need_K = this->viscosity_active(), cons = (hg_form == 2 && gamma != 0.0);
  const bool with_R = gather_rows;
  const double g = gamma, alpha0 = alpha;

  int bad = nlocal;
  Kokkos::parallel_reduce(
      "tlsph/kk:deformation", Kokkos::RangePolicy<DeviceType>(0, nlocal),
      KOKKOS_LAMBDA(const int i, int &first) {
        const auto b = dc.template bonds<DIM>(i);
        const double Vi = b.Vi;
        double *Fi = F + 9 * i;
        TLSPH::deformation_gradient_bonds<DIM>(x, i, b, nb[i], Fi);
        const TLSPH::HourglassWeights<decltype(b), TLSPH::TypeArray> coeff(pm, type, b, g, i, Vi);
        double J;
        psi[i] = PairTLSPH::stress_row<DIM, ORDER, LAWS>(
            mt[type(i)], pstress, Fi, P + 9 * i, need_K, cons, x, i, b, nb[i], coeff, Vi,
            Q + qs * i, alpha0, sumg + 3 * i, with_R, pk + (long) ps * i, fown + 3 * i, ehg + i,
            &J);
        if (!(J > 0.0) || !std::isfinite(psi[i])) first = (i < first) ? i : first;
      },
      Kokkos::Min<int>(bad));
  return bad < nlocal ? bad : -1;
}

/* ----------------------------------------------------------------------
   pass (3): stress, viscous and hourglass forces, gather form; the
   hourglass and viscous parts go to the bond fix's work tallies
------------------------------------------------------------------------- */

template <class DeviceType, class Base>
template <int DIM, int ORDER, int HG, int VISC, int VIRIAL>
void PairTLSPHKokkosT<DeviceType, Base>::force_kernel(double *vir)
{
  const int ps = packed_size();
  if (!pk_columns) {
    force_gather<DIM, ORDER, HG, VISC, VIRIAL>(vir, TLSPH::StridedRows{d_pk.data(), ps});
    return;
  }
  // the packed rows of the local and ghost particles, column by column
  const int nall = atom->nlocal + atom->nghost;
  TLSPHKK::reserve(d_pkc, (size_t) ps * MAX(nall, 1), "tlsph/kk:packed_columns");
  const double *pk = d_pk.data();
  double *pkc = d_pkc.data();
  Kokkos::parallel_for(
      "tlsph/kk:packed_columns", Kokkos::RangePolicy<DeviceType>(0, nall), KOKKOS_LAMBDA(const int j) {
        for (int k = 0; k < ps; k++) pkc[(long) k * nall + j] = pk[(long) ps * j + k];
      });
  force_gather<DIM, ORDER, HG, VISC, VIRIAL>(vir, TLSPH::ColumnRows{pkc, nall});
}

/* pass (2), the gather form, with the partner rows read through pkr; an
   ordinary step (no virial) runs it as a parallel_for */
template <class DeviceType, class Base>
template <int DIM, int ORDER, int HG, int VISC, int VIRIAL, class Rows>
void PairTLSPHKokkosT<DeviceType, Base>::force_gather(double *vir, const Rows &pkr)
{
  using TLSPH::StridedRows;
  const int nlocal = atom->nlocal;
  const StridedRows x{atomKK->k_x.template view<DeviceType>().data(), 3};
  const StridedRows v{atomKK->k_v.template view<DeviceType>().data(), 3};
  double *f = atomKK->k_f.template view<DeviceType>().data();
  const TLSPH::TypeArray type{atomKK->k_type.template view<DeviceType>().data()};
  const DeviceCache dc = device_cache();
  const int *nb = d_nbond.data();
  const double *P = d_P.data(), *fown = d_fown.data();
  double *fhg = d_fhg.data(), *fvisc = d_fvisc.data();
  const TLSPH::PairMaterial *pm = d_pm.data();
  const double hh = h, bb = beta, gg = gamma;

  auto body = KOKKOS_LAMBDA(const int i, double *vacc) {
    const auto b = dc.template bonds<DIM>(i);
    const double Vi = b.Vi;
    double fs[3] = {fown[3 * i], fown[3 * i + 1], fown[3 * i + 2]};
    double fv[3] = {0.0, 0.0, 0.0}, fh[3] = {0.0, 0.0, 0.0};
    const TLSPH::VirialTally tally{vacc};
    TLSPH::particle_force_bonds<DIM, ORDER, HG, VISC, VIRIAL, 0>(
        i, Vi, b, nb[i], x, v, pkr, type, pm, hh, bb, gg, P + 9 * i, fs, fv, fh, tally);
    for (int d = 0; d < DIM; d++) f[3 * i + d] += fs[d] + fv[d] + fh[d];
    for (int d = 0; d < 3; d++) {
      fhg[3 * i + d] = (HG != 2) ? fh[d] : 0.0;
      fvisc[3 * i + d] = fv[d];
    }
  };
  if (!VIRIAL) {
    Kokkos::parallel_for(
        "tlsph/kk:forces", Kokkos::RangePolicy<DeviceType>(0, nlocal), KOKKOS_LAMBDA(const int i) {
          double none[6];    // (no tally without VIRIAL)
          body(i, none);
        });
    return;
  }
  EV_FLOAT ev;
  Kokkos::parallel_reduce(
      "tlsph/kk:forces", Kokkos::RangePolicy<DeviceType>(0, nlocal),
      KOKKOS_LAMBDA(const int i, EV_FLOAT &acc) { body(i, acc.v); }, ev);
  for (int k = 0; k < 6; k++) vir[k] += ev.v[k];
}

template <class DeviceType, class Base>
template <int DIM, int ORDER, int HG, int VISC, int VIRIAL>
void PairTLSPHKokkosT<DeviceType, Base>::force_pass(double *vir)
{
  if (gather_rows) force_kernel<DIM, ORDER, HG, VISC, VIRIAL>(vir);
  else force_kernel_scatter<DIM, ORDER, HG, VISC, VIRIAL>(vir);
}

namespace {
// the scatter form's writes to other particles (pair_tlsph.cpp: ScatterForce,
// PairForces), through Kokkos ScatterView accessors
template <class FA> struct KKScatterForce {
  const FA &f;
  KOKKOS_INLINE_FUNCTION void operator()(int j, const double *t) const
  {
    f(j, 0) -= t[0];
    f(j, 1) -= t[1];
    f(j, 2) -= t[2];
  }
};
template <class FA, class TA> struct KKPairForces {
  static constexpr bool enabled = true;
  int nlead;
  int nlocal;
  const FA &f;
  const TA &fhg, &fvisc;
  bool tally_hg;    // false with the conservative hourglass form (it has an energy)
  KOKKOS_INLINE_FUNCTION void operator()(int j, const double *pv, const double *ph) const
  {
    for (int d = 0; d < 3; d++) {
      f(j, d) -= pv[d] + ph[d];
      fvisc(3 * j + d) -= pv[d];
      if (tally_hg) fhg(3 * j + d) -= ph[d];
    }
  }
};
}    // namespace

/* ----------------------------------------------------------------------
   pass (3), scatter form (newton_pair on): as PairTLSPH::compute_forces
   with SCATTER, Newton's third law for the stress term and, for the leading
   bonds, the viscous and hourglass pair forces; ghost forces are summed by
   LAMMPS's reverse communication
------------------------------------------------------------------------- */

template <class DeviceType, class Base>
template <int DIM, int ORDER, int HG, int VISC, int VIRIAL>
void PairTLSPHKokkosT<DeviceType, Base>::force_kernel_scatter(double *vir)
{
  using TLSPH::StridedRows;
  namespace KE = Kokkos::Experimental;
  const int nlocal = atom->nlocal;
  const StridedRows x{atomKK->k_x.template view<DeviceType>().data(), 3};
  const StridedRows v{atomKK->k_v.template view<DeviceType>().data(), 3};
  auto f = atomKK->k_f.template view<DeviceType>();
  const TLSPH::TypeArray type{atomKK->k_type.template view<DeviceType>().data()};
  const DeviceCache dc = device_cache();
  const int *nb = d_nbond.data(), *nl = d_nlead.data();
  const double *P = d_P.data(), *fown = d_fown.data();
  const StridedRows pkr{d_pk.data(), packed_size()};
  const TLSPH::PairMaterial *pm = d_pm.data();
  const double hh = h, bb = beta, gg = gamma;
  // the tallies are sums (partners add their share): zero them first
  auto fhg = Kokkos::subview(d_fhg, std::make_pair(0, 3 * nlocal));
  auto fvisc = Kokkos::subview(d_fvisc, std::make_pair(0, 3 * nlocal));
  Kokkos::deep_copy(fhg, 0.0);
  Kokkos::deep_copy(fvisc, 0.0);
  auto sf = KE::create_scatter_view(f);
  auto shg = KE::create_scatter_view(fhg);
  auto svisc = KE::create_scatter_view(fvisc);

  EV_FLOAT ev;
  Kokkos::parallel_reduce(
      "tlsph/kk:forces_scatter", Kokkos::RangePolicy<DeviceType>(0, nlocal),
      KOKKOS_LAMBDA(const int i, EV_FLOAT &acc) {
        auto af = sf.access();
        auto ahg = shg.access();
        auto avisc = svisc.access();
        const auto b = dc.template bonds<DIM>(i);
        const double Vi = b.Vi;
        double fs[3] = {fown[3 * i], fown[3 * i + 1], fown[3 * i + 2]};
        double fv[3] = {0.0, 0.0, 0.0}, fh[3] = {0.0, 0.0, 0.0};
        const TLSPH::VirialTally tally{acc.v};
        const KKScatterForce<decltype(af)> scatter{af};
        const KKPairForces<decltype(af), decltype(ahg)> pairs{nl[i], nlocal, af, ahg, avisc,
                                                              HG != 2};
        TLSPH::particle_force_bonds<DIM, ORDER, HG, VISC, VIRIAL, 1>(
            i, Vi, b, nb[i], x, v, pkr, type, pm, hh, bb, gg, P + 9 * i, fs, fv, fh, tally,
            scatter, pairs);
        for (int d = 0; d < DIM; d++) af(i, d) += fs[d] + fv[d] + fh[d];
        for (int d = 0; d < 3; d++) {
          if (HG != 2) ahg(3 * i + d) += fh[d];
          avisc(3 * i + d) += fv[d];
        }
      },
      ev);
  KE::contribute(f, sf);
  KE::contribute(fhg, shg);
  KE::contribute(fvisc, svisc);
  if (VIRIAL)
    for (int k = 0; k < 6; k++) vir[k] += ev.v[k];
}

template <class DeviceType, class Base>
template <int DIM, int ORDER>
void PairTLSPHKokkosT<DeviceType, Base>::dispatch_force(int hg, int visc, int vir, double *vr)
{
  const int key = hg + 3 * visc + 6 * vir;
  switch (key) {
    // clang-format off
    case 0:  force_pass<DIM, ORDER, 0, 0, 0>(vr); break;
    case 1:  force_pass<DIM, ORDER, 1, 0, 0>(vr); break;
    case 2:  force_pass<DIM, ORDER, 2, 0, 0>(vr); break;
    case 3:  force_pass<DIM, ORDER, 0, 1, 0>(vr); break;
    case 4:  force_pass<DIM, ORDER, 1, 1, 0>(vr); break;
    case 5:  force_pass<DIM, ORDER, 2, 1, 0>(vr); break;
    case 6:  force_pass<DIM, ORDER, 0, 0, 1>(vr); break;
    case 7:  force_pass<DIM, ORDER, 1, 0, 1>(vr); break;
    case 8:  force_pass<DIM, ORDER, 2, 0, 1>(vr); break;
    case 9:  force_pass<DIM, ORDER, 0, 1, 1>(vr); break;
    case 10: force_pass<DIM, ORDER, 1, 1, 1>(vr); break;
    default: force_pass<DIM, ORDER, 2, 1, 1>(vr); break;
      // clang-format on
  }
}

/* ---------------------------------------------------------------------- */

template <class DeviceType, class Base>
void PairTLSPHKokkosT<DeviceType, Base>::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  host_current = 0;
  auto *avec = static_cast<AtomVecPeriKokkos *>(atom->avec);

  // after a neighbor build the bond cache is rebuilt (build_bond_cache: the
  // partners resolved and the bond math run on the device, x0c set on the
  // host from x and x0, which need to be there)
  if (bonds->rebuild) {
    host_sync(X_MASK | TYPE_MASK | TAG_MASK);
    host_sync(EXTENDED_MASK | VFRAC_MASK | X0_MASK);
  }
  // (tlsph/damage: the pre-cracks, once, with a cache rebuild)
  this->refresh_bond_cache();
  this->update_bonds();
  if (uploaded_version != cache_version) upload_bond_cache();
  grow_device();

  atomKK->sync(execution_space, datamask_read);
  avec->k_vfrac.template sync<DeviceType>();
  if (eflag || vflag) atomKK->modified(execution_space, datamask_modify);
  else atomKK->modified(execution_space, F_MASK);

  // (1) F, stress and packed rows (tlsph/damage: bonds break in it), then
  // the damage and alpha_i (tlsph/damage)
  const int bad = deformation_step();
  if (bad >= 0) {
    double Fi[9];
    download(Fi, d_F, (size_t) 9 * bad, 9);
    this->unstable_particle(bad, TLSPH::mat_det(Fi));
  }
  damage_step();

  // (2) the packed rows of the ghosts
  comm->forward_comm_pair(this);

  // (3) forces
  const int hg = (gamma != 0.0) ? hg_form : 0;
  const int visc = this->viscosity_active() ? 1 : 0;
  const int vir = vflag_global ? 1 : 0;
  if (dim == 2) {
    if (order == 1) dispatch_force<2, 1>(hg, visc, vir, virial);
    else dispatch_force<2, 2>(hg, visc, vir, virial);
  } else {
    if (order == 1) dispatch_force<3, 1>(hg, visc, vir, virial);
    else dispatch_force<3, 2>(hg, visc, vir, virial);
  }

  // the hourglass and viscous forces stay on the device: the bond fix's
  // work tallies use them there (tally_work_device)
  forces_on_host = false;

  if (eflag_either) {
    sync_host();
    this->tally_energy();
  }
}

/* the bond fix's work tallies (FixTLSPHBonds::tally_work) on the device:
   w -= dt f . v for the hourglass and the viscous force of every local
   particle, the same expression; the fix's host arrays are copied up first
   when they are the current ones (after an exchange, a restart, ...) */
template <class DeviceType, class Base>
bool PairTLSPHKokkosT<DeviceType, Base>::tally_work_device(double dt)
{
  const int nlocal = atom->nlocal;
  if (!work_device) {
    upload(d_whg, bonds->work_hg, nlocal, "tlsph/kk:work_hg");
    upload(d_wvisc, bonds->work_visc, nlocal, "tlsph/kk:work_visc");
    work_device = true;
  }
  atomKK->sync(execution_space, V_MASK);
  const auto v = atomKK->k_v.template view<DeviceType>();
  const double *fhg = d_fhg.data(), *fvisc = d_fvisc.data();
  double *whg = d_whg.data(), *wvisc = d_wvisc.data();
  Kokkos::parallel_for(
      "tlsph/kk:tally_work", Kokkos::RangePolicy<DeviceType>(0, nlocal),
      KOKKOS_LAMBDA(const int i) {
        whg[i] -= dt * (fhg[3 * i] * v(i, 0) + fhg[3 * i + 1] * v(i, 1) + fhg[3 * i + 2] * v(i, 2));
        wvisc[i] -=
            dt * (fvisc[3 * i] * v(i, 0) + fvisc[3 * i + 1] * v(i, 1) + fvisc[3 * i + 2] * v(i, 2));
      });
  return true;
}

/* the bond fix's work tallies and this step's hourglass and viscous forces
   to its host arrays (before it reads or moves them) */
template <class DeviceType, class Base>
void PairTLSPHKokkosT<DeviceType, Base>::work_to_host()
{
  const int nlocal = atom->nlocal;
  if (work_device) {
    download(bonds->work_hg, d_whg, 0, nlocal);
    download(bonds->work_visc, d_wvisc, 0, nlocal);
    work_device = false;
  }
  if (!forces_on_host && d_fhg.extent(0) >= (size_t) 3 * nlocal) {
    download(bonds->f_hg[0], d_fhg, 0, (size_t) 3 * nlocal);
    download(bonds->f_visc[0], d_fvisc, 0, (size_t) 3 * nlocal);
    forces_on_host = true;
  }
}

/* atom data of mask current on the host for host code of ours (the bond
   fix's work and energy, the bond cache rebuild, the classic communication
   of the velocity filter). On a GPU the atom style's ledger counts what
   this copies; in the device model (one memory) it is counted here, as a
   copy to the host of the fields the mask names. host_modified: host code
   changed them, and the device's next read copies them back. */
template <class DeviceType, class Base>
void PairTLSPHKokkosT<DeviceType, Base>::host_sync(unsigned int mask)
{
  atomKK->sync(Host, mask);
  count_host_code(mask, 1);
}

template <class DeviceType, class Base>
void PairTLSPHKokkosT<DeviceType, Base>::host_modified(unsigned int mask)
{
  atomKK->modified(Host, mask);
  count_host_code(mask, 0);
}

// the device model's count of a host access (to_host 1) or change (0) of
// the fields the mask names (as modified() reads it); a field read again in
// the same step is on the host already (the device changes it once per
// step, in the integrator): counted once per step
template <class DeviceType, class Base>
void PairTLSPHKokkosT<DeviceType, Base>::count_host_code(unsigned int mask, int to_host)
{
  if (!TLSPHKK::device_model()) return;
  double bytes;
  const auto *avec = static_cast<AtomVecPeriKokkos *>(atom->avec);
  const std::string f = avec->mask_fields(mask, true, &bytes);
  if (f.empty()) return;
  if (to_host) {
    bigint &last = host_synced[f];
    if (last == update->ntimestep) return;
    last = update->ntimestep;
  }
  TLSPHKK::count_copy("host-code " + f, to_host, bytes);
}

/* The host<->device copies of the run just ended (FixTLSPHBonds::post_run),
   summed over the ranks, one log line per source that copied; then the
   counts are cleared. Sources:
     atom FIELD     the atom style's ledger of the DualView protocol (GPU)
     own LABEL      this style's and its fixes' own arrays (upload, download)
     host-code F..  host code of ours reading (to host) or changing (to
                    device) atom fields (device model: tlsph_kk_copies.h)
     host-fix ID/STYLE:masks|no-masks  a fix without a Kokkos variant that
                    LAMMPS runs on the host every step: its datamask_read
                    goes to the host, its datamask_modify back (counted as
                    one each way per hook call; no-masks: it declares no
                    atom data, see there)
     comm-host NAME LAMMPS's forward (x) or reverse (f) communication on the
                    host (-pk kokkos comm host/no, or no GPU-aware MPI)
   On a host backend without the device model (one memory, every call names
   Host) nothing is counted, and the report says so. Format, for scripts
   (unittest/kokkos/check_kokkos.py, case transfers):
     tlsph/kk copies: run of N steps on the device|the device model|a host backend ...
     tlsph/kk copies: SOURCE NAME TO_DEVICE TO_HOST MBYTES */
template <class DeviceType, class Base>
void PairTLSPHKokkosT<DeviceType, Base>::report_copies(bigint nsteps)
{
  auto *avec = dynamic_cast<AtomVecPeriKokkos *>(atom->avec);
  auto &own = TLSPHKK::copy_ledger();
  // where the bond caches of this run were built (every rank builds at
  // every neighbor build: rank 0's counts)
  if (comm->me == 0) {
    std::string line = fmt::format("tlsph/kk bond cache: {} device builds, {} host builds",
                                   device_builds, host_builds);
    if (device_builds)
      line += fmt::format(" (per device build on rank 0: partners resolved {:.3f} ms, of {} builds "
                          "{} on the device; uploads {:.3f} ms, bond math {:.3f} ms)",
                          1e3 * build_time[0] / device_builds, device_builds, device_resolves,
                          1e3 * build_time[1] / device_builds, 1e3 * build_time[2] / device_builds);
    if (device_builds || host_builds)
      line += fmt::format("; layout: chunks of {} particles: the last cache {:.0f} records for "
                          "{:.0f} bonds on rank 0 = {:.1f} % padding", slice, layout_records,
                          layout_bonds,
                          layout_records > 0.0 ? 100.0 * (1.0 - layout_bonds / layout_records) : 0.0) +
          (pk_columns ? " (partner rows read as columns)" : "");
    if (env_flag("TLSPH_KK_CACHE_CHECK"))
      line += fmt::format(", the device builds checked against the host build: largest "
                          "relative difference {:.3g}", cache_check_worst);
    utils::logmesg(this->lmp, line + "\n");
  }
  device_builds = host_builds = device_resolves = 0;
  cache_check_worst = 0.0;
  build_time[0] = build_time[1] = build_time[2] = 0.0;
  if (!on_device()) {
    if (avec) avec->ledger_clear_counts();
    own.clear();
    if (comm->me == 0)
      utils::logmesg(this->lmp, fmt::format("tlsph/kk copies: run of {} steps on a host backend: "
                                            "one memory, no copies to count\n", nsteps));
    return;
  }
  const bool model = TLSPHKK::device_model();
  std::vector<std::string> names;
  std::vector<double> counts;    // per entry: to device, to host, bytes
  auto add = [&](const std::string &name, double to_dev, double to_host, double bytes) {
    names.push_back(name);
    counts.push_back(to_dev);
    counts.push_back(to_host);
    counts.push_back(bytes);
  };
  if (avec) {
    // on a GPU; the device model's calls name Host and Device as it pleases
    // LAMMPS's own styles (one memory): their counts would mean nothing
    if (!model)
      for (int k = 0; k < AtomVecPeriKokkos::NFIELD; k++)
        add(std::string("atom ") + AtomVecPeriKokkos::field_name(k), avec->ledger.copies[k][0],
            avec->ledger.copies[k][1], avec->ledger.bytes[k][0] + avec->ledger.bytes[k][1]);
    avec->ledger_clear_counts();
  }
  // fixes LAMMPS runs on the host every step (ModifyKokkos: their masks to
  // the host before each hook, back after it); the same on every rank
  {
    using namespace FixConst;
    const int hooks[] = {INITIAL_INTEGRATE, POST_INTEGRATE, PRE_FORCE,     PRE_REVERSE,
                         POST_FORCE,        FINAL_INTEGRATE, END_OF_STEP};
    for (int f = 0; f < this->modify->nfix; f++) {
      Fix *fix = this->modify->fix[f];
      if (fix->kokkosable) continue;
      int calls = 0;
      for (const int h : hooks)
        if (this->modify->fmask[f] & h) calls += (h == END_OF_STEP) ? 0 : 1;
      double per_step = calls;
      if ((this->modify->fmask[f] & END_OF_STEP) && fix->nevery > 0)
        per_step += 1.0 / fix->nevery;
      if (per_step == 0.0) continue;
      // counted as one copy each way per hook call whatever its masks say
      // (an upper bound), and named with them: a host fix that declares no
      // atom data (many fixes of this LAMMPS version declare none) makes
      // LAMMPS copy nothing; if it reads per-atom data anyway, it reads them
      // stale on a GPU, which is no better
      const double n = per_step * nsteps;
      const bool masked = fix->datamask_read != EMPTY_MASK || fix->datamask_modify != EMPTY_MASK;
      add(fmt::format("host-fix {}/{}:{}", fix->id, fix->style, masked ? "masks" : "no-masks"), n,
          n, 0.0);
    }
  }
  // LAMMPS's communication of x (forward, every step) and of f (reverse,
  // newton on) through the host
  {
    const auto *kk = this->lmp->kokkos;
    if (kk->forward_comm_classic || kk->forward_comm_on_host)
      add("comm-host x", (double) nsteps, (double) nsteps, 0.0);
    if (this->force->newton_pair && (kk->reverse_comm_classic || kk->reverse_comm_on_host))
      add("comm-host f", (double) nsteps, (double) nsteps, 0.0);
  }
  // the labels of the own ledger are the same on every rank, but a rank may
  // not have copied one of them: agree on the union first (rank 0's list
  // plus what the others add, gathered as one string)
  std::string mine;
  for (const auto &e : own) mine += e.first + "\n";
  int len = mine.size(), nprocs = comm->nprocs;
  std::vector<int> lens(nprocs), displs(nprocs, 0);
  MPI_Allgather(&len, 1, MPI_INT, lens.data(), 1, MPI_INT, this->world);
  for (int p = 1; p < nprocs; p++) displs[p] = displs[p - 1] + lens[p - 1];
  std::string all(displs[nprocs - 1] + lens[nprocs - 1], '\0');
  MPI_Allgatherv(&mine[0], len, MPI_CHAR, &all[0], lens.data(), displs.data(), MPI_CHAR,
                 this->world);
  std::map<std::string, int> labels;
  for (size_t a = 0, b; (b = all.find('\n', a)) != std::string::npos; a = b + 1)
    labels[all.substr(a, b - a)] = 0;
  for (const auto &l : labels) {
    const auto it = own.find(l.first);
    std::string name = l.first.empty() ? std::string("(unlabelled)") : l.first;
    if (name.compare(0, 10, "host-code ") != 0) name = "own " + name;
    if (it == own.end()) add(name, 0.0, 0.0, 0.0);
    else add(name, it->second.n[0], it->second.n[1], it->second.bytes[0] + it->second.bytes[1]);
  }
  own.clear();
  std::vector<double> sum(counts.size());
  MPI_Allreduce(counts.data(), sum.data(), (int) counts.size(), MPI_DOUBLE, MPI_SUM, this->world);
  if (comm->me != 0) return;
  std::string out = fmt::format("tlsph/kk copies: run of {} steps on {} (host<->device, all "
                                "ranks)\n", nsteps,
                                model ? "the device model (a host backend, TLSPH_KK_DEVICE_MODEL)"
                                      : "the device");
  for (size_t e = 0; e < names.size(); e++)
    if (sum[3 * e] > 0 || sum[3 * e + 1] > 0)
      out += fmt::format("tlsph/kk copies: {} {:.0f} {:.0f} {:.3f}\n", names[e], sum[3 * e],
                         sum[3 * e + 1], sum[3 * e + 2] / 1.0e6);
  utils::logmesg(this->lmp, out);
}

/* F, psi and the hourglass energy of the local particles to the host
   arrays of PairTLSPH (the computes read them there) */
template <class DeviceType, class Base>
void PairTLSPHKokkosT<DeviceType, Base>::sync_host()
{
  if (host_current && host_step == update->ntimestep) return;
  if (kk_nmax == 0 || d_F.extent(0) == 0) return;    // no force call yet
  const int nlocal = atom->nlocal;
  download(F[0], d_F, 0, (size_t) 9 * nlocal);
  download(psi, d_psi, 0, nlocal);
  download(ehg, d_ehg, 0, nlocal);
  // the bond rows for host code that reads them (compute tlsph/damage/atom,
  // the CPU velocity filter: counts, row starts, partner indices); the
  // device holds the bond cache, breaks included
  if (uploaded_version >= 0 && d_start.extent(0) > (size_t) nlocal) {
    // the sliced layout back to rows (bond m of i at record st[i] + m slice)
    std::vector<int> st, nc;
    download_rows(st, nc);
    const size_t nrec = st[nlocal];
    std::vector<int> js(nrec);
    download(js.data(), d_bj, 0, nrec);
    int nb = 0;
    for (int i = 0; i < nlocal; i++) nb += nc[i];
    this->reserve_bond_cache(nb);
    download(nbond, d_nbond, 0, nlocal);
    download(nlead, d_nlead, 0, nlocal);
    bond_start[0] = 0;
    for (int i = 0; i < nlocal; i++) bond_start[i + 1] = bond_start[i] + nc[i];
    records_to_rows(js.data(), 1, st, nc, slice, bond_start, lean.j);
  }
  host_current = 1;
  host_step = update->ntimestep;
}

/* ---------------------------------------------------------------------- */

/* forward communication on the device: the packed rows (tlsph/damage's
   stage 1: the damage phi), rows of comm_stride() values */
template <class DeviceType, class Base>
int PairTLSPHKokkosT<DeviceType, Base>::pack_forward_comm_kokkos(int n, DAT::tdual_int_2d k_sendlist,
                                                                int iswap, DAT::tdual_xfloat_1d &buf,
                                                                int /*pbc_flag*/, int * /*pbc*/)
{
  const int stage = comm_stage_now();
  const auto list = k_sendlist.template view<DeviceType>();
  const auto out = buf.template view<DeviceType>();
  const double *rows = comm_view(stage).data();
  const int ps = comm_stride(stage);
  Kokkos::parallel_for(
      "tlsph/kk:pack", Kokkos::RangePolicy<DeviceType>(0, n), KOKKOS_LAMBDA(const int ii) {
        const int j = list(iswap, ii);
        for (int k = 0; k < ps; k++) out(ps * ii + k) = rows[(long) ps * j + k];
      });
  return n * ps;
}

template <class DeviceType, class Base>
void PairTLSPHKokkosT<DeviceType, Base>::unpack_forward_comm_kokkos(int n, int first,
                                                                   DAT::tdual_xfloat_1d &buf)
{
  const int stage = comm_stage_now();
  const auto in = buf.template view<DeviceType>();
  double *rows = comm_view(stage).data();
  const int ps = comm_stride(stage);
  Kokkos::parallel_for(
      "tlsph/kk:unpack", Kokkos::RangePolicy<DeviceType>(0, n), KOKKOS_LAMBDA(const int ii) {
        for (int k = 0; k < ps; k++) rows[(long) ps * (first + ii) + k] = in(ps * ii + k);
      });
}

/* host path of the forward communication (tlsph/kk/host, or LAMMPS's
   classic communication): the rows go through the CPU style's host arrays */
template <class DeviceType, class Base>
int PairTLSPHKokkosT<DeviceType, Base>::pack_forward_comm(int n, int *list, double *buf,
                                                         int pbc_flag, int *pbc)
{
  // every row a swap may send: local particles and ghosts received earlier
  const int stage = comm_stage_now();
  const int nall = atom->nlocal + atom->nghost;
  download(comm_host(stage), comm_view(stage), 0, (size_t) comm_stride(stage) * nall);
  return Base::pack_forward_comm(n, list, buf, pbc_flag, pbc);
}

template <class DeviceType, class Base>
void PairTLSPHKokkosT<DeviceType, Base>::unpack_forward_comm(int n, int first, double *buf)
{
  Base::unpack_forward_comm(n, first, buf);
  const int stage = comm_stage_now();
  const size_t ps = comm_stride(stage);
  Kokkos::deep_copy(Kokkos::subview(comm_view(stage), std::make_pair(ps * first, ps * (first + n))),
                    HostUnmanaged<const double>(comm_host(stage) + ps * first, ps * n));
  TLSPHKK::count_copy(comm_view(stage).label(), 0, sizeof(double) * (double) (ps * n));
}

template <class DeviceType, class Base>
double PairTLSPHKokkosT<DeviceType, Base>::memory_usage()
{
  double bytes = Base::memory_usage();
  for (const dview *v : {&d_Q, &d_sumg, &d_F, &d_P, &d_fown, &d_pk, &d_psi, &d_ehg, &d_x0c,
                         &d_fhg, &d_fvisc, &d_bg, &d_bw, &d_whg, &d_wvisc})
    bytes += sizeof(double) * v->extent(0);
  for (const iview *v : {&d_nbond, &d_nlead, &d_start, &d_bj, &d_bk, &d_ncache, &d_cbase})
    bytes += sizeof(int) * v->extent(0);
  return bytes;
}

namespace LAMMPS_NS {
template class PairTLSPHKokkosT<LMPDeviceType, PairTLSPH>;
template class PairTLSPHKokkosT<LMPDeviceType, PairTLSPHDamage>;
template class PairTLSPHKokkos<LMPDeviceType>;
#ifdef LMP_KOKKOS_GPU
template class PairTLSPHKokkosT<LMPHostType, PairTLSPH>;
template class PairTLSPHKokkosT<LMPHostType, PairTLSPHDamage>;
template class PairTLSPHKokkos<LMPHostType>;
#endif
}    // namespace LAMMPS_NS
