/* ----------------------------------------------------------------------
   USER-TLSPH: pair_style tlsph, see pair_tlsph.h and doc/pair_tlsph.rst
------------------------------------------------------------------------- */

#include "pair_tlsph.h"

#include "atom.h"
#include "atom_masks.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "fix_tlsph_bonds.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "pair_tlsph_step.h"
#include "potential_file_reader.h"
#include "tlsph_particle.h"
#include "tlsph_input.h"
#include "tokenizer.h"
#include "update.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <type_traits>
#include <utility>

using namespace LAMMPS_NS;
using namespace TLSPH;

namespace {
const char *const MATERIAL_KEYS = "E, nu, rho";
const char *const ORTHO_KEYS = "E1, E2, E3, G12, G13, G23, nu12, nu13, nu23, rho, theta";
}    // namespace

PairTLSPH::PairTLSPH(LAMMPS *lmp) : Pair(lmp)
{
  bonds = nullptr;
  any_orthotropic = 0;
  set_defaults();
  ndegraded = 0;
  report_fallback = 1;
  dim = 3;
  nmax = 0;
  Q = sumg = F = P = fown = pk = nullptr;
  gather_rows = 1;
  psi = ehg = nullptr;
  nbond = nlead = nullptr;
  bond_start = nullptr;
  lean = TLSPH::LeanArrays{nullptr, nullptr, nullptr, nullptr};
  x0c = nullptr;
  ncache_max = nstart_max = 0;

  single_enable = 0;
  restartinfo = 1;
  manybody_flag = 1;
  no_virial_fdotr_compute = 1;
  centroidstressflag = CENTROID_NOTAVAIL;
}

PairTLSPH::~PairTLSPH()
{
  if (modify->nfix && bonds) {
    int ifix = modify->find_fix_by_style("^TLSPH_BONDS$");
    if (ifix >= 0 && modify->fix[ifix] == (Fix *) bonds) modify->delete_fix(bonds->id);
  }
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
  }
  destroy_peratom();
  memory->destroy(bond_start);
  memory->destroy(lean.j);
  memory->destroy(lean.g);
  memory->destroy(lean.w);
  memory->destroy(lean.k);
  memory->destroy(ell.start);
  memory->destroy(ell.j);
  memory->destroy(ell.v);
  memory->destroy(ell.kind);
  memory->destroy(ell.shared);
  memory->destroy(ell.first);
  memory->destroy(ell.n);
  memory->destroy(ell.pat);
  memory->destroy(ell.pat_start);
  memory->destroy(ell.pat_off);
  memory->destroy(ell.pat_v);
  memory->destroy(ell_perm);
  memory->destroy(ell_inv);
  memory->destroy(ell_chunk_of);
  memory->destroy(ell.width);
  memory->destroy(ell_soa);
}

void PairTLSPH::allocate()
{
  allocated = 1;
  const int n = atom->ntypes;
  memory->create(setflag, n + 1, n + 1, "pair:setflag");
  // setflag = 1 for every type: Pair::init() checks setflag before init_style()
  // and would only say "All pair coeffs are not set"; init_one() names the type
  // that has no material instead (a type has one when its rho > 0)
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) setflag[i][j] = 1;
  memory->create(cutsq, n + 1, n + 1, "pair:cutsq");
  mat.assign(n + 1, Material{});
  pairmat.assign(n + 1, TLSPH::PairMaterial{0, 0, 0});
  any_orthotropic = 0;
}

/* ----------------------------------------------------------------------
   pair_style tlsph h VALUE [alpha A] [beta B] [gamma G]
                            [hourglass thesis|conservative] [plane strain|stress]
                            [thickness T] [gradient linear|quadratic] [cutfactor C]
                            [check_partners yes|no] [check_volume yes|no]
------------------------------------------------------------------------- */

// the documented defaults of pair_style tlsph (doc/pair_tlsph.rst, "Default")
void PairTLSPH::set_defaults()
{
  h = 0.0;
  alpha = 1.0;
  beta = 0.0;
  gamma = 1.0;
  hg_form = 1;
  plane_stress = 0;
  cutfactor = 1.1;
  order = 2;
  thickness = 1.0;
  check_partners = 1;
  check_volume = 1;
  // the default of 'simd' may come from the environment (TLSPH_SIMD, e.g.
  // "no" in the Kokkos checks, whose reference is the scalar step)
  simd_request = SIMD_AUTO;
  if (const char *env = getenv("TLSPH_SIMD")) {
    simd_request = simd_value(env);
    if (simd_request == SIMD_INVALID)
      error->all(FLERR, "environment variable TLSPH_SIMD (the default of pair_style tlsph's "
                        "simd) must be 'auto', 'no', 'portable', 'avx2' or 'avx512', got '{}'", env);
  }
}

void PairTLSPH::settings(int narg, char **arg)
{
  set_defaults();
  dim = domain->dimension;
  bool have_h = false;

  int iarg = 0;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (iarg + 1 >= narg)
      error->all(FLERR, "pair_style tlsph: keyword '{}' needs a value", key);
    const char *val = arg[iarg + 1];
    if (key == "h") {
      h = TLSPHInput::number(error, "pair_style tlsph", key, val);
      if (h <= 0.0) error->all(FLERR, "pair_style tlsph: h must be > 0 (smoothing length), got {}", val);
      have_h = true;
    } else if (key == "alpha") {
      alpha = TLSPHInput::number(error, "pair_style tlsph", key, val);
      if (alpha < 0.0) error->all(FLERR, "pair_style tlsph: alpha must be >= 0, got {}", val);
    } else if (key == "beta") {
      beta = TLSPHInput::number(error, "pair_style tlsph", key, val);
      if (beta < 0.0) error->all(FLERR, "pair_style tlsph: beta must be >= 0, got {}", val);
    } else if (key == "gamma") {
      gamma = TLSPHInput::number(error, "pair_style tlsph", key, val);
      if (gamma < 0.0) error->all(FLERR, "pair_style tlsph: gamma must be >= 0, got {}", val);
    } else if (key == "hourglass") {
      if (strcmp(val, "thesis") == 0) hg_form = 1;
      else if (strcmp(val, "conservative") == 0) hg_form = 2;
      else error->all(FLERR, "pair_style tlsph: hourglass must be 'thesis' or 'conservative', got "
                             "'{}'", val);
    } else if (key == "plane") {
      if (dim != 2)
        error->all(FLERR, "pair_style tlsph: keyword 'plane' is only allowed with dimension 2 "
                          "(this simulation is 3D)");
      if (strcmp(val, "strain") == 0) plane_stress = 0;
      else if (strcmp(val, "stress") == 0) plane_stress = 1;
      else error->all(FLERR, "pair_style tlsph: plane must be 'strain' or 'stress', got '{}'", val);
    } else if (key == "thickness") {
      if (dim != 2)
        error->all(FLERR, "pair_style tlsph: keyword 'thickness' is only allowed with dimension 2 "
                          "(this simulation is 3D)");
      thickness = TLSPHInput::number(error, "pair_style tlsph", key, val);
      if (thickness <= 0.0)
        error->all(FLERR, "pair_style tlsph: thickness must be > 0, got {}", val);
    } else if (key == "gradient") {
      if (strcmp(val, "linear") == 0) order = 1;
      else if (strcmp(val, "quadratic") == 0) order = 2;
      else error->all(FLERR, "pair_style tlsph: gradient must be 'linear' or 'quadratic', got '{}'", val);
    } else if (key == "cutfactor") {
      cutfactor = TLSPHInput::number(error, "pair_style tlsph", key, val);
      if (cutfactor < 1.0)
        error->all(FLERR, "pair_style tlsph: cutfactor must be >= 1, got {}", val);
    } else if (key == "check_partners" || key == "check_volume") {
      int flag;
      if (strcmp(val, "yes") == 0) flag = 1;
      else if (strcmp(val, "no") == 0) flag = 0;
      else error->all(FLERR, "pair_style tlsph: {} must be 'yes' or 'no', got '{}'", key, val);
      (key == "check_partners" ? check_partners : check_volume) = flag;
    } else if (key == "simd") {
      simd_request = simd_value(val);
      if (simd_request == SIMD_INVALID) error->all(FLERR, "pair_style tlsph: simd must be 'auto', 'no', 'portable', 'avx2' or "
                             "'avx512', got '{}'", val);
    } else {
      error->all(FLERR,
                 "pair_style tlsph: unknown keyword '{}' (allowed: h, alpha, beta, gamma, hourglass, "
                 "plane, thickness, gradient, cutfactor, check_partners, check_volume, simd)", key);
    }
    iarg += 2;
  }
  if (!have_h) error->all(FLERR, "pair_style tlsph: keyword 'h' (smoothing length) is required");
  kernel = CubicSpline(h, dim);
  // the kernel's normalisation ~ 1/h^dim and LAMMPS's squared cutoff
  // (2 h cutfactor)^2 must be finite and > 0 (an underflow to 0 would mean
  // no cutoff, an overflow no kernel)
  const double cut = 2.0 * h * cutfactor;
  if (!(std::isfinite(kernel.norm) && kernel.norm > 0.0 && std::isfinite(cut * cut) &&
        cut * cut > 0.0))
    error->all(FLERR, "pair_style tlsph: h = {} with cutfactor {} is out of the range a {}D kernel "
                      "can be computed in (1/h^{} and (2 h cutfactor)^2 must be finite and > 0)",
               h, cutfactor, dim, dim);
}

/* ----------------------------------------------------------------------
   pair_coeff I J E value nu value rho value      (inline, I and J ranges)
   pair_coeff I J E1 v E2 v E3 v G12 v G13 v G23 v nu12 v nu13 v nu23 v
                  rho v [theta v]                 (orthotropic ply)
   pair_coeff * * file.tlsph name1 name2 ...      (one name per atom type,
                                                   name@angle: a ply at angle)
------------------------------------------------------------------------- */

namespace {
// the orthotropic constants, in the order of TLSPH::OrthotropicConstants
const char *const ORTHO_NAMES[9] = {"E1", "E2", "E3", "G12", "G13", "G23", "nu12", "nu13", "nu23"};

int ortho_index(const std::string &key)
{
  for (int k = 0; k < 9; k++)
    if (key == ORTHO_NAMES[k]) return k;
  return -1;
}

bool is_material_keyword(const std::string &key)
{
  return key == "E" || key == "nu" || key == "rho" || key == "theta" || ortho_index(key) >= 0;
}

// keyword/value pairs: does any keyword make this an orthotropic material?
bool has_orthotropic_key(const std::vector<std::string> &words)
{
  for (size_t m = 0; m < words.size(); m += 2)
    if (words[m] == "theta" || ortho_index(words[m]) >= 0) return true;
  return false;
}
}    // namespace

