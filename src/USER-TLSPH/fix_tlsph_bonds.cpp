/* ----------------------------------------------------------------------
   USER-TLSPH: internal fix TLSPH_BONDS, see fix_tlsph_bonds.h
------------------------------------------------------------------------- */

#include "fix_tlsph_bonds.h"

#include "atom.h"
#include "atom_masks.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "memory.h"
#include "my_page.h"
#include "neigh_list.h"
#include "neigh_request.h"
#include "neighbor.h"
#include "pair_tlsph.h"
#include "update.h"

#include <cmath>
#include <cstring>

#ifdef LMP_KOKKOS    // compiled into a LAMMPS with the KOKKOS package (make kokkos)
#include "atom_kokkos.h"
#include "kokkos.h"
#endif

using namespace LAMMPS_NS;
using namespace FixConst;

FixTLSPHBonds::FixTLSPHBonds(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), npartner(nullptr), nintact0(nullptr), partner(nullptr), state(nullptr),
    work_hg(nullptr), work_visc(nullptr), f_hg(nullptr), f_visc(nullptr),
    list(nullptr)
{
  if (narg != 3) error->all(FLERR, "Illegal fix TLSPH_BONDS command: it takes no arguments");
  restart_global = 1;
  restart_peratom = 1;
  create_attribute = 1;
  first = 1;
  precounted = 0;
  tallied_step = -1;
  rebuild = 1;
  fresh = 0;
  check_pending = 0;
  nfrozen = 0;
  frozen = nullptr;
  cutoff = 0.0;
  nbonds_total = 0;

  // with -k on (KOKKOS): LAMMPS copies datamask_read to the host before
  // each hook of this fix and marks datamask_modify as changed there after
  // it. Every step (end_of_step) this fix reads only v and changes no atom
  // data; the partner search syncs what it needs itself (find_partners).
  // The default, ALL_MASK both, would move every atom array to the host and
  // back each step (a no-op with the host backends, not on a GPU). With a
  // /kk pair style init() makes this a Kokkos fix on the device that reads
  // nothing on the host (see there).
  datamask_read = V_MASK | MASK_MASK;
  datamask_modify = EMPTY_MASK;

  // placeholder size until the partners are known
  maxpartner = 1;
  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nmax; i++) {
    npartner[i] = 0;
    nintact0[i] = 0;
    work_hg[i] = work_visc[i] = 0.0;
    for (int d = 0; d < 3; d++) f_hg[i][d] = f_visc[i][d] = 0.0;
  }
}

FixTLSPHBonds::~FixTLSPHBonds()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(npartner);
  memory->destroy(nintact0);
  memory->destroy(partner);
  memory->destroy(state);
  memory->destroy(work_hg);
  memory->destroy(work_visc);
  memory->destroy(f_hg);
  memory->destroy(f_visc);
  memory->destroy(frozen);
}

int FixTLSPHBonds::setmask()
{
  return POST_NEIGHBOR | MIN_POST_NEIGHBOR | END_OF_STEP | POST_RUN;
}

void FixTLSPHBonds::init()
{
  // With a /kk pair style the per-step work tally runs on the device
  // (PairTLSPHKokkosT::tally_work_device), so this fix declares itself a
  // Kokkos fix on the device that reads and changes no atom data on the
  // host: LAMMPS (ModifyKokkos) then copies nothing before or after its
  // hooks, and does not switch on auto_sync for them, which would mark v as
  // changed on the host and copy it back to the device every step. Its
  // host code syncs what it reads itself (sync_host_v, find_partners).
  if (owner && owner->on_device()) {
    kokkosable = 1;
    execution_space = Device;
    datamask_read = EMPTY_MASK;
    datamask_modify = EMPTY_MASK;
  } else {
    kokkosable = 0;
    execution_space = Host;
    datamask_read = V_MASK | MASK_MASK;
    datamask_modify = EMPTY_MASK;
  }
  if (!first) return;
  // an occasional full list, used once to find the reference partners
  int irequest = neighbor->request(this, instance_me);
  neighbor->requests[irequest]->pair = 0;
  neighbor->requests[irequest]->fix = 1;
  neighbor->requests[irequest]->half = 0;
  neighbor->requests[irequest]->full = 1;
  neighbor->requests[irequest]->occasional = 1;
}

void FixTLSPHBonds::init_list(int /*id*/, NeighList *ptr)
{
  list = ptr;
}

void FixTLSPHBonds::setup_post_neighbor()
{
  if (first) find_partners();
  rebuild = 1;
}

void FixTLSPHBonds::post_neighbor()
{
  rebuild = 1;
}

void FixTLSPHBonds::min_post_neighbor()
{
  rebuild = 1;
}

