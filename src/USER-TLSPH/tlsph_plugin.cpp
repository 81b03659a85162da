/* ----------------------------------------------------------------------
   USER-TLSPH: style registration, see tlsph_styles.h
------------------------------------------------------------------------- */

#include "tlsph_styles.h"

#include "lammpsplugin.h"
#include "version.h"

#include "command.h"
#include "comm.h"
#include "compute_tlsph_crack_tips.h"
#include "compute_tlsph_energy.h"
#include "compute_tlsph_tensor_atom.h"
#include "error.h"
#include "fix_tlsph_bonds.h"
#include "fix_tlsph_dt.h"
#include "fix_tlsph_relax.h"
#include "force.h"
#include "input.h"
#include "lammps.h"
#include "modify.h"
#include "pair_tlsph.h"
#include "pair_tlsph_damage.h"
#include "fix_tlsph_velocity_filter.h"
#include "compute_tlsph_damage_atom.h"

#include <cstdlib>
#include <cstring>
#include <dlfcn.h>
#include <fstream>
#include <iterator>
#include <string>

// the package's version, from the file VERSION (CMakeLists.txt,
// scripts/build-kk-plugin.sh and fuzz/CMakeLists.txt define it)
#ifndef TLSPH_VERSION
#define TLSPH_VERSION "unknown (built without TLSPH_VERSION)"
#endif

using namespace LAMMPS_NS;

// marks a file as a build of this package: the launcher's 'plugin load'
// looks for it in the file it is given instead of opening it (exported, so
// that neither the compiler nor the linker drops it)
extern "C" __attribute__((visibility("default"), used)) const char tlsph_build_id[] =
    "USER-TLSPH-BUILD " TLSPH_VERSION " (LAMMPS " LAMMPS_VERSION ")";

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
    {"tlsph/crack/tips", "crack tips of pair tlsph/damage criterion tip: position, K_I, K_II, G",
     &compute_creator<ComputeTLSPHCrackTips>},
};

// one line, to screen and log: the package and the LAMMPS it runs in
void announce(LAMMPS *lmp, const std::string &what)
{
  if (lmp->comm->me == 0)
    utils::logmesg(lmp, "USER-TLSPH {} (LAMMPS {}){}\n", TLSPH_VERSION, lmp->version, what);
}

void insert_styles(LAMMPS *lmp)
{
  for (const auto &s : pair_styles) (*lmp->force->pair_map)[s.name] = s.create;
  for (const auto &s : fix_styles) (*lmp->modify->fix_map)[s.name] = s.create;
  for (const auto &s : compute_styles) (*lmp->modify->compute_map)[s.name] = s.create;
}

// the file (executable or shared library) this code was loaded from
std::string own_file()
{
  Dl_info info;
  if (dladdr((void *) &tlsph_build_id, &info) && info.dli_fname && *info.dli_fname) {
    char *r = realpath(info.dli_fname, nullptr);
    if (r) {
      std::string s = r;
      free(r);
      return s;
    }
    return info.dli_fname;
  }
  return "this executable";
}

/* ----------------------------------------------------------------------
   the 'plugin' command of a LAMMPS without the PLUGIN package (the
   lmp_tlsph launcher, python3-lammps after tlsph.register; doc/Howto_load.rst).
   The styles are compiled in (or already loaded): 'plugin load' of a
   USER-TLSPH library registers them again, e.g. after 'clear', which
   empties the style maps but not Input's command map. The file is only
   read, for its build mark, never opened as a library: no second copy of
   the same code.
------------------------------------------------------------------------- */

class TLSPHPluginCommand : public Command {
 public:
  TLSPHPluginCommand(LAMMPS *lmp) : Command(lmp) {}
  void command(int narg, char **arg) override
  {
    const std::string own = own_file();
    if (narg < 1)
      error->all(FLERR, "plugin: expected 'plugin load <file>', 'plugin list', 'plugin unload "
                        "<style> <name>' or 'plugin clear'");
    const std::string cmd = arg[0];
    if (cmd == "load") {
      if (narg < 2) error->all(FLERR, "plugin load: expected 'plugin load <file>'");
      for (int k = 1; k < narg; k++) load(arg[k], own);
    } else if (cmd == "list") {
      list(own);
    } else if (cmd == "unload" || cmd == "clear") {
      error->all(FLERR, "plugin {}: this LAMMPS has no PLUGIN package; the USER-TLSPH styles are "
                        "compiled into {} and cannot be unloaded (its 'plugin' command knows "
                        "'load <path>/tlsphplugin.so' and 'list'; use a LAMMPS built with PLUGIN "
                        "to unload plugins)", cmd, own);
    } else {
      error->all(FLERR, "plugin: unknown subcommand '{}' (allowed: load, list; unload and clear "
                        "are refused: the styles are compiled in)", cmd);
    }
  }

