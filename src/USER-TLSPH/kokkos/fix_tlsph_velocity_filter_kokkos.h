/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: fix tlsph/velocity/filter/kk, the KOKKOS variant of fix
   tlsph/velocity/filter (doc/fix_tlsph_velocity_filter.rst): the ghost
   velocities by a forward communication on the device, then the same Jacobi
   filter as a Kokkos kernel over the bonds and damage that
   pair_style tlsph/damage/kk keeps on the device.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(tlsph/velocity/filter/kk,FixTLSPHVelocityFilterKokkos<LMPDeviceType>);
FixStyle(tlsph/velocity/filter/kk/device,FixTLSPHVelocityFilterKokkos<LMPDeviceType>);
FixStyle(tlsph/velocity/filter/kk/host,FixTLSPHVelocityFilterKokkos<LMPHostType>);
// clang-format on
#else

#ifndef LMP_FIX_TLSPH_VELOCITY_FILTER_KOKKOS_H
#define LMP_FIX_TLSPH_VELOCITY_FILTER_KOKKOS_H

#include "fix_tlsph_velocity_filter.h"
#include "kokkos_base.h"
#include "kokkos_type.h"

namespace LAMMPS_NS {

template <class DeviceType> class PairTLSPHDamageKokkos;

template <class DeviceType>
class FixTLSPHVelocityFilterKokkos : public FixTLSPHVelocityFilter, public KokkosBase {
 public:
  FixTLSPHVelocityFilterKokkos(class LAMMPS *, int, char **);
  void init() override;
  void end_of_step() override;
  int pack_forward_comm_fix_kokkos(int, DAT::tdual_int_2d, int, DAT::tdual_xfloat_1d &, int,
                                   int *) override;
  void unpack_forward_comm_fix_kokkos(int, int, DAT::tdual_xfloat_1d &) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  template <int DIM> void filter();    // public: it holds device lambdas

 protected:
  class AtomKokkos *atomKK;
  PairTLSPHDamageKokkos<DeviceType> *kkpair;
  Kokkos::View<double *, DeviceType> d_vnew;
};

}    // namespace LAMMPS_NS

#endif
#endif
