// Tests of the variational integrator (implicit midpoint in (theta, p = M beta)) and of its
// O(N) parts, on random chains of the hinges whose coordinates add (revolute, prismatic,
// helical, universal) from fixed seeds:
// - kinetic_gradient(): p against the dense M beta, dT/dtheta against central differences of
//   T = beta* M(theta) beta / 2 (dense mass matrix); mass_matrix_inverse_times() against a
//   dense solve (every hinge type);
// - ChainSystem::momentum_rate() against d/dt(M beta) = M_dot beta + M beta_dot along the
//   motion (forward dynamics, central differences of the dense M), with gravity, springs,
//   dampers, external forces and a control law;
// - a fixed step converges at order 2 (against dopri5 at 1e-13);
// - the energy error stays bounded on the double pendulum at h = 0.02 s; Newton's method gets
//   through the seven-joint arm's fast phases at h = 0.005 s; where Newton from the step's
//   start fails (the arm at h = 0.02 s), continuation in the step finds the symmetric map;
// - a step in which a hinge turns further than SimulationOptions::max_turn is taken in
//   pieces, bitwise the variational map of those pieces;
// - a chain with a spherical hinge is refused with one line naming the body and the hinge.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "count_allocations.hpp"  // this program's one file that includes it
#include "fit.hpp"
#include "property.hpp"
#include "random_chain.hpp"
#include "soa/scene.hpp"
#include "soa/soa.hpp"

