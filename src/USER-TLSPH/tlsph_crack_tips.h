/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: the crack tips of crack-tip tracking (pair_style tlsph/damage
   criterion tip; doc/pair_tlsph_damage.rst, "Crack-tip tracking").

   TLSPHCrackTips owns the tips: their settings (the tip keywords of the
   pair style), their paths in the reference configuration (identical on
   every MPI rank), their restart, and each step's measurement and growth
   (grow). The mechanics it applies, with no LAMMPS in them, are in
   tlsph_crack.h: the stress intensity factors (displacement correlation,
   domain J-integral), the kink rule, the speed law and the branching rule.
   The damage style keeps the bonds: a tip that grows asks it to cut the
   bonds its new piece of path crosses (PairTLSPHDamage::cut_path), and it
   reads the particles' fields through the style.
------------------------------------------------------------------------- */

#ifndef LMP_TLSPH_CRACK_TIPS_H
#define LMP_TLSPH_CRACK_TIPS_H

#include "lmptype.h"
#include "pointers.h"

#include <array>
#include <cstdio>
#include <vector>

namespace LAMMPS_NS {

class PairTLSPHDamage;

// one crack tip: its path (vertices, the last one the tip) and its state
struct CrackTip {
  std::vector<std::array<double, 2>> path;    // vertices, the last one is the tip
  double t[2];                                // direction of the current segment
  double seg;                                 // length grown on the current segment
  double own;                                 // length grown since the tip was born
  int alive, growing;
  int newborn = 0;    // nucleated at the end of the last step: its bonds are cut at the next cut_newborn
  // at the last force evaluation (not in restart files: measured every step)
  double KI = 0.0, KII = 0.0;    // stress intensity factors
  double G = 0.0;                // energy release rate of the kink direction
  double kink = 0.0;             // kink angle of the maximum tangential stress [rad]
  double T = 0.0;                // T-stress (tipdir segment; 0 otherwise)
  double speed = 0.0;            // advance speed (0: not growing)
  // jinertia: the force part of J's inertia term, per reference direction
  // x, y (tlsph_crack.h, j_inertia_force), summed over the J domain at the
  // end of the last step, all ranks (not in restart files: taken again from
  // the set-up force of each run, inertia_forces)
  double jf[2] = {0.0, 0.0};
};

class TLSPHCrackTips : protected Pointers {
 public:
  TLSPHCrackTips(LAMMPS *lmp, PairTLSPHDamage *pair);

  // the settings: defaults, then the tip keyword at arg[iarg] (returns the
  // number of words it took, 0 if arg[iarg] is not a tip keyword)
  void defaults();
  int parse(int narg, char **arg, int iarg);
  // restart: the settings (and the pair's tipmode) and every tip with its path
  void write_restart(FILE *fp, int tipmode);
  int read_restart(FILE *fp);    // returns tipmode
  // from the pair's init_style: the material's E', G_c, Rayleigh speed and
  // tensile strength (0: no nucleation)
  // E', the shear modulus and kappa (3 - 4 nu, plane stress (3 - nu) / (1 + nu)), G_c, c_R, sigma_t
  void init(double Eprime, double mu, double kappa, double Gc, double cR, double cs, double strength);
  // every step before the deformation pass: the bonds of the cracks
  // nucleated at the end of the last step are cut
  void cut_newborn();
  // every step after cut_newborn, before the deformation pass: the Cauchy
  // stress of the last pass near each tip whose hoop stress grow may read
  // this step (hoop_snap)
  void snapshot_hoop();
  // every step after the deformation pass (each local particle's F, P and W
  // are this step's): the tips found (first call), measured, turned, grown
  // and split; the damage style then redoes pass (1) for the particles
  // whose bonds they cut
  void grow();
  // after each step's nucleate: the atom of each local index (stress_now)
  void note_pass();
  // every step after grow (pair_coeff strength): new cracks where the stress
  // reaches the strength (their bonds are cut by the next cut_newborn)
  void nucleate();
  // jinertia: at the end of every step of a run and after its set-up force
  // (f, F and the tips of the step just done), each tip's jf
  void inertia_forces();

  const std::vector<CrackTip> &tips() const { return list; }
  double fracture_energy() const { return Gc; }

  // the local particles whose reference position lies in [lo, hi] (xy),
  // ascending (cells rebuilt when the bond cache is)
  void particles_in_box(const double *lo, const double *hi, std::vector<int> &out);

  // settings (the pair_style keywords)
  int tipdir_hoop;  // tipdir: 0 kink angle from K_I, K_II, 1 largest hoop stress
  int tipdir_seg;   // tipdir segment: 1 the kink from K_I, K_II and the T-stress that leaves
                    // the segment's end in mode I (Cotterell & Rice; kfit interaction)
  int kfit;         // K: 0 fit anchored at the path's end, 1 with the tip's offset fitted,
                    // 2 size from the domain J-integral (ratio: fit 0), 3 size from J,
                    // ratio from the interaction integrals over the same ring
  double jr1, jr2;  // kfit j, interaction: the J domain's ring, q = 1 inside r1, 0 beyond r2 [h]
  int jinertia;     // kfit j, interaction: 1 adds the inertia term of the dynamic J-integral
  int kratio_run;   // kratio running: K_II / K_I corrected for the tip's speed (kfit j, interaction)
  double seg;       // segment length in h (0: the sampling reach)
  double branch;    // half angle of a branching [rad] (0: never), or one of the rules below
  // the branching rules (values of branch < 0; also in the restart files)
  static constexpr double YOFFE = -1.0, YOFFE_STEP = -2.0, TSTRESS = -3.0, TSTRESS_DYNAMIC = -4.0;
  bool tstress_rule() const { return branch == TSTRESS || branch == TSTRESS_DYNAMIC; }
  // tipparam: the tip model's numerical constants (scanned in bench/tipconst.md)
  double p_sample;  // start of the K samples behind the tip [h] (samples every 0.5 h, 4)
  double p_disc;    // radius of each sample's kernel disc [h]
  double p_hoopr;   // radius of the circle the hoop stress is read on [h]
  int p_window;     // branch yoffe: largest angle of a branch from the line [deg]
  double p_split;   // a tip may split once it has grown this many segments
  double p_rc;      // branch tstress(/dynamic): the material's distance r_c of the hoop maximum [length]
  // the interaction integrals also give the T-stress (tipdir segment, branch tstress)
  bool need_t() const { return tipdir_seg || tstress_rule(); }