// the constants derived from a material's values (isotropic: lambda, mu;
// a ply: its rotated stiffness; both: the wave speed c0 and the hourglass
// modulus E_hg) must be finite, and c0, E_hg, mu > 0: values of extreme
// magnitudes can overflow them
static void check_derived(Error *error, const PairTLSPH::Material &m, const std::string &where)
{
  auto good = [](double v) { return std::isfinite(v) && v > 0.0; };
  bool ok = good(m.c0) && good(m.E_hg);
  if (m.orthotropic)
    for (double c : m.ortho_law.C) ok = ok && std::isfinite(c);
  else
    ok = ok && std::isfinite(m.lambda) && good(m.mu);
  if (!ok)
    error->all(FLERR, "{}: the material values are out of the range this style can compute "
                      "with: they give a wave speed c0 = {:.6g}, hourglass modulus E_hg = {:.6g}{} "
                      "(these must be finite and > 0)", where, m.c0, m.E_hg,
               m.orthotropic ? "" : fmt::format(", lambda = {:.6g}, mu = {:.6g}", m.lambda, m.mu));
}

// Gc, sc: accepted (one material file serves both styles) but unused by
// tlsph; given inline they are most likely meant for tlsph/damage: say so
bool PairTLSPH::material_key(int, const std::string &key, double, const std::string &where)
{
  if (key != "Gc" && key != "sc") return false;
  if (comm->me == 0 && where.rfind("pair_coeff", 0) == 0)
    error->warning(FLERR, "{}: '{}' is a fracture value of pair_style tlsph/damage; pair_style "
                          "tlsph ignores it", where, key);
  return true;
}

void PairTLSPH::set_material(int type, const std::vector<std::string> &words,
                             const std::string &where)
{
  if (words.size() % 2)
    error->all(FLERR, "{}: material values come as keyword/value pairs ({}), got an odd count",
               where, MATERIAL_KEYS);
  // one parse for the unknown keywords and the fracture values (material_key)
  std::string iso_key, ortho_key;
  for (size_t m = 0; m < words.size(); m += 2) {
    const std::string &key = words[m];
    const double v = TLSPHInput::number(error, where, key, words[m + 1].c_str());
    if (key == "E" || key == "nu") {
      if (iso_key.empty()) iso_key = key;
    } else if (key == "theta" || ortho_index(key) >= 0) {
      if (ortho_key.empty()) ortho_key = key;
    } else if (key != "rho" && !material_key(type, key, v, where))
      error->all(FLERR, "{}: unknown material keyword '{}' (allowed: {} for an isotropic "
                        "material; {} for an orthotropic ply{})", where, key, MATERIAL_KEYS,
                 ORTHO_KEYS, extra_material_keys());
  }
  if (!iso_key.empty() && !ortho_key.empty())
    error->all(FLERR, "{}: isotropic and orthotropic material keywords cannot be mixed (got '{}' "
                      "and '{}'): give either E, nu, rho or E1, E2, E3, G12, G13, G23, nu12, "
                      "nu13, nu23, rho [theta]", where, iso_key, ortho_key);
  if (!ortho_key.empty()) {
    set_orthotropic(type, words, where);
    return;
  }

  double E = -1.0, nu = -2.0, rho = -1.0;
  bool hE = false, hnu = false, hrho = false;
  for (size_t m = 0; m < words.size(); m += 2) {
    const std::string &key = words[m];
    const double v = TLSPHInput::number(error, where, key, words[m + 1].c_str());
    if (key == "E") E = v, hE = true;
    else if (key == "nu") nu = v, hnu = true;
    else if (key == "rho") rho = v, hrho = true;
  }
  if (!hE) error->all(FLERR, "{}: missing material value 'E' (Young's modulus)", where);
  if (!hnu) error->all(FLERR, "{}: missing material value 'nu' (Poisson's ratio)", where);
  if (!hrho) error->all(FLERR, "{}: missing material value 'rho' (reference density)", where);
  if (E <= 0.0) error->all(FLERR, "{}: E must be > 0, got {}", where, E);
  if (nu <= -1.0 || nu >= 0.5)
    error->all(FLERR, "{}: nu must satisfy -1 < nu < 0.5, got {}", where, nu);
  if (rho <= 0.0) error->all(FLERR, "{}: rho must be > 0, got {}", where, rho);

  Material &m = mat[type];
  m = Material{};
  m.orthotropic = 0;
  m.E = E;
  m.nu = nu;
  m.rho = rho;
  m.lambda = lame_lambda(E, nu);
  m.mu = lame_mu(E, nu);
  m.c0 = wave_speed(m.lambda, m.mu, rho);
  m.E_hg = E;
  check_derived(error, m, where);
  pairmat[type] = PairMaterial{m.c0, m.rho, m.E_hg};
  sync_laws();
  check_material(type, where);
}

/* An orthotropic ply (doc: "Orthotropic materials"): validated so that the
   compliance is positive definite, i.e. the strain energy is positive for
   every strain. */
void PairTLSPH::set_orthotropic(int type, const std::vector<std::string> &words,
                                const std::string &where)
{
  double k[9], rho = -1.0, theta = 0.0;
  bool have[9] = {false, false, false, false, false, false, false, false, false}, hrho = false;
  for (size_t m = 0; m < words.size(); m += 2) {
    const std::string &key = words[m];
    const double v = TLSPHInput::number(error, where, key, words[m + 1].c_str());
    const int idx = ortho_index(key);
    if (idx >= 0) k[idx] = v, have[idx] = true;
    else if (key == "rho") rho = v, hrho = true;
    else if (key == "theta") theta = v;
  }
  std::string missing;
  for (int n = 0; n < 9; n++)
    if (!have[n]) missing += fmt::format("{}'{}'", missing.empty() ? "" : ", ", ORTHO_NAMES[n]);
  if (!hrho) missing += fmt::format("{}'rho'", missing.empty() ? "" : ", ");
  if (!missing.empty())
    error->all(FLERR, "{}: missing orthotropic material value(s) {} (an orthotropic ply needs "
                      "E1, E2, E3, G12, G13, G23, nu12, nu13, nu23 and rho; theta is optional, "
                      "default 0)", where, missing);
  for (int n = 0; n < 6; n++)
    if (!(k[n] > 0.0)) error->all(FLERR, "{}: {} must be > 0, got {}", where, ORTHO_NAMES[n], k[n]);
  if (!(rho > 0.0)) error->all(FLERR, "{}: rho must be > 0, got {}", where, rho);
  if (!std::isfinite(theta))
    error->all(FLERR, "{}: theta (fibre angle, degrees) must be finite, got {}", where, theta);
  const OrthotropicConstants c{k[0], k[1], k[2], k[3], k[4], k[5], k[6], k[7], k[8]};
  // |nu_ij| < sqrt(E_i / E_j): the 2x2 minors of the compliance (nu_ij nu_ji < 1)
  const struct {
    int nu, Ei, Ej;
  } pairs[3] = {{6, 0, 1}, {7, 0, 2}, {8, 1, 2}};
  for (const auto &p : pairs) {
    const double bound = sqrt(k[p.Ei] / k[p.Ej]);
    if (!(fabs(k[p.nu]) < bound))
      error->all(FLERR, "{}: {} = {} is out of range: |{}| must be < sqrt({}/{}) = {:.6g} for a "
                        "positive-definite compliance", where, ORTHO_NAMES[p.nu], k[p.nu],
                 ORTHO_NAMES[p.nu], ORTHO_NAMES[p.Ei], ORTHO_NAMES[p.Ej], bound);
  }
  const double delta = orthotropic_delta(c);
  if (!(delta > 0.0))
    error->all(FLERR, "{}: the orthotropic constants give a compliance matrix that is not positive "
                      "definite: 1 - nu12 nu21 - nu23 nu32 - nu31 nu13 - 2 nu21 nu32 nu13 = {:.6g} "
                      "must be > 0 (nu_ji = nu_ij E_j/E_i)", where, delta);

  Material &m = mat[type];
  m = Material{};
  m.orthotropic = 1;
  m.rho = rho;
  m.ortho = c;
  m.theta = theta;
  if (!make_orthotropic(c, theta, dim == 2 ? plane_stress : 0, m.ortho_law))
    error->all(FLERR, "{}: the orthotropic compliance matrix cannot be inverted", where);
  // rho c^2 of the fastest plane wave over all directions: independent of
  // theta, so found in the material axes (which the search grid contains)
  double Clocal[36];
  orthotropic_stiffness_local(c, Clocal);
  m.c0 = sqrt(max_acoustic_modulus(Clocal) / rho);
  // the Voigt average is invariant under the rotation: taken in the material
  // axes, where the shear moduli do not enter the bulk part (in the rotated C
  // they do, with opposite signs, and a G12 many orders above E1 cancels
  // there to a zero or negative E_hg)
  m.E_hg = voigt_young_modulus(Clocal);
  check_derived(error, m, where);
  pairmat[type] = PairMaterial{m.c0, m.rho, m.E_hg};
  sync_laws();
  if (comm->me == 0)
    utils::logmesg(lmp, "pair tlsph: type {} is an orthotropic ply at theta = {} degrees: wave "
                        "speed c0 = {:.6g}, hourglass modulus (Voigt average) E_hg = {:.6g}\n",
                   type, theta, m.c0, m.E_hg);
  check_material(type, where);
}

/* the 2D mode of the orthotropic laws (settings may change after pair_coeff)
   and whether the per-particle law test must be compiled into the step */
void PairTLSPH::sync_laws()
{
  any_orthotropic = 0;
  for (int t = 1; t < (int) mat.size(); t++) {
    mat[t].ortho_law.plane_stress = (dim == 2) ? plane_stress : 0;
    if (mat[t].orthotropic && mat[t].rho > 0.0) any_orthotropic = 1;
  }
}

