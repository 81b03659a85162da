/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: internal fix that owns every particle's reference partners

   Created by pair_style tlsph (style name TLSPH_BONDS, like PERI_NEIGH).
   Per atom: the global IDs of the partners found within the kernel support
   2h in the reference configuration at the first run, and one state byte
   per bond (intact, broken or pre-cracked). The rows migrate with their atom and are
   written to restart files; nothing else about a bond needs to be kept,
   because the geometric bond data are recomputed from x0 on every
   reneighboring (see PairTLSPH::build_bond_cache).
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(TLSPH_BONDS,FixTLSPHBonds)
// clang-format on
#else

#ifndef LMP_FIX_TLSPH_BONDS_H
#define LMP_FIX_TLSPH_BONDS_H

#include "fix.h"

namespace LAMMPS_NS {

class FixTLSPHBonds : public Fix {
 public:
  // PRECRACKED: removed by a pre-crack before the first step (never part of
  // the material: also left out of the 'setup' gradient correction)
  enum { BROKEN = 0, INTACT = 1, PRECRACKED = 2 };

  FixTLSPHBonds(class LAMMPS *, int, char **);
  ~FixTLSPHBonds() override;
  int setmask() override;
  void init() override;
  void init_list(int, class NeighList *) override;
  void setup_post_neighbor() override;
  void post_neighbor() override;
  void min_post_neighbor() override;
  void setup(int) override;
  void end_of_step() override;
  void post_run() override;

  double memory_usage() override;
  void grow_arrays(int) override;
  void set_arrays(int) override;
  void copy_arrays(int, int, int) override;
  // the SIMD step of the pair style sorts the local particles (PRE_EXCHANGE
  // is added to this fix's mask by the pair style when it runs that step)
  void setup_pre_exchange() override;
  void pre_exchange() override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  void write_restart(FILE *) override;
  void restart(char *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;

  // set by the pair style before the first run: reference search radius
  void set_cutoff(double cut) { cutoff = cut; }
  bool have_partners() const { return !first; }
  // work done against the hourglass and viscous forces of atom i up to now
  // (compute tlsph/energy): work_hg/work_visc minus the half kick to come
  void work_now(int i, double &hg, double &visc) const;

  int maxpartner;       // max # of partners of any atom (all ranks)
  int *npartner;        // # of partners of each atom
  int *nintact0;        // # of partners at setup (denominator of the damage)
  tagint **partner;     // global IDs of partners
  unsigned char **state;    // BROKEN, INTACT or PRECRACKED, per bond (one byte)
  // gradient correction frozen at setup (pair tlsph/damage 'correction
  // setup'): per atom [0] = 1 once set, then the correction matrix Q. It
  // migrates and restarts with the atom, so it never depends on which
  // broken partners are still present as ghosts.
  int nfrozen;          // doubles of Q kept per atom (0: none kept)
  double **frozen;
  void set_frozen_size(int n);
  double *work_hg;      // work done against hourglass forces, per atom
  double *work_visc;    // work dissipated by artificial viscosity, per atom
  class PairTLSPH *owner = nullptr;    // the pair style (set in its init_style)
  double **f_hg;        // hourglass and viscous force of this step, per atom: written
  double **f_visc;      //   by pair tlsph, turned into work in end_of_step()
  int fresh;           // 1 right after the partner search (pre-cracks are applied then)
  int check_pending;   // 1 right after the partner search: the pair checks that every
                       // particle has enough partners for a gradient (not after a restart)
  int rebuild;          // 1 after every neighbor build: the pair re-caches bonds
  bigint nbonds_total;  // all bonds (counted twice, once from each end) at setup

 private:
  // the work and force arrays current on the host (a /kk pair may hold them on the device)
  void host_arrays() const;
  void sync_host_v() const;
  int first;             // 1 until the partners have been found
  int precounted;        // 1 once the work tallies include the next half kick
  bigint tallied_step;   // step of the last tally (end_of_step or setup)
  double cutoff;         // reference search radius (2h)
  class NeighList *list;
  void find_partners();
  void tally_work(double);
};

}    // namespace LAMMPS_NS

#endif
#endif
