/// \file
/// The reference composite-body mass matrix (lesson 5; Jain 2011, chapter 5).
#pragma once

#include "soa/reference/kinematics.hpp"

namespace soa::reference {

/// The mass matrix \f$\mathcal M(\theta)\f$ from the composite inertias \f$R(k)\f$, in
/// \f$O(N^2)\f$ (lesson 5, sections 1-3). \p Mass is nv x nv. Fast forms:
/// soa::mass_matrix_inertial(), soa::mass_matrix_crb().
template <class S>
void mass_matrix(const ModelT<S>& m, const StateT<S>& x, WorkspaceT<S>& ws, MatX<S>& Mass) {
  joint_transforms(m, x.theta, ws);
  // R(k) = \phi(k,k-1)\,R(k-1)\,\phi^*(k,k-1) + M(k), \quad R(0) = 0
  for (int k = 1; k <= m.n(); ++k)
    ws.R[k - 1] =
        (k > 1 ? transform(ws.phi[k - 2], ws.R[k - 2], false) : SpatialInertiaT<S>()) + m.body(k).M;
  for (int j = 1; j <= m.n(); ++j) {
    const BodyT<S>& Bj = m.body(j);
    const JointMap<S> Hs_j = Bj.hinge.H_star(x.theta.data() + Bj.q_offset);
    for (int c = 0; c < Bj.hinge.nv(); ++c) {
      const int col = Bj.v_offset + c;
      // X(j) = R(j)\,H^*(j)\,e_c, a force at O_j
      ForceT<S> X((ws.R[j - 1] * VelocityT<S>(Vec6<S>(Hs_j.col(c)))).vector());
      for (int i = j; i <= m.n(); ++i) {
        const BodyT<S>& Bi = m.body(i);
        // X(i) = \phi(i,i-1)\,X(i-1) = \phi(i,j)\,R(j)\,H^*(j)\,e_c
        if (i > j) X = ws.phi[i - 2].apply(X);
        // \mathcal M(i,j) = H(i)\,\phi(i,j)\,R(j)\,H^*(j) = \mathcal M^*(j,i), \quad i \ge j
        const JointMap<S> Hs_i = Bi.hinge.H_star(x.theta.data() + Bi.q_offset);
        for (int r = 0; r < Bi.hinge.nv(); ++r)
          Mass(Bi.v_offset + r, col) = Mass(col, Bi.v_offset + r) = Hs_i.col(r).dot(X.vector());
      }
    }
  }
}

}  // namespace soa::reference
