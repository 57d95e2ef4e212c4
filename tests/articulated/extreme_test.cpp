// Property tests of the extreme chains of lesson 6 (section 7): on soa::test::kCases random
// chains from the fixed seed whose masses alternate heavy (1) and light (1e-8), heavy or light
// first, with point-like bodies (isotropic rotational inertia 1e-9 to 1e-6 about a centre of
// mass offset from the hinge), n <= 100,
// - the mass matrix from the composite inertias (soa::mass_matrix_crb) equals the operator
//   form H phi M phi* H* (soa::OperatorsT::mass_matrix), relative to the largest entry, to
//   c n eps: the extreme masses cost no accuracy;
// - a massless tip is diagnosed: soa::articulated_inertias throws soa::Error naming the tip
//   and D(1);
// - a massless body inside a straight chain of point masses (every axis parallel, theta = 0)
//   is diagnosed at that body: the stretched outboard chain gives its hinge nothing to move.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "property.hpp"
#include "random_chain.hpp"
#include "soa/chain.hpp"
#include "soa/soa.hpp"

namespace {

using soa::test::kCases;
using soa::test::Random;
using soa::test::Worst;
using MatX = soa::MatX<double>;
using Vec3 = soa::Vec3<double>;
using Mat3 = soa::Mat3<double>;

constexpr double kEps = soa::eps<double>();

// n of case i: mostly short chains, every 100th one of 100 bodies.
int bodies(int i) {
  return i % 100 == 99 ? 100 : 1 + i % 25;
}

// A random chain of every hinge type whose masses alternate 1 and 1e-8 (heavy first for even
// i), each body a point-like body: its centre of mass where random_chain put it, isotropic
// rotational inertia 10^u, u uniform in [-9, -6].
soa::Model extreme_chain(Random<double>& rnd, int i) {
  soa::Model m = soa::test::random_chain(rnd, bodies(i));
  for (int k = 1; k <= m.n(); ++k) {
    const bool heavy = (k % 2 == 0) == (i % 2 == 0);
    const double mass = heavy ? 1.0 : 1e-8;
    const double J = std::pow(10.0, rnd.uniform(-9, -6));
    soa::Body& B = m.body(k);
    B.M = soa::SpatialInertia::from_cm(mass, B.M.h() / B.M.mass(), J * Mat3::Identity());
  }
  return m;
}

TEST(articulated_Extreme, MassMatrixFromRMatchesOperatorForm) {
  Random<double> rnd;
  Worst worst("max|M_R - H phi M phi* H*| / (max M(k,k) n eps)");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = extreme_chain(rnd, i);
    const soa::State x = soa::test::random_state(rnd, m);
    soa::Workspace ws(m);
    soa::update_phi(m, x.theta, ws);
    std::vector<soa::SpatialInertia> R(static_cast<std::size_t>(m.n()));
    MatX M;
    soa::mass_matrix_crb(m, x, ws, R, M);
    const MatX M_op = soa::Operators::build(m, x, {}).mass_matrix();
    const double scale = M.diagonal().maxCoeff();
    ASSERT_GT(scale, 0) << "case " << i;
    const double residual = (M - M_op).cwiseAbs().maxCoeff() / (scale * m.n() * kEps);
    worst.add(residual, i);
    // Each entry: at most n terms of total size <= max M(k,k), each through <= n steps of phi;
    // the random placements (offsets ~ N(0,1) per axis) make the lever arms a few units.
    ASSERT_LE(residual, 64.0) << "case " << i << ", n = " << m.n();
  }
}

TEST(articulated_Extreme, MasslessTipIsDiagnosed) {
  Random<double> rnd(soa::test::kSeed + 1);
  int thrown = 0;
  for (int i = 0; i < kCases; ++i) {
    soa::Model m = extreme_chain(rnd, i);
    m.body(1).M = soa::SpatialInertia();  // massless tip: D(1) = M(1,1) = 0
    const soa::State x = soa::test::random_state(rnd, m);
    soa::Workspace ws(m);
    soa::update_phi(m, x.theta, ws);
    soa::Articulated art(m);
    try {
      soa::articulated_inertias(m, x, ws, art);
      ADD_FAILURE() << "case " << i << ": no soa::Error for a massless tip";
    } catch (const soa::Error& e) {
      const std::string expected =
          "body '" + m.body(1).name + "': articulated inertia D(1) singular";
      ASSERT_EQ(std::string(e.what()).rfind(expected, 0), 0u) << "case " << i << ": " << e.what();
      ++thrown;
    }
  }
  EXPECT_EQ(thrown, kCases);
}

// A straight chain along x of n revolute hinges about z (theta = 0), random link lengths L,
// point masses (no rotational inertia) of mass in [0.5, 2] at a fraction r/L in [0.5, 0.8] of
// each link, with body k_massless massless. Exactly, the articulated inertia a pin passes on
// has no mass across the links (the point masses can stay put while the links turn), so a
// massless body's hinge moves nothing: D(k) = 0. In rounding, that transverse mass p obeys
// p' = m p (L - r)^2 / (m r^2 + p L^2) from one body to the next, which damps p for r >= L/2
// and would amplify it by up to ((L - r)/r)^2 per link for r < L/2 (there zero is an unstable
// fixed point; a rotational inertia as small as the rounding then decides D(k)).
soa::Model straight_point_chain(Random<double>& rnd, int n, int k_massless) {
  std::vector<soa::Body> base_first(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {  // j = 0 next to the base: course number n - j
    const int k = n - j;
    const double length = rnd.uniform(0.5, 2.0);
    soa::Body& b = base_first[std::size_t(j)];
    b.name = "link" + std::to_string(k);
    if (k != k_massless)
      b.M = soa::SpatialInertia::from_cm(rnd.uniform(0.5, 2.0),
                                         Vec3(rnd.uniform(0.5, 0.8) * length, 0, 0), Mat3::Zero());
    b.placement = soa::Pose(Mat3::Identity(), j == 0 ? Vec3::Zero() : Vec3(length, 0, 0));
    b.hinge.type = soa::HingeType::Revolute;
    b.hinge.axis = Vec3::UnitZ();
  }
  return soa::Model::from_base_first(std::move(base_first));
}

TEST(articulated_Extreme, MasslessBodyInStraightChainIsDiagnosedAtThatBody) {
  Random<double> rnd(soa::test::kSeed + 2);
  int thrown = 0;
  for (int i = 0; i < kCases; ++i) {
    const int n = 2 + i % 19;
    const int k = 2 + int(rnd.uniform(0, n - 1 - 1e-9));  // 2..n: inboard of the tip
    const soa::Model m = straight_point_chain(rnd, n, k);
    const soa::State x = soa::State::rest(m);
    soa::Workspace ws(m);
    soa::update_phi(m, x.theta, ws);
    soa::Articulated art(m);
    try {
      soa::articulated_inertias(m, x, ws, art);
      ADD_FAILURE() << "case " << i << ": no soa::Error for massless body " << k << " of " << n;
    } catch (const soa::Error& e) {
      const std::string expected = "body 'link" + std::to_string(k) + "': articulated inertia D(" +
                                   std::to_string(k) + ") singular";
      ASSERT_EQ(std::string(e.what()).rfind(expected, 0), 0u) << "case " << i << ": " << e.what();
      ++thrown;
    }
  }
  EXPECT_EQ(thrown, kCases);
}

}  // namespace
