/* -*- c++ -*- ----------------------------------------------------------
   USER-TLSPH: the LAMMPS-free crack-tip mechanics of crack-tip tracking
   (pair_style tlsph/damage criterion tip; PairTLSPHDamage::grow_tips):
   the stress intensity factors by displacement correlation and the
   maximum-tangential-stress rule (Erdogan & Sih 1963), the energy release
   rate by the domain J-integral, the mode mix by the interaction integral,
   the speed law (Freund) and the branching
   rule (Yoffe). Plain C++, tested without LAMMPS
   (unittest/physics/test_crack.cpp) against the Williams near-tip fields.
   The crack-tips class (tlsph_crack_tips.h) applies them in a run.
------------------------------------------------------------------------- */

#ifndef TLSPH_CRACK_H
#define TLSPH_CRACK_H

#include "tlsph_math.h"

#include <cmath>
#include <complex>

namespace TLSPH {

/* K_I and K_II from the displacement jump across the crack faces at n
   distances r[k] behind the tip: jn[k] the jump normal to the faces (the +
   face, to the left of the path's direction, minus the - face), jt[k] the
   tangential jump. Near the tip (Williams) the jump is
   du(r) = 8 K / E' sqrt(r / 2 pi) + O(r^3/2), E' = E in plane stress and
   E / (1 - nu^2) in plane strain: du / sqrt(r) = c1 + c3 r is fitted by
   least squares (the mean of du / sqrt(r) for one sample) and
   K = E' sqrt(2 pi) / 8 c1, the fit extrapolated to r = 0. Faces that
   overlap (c1 < 0 normal) give K_I = 0: no opening mode. */
struct CrackK {
  double KI, KII;
};
inline CrackK displacement_correlation(int n, const double *r, const double *jn, const double *jt,
                                       double Eprime)
{
  double sr = 0, sr2 = 0, syn = 0, syt = 0, srn = 0, srt = 0;
  for (int k = 0; k < n; k++) {
    const double yn = jn[k] / std::sqrt(r[k]);
    const double yt = jt[k] / std::sqrt(r[k]);
    sr += r[k];
    sr2 += r[k] * r[k];
    syn += yn;
    syt += yt;
    srn += r[k] * yn;
    srt += r[k] * yt;
  }
  if (n == 0) return CrackK{0.0, 0.0};
  double cn = syn / n, ct = syt / n;
  if (n >= 2) {
    const double det = n * sr2 - sr * sr;
    cn = (sr2 * syn - sr * srn) / det;
    ct = (sr2 * syt - sr * srt) / det;
  }
  const double f = Eprime / 8.0 * std::sqrt(2.0 * M_PI);
  const double KI = f * cn;
  return CrackK{KI > 0.0 ? KI : 0.0, f * ct};
}

/* The same with the tip's effective position fitted too (kfit offset).
   Behind the tip of a discrete crack the faces open as if the tip lay a
   distance delta further on (the bonds cut through the tip's end weaken the
   material just ahead of it; measured delta ~ 0.5 h, bench/kcheck.md), and
   a sample at r then reads du(r) = 8 K / E' sqrt((r + delta) / 2 pi)
   (1 + O(r)): the fit above, anchored at the path's end, turns that into an
   error of sqrt(1 + delta / r) that does not shrink with the resolution
   (the samples lie at fixed multiples of h). Squared, the expansion is
   du^2 = A r + B + C r^2 + O(r^3) with A = 32 K^2 / (pi E'^2), B = A delta
   and C from the next Williams term (and a finite crack's curvature): fitted
   by least squares, K = E' sqrt(pi A / 32), with the sign of the mean jump
   (K_I = 0 for closed faces, or A <= 0: no sqrt(r) opening). Needs three
   samples at distinct r; with fewer, displacement_correlation. */
inline double fit_squared_jump(int n, const double *r, const double *j)
{
  // normal equations of j^2 = A r + B + C r^2, solved by Cramer's rule
  double s[5] = {0, 0, 0, 0, 0}, t[3] = {0, 0, 0};
  for (int k = 0; k < n; k++) {
    double p = 1.0;
    for (int e = 0; e < 5; e++) s[e] += p, p *= r[k];
    const double y = j[k] * j[k];
    t[0] += y, t[1] += y * r[k], t[2] += y * r[k] * r[k];
  }
  // unknowns (B, A, C) with powers 0, 1, 2: M[a][b] = s[a + b]
  const double M[3][3] = {{s[0], s[1], s[2]}, {s[1], s[2], s[3]}, {s[2], s[3], s[4]}};
  const auto det3 = [](const double m[3][3]) {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
        m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
        m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  };
  const double d = det3(M);
  if (!(std::fabs(d) > 0.0)) return 0.0;
  double MA[3][3] = {{s[0], t[0], s[2]}, {s[1], t[1], s[3]}, {s[2], t[2], s[4]}};
  return det3(MA) / d;    // A
}

inline CrackK displacement_correlation_offset(int n, const double *r, const double *jn,
                                              const double *jt, double Eprime)
{
  if (n < 3) return displacement_correlation(n, r, jn, jt, Eprime);
  double mn = 0.0, mt = 0.0;
  for (int k = 0; k < n; k++) mn += jn[k], mt += jt[k];
  const double An = fit_squared_jump(n, r, jn), At = fit_squared_jump(n, r, jt);
  const double f = Eprime * std::sqrt(M_PI / 32.0);
  const double KI = (mn > 0.0 && An > 0.0) ? f * std::sqrt(An) : 0.0;
  const double KII = (At > 0.0) ? (mt >= 0.0 ? 1.0 : -1.0) * f * std::sqrt(At) : 0.0;
  return CrackK{KI, KII};
}

/* The maximum-tangential-stress kink angle (Erdogan & Sih): the direction
   theta, from the crack's line, where the hoop stress
   sigma_tt ~ cos(theta/2) [K_I cos^2(theta/2) - 3/2 K_II sin(theta)] is
   largest: d sigma_tt / d theta = 0 gives
   theta = 2 atan((K_I - sqrt(K_I^2 + 8 K_II^2)) / (4 K_II));
   0 for pure mode I, -/+70.53 deg for pure mode II with K_II >/< 0. */
inline double mts_kink_angle(double KI, double KII)
{
  if (std::fabs(KII) > 1.0e-12 * (std::fabs(KI) + std::fabs(KII)))
    return 2.0 * std::atan((KI - std::sqrt(KI * KI + 8.0 * KII * KII)) / (4.0 * KII));
  return 0.0;
}

/* The equivalent mode-I factor of that direction: sigma_tt(theta) sqrt(2 pi r)
   = cos(theta/2) [K_I cos^2(theta/2) - 3/2 K_II sin(theta)]; G = K_eq^2 / E'
   is the energy release rate the tip compares with G_c. */
inline double mts_equivalent_K(double KI, double KII, double theta)
{
  const double c2 = std::cos(0.5 * theta);
  return c2 * (KI * c2 * c2 - 1.5 * KII * std::sin(theta));
}

/* The kink of a straight segment of length s that leaves its end in mode I
   (tipdir segment). To first order in the kink theta, a kinked crack's
   tip a distance s along the kink has (Cotterell & Rice 1980)
     k_II(s) = K_II + theta [K_I / 2 - T sqrt(8 s / pi)],
   T the stress along the crack's line (the faces' tractions that the T
   stress puts on the kinked faces, -T theta, through the point-load weight
   sqrt(2 / (pi r)) of a semi-infinite crack). The maximum-tangential-stress
   kink (mts_kink_angle) zeroes the first two terms; a segment that keeps
   that direction for s ends with k_II = -theta T sqrt(8 s / pi), which
   under T < 0 has the sign opposite to K_II: the next segment kinks back
   past the path, and the path zigzags. This angle zeroes k_II(s): the
   maximum-tangential-stress kink of K_II against K_I - 2 T sqrt(8 s / pi).
   Under T > 0 the correction would enlarge the kink without bound as
   T sqrt(8 s / pi) nears K_I / 2 (the path is unstable there, and the
   first-order form fails first): the kink is then the local one. */
inline double segment_kink_angle(double KI, double KII, double T, double s)
{
  const double KIe = T < 0.0 ? KI - 2.0 * T * std::sqrt(8.0 * s / M_PI) : KI;
  return mts_kink_angle(KIe, KII);
}

/* The energy release rate by the domain form of the dynamic J-integral
   (Moran & Shih 1987; Shih, Moran & Nakamura 1986), written in the
   reference configuration (total Lagrangian: P the first Piola-Kirchhoff
   stress, H = F - I the displacement gradient, W the strain energy and
   T = rho0 |v|^2 / 2 the kinetic energy per reference volume):
     J = int_A [P_iJ H_iK e_K - (W + T) e_J] q_,J dA
       + int_A rho0 [a_i H_iK e_K - v_i L_iK e_K] q dA
   e the crack's direction at the tip, a the acceleration, L = dv/dX, and q
   a weight that is 1 at the tip and 0 on the domain's outer edge (here 1
   inside r1, linear in r to 0 at r2). The faces inside the domain carry
   no traction, so no line integral remains. The second integral is zero
   for a static field, and for a crack running steadily (the field moves
   with the tip: v = -V u_,1, a = V^2 u_,11); it is the inertia of a field
   that changes as it moves (a stress wave passing a crack at rest). The
   crack tips add it with 'jinertia yes' (tlsph_crack_tips.cpp);
   j_integrand below is the first integral, j_inertia_force and
   j_inertia_velocity the two parts of the second. For a particle method A is
   a sum over the particles' volumes; the integrand of one particle is
   j_integrand(...) (3 x 3 row-major tensors, z rows and columns zero in
   2D but F_33). In linear elasticity J = (K_I^2 + K_II^2) / E' for a crack
   at rest. */
inline double ring_weight(double r, double r1, double r2, double *dqdr)
{
  if (r <= r1) {
    *dqdr = 0.0;
    return 1.0;
  }
  if (r >= r2) {
    *dqdr = 0.0;
    return 0.0;
  }
  *dqdr = -1.0 / (r2 - r1);
  return (r2 - r) / (r2 - r1);
}

// one particle's integrand; gq = grad q (reference frame), e unit, v its
// velocity, 3 components each
inline double j_integrand(const double *F, const double *P, double W, double rho0,
                          const double *v, const double *e, const double *gq)
{
  const double T = 0.5 * rho0 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  double j = -(W + T) * (e[0] * gq[0] + e[1] * gq[1] + e[2] * gq[2]);
  for (int i = 0; i < 3; i++) {
    // u_i,K e_K
    const double He = (F[3 * i] - (i == 0 ? 1.0 : 0.0)) * e[0] +
        (F[3 * i + 1] - (i == 1 ? 1.0 : 0.0)) * e[1] + (F[3 * i + 2] - (i == 2 ? 1.0 : 0.0)) * e[2];
    j += He * (P[3 * i] * gq[0] + P[3 * i + 1] * gq[1] + P[3 * i + 2] * gq[2]);
  }
  return j;
}

/* The inertia term of J, one particle's share, in two parts (the crack
   tips take them at different moments: the force where the step's forces
   are known, the velocity's with the step's deformation):
     rho0 V (a . H e) q = q (m a) . (H e), m a the particle's force f: per
   reference direction K (x, y), out[K] = f . H_(:,K), so that the part is
   q (out . e) once e is known;
     rho0 V (v . L e) q = q m v . (L e), L = dv/dX (3 x 3 row-major), v its
   velocity, returned for mv = m v. */
inline void j_inertia_force(const double *F, const double *f, double *out)
{
  for (int K = 0; K < 2; K++) {
    double s = 0.0;
    for (int i = 0; i < 3; i++) s += f[i] * (F[3 * i + K] - (i == K ? 1.0 : 0.0));
    out[K] = s;
  }
}

inline double j_inertia_velocity(const double *L, const double *mv, const double *e)
{
  double s = 0.0;
  for (int i = 0; i < 3; i++) s += mv[i] * (L[3 * i] * e[0] + L[3 * i + 1] * e[1] + L[3 * i + 2] * e[2]);
  return s;
}

/* K_I and K_II from J and the displacement correlation's mode mix: J sets
   the size, K_I^2 + K_II^2 = E' J, the correlation (kd) the ratio and the
   signs. J <= 0, or no mix to take (kd zero), gives zero. */
inline CrackK k_from_j(double J, const CrackK &kd, double Eprime)
{
  const double n2 = kd.KI * kd.KI + kd.KII * kd.KII;
  if (!(J > 0.0) || !(n2 > 0.0)) return CrackK{0.0, 0.0};
  const double s = std::sqrt(Eprime * J / n2);
  return CrackK{s * kd.KI, s * kd.KII};
}

/* The mode mix by the interaction integral (Yau, Wang & Corten 1980; the
   domain form of Moran & Shih 1987, as for J): the J-integral of the sum
   of the actual field and an auxiliary one, less the J of each, is
     I = int_A [P_ij Ha_i1 + Pa_ij H_i1 - Pa_ij H_ij delta_1j] q_,j dA
   in the crack's frame (x1 along e, x2 to its left), H = F - I and P the
   actual displacement gradient and stress (small strain: P for sigma), Ha
   and Pa the auxiliary Williams field of mode I or II with K = 1. In
   linear elasticity I = 2 K / E' of the actual field's K of that mode (a
   crack at rest; the inertia term left out as in J). Only the in-plane
   components enter: the auxiliary field has no u_3, and q_,3 = 0 (a disc
   in 2D, a cylinder through the thickness in 3D).

   williams_aux: the auxiliary field at (r, theta) in the crack's frame
   (theta from e, +-pi on the faces), mode 0 (I) or 1 (II), K = 1, plane
   strain (kappa = 3 - 4 nu) or stress (kappa = (3 - nu) / (1 + nu)), mu
   the shear modulus: its displacement gradient Ha[2][2] (Ha[i][j] =
   du_i/dx_j) and stress Pa[2][2]. */
inline void williams_aux(int mode, double r, double th, double mu, double kappa, double Ha[2][2],
                         double Pa[2][2])
{
  const double c = std::cos(th), s = std::sin(th), c2 = std::cos(0.5 * th), s2 = std::sin(0.5 * th);
  const double c32 = std::cos(1.5 * th), s32 = std::sin(1.5 * th);
  // u = sqrt(r) f(theta) / (2 mu sqrt(2 pi)); f and df/dtheta
  double f[2], g[2];
  if (mode == 0) {
    f[0] = (kappa - c) * c2;
    f[1] = (kappa - c) * s2;
    g[0] = s * c2 - 0.5 * (kappa - c) * s2;
    g[1] = s * s2 + 0.5 * (kappa - c) * c2;
  } else {
    f[0] = (kappa + 2.0 + c) * s2;
    f[1] = -(kappa - 2.0 + c) * c2;
    g[0] = 0.5 * (kappa + 2.0 + c) * c2 - s * s2;
    g[1] = 0.5 * (kappa - 2.0 + c) * s2 + s * c2;
  }
  // d/dx1 = cos d/dr - sin / r d/dtheta, d/dx2 = sin d/dr + cos / r d/dtheta
  const double a = 1.0 / (2.0 * mu * std::sqrt(2.0 * M_PI * r));
  for (int i = 0; i < 2; i++) {
    Ha[i][0] = a * (0.5 * c * f[i] - s * g[i]);
    Ha[i][1] = a * (0.5 * s * f[i] + c * g[i]);
  }
  const double b = 1.0 / std::sqrt(2.0 * M_PI * r);
  if (mode == 0) {
    Pa[0][0] = b * c2 * (1.0 - s2 * s32);
    Pa[1][1] = b * c2 * (1.0 + s2 * s32);
    Pa[0][1] = Pa[1][0] = b * c2 * s2 * c32;
  } else {
    Pa[0][0] = -b * s2 * (2.0 + c2 * c32);
    Pa[1][1] = b * s2 * c2 * c32;
    Pa[0][1] = Pa[1][0] = b * c2 * (1.0 - s2 * s32);
  }
}

/* The T-stress by the same integral (Kfouri 1986): the auxiliary field of
   a point force f = 1 per unit depth at the tip, pointing along the crack
   (+x1), in the body with the traction-free crack, Flamant's radial field
   sigma_rr = -cos(theta) / (pi r), sigma_tt = sigma_rt = 0, with the
   displacement
     u1 = -(kappa + 1) / (8 pi mu) ln r - sin^2(theta) / (4 pi mu)
     u2 = -(kappa - 1) / (8 pi mu) theta + sin(theta) cos(theta) / (4 pi mu).
   Its interaction integral with the actual field is T / E' (T the stress
   along the crack's line that the crack does not carry, the second term of
   Williams's series; the K fields and the higher terms give zero), as
   ctest physics.CrackTip.InteractionIntegralGivesTheTStress checks.
   point_force_aux: its displacement gradient Ha and stress Pa at (r, theta)
   (theta from e), mu and kappa as williams_aux. */
inline void point_force_aux(double r, double th, double mu, double kappa, double Ha[2][2],
                            double Pa[2][2])
{
  const double c = std::cos(th), s = std::sin(th), c2t = c * c - s * s;
  const double c1 = (kappa + 1.0) / (8.0 * M_PI * mu), cs = 1.0 / (4.0 * M_PI * mu),
               c3 = (kappa - 1.0) / (8.0 * M_PI * mu);
  // d/dx1: dr = cos, dtheta = -sin / r; d/dx2: dr = sin, dtheta = cos / r
  Ha[0][0] = (-c1 * c + 2.0 * cs * s * s * c) / r;
  Ha[0][1] = (-c1 * s - 2.0 * cs * s * c * c) / r;
  Ha[1][0] = (c3 * s - cs * c2t * s) / r;
  Ha[1][1] = (-c3 * c + cs * c2t * c) / r;
  const double srr = -c / (M_PI * r);
  Pa[0][0] = srr * c * c;
  Pa[1][1] = srr * s * s;
  Pa[0][1] = Pa[1][0] = srr * s * c;
}

/* one particle's integrands of I for modes I and II (out[0], out[1]) and of
   the point force's (out[2], with nout = 3): F, P 3 x 3 row-major
   (reference frame), X its reference position less the tip's, e the crack's
   unit direction, gq = grad q (3 components each); mu, kappa as
   williams_aux. A particle at the tip (r = 0) adds nothing. */
inline void interaction_integrand(const double *F, const double *P, const double *X,
                                  const double *e, const double *gq, double mu, double kappa,
                                  double *out, int nout = 2)
{
  for (int m = 0; m < nout; m++) out[m] = 0.0;
  // the crack's frame: rows e and n = e turned by +90 deg
  const double R[2][2] = {{e[0], e[1]}, {-e[1], e[0]}};
  const double x1 = R[0][0] * X[0] + R[0][1] * X[1], x2 = R[1][0] * X[0] + R[1][1] * X[1];
  const double r = std::hypot(x1, x2);
  if (!(r > 0.0)) return;
  const double th = std::atan2(x2, x1);
  double H[2][2], S[2][2], q[2];
  for (int i = 0; i < 2; i++) {
    q[i] = R[i][0] * gq[0] + R[i][1] * gq[1];
    for (int j = 0; j < 2; j++) {
      double h = 0.0, p = 0.0;
      for (int k = 0; k < 2; k++)
        for (int l = 0; l < 2; l++) {
          h += R[i][k] * (F[3 * k + l] - (k == l ? 1.0 : 0.0)) * R[j][l];
          p += R[i][k] * P[3 * k + l] * R[j][l];
        }
      H[i][j] = h;
      S[i][j] = p;
    }
  }
  for (int mode = 0; mode < nout; mode++) {
    double Ha[2][2], Pa[2][2];
    if (mode < 2) williams_aux(mode, r, th, mu, kappa, Ha, Pa);
    else point_force_aux(r, th, mu, kappa, Ha, Pa);
    double w12 = 0.0, v = 0.0;
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++) {
        w12 += Pa[i][j] * H[i][j];
        v += (S[i][j] * Ha[i][0] + Pa[i][j] * H[i][0]) * q[j];
      }
    out[mode] = v - w12 * q[0];
  }
}

