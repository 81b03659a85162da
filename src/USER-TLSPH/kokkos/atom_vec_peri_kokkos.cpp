// clang-format off
/* ----------------------------------------------------------------------
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
   Kokkos version of atom_style peri, written after the Kokkos atom styles
   atomic/kk and sphere/kk and the CPU style peri (AtomVecPeri) of LAMMPS
   29 Sep 2021. See atom_vec_peri_kokkos.h for the fields and masks.

   Record layouts (values per atom, same on host and device):
     comm       x[3] s0
     comm_vel   x[3] v[3] s0
     border     x[3] tag type mask rmass vfrac s0 x0[3]
     border_vel x[3] tag type mask rmass vfrac s0 x0[3] v[3]
     exchange   n x[3] v[3] tag type mask image rmass vfrac s0 x0[3]
     restart    n x[3] tag type mask image v[3] rmass vfrac s0 x0[3]
                (the layout of AtomVecPeri, so that restart files can be
                 read by either style)
   x0 is a reference position: it is sent without periodic shift, as the
   CPU style does.
------------------------------------------------------------------------- */

#include "atom_vec_peri_kokkos.h"

#include "atom_kokkos.h"
#include "atom_masks.h"
#include "citeme.h"
#include "comm_kokkos.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "memory_kokkos.h"
#include "modify.h"

#include <cfloat>
#include <cstring>

using namespace LAMMPS_NS;

static const char cite_peri_package[] =
  "PERI package for Peridynamics:\n\n"
  "@Article{Parks08,\n"
  " author = {M. L. Parks, R. B. Lehoucq, S. J. Plimpton, S. A. Silling},\n"
  " title = {Implementing peridynamics within a molecular dynamics code},\n"
  " journal = {Comp.~Phys.~Comm.},\n"
  " year =    2008,\n"
  " volume =  179,\n"
  " pages =   {777--783}\n"
  "}\n\n";

namespace {

// the extended-mask fields of this style

constexpr unsigned int PERI_EXT = VFRAC_MASK | S0_MASK | X0_MASK;    // == PERI_MASK
constexpr unsigned int EXT_ALL = EXTENDED_MASK | PERI_EXT;
constexpr unsigned int EXT_S0 = EXTENDED_MASK | S0_MASK;

// fields sent in border and exchange, and stored per owned atom

constexpr unsigned int BORDER_STD = X_MASK | TAG_MASK | TYPE_MASK | MASK_MASK | RMASS_MASK;
constexpr unsigned int OWNED_STD = X_MASK | V_MASK | TAG_MASK | TYPE_MASK | MASK_MASK |
  IMAGE_MASK | RMASS_MASK;

// a mask that has EXTENDED_MASK and SAMETAG_MASK was built from ALL_MASK
// (nothing sets SAMETAG_MASK otherwise): it addresses every field

inline bool is_all_mask(unsigned int mask)
{
  return (mask & (EXTENDED_MASK | SAMETAG_MASK)) == (EXTENDED_MASK | SAMETAG_MASK);
}

// parameters of one pack call, copied into the kernels

struct PeriPackParams {
  X_FLOAT xprd, yprd, zprd, xy, xz, yz;
  X_FLOAT pbc[6];
  X_FLOAT h_rate[6];
  X_FLOAT dx, dy, dz;        // border: shift of x
  X_FLOAT dvx, dvy, dvz;     // border_vel with deform remap: shift of v
  int deform_groupbit;
};

}    // namespace

/* ----------------------------------------------------------------------
   forward comm: x (+v) + s0 into a buffer
------------------------------------------------------------------------- */

template<class DeviceType,int PBC_FLAG,int TRICLINIC,int VEL,int DEFORM_VREMAP>
struct AtomVecPeriKokkos_PackComm {
  typedef DeviceType device_type;
  typedef ArrayTypes<DeviceType> AT;

  typename AT::t_x_array_randomread _x;
  typename AT::t_v_array_randomread _v;
  typename AT::t_int_1d_randomread _mask;
  typename AT::t_float_1d_randomread _s0;
  typename AT::t_xfloat_2d_um _buf;
  typename AT::t_int_2d_const _list;
  const int _iswap;
  PeriPackParams _p;

  AtomVecPeriKokkos_PackComm(const AtomKokkos *atomKK, const DAT::tdual_float_1d &s0,
                             const DAT::tdual_xfloat_2d &buf, const DAT::tdual_int_2d &list,
                             const int &iswap, const PeriPackParams &p) :
    _x(atomKK->k_x.view<DeviceType>()), _v(atomKK->k_v.view<DeviceType>()),
    _mask(atomKK->k_mask.view<DeviceType>()), _s0(s0.view<DeviceType>()),
    _list(list.view<DeviceType>()), _iswap(iswap), _p(p)
  {
    const size_t elements = VEL ? AtomVecPeriKokkos::COMM_VEL_SIZE : AtomVecPeriKokkos::COMM_SIZE;
    const size_t maxsend = (buf.view<DeviceType>().extent(0)*buf.view<DeviceType>().extent(1))/elements;
    buffer_view<DeviceType>(_buf,buf,maxsend,elements);
  }

  KOKKOS_INLINE_FUNCTION
  void operator() (const int &i) const {
    const int j = _list(_iswap,i);
    if (PBC_FLAG == 0) {
      _buf(i,0) = _x(j,0);
      _buf(i,1) = _x(j,1);
      _buf(i,2) = _x(j,2);
    } else if (TRICLINIC == 0) {
      _buf(i,0) = _x(j,0) + _p.pbc[0]*_p.xprd;
      _buf(i,1) = _x(j,1) + _p.pbc[1]*_p.yprd;
      _buf(i,2) = _x(j,2) + _p.pbc[2]*_p.zprd;
    } else {
      _buf(i,0) = _x(j,0) + _p.pbc[0]*_p.xprd + _p.pbc[5]*_p.xy + _p.pbc[4]*_p.xz;
      _buf(i,1) = _x(j,1) + _p.pbc[1]*_p.yprd + _p.pbc[3]*_p.yz;
      _buf(i,2) = _x(j,2) + _p.pbc[2]*_p.zprd;
    }
    if (VEL) {
      if (DEFORM_VREMAP && (_mask(j) & _p.deform_groupbit)) {
        _buf(i,3) = _v(j,0) + _p.pbc[0]*_p.h_rate[0] + _p.pbc[5]*_p.h_rate[5] +
          _p.pbc[4]*_p.h_rate[4];
        _buf(i,4) = _v(j,1) + _p.pbc[1]*_p.h_rate[1] + _p.pbc[3]*_p.h_rate[3];
        _buf(i,5) = _v(j,2) + _p.pbc[2]*_p.h_rate[2];
      } else {
        _buf(i,3) = _v(j,0);
        _buf(i,4) = _v(j,1);
        _buf(i,5) = _v(j,2);
      }
      _buf(i,6) = _s0(j);
    } else {
      _buf(i,3) = _s0(j);
    }
  }
};

/* ----------------------------------------------------------------------
   forward comm: buffer into ghost x (+v) + s0
------------------------------------------------------------------------- */

template<class DeviceType,int VEL>
struct AtomVecPeriKokkos_UnpackComm {
  typedef DeviceType device_type;
  typedef ArrayTypes<DeviceType> AT;

  typename AT::t_x_array _x;
  typename AT::t_v_array _v;
  typename AT::t_float_1d _s0;
  typename AT::t_xfloat_2d_const_um _buf;
  int _first;

  AtomVecPeriKokkos_UnpackComm(const AtomKokkos *atomKK, const DAT::tdual_float_1d &s0,
                               const DAT::tdual_xfloat_2d &buf, const int &first) :
    _x(atomKK->k_x.view<DeviceType>()), _v(atomKK->k_v.view<DeviceType>()),
    _s0(s0.view<DeviceType>()), _first(first)
  {
    const size_t elements = VEL ? AtomVecPeriKokkos::COMM_VEL_SIZE : AtomVecPeriKokkos::COMM_SIZE;
    const size_t maxsend = (buf.view<DeviceType>().extent(0)*buf.view<DeviceType>().extent(1))/elements;
    buffer_view<DeviceType>(_buf,buf,maxsend,elements);
  }

  KOKKOS_INLINE_FUNCTION
  void operator() (const int &i) const {
    _x(i+_first,0) = _buf(i,0);
    _x(i+_first,1) = _buf(i,1);
    _x(i+_first,2) = _buf(i,2);
    if (VEL) {
      _v(i+_first,0) = _buf(i,3);
      _v(i+_first,1) = _buf(i,4);
      _v(i+_first,2) = _buf(i,5);
      _s0(i+_first) = _buf(i,6);
    } else {
      _s0(i+_first) = _buf(i,3);
    }
  }
};

/* ----------------------------------------------------------------------
   forward comm with self: x + s0 of owned/ghost atom j into ghost i+nfirst
------------------------------------------------------------------------- */

template<class DeviceType,int PBC_FLAG,int TRICLINIC>
struct AtomVecPeriKokkos_PackCommSelf {
  typedef DeviceType device_type;
  typedef ArrayTypes<DeviceType> AT;

  typename AT::t_x_array_randomread _x;
  typename AT::t_x_array _xw;
  typename AT::t_float_1d _s0;
  int _nfirst;
  typename AT::t_int_2d_const _list;
  const int _iswap;
  PeriPackParams _p;

  AtomVecPeriKokkos_PackCommSelf(const AtomKokkos *atomKK, const DAT::tdual_float_1d &s0,
                                 const int &nfirst, const DAT::tdual_int_2d &list,
                                 const int &iswap, const PeriPackParams &p) :
    _x(atomKK->k_x.view<DeviceType>()), _xw(atomKK->k_x.view<DeviceType>()),
    _s0(s0.view<DeviceType>()), _nfirst(nfirst), _list(list.view<DeviceType>()),
    _iswap(iswap), _p(p) {}

  KOKKOS_INLINE_FUNCTION
  void operator() (const int &i) const {
    const int j = _list(_iswap,i);
    if (PBC_FLAG == 0) {
      _xw(i+_nfirst,0) = _x(j,0);
      _xw(i+_nfirst,1) = _x(j,1);
      _xw(i+_nfirst,2) = _x(j,2);
    } else if (TRICLINIC == 0) {
      _xw(i+_nfirst,0) = _x(j,0) + _p.pbc[0]*_p.xprd;
      _xw(i+_nfirst,1) = _x(j,1) + _p.pbc[1]*_p.yprd;
      _xw(i+_nfirst,2) = _x(j,2) + _p.pbc[2]*_p.zprd;
    } else {
      _xw(i+_nfirst,0) = _x(j,0) + _p.pbc[0]*_p.xprd + _p.pbc[5]*_p.xy + _p.pbc[4]*_p.xz;
      _xw(i+_nfirst,1) = _x(j,1) + _p.pbc[1]*_p.yprd + _p.pbc[3]*_p.yz;
      _xw(i+_nfirst,2) = _x(j,2) + _p.pbc[2]*_p.zprd;
    }
    _s0(i+_nfirst) = _s0(j);
  }
};

/* ----------------------------------------------------------------------
   forward comm with self, all swaps in one kernel (single process)
------------------------------------------------------------------------- */

template<class DeviceType,int TRICLINIC>
struct AtomVecPeriKokkos_PackCommSelfFused {
  typedef DeviceType device_type;
  typedef ArrayTypes<DeviceType> AT;

  typename AT::t_x_array_randomread _x;
  typename AT::t_x_array _xw;
  typename AT::t_float_1d _s0;
  typename AT::t_int_2d_const _list;
  typename AT::t_int_2d_const _pbc;
  typename AT::t_int_1d_const _pbc_flag;
  typename AT::t_int_1d_const _firstrecv;
  typename AT::t_int_1d_const _sendnum_scan;
  typename AT::t_int_1d_const _g2l;
  PeriPackParams _p;

