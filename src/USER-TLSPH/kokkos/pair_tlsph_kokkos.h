/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: pair_style tlsph/kk, the KOKKOS variant of pair_style tlsph
   (doc/pair_tlsph_kokkos.rst)

   Same settings, materials, restart data and physics as tlsph: the two
   per-particle passes of the step run as Kokkos kernels over the local
   particles and call the same physics headers (tlsph_particle.h through
   PairTLSPH::stress_row and TLSPH::particle_force_bonds). Per-particle
   state (F, P, packed rows, psi, ...) and the lean bond arrays live in
   device views between steps; the bond cache is built on the host after
   each neighbor build (as tlsph does) and copied to the device then.
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

namespace LAMMPS_NS {

template <class DeviceType> class PairTLSPHKokkos : public PairTLSPH, public KokkosBase {
 public:
  typedef DeviceType device_type;
  typedef ArrayTypes<DeviceType> AT;
  typedef Kokkos::View<double *, DeviceType> dview;
  typedef Kokkos::View<int *, DeviceType> iview;

  PairTLSPHKokkos(class LAMMPS *);
  ~PairTLSPHKokkos() override;
  void compute(int, int) override;
  void init_style() override;
  void sync_host() override;

  int pack_forward_comm_kokkos(int, DAT::tdual_int_2d, int, DAT::tdual_xfloat_1d &, int,
                               int *) override;
  void unpack_forward_comm_kokkos(int, int, DAT::tdual_xfloat_1d &) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  double memory_usage() override;

  // the kernels (public: device lambdas may not live in private members)
  template <int DIM, int ORDER, int LAWS> int deformation_kernel();
  template <int DIM, int ORDER, int HG, int VISC, int VIRIAL> void force_kernel(double *vir);
  template <int DIM, int ORDER> void dispatch_force(int hg, int visc, int vir, double *v);

 protected:
  class AtomKokkos *atomKK;
  // device copies: per particle (strides as in PairTLSPH), per bond, per type
  int kk_nmax;                 // particles the per-particle views hold
  dview d_Q, d_sumg, d_F, d_P, d_fown, d_pk, d_psi, d_ehg, d_x0c, d_fhg, d_fvisc;
  iview d_nbond, d_start, d_bj;
  dview d_bg, d_bw;
  Kokkos::View<Material *, DeviceType> d_mat;
  Kokkos::View<TLSPH::PairMaterial *, DeviceType> d_pm;
  int host_current;            // 1: the host arrays F, psi, ehg hold this step's values
  bigint host_step;
  // forward communication (device path)
  typename AT::t_int_2d d_sendlist;
  typename AT::t_xfloat_1d d_buf;
  int first_recv;
  void grow_device();
  void upload_bond_cache();
};

}    // namespace LAMMPS_NS

#endif
#endif