void PairTLSPH::coeff(int narg, char **arg)
{
  if (narg < 3)
    error->all(FLERR, "pair_coeff tlsph: expected 'I J E value nu value rho value' or "
                      "'* * file name1 name2 ...'");
  if (!allocated) allocate();
  const int ntypes = atom->ntypes;

  const std::string first = arg[2];
  double dummy;
  const bool inline_form = is_material_keyword(first) || is_extra_material_key(first, dummy);
  if (!inline_form) {
    if (strcmp(arg[0], "*") != 0 || strcmp(arg[1], "*") != 0)
      error->all(FLERR, "pair_coeff tlsph: the file form must be 'pair_coeff * * {} name1 ... "
                        "name{}' (or give inline values: {}; or {})", first, ntypes, MATERIAL_KEYS,
                 ORTHO_KEYS);
    if (narg != 3 + ntypes)
      error->all(FLERR, "pair_coeff tlsph: file '{}' needs one material name per atom type ({}), "
                        "got {}", first, ntypes, narg - 3);
    read_material_file(first, ntypes, &arg[3]);
  } else {
    int ilo, ihi, jlo, jhi;
    utils::bounds(FLERR, arg[0], 1, ntypes, ilo, ihi, error);
    utils::bounds(FLERR, arg[1], 1, ntypes, jlo, jhi, error);
    const int lo = MAX(ilo, jlo), hi = MIN(ihi, jhi);
    if (lo > hi)
      error->all(FLERR, "pair_coeff tlsph: a material belongs to one atom type (pair_coeff I I "
                        "...); partners of different types interact automatically");
    std::vector<std::string> words(arg + 2, arg + narg);
    for (int i = lo; i <= hi; i++) {
      set_material(i, words, fmt::format("pair_coeff {} {}", i, i));
      setflag[i][i] = 1;
    }
  }
  for (int i = 1; i <= ntypes; i++)
    for (int j = i + 1; j <= ntypes; j++) setflag[i][j] = (setflag[i][i] && setflag[j][j]);
}

/* Debian's LAMMPS ignores $LAMMPS_POTENTIALS (its potential path is fixed to
   /usr/share/lammps/potentials), so material files are also looked up in
   $TLSPH_POTENTIALS and in the package's own potentials/ folder. */
static std::string find_material_file(const std::string &file)
{
  auto readable = [](const std::string &p) { return std::ifstream(p).good(); };
  if (readable(file) || file.find('/') != std::string::npos) return file;
  std::vector<std::string> dirs;
  if (const char *env = getenv("TLSPH_POTENTIALS")) dirs.emplace_back(env);
#ifdef TLSPH_POTENTIALS_DIR
  dirs.emplace_back(TLSPH_POTENTIALS_DIR);
#endif
  for (const auto &d : dirs)
    if (readable(d + "/" + file)) return d + "/" + file;
  return file;    // LAMMPS's own search and error message
}

void PairTLSPH::read_material_file(const std::string &file, int ntypes, char **names)
{
  // a name may carry a ply angle, NAME@THETA (degrees): one file line then
  // serves the plies of a laminate
  std::vector<std::string> base(ntypes + 1), angle(ntypes + 1);
  for (int t = 1; t <= ntypes; t++) {
    const std::string name = names[t - 1];
    const size_t at = name.find('@');
    base[t] = name.substr(0, at);
    if (at == std::string::npos) continue;
    angle[t] = name.substr(at + 1);
    if (!utils::is_double(angle[t]))
      error->all(FLERR, "pair_coeff tlsph: '{}' (atom type {}): the ply angle after '@' must be a "
                        "number (degrees), got '{}'", name, t, angle[t]);
  }
  // rank 0 reads the (small) file -- LAMMPS's reader refuses other ranks --
  // and broadcasts its lines; lines: name key value key value ...
  std::string text;
  if (comm->me == 0) {
    PotentialFileReader reader(lmp, find_material_file(file), "tlsph material");
    char *line;
    while ((line = reader.next_line())) {
      text += line;
      text += '\n';
    }
  }
  int len = text.size();
  MPI_Bcast(&len, 1, MPI_INT, 0, world);
  text.resize(len);
  MPI_Bcast(&text[0], len, MPI_CHAR, 0, world);
  std::vector<std::vector<std::string>> found(ntypes + 1);
  std::vector<bool> have(ntypes + 1, false);
  for (const auto &line : Tokenizer(text, "\n").as_vector()) {
    std::vector<std::string> words = Tokenizer(line, " \t\r\f").as_vector();
    if (words.empty()) continue;
    for (int t = 1; t <= ntypes; t++) {
      if (words[0] != base[t]) continue;
      found[t].assign(words.begin() + 1, words.end());
      have[t] = true;
    }
  }
  for (int t = 1; t <= ntypes; t++) {
    if (strcmp(names[t - 1], "NULL") == 0) continue;
    if (!have[t])
      error->all(FLERR, "pair_coeff tlsph: material '{}' (atom type {}) not found in file '{}'",
                 base[t], t, file);
    if (!angle[t].empty()) {
      if (!has_orthotropic_key(found[t]))
        error->all(FLERR, "pair_coeff tlsph: '{}' (atom type {}): a ply angle '@{}' needs an "
                          "orthotropic material, but '{}' in {} is isotropic (E, nu)",
                   names[t - 1], t, angle[t], base[t], file);
      // after the line's own values: replaces a theta given there
      found[t].emplace_back("theta");
      found[t].push_back(angle[t]);
    }
    set_material(t, found[t], fmt::format("material '{}' in {}", names[t - 1], file));
    setflag[t][t] = 1;
  }
}

/* ---------------------------------------------------------------------- */

void PairTLSPH::init_style()
{
  if (!atom->peri_flag || !atom->rmass_flag || !atom->vfrac_flag)
    error->all(FLERR, "pair tlsph requires atom_style peri (per-particle mass, volume and "
                      "reference position x0)");
  if (domain->dimension != dim)
    error->all(FLERR, "pair tlsph was set up for dimension {} but the simulation is {}D: "
                      "re-issue pair_style after the dimension command", dim, domain->dimension);
  if (dim == 2 && domain->zperiodic == 0)
    error->all(FLERR, "pair tlsph in 2D needs a periodic z dimension (LAMMPS 2D convention)");
  // pair_style may have been re-issued (plane strain/stress) after pair_coeff
  sync_laws();

  // partners are found through global IDs: make sure an atom map exists
  if (atom->tag_enable == 0) error->all(FLERR, "pair tlsph requires atom IDs");
  if (atom->map_style == Atom::MAP_NONE) {
    atom->map_init();
    atom->map_set();
  }

  // the internal fix that owns the bonds
  int ifix = modify->find_fix_by_style("^TLSPH_BONDS$");
  if (ifix < 0) {
    modify->add_fix("TLSPH_BONDS all TLSPH_BONDS");
    ifix = modify->find_fix_by_style("^TLSPH_BONDS$");
  }
  bonds = dynamic_cast<FixTLSPHBonds *>(modify->fix[ifix]);
  bonds->owner = this;
  bonds->datamask_read = V_MASK | MASK_MASK;    // (-k on: the host tally reads v)
  bonds->set_cutoff(2.0 * h);
  bonds->rebuild = 1;

  // forward communication: the packed rows; R only for the gather form
  // (newton_pair off, or the SIMD step), which alone reads it
  select_simd();
  bond_values_kept = keeps_bond_values();
  rows_kept = keeps_rows();
  if (!bond_values_kept) {
    memory->destroy(lean.g);
    memory->destroy(lean.w);
    ngw_max = 0;
  }
  ell_version = -1;
  ell_nrefill = ell_nrelaid = ell_nunshared = 0;
  ell_nscreened = ell_nskipped = 0;
  ell_nperm = 0;    // the columns' size follows the packed rows
  report_simd = 1;
  /* the SIMD step keeps the local particles sorted by reference position
     (sort_particles, at every reneighboring before the exchange, through
     the bond fix's pre_exchange): that order replaces LAMMPS's spatial sort
     (atom_modify sort), which would undo it */
  if (simd_isa != SIMD_NO) {
    modify->fmask[ifix] |= FixConst::PRE_EXCHANGE;
    if (atom->sortfreq > 0) {
      atom->sortfreq = 0;
      if (comm->me == 0)
        utils::logmesg(lmp, "pair tlsph: the SIMD step ({}) sorts the particles by reference "
                            "position itself: LAMMPS's atom sorting (atom_modify sort) is off\n",
                       simd_name(simd_isa));
    }
  } else {
    modify->fmask[ifix] &= ~FixConst::PRE_EXCHANGE;
  }
  gather_rows = (force->newton_pair && simd_isa == SIMD_NO) ? 0 : 1;
  comm_forward = packed_size();
  // the packed rows change size with the gradient order and dimension:
  // reallocate the per-atom arrays at the next force call
  nmax = 0;
  report_fallback = 1;

  // the viscosity reads the partners' velocities, ghosts included: without
  // this LAMMPS leaves ghost velocities unset (zero) and the result depends on
  // the domain decomposition (comm->init() runs after this and sizes buffers)
  if (viscosity_active()) comm->ghost_velocity = 1;

  // sanity checks of the per-particle data against the materials
  const int nlocal = atom->nlocal;
  int bad_volume = 0;
  // the particle whose mass/volume is farthest from its material's rho
  struct {
    double rel;
    int rank;
  } worst = {0.0, comm->me}, worst_all;
  int iworst = -1;
  for (int i = 0; i < nlocal; i++) {
    if (atom->vfrac[i] <= 0.0) bad_volume = 1;
    else {
      const double rho = atom->rmass[i] / atom->vfrac[i];
      const double rel = fabs(rho - mat[atom->type[i]].rho) / mat[atom->type[i]].rho;
      if (rel > worst.rel) worst.rel = rel, iworst = i;
    }
  }
  int any_bad;
  MPI_Allreduce(&bad_volume, &any_bad, 1, MPI_INT, MPI_MAX, world);
  if (any_bad)
    error->all(FLERR, "pair tlsph: every particle needs a volume > 0 (set ... volume, or the "
                      "volume column of read_data)");
  MPI_Allreduce(&worst, &worst_all, 1, MPI_DOUBLE_INT, MPI_MAXLOC, world);
  /* mass/volume against rho: the inertia uses the mass, the wave speed (the
     time step of fix tlsph/dt) and the viscosity use rho, so a ratio k
     between them changes the real wave speed against the assumed one by
     sqrt(k). Up to 1e-6 is round-off of the input numbers. Above 1 % it is
     not rounding either (numbers typed to 3 significant digits are within
     0.5 %): a forgotten 'set ... volume' (atom_style peri's default volume
     is 1: mass/volume is then ~100 % off) or 'set ... mass', another
     material's mass, or volumes in other units -- an error, unless
     'check_volume no' (e.g. mass scaling on purpose). In between: a warning. */
  if (worst_all.rel > 1.0e-6) {
    // the worst particle's numbers, from its rank
    double w[5] = {0.0, 0.0, 0.0, 0.0, 0.0};    // tag, type, mass, volume, rho
    if (comm->me == worst_all.rank && iworst >= 0) {
      w[0] = (double) atom->tag[iworst];
      w[1] = atom->type[iworst];
      w[2] = atom->rmass[iworst];
      w[3] = atom->vfrac[iworst];
      w[4] = mat[atom->type[iworst]].rho;
    }
    MPI_Bcast(w, 5, MPI_DOUBLE, worst_all.rank, world);
    const auto tag = (tagint) w[0];
    const int type = (int) w[1];
    const std::string what = fmt::format(
        "particle {} (type {}) has mass {:.6g} and volume {:.6g}: mass/volume = {:.6g}, but its "
        "material has rho = {:.6g} ({:.3g}% off)", tag, type, w[2], w[3], w[2] / w[3], w[4],
        100.0 * worst_all.rel);
    const std::string fix = fmt::format(
        "set the volume to the particle's share of the body, 'set type {} volume <{}>' for a "
        "lattice spacing dx, and the mass to rho*volume, 'set type {} mass <{:.6g}*volume>' (or "
        "the volume and mass columns of read_data){}", type,
        dim == 2 ? "dx^2 in 2D, dx^2 t with pair_style ... thickness t" : "dx^3 in 3D", type, w[4],
        w[3] == 1.0 ? "; volume 1 is atom_style peri's default: is 'set ... volume' missing?" : "");
    if (worst_all.rel > 0.01 && check_volume)
      error->all(FLERR, "pair tlsph: {}: {}; to run on anyway (e.g. masses scaled on purpose) "
                        "add 'check_volume no' to pair_style", what, fix);
    if (comm->me == 0)
      error->warning(FLERR, "pair tlsph: mass/volume differs from rho: {}; the wave speed and "
                            "viscosity use rho, the inertia uses the mass", what);
  }
}

