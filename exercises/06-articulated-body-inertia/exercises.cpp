// Lesson 6 exercises: replace each body with your code (statements in exercises.hpp).
#include "exercises.hpp"

#include "not_done.hpp"

namespace soa::ex06 {

RiccatiStep riccati_step(const Mat6& P_plus_prev, const Phi& phi, const SpatialInertia& M,
                         const MatX<double>& H_star) {
  (void)P_plus_prev, (void)phi, (void)M, (void)H_star;
  throw exercise::NotDone("6.1 riccati_step");
}

Mat6 tau_bar(const Mat6& P, const MatX<double>& H_star) {
  (void)P, (void)H_star;
  throw exercise::NotDone("6.2 tau_bar");
}

VecX<double> revolute_D(const Model& m, const VecX<double>& theta) {
  (void)m, (void)theta;
  throw exercise::NotDone("6.3 revolute_D");
}

Mat6 transform_symmetric(const Phi& phi, const Mat6& P) {
  (void)phi, (void)P;
  throw exercise::NotDone("6.4 transform_symmetric");
}

std::vector<Vec6<double>> articulated_forces(const Model& m, const State& x,
                                             const VecX<double>& T) {
  (void)m, (void)x, (void)T;
  throw exercise::NotDone("6.5 articulated_forces");
}

std::vector<Vec6<double>> composite_bias(const Model& m, const State& x,
                                         const VecX<double>& beta_dot) {
  (void)m, (void)x, (void)beta_dot;
  throw exercise::NotDone("6.6 composite_bias");
}

std::vector<Mat6> riccati_sweep(const Model& m, const VecX<double>& theta) {
  throw exercise::NotDone("6.7 riccati_sweep");
  // The code below has one bug. Find it, fix it, and delete the throw above.
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
    P_plus = Pk * tau_bar;
    P[std::size_t(k - 1)] = Pk;
  }
  return P;
}

std::vector<MatX<double>> P_plus_null_spaces(const Model& m, const VecX<double>& theta) {
  (void)m, (void)theta;
  throw exercise::NotDone("6.8 P_plus_null_spaces");
}

VecX<double> shaken_base(const Model& m, const VecX<double>& theta, const Vec3<double>& a0) {
  (void)m, (void)theta, (void)a0;
  throw exercise::NotDone("6.9 shaken_base");
}

}  // namespace soa::ex06
