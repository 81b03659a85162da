/* ----------------------------------------------------------------------
   USER-TLSPH unit tests: a small particle system built with the physics
   headers alone (no LAMMPS). It does what pair_tlsph.cpp does for one rank
   (build_bond_cache, compute_deformation, compute_forces) on std::vector
   storage, so the tests can run the physics kernels on whole lattices, with
   either gradient order (1: the thesis's A^-1 grad W, 2: quadratic moving
   least squares).
------------------------------------------------------------------------- */

#ifndef TLSPH_TEST_PHYSICS_SYSTEM_H
#define TLSPH_TEST_PHYSICS_SYSTEM_H

#include "tlsph_particle.h"

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <utility>
#include <vector>

namespace tlsph_test {

// row accessor over flat storage (stride 3 for vectors, 9 for tensors, the
// packed size for packed rows), the std::vector counterpart of pair_tlsph.cpp's Rows
struct Rows {
  const double *p;
  int stride;
  const double *operator()(int j) const { return p + stride * j; }
};

struct TypeOf {
  const int *t;
  int operator()(int j) const { return t[j]; }
};

// steel, the material of the brief
constexpr double STEEL_E = 210.0e9;
constexpr double STEEL_NU = 0.3;
constexpr double STEEL_RHO = 7850.0;

// both gradient orders, for `for (int order : ORDERS)`
constexpr int ORDERS[2] = {1, 2};

/* Call fn(std::integral_constant<int, DIM>, std::integral_constant<int, ORDER>)
   for a run-time dim (2, 3) and order (1, 2), the way pair_tlsph.cpp
   dispatches to its templates. */
template <class Fn> void with_dim_order(int dim, int order, Fn &&fn)
{
  using D2 = std::integral_constant<int, 2>;
  using D3 = std::integral_constant<int, 3>;
  using O1 = std::integral_constant<int, 1>;
  using O2 = std::integral_constant<int, 2>;
  if (dim == 2) {
    if (order == 1) fn(D2{}, O1{});
    else fn(D2{}, O2{});
  } else {
    if (order == 1) fn(D3{}, O1{});
    else fn(D3{}, O2{});
  }
}

struct System {
  int dim = 3;
  int order = 1;    // gradient order requested from correction()
  int n[3] = {1, 1, 1};
  double dx = 1.0e-3;
  double h = 1.33e-3;
  double kernel_scale = 1.0;    // make_bond(): 1 / thickness in 2D (pair_tlsph.cpp)
  TLSPH::CubicSpline kernel;

  std::vector<double> X, x, v;    // reference / current positions, velocities (3 per particle)
  std::vector<double> V;          // reference volumes
  std::vector<int> type;          // index into laws / mats
  std::vector<int> layer;         // lattice index distance to the nearest face
  std::vector<std::vector<TLSPH::Bond>> bonds;

  // correction(): Q_i (QMAX per particle, DIM x Basis size row-major),
  // sum_j g_ij, and the order achieved (2, 1 or 0)
  std::vector<double> Q, sumg;
  std::vector<int> achieved;
  // deform(): F, P, K = J F^-T (9 each), psi, J, the own force V_i P_i sum_j g_ij
  std::vector<double> F, P, K, psi, J, fown;
  std::vector<double> packed;    // pack_row() rows, the force pass's input
  std::vector<double> fs, fv, fh;

  std::vector<TLSPH::IsotropicSVK> laws;
  std::vector<TLSPH::PairMaterial> mats;

  int size() const { return static_cast<int>(V.size()); }
  const double *Xr(int i) const { return &X[3 * i]; }
  double *xr(int i) { return &x[3 * i]; }

  // regular square (2D) or cubic (3D) lattice, nx * ny (* nz) particles
  // with spacing dx, h = hfac * dx, volume dx^dim, one material (type 0),
  // gradient order `order`
  static System lattice(int dim, int nx, int ny, int nz, double dx, double hfac, int order)
  {
    System s;
    s.dim = dim;
    s.order = order;
    s.n[0] = nx;
    s.n[1] = ny;
    s.n[2] = (dim == 2) ? 1 : nz;
    s.dx = dx;
    s.h = hfac * dx;
    s.kernel = TLSPH::CubicSpline(s.h, dim);
    const double vol = (dim == 2) ? dx * dx : dx * dx * dx;
    for (int k = 0; k < s.n[2]; k++)
      for (int j = 0; j < s.n[1]; j++)
        for (int i = 0; i < s.n[0]; i++) {
          s.X.push_back(i * dx);
          s.X.push_back(j * dx);
          s.X.push_back(dim == 2 ? 0.0 : k * dx);
          s.V.push_back(vol);
          s.type.push_back(0);
          int l = std::min(std::min(i, nx - 1 - i), std::min(j, ny - 1 - j));
          if (dim == 3) l = std::min(l, std::min(k, nz - 1 - k));
          s.layer.push_back(l);
        }
    s.x = s.X;
    s.v.assign(s.X.size(), 0.0);
    s.set_single_material(STEEL_E, STEEL_NU, STEEL_RHO, 0);
    return s;
  }

