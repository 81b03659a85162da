/* -*- c++ -*- ----------------------------------------------------------
   Test helpers shared by unittest/lammps and unittest/damage: an in-process
   LAMMPS instance with the USER-TLSPH styles registered, driven line by line.
------------------------------------------------------------------------- */

#ifndef TLSPH_TEST_LAMMPS_DRIVER_H
#define TLSPH_TEST_LAMMPS_DRIVER_H

#include "input.h"
#include "lammps.h"
#include "tlsph_styles.h"

#include "gtest/gtest.h"

#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace tlsph_test {

// quiet unless TLSPH_TEST_VERBOSE is set; name appears as argv[0]
inline LAMMPS_NS::LAMMPS *open_lammps(const char *name)
{
  std::vector<const char *> args = {name, "-log", "none", "-nocite"};
  if (!getenv("TLSPH_TEST_VERBOSE")) {
    args.push_back("-screen");
    args.push_back("none");
  }
  auto lmp = new LAMMPS_NS::LAMMPS((int) args.size(), (char **) args.data(), MPI_COMM_WORLD);
  EXPECT_EQ(tlsph_register_styles(lmp), 0);
  return lmp;
}

// every non-blank line of script as one LAMMPS command
inline void run_script(LAMMPS_NS::LAMMPS *lmp, const std::string &script)
{
  std::istringstream in(script);
  std::string line;
  while (std::getline(in, line))
    if (line.find_first_not_of(" \t") != std::string::npos) lmp->input->one(line);
}

}    // namespace tlsph_test

#endif
