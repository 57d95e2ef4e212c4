/// \file
/// The reference \f$\mathcal M^{-1}\,T\f$ in O(N) (lessons 7 and 8; Jain 2011, chapter 7).
#pragma once

#include "soa/reference/forward_dynamics.hpp"

namespace soa::reference {

/// \f$\mathcal M^{-1}\,T\f$ from the innovations factorization \f$\mathcal M^{-1} =
/// [I - H\psi K]^* D^{-1} [I - H\psi K]\f$ (lesson 7, section 4): the sweeps of the
/// articulated body algorithm without velocity, gravity, springs or external forces
/// (lesson 8, section 4). Needs joint_transforms() and articulated_inertias(); \p out has
/// size nv.
template <class S>
void articulated_solve(const ModelT<S>& m, const StateT<S>& x, const VecX<S>& T, WorkspaceT<S>& ws,
                       VecX<S>& out) {
  for (int k = 1; k <= m.n(); ++k) {  // tip to base
    const BodyT<S>& B = m.body(k);
    const int nk = B.hinge.nv();
    // z(k) = \phi(k,k-1)\,z^+(k-1), \quad z^+(0) = 0
    ws.z[k - 1] = k > 1 ? ws.phi[k - 2].apply(ws.z_plus[k - 2]) : ForceT<S>();
    // \epsilon(k) = T(k) - H(k)\,z(k)
    S Hz[6];
    B.hinge.H_times(x.theta.data() + B.q_offset, ws.z[k - 1], Hz);
    for (int i = 0; i < nk; ++i) ws.epsilon[k - 1][i] = T[B.v_offset + i] - Hz[i];
    // \nu(k) = D^{-1}(k)\,\epsilon(k), \quad z^+(k) = z(k) + G(k)\,\epsilon(k)
    ws.nu[k - 1] = ws.D_inv[k - 1] * ws.epsilon[k - 1];
    ws.z_plus[k - 1] = ws.z[k - 1] + ForceT<S>(Vec6<S>(ws.G[k - 1] * ws.epsilon[k - 1]));
  }
  // \alpha(n+1) = 0, \ a(k) = 0; \quad (\mathcal M^{-1} T)(k) = \nu(k) - G^*(k)\,\alpha^+(k)
  hinge_accelerations(m, x, AccelerationT<S>(), ws.a_rest, ws, out);
}

/// \f$\mathcal M^{-1}(\theta)\,T\f$ in O(N): joint_transforms(), articulated_inertias(),
/// articulated_solve(). Only \p x.theta is read. Fast form: soa::mass_matrix_inverse_times().
template <class S>
void mass_matrix_inverse_times(const ModelT<S>& m, const StateT<S>& x, const VecX<S>& T,
                               WorkspaceT<S>& ws, VecX<S>& out) {
  joint_transforms(m, x.theta, ws);
  articulated_inertias(m, x, ws);
  articulated_solve(m, x, T, ws, out);
}

}  // namespace soa::reference
