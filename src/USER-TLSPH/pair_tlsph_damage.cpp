/* ----------------------------------------------------------------------
   USER-TLSPH: pair_style tlsph/damage, see pair_tlsph_damage.h and
   doc/pair_tlsph_damage.rst
------------------------------------------------------------------------- */

#include "pair_tlsph_damage.h"

#include "tlsph_crack.h"
#include "tlsph_input.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix_tlsph_bonds.h"
#include "memory.h"
#include "pair_tlsph_step.h"
#include "tlsph_pair_terms.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

using namespace LAMMPS_NS;
using namespace TLSPH;

PairTLSPHDamage::PairTLSPHDamage(LAMMPS *lmp) : PairTLSPH(lmp)
{
  alpha_d = 1.0;
  absolute = 0;
  rebuild = 0;
  family = 0.0;
  damping_linear = 0;
  nmax_d = 0;
  phi = phis = alphas = phi_prev = mark = nullptr;
  phis_valid = 0;
  phis_stamp = {-1, -1, -1};
  comm_stage = 0;
  nbroken_local = 0;
  order = 1;
  tipmode = 0;
  tip_branch = 0.0;
  tips_ready = 0;
  tip_Eprime = tip_Gc = tip_cR = 0.0;
}

PairTLSPHDamage::~PairTLSPHDamage()
{
  memory->destroy(phi);
  memory->destroy(phis);
  memory->destroy(alphas);
  memory->destroy(phi_prev);
  memory->destroy(mark);
}

/* ----------------------------------------------------------------------
   pair_style tlsph/damage (keywords of tlsph) [alpha_d A] [criterion tension|absolute]
     [correction rebuild|setup] [family R] [damping step|linear] [precrack x1 y1 x2 y2 | x1 y1 z1 x2 y2 z2 x3 y3 z3] ...
------------------------------------------------------------------------- */

