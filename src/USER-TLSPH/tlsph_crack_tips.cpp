/* ----------------------------------------------------------------------
   USER-TLSPH: the crack tips of crack-tip tracking, see tlsph_crack_tips.h
   and doc/pair_tlsph_damage.rst ("Crack-tip tracking")
------------------------------------------------------------------------- */

#include "tlsph_crack_tips.h"

#include "pair_tlsph_damage.h"
#include "tlsph_crack.h"
#include "tlsph_input.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

using namespace LAMMPS_NS;

namespace {
/* The trace of pre-crack c in the xy plane (ends A = (t[0], t[1]) and
   B = (t[2], t[3])): in 2D its segment; in 3D, a parallelogram with one
   edge along z (find_tips refuses others), its edge that is not along z. */
std::array<double, 4> crack_trace(int dim, const std::array<double, 9> &c)
{
  if (dim == 2) return {c[0], c[1], c[2], c[3]};
  const bool wz = (c[6] == c[0] && c[7] == c[1]);
  return {c[0], c[1], wz ? c[3] : c[6], wz ? c[4] : c[7]};
}
}    // namespace

TLSPHCrackTips::TLSPHCrackTips(LAMMPS *lmp, PairTLSPHDamage *p) : Pointers(lmp), pair(p)
{
  defaults();
  ready = depth_ready = 0;
  Eprime = Gc = cR = cs = depth = 0.0;
}

void TLSPHCrackTips::defaults()
{
  tipdir_hoop = 0;
  tipdir_seg = 0;
  kfit = 0;
  jr1 = 2.0;
  jr2 = 4.0;
  jinertia = 0;
  kratio_run = 0;
  seg = 0.0;
  branch = 0.0;
  p_sample = 1.5;
  p_disc = 1.5;
  p_hoopr = 2.0;
  p_window = 65;
  p_split = 1.0;
  p_rc = 0.0;
}

/* the tip keywords of pair_style tlsph/damage: tipdir faces|hoop|segment,
   kfit tip|offset|j|interaction, jring r1 r2, tipseg L, branch yoffe|A */
int TLSPHCrackTips::parse(int narg, char **arg, int iarg)
{
  const std::string key = arg[iarg];
  if (key == "tipdir") {
    if (iarg + 1 >= narg) error->all(FLERR, "pair_style tlsph/damage: tipdir needs a value");
    if (strcmp(arg[iarg + 1], "faces") == 0) tipdir_hoop = 0, tipdir_seg = 0;
    else if (strcmp(arg[iarg + 1], "hoop") == 0) tipdir_hoop = 1, tipdir_seg = 0;
    else if (strcmp(arg[iarg + 1], "segment") == 0) tipdir_hoop = 0, tipdir_seg = 1;
    else
      error->all(FLERR, "pair_style tlsph/damage: tipdir must be 'faces', 'hoop' or 'segment', got '{}'",
                 arg[iarg + 1]);
    return 2;
  }
  if (key == "kfit") {
    if (iarg + 1 >= narg) error->all(FLERR, "pair_style tlsph/damage: kfit needs a value");
    if (strcmp(arg[iarg + 1], "tip") == 0) kfit = 0;
    else if (strcmp(arg[iarg + 1], "offset") == 0) kfit = 1;
    else if (strcmp(arg[iarg + 1], "j") == 0) kfit = 2;
    else if (strcmp(arg[iarg + 1], "interaction") == 0) kfit = 3;
    else
      error->all(FLERR, "pair_style tlsph/damage: kfit must be 'tip', 'offset', 'j' or "
                        "'interaction', got '{}'", arg[iarg + 1]);
    return 2;
  }
  if (key == "jinertia") {
    if (iarg + 1 >= narg) error->all(FLERR, "pair_style tlsph/damage: jinertia needs a value");
    if (strcmp(arg[iarg + 1], "yes") == 0) jinertia = 1;
    else if (strcmp(arg[iarg + 1], "no") == 0) jinertia = 0;
    else
      error->all(FLERR, "pair_style tlsph/damage: jinertia must be 'yes' or 'no', got '{}'",
                 arg[iarg + 1]);
    return 2;
  }
  if (key == "kratio") {
    if (iarg + 1 >= narg) error->all(FLERR, "pair_style tlsph/damage: kratio needs a value");
    if (strcmp(arg[iarg + 1], "running") == 0) kratio_run = 1;
    else if (strcmp(arg[iarg + 1], "static") == 0) kratio_run = 0;
    else
      error->all(FLERR, "pair_style tlsph/damage: kratio must be 'static' or 'running', got '{}'",
                 arg[iarg + 1]);
    return 2;
  }
  if (key == "jring") {
    if (iarg + 2 >= narg)
      error->all(FLERR, "pair_style tlsph/damage: jring needs two values (the J domain's inner "
                        "and outer radius in h)");
    jr1 = TLSPHInput::number(error, "pair_style tlsph/damage", key, arg[iarg + 1]);
    jr2 = TLSPHInput::number(error, "pair_style tlsph/damage", key, arg[iarg + 2]);
    if (!(jr1 >= 0.0 && jr2 > jr1 && jr2 < 1.0e3))
      error->all(FLERR, "pair_style tlsph/damage: jring must be two radii in h with 0 <= r1 < "
                        "r2, got {} {}", arg[iarg + 1], arg[iarg + 2]);
    return 3;
  }
  if (key == "tipparam") {
    if (iarg + 2 >= narg)
      error->all(FLERR, "pair_style tlsph/damage: tipparam needs a name and a value (names: "
                        "sample, disc, hoopr, window, split)");
    const std::string name = arg[iarg + 1];
    const double val = TLSPHInput::number(error, "pair_style tlsph/damage", "tipparam " + name, arg[iarg + 2]);
    if (name == "sample" || name == "disc" || name == "hoopr" || name == "split") {
      if (!(val > 0.0 && val < 100.0))
        error->all(FLERR, "pair_style tlsph/damage: tipparam {} must be > 0 and < 100 (in h, or "
                          "in segments for split), got {}", name, arg[iarg + 2]);
      (name == "sample" ? p_sample : name == "disc" ? p_disc : name == "hoopr" ? p_hoopr : p_split) = val;
    } else if (name == "window") {
      if (!(val >= 1.0 && val <= 80.0 && val == std::floor(val)))
        error->all(FLERR, "pair_style tlsph/damage: tipparam window must be a whole number of "
                          "degrees in [1, 80], got {}", arg[iarg + 2]);
      p_window = (int) val;
    } else {
      error->all(FLERR, "pair_style tlsph/damage: tipparam name must be sample, disc, hoopr, "
                        "window or split, got '{}'", name);
    }
    return 3;
  }
  if (key == "tipseg") {
    if (iarg + 1 >= narg) error->all(FLERR, "pair_style tlsph/damage: tipseg needs a value");
    seg = TLSPHInput::number(error, "pair_style tlsph/damage", key, arg[iarg + 1]);
    if (!(seg >= 0.0))
      error->all(FLERR, "pair_style tlsph/damage: tipseg must be >= 0 (a length in h; 0: the "
                        "sampling reach), got {}", arg[iarg + 1]);
    return 2;
  }
  if (key == "branch") {
    if (iarg + 1 >= narg)
      error->all(FLERR, "pair_style tlsph/damage: branch needs a value (half angle in degrees)");
    if (strcmp(arg[iarg + 1], "yoffe") == 0) {
      branch = YOFFE;
    } else if (strcmp(arg[iarg + 1], "yoffe/step") == 0) {
      branch = YOFFE_STEP;
    } else if (strcmp(arg[iarg + 1], "tstress") == 0 || strcmp(arg[iarg + 1], "tstress/dynamic") == 0) {
      const std::string w = arg[iarg + 1];
      if (iarg + 2 >= narg)
        error->all(FLERR, "pair_style tlsph/damage: branch {} needs the distance r_c (a length > 0)", w);
      const double rc = TLSPHInput::number(error, "pair_style tlsph/damage", "branch " + w, arg[iarg + 2]);
      if (!(rc > 0.0))
        error->all(FLERR, "pair_style tlsph/damage: branch {} needs the distance r_c > 0, got {}", w,
                   arg[iarg + 2]);
      branch = w == "tstress" ? TSTRESS : TSTRESS_DYNAMIC;
      p_rc = rc;
      return 3;
    } else {
      // (a word other than these two gets the message that lists them)
      const char *v = arg[iarg + 1];
      const double a =
          utils::is_double(v) ? TLSPHInput::number(error, "pair_style tlsph/damage", key, v) : -1.0;
      if (!(a >= 0.0 && a < 90.0))
        error->all(FLERR, "pair_style tlsph/damage: branch must be 'yoffe', 'yoffe/step', "
                          "'tstress', 'tstress/dynamic' or an angle in [0, 90) degrees, got {}",
                   arg[iarg + 1]);
      branch = a * M_PI / 180.0;
    }
    return 2;
  }
  return 0;
}

/* ----------------------------------------------------------------------
   restart: the settings, then every tip with its path (identical on all
   ranks). tipdir and kfit share one value, tipdir + 2 kfit + 8 (tipdir
   segment) + 16 (kratio running), 0 to 31 (files written before kfit read
   as kfit tip, before tipdir segment as faces or hoop, before kratio as
   kratio static); tipmode + 2 marks the layout with the J ring after the six
   (files written before it have tipmode 0 or 1 there and the default ring), + 4 the ring and the
   tipparam values, + 8 those and jinertia, + 16 those and branch tstress's r_c
------------------------------------------------------------------------- */

