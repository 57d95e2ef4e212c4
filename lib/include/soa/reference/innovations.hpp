/// \file
/// The reference innovations factorization applied to a vector (lesson 7; Jain 2011,
/// chapter 7).
#pragma once

#include "soa/reference/articulated.hpp"

namespace soa::reference {

/// \f$y = [I + H\phi K]\,v\f$, the innovations factor of \f$\mathcal M = [I + H\phi K]\,D\,
/// [I + H\phi K]^*\f$ times \p v, in O(N) (lesson 7, section 3): with \f$K(k+1,k) =
/// \phi(k+1,k)\,G(k)\f$, tip to base. Needs joint_transforms() and articulated_inertias();
/// \p y has size nv. Dense form: soa::InnovationsOperatorsT::factor().
template <class S>
void innovations_factor_times(const ModelT<S>& m, const StateT<S>& x, const VecX<S>& v,
                              WorkspaceT<S>& ws, VecX<S>& y) {
  for (int k = 1; k <= m.n(); ++k) {
    const BodyT<S>& B = m.body(k);
    const int nk = B.hinge.nv();
    // (\phi K v)(k) = \phi(k,k-1)\,\bigl[(\phi K v)(k-1) + G(k-1)\,v(k-1)\bigr], \quad
    // (\phi K v)(1) = 0
    if (k == 1) {
      ws.phi_K_v[0] = ForceT<S>();
    } else {
      const BodyT<S>& B_prev = m.body(k - 1);
      const Vec6<S> Gv = ws.G[k - 2] * v.segment(B_prev.v_offset, B_prev.hinge.nv());
      ws.phi_K_v[k - 1] = ws.phi[k - 2].apply(ws.phi_K_v[k - 2] + ForceT<S>(Gv));
    }
    // y(k) = v(k) + H(k)\,(\phi K v)(k)
    S Hz[6];
    B.hinge.H_times(x.theta.data() + B.q_offset, ws.phi_K_v[k - 1], Hz);
    for (int i = 0; i < nk; ++i) y[B.v_offset + i] = v[B.v_offset + i] + Hz[i];
  }
}

}  // namespace soa::reference
