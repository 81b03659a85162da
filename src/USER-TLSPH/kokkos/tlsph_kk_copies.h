/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: the host <-> device copies of the /kk styles, counted
   (doc/kokkos-cuda.md, "Host-device copies"), and the device model of a
   host backend

   Every copy of the styles' own arrays goes through upload() and
   download() below, and every host access of atom data by their host code
   through PairTLSPHKokkosT::host_sync(); both count into copy_ledger(), by
   name: [0] to the device, [1] to the host (counts and bytes). The bond fix
   reports the ledger after every run (PairTLSPHKokkosT::report_copies), so
   that unittest/kokkos/check_kokkos.py (case transfers) can fail a step
   that copies.

   The device model (TLSPH_KK_DEVICE_MODEL=1 in the environment; host
   backends only): on a host backend host and device are one memory, and
   LAMMPS names that one space Host in every call, so nothing would tell a
   copy. In the device model the /kk styles declare the Device execution
   space, as they do on a GPU: LAMMPS then runs them, and the bond fix, as
   device styles (device-side communication, no host hooks), and their own
   code takes its GPU paths, whose crossings the ledger counts. The
   arithmetic is that of the host backend (the same memory, the same
   kernels): the model changes only which paths run.
------------------------------------------------------------------------- */

#ifndef LMP_TLSPH_KK_COPIES_H
#define LMP_TLSPH_KK_COPIES_H

#include "kokkos_type.h"

#include <cstdlib>
#include <map>
#include <string>
#include <utility>

namespace TLSPHKK {
template <class T>
using HostUnmanaged = Kokkos::View<T *, Kokkos::HostSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>>;

// the device model (above): set, and on a host backend
inline bool device_model()
{
#ifdef LMP_KOKKOS_GPU
  return false;
#else
  static const bool on = [] {
    const char *e = std::getenv("TLSPH_KK_DEVICE_MODEL");
    return e != nullptr && *e != '\0' && std::string(e) != "0";
  }();
  return on;
#endif
}

// the execution space a /kk style on DeviceType declares (the device model above)
template <class DeviceType> inline LAMMPS_NS::ExecutionSpace execution_space_of()
{
  return device_model() ? LAMMPS_NS::Device : ExecutionSpaceFromDevice<DeviceType>::space;
}

struct Copies {
  long n[2] = {0, 0};
  double bytes[2] = {0.0, 0.0};
};
inline std::map<std::string, Copies> &copy_ledger()
{
  static std::map<std::string, Copies> ledger;
  return ledger;
}
inline void count_copy(const std::string &label, int to_host, double bytes)
{
  Copies &c = copy_ledger()[label];
  c.n[to_host]++;
  c.bytes[to_host] += bytes;
}

// view v with room for n elements (reallocated with slack when too short;
// its contents are then not kept)
template <class View> inline void reserve(View &v, size_t n, const char *name)
{
  if (v.extent(0) < n)
    v = View(Kokkos::view_alloc(Kokkos::WithoutInitializing, std::string(name)), n + n / 8 + 16);
}

// host array h[0..n) -> device view d (grown, with slack, when too short)
template <class View, class T> inline void upload(View &d, const T *h, size_t n, const char *name)
{
  reserve(d, n, name);
  if (n == 0) return;
  Kokkos::deep_copy(Kokkos::subview(d, std::make_pair(size_t(0), n)),
                    HostUnmanaged<const T>(h, n));
  count_copy(name, 0, sizeof(T) * (double) n);
}

// device view d[first .. first + n) -> host array h[0..n)
template <class View, class T> inline void download(T *h, const View &d, size_t first, size_t n)
{
  if (n == 0) return;
  Kokkos::deep_copy(HostUnmanaged<T>(h, n), Kokkos::subview(d, std::make_pair(first, first + n)));
  count_copy(d.label(), 1, sizeof(T) * (double) n);
}
}    // namespace TLSPHKK

#endif
