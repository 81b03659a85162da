/* ----------------------------------------------------------------------
   USER-TLSPH: the plugin entry point of the KOKKOS build, tlsphkkplugin.so
   (scripts/build-kk-plugin.sh; doc/kokkos.md, "Loading the /kk styles as a
   plugin"). It registers everything tlsphplugin.so registers (the tables
   of ../tlsph_plugin.cpp, included below with its lammpsplugin_init
   renamed) plus the KOKKOS styles:

     pair  tlsph/kk, tlsph/damage/kk                 (+ /device, /host)
     fix   tlsph/dt/kk, tlsph/velocity/filter/kk     (+ /device, /host)
     atom  peri/kk                                   (+ /device, /host)

   LAMMPS's PLUGIN package (29 Sep 2021) has no atom styles: they go
   straight into the public Atom::avec_map of the instance. Consequences:
     - `plugin load` must come before `atom_style peri` (with -k on, an
       earlier `atom_style peri` stops with "KOKKOS package requires a
       kokkos enabled atom_style", src/KOKKOS/atom_kokkos.cpp:382);
     - `plugin list` does not show the atom styles, `plugin unload` cannot
       remove them, and `clear` drops them (the Atom instance is rebuilt).
   An AtomVecPeriKokkos outlives plugin_clear() (LAMMPS::destroy() unloads
   the plugins before it deletes Atom), so the library is linked with
   -z nodelete: dlclose() never unmaps its code.

   Not compiled into a LAMMPS (build-lammps-plugin.sh skips this file).

   TLSPH_KK_PLUGIN_TRACE=1 in the environment: every /kk object created
   through this plugin logs the shared object its code comes from (the
   entry of its vtable for Pair::compute, Fix::init or AtomVec::grow,
   located with dladdr); without it, only a warning when that is not this
   plugin (e.g. a LAMMPS with the package compiled in and a plugin linked
   without -Bsymbolic).
------------------------------------------------------------------------- */

// the CPU plugin's tables and creators, its lammpsplugin_init renamed
#define lammpsplugin_init tlsph_cpu_lammpsplugin_init
#include "../tlsph_plugin.cpp"
#undef lammpsplugin_init

#include "atom.h"
#include "comm.h"
#include "domain.h"

#include "atom_vec_peri_kokkos.h"
#include "fix_tlsph_dt_kokkos.h"
#include "fix_tlsph_velocity_filter_kokkos.h"
#include "pair_tlsph_damage_kokkos.h"
#include "pair_tlsph_kokkos.h"

#include <cstdint>
#include <cstdlib>
#include <cxxabi.h>
#include <dlfcn.h>
#include <string>
#include <typeinfo>

