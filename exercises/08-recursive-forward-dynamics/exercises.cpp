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

}  // namespace soa::ex08
