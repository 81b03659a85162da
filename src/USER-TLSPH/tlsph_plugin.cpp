/* ----------------------------------------------------------------------
   USER-TLSPH: style registration, see tlsph_styles.h
------------------------------------------------------------------------- */

#include "tlsph_styles.h"

#include "lammpsplugin.h"
#include "version.h"

#include "compute_tlsph_energy.h"
#include "compute_tlsph_tensor_atom.h"
#include "error.h"
#include "fix_tlsph_bonds.h"
#include "fix_tlsph_dt.h"
#include "fix_tlsph_relax.h"
#include "force.h"
#include "lammps.h"
#include "modify.h"
#include "pair_tlsph.h"
#include "pair_tlsph_damage.h"
#include "fix_tlsph_velocity_filter.h"
#include "compute_tlsph_damage_atom.h"

#include <cstring>

using namespace LAMMPS_NS;

namespace {

template <class T> Pair *pair_creator(LAMMPS *lmp)
{
  return new T(lmp);
}
template <class T> Fix *fix_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new T(lmp, argc, argv);
}
template <class T> Compute *compute_creator(LAMMPS *lmp, int argc, char **argv)
{
  return new T(lmp, argc, argv);
}

struct PairEntry {
  const char *name, *info;
  Force::PairCreator create;
};
struct FixEntry {
  const char *name, *info;
  Modify::FixCreator create;
};
struct ComputeEntry {
  const char *name, *info;
  Modify::ComputeCreator create;
};

// the creator in the plugin record: pair styles have the one-argument form
void set_creator(lammpsplugin_t &p, Force::PairCreator c)
{
  p.creator.v1 = (lammpsplugin_factory1 *) c;
}
void set_creator(lammpsplugin_t &p, Modify::FixCreator c)
{
  p.creator.v2 = (lammpsplugin_factory2 *) c;
}
void set_creator(lammpsplugin_t &p, Modify::ComputeCreator c)
{
  p.creator.v2 = (lammpsplugin_factory2 *) c;
}

// registers one table of styles of one category through LAMMPS's plugin
// registration function
template <class Entry, size_t N>
void register_styles(const Entry (&table)[N], const char *style, void *handle, void *regfunc,
                     void *lmp)
{
  lammpsplugin_t plugin;
  plugin.version = LAMMPS_VERSION;
  plugin.author = "USER-TLSPH developers";
  plugin.handle = handle;
  plugin.style = style;
  for (const auto &s : table) {
    plugin.name = s.name;
    plugin.info = s.info;
    set_creator(plugin, s.create);
    ((lammpsplugin_regfunc) regfunc)(&plugin, lmp);
  }
}

const PairEntry pair_styles[] = {
    {"tlsph", "Total Lagrangian SPH for elastic solids", &pair_creator<PairTLSPH>},
    {"tlsph/damage", "Total Lagrangian SPH with critical-stretch bond damage",
     &pair_creator<PairTLSPHDamage>},
};
const FixEntry fix_styles[] = {
    {"TLSPH_BONDS", "internal: reference partners and bond state of pair tlsph",
     &fix_creator<FixTLSPHBonds>},
    {"tlsph/dt", "CFL time step for pair tlsph", &fix_creator<FixTLSPHDt>},
    {"tlsph/relax", "kinetic damping (dynamic relaxation) for quasi-static scenes",
     &fix_creator<FixTLSPHRelax>},
    {"tlsph/velocity/filter", "velocity smoothing in damaged zones (tlsph/damage)",
     &fix_creator<FixTLSPHVelocityFilter>},
};
const ComputeEntry compute_styles[] = {
    {"tlsph/stress/atom", "Cauchy stress of pair tlsph", &compute_creator<ComputeTLSPHTensorAtom>},
    {"tlsph/strain/atom", "Green-Lagrange strain of pair tlsph",
     &compute_creator<ComputeTLSPHTensorAtom>},
    {"tlsph/defgrad/atom", "deformation gradient of pair tlsph",
     &compute_creator<ComputeTLSPHTensorAtom>},
    {"tlsph/energy", "strain, hourglass, viscous and kinetic energy of pair tlsph",
     &compute_creator<ComputeTLSPHEnergy>},
    {"tlsph/damage/atom", "damage and smoothed damage of pair tlsph/damage",
     &compute_creator<ComputeTLSPHDamageAtom>},
};

}    // namespace

extern "C" const char *tlsph_lammps_version()
{
  return LAMMPS_VERSION;
}

extern "C" int tlsph_register_styles(void *ptr)
{
  auto lmp = (LAMMPS *) ptr;
  if (strcmp(lmp->version, LAMMPS_VERSION) != 0) {
    lmp->error->all(FLERR,
                    "USER-TLSPH was compiled against the headers of LAMMPS {} but is loaded into "
                    "LAMMPS {}: rebuild the package against the matching source ('make build')",
                    LAMMPS_VERSION, lmp->version);
    return 1;
  }
  for (const auto &s : pair_styles) (*lmp->force->pair_map)[s.name] = s.create;
  for (const auto &s : fix_styles) (*lmp->modify->fix_map)[s.name] = s.create;
  for (const auto &s : compute_styles) (*lmp->modify->compute_map)[s.name] = s.create;
  return 0;
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto host = (LAMMPS *) lmp;
  if (strcmp(host->version, LAMMPS_VERSION) != 0)
    host->error->all(FLERR,
                     "USER-TLSPH plugin was compiled against the headers of LAMMPS {} but is "
                     "loaded into LAMMPS {}: build it against the matching source",
                     LAMMPS_VERSION, host->version);
  register_styles(pair_styles, "pair", handle, regfunc, lmp);
  register_styles(fix_styles, "fix", handle, regfunc, lmp);
  register_styles(compute_styles, "compute", handle, regfunc, lmp);
}
