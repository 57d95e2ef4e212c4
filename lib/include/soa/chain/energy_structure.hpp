/// \file
/// The energy structure of the equations of motion (lesson 4, section 11): the rate of the
/// mass matrix \f$\dot{\mathcal M}\f$ and a Coriolis matrix \f$\mathcal C_v(\theta,\beta)\f$
/// with \f$\dot{\mathcal M} - 2\,\mathcal C_v\f$ skew-symmetric, in operator form.
///
/// Dense operator forms for small n, for teaching and tests only: 6n x 6n matrices, as in
/// soa::OperatorsT. Everything is in body coordinates (body k's quantities at \f$O_k\f$, in
/// \f$O_k\f$ coordinates), where \f$M(k)\f$ is constant.
#pragma once

#include <Eigen/Dense>

#include "soa/chain/operators.hpp"
#include "soa/spatial_cross.hpp"

namespace soa {

/// \f$\breve h\f$ of a force or momentum \f$h = [N; F]\f$, the matrix with
/// \f$\breve h\, V = \bar V h\f$ for every motion vector V (lesson 4, section 11; \f$\bar V\f$
/// of slide 55):
/// \f[ \breve h = -\begin{pmatrix} \tilde N & \tilde F \\ \tilde F & 0 \end{pmatrix}
///     = -\breve h^* . \f]
template <class S, class K>
Mat6<S> breve(const SpatialVector<S, K>& h) {
  static_assert(!K::is_motion, "breve(h) takes a force or a momentum");
  Mat6<S> m = Mat6<S>::Zero();
  const Mat3<S> N = tilde<S>(h.angular()), F = tilde<S>(h.linear());
  m.template topLeftCorner<3, 3>() = -N;
  m.template topRightCorner<3, 3>() = -F;
  m.template bottomLeftCorner<3, 3>() = -F;
  return m;
}

/// \f$\dot H^*(k)\f$, the rate of the joint map in \f$O_k\f$ coordinates (lesson 4, section
/// 11): zero but for the universal hinge, whose first column \f$c_1 = e^{-\theta_2\tilde
/// a_2}a_1\f$ turns with \f$\dot c_1 = \beta_2\, c_1 \times a_2\f$ (so \f$\dot H^*\beta =\f$
/// HingeT::H_star_dot_times()).
template <class S>
JointMap<S> hinge_map_rate(const HingeT<S>& h, const S* theta, const S* beta) {
  JointMap<S> Hd = JointMap<S>::Zero(6, h.nv());
  if (h.type == HingeType::Universal)
    Hd.col(0).template head<3>() = beta[1] * h.universal_c1(theta).cross(h.axis2);
  return Hd;
}

/// \f$\dot\phi(k+1,k) = \phi(k+1,k)\,\bar\Delta_V(k)\f$ (lesson 4, section 11; slide 61's
/// \f$\dot\phi^*\f$): with \f$\dot R = R\tilde\Delta_\omega\f$ and \f$\dot l = R\Delta_v\f$ for
/// \f$\phi(k+1,k) = [R, \tilde l R; 0, R]\f$ and \f$\Delta_V(k) = H^*(k)\beta(k)\f$. The
/// 6x6 matrix, for teaching and tests.
template <class S>
Mat6<S> joint_phi_rate(const PhiT<S>& phi, const VelocityT<S>& Delta_V) {
  return phi.matrix() * bar(Delta_V);
}

/// The operators of the energy structure of a chain at one state (lesson 4, section 11),
/// next to those of soa::OperatorsT (which the member `op` holds, gravity and external
/// forces left out: they do not enter \f$\dot{\mathcal M}\f$ or \f$\mathcal C_v\f$).
template <class S>
struct EnergyStructureT {
  OperatorsT<S> op;   ///< \f$\mathcal E_\phi, \phi, H, M, a, b\f$ at the state
  MatX<S> Delta_bar;  ///< \f$\bar\Delta_V = \mathrm{diag}(\bar\Delta_V(k))\f$, 6n x 6n
  MatX<S> H_dot;      ///< \f$\dot H = \mathrm{diag}(\dot H(k))\f$, nv x 6n
  MatX<S> h_breve;    ///< \f$\breve h = \mathrm{diag}(\breve h(k))\f$, \f$h(k) = M(k)V(k)\f$
  VecX<S> V;          ///< stacked \f$V(k)\f$

