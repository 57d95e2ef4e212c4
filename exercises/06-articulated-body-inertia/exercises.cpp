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

}  // namespace soa::ex06