void TLSPHCrackTips::write_restart(FILE *fp, int tipmode)
{
  double w[6] = {(double) tipmode + 16.0, (double) (tipdir_hoop + 2 * kfit + 8 * tipdir_seg + 16 * kratio_run), seg, branch,
                 (double) ready, (double) list.size()};
  fwrite(w, sizeof(double), 6, fp);
  const double jr[9] = {jr1, jr2, p_sample, p_disc, p_hoopr, (double) p_window, p_split, (double) jinertia,
                        p_rc};
  fwrite(jr, sizeof(double), 9, fp);
  for (const auto &tp : list) {
    std::vector<double> r = {(double) tp.path.size(), tp.t[0], tp.t[1], tp.seg, tp.own,
                             (double) tp.alive, (double) (tp.growing + 2 * tp.newborn)};
    for (const auto &p : tp.path) r.insert(r.end(), {p[0], p[1]});
    fwrite(r.data(), sizeof(double), r.size(), fp);
  }
}

int TLSPHCrackTips::read_restart(FILE *fp)
{
  double w[6];
  if (comm->me == 0) utils::sfread(FLERR, w, sizeof(double), 6, fp, nullptr, error);
  MPI_Bcast(w, 6, MPI_DOUBLE, 0, world);
  // layouts: tipmode + 16: the ring, the tipparam values, jinertia and r_c;
  // + 8: the ring, the tipparam values and jinertia
  // follow; + 4: the ring and the tipparam values; + 2: the ring only;
  // tipmode alone: none (the defaults)
  const int extra = (w[0] >= 16.0) ? 9 : (w[0] >= 8.0) ? 8 : (w[0] >= 4.0) ? 7 : (w[0] >= 2.0) ? 2 : 0;
  if (extra == 9) w[0] -= 16.0;
  else if (extra == 8) w[0] -= 8.0;
  else if (extra == 7) w[0] -= 4.0;
  else if (extra == 2) w[0] -= 2.0;
  if (!((w[0] == 0.0 || w[0] == 1.0) && (w[1] >= 0.0 && w[1] <= 31.0 && w[1] == std::floor(w[1])) &&
        w[2] >= 0.0 &&
        (w[3] == YOFFE || w[3] == YOFFE_STEP || w[3] == TSTRESS || w[3] == TSTRESS_DYNAMIC ||
         (w[3] >= 0.0 && w[3] < 2.0)) &&
        (w[4] == 0.0 || w[4] == 1.0) && w[5] >= 0.0 &&
        w[5] == std::floor(w[5]) && w[5] < 1.0e7))
    error->all(FLERR, "pair tlsph/damage: the restart file's pair settings are not in this "
                      "version's layout (written by another version of the package?)");
  const int tipmode = static_cast<int>(w[0]);
  defaults();    // what an older layout does not carry
  tipdir_hoop = static_cast<int>(w[1]) % 2;
  kfit = (static_cast<int>(w[1]) / 2) % 4;
  tipdir_seg = (static_cast<int>(w[1]) / 8) % 2;
  kratio_run = static_cast<int>(w[1]) / 16;
  seg = w[2];
  branch = w[3];
  ready = static_cast<int>(w[4]);
  depth_ready = 0;
  if (extra) {
    double jr[9];
    if (comm->me == 0) utils::sfread(FLERR, jr, sizeof(double), extra, fp, nullptr, error);
    MPI_Bcast(jr, extra, MPI_DOUBLE, 0, world);
    if (!(jr[0] >= 0.0 && jr[1] > jr[0] && jr[1] < 1.0e3) ||
        (extra >= 7 && !(jr[2] > 0.0 && jr[3] > 0.0 && jr[4] > 0.0 && jr[5] >= 1.0 && jr[6] > 0.0)) ||
        (extra >= 8 && !(jr[7] == 0.0 || jr[7] == 1.0)) || (extra == 9 && !(jr[8] >= 0.0)) ||
        ((w[3] == TSTRESS || w[3] == TSTRESS_DYNAMIC) && !(extra == 9 && jr[8] > 0.0)))
      error->all(FLERR, "pair tlsph/damage: the restart file's pair settings are not in this "
                        "version's layout (written by another version of the package?)");
    jr1 = jr[0];
    jr2 = jr[1];
    if (extra >= 7) {
      p_sample = jr[2], p_disc = jr[3], p_hoopr = jr[4], p_window = (int) jr[5], p_split = jr[6];
    }
    if (extra >= 8) jinertia = (int) jr[7];
    if (extra == 9) p_rc = jr[8];
  }
  list.assign(static_cast<size_t>(w[5]), CrackTip{});
  for (auto &tp : list) {
    double r[7];
    if (comm->me == 0) utils::sfread(FLERR, r, sizeof(double), 7, fp, nullptr, error);
    MPI_Bcast(r, 7, MPI_DOUBLE, 0, world);
    const int np = static_cast<int>(r[0]);
    tp.t[0] = r[1];
    tp.t[1] = r[2];
    tp.seg = r[3];
    tp.own = r[4];
    tp.alive = static_cast<int>(r[5]);
    tp.growing = static_cast<int>(r[6]) % 2;
    tp.newborn = static_cast<int>(r[6]) / 2;
    std::vector<double> q(2 * (size_t) np);
    if (comm->me == 0 && np > 0)
      utils::sfread(FLERR, q.data(), sizeof(double), q.size(), fp, nullptr, error);
    if (np > 0) MPI_Bcast(q.data(), (int) q.size(), MPI_DOUBLE, 0, world);
    tp.path.resize(np);
    for (int k = 0; k < np; k++) tp.path[k] = {q[2 * k], q[2 * k + 1]};
  }
  return tipmode;
}

void TLSPHCrackTips::init(double Ep, double shear, double kap, double G_c, double c_R, double c_s,
                          double strength)
{
  cs = c_s;
  Eprime = Ep;
  mu = shear;
  kappa = kap;
  Gc = G_c;
  cR = c_R;
  sigma_t = strength;
  // the settings may have changed since the stencils were made
  sample_st.clear();
  j_st.clear();
}

/* ----------------------------------------------------------------------
   'criterion tip': crack-tip tracking (2D, and through-thickness cracks in 3D)
------------------------------------------------------------------------- */

// the volume of the particles within radius R of each point (all ranks)
void TLSPHCrackTips::refresh_cells()
{
  RefCells &rc = cells;
  const int nlocal = atom->nlocal;
  const std::array<int, 2> stamp = {pair->cache_version, nlocal};
  if (stamp == rc.stamp) return;
  rc.stamp = stamp;
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (int i = 0; i < nlocal; i++)
    for (int d = 0; d < 2; d++) lo[d] = MIN(lo[d], pair->x0c[i][d]), hi[d] = MAX(hi[d], pair->x0c[i][d]);
  if (nlocal == 0) lo[0] = lo[1] = hi[0] = hi[1] = 0.0;
  // cells of side h, larger where that would give more cells than 4 per particle
  double cs = pair->h;
  const double ncell_max = 4.0 * nlocal + 1024.0;
  while (((hi[0] - lo[0]) / cs + 1.0) * ((hi[1] - lo[1]) / cs + 1.0) > ncell_max) cs *= 2.0;
  rc.lo[0] = lo[0], rc.lo[1] = lo[1], rc.cs = cs;
  rc.nx = (int) ((hi[0] - lo[0]) / cs) + 1;
  rc.ny = (int) ((hi[1] - lo[1]) / cs) + 1;
  const int nc = rc.nx * rc.ny;
  std::vector<int> cell(nlocal);
  rc.start.assign(nc + 1, 0);
  for (int i = 0; i < nlocal; i++) {
    const int cx = MIN(rc.nx - 1, (int) ((pair->x0c[i][0] - lo[0]) / cs));
    const int cy = MIN(rc.ny - 1, (int) ((pair->x0c[i][1] - lo[1]) / cs));
    cell[i] = cx + rc.nx * cy;
    rc.start[cell[i] + 1]++;
  }
  for (int c = 0; c < nc; c++) rc.start[c + 1] += rc.start[c];
  rc.idx.resize(nlocal);
  std::vector<int> fill(rc.start.begin(), rc.start.end() - 1);
  for (int i = 0; i < nlocal; i++) rc.idx[fill[cell[i]]++] = i;
}

bool TLSPHCrackTips::stencil_current(std::vector<Stencil> &v, int a)
{
  if ((int) v.size() < (int) list.size()) v.resize(list.size());
  Stencil &st = v[a];
  const CrackTip &tp = list[a];
  const int nv = tp.path.size();
  if (st.nv == nv && st.at == tp.path.back() && st.stamp == cells.stamp) return true;
  st.nv = nv;
  st.at = tp.path.back();
  st.stamp = cells.stamp;
  st.idx.clear();
  st.slot.clear();
  st.w.clear();
  st.q.clear();
  return false;
}

const std::vector<int> &TLSPHCrackTips::candidates(Stencil &st, const double *lo, const double *hi)
{
  if (st.cstamp == cells.stamp && lo[0] >= st.clo[0] && lo[1] >= st.clo[1] && hi[0] <= st.chi[0] &&
      hi[1] <= st.chi[1])
    return st.cand;
  const double m = pair->h;
  st.clo[0] = lo[0] - m, st.clo[1] = lo[1] - m, st.chi[0] = hi[0] + m, st.chi[1] = hi[1] + m;
  st.cstamp = cells.stamp;
  particles_in_box(st.clo, st.chi, st.cand);
  return st.cand;
}

