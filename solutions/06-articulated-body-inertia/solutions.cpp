// Lesson 6 reference solutions (statements in exercises/06-articulated-body-inertia).
// Each is self-contained: it calls the library where its statement allows it, never
// another exercise's function.
#include "exercises.hpp"

namespace soa::ex06 {

// Lesson 6, section 2: the Riccati step, tip to base.
RiccatiStep riccati_step(const Mat6& P_plus_prev, const Phi& phi, const SpatialInertia& M,
                         const MatX<double>& H_star) {
  RiccatiStep s;
  const Mat6 phi6 = phi.matrix();
  s.P = phi6 * P_plus_prev * phi6.transpose() + M.matrix();
  const MatX<double> PHs = s.P * H_star;
  s.D = H_star.transpose() * PHs;
  s.G = PHs * s.D.inverse();
  s.P_plus = s.P - s.G * PHs.transpose();
  return s;
}

// Lesson 6, section 3: tau_bar = I - G H.
Mat6 tau_bar(const Mat6& P, const MatX<double>& H_star) {
  const MatX<double> PHs = P * H_star;
  const MatX<double> D = H_star.transpose() * PHs;
  const MatX<double> G = PHs * D.inverse();
  return Mat6::Identity() - G * H_star.transpose();
}

// Lesson 6, section 2, for 1-dof revolute hinges: D(k) = a* P_aa a, G = P [a; 0] / D.
VecX<double> revolute_D(const Model& m, const VecX<double>& theta) {
  Workspace ws(m);
  update_phi(m, theta, ws);
  VecX<double> D(m.n());
  Mat6 P_plus = Mat6::Zero();
  for (int k = 1; k <= m.n(); ++k) {
    Mat6 P = m.body(k).M.matrix();
    if (k > 1) P += soa::transform_symmetric(ws.phi[std::size_t(k - 2)], P_plus);
    Vec6<double> Hs = Vec6<double>::Zero();
    Hs.head<3>() = m.body(k).hinge.axis;
    const Vec6<double> PHs = P * Hs;
    D[k - 1] = Hs.dot(PHs);
    P_plus = P - PHs * PHs.transpose() / D[k - 1];
  }
  return D;
}

// Lesson 6, section 2: phi P phi* by blocks.
Mat6 transform_symmetric(const Phi& phi, const Mat6& P) {
  const Mat3<double>& R = phi.R();
  const Mat3<double> A = R * P.topLeftCorner<3, 3>() * R.transpose();
  const Mat3<double> B = R * P.topRightCorner<3, 3>() * R.transpose();
  const Mat3<double> C = R * P.bottomRightCorner<3, 3>() * R.transpose();
  const Mat3<double> L = tilde(phi.l());
  const Mat3<double> BLC = B + L * C;
  Mat6 out;
  out.topLeftCorner<3, 3>() = A + L * B.transpose() - B * L - L * C * L;
  out.topRightCorner<3, 3>() = BLC;
  out.bottomLeftCorner<3, 3>() = BLC.transpose();
  out.bottomRightCorner<3, 3>() = C;
  return out;
}

// Lesson 6, sections 2 and 8: f(k) = P+(k) alpha+(k) + z+(k) from the forward dynamics.
std::vector<Vec6<double>> articulated_forces(const Model& m, const State& x,
                                             const VecX<double>& T) {
  Workspace ws(m);
  ForwardDynamics fd(m);
  VecX<double> beta_dot(m.nv());
  forward_dynamics(m, x, T, {}, ws, fd, beta_dot);
  std::vector<Vec6<double>> f;
  for (int k = 1; k <= m.n(); ++k) {
    const std::size_t j = std::size_t(k - 1);
    f.push_back(fd.art.P_plus[j] * fd.alpha_plus[j].vector() + fd.z_plus[j].vector());
  }
  return f;
}

// Lesson 6, section 8: y(k) = phi(k,k-1) y(k-1) + R(k) (alpha(k) - alpha+(k)) + b(k).
std::vector<Vec6<double>> composite_bias(const Model& m, const State& x,
                                         const VecX<double>& beta_dot) {
  Workspace ws(m);
  VecX<double> T(m.nv());
  inverse_dynamics(m, x, beta_dot, {}, ws, T);
  std::vector<SpatialInertia> R(std::size_t(m.n()));
  soa::composite_inertias(m, ws, R);
  const Vec6<double> base =
      m.has_gravity() ? gravity_base_acceleration(m).vector() : Vec6<double>::Zero();
  std::vector<Vec6<double>> y;
  for (int k = 1; k <= m.n(); ++k) {
    const std::size_t j = std::size_t(k - 1);
    const Mat6 phi = ws.phi[j].matrix();  // phi(k+1,k)
    const Vec6<double> alpha_next = k < m.n() ? ws.alpha[j + 1].vector() : base;
    const Vec6<double> alpha_plus = phi.transpose() * alpha_next;
    Vec6<double> yk = R[j].matrix() * (ws.alpha[j].vector() - alpha_plus) +
                      gyroscopic_force(m.body(k).M, ws.V[j]).vector();
    if (k > 1) yk += ws.phi[j - 1].matrix() * y.back();
    y.push_back(yk);
  }
  return y;
}

// Lesson 6, sections 2-3: the stub's sweep with its bug fixed. P+(k) = tau_bar(k) P(k):
// tau_bar acts on forces, on the left (P tau_bar is neither symmetric nor H P+ = 0).
std::vector<Mat6> riccati_sweep(const Model& m, const VecX<double>& theta) {
  Workspace ws(m);
  update_phi(m, theta, ws);
  std::vector<Mat6> P(std::size_t(m.n()));
  Mat6 P_plus = Mat6::Zero();  // P+(0): nothing outboard of the tip
  for (int k = 1; k <= m.n(); ++k) {
    const Body& B = m.body(k);
    Mat6 Pk = B.M.matrix();
    if (k > 1) {
      const Mat6 phi = ws.phi[std::size_t(k - 2)].matrix();  // phi(k,k-1)
      Pk += phi * P_plus * phi.transpose();
    }
    const MatX<double> Hs = B.hinge.H_star(theta.data() + B.q_offset);
    const MatX<double> D = Hs.transpose() * Pk * Hs;
    const MatX<double> G = Pk * Hs * D.inverse();
    const Mat6 tau_bar = Mat6::Identity() - G * Hs.transpose();
    P_plus = tau_bar * Pk;
    P[std::size_t(k - 1)] = Pk;
  }
  return P;
}

// Lesson 6, section 3: P+(k) H*(k) = tau_bar P H* = G D - G D = 0, and P+(k) = tau_bar P has
// rank 6 - n_k when P(k) > 0: the null space of P+(k) is the range of H*(k). Accelerating
// body k+1 along hinge k's free directions moves nothing outboard: the hinge gives way.
std::vector<MatX<double>> P_plus_null_spaces(const Model& m, const VecX<double>& theta) {
  std::vector<MatX<double>> X;
  for (int k = 1; k <= m.n(); ++k)
    X.push_back(MatX<double>(m.body(k).hinge.H_star(theta.data() + m.body(k).q_offset)));
  return X;
}

// Lesson 6, section 2 at rest, no forces: z = 0, epsilon = T - H z = 0, nu = 0, so
// beta_dot(k) = -G*(k) alpha+(k) and alpha(k) = alpha+(k) + H* beta_dot(k) = tau_bar*(k)
// alpha+(k): base to tip, alpha(k) = psi*(k+1,k) alpha(k+1) from alpha(n+1) = [0; a0].
VecX<double> shaken_base(const Model& m, const VecX<double>& theta, const Vec3<double>& a0) {
  Workspace ws(m);
  update_phi(m, theta, ws);
  Articulated art(m);
  articulated_inertias(m, State{theta, VecX<double>::Zero(m.nv())}, ws, art);
  VecX<double> beta_dot(m.nv());
  Vec6<double> alpha;  // alpha(k+1)
  alpha << Vec3<double>::Zero(), a0;
  for (int k = m.n(); k >= 1; --k) {
    const Body& B = m.body(k);
    const std::size_t j = std::size_t(k - 1);
    const Vec6<double> alpha_plus = ws.phi[j].matrix().transpose() * alpha;
    const MatX<double> Hs = B.hinge.H_star(theta.data() + B.q_offset);
    const VecX<double> bd = -art.G[j].transpose() * alpha_plus;
    beta_dot.segment(B.v_offset, B.hinge.nv()) = bd;
    alpha = alpha_plus + Hs * bd;
  }
  return beta_dot;
}

}  // namespace soa::ex06
