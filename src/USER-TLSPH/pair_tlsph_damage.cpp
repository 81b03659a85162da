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
#include "timer.h"
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
  crack = new TLSPHCrackTips(lmp, this);
}

PairTLSPHDamage::~PairTLSPHDamage()
{
  memory->destroy(phi);
  memory->destroy(phis);
  memory->destroy(alphas);
  memory->destroy(phi_prev);
  memory->destroy(mark);
  delete crack;
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
  crack->defaults();
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
    } else if (const int used = crack->parse(narg, arg, iarg)) {
      have_branch = true;
      iarg += used;
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
    error->all(FLERR, "pair_style tlsph/damage: branch, tipdir, tipseg, kfit, kratio, jinertia, "
                      "jring and tipparam are settings of 'criterion tip'");
  if (crack->tstress_rule() && crack->kfit < 2)
    error->all(FLERR, "pair_style tlsph/damage: branch {} takes the T-stress from an "
                      "interaction integral over J's ring: it needs kfit j or kfit interaction",
               crack->branch == TLSPHCrackTips::TSTRESS ? "tstress" : "tstress/dynamic");
  if (crack->tipdir_seg && crack->kfit < 2)
    error->all(FLERR, "pair_style tlsph/damage: tipdir segment takes the T-stress from an "
                      "interaction integral over J's ring: it needs kfit j or kfit interaction");
  if (crack->kratio_run && crack->kfit < 2)
    error->all(FLERR, "pair_style tlsph/damage: kratio running corrects the mode ratio of tips "
                      "whose K takes its size from the J-integral: it needs kfit j or kfit interaction");
  if (crack->jinertia && crack->kfit < 2)
    error->all(FLERR, "pair_style tlsph/damage: jinertia yes adds the inertia term to the tips' "
                      "J-integral: it needs kfit j or kfit interaction");
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
    strength.assign(atom->ntypes + 1, 0.0);
  }
  if (key == "strength") {
    if (!(v > 0.0))
      error->all(FLERR, "{}: strength must be > 0 (the tensile strength at which 'criterion tip' "
                        "nucleates a crack), got {}", where, v);
    strength[type] = v;
    return true;
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

// G_c, the given s_c and the strength (files whose settings carry no
// strength mark, read_restart_settings, have the first two only)
void PairTLSPHDamage::write_material_extra(FILE *fp, int type)
{
  double v[3] = {Gc[type], sc_given[type], (int) strength.size() > type ? strength[type] : 0.0};
  fwrite(v, sizeof(double), 3, fp);
}

void PairTLSPHDamage::read_material_extra(FILE *fp, int type)
{
  double v[3] = {0.0, 0.0, 0.0};
  const int n = restart_has_strength ? 3 : 2;
  if (comm->me == 0) utils::sfread(FLERR, v, sizeof(double), n, fp, nullptr, error);
  MPI_Bcast(v, 3, MPI_DOUBLE, 0, world);
  if ((int) Gc.size() <= atom->ntypes) {
    Gc.assign(atom->ntypes + 1, 0.0);
    sc_given.assign(atom->ntypes + 1, 0.0);
    sc.assign(atom->ntypes + 1, 0.0);
    strength.assign(atom->ntypes + 1, 0.0);
  }
  Gc[type] = v[0];
  sc_given[type] = v[1];
  strength[type] = v[2];
}

void PairTLSPHDamage::write_restart_settings(FILE *fp)
{
  PairTLSPH::write_restart_settings(fp);
  // damping + 2: the materials' extra values carry the strength (3 values)
  double v[6] = {alpha_d, (double) absolute, (double) rebuild, (double) cracks.size(), family,
                 (double) damping_linear + 2.0};
  fwrite(v, sizeof(double), 6, fp);
  for (const auto &c : cracks) fwrite(c.data(), sizeof(double), 9, fp);
  // 'criterion tip': the settings, then every tip with its path (identical on all ranks)
  crack->write_restart(fp, tipmode);
}

void PairTLSPHDamage::read_restart_settings(FILE *fp)
{
  PairTLSPH::read_restart_settings(fp);
  double v[6];
  if (comm->me == 0) utils::sfread(FLERR, v, sizeof(double), 6, fp, nullptr, error);
  MPI_Bcast(v, 6, MPI_DOUBLE, 0, world);
  // a file of another layout (e.g. before 'family' and 'damping' were
  // stored) reads numbers out of place: refuse it with a message
  restart_has_strength = (v[5] >= 2.0);
  if (restart_has_strength) v[5] -= 2.0;
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
  tipmode = crack->read_restart(fp);
}

/* ---------------------------------------------------------------------- */

void PairTLSPHDamage::init_style()
{
  correction_from_all_partners = !rebuild;
  tip_wall = 0.0;    // (report_run: this run's)
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
    for (int t = 2; t <= atom->ntypes; t++)
      if (mat[t].rho > 0.0 && (int) strength.size() > t && strength[t] != strength[1])
        error->all(FLERR, "pair tlsph/damage: 'criterion tip' needs one material (all types "
                          "alike): type {} has strength {}, type 1 {}", t, strength[t], strength[1]);
    crack->init(plane_stress ? m.E : m.E / (1.0 - m.nu * m.nu), m.mu,
                plane_stress ? (3.0 - m.nu) / (1.0 + m.nu) : 3.0 - 4.0 * m.nu, Gc[1],
                sqrt(m.mu / m.rho) * (0.862 + 1.14 * m.nu) / (1.0 + m.nu), sqrt(m.mu / m.rho),
                (int) strength.size() > 1 ? strength[1] : 0.0);
    nuc_screen_s = (int) strength.size() > 1 ? strength[1] : 0.0;
  } else {
    nuc_screen_s = 0.0;
    for (int t = 1; t < (int) strength.size(); t++)
      if (strength[t] > 0.0)
        error->all(FLERR, "pair tlsph/damage: type {}: strength (crack nucleation) needs "
                          "'criterion tip'; the bond criteria break bonds anywhere already", t);
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
  // (the next after_deformation sets them all: phis_valid below; until then
  // pass (1) copies them into the rows)
  std::fill(alphas, alphas + nmax_d, alpha);
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
  // 1e-9 |AB| |PR| (sqrt of the product: hypot, which guards against
  // overflow these lengths cannot reach, took a fifth of a step with 110
  // growing tips, bench/manytips.sh)
  const double lab2 = (B[0] - A[0]) * (B[0] - A[0]) + (B[1] - A[1]) * (B[1] - A[1]);
  const double lpr2 = (R[0] - P[0]) * (R[0] - P[0]) + (R[1] - P[1]) * (R[1] - P[1]);
  // A and B clearly on one side of PR: not crossed, without the square root
  // (sqrt(lab2 lpr2) <= (lab2 + lpr2) / 2, so neither would snap to zero)
  {
    const double oa = orient(P, R, A), ob = orient(P, R, B);
    const double big = 1.0e-9 * 0.5 * (lab2 + lpr2) * (1.0 + 1.0e-12);
    if (oa * ob > 0.0 && std::fabs(oa) >= big && std::fabs(ob) >= big) return false;
  }
  const double tol = 1.0e-9 * std::sqrt(lab2 * lpr2);
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
  if (!bond_values_kept) return;    // bond_values computes them from the new Q[i]
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
    // the values: lean.g and lean.w, or (not kept) computed again into a
    // scratch copy that drop_bond reorders with lean.j and lean.k
    double *bg, *bw;
    bond_values_mutable(i, bg, bw);
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
        TLSPH::drop_bond<DIM>(bj, bg, bw, lean.k + s, m, nlead[i], n);
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
        bond_values_mutable(i, bg, bw);
        const struct {
          double **p;
          const double *operator()(int k) const { return p[k]; }
        } rows{x};
        TLSPH::deformation_gradient_bonds<DIM>(rows, i, bond_view<DIM>(i, bg, bw), n, Fi);
      }
    }
    particle_stress_of<DIM, ORDER, LAWS>(i, need_K, bond_view<DIM>(i, bg, bw));
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
  // their stress changed after the lanes' nucleation screen: tested exactly
  if (nuc_hit_step == update->ntimestep)
    for (int q = 0; q < n; q++) nuc_hit[list[q]] = 1;
}

