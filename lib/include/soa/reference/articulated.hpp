/// \file
/// The reference articulated body inertias: the Riccati recursion (lesson 6; Jain 2011,
/// chapter 6).
#pragma once

#include "soa/reference/kinematics.hpp"

namespace soa::reference {

/// \f$\phi\,P\,\phi^*\f$ for a symmetric 6x6 \f$P\f$, as \f$\phi\,(\phi P)^*\f$: PhiT::apply
/// on the columns of \f$P\f$, then on the columns of \f$(\phi P)^*\f$ (slides 49, 70).
template <class S>
Mat6<S> phi_P_phi_star(const PhiT<S>& phi, const Mat6<S>& P) {
  Mat6<S> phi_P, out;
  for (int j = 0; j < 6; ++j) phi_P.col(j) = phi.apply(ForceT<S>(Vec6<S>(P.col(j)))).vector();
  for (int j = 0; j < 6; ++j)
    out.col(j) = phi.apply(ForceT<S>(Vec6<S>(phi_P.row(j).transpose()))).vector();
  return out;
}

/// The articulated body inertias, tip to base: \f$P(k)\f$, \f$D(k)\f$, \f$D^{-1}(k)\f$,
/// \f$G(k)\f$ and \f$P^+(k)\f$ into \p ws (lesson 6, section 2). The operators of lesson 6,
/// section 4 follow from them: \f$K(k+1,k) = \phi(k+1,k)\,G(k)\f$ and
/// \f$\mathcal E_\psi(k+1,k) = \phi(k+1,k)\,\bar\tau(k)\f$. Needs joint_transforms().
/// Fast form: soa::articulated_inertias().
template <class S>
void articulated_inertias(const ModelT<S>& m, const StateT<S>& x, WorkspaceT<S>& ws) {
  for (int k = 1; k <= m.n(); ++k) {
    const BodyT<S>& B = m.body(k);
    // P(k) = \phi(k,k-1)\,P^+(k-1)\,\phi^*(k,k-1) + M(k), \quad P^+(0) = 0
    Mat6<S>& P = ws.P[k - 1];
    P = (k > 1 ? phi_P_phi_star(ws.phi[k - 2], ws.P_plus[k - 2]) : Mat6<S>::Zero()) + B.M.matrix();
    const JointMap<S> Hs = B.hinge.H_star(x.theta.data() + B.q_offset);
    // D(k) = H(k)\,P(k)\,H^*(k)
    ws.D[k - 1] = Hs.transpose() * P * Hs;
    ws.D_inv[k - 1] = ws.D[k - 1].inverse();
    // G(k) = P(k)\,H^*(k)\,D^{-1}(k)
    ws.G[k - 1] = P * Hs * ws.D_inv[k - 1];
    // \bar\tau(k) = I - G(k)\,H(k), \quad P^+(k) = \bar\tau(k)\,P(k)
    const Mat6<S> tau_bar = Mat6<S>::Identity() - ws.G[k - 1] * Hs.transpose();
    ws.P_plus[k - 1] = tau_bar * P;
  }
}

}  // namespace soa::reference
