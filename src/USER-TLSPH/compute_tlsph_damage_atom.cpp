/* ----------------------------------------------------------------------
   USER-TLSPH: compute tlsph/damage/atom, see compute_tlsph_damage_atom.h
------------------------------------------------------------------------- */

#include "compute_tlsph_damage_atom.h"

#include "atom.h"
#include "error.h"
#include "fix_tlsph_bonds.h"
#include "force.h"
#include "memory.h"
#include "pair_tlsph_damage.h"
#include "update.h"

using namespace LAMMPS_NS;

ComputeTLSPHDamageAtom::ComputeTLSPHDamageAtom(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), nmax(0), values(nullptr), pair(nullptr)
{
  if (narg != 3) error->all(FLERR, "compute tlsph/damage/atom takes no arguments");
  peratom_flag = 1;
  size_peratom_cols = 4;
}

ComputeTLSPHDamageAtom::~ComputeTLSPHDamageAtom()
{
  memory->destroy(values);
}

void ComputeTLSPHDamageAtom::init()
{
  pair = dynamic_cast<PairTLSPHDamage *>(force->pair_match("^tlsph/damage", 0));
  if (!pair) error->all(FLERR, "compute tlsph/damage/atom requires pair_style tlsph/damage");
}

void ComputeTLSPHDamageAtom::compute_peratom()
{
  invoked_peratom = update->ntimestep;
  if (atom->nmax > nmax) {
    memory->destroy(values);
    nmax = atom->nmax;
    memory->create(values, nmax, 4, "tlsph/damage/atom:values");
    array_atom = values;
  }
  pair->sync_host();    // tlsph/damage/kk: the damage to the host
  const int nlocal = atom->nlocal;
  int *mask = atom->mask;
  for (int i = 0; i < nlocal; i++) {
    values[i][0] = values[i][1] = values[i][2] = values[i][3] = 0.0;
    if (!(mask[i] & groupbit)) continue;
    int nb;
    pair->intact_partners(i, nb);
    values[i][0] = pair->damage(i);
    values[i][1] = pair->smoothed_damage(i);
    values[i][2] = nb;
    values[i][3] = pair->bonds->nintact0[i];
  }
}

double ComputeTLSPHDamageAtom::memory_usage()
{
  return (double) nmax * 4 * sizeof(double);
}
