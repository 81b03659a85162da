/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: the per-particle part of pass (1) of the step that both pair
   styles run after F_i is known (pair_tlsph.cpp: compute_deformation;
   pair_tlsph_damage.cpp: the deformation pass with bond breaking fused in).
   Internal to the package's .cpp files.
------------------------------------------------------------------------- */

#ifndef LMP_PAIR_TLSPH_STEP_H
#define LMP_PAIR_TLSPH_STEP_H

#include "atom.h"
#include "pair_tlsph.h"
#include "tlsph_particle.h"

#include <cmath>

namespace LAMMPS_NS {

/* stress P_i, strain energy density psi_i and the packed row of local
   particle i from its deformation gradient F[i] (doc: "Kinematics and
   stress"); stops with a message naming the particle when det F <= 0 or the
   energy is not finite */
template <int DIM, int ORDER, int LAWS>
inline __attribute__((always_inline)) void PairTLSPH::particle_stress(int i, bool need_K)
{
  particle_stress_of<DIM, ORDER, LAWS>(i, need_K, bonds_of<DIM>(i));
}

// the same with the bonds' view b of particle i (its values as bond_values
// gives them, or a reordered copy of them: tlsph/damage)
template <int DIM, int ORDER, int LAWS, class Bonds>
inline __attribute__((always_inline)) void PairTLSPH::particle_stress_of(int i, bool need_K,
                                                                         const Bonds &b)
{
  const TLSPH::StridedRows rows{atom->x[0], 3};
  const int *type = atom->type;
  const double Vi = atom->vfrac[i];
  const TLSPH::HourglassWeights<Bonds, TLSPH::TypeArray> coeff(
      pairmat.data(), TLSPH::TypeArray{type}, b, gamma, i, Vi);
  double J;
  psi[i] = stress_row<DIM, ORDER, LAWS>(mat[type[i]], plane_stress, F[i], P[i], need_K,
                                        hg_form == 2 && gamma != 0.0, rows, i, b, nbond[i], coeff,
                                        Vi, Q[i], alpha_atom ? alpha_atom[i] : alpha, sumg[i],
                                        gather_rows != 0, pk[i], fown[i], &ehg[i], &J);
  if (!(J > 0.0) || !std::isfinite(psi[i])) unstable_particle(i, J);
}

}    // namespace LAMMPS_NS

#endif