/* ----------------------------------------------------------------------
   work of the hourglass and viscous forces (compute tlsph/energy)
   In velocity Verlet the force f_n of step n gives two half kicks, at the
   end of step n and at the start of step n+1, and the kinetic energy they
   change together is exactly dt f_n . (v_{n-1/2} + v_{n+1/2}) / 2
   = dt f_n . v_n, with the full-step velocity v_n known only here, after
   final_integrate. (The pair sees v_{n-1/2}: tallying with it is off by
   dt^2/(2m) f_n . f_n^total every step, a bias that does not average out; it
   overestimated the hourglass work 25-fold at Courant number 0.3.)
   So the tallies run half a kick ahead: work_now() takes it off. The very
   first setup force gives only one half kick (the start of step 1); a later
   run's setup force replaces the last force of the previous run, whose
   second half kick is already counted.
------------------------------------------------------------------------- */

void FixTLSPHBonds::setup(int /*vflag*/)
{
  if (!precounted) tally_work(0.5 * update->dt);
  precounted = 1;
  tallied_step = update->ntimestep;
  if (owner) owner->step_done();
}

void FixTLSPHBonds::end_of_step()
{
  tally_work(update->dt);
  precounted = 1;
  tallied_step = update->ntimestep;
  if (owner) owner->step_done();
}

// the /kk styles: what was copied between host and device in this run
void FixTLSPHBonds::post_run()
{
  if (!owner) return;
  owner->report_copies(update->nsteps);
  owner->report_run(update->nsteps);
}

// v current on the host, for the host code of a Kokkos run (init()); a /kk
// pair style counts it (tlsph_kk_copies.h)
void FixTLSPHBonds::sync_host_v() const
{
  if (owner && owner->kokkosable) {
    owner->host_sync(V_MASK);
    return;
  }
#ifdef LMP_KOKKOS
  if (lmp->kokkos) ((AtomKokkos *) atom)->sync(Host, V_MASK);
#endif
}

void FixTLSPHBonds::work_now(int i, double &hg, double &visc) const
{
  host_arrays();
  sync_host_v();
  // during a step the force of this step has given one half kick; the
  // tallies hold two of it once end_of_step() has run, none before. A setup
  // force has given none: the tallies hold one of it (the first run, after
  // setup()) or of the previous run's last force (later runs)
  double **v = atom->v;
  double s;
  if (update->setupflag) s = precounted ? 0.5 : 0.0;
  else s = (tallied_step == update->ntimestep) ? 0.5 : -0.5;
  s *= update->dt;
  hg = work_hg[i] + s * (f_hg[i][0] * v[i][0] + f_hg[i][1] * v[i][1] + f_hg[i][2] * v[i][2]);
  visc = work_visc[i] +
      s * (f_visc[i][0] * v[i][0] + f_visc[i][1] * v[i][1] + f_visc[i][2] * v[i][2]);
}

void FixTLSPHBonds::host_arrays() const
{
  if (owner) owner->work_to_host();
}

void FixTLSPHBonds::tally_work(double dt)
{
  if (owner && owner->tally_work_device(dt)) return;
  host_arrays();
  sync_host_v();
  double **v = atom->v;
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++) {
    work_hg[i] -= dt * (f_hg[i][0] * v[i][0] + f_hg[i][1] * v[i][1] + f_hg[i][2] * v[i][2]);
    work_visc[i] -=
        dt * (f_visc[i][0] * v[i][0] + f_visc[i][1] * v[i][1] + f_visc[i][2] * v[i][2]);
  }
}

/* ----------------------------------------------------------------------
   partners: every other atom within the reference support |X_j - X_i| < 2h
------------------------------------------------------------------------- */

