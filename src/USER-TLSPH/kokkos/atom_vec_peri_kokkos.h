/* -*- c++ -*- ----------------------------------------------------------
   LAMMPS - Large-scale Atomic/Molecular Massively Parallel Simulator
   https://www.lammps.org/, Sandia National Laboratories
   Steve Plimpton, sjplimp@sandia.gov

   Copyright (2003) Sandia Corporation.  Under the terms of Contract
   DE-AC04-94AL85000 with Sandia Corporation, the U.S. Government retains
   certain rights in this software.  This software is distributed under
   the GNU General Public License.

   See the README file in the top-level LAMMPS directory.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Kokkos version of atom_style peri (PERI package, AtomVecPeri) for the
   LAMMPS version 29 Sep 2021 (Debian 20220106), which has none.

   Per-atom fields, as in AtomVecPeri:
     rmass  (AtomKokkos::k_rmass, mask RMASS_MASK)
     vfrac  (k_vfrac below, extended mask VFRAC_MASK)
     s0     (k_s0 below,    extended mask S0_MASK)
     x0     (k_x0 below,    extended mask X0_MASK)
   AtomKokkos of this version has no DualViews for vfrac, s0 and x0, so this
   class owns them (public, for Kokkos pair styles:
   static_cast<AtomVecPeriKokkos *>(atom->avec)->k_x0); atom->vfrac,
   atom->s0 and atom->x0 point at their host views.

   Masks: VFRAC_MASK, S0_MASK and X0_MASK (atom_masks.h) are "extended"
   masks, whose bits coincide with X_MASK, V_MASK and F_MASK. They are
   addressed by setting EXTENDED_MASK in the same mask, e.g.
     atomKK->sync(Device, EXTENDED_MASK | X0_MASK | VFRAC_MASK);
     atomKK->modified(Device, EXTENDED_MASK | S0_MASK);
   A mask with EXTENDED_MASK refers to the extended fields only (its low
   bits are not X/V/F then); ALL_MASK refers to every field. As a safety
   net, sync() and sync_overlapping_device() also sync vfrac/s0/x0 when the
   coinciding X/V/F bits are given without EXTENDED_MASK (a sync copies only
   what the other side marked modified, so this never loses data), but
   modified() marks vfrac/s0/x0 only for EXTENDED_MASK or ALL_MASK.
------------------------------------------------------------------------- */

#ifdef ATOM_CLASS
// clang-format off
AtomStyle(peri/kk,AtomVecPeriKokkos);
AtomStyle(peri/kk/device,AtomVecPeriKokkos);
AtomStyle(peri/kk/host,AtomVecPeriKokkos);
// clang-format on
#else

// clang-format off
#ifndef LMP_ATOM_VEC_PERI_KOKKOS_H
#define LMP_ATOM_VEC_PERI_KOKKOS_H

#include "atom_vec_kokkos.h"
#include "kokkos_type.h"

#include <string>

namespace LAMMPS_NS {

class AtomVecPeriKokkos : public AtomVecKokkos {
 public:
  void init() override;
  AtomVecPeriKokkos(class LAMMPS *);
  ~AtomVecPeriKokkos();

  void grow(int);
  void grow_pointers();
  void copy(int, int, int);

  int pack_comm(int, int *, double *, int, int *);
  int pack_comm_vel(int, int *, double *, int, int *);
  void unpack_comm(int, int, double *);
  void unpack_comm_vel(int, int, double *);
  int pack_border(int, int *, double *, int, int *);
  int pack_border_vel(int, int *, double *, int, int *);
  void unpack_border(int, int, double *);
  void unpack_border_vel(int, int, double *);
  int pack_exchange(int, double *);
  int unpack_exchange(double *);
  int size_restart();
  int pack_restart(int, double *);
  int unpack_restart(double *);
  void create_atom(int, double *);
  void data_atom(double *, imageint, char **);
  void pack_data(double **);
  void write_data(FILE *, int, double **);
  int property_atom(char *);
  void pack_property_atom(int, double *, int, int);
  double memory_usage();

