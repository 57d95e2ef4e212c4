// Lesson 8 reference solutions (statements in exercises/08-recursive-forward-dynamics).
#include "exercises.hpp"

namespace soa::ex08 {

namespace {

// H*(k) of a one-degree-of-freedom hinge as a 6-vector (lesson 3): [a; 0], [0; a], [a; h a].
Vec6 joint_map(const Hinge& h) {
  Vec6 s = Vec6::Zero();
  if (h.type == HingeType::Prismatic) {
    s.tail<3>() = h.axis;
  } else {
    s.head<3>() = h.axis;
    if (h.type == HingeType::Helical) s.tail<3>() = h.pitch * h.axis;
  }
  return s;
}

}  // namespace

// Lesson 8, section 2, sweep 2 for revolute hinges: z, epsilon, nu, z+, tip to base.
TipToBase tip_to_base(const Model& m, const State& x, const VecX<double>& T) {
  Workspace ws(m);
  update_phi(m, x.theta, ws);
  update_velocities(m, x, ws);
  Articulated art(m);
  articulated_inertias(m, x, ws, art);
  const int n = m.n();
  TipToBase r{std::vector<Vec6>(std::size_t(n)), std::vector<Vec6>(std::size_t(n)), VecX<double>(n),
              VecX<double>(n)};
  for (int k = 1; k <= n; ++k) {
    const std::size_t j = std::size_t(k - 1);
    const Body& B = m.body(k);
    Vec6 s = Vec6::Zero();
    s.head<3>() = B.hinge.axis;
    Vec6 z = art.P[j] * ws.a[j].vector() + gyroscopic_force(B.M, ws.V[j]).vector();
    if (k > 1) z += ws.phi[j - 1].apply(Force(r.z_plus[j - 1])).vector();  // phi(k,k-1) z+(k-1)
    const double eps = T[B.v_offset] - s.dot(z);
    r.z[j] = z;
    r.eps[k - 1] = eps;
    r.nu[k - 1] = eps / art.D[j](0, 0);
    r.z_plus[j] = z + art.G[j].col(0) * eps;
  }
  return r;
}

// Lesson 8, section 2, sweep 3: alpha+, beta_dot, alpha, base to tip.
VecX<double> base_to_tip(const Model& m, const State& x, const Workspace& ws,
                         const Articulated& art, const std::vector<VecX<double>>& nu,
                         const Acceleration& alpha_base, std::vector<Acceleration>& alpha) {
  VecX<double> beta_dot(m.nv());
  alpha.assign(std::size_t(m.n()), Acceleration());
  Acceleration next = alpha_base;  // alpha(k+1)
  for (int k = m.n(); k >= 1; --k) {
    const std::size_t j = std::size_t(k - 1);
    const Body& B = m.body(k);
    const JointMap<double>& G = art.G[j];  // G(k)
    const Acceleration alpha_plus = ws.phi[j].transpose_apply(next);
    const VecX<double> bd = nu[j] - G.transpose() * alpha_plus.vector();
    beta_dot.segment(B.v_offset, B.hinge.nv()) = bd;
    const Vec6 a =
        alpha_plus.vector() + B.hinge.H_star(x.theta.data() + B.q_offset) * bd + ws.a[j].vector();
    alpha[j] = Acceleration(a);
    next = alpha[j];
  }
  return beta_dot;
}

// Lesson 8, section 2, all three sweeps with the Riccati recursion of lesson 6, scalar D.
VecX<double> forward_dynamics_1dof(const Model& m, const State& x, const VecX<double>& T,
                                   const ExternalForces<double>& f_ext) {
  const int n = m.n();
  const std::size_t N = std::size_t(n);
  Workspace ws(m);
  update_phi(m, x.theta, ws);
  update_velocities(m, x, ws);  // V(k), a(k)
  std::vector<Mat6<double>> P_plus(N);
  std::vector<Vec6> g(N), z_plus(N), s(N);
  std::vector<double> nu(N);
  for (int k = 1; k <= n; ++k) {  // tip to base
    const std::size_t j = std::size_t(k - 1);
    const Body& B = m.body(k);
    Mat6<double> P = B.M.matrix();
    Vec6 b = gyroscopic_force(B.M, ws.V[j]).vector();
    if (!f_ext.empty()) b -= f_ext[j].vector();
    Vec6 z = b;
    if (k > 1) {
      const Mat6<double> phi = ws.phi[j - 1].matrix();  // phi(k,k-1)
      P += phi * P_plus[j - 1] * phi.transpose();
      z += phi * z_plus[j - 1];
    }
    z += P * ws.a[j].vector();
    s[j] = joint_map(B.hinge);
    const Vec6 Ps = P * s[j];
    const double D = s[j].dot(Ps);
    g[j] = Ps / D;
    P_plus[j] = P - g[j] * Ps.transpose();
    const double eps = T[B.v_offset] - s[j].dot(z);
    nu[j] = eps / D;
    z_plus[j] = z + g[j] * eps;
  }
  VecX<double> beta_dot(m.nv());
  Vec6 next = gravity_base_acceleration(m).vector();  // alpha(n+1) = [0; -g]
  for (int k = n; k >= 1; --k) {                      // base to tip
    const std::size_t j = std::size_t(k - 1);
    const Vec6 alpha_plus = ws.phi[j].matrix().transpose() * next;
    const double bd = nu[j] - g[j].dot(alpha_plus);
    beta_dot[m.body(k).v_offset] = bd;
    next = alpha_plus + s[j] * bd + ws.a[j].vector();
  }
  return beta_dot;
}

// Lesson 8, sections 2-3: f(k) = P+(k) alpha+(k) + z+(k), and H(k) f(k).
std::vector<Force> inter_body_forces(const Model& m, const State& x, const ForwardDynamics& fd,
                                     VecX<double>& T_hinge) {
  std::vector<Force> f;
  T_hinge.resize(m.nv());
  for (int k = 1; k <= m.n(); ++k) {
    const std::size_t j = std::size_t(k - 1);
    const Body& B = m.body(k);
    f.push_back(Force(fd.art.P_plus[j] * fd.alpha_plus[j].vector() + fd.z_plus[j].vector()));
    B.hinge.H_times(x.theta.data() + B.q_offset, f.back(), T_hinge.data() + B.v_offset);
  }
  return f;
}

// Lesson 8, section 7: one RK4 step of theta_dot = beta, beta_dot = FD(theta, beta, T).
State rk4_step(const Model& m, const State& x, const VecX<double>& T, double h) {
  Workspace ws(m);
  ForwardDynamics fd(m);
  const auto F = [&](const VecX<double>& theta, const VecX<double>& beta) {
    VecX<double> bd(m.nv());
    forward_dynamics(m, State{theta, beta}, T, {}, ws, fd, bd);
    return bd;
  };
  const VecX<double> k1q = x.beta, k1v = F(x.theta, x.beta);
  const VecX<double> k2q = x.beta + h / 2 * k1v, k2v = F(x.theta + h / 2 * k1q, k2q);
  const VecX<double> k3q = x.beta + h / 2 * k2v, k3v = F(x.theta + h / 2 * k2q, k3q);
  const VecX<double> k4q = x.beta + h * k3v, k4v = F(x.theta + h * k3q, k4q);
  return State{x.theta + h / 6 * (k1q + 2 * k2q + 2 * k3q + k4q),
               x.beta + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)};
}