void FixTLSPHBonds::find_partners()
{
  if (cutoff <= 0.0) error->all(FLERR, "TLSPH_BONDS: search radius not set by pair tlsph");
#ifdef LMP_KOKKOS
  // (datamask_read above has only v): x, x0, tag, ... to the host
  if (lmp->kokkos) ((AtomKokkos *) atom)->sync(Host, ALL_MASK);
#endif
  first = 0;
  fresh = 1;
  check_pending = 1;

  // the neighbor list is built from current positions: partners within 2h
  // of X are all in it only if no particle has moved too far from x0 yet
  {
    double **x = atom->x, **x0 = atom->x0;
    double dmax = 0.0;
    for (int i = 0; i < atom->nlocal; i++) {
      double d[3] = {x[i][0] - x0[i][0], x[i][1] - x0[i][1], x[i][2] - x0[i][2]};
      domain->minimum_image(d[0], d[1], d[2]);
      dmax = MAX(dmax, d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    }
    double dall;
    MPI_Allreduce(&dmax, &dall, 1, MPI_DOUBLE, MPI_MAX, world);
    dall = sqrt(dall);
    const double margin = 0.5 * (neighbor->cutneighmax - cutoff);
    if (dall > margin)
      error->all(FLERR, "TLSPH bonds: a particle is {:.4g} away from its reference position x0 at "
                        "the first run, more than the {:.4g} the partner search can bridge: "
                        "find the partners first (run 0) and displace afterwards, or raise the "
                        "neighbor skin", dall, margin);
  }
  neighbor->build_one(list);

  double **x0 = atom->x0;
  tagint *tag = atom->tag;
  const int nlocal = atom->nlocal;
  const int inum = list->inum;
  int *ilist = list->ilist;
  int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;
  const double cutsq = cutoff * cutoff;

  auto within = [&](int i, int j) {
    double d[3] = {x0[j][0] - x0[i][0], x0[j][1] - x0[i][1], x0[j][2] - x0[i][2]};
    domain->minimum_image(d[0], d[1], d[2]);
    const double rsq = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    return rsq < cutsq && rsq > 0.0;
  };

  for (int i = 0; i < nlocal; i++) npartner[i] = 0;
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    int *jlist = firstneigh[i];
    for (int jj = 0; jj < numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      if (within(i, j)) npartner[i]++;
    }
  }
  int mymax = 0;
  for (int i = 0; i < nlocal; i++) mymax = MAX(mymax, npartner[i]);
  MPI_Allreduce(&mymax, &maxpartner, 1, MPI_INT, MPI_MAX, world);
  const int maxfound = maxpartner;
  maxpartner = MAX(maxpartner, 1);    // the arrays have at least one column

  memory->destroy(partner);
  memory->destroy(state);
  memory->create(partner, atom->nmax, maxpartner, "tlsph/bonds:partner");
  memory->create(state, atom->nmax, maxpartner, "tlsph/bonds:state");

  bigint nmine = 0;
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    int *jlist = firstneigh[i];
    int n = 0;
    for (int jj = 0; jj < numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      if (!within(i, j)) continue;
      partner[i][n] = tag[j];
      state[i][n] = INTACT;
      n++;
    }
    npartner[i] = n;
    nintact0[i] = n;
    nmine += n;
  }
  MPI_Allreduce(&nmine, &nbonds_total, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (comm->me == 0)
    utils::logmesg(lmp, "TLSPH bonds: {} reference partners in total (max {} per particle)\n",
                   nbonds_total, maxfound);

  /* the list's pages are read only here: give them back (MyPage::init frees
     them and keeps one empty page; a later build_one would fill it again).
     Otherwise LAMMPS keeps them until the next run's init drops this
     occasional request: 0.21 kB per particle of the 2D block of
     bench/in.compare and 0.93 kB of the 3D one, in every step of the first
     run (doc/bench.md, "Memory per particle") */
  if (list->ipage)
    for (int t = 0; t < comm->nthreads; t++) list->ipage[t].init(list->oneatom, list->pgsize, 1);
}

/* ---------------------------------------------------------------------- */

double FixTLSPHBonds::memory_usage()
{
  const double n = atom->nmax;
  return 2.0 * n * (sizeof(int) + 4.0 * sizeof(double)) +
      n * maxpartner * (sizeof(tagint) + sizeof(unsigned char));
}

void FixTLSPHBonds::grow_arrays(int nmax)
{
  memory->grow(npartner, nmax, "tlsph/bonds:npartner");
  memory->grow(nintact0, nmax, "tlsph/bonds:nintact0");
  memory->grow(partner, nmax, maxpartner, "tlsph/bonds:partner");
  memory->grow(state, nmax, maxpartner, "tlsph/bonds:state");
  memory->grow(work_hg, nmax, "tlsph/bonds:work_hg");
  memory->grow(work_visc, nmax, "tlsph/bonds:work_visc");
  memory->grow(f_hg, nmax, 3, "tlsph/bonds:f_hg");
  memory->grow(f_visc, nmax, 3, "tlsph/bonds:f_visc");
  if (nfrozen) memory->grow(frozen, nmax, 1 + nfrozen, "tlsph/bonds:frozen");
}

void FixTLSPHBonds::set_frozen_size(int n)
{
  if (n == nfrozen) return;
  // a different correction: every particle recomputes and freezes it again
  nfrozen = n;
  memory->destroy(frozen);
  if (n) {
    memory->create(frozen, atom->nmax, 1 + n, "tlsph/bonds:frozen");
    for (int i = 0; i < atom->nmax; i++) frozen[i][0] = 0.0;
  }
}