void TLSPHCrackTips::particles_in_box(const double *lo, const double *hi, std::vector<int> &out)
{
  const RefCells &rc = cells;
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
        const double *X = pair->x0c[i];
        if (X[0] >= lo[0] && X[0] <= hi[0] && X[1] >= lo[1] && X[1] <= hi[1]) out.push_back(i);
      }
    }
  std::sort(out.begin(), out.end());
}

// the volume of the local particles within R of each point (xy), all ranks
void TLSPHCrackTips::volume_near(const std::vector<std::array<double, 2>> &pts, double R,
                                  std::vector<double> &vol)
{
  refresh_cells();
  const double *vfrac = atom->vfrac;
  std::vector<double> mine(pts.size(), 0.0);
  std::vector<int> near;
  for (size_t p = 0; p < pts.size(); p++) {
    const double lo[2] = {pts[p][0] - R, pts[p][1] - R}, hi[2] = {pts[p][0] + R, pts[p][1] + R};
    particles_in_box(lo, hi, near);
    for (int i : near) {
      const double dx = pair->x0c[i][0] - pts[p][0], dy = pair->x0c[i][1] - pts[p][1];
      if (dx * dx + dy * dy < R * R) mine[p] += vfrac[i];
    }
  }
  vol.assign(pts.size(), 0.0);
  MPI_Allreduce(mine.data(), vol.data(), (int) pts.size(), MPI_DOUBLE, MPI_SUM, world);
}

// the depth of the body along z (2D: the thickness in the particle volumes),
// which turns volumes into areas; measured at the first step of a run
// (restart files do not carry it)
void TLSPHCrackTips::measure_depth()
{
  depth = pair->thickness;
  if (pair->dim == 3) {
    double lo = 1.0e300, hi = -1.0e300, vmax = 0.0, g[3];
    for (int i = 0; i < atom->nlocal; i++) {
      lo = MIN(lo, pair->x0c[i][2]);
      hi = MAX(hi, pair->x0c[i][2]);
      vmax = MAX(vmax, atom->vfrac[i]);
    }
    double m[3] = {-lo, hi, vmax};
    MPI_Allreduce(m, g, 3, MPI_DOUBLE, MPI_MAX, world);
    depth = g[1] + g[0] + cbrt(g[2]);
  }
  depth_ready = 1;
}

// a pre-crack end is a tip when the body fills at least 3/4 of the disc of
// radius 2h about it (an end outside the plate, or at its edge, is not) and
// it does not lie on another pre-crack (within 1e-3 h: the joint of a kinked
// or branched pre-crack given as several segments, or an end on a crack)
void TLSPHCrackTips::find_tips()
{
  ready = 1;
  list.clear();
  std::vector<std::array<double, 2>> ends;
  std::vector<std::array<double, 4>> traces;
  for (const auto &c : pair->cracks) {
    // 3D: through-thickness cracks only, a parallelogram with one edge
    // along z; its trace in the xy plane is tracked (the crack surface is
    // that trace extruded through the thickness)
    if (pair->dim == 3 && !(c[6] == c[0] && c[7] == c[1]) && !(c[3] == c[0] && c[4] == c[1]))
      error->all(FLERR, "pair tlsph/damage: 'criterion tip' in 3D needs pre-cracks through "
                        "the thickness (a parallelogram with one edge along z)");
    const auto t = crack_trace(pair->dim, c);
    ends.push_back({t[0], t[1]});
    ends.push_back({t[2], t[3]});
    traces.push_back(t);
  }
  std::vector<double> vol;
  volume_near(ends, 2.0 * pair->h, vol);
  const double full = M_PI * 4.0 * pair->h * pair->h * depth;
  for (size_t e = 0; e < ends.size(); e++) {
    if (vol[e] < 0.75 * full) continue;
    const auto &E = ends[e], &O = ends[e ^ 1];
    bool joint = false;
    for (size_t k = 0; k < traces.size() && !joint; k++)
      joint = k != e / 2 &&
          TLSPH::point_segment_distance(E.data(), &traces[k][0], &traces[k][2]) < 1.0e-3 * pair->h;
    if (joint) {
      if (comm->me == 0)
        utils::logmesg(lmp, "pair tlsph/damage: pre-crack end ({:.6g}, {:.6g}) lies on another "
                            "pre-crack: not a tip\n", E[0], E[1]);
      continue;
    }
    CrackTip tp;
    tp.path = {O, E};
    const double L = std::hypot(E[0] - O[0], E[1] - O[1]);
    tp.t[0] = (E[0] - O[0]) / L;
    tp.t[1] = (E[1] - O[1]) / L;
    tp.seg = tp.own = 0.0;
    tp.alive = 1;
    tp.growing = 0;
    list.push_back(tp);
    if (comm->me == 0)
      utils::logmesg(lmp, "pair tlsph/damage: crack tip at ({:.6g}, {:.6g}), direction ({:.4f}, "
                          "{:.4f}); E' {:.6g} G_c {:.6g} c_R {:.6g}\n", E[0], E[1], tp.t[0], tp.t[1],
                     Eprime, Gc, cR);
  }
}


/* kfit j: the domain J-integral (tlsph_crack.h, j_integrand) of each tip in
   'live', along the unit direction dir (2 per tip: the direction of the
   faces its K_I / K_II are measured on, below), over the particles whose
   reference position lies within jr2 h of
   the tip (a cylinder through the thickness in 3D), per unit depth, all
   ranks. Each particle's F, P and W are those of this step's deformation
   pass (grow runs after it; the bonds this step's growth cuts are not yet
   cut), read from the pair's per-atom arrays, not computed again (with the
   conservative hourglass form the stored P carries the hourglass term: P
   then comes from the law). The sums run over the particles in ascending
   order. The inertia term (the area integral of
   rho0 (a . u_,1 - v . v_,1) q) is zero for a crack at rest and for one
   running steadily, and it falls with the domain (as r2^3/2 against J's
   r2^0), which shrinks with h; but a stress wave that passes a crack at
   rest (a field that changes as it moves) makes J without it read an
   energy release rate the crack does not have. 'jinertia yes' adds it: its
   velocity part here, with this pass's velocities (those of T) and
   L = dv/dX over each particle's intact bonds; its force part, f . H e q
   (m a = f), is each tip's jf, summed at the end of the last step where
   the step's forces are known (inertia_forces): one step behind, as the
   acceleration, known only after the force pass, would be. */
// how many particles ahead j_integrals fetches a domain particle's rows
static constexpr int J_AHEAD = 6;

/* tip a's J domain (j_st[a]), made again when the tip moved or the
   particle indices changed: the particles within r2 of its end, ascending,
   their mass, with jinertia their q, and for the ring r1 < r < r2 (where
   grad q is not zero) its particles and their gq, ex, ey, volume, rho0.
   j_integrals and inertia_forces share it: a tip that moves in a step gets
   its new domain at the step's end, which the next step's J then reads. */
const TLSPHCrackTips::Stencil &TLSPHCrackTips::j_stencil(int a)
{
  const bool have = stencil_current(j_st, a);
  Stencil &st = j_st[a];
  if (have) return st;
  const double *vfrac = atom->vfrac, *rmass = atom->rmass;
  const double r1 = jr1 * pair->h, r2 = jr2 * pair->h;
  const auto &T = list[a].path.back();
  const double lo[2] = {T[0] - r2, T[1] - r2}, hi[2] = {T[0] + r2, T[1] + r2};
  const std::vector<int> &near = candidates(st, lo, hi);
  std::vector<double> ring;
  for (int i : near) {
    const double ex = pair->x0c[i][0] - T[0], ey = pair->x0c[i][1] - T[1];
    if (ex * ex + ey * ey >= r2 * r2) continue;
    st.idx.push_back(i);
    st.w.push_back(rmass[i]);
    const double r = std::sqrt(ex * ex + ey * ey);
    double dq;
    const double q = TLSPH::ring_weight(r, r1, r2, &dq);
    if (jinertia) st.q.push_back(q);
    // (the first integral: only the ring r1 < r < r2, where grad q is
    // not zero; the inertia term, with q, over the whole disc: st.q)
    if (dq == 0.0) continue;
    st.slot.push_back(i);
    ring.insert(ring.end(), {r > 0.0 ? dq * ex / r : 0.0, r > 0.0 ? dq * ey / r : 0.0, ex, ey,
                             vfrac[i], rmass[i] / vfrac[i]});
  }
  st.w.insert(st.w.end(), ring.begin(), ring.end());
  return st;
}

const double *TLSPHCrackTips::bond_grads(int i)
{
  GradCache &gc = gcache;
  const int nlocal = atom->nlocal, dim = pair->dim, nb = pair->nbond[i];
  if (gc.stamp != cells.stamp) {
    gc.stamp = cells.stamp;
    gc.off.assign(nlocal, -1);
    gc.nb.assign(nlocal, -1);
    gc.g.clear();
  }
  if (gc.off[i] >= 0 && gc.nb[i] == nb) return gc.g.data() + gc.off[i];
  const double *g, *w;
  pair->bond_values(i, g, w);
  gc.off[i] = gc.g.size();
  gc.nb[i] = nb;
  gc.g.insert(gc.g.end(), g, g + (long) dim * nb);
  return gc.g.data() + gc.off[i];
}

