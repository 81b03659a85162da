/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: pair_style tlsph/kk, the KOKKOS variant of pair_style tlsph
   (doc/pair_tlsph_kokkos.rst)

   Same settings, materials, restart data and physics as tlsph: the two
   per-particle passes of the step run as Kokkos kernels over the local
   particles and call the same physics headers (tlsph_particle.h through
   PairTLSPH::stress_row and TLSPH::particle_force_bonds). Per-particle
   state (F, P, packed rows, psi, ...) and the lean bond arrays live in
   device views between steps. After each neighbor build the bond cache is
   built on the device from the bond fix's partner rows (build_bond_cache);
   an ordinary step copies nothing between host and
   device (tlsph_kk_copies.h, ctest kokkos.transfers).
   The force pass uses the gather form of the stress term (every particle
   sums its whole force from its bonds, no scatter, no atomics), i.e. the
   form that tlsph uses with newton_pair off; forces equal tlsph's to
   round-off.
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(tlsph/kk,PairTLSPHKokkos<LMPDeviceType>);
PairStyle(tlsph/kk/device,PairTLSPHKokkos<LMPDeviceType>);
PairStyle(tlsph/kk/host,PairTLSPHKokkos<LMPHostType>);
// clang-format on
#else

#ifndef LMP_PAIR_TLSPH_KOKKOS_H
#define LMP_PAIR_TLSPH_KOKKOS_H

#ifndef TLSPH_KOKKOS
#define TLSPH_KOKKOS    // physics headers: KOKKOS_INLINE_FUNCTION
#endif

#include "kokkos_base.h"
#include "kokkos_type.h"
#include "pair_tlsph.h"
#include "tlsph_kk_copies.h"

#include <map>
#include <string>
#include <utility>