/* ----------------------------------------------------------------------
   the run just ended ('criterion tip'): the wall time of the tips' work in
   its steps beside the run's loop time, the slowest rank's, into the log:
   a measure of what the tips cost taken inside one run, so that a shared
   machine's drift between runs does not enter it (bench/manytips.sh)
------------------------------------------------------------------------- */

void PairTLSPHDamage::report_run(bigint nsteps)
{
  if (!tipmode || nsteps <= 0) return;
  double mine = tip_wall, most = 0.0;
  MPI_Allreduce(&mine, &most, 1, MPI_DOUBLE, MPI_MAX, world);
  const double loop = timer->get_wall(Timer::TOTAL);    // (Finish's 'Loop time', rank 0's)
  if (comm->me == 0 && loop > 0.0)
    utils::logmesg(lmp,
                   "pair tlsph/damage: crack tips' work {:.6g} s of the loop's {:.6g} s in {} steps "
                   "({:.2f} %; {:.3f} of the rest of the loop)\n",
                   most, loop, nsteps, 100.0 * most / loop, loop > most ? most / (loop - most) : 0.0);
  tip_wall = 0.0;
}

// 'criterion tip' with jinertia: the tips' share of the step's force (J's
// inertia term, TLSPHCrackTips::inertia_forces)
void PairTLSPHDamage::step_done()
{
  if (!tipmode) return;
  const double t0 = MPI_Wtime();
  crack->inertia_forces();
  if (!update->setupflag) tip_wall += MPI_Wtime() - t0;
}