  AtomVecPeriKokkos_PackCommSelfFused(const AtomKokkos *atomKK, const DAT::tdual_float_1d &s0,
                                      const DAT::tdual_int_2d &list,
                                      const DAT::tdual_int_2d &pbc,
                                      const DAT::tdual_int_1d &pbc_flag,
                                      const DAT::tdual_int_1d &firstrecv,
                                      const DAT::tdual_int_1d &sendnum_scan,
                                      const DAT::tdual_int_1d &g2l,
                                      const PeriPackParams &p) :
    _x(atomKK->k_x.view<DeviceType>()), _xw(atomKK->k_x.view<DeviceType>()),
    _s0(s0.view<DeviceType>()), _list(list.view<DeviceType>()),
    _pbc(pbc.view<DeviceType>()), _pbc_flag(pbc_flag.view<DeviceType>()),
    _firstrecv(firstrecv.view<DeviceType>()), _sendnum_scan(sendnum_scan.view<DeviceType>()),
    _g2l(g2l.view<DeviceType>()), _p(p) {}

  KOKKOS_INLINE_FUNCTION
  void operator() (const int &ii) const {
    int iswap = 0;
    while (ii >= _sendnum_scan[iswap]) iswap++;
    int i = ii;
    if (iswap > 0) i = ii - _sendnum_scan[iswap-1];

    const int _nfirst = _firstrecv[iswap];
    const int nlocal = _firstrecv[0];

    int j = _list(iswap,i);
    if (j >= nlocal) j = _g2l(j-nlocal);

    if (_pbc_flag(ii) == 0) {
      _xw(i+_nfirst,0) = _x(j,0);
      _xw(i+_nfirst,1) = _x(j,1);
      _xw(i+_nfirst,2) = _x(j,2);
    } else if (TRICLINIC == 0) {
      _xw(i+_nfirst,0) = _x(j,0) + _pbc(ii,0)*_p.xprd;
      _xw(i+_nfirst,1) = _x(j,1) + _pbc(ii,1)*_p.yprd;
      _xw(i+_nfirst,2) = _x(j,2) + _pbc(ii,2)*_p.zprd;
    } else {
      _xw(i+_nfirst,0) = _x(j,0) + _pbc(ii,0)*_p.xprd + _pbc(ii,5)*_p.xy + _pbc(ii,4)*_p.xz;
      _xw(i+_nfirst,1) = _x(j,1) + _pbc(ii,1)*_p.yprd + _pbc(ii,3)*_p.yz;
      _xw(i+_nfirst,2) = _x(j,2) + _pbc(ii,2)*_p.zprd;
    }
    _s0(i+_nfirst) = _s0(j);
  }
};

/* ----------------------------------------------------------------------
   border comm: x tag type mask rmass vfrac s0 x0[3] (+v) into a buffer
------------------------------------------------------------------------- */

template<class DeviceType,int PBC_FLAG,int VEL,int DEFORM_VREMAP>
struct AtomVecPeriKokkos_PackBorder {
  typedef DeviceType device_type;
  typedef ArrayTypes<DeviceType> AT;

  typename AT::t_xfloat_2d_um _buf;
  typename AT::t_int_2d_const _list;
  const int _iswap;
  typename AT::t_x_array_randomread _x;
  typename AT::t_v_array_randomread _v;
  typename AT::t_tagint_1d_randomread _tag;
  typename AT::t_int_1d_randomread _type, _mask;
  typename AT::t_float_1d_randomread _rmass, _vfrac, _s0;
  typename AT::t_x_array_randomread _x0;
  PeriPackParams _p;

  AtomVecPeriKokkos_PackBorder(const AtomKokkos *atomKK,
                               const DAT::tdual_float_1d &vfrac,
                               const DAT::tdual_float_1d &s0,
                               const DAT::tdual_x_array &x0,
                               const DAT::tdual_xfloat_2d &buf,
                               const DAT::tdual_int_2d &list,
                               const int &iswap, const PeriPackParams &p) :
    _list(list.view<DeviceType>()), _iswap(iswap),
    _x(atomKK->k_x.view<DeviceType>()), _v(atomKK->k_v.view<DeviceType>()),
    _tag(atomKK->k_tag.view<DeviceType>()), _type(atomKK->k_type.view<DeviceType>()),
    _mask(atomKK->k_mask.view<DeviceType>()), _rmass(atomKK->k_rmass.view<DeviceType>()),
    _vfrac(vfrac.view<DeviceType>()), _s0(s0.view<DeviceType>()),
    _x0(x0.view<DeviceType>()), _p(p)
  {
    const size_t elements = VEL ? AtomVecPeriKokkos::BORDER_VEL_SIZE : AtomVecPeriKokkos::BORDER_SIZE;
    const size_t maxsend = (buf.view<DeviceType>().extent(0)*buf.view<DeviceType>().extent(1))/elements;
    buffer_view<DeviceType>(_buf,buf,maxsend,elements);
  }

  KOKKOS_INLINE_FUNCTION
  void operator() (const int &i) const {
    const int j = _list(_iswap,i);
    if (PBC_FLAG == 0) {
      _buf(i,0) = _x(j,0);
      _buf(i,1) = _x(j,1);
      _buf(i,2) = _x(j,2);
    } else {
      _buf(i,0) = _x(j,0) + _p.dx;
      _buf(i,1) = _x(j,1) + _p.dy;
      _buf(i,2) = _x(j,2) + _p.dz;
    }
    _buf(i,3) = d_ubuf(_tag(j)).d;
    _buf(i,4) = d_ubuf(_type(j)).d;
    _buf(i,5) = d_ubuf(_mask(j)).d;
    _buf(i,6) = _rmass(j);
    _buf(i,7) = _vfrac(j);
    _buf(i,8) = _s0(j);
    _buf(i,9) = _x0(j,0);
    _buf(i,10) = _x0(j,1);
    _buf(i,11) = _x0(j,2);
    if (VEL) {
      if (PBC_FLAG && DEFORM_VREMAP && (_mask(j) & _p.deform_groupbit)) {
        _buf(i,12) = _v(j,0) + _p.dvx;
        _buf(i,13) = _v(j,1) + _p.dvy;
        _buf(i,14) = _v(j,2) + _p.dvz;
      } else {
        _buf(i,12) = _v(j,0);
        _buf(i,13) = _v(j,1);
        _buf(i,14) = _v(j,2);
      }
    }
  }
};

/* ----------------------------------------------------------------------
   border comm: buffer into new ghost atoms
------------------------------------------------------------------------- */

template<class DeviceType,int VEL>
struct AtomVecPeriKokkos_UnpackBorder {
  typedef DeviceType device_type;
  typedef ArrayTypes<DeviceType> AT;

  typename AT::t_xfloat_2d_const_um _buf;
  typename AT::t_x_array _x;
  typename AT::t_v_array _v;
  typename AT::t_tagint_1d _tag;
  typename AT::t_int_1d _type, _mask;
  typename AT::t_float_1d _rmass, _vfrac, _s0;
  typename AT::t_x_array _x0;
  int _first;

  AtomVecPeriKokkos_UnpackBorder(const AtomKokkos *atomKK,
                                 const DAT::tdual_float_1d &vfrac,
                                 const DAT::tdual_float_1d &s0,
                                 const DAT::tdual_x_array &x0,
                                 const DAT::tdual_xfloat_2d &buf, const int &first) :
    _x(atomKK->k_x.view<DeviceType>()), _v(atomKK->k_v.view<DeviceType>()),
    _tag(atomKK->k_tag.view<DeviceType>()), _type(atomKK->k_type.view<DeviceType>()),
    _mask(atomKK->k_mask.view<DeviceType>()), _rmass(atomKK->k_rmass.view<DeviceType>()),
    _vfrac(vfrac.view<DeviceType>()), _s0(s0.view<DeviceType>()),
    _x0(x0.view<DeviceType>()), _first(first)
  {
    const size_t elements = VEL ? AtomVecPeriKokkos::BORDER_VEL_SIZE : AtomVecPeriKokkos::BORDER_SIZE;
    const size_t maxsend = (buf.view<DeviceType>().extent(0)*buf.view<DeviceType>().extent(1))/elements;
    buffer_view<DeviceType>(_buf,buf,maxsend,elements);
  }

  KOKKOS_INLINE_FUNCTION
  void operator() (const int &i) const {
    const int k = i + _first;
    _x(k,0) = _buf(i,0);
    _x(k,1) = _buf(i,1);
    _x(k,2) = _buf(i,2);
    _tag(k) = static_cast<tagint>(d_ubuf(_buf(i,3)).i);
    _type(k) = static_cast<int>(d_ubuf(_buf(i,4)).i);
    _mask(k) = static_cast<int>(d_ubuf(_buf(i,5)).i);
    _rmass(k) = _buf(i,6);
    _vfrac(k) = _buf(i,7);
    _s0(k) = _buf(i,8);
    _x0(k,0) = _buf(i,9);
    _x0(k,1) = _buf(i,10);
    _x0(k,2) = _buf(i,11);
    if (VEL) {
      _v(k,0) = _buf(i,12);
      _v(k,1) = _buf(i,13);
      _v(k,2) = _buf(i,14);
    }
  }
};

/* ----------------------------------------------------------------------
   exchange: pack leaving atoms, fill their slots with atoms from the end
------------------------------------------------------------------------- */

template<class DeviceType>
struct AtomVecPeriKokkos_PackExchange {
  typedef DeviceType device_type;
  typedef ArrayTypes<DeviceType> AT;

  typename AT::t_x_array _x;
  typename AT::t_v_array _v;
  typename AT::t_tagint_1d _tag;
  typename AT::t_int_1d _type, _mask;
  typename AT::t_imageint_1d _image;
  typename AT::t_float_1d _rmass, _vfrac, _s0;
  typename AT::t_x_array _x0;
  typename AT::t_xfloat_2d_um _buf;
  typename AT::t_int_1d_const _sendlist;
  typename AT::t_int_1d_const _copylist;

  AtomVecPeriKokkos_PackExchange(const AtomKokkos *atomKK,
                                 const DAT::tdual_float_1d &vfrac,
                                 const DAT::tdual_float_1d &s0,
                                 const DAT::tdual_x_array &x0,
                                 const DAT::tdual_xfloat_2d &buf,
                                 const DAT::tdual_int_1d &sendlist,
                                 const DAT::tdual_int_1d &copylist) :
    _x(atomKK->k_x.view<DeviceType>()), _v(atomKK->k_v.view<DeviceType>()),
    _tag(atomKK->k_tag.view<DeviceType>()), _type(atomKK->k_type.view<DeviceType>()),
    _mask(atomKK->k_mask.view<DeviceType>()), _image(atomKK->k_image.view<DeviceType>()),
    _rmass(atomKK->k_rmass.view<DeviceType>()),
    _vfrac(vfrac.view<DeviceType>()), _s0(s0.view<DeviceType>()),
    _x0(x0.view<DeviceType>()),
    _sendlist(sendlist.view<DeviceType>()), _copylist(copylist.view<DeviceType>())
  {
    const size_t elements = AtomVecPeriKokkos::EXCHANGE_SIZE;
    const size_t maxsend = (buf.view<DeviceType>().extent(0)*buf.view<DeviceType>().extent(1))/elements;
    buffer_view<DeviceType>(_buf,buf,maxsend,elements);
  }

