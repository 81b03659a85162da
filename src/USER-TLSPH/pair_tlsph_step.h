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
  double *Fi = F[i];
  const Material &m = mat[atom->type[i]];
  double J, K[9];
  if (LAWS && m.orthotropic) {
    psi[i] = TLSPH::stress_tensors(m.ortho_law, DIM, Fi, P[i], need_K ? K : nullptr, &J);
  } else {
    const TLSPH::IsotropicSVK law{m.lambda, m.mu, DIM == 2 ? plane_stress : 0};
    psi[i] = TLSPH::stress_tensors(law, DIM, Fi, P[i], need_K ? K : nullptr, &J);
  }
  if (!(J > 0.0) || !std::isfinite(psi[i])) unstable_particle(i, J);
  if (hg_form == 2 && gamma != 0.0) {
    // conservative hourglass control: (1/2) H_i joins V_i P_i (tlsph_particle.h)
    const struct {
      double **p;
      const double *operator()(int k) const { return p[k]; }
    } rows{atom->x};
    const auto b = bonds_of<DIM>(i);
    const TLSPH::PairMaterial *pm = pairmat.data();
    const int *type = atom->type;
    const double Vi = atom->vfrac[i], gEi = 0.5 * gamma * pm[type[i]].E;
    auto coeff = [&](int m) { return (gEi + 0.5 * gamma * pm[type[b.partner(m)]].E) * Vi * b.whg(m); };
    double H[DIM * DIM];
    ehg[i] = 0.25 * TLSPH::hourglass_moment<DIM>(rows, i, b, nbond[i], Fi, coeff, H);
    const double s = 0.5 / Vi;
    for (int r = 0; r < DIM; r++)
      for (int c = 0; c < DIM; c++) P[i][3 * r + c] += s * H[DIM * r + c];
  }
  TLSPH::pack_row<DIM, ORDER>(atom->vfrac[i], P[i], Q[i], Fi, need_K ? K : nullptr,
                              alpha_atom ? alpha_atom[i] : alpha, sumg[i], pk[i], fown[i],
                              gather_rows != 0);
}

}    // namespace LAMMPS_NS

#endif