/* ----------------------------------------------------------------------
   every step, before the deformation pass: the pre-cracks once, and the
   bonds of the cracks nucleated at the end of the last step ('criterion
   tip'; its tips grow after the pass, in after_deformation)
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
  if (tipmode) {
    const double t0 = MPI_Wtime();
    crack->cut_newborn();
    crack->snapshot_hoop();
    if (!update->setupflag) tip_wall += MPI_Wtime() - t0;
  }
}

/* ----------------------------------------------------------------------
   after the deformation pass (this step's bonds are decided): damage, the
   smoothed damage and the viscosity coefficient of every local particle,
   which then goes into its packed row
------------------------------------------------------------------------- */

void PairTLSPHDamage::after_deformation()
{
  if (tipmode) {
    // the tips, measured on this pass's fields, grow and cut bonds: pass (1)
    // again for the particles that lost bonds (and, SIMD step, their columns)
    const double t0 = MPI_Wtime();
    tip_cut.clear();
    crack->grow();
    if (!tip_cut.empty()) {
      std::sort(tip_cut.begin(), tip_cut.end());
      tip_cut.erase(std::unique(tip_cut.begin(), tip_cut.end()), tip_cut.end());
      if (simd_isa != SIMD_NO) simd_breaks(tip_cut.data(), (int) tip_cut.size());
      else deform_and_break_pass(tip_cut.data(), (int) tip_cut.size());
    }
    crack->nucleate();
    crack->note_pass();
    if (!update->setupflag) tip_wall += MPI_Wtime() - t0;
  }
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
  // phi changes only where a bond broke: none on this rank since the last
  // call (and the same particle indices) leaves every phi as it is
  if (full || nbroken_local != nbroken_seen)
    for (int i = 0; i < nlocal; i++) {
      const int n0 = bonds->nintact0[i];
      phi[i] = (n0 > 0) ? 1.0 - (double) nbond[i] / n0 : 0.0;
      if (phi[i] < 0.0) phi[i] = 0.0;
      if (phi[i] != phi_prev[i]) lchg = 1;
    }
  nbroken_seen = nbroken_local;
  int gchg = lchg;
  if (comm->nprocs > 1) MPI_Allreduce(&lchg, &gchg, 1, MPI_INT, MPI_MAX, world);
  const int ia = 2 * dim * dim;    // alpha_i in the packed row (TLSPH::Packed::A)
  // no alpha_i changed: pass (1) wrote this alpha_i (alpha_atom) into the
  // rows and the SIMD columns already
  alpha_changed = gchg != 0;
  if (!gchg) return;
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
   'criterion tip': the bonds a tip's path cuts (the tips: tlsph_crack_tips.cpp)
------------------------------------------------------------------------- */

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
  std::vector<int> near;
  crack->particles_in_box(lo, hi, near);
  for (int i : near) {
    const double *Xi = x0c[i];
    const int s = bond_start[i];
    int *bj = lean.j + s;
    // lean.g and lean.w, or a scratch copy (deform_and_break): fetched at the
    // first bond cut (not kept, they are computed again: most particles in
    // the box lose none)
    double *bg = nullptr, *bw = nullptr;
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
      if (!bg) bond_values_mutable(i, bg, bw);
      if (!rebuild)
        for (int d = 0; d < dim; d++) sumg[i][d] -= bg[dim * m + d];
      if (dim == 2) TLSPH::drop_bond<2>(bj, bg, bw, lean.k + s, m, nlead[i], n);
      else TLSPH::drop_bond<3>(bj, bg, bw, lean.k + s, m, nlead[i], n);
      changed = true;
    }
    if (changed) {
      nbond[i] = n;
      ell_mark(i);
      if (rebuild) recorrect(i);
      tip_cut.push_back(i);
    }
  }
}
