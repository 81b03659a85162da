/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: pair_style tlsph, Total Lagrangian SPH for elastic solids
   (doc/pair_tlsph.rst)

   One step, as in the doc page:
     (1) F_i, stress and the pair tensors of every local particle, from its
         intact reference bonds            -> compute_deformation()
     (2) forward communication to ghosts    -> pack/unpack_forward_comm()
     (3) stress, viscous and hourglass pair forces -> compute_forces()
   The physics lives in tlsph_*.h; this class parses, loops and calls it.
------------------------------------------------------------------------- */

#ifdef PAIR_CLASS
// clang-format off
PairStyle(tlsph,PairTLSPH)
// clang-format on
#else

#ifndef LMP_PAIR_TLSPH_H
#define LMP_PAIR_TLSPH_H

#include "atom.h"
#include "pair.h"
#include "tlsph_kernel.h"
#include "tlsph_material.h"
#include "tlsph_ell.h"
#include "tlsph_particle.h"

#include <string>
#include <vector>

namespace LAMMPS_NS {

class PairTLSPH : public Pair {
 public:
  struct Material {
    int orthotropic;      // 0: isotropic (E, nu), 1: orthotropic ply (ortho, theta)
    double E, nu, rho;    // as given (E, nu: isotropic only)
    double lambda, mu;    // Lame constants (isotropic only)
    double c0;            // fastest longitudinal wave speed: time step and viscosity
    double E_hg;          // modulus of the hourglass term: E, or a ply's Voigt-average E
    TLSPH::OrthotropicConstants ortho;    // as given (orthotropic only)
    double theta;                         // fibre angle about +z from the x axis [degrees]
    TLSPH::OrthotropicSVK ortho_law;      // C(theta) in global axes and the 2D mode
  };

  using BondCache = TLSPH::Bond;

  PairTLSPH(class LAMMPS *);
  ~PairTLSPH() override;
  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;
  int pack_forward_comm(int, int *, double *, int, int *) override;
  void unpack_forward_comm(int, int, double *) override;
  double memory_usage() override;
  void *extract(const char *, int &) override;

  // read by the computes and fixes of the package (valid after a force call)
  const Material &material(int type) const { return mat[type]; }
  double smoothing_length() const { return h; }
  double max_wave_speed() const;
  void cauchy_stress(int i, double *sigma) const;
  // the same from a given F (3 x 3) instead of the stored one
  void cauchy_stress(int i, const double *Fi, double *sigma) const;
  // its in-plane part xx, yy, xy (stored F; cheaper in 2D)
  void cauchy_stress_xy(int i, double *s) const;
  // the local particles whose largest in-plane principal stress is >= s_min
  void principal_screen_xy(double s_min, std::vector<int> &out) const;
  void green_lagrange_strain(int i, double *E) const;
  const double *deformation_gradient(int i) const { return F[i]; }
  // the first Piola-Kirchhoff stress P of particle i's law at the deformation
  // gradient F (3 x 3; F33 = 1 in 2D, set from E33 in plane stress); returns
  // the strain energy density
  double pk1_stress(int i, double *F, double *P) const;
  double strain_energy_density(int i) const { return psi[i]; }
  // the hourglass energy of particle i (its share of E_hg) with the
  // conservative form; 0 with the thesis's (its work is tallied by the bond fix)
  double hourglass_energy(int i) const { return hg_form == 2 ? ehg[i] : 0.0; }
  int dimension() const { return dim; }
  // the /kk styles keep F, psi, ... on the device: the computes call this
  // before reading them (a no-op for the CPU styles)
  virtual void sync_host() {}
  // the /kk styles keep the bond fix's work tallies on the device: the fix
  // hands its tally to tally_work_device() (false: do it on the host) and
  // calls work_to_host() before it touches its work or force arrays
  virtual bool tally_work_device(double) { return false; }
  virtual void work_to_host() {}
  // /kk styles: the host<->device copies of the run just ended (its nsteps
  // steps) into the log, then the counts cleared (called by the bond fix)
  virtual void report_copies(bigint) {}
  // the run just ended (its nsteps steps): a style's own timings into the log
  virtual void report_run(bigint) {}
  // after a run's set-up force and at the end of every step (the bond fix's
  // setup and end_of_step): the step's whole force is in f
  virtual void step_done() {}
  // /kk styles: true when the step's arrays live on the device (the bond
  // fix then runs as a Kokkos fix with no per-step host copies)
  virtual bool on_device() const { return false; }
  // /kk styles: the atom data of mask current on the host for host code
  // (counted, tlsph_kk_copies.h); host_modified: host code changed it
  virtual void host_sync(unsigned int) {}
  virtual void host_modified(unsigned int) {}

