/// \file
/// Composite rigid body inertias and the O(N^2) mass matrix (lesson 5).
#pragma once

#include <vector>

#include "soa/chain/inverse_dynamics.hpp"
#include "soa/chain/kinematics.hpp"
#include "soa/detail/plane.hpp"

namespace soa {

namespace detail {

/// composite_inertias() inline, for mass_matrix_inertial(); \p axes, when not null (n
/// entries), gets at k - 1 the coordinate axis \f$\phi(k+1,k)\f$ turns about
/// (detail::plane_rotation_axis()), or -1 (always -1 with the fast paths off).
template <class S>
EIGEN_ALWAYS_INLINE void composite_sweep(const ModelT<S>& m, const WorkspaceT<S>& ws,
                                         SpatialInertiaT<S>* R, int* axes) {
  const bool fast = m.fast_paths;
  const int n = m.n();
  int axis = -1;  // of phi(k,k-1)
  for (int k = 1; k <= n; ++k) {
    R[k - 1] =
        k == 1 ? m.body(1).M : detail::transform_about(ws.phi[k - 2], R[k - 2], axis) + m.body(k).M;
    axis = fast ? detail::plane_rotation_axis(ws.phi[k - 1].R()) : -1;
    if (axes) axes[k - 1] = axis;
  }
}

}  // namespace detail

/// The composite rigid body inertias by the forward Lyapunov recursion (lesson 5), tip to
/// base: \f[ R(k) = \phi(k,k-1)\, R(k-1)\, \phi^*(k,k-1) + M(k), \qquad R(0) = 0 , \f]
/// each the inertia, about \f$O_k\f$, of bodies 1..k welded together: a rigid body inertia,
/// so it is kept as \f$(m, mp, J)\f$. Operator form: \f$R = \mathcal{E}_\phi R
/// \mathcal{E}_\phi^* + M\f$. A \f$\phi(k,k-1)\f$ turning about a coordinate axis moves
/// \f$R(k-1)\f$ in its plane (soa::transform()'s fast path, the general one to an ulp)
/// unless Model::fast_paths is off. Needs update_phi(); \p R must have n entries.
template <class S>
void composite_inertias(const ModelT<S>& m, const WorkspaceT<S>& ws,
                        std::vector<SpatialInertiaT<S>>& R) {
  detail::composite_sweep(m, ws, R.data(), static_cast<int*>(nullptr));
}

/// The fast form of soa::reference::mass_matrix().
/// The mass matrix from the composite inertias (lesson 5), \f$O(N^2)\f$:
/// \f[ \mathcal{M}(k,k) = H(k) R(k) H^*(k), \qquad
///     \mathcal{M}(i,j) = H(i)\,\phi(i,j)\,R(j)\,H^*(j) = \mathcal{M}^*(j,i),\ i > j, \f]
/// from \f$\phi M \phi^* = R + \tilde\phi R + R\tilde\phi^*\f$. The force columns
/// \f$R(j)H^*(j)\f$ are carried to each inboard body by \f$\phi(i,i-1)\f$, never as a 6x6.
/// Needs update_phi(); \p R is workspace for the composite inertias (n entries).
template <class S>
void mass_matrix_crb(const ModelT<S>& m, const StateT<S>& x, const WorkspaceT<S>& ws,
                     std::vector<SpatialInertiaT<S>>& R, MatX<S>& Mass) {
  composite_inertias(m, ws, R);
  Mass.setZero(m.nv(), m.nv());
  for (int j = 1; j <= m.n(); ++j) {
    const BodyT<S>& Bj = m.body(j);
    const JointMap<S> Hs = Bj.hinge.H_star(x.theta.data() + Bj.q_offset);
    for (int c = 0; c < Hs.cols(); ++c) {
      const MomentumT<S> h = R[j - 1] * VelocityT<S>(Vec6<S>(Hs.col(c)));
      ForceT<S> F(h.vector());  // R(j) H*(j) e_c, a force at O_j
      const int col = Bj.v_offset + c;
      for (int i = j; i <= m.n(); ++i) {
        if (i > j) F = ws.phi[i - 2].apply(F);  // phi(i, i-1)
        const BodyT<S>& Bi = m.body(i);
        S T[6] = {};
        Bi.hinge.H_times(x.theta.data() + Bi.q_offset, F, T);
        for (int r = 0; r < Bi.hinge.nv(); ++r) {
          Mass(Bi.v_offset + r, col) = T[r];
          Mass(col, Bi.v_offset + r) = T[r];
        }
      }
    }
  }
}

/// The composite inertias as the dense block-diagonal operator \f$R = \mathrm{diag}(R(k))\f$
/// (6n x 6n, body k at rows \f$6(k-1)\f$), the solution of the forward Lyapunov equation
/// \f$R = \mathcal{E}_\phi R \mathcal{E}_\phi^* + M\f$ (lesson 5). Needs update_phi().
template <class S>
MatX<S> composite_inertia_operator(const ModelT<S>& m, const WorkspaceT<S>& ws) {
  std::vector<SpatialInertiaT<S>> R(std::size_t(m.n()));
  composite_inertias(m, ws, R);
  MatX<S> Rd = MatX<S>::Zero(6 * m.n(), 6 * m.n());
  for (int k = 1; k <= m.n(); ++k) Rd.block(6 * (k - 1), 6 * (k - 1), 6, 6) = R[k - 1].matrix();
  return Rd;
}

/// The fast form of soa::reference::inverse_dynamics().
/// Inverse dynamics through the composite bodies (lesson 5), O(N). With the relative
/// accelerations \f$z = H^*\dot\beta + a\f$ (so \f$\alpha = \phi^* z\f$) the decomposition
/// \f$\phi M\phi^* = R + \tilde\phi R + R\tilde\phi^*\f$ turns \f$f = \phi(M\phi^* z + b)\f$
/// into
/// \f[ f(k) = R(k)\,\alpha^+(k) + y(k), \qquad
///     y(k) = \phi(k,k-1)\, y(k-1) + R(k)\, z(k) + b(k), \quad y(0) = 0, \f]
/// with \f$\alpha^+(k) = \phi^*(k+1,k)\,\alpha(k+1)\f$ (\f$\alpha(n+1) = [0;-g]\f$) the
/// acceleration body k would have if hinge k were locked: the composite body 1..k rides on
/// body k+1, and each hinge j ≤ k adds the force its relative acceleration needs from the
/// composite body outboard of it. Then \f$T(k) = H(k) f(k)\f$ less the spring force, as
/// soa::inverse_dynamics. Fills ws.phi, V, a, alpha, f; \p R gets the composite inertias.
template <class S>
void inverse_dynamics_composite(const ModelT<S>& m, const StateT<S>& x, const VecX<S>& beta_dot,
                                const ExternalForces<S>& f_ext, WorkspaceT<S>& ws,
                                std::vector<SpatialInertiaT<S>>& R, VecX<S>& T) {
  update_phi(m, x.theta, ws);
  update_velocities(m, x, ws);
  const AccelerationT<S> alpha_base =
      m.has_gravity() ? gravity_base_acceleration(m) : AccelerationT<S>();
  update_accelerations(m, x, beta_dot.data(), alpha_base, ws);
  composite_inertias(m, ws, R);
  WorkspaceT<S>::size(ws.f, m);
  ForceT<S> y;
  for (int k = 1; k <= m.n(); ++k) {
    const BodyT<S>& B = m.body(k);
    const S* th = x.theta.data() + B.q_offset;
    const AccelerationT<S> z(
        (B.hinge.H_star_times(th, beta_dot.data() + B.v_offset).vector() + ws.a[k - 1].vector())
            .eval());
    const AccelerationT<S> alpha_plus =
        ws.phi[k - 1].transpose_apply(k < m.n() ? ws.alpha[k] : alpha_base);
    ForceT<S> b = gyroscopic_force(B.M, ws.V[k - 1]);
    if (!f_ext.empty()) b -= f_ext[k - 1];
    y = (k > 1 ? ws.phi[k - 2].apply(y) : ForceT<S>()) + R[k - 1] * z + b;
    const ForceT<S> f = R[k - 1] * alpha_plus + y;
    ws.f[k - 1] = f;
    S* Tk = T.data() + B.v_offset;
    B.hinge.H_times(th, f, Tk);
    if (B.stiffness != S(0) || B.damping != S(0)) {
      S tau[6] = {0, 0, 0, 0, 0, 0};
      add_spring_force(B, th, x.beta.data() + B.v_offset, tau);
      for (int i = 0; i < B.hinge.nv(); ++i) Tk[i] -= tau[i];
    }
  }
}

/// inverse_dynamics_composite() of an Eigen expression \p beta_dot: forwards to the VecX one.
template <class S, class D>
void inverse_dynamics_composite(const ModelT<S>& m, const StateT<S>& x,
                                const Eigen::MatrixBase<D>& beta_dot,
                                const ExternalForces<S>& f_ext, WorkspaceT<S>& ws,
                                std::vector<SpatialInertiaT<S>>& R, VecX<S>& T) {
  inverse_dynamics_composite(m, x, VecX<S>(beta_dot), f_ext, ws, R, T);
}

}  // namespace soa
