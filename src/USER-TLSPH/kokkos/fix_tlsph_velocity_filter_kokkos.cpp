/* ----------------------------------------------------------------------
   USER-TLSPH: fix tlsph/velocity/filter/kk (fix_tlsph_velocity_filter_kokkos.h)
------------------------------------------------------------------------- */

#ifndef TLSPH_KOKKOS
#define TLSPH_KOKKOS
#endif

#include "fix_tlsph_velocity_filter_kokkos.h"

#include "atom_kokkos.h"
#include "atom_masks.h"
#include "comm.h"
#include "error.h"
#include "pair_tlsph_damage_kokkos.h"

#include <cmath>
#include <string>

using namespace LAMMPS_NS;

template <class DeviceType>
FixTLSPHVelocityFilterKokkos<DeviceType>::FixTLSPHVelocityFilterKokkos(LAMMPS *lmp, int narg,
                                                                      char **arg) :
    FixTLSPHVelocityFilter(lmp, narg, arg), kkpair(nullptr)
{
  if (lmp->kokkos == nullptr)
    error->all(FLERR, "fix tlsph/velocity/filter/kk needs the KOKKOS package enabled (-k on)");
  kokkosable = 1;
  forward_comm_device = 1;
  atomKK = (AtomKokkos *) atom;
  execution_space = TLSPHKK::execution_space_of<DeviceType>();
  datamask_read = V_MASK | MASK_MASK | RMASS_MASK;
  datamask_modify = V_MASK;
}

template <class DeviceType> void FixTLSPHVelocityFilterKokkos<DeviceType>::init()
{
  FixTLSPHVelocityFilter::init();
  kkpair = dynamic_cast<PairTLSPHDamageKokkos<DeviceType> *>(pair);
  if (!kkpair)
    error->all(FLERR, "fix tlsph/velocity/filter/kk needs pair_style tlsph/damage/kk (on the "
                      "same Kokkos device): use -sf kk for both, or the fix without /kk");
}

/* as FixTLSPHVelocityFilter::end_of_step: the ghosts get this step's
   velocities, then every particle is filtered from the old velocities */
template <class DeviceType> void FixTLSPHVelocityFilterKokkos<DeviceType>::end_of_step()
{
  atomKK->sync(execution_space, datamask_read);
  comm->forward_comm_fix(this);
  if (kkpair->dimension() == 2) filter<2>();
  else filter<3>();
  atomKK->modified(execution_space, V_MASK);
}

template <class DeviceType>
template <int DIM>
void FixTLSPHVelocityFilterKokkos<DeviceType>::filter()
{
  const int nlocal = atom->nlocal;
  if (d_vnew.extent(0) < (size_t) 3 * nlocal)
    d_vnew = Kokkos::View<double *, DeviceType>("tlsph/velocity/filter/kk:vnew", 3 * atom->nmax);
  const auto v = atomKK->k_v.template view<DeviceType>();
  const auto mask = atomKK->k_mask.template view<DeviceType>();
  const auto b = kkpair->device_bonds();
  double *vnew = d_vnew.data();
  const int gb = groupbit;
  const double pc = phi_c, e = eps;
  int n = 0;
  Kokkos::parallel_reduce(
      "tlsph/velocity/filter/kk", Kokkos::RangePolicy<DeviceType>(0, nlocal),
      KOKKOS_LAMBDA(const int i, int &count) {
        for (int d = 0; d < 3; d++) vnew[3 * i + d] = v(i, d);
        if (!(mask(i) & gb) || !(b.phi[i] > pc)) return;
        double s[3] = {0.0, 0.0, 0.0}, wsum = 0.0;
        const int *bj = b.bj + b.start[i];
        for (int m = 0; m < b.nbond[i]; m++) {
          const int j = bj[(long) m * b.stride];
          double r2 = 0.0;
          for (int d = 0; d < DIM; d++) {
            const double X = b.x0c[3 * j + d] - b.x0c[3 * i + d];
            r2 += X * X;
          }
          const double W = b.kernel.value(std::sqrt(r2));
          for (int d = 0; d < 3; d++) s[d] += (v(i, d) - v(j, d)) * W;
          wsum += W;
        }
        if (wsum > 0.0)
          for (int d = 0; d < 3; d++) vnew[3 * i + d] = v(i, d) - e * s[d] / wsum;
        count++;
      },
      n);
  // the new velocities, and the kinetic energy they take out
  const auto rmass = atomKK->k_rmass.template view<DeviceType>();
  double de = 0.0;
  Kokkos::parallel_reduce(
      "tlsph/velocity/filter/kk:copy", Kokkos::RangePolicy<DeviceType>(0, nlocal),
      KOKKOS_LAMBDA(const int i, double &sum) {
        double v2 = 0.0;
        for (int d = 0; d < 3; d++) {
          v2 += v(i, d) * v(i, d) - vnew[3 * i + d] * vnew[3 * i + d];
          v(i, d) = vnew[3 * i + d];
        }
        sum += 0.5 * rmass(i) * v2;
      },
      de);
  nfiltered = n;
  record_energy(de);
}

template <class DeviceType>
int FixTLSPHVelocityFilterKokkos<DeviceType>::pack_forward_comm_fix_kokkos(
    int n, DAT::tdual_int_2d k_sendlist, int iswap, DAT::tdual_xfloat_1d &buf, int, int *)
{
  const auto list = k_sendlist.template view<DeviceType>();
  const auto out = buf.template view<DeviceType>();
  const auto v = atomKK->k_v.template view<DeviceType>();
  Kokkos::parallel_for(
      "tlsph/velocity/filter/kk:pack", Kokkos::RangePolicy<DeviceType>(0, n),
      KOKKOS_LAMBDA(const int ii) {
        const int j = list(iswap, ii);
        for (int d = 0; d < 3; d++) out(3 * ii + d) = v(j, d);
      });
  return 3 * n;
}

template <class DeviceType>
void FixTLSPHVelocityFilterKokkos<DeviceType>::unpack_forward_comm_fix_kokkos(
    int n, int first, DAT::tdual_xfloat_1d &buf)
{
  const auto in = buf.template view<DeviceType>();
  const auto v = atomKK->k_v.template view<DeviceType>();
  Kokkos::parallel_for(
      "tlsph/velocity/filter/kk:unpack", Kokkos::RangePolicy<DeviceType>(0, n),
      KOKKOS_LAMBDA(const int ii) {
        for (int d = 0; d < 3; d++) v(first + ii, d) = in(3 * ii + d);
      });
}

// host path (LAMMPS's classic communication): through atom->v on the host
template <class DeviceType>
int FixTLSPHVelocityFilterKokkos<DeviceType>::pack_forward_comm(int n, int *list, double *buf,
                                                               int pbc_flag, int *pbc)
{
  kkpair->host_sync(V_MASK);
  return FixTLSPHVelocityFilter::pack_forward_comm(n, list, buf, pbc_flag, pbc);
}

template <class DeviceType>
void FixTLSPHVelocityFilterKokkos<DeviceType>::unpack_forward_comm(int n, int first, double *buf)
{
  kkpair->host_sync(V_MASK);
  FixTLSPHVelocityFilter::unpack_forward_comm(n, first, buf);
  kkpair->host_modified(V_MASK);
  atomKK->sync(execution_space, V_MASK);
}

namespace LAMMPS_NS {
template class FixTLSPHVelocityFilterKokkos<LMPDeviceType>;
#ifdef LMP_KOKKOS_GPU
template class FixTLSPHVelocityFilterKokkos<LMPHostType>;
#endif
}    // namespace LAMMPS_NS