  KOKKOS_INLINE_FUNCTION
  void operator() (const int &mysend) const {
    const int i = _sendlist(mysend);
    _buf(mysend,0) = AtomVecPeriKokkos::EXCHANGE_SIZE;
    _buf(mysend,1) = _x(i,0);
    _buf(mysend,2) = _x(i,1);
    _buf(mysend,3) = _x(i,2);
    _buf(mysend,4) = _v(i,0);
    _buf(mysend,5) = _v(i,1);
    _buf(mysend,6) = _v(i,2);
    _buf(mysend,7) = d_ubuf(_tag(i)).d;
    _buf(mysend,8) = d_ubuf(_type(i)).d;
    _buf(mysend,9) = d_ubuf(_mask(i)).d;
    _buf(mysend,10) = d_ubuf(_image(i)).d;
    _buf(mysend,11) = _rmass(i);
    _buf(mysend,12) = _vfrac(i);
    _buf(mysend,13) = _s0(i);
    _buf(mysend,14) = _x0(i,0);
    _buf(mysend,15) = _x0(i,1);
    _buf(mysend,16) = _x0(i,2);

    const int j = _copylist(mysend);
    if (j > -1) {
      _x(i,0) = _x(j,0);
      _x(i,1) = _x(j,1);
      _x(i,2) = _x(j,2);
      _v(i,0) = _v(j,0);
      _v(i,1) = _v(j,1);
      _v(i,2) = _v(j,2);
      _tag(i) = _tag(j);
      _type(i) = _type(j);
      _mask(i) = _mask(j);
      _image(i) = _image(j);
      _rmass(i) = _rmass(j);
      _vfrac(i) = _vfrac(j);
      _s0(i) = _s0(j);
      _x0(i,0) = _x0(j,0);
      _x0(i,1) = _x0(j,1);
      _x0(i,2) = _x0(j,2);
    }
  }
};

/* ----------------------------------------------------------------------
   exchange: append the received atoms that lie in my subdomain
------------------------------------------------------------------------- */

template<class DeviceType>
struct AtomVecPeriKokkos_UnpackExchange {
  typedef DeviceType device_type;
  typedef ArrayTypes<DeviceType> AT;

  typename AT::t_x_array _x;
  typename AT::t_v_array _v;
  typename AT::t_tagint_1d _tag;
  typename AT::t_int_1d _type, _mask;
  typename AT::t_imageint_1d _image;
  typename AT::t_float_1d _rmass, _vfrac, _s0;
  typename AT::t_x_array _x0;
  typename AT::t_xfloat_2d_um _buf;
  typename AT::t_int_1d _nlocal;
  int _dim;
  X_FLOAT _lo, _hi;

  AtomVecPeriKokkos_UnpackExchange(const AtomKokkos *atomKK,
                                   const DAT::tdual_float_1d &vfrac,
                                   const DAT::tdual_float_1d &s0,
                                   const DAT::tdual_x_array &x0,
                                   const DAT::tdual_xfloat_2d &buf,
                                   const DAT::tdual_int_1d &nlocal,
                                   int dim, X_FLOAT lo, X_FLOAT hi) :
    _x(atomKK->k_x.view<DeviceType>()), _v(atomKK->k_v.view<DeviceType>()),
    _tag(atomKK->k_tag.view<DeviceType>()), _type(atomKK->k_type.view<DeviceType>()),
    _mask(atomKK->k_mask.view<DeviceType>()), _image(atomKK->k_image.view<DeviceType>()),
    _rmass(atomKK->k_rmass.view<DeviceType>()),
    _vfrac(vfrac.view<DeviceType>()), _s0(s0.view<DeviceType>()),
    _x0(x0.view<DeviceType>()),
    _nlocal(nlocal.view<DeviceType>()), _dim(dim), _lo(lo), _hi(hi)
  {
    const size_t elements = AtomVecPeriKokkos::EXCHANGE_SIZE;
    const size_t maxsend = (buf.view<DeviceType>().extent(0)*buf.view<DeviceType>().extent(1))/elements;
    buffer_view<DeviceType>(_buf,buf,maxsend,elements);
  }

  KOKKOS_INLINE_FUNCTION
  void operator() (const int &myrecv) const {
    const X_FLOAT xdim = _buf(myrecv,_dim+1);
    if (xdim >= _lo && xdim < _hi) {
      const int i = Kokkos::atomic_fetch_add(&_nlocal(0),1);
      _x(i,0) = _buf(myrecv,1);
      _x(i,1) = _buf(myrecv,2);
      _x(i,2) = _buf(myrecv,3);
      _v(i,0) = _buf(myrecv,4);
      _v(i,1) = _buf(myrecv,5);
      _v(i,2) = _buf(myrecv,6);
      _tag(i) = (tagint) d_ubuf(_buf(myrecv,7)).i;
      _type(i) = (int) d_ubuf(_buf(myrecv,8)).i;
      _mask(i) = (int) d_ubuf(_buf(myrecv,9)).i;
      _image(i) = (imageint) d_ubuf(_buf(myrecv,10)).i;
      _rmass(i) = _buf(myrecv,11);
      _vfrac(i) = _buf(myrecv,12);
      _s0(i) = _buf(myrecv,13);
      _x0(i,0) = _buf(myrecv,14);
      _x0(i,1) = _buf(myrecv,15);
      _x0(i,2) = _buf(myrecv,16);
    }
  }
};

/* ----------------------------------------------------------------------
   restart and data files name the atom style by atom->atom_style: give it
   the CPU style's name, as newer LAMMPS versions do with every suffix, so
   that a file written with -k on is read by atom_style peri, and by peri/kk
   with -sf kk (pair_style tlsph/kk does the same for the pair style)
------------------------------------------------------------------------- */

void AtomVecPeriKokkos::init()
{
  AtomVecKokkos::init();
  if (atom->atom_style && utils::strmatch(atom->atom_style, "^peri/kk")) {
    delete[] atom->atom_style;
    atom->atom_style = utils::strdup("peri");
  }
}

/* ====================================================================== */

AtomVecPeriKokkos::AtomVecPeriKokkos(LAMMPS *lmp) : AtomVecKokkos(lmp)
{
  // this class needs AtomKokkos and MemoryKokkos, which exist only with -k on

  if (lmp->kokkos == nullptr)
    error->all(FLERR,"Atom style peri/kk requires the KOKKOS package to be "
               "enabled (-k on)");

  if (lmp->citeme) lmp->citeme->add(cite_peri_package);

  molecular = Atom::ATOMIC;
  mass_type = PER_ATOM;

  comm_x_only = 0;        // s0 is sent with x
  comm_f_only = 1;
  size_forward = COMM_SIZE;
  size_reverse = 3;
  size_border = BORDER_SIZE;
  size_velocity = 3;
  size_data_atom = 7;     // id type vfrac rmass x y z
  size_data_vel = 4;
  xcol_data = 5;
  for (int k = 0; k < NFIELD; k++) ledger.newer[k] = 0;
  ledger_clear_counts();

  atom->rmass_flag = 1;
  atom->peri_flag = 1;
  atom->vfrac_flag = 1;

  no_comm_vel_flag = 0;
  no_border_vel_flag = 0;

  k_count = DAT::tdual_int_1d("atom::k_count",1);
  atomKK = (AtomKokkos *) atom;
  commKK = (CommKokkos *) comm;
  owner = atomKK;
}

/* ----------------------------------------------------------------------
   free the fields this class owns; the pointers in its Atom must not
   dangle, since a later atom style grows from them (Atom::create_avec).
   Its Atom, not lmp->atom: replicate deletes the old Atom (and this style)
   after lmp->atom was set to the new one, whose arrays must stay.
------------------------------------------------------------------------- */

AtomVecPeriKokkos::~AtomVecPeriKokkos()
{
  if (lmp->kokkos == nullptr) return;    // constructor failed
  memoryKK->destroy_kokkos(k_vfrac,owner->vfrac);
  memoryKK->destroy_kokkos(k_s0,owner->s0);
  memoryKK->destroy_kokkos(k_x0,owner->x0);
  k_vfrac = DAT::tdual_float_1d();
  k_s0 = DAT::tdual_float_1d();
  k_x0 = DAT::tdual_x_array();
}

/* ----------------------------------------------------------------------
   grow atom arrays
   n = 0 grows arrays by a chunk
   n > 0 allocates arrays to size n
------------------------------------------------------------------------- */

void AtomVecPeriKokkos::grow(int n)
{
  auto DELTA = LMP_KOKKOS_AV_DELTA;
  int step = MAX(DELTA,nmax*0.01);
  if (n == 0) nmax += step;
  else nmax = n;
  atomKK->nmax = nmax;
  if (nmax < 0 || nmax > MAXSMALLINT)
    error->one(FLERR,"Per-processor system is too big");

  atomKK->sync(Device,ALL_MASK);
  atomKK->modified(Device,ALL_MASK);

  memoryKK->grow_kokkos(atomKK->k_tag,atomKK->tag,nmax,"atom:tag");
  memoryKK->grow_kokkos(atomKK->k_type,atomKK->type,nmax,"atom:type");
  memoryKK->grow_kokkos(atomKK->k_mask,atomKK->mask,nmax,"atom:mask");
  memoryKK->grow_kokkos(atomKK->k_image,atomKK->image,nmax,"atom:image");

  memoryKK->grow_kokkos(atomKK->k_x,atomKK->x,nmax,"atom:x");
  memoryKK->grow_kokkos(atomKK->k_v,atomKK->v,nmax,"atom:v");
  memoryKK->grow_kokkos(atomKK->k_f,atomKK->f,nmax,"atom:f");

  memoryKK->grow_kokkos(atomKK->k_rmass,atomKK->rmass,nmax,"atom:rmass");
  memoryKK->grow_kokkos(k_vfrac,atomKK->vfrac,nmax,"atom:vfrac");
  memoryKK->grow_kokkos(k_s0,atomKK->s0,nmax,"atom:s0");
  memoryKK->grow_kokkos(k_x0,atomKK->x0,nmax,"atom:x0");

  grow_pointers();
  atomKK->sync(Host,ALL_MASK);

  if (atom->nextra_grow)
    for (int iextra = 0; iextra < atom->nextra_grow; iextra++)
      modify->fix[atom->extra_grow[iextra]]->grow_arrays(nmax);
}

/* ----------------------------------------------------------------------
   reset local array ptrs
------------------------------------------------------------------------- */

void AtomVecPeriKokkos::grow_pointers()
{
  tag = atomKK->tag;
  d_tag = atomKK->k_tag.d_view;
  h_tag = atomKK->k_tag.h_view;

  type = atomKK->type;
  d_type = atomKK->k_type.d_view;
  h_type = atomKK->k_type.h_view;
  mask = atomKK->mask;
  d_mask = atomKK->k_mask.d_view;
  h_mask = atomKK->k_mask.h_view;
  image = atomKK->image;
  d_image = atomKK->k_image.d_view;
  h_image = atomKK->k_image.h_view;

  x = atomKK->x;
  d_x = atomKK->k_x.d_view;
  h_x = atomKK->k_x.h_view;
  v = atomKK->v;
  d_v = atomKK->k_v.d_view;
  h_v = atomKK->k_v.h_view;
  f = atomKK->f;
  d_f = atomKK->k_f.d_view;
  h_f = atomKK->k_f.h_view;

  rmass = atomKK->rmass;
  d_rmass = atomKK->k_rmass.d_view;
  h_rmass = atomKK->k_rmass.h_view;
  vfrac = atomKK->vfrac;
  d_vfrac = k_vfrac.d_view;
  h_vfrac = k_vfrac.h_view;
  s0 = atomKK->s0;
  d_s0 = k_s0.d_view;
  h_s0 = k_s0.h_view;
  x0 = atomKK->x0;
  d_x0 = k_x0.d_view;
  h_x0 = k_x0.h_view;
}

/* ----------------------------------------------------------------------
   copy atom I info to atom J
------------------------------------------------------------------------- */