// 8.6: the given code with its bug fixed: alpha(k) = alpha+(k) + H*(k) beta_dot(k) + a(k), with
// the hinge's acceleration beta_dot(k) = nu(k) - G*(k) alpha+(k), not nu(k) (the body outboard
// sees the acceleration of body k; at the tip nothing does, so one body was always right).
VecX<double> forward_dynamics_fixed(const Model& m, const State& x, const VecX<double>& T,
                                    const ExternalForces<double>& f_ext) {
  const int n = m.n();
  Workspace ws(m);
  update_phi(m, x.theta, ws);
  update_velocities(m, x, ws);  // V(k), a(k)
  Articulated art(m);
  articulated_inertias(m, x, ws, art);  // P(k), D(k), G(k), P+(k)
  std::vector<Force> z_plus(static_cast<std::size_t>(n));
  std::vector<VecX<double>> nu(static_cast<std::size_t>(n));
  // Tip to base: z, epsilon, nu, z+.
  for (int k = 1; k <= n; ++k) {
    const std::size_t j = std::size_t(k - 1);
    const Body& B = m.body(k);
    const double* th = x.theta.data() + B.q_offset;
    Force z = Force(art.P[j] * ws.a[j].vector()) + gyroscopic_force(B.M, ws.V[j]);
    if (!f_ext.empty()) z -= f_ext[j];
    if (k > 1) z += ws.phi[j - 1].apply(z_plus[j - 1]);  // phi(k,k-1) z+(k-1)
    VecX<double> eps = T.segment(B.v_offset, B.hinge.nv());
    add_spring_force(B, th, x.beta.data() + B.v_offset, eps.data());  // T + tau_s
    eps -= B.hinge.H_star(th).transpose() * z.vector();
    nu[j] = art.D_inv[j] * eps;
    z_plus[j] = z + Force(art.G[j] * eps);
  }
  // Base to tip: alpha+, beta_dot, alpha, from alpha(n+1) = [0; -g].
  VecX<double> beta_dot(m.nv());
  Acceleration alpha = gravity_base_acceleration(m);  // alpha(k+1)
  for (int k = n; k >= 1; --k) {
    const std::size_t j = std::size_t(k - 1);
    const Body& B = m.body(k);
    const Acceleration alpha_plus = ws.phi[j].transpose_apply(alpha);
    const VecX<double> bd = nu[j] - art.G[j].transpose() * alpha_plus.vector();
    beta_dot.segment(B.v_offset, B.hinge.nv()) = bd;
    const JointMap<double> Hs = B.hinge.H_star(x.theta.data() + B.q_offset);
    alpha = alpha_plus + Acceleration(Hs * bd) + ws.a[j];  // the fix: bd, not nu[j]
  }
  return beta_dot;
}

