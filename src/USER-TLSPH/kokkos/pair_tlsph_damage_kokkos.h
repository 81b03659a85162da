/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: pair_style tlsph/damage/kk, the KOKKOS variant of
   pair_style tlsph/damage (doc/pair_tlsph_kokkos.rst)

   tlsph/kk (pair_tlsph_kokkos.h) plus, on the device: the stretch criterion
   fused into pass (1) (bonds break inside the deformation kernel, in the
   order tlsph/damage breaks them), the damage phi, its smoothed form and
   the adaptive viscosity alpha_i. The kernel's breaks (particle, slot) are
   replayed on the host copy of the bond cache and on the bond fix (the
   state that migrates and is written to restart files): the same few
   operations, so that both copies stay equal without copying the cache.
   The 'correction setup' policy (the thesis's, the default) only.
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(tlsph/damage/kk,PairTLSPHDamageKokkos<LMPDeviceType>);
PairStyle(tlsph/damage/kk/device,PairTLSPHDamageKokkos<LMPDeviceType>);
PairStyle(tlsph/damage/kk/host,PairTLSPHDamageKokkos<LMPHostType>);
// clang-format on
#else

#ifndef LMP_PAIR_TLSPH_DAMAGE_KOKKOS_H
#define LMP_PAIR_TLSPH_DAMAGE_KOKKOS_H

#include "pair_tlsph_kokkos.h"    // first: it defines TLSPH_KOKKOS
#include "pair_tlsph_damage.h"

namespace LAMMPS_NS {

template <class DeviceType>
class PairTLSPHDamageKokkos : public PairTLSPHKokkosT<DeviceType, PairTLSPHDamage> {
 public:
  typedef PairTLSPHKokkosT<DeviceType, PairTLSPHDamage> KK;
  typedef typename KK::dview dview;
  typedef typename KK::iview iview;

  PairTLSPHDamageKokkos(class LAMMPS *);
  void init_style() override;
  void sync_host() override;
  double memory_usage() override;

  // what fix tlsph/velocity/filter/kk reads on the device (valid after a
  // force call): the intact bonds of local particle i are bj[start[i] + m
  // stride] for m < nbond[i] (the sliced layout, pair_tlsph_kokkos.h),
  // X_ij = x0c_j - x0c_i (3 per particle), phi its damage
  struct DeviceBonds {
    const int *start, *nbond, *bj;
    const double *x0c, *phi;
    TLSPH::CubicSpline kernel;
    int stride;
  };
  DeviceBonds device_bonds() const
  {
    return DeviceBonds{this->d_start.data(), this->d_nbond.data(), this->d_bj.data(),
                       this->d_x0c.data(), d_phi.data(), this->kernel, this->slice};
  }

  // the kernels (public: device lambdas may not live in private members)
  template <int DIM, int ORDER, int LAWS, int ABS, int PAIRS> int break_kernel();
  template <int DIM, int ORDER, int LAWS> int dispatch_break();
  template <int DIM> void smooth_kernel();
  template <int DIM> void replay_breaks(int n);
  void damage_step() override;    // public: it holds device lambdas

 protected:
  int deformation_step() override;
  void after_cache_build(size_t nb) override;
  int comm_stage_now() const override { return this->comm_stage == 1 ? 1 : 0; }
  dview &comm_view(int stage) override { return stage == 1 ? d_phi : this->d_pk; }
  double *comm_host(int stage) override { return stage == 1 ? this->phi : this->pk[0]; }
  int comm_stride(int stage) override { return stage == 1 ? 1 : this->packed_size(); }

  dview d_phi, d_mark, d_phis;          // damage, marks of damaged partners, smoothed damage
  dview d_sc, d_up, d_down;             // per type s_c; per type pair (1 +- s_c)^2
  iview d_nintact0;                     // bonds at setup (the damage's denominator)
  iview d_broken_i, d_broken_m;         // this step's breaks: particle, slot in the bond fix
  Kokkos::View<int, DeviceType> d_nbroken;
  int damage_current;                   // 1: the host phi, phis hold this step's values
};

}    // namespace LAMMPS_NS

#endif
#endif