void AtomVecPeriKokkos::copy(int i, int j, int delflag)
{
  atomKK->sync(Host,OWNED_STD);
  atomKK->sync(Host,EXT_ALL);

  h_tag[j] = h_tag[i];
  h_type[j] = h_type[i];
  h_mask[j] = h_mask[i];
  h_image[j] = h_image[i];
  h_x(j,0) = h_x(i,0);
  h_x(j,1) = h_x(i,1);
  h_x(j,2) = h_x(i,2);
  h_v(j,0) = h_v(i,0);
  h_v(j,1) = h_v(i,1);
  h_v(j,2) = h_v(i,2);

  h_rmass[j] = h_rmass[i];
  h_vfrac[j] = h_vfrac[i];
  h_s0[j] = h_s0[i];
  h_x0(j,0) = h_x0(i,0);
  h_x0(j,1) = h_x0(i,1);
  h_x0(j,2) = h_x0(i,2);

  if (atom->nextra_grow)
    for (int iextra = 0; iextra < atom->nextra_grow; iextra++)
      modify->fix[atom->extra_grow[iextra]]->copy_arrays(i,j,delflag);

  atomKK->modified(Host,OWNED_STD);
  atomKK->modified(Host,EXT_ALL);
}

/* ======================================================================
   Kokkos forward communication
   ====================================================================== */

template<class DeviceType>
int AtomVecPeriKokkos::pack_comm_kk(const int &n, const DAT::tdual_int_2d &list,
                                    const int &iswap, const DAT::tdual_xfloat_2d &buf,
                                    const int &pbc_flag, const int *pbc, int vel)
{
  const ExecutionSpace space = commKK->forward_comm_on_host ? Host : Device;
  atomKK->sync(space,vel ? (X_MASK|V_MASK|MASK_MASK) : X_MASK);
  atomKK->sync(space,EXT_S0);

  PeriPackParams p;
  memset(&p,0,sizeof(p));
  p.xprd = domain->xprd; p.yprd = domain->yprd; p.zprd = domain->zprd;
  p.xy = domain->xy; p.xz = domain->xz; p.yz = domain->yz;
  for (int k = 0; k < 6; k++) p.pbc[k] = pbc[k];
  if (vel && deform_vremap)
    for (int k = 0; k < 6; k++) p.h_rate[k] = h_rate[k];
  p.deform_groupbit = deform_groupbit;
  const int triclinic = domain->triclinic;

#define PERI_PACK_COMM(PBC,TRI,VEL,DEF) { \
    AtomVecPeriKokkos_PackComm<DeviceType,PBC,TRI,VEL,DEF> \
      functor(atomKK,k_s0,buf,list,iswap,p); \
    Kokkos::parallel_for(n,functor); }

  if (vel) {
    if (pbc_flag) {
      if (deform_vremap) {
        if (triclinic) PERI_PACK_COMM(1,1,1,1)
        else PERI_PACK_COMM(1,0,1,1)
      } else {
        if (triclinic) PERI_PACK_COMM(1,1,1,0)
        else PERI_PACK_COMM(1,0,1,0)
      }
    } else PERI_PACK_COMM(0,0,1,0)
  } else {
    if (pbc_flag) {
      if (triclinic) PERI_PACK_COMM(1,1,0,0)
      else PERI_PACK_COMM(1,0,0,0)
    } else PERI_PACK_COMM(0,0,0,0)
  }
#undef PERI_PACK_COMM

  return n*(vel ? COMM_VEL_SIZE : COMM_SIZE);
}

/* ---------------------------------------------------------------------- */

template<class DeviceType>
void AtomVecPeriKokkos::unpack_comm_kk(const int &n, const int &first,
                                       const DAT::tdual_xfloat_2d &buf, int vel)
{
  const ExecutionSpace space = commKK->forward_comm_on_host ? Host : Device;
  atomKK->sync(space,vel ? (X_MASK|V_MASK) : X_MASK);
  atomKK->sync(space,EXT_S0);
  if (vel) {
    AtomVecPeriKokkos_UnpackComm<DeviceType,1> functor(atomKK,k_s0,buf,first);
    Kokkos::parallel_for(n,functor);
  } else {
    AtomVecPeriKokkos_UnpackComm<DeviceType,0> functor(atomKK,k_s0,buf,first);
    Kokkos::parallel_for(n,functor);
  }
  atomKK->modified(space,vel ? (X_MASK|V_MASK) : X_MASK);
  atomKK->modified(space,EXT_S0);
}

/* ---------------------------------------------------------------------- */

int AtomVecPeriKokkos::pack_comm_kokkos(const int &n, const DAT::tdual_int_2d &list,
                                        const int &iswap, const DAT::tdual_xfloat_2d &buf,
                                        const int &pbc_flag, const int *pbc)
{
  if (commKK->forward_comm_on_host)
    return pack_comm_kk<LMPHostType>(n,list,iswap,buf,pbc_flag,pbc,0);
  return pack_comm_kk<LMPDeviceType>(n,list,iswap,buf,pbc_flag,pbc,0);
}

void AtomVecPeriKokkos::unpack_comm_kokkos(const int &n, const int &first,
                                           const DAT::tdual_xfloat_2d &buf)
{
  if (commKK->forward_comm_on_host) unpack_comm_kk<LMPHostType>(n,first,buf,0);
  else unpack_comm_kk<LMPDeviceType>(n,first,buf,0);
}

int AtomVecPeriKokkos::pack_comm_vel_kokkos(const int &n, const DAT::tdual_int_2d &list,
                                            const int &iswap, const DAT::tdual_xfloat_2d &buf,
                                            const int &pbc_flag, const int *pbc)
{
  if (commKK->forward_comm_on_host)
    return pack_comm_kk<LMPHostType>(n,list,iswap,buf,pbc_flag,pbc,1);
  return pack_comm_kk<LMPDeviceType>(n,list,iswap,buf,pbc_flag,pbc,1);
}

void AtomVecPeriKokkos::unpack_comm_vel_kokkos(const int &n, const int &first,
                                               const DAT::tdual_xfloat_2d &buf)
{
  if (commKK->forward_comm_on_host) unpack_comm_kk<LMPHostType>(n,first,buf,1);
  else unpack_comm_kk<LMPDeviceType>(n,first,buf,1);
}

/* ---------------------------------------------------------------------- */

template<class DeviceType>
int AtomVecPeriKokkos::pack_comm_self_kk(const int &n, const DAT::tdual_int_2d &list,
                                         const int &iswap, const int nfirst,
                                         const int &pbc_flag, const int *pbc)
{
  const ExecutionSpace space = commKK->forward_comm_on_host ? Host : Device;
  atomKK->sync(space,X_MASK);
  atomKK->sync(space,EXT_S0);

  PeriPackParams p;
  memset(&p,0,sizeof(p));
  p.xprd = domain->xprd; p.yprd = domain->yprd; p.zprd = domain->zprd;
  p.xy = domain->xy; p.xz = domain->xz; p.yz = domain->yz;
  for (int k = 0; k < 6; k++) p.pbc[k] = pbc[k];

  if (pbc_flag) {
    if (domain->triclinic) {
      AtomVecPeriKokkos_PackCommSelf<DeviceType,1,1> functor(atomKK,k_s0,nfirst,list,iswap,p);
      Kokkos::parallel_for(n,functor);
    } else {
      AtomVecPeriKokkos_PackCommSelf<DeviceType,1,0> functor(atomKK,k_s0,nfirst,list,iswap,p);
      Kokkos::parallel_for(n,functor);
    }
  } else {
    AtomVecPeriKokkos_PackCommSelf<DeviceType,0,0> functor(atomKK,k_s0,nfirst,list,iswap,p);
    Kokkos::parallel_for(n,functor);
  }

  atomKK->modified(space,X_MASK);
  atomKK->modified(space,EXT_S0);
  return n*COMM_SIZE;
}

int AtomVecPeriKokkos::pack_comm_self(const int &n, const DAT::tdual_int_2d &list,
                                      const int &iswap, const int nfirst,
                                      const int &pbc_flag, const int *pbc)
{
  if (commKK->forward_comm_on_host)
    return pack_comm_self_kk<LMPHostType>(n,list,iswap,nfirst,pbc_flag,pbc);
  return pack_comm_self_kk<LMPDeviceType>(n,list,iswap,nfirst,pbc_flag,pbc);
}

/* ---------------------------------------------------------------------- */

int AtomVecPeriKokkos::pack_comm_self_fused(const int &n, const DAT::tdual_int_2d &list,
                                            const DAT::tdual_int_1d &sendnum_scan,
                                            const DAT::tdual_int_1d &firstrecv,
                                            const DAT::tdual_int_1d &pbc_flag,
                                            const DAT::tdual_int_2d &pbc,
                                            const DAT::tdual_int_1d &g2l)
{
  const ExecutionSpace space = commKK->forward_comm_on_host ? Host : Device;
  atomKK->sync(space,X_MASK);
  atomKK->sync(space,EXT_S0);

  PeriPackParams p;
  memset(&p,0,sizeof(p));
  p.xprd = domain->xprd; p.yprd = domain->yprd; p.zprd = domain->zprd;
  p.xy = domain->xy; p.xz = domain->xz; p.yz = domain->yz;

#define PERI_PACK_SELF_FUSED(DEVICE,TRI) { \
    AtomVecPeriKokkos_PackCommSelfFused<DEVICE,TRI> functor(atomKK,k_s0,list,pbc,pbc_flag, \
                                                            firstrecv,sendnum_scan,g2l,p); \
    Kokkos::parallel_for(n,functor); }

  if (space == Host) {
    if (domain->triclinic) PERI_PACK_SELF_FUSED(LMPHostType,1)
    else PERI_PACK_SELF_FUSED(LMPHostType,0)
  } else {
    if (domain->triclinic) PERI_PACK_SELF_FUSED(LMPDeviceType,1)
    else PERI_PACK_SELF_FUSED(LMPDeviceType,0)
  }
#undef PERI_PACK_SELF_FUSED

  atomKK->modified(space,X_MASK);
  atomKK->modified(space,EXT_S0);
  return n*COMM_SIZE;
}

/* ======================================================================
   Kokkos border communication
   ====================================================================== */

template<class DeviceType>
int AtomVecPeriKokkos::pack_border_kk(int n, DAT::tdual_int_2d k_sendlist,
                                      DAT::tdual_xfloat_2d buf, int iswap,
                                      int pbc_flag, int *pbc, int vel)
{
  PeriPackParams p;
  memset(&p,0,sizeof(p));
  p.deform_groupbit = deform_groupbit;
  if (pbc_flag) {
    if (domain->triclinic == 0) {
      p.dx = pbc[0]*domain->xprd;
      p.dy = pbc[1]*domain->yprd;
      p.dz = pbc[2]*domain->zprd;
    } else {
      p.dx = pbc[0];
      p.dy = pbc[1];
      p.dz = pbc[2];
    }
    if (vel && deform_vremap) {
      p.dvx = pbc[0]*h_rate[0] + pbc[5]*h_rate[5] + pbc[4]*h_rate[4];
      p.dvy = pbc[1]*h_rate[1] + pbc[3]*h_rate[3];
      p.dvz = pbc[2]*h_rate[2];
    }
  }

#define PERI_PACK_BORDER(PBC,VEL,DEF) { \
    AtomVecPeriKokkos_PackBorder<DeviceType,PBC,VEL,DEF> \
      functor(atomKK,k_vfrac,k_s0,k_x0,buf,k_sendlist,iswap,p); \
    Kokkos::parallel_for(n,functor); }

  if (vel) {
    if (pbc_flag) {
      if (deform_vremap) PERI_PACK_BORDER(1,1,1)
      else PERI_PACK_BORDER(1,1,0)
    } else PERI_PACK_BORDER(0,1,0)
  } else {
    if (pbc_flag) PERI_PACK_BORDER(1,0,0)
    else PERI_PACK_BORDER(0,0,0)
  }
#undef PERI_PACK_BORDER

  return n*(vel ? BORDER_VEL_SIZE : BORDER_SIZE);
}

