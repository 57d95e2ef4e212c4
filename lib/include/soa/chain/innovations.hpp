/// \file
/// The innovations operators of a chain as explicit dense matrices, for teaching and tests
/// (lesson 7): \f$G\f$, \f$K = \mathcal E_\phi G\f$, \f$\bar\tau\f$,
/// \f$\mathcal E_\psi = \mathcal E_\phi\bar\tau\f$, \f$\psi = (I - \mathcal E_\psi)^{-1}\f$,
/// \f$D\f$, and the factors of the innovations factorization of the mass matrix.
///
/// Built for small n only (6n x 6n matrices), on top of OperatorsT (lessons 3-4) and the
/// Riccati recursion articulated_inertias() (lesson 6). The O(N) and O(N^2) algorithms
/// (forward_dynamics(), mass_matrix_inverse()) never form any of them.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "soa/chain/articulated.hpp"
#include "soa/chain/operators.hpp"

namespace soa {

/// The operators of the innovations factorization at one state (\ref conventions, lesson 7).
/// Stacked tip first like OperatorsT: block k (1-based) of a spatial stack is rows
/// 6(k-1)..6k-1, of a hinge stack rows `v_offset(k)`..`v_offset(k) + n_k - 1`.
template <class S>
struct InnovationsOperatorsT {
  OperatorsT<S> op;  ///< \f$\mathcal E_\phi\f$, \f$\phi\f$, \f$H\f$, \f$M\f$ (and \f$a\f$, \f$b\f$)
  MatX<S> P;         ///< \f$P = \mathrm{diag}(P(k))\f$, 6n x 6n
  MatX<S> P_plus;    ///< \f$P^+ = \mathrm{diag}(P^+(k))\f$, 6n x 6n
  MatX<S> G;         ///< \f$G = \mathrm{diag}(G(k))\f$, 6n x nv (stacked)
  MatX<S> K;         ///< \f$K = \mathcal E_\phi G\f$: \f$\phi(k+1,k) G(k)\f$ at block (k+1, k)
  MatX<S> tau_bar;   ///< \f$\bar\tau = I - G H\f$, block diagonal, 6n x 6n
  MatX<S> E_psi;     ///< \f$\mathcal E_\psi = \mathcal E_\phi\bar\tau\f$
  MatX<S> psi;       ///< \f$\psi = (I - \mathcal E_\psi)^{-1}\f$, block lower triangular
  MatX<S> D;         ///< \f$D = \mathrm{diag}(D(k))\f$, nv x nv
  MatX<S> D_inv;     ///< \f$D^{-1} = \mathrm{diag}(D^{-1}(k))\f$, nv x nv

  /// The operators at state \p x (the Riccati recursion of lesson 6, then the stacks). A
  /// singular \f$D(k)\f$ throws soa::Error as in articulated_inertias().
  static InnovationsOperatorsT build(const ModelT<S>& m, const StateT<S>& x);

