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

/// The three blocks of \f$P\f$ rotated about the coordinate axis \f$I\f$ (plane_rotate()).
template <int I, class S>
EIGEN_ALWAYS_INLINE void plane_rotate_blocks(const Mat3<S>& R, const Mat6<S>& P, Mat3<S>& A,
                                             Mat3<S>& B, Mat3<S>& C) {
  A = plane_rotate<I>(R, Mat3<S>(P.template topLeftCorner<3, 3>()), true);
  B = plane_rotate<I>(R, Mat3<S>(P.template topRightCorner<3, 3>()), false);
  C = plane_rotate<I>(R, Mat3<S>(P.template bottomRightCorner<3, 3>()), true);
}

/// The shift of transform_symmetric() for an offset \f$l = \lambda e_I\f$ along a coordinate
/// axis (detail::coordinate_offset()): \f$L = \lambda \tilde e_I\f$ makes row \f$I\f$ of
/// \f$K = LB^*\f$, \f$Q = LC\f$ and \f$LQ^*\f$ zero, and column \f$I\f$ of \f$LQ^*\f$ too;
/// the other entries are the general ones (axis_cross()), each sum in the general order less
/// its exactly zero terms: 32 flops instead of 108, the general result bit for bit (up to
/// the sign of a zero).
template <int I, class S>
EIGEN_ALWAYS_INLINE void shift_on_axis(S lambda, const Mat3<S>& A, const Mat3<S>& B,
                                       const Mat3<S>& C, Mat6<S>& out) {
  constexpr int J = I == 2 ? 0 : I + 1, K = J == 2 ? 0 : J + 1;
  Mat3<S> LB, LC;  // K = L B^* and Q = L C, rows J and K only
  for (int j = 0; j < 3; ++j)
    for (int i : {J, K}) {
      LB(i, j) = axis_cross<I>(i, lambda, B(j, J), B(j, K));
      LC(i, j) = axis_cross<I>(i, lambda, C(J, j), C(K, j));
    }
  for (int j = 0; j < 3; ++j)
    for (int i = j; i < 3; ++i) {
      S o = A(i, j);
      if (i != I) o += LB(i, j);
      if (j != I) o += LB(j, i);
      if (i != I && j != I) o += axis_cross<I>(i, lambda, LC(j, J), LC(j, K));  // (L Q^*)(i,j)
      out(i, j) = o;
    }
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < j; ++i) out(i, j) = out(j, i);
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)
      out(i, j + 3) = out(j + 3, i) = i == I ? B(i, j) : B(i, j) + LC(i, j);
  out.template bottomRightCorner<3, 3>() = C;
}

}  // namespace detail