int AtomVecPeriKokkos::pack_border_kokkos(int n, DAT::tdual_int_2d k_sendlist,
                                          DAT::tdual_xfloat_2d buf, int iswap,
                                          int pbc_flag, int *pbc, ExecutionSpace space)
{
  atomKK->sync(space,BORDER_STD);
  atomKK->sync(space,EXT_ALL);
  if (space == Host)
    return pack_border_kk<LMPHostType>(n,k_sendlist,buf,iswap,pbc_flag,pbc,0);
  return pack_border_kk<LMPDeviceType>(n,k_sendlist,buf,iswap,pbc_flag,pbc,0);
}

int AtomVecPeriKokkos::pack_border_vel_kokkos(int n, DAT::tdual_int_2d k_sendlist,
                                              DAT::tdual_xfloat_2d buf, int iswap,
                                              int pbc_flag, int *pbc, ExecutionSpace space)
{
  atomKK->sync(space,BORDER_STD|V_MASK);
  atomKK->sync(space,EXT_ALL);
  if (space == Host)
    return pack_border_kk<LMPHostType>(n,k_sendlist,buf,iswap,pbc_flag,pbc,1);
  return pack_border_kk<LMPDeviceType>(n,k_sendlist,buf,iswap,pbc_flag,pbc,1);
}

/* ---------------------------------------------------------------------- */

template<class DeviceType>
void AtomVecPeriKokkos::unpack_border_kk(const int &n, const int &first,
                                         const DAT::tdual_xfloat_2d &buf, int vel)
{
  if (vel) {
    AtomVecPeriKokkos_UnpackBorder<DeviceType,1> functor(atomKK,k_vfrac,k_s0,k_x0,buf,first);
    Kokkos::parallel_for(n,functor);
  } else {
    AtomVecPeriKokkos_UnpackBorder<DeviceType,0> functor(atomKK,k_vfrac,k_s0,k_x0,buf,first);
    Kokkos::parallel_for(n,functor);
  }
}

void AtomVecPeriKokkos::unpack_border_kokkos(const int &n, const int &first,
                                             const DAT::tdual_xfloat_2d &buf,
                                             ExecutionSpace space)
{
  while (first+n >= nmax) grow(0);
  atomKK->sync(space,BORDER_STD);
  atomKK->sync(space,EXT_ALL);
  if (space == Host) unpack_border_kk<LMPHostType>(n,first,buf,0);
  else unpack_border_kk<LMPDeviceType>(n,first,buf,0);
  atomKK->modified(space,BORDER_STD);
  atomKK->modified(space,EXT_ALL);
}

void AtomVecPeriKokkos::unpack_border_vel_kokkos(const int &n, const int &first,
                                                 const DAT::tdual_xfloat_2d &buf,
                                                 ExecutionSpace space)
{
  while (first+n >= nmax) grow(0);
  atomKK->sync(space,BORDER_STD|V_MASK);
  atomKK->sync(space,EXT_ALL);
  if (space == Host) unpack_border_kk<LMPHostType>(n,first,buf,1);
  else unpack_border_kk<LMPDeviceType>(n,first,buf,1);
  atomKK->modified(space,BORDER_STD|V_MASK);
  atomKK->modified(space,EXT_ALL);
}

/* ======================================================================
   Kokkos exchange
   ====================================================================== */

int AtomVecPeriKokkos::pack_exchange_kokkos(const int &nsend, DAT::tdual_xfloat_2d &k_buf,
                                            DAT::tdual_int_1d k_sendlist,
                                            DAT::tdual_int_1d k_copylist,
                                            ExecutionSpace space, int /*dim*/,
                                            X_FLOAT /*lo*/, X_FLOAT /*hi*/)
{
  const int ncols = k_buf.view<LMPHostType>().extent(1);
  if (nsend > (int) (k_buf.view<LMPHostType>().extent(0)*ncols)/EXCHANGE_SIZE) {
    int newsize = nsend*(EXCHANGE_SIZE+1)/ncols + 1;
    k_buf.resize(newsize,ncols);
  }

  atomKK->sync(space,OWNED_STD);
  atomKK->sync(space,EXT_ALL);

  if (space == Host) {
    AtomVecPeriKokkos_PackExchange<LMPHostType>
      functor(atomKK,k_vfrac,k_s0,k_x0,k_buf,k_sendlist,k_copylist);
    Kokkos::parallel_for(nsend,functor);
  } else {
    AtomVecPeriKokkos_PackExchange<LMPDeviceType>
      functor(atomKK,k_vfrac,k_s0,k_x0,k_buf,k_sendlist,k_copylist);
    Kokkos::parallel_for(nsend,functor);
  }

  // the slots of the leaving atoms were refilled

  atomKK->modified(space,OWNED_STD);
  atomKK->modified(space,EXT_ALL);
  return nsend*EXCHANGE_SIZE;
}

/* ---------------------------------------------------------------------- */

int AtomVecPeriKokkos::unpack_exchange_kokkos(DAT::tdual_xfloat_2d &k_buf, int nrecv,
                                              int nlocal, int dim, X_FLOAT lo, X_FLOAT hi,
                                              ExecutionSpace space)
{
  // room for all received atoms (at most nrecv/EXCHANGE_SIZE stay here)

  const int nrecv_atoms = nrecv/EXCHANGE_SIZE;
  while (nlocal + nrecv_atoms >= nmax) grow(0);

  atomKK->sync(space,OWNED_STD);
  atomKK->sync(space,EXT_ALL);

  k_count.h_view(0) = nlocal;
  if (space == Host) {
    AtomVecPeriKokkos_UnpackExchange<LMPHostType>
      functor(atomKK,k_vfrac,k_s0,k_x0,k_buf,k_count,dim,lo,hi);
    Kokkos::parallel_for(nrecv_atoms,functor);
  } else {
    k_count.modify<LMPHostType>();
    k_count.sync<LMPDeviceType>();
    AtomVecPeriKokkos_UnpackExchange<LMPDeviceType>
      functor(atomKK,k_vfrac,k_s0,k_x0,k_buf,k_count,dim,lo,hi);
    Kokkos::parallel_for(nrecv_atoms,functor);
    k_count.modify<LMPDeviceType>();
    k_count.sync<LMPHostType>();
  }

  atomKK->modified(space,OWNED_STD);
  atomKK->modified(space,EXT_ALL);

  return k_count.h_view(0);
}

/* ======================================================================
   host (classic) communication
   ====================================================================== */

int AtomVecPeriKokkos::pack_comm(int n, int *list, double *buf, int pbc_flag, int *pbc)
{
  int i,j,m;
  double dx,dy,dz;

  atomKK->sync(Host,X_MASK);
  atomKK->sync(Host,EXT_S0);

  m = 0;
  if (pbc_flag == 0) {
    dx = dy = dz = 0.0;
  } else if (domain->triclinic == 0) {
    dx = pbc[0]*domain->xprd;
    dy = pbc[1]*domain->yprd;
    dz = pbc[2]*domain->zprd;
  } else {
    dx = pbc[0]*domain->xprd + pbc[5]*domain->xy + pbc[4]*domain->xz;
    dy = pbc[1]*domain->yprd + pbc[3]*domain->yz;
    dz = pbc[2]*domain->zprd;
  }
  for (i = 0; i < n; i++) {
    j = list[i];
    if (pbc_flag == 0) {
      buf[m++] = h_x(j,0);
      buf[m++] = h_x(j,1);
      buf[m++] = h_x(j,2);
    } else {
      buf[m++] = h_x(j,0) + dx;
      buf[m++] = h_x(j,1) + dy;
      buf[m++] = h_x(j,2) + dz;
    }
    buf[m++] = h_s0[j];
  }
  return m;
}

/* ---------------------------------------------------------------------- */

int AtomVecPeriKokkos::pack_comm_vel(int n, int *list, double *buf, int pbc_flag, int *pbc)
{
  int i,j,m;
  double dx,dy,dz,dvx,dvy,dvz;

  atomKK->sync(Host,X_MASK|V_MASK|MASK_MASK);
  atomKK->sync(Host,EXT_S0);

  dx = dy = dz = dvx = dvy = dvz = 0.0;
  if (pbc_flag) {
    if (domain->triclinic == 0) {
      dx = pbc[0]*domain->xprd;
      dy = pbc[1]*domain->yprd;
      dz = pbc[2]*domain->zprd;
    } else {
      dx = pbc[0]*domain->xprd + pbc[5]*domain->xy + pbc[4]*domain->xz;
      dy = pbc[1]*domain->yprd + pbc[3]*domain->yz;
      dz = pbc[2]*domain->zprd;
    }
    if (deform_vremap) {
      dvx = pbc[0]*h_rate[0] + pbc[5]*h_rate[5] + pbc[4]*h_rate[4];
      dvy = pbc[1]*h_rate[1] + pbc[3]*h_rate[3];
      dvz = pbc[2]*h_rate[2];
    }
  }

  m = 0;
  for (i = 0; i < n; i++) {
    j = list[i];
    if (pbc_flag == 0) {
      buf[m++] = h_x(j,0);
      buf[m++] = h_x(j,1);
      buf[m++] = h_x(j,2);
    } else {
      buf[m++] = h_x(j,0) + dx;
      buf[m++] = h_x(j,1) + dy;
      buf[m++] = h_x(j,2) + dz;
    }
    if (pbc_flag && deform_vremap && (h_mask[j] & deform_groupbit)) {
      buf[m++] = h_v(j,0) + dvx;
      buf[m++] = h_v(j,1) + dvy;
      buf[m++] = h_v(j,2) + dvz;
    } else {
      buf[m++] = h_v(j,0);
      buf[m++] = h_v(j,1);
      buf[m++] = h_v(j,2);
    }
    buf[m++] = h_s0[j];
  }
  return m;
}

/* ---------------------------------------------------------------------- */

void AtomVecPeriKokkos::unpack_comm(int n, int first, double *buf)
{
  atomKK->sync(Host,X_MASK);
  atomKK->sync(Host,EXT_S0);
  int m = 0;
  const int last = first + n;
  for (int i = first; i < last; i++) {
    h_x(i,0) = buf[m++];
    h_x(i,1) = buf[m++];
    h_x(i,2) = buf[m++];
    h_s0[i] = buf[m++];
  }
  atomKK->modified(Host,X_MASK);
  atomKK->modified(Host,EXT_S0);
}

/* ---------------------------------------------------------------------- */

void AtomVecPeriKokkos::unpack_comm_vel(int n, int first, double *buf)
{
  atomKK->sync(Host,X_MASK|V_MASK);
  atomKK->sync(Host,EXT_S0);
  int m = 0;
  const int last = first + n;
  for (int i = first; i < last; i++) {
    h_x(i,0) = buf[m++];
    h_x(i,1) = buf[m++];
    h_x(i,2) = buf[m++];
    h_v(i,0) = buf[m++];
    h_v(i,1) = buf[m++];
    h_v(i,2) = buf[m++];
    h_s0[i] = buf[m++];
  }
  atomKK->modified(Host,X_MASK|V_MASK);
  atomKK->modified(Host,EXT_S0);
}

/* ---------------------------------------------------------------------- */

int AtomVecPeriKokkos::pack_comm_hybrid(int n, int *list, double *buf)
{
  atomKK->sync(Host,EXT_S0);
  int m = 0;
  for (int i = 0; i < n; i++) buf[m++] = h_s0[list[i]];
  return m;
}

int AtomVecPeriKokkos::unpack_comm_hybrid(int n, int first, double *buf)
{
  atomKK->sync(Host,EXT_S0);
  int m = 0;
  const int last = first + n;
  for (int i = first; i < last; i++) h_s0[i] = buf[m++];
  atomKK->modified(Host,EXT_S0);
  return m;
}

/* ----------------------------------------------------------------------
   border pack for host comm, with (vel = 1) or without velocities
------------------------------------------------------------------------- */

