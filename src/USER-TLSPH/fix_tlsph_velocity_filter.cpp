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

#include <cstring>

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
  // the kinetic energy taken out: in the last step, and in all (extensive)
  vector_flag = 1;
  size_vector = 2;
  extvector = 1;
  restart_global = 1;
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
  const double *rmass = atom->rmass;
  double de = 0.0;
  for (size_t k = 0; k < fidx.size(); k++) {
    const int i = fidx[k];
    double v2 = 0.0;
    for (int d = 0; d < 3; d++) {
      v2 += v[i][d] * v[i][d] - fvel[3 * k + d] * fvel[3 * k + d];
      v[i][d] = fvel[3 * k + d];
    }
    de += 0.5 * (rmass ? rmass[i] : atom->mass[atom->type[i]]) * v2;
  }
  nfiltered = fidx.size();
  record_energy(de);
}

void FixTLSPHVelocityFilter::record_energy(double de)
{
  de_step = de;
  de_sum += de;
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

// the kinetic energy taken out (sum over the ranks): 1 in the last step,
// 2 since the fix was defined (restart files carry it)
double FixTLSPHVelocityFilter::compute_vector(int n)
{
  double mine = n == 0 ? de_step : de_sum, all;
  MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_SUM, world);
  return all;
}

void FixTLSPHVelocityFilter::write_restart(FILE *fp)
{
  double all;
  MPI_Allreduce(&de_sum, &all, 1, MPI_DOUBLE, MPI_SUM, world);
  if (comm->me == 0) {
    const int size = sizeof(double);    // bytes, as Modify::read_restart reads them
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(&all, sizeof(double), 1, fp);
  }
}

// the sum goes to rank 0 (compute_vector adds the ranks' shares)
void FixTLSPHVelocityFilter::restart(char *buf)
{
  double all;
  memcpy(&all, buf, sizeof(double));
  de_sum = comm->me == 0 ? all : 0.0;
}

// number of particles filtered on this rank in the last step (global sum)
double FixTLSPHVelocityFilter::compute_scalar()
{
  double mine = nfiltered, all;
  MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_SUM, world);
  return all;
}
