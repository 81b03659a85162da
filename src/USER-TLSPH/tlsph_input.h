/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: numbers from the input script with messages that name the
   command and the keyword (LAMMPS's utils::numeric says only "Expected
   floating point parameter instead of 'x'", and accepts "1e" or "+-1" or a
   value that overflows to inf). Internal to the package's .cpp files.
------------------------------------------------------------------------- */

#ifndef LMP_TLSPH_INPUT_H
#define LMP_TLSPH_INPUT_H

#include "error.h"
#include "utils.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

namespace LAMMPS_NS {
namespace TLSPHInput {

/* the finite number val of keyword key of command where (e.g.
   "pair_style tlsph"), or an error naming both */
inline double number(Error *error, const std::string &where, const std::string &key,
                     const char *val)
{
  const std::string s = val ? val : "";
  // is_double admits only the characters of a number ("e", "1e" and "+-1"
  // pass it): the whole string must also be what strtod reads
  char *end = nullptr;
  errno = 0;
  const double v = s.empty() ? 0.0 : std::strtod(s.c_str(), &end);
  if (s.empty() || !utils::is_double(s) || end != s.c_str() + s.size())
    error->all(FLERR, "{}: {} needs a number, got '{}'", where, key, s);
  if (errno == ERANGE || !std::isfinite(v))
    error->all(FLERR, "{}: {} = '{}' is out of the range of a double", where, key, s);
  return v;
}

/* the integer val of keyword key, or an error naming both */
inline long integer(Error *error, const std::string &where, const std::string &key,
                    const char *val)
{
  const std::string s = val ? val : "";
  char *end = nullptr;
  errno = 0;
  const long v = s.empty() ? 0 : std::strtol(s.c_str(), &end, 10);
  if (s.empty() || !utils::is_integer(s) || end != s.c_str() + s.size())
    error->all(FLERR, "{}: {} needs an integer, got '{}'", where, key, s);
  if (errno == ERANGE) error->all(FLERR, "{}: {} = '{}' is out of range", where, key, s);
  return v;
}

}    // namespace TLSPHInput
}    // namespace LAMMPS_NS

#endif
