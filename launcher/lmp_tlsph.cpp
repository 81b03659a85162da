/* ----------------------------------------------------------------------
   lmp_tlsph: the LAMMPS executable, plus the USER-TLSPH styles.

   Links the installed liblammps (Debian's, which has no PLUGIN package),
   registers the package's styles into the running instance, then reads
   the input exactly like lmp: same command-line flags, stdin or -in,
   works under mpirun.
------------------------------------------------------------------------- */

#include "input.h"
#include "lammps.h"
#include "tlsph_styles.h"

#include <mpi.h>

using namespace LAMMPS_NS;

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  auto lammps = new LAMMPS(argc, argv, MPI_COMM_WORLD);
  tlsph_register_styles(lammps);
  lammps->input->file();
  delete lammps;
  MPI_Barrier(MPI_COMM_WORLD);
  MPI_Finalize();
  return 0;
}
