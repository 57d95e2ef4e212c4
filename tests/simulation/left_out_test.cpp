// "Pay only for what the scene uses": a part of the scene that is left out is skipped by
// soa::forward_dynamics() and so by every integrator of soa::StepperT, and the
// skipped result must be bitwise (==, so 0 and -0 count as equal) the result with the part
// present and zero. On random chains of every hinge type from the fixed seed, with gravity,
// external forces, springs and dampers on every hinge and random rates ("full"), each part
// is left out in turn and the forward dynamics and one step of each integrator (euler,
// symplectic-euler, rk4, dopri5 with its error estimate, implicit-midpoint) compared:
// - external forces: an empty list against a list of zero forces, for the five steps (the
//   forward dynamics alone is checked by dynamics_Forward.NoExternalForcesEqualsExplicitZeros
//   and an RK4 trajectory by simulation_LeftOut.NoExternalForcesEqualsExplicitZeros);
// - gravity: never set, (0, 0, 0), (-0, -0, -0) and a vector whose squared norm underflows
//   all fail ModelT::has_gravity() and so take the same path (the one with no gravity
//   pass); to compare that path with the gravity code, the gravity pass is also run with
//   \f$|g| = 2^{-500}\f$ (has_gravity() true), whose every contribution lies far below half
//   an ulp of the terms it is added to: the result must not change by a bit;
// - springs and dampers: stiffness and damping never set, set to 0 and to -0 (about random
//   rest positions) take the no-spring path of each hinge; the spring path itself is run
//   fed with exact zeros (every other hinge sprung and damped, at its rest position,
//   \f$\delta = 0\f$, with its own rate 0, the others moving) for the forward dynamics, and
//   with stiffness and damping \f$2^{-600}\f$ for the steps (which leave the rest position);
// - at rest: beta = 0 and beta = -0 skip the velocity terms; the moving path is run with
//   rates of size \f$2^{-600}\f$, whose velocity products underflow to zero.
// Each part must also change the result when present with its ordinary size (gravity
// 9.81, random forces, springs, random rates), or the comparison could not fail. Where
// implicit midpoint's Newton iteration fails on both sides (a few fast random chains) there
// is no step to compare; the failures must agree and stay under a tenth of the cases.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "property.hpp"
#include "random_chain.hpp"
#include "soa/soa.hpp"

namespace {

using soa::test::Random;
using soa::test::Worst;
using Model = soa::Model;
using State = soa::State;
using VecX = soa::VecX<double>;
using Forces = soa::ExternalForces<double>;

constexpr int kCases = soa::test::kCases;
constexpr double kStep = 0.01;
/// A size whose products with O(1) terms vanish when added to them, and whose products
/// with each other underflow to zero: 2^-600.
const double kTiny = std::ldexp(1.0, -600);

/// The forward dynamics, then one step of each integrator.
constexpr int kMethods = 6;
const std::array<const char*, kMethods> kMethodNames{
    "forward dynamics", "euler", "symplectic-euler", "rk4", "dopri5", "implicit-midpoint"};

/// What one scene gives: beta_dot, the state after one step of each integrator, dopri5's
/// error estimate and whether implicit midpoint's Newton iteration converged.
struct Outcome {
  VecX beta_dot;
  std::array<State, kMethods - 1> x1;
  VecX err;
  bool converged = false;
};

/// Runs the forward dynamics and one step of every integrator on the scene (m, f_ext) from
/// x, under the constant hinge forces T.
Outcome evaluate(const Model& m, const Forces& f_ext, const State& x, const VecX& T) {
  Outcome o;
  soa::Workspace ws(m);
  soa::ForwardDynamics fd(m);
  o.beta_dot.resize(m.nv());
  soa::forward_dynamics(m, x, T, f_ext, ws, fd, o.beta_dot);
  soa::ChainSystem sys(m, f_ext, [&T](double, const State&, VecX& out) { out = T; });
  soa::Stepper step(sys);
  for (State& x1 : o.x1) x1 = x;
  step.euler(0, kStep, x, o.x1[0]);
  step.symplectic_euler(0, kStep, x, o.x1[1]);
  step.rk4(0, kStep, x, o.x1[2]);
  step.dopri5(0, kStep, x, o.x1[3], o.err);
  o.converged = step.implicit_midpoint(0, kStep, x, o.x1[4]);
  return o;
}

/// The largest |a_i - b_i|: 0 when a == b entrywise (NaN equal to NaN), infinite when the
/// sizes differ or only one is NaN.
double difference(const VecX& a, const VecX& b) {
  if (a.size() != b.size()) return INFINITY;
  double d = 0;
  for (int i = 0; i < a.size(); ++i) {
    if (a[i] == b[i] || (std::isnan(a[i]) && std::isnan(b[i]))) continue;
    d = std::max(d, std::isnan(a[i] - b[i]) ? INFINITY : std::abs(a[i] - b[i]));
  }
  return d;
}

/// The difference of each method's result (the step's state; dopri5's error estimate too,
/// implicit midpoint's convergence flag). When implicit midpoint's Newton iteration fails
/// on both sides there is no step to compare: its entry is NaN.
std::array<double, kMethods> differences(const Outcome& a, const Outcome& b) {
  std::array<double, kMethods> d{};
  d[0] = difference(a.beta_dot, b.beta_dot);
  for (int j = 1; j < kMethods; ++j)
    d[j] = std::max(difference(a.x1[j - 1].theta, b.x1[j - 1].theta),
                    difference(a.x1[j - 1].beta, b.x1[j - 1].beta));
  d[4] = std::max(d[4], difference(a.err, b.err));
  if (a.converged != b.converged) d[5] = INFINITY;
  if (!a.converged && !b.converged) d[5] = NAN;
  return d;
}

/// The worst difference per method between left-out and explicit-zero versions (must be 0)
/// and the smallest between left-out and full versions (must not be 0), over all cases.
class Check {
 public:
  explicit Check(const std::string& part, bool with_fd = true) : with_fd_(with_fd) {
    for (int j = 0; j < kMethods; ++j) {
      same_.emplace_back(part + ": " + kMethodNames[j] + " |left out - zeros|");
      differ_[j] = INFINITY;
    }
  }
  /// \p left_out against a version with the part present and zero.
  void same(const Outcome& left_out, const Outcome& zeros, int i) {
    const auto d = differences(left_out, zeros);
    ++steps_;
    if (std::isnan(d[5])) ++failed_;
    for (int j = first(); j < kMethods; ++j)
      if (!std::isnan(d[j])) same_[j].add(d[j], i);
  }
  /// \p left_out against the version with the part present.
  void differ(const Outcome& left_out, const Outcome& full) {
    const auto d = differences(left_out, full);
    for (int j = first(); j < kMethods; ++j)
      if (!std::isnan(d[j])) differ_[j] = std::min(differ_[j], d[j]);
  }
  ~Check() {
    std::printf("[ midpoint ] Newton failed on both sides in %ld of %ld comparisons (skipped)\n",
                failed_, steps_);
    EXPECT_LT(failed_ * 10, steps_);
    for (int j = first(); j < kMethods; ++j) {
      EXPECT_EQ(same_[j].value(), 0.0) << kMethodNames[j];
      EXPECT_GT(differ_[j], 0.0) << kMethodNames[j] << ": the full version does not differ";
    }
  }