int AtomVecPeriKokkos::pack_border_common(int n, int *list, double *buf,
                                          int pbc_flag, int *pbc, int vel)
{
  int i,j,m;
  double dx,dy,dz,dvx,dvy,dvz;

  atomKK->sync(Host,BORDER_STD|(vel ? V_MASK : 0));
  atomKK->sync(Host,EXT_ALL);

  dx = dy = dz = dvx = dvy = dvz = 0.0;
  if (pbc_flag) {
    if (domain->triclinic == 0) {
      dx = pbc[0]*domain->xprd;
      dy = pbc[1]*domain->yprd;
      dz = pbc[2]*domain->zprd;
    } else {
      dx = pbc[0];
      dy = pbc[1];
      dz = pbc[2];
    }
    if (vel && deform_vremap) {
      dvx = pbc[0]*h_rate[0] + pbc[5]*h_rate[5] + pbc[4]*h_rate[4];
      dvy = pbc[1]*h_rate[1] + pbc[3]*h_rate[3];
      dvz = pbc[2]*h_rate[2];
    }
  }

  m = 0;
  for (i = 0; i < n; i++) {
    j = list[i];
    buf[m++] = h_x(j,0) + dx;
    buf[m++] = h_x(j,1) + dy;
    buf[m++] = h_x(j,2) + dz;
    buf[m++] = ubuf(h_tag[j]).d;
    buf[m++] = ubuf(h_type[j]).d;
    buf[m++] = ubuf(h_mask[j]).d;
    buf[m++] = h_rmass[j];
    buf[m++] = h_vfrac[j];
    buf[m++] = h_s0[j];
    buf[m++] = h_x0(j,0);
    buf[m++] = h_x0(j,1);
    buf[m++] = h_x0(j,2);
    if (vel) {
      if (pbc_flag && deform_vremap && (h_mask[j] & deform_groupbit)) {
        buf[m++] = h_v(j,0) + dvx;
        buf[m++] = h_v(j,1) + dvy;
        buf[m++] = h_v(j,2) + dvz;
      } else {
        buf[m++] = h_v(j,0);
        buf[m++] = h_v(j,1);
        buf[m++] = h_v(j,2);
      }
    }
  }

  if (atom->nextra_border)
    for (int iextra = 0; iextra < atom->nextra_border; iextra++)
      m += modify->fix[atom->extra_border[iextra]]->pack_border(n,list,&buf[m]);

  return m;
}

int AtomVecPeriKokkos::pack_border(int n, int *list, double *buf, int pbc_flag, int *pbc)
{
  return pack_border_common(n,list,buf,pbc_flag,pbc,0);
}

int AtomVecPeriKokkos::pack_border_vel(int n, int *list, double *buf, int pbc_flag, int *pbc)
{
  return pack_border_common(n,list,buf,pbc_flag,pbc,1);
}

int AtomVecPeriKokkos::pack_border_hybrid(int n, int *list, double *buf)
{
  atomKK->sync(Host,RMASS_MASK);
  atomKK->sync(Host,EXT_ALL);
  int m = 0;
  for (int i = 0; i < n; i++) {
    const int j = list[i];
    buf[m++] = h_rmass[j];
    buf[m++] = h_vfrac[j];
    buf[m++] = h_s0[j];
    buf[m++] = h_x0(j,0);
    buf[m++] = h_x0(j,1);
    buf[m++] = h_x0(j,2);
  }
  return m;
}

/* ---------------------------------------------------------------------- */

void AtomVecPeriKokkos::unpack_border_common(int n, int first, double *buf, int vel)
{
  int i,m,last;

  while (first+n >= nmax) grow(0);
  atomKK->sync(Host,BORDER_STD|(vel ? V_MASK : 0));
  atomKK->sync(Host,EXT_ALL);

  m = 0;
  last = first + n;
  for (i = first; i < last; i++) {
    h_x(i,0) = buf[m++];
    h_x(i,1) = buf[m++];
    h_x(i,2) = buf[m++];
    h_tag[i] = (tagint) ubuf(buf[m++]).i;
    h_type[i] = (int) ubuf(buf[m++]).i;
    h_mask[i] = (int) ubuf(buf[m++]).i;
    h_rmass[i] = buf[m++];
    h_vfrac[i] = buf[m++];
    h_s0[i] = buf[m++];
    h_x0(i,0) = buf[m++];
    h_x0(i,1) = buf[m++];
    h_x0(i,2) = buf[m++];
    if (vel) {
      h_v(i,0) = buf[m++];
      h_v(i,1) = buf[m++];
      h_v(i,2) = buf[m++];
    }
  }

  atomKK->modified(Host,BORDER_STD|(vel ? V_MASK : 0));
  atomKK->modified(Host,EXT_ALL);

  if (atom->nextra_border)
    for (int iextra = 0; iextra < atom->nextra_border; iextra++)
      m += modify->fix[atom->extra_border[iextra]]->unpack_border(n,first,&buf[m]);
}

void AtomVecPeriKokkos::unpack_border(int n, int first, double *buf)
{
  unpack_border_common(n,first,buf,0);
}

void AtomVecPeriKokkos::unpack_border_vel(int n, int first, double *buf)
{
  unpack_border_common(n,first,buf,1);
}

int AtomVecPeriKokkos::unpack_border_hybrid(int n, int first, double *buf)
{
  atomKK->sync(Host,RMASS_MASK);
  atomKK->sync(Host,EXT_ALL);
  int m = 0;
  const int last = first + n;
  for (int i = first; i < last; i++) {
    h_rmass[i] = buf[m++];
    h_vfrac[i] = buf[m++];
    h_s0[i] = buf[m++];
    h_x0(i,0) = buf[m++];
    h_x0(i,1) = buf[m++];
    h_x0(i,2) = buf[m++];
  }
  atomKK->modified(Host,RMASS_MASK);
  atomKK->modified(Host,EXT_ALL);
  return m;
}

/* ----------------------------------------------------------------------
   pack data for atom I for sending to another proc
   xyz must be 1st 3 values, so comm::exchange() can test on them
------------------------------------------------------------------------- */

int AtomVecPeriKokkos::pack_exchange(int i, double *buf)
{
  atomKK->sync(Host,OWNED_STD);
  atomKK->sync(Host,EXT_ALL);

  int m = 1;
  buf[m++] = h_x(i,0);
  buf[m++] = h_x(i,1);
  buf[m++] = h_x(i,2);
  buf[m++] = h_v(i,0);
  buf[m++] = h_v(i,1);
  buf[m++] = h_v(i,2);
  buf[m++] = ubuf(h_tag[i]).d;
  buf[m++] = ubuf(h_type[i]).d;
  buf[m++] = ubuf(h_mask[i]).d;
  buf[m++] = ubuf(h_image[i]).d;
  buf[m++] = h_rmass[i];
  buf[m++] = h_vfrac[i];
  buf[m++] = h_s0[i];
  buf[m++] = h_x0(i,0);
  buf[m++] = h_x0(i,1);
  buf[m++] = h_x0(i,2);

  if (atom->nextra_grow)
    for (int iextra = 0; iextra < atom->nextra_grow; iextra++)
      m += modify->fix[atom->extra_grow[iextra]]->pack_exchange(i,&buf[m]);

  buf[0] = m;
  return m;
}

/* ---------------------------------------------------------------------- */

int AtomVecPeriKokkos::unpack_exchange(double *buf)
{
  int nlocal = atom->nlocal;
  if (nlocal == nmax) grow(0);
  atomKK->sync(Host,OWNED_STD);
  atomKK->sync(Host,EXT_ALL);

  int m = 1;
  h_x(nlocal,0) = buf[m++];
  h_x(nlocal,1) = buf[m++];
  h_x(nlocal,2) = buf[m++];
  h_v(nlocal,0) = buf[m++];
  h_v(nlocal,1) = buf[m++];
  h_v(nlocal,2) = buf[m++];
  h_tag[nlocal] = (tagint) ubuf(buf[m++]).i;
  h_type[nlocal] = (int) ubuf(buf[m++]).i;
  h_mask[nlocal] = (int) ubuf(buf[m++]).i;
  h_image[nlocal] = (imageint) ubuf(buf[m++]).i;
  h_rmass[nlocal] = buf[m++];
  h_vfrac[nlocal] = buf[m++];
  h_s0[nlocal] = buf[m++];
  h_x0(nlocal,0) = buf[m++];
  h_x0(nlocal,1) = buf[m++];
  h_x0(nlocal,2) = buf[m++];

  atomKK->modified(Host,OWNED_STD);
  atomKK->modified(Host,EXT_ALL);

  if (atom->nextra_grow)
    for (int iextra = 0; iextra < atom->nextra_grow; iextra++)
      m += modify->fix[atom->extra_grow[iextra]]->unpack_exchange(nlocal,&buf[m]);

  atom->nlocal++;
  return m;
}

/* ----------------------------------------------------------------------
   size of restart data for all atoms owned by this proc
   include extra data stored by fixes
------------------------------------------------------------------------- */

int AtomVecPeriKokkos::size_restart()
{
  int nlocal = atom->nlocal;
  int n = RESTART_SIZE * nlocal;

  if (atom->nextra_restart)
    for (int iextra = 0; iextra < atom->nextra_restart; iextra++)
      for (int i = 0; i < nlocal; i++)
        n += modify->fix[atom->extra_restart[iextra]]->size_restart(i);

  return n;
}

/* ----------------------------------------------------------------------
   pack atom I's data for restart file including extra quantities
   xyz must be 1st 3 values, so that read_restart can test on them
   same layout as AtomVecPeri (default fields, then rmass vfrac s0 x0)
------------------------------------------------------------------------- */

int AtomVecPeriKokkos::pack_restart(int i, double *buf)
{
  // sync the arrays of this style's own Atom: inside replicate, atomKK is
  // already the new Atom while the old style packs its atoms

  owner->k_x.sync<LMPHostType>();
  owner->k_v.sync<LMPHostType>();
  owner->k_tag.sync<LMPHostType>();
  owner->k_type.sync<LMPHostType>();
  owner->k_mask.sync<LMPHostType>();
  owner->k_image.sync<LMPHostType>();
  owner->k_rmass.sync<LMPHostType>();
  k_vfrac.sync<LMPHostType>();
  k_s0.sync<LMPHostType>();
  k_x0.sync<LMPHostType>();

  int m = 1;
  buf[m++] = h_x(i,0);
  buf[m++] = h_x(i,1);
  buf[m++] = h_x(i,2);
  buf[m++] = ubuf(h_tag[i]).d;
  buf[m++] = ubuf(h_type[i]).d;
  buf[m++] = ubuf(h_mask[i]).d;
  buf[m++] = ubuf(h_image[i]).d;
  buf[m++] = h_v(i,0);
  buf[m++] = h_v(i,1);
  buf[m++] = h_v(i,2);
  buf[m++] = h_rmass[i];
  buf[m++] = h_vfrac[i];
  buf[m++] = h_s0[i];
  buf[m++] = h_x0(i,0);
  buf[m++] = h_x0(i,1);
  buf[m++] = h_x0(i,2);

  if (atom->nextra_restart)
    for (int iextra = 0; iextra < atom->nextra_restart; iextra++)
      m += modify->fix[atom->extra_restart[iextra]]->pack_restart(i,&buf[m]);

  buf[0] = m;
  return m;
}

/* ----------------------------------------------------------------------
   unpack data for one atom from restart file including extra quantities
------------------------------------------------------------------------- */

