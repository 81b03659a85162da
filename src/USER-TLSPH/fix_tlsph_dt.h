/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: fix tlsph/dt, CFL time step for pair tlsph
   (doc/fix_tlsph_dt.rst)

   dt = C h / max_i (c0_i + |v_i|), c0 the longitudinal wave speed of the
   particle's material; reset every N steps like fix dt/reset.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(tlsph/dt,FixTLSPHDt)
// clang-format on
#else

#ifndef LMP_FIX_TLSPH_DT_H
#define LMP_FIX_TLSPH_DT_H

#include "fix.h"

namespace LAMMPS_NS {

class FixTLSPHDt : public Fix {
 public:
  FixTLSPHDt(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup(int) override;
  void end_of_step() override;
  double compute_scalar() override;

 protected:
  double courant;
  class PairTLSPH *pair;
  void update_dt();
  // max over the local particles of the group of c0 + |v| (fix tlsph/dt/kk: on the device)
  virtual double local_max_speed();
};

}    // namespace LAMMPS_NS

#endif
#endif
