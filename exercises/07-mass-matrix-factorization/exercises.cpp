// Lesson 7 exercises: replace each body with your code (statements in exercises.hpp).
#include "exercises.hpp"

#include "not_done.hpp"

namespace soa::ex07 {

KAndPsi k_and_psi(const Model& m, const State& x) {
  (void)m, (void)x;
  throw exercise::NotDone("7.1 k_and_psi");
}

InnovationsFactor innovations_factor(const Model& m, const State& x) {
  (void)m, (void)x;
  throw exercise::NotDone("7.2 innovations_factor");
}

std::vector<MatX> minv_diagonal(const Model& m, const State& x) {
  (void)m, (void)x;
  throw exercise::NotDone("7.3 minv_diagonal");
}

VecX solve(const Model& m, const State& x, const VecX& b) {
  (void)m, (void)x, (void)b;
  throw exercise::NotDone("7.4 solve");
}

double log_det_mass_matrix(const Model& m, const State& x) {
  (void)m, (void)x;
  throw exercise::NotDone("7.5 log_det_mass_matrix");
}

MatX omega_from_upsilon(const Model& m, const State& x) {
  (void)m, (void)x;
  throw exercise::NotDone("7.6 omega_from_upsilon");
}

MatX minv_from_upsilon(const Model& m, const State& x) {
  (void)m, (void)x;
  throw exercise::NotDone("7.7 minv_from_upsilon");
}

soa::Mat6<double> operational_inverse_inertia(const Model& m, const State& x, int k,
                                              const Pose& frame) {
  (void)m, (void)x, (void)k, (void)frame;
  throw exercise::NotDone("7.8 operational_inverse_inertia");
}

VecX innovations_coordinates(const Model& m, const State& x) {
  (void)m, (void)x;
  throw exercise::NotDone("7.9 innovations_coordinates");
}

MatX minv_zero_pattern(const std::vector<HingeType>& hinges) {
  (void)hinges;
  throw exercise::NotDone("7.10 minv_zero_pattern");
}

MatX sweep_operator(const Model& m, const State& x) {
  (void)m, (void)x;
  throw exercise::NotDone("7.11 sweep_operator");
}

}  // namespace soa::ex07
