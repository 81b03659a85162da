/* ----------------------------------------------------------------------
   USER-TLSPH: fix tlsph/dt/kk (fix_tlsph_dt_kokkos.h)
------------------------------------------------------------------------- */

#include "fix_tlsph_dt_kokkos.h"

#include "atom_kokkos.h"
#include "atom_masks.h"
#include "error.h"
#include "pair_tlsph.h"
#include "tlsph_kk_copies.h"

#include <cmath>

using namespace LAMMPS_NS;

template <class DeviceType>
FixTLSPHDtKokkos<DeviceType>::FixTLSPHDtKokkos(LAMMPS *lmp, int narg, char **arg) :
    FixTLSPHDt(lmp, narg, arg)
{
  if (lmp->kokkos == nullptr)
    error->all(FLERR, "fix tlsph/dt/kk needs the KOKKOS package enabled (-k on)");
  kokkosable = 1;
  execution_space = TLSPHKK::execution_space_of<DeviceType>();
  datamask_read = V_MASK | TYPE_MASK | MASK_MASK;
  datamask_modify = EMPTY_MASK;
}

template <class DeviceType> void FixTLSPHDtKokkos<DeviceType>::init()
{
  FixTLSPHDt::init();
  const int nt = atom->ntypes + 1;
  d_c0 = Kokkos::View<double *, DeviceType>("tlsph/dt/kk:c0", nt);
  auto h_c0 = Kokkos::create_mirror_view(d_c0);
  for (int t = 0; t < nt; t++) h_c0(t) = (t > 0) ? pair->material(t).c0 : 0.0;
  Kokkos::deep_copy(d_c0, h_c0);
}

// as FixTLSPHDt::local_max_speed (a maximum: the same value in any order)
template <class DeviceType> double FixTLSPHDtKokkos<DeviceType>::local_max_speed()
{
  auto *atomKK = (AtomKokkos *) atom;
  atomKK->sync(execution_space, datamask_read);
  const auto v = atomKK->k_v.template view<DeviceType>();
  const auto type = atomKK->k_type.template view<DeviceType>();
  const auto mask = atomKK->k_mask.template view<DeviceType>();
  const double *c0 = d_c0.data();
  const int gb = groupbit;
  double cmax = 0.0;
  Kokkos::parallel_reduce(
      "tlsph/dt/kk:speed", Kokkos::RangePolicy<DeviceType>(0, atom->nlocal),
      KOKKOS_LAMBDA(const int i, double &mx) {
        if (!(mask(i) & gb)) return;
        const double vel = std::sqrt(v(i, 0) * v(i, 0) + v(i, 1) * v(i, 1) + v(i, 2) * v(i, 2));
        const double c = c0[type(i)] + vel;
        if (c > mx) mx = c;
      },
      Kokkos::Max<double>(cmax));
  return cmax > 0.0 ? cmax : 0.0;
}

namespace LAMMPS_NS {
template class FixTLSPHDtKokkos<LMPDeviceType>;
#ifdef LMP_KOKKOS_GPU
template class FixTLSPHDtKokkos<LMPHostType>;
#endif
}    // namespace LAMMPS_NS
