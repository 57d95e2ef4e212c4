/// \file
/// Articulated body inertias by the Riccati recursion (lesson 6).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "soa/chain/composite.hpp"
#include "soa/detail/plane.hpp"

namespace soa {

/// \f$n_k \times n_k\f$ matrices of one hinge (at most 6 x 6, no heap).
template <class S>
using HingeMatrix = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;

namespace detail {

/// The coordinate axis \f$\pm e_i\f$ of a one-degree-of-freedom hinge (its \f$i\f$), when its
/// axis is exactly one; -1 otherwise.
template <class S>
EIGEN_ALWAYS_INLINE int coordinate_axis(const HingeT<S>& h) {
  return coordinate_axis(h.axis);
}

/// The three blocks of \f$P\f$ rotated about the coordinate axis Axis (plane_rotate()).
template <int Axis, class S>
EIGEN_ALWAYS_INLINE void plane_rotate_blocks(const Mat3<S>& R, const Mat6<S>& P, Mat3<S>& P11,
                                             Mat3<S>& P12, Mat3<S>& P22) {
  P11 = plane_rotate<Axis>(R, Mat3<S>(P.template topLeftCorner<3, 3>()), true);
  P12 = plane_rotate<Axis>(R, Mat3<S>(P.template topRightCorner<3, 3>()), false);
  P22 = plane_rotate<Axis>(R, Mat3<S>(P.template bottomRightCorner<3, 3>()), true);
}

/// The shift of transform_symmetric() for an offset \f$l = \lambda e_{Axis}\f$ along a
/// coordinate axis (detail::coordinate_offset()): \f$L = \lambda \tilde e_{Axis}\f$ makes row
/// Axis of \f$L P_{12}^*\f$, \f$L P_{22}\f$ and \f$L (L P_{22})^*\f$ zero, and column Axis of
/// \f$L (L P_{22})^*\f$ too; the other entries are the general ones (axis_cross()), each sum
/// in the general order less its exactly zero terms: 32 flops instead of 108, the general
/// result bit for bit (up to the sign of a zero). Index names as in soa/detail/plane.hpp.
template <int Axis, class S>
EIGEN_ALWAYS_INLINE void shift_on_axis(S lambda, const Mat3<S>& P11, const Mat3<S>& P12,
                                       const Mat3<S>& P22, Mat6<S>& out) {
  constexpr int U = Axis == 2 ? 0 : Axis + 1, W = U == 2 ? 0 : U + 1;
  Mat3<S> LP12s, LP22;  // L P12^* and L P22, rows U and W only
  for (int j = 0; j < 3; ++j)
    for (int i : {U, W}) {
      LP12s(i, j) = axis_cross<Axis>(i, lambda, P12(j, U), P12(j, W));
      LP22(i, j) = axis_cross<Axis>(i, lambda, P22(U, j), P22(W, j));
    }
  for (int j = 0; j < 3; ++j)
    for (int i = j; i < 3; ++i) {
      S o = P11(i, j);
      if (i != Axis) o += LP12s(i, j);
      if (j != Axis) o += LP12s(j, i);
      if (i != Axis && j != Axis)
        o += axis_cross<Axis>(i, lambda, LP22(j, U), LP22(j, W));  // (L (L P22)^*)(i,j)
      out(i, j) = o;
    }
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < j; ++i) out(i, j) = out(j, i);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      out(i, j + 3) = out(j + 3, i) = i == Axis ? P12(i, j) : P12(i, j) + LP22(i, j);
  out.template bottomRightCorner<3, 3>() = P22;
}

}  // namespace detail

