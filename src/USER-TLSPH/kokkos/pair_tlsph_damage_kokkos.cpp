/* ----------------------------------------------------------------------
   USER-TLSPH: pair_style tlsph/damage/kk (pair_tlsph_damage_kokkos.h,
   doc/pair_tlsph_kokkos.rst)
------------------------------------------------------------------------- */

#ifndef TLSPH_KOKKOS
#define TLSPH_KOKKOS
#endif

#include "pair_tlsph_damage_kokkos.h"

#include "atom_kokkos.h"
#include "atom_vec_peri_kokkos.h"
#include "comm.h"
#include "error.h"
#include "fix_tlsph_bonds.h"
#include "tlsph_pair_terms.h"
#include "update.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

using namespace LAMMPS_NS;
using TLSPHKK::download;
using TLSPHKK::upload;

template <class DeviceType>
PairTLSPHDamageKokkos<DeviceType>::PairTLSPHDamageKokkos(LAMMPS *lmp) : KK(lmp)
{
  damage_current = 0;
  d_nbroken = Kokkos::View<int, DeviceType>("tlsph/damage/kk:nbroken");
}

template <class DeviceType> void PairTLSPHDamageKokkos<DeviceType>::init_style()
{
  KK::init_style();
  if (this->rebuild)
    this->error->all(FLERR, "pair_style tlsph/damage/kk: 'correction rebuild' is not available "
                            "in the KOKKOS variant (it supports 'correction setup', the default): "
                            "use pair_style tlsph/damage");
  if (this->tipmode)
    this->error->all(FLERR, "pair_style tlsph/damage/kk: 'criterion tip' is not "
                            "available in the KOKKOS variant: use pair_style tlsph/damage");
  const int ntp = this->atom->ntypes + 1;
  upload(d_sc, this->sc.data(), ntp, "tlsph/damage/kk:sc");
  upload(d_up, this->stretch_up.data(), (size_t) ntp * ntp, "tlsph/damage/kk:up");
  upload(d_down, this->stretch_down.data(), (size_t) ntp * ntp, "tlsph/damage/kk:down");
}

/* with every bond cache on the device (uploaded or built there): each
   particle's bond count at setup and room for every bond to break in one step */
template <class DeviceType> void PairTLSPHDamageKokkos<DeviceType>::after_cache_build(size_t nb)
{
  const int nlocal = this->atom->nlocal;
  upload(d_nintact0, this->bonds->nintact0, nlocal, "tlsph/damage/kk:nintact0");
  TLSPHKK::reserve(d_broken_i, nb + 1, "tlsph/damage/kk:broken_i");
  TLSPHKK::reserve(d_broken_m, nb + 1, "tlsph/damage/kk:broken_m");
}

/* ----------------------------------------------------------------------
   pass (1) with the stretch criterion fused in, as
   PairTLSPHDamage::deform_and_break (its comments): each broken bond is
   recorded as (particle, slot at the time), for the host replay
------------------------------------------------------------------------- */