  class FixTLSPHBonds *bonds;

  // the SIMD step (pair_tlsph_simd.cpp, tlsph_ell.h): pair_style ... simd VALUE
  enum { SIMD_INVALID = -2, SIMD_AUTO = -1, SIMD_NO = 0, SIMD_PORTABLE = 1, SIMD_AVX2 = 2,
         SIMD_AVX512 = 3 };
  static const char *simd_name(int isa);
  static int simd_value(const char *word);    // SIMD_INVALID for an unknown word
  static bool simd_supported(int isa);
  int simd_in_use() const { return simd_isa; }
  // the bonds' corrected gradients and weights are stored per bond (lean.g,
  // lean.w), not computed again where needed (set by init_style)
  bool bond_values_stored() const { return bond_values_kept; }
  // the SIMD step's layout (TLSPH::EllArrays) and the number of patterns
  void simd_chunks(int *kinds, int *npat) const
  {
    // particles in stencil chunks, in pattern chunks, alone in a chunk
    kinds[0] = kinds[1] = kinds[2] = 0;
    for (int c = 0; simd_isa && c < ell.nchunk; c++) {
      kinds[ell.kind[c]] += ell.n[c];
      if (ell.n[c] == 1) kinds[2]++;
    }
    *npat = simd_isa ? ell.npat : 0;
  }
  // tlsph/damage: lanes re-filled, pattern chunks given blocks of their own
  // and chunks that shared blocks given a copy of their own, since init
  void simd_refills(bigint *lanes, bigint *relaid, bigint *unshared = nullptr) const
  {
    *lanes = ell_nrefill;
    *relaid = ell_nrelaid;
    if (unshared) *unshared = ell_nunshared;
  }
  // tlsph/damage: chunks the stretch screen visited, and chunks it could skip, since init
  void simd_screens(bigint *screened, bigint *skipped) const
  {
    *screened = ell_nscreened;
    *skipped = ell_nskipped;
  }
  void sort_axes(int *ax) const;    // the axes of the SIMD step's order, slowest first
  void sort_particles();    // the SIMD step's order of the local particles (its bond fix calls it)

  /* the per-particle part of pass (1) for material m (TLSPH::particle_stress_row
     with the material's law; LAWS 0: isotropic only); the CPU loop and the
     Kokkos kernels of tlsph/kk both call this */
  template <int DIM, int ORDER, int LAWS, class Rows, class Bonds, class Coeff>
  static TLSPH_FORCE_INLINE double stress_row(const Material &m, int plane_stress, double *F,
                                              double *P, bool need_K, bool conservative,
                                              const Rows &x, int i, const Bonds &b, int nb,
                                              const Coeff &coeff, double Vi, const double *Q,
                                              double alpha_i, const double *sumg, bool with_R,
                                              double *row, double *fown, double *ehg, double *J)
  {
    if (LAWS && m.orthotropic)
      return TLSPH::particle_stress_row<DIM, ORDER>(m.ortho_law, F, P, need_K, conservative, x,
                                                    i, b, nb, coeff, Vi, Q, alpha_i, sumg,
                                                    with_R, row, fown, ehg, J);
    const TLSPH::IsotropicSVK law{m.lambda, m.mu, DIM == 2 ? plane_stress : 0};
    return TLSPH::particle_stress_row<DIM, ORDER>(law, F, P, need_K, conservative, x, i, b, nb,
                                                  coeff, Vi, Q, alpha_i, sumg, with_R, row, fown,
                                                  ehg, J);
  }

 protected:
  // settings
  double h;               // smoothing length
  double alpha, beta;     // artificial viscosity coefficients
  double gamma;           // hourglass coefficient
  int hg_form;            // hourglass force: 1 the thesis's pair force, 2 conservative
  int plane_stress;       // 2D: 1 plane stress, 0 plane strain
  double cutfactor;       // ghost cutoff = cutfactor * 2h
  int order;              // gradient correction: 1 linear (thesis), 2 quadratic
  double thickness;       // 2D: out-of-plane thickness contained in the particle volumes
  int check_partners;     // 1: stop if a particle has too few reference partners for a gradient
  int check_volume;       // 1: stop if the volumes (masses) do not fit h and the kernel (rho)
  int ndegraded;          // local particles whose correction fell back to a lower order
  int report_fallback;    // 1: log the fallback count at the next bond-cache build
  int dim;
  TLSPH::CubicSpline kernel;

