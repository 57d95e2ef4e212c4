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

VecX beta_from_eta(const Model& m, const State& x, const VecX& eta) {
  throw exercise::NotDone("7.12 beta_from_eta");
  // The code below has one bug. Find it, fix it, delete the throw line above, and say here
  // what was wrong.
  Workspace ws(m);
  update_phi(m, x.theta, ws);
  Articulated art(m);
  articulated_inertias(m, x, ws, art);
  VecX beta(m.nv());
  Velocity V = Velocity::Zero();  // V(k+1), zero beyond the base
  for (int k = m.n(); k >= 1; --k) {
    const Body& B = m.body(k);
    const int o = B.v_offset, nk = B.hinge.nv();
    const MatX Hs = B.hinge.H_star(x.theta.data() + B.q_offset);  // H*(k), 6 x n_k
    // phi*(k+1,k) V(k+1): the velocity of body k+1, moved to O_k.
    const Velocity V_plus = k < m.n() ? ws.phi[k - 1].transpose_apply(V) : Velocity::Zero();
    const VecX eta_k = eta.segment(o, nk);
    // eta(k) = G*(k) V(k) = G*(k) V_plus + beta(k), since G*(k) H*(k) = I.
    const VecX beta_k = eta_k - MatX(art.G[std::size_t(k - 1)]).transpose() * V_plus.vector();
    beta.segment(o, nk) = beta_k;
    V = Velocity(Vec6<double>(V_plus.vector() + Hs * eta_k));  // V(k)
  }
  return beta;
}

}  // namespace soa::ex07
