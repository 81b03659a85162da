/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: compute tlsph/energy (doc/compute_tlsph_energy.rst)

   Global vector over the group:
     [1] strain energy      sum_i V_i psi(E_i)
     [2] hourglass energy   work done against the hourglass forces
     [3] viscous dissipation work dissipated by the artificial viscosity
     [4] kinetic energy     sum_i m_i |v_i|^2 / 2
   so that [1] + [2] + [3] + [4] - (work of external loads) is conserved.
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(tlsph/energy,ComputeTLSPHEnergy)
// clang-format on
#else

#ifndef LMP_COMPUTE_TLSPH_ENERGY_H
#define LMP_COMPUTE_TLSPH_ENERGY_H

#include "compute.h"

namespace LAMMPS_NS {

class ComputeTLSPHEnergy : public Compute {
 public:
  ComputeTLSPHEnergy(class LAMMPS *, int, char **);
  void init() override;
  void compute_vector() override;

 private:
  double values[4];
  class PairTLSPH *pair;
};

}    // namespace LAMMPS_NS

#endif
#endif