 private:
  void load(const std::string &file, const std::string &own)
  {
    // rank 0 reads the file's build mark: 0 ok, 1 cannot read, 2 no mark,
    // 3 another build
    int status = 0;
    std::string theirs;
    if (comm->me == 0) {
      std::ifstream in(file, std::ios::binary);
      if (!in) status = 1;
      else {
        const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const std::string key = "USER-TLSPH-BUILD ";
        const size_t at = data.find(key);
        if (at == std::string::npos) status = 2;
        else {
          const size_t end = data.find('\0', at);
          theirs = data.substr(at + key.size(),
                               (end == std::string::npos ? data.size() : end) - at - key.size());
          const std::string mine = tlsph_build_id + key.size();
          if (theirs != mine) status = 3;
        }
      }
    }
    MPI_Bcast(&status, 1, MPI_INT, 0, world);
    int len = (int) theirs.size();
    MPI_Bcast(&len, 1, MPI_INT, 0, world);
    theirs.resize(len);
    if (len) MPI_Bcast(&theirs[0], len, MPI_CHAR, 0, world);
    if (status == 1)
      error->all(FLERR, "plugin load: cannot open file '{}'", file);
    if (status == 2)
      error->all(FLERR, "plugin load {}: not a USER-TLSPH library. This LAMMPS has no PLUGIN "
                        "package: its 'plugin' command only registers the USER-TLSPH styles "
                        "compiled into {} again ('plugin load <path>/tlsphplugin.so', e.g. after "
                        "'clear'); other plugins need a LAMMPS built with PLUGIN "
                        "(doc/Howto_load.rst)", file, own);
    if (status == 3)
      error->all(FLERR, "plugin load {}: that library is USER-TLSPH {}, but {} has USER-TLSPH {} "
                        "(LAMMPS {}) compiled in, which is what would run: this LAMMPS has no "
                        "PLUGIN package and does not open the file; load a tlsphplugin.so of the "
                        "same build", file, theirs, own, TLSPH_VERSION, LAMMPS_VERSION);
    insert_styles(lmp);
    char *r = realpath(file.c_str(), nullptr);
    const std::string path = r ? r : file;
    free(r);
    if (path == own) announce(lmp, fmt::format(": styles registered again from {}", own));
    else
      announce(lmp, fmt::format(": styles registered again, from the copy compiled into {} ({} "
                                "is the same build; not opened)", own, file));
  }

  void list(const std::string &own)
  {
    if (comm->me != 0) return;
    utils::logmesg(lmp, "USER-TLSPH {} (LAMMPS {}): styles compiled into {} (no PLUGIN package: "
                        "no plugins loaded)\n", TLSPH_VERSION, lmp->version, own);
    int n = 0;
    auto line = [&](const char *style, const char *name, bool in) {
      utils::logmesg(lmp, "{:4}: {} style {}{}\n", ++n, style, name,
                     in ? "" : " (not registered since 'clear': 'plugin load' registers it)");
    };
    for (const auto &s : pair_styles) line("pair", s.name, force->pair_map->count(s.name) > 0);
    for (const auto &s : fix_styles) line("fix", s.name, modify->fix_map->count(s.name) > 0);
    for (const auto &s : compute_styles)
      line("compute", s.name, modify->compute_map->count(s.name) > 0);
  }
};

Command *plugin_command_creator(LAMMPS *lmp)
{
  return new TLSPHPluginCommand(lmp);
}

}    // namespace

extern "C" const char *tlsph_lammps_version()
{
  return LAMMPS_VERSION;
}

extern "C" const char *tlsph_version()
{
  return TLSPH_VERSION;
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
  insert_styles(lmp);
  // a 'plugin' command, unless this LAMMPS has one (PLUGIN package): the
  // command map survives 'clear', the style maps do not
  auto cmap = lmp->input->command_map;
  if (cmap->find("plugin") == cmap->end()) (*cmap)["plugin"] = &plugin_command_creator;
  announce(lmp, "");
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
  announce(host, "");
}
