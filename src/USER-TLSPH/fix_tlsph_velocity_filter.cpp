/* ----------------------------------------------------------------------
   USER-TLSPH: fix tlsph/velocity/filter, see fix_tlsph_velocity_filter.h
------------------------------------------------------------------------- */

#include "fix_tlsph_velocity_filter.h"
#include "tlsph_input.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "pair_tlsph_damage.h"
#include "update.h"

using namespace LAMMPS_NS;
using namespace FixConst;

FixTLSPHVelocityFilter::FixTLSPHVelocityFilter(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), pair(nullptr), nfiltered(0)
{
  if (narg != 5)
    error->all(FLERR, "fix tlsph/velocity/filter: expected 'fix ID group tlsph/velocity/filter "
                      "phi_c eps'");
  phi_c = TLSPHInput::number(error, "fix tlsph/velocity/filter", "phi_c", arg[3]);
  eps = TLSPHInput::number(error, "fix tlsph/velocity/filter", "eps", arg[4]);
  if (phi_c < 0.0 || phi_c > 1.0)
    error->all(FLERR, "fix tlsph/velocity/filter: phi_c (damage threshold) must be in [0,1], "
                      "got {}", arg[3]);
  if (eps <= 0.0 || eps > 1.0)
    error->all(FLERR, "fix tlsph/velocity/filter: eps (smoothing factor) must be in (0,1], got {}",
               arg[4]);
  comm_forward = 3;
  scalar_flag = 1;
  global_freq = 1;
  extscalar = 0;
}

FixTLSPHVelocityFilter::~FixTLSPHVelocityFilter() = default;

int FixTLSPHVelocityFilter::setmask()
{
  return END_OF_STEP;
}

void FixTLSPHVelocityFilter::init()
{
  pair = dynamic_cast<PairTLSPHDamage *>(force->pair_match("^tlsph/damage", 0));
  if (!pair)
    error->all(FLERR, "fix tlsph/velocity/filter requires pair_style tlsph/damage (it filters "
                      "by the damage of each particle)");
}

void FixTLSPHVelocityFilter::end_of_step()
{
  // ghosts need the velocities of this step's update
  comm->forward_comm_fix(this);
  pair->sync_host();    // tlsph/damage/kk: the damage to the host
  double **v = atom->v;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  // the new velocities of the filtered particles only (from the old ones of
  // every partner), written back after the sweep
  fidx.clear();
  fvel.clear();
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit) || !(pair->damage(i) > phi_c)) continue;
    int nb;
    const int *partner = pair->intact_partners(i, nb);
    double s[3] = {0, 0, 0}, wsum = 0.0;
    const double *Wm = pair->kernel_weights(i);
    for (int m = 0; m < nb; m++) {
      const int j = partner[m];
      const double W = Wm[m];
      for (int d = 0; d < 3; d++) s[d] += (v[i][d] - v[j][d]) * W;
      wsum += W;
    }
    fidx.push_back(i);
    for (int d = 0; d < 3; d++) fvel.push_back(wsum > 0.0 ? v[i][d] - eps * s[d] / wsum : v[i][d]);
  }
  for (size_t k = 0; k < fidx.size(); k++)
    for (int d = 0; d < 3; d++) v[fidx[k]][d] = fvel[3 * k + d];
  nfiltered = fidx.size();
}

int FixTLSPHVelocityFilter::pack_forward_comm(int n, int *list, double *buf, int, int *)
{
  double **v = atom->v;
  int m = 0;
  for (int i = 0; i < n; i++) {
    buf[m++] = v[list[i]][0];
    buf[m++] = v[list[i]][1];
    buf[m++] = v[list[i]][2];
  }
  return m;
}

void FixTLSPHVelocityFilter::unpack_forward_comm(int n, int first, double *buf)
{
  double **v = atom->v;
  int m = 0;
  for (int i = first; i < first + n; i++) {
    v[i][0] = buf[m++];
    v[i][1] = buf[m++];
    v[i][2] = buf[m++];
  }
}

// number of particles filtered on this rank in the last step (global sum)
double FixTLSPHVelocityFilter::compute_scalar()
{
  double mine = nfiltered, all;
  MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_SUM, world);
  return all;
}