/// \f$\phi(x,y)\, P\, \phi^*(x,y)\f$ for a symmetric 6x6 \f$P\f$ (an articulated inertia),
/// from \f$(R, l)\f$ without the 6x6 \f$\phi\f$ (slide 79): rotate the blocks, then shift by
/// \f$L = \tilde l\f$: with \f$P' = \begin{pmatrix} P_{11} & P_{12} \\ P_{12}^* & P_{22}
/// \end{pmatrix}\f$ the blocks of \f$R P R^*\f$,
/// \f[ \phi P \phi^* = \begin{pmatrix} P_{11} + L P_{12}^* - P_{12} L + L P_{22} L^* &
///     P_{12} + L P_{22} \\ (P_{12} + L P_{22})^* & P_{22} \end{pmatrix}, \quad L^* = -L. \f]
/// The top left block is \f$P_{11} + L P_{12}^* + (L P_{12}^*)^* + L (L P_{22})^*\f$
/// (\f$P_{12} L = -(L P_{12}^*)^*\f$, \f$L P_{22} L^* = L (L P_{22})^*\f$): every product with
/// \f$L\f$ is a cross product with \f$l\f$ of a column, and the symmetric blocks are filled
/// from one triangle, so the result is symmetric exactly. A rotation about a coordinate axis
/// (detail::plane_rotation_axis()) rotates the blocks in its plane only
/// (detail::plane_rotate(), the same products less those with exact zeros and ones), and an
/// offset along a coordinate axis shifts by detail::shift_on_axis(), unless \p fast_path is
/// false: both give the general path's numbers (tested bit for bit). Writes \p out, which
/// must not be \p P.
template <class S>
void transform_symmetric(const PhiT<S>& phi, const Mat6<S>& P, Mat6<S>& out,
                         bool fast_path = true) {
  const Mat3<S>& R = phi.R();
  const Vec3<S>& l = phi.l();
  Mat3<S> P11, P12, P22, LP12s, LP22;
  const int axis = fast_path ? detail::plane_rotation_axis(R) : -1;
  if (axis == 0) {
    detail::plane_rotate_blocks<0>(R, P, P11, P12, P22);
  } else if (axis == 1) {
    detail::plane_rotate_blocks<1>(R, P, P11, P12, P22);
  } else if (axis == 2) {
    detail::plane_rotate_blocks<2>(R, P, P11, P12, P22);
  } else {
    const Mat3<S> RP11 = R * P.template topLeftCorner<3, 3>();
    const Mat3<S> RP22 = R * P.template bottomRightCorner<3, 3>();
    P12 = R * P.template topRightCorner<3, 3>() * R.transpose();
    // the symmetric blocks from their lower triangle
    for (int j = 0; j < 3; ++j)
      for (int i = j; i < 3; ++i) {
        P11(i, j) = RP11.row(i).dot(R.row(j));
        P22(i, j) = RP22.row(i).dot(R.row(j));
      }
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < j; ++i) P11(i, j) = P11(j, i), P22(i, j) = P22(j, i);
  }
  if (fast_path && detail::with_plane_axis(detail::coordinate_offset(l), [&](auto axis_c) {
        detail::shift_on_axis<decltype(axis_c)::value>(l[axis_c], P11, P12, P22, out);
      }))
    return;
  for (int j = 0; j < 3; ++j) {
    LP12s.col(j) = l.cross(P12.row(j).transpose());  // L P12^*
    LP22.col(j) = l.cross(P22.col(j));               // L P22
  }
  for (int j = 0; j < 3; ++j) {
    const Vec3<S> LLP22j = l.cross(LP22.row(j).transpose());  // column j of L (L P22)^*
    for (int i = j; i < 3; ++i) out(i, j) = P11(i, j) + LP12s(i, j) + LP12s(j, i) + LLP22j[i];
  }
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < j; ++i) out(i, j) = out(j, i);
  const Mat3<S> P12_LP22 = P12 + LP22;
  out.template topRightCorner<3, 3>() = P12_LP22;
  out.template bottomLeftCorner<3, 3>() = P12_LP22.transpose();
  out.template bottomRightCorner<3, 3>() = P22;
}

/// transform_symmetric() returning the result.
template <class S>
Mat6<S> transform_symmetric(const PhiT<S>& phi, const Mat6<S>& P) {
  Mat6<S> out;
  transform_symmetric(phi, P, out);
  return out;
}