double PairTLSPH::init_one(int i, int j)
{
  if (!(mat[i].rho > 0.0))
    error->all(FLERR, "pair tlsph: atom type {} has no material: use pair_coeff {} {} E ... nu ... "
                      "rho ...", i, i, i);
  if (!(mat[j].rho > 0.0))
    error->all(FLERR, "pair tlsph: atom type {} has no material: use pair_coeff {} {} E ... nu ... "
                      "rho ...", j, j, j);
  return 2.0 * h * cutfactor;
}

double PairTLSPH::max_wave_speed() const
{
  double c = 0.0;
  for (int t = 1; t <= atom->ntypes; t++)
    if (setflag && setflag[t][t]) c = MAX(c, mat[t].c0);
  return c;
}

/* ---------------------------------------------------------------------- */

void PairTLSPH::destroy_peratom()
{
  memory->destroy(Q);
  memory->destroy(sumg);
  memory->destroy(F);
  memory->destroy(P);
  memory->destroy(fown);
  memory->destroy(pk);
  memory->destroy(psi);
  memory->destroy(ehg);
  memory->destroy(nbond);
  memory->destroy(nlead);
  memory->destroy(x0c);
}

void PairTLSPH::grow_peratom()
{
  /* rows for the local and ghost particles (+1/32): not atom->nmax, which
     LAMMPS grows in steps of 16384 (36 % above the particle count of a
     36,100-particle block); nothing here migrates with an atom, and the
     count changes only at a reneighboring (peratom_rows_short). memory->grow
     keeps the rows that exist (init_style sets nmax = 0: the rows change
     width, and are made anew) */
  const int nall = atom->nlocal + atom->nghost;
  const int fresh = (nmax == 0);
  nmax = nall + nall / 32 + 16;
  if (fresh) destroy_peratom();
  // Q: DIM x basis size, <= QMAX; without rows_kept the SIMD layout's
  // columns hold it (q_build until build_ell)
  if (rows_kept) memory->grow(Q, nmax, correction_size(), "tlsph:Q");
  else memory->destroy(Q);
  memory->grow(sumg, nmax, 3, "tlsph:sumg");
  memory->grow(F, nmax, 9, "tlsph:F");
  memory->grow(P, nmax, 9, "tlsph:P");
  memory->grow(fown, nmax, 3, "tlsph:fown");
  // the packed rows: without rows_kept only the SIMD layout's columns hold
  // them (the lanes write them there, the forward communication packs and
  // unpacks them there)
  if (rows_kept) memory->grow(pk, nmax, packed_size(), "tlsph:packed");
  else memory->destroy(pk);
  memory->grow(psi, nmax, "tlsph:psi");
  memory->grow(ehg, nmax, "tlsph:ehg");
  memory->grow(nbond, nmax, "tlsph:nbond");
  memory->grow(nlead, nmax, "tlsph:nlead");
  memory->grow(x0c, nmax, 3, "tlsph:x0c");
}

/* x0c: the reference positions of local and ghost particles, shifted by
   the periodic image that x is in (x of a ghost carries the image shift,
   its x0 does not; x of a local atom is wrapped into the box at
   reneighboring, its x0 is not): x0c = x0 + (u - minimum_image(u)),
   u = x - x0. Then X_ij = x0c_j - x0c_i for every bond, and nothing
   changes between two reneighborings. Without a periodic dimension
   x0c = x0 exactly. */
void PairTLSPH::set_reference_images()
{
  double **x = atom->x, **x0 = atom->x0;
  const int nall = atom->nlocal + atom->nghost;
  const bool periodic = domain->xperiodic || domain->yperiodic || domain->zperiodic;
  for (int i = 0; i < nall; i++) {
    double u[3] = {x[i][0] - x0[i][0], x[i][1] - x0[i][1], x[i][2] - x0[i][2]};
    double um[3] = {u[0], u[1], u[2]};
    if (periodic) domain->minimum_image(um[0], um[1], um[2]);
    for (int d = 0; d < 3; d++) x0c[i][d] = (um[d] == u[d]) ? x0[i][d] : x0[i][d] + (u[d] - um[d]);
  }
}

/* room for a bond cache of nbonds bonds over the local particles (lean
   arrays with slack, row starts) */
void PairTLSPH::reserve_bond_cache(int nbonds)
{
  if (nbonds > ncache_max) {
    ncache_max = nbonds + nbonds / 32 + 16;
    memory->destroy(lean.j);
    memory->destroy(lean.k);
    memory->create(lean.j, ncache_max, "tlsph:bond_j");
    memory->create(lean.k, ncache_max, "tlsph:bond_k");
  }
  // the values only where they are kept (bond_values_kept)
  if (bond_values_kept && ngw_max < ncache_max) {
    ngw_max = ncache_max;
    memory->destroy(lean.g);
    memory->destroy(lean.w);
    memory->create(lean.g, ngw_max * dim, "tlsph:bond_g");
    memory->create(lean.w, ngw_max * 2, "tlsph:bond_w");
  }
  if (atom->nlocal + 1 > nstart_max) {
    nstart_max = atom->nlocal + 1 + atom->nlocal / 32 + 16;
    memory->destroy(bond_start);
    memory->create(bond_start, nstart_max, "tlsph:bond_start");
  }
}

/* The partners of the bond cache (pair_tlsph.h), without the bond math:
   x0c, and per local particle its partner indices lean.j and slots lean.k
   in the cache's order (the intact bonds that lead their pair, then the
   other intact ones, then, for correction_from_all_partners, the broken
   ones, which only enter the correction), nlead, nbond and bond_start (the
   broken ones are counted by bond_start only). Also the checks that need
   LAMMPS's map and images (a partner beyond the ghost cutoff, bond vectors
   no longer given by the minimum image) and, in shepard_max/shepard_i, the
   largest Shepard sum (kernel_scale sum_j V_j W_ij over the intact bonds,
   self included), when shepard is set (only its check right after the
   partner search reads it). The bond math (particle_bonds, tlsph_particle.h) follows
   on the host (build_bond_cache) or on a Kokkos device (the /kk styles). */
void PairTLSPH::resolve_bonds(bool shepard_sum, double &shepard_max, int &shepard_i)
{
  const int nlocal = atom->nlocal;
  double **x0 = atom->x0;
  double *vfrac = atom->vfrac;
  tagint *tag = atom->tag;
  if (peratom_rows_short()) grow_peratom();
  set_reference_images();

  int total = 0;
  for (int i = 0; i < nlocal; i++) total += bonds->npartner[i];
  reserve_bond_cache(total);

  const double kernel_scale = (dim == 2) ? 1.0 / thickness : 1.0;
  int nb = 0;
  shepard_max = 0.0;
  shepard_i = -1;
  // largest |X_ij (minimum image of x0) - (x0c_j - x0c_i)| relative to |X_ij|
  double image_error = 0.0;
  tagint image_i = 0;
  for (int i = 0; i < nlocal; i++) {
    bond_start[i] = nb;
    const int np = bonds->npartner[i];
    double shepard = kernel_scale * vfrac[i] * kernel.value(0.0);
    tagint *partner = bonds->partner[i];
    const unsigned char *state = bonds->state[i];
    int n = 0;
    for (int pass = 0; pass < 3; pass++) {
      if (pass == 2 && !correction_from_all_partners) break;
      for (int k = 0; k < np; k++) {
        if (pass < 2 && state[k] != FixTLSPHBonds::INTACT) continue;
        if (pass == 2 && state[k] != FixTLSPHBonds::BROKEN) continue;
        int j = atom->map(partner[k]);
        if (j < 0) {
          if (pass == 2) continue;    // a broken partner may have left the ghost shell
          error->one(FLERR, "pair tlsph: partner {} of particle {} is farther away than the "
                            "ghost cutoff at step {}: raise comm_modify cutoff or pair_style "
                            "cutfactor", partner[k], tag[i], update->ntimestep);
        }
        j = domain->closest_image(i, j);
        if (pass < 2 && (pass == 0) != (j >= nlocal || j > i)) continue;
        double Xm[3] = {x0[j][0] - x0[i][0], x0[j][1] - x0[i][1], x0[j][2] - x0[i][2]};
        domain->minimum_image(Xm[0], Xm[1], Xm[2]);
        // the step takes X_ij from x0c: the same vector unless a particle has
        // moved by half a periodic box length or more
        double X[3] = {x0c[j][0] - x0c[i][0], x0c[j][1] - x0c[i][1], x0c[j][2] - x0c[i][2]};
        if (dim == 2) X[2] = Xm[2] = 0.0;
        const double e = sqrt(((X[0] - Xm[0]) * (X[0] - Xm[0]) + (X[1] - Xm[1]) * (X[1] - Xm[1]) +
                               (X[2] - Xm[2]) * (X[2] - Xm[2])) / dot3(Xm, Xm));
        if (!(e <= image_error)) image_error = e, image_i = tag[i];
        if (shepard_sum && pass < 2)
          shepard += kernel_scale * vfrac[j] * kernel.value(sqrt(dot3(X, X)));
        lean.j[nb + n] = j;
        lean.k[nb + n] = k;
        n++;
      }
      if (pass == 0) nlead[i] = n;
      if (pass == 1) nbond[i] = n;
    }
    if (shepard > shepard_max || shepard_i < 0) shepard_max = shepard, shepard_i = i;
    nb += n;
  }
  bond_start[nlocal] = nb;
  if (image_error > 1.0e-8)
    error->one(FLERR, "pair tlsph: particle {} has moved by half a periodic box length or more "
                      "since its reference position was set (its bond vectors no longer follow "
                      "from the minimum image): not supported; enlarge the periodic box",
               image_i);
}