template <class DeviceType>
template <int DIM, int ORDER, int LAWS, int ABS, int PAIRS>
int PairTLSPHDamageKokkos<DeviceType>::break_kernel()
{
  using TLSPH::StridedRows;
  const int nlocal = this->atom->nlocal;
  const StridedRows x{this->atomKK->k_x.template view<DeviceType>().data(), 3};
  const TLSPH::TypeArray type{this->atomKK->k_type.template view<DeviceType>().data()};
  const int *start = this->d_start.data();
  int *nb = this->d_nbond.data(), *nl = this->d_nlead.data(), *bj = this->d_bj.data(),
      *bk = this->d_bk.data();
  const int C = this->slice;    // bond m of i: record start[i] + m C
  double *bg = this->d_bg.data(), *bw = this->d_bw.data(), *sumg = this->d_sumg.data();
  const double *x0c = this->d_x0c.data(), *Q = this->d_Q.data();
  double *F = this->d_F.data(), *P = this->d_P.data(), *pk = this->d_pk.data(),
         *fown = this->d_fown.data(), *psi = this->d_psi.data(), *ehg = this->d_ehg.data();
  const typename KK::Material *mt = this->d_mat.data();
  const TLSPH::PairMaterial *pm = this->d_pm.data();
  const double *sc = d_sc.data(), *up = d_up.data(), *down = d_down.data();
  const int ntp = this->atom->ntypes + 1;
  const double up0 = this->stretch_up[ntp + 1] * (1.0 - 1.0e-10);
  const double down0 = this->stretch_down[ntp + 1] * (1.0 + 1.0e-10);
  const int qs = this->correction_size(), ps = this->packed_size(), pstress = this->plane_stress;
  const typename KK::DeviceCache dc = this->device_cache();
  const bool need_K = this->viscosity_active(), cons = (this->hg_form == 2 && this->gamma != 0.0);
  const double g = this->gamma, alpha0 = this->alpha;
  const bool with_R = this->gather_rows;
  const auto count = d_nbroken;
  const auto broken_i = d_broken_i, broken_m = d_broken_m;
  Kokkos::deep_copy(count, 0);

  int bad = nlocal;
  Kokkos::parallel_reduce(
      "tlsph/damage/kk:deform_and_break", Kokkos::RangePolicy<DeviceType>(0, nlocal),
      KOKKOS_LAMBDA(const int i, int &first) {
        const int s = start[i];
        int n = nb[i], nlead_i = nl[i];
        int *bj_ = bj + s, *bk_ = bk + s;
        double *bg_ = bg + DIM * s, *bw_ = bw + 2 * s;
        const double *xi = x(i), *x0i = x0c + 3 * i;
        const int ti = type(i);
        double Fa[DIM * DIM];
        for (int k = 0; k < DIM * DIM; k++) Fa[k] = 0.0;
        for (int m = 0; m < n;) {
          const long r = (long) m * C;
          const int j = bj_[r];
          const int tj = type(j);
          const double *xj = x(j), *x0j = x0c + 3 * j;
          const double lim_up = PAIRS ? up[ti * ntp + tj] * (1.0 - 1.0e-10) : up0;
          const double lim_down =
              ABS ? (PAIRS ? down[ti * ntp + tj] * (1.0 + 1.0e-10) : down0) : 0.0;
          double du[3];
          if (TLSPH::bond_breaks<DIM, ABS>(xi, xj, x0i, x0j, lim_up, lim_down,
                                           sc[ti] < sc[tj] ? sc[ti] : sc[tj], du)) {
            const int e = Kokkos::atomic_fetch_add(&count(), 1);
            broken_i(e) = i;
            broken_m(e) = bk_[r];    // the bond's slot in the bond fix's rows
            for (int d = 0; d < DIM; d++) sumg[3 * i + d] -= bg_[DIM * r + d];
            TLSPH::drop_bond<DIM>(bj_, bg_, bw_, bk_, m, nlead_i, n, C);
            continue;
          }
          const double *gm = bg_ + DIM * r;
          for (int r = 0; r < DIM; r++)
            for (int c = 0; c < DIM; c++) Fa[DIM * r + c] += du[r] * gm[c];
          m++;
        }
        nb[i] = n;
        nl[i] = nlead_i;
        double *Fi = F + 9 * i;
        TLSPH::mat_identity(Fi);
        for (int r = 0; r < DIM; r++)
          for (int c = 0; c < DIM; c++) Fi[3 * r + c] += Fa[DIM * r + c];
        // the stress row, as in tlsph/kk's deformation kernel
        const auto b = dc.template bonds<DIM>(i);
        const double Vi = b.Vi;
        const TLSPH::HourglassWeights<decltype(b), TLSPH::TypeArray> coeff(pm, type, b, g, i, Vi);
        double J;
        psi[i] = PairTLSPH::stress_row<DIM, ORDER, LAWS>(
            mt[ti], pstress, Fi, P + 9 * i, need_K, cons, x, i, b, n, coeff, Vi, Q + qs * i,
            alpha0, sumg + 3 * i, with_R, pk + (long) ps * i, fown + 3 * i, ehg + i, &J);
        if (!(J > 0.0) || !std::isfinite(psi[i])) first = (i < first) ? i : first;
      },
      Kokkos::Min<int>(bad));

  int nbroken = 0;
  Kokkos::deep_copy(nbroken, count);
  if (nbroken) replay_breaks<DIM>(nbroken);
  return bad < nlocal ? bad : -1;
}