  /// The operators at state \p x; the model's gravity is ignored.
  static EnergyStructureT build(const ModelT<S>& m, const StateT<S>& x) {
    ModelT<S> m0 = m;
    m0.gravity.setZero();
    EnergyStructureT es;
    es.op = OperatorsT<S>::build(m0, x);
    const int n = m.n(), N = 6 * n;
    es.Delta_bar = MatX<S>::Zero(N, N);
    es.H_dot = MatX<S>::Zero(m.nv(), N);
    es.h_breve = MatX<S>::Zero(N, N);
    es.V = es.op.V(x.beta);
    for (int k = 1; k <= n; ++k) {
      const BodyT<S>& B = m.body(k);
      const int r = 6 * (k - 1);
      const S* th = x.theta.data() + B.q_offset;
      const S* be = x.beta.data() + B.v_offset;
      es.Delta_bar.block(r, r, 6, 6) = bar(B.hinge.H_star_times(th, be));
      es.H_dot.block(B.v_offset, r, B.hinge.nv(), 6) = hinge_map_rate(B.hinge, th, be).transpose();
      const VelocityT<S> Vk(Vec6<S>(es.V.template segment<6>(r)));
      es.h_breve.block(r, r, 6, 6) = breve(B.M * Vk);
    }
    return es;
  }

  /// \f$\dot{\mathcal E}_\phi = \mathcal E_\phi\,\bar\Delta_V\f$ (block (k+1,k) is
  /// joint_phi_rate()).
  MatX<S> E_phi_dot() const { return op.E_phi * Delta_bar; }
  /// \f$\tilde\phi = \phi - I = \phi\,\mathcal E_\phi\f$.
  MatX<S> phi_tilde() const { return op.phi - MatX<S>::Identity(op.phi.rows(), op.phi.cols()); }
  /// \f$\dot\phi = \phi\,\dot{\mathcal E}_\phi\,\phi = \tilde\phi\,\bar\Delta_V\,\phi\f$
  /// (from \f$\phi = (I - \mathcal E_\phi)^{-1}\f$).
  MatX<S> phi_dot() const { return phi_tilde() * Delta_bar * op.phi; }
  /// \f$B = \phi^* H^*\f$, so \f$V = B\beta\f$ and \f$\mathcal M = B^* M B\f$.
  MatX<S> B() const { return op.phi.transpose() * op.H.transpose(); }
  /// \f$\dot B = \dot\phi^* H^* + \phi^*\dot H^* = \phi^*(\dot H^* - \tilde\Delta_V
  /// \tilde\phi^* H^*)\f$.
  MatX<S> B_dot() const {
    return phi_dot().transpose() * op.H.transpose() + op.phi.transpose() * H_dot.transpose();
  }
  /// \f$\dot{\mathcal M} = \dot B^* M B + B^* M \dot B\f$ (\f$\dot M = 0\f$ in body
  /// coordinates).
  MatX<S> mass_matrix_rate() const {
    const MatX<S> X = B().transpose() * op.M * B_dot();
    return X + X.transpose();
  }
  /// The Coriolis matrix \f$\mathcal C_v = B^*(M\dot B + \breve h B)\f$: \f$\mathcal C_v\beta
  /// = \mathcal C(\theta,\beta) - \mathcal C(\theta,0)\f$ without external forces, and
  /// \f$\mathcal C_v + \mathcal C_v^* = \dot{\mathcal M}\f$ (as \f$\breve h^* = -\breve h\f$).
  MatX<S> coriolis_matrix() const {
    const MatX<S> Bm = B();
    return Bm.transpose() * (op.M * B_dot() + h_breve * Bm);
  }
};
using EnergyStructure = EnergyStructureT<double>;

}  // namespace soa