void TLSPHCrackTips::j_integrals(const std::vector<int> &live, const std::vector<double> &dir,
                                 std::vector<double> &J, std::vector<double> *Imix)
{
  const int nt = live.size();
  J.assign(nt, 0.0);
  // kfit interaction: per tip J, then the interaction integrals of modes I
  // and II, and with tipdir segment the point force's (the T-stress)
  const int ni = Imix ? (need_t() ? 3 : 2) : 0, nw = 1 + ni;
  double **v = atom->v;
  // the stored P is the law's unless the conservative hourglass term is in it
  const bool law_P = pair->hg_form == 2 && pair->gamma != 0.0;
  // each domain's particles, and its momentum and mass (all ranks): J is
  // taken in the frame of the domain's mean velocity. In that of the
  // continuum a uniform velocity changes nothing (its kinetic energy has
  // zero divergence), but the particle sum of T grad q is not exactly zero,
  // and a body in flight (T >> W) would drown J in that sum's error.
  // (the particles of each domain and their gq, ex, ey: kept while the tip
  // stands, Stencil; gq zero inside r1)
  std::vector<double> pm(4 * nt, 0.0), pmall(4 * nt, 0.0);
  for (int a = 0; a < nt; a++) {
    const Stencil &st = j_stencil(live[a]);
    // (in registers: the same sums in the same order)
    const int nd = st.idx.size();
    double p0 = 0.0, p1 = 0.0, p2 = 0.0, ms = 0.0;
    for (int m = 0; m < nd; m++) {
      // (the domain's rows are scattered over the per-atom arrays: fetched
      // a few particles ahead, which leaves the sums as they are)
      if (m + J_AHEAD < nd) __builtin_prefetch(v[0] + 3 * (bigint) st.idx[m + J_AHEAD]);
      const double *vi = v[0] + 3 * (bigint) st.idx[m], mi = st.w[m];
      p0 += mi * vi[0];
      p1 += mi * vi[1];
      p2 += mi * vi[2];
      ms += mi;
    }
    pm[4 * a] = p0, pm[4 * a + 1] = p1, pm[4 * a + 2] = p2, pm[4 * a + 3] = ms;
  }
  MPI_Allreduce(pm.data(), pmall.data(), 4 * nt, MPI_DOUBLE, MPI_SUM, world);
  std::vector<double> mine(nw * nt, 0.0), all(nw * nt, 0.0);
  for (int a = 0; a < nt; a++) {
    const Stencil &st = j_st[live[a]];
    const double e[3] = {dir[2 * a], dir[2 * a + 1], 0.0};
    double vm[3] = {0.0, 0.0, 0.0};
    if (pmall[4 * a + 3] > 0.0)
      for (int d = 0; d < 3; d++) vm[d] = pmall[4 * a + d] / pmall[4 * a + 3];
    // (the per-atom arrays are contiguous, rows of 9 and 3: no row pointers)
    const double *Fs = pair->F[0], *Ps = pair->P[0], *vs = v[0];
    const double *psi = pair->psi;
    const double *rw = st.w.data() + st.idx.size();
    double Ja = 0.0, I1[3] = {0.0, 0.0, 0.0};
    const size_t nr = st.slot.size();
    for (size_t m = 0; m < nr; m++, rw += 6) {
      const int i = st.slot[m];
      if (m + J_AHEAD < nr) {
        const bigint k = st.slot[m + J_AHEAD];
        for (const double *r : {Fs + 9 * k, Ps + 9 * k}) {
          __builtin_prefetch(r);
          __builtin_prefetch(r + 8);
        }
        __builtin_prefetch(vs + 3 * k);
        __builtin_prefetch(psi + k);
      }
      const double gq[3] = {rw[0], rw[1], 0.0};
      const double *F = Fs + 9 * (bigint) i, *P = Ps + 9 * (bigint) i, *vi = vs + 3 * (bigint) i;
      double W = psi[i], Fl[9], Pl[9];
      if (law_P) {
        for (int k = 0; k < 9; k++) Fl[k] = F[k];
        W = pair->pk1_stress(i, Fl, Pl);
        P = Pl;
      }
      const double vr[3] = {vi[0] - vm[0], vi[1] - vm[1], vi[2] - vm[2]};
      Ja += rw[4] * TLSPH::j_integrand(F, P, W, rw[5], vr, e, gq);
      if (Imix) {
        const double X[3] = {rw[2], rw[3], 0.0};
        double o[3];
        TLSPH::interaction_integrand(F, P, X, e, gq, mu, kappa, o, ni);
        for (int k = 0; k < ni; k++) I1[k] += rw[4] * o[k];
      }
    }
    if (jinertia) {
      // the velocity part of the inertia term: - q m (v - vm) . (L e)
      // over the whole disc (q = 1 inside r1); L over the intact bonds
      const auto vrows = TLSPH::StridedRows{vs, 3};
      const int nd = st.idx.size();
      for (int m = 0; m < nd; m++) {
        const int i = st.idx[m];
        double L[9];
        const double *g = bond_grads(i);
        if (pair->dim == 2)
          TLSPH::velocity_gradient_bonds<2>(vrows, i, pair->bond_view<2>(i, g, nullptr),
                                            pair->nbond[i], L);
        else
          TLSPH::velocity_gradient_bonds<3>(vrows, i, pair->bond_view<3>(i, g, nullptr),
                                            pair->nbond[i], L);
        const double *vi = vs + 3 * (bigint) i, mi = st.w[m];
        const double mv[3] = {mi * (vi[0] - vm[0]), mi * (vi[1] - vm[1]), mi * (vi[2] - vm[2])};
        Ja -= st.q[m] * TLSPH::j_inertia_velocity(L, mv, e);
      }
    }
    mine[nw * a] = Ja;
    for (int k = 0; k < ni; k++) mine[nw * a + 1 + k] = I1[k];
  }
  MPI_Allreduce(mine.data(), all.data(), nw * nt, MPI_DOUBLE, MPI_SUM, world);
  for (int a = 0; a < nt; a++) {
    double Ja = all[nw * a];
    // the force part, summed at the end of the last step (all ranks)
    if (jinertia) {
      const CrackTip &tp = list[live[a]];
      Ja += tp.jf[0] * dir[2 * a] + tp.jf[1] * dir[2 * a + 1];
    }
    J[a] = Ja / depth;
  }
  if (Imix) {
    Imix->assign(3 * nt, 0.0);
    for (int a = 0; a < nt; a++)
      for (int m = 0; m < ni; m++) (*Imix)[3 * a + m] = all[nw * a + 1 + m] / depth;
  }
}

/* jinertia: each live tip's jf, the force part of J's inertia term
   (tlsph_crack.h, j_inertia_force) summed over its J domain, q-weighted,
   all ranks: at the end of every step of a run, and after the set-up force
   of each (a run continued from a restart file, or split in two, takes it
   again from the same forces); f is then the step's whole force, the
   fixes' and the other ranks' shares included, and F that of its pass.
   Zero outside a run (minimize: f is no inertia). */
void TLSPHCrackTips::inertia_forces()
{
  if (!jinertia || kfit < 2 || !ready) return;
  const int nt = list.size();
  std::vector<double> mine(2 * nt, 0.0), all(2 * nt, 0.0);
  if (update->whichflag == 1) {
    refresh_cells();
    double **f = atom->f;
    // (the domain that the next step's J reads: j_stencil)
    for (int a = 0; a < nt; a++) {
      if (!list[a].alive) continue;
      const Stencil &st = j_stencil(a);
      for (size_t m = 0; m < st.idx.size(); m++) {
        const int i = st.idx[m];
        double o[2];
        TLSPH::j_inertia_force(pair->F[i], f[i], o);
        mine[2 * a] += st.q[m] * o[0];
        mine[2 * a + 1] += st.q[m] * o[1];
      }
    }
  }
  MPI_Allreduce(mine.data(), all.data(), 2 * nt, MPI_DOUBLE, MPI_SUM, world);
  for (int a = 0; a < nt; a++) list[a].jf[0] = all[2 * a], list[a].jf[1] = all[2 * a + 1];
}

double TLSPHCrackTips::sample_radius(int k) const
{
  return (p_sample + 0.5 * k) * pair->h;
}

/* a segment keeps its direction until the K samples lie on it (tipseg 0:
   their reach, the last sample's distance behind the tip plus its disc) */
double TLSPHCrackTips::segment_length() const
{
  return seg > 0.0 ? seg * pair->h : sample_radius(NSAMPLE - 1) + p_disc * pair->h;
}

/* grow reads the hoop stress of a tip that starts a segment this step with
   G >= G_c, under 'tipdir hoop', or under 'branch yoffe' once it has grown
   p_split segments (and G >= 2 G_c): all of it but G is known before the
   tip is measured */
bool TLSPHCrackTips::may_read_hoop(int a, double seglen) const
{
  const CrackTip &tp = list[a];
  if (!tp.alive) return false;
  if (branch == YOFFE_STEP && tp.own >= p_split * seglen) return true;    // yoffe/step: every step
  if (tp.seg != 0.0) return false;
  return tipdir_hoop || ((branch == YOFFE || branch == YOFFE_STEP) && tp.own >= p_split * seglen);
}

// some tip may read its hoop stress this step (seglen: segment_length())
bool TLSPHCrackTips::any_may_read_hoop(double seglen) const
{
  for (int a = 0; a < (int) list.size(); a++)
    if (may_read_hoop(a, seglen)) return true;
  return false;
}