 private:
  PairTLSPHDamage *pair;
  std::vector<CrackTip> list;
  int ready, depth_ready;
  double Eprime, Gc, cR, cs, depth;    // cs: the shear wave speed (branch tstress/dynamic)
  double mu = 0.0, kappa = 0.0;    // the interaction integral's auxiliary fields (kfit interaction)
  double sigma_t = 0.0;    // tensile strength: cracks nucleate where the stress reaches it (0: never)
  void measure_depth();

  // the local particles in square cells of their reference positions (xy),
  // so that the tip work visits only the particles near a tip: rebuilt when
  // the bond cache is (the particle indices change only at neighbor builds)
  struct RefCells {
    double lo[2] = {0.0, 0.0}, cs = 1.0;
    int nx = 0, ny = 0;
    std::vector<int> start, idx;    // cell c holds idx[start[c] .. start[c + 1]), ascending
    std::array<int, 2> stamp = {-1, -1};
  } cells;
  void refresh_cells();

  /* Per tip, the particles its sums visit and their weights (the K samples'
     discs in grow, the J domain in j_integrals), kept while the tip stands
     and the particle indices hold: the same tip position, path vertex
     count and cells stamp. A standing tip's sums then skip the cell search
     and the distances; the entries keep the search's order, so the sums
     are the same bits. */
  struct Stencil {
    std::array<double, 2> at = {0.0, 0.0};    // the tip's position when it was made
    int nv = -1;                              // its path's vertex count then (-1: none)
    std::array<int, 2> stamp = {-1, -1};      // cells.stamp then
    std::vector<int> idx;                     // the particles, in the order of the sums
    std::vector<int> slot;                    // grow: the sample sum each adds to; j_integrals: the ring's
    std::vector<double> w;                    // grow: weight; j_integrals: mass (idx), then
                                              // gq x, gq y, ex, ey, volume, rho0 (slot)
    std::vector<double> q;                    // j_integrals with jinertia: q of each of idx
    // a growing tip: the particles of a box larger than the sums need by h
    // each way (ascending), searched again only when the box the sums need
    // leaves it or the indices change; the sums filter them as the cell
    // search's, so the same particles in the same order
    std::vector<int> cand;
    double clo[2] = {0.0, 0.0}, chi[2] = {-1.0, -1.0};
    std::array<int, 2> cstamp = {-1, -1};
  };
  /* jinertia: the corrected gradients of the bonds of the J domains'
     particles, kept per local particle while its bonds and the indices
     hold (cells.stamp, nbond): where the SIMD step keeps them only in its
     layout, bonds_of computes them again from Q_i at every call (its
     kernel and correction), which was most of the inertia term's cost */
  struct GradCache {
    std::array<int, 2> stamp = {-1, -1};
    std::vector<long> off;    // per local particle: its gradients in g (-1: none)
    std::vector<int> nb;      // its intact bonds when they were kept
    std::vector<double> g;
  } gcache;
  const double *bond_grads(int i);    // particle i's DIM x nbond[i] gradients
  std::vector<Stencil> sample_st, j_st;    // per tip (its index in list)
  const Stencil &j_stencil(int a);         // tip a's J domain, made again if stale
  // true (and st kept) if st was made for tip a as it is; else st emptied and stamped for it
  bool stencil_current(std::vector<Stencil> &v, int a);
  // the particles whose reference position may lie in [lo, hi]: st's candidates
  const std::vector<int> &candidates(Stencil &st, const double *lo, const double *hi);
  void volume_near(const std::vector<std::array<double, 2>> &pts, double R, std::vector<double> &vol);

  /* The hoop stress that 'tipdir hoop' and 'branch yoffe' read is that of
     the last step's pass (the stress the tip's K and J are measured in
     this step is this pass's): grow runs after the pass, so the stress
     near the tips that may need it is kept before it. Per tip (its index in
     list), the particles within (p_hoopr + 1) h of it, ascending, and their
     Cauchy stress xx, yy, xy; valid for the step it was taken in. */
  struct HoopSnap {
    bigint step = -1;
    std::vector<int> idx;
    std::vector<double> sig;
  };
  std::vector<HoopSnap> hoop_snap;
  // may grow read tip a's hoop stress this step (before its measurement)
  bool may_read_hoop(int a, double seglen) const;
  bool any_may_read_hoop(double seglen) const;
  double segment_length() const;
  // the K samples: NSAMPLE points behind the tip, sample k at sample_radius(k)
  static constexpr int NSAMPLE = 4;
  double sample_radius(int k) const;
  std::vector<tagint> ftag;    // atom ID of each local index at the last deformation pass
  // the Cauchy stress of local particle i at the last deformation pass
  void stress_now(int i, double *sig);

  double first_crossing(int a, const double *P, const double *Q);
  // Imix: also the interaction integrals of modes I and II (2 per tip)
  void j_integrals(const std::vector<int> &live, const std::vector<double> &dir, std::vector<double> &J,
                   std::vector<double> *Imix = nullptr);

  void find_tips();
};

}    // namespace LAMMPS_NS

#endif