int AtomVecPeriKokkos::unpack_restart(double *buf)
{
  int nlocal = atom->nlocal;
  if (nlocal == nmax) {
    grow(0);
    if (atom->nextra_store)
      memory->grow(atom->extra,nmax,atom->nextra_store,"atom:extra");
  }
  atomKK->sync(Host,OWNED_STD);
  atomKK->sync(Host,EXT_ALL);

  int m = 1;
  h_x(nlocal,0) = buf[m++];
  h_x(nlocal,1) = buf[m++];
  h_x(nlocal,2) = buf[m++];
  h_tag[nlocal] = (tagint) ubuf(buf[m++]).i;
  h_type[nlocal] = (int) ubuf(buf[m++]).i;
  h_mask[nlocal] = (int) ubuf(buf[m++]).i;
  h_image[nlocal] = (imageint) ubuf(buf[m++]).i;
  h_v(nlocal,0) = buf[m++];
  h_v(nlocal,1) = buf[m++];
  h_v(nlocal,2) = buf[m++];
  h_rmass[nlocal] = buf[m++];
  h_vfrac[nlocal] = buf[m++];
  h_s0[nlocal] = buf[m++];
  h_x0(nlocal,0) = buf[m++];
  h_x0(nlocal,1) = buf[m++];
  h_x0(nlocal,2) = buf[m++];

  atomKK->modified(Host,OWNED_STD);
  atomKK->modified(Host,EXT_ALL);

  double **extra = atom->extra;
  if (atom->nextra_store) {
    int size = static_cast<int> (buf[0]) - m;
    for (int i = 0; i < size; i++) extra[nlocal][i] = buf[m++];
  }

  atom->nlocal++;
  return m;
}

/* ----------------------------------------------------------------------
   create one atom of itype at coord
   set other values to defaults (those of AtomVecPeri::create_atom_post)
------------------------------------------------------------------------- */

void AtomVecPeriKokkos::create_atom(int itype, double *coord)
{
  int nlocal = atom->nlocal;
  if (nlocal == nmax) grow(0);
  atomKK->sync(Host,ALL_MASK);

  h_tag[nlocal] = 0;
  h_type[nlocal] = itype;
  h_x(nlocal,0) = coord[0];
  h_x(nlocal,1) = coord[1];
  h_x(nlocal,2) = coord[2];
  h_mask[nlocal] = 1;
  h_image[nlocal] = ((imageint) IMGMAX << IMG2BITS) |
    ((imageint) IMGMAX << IMGBITS) | IMGMAX;
  h_v(nlocal,0) = 0.0;
  h_v(nlocal,1) = 0.0;
  h_v(nlocal,2) = 0.0;

  h_vfrac[nlocal] = 1.0;
  h_rmass[nlocal] = 1.0;
  h_s0[nlocal] = DBL_MAX;
  h_x0(nlocal,0) = coord[0];
  h_x0(nlocal,1) = coord[1];
  h_x0(nlocal,2) = coord[2];

  atomKK->modified(Host,ALL_MASK);

  atom->nlocal++;
}

/* ----------------------------------------------------------------------
   unpack one line from Atoms section of data file
   columns: id type vfrac rmass x y z (values[4..6] = coord)
   initialize other atom quantities as AtomVecPeri::data_atom_post
------------------------------------------------------------------------- */

void AtomVecPeriKokkos::data_atom(double *coord, imageint imagetmp, char **values)
{
  int nlocal = atom->nlocal;
  if (nlocal == nmax) grow(0);
  atomKK->sync(Host,ALL_MASK);

  h_tag[nlocal] = utils::tnumeric(FLERR,values[0],true,lmp);
  h_type[nlocal] = utils::inumeric(FLERR,values[1],true,lmp);
  h_vfrac[nlocal] = utils::numeric(FLERR,values[2],true,lmp);
  h_rmass[nlocal] = utils::numeric(FLERR,values[3],true,lmp);

  h_x(nlocal,0) = coord[0];
  h_x(nlocal,1) = coord[1];
  h_x(nlocal,2) = coord[2];
  h_image[nlocal] = imagetmp;
  h_mask[nlocal] = 1;
  h_v(nlocal,0) = 0.0;
  h_v(nlocal,1) = 0.0;
  h_v(nlocal,2) = 0.0;

  h_s0[nlocal] = DBL_MAX;
  h_x0(nlocal,0) = coord[0];
  h_x0(nlocal,1) = coord[1];
  h_x0(nlocal,2) = coord[2];

  atomKK->modified(Host,ALL_MASK);

  if (h_tag[nlocal] <= 0)
    error->one(FLERR,"Invalid atom ID in Atoms section of data file");
  if (h_type[nlocal] <= 0 || h_type[nlocal] > atom->ntypes)
    error->one(FLERR,"Invalid atom type in Atoms section of data file");
  if (h_rmass[nlocal] <= 0.0)
    error->one(FLERR,"Invalid mass in Atoms section of data file");

  atom->nlocal++;
}

/* ----------------------------------------------------------------------
   unpack hybrid quantities from one line in Atoms section of data file
   (values: vfrac rmass)
------------------------------------------------------------------------- */

int AtomVecPeriKokkos::data_atom_hybrid(int nlocal, char **values)
{
  atomKK->sync(Host,RMASS_MASK|X_MASK);
  atomKK->sync(Host,EXT_ALL);

  h_vfrac[nlocal] = utils::numeric(FLERR,values[0],true,lmp);
  h_rmass[nlocal] = utils::numeric(FLERR,values[1],true,lmp);
  if (h_rmass[nlocal] <= 0.0)
    error->one(FLERR,"Invalid mass in Atoms section of data file");

  h_s0[nlocal] = DBL_MAX;
  h_x0(nlocal,0) = h_x(nlocal,0);
  h_x0(nlocal,1) = h_x(nlocal,1);
  h_x0(nlocal,2) = h_x(nlocal,2);

  atomKK->modified(Host,RMASS_MASK);
  atomKK->modified(Host,EXT_ALL);
  return 2;
}

/* ----------------------------------------------------------------------
   pack atom info for data file including 3 image flags
   (layout of AtomVec::pack_data for fields "id type vfrac rmass x")
------------------------------------------------------------------------- */

void AtomVecPeriKokkos::pack_data(double **buf)
{
  atomKK->sync(Host,TAG_MASK|TYPE_MASK|X_MASK|IMAGE_MASK|RMASS_MASK);
  atomKK->sync(Host,EXTENDED_MASK|VFRAC_MASK);

  int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++) {
    buf[i][0] = ubuf(h_tag[i]).d;
    buf[i][1] = ubuf(h_type[i]).d;
    buf[i][2] = h_vfrac[i];
    buf[i][3] = h_rmass[i];
    buf[i][4] = h_x(i,0);
    buf[i][5] = h_x(i,1);
    buf[i][6] = h_x(i,2);
    buf[i][7] = ubuf((h_image[i] & IMGMASK) - IMGMAX).d;
    buf[i][8] = ubuf((h_image[i] >> IMGBITS & IMGMASK) - IMGMAX).d;
    buf[i][9] = ubuf((h_image[i] >> IMG2BITS) - IMGMAX).d;
  }
}

int AtomVecPeriKokkos::pack_data_hybrid(int i, double *buf)
{
  atomKK->sync(Host,RMASS_MASK);
  atomKK->sync(Host,EXTENDED_MASK|VFRAC_MASK);
  buf[0] = h_vfrac[i];
  buf[1] = h_rmass[i];
  return 2;
}

/* ----------------------------------------------------------------------
   write atom info to data file, as AtomVec::write_data
------------------------------------------------------------------------- */

void AtomVecPeriKokkos::write_data(FILE *fp, int n, double **buf)
{
  for (int i = 0; i < n; i++)
    fmt::print(fp,"{} {} {} {} {} {} {} {} {} {}\n",
               ubuf(buf[i][0]).i,ubuf(buf[i][1]).i,
               buf[i][2],buf[i][3],buf[i][4],buf[i][5],buf[i][6],
               (int) ubuf(buf[i][7]).i,(int) ubuf(buf[i][8]).i,(int) ubuf(buf[i][9]).i);
}

int AtomVecPeriKokkos::write_data_hybrid(FILE *fp, double *buf)
{
  fmt::print(fp," {} {}",buf[0],buf[1]);
  return 2;
}

/* ----------------------------------------------------------------------
   assign an index to named atom property and return index
   return -1 if name is unknown to this atom style
------------------------------------------------------------------------- */

int AtomVecPeriKokkos::property_atom(char *name)
{
  if (strcmp(name,"vfrac") == 0) return 0;
  if (strcmp(name,"s0") == 0) return 1;
  return -1;
}

/* ----------------------------------------------------------------------
   pack per-atom data into buf for ComputePropertyAtom
   index maps to data specific to this atom style
------------------------------------------------------------------------- */

void AtomVecPeriKokkos::pack_property_atom(int index, double *buf, int nvalues, int groupbit)
{
  atomKK->sync(Host,MASK_MASK);
  atomKK->sync(Host,EXTENDED_MASK|VFRAC_MASK|S0_MASK);

  int nlocal = atom->nlocal;
  int n = 0;
  if (index == 0) {
    for (int i = 0; i < nlocal; i++) {
      if (h_mask[i] & groupbit) buf[n] = h_vfrac[i];
      else buf[n] = 0.0;
      n += nvalues;
    }
  } else if (index == 1) {
    for (int i = 0; i < nlocal; i++) {
      if (h_mask[i] & groupbit) buf[n] = h_s0[i];
      else buf[n] = 0.0;
      n += nvalues;
    }
  }
}

/* ----------------------------------------------------------------------
   return # of bytes of allocated memory
------------------------------------------------------------------------- */

double AtomVecPeriKokkos::memory_usage()
{
  double bytes = 0;

  if (atom->memcheck("tag")) bytes += memory->usage(tag,nmax);
  if (atom->memcheck("type")) bytes += memory->usage(type,nmax);
  if (atom->memcheck("mask")) bytes += memory->usage(mask,nmax);
  if (atom->memcheck("image")) bytes += memory->usage(image,nmax);
  if (atom->memcheck("x")) bytes += memory->usage(x,nmax,3);
  if (atom->memcheck("v")) bytes += memory->usage(v,nmax,3);
  if (atom->memcheck("f")) bytes += memory->usage(f,nmax*commKK->nthreads,3);
  if (atom->memcheck("rmass")) bytes += memory->usage(rmass,nmax);
  if (atom->memcheck("vfrac")) bytes += memory->usage(vfrac,nmax);
  if (atom->memcheck("s0")) bytes += memory->usage(s0,nmax);
  if (atom->memcheck("x0")) bytes += memory->usage(x0,nmax,3);

  return bytes;
}

/* ======================================================================
   sync / modified
   standard masks: X V F TAG TYPE MASK IMAGE RMASS
   extended masks (with EXTENDED_MASK): VFRAC S0 X0
   ====================================================================== */

/* the copy ledger (header): fields in the order of the masks below */

const char *AtomVecPeriKokkos::field_name(int k)
{
  static const char *names[NFIELD] = {"x", "v", "f", "tag", "type", "mask", "image", "rmass",
                                      "vfrac", "s0", "x0"};
  return (k >= 0 && k < NFIELD) ? names[k] : "?";
}

void AtomVecPeriKokkos::ledger_clear_counts()
{
  for (int k = 0; k < NFIELD; k++)
    for (int d = 0; d < 2; d++) ledger.copies[k][d] = 0, ledger.bytes[k][d] = 0.0;
}

// bytes a copy of field k moves: the whole allocation, as DualView copies it
double AtomVecPeriKokkos::field_bytes(int k) const
{
  switch (k) {
    case 0: return sizeof(X_FLOAT) * atomKK->k_x.d_view.span();
    case 1: return sizeof(V_FLOAT) * atomKK->k_v.d_view.span();
    case 2: return sizeof(F_FLOAT) * atomKK->k_f.d_view.span();
    case 3: return sizeof(tagint) * atomKK->k_tag.d_view.span();
    case 4: return sizeof(int) * atomKK->k_type.d_view.span();
    case 5: return sizeof(int) * atomKK->k_mask.d_view.span();
    case 6: return sizeof(imageint) * atomKK->k_image.d_view.span();
    case 7: return sizeof(double) * atomKK->k_rmass.d_view.span();
    case 8: return sizeof(double) * k_vfrac.d_view.span();
    case 9: return sizeof(double) * k_s0.d_view.span();
    case 10: return sizeof(X_FLOAT) * k_x0.d_view.span();
  }
  return 0.0;
}