namespace {

using soa::test::slope;

using soa::HingeType;
using soa::Integrator;
using soa::MatX;
using soa::VecX;
using soa::test::Random;
using State = soa::State;

// A chain of n bodies whose hinges are drawn from revolute, prismatic, helical, universal.
soa::Model vector_space_chain(Random<double>& rnd, int n, bool springs) {
  soa::test::ChainOptions opt;
  opt.gravity = true;
  opt.springs = springs;
  static constexpr HingeType kTypes[] = {HingeType::Revolute, HingeType::Prismatic,
                                         HingeType::Helical, HingeType::Universal};
  std::vector<soa::Body> bodies;
  for (int i = 0; i < n; ++i)
    bodies.push_back(soa::test::detail::random_body(rnd, i, kTypes[rnd.engine()() % 4], opt));
  return soa::test::detail::finish_chain(std::move(bodies), opt);
}

// The dense mass matrix at theta (lesson 5's composite bodies).
MatX<double> mass_matrix(const soa::Model& m, const VecX<double>& theta) {
  soa::Workspace ws(m);
  std::vector<soa::SpatialInertia> R(std::size_t(m.n()));
  const State x{theta, VecX<double>::Zero(m.nv())};
  soa::update_phi(m, theta, ws);
  MatX<double> M;
  soa::mass_matrix_crb(m, x, ws, R, M);
  return M;
}

TEST(simulation_Variational, KineticGradientMatchesFiniteDifferences) {
  Random<double> rnd(211);
  double worst_p = 0, worst_g = 0;
  int types[4] = {0, 0, 0, 0};
  for (int c = 0; c < 200; ++c) {
    const soa::Model m = vector_space_chain(rnd, 1 + c % 8, false);
    const State x = soa::test::random_state(rnd, m);
    for (const soa::Body& B : m.bodies()) ++types[int(B.hinge.type)];
    soa::Workspace ws(m);
    VecX<double> p(m.nv()), g(m.nv());
    soa::kinetic_gradient(m, x, ws, p, g);
    const VecX<double> Mb = mass_matrix(m, x.theta) * x.beta;
    worst_p =
        std::max(worst_p, (p - Mb).lpNorm<Eigen::Infinity>() / (1 + Mb.lpNorm<Eigen::Infinity>()));
    // Central differences of T(theta) at fixed beta: error O(d^2) plus rounding.
    const double d = 1e-5;
    VecX<double> fd(m.nv());
    for (int i = 0; i < m.nv(); ++i) {
      VecX<double> tp = x.theta, tm = x.theta;
      tp[i] += d;
      tm[i] -= d;
      const double Tp = x.beta.dot(mass_matrix(m, tp) * x.beta) / 2;
      const double Tm = x.beta.dot(mass_matrix(m, tm) * x.beta) / 2;
      fd[i] = (Tp - Tm) / (2 * d);
    }
    const double scale = 1 + x.beta.dot(Mb);  // 1 + 2T
    worst_g = std::max(worst_g, (g - fd).lpNorm<Eigen::Infinity>() / scale);
  }
  std::printf(
      "[ worst    ] 200 chains (%d revolute, %d prismatic, %d helical, %d universal hinges): "
      "|p - M beta| %.2e, |dT/dtheta - central differences| %.2e (relative to 1 + 2T)\n",
      types[0], types[1], types[2], types[3], worst_p, worst_g);
  EXPECT_GT(types[int(HingeType::Universal)], 0);
  EXPECT_LE(worst_p, 1e-12);
  EXPECT_LE(worst_g, 1e-7);
}

TEST(simulation_Variational, KineticGradientRefusesQuaternionHinges) {
  Random<double> rnd(212);
  const soa::Model m = soa::test::random_chain_of_type(rnd, 2, HingeType::Spherical);
  const State x = soa::test::random_state(rnd, m);
  soa::Workspace ws(m);
  VecX<double> p(m.nv()), g(m.nv());
  EXPECT_THROW(soa::kinetic_gradient(m, x, ws, p, g), soa::Error);
}

TEST(simulation_Variational, MassMatrixInverseTimesSolves) {
  Random<double> rnd(213);
  soa::test::ChainOptions opt;  // every hinge type
  double worst = 0;
  for (int c = 0; c < 100; ++c) {
    const soa::Model m = soa::test::random_chain_mixed(rnd, 1 + c % 10, opt);
    const State x = soa::test::random_state(rnd, m);
    const VecX<double> T = soa::test::random_vector(rnd, m.nv());
    soa::Workspace ws(m);
    soa::ForwardDynamics fd(m);
    VecX<double> beta(m.nv());
    soa::mass_matrix_inverse_times(m, x, T, ws, fd, beta);
    const MatX<double> M = mass_matrix(m, x.theta);
    worst = std::max(worst,
                     (M * beta - T).lpNorm<Eigen::Infinity>() / (1 + T.lpNorm<Eigen::Infinity>()));
  }
  std::printf("[ worst    ] 100 chains of every hinge type: |M (M^-1 T) - T| %.2e\n", worst);
  EXPECT_LE(worst, 1e-10);
}

// p_dot = dT/dtheta + Q against d/dt(M(theta) beta) = (M(theta + e beta)(beta + e beta_dot) -
// M(theta - e beta)(beta - e beta_dot)) / 2e, theta_dot = beta and beta_dot from the forward
// dynamics: the rate along the true motion through x.
TEST(simulation_Variational, MomentumRateIsTheRateOfMBeta) {
  Random<double> rnd(214);
  double worst = 0;
  for (int c = 0; c < 60; ++c) {
    const soa::Model m = vector_space_chain(rnd, 1 + c % 7, true);  // springs and dampers
    const State x = soa::test::random_state(rnd, m);
    const soa::ExternalForces<double> f_ext = soa::test::random_forces(rnd, m);
    const VecX<double> K = soa::test::random_vector(rnd, m.nv());
    soa::ChainSystem sys(m, f_ext, [&](double t, const State& y, VecX<double>& T) {
      T = std::sin(3 * t) * K - 0.5 * y.beta + 0.3 * y.theta;
    });
    const double t = 0.7;
    VecX<double> beta_dot(m.nv()), p_dot(m.nv());
    sys.acceleration(t, x, beta_dot);
    sys.momentum_rate(t, x, p_dot);
    const double e = 1e-6;
    const VecX<double> fd = (mass_matrix(m, x.theta + e * x.beta) * (x.beta + e * beta_dot) -
                             mass_matrix(m, x.theta - e * x.beta) * (x.beta - e * beta_dot)) /
                            (2 * e);
    worst = std::max(worst,
                     (p_dot - fd).lpNorm<Eigen::Infinity>() / (1 + fd.lpNorm<Eigen::Infinity>()));
    // momentum() and velocity() invert each other.
    VecX<double> p(m.nv()), b(m.nv());
    sys.momentum(x, p);
    sys.velocity(x, p, b);
    EXPECT_LE((b - x.beta).lpNorm<Eigen::Infinity>(), 1e-9 * (1 + x.beta.norm())) << c;
  }
  std::printf("[ worst    ] 60 chains: |p_dot - d/dt(M beta)| %.2e (relative)\n", worst);
  EXPECT_LE(worst, 1e-6);
}

struct Scene {
  soa::Model m;
  State x0;
};

State run(const Scene& s, Integrator method, double dt, double tol, double t_end,
          std::vector<double>* energy = nullptr, soa::SimulationSummary* summary = nullptr,
          double max_turn = soa::SimulationOptions{}.max_turn) {
  soa::ChainSystem sys(s.m);
  soa::SimulationOptions opt;
  opt.method = method;
  opt.dt = dt;
  opt.tol = tol;
  opt.t_end = t_end;
  opt.max_turn = max_turn;
  State x = s.x0;
  const soa::SimulationSummary sum = soa::simulate(sys, x, opt, [&](double, const State& y) {
    if (energy) energy->push_back(sys.energy(y));
  });
  if (summary) *summary = sum;
  return x;
}

TEST(simulation_Variational, ConvergesAtOrderTwo) {
  for (bool mixed : {false, true}) {
    Random<double> rnd(215);
    soa::test::ChainOptions opt;
    opt.gravity = true;
    opt.springs = true;  // dampers too: a non-conservative Q
    Scene s{mixed ? vector_space_chain(rnd, 6, true)
                  : soa::test::random_chain_of_type(rnd, 3, HingeType::Revolute, opt),
            {}};
    s.x0 = soa::test::random_state(rnd, s.m);
    s.x0.beta *= 0.5;
    const double T = 0.5;
    const State ref = run(s, Integrator::DormandPrince, 0, 1e-13, T);
    std::vector<double> hs, errs;
    for (int k = 0; k < 4; ++k) {
      const double h = T / 100 / double(1 << k);
      const State x = run(s, Integrator::Variational, h, 0, T);
      hs.push_back(h);
      errs.push_back(
          std::sqrt((x.theta - ref.theta).squaredNorm() + (x.beta - ref.beta).squaredNorm()));
    }
    const double q = slope(hs, errs);
    std::string types;
    for (const soa::Body& B : s.m.bodies())
      types += std::string(" ") + hinge_type_name(B.hinge.type);
    std::printf("[ order    ] variational (%s): fitted %.2f (expected 2), errors %.2e .. %.2e\n",
                types.c_str() + 1, q, errs.front(), errs.back());
    EXPECT_NEAR(q, 2.0, 0.25);
  }
}

// The double pendulum of lesson 3 from its file's state, h = 0.02 s: the largest |E - E0|
// over the second half of the run at most 1.3 times that over the first (a drift linear in
// time would double it).
TEST(simulation_Variational, EnergyStaysBoundedOnTheDoublePendulum) {
  const soa::Scene sc = soa::load_scene(std::string(SOA_SCENE_DIR) + "/double_pendulum.json");
  const Scene s{sc.model, sc.state};
  const double T = 1000;
  std::vector<double> E;
  run(s, Integrator::Variational, 0.02, 0, T, &E);
  const std::size_t half = E.size() / 2;
  double first = 0, second = 0;
  for (std::size_t i = 0; i < E.size(); ++i)
    (i < half ? first : second) = std::max(i < half ? first : second, std::abs(E[i] - E[0]));
  std::printf(
      "[ drift    ] variational, double pendulum, h = 0.02 s over %g s: max |E - E0| first half "
      "%.3e J, second half %.3e J (x %.2f)\n",
      T, first, second, second / first);
  EXPECT_GT(first, 0);
  EXPECT_LE(second, 1.3 * first);
}

// The seven-joint arm from its file's state falls and whips its light wrist links at up to
// about 90 rad/s; at h = 0.005 s a wrist turns by up to 0.45 rad in a step. Newton's
// corrections stall at rounding level where the mass matrix is ill-conditioned (once a
// reported failure), and earlier steps contract slowly until the Jacobian is taken again.
// In one piece per step (max_turn = 0) the midpoint rule under-resolves the fastest turns:
// one step of the fastest turn can gain much of the energy that the same step in pieces does
// not, and how much depends on the last bits of the sine and cosine used. With the default
// max_turn = 0.5 rad the steps that turn further are taken in pieces, and the error stays
// within the bound, a tenth of the energy, with glibc's sine and SLEEF's alike and from
// starts perturbed by an ulp.
TEST(simulation_Variational, NewtonGetsThroughTheArmsFastPhases) {
  const soa::Scene sc = soa::load_scene(std::string(SOA_SCENE_DIR) + "/arm7.json");
  const Scene s{sc.model, sc.state};
  std::vector<double> E;
  soa::SimulationSummary sum;
  EXPECT_NO_THROW(run(s, Integrator::Variational, 0.005, 0, 40, &E, &sum));
  double worst = 0;
  for (double e : E) worst = std::max(worst, std::abs(e - E.front()));
  std::printf(
      "[ drift    ] variational, arm7, h = 0.005 s over 40 s: max |E - E0| %.3e J of %.3f J; "
      "%ld of %ld steps in pieces (at most %d), %ld evaluations\n",
      worst, E.front(), sum.subdivided, sum.steps, sum.max_pieces, sum.evaluations);
  EXPECT_LE(worst, 0.1 * std::abs(E.front()));
  EXPECT_GT(sum.subdivided, 0);
  EXPECT_GE(sum.max_pieces, 2);
}

// A step taken in pieces is the variational map of its pieces: on random revolute chains
// moving fast enough that a step of h turns a hinge by 1 to 3 rad, one simulate() step equals
// (bitwise) max_pieces variational() steps of h / max_pieces, in each of which no hinge turns
// by more than max_turn at either end; with max_turn = 0, at a turn of 0.3 to 0.6 rad (where
// Newton converges in one piece), it is one variational() step of h.
TEST(simulation_Variational, AStepInPiecesIsTheMapOfItsPieces) {
  Random<double> rnd(71);
  soa::test::ChainOptions copt;
  copt.gravity = true;
  int cases = 0, most = 1;
  for (int c = 0; c < 20; ++c) {
    const int n = 2 + int(rnd.engine()() % 6);
    const Scene chain{soa::test::random_chain_of_type(rnd, n, HingeType::Revolute, copt), {}};
    const State x0 = soa::test::random_state(rnd, chain.m);
    const double h = 0.05;
    for (const double max_turn : {0.25, 0.0}) {
      Scene s = chain;
      s.x0 = x0;
      const double turn = max_turn > 0 ? rnd.uniform(1, 3) : rnd.uniform(0.3, 0.6);
      s.x0.beta *= turn / (h * s.x0.beta.cwiseAbs().maxCoeff());
      soa::SimulationSummary sum;
      const State x = run(s, Integrator::Variational, h, 0, h, nullptr, &sum, max_turn);
      ASSERT_EQ(sum.steps, 1);
      const int m = sum.max_pieces;
      EXPECT_EQ(sum.subdivided, m > 1 ? 1 : 0);
      if (max_turn == 0) {
        EXPECT_EQ(m, 1);
      } else {
        EXPECT_GE(m, 4) << "a turn of " << turn << " rad in one step";
      }
      soa::ChainSystem sys(s.m);
      soa::Stepper stepper(sys);
      State y = s.x0, y1 = y;
      const double hm = h / m;
      for (int j = 0; j < m; ++j) {
        ASSERT_TRUE(stepper.variational(j * hm, hm, y, y1)) << "piece " << j;
        if (max_turn > 0 && m < soa::kVariationalPieces) {
          EXPECT_LE(soa::variational_turn(s.m, hm, y1.beta), max_turn) << "piece " << j;
        }
        y = y1;
      }
      EXPECT_TRUE(x.theta == y.theta && x.beta == y.beta)
          << "case " << c << ", " << m << " pieces: |dtheta| = " << (x.theta - y.theta).norm();
      ++cases;
      most = std::max(most, m);
    }
  }
  std::printf("[ pieces   ] %d steps compared bitwise with their pieces, at most %d pieces\n",
              cases, most);
}

// Newton's failure from the step's start handled by continuation in the step: the
// seven-joint arm at h = 0.02 s meets, within its first 2 s, steps where Newton from Z = 0
// diverges (before continued_solve(), the variational run stopped at step 96, t = 1.9 s, the
// implicit midpoint one at t = 0.6 s). The continued step must be the implicit midpoint map
// itself: that map is symmetric, so the step back (-h from the new state) returns to the old
// one, to Newton's tolerance times the conditioning (checked on every continued step, worst
// reported); both runs get past t = 2 s; and the continued steps allocate nothing.
TEST(simulation_Variational, NewtonFailureIsHandledByContinuationInTheStep) {
  const soa::Scene sc = soa::load_scene(std::string(SOA_SCENE_DIR) + "/arm7.json");
  for (const Integrator method : {Integrator::Variational, Integrator::ImplicitMidpoint}) {
    soa::ChainSystem sys(sc.model);
    soa::Stepper stepper(sys);
    const double h = 0.02;
    State x = sc.state, x1 = x, back = x;
    int continued = 0, steps = 0;
    double worst = 0, t = 0;
    const auto step = [&](double t0, double dt, const State& a, State& b) {
      return method == Integrator::Variational ? stepper.variational(t0, dt, a, b)
                                               : stepper.implicit_midpoint(t0, dt, a, b);
    };
    long allocated = 0;  // by the continued steps
    for (; steps < 150; ++steps, t += h) {
      const long before = stepper.continuations(), heap = soa::test::allocations();
      if (!step(t, h, x, x1)) break;
      if (stepper.continuations() > before) {
        allocated += soa::test::allocations() - heap;
        ++continued;
        ASSERT_TRUE(step(t + h, -h, x1, back)) << "the step back from t = " << t + h;
        const double size = 1 + x.theta.norm() + x.beta.norm();
        worst = std::max(worst, std::sqrt((back.theta - x.theta).squaredNorm() +
                                          (back.beta - x.beta).squaredNorm()) /
                                    size);
      }
      x = x1;
    }
    std::printf(
        "[ newton   ] %s, arm7, h = %g s: %d steps, %d continued, worst |back - x0| / (1 + "
        "|x0|) %.3e\n",
        soa::integrator_name(method), h, steps, continued, worst);
    EXPECT_GT(steps * h, 2.0) << "stopped at t = " << steps * h;
    EXPECT_GT(continued, 0);
    EXPECT_LE(worst, 1e-8);
    EXPECT_EQ(allocated, 0) << "heap allocations in the continued steps";
  }
}

TEST(simulation_Variational, QuaternionHingesAreRefusedInOneLine) {
  Random<double> rnd(216);
  soa::test::ChainOptions opt;
  const soa::Model m = soa::test::random_chain(rnd, 5, opt);  // revolute ... spherical
  const Scene s{m, soa::test::random_state(rnd, m)};
  std::string msg = "(no error)";
  try {
    run(s, Integrator::Variational, 0.01, 0, 0.1);
  } catch (const soa::Error& e) {
    msg = e.what();
  }
  std::printf("[ message  ] %s\n", msg.c_str());
  EXPECT_NE(msg.find("variational: body 'body4' has a spherical hinge"), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  EXPECT_EQ(msg.find("blow-up"), std::string::npos) << msg;
}

}  // namespace
