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

}  // namespace soa::ex07
