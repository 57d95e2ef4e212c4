// A probe "student" for the test of the forbidden-call watch (exercises.watch-probe): its
// 4.2 gives the right answer by calling soa::inverse_dynamics, which 4.2 forbids, and its 4.4
// calls soa::inverse_dynamics too, which 4.4 allows. The watch must fail 4.2 alone. (Every
// function of exercises/04-*/exercises.hpp needs a definition here.)
#include "exercises.hpp"
#include "not_done.hpp"

namespace soa::ex04 {

Gathered gather_forces(const Model&, const VecX<double>&, const std::vector<Phi>&,
                       const std::vector<Acceleration>&, const std::vector<Force>&) {
  throw exercise::NotDone("4.1");
}

VecX<double> newton_euler(const Model& m, const State& x, const VecX<double>& beta_dot) {
  Workspace ws(m);
  VecX<double> T(m.nv());
  inverse_dynamics(m, x, beta_dot, {}, ws, T);
  return T;
}

MatX<double> mass_matrix_operators(const Operators&) {
  throw exercise::NotDone("4.3");
}

MatX<double> mass_matrix_columns(const Model& m, const VecX<double>& theta) {
  const int nv = m.nv();
  const State x{theta, VecX<double>::Zero(nv)};
  Workspace ws(m);
  VecX<double> beta_dot = VecX<double>::Zero(nv), T0(nv), Tj(nv);
  inverse_dynamics(m, x, beta_dot, {}, ws, T0);
  MatX<double> M(nv, nv);
  for (int j = 0; j < nv; ++j) {
    beta_dot.setUnit(j);
    inverse_dynamics(m, x, beta_dot, {}, ws, Tj);
    M.col(j) = Tj - T0;
  }
  return M;
}

VecX<double> bias_operators(const Operators&) {
  throw exercise::NotDone("4.5");
}

VecX<double> gravity_torques(const Model&, const VecX<double>&) {
  throw exercise::NotDone("4.6");
}

MatX<double> coriolis_matrix_operators(const EnergyStructure&) {
  throw exercise::NotDone("4.7");
}

Acceleration helical_coriolis(const Vec3<double>&, const Vec3<double>&, const Vec3<double>&, double,
                              double) {
  throw exercise::NotDone("4.8");
}

VecX<double> gravity_torque_signs(const Model&, const VecX<double>&) {
  throw exercise::NotDone("4.9");
}

}  // namespace soa::ex04
