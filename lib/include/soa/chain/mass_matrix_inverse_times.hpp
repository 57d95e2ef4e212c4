/// \file
/// \f$\mathcal M^{-1}(\theta)\,T\f$ in O(N), without forming \f$\mathcal M\f$ (lessons 7-8).
#pragma once

#include <cmath>
#include <string>

#include "soa/chain/forward_dynamics.hpp"

namespace soa {

/// The fast form of soa::reference::mass_matrix_inverse_times().
/// \f$\beta = \mathcal M^{-1}(\theta)\,T\f$ by the innovations factorization \f$\mathcal
/// M^{-1} = [I - H\psi K]^* D^{-1} [I - H\psi K]\f$ (lesson 7), i.e. soa::forward_dynamics()
/// with every bias term dropped (no velocity, gravity, springs or external forces). Tip to
/// base, with the Riccati recursion (riccati_step()):
/// \f[ z(k) = \phi(k,k-1)\,z^+(k-1), \quad \epsilon(k) = T(k) - H(k)\,z(k), \quad
///     \nu(k) = D^{-1}(k)\,\epsilon(k), \quad z^+(k) = z(k) + G(k)\,\epsilon(k); \f]
/// base to tip, from \f$\alpha(n+1) = 0\f$:
/// \f[ \alpha^+(k) = \phi^*(k+1,k)\,\alpha(k+1), \quad \beta(k) = \nu(k) - G^*(k)\,\alpha^+(k),
///     \quad \alpha(k) = \alpha^+(k) + H^*(k)\,\beta(k). \f]
/// Only \p x.theta is read. Fills ws.phi and fd.art, fd.nu (not lean storage); \p out must
/// have size nv and not be \p T; nothing is allocated. A singular \f$D(k)\f$ throws as in
/// articulated_inertias().
template <class S>
void mass_matrix_inverse_times(const ModelT<S>& m, const StateT<S>& x, const VecX<S>& T,
                               WorkspaceT<S>& ws, ForwardDynamicsT<S>& fd, VecX<S>& out) {
  if (fd.is_lean()) throw Error("mass_matrix_inverse_times: needs full ForwardDynamicsT storage");
  update_phi(m, x.theta, ws);
  ArticulatedT<S>& art = fd.art;
  CompositeTraceT<S> guard;
  ForceT<S> z_plus;
  for (int k = 1; k <= m.n(); ++k) {
    const BodyT<S>& B = m.body(k);
    const S* th = x.theta.data() + B.q_offset;
    if (!std::isfinite(double(riccati_step(m, x, ws, k, art, guard))))
      throw Error("body '" + B.name + "': articulated inertia D(" + std::to_string(k) +
                  ") is not finite (check theta and the inertias)");
    const int nv = B.hinge.nv(), slot = art.slot(k);
    const ForceT<S> z = k > 1 ? ws.phi[k - 2].apply(z_plus) : ForceT<S>();
    S Hz[6];
    B.hinge.H_times(th, z, Hz);
    HingeVector<S> eps(nv);
    for (int i = 0; i < nv; ++i) eps[i] = T[B.v_offset + i] - Hz[i];
    fd.nu[k - 1] = art.D_inv[slot] * eps;
    z_plus = ForceT<S>(Vec6<S>(z.vector() + art.G[slot] * eps));
  }
  AccelerationT<S> alpha;
  for (int k = m.n(); k >= 1; --k) {
    const BodyT<S>& B = m.body(k);
    const int nv = B.hinge.nv();
    const AccelerationT<S> alpha_plus =
        k < m.n() ? ws.phi[k - 1].transpose_apply(alpha) : AccelerationT<S>();
    S* beta_k = out.data() + B.v_offset;
    for (int i = 0; i < nv; ++i)
      beta_k[i] = fd.nu[k - 1][i] - art.G[k - 1].col(i).dot(alpha_plus.vector());
    alpha = AccelerationT<S>(Vec6<S>(
        alpha_plus.vector() + B.hinge.H_star_times(x.theta.data() + B.q_offset, beta_k).vector()));
  }
}

}  // namespace soa