 private:
  int first() const { return with_fd_ ? 0 : 1; }
  bool with_fd_;
  std::vector<Worst> same_;
  std::array<double, kMethods> differ_{};
  long steps_ = 0, failed_ = 0;
};

/// Case i: a chain of 1..10 bodies of every hinge type with gravity, springs and dampers,
/// random external forces, a random moving state and random hinge forces.
struct Case {
  Model m;
  Forces f_ext;
  State x;
  VecX T;
  Case(Random<double>& rnd, int i) {
    soa::test::ChainOptions opt;
    opt.gravity = true;
    opt.springs = true;
    m = soa::test::random_chain(rnd, 1 + i % 10, opt);
    f_ext = soa::test::random_forces(rnd, m);
    x = soa::test::random_state(rnd, m);
    T = soa::test::random_vector(rnd, m.nv());
  }
};

/// The model without springs and dampers: stiffness and damping set to \p value.
Model with_springs(Model m, double value) {
  for (int k = 1; k <= m.n(); ++k) m.body(k).stiffness = m.body(k).damping = value;
  return m;
}

TEST(simulation_LeftOut, ExternalForcesEqualZeroForcesInEveryStep) {
  Random<double> rnd(601);
  Check check("no f_ext", false);
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const Outcome left_out = evaluate(c.m, {}, c.x, c.T);
    check.same(left_out, evaluate(c.m, Forces(std::size_t(c.m.n()), soa::Force::Zero()), c.x, c.T),
               i);
    check.differ(left_out, evaluate(c.m, c.f_ext, c.x, c.T));
  }
}

TEST(simulation_LeftOut, NoGravityEqualsZeroGravity) {
  Random<double> rnd(602);
  Check check("no gravity");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    Model m = c.m;
    m.gravity.setZero();
    const Model none = m;  // as never set: the default is the zero vector
    const Outcome left_out = evaluate(none, c.f_ext, c.x, c.T);
    // The same path (has_gravity() false): zero, negative zero, a squared norm that
    // underflows.
    m.gravity = soa::Vec3<double>(0, 0, 0);
    check.same(left_out, evaluate(m, c.f_ext, c.x, c.T), i);
    m.gravity = soa::Vec3<double>(-0.0, -0.0, -0.0);
    check.same(left_out, evaluate(m, c.f_ext, c.x, c.T), i);
    m.gravity = soa::Vec3<double>(0, 0, -1e-170);
    EXPECT_FALSE(m.has_gravity());
    check.same(left_out, evaluate(m, c.f_ext, c.x, c.T), i);
    // The gravity pass, with a gravity far below the rounding of everything it meets.
    m.gravity = std::ldexp(1.0, -500) * rnd.unit3();
    ASSERT_TRUE(m.has_gravity());
    check.same(left_out, evaluate(m, c.f_ext, c.x, c.T), i);
    check.differ(left_out, evaluate(c.m, c.f_ext, c.x, c.T));
  }
}