/* Merging: the first point where a tip's move P -> Q meets the segment
   A -> B (a piece of another crack, or of its own path further back), as the
   fraction t of the move, 0 < t <= 1; -1 if it does not meet it. A segment
   through P itself (t = 0: the path the tip grows from, or a sibling branch
   born at the same point) does not count. A segment along the move's line
   (collinear, e.g. two tips running head-on) is met where it begins. */
inline double segment_crossing(const double *P, const double *Q, const double *A, const double *B)
{
  const double rx = Q[0] - P[0], ry = Q[1] - P[1];
  const double sx = B[0] - A[0], sy = B[1] - A[1];
  const double ax = A[0] - P[0], ay = A[1] - P[1];
  const double rr = rx * rx + ry * ry, ss = sx * sx + sy * sy;
  if (!(rr > 0.0)) return -1.0;
  constexpr double tiny = 1.0e-12;
  const double den = rx * sy - ry * sx;
  if (std::fabs(den) > tiny * std::sqrt(rr * ss)) {
    const double t = (ax * sy - ay * sx) / den, u = (ax * ry - ay * rx) / den;
    return (t > tiny && t <= 1.0 && u >= 0.0 && u <= 1.0) ? t : -1.0;
  }
  // parallel: only a collinear segment meets the move
  if (std::fabs(ax * ry - ay * rx) > tiny * rr) return -1.0;
  const double t0 = (ax * rx + ay * ry) / rr, t1 = ((B[0] - P[0]) * rx + (B[1] - P[1]) * ry) / rr;
  const double lo = std::fmin(t0, t1), hi = std::fmax(t0, t1);
  if (!(hi > tiny) || lo > 1.0) return -1.0;
  return lo > tiny ? lo : -1.0;
}