  /// The innovations factor \f$[I + H\phi K]\f$ (nv x nv, block lower triangular with
  /// identity diagonal).
  MatX<S> factor() const;
  /// Its inverse by the identity \f$[I + H\phi K]^{-1} = I - H\psi K\f$.
  MatX<S> factor_inverse() const;
  /// The mass matrix from the innovations factorization,
  /// \f$\mathcal M = [I + H\phi K]\, D\, [I + H\phi K]^*\f$.
  MatX<S> mass_matrix() const;
  /// Its inverse, \f$\mathcal M^{-1} = [I - H\psi K]^*\, D^{-1}\, [I - H\psi K]\f$.
  MatX<S> mass_matrix_inverse() const;
  /// \f$\Omega = \psi^* H^* D^{-1} H \psi\f$ (6n x 6n, lesson 7, section 6), which equals
  /// \f$\phi^* H^* \mathcal M^{-1} H \phi\f$.
  MatX<S> Omega() const;
  /// \f$\Upsilon = \mathrm{diag}(\Upsilon(k))\f$: the diagonal 6x6 blocks of Omega(), so
  /// that \f$\Omega = \Upsilon + \tilde\psi^*\Upsilon + \Upsilon\tilde\psi\f$ (lesson 7,
  /// section 6).
  MatX<S> Upsilon() const;
  /// The innovations coordinates \f$\eta = [I + H\phi K]^*\beta\f$ (lesson 7, section 9),
  /// with \f$\tfrac12\beta^*\mathcal M\beta = \tfrac12\eta^* D\eta\f$.
  VecX<S> eta(const VecX<S>& beta) const;
};

// Defined out of the class, not inline, as OperatorsT's members are (soa/chain/operators.hpp).

template <class S>
InnovationsOperatorsT<S> InnovationsOperatorsT<S>::build(const ModelT<S>& m, const StateT<S>& x) {
  const int n = m.n(), N = 6 * n, nv = m.nv();
  InnovationsOperatorsT io;
  io.op = OperatorsT<S>::build(m, x);
  WorkspaceT<S> ws(m);
  update_phi(m, x.theta, ws);
  ArticulatedT<S> art(m);
  articulated_inertias(m, x, ws, art);
  io.P = MatX<S>::Zero(N, N);
  io.P_plus = MatX<S>::Zero(N, N);
  io.G = MatX<S>::Zero(N, nv);
  io.D = MatX<S>::Zero(nv, nv);
  io.D_inv = MatX<S>::Zero(nv, nv);
  for (int k = 1; k <= n; ++k) {
    const BodyT<S>& B = m.body(k);
    const int r = 6 * (k - 1), c = B.v_offset, nk = B.hinge.nv();
    io.P.block(r, r, 6, 6) = art.P[k - 1];
    io.P_plus.block(r, r, 6, 6) = art.P_plus[k - 1];
    io.G.block(r, c, 6, nk) = art.G[k - 1];
    io.D.block(c, c, nk, nk) = art.D[k - 1];
    io.D_inv.block(c, c, nk, nk) = art.D_inv[k - 1];
  }
  const MatX<S> I = MatX<S>::Identity(N, N);
  io.K = io.op.E_phi * io.G;
  io.tau_bar = I - io.G * io.op.H;
  io.E_psi = io.op.E_phi * io.tau_bar;
  // psi by forward substitution on the unit lower triangular I - E_psi.
  io.psi = (I - io.E_psi).template triangularView<Eigen::UnitLower>().solve(I);
  return io;
}

template <class S>
MatX<S> InnovationsOperatorsT<S>::factor() const {
  return MatX<S>::Identity(op.H.rows(), op.H.rows()) + op.H * op.phi * K;
}

template <class S>
MatX<S> InnovationsOperatorsT<S>::factor_inverse() const {
  return MatX<S>::Identity(op.H.rows(), op.H.rows()) - op.H * psi * K;
}

template <class S>
MatX<S> InnovationsOperatorsT<S>::mass_matrix() const {
  const MatX<S> L = factor();
  return L * D * L.transpose();
}

template <class S>
MatX<S> InnovationsOperatorsT<S>::mass_matrix_inverse() const {
  const MatX<S> Li = factor_inverse();
  return Li.transpose() * D_inv * Li;
}

template <class S>
MatX<S> InnovationsOperatorsT<S>::Omega() const {
  return psi.transpose() * op.H.transpose() * D_inv * op.H * psi;
}

template <class S>
MatX<S> InnovationsOperatorsT<S>::Upsilon() const {
  const MatX<S> W = Omega();
  MatX<S> U = MatX<S>::Zero(W.rows(), W.cols());
  for (Eigen::Index r = 0; r < W.rows(); r += 6) U.block(r, r, 6, 6) = W.block(r, r, 6, 6);
  return U;
}

template <class S>
VecX<S> InnovationsOperatorsT<S>::eta(const VecX<S>& beta) const {
  return factor().transpose() * beta;
}

using InnovationsOperators = InnovationsOperatorsT<double>;

}  // namespace soa