/* The bond cache in the lean layout (pair_tlsph.h): the partners
   (resolve_bonds), then the bond math of each particle on the host
   (particle_bonds: the full records are made in a scratch buffer -- the
   corrections work on them -- and only what the step reads is kept). */
void PairTLSPH::build_bond_cache()
{
  const int nlocal = atom->nlocal;
  double *vfrac = atom->vfrac;
  tagint *tag = atom->tag;
  double shepard_max;
  int shepard_i;
  resolve_bonds(bonds->check_pending != 0, shepard_max, shepard_i);

  const double kernel_scale = (dim == 2) ? 1.0 / thickness : 1.0;
  std::vector<double> vj(bonds->maxpartner);
  std::vector<BondCache> scratch(bonds->maxpartner);
  // the values of one particle when they are not kept (the SIMD layout gets
  // them in build_ell), and then Q too, in LAMMPS's order until build_ell
  std::vector<double> gone, wone;
  const int qsz = correction_size();
  if (!rows_kept) q_build.assign((size_t) qsz * nlocal, 0.0);
  int degraded = 0, nostress = 0;
  // right after the partner search: the particles whose gradient cannot be
  // formed (check_reference_partners); the one with the smallest ID is named
  const bool check_now = bonds->check_pending;
  tagint bad_tag = 0;
  int bad_np = 0;
  double bad_vol = 0.0, bad_dmin = 0.0;
  const X0Rows x0rows{x0c[0]};
  for (int i = 0; i < nlocal; i++) {
    const int s = bond_start[i], nall = bond_start[i + 1] - s;
    if (nall > (int) vj.size()) {
      vj.resize(nall);
      scratch.resize(nall);
    }
    if (!bond_values_kept && (int) wone.size() < 2 * nall) {
      gone.resize((size_t) 3 * nall);
      wone.resize((size_t) 2 * nall);
    }
    BondCache *b = scratch.data();
    double *fz = (correction_from_all_partners && bonds->nfrozen) ? bonds->frozen[i] : nullptr;
    // a correction frozen at setup: independent of which broken partners
    // are still present as ghosts
    const double *frozen = (fz && fz[0] == 1.0) ? fz + 1 : nullptr;
    auto math = [&](auto dim_order) {
      constexpr int D = decltype(dim_order)::first_type::value;
      constexpr int O = decltype(dim_order)::second_type::value;
      double *g = bond_values_kept ? lean.g + D * (bigint) s : gone.data();
      double *w = bond_values_kept ? lean.w + 2 * (bigint) s : wone.data();
      double *Qi = rows_kept ? Q[i] : q_build.data() + (size_t) qsz * i;
      return TLSPH::particle_bonds<D, O>(i, lean.j + s, lean.k + s, nall, nbond[i], x0rows, vfrac,
                                         kernel, kernel_scale, frozen, b, vj.data(), Qi, sumg[i],
                                         g, w);
    };
    using I1 = std::integral_constant<int, 1>;
    using I2 = std::integral_constant<int, 2>;
    using I3 = std::integral_constant<int, 3>;
    const int achieved = (dim == 2)
        ? (order == 1 ? math(std::pair<I2, I1>()) : math(std::pair<I2, I2>()))
        : (order == 1 ? math(std::pair<I3, I1>()) : math(std::pair<I3, I2>()));
    if (frozen) continue;
    if (achieved < order) degraded++;
    if (achieved == 0) {
      nostress++;
      if (check_now && (bad_tag == 0 || tag[i] < bad_tag)) {
        bad_tag = tag[i];
        bad_np = bonds->npartner[i];
        bad_vol = vfrac[i];
        bad_dmin = 0.0;
        for (int m = 0; m < nall; m++) {
          const double r = sqrt(dot3(b[m].X, b[m].X));
          if (m == 0 || r < bad_dmin) bad_dmin = r;
        }
      }
    }
    if (fz) {
      for (int k = 0; k < bonds->nfrozen; k++) fz[1 + k] = Q[i][k];
      fz[0] = 1.0;
    }
  }
  ndegraded = degraded;
  if (check_now) {
    bonds->check_pending = 0;
    check_reference_partners(nostress, bad_tag, bad_np, bad_vol, bad_dmin);
  }
  /* The kernel normalisation: sum_j V_j W_ij (the particle itself included,
     V in the kernel's measure: per thickness in 2D) is the SPH interpolant
     of 1, about 1 inside a body whose volumes tile it -- within a few % on a
     regular lattice for h >= dx (0.99 to 1.01 for h = 1.33 dx and 2 dx, 2D
     and 3D), less near a surface (the largest over all particles is
     taken). Off by a factor 2 or more, the volumes do not fit the spacing
     and h: a forgotten 'set ... volume' (default 1), volumes in other units,
     a 2D volume with a thickness not given by 'thickness', or h smaller
     than the spacing (then the particle's own term alone, 10/(7 pi h^2) V,
     exceeds 1). An error unless 'check_volume no'. Checked in the reference
     configuration, right after the partner search, when every bond is
     intact (later, broken bonds leave fragments with smaller sums). */
  if (check_now) {
    struct {
      double v;
      int rank;
    } mine = {shepard_i >= 0 ? shepard_max : -1.0, comm->me}, all;
    MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE_INT, MPI_MAXLOC, world);
    if (all.v >= 0.0 && (all.v < 0.5 || all.v > 2.0)) {
      double w[3] = {0.0, 0.0, 0.0};    // tag, volume, nearest partner distance
      if (comm->me == all.rank && shepard_i >= 0) {
        w[0] = (double) tag[shepard_i];
        w[1] = vfrac[shepard_i];
        for (int m = 0; m < nbond[shepard_i]; m++) {
          double X[3];
          bond_vector(shepard_i, m, X);
          const double r = sqrt(dot3(X, X));
          if (m == 0 || r < w[2]) w[2] = r;
        }
      }
      MPI_Bcast(w, 3, MPI_DOUBLE, all.rank, world);
      const double t = (dim == 2) ? thickness : 1.0;
      std::string expect;
      if (w[2] > 0.0)
        expect = fmt::format(" (its nearest partner is {:.4g} away: on a lattice of that spacing "
                             "its volume would be {:.4g})", w[2],
                             dim == 2 ? w[2] * w[2] * t : w[2] * w[2] * w[2]);
      else
        expect = fmt::format(" (it has no partner within 2h = {:.4g}: is h smaller than the "
                             "particle spacing?)", 2.0 * h);
      const std::string what = fmt::format(
          "the particle volumes do not match the kernel normalisation: sum_j V_j W_ij = {:.4g} "
          "at particle {} (volume {:.4g}, h = {:.4g}), about 1 expected (0.5 to 2 accepted){}",
          all.v, (tagint) w[0], w[1], h, expect);
      const std::string fix = fmt::format(
          "each particle's volume must be its share of the body, 'set type N volume <{}>' for a "
          "lattice spacing dx, and its mass rho*volume ('set type N mass ...'), or the volume and "
          "mass columns of read_data (atom_style peri's default volume is 1)",
          dim == 2 ? fmt::format("dx^2 in 2D, dx^2 t with pair_style ... thickness t (t = {:.4g} "
                                 "now)", thickness)
                   : "dx^3 in 3D");
      if (check_volume)
        error->all(FLERR, "pair tlsph: {}: {}; to run on anyway add 'check_volume no' to "
                          "pair_style", what, fix);
      if (comm->me == 0) error->warning(FLERR, "pair tlsph: {} ({})", what, fix);
    }
  }
  cache_version++;
}

/* the values of local particle i's bonds when lean.g and lean.w do not keep
   them (bond_values): particle_bonds with Q_i as a frozen correction, which
   makes the records as build_bond_cache's correction did and applies the
   same Q_i to them (apply_correction): the same values, bit for bit */
void PairTLSPH::recompute_bond_values(int i, const double *&g, const double *&w) const
{
  const int s = bond_start[i], nall = bond_start[i + 1] - s;
  if ((int) val_vj.size() < nall) {
    val_b.resize(nall);
    val_vj.resize(nall);
    val_g.resize((size_t) 3 * nall);
    val_w.resize((size_t) 2 * nall);
  }
  // Q_i: its row (rows_kept: tlsph/damage, whose rows follow a new
  // correction) or its column of the SIMD layout (build_ell has filled it
  // before any call)
  const int qsz = correction_size();
  val_q.resize((size_t) 2 * qsz);
  if (Q) {
    for (int q = 0; q < qsz; q++) val_q[qsz + q] = Q[i][q];
  } else {
    const double *qcol = ell_soa + (bigint) (3 * dim + packed_size()) * ell_nperm;
    for (int q = 0; q < qsz; q++) val_q[qsz + q] = qcol[(bigint) q * ell_nperm + ell_inv[i]];
  }
  const double kernel_scale = (dim == 2) ? 1.0 / thickness : 1.0;
  const X0Rows x0rows{x0c[0]};
  double sg[3];
  auto math = [&](auto dim_order) {
    constexpr int D = decltype(dim_order)::first_type::value;
    constexpr int O = decltype(dim_order)::second_type::value;
    TLSPH::particle_bonds<D, O>(i, lean.j + s, lean.k + s, nall, nbond[i], x0rows, atom->vfrac,
                                kernel, kernel_scale, val_q.data() + qsz, val_b.data(), val_vj.data(),
                                val_q.data(), sg, val_g.data(), val_w.data());
  };
  using I1 = std::integral_constant<int, 1>;
  using I2 = std::integral_constant<int, 2>;
  using I3 = std::integral_constant<int, 3>;
  if (dim == 2) order == 1 ? math(std::pair<I2, I1>()) : math(std::pair<I2, I2>());
  else order == 1 ? math(std::pair<I3, I1>()) : math(std::pair<I3, I2>());
  g = val_g.data();
  w = val_w.data();
}

