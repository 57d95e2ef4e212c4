// Lesson 4 exercise tests: each exercise of exercises/04-serial-chain-dynamics/exercises.hpp
// against the library, on soa::test::kCases random chains (1 to 7 bodies, every hinge type
// unless the exercise is for revolute chains) from the fixed seed. Built against the
// solutions (ctest) and against the students' stubs (make exercises).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "exercises.hpp"
#include "property.hpp"
#include "random_chain.hpp"

namespace {

using soa::test::ChainOptions;
using soa::test::kCases;
using soa::test::Random;
using soa::test::Worst;
using VecX = soa::VecX<double>;
using MatX = soa::MatX<double>;

constexpr double kEps = soa::eps<double>();

// Case i has 1 + i mod 7 bodies before locked hinges merge.
int bodies(int i) {
  return 1 + i % 7;
}

// Per-body spatial vectors stacked tip first, as the operators lay them out.
template <class SV>
VecX stack(const std::vector<SV>& v) {
  VecX s(6 * Eigen::Index(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) s.segment<6>(6 * Eigen::Index(i)) = v[i].vector();
  return s;
}

// Random external forces on every body (half the cases have none).
soa::ExternalForces<double> random_forces(Random<double>& rnd, const soa::Model& m, int i) {
  soa::ExternalForces<double> f_ext;
  if (i % 2 == 0) return f_ext;
  for (int k = 1; k <= m.n(); ++k) f_ext.push_back(rnd.force());
  return f_ext;
}

// The library's inverse dynamics: T, and the inter-body forces f in ws.
VecX library_T(const soa::Model& m, const soa::State& x, const VecX& beta_dot,
               const soa::ExternalForces<double>& f_ext, soa::Workspace& ws) {
  VecX T(m.nv());
  soa::inverse_dynamics(m, x, beta_dot, f_ext, ws, T);
  return T;
}

// The magnitude that rounding errors of T and f scale with: the inter-body forces.
double force_scale(const soa::Workspace& ws) {
  return std::max(1.0, stack(ws.f).norm());
}

}  // namespace

// 4.1: the gather sweep, given phi, alpha and b from the library's scatter sweep, against
// soa::inverse_dynamics (gravity and external forces included).
TEST(Exercise4_1_GatherForces, MatchesInverseDynamics) {
  Random<double> rnd;
  Worst w_f("f residual / |f|"), w_T("T residual / |f|");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = soa::test::random_chain(rnd, bodies(i), ChainOptions{true, true, false});
    const soa::State x = soa::test::random_state(rnd, m);
    const VecX beta_dot = soa::test::random_vector(rnd, m.nv());
    const soa::ExternalForces<double> f_ext = random_forces(rnd, m, i);
    soa::Workspace ws(m);
    soa::update_phi(m, x.theta, ws);
    soa::update_velocities(m, x, ws);
    soa::update_accelerations(m, x, beta_dot.data(), soa::gravity_base_acceleration(m), ws);
    std::vector<soa::Force> b;
    for (int k = 1; k <= m.n(); ++k) {
      soa::Force bk = soa::gyroscopic_force(m.body(k).M, ws.V[std::size_t(k - 1)]);
      if (!f_ext.empty()) bk -= f_ext[std::size_t(k - 1)];
      b.push_back(bk);
    }
    const soa::ex04::Gathered g = soa::ex04::gather_forces(m, x.theta, ws.phi, ws.alpha, b);
    ASSERT_EQ(int(g.f.size()), m.n()) << "one f(k) per body";
    ASSERT_EQ(int(g.T.size()), m.nv()) << "T has one entry per degree of freedom";
    soa::Workspace ref(m);
    const VecX T = library_T(m, x, beta_dot, f_ext, ref);
    const double scale = force_scale(ref);
    w_f.add((stack(g.f) - stack(ref.f)).norm() / scale, i);
    w_T.add((g.T - T).norm() / scale, i);
  }
  EXPECT_LE(w_f.value(), 64 * kEps);
  EXPECT_LE(w_T.value(), 64 * kEps);
}

// 4.2: Newton-Euler inverse dynamics of random revolute chains with gravity, against
// soa::inverse_dynamics.
TEST(Exercise4_2_NewtonEuler, MatchesInverseDynamics) {
  Random<double> rnd;
  Worst w_T("T residual / |f|");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m =
        soa::test::random_chain(rnd, bodies(i), ChainOptions{false, i % 4 != 0, false});
    const soa::State x = soa::test::random_state(rnd, m);
    const VecX beta_dot = soa::test::random_vector(rnd, m.nv());
    const VecX T = soa::ex04::newton_euler(m, x, beta_dot);
    ASSERT_EQ(int(T.size()), m.nv()) << "T has one entry per degree of freedom";
    soa::Workspace ref(m);
    const VecX T_ref = library_T(m, x, beta_dot, {}, ref);
    w_T.add((T - T_ref).norm() / force_scale(ref), i);
  }
  EXPECT_LE(w_T.value(), 64 * kEps);
}

