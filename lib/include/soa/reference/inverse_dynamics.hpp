/// \file
/// Reference Newton-Euler inverse dynamics (lesson 4; Jain 2011, chapter 4).
#pragma once

#include "soa/chain/inverse_dynamics.hpp"
#include "soa/reference/kinematics.hpp"
#include "soa/rigid_body.hpp"

namespace soa::reference {

/// The hinge forces \f$T\f$ that give the chain the accelerations \p beta_dot at the state
/// \p x, under gravity, the external forces \p f_ext (entry k - 1 on body k at \f$O_k\f$,
/// or empty) and the springs and dampers (lesson 4, sections 1, 5, 6 and 7). \p T has size
/// nv. Fast form: soa::inverse_dynamics().
template <class S>
void inverse_dynamics(const ModelT<S>& m, const StateT<S>& x, const VecX<S>& beta_dot,
                      const ExternalForces<S>& f_ext, WorkspaceT<S>& ws, VecX<S>& T) {
  kinematics(m, x, beta_dot, ws);
  ForceT<S> f_prev;  // f(0) = 0
  for (int k = 1; k <= m.n(); ++k) {
    const BodyT<S>& B = m.body(k);
    const S* theta = x.theta.data() + B.q_offset;
    // b(k) = [\tilde\omega J \omega;\ m\tilde\omega\tilde\omega p] - f_{ext}(k)   (lesson 2)
    ForceT<S> b = gyroscopic_force(B.M, ws.V[k - 1]);
    if (!f_ext.empty()) b -= f_ext[k - 1];
    // f(k) = \phi(k,k-1)\,f(k-1) + M(k)\,\alpha(k) + b(k)
    const ForceT<S> f_carried = k > 1 ? ws.phi[k - 2].apply(f_prev) : ForceT<S>();
    ws.f[k - 1] = f_carried + B.M * ws.alpha[k - 1] + b;
    f_prev = ws.f[k - 1];
    // T(k) = H(k)\,f(k) - \tau_s(k), \quad \tau_s = -k\,\delta(\theta) - c\,\beta
    S tau_s[6] = {0, 0, 0, 0, 0, 0};
    add_spring_force(B, theta, x.beta.data() + B.v_offset, tau_s);
    B.hinge.H_times(theta, ws.f[k - 1], T.data() + B.v_offset);
    for (int i = 0; i < B.hinge.nv(); ++i) T[B.v_offset + i] -= tau_s[i];
  }
}

}  // namespace soa::reference