  // materials, per atom type
  std::vector<Material> mat;
  std::vector<TLSPH::PairMaterial> pairmat;    // what the force pass reads
  int any_orthotropic;    // 1: some type is orthotropic (the per-particle law test is compiled in)
  void set_material(int type, const std::vector<std::string> &words, const std::string &where);
  void set_orthotropic(int type, const std::vector<std::string> &words, const std::string &where);
  void sync_laws();

  // hooks for derived styles (tlsph/damage): extra material keywords, their
  // check and restart data, the bond update of every step (update_bonds,
  // deformation_pass, after_deformation), and the policy of the gradient
  // correction after bonds break
  // the fracture values of a material (Gc, sc) are read by tlsph/damage and
  // ignored here, so that one material file serves both styles
  virtual bool material_key(int, const std::string &key, double, const std::string &where);
  virtual const char *extra_material_keys() const { return ""; }
  virtual bool is_extra_material_key(const std::string &, double &) const { return false; }
  virtual void check_material(int, const std::string &) {}
  virtual void write_material_extra(FILE *, int) {}
  virtual void read_material_extra(FILE *, int) {}
  virtual void update_bonds() {}
  virtual bool viscosity_active() const { return alpha > 0.0 || beta > 0.0; }
  bool correction_from_all_partners = false;    // true: broken bonds stay in the correction
  double *alpha_atom = nullptr;                  // per-particle viscosity alpha (null: alpha)
  int correct_particle(int i, BondCache *b, int n, const double *vj);
  void apply_particle(int i, BondCache *b, int n, const double *vj);
  int correction_size() const    // doubles of Q: DIM x basis size
  {
    const int nbasis = (order == 1) ? dim : (dim == 2 ? 5 : 9);
    return dim * nbasis;
  }
  void read_material_file(const std::string &file, int narg, char **names);

  // per-atom arrays (nmax rows: the local and ghost particles, grow_peratom)
  int nmax;
  double **Q;         // gradient correction (TLSPH::correction), DIM x basis size;
                      // null without bond_values_kept (the SIMD layout's columns hold it)
  double **sumg;      // sum_j g_ij over the cached bonds
  double **F;         // deformation gradient
  double **P;         // first Piola-Kirchhoff stress, plus H_i / (2 V_i) with the
                      // conservative hourglass form (what the force pass uses)
  double **fown;      // V_i P_i sum_j g_ij
  double **pk;        // packed rows F, K = J F^-T, alpha_i [, R = V P Q] (TLSPH::Packed),
                      // communicated; null without bond_values_kept (the SIMD
                      // layout's columns hold them)
  int gather_rows;    // 1: rows carry R (newton_pair off: the gather form of the
                      // stress term reads it); 0: compact rows (set in init_style)
  int packed_size() const
  {
    if (!gather_rows) return 2 * dim * dim + 1;    // TLSPH::Packed<DIM, ORDER>::compact
    if (dim == 2) return order == 1 ? TLSPH::Packed<2, 1>::size : TLSPH::Packed<2, 2>::size;
    return order == 1 ? TLSPH::Packed<3, 1>::size : TLSPH::Packed<3, 2>::size;
  }
  double *psi;        // strain energy density
  double *ehg;        // hourglass energy of the particle (conservative form)
  int *nbond;         // # of cached (intact) bonds
  int *nlead;         // # of them that lead their pair (first in the segment):
                      // partner a ghost or a local particle after i
  void grow_peratom();
  void destroy_peratom();    // the arrays grow_peratom makes
  // the per-atom rows (nmax) cannot hold the local and ghost particles, or
  // do not exist (nmax = 0, set by init_style; also a rank with no particle
  // gets rows)
  bool peratom_rows_short() const { return nmax == 0 || atom->nlocal + atom->nghost > nmax; }

