/// \file
/// Spatial operators as explicit dense matrices, for teaching and tests (lessons 3-4).
///
/// Built for small n only: a 6n x 6n matrix per operator. The O(N) recursions never form
/// any of them. Block k (1-based, tip first) of a stacked vector is rows 6(k-1)..6k-1.
#pragma once

#include <Eigen/Dense>

#include "soa/chain/kinematics.hpp"
#include "soa/rigid_body.hpp"

namespace soa {

/// The operators of a chain at one state (\ref conventions, lessons 3-4).
template <class S>
struct OperatorsT {
  MatX<S> E_phi;  ///< \f$\mathcal{E}_\phi\f$: \f$\phi(k+1,k)\f$ at block (k+1, k)
  MatX<S> phi;    ///< \f$\phi = (I - \mathcal{E}_\phi)^{-1}\f$, block lower triangular
  MatX<S> H;      ///< \f$H = \mathrm{diag}(H(k))\f$, nv x 6n
  MatX<S> M;      ///< \f$M = \mathrm{diag}(M(k))\f$
  VecX<S> a;      ///< stacked \f$a(k)\f$, with the base acceleration folded into \f$a(n)\f$
  VecX<S> b;      ///< stacked \f$b(k)\f$, gyroscopic terms less external forces

  /// The operators at state \p x (gravity and external forces as in inverse_dynamics()).
  static OperatorsT build(const ModelT<S>& m, const StateT<S>& x,
                          const std::vector<ForceT<S>>& f_ext = {});

  /// \f$V = \phi^* H^* \beta\f$.
  VecX<S> V(const VecX<S>& beta) const;
  /// \f$\alpha = \phi^*(H^*\dot\beta + a)\f$.
  VecX<S> alpha(const VecX<S>& beta_dot) const;
  /// \f$f = \phi(M\alpha + b)\f$.
  VecX<S> f(const VecX<S>& beta_dot) const;
  /// \f$T = H f\f$ (springs not included).
  VecX<S> T(const VecX<S>& beta_dot) const;
  /// The mass matrix \f$\mathcal{M} = H\phi M\phi^* H^*\f$ (Newton-Euler factorization).
  MatX<S> mass_matrix() const;
  /// \f$\mathcal{C} = H\phi(M\phi^* a + b)\f$.
  VecX<S> bias() const;
};

// The members are defined out of the class, not inline: the library compiles them once for
// each precision (soa/instantiations.hpp), and the programs, which declare them extern, do
// not compile them again.

template <class S>
OperatorsT<S> OperatorsT<S>::build(const ModelT<S>& m, const StateT<S>& x,
                                   const std::vector<ForceT<S>>& f_ext) {
  const int n = m.n(), N = 6 * n;
  WorkspaceT<S> ws(m);
  update_phi(m, x.theta, ws);
  update_velocities(m, x, ws);
  OperatorsT op;
  op.E_phi = MatX<S>::Zero(N, N);
  for (int k = 1; k < n; ++k) op.E_phi.block(6 * k, 6 * (k - 1), 6, 6) = ws.phi[k - 1].matrix();
  op.phi = (MatX<S>::Identity(N, N) - op.E_phi).inverse();
  op.H = MatX<S>::Zero(m.nv(), N);
  op.M = MatX<S>::Zero(N, N);
  op.a = VecX<S>::Zero(N);
  op.b = VecX<S>::Zero(N);
  for (int k = 1; k <= n; ++k) {
    const BodyT<S>& B = m.body(k);
    const int r = 6 * (k - 1);
    op.H.block(B.v_offset, r, B.hinge.nv(), 6) =
        B.hinge.H_star(x.theta.data() + B.q_offset).transpose();
    op.M.block(r, r, 6, 6) = B.M.matrix();
    op.a.segment(r, 6) = ws.a[k - 1].vector();
    ForceT<S> bk = gyroscopic_force(B.M, ws.V[k - 1]);
    if (!f_ext.empty()) bk -= f_ext[k - 1];
    op.b.segment(r, 6) = bk.vector();
  }
  if (n > 0 && m.has_gravity())  // phi*(n+1,n) alpha(n+1) joins a(n)
    op.a.segment(6 * (n - 1), 6) +=
        ws.phi[n - 1].transpose_apply(gravity_base_acceleration(m)).vector();
  return op;
}

template <class S>
VecX<S> OperatorsT<S>::V(const VecX<S>& beta) const {
  return phi.transpose() * (H.transpose() * beta);
}

template <class S>
VecX<S> OperatorsT<S>::alpha(const VecX<S>& beta_dot) const {
  return phi.transpose() * (H.transpose() * beta_dot + a);
}

template <class S>
VecX<S> OperatorsT<S>::f(const VecX<S>& beta_dot) const {
  return phi * (M * alpha(beta_dot) + b);
}

template <class S>
VecX<S> OperatorsT<S>::T(const VecX<S>& beta_dot) const {
  return H * f(beta_dot);
}

template <class S>
MatX<S> OperatorsT<S>::mass_matrix() const {
  const MatX<S> B = phi.transpose() * H.transpose();
  return B.transpose() * M * B;
}

template <class S>
VecX<S> OperatorsT<S>::bias() const {
  return H * (phi * (M * (phi.transpose() * a) + b));
}

using Operators = OperatorsT<double>;

}  // namespace soa
