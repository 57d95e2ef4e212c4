// Lesson 8 exercises: replace each body with your code (statements in exercises.hpp).
#include "exercises.hpp"

#include "not_done.hpp"

namespace soa::ex08 {

TipToBase tip_to_base(const Model& m, const State& x, const VecX<double>& T) {
  (void)m, (void)x, (void)T;
  throw exercise::NotDone("8.1 tip_to_base");
}

VecX<double> base_to_tip(const Model& m, const State& x, const Workspace& ws,
                         const Articulated& art, const std::vector<VecX<double>>& nu,
                         const Acceleration& alpha_base, std::vector<Acceleration>& alpha) {
  (void)m, (void)x, (void)ws, (void)art, (void)nu, (void)alpha_base, (void)alpha;
  throw exercise::NotDone("8.2 base_to_tip");
}

VecX<double> forward_dynamics_1dof(const Model& m, const State& x, const VecX<double>& T,
                                   const ExternalForces<double>& f_ext) {
  (void)m, (void)x, (void)T, (void)f_ext;
  throw exercise::NotDone("8.3 forward_dynamics_1dof");
}

std::vector<Force> inter_body_forces(const Model& m, const State& x, const ForwardDynamics& fd,
                                     VecX<double>& T_hinge) {
  (void)m, (void)x, (void)fd, (void)T_hinge;
  throw exercise::NotDone("8.4 inter_body_forces");
}

State rk4_step(const Model& m, const State& x, const VecX<double>& T, double h) {
  (void)m, (void)x, (void)T, (void)h;
  throw exercise::NotDone("8.5 rk4_step");
}

VecX<double> forward_dynamics_fixed(const Model& m, const State& x, const VecX<double>& T,
                                    const ExternalForces<double>& f_ext) {
  throw exercise::NotDone("8.6 forward_dynamics_fixed");
  // The code to fix. It has one bug; delete the throw line above, then find it.
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
    alpha = alpha_plus + Acceleration(Hs * nu[j]) + ws.a[j];
  }
  return beta_dot;
}

Hybrid hybrid_dynamics(const Model& m, const State& x, const std::vector<bool>& prescribed,
                       const VecX<double>& T, const VecX<double>& beta_dot) {
  (void)m, (void)x, (void)prescribed, (void)T, (void)beta_dot;
  throw exercise::NotDone("8.7 hybrid_dynamics");
}

}  // namespace soa::ex08