// full records of the first n bonds of local particle i (g, c and the
// weights as made by make_bond(); a correction completes them)
void PairTLSPH::unpack_bonds(int i, int n, std::vector<BondCache> &b,
                             std::vector<double> &vj) const
{
  const double kernel_scale = (dim == 2) ? 1.0 / thickness : 1.0;
  const double *vfrac = atom->vfrac;
  if ((int) b.size() < n) b.resize(n), vj.resize(n);
  const int s = bond_start[i];
  for (int m = 0; m < n; m++) {
    double X[3];
    bond_vector(i, m, X);
    const int j = lean.j[s + m];
    make_bond(kernel, X, vfrac[i], vfrac[j], j, lean.k[s + m], b[m], kernel_scale);
    vj[m] = vfrac[j];
  }
}

/* Right after the partner search: every particle needs a corrected
   gradient. The correction inverts the moment matrix of its reference
   partners (tlsph_particle.h, TLSPH::correction): sum_j V_j w_ij p p^T over
   the partners within 2h, p = X_ij/h (linear: DIM x DIM) or X_ij/h and its
   squares and products (quadratic: 5 x 5 in 2D, 9 x 9 in 3D). It is
   invertible only with at least DIM partners that do not lie on one line
   (2D) or in one plane (3D) -- with the particle itself DIM+1 points that
   span the space -- and, for the quadratic basis, at least 5 (2D) or 9 (3D)
   suitably spread ones. A quadratic matrix that is singular or
   ill-conditioned falls back to the linear one (corners and thin strips:
   accepted, reported once per run in refresh_bond_cache); a linear one that
   fails leaves Q = 0: the particle has F = I, carries no stress of its own
   and only feels its partners. That is the error here (nbad: the number of
   such particles on this rank; bad_*: the one with the smallest ID, its
   partner count, volume and nearest partner distance), unless
   'check_partners no' (isolated particles on purpose): then a warning. */
void PairTLSPH::check_reference_partners(int nbad, tagint bad_tag, int bad_np, double bad_vol,
                                         double bad_dmin)
{
  int nall = 0;
  MPI_Allreduce(&nbad, &nall, 1, MPI_INT, MPI_SUM, world);
  if (nall == 0) return;
  // the bad particle with the smallest ID, and its numbers from its rank
  struct {
    double tag;
    int rank;
  } mine = {nbad ? (double) bad_tag : 1.0e300, comm->me}, first;
  MPI_Allreduce(&mine, &first, 1, MPI_DOUBLE_INT, MPI_MINLOC, world);
  double w[3] = {(double) bad_np, bad_vol, bad_dmin};
  MPI_Bcast(w, 3, MPI_DOUBLE, first.rank, world);
  const int np = (int) w[0];
  const double t = (dim == 2) ? thickness : 1.0;
  // the spacing: from the nearest partner, else from the particle's volume
  const double dx = np > 0 ? w[2] : (dim == 2 ? sqrt(w[1] / t) : cbrt(w[1]));
  const std::string spacing =
      np > 0 ? fmt::format("nearest partner {:.4g} away", dx)
             : fmt::format("particle spacing dx = {:.4g} from its volume", dx);
  const char *const shape = (dim == 2) ? "on one line" : "in one plane";
  // with DIM or more partners the matrix is singular because they are collinear (coplanar)
  const std::string degenerate = np >= dim ? fmt::format(", all {}", shape) : "";
  const std::string what = fmt::format(
      "particle {} has {} reference partner{}{} (h = {:.4g}, kernel support 2h = {:.4g}; {}, "
      "h = {:.3g} dx): a corrected gradient needs at least {} partners within 2h, not all {} "
      "({} for the quadratic gradient); {} of {} particles have too few", (tagint) first.tag,
      np, np == 1 ? "" : "s", degenerate, h, 2.0 * h, spacing, h / dx, dim, shape,
      dim == 2 ? 5 : 9, nall, atom->natoms);
  // what to change: h below the spacing (the usual mistake), else the geometry
  std::string advice;
  if (h < 0.999 * dx)
    advice = fmt::format("h must be larger than the particle spacing (h = 1.33 dx is the usual "
                         "value: h {:.4g} for this spacing)", 1.33 * dx);
  else if (np >= dim)
    advice = "h is not smaller than the spacing, but a body one particle thick has no gradient "
             "across it: make it at least two particles thick";
  else
    advice = "h is not smaller than the spacing: the particle lies apart from the others (check "
             "its position)";
  if (check_partners)
    error->all(FLERR, "pair_style tlsph: {}: {}; to run on with these particles carrying no "
                      "stress of their own (e.g. isolated particles on purpose) add "
                      "'check_partners no' to pair_style", what, advice);
  if (comm->me == 0)
    error->warning(FLERR, "pair_style tlsph: {}: they carry no stress of their own "
                          "(check_partners no)", what);
}

namespace {
// rows of a contiguous per-atom array (memory->create's double** arrays
// are one block): row j is base + stride j, one load instead of two
TLSPH::StridedRows Rows(double **p, int n) { return TLSPH::StridedRows{p ? p[0] : nullptr, n}; }
// the packed rows as the SIMD layout's columns, by LAMMPS index (inv: the step's order)
struct EllColumnRows {
  const double *base;
  long ns;
  const int *inv;
  TLSPH::ColumnRows::Row operator()(int j) const { return TLSPH::ColumnRows::Row{base + inv[j], ns}; }
};
struct ScatterForce {
  double **f;
  void operator()(int j, const double *t) const
  {
    f[j][0] -= t[0];
    f[j][1] -= t[1];
    f[j][2] -= t[2];
  }
};
// Newton's third law for the viscous and hourglass pair forces (see
// TLSPH::NoPairs): the opposite force to a local partner, also into the
// per-atom tallies of the bond fix
struct PairForces {
  static constexpr bool enabled = true;
  int nlead;
  int nlocal;
  double **f, **f_hg, **f_visc;    // f_hg null: the hourglass force is not tallied
  void operator()(int j, const double *pv, const double *ph) const
  {
    for (int d = 0; d < 3; d++) {
      f[j][d] -= pv[d] + ph[d];
      f_visc[j][d] -= pv[d];
      if (f_hg) f_hg[j][d] -= ph[d];
    }
  }
};
}    // namespace

// corrected gradients of the bonds b[0..n) of particle i for its current Q[i]
void PairTLSPH::apply_particle(int i, BondCache *b, int n, const double *vj)
{
  if (dim == 2) {
    if (order == 1) apply_correction<2, 1>(b, n, vj, kernel, Q[i], sumg[i]);
    else apply_correction<2, 2>(b, n, vj, kernel, Q[i], sumg[i]);
  } else {
    if (order == 1) apply_correction<3, 1>(b, n, vj, kernel, Q[i], sumg[i]);
    else apply_correction<3, 2>(b, n, vj, kernel, Q[i], sumg[i]);
  }
}

/* corrected gradients of particle i over the bonds b[0..n) (vj: partner
   volumes); returns the order achieved */
int PairTLSPH::correct_particle(int i, BondCache *b, int n, const double *vj)
{
  if (dim == 2)
    return (order == 1) ? correction<2, 1>(b, n, vj, kernel, Q[i], sumg[i])
                        : correction<2, 2>(b, n, vj, kernel, Q[i], sumg[i]);
  return (order == 1) ? correction<3, 1>(b, n, vj, kernel, Q[i], sumg[i])
                      : correction<3, 2>(b, n, vj, kernel, Q[i], sumg[i]);
}

/* ----------------------------------------------------------------------
   pass (1): F, stress, and the packed row the force pass reads
------------------------------------------------------------------------- */

template <int DIM, int ORDER, int LAWS> void PairTLSPH::compute_deformation()
{
  const auto x = Rows(atom->x, 3);
  const int nlocal = atom->nlocal;
  const bool need_K = viscosity_active();
  for (int i = 0; i < nlocal; i++) {
    TLSPH::deformation_gradient_bonds<DIM>(x, i, bonds_of<DIM>(i), nbond[i], F[i]);
    particle_stress<DIM, ORDER, LAWS>(i, need_K);
  }
}

void PairTLSPH::unstable_particle(int i, double J) const
{
  error->one(FLERR, "pair tlsph: particle {} (type {}) has det(F) = {} at step {}: the simulation "
                    "is unstable (reduce the time step, e.g. fix tlsph/dt, or raise alpha/gamma)",
             atom->tag[i], atom->type[i], J, update->ntimestep);
  std::abort();    // not reached: error->one does not return
}

// a scene of isotropic types only runs the loop without the per-particle law test
template <int DIM, int ORDER> void PairTLSPH::dispatch_deformation()
{
  if (any_orthotropic) compute_deformation<DIM, ORDER, 1>();
  else compute_deformation<DIM, ORDER, 0>();
}

/* ----------------------------------------------------------------------
   pass (3): stress, viscous and hourglass forces (tlsph_particle.h)
------------------------------------------------------------------------- */

template <int DIM, int ORDER, int HG, int VISC, int VIRIAL, int SCATTER>
void PairTLSPH::compute_forces()
{
  const auto x = Rows(atom->x, 3), v = Rows(atom->v, 3);
  const TLSPH::TypeArray type{atom->type};
  double **f = atom->f;
  double *vfrac = atom->vfrac;
  const int nlocal = atom->nlocal;
  // the work of these two forces is tallied by the bond fix, which needs the
  // full-step velocity (FixTLSPHBonds::end_of_step)
  double **f_hg = bonds->f_hg;
  double **f_visc = bonds->f_visc;
  const TLSPH::VirialTally tally{virial};
  const ScatterForce scatter{f};
  const PairMaterial *pm = pairmat.data();

  // with Newton's third law the partners receive their share of the pair
  // forces: the tallies are sums
  for (int i = 0; i < nlocal; i++)
    for (int d = 0; d < 3; d++) f_hg[i][d] = f_visc[i][d] = 0.0;
  // the conservative hourglass form has an energy (ehg): its work is not tallied
  PairForces pairs{0, nlocal, f, HG == 2 ? nullptr : f_hg, f_visc};
  const auto loop = [&](const auto &pkr) {
  for (int i = 0; i < nlocal; i++) {
    double fs[3] = {fown[i][0], fown[i][1], fown[i][2]}, fv[3] = {0, 0, 0}, fh[3] = {0, 0, 0};
    if (SCATTER) {
      pairs.nlead = nlead[i];
      particle_force_bonds<DIM, ORDER, HG, VISC, VIRIAL, SCATTER>(
          i, vfrac[i], bonds_of<DIM>(i), nbond[i], x, v, pkr, type, pm, h, beta, gamma, P[i], fs,
          fv, fh, tally, scatter, pairs);
    } else {
      particle_force_bonds<DIM, ORDER, HG, VISC, VIRIAL, SCATTER>(
          i, vfrac[i], bonds_of<DIM>(i), nbond[i], x, v, pkr, type, pm, h, beta, gamma, P[i], fs,
          fv, fh, tally, scatter);
    }
    for (int d = 0; d < DIM; d++) f[i][d] += fs[d] + fv[d] + fh[d];
    for (int d = 0; d < 3; d++) {
      if (HG != 2) f_hg[i][d] += fh[d];
      f_visc[i][d] += fv[d];
    }
  }
  };
  // the rows of the partners: pk, or (the SIMD step's virial pass, in the
  // gather form: rows_in_columns) its columns
  if constexpr (VIRIAL && !SCATTER) {
    if (rows_in_columns()) {
      loop(EllColumnRows{ell_soa + (bigint) 3 * DIM * ell_nperm, ell_nperm, ell_inv});
      return;
    }
  }
  loop(Rows(pk, packed_size()));
}

