// Lesson 5 exercises: replace each body with your code (statements in exercises.hpp).
#include "exercises.hpp"

#include "not_done.hpp"

namespace soa::ex05 {

std::vector<SpatialInertia> composite_inertias(const Model& m, const std::vector<Phi>& phi) {
  (void)m, (void)phi;
  throw exercise::NotDone("5.1 composite_inertias");
}

MatX<double> mass_matrix_diagonal(const Model& m, const VecX<double>& theta,
                                  const std::vector<SpatialInertia>& R, int k) {
  (void)m, (void)theta, (void)R, (void)k;
  throw exercise::NotDone("5.2 mass_matrix_diagonal");
}

MatX<double> crb_mass_matrix_revolute(const Model& m, const VecX<double>& theta) {
  (void)m, (void)theta;
  throw exercise::NotDone("5.3 crb_mass_matrix_revolute");
}

MatX<double> decomposition(const Operators& op) {
  (void)op;
  throw exercise::NotDone("5.4 decomposition");
}

Mat6<double> phi_M_phi_star_block(const std::vector<Phi>& phi, const std::vector<SpatialInertia>& R,
                                  int i, int j) {
  (void)phi, (void)R, (void)i, (void)j;
  throw exercise::NotDone("5.5 phi_M_phi_star_block");
}

MatX<double> slider_mass_matrix(const std::vector<double>& mass,
                                const std::vector<Vec3<double>>& axis) {
  (void)mass, (void)axis;
  throw exercise::NotDone("5.6 slider_mass_matrix");
}

MatX<double> mass_matrix_column(const Model& m, const VecX<double>& theta,
                                const std::vector<Phi>& phi, const std::vector<SpatialInertia>& R,
                                int j) {
  (void)m, (void)theta, (void)phi, (void)R, (void)j;
  throw exercise::NotDone("5.7 mass_matrix_column");
}

}  // namespace soa::ex05
