// Lesson 3 exercises: replace each body with your code (statements in exercises.hpp).
#include "exercises.hpp"

#include "not_done.hpp"

namespace soa::ex03 {

Matrix6X joint_map(const Hinge& hinge, const VecX<double>& theta) {
  (void)hinge, (void)theta;
  throw exercise::NotDone("3.1 joint_map");
}

std::vector<Velocity> scatter_velocities(const std::vector<Phi>& phi,
                                         const std::vector<Velocity>& dV) {
  (void)phi, (void)dV;
  throw exercise::NotDone("3.2 scatter_velocities");
}

MatX<double> shift_operator(const std::vector<Phi>& phi) {
  (void)phi;
  throw exercise::NotDone("3.3 shift_operator");
}

MatX<double> phi_operator(const std::vector<Phi>& phi) {
  (void)phi;
  throw exercise::NotDone("3.4 phi_operator");
}

Matrix6X frame_jacobian(const Model& m, const VecX<double>& theta, int k, const Pose& frame) {
  (void)m, (void)theta, (void)k, (void)frame;
  throw exercise::NotDone("3.5 frame_jacobian");
}

Acceleration coriolis_acceleration(const Phi& phi, const Velocity& V_parent, const Velocity& dV,
                                   const Acceleration& Hdot_beta) {
  (void)phi, (void)V_parent, (void)dV, (void)Hdot_beta;
  throw exercise::NotDone("3.6 coriolis_acceleration");
}

}  // namespace soa::ex03