namespace LAMMPS_NS {

/* The Kokkos machinery of the /kk styles, on top of the CPU style Base
   (PairTLSPH for tlsph/kk, PairTLSPHDamage for tlsph/damage/kk): settings,
   materials, the bond cache build and restarts are Base's. */
template <class DeviceType, class Base> class PairTLSPHKokkosT : public Base, public KokkosBase {
 public:
  typedef DeviceType device_type;
  typedef ArrayTypes<DeviceType> AT;
  typedef Kokkos::View<double *, DeviceType> dview;
  typedef Kokkos::View<int *, DeviceType> iview;
  typedef typename Base::Material Material;

  PairTLSPHKokkosT(class LAMMPS *);
  void compute(int, int) override;
  void init_style() override;
  void sync_host() override;
  bool tally_work_device(double dt) override;
  void work_to_host() override;
  void report_copies(bigint nsteps) override;
  bool on_device() const override { return this->execution_space == Device; }
  // the Kokkos kernels are the step (no host SIMD step)
  bool simd_capable() const override { return false; }
  void host_sync(unsigned int mask) override;
  void host_modified(unsigned int mask) override;
  void count_host_code(unsigned int mask, int to_host);

  int pack_forward_comm_kokkos(int, DAT::tdual_int_2d, int, DAT::tdual_xfloat_1d &, int,
                               int *) override;
  void unpack_forward_comm_kokkos(int, int, DAT::tdual_xfloat_1d &) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  double memory_usage() override;

  // what every kernel reads of the bond cache, by value in the kernels:
  // bonds<DIM>(i) is particle i's view of its bonds (pair_tlsph.h: bonds_of)
  // (bond m of particle i is record start[i] + m stride: the sliced layout)
  struct DeviceCache {
    const int *start, *bj;
    const double *bg, *bw, *x0c, *vfrac;
    TLSPH::CubicSpline kernel;
    int order, stride;
    template <int DIM> KOKKOS_INLINE_FUNCTION TLSPH::LeanBonds<DIM, TLSPH::StridedRows> bonds(int i) const
    {
      const int s = start[i];
      return TLSPH::LeanBonds<DIM, TLSPH::StridedRows>{
          bj + s, bg + DIM * s, bw + 2 * s, TLSPH::StridedRows{x0c, 3}, x0c + 3 * i, kernel,
          vfrac[i], order, stride};
    }
  };
  DeviceCache device_cache() const;

  // the kernels (public: device lambdas may not live in private members)
  template <int DIM, int ORDER, int LAWS> int deformation_kernel();
  template <int DIM, int ORDER, int HG, int VISC, int VIRIAL> void force_kernel(double *vir);
  template <int DIM, int ORDER, int HG, int VISC, int VIRIAL, class Rows>
  void force_gather(double *vir, const Rows &pkr);
  template <int DIM, int ORDER, int HG, int VISC, int VIRIAL> void force_kernel_scatter(double *vir);
  template <int DIM, int ORDER, int HG, int VISC, int VIRIAL> void force_pass(double *vir);
  template <int DIM, int ORDER> void dispatch_force(int hg, int visc, int vir, double *v);
  // the partners of the bond cache resolved on the device (public: device lambdas)
  bool device_resolve_ok() const;
  size_t resolve_bonds_device();
  iview d_npartner;
  Kokkos::View<unsigned char *, DeviceType> d_pstate;    // the bond fix's states (one byte each)
  Kokkos::View<tagint *, DeviceType> d_ptag;
  template <int DIM, int ORDER> long long bond_math_chunk(int first, int last, int maxn, int nq,
                                                    bool has_frozen, double kscale);

 protected:
  using Base::alpha;
  using Base::any_orthotropic;
  using Base::atom;
  using Base::beta;
  using Base::bond_start;
  using Base::bonds;
  using Base::cache_version;
  using Base::comm;
  using Base::comm_forward;
  using Base::correction_size;
  using Base::dim;
  using Base::eflag_either;
  using Base::ehg;
  using Base::error;
  using Base::ev_init;
  using Base::execution_space;
  using Base::datamask_read;
  using Base::datamask_modify;
  using Base::kokkosable;
  using Base::gather_rows;
  using Base::vflag_global;
  using Base::F;
  using Base::force;
  using Base::gamma;
  using Base::h;
  using Base::hg_form;
  using Base::kernel;
  using Base::lean;
  using Base::mat;
  using Base::nbond;
  using Base::nlead;
  using Base::order;
  using Base::P;
  using Base::packed_size;
  using Base::pairmat;
  using Base::pk;
  using Base::plane_stress;
  using Base::psi;
  using Base::Q;
  using Base::sumg;
  using Base::update;
  using Base::virial;
  using Base::x0c;

  class AtomKokkos *atomKK;
  // device copies: per particle (strides as in PairTLSPH), per bond, per type
  int kk_nmax;    // particles the per-particle views hold
  dview d_Q, d_sumg, d_F, d_P, d_fown, d_pk, d_psi, d_ehg, d_x0c, d_fhg, d_fvisc;
  iview d_nbond, d_nlead, d_start, d_bj, d_bk;
  dview d_bg, d_bw;
  /* The sliced layout of the device's bond cache (doc/kokkos-cuda.md): the
     particles in chunks of `slice` (C) consecutive ones; chunk c has room
     for C x width_c records, width_c its longest row, from record base_c;
     particle i = c C + l has its bond m at record base_c + l + m C, so the
     C threads of a warp, one particle each, read adjacent records of the
     same slot. C = 1 is the row layout of the CPU styles. d_start[i] is the
     record of bond 0, d_start[nlocal] the records in all; d_ncache[i] the
     bonds cached for i (the intact ones, then for the correction broken ones
     still present). Default: 32 (a warp) on a GPU, 1 on a host backend;
     TLSPH_KK_SLICE=C sets it (the tests run the host backend with C > 1). */
  int slice = 1;
  /* The gather form's partner rows (the packed rows, ghosts included) read
     column by column: copied into d_pkc (value k of row j at k nall + j)
     before the force kernel, so that a warp's threads, whose partners are
     nearby particles, read nearby addresses (TLSPH::ColumnRows).
     TLSPH_KK_PK_COLUMNS=1 switches it on (off by default until measured on a
     GPU; the tests run it on the host backend). */
  bool pk_columns = false;
  dview d_pkc;
  double layout_records = 0.0, layout_bonds = 0.0;    // of the last cache on the device
  iview d_ncache, d_cbase;
  void set_slice();
  size_t upload_rows(bool with_gw);    // host rows (bond_start, lean) into the sliced layout
  void download_rows(std::vector<int> &st, std::vector<int> &nc);
  Kokkos::View<Material *, DeviceType> d_mat;
  Kokkos::View<TLSPH::PairMaterial *, DeviceType> d_pm;
  int uploaded_version;    // cache_version of the bond cache on the device
  dview d_whg, d_wvisc;    // the bond fix's work tallies while work_device is set
  bool work_device;        // the tallies live on the device (the fix's host copy is stale)
  bool forces_on_host;     // the fix's host f_hg, f_visc hold this step's forces
  std::map<std::string, bigint> host_synced;    // device model: step of each host_sync
  int host_current;        // 1: the host arrays F, psi, ehg hold this step's values
  bigint host_step;
  void grow_device();
  virtual void upload_bond_cache();
  // after every bond cache that reaches the device, with its nb bonds
  // (tlsph/damage/kk: its extras)
  virtual void after_cache_build(size_t /*nb*/) {}
  // the bond cache after a neighbor build: partners resolved
  // (resolve_bonds_device) and the bond math run (bond_math_chunk) on the
  // device; the host build where the device one does not apply (see the .cpp)
  void build_bond_cache() override;
  Kokkos::View<TLSPH::Bond *, DeviceType> d_scratch;    // bond records of a chunk of particles
  dview d_vjs, d_frozen;
  int device_builds = 0, host_builds = 0;    // bond cache builds of this run, by where
  int device_resolves = 0;                   // device builds whose partners the device resolved
  double build_time[3] = {0.0, 0.0, 0.0};    // device builds: resolve, uploads, bond math [s]
  double cache_check_worst = 0.0;            // TLSPH_KK_CACHE_CHECK: largest difference
  void check_device_cache();
  // pass (1), returns the first unstable particle or -1; tlsph/damage/kk breaks bonds in it
  virtual int deformation_step();
  // between passes (1) and (2): tlsph/damage/kk updates the damage and alpha_i
  virtual void damage_step() {}
  // what the forward communication moves (stage: tlsph/damage's comm_stage)
  virtual int comm_stage_now() const { return 0; }
  virtual dview &comm_view(int) { return d_pk; }
  virtual double *comm_host(int) { return pk[0]; }
  virtual int comm_stride(int) { return packed_size(); }
};

template <class DeviceType> class PairTLSPHKokkos : public PairTLSPHKokkosT<DeviceType, PairTLSPH> {
 public:
  PairTLSPHKokkos(class LAMMPS *lmp) : PairTLSPHKokkosT<DeviceType, PairTLSPH>(lmp) {}
};

}    // namespace LAMMPS_NS

#endif
#endif