/* the kernel's breaks on the bond fix: each broken bond's state, by its
   particle and slot (the device holds the bond cache; the host copy of it
   is not kept: no host code of the /kk styles reads it between builds, and
   sync_host() brings the bond counts for the computes) */
template <class DeviceType>
template <int DIM>
void PairTLSPHDamageKokkos<DeviceType>::replay_breaks(int n)
{
  std::vector<int> bi(n), bk(n);
  download(bi.data(), d_broken_i, 0, n);
  download(bk.data(), d_broken_m, 0, n);
  for (int e = 0; e < n; e++) this->bonds->state[bi[e]][bk[e]] = FixTLSPHBonds::BROKEN;
  this->nbroken_local += n;
}

template <class DeviceType>
template <int DIM, int ORDER, int LAWS>
int PairTLSPHDamageKokkos<DeviceType>::dispatch_break()
{
  bool pairs = false;
  for (int t = 2; t <= this->atom->ntypes; t++) pairs = pairs || (this->sc[t] != this->sc[1]);
  if (this->absolute)
    return pairs ? break_kernel<DIM, ORDER, LAWS, 1, 1>() : break_kernel<DIM, ORDER, LAWS, 1, 0>();
  return pairs ? break_kernel<DIM, ORDER, LAWS, 0, 1>() : break_kernel<DIM, ORDER, LAWS, 0, 0>();
}

template <class DeviceType> int PairTLSPHDamageKokkos<DeviceType>::deformation_step()
{
  damage_current = 0;
  const bool o = this->any_orthotropic;
  if (this->dim == 2) {
    if (this->order == 1) return o ? dispatch_break<2, 1, 1>() : dispatch_break<2, 1, 0>();
    return o ? dispatch_break<2, 2, 1>() : dispatch_break<2, 2, 0>();
  }
  if (this->order == 1) return o ? dispatch_break<3, 1, 1>() : dispatch_break<3, 1, 0>();
  return o ? dispatch_break<3, 2, 1>() : dispatch_break<3, 2, 0>();
}

/* ----------------------------------------------------------------------
   between passes (1) and (2), as PairTLSPHDamage::after_deformation (its
   comments): damage, its forward communication, the marks of the damaged
   particles' intact partners (gathered on the device, see there), the
   smoothed damage and alpha_i into the packed rows
------------------------------------------------------------------------- */

template <class DeviceType> void PairTLSPHDamageKokkos<DeviceType>::damage_step()
{
  const int nlocal = this->atom->nlocal, nall = nlocal + this->atom->nghost;
  if (d_phi.extent(0) < (size_t) this->atom->nmax) {
    const size_t n = this->atom->nmax;
    d_phi = dview("tlsph/damage/kk:phi", n);
    d_mark = dview("tlsph/damage/kk:mark", n);
    d_phis = dview("tlsph/damage/kk:phis", n);
  }
  const int *nb = this->d_nbond.data(), *n0 = d_nintact0.data();
  double *phi = d_phi.data();
  Kokkos::parallel_for(
      "tlsph/damage/kk:phi", Kokkos::RangePolicy<DeviceType>(0, nlocal), KOKKOS_LAMBDA(const int i) {
        double p = (n0[i] > 0) ? 1.0 - (double) nb[i] / n0[i] : 0.0;
        phi[i] = (p < 0.0) ? 0.0 : p;
      });
  this->comm_stage = 1;
  this->comm->forward_comm_pair(this);
  this->comm_stage = 0;

  // The marks, gathered: mark_i = the number of i's intact partners that are
  // damaged (phi_j > 0; a ghost's phi came with the forward communication
  // above). PairTLSPHDamage scatters instead (mark_j += 1 for every intact
  // partner j of a damaged i) and sums the ghosts' marks on their owners by
  // a reverse communication, which this LAMMPS version does on the host
  // only. Both ends of a bond decide its break from the same two positions,
  // so the intact bonds are symmetric and both forms count the same pairs;
  // the smoothing reads only whether mark_i > 0. Nothing leaves the device.
  (void) nall;
  double *mark = d_mark.data();
  const int *start = this->d_start.data(), *bj = this->d_bj.data();
  const int C = this->slice;
  Kokkos::parallel_for(
      "tlsph/damage/kk:mark", Kokkos::RangePolicy<DeviceType>(0, nlocal), KOKKOS_LAMBDA(const int i) {
        double c = 0.0;
        for (int m = 0; m < nb[i]; m++) c += (phi[bj[start[i] + (long) m * C]] > 0.0) ? 1.0 : 0.0;
        mark[i] = c;
      });

  if (this->dim == 2) smooth_kernel<2>();
  else smooth_kernel<3>();
}

