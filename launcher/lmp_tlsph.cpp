/* ----------------------------------------------------------------------
   lmp_tlsph: the LAMMPS executable, plus the USER-TLSPH styles.

   Links the installed liblammps (Debian's, which has no PLUGIN package),
   registers the package's styles into the running instance, then reads
   the input exactly like lmp: same command-line flags, stdin or -in,
   works under mpirun. The registration also adds a 'plugin' command
   (tlsph_plugin.cpp): 'plugin load .../tlsphplugin.so' registers the
   compiled-in styles again, e.g. after 'clear' (doc/Howto_load.rst).
------------------------------------------------------------------------- */

#include "input.h"
#include "lammps.h"
#include "tlsph_styles.h"

#include <cstdio>
#include <cstring>
#include <mpi.h>

using namespace LAMMPS_NS;

int main(int argc, char **argv)
{
  MPI_Init(&argc, &argv);
  // -h: LAMMPS prints its help and exits inside the constructor, before the
  // styles are registered: say here what is compiled in
  int me = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &me);
  for (int k = 1; k < argc; k++)
    if ((strcmp(argv[k], "-h") == 0 || strcmp(argv[k], "-help") == 0) && me == 0) {
      printf("lmp_tlsph: LAMMPS with USER-TLSPH %s (LAMMPS %s) compiled in; its styles are "
             "registered after start-up, so the lists below do not show them\n\n",
             tlsph_version(), tlsph_lammps_version());
      fflush(stdout);
      break;
    }
  auto lammps = new LAMMPS(argc, argv, MPI_COMM_WORLD);
  tlsph_register_styles(lammps);
  lammps->input->file();
  delete lammps;
  MPI_Barrier(MPI_COMM_WORLD);
  MPI_Finalize();
  return 0;
}