std::string AtomVecPeriKokkos::mask_fields(unsigned int mask, bool modify, double *bytes) const
{
  unsigned int std_mask, ext_mask;
  split_mask(mask, modify, std_mask, ext_mask);
  std::string out;
  *bytes = 0.0;
  for (int k = 0; k < NFIELD; k++)
    if (((k < 8) ? std_mask : ext_mask) & field_bit(k)) {
      out += (out.empty() ? "" : ",") + std::string(field_name(k));
      *bytes += field_bytes(k);
    }
  return out;
}

unsigned int AtomVecPeriKokkos::field_bit(int k)
{
  static const unsigned int bits[NFIELD] = {X_MASK,    V_MASK,     F_MASK,     TAG_MASK,
                                            TYPE_MASK, MASK_MASK,  IMAGE_MASK, RMASS_MASK,
                                            VFRAC_MASK, S0_MASK,   X0_MASK};
  return (k >= 0 && k < NFIELD) ? bits[k] : 0u;
}

// the standard and the extended fields of a mask, as sync() (modify false)
// and modified() (true) read it (see the header)
void AtomVecPeriKokkos::split_mask(unsigned int mask, bool modify, unsigned int &std_mask,
                                   unsigned int &ext_mask)
{
  if (is_all_mask(mask)) {
    std_mask = mask; ext_mask = PERI_EXT;
  } else if (mask & EXTENDED_MASK) {
    std_mask = 0; ext_mask = mask;
  } else {
    std_mask = mask; ext_mask = modify ? 0 : mask;
  }
}

/* a sync (sync = true) or a modification of the fields in std_mask (X V F
   TAG TYPE MASK IMAGE RMASS) and ext_mask (VFRAC S0 X0) */
void AtomVecPeriKokkos::ledger_note(ExecutionSpace space, unsigned int std_mask,
                                    unsigned int ext_mask, bool sync)
{
  const int side = (space == Device) ? 2 : 1;
  for (int k = 0; k < NFIELD; k++) {
    const unsigned int m = (k < 8) ? std_mask : ext_mask;
    if (!(m & field_bit(k))) continue;
    if (!sync) {
      ledger.newer[k] = side;
    } else if (ledger.newer[k] != 0 && ledger.newer[k] != side) {
      const int d = (space == Device) ? 0 : 1;
      ledger.copies[k][d]++;
      ledger.bytes[k][d] += field_bytes(k);
      ledger.newer[k] = 0;
    }
  }
}

void AtomVecPeriKokkos::sync(ExecutionSpace space, unsigned int mask)
{
  unsigned int std_mask, ext_mask;
  split_mask(mask, false, std_mask, ext_mask);    // see the header: a sync never hurts
  ledger_note(space, std_mask, ext_mask, true);

  if (space == Device) {
    if (std_mask & X_MASK) atomKK->k_x.sync<LMPDeviceType>();
    if (std_mask & V_MASK) atomKK->k_v.sync<LMPDeviceType>();
    if (std_mask & F_MASK) atomKK->k_f.sync<LMPDeviceType>();
    if (std_mask & TAG_MASK) atomKK->k_tag.sync<LMPDeviceType>();
    if (std_mask & TYPE_MASK) atomKK->k_type.sync<LMPDeviceType>();
    if (std_mask & MASK_MASK) atomKK->k_mask.sync<LMPDeviceType>();
    if (std_mask & IMAGE_MASK) atomKK->k_image.sync<LMPDeviceType>();
    if (std_mask & RMASS_MASK) atomKK->k_rmass.sync<LMPDeviceType>();
    if (ext_mask & VFRAC_MASK) k_vfrac.sync<LMPDeviceType>();
    if (ext_mask & S0_MASK) k_s0.sync<LMPDeviceType>();
    if (ext_mask & X0_MASK) k_x0.sync<LMPDeviceType>();
  } else {
    if (std_mask & X_MASK) atomKK->k_x.sync<LMPHostType>();
    if (std_mask & V_MASK) atomKK->k_v.sync<LMPHostType>();
    if (std_mask & F_MASK) atomKK->k_f.sync<LMPHostType>();
    if (std_mask & TAG_MASK) atomKK->k_tag.sync<LMPHostType>();
    if (std_mask & TYPE_MASK) atomKK->k_type.sync<LMPHostType>();
    if (std_mask & MASK_MASK) atomKK->k_mask.sync<LMPHostType>();
    if (std_mask & IMAGE_MASK) atomKK->k_image.sync<LMPHostType>();
    if (std_mask & RMASS_MASK) atomKK->k_rmass.sync<LMPHostType>();
    if (ext_mask & VFRAC_MASK) k_vfrac.sync<LMPHostType>();
    if (ext_mask & S0_MASK) k_s0.sync<LMPHostType>();
    if (ext_mask & X0_MASK) k_x0.sync<LMPHostType>();
  }
}

/* ---------------------------------------------------------------------- */

void AtomVecPeriKokkos::sync_overlapping_device(ExecutionSpace space, unsigned int mask)
{
  unsigned int std_mask, ext_mask;
  split_mask(mask, false, std_mask, ext_mask);
  ledger_note(space, std_mask, ext_mask, true);

  if (space == Device) {
    if ((std_mask & X_MASK) && atomKK->k_x.need_sync<LMPDeviceType>())
      perform_async_copy<DAT::tdual_x_array>(atomKK->k_x,space);
    if ((std_mask & V_MASK) && atomKK->k_v.need_sync<LMPDeviceType>())
      perform_async_copy<DAT::tdual_v_array>(atomKK->k_v,space);
    if ((std_mask & F_MASK) && atomKK->k_f.need_sync<LMPDeviceType>())
      perform_async_copy<DAT::tdual_f_array>(atomKK->k_f,space);
    if ((std_mask & TAG_MASK) && atomKK->k_tag.need_sync<LMPDeviceType>())
      perform_async_copy<DAT::tdual_tagint_1d>(atomKK->k_tag,space);
    if ((std_mask & TYPE_MASK) && atomKK->k_type.need_sync<LMPDeviceType>())
      perform_async_copy<DAT::tdual_int_1d>(atomKK->k_type,space);
    if ((std_mask & MASK_MASK) && atomKK->k_mask.need_sync<LMPDeviceType>())
      perform_async_copy<DAT::tdual_int_1d>(atomKK->k_mask,space);
    if ((std_mask & IMAGE_MASK) && atomKK->k_image.need_sync<LMPDeviceType>())
      perform_async_copy<DAT::tdual_imageint_1d>(atomKK->k_image,space);
    if ((std_mask & RMASS_MASK) && atomKK->k_rmass.need_sync<LMPDeviceType>())
      perform_async_copy<DAT::tdual_float_1d>(atomKK->k_rmass,space);
    if ((ext_mask & VFRAC_MASK) && k_vfrac.need_sync<LMPDeviceType>())
      perform_async_copy<DAT::tdual_float_1d>(k_vfrac,space);
    if ((ext_mask & S0_MASK) && k_s0.need_sync<LMPDeviceType>())
      perform_async_copy<DAT::tdual_float_1d>(k_s0,space);
    if ((ext_mask & X0_MASK) && k_x0.need_sync<LMPDeviceType>())
      perform_async_copy<DAT::tdual_x_array>(k_x0,space);
  } else {
    if ((std_mask & X_MASK) && atomKK->k_x.need_sync<LMPHostType>())
      perform_async_copy<DAT::tdual_x_array>(atomKK->k_x,space);
    if ((std_mask & V_MASK) && atomKK->k_v.need_sync<LMPHostType>())
      perform_async_copy<DAT::tdual_v_array>(atomKK->k_v,space);
    if ((std_mask & F_MASK) && atomKK->k_f.need_sync<LMPHostType>())
      perform_async_copy<DAT::tdual_f_array>(atomKK->k_f,space);
    if ((std_mask & TAG_MASK) && atomKK->k_tag.need_sync<LMPHostType>())
      perform_async_copy<DAT::tdual_tagint_1d>(atomKK->k_tag,space);
    if ((std_mask & TYPE_MASK) && atomKK->k_type.need_sync<LMPHostType>())
      perform_async_copy<DAT::tdual_int_1d>(atomKK->k_type,space);
    if ((std_mask & MASK_MASK) && atomKK->k_mask.need_sync<LMPHostType>())
      perform_async_copy<DAT::tdual_int_1d>(atomKK->k_mask,space);
    if ((std_mask & IMAGE_MASK) && atomKK->k_image.need_sync<LMPHostType>())
      perform_async_copy<DAT::tdual_imageint_1d>(atomKK->k_image,space);
    if ((std_mask & RMASS_MASK) && atomKK->k_rmass.need_sync<LMPHostType>())
      perform_async_copy<DAT::tdual_float_1d>(atomKK->k_rmass,space);
    if ((ext_mask & VFRAC_MASK) && k_vfrac.need_sync<LMPHostType>())
      perform_async_copy<DAT::tdual_float_1d>(k_vfrac,space);
    if ((ext_mask & S0_MASK) && k_s0.need_sync<LMPHostType>())
      perform_async_copy<DAT::tdual_float_1d>(k_s0,space);
    if ((ext_mask & X0_MASK) && k_x0.need_sync<LMPHostType>())
      perform_async_copy<DAT::tdual_x_array>(k_x0,space);
  }
}

/* ---------------------------------------------------------------------- */

void AtomVecPeriKokkos::modified(ExecutionSpace space, unsigned int mask)
{
  unsigned int std_mask, ext_mask;
  split_mask(mask, true, std_mask, ext_mask);
  ledger_note(space, std_mask, ext_mask, false);

  if (space == Device) {
    if (std_mask & X_MASK) atomKK->k_x.modify<LMPDeviceType>();
    if (std_mask & V_MASK) atomKK->k_v.modify<LMPDeviceType>();
    if (std_mask & F_MASK) atomKK->k_f.modify<LMPDeviceType>();
    if (std_mask & TAG_MASK) atomKK->k_tag.modify<LMPDeviceType>();
    if (std_mask & TYPE_MASK) atomKK->k_type.modify<LMPDeviceType>();
    if (std_mask & MASK_MASK) atomKK->k_mask.modify<LMPDeviceType>();
    if (std_mask & IMAGE_MASK) atomKK->k_image.modify<LMPDeviceType>();
    if (std_mask & RMASS_MASK) atomKK->k_rmass.modify<LMPDeviceType>();
    if (ext_mask & VFRAC_MASK) k_vfrac.modify<LMPDeviceType>();
    if (ext_mask & S0_MASK) k_s0.modify<LMPDeviceType>();
    if (ext_mask & X0_MASK) k_x0.modify<LMPDeviceType>();
  } else {
    if (std_mask & X_MASK) atomKK->k_x.modify<LMPHostType>();
    if (std_mask & V_MASK) atomKK->k_v.modify<LMPHostType>();
    if (std_mask & F_MASK) atomKK->k_f.modify<LMPHostType>();
    if (std_mask & TAG_MASK) atomKK->k_tag.modify<LMPHostType>();
    if (std_mask & TYPE_MASK) atomKK->k_type.modify<LMPHostType>();
    if (std_mask & MASK_MASK) atomKK->k_mask.modify<LMPHostType>();
    if (std_mask & IMAGE_MASK) atomKK->k_image.modify<LMPHostType>();
    if (std_mask & RMASS_MASK) atomKK->k_rmass.modify<LMPHostType>();
    if (ext_mask & VFRAC_MASK) k_vfrac.modify<LMPHostType>();
    if (ext_mask & S0_MASK) k_s0.modify<LMPHostType>();
    if (ext_mask & X0_MASK) k_x0.modify<LMPHostType>();
  }
}
