/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: per-atom tensors of pair tlsph (doc/compute_tlsph_atom.rst)

   compute ID group tlsph/stress/atom   -> Cauchy stress   xx yy zz xy xz yz
   compute ID group tlsph/strain/atom   -> Green-Lagrange  xx yy zz xy xz yz
   compute ID group tlsph/defgrad/atom  -> F (row-major 9) and det(F)
   One class, three styles: they differ only in which tensor they copy.
------------------------------------------------------------------------- */

#ifdef COMPUTE_CLASS
// clang-format off
ComputeStyle(tlsph/stress/atom,ComputeTLSPHTensorAtom)
ComputeStyle(tlsph/strain/atom,ComputeTLSPHTensorAtom)
ComputeStyle(tlsph/defgrad/atom,ComputeTLSPHTensorAtom)
// clang-format on
#else

#ifndef LMP_COMPUTE_TLSPH_TENSOR_ATOM_H
#define LMP_COMPUTE_TLSPH_TENSOR_ATOM_H

#include "compute.h"

namespace LAMMPS_NS {

class ComputeTLSPHTensorAtom : public Compute {
 public:
  enum Kind { STRESS, STRAIN, DEFGRAD };
  ComputeTLSPHTensorAtom(class LAMMPS *, int, char **);
  ~ComputeTLSPHTensorAtom() override;
  void init() override;
  void compute_peratom() override;
  double memory_usage() override;

 private:
  Kind kind;
  int nmax;
  double **values;
  class PairTLSPH *pair;
};

}    // namespace LAMMPS_NS

#endif
#endif
