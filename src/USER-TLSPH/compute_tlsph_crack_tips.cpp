/* ----------------------------------------------------------------------
   USER-TLSPH: compute tlsph/crack/tips, see compute_tlsph_crack_tips.h
------------------------------------------------------------------------- */

#include "compute_tlsph_crack_tips.h"

#include "error.h"
#include "force.h"
#include "memory.h"
#include "pair_tlsph_damage.h"
#include "update.h"

#include <cmath>

using namespace LAMMPS_NS;

ComputeTLSPHCrackTips::ComputeTLSPHCrackTips(LAMMPS *lmp, int narg, char **arg) :
    Compute(lmp, narg, arg), nrows_max(0), pair(nullptr)
{
  if (narg != 3) error->all(FLERR, "compute tlsph/crack/tips takes no arguments");
  vector_flag = 1;
  size_vector = 2;
  extvector = 0;
  vector = values;
  array_flag = 1;
  size_array_cols = NCOL;
  size_array_rows = 0;
  size_array_rows_variable = 1;
  extarray = 0;
  array = nullptr;
}

ComputeTLSPHCrackTips::~ComputeTLSPHCrackTips()
{
  memory->destroy(array);
}

void ComputeTLSPHCrackTips::init()
{
  pair = dynamic_cast<PairTLSPHDamage *>(force->pair_match("^tlsph/damage", 0));
  if (!pair || !pair->tip_mode())
    error->all(FLERR, "compute tlsph/crack/tips requires pair_style tlsph/damage with "
                      "'criterion tip' (the CPU style)");
}

// the tips are the same on every rank (pair_tlsph_damage.h): no communication
void ComputeTLSPHCrackTips::fill()
{
  const auto &tips = pair->crack_tips();
  const int n = (int) tips.size();
  if (n > nrows_max) {
    nrows_max = n;
    memory->destroy(array);
    memory->create(array, nrows_max, NCOL, "tlsph/crack/tips:array");
  }
  size_array_rows = n;
  const double Gc = pair->tip_fracture_energy();
  int live = 0;
  for (int a = 0; a < n; a++) {
    const auto &tp = tips[a];
    double len = 0.0;
    for (size_t v = 1; v < tp.path.size(); v++)
      len += std::hypot(tp.path[v][0] - tp.path[v - 1][0], tp.path[v][1] - tp.path[v - 1][1]);
    double *r = array[a];
    r[0] = tp.path.back()[0];
    r[1] = tp.path.back()[1];
    r[2] = tp.alive ? 1.0 : 0.0;
    r[3] = tp.KI;
    r[4] = tp.KII;
    r[5] = tp.G;
    r[6] = Gc > 0.0 ? tp.G / Gc : 0.0;
    r[7] = tp.kink * 180.0 / M_PI;
    r[8] = tp.alive ? tp.speed : 0.0;
    r[9] = len;
    r[10] = tp.T;
    live += tp.alive ? 1 : 0;
  }
  values[0] = n;
  values[1] = live;
}

void ComputeTLSPHCrackTips::compute_vector()
{
  invoked_vector = update->ntimestep;
  fill();
}

void ComputeTLSPHCrackTips::compute_array()
{
  invoked_array = update->ntimestep;
  fill();
}

double ComputeTLSPHCrackTips::memory_usage()
{
  return (double) nrows_max * NCOL * sizeof(double);
}
