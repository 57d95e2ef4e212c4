// Lesson 2 exercise tests: each exercise of exercises/02-single-rigid-body/exercises.hpp
// against the library, on soa::test::kCases random cases from the fixed seed. Built against
// the solutions (ctest) and against the students' stubs (make exercises).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "exercises.hpp"
#include "property.hpp"

namespace {

using soa::test::kCases;
using soa::test::Random;
using soa::test::Worst;
using V3 = soa::Vec3<double>;

constexpr double kEps = soa::eps<double>();

// The condition number of M(x), the amplification of rounding in a solve with it.
double condition(const soa::SpatialInertia& M) {
  const Eigen::SelfAdjointEigenSolver<soa::Mat6<double>> eig(M.matrix());
  return eig.eigenvalues().maxCoeff() / eig.eigenvalues().minCoeff();
}

// The scale of the terms of b(x): |J(x)| |w|^2 + m |w|^2 |p(x)|.
double b_scale(const soa::SpatialInertia& M, const soa::Velocity& V) {
  const double w2 = V.angular().squaredNorm();
  return M.J().norm() * w2 + M.mass() * w2 * M.p().norm();
}

// A random free-body state: any attitude, position and velocity.
soa::FreeBodyState random_state(Random<double>& rng) {
  soa::FreeBodyState x;
  x.q = soa::UnitQuaternion(rng.vec3(), rng.normal());
  x.r = rng.vec3();
  x.V = rng.velocity();
  return x;
}

}  // namespace

// 2.1: b(x) = [w~ J(x) w; m w~ w~ p(x)], against soa::gyroscopic_force.
TEST(Exercise2_1_GyroscopicTerm, MatchesLibrary) {
  Random<double> rng;
  Worst worst("b(x) residual / scale");
  for (int i = 0; i < kCases; ++i) {
    const soa::SpatialInertia M = rng.inertia();
    const soa::Velocity V = rng.velocity();
    const soa::Force b = soa::ex02::gyroscopic_term(M, V);
    const soa::Force ref = soa::gyroscopic_force(M, V);
    worst.add((b - ref).vector().norm() / std::max(1.0, b_scale(M, V)), i);
  }
  EXPECT_LE(worst.value(), 32 * kEps);
}

// 2.2: f(x) through C, against soa::rigid_body_force = M(x) alpha(x) + b(x).
TEST(Exercise2_2_SpatialForce, MatchesLibrary) {
  Random<double> rng;
  Worst worst("f(x) residual / scale");
  for (int i = 0; i < kCases; ++i) {
    const soa::SpatialInertia M = rng.inertia();
    const soa::Velocity V = rng.velocity();
    const soa::Acceleration alpha = rng.acceleration();
    const soa::Force f = soa::ex02::spatial_force(M.mass(), M.J_cm(), M.p(), V, alpha);
    const soa::Force ref = soa::rigid_body_force(M, V, alpha);
    const double scale = M.matrix().norm() * alpha.vector().norm() + b_scale(M, V);
    worst.add((f - ref).vector().norm() / std::max(1.0, scale), i);
  }
  EXPECT_LE(worst.value(), 64 * kEps);
}

// 2.3: the free-body rates, against soa::free_body_rate (with an applied force).
TEST(Exercise2_3_BodyRates, MatchesLibrary) {
  Random<double> rng;
  Worst w_omega("omega residual"), w_r("r_dot residual"), w_V("V_dot residual / (cond eps)");
  for (int i = 0; i < kCases; ++i) {
    const soa::SpatialInertia M = rng.inertia();
    const soa::FreeBodyState x = random_state(rng);
    const soa::Force f = rng.force();
    const auto d = soa::ex02::body_rates(M, x, f);
    const auto ref = soa::free_body_rate(M, x, f);
    w_omega.add(soa::test::rel(d.omega, ref.omega), i);
    w_r.add(soa::test::rel(d.r_dot, ref.r_dot), i);
    w_V.add(soa::test::rel(d.V_dot, ref.V_dot) / (condition(M) * kEps), i);
  }
  EXPECT_LE(w_omega.value(), 0.0);
  EXPECT_LE(w_r.value(), 16 * kEps);
  EXPECT_LE(w_V.value(), 64.0);
}

// 2.4: one torque-free Lie-group RK4 step, against soa::rk4_step. The steps are large enough
// (h |w| up to ~0.5) that a different fourth-order scheme would differ by far more than rounding.
TEST(Exercise2_4_Rk4Step, MatchesLibrary) {
  Random<double> rng;
  Worst w_q("q residual / (cond eps)"), w_r("r residual / (cond eps)"),
      w_V("V residual / (cond eps)"), w_unit("||q| - 1|");
  for (int i = 0; i < kCases; ++i) {
    const soa::SpatialInertia M = rng.inertia();
    const soa::FreeBodyState x0 = random_state(rng);
    const double h = rng.uniform(0.05, 0.2);
    const soa::FreeBodyState x1 = soa::ex02::rk4_torque_free(M, x0, h);
    const soa::FreeBodyState ref = soa::rk4_step(M, x0, h);
    const double unit = condition(M) * kEps;
    // q and -q are the same attitude.
    const double dq =
        std::min((x1.q.coeffs() - ref.q.coeffs()).norm(), (x1.q.coeffs() + ref.q.coeffs()).norm());
    w_q.add(dq / unit, i);
    w_r.add(soa::test::rel(x1.r, ref.r) / unit, i);
    w_V.add(soa::test::rel(x1.V.vector(), ref.V.vector()) / unit, i);
    w_unit.add(std::abs(x1.q.coeffs().norm() - 1), i);
  }
  EXPECT_LE(w_q.value(), 64.0);
  EXPECT_LE(w_r.value(), 64.0);
  EXPECT_LE(w_V.value(), 64.0);
  EXPECT_LE(w_unit.value(), 4 * kEps);
}

// 2.5: the body-frame form f = M V_dot + V-bar M V, against soa::rigid_body_force at the
// inertial derivative alpha = [w_dot; v_dot + w x v] (lesson 2, section 4).
TEST(Exercise2_5_BodyFrameForce, MatchesLibrary) {
  Random<double> rng;
  Worst worst("f(x) residual / scale");
  for (int i = 0; i < kCases; ++i) {
    const soa::SpatialInertia M = rng.inertia();
    const soa::Velocity V = rng.velocity();
    const soa::Acceleration V_dot = rng.acceleration();
    const V3 w = V.angular(), v = V.linear();
    const soa::Acceleration alpha(V_dot.angular(), V3(V_dot.linear()) + w.cross(v));
    const soa::Force f = soa::ex02::body_frame_force(M, V, V_dot);
    const soa::Force ref = soa::rigid_body_force(M, V, alpha);
    // The terms: M V_dot, and V-bar M V with |V-bar| <= |V| (w x v moves into alpha).
    const double scale = M.matrix().norm() * (V_dot.vector().norm() + V.vector().squaredNorm());
    worst.add((f - ref).vector().norm() / std::max(1.0, scale), i);
  }
  EXPECT_LE(worst.value(), 64 * kEps);
}
