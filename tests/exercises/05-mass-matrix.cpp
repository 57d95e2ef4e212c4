// Lesson 5 exercise tests: each exercise of exercises/05-mass-matrix/exercises.hpp against the
// library, on soa::test::kCases random chains (1 to 9 bodies, every hinge type unless the
// exercise is for revolute chains) from the fixed seed. Built against the solutions (ctest)
// and against the students' stubs (make exercises).
#include <gtest/gtest.h>

#include <algorithm>
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

// Case i has 1 + i mod 9 bodies before locked hinges merge.
int bodies(int i) {
  return 1 + i % 9;
}

}  // namespace

// 5.1: the composite inertias from phi, against soa::composite_inertias.
TEST(Exercise5_1_CompositeInertias, MatchesLibrary) {
  Random<double> rnd;
  Worst w("R(k) residual / |R(k)|");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = soa::test::random_chain(rnd, bodies(i));
    const soa::State x = soa::test::random_state(rnd, m);
    soa::Workspace ws(m);
    soa::update_phi(m, x.theta, ws);
    const std::vector<soa::SpatialInertia> R = soa::ex05::composite_inertias(m, ws.phi);
    ASSERT_EQ(int(R.size()), m.n()) << "one R(k) per body";
    std::vector<soa::SpatialInertia> R_ref(std::size_t(m.n()));
    soa::composite_inertias(m, ws, R_ref);
    double gap = 0;
    for (std::size_t k = 0; k < R.size(); ++k)
      gap = std::max(gap, (R[k].matrix() - R_ref[k].matrix()).norm() / R_ref[k].matrix().norm());
    w.add(gap, i);
  }
  EXPECT_LE(w.value(), 64 * kEps);
}

// 5.2: the diagonal blocks H(k) R(k) H*(k), against soa::OperatorsT::mass_matrix().
TEST(Exercise5_2_MassMatrixDiagonal, MatchesOperators) {
  Random<double> rnd;
  Worst w("M(k,k) residual / |M|");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = soa::test::random_chain(rnd, bodies(i));
    const soa::State x = soa::test::random_state(rnd, m);
    soa::Workspace ws(m);
    soa::update_phi(m, x.theta, ws);
    std::vector<soa::SpatialInertia> R(std::size_t(m.n()));
    soa::composite_inertias(m, ws, R);
    const MatX M_ref = soa::Operators::build(m, x).mass_matrix();
    double gap = 0;
    for (int k = 1; k <= m.n(); ++k) {
      const soa::Body& B = m.body(k);
      const MatX Mkk = soa::ex05::mass_matrix_diagonal(m, x.theta, R, k);
      ASSERT_EQ(Mkk.rows(), B.hinge.nv());
      ASSERT_EQ(Mkk.cols(), B.hinge.nv());
      const MatX ref = M_ref.block(B.v_offset, B.v_offset, B.hinge.nv(), B.hinge.nv());
      gap = std::max(gap, (Mkk - ref).norm() / M_ref.norm());
    }
    w.add(gap, i);
  }
  EXPECT_LE(w.value(), 64 * kEps);
}

// 5.3: the CRB mass matrix of random revolute chains, against
// soa::OperatorsT::mass_matrix().
TEST(Exercise5_3_CrbMassMatrixRevolute, MatchesOperators) {
  Random<double> rnd;
  Worst w("M residual / |M|");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = soa::test::random_chain(rnd, bodies(i), ChainOptions{false, false, false});
    const soa::State x = soa::test::random_state(rnd, m);
    const MatX M = soa::ex05::crb_mass_matrix_revolute(m, x.theta);
    ASSERT_EQ(M.rows(), m.nv());
    ASSERT_EQ(M.cols(), m.nv());
    const MatX M_ref = soa::Operators::build(m, x).mass_matrix();
    w.add((M - M_ref).norm() / M_ref.norm(), i);
  }
  EXPECT_LE(w.value(), 64 * kEps);
}

// 5.4: R + phi~ R + R phi~* from the block Lyapunov recursion, against phi M phi*.
TEST(Exercise5_4_Decomposition, MatchesPhiMPhiStar) {
  Random<double> rnd;
  Worst w("R + phi~ R + R phi~* residual / |phi M phi*|");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = soa::test::random_chain(rnd, bodies(i));
    const soa::State x = soa::test::random_state(rnd, m);
    const soa::Operators op = soa::Operators::build(m, x);
    const MatX D = soa::ex05::decomposition(op);
    ASSERT_EQ(D.rows(), op.M.rows());
    ASSERT_EQ(D.cols(), op.M.cols());
    const MatX ref = op.phi * op.M * op.phi.transpose();
    w.add((D - ref).norm() / ref.norm(), i);
  }
  EXPECT_LE(w.value(), 64 * kEps);
}
