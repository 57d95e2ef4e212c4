// Lesson 4 exercises: replace each body with your code (statements in exercises.hpp).
#include "exercises.hpp"

#include "not_done.hpp"

namespace soa::ex04 {

Gathered gather_forces(const Model& m, const VecX<double>& theta, const std::vector<Phi>& phi,
                       const std::vector<Acceleration>& alpha, const std::vector<Force>& b) {
  (void)m, (void)theta, (void)phi, (void)alpha, (void)b;
  throw exercise::NotDone("4.1 gather_forces");
}

VecX<double> newton_euler(const Model& m, const State& x, const VecX<double>& beta_dot) {
  (void)m, (void)x, (void)beta_dot;
  throw exercise::NotDone("4.2 newton_euler");
}

MatX<double> mass_matrix_operators(const Operators& op) {
  (void)op;
  throw exercise::NotDone("4.3 mass_matrix_operators");
}

MatX<double> mass_matrix_columns(const Model& m, const VecX<double>& theta) {
  (void)m, (void)theta;
  throw exercise::NotDone("4.4 mass_matrix_columns");
}

VecX<double> bias_operators(const Operators& op) {
  (void)op;
  throw exercise::NotDone("4.5 bias_operators");
}

VecX<double> gravity_torques(const Model& m, const VecX<double>& theta) {
  (void)m, (void)theta;
  throw exercise::NotDone("4.6 gravity_torques");
}

MatX<double> coriolis_matrix_operators(const EnergyStructure& es) {
  (void)es;
  throw exercise::NotDone("4.7 coriolis_matrix_operators");
}

Acceleration helical_coriolis(const Vec3<double>& omega_parent, const Vec3<double>& l,
                              const Vec3<double>& axis, double pitch, double beta) {
  (void)omega_parent, (void)l, (void)axis, (void)pitch, (void)beta;
  throw exercise::NotDone("4.8 helical_coriolis");
}

VecX<double> gravity_torque_signs(const Model& m, const VecX<double>& theta) {
  (void)m, (void)theta;
  throw exercise::NotDone("4.9 gravity_torque_signs");
}

}  // namespace soa::ex04
