/// \file
/// The operational-space (end-effector) inverse inertia \f$J\mathcal M^{-1}J^*\f$ of a frame
/// on the chain in \f$O(N)\f$, from \f$\Upsilon\f$ (lesson 7, section 8).
#pragma once

#include "soa/chain/mass_matrix_inverse_upsilon.hpp"

namespace soa {

/// \f$\Lambda^{-1} = J\mathcal M^{-1}J^* = \phi^*(O_k,F)\,\Upsilon(k)\,\phi(O_k,F)\f$ for a
/// frame F fixed on body k (lesson 7, section 8): \f$J = B^*\phi^*H^*\f$ (jacobian()) and
/// \f$\phi^*H^*\mathcal M^{-1}H\phi = \Omega\f$, whose diagonal block k is \f$\Upsilon(k)\f$.
/// \p frame is \f${}^{O_k}T_F\f$ and \p Upsilon_k is \f$\Upsilon(k)\f$ from upsilons().
template <class S>
void operational_space_inverse_inertia(const PoseT<S>& frame, const Mat6<S>& Upsilon_k,
                                       Mat6<S>& out) {
  transpose_transform_symmetric(PhiT<S>(frame), Upsilon_k, out);
}

/// The same from the state, \f$O(N)\f$: the Riccati recursion tip to base, the
/// \f$\Upsilon\f$ recursion base to tip down to body k only (upsilons()), then
/// \f$\phi^*(O_k,F)\,\Upsilon(k)\,\phi(O_k,F)\f$. For the tip, k = 1. Needs update_phi().
template <class S>
void operational_space_inverse_inertia(const ModelT<S>& m, const StateT<S>& x,
                                       const WorkspaceT<S>& ws, UpsilonT<S>& w, int k,
                                       const PoseT<S>& frame, Mat6<S>& out) {
  upsilons(m, x, ws, w, k);
  operational_space_inverse_inertia(frame, w.Upsilon[k - 1], out);
}

}  // namespace soa