/* Nucleation: the largest principal stress s1 of a plane stress state and
   its direction (angle phi from x, in (-pi/2, pi/2]); a crack nucleates
   normal to it, i.e. along (-sin phi, cos phi). */
struct Principal2 {
  double s1, phi;
};
inline Principal2 principal_stress_2d(double sx, double sy, double sxy)
{
  const double c = 0.5 * (sx + sy), d = 0.5 * (sx - sy);
  const double r = std::sqrt(d * d + sxy * sxy);
  return Principal2{c + r, 0.5 * std::atan2(2.0 * sxy, sx - sy)};
}

/* The half length of a nucleated crack: Irwin's a_c = E' G_c / (pi
   sigma_t^2), at which a crack of length 2 a_c in a remote stress sigma_t
   has G = G_c (it is critical when it is born), but no shorter than half the
   tip model's reach (a tip needs its path behind it to measure K: the
   sample reach, or the J domain's outer radius, 'reach'); so a crack born at
   the strength is at least critical, and the seed shrinks with h. */
inline double nucleation_half_length(double Eprime, double Gc, double sigma_t, double reach)
{
  const double ac = Eprime * Gc / (M_PI * sigma_t * sigma_t);
  return ac > 0.5 * reach ? ac : 0.5 * reach;
}

/* The distance from point X to the segment A -> B. */
inline double point_segment_distance(const double *X, const double *A, const double *B)
{
  const double sx = B[0] - A[0], sy = B[1] - A[1], ss = sx * sx + sy * sy;
  double u = ss > 0.0 ? ((X[0] - A[0]) * sx + (X[1] - A[1]) * sy) / ss : 0.0;
  u = u < 0.0 ? 0.0 : (u > 1.0 ? 1.0 : u);
  return std::hypot(X[0] - A[0] - u * sx, X[1] - A[1] - u * sy);
}