// 4.3: H phi M phi* H* with phi computed from E_phi (op.phi is zeroed), against
// soa::OperatorsT::mass_matrix().
TEST(Exercise4_3_MassMatrixOperators, MatchesOperators) {
  Random<double> rnd;
  Worst w_M("M residual / |M|");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = soa::test::random_chain(rnd, bodies(i), ChainOptions{true, true, false});
    const soa::State x = soa::test::random_state(rnd, m);
    soa::Operators op = soa::Operators::build(m, x);
    const MatX M_ref = op.mass_matrix();
    op.phi.setZero();
    const MatX M = soa::ex04::mass_matrix_operators(op);
    ASSERT_EQ(M.rows(), m.nv());
    ASSERT_EQ(M.cols(), m.nv());
    w_M.add((M - M_ref).norm() / M_ref.norm(), i);
  }
  EXPECT_LE(w_M.value(), 64 * kEps);
}

// 4.4: the mass matrix from nv + 1 inverse dynamics calls (gravity and springs in the model),
// against soa::OperatorsT::mass_matrix().
TEST(Exercise4_4_MassMatrixColumns, MatchesOperators) {
  Random<double> rnd;
  Worst w_M("M residual / (|M| + |T(0)|)");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = soa::test::random_chain(rnd, bodies(i), ChainOptions{true, true, true});
    const soa::State x = soa::test::random_state(rnd, m);
    const MatX M = soa::ex04::mass_matrix_columns(m, x.theta);
    ASSERT_EQ(M.rows(), m.nv());
    ASSERT_EQ(M.cols(), m.nv());
    const soa::State rest{x.theta, VecX::Zero(m.nv())};
    const MatX M_ref = soa::Operators::build(m, rest).mass_matrix();
    // Column j is a difference of two inverse dynamics results: rounding scales with the
    // forces of the static part T(0) (gravity, springs) as well as with M.
    soa::Workspace ws(m);
    library_T(m, rest, VecX::Zero(m.nv()), {}, ws);
    w_M.add((M - M_ref).norm() / (M_ref.norm() + force_scale(ws)), i);
  }
  EXPECT_LE(w_M.value(), 64 * kEps);
}

// 4.5: C = H phi (M phi* a + b) with phi from E_phi (op.phi zeroed), against the O(N)
// soa::inverse_dynamics at beta_dot = 0 (gravity and external forces included).
TEST(Exercise4_5_BiasOperators, MatchesInverseDynamics) {
  Random<double> rnd;
  Worst w_C("C residual / |f|");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = soa::test::random_chain(rnd, bodies(i), ChainOptions{true, true, false});
    const soa::State x = soa::test::random_state(rnd, m);
    const soa::ExternalForces<double> f_ext = random_forces(rnd, m, i);
    soa::Operators op = soa::Operators::build(m, x, f_ext);
    op.phi.setZero();
    const VecX C = soa::ex04::bias_operators(op);
    ASSERT_EQ(int(C.size()), m.nv());
    soa::Workspace ref(m);
    const VecX C_ref = library_T(m, x, VecX::Zero(m.nv()), f_ext, ref);
    w_C.add((C - C_ref).norm() / force_scale(ref), i);
  }
  EXPECT_LE(w_C.value(), 64 * kEps);
}

// 4.6: gravity torques from the Jacobians of the centres of mass, against
// soa::inverse_dynamics at rest with gravity.
TEST(Exercise4_6_GravityTorques, MatchesInverseDynamics) {
  Random<double> rnd;
  Worst w_G("G residual / |f|");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = soa::test::random_chain(rnd, bodies(i), ChainOptions{true, true, false});
    const soa::State x = soa::test::random_state(rnd, m);
    const VecX G = soa::ex04::gravity_torques(m, x.theta);
    ASSERT_EQ(int(G.size()), m.nv());
    soa::Workspace ref(m);
    const VecX G_ref =
        library_T(m, soa::State{x.theta, VecX::Zero(m.nv())}, VecX::Zero(m.nv()), {}, ref);
    w_G.add((G - G_ref).norm() / force_scale(ref), i);
  }
  EXPECT_LE(w_G.value(), 64 * kEps);
}

// 4.7: the Coriolis matrix from the operators, against soa::EnergyStructureT::coriolis_matrix()
// and, independently, C_v beta against the O(N) inverse dynamics at beta_dot = 0 without
// gravity. Rounding scales with the terms |B|^2 (|M| |Delta_bar| |phi| + |h_breve|).
TEST(Exercise4_7_CoriolisMatrixOperators, MatchesLibraryAndInverseDynamics) {
  Random<double> rnd;
  Worst w_C("C_v residual / terms"), w_Cb("C_v beta residual / (terms |beta|)");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = soa::test::random_chain(rnd, bodies(i));
    const soa::State x = soa::test::random_state(rnd, m);
    const soa::EnergyStructure es = soa::EnergyStructure::build(m, x);
    const MatX C = soa::ex04::coriolis_matrix_operators(es);
    ASSERT_EQ(C.rows(), m.nv());
    ASSERT_EQ(C.cols(), m.nv());
    const MatX B = es.B();
    const double terms = std::max(
        1e-300, B.squaredNorm() * (es.op.M.norm() * es.Delta_bar.norm() * es.op.phi.norm() +
                                   es.op.M.norm() * es.H_dot.norm() / std::max(1e-300, B.norm()) +
                                   es.h_breve.norm()));
    w_C.add((C - es.coriolis_matrix()).norm() / terms, i);
    soa::Workspace ws(m);
    const VecX C0 = library_T(m, x, VecX::Zero(m.nv()), {}, ws);
    w_Cb.add((C * x.beta - C0).norm() / (terms * x.beta.norm()), i);
  }
  EXPECT_LE(w_C.value(), 64 * kEps);
  EXPECT_LE(w_Cb.value(), 64 * kEps);
}