  int index(int i, int j, int k = 0) const { return i + n[0] * (j + n[1] * k); }

  void set_single_material(double E, double nu, double rho, int plane_stress)
  {
    laws.assign(1, TLSPH::IsotropicSVK{TLSPH::lame_lambda(E, nu), TLSPH::lame_mu(E, nu),
                                       plane_stress});
    mats.assign(1, TLSPH::PairMaterial{
                       TLSPH::wave_speed(laws[0].lambda, laws[0].mu, rho), rho, E});
  }

  void add_material(double E, double nu, double rho, int plane_stress)
  {
    laws.push_back(TLSPH::IsotropicSVK{TLSPH::lame_lambda(E, nu), TLSPH::lame_mu(E, nu),
                                       plane_stress});
    mats.push_back(TLSPH::PairMaterial{
        TLSPH::wave_speed(laws.back().lambda, laws.back().mu, rho), rho, E});
  }

  // partners: every other particle with |X_j - X_i| < 2h (fix_tlsph_bonds.cpp)
  void build_bonds()
  {
    const int N = size();
    const double cut2 = 4.0 * h * h;
    bonds.assign(N, {});
    for (int i = 0; i < N; i++)
      for (int j = 0; j < N; j++) {
        if (j == i) continue;
        double Xij[3] = {X[3 * j] - X[3 * i], X[3 * j + 1] - X[3 * i + 1],
                         X[3 * j + 2] - X[3 * i + 2]};
        if (dim == 2) Xij[2] = 0.0;
        const double r2 = TLSPH::dot3(Xij, Xij);
        if (r2 >= cut2 || r2 <= 0.0) continue;
        TLSPH::Bond b;
        TLSPH::make_bond(kernel, Xij, V[i], V[j], j, static_cast<int>(bonds[i].size()), b,
                         kernel_scale);
        bonds[i].push_back(b);
      }
  }

  // break the bond i-j from both ends (lambda_ij = lambda_ji = 0)
  void remove_bond(int i, int j)
  {
    auto drop = [&](int a, int b) {
      auto &row = bonds[a];
      row.erase(std::remove_if(row.begin(), row.end(),
                               [b](const TLSPH::Bond &bd) { return bd.j == b; }),
                row.end());
    };
    drop(i, j);
    drop(j, i);
  }

  // the bond i -> j, or null
  const TLSPH::Bond *find_bond(int i, int j) const
  {
    for (const auto &b : bonds[i])
      if (b.j == j) return &b;
    return nullptr;
  }

  // corrected gradients from the current bond rows (build_bond_cache)
  void correct()
  {
    const int N = size();
    Q.assign(static_cast<size_t>(TLSPH::QMAX) * N, 0.0);
    sumg.assign(3 * N, 0.0);
    achieved.assign(N, -1);
    std::vector<double> vj;
    with_dim_order(dim, order, [&](auto D, auto O) {
      constexpr int DIM = decltype(D)::value, ORD = decltype(O)::value;
      for (int i = 0; i < N; i++) {
        auto &b = bonds[i];
        vj.clear();
        for (const auto &bd : b) vj.push_back(V[bd.j]);
        achieved[i] = TLSPH::correction<DIM, ORD>(b.data(), static_cast<int>(b.size()), vj.data(),
                                                  kernel, &Q[TLSPH::QMAX * i], &sumg[3 * i]);
      }
    });
  }

  // number of particles whose correction reached order o
  int count_achieved(int o) const
  {
    return static_cast<int>(std::count(achieved.begin(), achieved.end(), o));
  }

  // only sum_j g_ij from the current bond rows, keeping Q and the g, c of
  // the remaining bonds as they are
  void update_sumg()
  {
    for (int i = 0; i < size(); i++) {
      double s[3] = {0, 0, 0};
      for (const auto &b : bonds[i])
        for (int d = 0; d < 3; d++) s[d] += b.g[d];
      for (int d = 0; d < 3; d++) sumg[3 * i + d] = s[d];
    }
  }

  int packed_size() const
  {
    int ps = 0;
    with_dim_order(dim, order, [&](auto D, auto O) {
      ps = TLSPH::Packed<decltype(D)::value, decltype(O)::value>::size;
    });
    return ps;
  }