template <class DeviceType>
template <int DIM>
void PairTLSPHDamageKokkos<DeviceType>::smooth_kernel()
{
  const int nlocal = this->atom->nlocal;
  const int *nb = this->d_nbond.data(), *start = this->d_start.data(), *bj = this->d_bj.data();
  const int C = this->slice;
  const double *phi = d_phi.data(), *mark = d_mark.data(), *x0c = this->d_x0c.data();
  double *phis = d_phis.data(), *pk = this->d_pk.data();
  const TLSPH::CubicSpline kern = this->kernel;
  const double alpha_d = this->alpha_d, alpha0 = this->alpha;
  const int linear = this->damping_linear;
  const int ps = this->packed_size(), ia = 2 * DIM * DIM;
  Kokkos::parallel_for(
      "tlsph/damage/kk:smooth", Kokkos::RangePolicy<DeviceType>(0, nlocal),
      KOKKOS_LAMBDA(const int i) {
        double p;
        if (nb[i] == 0) {
          p = phi[i];
        } else if (!(mark[i] > 0.0)) {
          p = 0.0;
        } else {
          double num = 0.0, den = 0.0;
          for (int m = 0; m < nb[i]; m++) {
            const int j = bj[start[i] + (long) m * C];
            double r2 = 0.0;
            for (int d = 0; d < DIM; d++) {
              const double X = x0c[3 * j + d] - x0c[3 * i + d];
              r2 += X * X;
            }
            const double w = kern.value(std::sqrt(r2));
            num += phi[j] * w;
            den += w;
          }
          p = (den > 0.0) ? num / den : 0.0;
        }
        phis[i] = p;
        pk[(long) ps * i + ia] = TLSPH::damaged_alpha(p, alpha0, alpha_d, linear);
      });
}

/* tlsph/kk's host copies plus the damage and its smoothed form */
template <class DeviceType> void PairTLSPHDamageKokkos<DeviceType>::sync_host()
{
  KK::sync_host();
  if (damage_current || d_phis.extent(0) == 0) return;
  const int nlocal = this->atom->nlocal;
  download(this->phi, d_phi, 0, nlocal);
  download(this->phis, d_phis, 0, nlocal);
  damage_current = 1;
}

template <class DeviceType> double PairTLSPHDamageKokkos<DeviceType>::memory_usage()
{
  double bytes = KK::memory_usage();
  for (const dview *v : {&d_phi, &d_mark, &d_phis}) bytes += sizeof(double) * v->extent(0);
  for (const iview *v : {&d_nintact0, &d_broken_i, &d_broken_m}) bytes += sizeof(int) * v->extent(0);
  return bytes;
}

namespace LAMMPS_NS {
template class PairTLSPHDamageKokkos<LMPDeviceType>;
#ifdef LMP_KOKKOS_GPU
template class PairTLSPHDamageKokkos<LMPHostType>;
#endif
}    // namespace LAMMPS_NS
