/// \file
/// The reference \f$\mathcal M^{-1}\f$ in \f$O(N^2)\f$ (lesson 7; Jain 2011, chapter 7).
#pragma once

#include "soa/reference/mass_matrix_inverse_times.hpp"

namespace soa::reference {

/// \f$\mathcal M^{-1}(\theta)\f$, column by column: \f$\mathcal M^{-1} e_j\f$ for each unit
/// hinge force \f$e_j\f$ by articulated_solve(), O(N) each after one Riccati recursion
/// (lesson 7, sections 4 and 7). \p Minv is nv x nv. Fast form: soa::mass_matrix_inverse().
template <class S>
void mass_matrix_inverse(const ModelT<S>& m, const StateT<S>& x, WorkspaceT<S>& ws, MatX<S>& Minv) {
  joint_transforms(m, x.theta, ws);
  articulated_inertias(m, x, ws);
  for (int j = 0; j < m.nv(); ++j) {
    ws.unit.setZero();
    ws.unit[j] = S(1);
    // \mathcal M^{-1}(\cdot, j) = [I - H\psi K]^* D^{-1} [I - H\psi K]\, e_j
    articulated_solve(m, x, ws.unit, ws, ws.column);
    Minv.col(j) = ws.column;
  }
}

}  // namespace soa::reference
