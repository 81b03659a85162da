/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: pair_style tlsph/damage (doc/pair_tlsph_damage.rst)

   pair tlsph plus bonds that break irreversibly at a critical stretch
   (from the fracture energy G_c, or given), the damage field phi and its
   smoothed form phi', and the adaptive artificial viscosity (alpha_d on
   damaged particles). The bond update runs at the start of every force
   call, on positions both ends of a bond see identically, so every MPI
   decomposition breaks the same bonds.
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(tlsph/damage,PairTLSPHDamage)
// clang-format on
#else

#ifndef LMP_PAIR_TLSPH_DAMAGE_H
#define LMP_PAIR_TLSPH_DAMAGE_H

#include "pair_tlsph.h"
#include "tlsph_crack_tips.h"

#include <array>
#include <vector>

namespace LAMMPS_NS {

class PairTLSPHDamage : public PairTLSPH {
 public:
  PairTLSPHDamage(class LAMMPS *);
  ~PairTLSPHDamage() override;
  void settings(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  int pack_reverse_comm(int, int, double *) override;
  void unpack_reverse_comm(int, int *, double *) override;
  double memory_usage() override;

  // read by compute tlsph/damage/atom and fix tlsph/velocity/filter
  double damage(int i) const { return phi[i]; }
  double smoothed_damage(int i) const { return phis[i]; }
  // the viscosity coefficient alpha_i of local particle i (after a force call)
  double viscosity_alpha(int i) const { return alphas[i]; }
  // the partners (particle indices) of the intact bonds of local particle i
  // (valid after a force call)
  const int *intact_partners(int i, int &n) const
  {
    n = nbond[i];
    return lean.j + bond_start[i];
  }
  // W(|X_ij|) of bond m of local particle i
  double kernel_value(int i, int m) const;
  // W(|X_ij|) of the intact bonds of local particle i, in their order (as
  // kernel_value; kept until a bond of i breaks or the bond cache is
  // rebuilt). The pointer is valid until the next call.
  const double *kernel_weights(int i);
  double critical_stretch_of(int type) const { return sc[type]; }
  // 'criterion tip': the crack tips (path vertices, the last one the tip), all ranks
  using CrackTip = LAMMPS_NS::CrackTip;
  const std::vector<CrackTip> &crack_tips() const { return crack->tips(); }
  double tip_fracture_energy() const { return crack->fracture_energy(); }
  int tip_mode() const { return tipmode; }

 protected:
  bool material_key(int, const std::string &, double, const std::string &) override;
  const char *extra_material_keys() const override
  {
    return "; and one of Gc, sc; with 'criterion tip' also strength";
  }
  bool is_extra_material_key(const std::string &key, double &) const override
  {
    return key == "Gc" || key == "sc" || key == "strength";
  }
  void check_material(int, const std::string &) override;
  void write_material_extra(FILE *, int) override;
  void read_material_extra(FILE *, int) override;
  void update_bonds() override;
  void deformation_pass() override;
  void after_deformation() override;
  bool viscosity_active() const override { return alpha > 0.0 || beta > 0.0 || alpha_d > 0.0; }

 protected:    // (the /kk variant reads these)
  double alpha_d;          // viscosity alpha on damaged particles (phi' > 0)
  int absolute;            // 1: |stretch| >= s_c breaks (thesis Eq. 2.27), 0: tension only
  int rebuild;             // 1: correction rebuilt from intact bonds, 0: kept from setup
  double family;           // radius of the bond family (damage decisions, phi); 0: 2h
  int damping_linear;      // 0: alpha_d where phi' > 0 (thesis Eq. 2.35), 1: alpha + (alpha_d - alpha) phi'
  std::vector<double> Gc, sc_given, sc;    // per type: fracture energy, given s_c, s_c used
  std::vector<double> strength;            // per type: tensile strength (criterion tip: nucleation; 0 none)
  int restart_has_strength = 0;            // the restart file's materials carry it
  std::vector<double> stretch_up, stretch_down;    // per type pair: (1 +- s_c)^2
  std::vector<std::array<double, 9>> cracks;    // pre-cracks: 2D segments, 3D parallelograms

  // 'criterion tip' (3D: through-thickness cracks): crack-tip tracking. Each pre-crack
  // end inside the body is a tip; its stress intensity factors come from
  // the crack-face displacement jump behind it (or the domain J-integral),
  // it turns by the maximum tangential stress angle and advances at the
  // speed of Freund's equation of motion, cutting the bonds its path crosses
  // (no other bond breaks). The tips live in 'crack' (tlsph_crack_tips.h),
  // which reads the particles' fields here and calls cut_path.
  friend class TLSPHCrackTips;
  int tipmode;
  TLSPHCrackTips *crack;
  void cut_path(const double *A, const double *B);
  std::vector<int> tip_cut;    // local particles whose bonds cut_path cut (after_deformation)
  // wall time of the tips' work in this run's steps (not its set-up call):
  // cut_newborn, snapshot_hoop, grow, pass (1) again, nucleate, note_pass
  double tip_wall = 0.0;
  void report_run(bigint nsteps) override;
  void step_done() override;

  int nmax_d;
  double *phi, *phis, *alphas;
  // after_deformation: phi of the local particles at its last call, the
  // flags of the particles to evaluate again (local and ghost: reverse
  // communication), and whether phis holds the values of the particles as
  // indexed by phis_stamp (cache version, nlocal, nghost)
  double *phi_prev, *mark;
  int phis_valid;
  // kernel_weights: per local particle its segment in wbuf (-1: none) and
  // its length, for the bond cache of version wver
  std::vector<int> wofs, wlen;
  std::vector<double> wbuf;
  int wver = -1;
  std::array<int, 3> phis_stamp;
  int comm_stage;          // forward: 0 packed rows (base), 1 damage phi; 2: reverse, flags
  bigint nbroken_local;    // bonds broken on this rank so far (from this end)
  bigint nbroken_seen = -1;    // nbroken_local at the last after_deformation

  double family_radius() const { return family > 0.0 ? family : 2.0 * h; }
  void grow_damage();
  void apply_precracks();
  bool crosses_crack(const double *A, const double *B) const;
  void recorrect(int i);
  // ABS: absolute criterion; PAIRS: per-type-pair limits (types differ in s_c)
  template <int DIM, int ORDER, int LAWS, int ABS, int PAIRS>
  void deform_and_break(const int *list, int nlist);
  template <int DIM, int ORDER, int LAWS> void dispatch_break(const int *list, int nlist);
  void deform_and_break_pass(const int *list, int nlist);
  // the SIMD step: its screen of the stretch limits, the exact test on the flagged particles
  bool simd_screen(double &up, double &down, double &reach2) const override;
  void simd_breaks(const int *list, int n) override;
  bool alpha_after_deformation() const override { return true; }
  // the rows Q and pk stay (pass (1) again for the particles that lose
  // bonds writes them); the bond values are kept as pair tlsph keeps them
  // (not with the stress on the lanes: bond_values computes a particle's
  // again from Q[i] where they are needed, bit for bit)
  bool keeps_rows() const override { return true; }
};

}    // namespace LAMMPS_NS

#endif
#endif