template <int DIM, int ORDER>
void PairTLSPH::dispatch_forces(int hg, int visc, int vir, int newton)
{
  if (hg == 0) dispatch_forces_hg<DIM, ORDER, 0>(visc, vir, newton);
  else if (hg == 1) dispatch_forces_hg<DIM, ORDER, 1>(visc, vir, newton);
  else dispatch_forces_hg<DIM, ORDER, 2>(visc, vir, newton);
}

template <int DIM, int ORDER, int HG>
void PairTLSPH::dispatch_forces_hg(int visc, int vir, int newton)
{
  // newton_pair on: the stress term is scattered to the partners and LAMMPS
  // sums the ghost forces; off: every particle gathers its whole force
  const int key = visc + 2 * vir + 4 * newton;
  switch (key) {
    // clang-format off
    case 0: compute_forces<DIM, ORDER, HG, 0, 0, 0>(); break;
    case 1: compute_forces<DIM, ORDER, HG, 1, 0, 0>(); break;
    case 2: compute_forces<DIM, ORDER, HG, 0, 1, 0>(); break;
    case 3: compute_forces<DIM, ORDER, HG, 1, 1, 0>(); break;
    case 4: compute_forces<DIM, ORDER, HG, 0, 0, 1>(); break;
    case 5: compute_forces<DIM, ORDER, HG, 1, 0, 1>(); break;
    case 6: compute_forces<DIM, ORDER, HG, 0, 1, 1>(); break;
    case 7: compute_forces<DIM, ORDER, HG, 1, 1, 1>(); break;
      // clang-format on
  }
}

void PairTLSPH::deformation_pass()
{
  if (dim == 2) {
    if (order == 1) dispatch_deformation<2, 1>();
    else dispatch_deformation<2, 2>();
  } else {
    if (order == 1) dispatch_deformation<3, 1>();
    else dispatch_deformation<3, 2>();
  }
}

/* ---------------------------------------------------------------------- */

/* the bond cache after a neighbor build (bond fix: rebuild); returns true
   when it was rebuilt. Once per run it reports the particles whose gradient
   correction fell back to a lower order. */
bool PairTLSPH::refresh_bond_cache()
{
  if (peratom_rows_short()) grow_peratom();
  if (!bonds->rebuild) return false;
  build_bond_cache();
  bonds->rebuild = 0;
  if (report_fallback) {
    // once per run: how many particles could not get the requested gradient order
    report_fallback = 0;
    int all = 0;
    MPI_Allreduce(&ndegraded, &all, 1, MPI_INT, MPI_SUM, world);
    if (all && comm->me == 0)
      utils::logmesg(lmp, "pair tlsph: {} particle(s) have too few or degenerate partners for "
                          "the {} gradient correction and use a lower order (see doc)\n",
                     all, order == 2 ? "quadratic" : "linear");
  }
  return true;
}

// global and per-atom energy of the step: V_i psi_i (+ E_hg,i, conservative form)
void PairTLSPH::tally_energy()
{
  if (!eflag_either) return;
  const int nlocal = atom->nlocal;
  double *vfrac = atom->vfrac;
  for (int i = 0; i < nlocal; i++) {
    const double e = vfrac[i] * psi[i] + (hg_form == 2 && gamma != 0.0 ? ehg[i] : 0.0);
    if (eflag_global) eng_vdwl += e;
    if (eflag_atom) eatom[i] += e;
  }
}

void PairTLSPH::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);
  refresh_bond_cache();

  // (1) F and stress; tlsph/damage applies its pre-cracks first, breaks bonds
  // inside the pass and then updates the damage and alpha_i (hooks, no-ops here)
  update_bonds();
  // the SIMD step (pair_tlsph_simd.cpp) reads the bond cache in its own layout
  const bool simd = simd_isa != SIMD_NO;
  if (simd && ell_version != cache_version) build_ell();
  if (simd) simd_deformation_pass();
  else deformation_pass();
  after_deformation();
  if (simd) simd_after_deformation();

  comm->forward_comm_pair(this);

  const int hg = (gamma != 0.0) ? hg_form : 0;
  const int visc = viscosity_active() ? 1 : 0;
  const int vir = vflag_global ? 1 : 0;
  // the SIMD step's force pass is the gather form; on a virial step (thermo
  // pressure, the setup of a run) the scalar gather form adds the virial,
  // its forces discarded, so that the forces of every step come from the
  // same code (a restart, whose setup step has the virial, stays bitwise)
  const int nt = (force->newton_pair && !simd) ? 1 : 0;
  if (simd) {
    simd_forces(hg, visc);
    if (vir) simd_virial(hg, visc);
  } else if (dim == 2) {
    if (order == 1) dispatch_forces<2, 1>(hg, visc, vir, nt);
    else dispatch_forces<2, 2>(hg, visc, vir, nt);
  } else {
    if (order == 1) dispatch_forces<3, 1>(hg, visc, vir, nt);
    else dispatch_forces<3, 2>(hg, visc, vir, nt);
  }
  tally_energy();
}

/* ---------------------------------------------------------------------- */

int PairTLSPH::pack_forward_comm(int n, int *list, double *buf, int /*pbc_flag*/, int * /*pbc*/)
{
  const int stride = packed_size();
  int m = 0;
  if (rows_in_columns()) {    // the SIMD layout's columns
    const double *pks = ell_soa + (bigint) 3 * dim * ell_nperm;
    for (int ii = 0; ii < n; ii++) {
      const double *c = pks + ell_inv[list[ii]];
      for (int k = 0; k < stride; k++) buf[m++] = c[(bigint) k * ell_nperm];
    }
    return m;
  }
  for (int ii = 0; ii < n; ii++) {
    const double *row = pk[list[ii]];
    for (int k = 0; k < stride; k++) buf[m++] = row[k];
  }
  return m;
}

void PairTLSPH::unpack_forward_comm(int n, int first, double *buf)
{
  const int stride = packed_size();
  int m = 0;
  if (rows_in_columns()) {
    double *pks = ell_soa + (bigint) 3 * dim * ell_nperm;
    for (int i = first; i < first + n; i++) {
      double *c = pks + ell_inv[i];
      for (int k = 0; k < stride; k++) c[(bigint) k * ell_nperm] = buf[m++];
    }
    return;
  }
  for (int i = first; i < first + n; i++)
    for (int k = 0; k < stride; k++) pk[i][k] = buf[m++];
}

/* ---------------------------------------------------------------------- */

void PairTLSPH::cauchy_stress(int i, double *sigma) const
{
  cauchy_stress(i, F[i], sigma);
}

void PairTLSPH::cauchy_stress(int i, const double *Fin, double *sigma) const
{
  const Material &m = mat[atom->type[i]];
  // sigma = P F^T / J from F, with the particle's own law
  auto cauchy = [&](const auto &law) {
    double Fi[9], E[9], S[9], P[9];
    for (int k = 0; k < 9; k++) Fi[k] = Fin[k];
    if (dim == 2) Fi[8] = 1.0;
    green_lagrange(Fi, E);
    law.stress(E, S);
    if (dim == 2 && plane_stress) Fi[8] = sqrt(1.0 + 2.0 * E[8]);
    mat_mul(Fi, S, P);
    const double J = mat_det(Fi);
    mat_mult(P, Fi, sigma);    // P F^T
    for (int k = 0; k < 9; k++) sigma[k] /= J;
  };
  if (m.orthotropic) cauchy(m.ortho_law);
  else cauchy(IsotropicSVK{m.lambda, m.mu, dim == 2 ? plane_stress : 0});
}

/* the in-plane Cauchy stress (xx, yy, xy) from the stored F: in 2D with an
   isotropic law the 2 x 2 products only (crack nucleation screens every
   particle every step with it), else from cauchy_stress */
void PairTLSPH::cauchy_stress_xy(int i, double *s) const
{
  const Material &m = mat[atom->type[i]];
  if (dim != 2 || m.orthotropic) {
    double sig[9];
    cauchy_stress(i, sig);
    s[0] = sig[0], s[1] = sig[4], s[2] = sig[1];
    return;
  }
  const double *Fi = F[i];
  const double f00 = Fi[0], f01 = Fi[1], f10 = Fi[3], f11 = Fi[4];
  double E[9] = {0.5 * (f00 * f00 + f10 * f10 - 1.0), 0.5 * (f00 * f01 + f10 * f11), 0.0,
                 0.5 * (f00 * f01 + f10 * f11), 0.5 * (f01 * f01 + f11 * f11 - 1.0), 0.0,
                 0.0, 0.0, 0.0};
  double S[9];
  IsotropicSVK{m.lambda, m.mu, plane_stress}.stress(E, S);
  const double J = (f00 * f11 - f01 * f10) * (plane_stress ? sqrt(1.0 + 2.0 * E[8]) : 1.0);
  const double a00 = f00 * S[0] + f01 * S[3], a01 = f00 * S[1] + f01 * S[4];
  const double a10 = f10 * S[0] + f11 * S[3], a11 = f10 * S[1] + f11 * S[4];
  s[0] = (a00 * f00 + a01 * f01) / J;
  s[1] = (a10 * f10 + a11 * f11) / J;
  s[2] = (a00 * f10 + a01 * f11) / J;
}

