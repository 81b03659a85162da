/* ----------------------------------------------------------------------
   USER-TLSPH: compute tlsph/stress/atom, tlsph/strain/atom, tlsph/defgrad/atom
------------------------------------------------------------------------- */

#include "compute_tlsph_tensor_atom.h"

#include "atom.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "pair_tlsph.h"
#include "tlsph_math.h"
#include "update.h"

#include <cstring>

using namespace LAMMPS_NS;

ComputeTLSPHTensorAtom::ComputeTLSPHTensorAtom(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), nmax(0), values(nullptr), pair(nullptr)
{
  if (narg != 3) error->all(FLERR, "compute {} takes no arguments", arg[2]);
  const std::string s = arg[2];
  if (s == "tlsph/stress/atom") kind = STRESS;
  else if (s == "tlsph/strain/atom") kind = STRAIN;
  else kind = DEFGRAD;
  peratom_flag = 1;
  size_peratom_cols = (kind == DEFGRAD) ? 10 : 6;
}

ComputeTLSPHTensorAtom::~ComputeTLSPHTensorAtom()
{
  memory->destroy(values);
}

void ComputeTLSPHTensorAtom::init()
{
  pair = dynamic_cast<PairTLSPH *>(force->pair_match("^tlsph", 0));
  if (!pair) error->all(FLERR, "compute {} requires pair_style tlsph or tlsph/damage", style);
}

void ComputeTLSPHTensorAtom::compute_peratom()
{
  invoked_peratom = update->ntimestep;
  pair->sync_host();
  if (atom->nmax > nmax) {
    memory->destroy(values);
    nmax = atom->nmax;
    memory->create(values, nmax, size_peratom_cols, "tlsph/atom:values");
    array_atom = values;
  }
  const int nlocal = atom->nlocal;
  int *mask = atom->mask;
  for (int i = 0; i < nlocal; i++) {
    double *out = values[i];
    for (int k = 0; k < size_peratom_cols; k++) out[k] = 0.0;
    if (!(mask[i] & groupbit)) continue;
    if (kind == DEFGRAD) {
      const double *F = pair->deformation_gradient(i);
      for (int k = 0; k < 9; k++) out[k] = F[k];
      out[9] = TLSPH::mat_det(F);
      continue;
    }
    double t[9];
    if (kind == STRESS) pair->cauchy_stress(i, t);
    else pair->green_lagrange_strain(i, t);
    out[0] = t[0];
    out[1] = t[4];
    out[2] = t[8];
    out[3] = t[1];
    out[4] = t[2];
    out[5] = t[5];
  }
}

double ComputeTLSPHTensorAtom::memory_usage()
{
  return (double) nmax * size_peratom_cols * sizeof(double);
}
