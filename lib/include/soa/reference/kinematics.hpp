/// \file
/// Reference serial-chain kinematics: \f$\phi\f$, \f$V\f$, \f$a\f$, \f$\alpha\f$, base to
/// tip (lesson 3; Jain 2011, chapter 3).
#pragma once

#include "soa/chain/kinematics.hpp"
#include "soa/reference/workspace.hpp"

namespace soa::reference {

/// \f$\phi(k+1,k)\f$ of every body (lesson 3, section 4).
template <class S>
void joint_transforms(const ModelT<S>& m, const VecX<S>& theta, WorkspaceT<S>& ws) {
  for (int k = m.n(); k >= 1; --k) {
    const BodyT<S>& B = m.body(k);
    // \phi(k+1,k) = {}^{O_{k+1}}T_{O_k^+}\; {}^{O_k^+}T_{O_k}(\theta(k))
    ws.phi[k - 1] = PhiT<S>(B.placement * B.hinge.transform(theta.data() + B.q_offset));
  }
}

/// \f$\phi(k+1,k)\f$, the velocities \f$V(k)\f$ and the Coriolis terms \f$a(k)\f$, base to
/// tip (lesson 3, sections 4, 6 and 7). Fast form: soa::update_phi(), then
/// soa::update_velocities().
template <class S>
void velocities(const ModelT<S>& m, const StateT<S>& x, WorkspaceT<S>& ws) {
  joint_transforms(m, x.theta, ws);
  VelocityT<S> V_next;  // V(n+1) = 0
  for (int k = m.n(); k >= 1; --k) {
    const BodyT<S>& B = m.body(k);
    const S* theta = x.theta.data() + B.q_offset;
    const S* beta = x.beta.data() + B.v_offset;
    // \Delta_V(k) = H^*(k)\,\beta(k)
    const VelocityT<S> dV = B.hinge.H_star_times(theta, beta);
    // V(k) = \phi^*(k+1,k)\,V(k+1) + H^*(k)\,\beta(k)
    ws.V[k - 1] = ws.phi[k - 1].transpose_apply(V_next) + dV;
    // a(k) = \tilde V(k)\,\Delta_V + \mathring H^*(k)\beta(k)
    //        + [0;\ \omega_k \times v_k - R^*(\omega_{k+1} \times v_{k+1})]
    ws.a[k - 1] = coriolis_term(ws.phi[k - 1], V_next, ws.V[k - 1], dV,
                                B.hinge.H_star_dot_times(theta, beta));
    V_next = ws.V[k - 1];
  }
}

/// velocities(), then the accelerations \f$\alpha(k)\f$ for the hinge accelerations
/// \p beta_dot, base to tip from gravity as the base acceleration (lesson 3, section 7;
/// lesson 4, section 5). Fast form: soa::update_accelerations().
template <class S>
void kinematics(const ModelT<S>& m, const StateT<S>& x, const VecX<S>& beta_dot,
                WorkspaceT<S>& ws) {
  velocities(m, x, ws);
  // \alpha(n+1) = [0;\ -g]
  AccelerationT<S> alpha_next = gravity_base_acceleration(m);
  for (int k = m.n(); k >= 1; --k) {
    const BodyT<S>& B = m.body(k);
    const AccelerationT<S> Hs_beta_dot(
        B.hinge.H_star_times(x.theta.data() + B.q_offset, beta_dot.data() + B.v_offset).vector());
    // \alpha(k) = \phi^*(k+1,k)\,\alpha(k+1) + H^*(k)\,\dot\beta(k) + a(k)
    ws.alpha[k - 1] = ws.phi[k - 1].transpose_apply(alpha_next) + Hs_beta_dot + ws.a[k - 1];
    alpha_next = ws.alpha[k - 1];
  }
}

}  // namespace soa::reference
