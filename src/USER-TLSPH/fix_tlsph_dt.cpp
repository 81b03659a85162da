/* ----------------------------------------------------------------------
   USER-TLSPH: fix tlsph/dt, see fix_tlsph_dt.h
------------------------------------------------------------------------- */

#include "fix_tlsph_dt.h"
#include "tlsph_input.h"

#include "atom.h"
#include "error.h"
#include "force.h"
#include "integrate.h"
#include "modify.h"
#include "pair_tlsph.h"
#include "respa.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

FixTLSPHDt::FixTLSPHDt(LAMMPS *lmp, int narg, char **arg) : Fix(lmp, narg, arg), pair(nullptr)
{
  if (narg < 4) error->all(FLERR, "fix tlsph/dt: expected 'fix ID group tlsph/dt C [every N]'");
  courant = TLSPHInput::number(error, "fix tlsph/dt", "C", arg[3]);
  if (courant <= 0.0 || courant > 1.0)
    error->all(FLERR, "fix tlsph/dt: Courant number C must satisfy 0 < C <= 1, got {}", arg[3]);
  nevery = 1;
  int iarg = 4;
  while (iarg < narg) {
    if (strcmp(arg[iarg], "every") == 0) {
      if (iarg + 1 >= narg) error->all(FLERR, "fix tlsph/dt: keyword 'every' needs a value");
      nevery = TLSPHInput::integer(error, "fix tlsph/dt", "every", arg[iarg + 1]);
      if (nevery <= 0) error->all(FLERR, "fix tlsph/dt: every must be > 0, got {}", nevery);
      iarg += 2;
    } else
      error->all(FLERR, "fix tlsph/dt: unknown keyword '{}' (allowed: every)", arg[iarg]);
  }
  scalar_flag = 1;
  global_freq = 1;
  extscalar = 0;
  time_depend = 1;
}

int FixTLSPHDt::setmask()
{
  return END_OF_STEP;
}

void FixTLSPHDt::init()
{
  pair = dynamic_cast<PairTLSPH *>(force->pair_match("^tlsph", 0));
  if (!pair) error->all(FLERR, "fix tlsph/dt requires pair_style tlsph or tlsph/damage");
  if (utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "fix tlsph/dt does not support run_style respa");
}

void FixTLSPHDt::setup(int)
{
  update_dt();
}

void FixTLSPHDt::end_of_step()
{
  update_dt();
}

double FixTLSPHDt::local_max_speed()
{
  double **v = atom->v;
  int *type = atom->type;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  double cmax = 0.0;
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double vel = sqrt(v[i][0] * v[i][0] + v[i][1] * v[i][1] + v[i][2] * v[i][2]);
    cmax = MAX(cmax, pair->material(type[i]).c0 + vel);
  }
  return cmax;
}

void FixTLSPHDt::update_dt()
{
  double cmax = local_max_speed();    // (not const: MPI STUBS take void *)
  double call;
  MPI_Allreduce(&cmax, &call, 1, MPI_DOUBLE, MPI_MAX, world);
  if (call <= 0.0) return;
  const double dt = courant * pair->smoothing_length() / call;
  if (dt == update->dt) return;
  update->update_time();
  update->dt = dt;
  update->dt_default = 0;
  if (force->pair) force->pair->reset_dt();
  for (int i = 0; i < modify->nfix; i++) modify->fix[i]->reset_dt();
}

double FixTLSPHDt::compute_scalar()
{
  return update->dt;
}