/* The speed of a tip whose G reaches G_c: Freund's equation of motion,
   v = c_R (1 - G_c / G), so a tip never runs faster than c_R. */
inline double freund_speed(double G, double Gc, double cR)
{
  return cR * (1.0 - Gc / G);
}

/* The hoop stress sigma_theta_theta on the ray at angle phi (from x) of a
   plane stress state sx, sy, sxy: e_theta = (-sin phi, cos phi). */
inline double hoop_stress(double sx, double sy, double sxy, double phi)
{
  const double c = std::cos(phi), sn = std::sin(phi);
  return sx * sn * sn + sy * c * c - 2.0 * sxy * sn * c;
}

/* The branching rule 'branch yoffe': a fast crack branches when the hoop
   stress about its tip has a maximum on each side of its line (Yoffe 1951:
   the maxima leave the line above about 0.6 c_s), and the branches take
   those directions. From n samples hoop[k] at angles u[k] from the crack's
   line (ok[k] false: no sample), first a smooth profile (the samples carry
   the lattice's ripple): the least squares fit of
   c0 + c1 cos u + c2 cos 2u + s1 sin u + s2 sin 2u (cf, in that order),
   then its largest local maximum on each side of the line on a 1 deg grid
   within +-window deg (window 65: the fit is loosely held near its ends, and
   the off-axis maxima of a running crack stay within about 60-65 deg of its
   line up to the Rayleigh speed). split: both maxima exist and are tensile
   (> 0); ul < 0 < ur their angles [rad], bl, br their values. */
