/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: fix tlsph/relax, kinetic damping for dynamic relaxation
   (doc/fix_tlsph_relax.rst)

   Cundall's kinetic damping: the undamped motion is integrated and, each
   time the kinetic energy of the group passes a maximum, all velocities of
   the group are set to zero. The static state of a quasi-static scene is
   reached without choosing a damping coefficient.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(tlsph/relax,FixTLSPHRelax)
// clang-format on
#else

#ifndef LMP_FIX_TLSPH_RELAX_H
#define LMP_FIX_TLSPH_RELAX_H

#include "fix.h"

namespace LAMMPS_NS {

class FixTLSPHRelax : public Fix {
 public:
  FixTLSPHRelax(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void end_of_step() override;
  double compute_vector(int) override;

 private:
  double ke_prev;    // kinetic energy at the previous check
  bigint nresets;    // number of velocity resets so far
  double ke_last;    // kinetic energy at the last check
  double kinetic_energy();
};

}    // namespace LAMMPS_NS

#endif
#endif
