/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: compute tlsph/crack/tips (doc/compute_tlsph_crack_tips.rst)

   The crack tips of pair_style tlsph/damage 'criterion tip', one row per
   tip (branches included; a stopped tip keeps its row):
     [1] x  [2] y   the tip (reference coordinates)
     [3] 1 while the tip is live, 0 once it stopped or branched
     [4] K_I  [5] K_II   stress intensity factors (displacement correlation)
     [6] G    [7] G / G_c   energy release rate of the kink direction
     [8] kink angle of the maximum tangential stress [deg]
     [9] speed (0 when not growing)  [10] length of its path (the
     pre-crack included)
   as measured at the last force evaluation. Global vector: [1] tips,
   [2] live tips.
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(tlsph/crack/tips,ComputeTLSPHCrackTips)
// clang-format on
#else

#ifndef LMP_COMPUTE_TLSPH_CRACK_TIPS_H
#define LMP_COMPUTE_TLSPH_CRACK_TIPS_H

#include "compute.h"

namespace LAMMPS_NS {

class ComputeTLSPHCrackTips : public Compute {
 public:
  ComputeTLSPHCrackTips(class LAMMPS *, int, char **);
  ~ComputeTLSPHCrackTips() override;
  void init() override;
  void compute_vector() override;
  void compute_array() override;
  double memory_usage() override;

  static constexpr int NCOL = 11;

 private:
  double values[2];
  int nrows_max;
  class PairTLSPHDamage *pair;
  void fill();
};

}    // namespace LAMMPS_NS

#endif
#endif