void FixTLSPHBonds::set_arrays(int i)
{
  host_arrays();
  // an atom created after the bonds were found has no partners
  npartner[i] = 0;
  nintact0[i] = 0;
  work_hg[i] = work_visc[i] = 0.0;
  for (int d = 0; d < 3; d++) f_hg[i][d] = f_visc[i][d] = 0.0;
  if (nfrozen) frozen[i][0] = 0.0;
}

void FixTLSPHBonds::setup_pre_exchange()
{
  if (owner) owner->sort_particles();
}

void FixTLSPHBonds::pre_exchange()
{
  if (owner) owner->sort_particles();
}

void FixTLSPHBonds::copy_arrays(int i, int j, int /*delflag*/)
{
  host_arrays();
  npartner[j] = npartner[i];
  nintact0[j] = nintact0[i];
  work_hg[j] = work_hg[i];
  work_visc[j] = work_visc[i];
  for (int d = 0; d < 3; d++) {
    f_hg[j][d] = f_hg[i][d];
    f_visc[j][d] = f_visc[i][d];
  }
  for (int m = 0; m < npartner[j]; m++) {
    partner[j][m] = partner[i][m];
    state[j][m] = state[i][m];
  }
  for (int k = 0; k < (nfrozen ? 1 + nfrozen : 0); k++) frozen[j][k] = frozen[i][k];
}

int FixTLSPHBonds::pack_exchange(int i, double *buf)
{
  host_arrays();
  int m = 0;
  buf[m++] = npartner[i];
  buf[m++] = nintact0[i];
  buf[m++] = work_hg[i];
  buf[m++] = work_visc[i];
  for (int n = 0; n < npartner[i]; n++) {
    buf[m++] = ubuf(partner[i][n]).d;
    buf[m++] = state[i][n];
  }
  for (int k = 0; k < (nfrozen ? 1 + nfrozen : 0); k++) buf[m++] = frozen[i][k];
  return m;
}

int FixTLSPHBonds::unpack_exchange(int nlocal, double *buf)
{
  host_arrays();
  int m = 0;
  npartner[nlocal] = static_cast<int>(buf[m++]);
  nintact0[nlocal] = static_cast<int>(buf[m++]);
  work_hg[nlocal] = buf[m++];
  work_visc[nlocal] = buf[m++];
  for (int n = 0; n < npartner[nlocal]; n++) {
    partner[nlocal][n] = (tagint) ubuf(buf[m++]).i;
    state[nlocal][n] = static_cast<unsigned char>(buf[m++]);
  }
  for (int k = 0; k < (nfrozen ? 1 + nfrozen : 0); k++) frozen[nlocal][k] = buf[m++];
  return m;
}

void FixTLSPHBonds::write_restart(FILE *fp)
{
  if (comm->me != 0) return;
  double list[5] = {(double) first, (double) maxpartner, (double) nbonds_total,
                     (double) precounted, (double) nfrozen};
  int n = 5;
  int size = n * sizeof(double);
  fwrite(&size, sizeof(int), 1, fp);
  fwrite(list, sizeof(double), n, fp);
}

void FixTLSPHBonds::restart(char *buf)
{
  double *list = (double *) buf;
  first = static_cast<int>(list[0]);
  maxpartner = static_cast<int>(list[1]);
  nbonds_total = static_cast<bigint>(list[2]);
  precounted = static_cast<int>(list[3]);
  nfrozen = static_cast<int>(list[4]);
  memory->destroy(frozen);
  if (nfrozen) memory->create(frozen, atom->nmax, 1 + nfrozen, "tlsph/bonds:frozen");
  // per-atom rows arrive through unpack_restart(): make room for them
  memory->destroy(partner);
  memory->destroy(state);
  memory->create(partner, atom->nmax, maxpartner, "tlsph/bonds:partner");
  memory->create(state, atom->nmax, maxpartner, "tlsph/bonds:state");
}

int FixTLSPHBonds::pack_restart(int i, double *buf)
{
  host_arrays();
  // first value is the count of values, as LAMMPS requires
  int m = 1;
  m += pack_exchange(i, &buf[1]);
  buf[0] = m;
  return m;
}

void FixTLSPHBonds::unpack_restart(int nlocal, int nth)
{
  host_arrays();
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  m++;
  unpack_exchange(nlocal, &extra[nlocal][m]);
}

int FixTLSPHBonds::maxsize_restart()
{
  return 2 * maxpartner + 5 + (nfrozen ? 1 + nfrozen : 0);
}

int FixTLSPHBonds::size_restart(int nlocal)
{
  return 2 * npartner[nlocal] + 5 + (nfrozen ? 1 + nfrozen : 0);
}