// 8.7: across a prescribed hinge beta_dot(k) is known, so
//   f(k) = P(k) (alpha(k) - a(k)) + z(k) = P(k) alpha+(k) + [z(k) + P(k) H*(k) beta_dot(k)]:
// P+(k) = P(k) (no projection: the hinge passes the whole inertia inboard) and
// z+(k) = z(k) + P(k) H*(k) beta_dot(k); base to tip, T(k) = H(k) (P+(k) alpha+(k) + z+(k)).
// Free hinges keep the sweeps of lesson 8, section 2.
Hybrid hybrid_dynamics(const Model& m, const State& x, const std::vector<bool>& prescribed,
                       const VecX<double>& T, const VecX<double>& beta_dot) {
  const int n = m.n();
  const std::size_t N = std::size_t(n);
  Workspace ws(m);
  update_phi(m, x.theta, ws);
  update_velocities(m, x, ws);  // V(k), a(k)
  std::vector<Mat6<double>> P_plus(N);
  std::vector<Vec6> z_plus(N);
  std::vector<MatX<double>> G(N);  // G(k) of the free hinges
  std::vector<VecX<double>> nu(N);
  Hybrid r{beta_dot, T};
  for (int k = 1; k <= n; ++k) {  // tip to base
    const std::size_t j = std::size_t(k - 1);
    const Body& B = m.body(k);
    const int nk = B.hinge.nv();
    const MatX<double> Hs = B.hinge.H_star(x.theta.data() + B.q_offset);  // 6 x n_k
    Mat6<double> P = B.M.matrix();
    Vec6 z = gyroscopic_force(B.M, ws.V[j]).vector();
    if (k > 1) {
      const Mat6<double> phi_k = ws.phi[j - 1].matrix();  // phi(k,k-1)
      P += phi_k * P_plus[j - 1] * phi_k.transpose();
      z += phi_k * z_plus[j - 1];
    }
    z += P * ws.a[j].vector();
    if (prescribed[j]) {
      P_plus[j] = P;
      z_plus[j] = z + P * (Hs * beta_dot.segment(B.v_offset, nk));
    } else {
      const MatX<double> PH = P * Hs;
      const MatX<double> D = Hs.transpose() * PH;
      G[j] = PH * D.inverse();
      const VecX<double> eps = T.segment(B.v_offset, nk) - Hs.transpose() * z;
      nu[j] = D.inverse() * eps;
      P_plus[j] = P - G[j] * PH.transpose();
      z_plus[j] = z + G[j] * eps;
    }
  }
  Vec6 next = gravity_base_acceleration(m).vector();  // alpha(n+1) = [0; -g]
  for (int k = n; k >= 1; --k) {                      // base to tip
    const std::size_t j = std::size_t(k - 1);
    const Body& B = m.body(k);
    const int nk = B.hinge.nv();
    const MatX<double> Hs = B.hinge.H_star(x.theta.data() + B.q_offset);
    const Vec6 alpha_plus = ws.phi[j].matrix().transpose() * next;
    if (prescribed[j]) {
      r.T.segment(B.v_offset, nk) = Hs.transpose() * (P_plus[j] * alpha_plus + z_plus[j]);
    } else {
      r.beta_dot.segment(B.v_offset, nk) = nu[j] - G[j].transpose() * alpha_plus;
    }
    next = alpha_plus + Hs * r.beta_dot.segment(B.v_offset, nk) + ws.a[j].vector();
  }
  return r;
}

}  // namespace soa::ex08
