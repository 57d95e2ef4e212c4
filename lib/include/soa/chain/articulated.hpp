/// \file
/// Articulated body inertias by the Riccati recursion (lesson 6).
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cstdio>
#include <string>
#include <vector>

#include "soa/chain/composite.hpp"

namespace soa {

/// \f$n_k \times n_k\f$ matrices of one hinge (at most 6 x 6, no heap).
template <class S>
using HingeMatrix = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic, 0, 6, 6>;

/// \f$\phi(x,y)\, P\, \phi^*(x,y)\f$ for a symmetric 6x6 \f$P\f$ (an articulated inertia),
/// from \f$(R, l)\f$ without the 6x6 \f$\phi\f$: rotate the blocks, then shift by
/// \f$L = \tilde l\f$: with \f$P' = \begin{pmatrix} A & B \\ B^* & C\end{pmatrix}\f$,
/// \f[ \phi P \phi^* = \begin{pmatrix} A + L B^* - B L + L C L^* & B + L C \\ (B + LC)^* &
///     C \end{pmatrix}, \quad L^* = -L. \f]
template <class S>
Mat6<S> transform_symmetric(const PhiT<S>& phi, const Mat6<S>& P) {
  const Mat3<S>& R = phi.R();
  const Mat3<S> A = R * P.template topLeftCorner<3, 3>() * R.transpose();
  const Mat3<S> B = R * P.template topRightCorner<3, 3>() * R.transpose();
  const Mat3<S> C = R * P.template bottomRightCorner<3, 3>() * R.transpose();
  const Mat3<S> L = tilde(phi.l());
  const Mat3<S> BLC = B + L * C;
  Mat6<S> out;
  out.template topLeftCorner<3, 3>() = A + L * B.transpose() - B * L - L * C * L;
  out.template topRightCorner<3, 3>() = BLC;
  out.template bottomLeftCorner<3, 3>() = BLC.transpose();
  out.template bottomRightCorner<3, 3>() = C;
  return out;
}

/// The smallest ratio \f$\lambda_{\min}(D(k)) / \lambda_{\max}(H(k) R(k) H^*(k))\f$ accepted
/// before \f$D(k)\f$ counts as singular: \f$10^3\,\varepsilon\f$ (2.2e-13 in double). The
/// ratio is the fraction of the locked composite inertia (lesson 5) that the hinge still
/// feels through the free hinges outboard of it (\f$0 < D \le H R H^*\f$); below the
/// threshold \f$D^{-1}\f$ carries no correct digit.
template <class S>
S singular_D_threshold() {
  return S(1000) * eps<S>();
}

/// Per-body results of the Riccati recursion; sized once for a model.
template <class S>
struct ArticulatedT {
  explicit ArticulatedT(const ModelT<S>& m)
      : P(m.n()), P_plus(m.n()), D(m.n()), G(m.n()), R(m.n()) {}
  std::vector<Mat6<S>> P;             ///< \f$P(k)\f$
  std::vector<Mat6<S>> P_plus;        ///< \f$P^+(k) = \bar\tau(k) P(k)\f$
  std::vector<HingeMatrix<S>> D;      ///< \f$D(k) = H(k) P(k) H^*(k)\f$
  std::vector<JointMap<S>> G;         ///< \f$G(k) = P(k) H^*(k) D^{-1}(k)\f$
  std::vector<SpatialInertiaT<S>> R;  ///< composite inertias, for the singularity ratio
  /// \f$\bar\tau(k) = I - G(k) H(k)\f$ (a projection), formed on request.
  Mat6<S> tau_bar(const ModelT<S>& m, const VecX<S>& theta, int k) const {
    const BodyT<S>& B = m.body(k);
    return Mat6<S>::Identity() - G[k - 1] * B.hinge.H_star(theta.data() + B.q_offset).transpose();
  }
};
using Articulated = ArticulatedT<double>;

/// The articulated body inertias by the Riccati recursion (lesson 6), tip to base:
/// \f[ P(k) = \phi(k,k-1)\, P^+(k-1)\, \phi^*(k,k-1) + M(k), \quad D(k) = H(k)P(k)H^*(k),
/// \quad G(k) = P(k)H^*(k)D^{-1}(k), \quad P^+(k) = P(k) - G(k) D(k) G^*(k), \f]
/// the last being \f$\bar\tau(k) P(k)\f$ written symmetrically. A hinge whose \f$D(k)\f$ is
/// singular or numerically singular (a massless tip, an inertia that gives the axis nothing
/// to move) stops the recursion with soa::Error naming the body and the ratio found (see
/// singular_D_threshold()). Needs update_phi().
template <class S>
void articulated_inertias(const ModelT<S>& m, const StateT<S>& x, const WorkspaceT<S>& ws,
                          ArticulatedT<S>& out) {
  composite_inertias(m, ws, out.R);
  for (int k = 1; k <= m.n(); ++k) {
    const BodyT<S>& B = m.body(k);
    Mat6<S> P = B.M.matrix();
    if (k > 1) P += transform_symmetric(ws.phi[k - 2], out.P_plus[k - 2]);
    const JointMap<S> Hs = B.hinge.H_star(x.theta.data() + B.q_offset);
    const JointMap<S> PHs = P * Hs;
    const HingeMatrix<S> D = Hs.transpose() * PHs;
    const HingeMatrix<S> DR = Hs.transpose() * out.R[k - 1].matrix() * Hs;
    const S d_min = Eigen::SelfAdjointEigenSolver<HingeMatrix<S>>(D, Eigen::EigenvaluesOnly)
                        .eigenvalues()
                        .minCoeff();
    const S r_max = Eigen::SelfAdjointEigenSolver<HingeMatrix<S>>(DR, Eigen::EigenvaluesOnly)
                        .eigenvalues()
                        .maxCoeff();
    const S ratio = r_max > S(0) ? d_min / r_max : S(0);
    if (!(ratio > singular_D_threshold<S>())) {
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    "': articulated inertia D(%d) singular: lambda_min(D)/lambda_max(H R H*) = "
                    "%.3g, below the threshold %.3g",
                    k, double(ratio), double(singular_D_threshold<S>()));
      throw Error("body '" + B.name + buf);
    }
    const JointMap<S> G = PHs * D.inverse();
    out.P[k - 1] = P;
    out.D[k - 1] = D;
    out.G[k - 1] = G;
    out.P_plus[k - 1] = P - G * PHs.transpose();
  }
}

}  // namespace soa
