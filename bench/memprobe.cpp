/* ----------------------------------------------------------------------
   bench/memprobe.cpp: read LAMMPS's own memory accounting from a running
   instance, split by owner, for bench/memory.py (through ctypes).

   The "Per MPI rank memory allocation" line of a run is the sum
   atom + neighbor + comm + update + force + modify (+ dumps), each
   object's memory_usage() (Info::get_memory_info). The pair style's share
   is force->pair->memory_usage() (PairTLSPH::memory_usage), the bond
   rows are FixTLSPHBonds::memory_usage() (part of modify). Built by
   bench/run.sh against the same LAMMPS headers as the plugin.
------------------------------------------------------------------------- */

#include "atom.h"
#include "domain.h"
#include "comm.h"
#include "fix.h"
#include "force.h"
#include "lammps.h"
#include "modify.h"
#include "neighbor.h"
#include "pair.h"
#include "update.h"

#include "fix_tlsph_bonds.h"
#include "tlsph_particle.h"

using namespace LAMMPS_NS;

/* out[0..12]: atom, neighbor, comm, update, force, modify, pair,
   bond fix (TLSPH_BONDS), nlocal, nghost, atom->nmax, bonds found at setup
   (all ranks, each counted from both ends = bond-cache entries),
   the bytes per bond of the lean bond layout; all bytes except the counts.
   Returns 0, or -1 when there is no pair style. */
extern "C" int tlsph_memprobe(void *handle, double *out)
{
  LAMMPS *lmp = static_cast<LAMMPS *>(handle);
  for (int k = 0; k < 13; k++) out[k] = 0.0;
  out[0] = lmp->atom->memory_usage();
  out[1] = lmp->neighbor->memory_usage();
  out[2] = lmp->comm->memory_usage();
  out[3] = lmp->update->memory_usage();
  out[4] = lmp->force->memory_usage();
  out[5] = lmp->modify->memory_usage();
  if (!lmp->force->pair) return -1;
  out[6] = lmp->force->pair->memory_usage();
  const int ifix = lmp->modify->find_fix_by_style("^TLSPH_BONDS$");
  if (ifix >= 0) {
    auto *bonds = dynamic_cast<FixTLSPHBonds *>(lmp->modify->fix[ifix]);
    out[7] = lmp->modify->fix[ifix]->memory_usage();
    if (bonds) out[11] = bonds->nbonds_total;
  }
  out[8] = lmp->atom->nlocal;
  out[9] = lmp->atom->nghost;
  out[10] = lmp->atom->nmax;
  // bytes per bond of the lean layout (pair_tlsph.h): partner, slot, g (dim), two weights
  out[12] = 2 * sizeof(int) + (lmp->domain->dimension + 2) * sizeof(double);
  return 0;
}
