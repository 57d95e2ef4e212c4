/// \file
/// The inter-body forces split by the composite inertias (lesson 6, section 8; lesson 5):
/// \f$f(k) = R(k)\,\alpha^+(k) + y(k)\f$, with \f$\alpha^+\f$ and the bias \f$y\f$.
#pragma once

#include <vector>

#include "soa/chain/composite.hpp"

namespace soa {

/// \f$\alpha^+(k) = \phi^*(k+1,k)\,\alpha(k+1)\f$, \f$\alpha(n+1) = [0; -g]\f$ (lesson 6,
/// sections 2 and 8; Jain 2011, chapter 6): the acceleration body k would have were hinge k
/// locked, \f$\alpha(k) = \alpha^+(k) + H^*(k)\dot\beta(k) + a(k)\f$. Needs ws.phi and
/// ws.alpha (from soa::inverse_dynamics() or soa::forward_dynamics()); \p out has n entries.
template <class S>
void alpha_plus(const ModelT<S>& m, const WorkspaceT<S>& ws, std::vector<AccelerationT<S>>& out) {
  const AccelerationT<S> base = m.has_gravity() ? gravity_base_acceleration(m) : AccelerationT<S>();
  for (int k = 1; k <= m.n(); ++k)
    out[k - 1] = ws.phi[k - 1].transpose_apply(k < m.n() ? ws.alpha[k] : base);
}

/// The composite-body bias of lesson 6, section 8, tip to base:
/// \f[ y(k) = \phi(k,k-1)\,y(k-1) + R(k)\,\bigl(\alpha(k) - \alpha^+(k)\bigr) + b(k),
///     \qquad y(0) = 0, \f]
/// the operator form \f$y = \phi(R\,\delta + b)\f$ with \f$\delta = \alpha - \alpha^+ =
/// H^*\dot\beta + a\f$, so that \f$f = R\,\alpha^+ + y\f$ (from \f$\phi M\phi^* = R +
/// \tilde\phi R + R\tilde\phi^*\f$). \f$b(k)\f$ is the gyroscopic force less the external one
/// (\p f_ext, empty for none). Needs ws.phi, ws.V and ws.alpha (from soa::inverse_dynamics()
/// or soa::forward_dynamics()), \p R from soa::composite_inertias() and \p alpha_p from
/// alpha_plus(); \p y has n entries.
template <class S>
void composite_bias(const ModelT<S>& m, const WorkspaceT<S>& ws,
                    const std::vector<SpatialInertiaT<S>>& R,
                    const std::vector<AccelerationT<S>>& alpha_p, const ExternalForces<S>& f_ext,
                    std::vector<ForceT<S>>& y) {
  for (int k = 1; k <= m.n(); ++k) {
    ForceT<S> yk = gyroscopic_force(m.body(k).M, ws.V[k - 1]);
    if (!f_ext.empty()) yk -= f_ext[k - 1];
    yk += R[k - 1] * (ws.alpha[k - 1] - alpha_p[k - 1]);
    if (k > 1) yk += ws.phi[k - 2].apply(y[k - 2]);
    y[k - 1] = yk;
  }
}

}  // namespace soa