struct YoffeBranches {
  int split;
  double ul, ur, bl, br;
  double cf[5];
};
inline YoffeBranches yoffe_branches(int n, const double *u, const double *hoop, const int *ok,
                                    int window)
{
  YoffeBranches r{0, 0.0, 0.0, -1.0, -1.0, {0.0, 0.0, 0.0, 0.0, 0.0}};
  double M[25] = {0.0}, rhs[5] = {0.0};
  auto basis = [](double v, double *b) {
    b[0] = 1.0;
    b[1] = std::cos(v);
    b[2] = std::cos(2.0 * v);
    b[3] = std::sin(v);
    b[4] = std::sin(2.0 * v);
  };
  int nfit = 0;
  for (int j = 0; j < n; j++) {
    if (!ok[j]) continue;
    double b[5];
    basis(u[j], b);
    for (int a = 0; a < 5; a++) {
      rhs[a] += b[a] * hoop[j];
      for (int c = 0; c < 5; c++) M[5 * a + c] += b[a] * b[c];
    }
    nfit++;
  }
  double Minv[25];
  if (nfit >= 5 && invert_small(5, M, Minv))
    for (int a = 0; a < 5; a++)
      for (int c = 0; c < 5; c++) r.cf[a] += Minv[5 * a + c] * rhs[c];
  auto smooth = [&](double v) {
    double b[5];
    basis(v, b);
    return r.cf[0] * b[0] + r.cf[1] * b[1] + r.cf[2] * b[2] + r.cf[3] * b[3] + r.cf[4] * b[4];
  };
  for (int d = -window; d <= window; d++) {
    const double v = d * M_PI / 180.0, e = M_PI / 180.0;
    const double f0 = smooth(v);
    if (!(f0 > smooth(v - e) && f0 >= smooth(v + e))) continue;
    if (d < 0 && (r.bl < 0.0 || f0 > r.bl)) r.bl = f0, r.ul = v;
    if (d > 0 && (r.br < 0.0 || f0 > r.br)) r.br = f0, r.ur = v;
  }
  r.split = (r.bl > 0.0 && r.br > 0.0) ? 1 : 0;
  return r;
}