void PairTLSPHDamage::settings(int narg, char **arg)
{
  std::vector<char *> base;
  bool have_alpha_d = false, have_gradient = false;
  double alpha_d_value = 0.0;
  absolute = 0;
  family = 0.0;
  damping_linear = 0;
  tipmode = 0;
  tip_branch = 0.0;
  tip_hoop = 0;
  tip_kfit = 0;
  tip_jr1 = 2.0;
  tip_jr2 = 4.0;
  tip_seg = 0.0;
  bool have_branch = false;
  rebuild = 0;    // 'setup' (the thesis): measured better on Kalthoff-Winkler, see doc
  cracks.clear();
  const int d = domain->dimension;
  int iarg = 0;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (key == "alpha_d") {
      if (iarg + 1 >= narg) error->all(FLERR, "pair_style tlsph/damage: alpha_d needs a value");
      alpha_d_value = TLSPHInput::number(error, "pair_style tlsph/damage", key, arg[iarg + 1]);
      if (alpha_d_value < 0.0)
        error->all(FLERR, "pair_style tlsph/damage: alpha_d must be >= 0, got {}", arg[iarg + 1]);
      have_alpha_d = true;
      iarg += 2;
    } else if (key == "criterion") {
      if (iarg + 1 >= narg) error->all(FLERR, "pair_style tlsph/damage: criterion needs a value");
      if (strcmp(arg[iarg + 1], "tension") == 0) absolute = 0;
      else if (strcmp(arg[iarg + 1], "absolute") == 0) absolute = 1;
      else if (strcmp(arg[iarg + 1], "tip") == 0) tipmode = 1;
      else
        error->all(FLERR, "pair_style tlsph/damage: criterion must be 'tension', 'absolute' or "
                          "'tip', got '{}'", arg[iarg + 1]);
      iarg += 2;
    } else if (key == "tipdir") {
      if (iarg + 1 >= narg) error->all(FLERR, "pair_style tlsph/damage: tipdir needs a value");
      have_branch = true;
      if (strcmp(arg[iarg + 1], "faces") == 0) tip_hoop = 0;
      else if (strcmp(arg[iarg + 1], "hoop") == 0) tip_hoop = 1;
      else
        error->all(FLERR, "pair_style tlsph/damage: tipdir must be 'faces' or 'hoop', got '{}'",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (key == "kfit") {
      if (iarg + 1 >= narg) error->all(FLERR, "pair_style tlsph/damage: kfit needs a value");
      have_branch = true;
      if (strcmp(arg[iarg + 1], "tip") == 0) tip_kfit = 0;
      else if (strcmp(arg[iarg + 1], "offset") == 0) tip_kfit = 1;
      else if (strcmp(arg[iarg + 1], "j") == 0) tip_kfit = 2;
      else
        error->all(FLERR, "pair_style tlsph/damage: kfit must be 'tip', 'offset' or 'j', got '{}'",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (key == "jring") {
      if (iarg + 2 >= narg)
        error->all(FLERR, "pair_style tlsph/damage: jring needs two values (the J domain's inner "
                          "and outer radius in h)");
      tip_jr1 = TLSPHInput::number(error, "pair_style tlsph/damage", key, arg[iarg + 1]);
      tip_jr2 = TLSPHInput::number(error, "pair_style tlsph/damage", key, arg[iarg + 2]);
      if (!(tip_jr1 >= 0.0 && tip_jr2 > tip_jr1 && tip_jr2 < 1.0e3))
        error->all(FLERR, "pair_style tlsph/damage: jring must be two radii in h with 0 <= r1 < "
                          "r2, got {} {}", arg[iarg + 1], arg[iarg + 2]);
      have_branch = true;
      iarg += 3;
    } else if (key == "tipseg") {
      if (iarg + 1 >= narg) error->all(FLERR, "pair_style tlsph/damage: tipseg needs a value");
      tip_seg = TLSPHInput::number(error, "pair_style tlsph/damage", key, arg[iarg + 1]);
      if (!(tip_seg >= 0.0))
        error->all(FLERR, "pair_style tlsph/damage: tipseg must be >= 0 (a length in h; 0: the "
                          "sampling reach), got {}", arg[iarg + 1]);
      have_branch = true;
      iarg += 2;
    } else if (key == "branch") {
      if (iarg + 1 >= narg)
        error->all(FLERR, "pair_style tlsph/damage: branch needs a value (half angle in degrees)");
      if (strcmp(arg[iarg + 1], "yoffe") == 0) {
        tip_branch = -1.0;
      } else {
        const double a = TLSPHInput::number(error, "pair_style tlsph/damage", key, arg[iarg + 1]);
        if (!(a >= 0.0 && a < 90.0))
          error->all(FLERR, "pair_style tlsph/damage: branch must be 'yoffe' or an angle in "
                            "[0, 90) degrees, got {}", arg[iarg + 1]);
        tip_branch = a * M_PI / 180.0;
      }
      have_branch = true;
      iarg += 2;
    } else if (key == "correction") {
      if (iarg + 1 >= narg) error->all(FLERR, "pair_style tlsph/damage: correction needs a value");
      if (strcmp(arg[iarg + 1], "rebuild") == 0) rebuild = 1;
      else if (strcmp(arg[iarg + 1], "setup") == 0) rebuild = 0;
      else
        error->all(FLERR, "pair_style tlsph/damage: correction must be 'rebuild' or 'setup', "
                          "got '{}'", arg[iarg + 1]);
      iarg += 2;
    } else if (key == "damping") {
      if (iarg + 1 >= narg) error->all(FLERR, "pair_style tlsph/damage: damping needs a value");
      if (strcmp(arg[iarg + 1], "step") == 0) damping_linear = 0;
      else if (strcmp(arg[iarg + 1], "linear") == 0) damping_linear = 1;
      else
        error->all(FLERR, "pair_style tlsph/damage: damping must be 'step' or 'linear', got '{}'",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (key == "family") {
      if (iarg + 1 >= narg)
        error->all(FLERR, "pair_style tlsph/damage: family needs a value (the radius of the bond "
                          "family, a length >= 2h)");
      family = TLSPHInput::number(error, "pair_style tlsph/damage", key, arg[iarg + 1]);
      if (!(family > 0.0))
        error->all(FLERR, "pair_style tlsph/damage: family must be > 0 (a length >= 2h), got {}",
                   arg[iarg + 1]);
      iarg += 2;
    } else if (key == "precrack") {
      const int nval = (d == 2) ? 4 : 9;
      // too few numbers, also when another keyword follows (it would
      // otherwise be read as a coordinate, with a message not naming precrack)
      bool enough = (iarg + nval < narg);
      for (int k = 1; enough && k <= nval; k++) enough = utils::is_double(arg[iarg + k]);
      if (!enough)
        error->all(FLERR, "pair_style tlsph/damage: precrack needs {} numbers in {}D ({})", nval,
                   d, d == 2 ? "x1 y1 x2 y2: a segment" : "three corners of a parallelogram");
      std::array<double, 9> c{};
      for (int k = 0; k < nval; k++)
        c[k] = TLSPHInput::number(error, "pair_style tlsph/damage", key, arg[iarg + 1 + k]);
      cracks.push_back(c);
      iarg += 1 + nval;
    } else {
      if (key == "gradient") have_gradient = true;
      base.push_back(arg[iarg]);
      if (iarg + 1 < narg) base.push_back(arg[iarg + 1]);
      iarg += 2;
    }
  }
  if (have_branch && !tipmode)
    error->all(FLERR, "pair_style tlsph/damage: branch, tipdir, tipseg, kfit and jring are "
                      "settings of 'criterion tip'");
  PairTLSPH::settings((int) base.size(), base.data());
  // the thesis's fracture model uses the linear correction: keep it the default
  if (!have_gradient) order = 1;
  alpha_d = have_alpha_d ? alpha_d_value : alpha;
  // the family reaches at least the kernel support: the force bonds are part of it
  if (family > 0.0 && family < 2.0 * h * (1.0 - 1.0e-12))
    error->all(FLERR, "pair_style tlsph/damage: family {} is shorter than the kernel support 2h = "
                      "{}: it must be >= 2h (the bonds that carry forces are part of the family)",
               family, 2.0 * h);
}

/* ---------------------------------------------------------------------- */

bool PairTLSPHDamage::material_key(int type, const std::string &key, double v,
                                   const std::string &where)
{
  if ((int) Gc.size() <= atom->ntypes) {
    Gc.assign(atom->ntypes + 1, 0.0);
    sc_given.assign(atom->ntypes + 1, 0.0);
    sc.assign(atom->ntypes + 1, 0.0);
  }
  if (key == "Gc") {
    if (v <= 0.0) error->all(FLERR, "{}: Gc must be > 0 (fracture energy), got {}", where, v);
    Gc[type] = v;
    sc_given[type] = 0.0;
    return true;
  }
  if (key == "sc") {
    if (v <= 0.0) error->all(FLERR, "{}: sc must be > 0 (critical stretch), got {}", where, v);
    sc_given[type] = v;
    Gc[type] = 0.0;
    return true;
  }
  return false;
}

void PairTLSPHDamage::check_material(int type, const std::string &where)
{
  if ((int) Gc.size() <= type || (Gc[type] <= 0.0 && sc_given[type] <= 0.0))
    error->all(FLERR, "{}: pair tlsph/damage needs a fracture value for every material: Gc "
                      "(fracture energy) or sc (critical stretch){}", where,
               mat[type].orthotropic ? "; an orthotropic ply needs sc" : "");
  // s_c from G_c (thesis Eq. 2.28) is derived for an isotropic solid (mu, K);
  // a ply's fracture energy depends on the direction, and no single pair of
  // effective moduli would be more than a guess: ask for s_c itself
  if (mat[type].orthotropic && Gc[type] > 0.0)
    error->all(FLERR, "{}: pair tlsph/damage: Gc cannot be used for an orthotropic material (the "
                      "critical stretch from Gc needs isotropic moduli): give its critical "
                      "stretch 'sc' instead", where);
}

void PairTLSPHDamage::write_material_extra(FILE *fp, int type)
{
  double v[2] = {Gc[type], sc_given[type]};
  fwrite(v, sizeof(double), 2, fp);
}

void PairTLSPHDamage::read_material_extra(FILE *fp, int type)
{
  double v[2];
  if (comm->me == 0) utils::sfread(FLERR, v, sizeof(double), 2, fp, nullptr, error);
  MPI_Bcast(v, 2, MPI_DOUBLE, 0, world);
  if ((int) Gc.size() <= atom->ntypes) {
    Gc.assign(atom->ntypes + 1, 0.0);
    sc_given.assign(atom->ntypes + 1, 0.0);
    sc.assign(atom->ntypes + 1, 0.0);
  }
  Gc[type] = v[0];
  sc_given[type] = v[1];
}

void PairTLSPHDamage::write_restart_settings(FILE *fp)
{
  PairTLSPH::write_restart_settings(fp);
  double v[6] = {alpha_d, (double) absolute, (double) rebuild, (double) cracks.size(), family,
                 (double) damping_linear};
  fwrite(v, sizeof(double), 6, fp);
  for (const auto &c : cracks) fwrite(c.data(), sizeof(double), 9, fp);
  // 'criterion tip': the settings, then every tip with its path (identical on all ranks)
  // tipdir and kfit share one value (files written before kfit read as kfit tip);
  // tipmode + 2 marks the layout with the J ring after these six (files
  // written before it have tipmode 0 or 1 there and the default ring)
  double w[6] = {(double) tipmode + 2.0, (double) (tip_hoop + 2 * tip_kfit), tip_seg, tip_branch,
                 (double) tips_ready,
                 (double) tips.size()};
  fwrite(w, sizeof(double), 6, fp);
  const double jr[2] = {tip_jr1, tip_jr2};
  fwrite(jr, sizeof(double), 2, fp);
  for (const auto &tp : tips) {
    std::vector<double> r = {(double) tp.path.size(), tp.t[0], tp.t[1], tp.seg, tp.own,
                             (double) tp.alive, (double) tp.growing};
    for (const auto &p : tp.path) r.insert(r.end(), {p[0], p[1]});
    fwrite(r.data(), sizeof(double), r.size(), fp);
  }
}

void PairTLSPHDamage::read_restart_settings(FILE *fp)
{
  PairTLSPH::read_restart_settings(fp);
  double v[6];
  if (comm->me == 0) utils::sfread(FLERR, v, sizeof(double), 6, fp, nullptr, error);
  MPI_Bcast(v, 6, MPI_DOUBLE, 0, world);
  // a file of another layout (e.g. before 'family' and 'damping' were
  // stored) reads numbers out of place: refuse it with a message
  const bool flag_ok = (v[1] == 0.0 || v[1] == 1.0) && (v[2] == 0.0 || v[2] == 1.0) &&
      (v[5] == 0.0 || v[5] == 1.0);
  if (!(flag_ok && v[0] >= 0.0 && v[3] >= 0.0 && v[3] == std::floor(v[3]) && v[3] < 1.0e6 &&
        v[4] >= 0.0 && std::isfinite(v[4])))
    error->all(FLERR, "pair tlsph/damage: the restart file's pair settings are not in this "
                      "version's layout (written by another version of the package?)");
  alpha_d = v[0];
  absolute = static_cast<int>(v[1]);
  rebuild = static_cast<int>(v[2]);
  family = v[4];
  damping_linear = static_cast<int>(v[5]);
  cracks.assign(static_cast<int>(v[3]), std::array<double, 9>{});
  for (auto &c : cracks) {
    if (comm->me == 0) utils::sfread(FLERR, c.data(), sizeof(double), 9, fp, nullptr, error);
    MPI_Bcast(c.data(), 9, MPI_DOUBLE, 0, world);
  }
  double w[6];
  if (comm->me == 0) utils::sfread(FLERR, w, sizeof(double), 6, fp, nullptr, error);
  MPI_Bcast(w, 6, MPI_DOUBLE, 0, world);
  const bool with_ring = (w[0] >= 2.0);
  if (with_ring) w[0] -= 2.0;
  if (!((w[0] == 0.0 || w[0] == 1.0) && (w[1] >= 0.0 && w[1] <= 5.0 && w[1] == std::floor(w[1])) &&
        w[2] >= 0.0 &&
        w[3] < 2.0 && (w[4] == 0.0 || w[4] == 1.0) && w[5] >= 0.0 && w[5] == std::floor(w[5]) &&
        w[5] < 1.0e7))
    error->all(FLERR, "pair tlsph/damage: the restart file's pair settings are not in this "
                      "version's layout (written by another version of the package?)");
  tipmode = static_cast<int>(w[0]);
  tip_hoop = static_cast<int>(w[1]) % 2;
  tip_kfit = static_cast<int>(w[1]) / 2;
  tip_jr1 = 2.0;
  tip_jr2 = 4.0;
  if (with_ring) {
    double jr[2];
    if (comm->me == 0) utils::sfread(FLERR, jr, sizeof(double), 2, fp, nullptr, error);
    MPI_Bcast(jr, 2, MPI_DOUBLE, 0, world);
    if (!(jr[0] >= 0.0 && jr[1] > jr[0] && jr[1] < 1.0e3))
      error->all(FLERR, "pair tlsph/damage: the restart file's pair settings are not in this "
                        "version's layout (written by another version of the package?)");
    tip_jr1 = jr[0];
    tip_jr2 = jr[1];
  }
  tip_seg = w[2];
  tip_branch = w[3];
  tips_ready = static_cast<int>(w[4]);
  tips.assign(static_cast<size_t>(w[5]), CrackTip{});
  for (auto &tp : tips) {
    double r[7];
    if (comm->me == 0) utils::sfread(FLERR, r, sizeof(double), 7, fp, nullptr, error);
    MPI_Bcast(r, 7, MPI_DOUBLE, 0, world);
    const int np = static_cast<int>(r[0]);
    tp.t[0] = r[1];
    tp.t[1] = r[2];
    tp.seg = r[3];
    tp.own = r[4];
    tp.alive = static_cast<int>(r[5]);
    tp.growing = static_cast<int>(r[6]);
    std::vector<double> q(2 * (size_t) np);
    if (comm->me == 0 && np > 0)
      utils::sfread(FLERR, q.data(), sizeof(double), q.size(), fp, nullptr, error);
    if (np > 0) MPI_Bcast(q.data(), (int) q.size(), MPI_DOUBLE, 0, world);
    tp.path.resize(np);
    for (int k = 0; k < np; k++) tp.path[k] = {q[2 * k], q[2 * k + 1]};
  }
}

/* ---------------------------------------------------------------------- */

void PairTLSPHDamage::init_style()
{
  correction_from_all_partners = !rebuild;
  PairTLSPH::init_style();
  // 'setup': each particle's correction is frozen once, after the pre-cracks
  bonds->set_frozen_size(rebuild ? 0 : correction_size());
  // the bond family: every partner within 'family' of the reference
  // position (default: the kernel support 2h). Bonds beyond 2h have W = 0
  // and a zero gradient: they carry no force and enter no kernel sum; they
  // only break (stretch criterion) and count in phi, as peridynamic bonds.
  const double radius = family_radius();
  bonds->set_cutoff(radius);
  // critical stretch per type (thesis Eq. 2.28 with its horizon h for a
  // family of radius 2h; a wider family keeps that ratio: horizon = radius/2;
  // K = lambda + 2 mu / 3)
  const double horizon = 0.5 * radius;
  for (int t = 1; t <= atom->ntypes; t++) {
    if (mat[t].rho <= 0.0) continue;
    if (sc_given[t] > 0.0) sc[t] = sc_given[t];
    else {
      // isotropic only: check_material refuses Gc for an orthotropic type
      const double K = mat[t].lambda + 2.0 * mat[t].mu / 3.0;
      sc[t] = critical_stretch(Gc[t], mat[t].mu, K, horizon, dim);
      if (!(std::isfinite(sc[t]) && sc[t] > 0.0))
        error->all(FLERR, "pair tlsph/damage: type {}: the critical stretch from Gc = {} (E = {}, "
                          "nu = {}, horizon h = {}) is {}: it must be finite and > 0 (give sc "
                          "instead, or values of usual magnitudes)", t, Gc[t], mat[t].E, mat[t].nu,
                   horizon, sc[t]);
    }
    if (comm->me == 0)
      utils::logmesg(lmp, "pair tlsph/damage: type {} critical stretch s_c = {:.6g}{}\n", t, sc[t],
                     sc_given[t] > 0.0 ? " (given)" : fmt::format(" (from Gc, horizon {:.6g})", horizon));
  }
  // squared stretch limits per type pair (the bond uses the smaller s_c)
  const int ntp = atom->ntypes + 1;
  stretch_up.assign(ntp * ntp, 0.0);
  stretch_down.assign(ntp * ntp, 0.0);
  for (int a = 1; a < ntp; a++)
    for (int b = 1; b < ntp; b++) {
      const double s_c = MIN(sc[a], sc[b]);
      stretch_up[a * ntp + b] = (1.0 + s_c) * (1.0 + s_c);
      stretch_down[a * ntp + b] = (s_c < 1.0) ? (1.0 - s_c) * (1.0 - s_c) : 0.0;
    }
  if (tipmode) {
    // only the tips cut bonds: no stretch limit is ever reached
    for (auto &u : stretch_up) u = 1.0e300;
    for (auto &w : stretch_down) w = 0.0;
    const Material &m = mat[1];
    if (m.orthotropic || Gc[1] <= 0.0)
      error->all(FLERR, "pair tlsph/damage: 'criterion tip' needs an isotropic type 1 with Gc");
    for (int t = 2; t <= atom->ntypes; t++)
      if (mat[t].rho > 0.0 && (mat[t].E != m.E || mat[t].nu != m.nu || mat[t].rho != m.rho))
        error->all(FLERR, "pair tlsph/damage: 'criterion tip' needs one material (all types alike)");
    // E' (plane stress E, plane strain E / (1 - nu^2)), G_c, and the Rayleigh
    // speed (Viktorov's approximation c_R = c_s (0.862 + 1.14 nu) / (1 + nu))
    tip_Eprime = plane_stress ? m.E : m.E / (1.0 - m.nu * m.nu);
    tip_Gc = Gc[1];
    tip_cR = sqrt(m.mu / m.rho) * (0.862 + 1.14 * m.nu) / (1.0 + m.nu);
    // kfit j: the velocity gradient of the J-integral reads the ghosts' velocities
    if (tip_kfit == 2) comm->ghost_velocity = 1;
  }
  comm_forward = MAX(comm_forward, 1);
  comm_reverse = MAX(comm_reverse, 1);
  nmax_d = 0;
}

// the neighbor list (and ghost cutoff) reaches the whole bond family
double PairTLSPHDamage::init_one(int i, int j)
{
  return MAX(PairTLSPH::init_one(i, j), family_radius() * cutfactor);
}

void PairTLSPHDamage::grow_damage()
{
  nmax_d = atom->nmax;
  memory->destroy(phi);
  memory->destroy(phis);
  memory->destroy(alphas);
  memory->destroy(phi_prev);
  memory->destroy(mark);
  memory->create(phi, nmax_d, "tlsph/damage:phi");
  memory->create(phis, nmax_d, "tlsph/damage:phis");
  memory->create(alphas, nmax_d, "tlsph/damage:alpha");
  memory->create(phi_prev, nmax_d, "tlsph/damage:phi_prev");
  memory->create(mark, nmax_d, "tlsph/damage:mark");
  alpha_atom = alphas;
  phis_valid = 0;
}

double PairTLSPHDamage::kernel_value(int i, int m) const
{
  double X[3];
  bond_vector(i, m, X);
  return kernel.value(sqrt(dot3(X, X)));
}

const double *PairTLSPHDamage::kernel_weights(int i)
{
  const int nlocal = atom->nlocal;
  // a new cache (or particles), or segments left behind by broken bonds
  // outgrowing the cache: start again
  if (wver != cache_version || (int) wofs.size() < nlocal || wbuf.size() > (size_t) ncache_max + 4096) {
    wver = cache_version;
    wofs.assign(nlocal, -1);
    wlen.assign(nlocal, -1);
    wbuf.clear();
  }
  const int n = nbond[i];
  if (wofs[i] < 0 || wlen[i] != n) {
    wofs[i] = (int) wbuf.size();
    wlen[i] = n;
    for (int m = 0; m < n; m++) wbuf.push_back(kernel_value(i, m));
  }
  return wbuf.data() + wofs[i];
}

/* ----------------------------------------------------------------------
   pre-cracks: a bond whose reference segment X_i -> X_j crosses a crack
   segment (2D) or parallelogram (3D) is broken before the first step
------------------------------------------------------------------------- */

/* does the reference bond segment A -> B cross the crack segment P -> R (2D)?
   Orientations within round-off of 0 count as 0 (tol: relative to
   |AB| |PR|): a bond through an end point of the segment is cut, one from a
   particle on the segment's line is not -- decided alike whatever the last
   bits of the coordinates (on a lattice, the bonds through a notch tip on a
   line between columns would otherwise be cut or kept by round-off) */
static bool segment_crossed(const double *A, const double *B, const double *P, const double *R)
{
  auto orient = [](const double *a, const double *b, const double *p) {
    return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
  };
  const double lab = std::hypot(B[0] - A[0], B[1] - A[1]);
  const double lpr = std::hypot(R[0] - P[0], R[1] - P[1]);
  const double tol = 1.0e-9 * lab * lpr;
  auto snap = [tol](double o) { return std::fabs(o) < tol ? 0.0 : o; };
  const double o1 = snap(orient(P, R, A)), o2 = snap(orient(P, R, B));
  const double o3 = snap(orient(A, B, P)), o4 = snap(orient(A, B, R));
  return o1 * o2 < 0.0 && o3 * o4 <= 0.0;
}

bool PairTLSPHDamage::crosses_crack(const double *A, const double *B) const
{
  for (const auto &c : cracks) {
    if (dim == 2) {
      const double P[2] = {c[0], c[1]}, R[2] = {c[2], c[3]};
      if (segment_crossed(A, B, P, R)) return true;
    } else {
      const double O[3] = {c[0], c[1], c[2]};
      const double U[3] = {c[3] - c[0], c[4] - c[1], c[5] - c[2]};
      const double W[3] = {c[6] - c[0], c[7] - c[1], c[8] - c[2]};
      const double N[3] = {U[1] * W[2] - U[2] * W[1], U[2] * W[0] - U[0] * W[2],
                           U[0] * W[1] - U[1] * W[0]};
      double dA = (A[0] - O[0]) * N[0] + (A[1] - O[1]) * N[1] + (A[2] - O[2]) * N[2];
      double dB = (B[0] - O[0]) * N[0] + (B[1] - O[1]) * N[1] + (B[2] - O[2]) * N[2];
      // as in 2D: distances and edge coordinates within round-off count as
      // on the plane / on the edge (a bond through an edge is cut)
      const double AB[3] = {B[0] - A[0], B[1] - A[1], B[2] - A[2]};
      const double tol = 1.0e-9 * std::sqrt(dot3(AB, AB) * dot3(N, N));
      if (std::fabs(dA) < tol) dA = 0.0;
      if (std::fabs(dB) < tol) dB = 0.0;
      if (!(dA * dB < 0.0)) continue;
      const double t = dA / (dA - dB);
      double Pp[3];
      for (int k = 0; k < 3; k++) Pp[k] = A[k] + t * (B[k] - A[k]) - O[k];
      // coordinates of the crossing point in the (U, W) frame
      const double uu = dot3(U, U), uw = dot3(U, W), ww = dot3(W, W);
      const double pu = dot3(Pp, U), pw = dot3(Pp, W);
      const double det = uu * ww - uw * uw;
      if (det == 0.0) continue;
      const double a = (pu * ww - pw * uw) / det, b = (pw * uu - pu * uw) / det;
      const double e = 1.0e-9;
      if (a >= -e && a <= 1.0 + e && b >= -e && b <= 1.0 + e) return true;
    }
  }
  return false;
}

void PairTLSPHDamage::apply_precracks()
{
  if (cracks.empty()) return;
  double **x0 = atom->x0;
  const int nlocal = atom->nlocal;
  bigint nmine = 0;
  for (int i = 0; i < nlocal; i++) {
    for (int k = 0; k < bonds->npartner[i]; k++) {
      if (bonds->state[i][k] != FixTLSPHBonds::INTACT) continue;
      int j = atom->map(bonds->partner[i][k]);
      if (j < 0) continue;
      j = domain->closest_image(i, j);
      double X[3] = {x0[j][0] - x0[i][0], x0[j][1] - x0[i][1], x0[j][2] - x0[i][2]};
      domain->minimum_image(X[0], X[1], X[2]);
      const double B[3] = {x0[i][0] + X[0], x0[i][1] + X[1], x0[i][2] + X[2]};
      if (crosses_crack(x0[i], B)) {
        // still counted in the initial bonds (thesis Algorithm 1, line 4, sets
        // lambda = 0 before the damage is defined): particles along a
        // pre-crack start damaged, so alpha_d and the filter act there
        bonds->state[i][k] = FixTLSPHBonds::PRECRACKED;
        nmine++;
      }
    }
  }
  bigint nall;
  MPI_Allreduce(&nmine, &nall, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (comm->me == 0)
    utils::logmesg(lmp, "pair tlsph/damage: {} pre-crack(s) removed {} bonds (counted from both "
                        "ends)\n", cracks.size(), nall);
}

// corrected gradients of particle i from its intact bonds (policy 'rebuild')
void PairTLSPHDamage::recorrect(int i)
{
  const int n = nbond[i];
  std::vector<BondCache> b;
  std::vector<double> vj;
  unpack_bonds(i, n, b, vj);
  correct_particle(i, b.data(), n, vj.data());
  const int s = bond_start[i];
  for (int m = 0; m < n; m++)
    for (int d = 0; d < dim; d++) lean.g[(bigint) dim * (s + m) + d] = b[m].g[d];
}

/* Pass (1) with the stretch criterion fused in: for each local particle,
   every intact bond whose stretch has reached s_c is broken before it would
   enter F_i, then F_i and the stress follow from the bonds left. Both ends
   of a bond compute the same stretch from the same positions (ghosts are
   current at this point), so both drop it. One pass over the bond cache
   instead of a breaking pass and a deformation pass. */
template <int DIM, int ORDER, int LAWS, int ABS, int PAIRS>
void PairTLSPHDamage::deform_and_break(const int *list, int nlist)
{
  double **x = atom->x;
  int *type = atom->type;
  const int nlocal = atom->nlocal;
  const double *up = stretch_up.data(), *down = stretch_down.data();
  const int ntp = atom->ntypes + 1;
  // PAIRS 0: one critical stretch for every pair of types (one limit)
  const double up0 = stretch_up[ntp + 1] * (1.0 - 1.0e-10);
  const double down0 = stretch_down[ntp + 1] * (1.0 + 1.0e-10);
  const bool need_K = viscosity_active();
  double **x0 = x0c;
  const int nloop = list ? nlist : nlocal;
  for (int ii = 0; ii < nloop; ii++) {
    const int i = list ? list[ii] : ii;
    const int s = bond_start[i];
    int *bj = lean.j + s;
    double *bg = lean.g + (bigint) DIM * s;
    int n = nbond[i];
    const int ti = type[i] * ntp;
    const double *xi = x[i], *x0i = x0[i];
    double *Fi = F[i];
    double Fa[DIM * DIM];
    for (int k = 0; k < DIM * DIM; k++) Fa[k] = 0.0;
    bool changed = false;
    for (int m = 0; m < n;) {
      const int j = bj[m];
      const double *xj = x[j], *x0j = x0[j];
      // the stretch criterion (tlsph_particle.h); PAIRS 0: one limit
      const int tj = type[j];
      const double lim_up = PAIRS ? up[ti + tj] * (1.0 - 1.0e-10) : up0;
      const double lim_down = ABS ? (PAIRS ? down[ti + tj] * (1.0 + 1.0e-10) : down0) : 0.0;
      double du[3];
      if (TLSPH::bond_breaks<DIM, ABS>(xi, xj, x0i, x0j, lim_up, lim_down,
                                       MIN(sc[type[i]], sc[tj]), du)) {
        bonds->state[i][lean.k[s + m]] = FixTLSPHBonds::BROKEN;
        nbroken_local++;
        // move the bond behind the intact ones (it stays in the segment:
        // the 'setup' policy keeps it in the correction); the bond moved
        // into slot m is examined next
        if (!rebuild)
          for (int d = 0; d < DIM; d++) sumg[i][d] -= bg[DIM * m + d];
        // keep the leading bonds first (pair_tlsph.h: nlead)
        TLSPH::drop_bond<DIM>(bj, bg, lean.w + 2 * (bigint) s, lean.k + s, m, nlead[i], n);
        changed = true;
        continue;
      }
      const double *g = bg + DIM * m;
      for (int r = 0; r < DIM; r++)
        for (int cc = 0; cc < DIM; cc++) Fa[DIM * r + cc] += du[r] * g[cc];
      m++;
    }
    mat_identity(Fi);
    for (int r = 0; r < DIM; r++)
      for (int cc = 0; cc < DIM; cc++) Fi[3 * r + cc] += Fa[DIM * r + cc];
    if (changed) {
      nbond[i] = n;
      ell_mark(i);
      if (rebuild) {
        // the corrected gradients changed: F again from the rebuilt ones
        recorrect(i);
        const struct {
          double **p;
          const double *operator()(int k) const { return p[k]; }
        } rows{x};
        TLSPH::deformation_gradient_bonds<DIM>(rows, i, bonds_of<DIM>(i), n, Fi);
      }
    }
    particle_stress<DIM, ORDER, LAWS>(i, need_K);
  }
}

template <int DIM, int ORDER, int LAWS>
void PairTLSPHDamage::dispatch_break(const int *list, int nlist)
{
  // one limit for all type pairs unless the types' critical stretches differ
  bool pairs = false;
  for (int t = 2; t <= atom->ntypes; t++) pairs = pairs || (sc[t] != sc[1]);
  if (absolute) {
    if (pairs) deform_and_break<DIM, ORDER, LAWS, 1, 1>(list, nlist);
    else deform_and_break<DIM, ORDER, LAWS, 1, 0>(list, nlist);
  } else {
    if (pairs) deform_and_break<DIM, ORDER, LAWS, 0, 1>(list, nlist);
    else deform_and_break<DIM, ORDER, LAWS, 0, 0>(list, nlist);
  }
}

// pass (1) fused with the stretch criterion for the particles of list (all
// local particles when list is null)
void PairTLSPHDamage::deform_and_break_pass(const int *list, int nlist)
{
  if (dim == 2) {
    if (order == 1) {
      if (any_orthotropic) dispatch_break<2, 1, 1>(list, nlist);
      else dispatch_break<2, 1, 0>(list, nlist);
    } else {
      if (any_orthotropic) dispatch_break<2, 2, 1>(list, nlist);
      else dispatch_break<2, 2, 0>(list, nlist);
    }
  } else {
    if (order == 1) {
      if (any_orthotropic) dispatch_break<3, 1, 1>(list, nlist);
      else dispatch_break<3, 1, 0>(list, nlist);
    } else {
      if (any_orthotropic) dispatch_break<3, 2, 1>(list, nlist);
      else dispatch_break<3, 2, 0>(list, nlist);
    }
  }
}

void PairTLSPHDamage::deformation_pass()
{
  deform_and_break_pass(nullptr, 0);
}

/* The SIMD step's pass (1) screens every bond against the stretch limits
   loosened by SIMD_SCREEN_MARGIN (the screen must never miss a bond that
   the exact test breaks; its vector sums differ from bond_breaks' by
   round-off, ~1e-16 relative): the lowest upper and the highest lower limit
   of all type pairs; lower -1 (never) without 'criterion absolute'. A
   family beyond the kernel support (2h) has bonds whose weights are zero
   there: the screen then takes every slot within the family's reach. */
bool PairTLSPHDamage::simd_screen(double &up, double &down, double &reach2) const
{
  // 'criterion tip': only the tips cut bonds, no stretch limit is ever
  // reached (init_style): pass (1) is tlsph's, without the screen
  if (tipmode) return false;
  constexpr double SIMD_SCREEN_MARGIN = 1.0e-8;
  const int ntp = atom->ntypes + 1;
  up = 1.0e300;
  down = -1.0;
  for (int a = 1; a < ntp; a++)
    for (int b = 1; b < ntp; b++) {
      up = MIN(up, stretch_up[a * ntp + b]);
      if (absolute) down = MAX(down, stretch_down[a * ntp + b]);
    }
  up *= 1.0 - SIMD_SCREEN_MARGIN;
  if (absolute) down *= 1.0 + SIMD_SCREEN_MARGIN;
  const double R = family_radius();
  reach2 = (R > 2.0 * h) ? R * R * (1.0 + SIMD_SCREEN_MARGIN) : 0.0;
  return true;
}

/* the particles the screen flagged: pass (1) again, the scalar one with the
   exact test (bonds break, F, the stress and the packed row from the bonds
   left), then their columns from their rows */
void PairTLSPHDamage::simd_breaks(const int *list, int n)
{
  deform_and_break_pass(list, n);
  for (int q = 0; q < n; q++) ell_row_to_columns(list[q]);
}

/* ----------------------------------------------------------------------
   every step, before the deformation pass: the pre-cracks once
------------------------------------------------------------------------- */

void PairTLSPHDamage::update_bonds()
{
  if (atom->nmax > nmax_d) grow_damage();
  if (bonds->fresh) {
    bonds->fresh = 0;
    apply_precracks();
    // the corrections frozen so far still contained the pre-cracked bonds
    if (bonds->nfrozen)
      for (int i = 0; i < atom->nlocal; i++) bonds->frozen[i][0] = 0.0;
    build_bond_cache();
  }
  if (tipmode) grow_tips();
}

/* ----------------------------------------------------------------------
   after the deformation pass (this step's bonds are decided): damage, the
   smoothed damage and the viscosity coefficient of every local particle,
   which then goes into its packed row
------------------------------------------------------------------------- */

void PairTLSPHDamage::after_deformation()
{
  const int nlocal = atom->nlocal;

  // damage phi = 1 - intact/initial (thesis Eq. 2.33), then its smoothed
  // form phi' (Eq. 2.34) over the intact bonds: a broken partner "no longer
  // contributes to the kernel interpolation of any field variable on i"
  // (thesis 2.3.1.1). Not over the cached segment: which broken bonds it
  // holds depends on the policy, on when the cache was last rebuilt (at
  // every reneighboring, 'rebuild' drops them) and, for 'setup', on whether
  // the broken partner is still a ghost -- phi', alpha_i and the trajectory
  // would change with the neighbor skin, a run split or a restart.
  //
  // phi' and alpha_i of a particle depend only on its intact bonds and its
  // partners' damage. Between two rebuilds of the bond cache (the particle
  // indices are those of the last neighbor build) bonds only break, and a
  // broken bond changes the damage of both ends. So a step where no rank's
  // phi changed (one reduction) leaves phi' and alpha_i as they are; else
  // the particles whose phi changed flag themselves and their intact
  // partners (ghosts' flags go to their owners by the reverse
  // communication), and only the flagged ones are evaluated again; after a
  // rebuild of the cache or at the start of a run, all of them. The same
  // operations on the same values as evaluating every particle every step:
  // the same bits. A crack that stands still costs no kernel evaluations.
  const std::array<int, 3> stamp = {cache_version, nlocal, atom->nghost};
  const bool full = !phis_valid || stamp != phis_stamp;
  int lchg = full ? 1 : 0;
  for (int i = 0; i < nlocal; i++) {
    const int n0 = bonds->nintact0[i];
    phi[i] = (n0 > 0) ? 1.0 - (double) nbond[i] / n0 : 0.0;
    if (phi[i] < 0.0) phi[i] = 0.0;
    if (phi[i] != phi_prev[i]) lchg = 1;
  }
  int gchg = lchg;
  if (comm->nprocs > 1) MPI_Allreduce(&lchg, &gchg, 1, MPI_INT, MPI_MAX, world);
  const int ia = 2 * dim * dim;    // alpha_i in the packed row (TLSPH::Packed::A)
  if (!gchg) {
    for (int i = 0; i < nlocal; i++) pk[i][ia] = alphas[i];
    return;
  }
  phis_valid = 1;
  phis_stamp = stamp;
  comm_stage = 1;
  comm->forward_comm_pair(this);
  comm_stage = 0;

  // the flags (in mark): a particle whose phi changed, and its intact partners
  double *dirty = mark;
  const int nall = nlocal + atom->nghost;
  if (!full) {
    for (int i = 0; i < nall; i++) dirty[i] = 0.0;
    for (int i = 0; i < nlocal; i++) {
      if (phi[i] == phi_prev[i]) continue;
      dirty[i] = 1.0;
      const int *bj = lean.j + bond_start[i];
      for (int m = 0; m < nbond[i]; m++) dirty[bj[m]] = 1.0;
    }
    comm_stage = 2;
    comm->reverse_comm_pair(this);
    comm_stage = 0;
  }

  for (int i = 0; i < nlocal; i++) {
    if (full || dirty[i] > 0.0) {
      const int *bj = lean.j + bond_start[i];
      const int n = nbond[i];
      // phi'_i > 0 exactly when an intact partner of i is damaged
      bool damaged_partner = false;
      for (int m = 0; m < n && !damaged_partner; m++) damaged_partner = phi[bj[m]] > 0.0;
      if (n == 0) {
        phis[i] = phi[i];    // a free particle: its own damage (1 once it had bonds)
      } else if (!damaged_partner) {
        phis[i] = 0.0;    // no damaged intact partner
      } else {
        double num = 0.0, den = 0.0;
        const double *W = kernel_weights(i);
        for (int m = 0; m < n; m++) {
          const double w = W[m];
          num += phi[bj[m]] * w;
          den += w;
        }
        // phi_i - sum_j (phi_i - phi_j) W_ij / sum_j W_ij, written as the
        // W-weighted mean of the partners' damage: the difference form leaves
        // +-1e-17 where it should be 0, and that would switch alpha_d on
        phis[i] = (den > 0.0) ? num / den : 0.0;
      }
      // adaptive viscosity (thesis Eq. 2.35: alpha_d wherever phi' > 0; or
      // 'damping linear': growing with phi' from alpha to alpha_d)
      alphas[i] = damaged_alpha(phis[i], alpha, alpha_d, damping_linear);
    }
    pk[i][ia] = alphas[i];
    phi_prev[i] = phi[i];
  }
}

int PairTLSPHDamage::pack_reverse_comm(int n, int first, double *buf)
{
  for (int i = 0; i < n; i++) buf[i] = mark[first + i];
  return n;
}

void PairTLSPHDamage::unpack_reverse_comm(int n, int *list, double *buf)
{
  for (int i = 0; i < n; i++) mark[list[i]] += buf[i];
}

int PairTLSPHDamage::pack_forward_comm(int n, int *list, double *buf, int pbc_flag, int *pbc)
{
  if (comm_stage == 0) return PairTLSPH::pack_forward_comm(n, list, buf, pbc_flag, pbc);
  for (int i = 0; i < n; i++) buf[i] = phi[list[i]];
  return n;
}

void PairTLSPHDamage::unpack_forward_comm(int n, int first, double *buf)
{
  if (comm_stage == 0) {
    PairTLSPH::unpack_forward_comm(n, first, buf);
    return;
  }
  for (int i = 0; i < n; i++) phi[first + i] = buf[i];
}

double PairTLSPHDamage::memory_usage()
{
  return PairTLSPH::memory_usage() + 5.0 * nmax_d * sizeof(double);
}

/* ----------------------------------------------------------------------
   'criterion tip': crack-tip tracking (2D, and through-thickness cracks in 3D)
------------------------------------------------------------------------- */

// the volume of the particles within radius R of each point (all ranks)
void PairTLSPHDamage::refresh_tip_cells()
{
  RefCells &rc = tip_cells;
  const int nlocal = atom->nlocal;
  const std::array<int, 2> stamp = {cache_version, nlocal};
  if (stamp == rc.stamp) return;
  rc.stamp = stamp;
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (int i = 0; i < nlocal; i++)
    for (int d = 0; d < 2; d++) lo[d] = MIN(lo[d], x0c[i][d]), hi[d] = MAX(hi[d], x0c[i][d]);
  if (nlocal == 0) lo[0] = lo[1] = hi[0] = hi[1] = 0.0;
  // cells of side h, larger where that would give more cells than 4 per particle
  double cs = h;
  const double ncell_max = 4.0 * nlocal + 1024.0;
  while (((hi[0] - lo[0]) / cs + 1.0) * ((hi[1] - lo[1]) / cs + 1.0) > ncell_max) cs *= 2.0;
  rc.lo[0] = lo[0], rc.lo[1] = lo[1], rc.cs = cs;
  rc.nx = (int) ((hi[0] - lo[0]) / cs) + 1;
  rc.ny = (int) ((hi[1] - lo[1]) / cs) + 1;
  const int nc = rc.nx * rc.ny;
  std::vector<int> cell(nlocal);
  rc.start.assign(nc + 1, 0);
  for (int i = 0; i < nlocal; i++) {
    const int cx = MIN(rc.nx - 1, (int) ((x0c[i][0] - lo[0]) / cs));
    const int cy = MIN(rc.ny - 1, (int) ((x0c[i][1] - lo[1]) / cs));
    cell[i] = cx + rc.nx * cy;
    rc.start[cell[i] + 1]++;
  }
  for (int c = 0; c < nc; c++) rc.start[c + 1] += rc.start[c];
  rc.idx.resize(nlocal);
  std::vector<int> fill(rc.start.begin(), rc.start.end() - 1);
  for (int i = 0; i < nlocal; i++) rc.idx[fill[cell[i]]++] = i;
}

void PairTLSPHDamage::particles_in_box(const double *lo, const double *hi, std::vector<int> &out) const
{
  const RefCells &rc = tip_cells;
  out.clear();
  out.reserve(64);
  if (rc.nx == 0 || !(lo[0] <= hi[0]) || !(lo[1] <= hi[1])) return;
  auto cell_of = [&](double v, int d, int n) {
    const double f = floor((v - rc.lo[d]) / rc.cs);
    return (int) MAX(0.0, MIN((double) (n - 1), f));
  };
  const int x0 = cell_of(lo[0], 0, rc.nx), x1 = cell_of(hi[0], 0, rc.nx);
  const int y0 = cell_of(lo[1], 1, rc.ny), y1 = cell_of(hi[1], 1, rc.ny);
  for (int cy = y0; cy <= y1; cy++)
    for (int cx = x0; cx <= x1; cx++) {
      const int c = cx + rc.nx * cy;
      for (int k = rc.start[c]; k < rc.start[c + 1]; k++) {
        const int i = rc.idx[k];
        const double *X = x0c[i];
        if (X[0] >= lo[0] && X[0] <= hi[0] && X[1] >= lo[1] && X[1] <= hi[1]) out.push_back(i);
      }
    }
  std::sort(out.begin(), out.end());
}

// the volume of the local particles within R of each point (xy), all ranks
void PairTLSPHDamage::volume_near(const std::vector<std::array<double, 2>> &pts, double R,
                                  std::vector<double> &vol)
{
  refresh_tip_cells();
  const double *vfrac = atom->vfrac;
  std::vector<double> mine(pts.size(), 0.0);
  std::vector<int> near;
  for (size_t p = 0; p < pts.size(); p++) {
    const double lo[2] = {pts[p][0] - R, pts[p][1] - R}, hi[2] = {pts[p][0] + R, pts[p][1] + R};
    particles_in_box(lo, hi, near);
    for (int i : near) {
      const double dx = x0c[i][0] - pts[p][0], dy = x0c[i][1] - pts[p][1];
      if (dx * dx + dy * dy < R * R) mine[p] += vfrac[i];
    }
  }
  vol.assign(pts.size(), 0.0);
  MPI_Allreduce(mine.data(), vol.data(), (int) pts.size(), MPI_DOUBLE, MPI_SUM, world);
}

// a pre-crack end is a tip when the body fills at least 3/4 of the disc of
// radius 2h about it (an end outside the plate, or at its edge, is not)
void PairTLSPHDamage::init_tips()
{
  tips_ready = 1;
  tips.clear();
  std::vector<std::array<double, 2>> ends;
  for (const auto &c : cracks) {
    if (dim == 2) {
      ends.push_back({c[0], c[1]});
      ends.push_back({c[2], c[3]});
    } else {
      // 3D: through-thickness cracks only, a parallelogram with one edge
      // along z; its trace in the xy plane is tracked (the crack surface is
      // that trace extruded through the thickness)
      const bool wz = (c[6] == c[0] && c[7] == c[1]), uz = (c[3] == c[0] && c[4] == c[1]);
      if (!wz && !uz)
        error->all(FLERR, "pair tlsph/damage: 'criterion tip' in 3D needs pre-cracks through "
                          "the thickness (a parallelogram with one edge along z)");
      ends.push_back({c[0], c[1]});
      if (wz) ends.push_back({c[3], c[4]});
      else ends.push_back({c[6], c[7]});
    }
  }
  // the depth of the body along z (2D: the thickness in the particle volumes)
  tip_depth = thickness;
  if (dim == 3) {
    double lo = 1.0e300, hi = -1.0e300, vmax = 0.0, g[3];
    for (int i = 0; i < atom->nlocal; i++) {
      lo = MIN(lo, x0c[i][2]);
      hi = MAX(hi, x0c[i][2]);
      vmax = MAX(vmax, atom->vfrac[i]);
    }
    double m[3] = {-lo, hi, vmax};
    MPI_Allreduce(m, g, 3, MPI_DOUBLE, MPI_MAX, world);
    tip_depth = g[1] + g[0] + cbrt(g[2]);
  }
  std::vector<double> vol;
  volume_near(ends, 2.0 * h, vol);
  const double full = M_PI * 4.0 * h * h * tip_depth;
  for (size_t e = 0; e < ends.size(); e++) {
    if (vol[e] < 0.75 * full) continue;
    const auto &E = ends[e], &O = ends[e ^ 1];
    CrackTip tp;
    tp.path = {O, E};
    const double L = std::hypot(E[0] - O[0], E[1] - O[1]);
    tp.t[0] = (E[0] - O[0]) / L;
    tp.t[1] = (E[1] - O[1]) / L;
    tp.seg = tp.own = 0.0;
    tp.alive = 1;
    tp.growing = 0;
    tips.push_back(tp);
    if (comm->me == 0)
      utils::logmesg(lmp, "pair tlsph/damage: crack tip at ({:.6g}, {:.6g}), direction ({:.4f}, "
                          "{:.4f}); E' {:.6g} G_c {:.6g} c_R {:.6g}\n", E[0], E[1], tp.t[0], tp.t[1],
                     tip_Eprime, tip_Gc, tip_cR);
  }
}

// cut every intact bond of a local particle whose reference segment crosses A -> B
void PairTLSPHDamage::cut_path(const double *A, const double *B)
{
  const double len = std::hypot(B[0] - A[0], B[1] - A[1]);
  const double reach = family_radius() + len;
  const double lo[2] = {MIN(A[0], B[0]) - reach, MIN(A[1], B[1]) - reach};
  const double hi[2] = {MAX(A[0], B[0]) + reach, MAX(A[1], B[1]) + reach};
  // a bond whose bounding box misses the path's, grown by half its length,
  // is not crossed: segment_crossed counts an end within its tolerance of
  // the other segment's line as on it, which can put the crossing of two
  // nearly parallel lines up to half the path's length beyond its ends,
  // never further (so the test below drops only bonds it would not cut)
  const double pad = 0.5 * len + 1.0e-6 * reach;
  const double plo[2] = {MIN(A[0], B[0]) - pad, MIN(A[1], B[1]) - pad};
  const double phi_[2] = {MAX(A[0], B[0]) + pad, MAX(A[1], B[1]) + pad};
  refresh_tip_cells();
  std::vector<int> near;
  particles_in_box(lo, hi, near);
  for (int i : near) {
    const double *Xi = x0c[i];
    const int s = bond_start[i];
    int *bj = lean.j + s;
    double *bg = lean.g + (bigint) dim * s;
    int n = nbond[i];
    bool changed = false;
    for (int m = 0; m < n;) {
      const double *Xj = x0c[bj[m]];
      const bool apart = MAX(Xi[0], Xj[0]) < plo[0] || MIN(Xi[0], Xj[0]) > phi_[0] ||
          MAX(Xi[1], Xj[1]) < plo[1] || MIN(Xi[1], Xj[1]) > phi_[1];
      if (apart || !segment_crossed(Xi, Xj, A, B)) {
        m++;
        continue;
      }
      bonds->state[i][lean.k[s + m]] = FixTLSPHBonds::BROKEN;
      nbroken_local++;
      if (!rebuild)
        for (int d = 0; d < dim; d++) sumg[i][d] -= bg[dim * m + d];
      if (dim == 2) TLSPH::drop_bond<2>(bj, bg, lean.w + 2 * (bigint) s, lean.k + s, m, nlead[i], n);
      else TLSPH::drop_bond<3>(bj, bg, lean.w + 2 * (bigint) s, lean.k + s, m, nlead[i], n);
      changed = true;
    }
    if (changed) {
      nbond[i] = n;
      ell_mark(i);
      if (rebuild) recorrect(i);
    }
  }
}

/* kfit j: the domain J-integral (tlsph_crack.h, j_integrand) of each tip in
   'live', over the particles whose reference position lies within
   tip_jr2 h of the tip (a cylinder through the thickness in 3D), per unit
   depth, all ranks. Each particle's F and velocity gradient come from its
   intact bonds and the positions and velocities now (the F of the last
   deformation pass is a step old and, at a neighbor build, another atom's),
   P and W from its law; its acceleration is the change of its velocity since
   the last step (none for a particle not visited then). The sums run over
   the particles in ascending order. */
void PairTLSPHDamage::tip_j_integrals(const std::vector<int> &live, std::vector<double> &J)
{
  const int nt = live.size();
  std::vector<double> mine(nt, 0.0);
  J.assign(nt, 0.0);
  double **x = atom->x, **v = atom->v;
  const double *vfrac = atom->vfrac, *rmass = atom->rmass;
  const tagint *tag = atom->tag;
  const bigint step = update->ntimestep;
  const double dt = update->dt;
  const double r1 = tip_jr1 * h, r2 = tip_jr2 * h;
  if ((int) jprev.size() < atom->nmax) jprev.resize(atom->nmax, JPrev{{0.0, 0.0, 0.0}, -1, -1});
  const auto xr = TLSPH::StridedRows{x[0], 3};
  std::vector<int> near, seen;
  for (int a = 0; a < nt; a++) {
    const CrackTip &tp = tips[live[a]];
    const auto &T = tp.path.back();
    const double e[3] = {tp.t[0], tp.t[1], 0.0};
    const double lo[2] = {T[0] - r2, T[1] - r2}, hi[2] = {T[0] + r2, T[1] + r2};
    particles_in_box(lo, hi, near);
    for (int i : near) {
      const double ex = x0c[i][0] - T[0], ey = x0c[i][1] - T[1];
      const double r = std::sqrt(ex * ex + ey * ey);
      if (r >= r2) continue;
      seen.push_back(i);
      double dq;
      const double q = TLSPH::ring_weight(r, r1, r2, &dq);
      const double gq[3] = {r > 0.0 ? dq * ex / r : 0.0, r > 0.0 ? dq * ey / r : 0.0, 0.0};
      double F[9], P[9], L[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
      const int nb = nbond[i];
      const int *pj;
      const double *pg;
      if (dim == 2) {
        const auto b = bonds_of<2>(i);
        TLSPH::deformation_gradient_bonds<2>(xr, i, b, nb, F);
        pj = b.j, pg = b.g;
      } else {
        const auto b = bonds_of<3>(i);
        TLSPH::deformation_gradient_bonds<3>(xr, i, b, nb, F);
        pj = b.j, pg = b.g;
      }
      for (int m = 0; m < nb; m++) {
        const double *vj = v[pj[m]], *g = pg + dim * m;
        for (int rr = 0; rr < 3; rr++)
          for (int c = 0; c < dim; c++) L[3 * rr + c] += (vj[rr] - v[i][rr]) * g[c];
      }
      const double W = pk1_stress(i, F, P);
      const double rho0 = rmass[i] / vfrac[i];
      double acc[3] = {0.0, 0.0, 0.0};
      const JPrev &pv = jprev[i];
      if (q != 0.0 && pv.tag == tag[i] && pv.step == step - 1 && dt > 0.0)
        for (int d = 0; d < 3; d++) acc[d] = (v[i][d] - pv.v[d]) / dt;
      mine[a] += vfrac[i] * TLSPH::j_integrand(F, P, W, rho0, v[i], acc, L, e, gq, q);
    }
  }
  // this step's velocities, for the next step's accelerations
  for (int i : seen) {
    JPrev &pv = jprev[i];
    for (int d = 0; d < 3; d++) pv.v[d] = v[i][d];
    pv.tag = tag[i];
    pv.step = step;
  }
  MPI_Allreduce(mine.data(), J.data(), nt, MPI_DOUBLE, MPI_SUM, world);
  for (double &j : J) j /= tip_depth;
}

/* Each step, for every live tip: the stress intensity factors from the
   displacement jump across the faces behind it (displacement correlation:
   du = 8 K sqrt(r / 2 pi) / E', sampled at r = 2h .. 5h along its path and
   extrapolated to r = 0), the maximum tangential stress direction and
   equivalent K (Erdogan & Sih), and, once G = K_eq^2 / E' reaches G_c, an
   advance at v = c_R (1 - G_c / G) (Freund's equation of motion). The
   direction is chosen at the start of a segment of length h and kept along
   it. With 'branch A' a tip whose G reaches 2 G_c (the flux that can feed
   two cracks) splits into two at +-A once it has grown 6h on its own. */
void PairTLSPHDamage::grow_tips()
{
  if (!tips_ready) init_tips();
  const int nt = tips.size();
  if (!nt) return;
  constexpr int NK = 4;
  const double rho = 1.5 * h;
  double rk[NK];
  for (int k = 0; k < NK; k++) rk[k] = (1.5 + 0.5 * k) * h;
  // a segment keeps its direction until the samples lie on it
  const double seglen = tip_seg > 0.0 ? tip_seg * h : rk[NK - 1] + rho;
  // sample points and the face normal there, walking back along each path
  std::vector<double> Q(nt * NK * 2), T(nt * NK * 2);
  std::vector<int> ok(nt * NK, 0);
  for (int a = 0; a < nt; a++) {
    const CrackTip &tp = tips[a];
    if (!tp.alive) continue;
    for (int k = 0; k < NK; k++) {
      double left = rk[k];
      for (int v = (int) tp.path.size() - 1; v > 0; v--) {
        const auto &p1 = tp.path[v], &p0 = tp.path[v - 1];
        const double L = std::hypot(p1[0] - p0[0], p1[1] - p0[1]);
        if (L <= 0.0) continue;
        if (L >= left) {
          const double tx = (p1[0] - p0[0]) / L, ty = (p1[1] - p0[1]) / L;
          Q[2 * (a * NK + k)] = p1[0] - left * tx;
          Q[2 * (a * NK + k) + 1] = p1[1] - left * ty;
          T[2 * (a * NK + k)] = tx;
          T[2 * (a * NK + k) + 1] = ty;
          ok[a * NK + k] = 1;
          break;
        }
        left -= L;
      }
    }
  }
  // kernel-weighted mean displacement on each side (6 sums per sample)
  std::vector<double> mine(nt * NK * 6, 0.0), sums(nt * NK * 6, 0.0);
  double **x = atom->x;
  // Each sample visits the particles of the reference cells within rho of
  // it (refresh_tip_cells), not every particle: the work grows with the
  // number of samples, not with the body. Its sums run over the particles in
  // ascending order, as a sweep over all of them would.
  refresh_tip_cells();
  std::vector<int> near;
  for (int a = 0; a < nt; a++) {
    // one query for the samples of a tip: the box around all of them
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int k = 0; k < NK; k++) {
      const int q = a * NK + k;
      if (!ok[q]) continue;
      for (int d = 0; d < 2; d++) lo[d] = MIN(lo[d], Q[2 * q + d] - rho), hi[d] = MAX(hi[d], Q[2 * q + d] + rho);
    }
    particles_in_box(lo, hi, near);
    for (int k = 0; k < NK; k++) {
      const int q = a * NK + k;
      if (!ok[q]) continue;
      for (int i : near) {
        const double *X = x0c[i];
        const double dx = X[0] - Q[2 * q], dy = X[1] - Q[2 * q + 1];
        const double r2 = dx * dx + dy * dy;
        if (r2 >= rho * rho) continue;
        const double w = (1.0 - r2 / (rho * rho)) * (1.0 - r2 / (rho * rho));
        // + side: to the left of the path (n = t rotated by +90 deg)
        const double dn = -T[2 * q + 1] * dx + T[2 * q] * dy;
        if (dn == 0.0) continue;
        double *S = mine.data() + 6 * q + (dn > 0.0 ? 0 : 3);
        S[0] += w;
        S[1] += w * (x[i][0] - X[0]);
        S[2] += w * (x[i][1] - X[1]);
      }
    }
  }
  MPI_Allreduce(mine.data(), sums.data(), nt * NK * 6, MPI_DOUBLE, MPI_SUM, world);
  // kfit j: the energy release rate of each live tip (the domain J-integral)
  std::vector<double> Jt(nt, 0.0);
  if (tip_kfit == 2) {
    std::vector<int> live;
    for (int a = 0; a < nt; a++)
      if (tips[a].alive) live.push_back(a);
    std::vector<double> Jl;
    tip_j_integrals(live, Jl);
    for (size_t k = 0; k < live.size(); k++) Jt[live[k]] = Jl[k];
  }

  const double dt = update->dt;
  // per tip: G of the maximum tangential stress direction, and the direction
  // a new segment would take (nd)
  std::vector<double> Gt(nt, 0.0), nd(2 * nt, 0.0), Kt(2 * nt, 0.0), tht(nt, 0.0);
  std::vector<int> want;    // tips that start a new segment this step
  for (int a = 0; a < nt; a++) {
    CrackTip &tp = tips[a];
    if (!tp.alive) continue;
    // the faces' jump at the samples, normal and tangential to the faces
    double rr[NK], jn[NK], jt[NK];
    double fr[2] = {0.0, 0.0};    // the faces' mean direction: the frame of K_I, K_II
    int cnt = 0;
    for (int k = 0; k < NK; k++) {
      const int q = a * NK + k;
      const double *S = sums.data() + 6 * q;
      if (!ok[q] || !(S[0] > 0.0) || !(S[3] > 0.0)) continue;
      const double dux = S[1] / S[0] - S[4] / S[3], duy = S[2] / S[0] - S[5] / S[3];
      const double tx = T[2 * q], ty = T[2 * q + 1];
      fr[0] += tx;
      fr[1] += ty;
      rr[cnt] = rk[k];
      jn[cnt] = -ty * dux + tx * duy;
      jt[cnt] = tx * dux + ty * duy;
      cnt++;
    }
    if (cnt == 0) continue;
    // K_I, K_II (displacement correlation), the kink angle and the
    // equivalent K of the maximum tangential stress (tlsph_crack.h)
    // (kfit j: their size from J, their ratio from the correlation)
    const TLSPH::CrackK K = tip_kfit == 1
        ? TLSPH::displacement_correlation_offset(cnt, rr, jn, jt, tip_Eprime)
        : tip_kfit == 2
        ? TLSPH::k_from_j(Jt[a], TLSPH::displacement_correlation(cnt, rr, jn, jt, tip_Eprime), tip_Eprime)
        : TLSPH::displacement_correlation(cnt, rr, jn, jt, tip_Eprime);
    const double KI = K.KI, KII = K.KII;
    const double th = TLSPH::mts_kink_angle(KI, KII);
    const double Keq = TLSPH::mts_equivalent_K(KI, KII, th);
    Gt[a] = (Keq > 0.0) ? Keq * Keq / tip_Eprime : 0.0;
    Kt[2 * a] = KI;
    Kt[2 * a + 1] = KII;
    tht[a] = th;
    tp.KI = KI, tp.KII = KII, tp.G = Gt[a], tp.kink = th;
    tp.speed = 0.0;
    if (Gt[a] < tip_Gc || tp.seg != 0.0) continue;
    // a new segment: the kink angle turns the direction of the faces that
    // K was measured on (not the last segment's, which may already have turned)
    const double fl = std::hypot(fr[0], fr[1]);
    const double c = cos(th), sn = sin(th), f0 = fr[0] / fl, f1 = fr[1] / fl;
    nd[2 * a] = c * f0 - sn * f1;
    nd[2 * a + 1] = sn * f0 + c * f1;
    want.push_back(a);
  }

  // 'tipdir hoop': the new direction where the hoop stress on the circle of
  // radius 2h about the tip is largest (within +-80 deg of the current
  // direction; stresses interpolated over discs of radius h, which never
  // reach the faces behind the tip)
  // 'branch yoffe': a tip with G >= 2 G_c branches where the hoop stress
  // about it has two maxima, one each side of its direction (Yoffe's
  // instability of a fast crack); the branches take those two directions
  std::vector<double> bdir(2 * nt, 0.0);
  std::vector<int> bsplit(nt, 0);
  const int yoffe = (tip_branch < 0.0);
  auto yoffe_candidate = [&](int a) {
    return yoffe && Gt[a] >= 2.0 * tip_Gc && tips[a].own >= seglen;
  };
  bool need_hoop = false;
  for (int a : want) need_hoop = need_hoop || tip_hoop || yoffe_candidate(a);
  if (need_hoop) {
    constexpr int NA = 33;
    const double rs = 2.0 * h, rh = h, dth = 5.0 * M_PI / 180.0;
    const int nw = want.size();
    std::vector<double> hm(nw * NA * 4, 0.0), hs(nw * NA * 4, 0.0), ang(nw * NA);
    for (int w = 0; w < nw; w++) {
      const CrackTip &tp = tips[want[w]];
      const double phi0 = atan2(tp.t[1], tp.t[0]);
      for (int j = 0; j < NA; j++) ang[w * NA + j] = phi0 + (j - NA / 2) * dth;
    }
    // each tip's sums over the particles near it, in ascending order
    for (int w = 0; w < nw; w++) {
      const auto &P = tips[want[w]].path.back();
      const double lo[2] = {P[0] - (rs + rh), P[1] - (rs + rh)}, hi[2] = {P[0] + rs + rh, P[1] + rs + rh};
      particles_in_box(lo, hi, near);
      for (int i : near) {
        const double *X = x0c[i];
        bool have = false;
        double sig[9];
        const double ex = X[0] - P[0], ey = X[1] - P[1];
        if (ex * ex + ey * ey > (rs + rh) * (rs + rh)) continue;
        for (int j = 0; j < NA; j++) {
          const double cx = P[0] + rs * cos(ang[w * NA + j]), cy = P[1] + rs * sin(ang[w * NA + j]);
          const double r2 = (X[0] - cx) * (X[0] - cx) + (X[1] - cy) * (X[1] - cy);
          if (r2 >= rh * rh) continue;
          if (!have) {
            cauchy_stress(i, sig);
            have = true;
          }
          const double wt = (1.0 - r2 / (rh * rh)) * (1.0 - r2 / (rh * rh));
          double *H = hm.data() + 4 * (w * NA + j);
          H[0] += wt;
          H[1] += wt * sig[0];
          H[2] += wt * sig[4];
          H[3] += wt * sig[1];
        }
      }
    }
    MPI_Allreduce(hm.data(), hs.data(), nw * NA * 4, MPI_DOUBLE, MPI_SUM, world);
    for (int w = 0; w < nw; w++) {
      std::vector<double> hoop(NA, -1.0e300);
      for (int j = 0; j < NA; j++) {
        const double *H = hs.data() + 4 * (w * NA + j);
        if (!(H[0] > 0.0)) continue;
        const double sx = H[1] / H[0], sy = H[2] / H[0], sxy = H[3] / H[0];
        const double c = cos(ang[w * NA + j]), sn = sin(ang[w * NA + j]);
        // e_theta = (-sin, cos)
        hoop[j] = sx * sn * sn + sy * c * c - 2.0 * sxy * sn * c;
      }
      // the angle of the maximum at sample jm (parabola through its neighbours)
      auto peak = [&](int jm) {
        double phi = ang[w * NA + jm];
        if (jm > 0 && jm < NA - 1) {
          const double y0 = hoop[jm - 1], y1 = hoop[jm], y2 = hoop[jm + 1];
          const double den = y0 - 2.0 * y1 + y2;
          if (den < 0.0) phi += 0.5 * dth * (y0 - y2) / den;
        }
        return phi;
      };
      const int a = want[w];
      if (tip_hoop) {
        int jm = 0;
        for (int j = 1; j < NA; j++)
          if (hoop[j] > hoop[jm]) jm = j;
        const double phi = peak(jm);
        nd[2 * a] = cos(phi);
        nd[2 * a + 1] = sin(phi);
      }
      if (yoffe_candidate(a)) {
        // a smooth profile first (the samples carry the lattice's ripple):
        // least squares fit of c0 + c1 cos + c2 cos 2 + s1 sin + s2 sin 2 of
        // the angle to the direction, then its largest local maximum on
        // each side of the direction (1 deg grid)
        double M[25] = {0.0}, rhs[5] = {0.0};
        const double phi0 = ang[w * NA + NA / 2];
        auto basis = [](double u, double *b) {
          b[0] = 1.0;
          b[1] = cos(u);
          b[2] = cos(2.0 * u);
          b[3] = sin(u);
          b[4] = sin(2.0 * u);
        };
        int nfit = 0;
        for (int j = 0; j < NA; j++) {
          if (hoop[j] < -1.0e299) continue;
          double b[5];
          basis(ang[w * NA + j] - phi0, b);
          for (int r = 0; r < 5; r++) {
            rhs[r] += b[r] * hoop[j];
            for (int c = 0; c < 5; c++) M[5 * r + c] += b[r] * b[c];
          }
          nfit++;
        }
        double cf[5] = {0.0}, Minv[25];
        if (nfit >= 5 && invert_small(5, M, Minv))
          for (int r = 0; r < 5; r++)
            for (int c = 0; c < 5; c++) cf[r] += Minv[5 * r + c] * rhs[c];
        auto smooth = [&](double u) {
          double b[5];
          basis(u, b);
          return cf[0] * b[0] + cf[1] * b[1] + cf[2] * b[2] + cf[3] * b[3] + cf[4] * b[4];
        };
        // maxima beyond 65 deg are not taken: the fit is loosely held near
        // its ends (80 deg), and the hoop stress maxima of a running crack
        // stay within about 60-65 deg of its line up to the Rayleigh speed
        // (Yoffe 1951)
        const int nd1 = 65;
        double bl = -1.0, br = -1.0, ul = 0.0, ur = 0.0;
        for (int d = -nd1; d <= nd1; d++) {
          const double u = d * M_PI / 180.0, e = M_PI / 180.0;
          const double f0 = smooth(u);
          if (!(f0 > smooth(u - e) && f0 >= smooth(u + e))) continue;
          if (d < 0 && (bl < 0.0 || f0 > bl)) bl = f0, ul = u;
          if (d > 0 && (br < 0.0 || f0 > br)) br = f0, ur = u;
        }
        const int jl = (bl > 0.0) ? 1 : -1, jr = (br > 0.0) ? 1 : -1;
        if (getenv("TLSPH_TIP_TRACE") && comm->me == 0) {
          std::string line = fmt::format("hoop-trace {} {} G/Gc {:.3f}:", update->ntimestep, a,
                                         Gt[a] / tip_Gc);
          for (int j = 0; j < NA; j += 2) line += fmt::format(" {:.3g}", hoop[j]);
          line += fmt::format(" | fit {:.3g} {:.3g} {:.3g} {:.3g} {:.3g} | maxima {:.1f} {:.1f}", cf[0],
                              cf[1], cf[2], cf[3], cf[4], bl > 0 ? ul * 180 / M_PI : 0.0,
                              br > 0 ? ur * 180 / M_PI : 0.0);
          utils::logmesg(lmp, line + "\n");
        }
        if (jl >= 0 && jr >= 0) {
          bdir[2 * a] = phi0 + ul;
          bdir[2 * a + 1] = phi0 + ur;
          bsplit[a] = 1;
        }
      }
    }
  }

  std::vector<CrackTip> born;
  std::vector<int> moved;
  for (int a = 0; a < nt; a++) {
    CrackTip &tp = tips[a];
    if (!tp.alive || Gt[a] < tip_Gc) continue;
    const double G = Gt[a];
    const double v = tip_cR * (1.0 - tip_Gc / G);
    tp.speed = v;
    double P[2] = {tp.path.back()[0], tp.path.back()[1]};
    if (tp.seg == 0.0) {
      const double t0 = nd[2 * a], t1 = nd[2 * a + 1];
      if (comm->me == 0 && !tp.growing)
        utils::logmesg(lmp, "pair tlsph/damage: step {} t {:.6g}: tip {} at ({:.6g}, {:.6g}) "
                            "grows, K_I {:.4g} K_II {:.4g} kink {:.2f} deg\n", update->ntimestep,
                       update->atime + (update->ntimestep - update->atimestep) * dt, a, P[0], P[1],
                       Kt[2 * a], Kt[2 * a + 1], tht[a] * 180.0 / M_PI);
      tp.growing = 1;
      if ((tip_branch > 0.0 && G >= 2.0 * tip_Gc && tp.own >= seglen) || bsplit[a]) {
        for (int sgn = -1; sgn <= 1; sgn += 2) {
          CrackTip b = tp;
          if (bsplit[a]) {
            const double phi = bdir[2 * a + (sgn > 0 ? 1 : 0)];
            b.t[0] = cos(phi);
            b.t[1] = sin(phi);
          } else {
            const double cb = cos(sgn * tip_branch), sb = sin(sgn * tip_branch);
            b.t[0] = cb * t0 - sb * t1;
            b.t[1] = sb * t0 + cb * t1;
          }
          b.path.push_back({P[0], P[1]});
          // its first segment keeps the branching direction (seg > 0)
          b.seg = 1.0e-300;
          b.own = 0.0;
          born.push_back(b);
        }
        tp.alive = 0;
        if (comm->me == 0)
          utils::logmesg(lmp, "pair tlsph/damage: step {} tip {} at ({:.6g}, {:.6g}) branches "
                              "(G {:.4g} = {:.3f} G_c)\n", update->ntimestep, a, P[0], P[1], G,
                         G / tip_Gc);
        continue;
      }
      tp.t[0] = t0;
      tp.t[1] = t1;
      tp.path.push_back({P[0], P[1]});
      if (comm->me == 0 && getenv("TLSPH_TIP_TRACE"))
        utils::logmesg(lmp, "tip-trace {} {} {:.6g} {:.6g} {:.4g} {:.4g} {:.4g} {:.3f} {:.2f}\n",
                       update->ntimestep, a, P[0], P[1], Kt[2 * a], Kt[2 * a + 1], G / tip_Gc,
                       v / tip_cR, atan2(t1, t0) * 180.0 / M_PI);
    }
    const double da = v * dt;
    const double Pn[2] = {P[0] + da * tp.t[0], P[1] + da * tp.t[1]};
    cut_path(P, Pn);
    tp.path.back() = {Pn[0], Pn[1]};
    tp.seg += da;
    tp.own += da;
    if (tp.seg >= seglen) tp.seg = 0.0;
    moved.push_back(a);
  }
  // new branches take their first step next time; live tips that left the body stop
  for (auto &b : born) tips.push_back(b);
  if (!born.empty()) {
    int nlive = 0;
    for (const auto &tp : tips) nlive += tp.alive;
    if (nlive > 1000)
      error->all(FLERR, "pair tlsph/damage: step {}: {} live crack tips (branching runs away; "
                        "with 'branch A' every tip with G >= 2 G_c splits): stopped", update->ntimestep,
                 nlive);
  }
  if (!moved.empty()) {
    std::vector<std::array<double, 2>> pts;
    for (int a : moved) pts.push_back(tips[a].path.back());
    std::vector<double> vol;
    volume_near(pts, h, vol);
    for (size_t p = 0; p < moved.size(); p++)
      if (vol[p] < 0.4 * M_PI * h * h * tip_depth) {
        tips[moved[p]].alive = 0;
        if (comm->me == 0)
          utils::logmesg(lmp, "pair tlsph/damage: step {} tip {} stops at ({:.6g}, {:.6g}), "
                              "outside the body\n", update->ntimestep, moved[p], pts[p][0], pts[p][1]);
      }
  }
}