void TLSPHCrackTips::snapshot_hoop()
{
  if (!ready || update->setupflag) return;    // (the set-up call reads no hoop stress)
  const int nt = list.size();
  if ((int) hoop_snap.size() < nt) hoop_snap.resize(nt);
  const double seglen = segment_length();
  const double R = p_hoopr * pair->h + pair->h;    // (as grow: rs + rh)
  if (!any_may_read_hoop(seglen)) return;
  refresh_cells();
  std::vector<int> near;
  for (int a = 0; a < nt; a++) {
    if (!may_read_hoop(a, seglen)) continue;
    HoopSnap &hs = hoop_snap[a];
    hs.step = update->ntimestep;
    hs.idx.clear();
    hs.sig.clear();
    const auto &P = list[a].path.back();
    const double lo[2] = {P[0] - R, P[1] - R}, hi[2] = {P[0] + R, P[1] + R};
    particles_in_box(lo, hi, near);
    for (int i : near) {
      const double ex = pair->x0c[i][0] - P[0], ey = pair->x0c[i][1] - P[1];
      if (ex * ex + ey * ey > R * R) continue;
      double sig[9];
      stress_now(i, sig);
      hs.idx.push_back(i);
      hs.sig.insert(hs.sig.end(), {sig[0], sig[4], sig[1]});
    }
  }
}

/* after each deformation pass (and the tips' growth and nucleation): which
   atom each local index held, so that stress_now knows whose F the stored
   F[i] is; only when a tip may read its hoop stress in the next step (the
   tips do not change before snapshot_hoop asks) */
void TLSPHCrackTips::note_pass()
{
  if (any_may_read_hoop(segment_length())) ftag.assign(atom->tag, atom->tag + atom->nlocal);
  else ftag.clear();
}

/* the Cauchy stress of local particle i at the last deformation pass (called
   before this step's): from the stored F if it is this atom's, else (the
   atoms were sorted or migrated at a neighbor build since, or it is new on
   this rank) from its intact bonds and the positions now */
void TLSPHCrackTips::stress_now(int i, double *sig)
{
  if (i < (int) ftag.size() && ftag[i] == atom->tag[i]) {
    pair->cauchy_stress(i, sig);
    return;
  }
  double Fn[9];
  const auto xr = TLSPH::StridedRows{atom->x[0], 3};
  const int nb = pair->nbond[i];
  if (pair->dim == 2) TLSPH::deformation_gradient_bonds<2>(xr, i, pair->bonds_of<2>(i), nb, Fn);
  else TLSPH::deformation_gradient_bonds<3>(xr, i, pair->bonds_of<3>(i), nb, Fn);
  pair->cauchy_stress(i, Fn, sig);
}

/* merging: the first point, as a fraction of the move P -> Q of tip a,
   where the move meets a crack: a pre-crack's trace, the path of another tip
   (alive or not; branches share their parent's path up to the branching
   point, where a move starting there meets nothing, segment_crossing), or
   tip a's own path before its last segment; -1 if none. Each path's
   bounding box is tested first. The same on every rank (the paths and
   pre-cracks are). */
double TLSPHCrackTips::first_crossing(int a, const double *P, const double *Q)
{
  double best = -1.0;
  const double blo[2] = {MIN(P[0], Q[0]), MIN(P[1], Q[1])}, bhi[2] = {MAX(P[0], Q[0]), MAX(P[1], Q[1])};
  auto test = [&](const double *A, const double *B) {
    if (MAX(A[0], B[0]) < blo[0] || MIN(A[0], B[0]) > bhi[0] || MAX(A[1], B[1]) < blo[1] ||
        MIN(A[1], B[1]) > bhi[1])
      return;
    const double t = TLSPH::segment_crossing(P, Q, A, B);
    if (t > 0.0 && (best < 0.0 || t < best)) best = t;
  };
  for (const auto &c : pair->cracks) {
    const auto t = crack_trace(pair->dim, c);
    test(&t[0], &t[2]);
  }
  for (size_t b = 0; b < list.size(); b++) {
    const auto &path = list[b].path;
    // tip a's own last segment ends at P (the move continues it)
    const size_t nv = (b == (size_t) a) ? path.size() - 1 : path.size();
    for (size_t v = 1; v < nv; v++) test(path[v - 1].data(), path[v].data());
  }
  return best;
}

void TLSPHCrackTips::cut_newborn()
{
  // cracks born at the end of the last step (nucleate): their bonds go now,
  // before this step's deformation pass (not in the set-up call of a run,
  // which recomputes the forces of the step they were born in: a run split
  // in two, or continued from a restart file, cuts them where one run does)
  if (update->setupflag) return;
  bool any = false;
  for (const auto &tp : list) any = any || tp.newborn;
  if (!any) return;
  refresh_cells();    // (cut_path visits the cells: a neighbor build may have renumbered them)
  for (auto &tp : list)
    if (tp.newborn) {
      pair->cut_path(tp.path[0].data(), tp.path[1].data());
      tp.newborn = 0;
    }
}

/* Each step, after the deformation pass (the cracks nucleated at the end
   of the last step were cut before it, cut_newborn): for every live tip,
   the stress intensity factors from the displacement jump across the faces
   behind it (displacement correlation, samples at r = sample .. sample +
   1.5 h along its path, extrapolated to r = 0; kfit j: their size from the
   domain J-integral over this pass's F, P and W), the kink angle and
   equivalent K of the maximum tangential stress rule (Erdogan & Sih), and,
   once G = K_eq^2 / E' reaches G_c, an advance at v = c_R (1 - G_c / G)
   (Freund's equation of motion) that stops where it meets another crack
   (merging) or leaves the body. The direction is chosen at the start of a
   segment (tipseg, default the K samples' reach, 4.5 h) and kept along it;
   'branch yoffe' (or 'branch A') splits a tip with G >= 2 G_c once it has
   grown p_split segments. The bonds the advances cut are cut at once; the
   damage style then computes pass (1) again for their particles, so that
   this step's forces are those of the bonds left (as when the tips grew
   before the pass: the same measurement, from the positions of this step
   and the bonds of the last). */
