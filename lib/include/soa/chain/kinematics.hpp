/// \file
/// Serial-chain kinematics: the O(N) scatter recursions, base to tip (lesson 3).
#pragma once

#include "soa/chain/workspace.hpp"
#include "soa/spatial_cross.hpp"

namespace soa {

/// \f$\phi(k+1,k) = {}^{O_{k+1}}T_{O_k^+}\; {}^{O_k^+}T_{O_k}(\theta(k))\f$ for every body.
template <class S>
void update_phi(const ModelT<S>& m, const VecX<S>& theta, WorkspaceT<S>& ws) {
  for (int k = m.n(); k >= 1; --k) {
    const BodyT<S>& B = m.body(k);
    ws.phi[k - 1] = PhiT<S>(B.placement * B.hinge.transform(theta.data() + B.q_offset));
  }
}

/// Poses by the scatter recursion (slides 25-27), base to tip:
/// \f${}^I T_{O_k} = {}^I T_{O_{k+1}}\; {}^{O_{k+1}}T_{O_k}\f$. Needs update_phi().
template <class S>
void update_poses(const ModelT<S>& m, WorkspaceT<S>& ws) {
  const int n = m.n();
  if (n == 0) return;
  ws.pose[n - 1] = ws.phi[n - 1].pose();
  for (int k = n - 1; k >= 1; --k) ws.pose[k - 1] = ws.pose[k] * ws.phi[k - 1].pose();
}

/// The Coriolis term of the acceleration recursion (lesson 3, derived there from slide 61):
/// with \f$\Delta_V = H^*(k)\beta(k)\f$ and \f$V(k) = [\omega_k; v_k]\f$,
/// \f[ a(k) = \tilde V(k)\,\Delta_V + \mathring H^*(k)\beta(k) +
///     \begin{pmatrix} 0 \\ \omega_k \times v_k - R^*(\omega_{k+1} \times v_{k+1})
///     \end{pmatrix}, \f]
/// \f$R = {}^{k+1}R_k\f$; equal to the coordinate-free
/// \f$[\omega_{k+1}\times\Delta_\omega;\ \omega_k\times\Delta_v + \omega_{k+1}\times
/// (v(k) - v(k+1))] + \mathring H^*\beta\f$, where \f$\omega_k\times\Delta_v =
/// \omega_{k+1}\times\Delta_v + \Delta_\omega\times\Delta_v\f$ and the last term is non-zero
/// only for free hinges (\f$\mathring H^*\f$ is the rate seen from \f$O_k\f$).
template <class S>
AccelerationT<S> coriolis_term(const PhiT<S>& phi, const VelocityT<S>& V_parent,
                               const VelocityT<S>& V, const VelocityT<S>& dV,
                               const AccelerationT<S>& Hdot_beta) {
  const Vec3<S> w = V.angular(), v = V.linear();
  const Vec3<S> wp = V_parent.angular(), vp = V_parent.linear();
  const Vec3<S> wpvp = phi.R().transpose() * wp.cross(vp);
  return cross(V, dV) + Hdot_beta + AccelerationT<S>(Vec3<S>::Zero(), w.cross(v) - wpvp);
}

/// Velocities \f$V(k) = \phi^*(k+1,k)\,V(k+1) + H^*(k)\beta(k)\f$ and Coriolis terms
/// \f$a(k)\f$, base to tip (\f$V(n+1) = 0\f$). Needs update_phi(). At rest (\f$\beta = 0\f$)
/// every \f$V\f$ and \f$a\f$ is zero and nothing else is computed.
template <class S>
void update_velocities(const ModelT<S>& m, const StateT<S>& x, WorkspaceT<S>& ws) {
  const bool at_rest = x.beta.isZero(0);
  VelocityT<S> V_parent;
  for (int k = m.n(); k >= 1; --k) {
    if (at_rest) {
      ws.V[k - 1] = VelocityT<S>();
      ws.a[k - 1] = AccelerationT<S>();
      continue;
    }
    const BodyT<S>& B = m.body(k);
    const S* th = x.theta.data() + B.q_offset;
    const S* be = x.beta.data() + B.v_offset;
    const VelocityT<S> dV = B.hinge.H_star_times(th, be);
    const PhiT<S>& phi = ws.phi[k - 1];
    ws.V[k - 1] = phi.transpose_apply(V_parent) + dV;
    ws.a[k - 1] = coriolis_term(phi, V_parent, ws.V[k - 1], dV, B.hinge.H_star_dot_times(th, be));
    V_parent = ws.V[k - 1];
  }
}

/// Accelerations \f$\alpha(k) = \phi^*(k+1,k)\,\alpha(k+1) + H^*(k)\dot\beta(k) + a(k)\f$,
/// base to tip, from the base acceleration \f$\alpha(n+1) = [0; -g]\f$ (gravity, lesson 4)
/// given in inertial coordinates. \p beta_dot may be null for \f$\dot\beta = 0\f$.
/// Needs update_velocities().
template <class S>
void update_accelerations(const ModelT<S>& m, const StateT<S>& x, const S* beta_dot,
                          const AccelerationT<S>& alpha_base, WorkspaceT<S>& ws) {
  AccelerationT<S> alpha_parent = alpha_base;
  for (int k = m.n(); k >= 1; --k) {
    const BodyT<S>& B = m.body(k);
    AccelerationT<S> alpha = ws.phi[k - 1].transpose_apply(alpha_parent) + ws.a[k - 1];
    if (beta_dot)
      alpha += AccelerationT<S>(
          B.hinge.H_star_times(x.theta.data() + B.q_offset, beta_dot + B.v_offset).vector());
    ws.alpha[k - 1] = alpha;
    alpha_parent = alpha;
  }
}

/// The base acceleration that stands for gravity: \f$\alpha(n+1) = [0; -g]\f$ (lesson 4).
template <class S>
AccelerationT<S> gravity_base_acceleration(const ModelT<S>& m) {
  return AccelerationT<S>(Vec3<S>::Zero(), -m.gravity);
}

}  // namespace soa