/// The smallest ratio \f$\lambda_{\min}(D(k)) / \lambda_{\max}(H(k) Q(k) H^*(k))\f$ accepted
/// before \f$D(k)\f$ counts as singular: \f$10^3\,\varepsilon\f$ (2.2e-13 in double). Here
/// \f$Q(k) = \phi(k,k-1)\,P(k-1)\,\phi^*(k,k-1) + M(k)\f$ is \f$P(k)\f$ before hinge k-1's
/// projection: \f$P^+(k-1) = P(k-1) - G D G^*\f$ is a subtraction, and \f$D(k) = H Q H^* -
/// H\phi\,G D G^*\phi^* H^*\f$ keeps about \f$\log_{10}(\text{ratio}/\varepsilon)\f$ correct
/// digits (\f$0 < D \le H Q H^* \le H R H^*\f$). Below the threshold fewer than three
/// remain. At the tip \f$Q(1) = M(1)\f$: a massless tip, or a body that gives its axis
/// nothing to move, has ratio 0. (The ratio to the locked composite inertia \f$H R H^*\f$ of
/// lesson 5 would be far more cautious: it shrinks with the square of a long chain's length
/// while the rounding of \f$D\f$ does not.) singular_D_ratio() computes it.
template <class S>
S singular_D_threshold() {
  return S(1000) * eps<S>();
}

/// Stops a recursion at a singular \f$D(k)\f$: soa::Error naming body k and the ratio found.
template <class S>
[[noreturn]] void throw_singular_D(const std::string& name, int k, S ratio) {
  char buf[240];
  std::snprintf(buf, sizeof buf,
                "': articulated inertia D(%d) singular: lambda_min(D)/lambda_max(H Q H*) = "
                "%.3g, below the threshold %.3g (Q = phi P(k-1) phi* + M(k))",
                k, double(ratio), double(singular_D_threshold<S>()));
  throw Error("body '" + name + buf);
}

/// Per-body results of the Riccati recursion; sized once for a model (\f$D, D^{-1}, G\f$ to
/// each hinge's \f$n_k\f$, so that riccati_step() writes their entries and not their sizes).
template <class S>
struct ArticulatedT {
  explicit ArticulatedT(const ModelT<S>& m) : ArticulatedT(m.n(), m.n(), false) {
    for (int k = 1; k <= m.n(); ++k) {
      const int nv = m.body(k).hinge.nv();
      D[k - 1].resize(nv, nv), D_inv[k - 1].resize(nv, nv), G[k - 1].resize(6, nv);
    }
  }
  /// Rolling storage: \f$P, P^+, D, D^{-1}, G\f$ of the last two bodies of the recursion
  /// only (riccati_step() needs body k-1's to make body k's), no \f$R\f$: what the O(N)
  /// forward dynamics of a long chain keeps (ForwardDynamicsT's lean storage).
  static ArticulatedT rolling() { return ArticulatedT(2, 0, true); }
  /// Where body k's entries are: k - 1, or (k - 1) mod 2 in rolling storage.
  int slot(int k) const { return rolling_ ? (k - 1) & 1 : k - 1; }
  std::vector<Mat6<S>> P;             ///< \f$P(k)\f$
  std::vector<Mat6<S>> P_plus;        ///< \f$P^+(k) = \bar\tau(k) P(k)\f$
  std::vector<HingeMatrix<S>> D;      ///< \f$D(k) = H(k) P(k) H^*(k)\f$
  std::vector<HingeMatrix<S>> D_inv;  ///< \f$D^{-1}(k)\f$
  std::vector<JointMap<S>> G;         ///< \f$G(k) = P(k) H^*(k) D^{-1}(k)\f$
  /// Composite inertias \f$R(k)\f$ of lesson 5, filled by articulated_inertias() (lesson 6
  /// compares \f$P(k) \le R(k)\f$); the O(N) algorithms leave them alone.
  std::vector<SpatialInertiaT<S>> R;
  /// \f$\bar\tau(k) = I - G(k) H(k)\f$ (a projection), formed on request.
  Mat6<S> tau_bar(const ModelT<S>& m, const VecX<S>& theta, int k) const {
    const BodyT<S>& B = m.body(k);
    return Mat6<S>::Identity() - G[k - 1] * B.hinge.H_star(theta.data() + B.q_offset).transpose();
  }