  // old-style hybrid interface (used by atom_style hybrid/kk)

  int pack_comm_hybrid(int, int *, double *);
  int unpack_comm_hybrid(int, int, double *);
  int pack_border_hybrid(int, int *, double *);
  int unpack_border_hybrid(int, int, double *);
  int data_atom_hybrid(int, char **);
  int pack_data_hybrid(int, double *);
  int write_data_hybrid(FILE *, double *);

  // Kokkos communication

  int pack_comm_kokkos(const int &n, const DAT::tdual_int_2d &k_sendlist,
                       const int &iswap, const DAT::tdual_xfloat_2d &buf,
                       const int &pbc_flag, const int pbc[]);
  void unpack_comm_kokkos(const int &n, const int &nfirst,
                          const DAT::tdual_xfloat_2d &buf);
  int pack_comm_vel_kokkos(const int &n, const DAT::tdual_int_2d &k_sendlist,
                           const int &iswap, const DAT::tdual_xfloat_2d &buf,
                           const int &pbc_flag, const int pbc[]);
  void unpack_comm_vel_kokkos(const int &n, const int &nfirst,
                              const DAT::tdual_xfloat_2d &buf);
  int pack_comm_self(const int &n, const DAT::tdual_int_2d &list,
                     const int &iswap, const int nfirst,
                     const int &pbc_flag, const int pbc[]);
  int pack_comm_self_fused(const int &n, const DAT::tdual_int_2d &list,
                           const DAT::tdual_int_1d &sendnum_scan,
                           const DAT::tdual_int_1d &firstrecv,
                           const DAT::tdual_int_1d &pbc_flag,
                           const DAT::tdual_int_2d &pbc,
                           const DAT::tdual_int_1d &g2l);
  int pack_border_kokkos(int n, DAT::tdual_int_2d k_sendlist,
                         DAT::tdual_xfloat_2d buf, int iswap,
                         int pbc_flag, int *pbc, ExecutionSpace space);
  void unpack_border_kokkos(const int &n, const int &nfirst,
                            const DAT::tdual_xfloat_2d &buf,
                            ExecutionSpace space);
  int pack_border_vel_kokkos(int n, DAT::tdual_int_2d k_sendlist,
                             DAT::tdual_xfloat_2d buf, int iswap,
                             int pbc_flag, int *pbc, ExecutionSpace space);
  void unpack_border_vel_kokkos(const int &n, const int &nfirst,
                                const DAT::tdual_xfloat_2d &buf,
                                ExecutionSpace space);
  int pack_exchange_kokkos(const int &nsend, DAT::tdual_xfloat_2d &buf,
                           DAT::tdual_int_1d k_sendlist,
                           DAT::tdual_int_1d k_copylist,
                           ExecutionSpace space, int dim,
                           X_FLOAT lo, X_FLOAT hi);
  int unpack_exchange_kokkos(DAT::tdual_xfloat_2d &k_buf, int nrecv,
                             int nlocal, int dim, X_FLOAT lo, X_FLOAT hi,
                             ExecutionSpace space);

  void sync(ExecutionSpace space, unsigned int mask);
  void modified(ExecutionSpace space, unsigned int mask);
  void sync_overlapping_device(ExecutionSpace space, unsigned int mask);

  // per-atom fields that AtomKokkos does not hold (see above)

  DAT::tdual_float_1d k_vfrac, k_s0;
  DAT::tdual_x_array k_x0;