namespace {

// the function a virtual member pointer of base B names in obj's vtable
// (Itanium C++ ABI, GCC/Clang on x86-64: a virtual member pointer is
// 1 + the byte offset of its vtable slot)
template <class B, class F> void *vtable_entry(B *obj, F B::*pm)
{
  struct {
    std::ptrdiff_t ptr, adj;
  } rep;
  static_assert(sizeof(pm) == sizeof(rep), "not an Itanium C++ ABI member function pointer");
  memcpy(&rep, &pm, sizeof(rep));
  if (!(rep.ptr & 1)) return nullptr;
  auto vtable = *reinterpret_cast<void ***>(reinterpret_cast<char *>(obj) + rep.adj);
  return vtable[(rep.ptr - 1) / sizeof(void *)];
}

std::string demangle(const char *name)
{
  int status = 0;
  char *s = abi::__cxa_demangle(name, nullptr, nullptr, &status);
  std::string out = (status == 0 && s) ? s : name;
  free(s);
  return out;
}

// log (TLSPH_KK_PLUGIN_TRACE=1) or warn (code not from this plugin) where
// the code of a newly created /kk object comes from
void check_origin(LAMMPS *lmp, const char *kind, const std::type_info &type, const char *what,
                  void *fn)
{
  Dl_info self, code;
  const bool have_self = dladdr((void *) &check_origin, &self) != 0;
  const bool have_code = fn && dladdr(fn, &code) != 0;
  const bool ours = have_self && have_code && self.dli_fbase == code.dli_fbase;
  const char *trace = getenv("TLSPH_KK_PLUGIN_TRACE");
  const bool verbose = trace && *trace && strcmp(trace, "0") != 0;
  if (lmp->comm->me != 0 || (ours && !verbose)) return;
  std::string msg = fmt::format("{} {}: {} from {}", kind, demangle(type.name()), what,
                                have_code ? code.dli_fname : "(unknown)");
  if (ours)
    utils::logmesg(lmp, "tlsph kk plugin: {} (this plugin)\n", msg);
  else
    lmp->error->warning(FLERR, "tlsph kk plugin: {}, not from this plugin ({})", msg,
                        have_self ? self.dli_fname : "?");
}

template <class T> Pair *kk_pair_creator(LAMMPS *lmp)
{
  Pair *p = new T(lmp);
  check_origin(lmp, "pair", typeid(T), "compute()", vtable_entry(p, &Pair::compute));
  return p;
}
template <class T> Fix *kk_fix_creator(LAMMPS *lmp, int argc, char **argv)
{
  Fix *f = new T(lmp, argc, argv);
  check_origin(lmp, "fix", typeid(T), "init()", vtable_entry(f, &Fix::init));
  return f;
}
template <class T> AtomVec *kk_avec_creator(LAMMPS *lmp)
{
  AtomVec *a = new T(lmp);
  check_origin(lmp, "atom style", typeid(T), "grow()", vtable_entry(a, &AtomVec::grow));
  return a;
}

struct AtomEntry {
  const char *name;
  Atom::AtomVecCreator create;
};

const PairEntry kk_pair_styles[] = {
    {"tlsph/kk", "Total Lagrangian SPH, KOKKOS", &kk_pair_creator<PairTLSPHKokkos<LMPDeviceType>>},
    {"tlsph/kk/device", "Total Lagrangian SPH, KOKKOS (device)",
     &kk_pair_creator<PairTLSPHKokkos<LMPDeviceType>>},
    {"tlsph/kk/host", "Total Lagrangian SPH, KOKKOS (host)",
     &kk_pair_creator<PairTLSPHKokkos<LMPHostType>>},
    {"tlsph/damage/kk", "Total Lagrangian SPH with bond damage, KOKKOS",
     &kk_pair_creator<PairTLSPHDamageKokkos<LMPDeviceType>>},
    {"tlsph/damage/kk/device", "Total Lagrangian SPH with bond damage, KOKKOS (device)",
     &kk_pair_creator<PairTLSPHDamageKokkos<LMPDeviceType>>},
    {"tlsph/damage/kk/host", "Total Lagrangian SPH with bond damage, KOKKOS (host)",
     &kk_pair_creator<PairTLSPHDamageKokkos<LMPHostType>>},
};
const FixEntry kk_fix_styles[] = {
    {"tlsph/dt/kk", "CFL time step for pair tlsph, KOKKOS",
     &kk_fix_creator<FixTLSPHDtKokkos<LMPDeviceType>>},
    {"tlsph/dt/kk/device", "CFL time step for pair tlsph, KOKKOS (device)",
     &kk_fix_creator<FixTLSPHDtKokkos<LMPDeviceType>>},
    {"tlsph/dt/kk/host", "CFL time step for pair tlsph, KOKKOS (host)",
     &kk_fix_creator<FixTLSPHDtKokkos<LMPHostType>>},
    {"tlsph/velocity/filter/kk", "velocity smoothing in damaged zones, KOKKOS",
     &kk_fix_creator<FixTLSPHVelocityFilterKokkos<LMPDeviceType>>},
    {"tlsph/velocity/filter/kk/device", "velocity smoothing in damaged zones, KOKKOS (device)",
     &kk_fix_creator<FixTLSPHVelocityFilterKokkos<LMPDeviceType>>},
    {"tlsph/velocity/filter/kk/host", "velocity smoothing in damaged zones, KOKKOS (host)",
     &kk_fix_creator<FixTLSPHVelocityFilterKokkos<LMPHostType>>},
};
const AtomEntry kk_atom_styles[] = {
    {"peri/kk", &kk_avec_creator<AtomVecPeriKokkos>},
    {"peri/kk/device", &kk_avec_creator<AtomVecPeriKokkos>},
    {"peri/kk/host", &kk_avec_creator<AtomVecPeriKokkos>},
};

}    // namespace

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto host = (LAMMPS *) lmp;
  // the CPU styles, exactly as tlsphplugin.so registers them (also the
  // LAMMPS version check)
  tlsph_cpu_lammpsplugin_init(lmp, handle, regfunc);

  register_styles(kk_pair_styles, "pair", handle, regfunc, lmp);
  register_styles(kk_fix_styles, "fix", handle, regfunc, lmp);

  // atom styles: not a plugin category of this LAMMPS, into avec_map directly
  auto avec_map = host->atom->avec_map;
  for (const auto &s : kk_atom_styles) {
    if (avec_map->find(s.name) != avec_map->end()) {
      if (host->comm->me == 0)
        host->error->warning(FLERR, "Overriding built-in atom style {} from plugin", s.name);
    } else if (host->comm->me == 0) {
      utils::logmesg(host, "Loading plugin: atom style {} (Atom::avec_map) by USER-TLSPH "
                           "developers\n", s.name);
    }
    (*avec_map)[s.name] = s.create;
  }
  // too late for atom_style peri/kk: the box (and with it the atom style) exists
  if (host->domain->box_exist && host->comm->me == 0)
    host->error->warning(FLERR,
                         "tlsph kk plugin loaded after the simulation box was defined: "
                         "atom_style peri/kk can only be chosen by an atom_style command "
                         "(or read_restart) that follows plugin load (current atom style: {})",
                         host->atom->atom_style);
}