/* The singular field of a tip running at a constant speed v (Freund 1990,
   chapter 4; Yoffe 1951 for mode I), in the tip's frame, x_1
   along the crack's line: with b_d = v / c_d, b_s = v / c_s, alpha_j =
   sqrt(1 - b_j^2), D = 4 alpha_d alpha_s - (1 + alpha_s^2)^2 (zero at the
   Rayleigh speed), and on the ray at angle u the scaled angles and radii
   tan u_j = alpha_j tan u, g_j = sqrt(1 - (b_j sin u)^2):
     mode I  (K_I / sqrt(2 pi r)):
       s11 = [(1 + a_s^2)(1 + 2 a_d^2 - a_s^2) C_d - 4 a_d a_s C_s] / D
       s22 = [-(1 + a_s^2)^2 C_d + 4 a_d a_s C_s] / D
       s12 = 2 a_d (1 + a_s^2) (S_d - S_s) / D
     mode II (K_II / sqrt(2 pi r)):
       s11 = -2 a_s [(1 + 2 a_d^2 - a_s^2) S_d - (1 + a_s^2) S_s] / D
       s22 = 2 a_s (1 + a_s^2) (S_d - S_s) / D
       s12 = [4 a_d a_s C_d - (1 + a_s^2)^2 C_s] / D
   with C_j = cos(u_j / 2) / sqrt(g_j), S_j = sin(u_j / 2) / sqrt(g_j). At v
   -> 0 it is the static field (tested), at u = 0 s22 (mode I) and s12 (mode
   II) are 1 (the definition of K), and on the faces (u = +-pi) the
   tractions vanish. c_d / c_s from kappa: c_d^2 / c_s^2 = (kappa + 1) /
   (kappa - 1) in plane strain (kappa = 3 - 4 nu) and plane stress (kappa =
   (3 - nu) / (1 + nu)) alike. Below v = 1e-3 c_s the static field is used
   (D and the brackets both vanish as v^2). */
struct RunningTip {
  double ad, as, bd, bs, D;
  bool stat;
};
inline RunningTip running_tip(double v_over_cs, double kappa)
{
  RunningTip t{1.0, 1.0, 0.0, 0.0, 0.0, true};
  if (!(v_over_cs > 1.0e-3)) return t;
  t.stat = false;
  t.bs = v_over_cs;
  t.bd = v_over_cs * std::sqrt((kappa - 1.0) / (kappa + 1.0));
  t.as = std::sqrt(std::max(0.0, 1.0 - t.bs * t.bs));
  t.ad = std::sqrt(std::max(0.0, 1.0 - t.bd * t.bd));
  t.D = 4.0 * t.ad * t.as - (1.0 + t.as * t.as) * (1.0 + t.as * t.as);
  return t;
}
/* the stress (s11, s22, s12) of the unit K of mode 1 or 2 at angle u, r with
   sqrt(2 pi r) = 1, in the tip's frame */
inline void running_tip_stress(const RunningTip &t, int mode, double u, double s[3])
{
  if (t.stat) {
    const double c = std::cos(0.5 * u), sn = std::sin(0.5 * u), c3 = std::cos(1.5 * u), s3 = std::sin(1.5 * u);
    if (mode == 1) {
      s[0] = c * (1.0 - sn * s3);
      s[1] = c * (1.0 + sn * s3);
      s[2] = c * sn * c3;
    } else {
      s[0] = -sn * (2.0 + c * c3);
      s[1] = sn * c * c3;
      s[2] = c * (1.0 - sn * s3);
    }
    return;
  }
  const double cu = std::cos(u), su = std::sin(u);
  const double ud = std::atan2(t.ad * su, cu), us = std::atan2(t.as * su, cu);
  const double gd = std::sqrt(std::sqrt(cu * cu + t.ad * t.ad * su * su));
  const double gs = std::sqrt(std::sqrt(cu * cu + t.as * t.as * su * su));
  const double Cd = std::cos(0.5 * ud) / gd, Cs = std::cos(0.5 * us) / gs;
  const double Sd = std::sin(0.5 * ud) / gd, Ss = std::sin(0.5 * us) / gs;
  const double a2 = 1.0 + t.as * t.as;
  if (mode == 1) {
    s[0] = (a2 * (1.0 + 2.0 * t.ad * t.ad - t.as * t.as) * Cd - 4.0 * t.ad * t.as * Cs) / t.D;
    s[1] = (-a2 * a2 * Cd + 4.0 * t.ad * t.as * Cs) / t.D;
    s[2] = 2.0 * t.ad * a2 * (Sd - Ss) / t.D;
  } else {
    s[0] = -2.0 * t.as * ((1.0 + 2.0 * t.ad * t.ad - t.as * t.as) * Sd - a2 * Ss) / t.D;
    s[1] = 2.0 * t.as * a2 * (Sd - Ss) / t.D;
    s[2] = (4.0 * t.ad * t.as * Cd - a2 * a2 * Cs) / t.D;
  }
}
/* Freund's universal functions of the energy release rate of a running tip,
   G = (A_I K_I^2 + A_II K_II^2) / E': A_I = 4 b_s^2 a_d / ((kappa + 1) D),
   A_II = 4 b_s^2 a_s / ((kappa + 1) D) (Freund 1990, chapter 5, with 1 / (1 - nu)
   = 4 / (kappa + 1) in plane strain); both 1 at rest, growing without
   bound towards the Rayleigh speed. */
