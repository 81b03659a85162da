/* ----------------------------------------------------------------------
   USER-TLSPH: compute tlsph/energy, see compute_tlsph_energy.h
------------------------------------------------------------------------- */

#include "compute_tlsph_energy.h"

#include "atom.h"
#include "error.h"
#include "fix_tlsph_bonds.h"
#include "force.h"
#include "pair_tlsph.h"
#include "update.h"

using namespace LAMMPS_NS;

ComputeTLSPHEnergy::ComputeTLSPHEnergy(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), pair(nullptr)
{
  if (narg != 3) error->all(FLERR, "compute tlsph/energy takes no arguments");
  vector_flag = 1;
  size_vector = 4;
  extvector = 1;
  vector = values;
}

void ComputeTLSPHEnergy::init()
{
  pair = dynamic_cast<PairTLSPH *>(force->pair_match("^tlsph", 0));
  if (!pair) error->all(FLERR, "compute tlsph/energy requires pair_style tlsph or tlsph/damage");
}

void ComputeTLSPHEnergy::compute_vector()
{
  invoked_vector = update->ntimestep;
  pair->sync_host();
  double mine[4] = {0, 0, 0, 0};
  const int nlocal = atom->nlocal;
  int *mask = atom->mask;
  double **v = atom->v;
  double *rmass = atom->rmass;
  double *vfrac = atom->vfrac;
  FixTLSPHBonds *bonds = pair->bonds;
  if (bonds) {
    for (int i = 0; i < nlocal; i++) {
      if (!(mask[i] & groupbit)) continue;
      mine[0] += vfrac[i] * pair->strain_energy_density(i);
      double whg, wvisc;
      bonds->work_now(i, whg, wvisc);
      // the thesis's form: the tallied work; the conservative form: its energy
      mine[1] += whg + pair->hourglass_energy(i);
      mine[2] += wvisc;
      mine[3] += 0.5 * rmass[i] * (v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
    }
  }
  MPI_Allreduce(mine, values, 4, MPI_DOUBLE, MPI_SUM, world);
  // LAMMPS energy units: mvv2e converts m v^2 to energy (1 in si/metal-free units)
  values[3] *= force->mvv2e;
}
