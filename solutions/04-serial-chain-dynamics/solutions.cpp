// Lesson 4 exercises, solved from the formulas of the statements (exercises.hpp).
#include "exercises.hpp"

#include <cmath>

namespace soa::ex04 {

// 4.1: tip to base, f(k) = phi(k,k-1) f(k-1) + M(k) alpha(k) + b(k), T(k) = H(k) f(k).
Gathered gather_forces(const Model& m, const VecX<double>& theta, const std::vector<Phi>& phi,
                       const std::vector<Acceleration>& alpha, const std::vector<Force>& b) {
  Gathered g;
  g.f.assign(std::size_t(m.n()), Force::Zero());
  g.T = VecX<double>::Zero(m.nv());
  for (int k = 1; k <= m.n(); ++k) {
    const Body& B = m.body(k);
    const auto i = std::size_t(k - 1);
    Force f = B.M * alpha[i] + b[i];
    if (k > 1) f += phi[i - 1].apply(g.f[i - 1]);  // phi(k,k-1) = phi[k-2]
    g.f[i] = f;
    B.hinge.H_times(theta.data() + B.q_offset, f, g.T.data() + B.v_offset);
  }
  return g;
}

// 4.2: base to tip V, alpha (revolute Coriolis term), tip to base f, T = a* N.
VecX<double> newton_euler(const Model& m, const State& x, const VecX<double>& beta_dot) {
  const int n = m.n();
  const auto size = std::size_t(n);
  std::vector<Phi> phi(size);
  std::vector<Velocity> V(size);
  std::vector<Acceleration> alpha(size);
  Velocity V_parent;
  Acceleration alpha_parent(Vec3<double>::Zero(), -m.gravity);  // alpha(n+1) = [0; -g]
  for (int k = n; k >= 1; --k) {
    const Body& B = m.body(k);
    const auto i = std::size_t(k - 1);
    const Vec3<double> a = B.hinge.axis;
    const double th = x.theta[B.q_offset], be = x.beta[B.v_offset], bd = beta_dot[B.v_offset];
    phi[i] = Phi(B.placement * Pose(exp_so3(th * a)));
    const Mat3<double> Rt = phi[i].R().transpose();
    const Vec3<double> w_parent = Rt * Vec3<double>(V_parent.angular());  // omega(k+1), O_k
    const Vec3<double> l = Rt * phi[i].l();                               // l(O_{k+1}, O_k), O_k
    V[i] = phi[i].transpose_apply(V_parent) + Velocity(be * a, Vec3<double>::Zero());
    const Acceleration coriolis(w_parent.cross(be * a), w_parent.cross(w_parent.cross(l)));
    alpha[i] = phi[i].transpose_apply(alpha_parent) + Acceleration(bd * a, Vec3<double>::Zero()) +
               coriolis;
    V_parent = V[i];
    alpha_parent = alpha[i];
  }
  VecX<double> T(m.nv());
  Force f_child;
  for (int k = 1; k <= n; ++k) {
    const Body& B = m.body(k);
    const auto i = std::size_t(k - 1);
    Force f = B.M * alpha[i] + gyroscopic_force(B.M, V[i]);
    if (k > 1) f += phi[i - 1].apply(f_child);
    T[B.v_offset] = B.hinge.axis.dot(Vec3<double>(f.angular()));
    f_child = f;
  }
  return T;
}

// phi = (I - E_phi)^{-1}, by a triangular solve (I - E_phi is unit lower triangular).
static MatX<double> phi_from_shift(const MatX<double>& E_phi) {
  const Eigen::Index N = E_phi.rows();
  const MatX<double> I_minus_E = MatX<double>::Identity(N, N) - E_phi;
  return I_minus_E.triangularView<Eigen::UnitLower>().solve(MatX<double>::Identity(N, N));
}

// 4.3: M = H phi M phi* H*.
MatX<double> mass_matrix_operators(const Operators& op) {
  const MatX<double> phi = phi_from_shift(op.E_phi);
  const MatX<double> B = phi.transpose() * op.H.transpose();  // phi* H*
  return B.transpose() * op.M * B;
}

// 4.4: column j = T(beta_dot = e_j) - T(beta_dot = 0), at beta = 0.
MatX<double> mass_matrix_columns(const Model& m, const VecX<double>& theta) {
  const int nv = m.nv();
  const State x{theta, VecX<double>::Zero(nv)};
  Workspace ws(m);
  const ExternalForces<double> none;
  VecX<double> beta_dot = VecX<double>::Zero(nv), T0(nv), Tj(nv);
  inverse_dynamics(m, x, beta_dot, none, ws, T0);
  MatX<double> M(nv, nv);
  for (int j = 0; j < nv; ++j) {
    beta_dot.setUnit(j);
    inverse_dynamics(m, x, beta_dot, none, ws, Tj);
    M.col(j) = Tj - T0;
  }
  return M;
}

// 4.5: C = H phi (M phi* a + b).
VecX<double> bias_operators(const Operators& op) {
  const MatX<double> phi = phi_from_shift(op.E_phi);
  return op.H * (phi * (op.M * (phi.transpose() * op.a) + op.b));
}

// 4.6: G = -sum_k J*(C_k) [0; m_k R_k* g].
VecX<double> gravity_torques(const Model& m, const VecX<double>& theta) {
  Workspace ws(m);
  update_phi(m, theta, ws);
  update_poses(m, ws);
  VecX<double> G = VecX<double>::Zero(m.nv());
  Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, m.nv());
  for (int k = 1; k <= m.n(); ++k) {
    const SpatialInertia& M = m.body(k).M;
    jacobian(m, theta, ws, k, Pose(Mat3<double>::Identity(), M.p()), J);
    Vec6<double> f_g;
    f_g << Vec3<double>::Zero(),
        M.mass() * (ws.pose[std::size_t(k - 1)].R().transpose() * m.gravity);
    G -= J.transpose() * f_g;
  }
  return G;
}