  // bond cache in the lean layout (TLSPH::LeanBonds): structure of arrays,
  // CSR over the local atoms (bonds of i: bond_start[i] .. + the segment's
  // length; the first nbond[i] are intact)
  int *bond_start;
  TLSPH::LeanArrays lean;
  int ncache_max, nstart_max;
  int cache_version = 0;    // +1 at every build_bond_cache() (the /kk styles copy it then)
  double **x0c;       // reference positions consistent with the images of x
  // (virtual: the /kk styles build it on their device, pair_tlsph_kokkos.h)
  virtual void build_bond_cache();
  void resolve_bonds(bool shepard_sum, double &shepard_max, int &shepard_i);
  void reserve_bond_cache(int nbonds);
  void check_reference_partners(int nbad, tagint bad_tag, int bad_np, double bad_vol,
                                double bad_dmin);
  void set_reference_images();
  // full records of the bonds of local particle i, from the lean arrays
  // (for a new correction: tlsph/damage)
  void unpack_bonds(int i, int n, std::vector<BondCache> &b, std::vector<double> &vj) const;
  // the step's view of particle i's bonds
  struct X0Rows {    // rows of x0c (one contiguous block)
    const double *p;
    const double *operator()(int j) const { return p + 3 * (bigint) j; }
  };
  template <int DIM> TLSPH::LeanBonds<DIM, X0Rows> bonds_of(int i) const
  {
    const double *g, *w;
    bond_values(i, g, w);
    return bond_view<DIM>(i, g, w);
  }
  template <int DIM>
  TLSPH::LeanBonds<DIM, X0Rows> bond_view(int i, const double *g, const double *w) const
  {
    return TLSPH::LeanBonds<DIM, X0Rows>{lean.j + bond_start[i], g, w, X0Rows{x0c[0]}, x0c[i],
                                         kernel, atom->vfrac[i], order};
  }
  /* Where the corrected gradients and weights of the bonds live. With
     bond_values_kept (the scalar step, tlsph/damage, the /kk styles) in
     lean.g and lean.w. Without (pair_style tlsph's SIMD step with its stress
     on the lanes: keeps_bond_values) only in the SIMD layout, which reads
     them from its patterns and blocks: lean keeps partner and slot, and
     bond_values computes a particle's values again from its Q_i, as
     build_bond_cache did (bitwise the same), into a scratch buffer that the
     next call overwrites (the virial's gather pass, build_ell). */
  bool bond_values_kept = true;
  bigint ngw_max = 0;    // bonds that lean.g and lean.w have room for
  virtual bool keeps_bond_values() const;
  /* Q and the packed rows as per-atom rows (Q, pk): always but where
     pair_style tlsph's SIMD step keeps them only in its layout's columns
     (keeps_rows false: then bond_values_kept is false too). tlsph/damage
     keeps them (its scalar pass (1) again for the particles that lose
     bonds writes the rows) but not the bond values where the stress is on
     the lanes: bond_values computes them from Q[i] */
  bool rows_kept = true;
  /* the packed rows of the step live in the SIMD layout's columns (pk, where
     kept, holds only what the scalar pass (1) last wrote: a particle that
     tlsph/damage passes again, or every particle without the stress lanes);
     the communication and the virial's gather pass read the columns */
  bool rows_in_columns() const { return !pk || simd_isa != SIMD_NO; }
  virtual bool keeps_rows() const { return keeps_bond_values(); }
  bool stress_lanes_possible() const;
  // the same into a scratch buffer the caller may change (tlsph/damage:
  // drop_bond reorders it with lean.j and lean.k) when they are not kept
  void bond_values_mutable(int i, double *&g, double *&w)
  {
    const double *cg, *cw;
    bond_values(i, cg, cw);
    g = const_cast<double *>(cg);    // lean.g / lean.w, or the mutable scratch val_g / val_w
    w = const_cast<double *>(cw);
  }
  void bond_values(int i, const double *&g, const double *&w) const
  {
    const bigint s = bond_start[i];
    if (bond_values_kept) {
      g = lean.g + dim * s;
      w = lean.w + 2 * s;
    } else {
      recompute_bond_values(i, g, w);
    }
  }
  void recompute_bond_values(int i, const double *&g, const double *&w) const;
  mutable std::vector<TLSPH::Bond> val_b;
  mutable std::vector<double> val_vj, val_g, val_w, val_q;
  std::vector<double> q_build;    // Q_i by LAMMPS index from build_bond_cache to build_ell (not kept)
  // reference bond vector X_ij of bond m of particle i (3 components)
  void bond_vector(int i, int m, double *X) const
  {
    const double *a = x0c[i], *b = x0c[lean.j[bond_start[i] + m]];
    X[0] = b[0] - a[0];
    X[1] = b[1] - a[1];
    X[2] = (dim == 2) ? 0.0 : b[2] - a[2];
  }

  // LAWS 0: every type isotropic; 1: each particle picks its type's law
  template <int DIM, int ORDER, int LAWS> void compute_deformation();
  template <int DIM, int ORDER> void dispatch_deformation();
  // pass (1) of the step; tlsph/damage overrides it (bond breaking fused in)
  virtual void deformation_pass();
  // between passes (1) and (2): tlsph/damage updates the damage and alpha_i
  virtual void after_deformation() {}
  // stress, energy density and packed row of local particle i from its F
  // (pair_tlsph_step.h)
  template <int DIM, int ORDER, int LAWS> void particle_stress(int i, bool need_K);
  // the same from the bonds' view b (bonds_of or bond_view)
  template <int DIM, int ORDER, int LAWS, class Bonds>
  void particle_stress_of(int i, bool need_K, const Bonds &b);
  [[noreturn]] void unstable_particle(int i, double J) const;
  template <int DIM, int ORDER, int HG, int VISC, int VIRIAL, int SCATTER> void compute_forces();
  template <int DIM, int ORDER> void dispatch_forces(int hg, int visc, int vir, int newton);
  template <int DIM, int ORDER, int HG> void dispatch_forces_hg(int visc, int vir, int newton);

