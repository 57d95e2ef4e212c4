/// \file
/// The reference articulated body forward dynamics (lesson 8; Jain 2011).
#pragma once

#include "soa/chain/inverse_dynamics.hpp"
#include "soa/reference/articulated.hpp"
#include "soa/rigid_body.hpp"

namespace soa::reference {

/// Sweep 3 of the articulated body algorithm, base to tip from \p alpha_base (lesson 8,
/// section 2): \f$\dot\beta(k)\f$ into \p beta_dot, \f$\alpha^+(k)\f$ and \f$\alpha(k)\f$
/// into \p ws, from \f$\nu(k)\f$, \f$G(k)\f$ and the Coriolis terms \p a (entry k - 1 is
/// \f$a(k)\f$: ws.a for the forward dynamics, ws.a_rest for \f$\mathcal M^{-1} T\f$,
/// lesson 8, section 4).
template <class S>
void hinge_accelerations(const ModelT<S>& m, const StateT<S>& x, const AccelerationT<S>& alpha_base,
                         const std::vector<AccelerationT<S>>& a, WorkspaceT<S>& ws,
                         VecX<S>& beta_dot) {
  AccelerationT<S> alpha_next = alpha_base;
  for (int k = m.n(); k >= 1; --k) {
    const BodyT<S>& B = m.body(k);
    // \alpha^+(k) = \phi^*(k+1,k)\,\alpha(k+1)
    ws.alpha_plus[k - 1] = ws.phi[k - 1].transpose_apply(alpha_next);
    // \dot\beta(k) = \nu(k) - G^*(k)\,\alpha^+(k)
    beta_dot.segment(B.v_offset, B.hinge.nv()) =
        ws.nu[k - 1] - ws.G[k - 1].transpose() * ws.alpha_plus[k - 1].vector();
    // \alpha(k) = \alpha^+(k) + H^*(k)\,\dot\beta(k) + a(k)
    const AccelerationT<S> Hs_beta_dot(
        B.hinge.H_star_times(x.theta.data() + B.q_offset, beta_dot.data() + B.v_offset).vector());
    ws.alpha[k - 1] = ws.alpha_plus[k - 1] + Hs_beta_dot + a[k - 1];
    alpha_next = ws.alpha[k - 1];
  }
}

/// The hinge accelerations \f$\dot\beta = \mathcal M^{-1}(T - \mathcal C)\f$ under the hinge
/// forces \p T, gravity, the external forces \p f_ext (entry k - 1 on body k at \f$O_k\f$,
/// or empty) and the springs and dampers, in O(N) by the articulated body algorithm
/// (lesson 6, section 2; lesson 8, sections 2 and 5). \p beta_dot has size nv.
/// Fast form: soa::forward_dynamics().
template <class S>
void forward_dynamics(const ModelT<S>& m, const StateT<S>& x, const VecX<S>& T,
                      const ExternalForces<S>& f_ext, WorkspaceT<S>& ws, VecX<S>& beta_dot) {
  velocities(m, x, ws);
  articulated_inertias(m, x, ws);
  for (int k = 1; k <= m.n(); ++k) {  // tip to base
    const BodyT<S>& B = m.body(k);
    const S* theta = x.theta.data() + B.q_offset;
    const int nk = B.hinge.nv();
    // b(k) = [\tilde\omega J \omega;\ m\tilde\omega\tilde\omega p] - f_{ext}(k)   (lesson 2)
    ForceT<S> b = gyroscopic_force(B.M, ws.V[k - 1]);
    if (!f_ext.empty()) b -= f_ext[k - 1];
    // z(k) = \phi(k,k-1)\,z^+(k-1) + P(k)\,a(k) + b(k), \quad z^+(0) = 0
    const ForceT<S> z_carried = k > 1 ? ws.phi[k - 2].apply(ws.z_plus[k - 2]) : ForceT<S>();
    ws.z[k - 1] = z_carried + ForceT<S>(Vec6<S>(ws.P[k - 1] * ws.a[k - 1].vector())) + b;
    // \epsilon(k) = T(k) + \tau_s(k) - H(k)\,z(k), \quad \tau_s = -k\,\delta(\theta) - c\,\beta
    S tau_s[6] = {0, 0, 0, 0, 0, 0}, Hz[6];
    add_spring_force(B, theta, x.beta.data() + B.v_offset, tau_s);
    B.hinge.H_times(theta, ws.z[k - 1], Hz);
    for (int i = 0; i < nk; ++i) ws.epsilon[k - 1][i] = T[B.v_offset + i] + tau_s[i] - Hz[i];
    // \nu(k) = D^{-1}(k)\,\epsilon(k)
    ws.nu[k - 1] = ws.D_inv[k - 1] * ws.epsilon[k - 1];
    // z^+(k) = z(k) + G(k)\,\epsilon(k)
    ws.z_plus[k - 1] = ws.z[k - 1] + ForceT<S>(Vec6<S>(ws.G[k - 1] * ws.epsilon[k - 1]));
  }
  // \alpha(n+1) = [0;\ -g]
  hinge_accelerations(m, x, gravity_base_acceleration(m), ws.a, ws, beta_dot);
}

}  // namespace soa::reference