/* the local particles whose in-plane largest principal Cauchy stress (from
   the stored F) reaches s_min, ascending: in 2D with one isotropic law for
   all types a loop the compiler vectorises, comparing J s1 with J s_min (no
   division), else cauchy_stress_xy particle by particle */
void PairTLSPH::principal_screen_xy(double s_min, std::vector<int> &out) const
{
  out.clear();
  const int nlocal = atom->nlocal;
  if (nlocal == 0) return;
  bool one_law = (dim == 2);
  const Material &m0 = mat[atom->type[0]];
  for (int t = 1; t <= atom->ntypes && one_law; t++)
    if (mat[t].rho > 0.0 && (mat[t].orthotropic || mat[t].lambda != m0.lambda || mat[t].mu != m0.mu))
      one_law = false;
  if (!one_law || m0.orthotropic) {
    double s[3];
    for (int i = 0; i < nlocal; i++) {
      cauchy_stress_xy(i, s);
      const double d = 0.5 * (s[0] - s[1]);
      if (0.5 * (s[0] + s[1]) + sqrt(d * d + s[2] * s[2]) >= s_min) out.push_back(i);
    }
    return;
  }
  const double lam = m0.lambda, mu = m0.mu;
  const double *Fp = F[0];
  std::vector<unsigned char> hit(nlocal);
  // s1 >= s_min  <=>  sqrt(d^2 + xy^2) >= J s_min - c (c, d, xy of J sigma):
  // true when the right side is <= 0, else compared squared (no sqrt)
  // the particles that this step's stress lanes flagged (a superset:
  // simd_deformation), or every local particle
  const bool flagged = nuc_hit_step == update->ntimestep && (int) nuc_hit.size() >= nlocal;
  auto screen = [&](auto ps) {
    constexpr bool PS = decltype(ps)::value;
    for (int i = 0; i < nlocal; i++) {
      if (flagged && !nuc_hit[i]) {
        hit[i] = 0;
        continue;
      }
      const double *Fi = Fp + 9 * (bigint) i;
      const double f00 = Fi[0], f01 = Fi[1], f10 = Fi[3], f11 = Fi[4];
      const double e00 = 0.5 * (f00 * f00 + f10 * f10 - 1.0), e11 = 0.5 * (f01 * f01 + f11 * f11 - 1.0);
      const double e01 = 0.5 * (f00 * f01 + f10 * f11);
      // IsotropicSVK: plane stress E33 = -lambda (E11 + E22) / (lambda + 2 mu)
      const double e22 = PS ? -lam * (e00 + e11) / (lam + 2.0 * mu) : 0.0;
      const double tr = e00 + e11 + e22;
      const double s00 = 2.0 * mu * e00 + lam * tr, s11 = 2.0 * mu * e11 + lam * tr, s01 = 2.0 * mu * e01;
      const double a00 = f00 * s00 + f01 * s01, a01 = f00 * s01 + f01 * s11;
      const double a10 = f10 * s00 + f11 * s01, a11 = f10 * s01 + f11 * s11;
      const double xx = a00 * f00 + a01 * f01, yy = a10 * f10 + a11 * f11, xy = a00 * f10 + a01 * f11;
      const double J = (f00 * f11 - f01 * f10) * (PS ? sqrt(1.0 + 2.0 * e22) : 1.0);
      const double d = 0.5 * (xx - yy), rhs = s_min * J - 0.5 * (xx + yy);
      hit[i] = (rhs <= 0.0 || d * d + xy * xy >= rhs * rhs) ? 1 : 0;
    }
  };
  if (plane_stress) screen(std::true_type{});
  else screen(std::false_type{});
  for (int i = 0; i < nlocal; i++)
    if (hit[i]) out.push_back(i);
}

double PairTLSPH::pk1_stress(int i, double *Fi, double *Pi) const
{
  const Material &m = mat[atom->type[i]];
  // Fi: 3 x 3 with F33 = 1 in 2D (plane stress: set here from E33)
  double J;
  if (m.orthotropic) return stress_tensors(m.ortho_law, dim, Fi, Pi, nullptr, &J);
  return stress_tensors(IsotropicSVK{m.lambda, m.mu, dim == 2 ? plane_stress : 0}, dim, Fi, Pi,
                        nullptr, &J);
}

void PairTLSPH::green_lagrange_strain(int i, double *E) const
{
  const Material &m = mat[atom->type[i]];
  double Fi[9], S[9];
  mat_copy(F[i], Fi);
  if (dim == 2) Fi[8] = 1.0;
  green_lagrange(Fi, E);
  // the law sets the plane-stress E33
  if (m.orthotropic) m.ortho_law.stress(E, S);
  else IsotropicSVK{m.lambda, m.mu, dim == 2 ? plane_stress : 0}.stress(E, S);
}

/* ---------------------------------------------------------------------- */

/* per type: an int (0 no material, 1 isotropic, 2 orthotropic), then
   E nu rho, or E1 E2 E3 G12 G13 G23 nu12 nu13 nu23 rho theta, then the
   derived style's values; everything else is recomputed on reading */
void PairTLSPH::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  for (int i = 1; i <= atom->ntypes; i++) {
    const Material &m = mat[i];
    const int kind = !(m.rho > 0.0) ? 0 : (m.orthotropic ? 2 : 1);
    fwrite(&kind, sizeof(int), 1, fp);
    if (kind == 1) {
      double v[3] = {m.E, m.nu, m.rho};
      fwrite(v, sizeof(double), 3, fp);
    } else if (kind == 2) {
      const OrthotropicConstants &k = m.ortho;
      double v[11] = {k.E1, k.E2, k.E3, k.G12, k.G13, k.G23, k.nu12, k.nu13, k.nu23, m.rho, m.theta};
      fwrite(v, sizeof(double), 11, fp);
    }
    if (kind) write_material_extra(fp, i);
  }
}

void PairTLSPH::read_restart(FILE *fp)
{
  read_restart_settings(fp);
  allocate();
  const int me = comm->me;
  for (int i = 1; i <= atom->ntypes; i++) {
    int kind = 0;
    if (me == 0) utils::sfread(FLERR, &kind, sizeof(int), 1, fp, nullptr, error);
    MPI_Bcast(&kind, 1, MPI_INT, 0, world);
    if (kind != 0 && kind != 1 && kind != 2)
      error->all(FLERR, "pair tlsph: the restart file holds an unknown material kind {} for type "
                        "{} (written by another version?)", kind, i);
    if (!kind) continue;
    const int n = (kind == 1) ? 3 : 11;
    double v[11];
    if (me == 0) utils::sfread(FLERR, v, sizeof(double), n, fp, nullptr, error);
    MPI_Bcast(v, n, MPI_DOUBLE, 0, world);
    read_material_extra(fp, i);
    // rebuilt through set_material: the same derived values as from pair_coeff
    static const char *const iso_keys[3] = {"E", "nu", "rho"};
    static const char *const ortho_keys[11] = {"E1",   "E2",   "E3",   "G12", "G13",  "G23",
                                               "nu12", "nu13", "nu23", "rho", "theta"};
    std::vector<std::string> words;
    for (int k = 0; k < n; k++) {
      words.emplace_back(kind == 1 ? iso_keys[k] : ortho_keys[k]);
      words.push_back(fmt::format("{:.17g}", v[k]));
    }
    set_material(i, words, "restart file");
  }
}

void PairTLSPH::write_restart_settings(FILE *fp)
{
  // v[9]: the checks, 1000 + check_partners + 2 check_volume (the offset
  // tells this layout from the one before the checks were stored)
  double v[10] = {h,         alpha, beta, gamma, (double) plane_stress,
                  cutfactor, (double) order, thickness, (double) hg_form,
                  1000.0 + check_partners + 2.0 * check_volume};
  fwrite(v, sizeof(double), 10, fp);
  fwrite(&dim, sizeof(int), 1, fp);
}

void PairTLSPH::read_restart_settings(FILE *fp)
{
  double v[10];
  if (comm->me == 0) {
    utils::sfread(FLERR, v, sizeof(double), 10, fp, nullptr, error);
    utils::sfread(FLERR, &dim, sizeof(int), 1, fp, nullptr, error);
  }
  MPI_Bcast(v, 10, MPI_DOUBLE, 0, world);
  MPI_Bcast(&dim, 1, MPI_INT, 0, world);
  const int checks = static_cast<int>(v[9] - 1000.0);
  if (!(v[9] == 1000.0 + checks && checks >= 0 && checks <= 3 && (dim == 2 || dim == 3)))
    error->all(FLERR, "pair tlsph: the restart file's pair settings are not in this version's "
                      "layout (written by another version of the package?)");
  check_partners = checks & 1;
  check_volume = (checks >> 1) & 1;
  h = v[0];
  alpha = v[1];
  beta = v[2];
  gamma = v[3];
  plane_stress = static_cast<int>(v[4]);
  cutfactor = v[5];
  order = static_cast<int>(v[6]);
  thickness = v[7];
  hg_form = static_cast<int>(v[8]);
  kernel = CubicSpline(h, dim);
}

double PairTLSPH::memory_usage()
{
  double bytes =
      (double) nmax * (((Q ? correction_size() : 0) + 26 + (pk ? packed_size() : 0)) * sizeof(double) + sizeof(int));
  bytes += (double) nmax * (3 * sizeof(double) + sizeof(int));    // x0c, nlead
  // lean bond arrays: partner, slot; g (dim) and two weights where kept
  bytes += (double) ncache_max * 2 * sizeof(int) + (double) ngw_max * (dim + 2) * sizeof(double);
  bytes += (double) nstart_max * sizeof(int);
  // the SIMD step's layout: per slot and lane a partner and dim + 3 doubles
  bytes += (double) ell_nstart * 6 * sizeof(int);
  if (ell.npat) bytes += (double) ell.pat_start[ell.npat] * (sizeof(int) + (dim + 3) * sizeof(double));
  bytes += (double) ell_nblock_max * TLSPH::ELL_C * (sizeof(int) + (dim + 3) * sizeof(double));
  bytes += (double) ell_nperm * (3 * sizeof(int) + ell_ncolumns() * sizeof(double));
  return bytes;
}

void *PairTLSPH::extract(const char *name, int &dimflag)
{
  dimflag = 0;
  if (strcmp(name, "h") == 0) return (void *) &h;
  if (strcmp(name, "gamma") == 0) return (void *) &gamma;
  if (strcmp(name, "alpha") == 0) return (void *) &alpha;
  return nullptr;
}
