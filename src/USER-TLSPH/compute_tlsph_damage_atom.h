/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: compute tlsph/damage/atom (doc/compute_tlsph_damage_atom.rst)

   Per atom: [1] damage phi = 1 - intact/initial bonds (thesis Eq. 2.33),
   [2] smoothed damage phi' (Eq. 2.34), [3] intact bonds, [4] initial bonds.
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(tlsph/damage/atom,ComputeTLSPHDamageAtom)
// clang-format on
#else

#ifndef LMP_COMPUTE_TLSPH_DAMAGE_ATOM_H
#define LMP_COMPUTE_TLSPH_DAMAGE_ATOM_H

#include "compute.h"

namespace LAMMPS_NS {

class ComputeTLSPHDamageAtom : public Compute {
 public:
  ComputeTLSPHDamageAtom(class LAMMPS *, int, char **);
  ~ComputeTLSPHDamageAtom() override;
  void init() override;
  void compute_peratom() override;
  double memory_usage() override;

 private:
  int nmax;
  double **values;
  class PairTLSPHDamage *pair;
};

}    // namespace LAMMPS_NS

#endif
#endif
