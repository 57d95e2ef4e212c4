/// \file
/// Jacobians of body frames and the \f$\dot J\beta\f$ term (lesson 3).
#pragma once

#include "soa/chain/kinematics.hpp"

namespace soa {

/// The fast form of soa::reference::jacobian().
/// The Jacobian of a frame F fixed on body k, placed at \f${}^{O_k}T_F\f$:
/// \f$V(F) = J\,\beta\f$ with \f$V(F)\f$ in F coordinates (lesson 3:
/// \f$J = B^*\phi^* H^*\f$, \f$B^*\f$ picking body k and moving it to F). Column block of
/// hinge i (i ≥ k, inboard of F) is \f$\phi^*(O_i, F)\,H^*(i)\f$; the others are zero.
/// Needs update_phi() and update_poses(); \p J must be 6 x nv.
template <class S>
void jacobian(const ModelT<S>& m, const VecX<S>& theta, const WorkspaceT<S>& ws, int k,
              const PoseT<S>& frame, Eigen::Matrix<S, 6, Eigen::Dynamic>& J) {
  J.setZero(6, m.nv());
  const PoseT<S> T_F = ws.pose[k - 1] * frame;  // ^I T_F
  for (int i = k; i <= m.n(); ++i) {
    const BodyT<S>& B = m.body(i);
    const PhiT<S> phi_iF(ws.pose[i - 1].inverse() * T_F);  // phi(O_i, F)
    const JointMap<S> Hs = B.hinge.H_star(theta.data() + B.q_offset);
    for (int c = 0; c < Hs.cols(); ++c)
      J.col(B.v_offset + c) = phi_iF.transpose_apply(VelocityT<S>(Vec6<S>(Hs.col(c)))).vector();
  }
}

/// jacobian() of an Eigen expression \p theta: forwards to jacobian(m, const VecX<S>&, ...).
template <class S, class D>
void jacobian(const ModelT<S>& m, const Eigen::MatrixBase<D>& theta, const WorkspaceT<S>& ws, int k,
              const PoseT<S>& frame, Eigen::Matrix<S, 6, Eigen::Dynamic>& J) {
  jacobian(m, VecX<S>(theta), ws, k, frame, J);
}

/// \f$\dot J\beta\f$ of the same frame: its spatial acceleration when \f$\dot\beta = 0\f$
/// and there is no gravity, so that \f$\alpha(F) = J\dot\beta + \dot J\beta\f$. From
/// \f$\alpha(k)\f$ at \f$\dot\beta = 0\f$ moved rigidly to F (lesson 2's point acceleration):
/// \f$\phi^*(O_k,F)\,\alpha(k) + [0;\ R^*\,\omega\times(\omega\times l)]\f$, with
/// \f$(R, l) = {}^{O_k}T_F\f$. Needs update_velocities(); overwrites ws.alpha.
template <class S>
AccelerationT<S> jacobian_dot_times_beta(const ModelT<S>& m, const StateT<S>& x, WorkspaceT<S>& ws,
                                         int k, const PoseT<S>& frame) {
  update_accelerations<S>(m, x, nullptr, AccelerationT<S>(), ws);
  const Vec3<S> w = ws.V[k - 1].angular();
  const Vec3<S> centripetal = w.cross(w.cross(frame.l()));
  return PhiT<S>(frame).transpose_apply(ws.alpha[k - 1]) +
         AccelerationT<S>(Vec3<S>::Zero(), frame.R().transpose() * centripetal);
}

}  // namespace soa
