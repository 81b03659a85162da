/* ----------------------------------------------------------------------
   USER-TLSPH: fix tlsph/relax, see fix_tlsph_relax.h
------------------------------------------------------------------------- */

#include "fix_tlsph_relax.h"

#include "atom.h"
#include "error.h"
#include "force.h"
#include "update.h"

using namespace LAMMPS_NS;
using namespace FixConst;

FixTLSPHRelax::FixTLSPHRelax(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), ke_prev(0.0), nresets(0), ke_last(0.0)
{
  if (narg != 3) error->all(FLERR, "fix tlsph/relax takes no arguments: fix ID group tlsph/relax");
  if (!atom->rmass_flag) error->all(FLERR, "fix tlsph/relax requires per-atom masses (atom_style peri)");
  vector_flag = 1;
  size_vector = 2;
  global_freq = 1;
  extvector = 0;
}

int FixTLSPHRelax::setmask()
{
  return END_OF_STEP;
}

void FixTLSPHRelax::init()
{
  ke_prev = 0.0;
}

double FixTLSPHRelax::kinetic_energy()
{
  double **v = atom->v;
  double *rmass = atom->rmass;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  double ke = 0.0;
  for (int i = 0; i < nlocal; i++)
    if (mask[i] & groupbit) ke += rmass[i] * (v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
  double all;
  MPI_Allreduce(&ke, &all, 1, MPI_DOUBLE, MPI_SUM, world);
  return 0.5 * force->mvv2e * all;
}

void FixTLSPHRelax::end_of_step()
{
  const double ke = kinetic_energy();
  ke_last = ke;
  if (ke < ke_prev) {
    // the kinetic energy peaked during the last step: the configuration is
    // near a minimum of the potential energy along the current motion
    double **v = atom->v;
    int *mask = atom->mask;
    const int nlocal = atom->nlocal;
    for (int i = 0; i < nlocal; i++)
      if (mask[i] & groupbit) v[i][0] = v[i][1] = v[i][2] = 0.0;
    nresets++;
    ke_prev = 0.0;
  } else
    ke_prev = ke;
}

// [1] number of velocity resets, [2] kinetic energy at the last check
double FixTLSPHRelax::compute_vector(int n)
{
  return n == 0 ? (double) nresets : ke_last;
}
