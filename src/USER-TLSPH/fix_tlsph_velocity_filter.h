/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: fix tlsph/velocity/filter (doc/fix_tlsph_velocity_filter.rst)

   Velocity smoothing in damaged zones (thesis Eq. 2.36): after the
   velocity update, every particle of the group with damage phi > phi_c gets
     v_i <- v_i - eps sum_j (v_i - v_j) W_ij / sum_j W_ij
   over its intact bonds. All particles are filtered from the same old
   velocities (Jacobi), so the result does not depend on the order or on
   the MPI decomposition.
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(tlsph/velocity/filter,FixTLSPHVelocityFilter)
// clang-format on
#else

#ifndef LMP_FIX_TLSPH_VELOCITY_FILTER_H
#define LMP_FIX_TLSPH_VELOCITY_FILTER_H

#include "fix.h"

#include <vector>

namespace LAMMPS_NS {

class FixTLSPHVelocityFilter : public Fix {
 public:
  FixTLSPHVelocityFilter(class LAMMPS *, int, char **);
  ~FixTLSPHVelocityFilter() override;
  int setmask() override;
  void init() override;
  void end_of_step() override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  double compute_scalar() override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

 protected:
  double phi_c, eps;
  class PairTLSPHDamage *pair;
  void record_energy(double);    // the energy taken out in this step
  std::vector<int> fidx;       // the particles filtered in this step
  std::vector<double> fvel;    // their new velocities (3 each)
  bigint nfiltered;
  // the kinetic energy the filter took out: in the last step and since the
  // fix was defined (this rank's share; the restart file holds the sum)
  double de_step = 0.0, de_sum = 0.0;
};

}    // namespace LAMMPS_NS

#endif
#endif