  // Copy ledger (doc/kokkos-cuda.md, "Host-device copies"): the copies
  // between host and device memory that the calls of sync(),
  // sync_overlapping_device() and modified() above make, per field, counted
  // with DualView's own rule (a sync to one side copies the field when the
  // other side marked it modified last). On a GPU these are the copies made.
  // On the host backends both sides are one memory (DualView copies
  // nothing), and LAMMPS's own calls name that one space now Host
  // (ExecutionSpaceFromDevice), now Device: the counts mean nothing there,
  // and the report says so instead (PairTLSPHKokkosT::report_copies).
  // Copies LAMMPS makes by calling a DualView directly (not through
  // AtomKokkos::sync) are not seen.
  enum { NFIELD = 11 };
  struct CopyLedger {
    int newer[NFIELD];           // 0: both sides equal, 1: host newer, 2: device newer
    long copies[NFIELD][2];      // [field][0: to the device, 1: to the host]
    double bytes[NFIELD][2];
  } ledger;
  static const char *field_name(int);
  // the fields a mask of sync() or modified() names, with their bytes now
  // ("x,tag"; modify: as modified() reads the mask)
  std::string mask_fields(unsigned int mask, bool modify, double *bytes) const;
  void ledger_clear_counts();

  // sizes of the packed records (values per atom)

  enum { COMM_SIZE = 4,          // x[3] s0
         COMM_VEL_SIZE = 7,      // x[3] v[3] s0
         BORDER_SIZE = 12,       // x[3] tag type mask rmass vfrac s0 x0[3]
         BORDER_VEL_SIZE = 15,   // BORDER_SIZE + v[3]
         EXCHANGE_SIZE = 17,     // n x[3] v[3] tag type mask image rmass vfrac s0 x0[3]
         RESTART_SIZE = 17 };    // n x[3] tag type mask image v[3] rmass vfrac s0 x0[3]

 protected:
  // tag, type, mask, image, x, v, f: the AtomVec members (set in grow_pointers)
  double *rmass, *vfrac, *s0;
  double **x0;

  DAT::t_tagint_1d d_tag;
  HAT::t_tagint_1d h_tag;
  DAT::t_imageint_1d d_image;
  HAT::t_imageint_1d h_image;
  DAT::t_int_1d d_type, d_mask;
  HAT::t_int_1d h_type, h_mask;

  DAT::t_x_array d_x;
  DAT::t_v_array d_v;
  DAT::t_f_array d_f;

  DAT::t_float_1d d_rmass, d_vfrac, d_s0;
  HAT::t_float_1d h_rmass, h_vfrac, h_s0;
  DAT::t_x_array d_x0;
  HAT::t_x_array h_x0;

  DAT::tdual_int_1d k_count;

  // the Atom this style belongs to: lmp->atom, except inside replicate,
  // where a new Atom exists next to the old one and its style
  class AtomKokkos *owner;

 private:
  template <class DeviceType> int pack_comm_kk(const int &, const DAT::tdual_int_2d &,
                                               const int &, const DAT::tdual_xfloat_2d &,
                                               const int &, const int *, int);
  template <class DeviceType> void unpack_comm_kk(const int &, const int &,
                                                  const DAT::tdual_xfloat_2d &, int);
  template <class DeviceType> int pack_comm_self_kk(const int &, const DAT::tdual_int_2d &,
                                                    const int &, const int, const int &,
                                                    const int *);
  template <class DeviceType> int pack_border_kk(int, DAT::tdual_int_2d, DAT::tdual_xfloat_2d,
                                                 int, int, int *, int);
  template <class DeviceType> void unpack_border_kk(const int &, const int &,
                                                    const DAT::tdual_xfloat_2d &, int);
  void unpack_border_common(int, int, double *, int);
  int pack_border_common(int, int *, double *, int, int *, int);
  void ledger_note(ExecutionSpace space, unsigned int std_mask, unsigned int ext_mask, bool sync);
  double field_bytes(int) const;
  static unsigned int field_bit(int);
  static void split_mask(unsigned int mask, bool modify, unsigned int &std_mask,
                         unsigned int &ext_mask);
};

}    // namespace LAMMPS_NS

#endif
#endif