/// \f$\phi(x,y)\, P\, \phi^*(x,y)\f$ for a symmetric 6x6 \f$P\f$ (an articulated inertia),
/// from \f$(R, l)\f$ without the 6x6 \f$\phi\f$: rotate the blocks, then shift by
/// \f$L = \tilde l\f$: with \f$P' = \begin{pmatrix} A & B \\ B^* & C\end{pmatrix}\f$,
/// \f[ \phi P \phi^* = \begin{pmatrix} A + L B^* - B L + L C L^* & B + L C \\ (B + LC)^* &
///     C \end{pmatrix}, \quad L^* = -L. \f]
/// With \f$K = L B^*\f$ and \f$Q = L C\f$ the top left block is \f$A + K + K^* + L Q^*\f$
/// (\f$B L = -K^*\f$, \f$L C L^* = L Q^*\f$): every product with \f$L\f$ is a cross product
/// with \f$l\f$ of a column, and the symmetric blocks are filled from one triangle. A
/// rotation about a coordinate axis (detail::plane_rotation_axis()) rotates the blocks in
/// its plane only (detail::plane_rotate(), the same products less those with exact zeros
/// and ones), and an offset along a coordinate axis shifts by detail::shift_on_axis(),
/// unless \p fast_path is false. Writes \p out, which must not be \p P.
template <class S>
void transform_symmetric(const PhiT<S>& phi, const Mat6<S>& P, Mat6<S>& out,
                         bool fast_path = true) {
  const Mat3<S>& R = phi.R();
  const Vec3<S>& l = phi.l();
  Mat3<S> A, B, C, K, Q;
  const int axis = fast_path ? detail::plane_rotation_axis(R) : -1;
  if (axis == 0) {
    detail::plane_rotate_blocks<0>(R, P, A, B, C);
  } else if (axis == 1) {
    detail::plane_rotate_blocks<1>(R, P, A, B, C);
  } else if (axis == 2) {
    detail::plane_rotate_blocks<2>(R, P, A, B, C);
  } else {
    const Mat3<S> RA = R * P.template topLeftCorner<3, 3>();
    const Mat3<S> RC = R * P.template bottomRightCorner<3, 3>();
    B = R * P.template topRightCorner<3, 3>() * R.transpose();
    for (int j = 0; j < 3; ++j)
      for (int i = j; i < 3; ++i) {
        A(i, j) = RA.row(i).dot(R.row(j));
        C(i, j) = RC.row(i).dot(R.row(j));
      }
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < j; ++i) A(i, j) = A(j, i), C(i, j) = C(j, i);
  }
  if (fast_path && detail::with_plane_axis(detail::coordinate_offset(l), [&](auto I) {
        detail::shift_on_axis<decltype(I)::value>(l[I], A, B, C, out);
      }))
    return;
  for (int j = 0; j < 3; ++j) {
    K.col(j) = l.cross(B.row(j).transpose());  // K = L B^*
    Q.col(j) = l.cross(C.col(j));              // Q = L C
  }
  for (int j = 0; j < 3; ++j) {
    const Vec3<S> LQj = l.cross(Q.row(j).transpose());  // column j of L Q^*
    for (int i = j; i < 3; ++i) out(i, j) = A(i, j) + K(i, j) + K(j, i) + LQj[i];
  }
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < j; ++i) out(i, j) = out(j, i);
  const Mat3<S> BQ = B + Q;
  out.template topRightCorner<3, 3>() = BQ;
  out.template bottomLeftCorner<3, 3>() = BQ.transpose();
  out.template bottomRightCorner<3, 3>() = C;
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
  const int i = art.slot(k);
  Mat6<S>& P = art.P[i];
  if (k > 1)
    transform_symmetric(ws.phi[k - 2], art.P_plus[art.slot(k - 1)], P, m.fast_paths);
  else
    P.setZero();
  add_inertia(B.M, P);
  guard.step(k > 1 ? &ws.phi[k - 2] : nullptr, B.M);
  const int nv = B.hinge.nv();
  S d_min;
  if (nv == 1) {
    // P H*(k) as a column of P for a revolute or prismatic hinge about a coordinate axis
    // (+-e_i), else P s; then the rank-one P+ = P - G (P s)^*.
    const Vec6<S> s = one_dof_map(B.hinge);
    const int ax =
        m.fast_paths && B.hinge.type != HingeType::Helical ? detail::coordinate_axis(B.hinge) : -1;
    Vec6<S> Ps;
    S d;
    if (ax >= 0) {
      const int c = B.hinge.type == HingeType::Prismatic ? ax + 3 : ax;
      Ps = s[c] * P.col(c);
      d = s[c] * Ps[c];
    } else {
      Ps = B.hinge.type == HingeType::Revolute ? Vec6<S>(P.template leftCols<3>() * B.hinge.axis)
                                               : Vec6<S>(P * s);
      d = s.dot(Ps);
    }
    d_min = d;
    // Sized once (the model's constructor sizes them): no write to the size fields.
    if (art.D[i].rows() != 1 || art.D_inv[i].rows() != 1 || art.G[i].cols() != 1)
      art.D[i].resize(1, 1), art.D_inv[i].resize(1, 1), art.G[i].resize(6, 1);
    art.D[i](0, 0) = d;
    const S d_inv = S(1) / d;
    art.D_inv[i](0, 0) = d_inv;
    const Vec6<S> g = Ps * d_inv;
    art.G[i].col(0) = g;
    art.P_plus[i].noalias() = P - g * Ps.transpose();
  } else {
    const JointMap<S> Hs = B.hinge.H_star(th);
    const JointMap<S> PHs = P * Hs;
    art.D[i] = Hs.transpose() * PHs;
    d_min = detail::hinge_eigenvalues(art.D[i]).minCoeff();
    art.D_inv[i] = art.D[i].inverse();
    art.G[i] = PHs * art.D_inv[i];
    art.P_plus[i] = P - art.G[i] * PHs.transpose();
  }
  // |H*(k)|_F^2 times tr R(k) bounds lambda_max(H Q H*) from above (Q <= R).
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