inline void freund_A(const RunningTip &t, double kappa, double &AI, double &AII)
{
  if (t.stat || !(t.D > 0.0)) {
    AI = AII = t.stat ? 1.0 : INFINITY;
    return;
  }
  AI = 4.0 * t.bs * t.bs * t.ad / ((kappa + 1.0) * t.D);
  AII = 4.0 * t.bs * t.bs * t.as / ((kappa + 1.0) * t.D);
}

/* 'branch tstress/dynamic': the K of a tip running at v from its energy
   release rate. K_I and K_II here come from G = (K_I^2 + K_II^2) / E', the
   static relation, with their ratio rho = K_II / K_I; at speed, G = (A_I
   K_I^2 + A_II K_II^2) / E' with the same ratio, so both scale by sqrt((1 +
   rho^2) / (A_I + A_II rho^2)). */
inline void running_k(const RunningTip &t, double kappa, double &KI, double &KII)
{
  if (t.stat || !(KI > 0.0)) return;
  double AI, AII;
  freund_A(t, kappa, AI, AII);
  const double rho = KII / KI, f = std::sqrt((1.0 + rho * rho) / (AI + AII * rho * rho));
  KI *= f;
  KII *= f;
}

/* The displacement gradient H (H[i][j] = du_i/dx_j) and stress S of the
   running tip's singular field (unit K of mode 1 or 2, shear modulus mu) at
   (x1, x2) in the tip's frame, from Freund's potentials (1990, ch. 4): u =
   grad phi + curl psi with phi = Re F(z_d), psi = Im G(z_s), z_j = x1 + i
   a_j x2, F'' = a z_d^(-1/2), G'' = b z_s^(-1/2):
     u1,1 = Re F'' + a_s Re G''         u1,2 = -a_d Im F'' - a_s^2 Im G''
     u2,1 = -a_d Im F'' - Im G''        u2,2 = -a_d^2 Re F'' - a_s Re G''
   traction-free faces and K fix a, b: mode I a = (1 + a_s^2) c, b = -2 a_d c;
   mode II a = -2 i a_s c, b = i (1 + a_s^2) c, c = 1 / (mu D sqrt(2 pi)).
   Its stress is running_tip_stress's (tested); a static tip (t.stat) gives
   Williams's field (williams_aux). */
inline void running_tip_gradient(const RunningTip &t, int mode, double mu, double kappa, double x1,
                                 double x2, double H[2][2], double S[2][2])
{
  if (t.stat) {
    williams_aux(mode - 1, std::hypot(x1, x2), std::atan2(x2, x1), mu, kappa, H, S);
    return;
  }
  using C = std::complex<double>;
  const double c = 1.0 / (mu * t.D * std::sqrt(2.0 * M_PI)), a2 = 1.0 + t.as * t.as;
  const C a = mode == 1 ? C(a2 * c, 0.0) : C(0.0, -2.0 * t.as * c);
  const C b = mode == 1 ? C(-2.0 * t.ad * c, 0.0) : C(0.0, a2 * c);
  const C F = a / std::sqrt(C(x1, t.ad * x2)), G = b / std::sqrt(C(x1, t.as * x2));
  H[0][0] = F.real() + t.as * G.real();
  H[0][1] = -t.ad * F.imag() - t.as * t.as * G.imag();
  H[1][0] = -t.ad * F.imag() - G.imag();
  H[1][1] = -t.ad * t.ad * F.real() - t.as * G.real();
  const double lam = mu * (3.0 - kappa) / (kappa - 1.0), tr = H[0][0] + H[1][1];
  S[0][0] = lam * tr + 2.0 * mu * H[0][0];
  S[1][1] = lam * tr + 2.0 * mu * H[1][1];
  S[0][1] = S[1][0] = mu * (H[0][1] + H[1][0]);
}

/* The interaction integral on the circle r = 1 about a tip running at t
   (the actual field: its singular field of mode ma, K = 1) with the
   auxiliary field of mode mb of the tip tb (K = 1):
     I = int [S^b_ij H_ij delta_1j - S_ij H^b_i1 - S^b_ij H_i1] n_j ds
         + rho v^2 int H_i1 H^b_i1 n_1 ds   (kinetic: only with dynamic)
   (rho v^2 = mu (v / c_s)^2), by Gauss-Legendre quadrature in the angle
   (the integrand is smooth on [-pi, pi]; 48 points give 1e-10). With the
   singular fields alone the integral does not depend on the radius. With tb
   the same running tip and the kinetic term it is 2 A_m / E' for mb = ma
   (Freund's G) and 0 across modes; with a static tb and no kinetic term it
   is what the static domain integral of kfit interaction reads. */
inline double running_interaction(const RunningTip &t, int ma, const RunningTip &tb, int mb, double mu,
                                  double kappa, bool dynamic)
{
  // the 48 Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_48)
  struct Rule {
    double x[48], w[48];
  };
  static const Rule gl = [] {
    Rule r{};
    const int n = 48;
    for (int i = 0; i < n; i++) {
      double x = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 1.0;
      for (int it = 0; it < 100; it++) {
        double p0 = 1.0, p1 = x;
        for (int k = 2; k <= n; k++) {
          const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
          p0 = p1, p1 = p2;
        }
        dp = n * (x * p1 - p0) / (x * x - 1.0);
        const double dx = p1 / dp;
        x -= dx;
        if (std::fabs(dx) < 1.0e-16) break;
      }
      r.x[i] = x;
      r.w[i] = 2.0 / ((1.0 - x * x) * dp * dp);
    }
    return r;
  }();
  const double rv2 = dynamic && !t.stat ? mu * t.bs * t.bs : 0.0;
  double sum = 0.0;
  for (int k = 0; k < 48; k++) {
    const double th = M_PI * gl.x[k], w = M_PI * gl.w[k];
    const double n[2] = {std::cos(th), std::sin(th)};
    double H[2][2], S[2][2], Hb[2][2], Sb[2][2];
    running_tip_gradient(t, ma, mu, kappa, n[0], n[1], H, S);
    running_tip_gradient(tb, mb, mu, kappa, n[0], n[1], Hb, Sb);
    double w12 = 0.0, v = 0.0, kin = 0.0;
    for (int i = 0; i < 2; i++) {
      kin += H[i][0] * Hb[i][0];
      for (int j = 0; j < 2; j++) {
        w12 += Sb[i][j] * H[i][j];
        v += (S[i][j] * Hb[i][0] + Sb[i][j] * H[i][0]) * n[j];
      }
    }
    sum += w * ((w12 + rv2 * kin) * n[0] - v);
  }
  return sum;
}

