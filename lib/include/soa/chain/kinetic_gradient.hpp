/// \file
/// The derivatives of the kinetic energy, \f$p = \partial T/\partial\beta = \mathcal
/// M(\theta)\beta\f$ and \f$\partial T/\partial\theta\f$, in O(N) from the composite momenta
/// (the canonical equations of the variational integrator, \ref simulation_methods).
#pragma once

#include <string>

#include "soa/chain/kinematics.hpp"

namespace soa {

/// True for the hinges whose \f$\theta(k)\f$ is a vector that adds (\f$n_q = n_v\f$,
/// \f$\dot\theta = \beta\f$): revolute, prismatic, helical, universal.
inline bool hinge_coordinates_add(HingeType t) {
  return t == HingeType::Revolute || t == HingeType::Prismatic || t == HingeType::Helical ||
         t == HingeType::Universal;
}

/// The gradients of \f$T(\theta,\beta) = \tfrac12\sum_k V^*(k)M(k)V(k)\f$, tip to base from
/// the composite momenta \f$h(k)\f$ (the momentum of bodies 1..k about \f$O_k\f$, in
/// \f$O_k\f$ coordinates):
/// \f[ h(k) = \phi(k,k-1)\,h(k-1) + M(k)\,V(k), \qquad p(k) = H(k)\,h(k), \qquad
///     \frac{\partial T}{\partial\theta(k)} = -H(k)\,\bar V^+(k)\,h(k) +
///     \Big(\frac{\partial (H^*(k)\beta(k))}{\partial\theta(k)}\Big)^{\!*} h(k), \f]
/// with \f$V^+(k) = \phi^*(k+1,k)V(k+1) = V(k) - H^*(k)\beta(k)\f$ and \f$\bar X = -\tilde
/// X^*\f$ (soa::cross_bar()). Derivation: \f$p = \mathcal M\beta = H\phi M\phi^*H^*\beta =
/// H\phi M V\f$ and \f$(\phi M V)(k) = h(k)\f$. Changing \f$\theta(k)\f$ moves only
/// \f$\phi(k+1,k)\f$ and \f$H^*(k)\f$; the joint transform turns as \f$T(\theta + \delta e_i)
/// = T(\theta)\exp(\delta\,\hat s_i)\f$ with \f$s_i\f$ column i of \f$H^*(k)\f$ (as
/// \f$\beta = \dot\theta\f$), so \f$\phi^*(k+1,k) \to (I - \delta\tilde s_i)\,\phi^*(k+1,k)\f$
/// and \f$\partial V(k)/\partial\theta_i = \tilde V^+(k)\, s_i + \partial_i(H^*\beta)\f$;
/// the outboard velocities follow rigidly, \f$\partial V(j) = \phi^*(k,j)\,\partial V(k)\f$ for
/// \f$j < k\f$, whence \f$\partial T/\partial\theta_i = \sum_{j \le k} (\phi(k,j)M(j)V(j))^*
/// \partial V(k) = h^*(k)\,\partial V(k)/\partial\theta_i\f$. For a one-degree-of-freedom
/// hinge \f$\tilde V^+ s = \tilde V s\f$ (\f$\tilde s s = 0\f$) and \f$H^*\f$ is constant:
/// \f$\partial T/\partial\theta(k) = (\tilde V(k) H^*(k))^* h(k)\f$. The universal hinge has
/// \f$\partial_{\theta_2}(H^*\beta) = \beta_1\,[c_1 \times a_2;\ 0]\f$ (HingeT::universal_c1()).
/// Throws soa::Error for a hinge whose coordinates do not add (spherical, free): its
/// \f$\partial T/\partial\theta\f$ is not defined here. Fills ws.phi and ws.V; \p p and
/// \p dT_dtheta must have size nv; nothing is allocated.
template <class S>
void kinetic_gradient(const ModelT<S>& m, const StateT<S>& x, WorkspaceT<S>& ws, VecX<S>& p,
                      VecX<S>& dT_dtheta) {
  update_phi(m, x.theta, ws);
  update_velocities(m, x, ws);
  MomentumT<S> h;
  for (int k = 1; k <= m.n(); ++k) {
    const BodyT<S>& B = m.body(k);
    if (!hinge_coordinates_add(B.hinge.type))
      throw Error("kinetic_gradient: body '" + B.name + "' has a " + hinge_type_name(B.hinge.type) +
                  " hinge, whose coordinates do not add (revolute, prismatic, helical, universal)");
    const S* th = x.theta.data() + B.q_offset;
    const S* be = x.beta.data() + B.v_offset;
    const VelocityT<S>& V = ws.V[k - 1];
    h = (k > 1 ? ws.phi[k - 2].apply(h) : MomentumT<S>()) + B.M * V;
    B.hinge.H_times(th, ForceT<S>(h.vector()), p.data() + B.v_offset);
    const VelocityT<S> V_plus(Vec6<S>(V.vector() - B.hinge.H_star_times(th, be).vector()));
    S* g = dT_dtheta.data() + B.v_offset;
    B.hinge.H_times(th, cross_bar(V_plus, h), g);
    for (int i = 0; i < B.hinge.nv(); ++i) g[i] = -g[i];
    if (B.hinge.type == HingeType::Universal)
      g[1] += be[0] * B.hinge.universal_c1(th).cross(B.hinge.axis2).dot(h.angular());
  }
}

}  // namespace soa