 private:
  ArticulatedT(int n, int n_R, bool rolling)
      : P(n), P_plus(n), D(n), D_inv(n), G(n), R(n_R), rolling_(rolling) {}
  bool rolling_;
};
using Articulated = ArticulatedT<double>;

/// The hinge map \f$H^*(k)\f$ of a one-degree-of-freedom hinge as a 6-vector.
template <class S>
Vec6<S> one_dof_map(const HingeT<S>& h) {
  Vec6<S> s = Vec6<S>::Zero();
  if (h.type != HingeType::Prismatic) s.template head<3>() = h.axis;
  if (h.type == HingeType::Prismatic) s.template tail<3>() = h.axis;
  if (h.type == HingeType::Helical) s.template tail<3>() = h.pitch * h.axis;
  return s;
}

/// An upper bound of \f$\lambda_{\max}(R(k))\f$, the composite inertia of lesson 5, kept as
/// \f$\mathrm{tr}\, R(k) = 3m + \mathrm{tr}\, J(O_k)\f$ from \f$(m, h = m p, \mathrm{tr}\,J)\f$
/// in a few flops per body: moving the origin by \f$\phi(k,k-1) = (R, l)\f$ gives
/// \f$h \to Rh + m l\f$ and \f$\mathrm{tr}\,J \to \mathrm{tr}\,J + 4\, l\cdot Rh + 2m|l|^2\f$.
/// riccati_step() compares \f$D(k)\f$ with it and computes the exact ratio of
/// singular_D_threshold() only when the bound cannot tell.
template <class S>
struct CompositeTraceT {
  S m = S(0);
  Vec3<S> h = Vec3<S>::Zero();
  S trJ = S(0);
  /// Bodies 1..k-1 seen from \f$O_k\f$ (\p phi is \f$\phi(k,k-1)\f$, null at the tip), then
  /// body k added.
  void step(const PhiT<S>* phi, const SpatialInertiaT<S>& M) {
    if (phi) {
      const Vec3<S> Rh = phi->R() * h;
      trJ += S(4) * phi->l().dot(Rh) + S(2) * m * phi->l().squaredNorm();
      h = Rh + m * phi->l();
    }
    m += M.mass();
    h += M.h();
    trJ += M.J().trace();
  }
  S trace() const { return S(3) * m + trJ; }
};

/// \f$P \mathrel{+}= M\f$ for a spatial inertia \f$(m, h, J)\f$ (slide 68):
/// \f$M = \begin{pmatrix} J & \tilde h \\ -\tilde h & m I \end{pmatrix}\f$.
template <class S>
EIGEN_ALWAYS_INLINE void add_inertia(const SpatialInertiaT<S>& M, Mat6<S>& P) {
  const Vec3<S>& h = M.h();
  P.template topLeftCorner<3, 3>() += M.J();
  P(0, 4) -= h[2], P(0, 5) += h[1], P(1, 3) += h[2], P(1, 5) -= h[0], P(2, 3) -= h[1],
      P(2, 4) += h[0];
  P(4, 0) -= h[2], P(5, 0) += h[1], P(3, 1) += h[2], P(5, 1) -= h[0], P(3, 2) -= h[1],
      P(4, 2) += h[0];
  P.template bottomRightCorner<3, 3>().diagonal().array() += M.mass();
}

