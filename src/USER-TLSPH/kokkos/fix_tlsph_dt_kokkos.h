/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: fix tlsph/dt/kk, the KOKKOS variant of fix tlsph/dt
   (doc/fix_tlsph_dt.rst): the largest c0 + |v| of the group as a Kokkos
   reduction over the velocities on the device; the rest is fix tlsph/dt's.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(tlsph/dt/kk,FixTLSPHDtKokkos<LMPDeviceType>);
FixStyle(tlsph/dt/kk/device,FixTLSPHDtKokkos<LMPDeviceType>);
FixStyle(tlsph/dt/kk/host,FixTLSPHDtKokkos<LMPHostType>);
// clang-format on
#else

#ifndef LMP_FIX_TLSPH_DT_KOKKOS_H
#define LMP_FIX_TLSPH_DT_KOKKOS_H

#include "fix_tlsph_dt.h"
#include "kokkos_type.h"

namespace LAMMPS_NS {

template <class DeviceType> class FixTLSPHDtKokkos : public FixTLSPHDt {
 public:
  FixTLSPHDtKokkos(class LAMMPS *, int, char **);
  void init() override;
  double local_max_speed() override;    // public: it holds a device lambda

 protected:
  Kokkos::View<double *, DeviceType> d_c0;    // c0 per atom type
};

}    // namespace LAMMPS_NS

#endif
#endif