TEST(simulation_LeftOut, NoSpringsEqualZeroSprings) {
  Random<double> rnd(603);
  Check check("no springs");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    const Model none = with_springs(c.m, 0.0);
    const Outcome left_out = evaluate(none, c.f_ext, c.x, c.T);
    // The same path per hinge (stiffness and damping both zero), about random rest positions.
    Model zero = none, minus_zero = with_springs(c.m, -0.0);
    for (int k = 1; k <= zero.n(); ++k)
      for (int j = 0; j < zero.body(k).rest.size(); ++j) zero.body(k).rest[j] = rnd.normal();
    EXPECT_FALSE(zero.has_springs());
    EXPECT_FALSE(minus_zero.has_springs());
    check.same(left_out, evaluate(zero, c.f_ext, c.x, c.T), i);
    check.same(left_out, evaluate(minus_zero, c.f_ext, c.x, c.T), i);
    // The spring path, its stiffness and damping far below the rounding of the hinge forces.
    check.same(left_out, evaluate(with_springs(c.m, kTiny), c.f_ext, c.x, c.T), i);
    check.differ(left_out, evaluate(c.m, c.f_ext, c.x, c.T));
  }
}

// The forward dynamics through the spring path fed with exact zeros: every hinge at its
// rest position (delta = 0: theta = rest, the identity quaternion, the origin) and at rest
// itself (its own beta 0, the other hinges moving), positive stiffness and damping.
TEST(simulation_LeftOut, SpringsAtTheirRestPositionCostNothing) {
  Random<double> rnd(604);
  Worst w("springs at delta = 0, beta = 0: |beta_dot - beta_dot(no springs)|");
  double differ = INFINITY;
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    Model springs = c.m;
    State x = c.x;
    // Every other hinge (the tip first) at its rest position, the others moving freely.
    for (int k = 1; k <= springs.n(); k += 2) {
      soa::Body& B = springs.body(k);
      double* th = x.theta.data() + B.q_offset;
      if (B.hinge.type == soa::HingeType::Spherical || B.hinge.type == soa::HingeType::Free)
        for (int j = 0; j < B.hinge.nq(); ++j) th[j] = j == 3 ? 1.0 : 0.0;
      else
        for (int j = 0; j < B.rest.size(); ++j) B.rest[j] = th[j];
      x.beta.segment(B.v_offset, B.hinge.nv()).setZero();
    }
    for (int k = 2; k <= springs.n(); k += 2)
      springs.body(k).stiffness = springs.body(k).damping = 0;
    ASSERT_TRUE(springs.has_springs());
    const Model none = with_springs(c.m, 0.0);
    soa::Workspace ws(c.m);
    soa::ForwardDynamics fd(c.m);
    VecX a(c.m.nv()), b(c.m.nv()), full(c.m.nv());
    soa::forward_dynamics(none, x, c.T, c.f_ext, ws, fd, a);
    soa::forward_dynamics(springs, x, c.T, c.f_ext, ws, fd, b);
    w.add(difference(a, b), i);
    // The springs of the full chain, away from their rest positions, do change beta_dot.
    soa::forward_dynamics(c.m, c.x, c.T, c.f_ext, ws, fd, full);
    soa::forward_dynamics(none, c.x, c.T, c.f_ext, ws, fd, a);
    differ = std::min(differ, difference(a, full));
  }
  EXPECT_EQ(w.value(), 0.0);
  EXPECT_GT(differ, 0.0);
}

TEST(simulation_LeftOut, AtRestEqualsVanishingRates) {
  Random<double> rnd(605);
  Check check("at rest");
  for (int i = 0; i < kCases; ++i) {
    const Case c(rnd, i);
    State x = c.x;
    x.beta.setZero();
    const Outcome left_out = evaluate(c.m, c.f_ext, x, c.T);
    // The same path (beta.isZero(0)): negative zeros.
    x.beta.setConstant(-0.0);
    check.same(left_out, evaluate(c.m, c.f_ext, x, c.T), i);
    // The velocity pass, with rates whose products underflow.
    x.beta = kTiny * soa::test::random_vector(rnd, c.m.nv());
    check.same(left_out, evaluate(c.m, c.f_ext, x, c.T), i);
    check.differ(left_out, evaluate(c.m, c.f_ext, c.x, c.T));
  }
}

}  // namespace