namespace detail {

/// The eigenvalues of a symmetric \f$n_k \times n_k\f$ hinge matrix, out of line: only the
/// multi-degree-of-freedom hinges and the singularity check need them, and the Riccati step
/// stays small.
template <class S>
EIGEN_DONT_INLINE Eigen::Matrix<S, Eigen::Dynamic, 1, 0, 6, 1> hinge_eigenvalues(
    const HingeMatrix<S>& D) {
  return Eigen::SelfAdjointEigenSolver<HingeMatrix<S>>(D, Eigen::EigenvaluesOnly).eigenvalues();
}

}  // namespace detail

/// The ratio \f$\lambda_{\min}(D(k)) / \lambda_{\max}(H(k) Q(k) H^*(k))\f$ of
/// singular_D_threshold(), from \p art after step k of the Riccati recursion (0 when
/// \f$H Q H^* = 0\f$); \p d_min is \f$\lambda_{\min}(D(k))\f$.
template <class S>
S singular_D_ratio(const ModelT<S>& m, const StateT<S>& x, const WorkspaceT<S>& ws,
                   const ArticulatedT<S>& art, int k, S d_min) {
  const BodyT<S>& B = m.body(k);
  Mat6<S> Q = k > 1 ? transform_symmetric(ws.phi[k - 2], art.P[art.slot(k - 1)]) : Mat6<S>::Zero();
  add_inertia(B.M, Q);
  const JointMap<S> Hs = B.hinge.H_star(x.theta.data() + B.q_offset);
  const HingeMatrix<S> DQ = Hs.transpose() * Q * Hs;
  const S q_max = detail::hinge_eigenvalues(DQ).maxCoeff();
  return q_max > S(0) ? d_min / q_max : S(0);
}

/// The same, \f$\lambda_{\min}(D(k))\f$ taken from \p art.
template <class S>
S singular_D_ratio(const ModelT<S>& m, const StateT<S>& x, const WorkspaceT<S>& ws,
                   const ArticulatedT<S>& art, int k) {
  const S d_min = detail::hinge_eigenvalues(art.D[art.slot(k)]).minCoeff();
  return singular_D_ratio(m, x, ws, art, k, d_min);
}