void TLSPHCrackTips::grow()
{
  if (!depth_ready) measure_depth();
  if (!ready) find_tips();
  const int nt = list.size();
  if (!nt) return;
  constexpr int NK = NSAMPLE;
  const double rho = p_disc * pair->h;
  double rk[NK];
  for (int k = 0; k < NK; k++) rk[k] = sample_radius(k);
  const double seglen = segment_length();
  // sample points and the face normal there, walking back along each path
  std::vector<double> Q(nt * NK * 2), T(nt * NK * 2);
  std::vector<int> ok(nt * NK, 0);
  for (int a = 0; a < nt; a++) {
    const CrackTip &tp = list[a];
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
  // it (refresh_cells), not every particle: the work grows with the
  // number of samples, not with the body. Its sums run over the particles in
  // ascending order, as a sweep over all of them would.
  refresh_cells();
  std::vector<int> near;
  for (int a = 0; a < nt; a++) {
    if (!list[a].alive) continue;
    // the particles of the tip's samples (kept while it stands: Stencil),
    // found by one query, the box around all of them
    const bool have = stencil_current(sample_st, a);
    Stencil &st = sample_st[a];
    if (!have) {
      double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
      for (int k = 0; k < NK; k++) {
        const int q = a * NK + k;
        if (!ok[q]) continue;
        for (int d = 0; d < 2; d++) lo[d] = MIN(lo[d], Q[2 * q + d] - rho), hi[d] = MAX(hi[d], Q[2 * q + d] + rho);
      }
      const std::vector<int> &near = candidates(st, lo, hi);
      for (int k = 0; k < NK; k++) {
        const int q = a * NK + k;
        if (!ok[q]) continue;
        for (int i : near) {
          const double *X = pair->x0c[i];
          const double dx = X[0] - Q[2 * q], dy = X[1] - Q[2 * q + 1];
          const double r2 = dx * dx + dy * dy;
          if (r2 >= rho * rho) continue;
          const double w = (1.0 - r2 / (rho * rho)) * (1.0 - r2 / (rho * rho));
          // + side: to the left of the path (n = t rotated by +90 deg)
          const double dn = -T[2 * q + 1] * dx + T[2 * q] * dy;
          if (dn == 0.0) continue;
          st.idx.push_back(i);
          st.slot.push_back(6 * q + (dn > 0.0 ? 0 : 3));
          st.w.push_back(w);
        }
      }
    }
    for (size_t m = 0; m < st.idx.size(); m++) {
      const int i = st.idx[m];
      const double *X = pair->x0c[i], w = st.w[m];
      double *S = mine.data() + st.slot[m];
      S[0] += w;
      S[1] += w * (x[i][0] - X[0]);
      S[2] += w * (x[i][1] - X[1]);
    }
  }
  MPI_Allreduce(mine.data(), sums.data(), nt * NK * 6, MPI_DOUBLE, MPI_SUM, world);
  // the faces' mean direction at each tip's samples (those with particles
  // on both sides): the frame of its K_I, K_II and of the kink angle
  std::vector<double> frs(2 * nt, 0.0);
  for (int a = 0; a < nt; a++)
    for (int k = 0; k < NK; k++) {
      const int q = a * NK + k;
      const double *S = sums.data() + 6 * q;
      if (!ok[q] || !(S[0] > 0.0) || !(S[3] > 0.0)) continue;
      frs[2 * a] += T[2 * q];
      frs[2 * a + 1] += T[2 * q + 1];
    }
  // kfit j: the energy release rate of each live tip (the domain J-integral)
  // along those faces, not along the tip's last segment: just after a kink
  // the segment is shorter than the J domain's inner radius, the faces that
  // cross the domain are the parent crack's, and J along them is the parent
  // crack's energy release rate, from which the kink rule (Erdogan and Sih)
  // takes the kinked tip's (J along the new segment would add the unknown
  // term W (m . e) on the parent's faces, which are not parallel to it)
  std::vector<double> Jt(nt, 0.0), It(3 * nt, 0.0);
  if (kfit >= 2) {
    std::vector<int> live;
    std::vector<double> dir;
    for (int a = 0; a < nt; a++) {
      const double fl = std::hypot(frs[2 * a], frs[2 * a + 1]);
      if (!list[a].alive || !(fl > 0.0)) continue;
      live.push_back(a);
      dir.push_back(frs[2 * a] / fl);
      dir.push_back(frs[2 * a + 1] / fl);
    }
    std::vector<double> Jl, Il;
    // the interaction integrals: kfit interaction's mode ratio, and the
    // T-stress of tipdir segment and branch tstress (also with kfit j)
    const bool want_i = kfit == 3 || need_t();
    j_integrals(live, dir, Jl, want_i ? &Il : nullptr);
    for (size_t k = 0; k < live.size(); k++) {
      Jt[live[k]] = Jl[k];
      if (want_i)
        for (int m = 0; m < 3; m++) It[3 * live[k] + m] = Il[3 * k + m];
    }
  }

  const double dt = update->dt;
  // per tip: G of the maximum tangential stress direction, and the direction
  // a new segment would take (nd)
  std::vector<double> Gt(nt, 0.0), nd(2 * nt, 0.0), Kt(2 * nt, 0.0), tht(nt, 0.0);
  std::vector<int> want;    // list that start a new segment this step
  for (int a = 0; a < nt; a++) {
    CrackTip &tp = list[a];
    if (!tp.alive) continue;
    // the faces' jump at the samples, normal and tangential to the faces
    double rr[NK], jn[NK], jt[NK];
    const double fr[2] = {frs[2 * a], frs[2 * a + 1]};    // the frame of K_I, K_II
    int cnt = 0;
    for (int k = 0; k < NK; k++) {
      const int q = a * NK + k;
      const double *S = sums.data() + 6 * q;
      if (!ok[q] || !(S[0] > 0.0) || !(S[3] > 0.0)) continue;
      const double dux = S[1] / S[0] - S[4] / S[3], duy = S[2] / S[0] - S[5] / S[3];
      const double tx = T[2 * q], ty = T[2 * q + 1];
      rr[cnt] = rk[k];
      jn[cnt] = -ty * dux + tx * duy;
      jt[cnt] = tx * dux + ty * duy;
      cnt++;
    }
    if (cnt == 0) continue;
    // K_I, K_II (displacement correlation), the kink angle and the
    // equivalent K of the maximum tangential stress (tlsph_crack.h)
    // (kfit j: their size from J, their ratio from the correlation; kfit
    // interaction: their size from J, their ratio from the interaction
    // integrals, I_I = 2 K_I / E' and I_II = 2 K_II / E', faces that
    // overlap (I_I < 0) giving no mode I as in the correlation)
    const TLSPH::CrackK K = kfit == 1
        ? TLSPH::displacement_correlation_offset(cnt, rr, jn, jt, Eprime)
        : kfit == 2
        ? TLSPH::k_from_j(Jt[a], TLSPH::displacement_correlation(cnt, rr, jn, jt, Eprime), Eprime)
        : kfit == 3
        ? TLSPH::k_from_j(Jt[a], TLSPH::CrackK{It[3 * a] > 0.0 ? It[3 * a] : 0.0, It[3 * a + 1]}, Eprime)
        : TLSPH::displacement_correlation(cnt, rr, jn, jt, Eprime);
    double KI = K.KI, KII = K.KII;
    double th = TLSPH::mts_kink_angle(KI, KII);
    double Keq = TLSPH::mts_equivalent_K(KI, KII, th);
    Gt[a] = (Keq > 0.0) ? Keq * Keq / Eprime : 0.0;
    // kratio running: the static readings give the ratio of a running tip
    // low (tlsph_crack.h, running_ratio_factors); the ratio corrected at
    // the speed v = c_R (1 - G_c / G) of the G it gives, to a fixed point
    // (the size, from J, kept). A tip below G_c stands: its ratio is read right.
    if (kratio_run && Gt[a] >= Gc) {
      const double kn = std::hypot(K.KI, K.KII);
      for (int it = 0; it < 30; it++) {
        const double v = TLSPH::freund_speed(Gt[a], Gc, cR);
        double fI, fII;
        TLSPH::running_ratio_factors(TLSPH::running_tip(v / cs, kappa), mu, kappa, kfit == 3, fI, fII);
        const double kI = K.KI / fI, kII = K.KII / fII, f = kn / std::hypot(kI, kII);
        KI = f * kI, KII = f * kII;
        th = TLSPH::mts_kink_angle(KI, KII);
        Keq = TLSPH::mts_equivalent_K(KI, KII, th);
        const double G = (Keq > 0.0) ? Keq * Keq / Eprime : 0.0, dG = G - Gt[a];
        Gt[a] = G;
        if (!(std::fabs(dG) > 1.0e-12 * G) || G < Gc) break;
      }
    }
    Kt[2 * a] = KI;
    Kt[2 * a + 1] = KII;
    tht[a] = th;
    // tipdir segment, branch tstress: the T-stress (I of the point force = T / E')
    const double Ts = (kfit >= 2 && need_t()) ? Eprime * It[3 * a + 2] : 0.0;
    tp.KI = KI, tp.KII = KII, tp.G = Gt[a], tp.kink = th, tp.T = Ts;
    tp.speed = 0.0;
    if (Gt[a] < Gc || tp.seg != 0.0) continue;
    // a new segment: the kink angle turns the direction of the faces that
    // K was measured on (not the last segment's, which may already have turned)
    const double fl = std::hypot(fr[0], fr[1]);
    const double thd = tipdir_seg && tp.growing ? TLSPH::segment_kink_angle(KI, KII, Ts, seglen) : th;
    const double c = cos(thd), sn = sin(thd), f0 = fr[0] / fl, f1 = fr[1] / fl;
    nd[2 * a] = c * f0 - sn * f1;
    nd[2 * a + 1] = sn * f0 + c * f1;
    want.push_back(a);
  }
  // the set-up force call of a run measures the tips but moves none: the
  // last step of the run before moved them at these same positions, so a run
  // split in two, or continued from a restart file, grows them as one run
  if (update->setupflag) return;

  // 'tipdir hoop': the new direction where the hoop stress on the circle of
  // radius 2h about the tip is largest (within +-80 deg of the current
  // direction; stresses interpolated over discs of radius h, which never
  // reach the faces behind the tip; the stress of the last step's pass,
  // kept by snapshot_hoop before this one: both rules were set up reading
  // it, and branch yoffe's split depends on which step's stress it reads,
  // doc/pair_tlsph_damage.rst, "Which step's stress the hoop rules read")
  // 'branch yoffe': a tip with G >= 2 G_c branches where the hoop stress
  // about it has two maxima, one each side of its direction (Yoffe's
  // instability of a fast crack); the branches take those two directions
  std::vector<double> bdir(2 * nt, 0.0);
  std::vector<int> bsplit(nt, 0);
  // ('branch yoffe/step': tested at every step, not only where a segment
  // starts; the tips that read their hoop stress are then those of want
  // and any other with G >= 2 G_c)
  const int yoffe = (branch == YOFFE || branch == YOFFE_STEP), yoffe_step = (branch == YOFFE_STEP);
  auto yoffe_candidate = [&](int a) {
    return yoffe && Gt[a] >= 2.0 * Gc && list[a].own >= p_split * seglen &&
        (yoffe_step || list[a].seg == 0.0);
  };
  std::vector<int> hw;    // the tips that read their hoop stress, ascending
  {
    size_t m = 0;
    for (int a = 0; a < nt; a++) {
      const bool in_want = m < want.size() && want[m] == a;
      if (in_want) m++;
      if ((in_want && tipdir_hoop) || yoffe_candidate(a)) hw.push_back(a);
    }
  }
  if (!hw.empty()) {
    constexpr int NA = 33;
    const double rs = p_hoopr * pair->h, rh = pair->h, dth = 5.0 * M_PI / 180.0;
    const int nw = hw.size();
    std::vector<double> hm(nw * NA * 4, 0.0), hs(nw * NA * 4, 0.0), ang(nw * NA);
    for (int w = 0; w < nw; w++) {
      const CrackTip &tp = list[hw[w]];
      const double phi0 = atan2(tp.t[1], tp.t[0]);
      for (int j = 0; j < NA; j++) ang[w * NA + j] = phi0 + (j - NA / 2) * dth;
    }
    // each tip's sums over the particles near it, in ascending order, with
    // their stress of the last step's pass (snapshot_hoop)
    for (int w = 0; w < nw; w++) {
      const int a = hw[w];
      const HoopSnap *hs = a < (int) hoop_snap.size() ? &hoop_snap[a] : nullptr;
      if (!hs || hs->step != update->ntimestep)
        error->one(FLERR, "pair tlsph/damage: internal: no hoop stress kept for tip {} at step {}", a,
                   update->ntimestep);
      const auto &P = list[a].path.back();
      for (size_t m = 0; m < hs->idx.size(); m++) {
        const double *X = pair->x0c[hs->idx[m]];
        const double *sig = hs->sig.data() + 3 * m;
        for (int j = 0; j < NA; j++) {
          const double cx = P[0] + rs * cos(ang[w * NA + j]), cy = P[1] + rs * sin(ang[w * NA + j]);
          const double r2 = (X[0] - cx) * (X[0] - cx) + (X[1] - cy) * (X[1] - cy);
          if (r2 >= rh * rh) continue;
          const double wt = (1.0 - r2 / (rh * rh)) * (1.0 - r2 / (rh * rh));
          double *H = hm.data() + 4 * (w * NA + j);
          H[0] += wt;
          H[1] += wt * sig[0];
          H[2] += wt * sig[1];
          H[3] += wt * sig[2];
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
        hoop[j] = TLSPH::hoop_stress(sx, sy, sxy, ang[w * NA + j]);
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
      const int a = hw[w];
      if (tipdir_hoop) {
        int jm = 0;
        for (int j = 1; j < NA; j++)
          if (hoop[j] > hoop[jm]) jm = j;
        const double phi = peak(jm);
        nd[2 * a] = cos(phi);
        nd[2 * a + 1] = sin(phi);
      }
      if (yoffe_candidate(a)) {
        // a smooth profile and its maxima each side of the line (tlsph_crack.h)
        const double phi0 = ang[w * NA + NA / 2];
        double u[NA];
        int okh[NA];
        for (int j = 0; j < NA; j++) u[j] = ang[w * NA + j] - phi0, okh[j] = !(hoop[j] < -1.0e299);
        const TLSPH::YoffeBranches yb = TLSPH::yoffe_branches(NA, u, hoop.data(), okh, p_window);
        const double *cf = yb.cf;
        const double bl = yb.bl, br = yb.br, ul = yb.ul, ur = yb.ur;
        if (getenv("TLSPH_TIP_TRACE") && comm->me == 0) {
          std::string line = fmt::format("hoop-trace {} {} G/Gc {:.3f}:", update->ntimestep, a,
                                         Gt[a] / Gc);
          for (int j = 0; j < NA; j += 2) line += fmt::format(" {:.3g}", hoop[j]);
          line += fmt::format(" | fit {:.3g} {:.3g} {:.3g} {:.3g} {:.3g} | maxima {:.1f} {:.1f}", cf[0],
                              cf[1], cf[2], cf[3], cf[4], bl > 0 ? ul * 180 / M_PI : 0.0,
                              br > 0 ? ur * 180 / M_PI : 0.0);
          utils::logmesg(lmp, line + "\n");
        }
        if (yb.split) {
          bdir[2 * a] = phi0 + ul;
          bdir[2 * a + 1] = phi0 + ur;
          bsplit[a] = 1;
        }
      }
    }
  }

  // 'branch tstress': a tip with G >= 2 G_c that has grown p_split segments
  // branches, at any step, where the hoop stress of its two-term field (K_I,
  // K_II, T) at the material's distance r_c has a maximum on each side of
  // its line (tlsph_crack.h, tstress_branches); the branches take those
  // directions, from the faces' direction K and T were measured in.
  // 'branch tstress/dynamic': the same with the singular field of a tip
  // running at the speed it runs at now, v = c_R (1 - G_c / G), and its K
  // from G at that speed (tlsph_crack.h, running_tip, running_k)
  if (tstress_rule())
    for (int a = 0; a < nt; a++) {
      const CrackTip &tp = list[a];
      if (!tp.alive || Gt[a] < 2.0 * Gc || tp.own < p_split * seglen) continue;
      const double fl = std::hypot(frs[2 * a], frs[2 * a + 1]);
      if (!(fl > 0.0)) continue;
      const bool dyn = branch == TSTRESS_DYNAMIC;
      const double v = TLSPH::freund_speed(Gt[a], Gc, cR);
      const TLSPH::RunningTip rt = TLSPH::running_tip(dyn ? v / cs : 0.0, kappa);
      double KI = tp.KI, KII = tp.KII;
      TLSPH::running_k(rt, kappa, KI, KII);
      const TLSPH::YoffeBranches tb = TLSPH::tstress_branches(KI, KII, tp.T, p_rc, p_window, rt);
      if (!tb.split) continue;
      const double phi = atan2(frs[2 * a + 1], frs[2 * a]);
      bdir[2 * a] = phi + tb.ul;
      bdir[2 * a + 1] = phi + tb.ur;
      bsplit[a] = 1;
      if (comm->me == 0)
        utils::logmesg(lmp, "pair tlsph/damage: step {} tip {}: T sqrt(2 pi r_c) / K_I = {:.3f}{}, "
                            "branches at {:.1f} and {:.1f} deg\n", update->ntimestep, a,
                       tp.T * sqrt(2.0 * M_PI * p_rc) / KI,
                       dyn ? fmt::format(" at v = {:.3f} c_s (K_I {:.4g} at speed)", v / cs, KI) : " (> 3/8)",
                       tb.ul * 180.0 / M_PI, tb.ur * 180.0 / M_PI);
    }

  std::vector<CrackTip> born;
  std::vector<int> moved;
  for (int a = 0; a < nt; a++) {
    CrackTip &tp = list[a];
    if (!tp.alive || Gt[a] < Gc) continue;
    const double G = Gt[a];
    const double v = TLSPH::freund_speed(G, Gc, cR);
    tp.speed = v;
    double P[2] = {tp.path.back()[0], tp.path.back()[1]};
    // a split ('branch A' where a segment starts, 'branch yoffe' where the
    // hoop stress has two maxima: at a segment's start, or with yoffe/step
    // at any step) or a new segment
    const bool split =
        bsplit[a] || (branch > 0.0 && tp.seg == 0.0 && G >= 2.0 * Gc && tp.own >= p_split * seglen);
    if (tp.seg == 0.0 || split) {
      const double t0 = nd[2 * a], t1 = nd[2 * a + 1];
      if (comm->me == 0 && !tp.growing)
        utils::logmesg(lmp, "pair tlsph/damage: step {} t {:.6g}: tip {} at ({:.6g}, {:.6g}) "
                            "grows, K_I {:.4g} K_II {:.4g} kink {:.2f} deg\n", update->ntimestep,
                       update->atime + (update->ntimestep - update->atimestep) * dt, a, P[0], P[1],
                       Kt[2 * a], Kt[2 * a + 1], tht[a] * 180.0 / M_PI);
      tp.growing = 1;
      if (split) {
        for (int sgn = -1; sgn <= 1; sgn += 2) {
          CrackTip b = tp;
          if (bsplit[a]) {
            const double phi = bdir[2 * a + (sgn > 0 ? 1 : 0)];
            b.t[0] = cos(phi);
            b.t[1] = sin(phi);
          } else {
            const double cb = cos(sgn * branch), sb = sin(sgn * branch);
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
                         G / Gc);
        continue;
      }
    }
    if (tp.seg == 0.0) {
      const double t0 = nd[2 * a], t1 = nd[2 * a + 1];
      tp.t[0] = t0;
      tp.t[1] = t1;
      tp.path.push_back({P[0], P[1]});
      if (comm->me == 0 && getenv("TLSPH_TIP_TRACE"))
        utils::logmesg(lmp, "tip-trace {} {} {:.6g} {:.6g} {:.4g} {:.4g} {:.4g} {:.3f} {:.2f} {:.4g}\n",
                       update->ntimestep, a, P[0], P[1], Kt[2 * a], Kt[2 * a + 1], G / Gc,
                       v / cR, atan2(t1, t0) * 180.0 / M_PI, tp.T);
    }
    double da = v * dt;
    double Pn[2] = {P[0] + da * tp.t[0], P[1] + da * tp.t[1]};
    // merging: a tip whose move meets another crack (a pre-crack, another
    // tip's path, or its own further back) stops where it meets it
    const double tm = first_crossing(a, P, Pn);
    if (tm > 0.0) {
      da *= tm;
      Pn[0] = P[0] + da * tp.t[0];
      Pn[1] = P[1] + da * tp.t[1];
    }
    pair->cut_path(P, Pn);
    tp.path.back() = {Pn[0], Pn[1]};
    tp.seg += da;
    tp.own += da;
    if (tp.seg >= seglen) tp.seg = 0.0;
    if (tm > 0.0) {
      tp.alive = 0;
      if (comm->me == 0)
        utils::logmesg(lmp, "pair tlsph/damage: step {} tip {} stops at ({:.6g}, {:.6g}), "
                            "where it meets another crack\n", update->ntimestep, a, Pn[0], Pn[1]);
      continue;
    }
    moved.push_back(a);
  }
  // new branches take their first step next time; live list that left the body stop
  for (auto &b : born) list.push_back(b);
  if (!born.empty()) {
    int nlive = 0;
    for (const auto &tp : list) nlive += tp.alive;
    if (nlive > 1000)
      error->all(FLERR, "pair tlsph/damage: step {}: {} live crack list (branching runs away; "
                        "with 'branch A' every tip with G >= 2 G_c splits): stopped", update->ntimestep,
                 nlive);
  }
  if (!moved.empty()) {
    std::vector<std::array<double, 2>> pts;
    for (int a : moved) pts.push_back(list[a].path.back());
    std::vector<double> vol;
    volume_near(pts, pair->h, vol);
    for (size_t p = 0; p < moved.size(); p++)
      if (vol[p] < 0.4 * M_PI * pair->h * pair->h * depth) {
        list[moved[p]].alive = 0;
        if (comm->me == 0)
          utils::logmesg(lmp, "pair tlsph/damage: step {} tip {} stops at ({:.6g}, {:.6g}), "
                              "outside the body\n", update->ntimestep, moved[p], pts[p][0], pts[p][1]);
      }
  }
}

/* Nucleation (pair_coeff strength sigma_t): a crack is born where the
   kernel-averaged stress's largest principal value reaches the tensile
   strength, away from the cracks there are. Every step, after the
   deformation pass (each local particle's F is this step's), not in the
   set-up call:
   1. the local particles whose own in-plane principal stress reaches
      sigma_t and that lie at least L from every crack (a pre-crack, a tip's
      path) are the candidates (the average over a disc never exceeds the
      largest value in it, so no other particle can nucleate), all ranks;
   2. at each candidate's reference position the stress averaged over the
      particles within h (weights (1 - r^2/h^2)^2, all ranks, through the
      thickness in 3D), and its principal value s1 and direction;
   3. in the order of s1 (to 1e-9 sigma_t; ties: the smaller atom ID), a
      candidate with s1 >= sigma_t nucleates unless it lies within 2 L of a
      crack born before it this step;
   4. the crack: a straight cut of length 2 L through it (half a particle
      spacing beside it: a particle on the line would be on neither face),
      normal to the principal direction (in the reference configuration; the
      rotation since is neglected), L = nucleation_half_length (Irwin's a_c,
      at least half the tip's reach: tlsph_crack.h), with a tip at each end,
      as a pre-crack's; a tip outside the body (a crack born at a surface)
      stops at once, so the crack is an edge crack. Its bonds are cut at the
      start of the next step (cut_newborn: this step's forces are those of the
      bonds its F was made from); the new tips carry that mark, also in a
      restart file. */
void TLSPHCrackTips::nucleate()
{
  if (!(sigma_t > 0.0) || update->setupflag) return;
  if (!ready) find_tips();
  const double h = pair->h;
  if (!depth_ready) measure_depth();
  const double reach = std::max(seg > 0.0 ? seg * h : (p_sample + 1.5 + p_disc) * h,
                                kfit >= 2 ? jr2 * h : 0.0);
  const double L = TLSPH::nucleation_half_length(Eprime, Gc, sigma_t, reach);
  // the cracks there are: pre-crack traces and the tips' paths
  std::vector<std::array<double, 4>> segs;
  for (const auto &c : pair->cracks) segs.push_back(crack_trace(pair->dim, c));
  for (const auto &tp : list)
    for (size_t v = 1; v < tp.path.size(); v++)
      segs.push_back({tp.path[v - 1][0], tp.path[v - 1][1], tp.path[v][0], tp.path[v][1]});
  auto clear_of_cracks = [&](const double *X) {
    for (const auto &sg : segs)
      if (std::fabs(X[0] - 0.5 * (sg[0] + sg[2])) <= L + 0.5 * std::fabs(sg[2] - sg[0]) &&
          std::fabs(X[1] - 0.5 * (sg[1] + sg[3])) <= L + 0.5 * std::fabs(sg[3] - sg[1]) &&
          TLSPH::point_segment_distance(X, &sg[0], &sg[2]) < L)
        return false;
    return true;
  };
  // 1. candidates (atom ID, reference x, y, particle spacing)
  std::vector<double> mine;
  double sig[3];
  std::vector<int> over;
  pair->principal_screen_xy(sigma_t, over);
  for (int i : over) {
    if (clear_of_cracks(pair->x0c[i]))
      mine.insert(mine.end(), {(double) atom->tag[i], pair->x0c[i][0], pair->x0c[i][1],
                               pair->dim == 2 ? sqrt(atom->vfrac[i] / depth) : cbrt(atom->vfrac[i])});
  }
  int nm = mine.size(), nprocs = comm->nprocs;
  std::vector<int> counts(nprocs), displs(nprocs, 0);
  MPI_Allgather(&nm, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  for (int p = 1; p < nprocs; p++) displs[p] = displs[p - 1] + counts[p - 1];
  const int ntot = displs[nprocs - 1] + counts[nprocs - 1];
  if (ntot == 0) return;
  std::vector<double> all(ntot);
  MPI_Allgatherv(mine.data(), nm, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE,
                 world);
  const int nc = ntot / 4;
  std::vector<int> order(nc);
  for (int c = 0; c < nc; c++) order[c] = c;
  std::sort(order.begin(), order.end(), [&](int p, int q) { return all[4 * p] < all[4 * q]; });
  // 2. the averaged stress at each candidate
  refresh_cells();
  std::vector<double> part(4 * (size_t) nc, 0.0), sums(4 * (size_t) nc, 0.0);
  std::vector<int> near;
  for (int k = 0; k < nc; k++) {
    const double *C = &all[4 * order[k] + 1];
    const double lo[2] = {C[0] - h, C[1] - h}, hi[2] = {C[0] + h, C[1] + h};
    particles_in_box(lo, hi, near);
    for (int i : near) {
      const double dx = pair->x0c[i][0] - C[0], dy = pair->x0c[i][1] - C[1];
      const double r2 = dx * dx + dy * dy;
      if (r2 >= h * h) continue;
      const double w = (1.0 - r2 / (h * h)) * (1.0 - r2 / (h * h));
      pair->cauchy_stress_xy(i, sig);
      double *S = &part[4 * (size_t) k];
      S[0] += w;
      S[1] += w * sig[0];
      S[2] += w * sig[1];
      S[3] += w * sig[2];
    }
  }
  MPI_Allreduce(part.data(), sums.data(), 4 * nc, MPI_DOUBLE, MPI_SUM, world);
  std::vector<TLSPH::Principal2> pr(nc, TLSPH::Principal2{-1.0e300, 0.0});
  std::vector<int> rank;
  for (int k = 0; k < nc; k++) {
    const double *S = &sums[4 * (size_t) k];
    if (!(S[0] > 0.0)) continue;
    pr[k] = TLSPH::principal_stress_2d(S[1] / S[0], S[2] / S[0], S[3] / S[0]);
    if (pr[k].s1 >= sigma_t) rank.push_back(k);
  }
  if (rank.empty()) return;
  // s1 to 1e-9 sigma_t, so that round-off (the ranks sum in another order)
  // does not reorder equal stresses (a uniform field): those go by atom ID
  std::vector<long long> key(nc, 0);
  for (int k : rank) key[k] = std::llround(pr[k].s1 / (1.0e-9 * sigma_t));
  std::stable_sort(rank.begin(), rank.end(), [&](int p, int q) { return key[p] > key[q]; });
  // 3. away from each other
  std::vector<int> born;
  for (int k : rank) {
    const double *C = &all[4 * order[k] + 1];
    bool clear = true;
    for (int b : born)
      if (std::hypot(C[0] - all[4 * order[b] + 1], C[1] - all[4 * order[b] + 2]) < 2.0 * L) clear = false;
    if (clear) born.push_back(k);
    if (comm->me == 0 && getenv("TLSPH_TIP_TRACE"))
      utils::logmesg(lmp, "nucleation-trace {} atom {} s1 {:.10g} at ({:.6g}, {:.6g}){}\n", update->ntimestep,
                     (tagint) all[4 * order[k]], pr[k].s1, C[0], C[1], clear ? " nucleates" : "");
  }
  // 4. the new cracks, each with its two tips
  const size_t first = list.size();
  std::vector<std::array<double, 2>> ends;
  for (size_t n = 0; n < born.size(); n++) {
    const int k = born[n];
    const double *C = &all[4 * order[k] + 1];
    // the cut passes half a particle spacing beside the particle, along the
    // principal direction n (oriented n_x > 0, or n_y > 0 when n_x is nil to
    // round-off), so that no particle lies on it (a particle on a crack's line
    // would be on neither face) and on a lattice it runs midway between two
    // rows, as the decks' pre-cracks do
    double nx = cos(pr[k].phi), ny = sin(pr[k].phi);
    if (nx < -1.0e-9 || (std::fabs(nx) <= 1.0e-9 && ny < 0.0)) nx = -nx, ny = -ny;
    const double tx = -ny, ty = nx, off = 0.5 * C[2];
    const double M[2] = {C[0] + off * nx, C[1] + off * ny};
    const double A[2] = {M[0] - L * tx, M[1] - L * ty}, B[2] = {M[0] + L * tx, M[1] + L * ty};
    for (int sgn = 1; sgn >= -1; sgn -= 2) {
      CrackTip tp;
      tp.path = sgn > 0 ? std::vector<std::array<double, 2>>{{A[0], A[1]}, {B[0], B[1]}}
                        : std::vector<std::array<double, 2>>{{B[0], B[1]}, {A[0], A[1]}};
      tp.t[0] = sgn * tx;
      tp.t[1] = sgn * ty;
      tp.seg = tp.own = 0.0;
      tp.alive = 1;
      tp.growing = 0;
      tp.newborn = 1;
      list.push_back(tp);
      ends.push_back(tp.path.back());
    }
    if (comm->me == 0)
      utils::logmesg(lmp, "pair tlsph/damage: step {} t {:.6g}: a crack nucleates at ({:.6g}, {:.6g}) "
                          "(atom {}), principal stress {:.4g} >= strength {:.4g}, direction ({:.4f}, "
                          "{:.4f}), length {:.4g}: tips {} and {}\n", update->ntimestep,
                     update->atime + (update->ntimestep - update->atimestep) * update->dt, C[0], C[1],
                     (tagint) all[4 * order[k]], pr[k].s1, sigma_t, tx, ty, 2.0 * L,
                     first + 2 * n, first + 2 * n + 1);
  }
  if (ends.empty()) return;
  std::vector<double> vol;
  volume_near(ends, h, vol);
  for (size_t e = 0; e < ends.size(); e++)
    if (vol[e] < 0.4 * M_PI * h * h * depth) {
      list[first + e].alive = 0;
      if (comm->me == 0)
        utils::logmesg(lmp, "pair tlsph/damage: step {} tip {} at ({:.6g}, {:.6g}) lies outside the "
                            "body (an edge crack): it stops\n", update->ntimestep, first + e,
                       ends[e][0], ends[e][1]);
    }
}