/* 'kratio running': what the tips' static measurements of K_II / K_I read
   when the tip runs at t, as factors f_I, f_II of each mode (read K = f K),
   so that the true ratio is the read one times f_I / f_II.
   - The displacement correlation (kfit tip, offset, j): a running tip's
     faces open by A_I K_I and slide by A_II K_II times the static jump
     (Freund's fields on u = +-pi), f = A (freund_A), f_I / f_II = a_d / a_s.
   - The interaction integrals with Williams's static auxiliary fields and no
     kinetic term (kfit interaction): f_m = E' I / 2 of running_interaction
     with a static tb, e.g. 1.22 and 1.09 at 0.6 c_R (nu = 0.3, plane strain).
   Both read the ratio low at speed (0.87 and 0.90 of it at 0.6 c_R). */
inline void running_ratio_factors(const RunningTip &t, double mu, double kappa, bool interaction,
                                  double &fI, double &fII)
{
  if (t.stat) {
    fI = fII = 1.0;
    return;
  }
  if (!interaction) {
    freund_A(t, kappa, fI, fII);
    return;
  }
  const RunningTip st{1.0, 1.0, 0.0, 0.0, 0.0, true};
  const double h = 4.0 * mu / (kappa + 1.0);    // E' / 2
  fI = h * running_interaction(t, 1, st, 1, mu, kappa, false);
  fII = h * running_interaction(t, 2, st, 2, mu, kappa, false);
}

/* The branching rule 'branch tstress': the hoop stress of the tip's
   two-term field (K_I, K_II and the T-stress) at a distance r_c, a length
   of the material (after Ramulu and Kobayashi 1985, who put the crack-tip
   field's off-axis hoop maximum at a characteristic distance beside the
   energy condition):
     sigma_tt(r_c, u) = cos(u/2) [K_I cos^2(u/2) - 3/2 K_II sin u] / sqrt(2 pi r_c)
                        + T sin^2 u,
   u from the crack's line. In mode I it has a maximum off the line on each
   side when tau = T sqrt(2 pi r_c) / K_I > 3/8 (near u = 0 it is
   1 + (tau - 3/8) u^2 in units of the singular term), at cos u / cos(u/2) =
   3 / (8 tau): the maximum leaves the line at the distance
   r_0 = 9 K_I^2 / (128 pi T^2), and the crack branches where r_0 < r_c.
   The same maxima search as yoffe_branches (each side's largest local
   maximum within +-window deg, tensile), on the field itself (no fit), on a
   0.1 deg grid refined by a parabola. With a running tip t ('branch
   tstress/dynamic'), the singular field is that of running_tip_stress. */
inline YoffeBranches tstress_branches(double KI, double KII, double T, double rc, int window,
                                      const RunningTip &tip = RunningTip{1.0, 1.0, 0.0, 0.0, 0.0, true})
{
  YoffeBranches r{0, 0.0, 0.0, -1.0, -1.0, {0.0, 0.0, 0.0, 0.0, 0.0}};
  if (!(rc > 0.0)) return r;
  const double a = 1.0 / std::sqrt(2.0 * M_PI * rc);
  auto hoop = [&](double u) {
    const double s = std::sin(u);
    if (tip.stat) {
      const double c2 = std::cos(0.5 * u);
      return a * c2 * (KI * c2 * c2 - 1.5 * KII * s) + T * s * s;
    }
    double s1[3], s2[3];
    running_tip_stress(tip, 1, u, s1);
    running_tip_stress(tip, 2, u, s2);
    return a * (KI * hoop_stress(s1[0], s1[1], s1[2], u) + KII * hoop_stress(s2[0], s2[1], s2[2], u)) +
        T * s * s;
  };
  const double e = 0.1 * M_PI / 180.0;
  const int n = 10 * window;
  for (int d = -n; d <= n; d++) {
    if (d == 0) continue;
    const double v = d * e, f0 = hoop(v), fm = hoop(v - e), fp = hoop(v + e);
    if (!(f0 > fm && f0 >= fp)) continue;
    const double den = fm - 2.0 * f0 + fp;
    const double vm = den < 0.0 ? v + 0.5 * e * (fm - fp) / den : v;
    if (d < 0 && (r.bl < 0.0 || f0 > r.bl)) r.bl = f0, r.ul = vm;
    if (d > 0 && (r.br < 0.0 || f0 > r.br)) r.br = f0, r.ur = vm;
  }
  r.split = (r.bl > 0.0 && r.br > 0.0 && r.ul < 0.0 && r.ur > 0.0) ? 1 : 0;
  return r;
}

}    // namespace TLSPH

#endif