// 4.7: C_v = B*(M B_dot + h_breve B), B_dot = phi_dot* H* + phi* H_dot*,
// phi_dot = (phi - I) Delta_bar phi.
MatX<double> coriolis_matrix_operators(const EnergyStructure& es) {
  const MatX<double>& phi = es.op.phi;
  const MatX<double> phi_tilde = phi - MatX<double>::Identity(phi.rows(), phi.cols());
  const MatX<double> phi_dot = phi_tilde * es.Delta_bar * phi;
  const MatX<double> B = phi.transpose() * es.op.H.transpose();
  const MatX<double> B_dot =
      phi_dot.transpose() * es.op.H.transpose() + phi.transpose() * es.H_dot.transpose();
  return B.transpose() * (es.op.M * B_dot + es.h_breve * B);
}

// 4.8: differentiate V(k) = phi*(k+1,k) V(k+1) + Delta_V in the inertial frame (lesson 3,
// section 7): a(k) = [w' x Delta_w; w(k) x Delta_v + w' x (v(k) - v(k+1))] with
// v(k) - v(k+1) = w' x l + Delta_v in O_k coordinates (the velocity of O_{k+1} drops out).
// For the screw, Delta_w = beta a and Delta_v = h beta a, w(k) = w' + beta a and
// (beta a) x (h beta a) = 0, so the sliding enters twice:
//   a(k) = [w' x beta a;  w' x (w' x l) + 2 h beta w' x a].
Acceleration helical_coriolis(const Vec3<double>& omega_parent, const Vec3<double>& l,
                              const Vec3<double>& axis, double pitch, double beta) {
  const Vec3<double>& w = omega_parent;
  const Vec3<double> angular = w.cross(beta * axis);
  const Vec3<double> linear = w.cross(w.cross(l)) + 2.0 * beta * pitch * w.cross(axis);
  return Acceleration(angular, linear);
}

// 4.9: hinge k carries bodies 1 ... k (itself and everything outboard). Held still, its moment
// cancels gravity's about any point of the axis, O_k: G(k) = -a_k* sum_i l(O_k, C_i) x m_i g,
// in inertial coordinates. A vertical axis (a_k parallel to g) gives 0, whatever the pose.
VecX<double> gravity_torque_signs(const Model& m, const VecX<double>& theta) {
  Workspace ws(m);
  update_phi(m, theta, ws);
  update_poses(m, ws);
  VecX<double> sign(m.nv());
  for (int k = 1; k <= m.n(); ++k) {
    const Pose& O = ws.pose[std::size_t(k - 1)];
    const Vec3<double> a = O.R() * m.body(k).hinge.axis;  // inertial coordinates
    Vec3<double> moment = Vec3<double>::Zero();
    double W = 0;
    for (int i = 1; i <= k; ++i) {
      const SpatialInertia& Mi = m.body(i).M;
      const Vec3<double> r = ws.pose[std::size_t(i - 1)].apply(Mi.p()) - O.l();  // l(O_k, C_i)
      moment += r.cross(Mi.mass() * m.gravity);
      W += Mi.mass() * (1 + r.norm());
    }
    W *= m.gravity.norm();
    const double G = -a.dot(moment);  // the hinge's moment about its axis
    sign[m.body(k).v_offset] = std::abs(G) <= 1e-9 * W ? 0.0 : G > 0 ? 1.0 : -1.0;
  }
  return sign;
}

}  // namespace soa::ex04