  // pass (1): F, P, K, psi, J, the packed rows and fown (compute_deformation)
  void deform()
  {
    const int N = size(), ps = packed_size();
    F.assign(9 * N, 0.0);
    P.assign(9 * N, 0.0);
    K.assign(9 * N, 0.0);
    psi.assign(N, 0.0);
    J.assign(N, 0.0);
    fown.assign(3 * N, 0.0);
    packed.assign(static_cast<size_t>(ps) * N, 0.0);
    const Rows xr{x.data(), 3};
    with_dim_order(dim, order, [&](auto D, auto O) {
      constexpr int DIM = decltype(D)::value, ORD = decltype(O)::value;
      for (int i = 0; i < N; i++) {
        const auto &b = bonds[i];
        TLSPH::deformation_gradient<DIM>(xr, i, b.data(), static_cast<int>(b.size()), &F[9 * i]);
        psi[i] = TLSPH::stress_tensors(laws[type[i]], DIM, &F[9 * i], &P[9 * i], &K[9 * i], &J[i]);
        TLSPH::pack_row<DIM, ORD>(V[i], &P[9 * i], &Q[TLSPH::QMAX * i], &F[9 * i], &K[9 * i],
                                  0.0, &sumg[3 * i], &packed[static_cast<size_t>(ps) * i],
                                  &fown[3 * i]);
      }
    });
  }

  // pass (3): forces (compute_forces); fs, fv, fh are overwritten, fs
  // starting from fown. With VISIT, visit(j, xij, fij) receives every bond
  // force on i, in the order of the loop (i ascending, then bonds[i])
  template <int HG, int VISC, int VISIT = 0, class Visit = TLSPH::NoBondVisitor>
  void forces(double alpha, double beta, double gamma, const Visit &visit = Visit())
  {
    const int N = size();
    fs = fown;
    fv.assign(3 * N, 0.0);
    fh.assign(3 * N, 0.0);
    const Rows xr{x.data(), 3}, vr{v.data(), 3}, pk{packed.data(), packed_size()};
    const TypeOf tr{type.data()};
    with_dim_order(dim, order, [&](auto D, auto O) {
      constexpr int DIM = decltype(D)::value, ORD = decltype(O)::value;
      // the viscosity coefficient travels in the packed row (per particle)
      for (int i = 0; i < N; i++)
        packed[static_cast<size_t>(packed_size()) * i + TLSPH::Packed<DIM, ORD>::A] = alpha;
      for (int i = 0; i < N; i++) {
        const auto &b = bonds[i];
        TLSPH::particle_force<DIM, ORD, HG, VISC, VISIT>(
            i, V[i], b.data(), static_cast<int>(b.size()), xr, vr, pk, tr, mats.data(), h,
            beta, gamma, &P[9 * i], &fs[3 * i], &fv[3 * i], &fh[3 * i], visit);
      }
    });
  }

  // x = A X + c for a 3x3 row-major A
  void affine(const double *A, const double *c)
  {
    for (int i = 0; i < size(); i++) {
      double y[3];
      TLSPH::mat_vec(A, Xr(i), y);
      for (int d = 0; d < 3; d++) x[3 * i + d] = y[d] + c[d];
      if (dim == 2) x[3 * i + 2] = 0.0;
    }
  }
};

inline double norm3(const double *a)
{
  return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

// largest |A_k - B_k| over the 9 entries
inline double max_abs_diff9(const double *A, const double *B)
{
  double m = 0.0;
  for (int k = 0; k < 9; k++) m = std::max(m, std::fabs(A[k] - B[k]));
  return m;
}

// rotation by angle about a (not necessarily unit) axis, Rodrigues' formula
inline void rotation(const double *axis, double angle, double *R)
{
  const double nrm = norm3(axis);
  const double k[3] = {axis[0] / nrm, axis[1] / nrm, axis[2] / nrm};
  const double c = std::cos(angle), s = std::sin(angle), t = 1.0 - c;
  R[0] = c + t * k[0] * k[0];
  R[1] = t * k[0] * k[1] - s * k[2];
  R[2] = t * k[0] * k[2] + s * k[1];
  R[3] = t * k[1] * k[0] + s * k[2];
  R[4] = c + t * k[1] * k[1];
  R[5] = t * k[1] * k[2] - s * k[0];
  R[6] = t * k[2] * k[0] - s * k[1];
  R[7] = t * k[2] * k[1] + s * k[0];
  R[8] = c + t * k[2] * k[2];
}

}    // namespace tlsph_test

#endif
