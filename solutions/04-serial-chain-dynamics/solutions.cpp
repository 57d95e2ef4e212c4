// Lesson 4 exercises, solved from the formulas of the statements (exercises.hpp).
#include "exercises.hpp"

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

}  // namespace soa::ex04
