/// \file
/// Composite rigid body inertias and the O(N^2) mass matrix (lesson 5).
#pragma once

#include <vector>

#include "soa/chain/kinematics.hpp"

namespace soa {

/// The composite rigid body inertias by the forward Lyapunov recursion (lesson 5), tip to
/// base: \f[ R(k) = \phi(k,k-1)\, R(k-1)\, \phi^*(k,k-1) + M(k), \qquad R(0) = 0 , \f]
/// each the inertia, about \f$O_k\f$, of bodies 1..k welded together: a rigid body inertia,
/// so it is kept as \f$(m, mp, J)\f$. Operator form: \f$R = \mathcal{E}_\phi R
/// \mathcal{E}_\phi^* + M\f$. Needs update_phi(); \p R must have n entries.
template <class S>
void composite_inertias(const ModelT<S>& m, const WorkspaceT<S>& ws,
                        std::vector<SpatialInertiaT<S>>& R) {
  for (int k = 1; k <= m.n(); ++k)
    R[k - 1] = k == 1 ? m.body(1).M : transform(ws.phi[k - 2], R[k - 2]) + m.body(k).M;
}

/// The mass matrix from the composite inertias (lesson 5), \f$O(N^2)\f$:
/// \f[ \mathcal{M}(k,k) = H(k) R(k) H^*(k), \qquad
///     \mathcal{M}(i,j) = H(i)\,\phi(i,j)\,R(j)\,H^*(j) = \mathcal{M}^*(j,i),\ i > j, \f]
/// from \f$\phi M \phi^* = R + \tilde\phi R + R\tilde\phi^*\f$. The force columns
/// \f$R(j)H^*(j)\f$ are carried to each inboard body by \f$\phi(i,i-1)\f$, never as a 6x6.
/// Needs update_phi(); \p R is workspace for the composite inertias (n entries).
template <class S>
void mass_matrix_crb(const ModelT<S>& m, const StateT<S>& x, const WorkspaceT<S>& ws,
                     std::vector<SpatialInertiaT<S>>& R, MatX<S>& Mass) {
  composite_inertias(m, ws, R);
  Mass.setZero(m.nv(), m.nv());
  for (int j = 1; j <= m.n(); ++j) {
    const BodyT<S>& Bj = m.body(j);
    const JointMap<S> Hs = Bj.hinge.H_star(x.theta.data() + Bj.q_offset);
    for (int c = 0; c < Hs.cols(); ++c) {
      const MomentumT<S> h = R[j - 1] * VelocityT<S>(Vec6<S>(Hs.col(c)));
      ForceT<S> F(h.vector());  // R(j) H*(j) e_c, a force at O_j
      const int col = Bj.v_offset + c;
      for (int i = j; i <= m.n(); ++i) {
        if (i > j) F = ws.phi[i - 2].apply(F);  // phi(i, i-1)
        const BodyT<S>& Bi = m.body(i);
        S T[6] = {};
        Bi.hinge.H_times(x.theta.data() + Bi.q_offset, F, T);
        for (int r = 0; r < Bi.hinge.nv(); ++r) {
          Mass(Bi.v_offset + r, col) = T[r];
          Mass(col, Bi.v_offset + r) = T[r];
        }
      }
    }
  }
}

}  // namespace soa
