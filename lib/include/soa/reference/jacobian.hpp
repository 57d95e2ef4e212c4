/// \file
/// The reference Jacobian of a frame on a serial chain (lesson 3; Jain 2011, chapter 3).
#pragma once

#include "soa/reference/kinematics.hpp"

namespace soa::reference {

/// The Jacobian of the frame F fixed on body k at \f${}^{O_k}T_F\f$ (\p frame):
/// \f$V(F) = J\,\beta\f$ in F coordinates, \f$J = B^*\phi^* H^*\f$ (lesson 3, section 10).
/// \p J is 6 x nv. Fast form: soa::jacobian().
template <class S>
void jacobian(const ModelT<S>& m, const VecX<S>& theta, WorkspaceT<S>& ws, int k,
              const PoseT<S>& frame, Eigen::Matrix<S, 6, Eigen::Dynamic>& J) {
  joint_transforms(m, theta, ws);
  J.setZero();
  // \phi(O_k, F)
  PhiT<S> phi_iF(frame);
  for (int i = k; i <= m.n(); ++i) {
    const BodyT<S>& B = m.body(i);
    // \phi(O_i, F) = \phi(i,i-1)\,\phi(O_{i-1}, F), \quad i > k
    if (i > k) phi_iF = ws.phi[i - 2] * phi_iF;
    // J(\cdot, i) = \phi^*(O_i, F)\,H^*(i); the blocks of hinges outboard of k are zero
    const JointMap<S> Hs = B.hinge.H_star(theta.data() + B.q_offset);
    for (int c = 0; c < B.hinge.nv(); ++c)
      J.col(B.v_offset + c) = phi_iF.transpose_apply(VelocityT<S>(Vec6<S>(Hs.col(c)))).vector();
  }
}

}  // namespace soa::reference