  // the SIMD step: the requested and the selected instruction set, the
  // sliced-ELLPACK copy of the bond cache and the cache_version it copies
  int simd_request = SIMD_AUTO;
  int simd_isa = SIMD_NO;
  TLSPH::EllArrays ell;
  int ell_nstart = 0;
  bigint ell_nblock_max = 0;
  int ell_version = -1;
  int *ell_perm = nullptr;      // the step's particle order -> LAMMPS index
  int *ell_inv = nullptr;       // LAMMPS index -> the step's order
  double *ell_soa = nullptr;    // columns (length ell_nperm): x, v, x0c, packed rows
  int ell_nperm = 0;
  int *ell_chunk_of = nullptr;  // the step's order (local particles) -> its chunk
  bigint ell_nblock = 0;        // slot blocks in use
  std::vector<int> ell_dirty;   // local particles whose bonds changed since build_ell
  bigint ell_nrefill = 0, ell_nrelaid = 0, ell_nunshared = 0;    // (simd_refills)
  int report_simd = 1;             // 1: log the layout at the next build_ell
  // tlsph/damage: particle i's bonds changed (its lane is re-filled before the force pass)
  void ell_mark(int i)
  {
    if (simd_isa != SIMD_NO) ell_dirty.push_back(i);
  }
  // bond mm of local particle i into lane l of slot block vb; g, w: the particle's values (bond_values)
  void ell_put_bond(double *vb, int l, int i, int mm, const double *g, const double *w) const;
  void ell_fill_lane(int c, int l);
  void ell_apply_dirty();
  /* tlsph/damage: the SIMD step's pass (1) flags the local particles with a
     bond whose squared length ratio r^2/r0^2 reaches up (or, down > 0, falls
     to down); reach2: TLSPH::EllScreen; false: no screen */
  virtual bool simd_screen(double &, double &, double &) const { return false; }
  // the flagged particles: the style's exact test, and pass (1) again for them
  virtual void simd_breaks(const int *, int) {}
  // true: after_deformation writes alpha_i into the packed rows (the SIMD
  // step's stress lanes then run, and copy that column afterwards)
  virtual bool alpha_after_deformation() const { return false; }
  /* false: after_deformation changed no alpha_i this step, so the column
     that pass (1) wrote from alpha_atom holds them (simd_after_deformation
     copies it only when true) */
  bool alpha_changed = true;
  /* crack nucleation (tlsph/damage's strength, > 0; 2D): the SIMD step's
     stress lanes flag in nuc_hit the particles whose largest principal
     stress may reach nuc_screen_s (with a margin), in the pass of step
     nuc_hit_step (-1: none); principal_screen_xy then tests only those */
  double nuc_screen_s = 0.0;
  std::vector<unsigned char> nuc_hit;
  bigint nuc_hit_step = -1;
  std::vector<int> ell_flagged;    // the screen's particles (LAMMPS indices)
  /* The screen skips the chunks whose bonds cannot have reached a limit
     since their last full screen (simd_deformation): ell_xref, the
     positions (columns) at the last full screen of layout ell_screen_of
     (a count of build_ell), ell_cworst its per-chunk margins, ell_need the
     chunks to screen this step. */
  int ell_builds = 0, ell_screen_of = -1;
  std::vector<double> ell_xref, ell_cworst;
  std::vector<char> ell_need;
  bigint ell_nscreened = 0, ell_nskipped = 0;    // chunk screens done and skipped (simd_refills)
  void ell_row_to_columns(int i);
  void simd_screen_select(TLSPH::EllScreen &scr);
  void simd_after_deformation();
  void ell_columns_xv();
  TLSPH::EllParticles ell_particles();
  int ell_ncolumns() const;
  virtual bool simd_capable() const { return true; }    // false: styles without the SIMD step
  void select_simd();
  void build_ell();
  template <int DIM, int ORDER, int LAWS> void simd_deformation();
  void simd_deformation_pass();
  void simd_forces(int hg, int visc);
  void simd_virial(int hg, int visc);

  void allocate();
  void set_defaults();
  bool refresh_bond_cache();
  void tally_energy();
};

}    // namespace LAMMPS_NS

#endif
#endif