/// One step k of the Riccati recursion (lesson 6), after step k-1:
/// \f[ P(k) = \phi(k,k-1)\, P^+(k-1)\, \phi^*(k,k-1) + M(k), \quad D(k) = H(k)P(k)H^*(k),
/// \quad G(k) = P(k)H^*(k)D^{-1}(k), \quad P^+(k) = P(k) - G(k) D(k) G^*(k), \f]
/// the last being \f$\bar\tau(k) P(k)\f$ written symmetrically; one-degree-of-freedom
/// hinges take a scalar path. A \f$D(k)\f$ below singular_D_threshold() relative to
/// \f$H Q H^*\f$ throws (throw_singular_D()); the ratio is computed only when the cheap
/// bound \p guard cannot vouch for \f$D(k)\f$. Returns \f$\lambda_{\min}(D(k))\f$.
template <class S>
S riccati_step(const ModelT<S>& m, const StateT<S>& x, const WorkspaceT<S>& ws, int k,
               ArticulatedT<S>& art, CompositeTraceT<S>& guard) {
  const BodyT<S>& B = m.body(k);
  const S* th = x.theta.data() + B.q_offset;
  const int slot = art.slot(k);
  Mat6<S>& P = art.P[slot];
  if (k > 1)
    transform_symmetric(ws.phi[k - 2], art.P_plus[art.slot(k - 1)], P, m.fast_paths);
  else
    P.setZero();
  add_inertia(B.M, P);
  guard.step(k > 1 ? &ws.phi[k - 2] : nullptr, B.M);
  const int nv = B.hinge.nv();
  S d_min;
  if (nv == 1) {
    // One-dof hinge, H^*(k) = s a 6-vector: D(k) = s^* P s is a scalar, so D^{-1}(k) is a
    // division (no eigen-decomposition or inverse of an n_k x n_k matrix), G(k) = P s / D a
    // 6-vector and P^+ = P - G (P s)^* a rank-one update: the general branch's formulas for
    // n_k = 1. P s is a signed column of P for a revolute or prismatic hinge about a coordinate
    // axis (s = +-e_c: no products), P's first three columns times the axis for another
    // revolute one (s = [a; 0]: the products with s's zeros dropped), else P s.
    const Vec6<S> s = one_dof_map(B.hinge);
    const int axis =
        m.fast_paths && B.hinge.type != HingeType::Helical ? detail::coordinate_axis(B.hinge) : -1;
    Vec6<S> Ps;
    S d;
    if (axis >= 0) {
      const int c = B.hinge.type == HingeType::Prismatic ? axis + 3 : axis;
      Ps = s[c] * P.col(c);
      d = s[c] * Ps[c];
    } else {
      Ps = B.hinge.type == HingeType::Revolute ? Vec6<S>(P.template leftCols<3>() * B.hinge.axis)
                                               : Vec6<S>(P * s);
      d = s.dot(Ps);
    }
    d_min = d;  // the one eigenvalue of a 1x1 D(k)
    // Sized once (ArticulatedT's constructor): no write to the size fields.
    if (art.D[slot].rows() != 1 || art.D_inv[slot].rows() != 1 || art.G[slot].cols() != 1)
      art.D[slot].resize(1, 1), art.D_inv[slot].resize(1, 1), art.G[slot].resize(6, 1);
    art.D[slot](0, 0) = d;
    const S d_inv = S(1) / d;
    art.D_inv[slot](0, 0) = d_inv;
    const Vec6<S> g = Ps * d_inv;
    art.G[slot].col(0) = g;
    art.P_plus[slot].noalias() = P - g * Ps.transpose();
  } else {
    const JointMap<S> Hs = B.hinge.H_star(th);
    const JointMap<S> PHs = P * Hs;
    art.D[slot] = Hs.transpose() * PHs;
    d_min = detail::hinge_eigenvalues(art.D[slot]).minCoeff();
    art.D_inv[slot] = art.D[slot].inverse();
    art.G[slot] = PHs * art.D_inv[slot];
    art.P_plus[slot] = P - art.G[slot] * PHs.transpose();
  }
  // |H*(k)|_F^2 times tr R(k) bounds lambda_max(H Q H*) from above (Q <= R): when D(k)
  // clears the threshold against this bound it clears it against the exact ratio, and
  // singular_D_ratio()'s eigenvalues are computed only for the hinges near singular.
  const S h2 = B.hinge.type == HingeType::Helical ? S(1) + B.hinge.pitch * B.hinge.pitch : S(nv);
  if (!(d_min > singular_D_threshold<S>() * h2 * guard.trace()) && std::isfinite(double(d_min))) {
    const S ratio = singular_D_ratio(m, x, ws, art, k, d_min);
    if (!(ratio > singular_D_threshold<S>())) throw_singular_D(B.name, k, ratio);
  }
  return d_min;
}

/// The fast form of soa::reference::articulated_inertias().
/// The articulated body inertias by the Riccati recursion (lesson 6), tip to base: every
/// riccati_step(), with the composite inertias \f$R(k)\f$ of lesson 5 kept in \p out.R. A
/// hinge whose \f$D(k)\f$ is singular or numerically singular (a massless tip, an inertia
/// that gives the axis nothing to move) stops the recursion with soa::Error naming the body
/// and the ratio found (see singular_D_threshold()); so does a non-finite \f$\theta\f$.
/// Needs update_phi().
template <class S>
void articulated_inertias(const ModelT<S>& m, const StateT<S>& x, const WorkspaceT<S>& ws,
                          ArticulatedT<S>& out) {
  composite_inertias(m, ws, out.R);
  CompositeTraceT<S> guard;
  for (int k = 1; k <= m.n(); ++k) {
    const S d_min = riccati_step(m, x, ws, k, out, guard);
    if (!std::isfinite(double(d_min)))
      throw Error("body '" + m.body(k).name + "': articulated inertia D(" + std::to_string(k) +
                  ") is not finite (check theta and the inertias)");
  }
}

}  // namespace soa
