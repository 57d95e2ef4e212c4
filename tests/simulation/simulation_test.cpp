// Tests of the simulation loop (soa::simulate) and its integrators on random chains from the
// fixed seed:
// - each fixed-step method converges at its order (slope of log error against log h, fitted
//   over a halving sweep) against a reference by dopri5 at 1e-13, itself checked against
//   RK4 at a small step; dopri5's error falls as (evaluations)^-5;
// - spherical and free hinges stay on the unit quaternions (by construction);
// - the energy (ChainSystem::energy) is conserved by the exact flow: RK4's energy error
//   falls at order 4 on chains of every hinge type with gravity and springs (no dampers);
//   symplectic Euler and implicit midpoint keep it bounded over long runs;
// - a stiff spring blows up explicit methods with a message giving the time, the step and
//   the stiffness x step; implicit midpoint runs through at the same step;
// - no external forces and explicit zero forces give bitwise the same trajectory;
// - esdirk4 and radau5: their tableaus meet the order conditions (Radau IIA's
//   derived one: collocation, quadrature of order 5, the block form of T^-1 A^-1 T, the
//   embedded order 3), a fixed step converges at order 4 and 5, the adaptive run's error
//   follows the tolerance (radau5's within a few times it); a stiff, damped spring from its
//   own start runs at steps far above RK4's stability bound; Newton failures shrink the step.
#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <complex>

#include "fit.hpp"
#include "property.hpp"
#include "random_chain.hpp"
#include "soa/scene.hpp"
#include "soa/soa.hpp"

namespace {

using soa::test::slope;

using soa::Integrator;
using soa::test::Random;
using State = soa::State;

struct Scene {
  soa::Model m;
  State x0;
};

// A chain of n bodies (every hinge type when all), gravity, springs without dampers.
Scene chain(unsigned seed, int n, bool all_types, bool springs) {
  Random<double> rnd(seed);
  soa::test::ChainOptions opt;
  opt.all_hinge_types = all_types;
  opt.gravity = true;
  opt.springs = springs;
  Scene s{soa::test::random_chain(rnd, n, opt), {}};
  for (const soa::Body& B : s.m.bodies()) const_cast<soa::Body&>(B).damping = 0;
  s.x0 = soa::test::random_state(rnd, s.m);
  s.x0.beta *= 0.5;
  return s;
}

struct Trajectory {
  State x;
  soa::SimulationSummary sum;
  std::vector<double> energy;
};

Trajectory run(const Scene& s, Integrator method, double dt, double tol, double t_end,
               const soa::ExternalForces<double>& f_ext = {}) {
  soa::ChainSystem sys(s.m, f_ext);
  soa::SimulationOptions opt;
  opt.method = method;
  opt.dt = dt;
  opt.tol = tol;
  opt.t_end = t_end;
  Trajectory r{s.x0, {}, {}};
  r.sum = soa::simulate(sys, r.x, opt,
                        [&](double, const State& x) { r.energy.push_back(sys.energy(x)); });
  return r;
}

// Distance between two states: configurations through their local coordinates' scale
// (quaternion entries compared up to sign), velocities directly.
double distance(const soa::Model& m, const State& a, const State& b) {
  double d = (a.beta - b.beta).squaredNorm();
  for (const soa::Body& B : m.bodies()) {
    auto qa = a.theta.segment(B.q_offset, B.hinge.nq());
    auto qb = b.theta.segment(B.q_offset, B.hinge.nq());
    const bool quat =
        B.hinge.type == soa::HingeType::Spherical || B.hinge.type == soa::HingeType::Free;
    double dq = (qa - qb).squaredNorm();
    if (quat)
      dq = std::min(dq, (qa.head(4) + qb.head(4)).squaredNorm() +
                            (qa - qb).tail(qa.size() - 4).squaredNorm());
    d += dq;
  }
  return std::sqrt(d);
}

TEST(simulation_Order, EachMethodConvergesAtItsOrder) {
  for (bool all_types : {false, true}) {
    const Scene s = chain(101, all_types ? 6 : 3, all_types, true);
    const double T = 0.5;
    const State ref = run(s, Integrator::DormandPrince, 0, 1e-13, T).x;
    // The reference against a second method.
    const double check = distance(s.m, run(s, Integrator::RK4, T / 4096, 0, T).x, ref);
    EXPECT_LE(check, 1e-9) << "dopri5 reference vs RK4";
    for (Integrator I : {Integrator::Euler, Integrator::SymplecticEuler, Integrator::RK4,
                         Integrator::ImplicitMidpoint}) {
      const int p = soa::integrator_order(I);
      // Steps small enough to be asymptotic, errors well above the reference's.
      const double h0 = p == 1 ? T / 400 : p == 2 ? T / 100 : T / 25;
      std::vector<double> hs, errs;
      for (int k = 0; k < 4; ++k) {
        const double h = h0 / double(1 << k);
        hs.push_back(h);
        errs.push_back(distance(s.m, run(s, I, h, 0, T).x, ref));
      }
      const double q = slope(hs, errs);
      std::printf("[ order    ] %-18s %s: fitted %.2f (expected %d), errors %.2e .. %.2e\n",
                  soa::integrator_name(I), all_types ? "every hinge" : "revolute", q, p,
                  errs.front(), errs.back());
      EXPECT_NEAR(q, double(p), 0.25) << soa::integrator_name(I);
    }
    // dopri5: error against work (at least the fifth order's slope; tolerances that are
    // not yet asymptotic make it steeper) and tolerance proportionality.
    std::vector<double> evals, errs, tols;
    for (double tol : {1e-6, 1e-8, 1e-10}) {
      const Trajectory r = run(s, Integrator::DormandPrince, 0, tol, T);
      tols.push_back(tol);
      evals.push_back(double(r.sum.evaluations));
      errs.push_back(distance(s.m, r.x, ref));
    }
    const double q = -slope(evals, errs), p = slope(tols, errs);
    std::printf(
        "[ order    ] dopri5: error vs evaluations %.2f (expected >= 5), vs tolerance %.2f\n", q,
        p);
    EXPECT_GE(q, 4.5);
    EXPECT_NEAR(p, 1.0, 0.4);
  }
}

TEST(simulation_Manifold, QuaternionsStayUnit) {
  const Scene s = chain(103, 12, true, true);  // two spherical and two free hinges
  for (Integrator I : {Integrator::Euler, Integrator::RK4, Integrator::ImplicitMidpoint}) {
    soa::ChainSystem sys(s.m);
    soa::SimulationOptions opt;
    opt.method = I;
    opt.dt = 0.01;
    opt.t_end = 1;
    State x = s.x0;
    double worst = 0;
    int quats = 0;
    soa::simulate(sys, x, opt, [&](double, const State& y) {
      for (const soa::Body& B : s.m.bodies())
        if (B.hinge.type == soa::HingeType::Spherical || B.hinge.type == soa::HingeType::Free)
          worst = std::max(worst, std::abs(y.theta.segment<4>(B.q_offset).norm() - 1)), ++quats;
    });
    ASSERT_GT(quats, 0);
    std::printf("[ worst    ] %-18s max | |q| - 1 | = %.2e\n", soa::integrator_name(I), worst);
    EXPECT_LE(worst, 64 * soa::eps<double>());
  }
}

TEST(simulation_Energy, RK4ConservesTheEnergyAtOrderFour) {
  // Gravity and springs on every hinge type, no dampers: E is constant along the exact flow,
  // so RK4's energy error falls as h^4 (else the energy or the dynamics is wrong).
  const Scene s = chain(107, 8, true, true);
  std::vector<double> hs, errs;
  for (int k = 0; k < 3; ++k) {
    const double h = 0.02 / double(1 << k);
    const Trajectory r = run(s, Integrator::RK4, h, 0, 0.4);
    hs.push_back(h);
    errs.push_back(std::abs(r.energy.back() - r.energy.front()) / (1 + std::abs(r.energy.front())));
  }
  const double q = slope(hs, errs);
  std::printf("[ order    ] RK4 energy error: fitted %.2f, errors %.2e .. %.2e\n", q, errs.front(),
              errs.back());
  EXPECT_GE(q, 3.5);
  EXPECT_LE(errs.back(), 1e-6);
}

// Symplectic Euler is symplectic where the mass matrix is constant (one hinge: a pendulum);
// implicit midpoint is symmetric, and keeps the energy bounded on the double pendulum too.
TEST(simulation_Energy, SymplecticEulerAndMidpointStayBounded) {
  for (Integrator I : {Integrator::SymplecticEuler, Integrator::ImplicitMidpoint}) {
    const Scene s = chain(109, I == Integrator::SymplecticEuler ? 1 : 2, false, false);
    const Trajectory r = run(s, I, 0.002, 0, 40);
    const std::size_t n = r.energy.size(), q = n / 4;
    double first = 0, last = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double d = std::abs(r.energy[i] - r.energy[0]);
      (i < q ? first : last) = std::max(i < q ? first : last, d);
    }
    std::printf("[ drift    ] %-18s max |E - E0|: first quarter %.2e, rest %.2e\n",
                soa::integrator_name(I), first, last);
    EXPECT_LE(last, 1.5 * first + 1e-12) << soa::integrator_name(I) << ": secular drift";
  }
}

std::string blow_up_message(Integrator I, double dt,
                            soa::StiffnessPolicy policy = soa::StiffnessPolicy::Off) {
  // One pendulum with a stiff spring: omega = sqrt(k / J) ~ 1e4 rad/s.
  soa::Body b;
  b.name = "stiff";
  b.M = soa::SpatialInertia::from_cm(1, soa::Vec3<double>(0.1, 0, 0),
                                     soa::Mat3<double>::Identity() * 0.01);
  b.hinge.type = soa::HingeType::Revolute;
  b.stiffness = 1e6;
  Scene s{soa::Model::from_base_first({b}), {}};
  s.x0 = State::rest(s.m);
  s.x0.theta[0] = 0.1;
  soa::ChainSystem sys(s.m, {});
  soa::SimulationOptions opt;
  opt.method = I;
  opt.dt = dt;
  opt.stiffness = policy;
  State x = s.x0;
  try {
    soa::simulate(sys, x, opt, [](double, const State&) {});
  } catch (const soa::Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(simulation_BlowUp, ExplicitMethodsStopWithADiagnostic) {
  for (Integrator I : {Integrator::Euler, Integrator::RK4}) {
    const std::string msg = blow_up_message(I, 1e-3);  // h omega ~ 6
    EXPECT_NE(msg.find("blow-up at t = "), std::string::npos) << msg;
    // The estimate at the start is the spring's h omega (about 6), whatever the blown-up
    // state's rates did to the estimate at the end.
    const std::size_t at = msg.find("stiffness x step = ");
    ASSERT_NE(at, std::string::npos) << msg;
    double h_lambda = 0;
    ASSERT_EQ(std::sscanf(msg.c_str() + at, "stiffness x step = %lf at t = 0", &h_lambda), 1);
    EXPECT_GT(h_lambda, 4) << msg;
    EXPECT_LT(h_lambda, 9) << msg;
  }
  EXPECT_EQ(blow_up_message(Integrator::ImplicitMidpoint, 1e-3), "(no error)");
  EXPECT_EQ(blow_up_message(Integrator::RK4, 1e-4), "(no error)");  // h omega ~ 0.6
}

// A blow-up's cause can quote a body's name, which a scene or URDF file may make long: the
// message keeps it whole, between the run's place and the stiffness estimates.
TEST(simulation_BlowUp, TheMessageKeepsALongCauseWhole) {
  for (const std::size_t length : {1, 400, 5000}) {
    const std::string what =
        "forward dynamics: beta_dot of body '" + std::string(length, 'q') + "' is not finite";
    const std::string msg = soa::blow_up_message(Integrator::RK4, 1.5, 12, 1e-3, what, 6.25, 1e5);
    const std::string head = std::string("simulate (") + soa::integrator_name(Integrator::RK4) +
                             "): blow-up at t = 1.5 s, step 12 (h = 0.001): ";
    const std::string tail =
        "; estimated stiffness x step = 6.25 at t = 0 (1e+05 at the last "
        "state) (" +
        std::string(soa::stability_note(Integrator::RK4)) + ")";
    EXPECT_EQ(msg, head + what + tail) << "cause of " << what.size() << " characters";
  }
}

// The stiff pendulum of blow_up_message(): omega = sqrt(k / I), I its inertia about the hinge
// from the kinetic energy at a unit rate.
double stiff_omega() {
  soa::Body b;
  b.M = soa::SpatialInertia::from_cm(1, soa::Vec3<double>(0.1, 0, 0),
                                     soa::Mat3<double>::Identity() * 0.01);
  b.hinge.type = soa::HingeType::Revolute;
  const soa::Model m = soa::Model::from_base_first({b});
  soa::ChainSystem sys(m, {});
  State x = State::rest(m);
  const double E0 = sys.energy(x);
  x.beta[0] = 1;
  return std::sqrt(1e6 / (2 * (sys.energy(x) - E0)));
}

// The stiffness monitor (on by default) stops the explicit methods at the first step, before
// the blow-up, with h lambda; at h omega ~ 0.6 it lets RK4 run.
TEST(simulation_Stiffness, TheMonitorStopsExplicitMethodsBeyondTheirBound) {
  for (Integrator I : {Integrator::Euler, Integrator::SymplecticEuler, Integrator::RK4}) {
    const std::string msg = blow_up_message(I, 1e-3, soa::StiffnessPolicy::Stop);
    const std::size_t at = msg.find("beyond the stability bound at t = 0 s, step 0");
    ASSERT_NE(at, std::string::npos) << soa::integrator_name(I) << ": " << msg;
    const std::size_t hl = msg.find("|h lambda| = ");
    ASSERT_NE(hl, std::string::npos) << msg;
    double h_lambda = 0;
    ASSERT_EQ(std::sscanf(msg.c_str() + hl, "|h lambda| = %lf", &h_lambda), 1) << msg;
    EXPECT_NEAR(h_lambda, 1e-3 * stiff_omega(), 2e-3 * h_lambda) << msg;  // printed to 3 digits
  }
  EXPECT_EQ(blow_up_message(Integrator::RK4, 1e-4, soa::StiffnessPolicy::Stop), "(no error)");
}

// The spring of stiffness k on a link of inertia I about its hinge, damper c: one mode,
// lambda = (-c +- sqrt(c^2 - 4 k I)) / 2I.
Scene spring(double k, double c) {
  soa::Body b;
  b.name = "spring";
  b.M = soa::SpatialInertia::from_cm(1, soa::Vec3<double>(0.1, 0, 0),
                                     soa::Mat3<double>::Identity() * 0.01);
  b.hinge.type = soa::HingeType::Revolute;
  b.hinge.axis = soa::Vec3<double>::UnitZ();
  b.stiffness = k;
  b.damping = c;
  Scene s{soa::Model::from_base_first({b}), {}};
  s.m.gravity.setZero();
  s.x0 = State::rest(s.m);
  return s;
}

// The dominant eigenvalue by power iteration against the eigenvalues of the Jacobian formed
// column by column (central differences, Eigen's eigensolver), on random chains with
// springs and dampers of stiffness ratios up to 1e6 (every hinge type), at random states: its
// modulus is the largest and it is an eigenvalue, within 1 % of the largest modulus (the
// chains have up to 72 states; 24 Arnoldi steps, as the monitor's first check).
TEST(simulation_Stiffness, DominantEigenvalueAgreesWithTheJacobiansSpectrum) {
  soa::test::Random<double> rnd(1601);
  double worst_abs = 0, worst_re = 0;
  for (int trial = 0; trial < 40; ++trial) {
    soa::test::ChainOptions co;
    co.gravity = true;
    co.springs = true;
    co.all_hinge_types = true;
    soa::Model m = soa::test::random_chain(rnd, 2 + trial % 5, co);
    for (int k = 1; k <= m.n(); ++k) {  // stiffness 1 ... 1e6 spread over the chain
      auto& B = const_cast<soa::Body&>(m.body(k));
      B.stiffness = std::pow(10.0, 6.0 * double(k - 1) / std::max(1, m.n() - 1));
      B.damping = 0.05 * std::sqrt(B.stiffness);
    }
    const State x = soa::test::random_state(rnd, m);
    soa::ChainSystem sys(m, {});
    soa::Stepper st(sys);
    const int n2 = 2 * m.nv();
    Eigen::MatrixXd J(n2, n2);
    Eigen::VectorXd Fp(n2), Fm(n2), z = Eigen::VectorXd::Zero(n2);
    for (int i = 0; i < n2; ++i) {
      const double d = 1e-6;
      z[i] = d;
      st.rate_at(0, x, z, Fp);
      z[i] = -d;
      st.rate_at(0, x, z, Fm);
      z[i] = 0;
      J.col(i) = (Fp - Fm) / (2 * d);
    }
    const Eigen::VectorXcd ev = Eigen::EigenSolver<Eigen::MatrixXd>(J, false).eigenvalues();
    int top = 0;
    for (int i = 1; i < ev.size(); ++i)
      if (std::abs(ev[i]) > std::abs(ev[top])) top = i;
    soa::DominantEigenvalueT<double> dominant(m.nv());
    const std::complex<double> l = dominant(st, 0.0, x, 24);
    // Its modulus is the largest, and it is an eigenvalue (where two moduli tie, either).
    double nearest = std::numeric_limits<double>::infinity();
    for (int i = 0; i < ev.size(); ++i) nearest = std::min(nearest, std::abs(l - ev[i]));
    worst_abs = std::max(worst_abs, std::abs(std::abs(l) - std::abs(ev[top])) / std::abs(ev[top]));
    worst_re = std::max(worst_re, nearest / std::abs(ev[top]));
  }
  std::printf(
      "[ stiff    ] dominant eigenvalue: worst relative error of |lambda| %.2e, distance to "
      "the nearest eigenvalue %.2e\n",
      worst_abs, worst_re);
  EXPECT_LE(worst_abs, 1e-2);
  EXPECT_LE(worst_re, 1e-2);
}

// A fast mode that the start does not excite (a stiff spring at rest) leaves an explicit
// run beyond its bound with nothing to show for it: the monitor stops it all the same
// (Stop), or notes it and lets it finish (Warn); Off spends no evaluation on it. Its cost: a
// check every 25 RK4 steps and at the end, 1 + min(k, 2 n_v) evaluations for k Arnoldi steps
// (24 at the start, 4 after): 3 on this one-hinge chain.
TEST(simulation_Stiffness, NothingFinishesBeyondTheBoundUnnoticed) {
  const Scene s = spring(1e6, 10);  // omega = 1e6 / 0.02 ^ 1/2 ~ 7071 rad/s
  const double omega = std::sqrt(1e6 / 0.02), h = 1.5 * 2.83 / omega;
  const long n = 200;
  auto go = [&](soa::StiffnessPolicy policy, double dt) {
    soa::ChainSystem sys(s.m, {});
    soa::SimulationOptions opt;
    opt.method = Integrator::RK4;
    opt.dt = dt;
    opt.t_end = dt * double(n);
    opt.stiffness = policy;
    State x = s.x0;
    return soa::simulate(sys, x, opt, [](double, const State&) {});
  };
  EXPECT_EQ(go(soa::StiffnessPolicy::Off, h).evaluations, 4 * n);  // finishes, at rest
  EXPECT_THROW(go(soa::StiffnessPolicy::Stop, h), soa::Error);
  const soa::SimulationSummary warned = go(soa::StiffnessPolicy::Warn, h);
  EXPECT_NE(warned.stiffness_warning.find("beyond the stability bound at t = 0 s"),
            std::string::npos)
      << warned.stiffness_warning;
  EXPECT_NEAR(warned.max_h_lambda, h * omega, 1e-3 * h * omega);
  const soa::SimulationSummary inside = go(soa::StiffnessPolicy::Stop, 0.5 * h);
  EXPECT_TRUE(inside.stiffness_warning.empty());
  const long checks = 1 + (n - 1) / 25 + 1;  // steps 0, 25, ..., 175, and the end (200)
  EXPECT_EQ(inside.stiffness_checks, checks);
  EXPECT_EQ(inside.evaluations, 4 * n + 3 * checks);
  std::printf("[ stiff    ] monitor: %ld checks, %ld evaluations beside RK4's %ld (%.1f %%)\n",
              inside.stiffness_checks, inside.evaluations - 4 * n, 4 * n,
              100.0 * double(inside.evaluations - 4 * n) / double(4 * n));
}

// A mode that grows by itself is the motion, not an instability: the inverted pendulum
// (lambda = sqrt(m g r / I), real) at h lambda = 1.2 is followed by RK4 (|R| < e^{h lambda}),
// while symplectic Euler, whose first-order step leaves (h lambda)^2 / 2 per step, is stopped.
TEST(simulation_Stiffness, AGrowingModeIsFollowedByRK4) {
  soa::Body b;
  b.name = "inverted";
  b.M = soa::SpatialInertia::from_cm(1, soa::Vec3<double>(0, 0, 0.5),
                                     soa::Mat3<double>::Identity() * 0.01);
  b.hinge.type = soa::HingeType::Revolute;
  b.hinge.axis = soa::Vec3<double>::UnitY();
  Scene s{soa::Model::from_base_first({b}), {}};
  s.m.gravity = soa::Vec3<double>(0, 0, -9.81);
  s.x0 = State::rest(s.m);
  s.x0.theta[0] = 1e-3;
  const double lambda = std::sqrt(9.81 * 0.5 / (0.01 + 0.25)), h = 1.2 / lambda;
  for (Integrator I : {Integrator::RK4, Integrator::SymplecticEuler}) {
    soa::ChainSystem sys(s.m, {});
    soa::SimulationOptions opt;
    opt.method = I;
    opt.dt = h;
    opt.t_end = 3 * h;
    State x = s.x0;
    std::string msg = "(no error)";
    try {
      const soa::SimulationSummary sum = soa::simulate(sys, x, opt, [](double, const State&) {});
      EXPECT_NEAR(sum.max_h_lambda, 1.2, 0.05) << soa::integrator_name(I);
    } catch (const soa::Error& e) {
      msg = e.what();
    }
    if (I == Integrator::RK4)
      EXPECT_EQ(msg, "(no error)");
    else
      EXPECT_NE(msg.find("beyond the stability bound at t = 0 s"), std::string::npos) << msg;
  }
}

// The bound the monitor applies is the method's: RK4 runs at 0.95 of 2.83 / omega on an
// undamped spring and is stopped at 1.05; symplectic Euler at 0.95 and 1.05 of 2 / omega.
TEST(simulation_Stiffness, TheBoundIsTheMethods) {
  const Scene s = spring(1e6, 0);
  const double omega = std::sqrt(1e6 / 0.02);
  for (const auto& [I, bound] : {std::pair{Integrator::RK4, 2.0 * std::sqrt(2.0)},
                                 std::pair{Integrator::SymplecticEuler, 2.0}}) {
    for (const double f : {0.95, 1.05}) {
      soa::ChainSystem sys(s.m, {});
      soa::SimulationOptions opt;
      opt.method = I;
      opt.dt = f * bound / omega;
      opt.t_end = 10 * opt.dt;
      State x = s.x0;
      x.theta[0] = 1e-3;
      bool stopped = false;
      try {
        soa::simulate(sys, x, opt, [](double, const State&) {});
      } catch (const soa::Error&) {
        stopped = true;
      }
      EXPECT_EQ(stopped, f > 1) << soa::integrator_name(I) << " at " << f << " x its bound";
    }
  }
}

// A step count that does not fit is refused with the numbers (it overflowed a long and ran one
// step of 1 s); dopri5 with its error control switched off (tol 1e300) blows up at a time
// inside [0, t_end], not a negative one.
TEST(simulation_Limits, StepCountsThatDoNotFitAreRefused) {
  const Scene s = chain(117, 3, false, true);
  for (const auto& [dt, t_end] : {std::pair{1e-300, 1.0}, std::pair{1.0, 1e30}}) {
    std::string msg = "(no error)";
    try {
      run(s, Integrator::RK4, dt, 0, t_end);
    } catch (const soa::Error& e) {
      msg = e.what();
    }
    EXPECT_EQ(msg.rfind("simulate: t_end / dt = ", 0), 0u) << msg;
    EXPECT_NE(msg.find("steps, more than a run can count"), std::string::npos) << msg;
  }
}

TEST(simulation_BlowUp, Dopri5WithoutErrorControlReportsATimeInTheRun) {
  const Scene s = chain(119, 3, false, true);
  std::string msg = "(no error)";
  try {
    run(s, Integrator::DormandPrince, 0, 1e300, 1e6);
  } catch (const soa::Error& e) {
    msg = e.what();
  }
  const std::size_t at = msg.find("blow-up at t = ");
  ASSERT_NE(at, std::string::npos) << msg;
  double t = -1;
  ASSERT_EQ(std::sscanf(msg.c_str() + at, "blow-up at t = %lf", &t), 1) << msg;
  EXPECT_GE(t, 0) << msg;
  EXPECT_LE(t, 1e6) << msg;
}

// The stop flag (set by a signal handler in soa simulate) ends the run at a step boundary.
TEST(simulation_Stop, AStopFlagEndsTheRunAtAStepBoundary) {
  const Scene s = chain(121, 3, false, true);
  soa::ChainSystem sys(s.m, {});
  soa::SimulationOptions opt;
  opt.method = Integrator::RK4;
  opt.dt = 0.01;
  opt.t_end = 1;
  volatile std::sig_atomic_t stop = 0;
  opt.stop = &stop;
  State x = s.x0;
  int observed = 0;
  const soa::SimulationSummary sum = soa::simulate(sys, x, opt, [&](double, const State&) {
    if (++observed == 11) stop = 1;  // t = 0 and 10 steps
  });
  EXPECT_TRUE(sum.interrupted);
  EXPECT_EQ(sum.steps, 10);
  EXPECT_NEAR(sum.t, 0.1, 1e-12);
  stop = 0;
  x = s.x0;
  const soa::SimulationSummary full = soa::simulate(sys, x, opt, [](double, const State&) {});
  EXPECT_FALSE(full.interrupted);
  EXPECT_EQ(full.steps, 100);
  EXPECT_NEAR(full.t, 1.0, 1e-12);
}

TEST(simulation_LeftOut, NoExternalForcesEqualsExplicitZeros) {
  const Scene s = chain(113, 6, true, true);
  const Trajectory a = run(s, Integrator::RK4, 0.01, 0, 0.5);
  const Trajectory b = run(s, Integrator::RK4, 0.01, 0, 0.5,
                           soa::ExternalForces<double>(std::size_t(s.m.n()), soa::Force::Zero()));
  EXPECT_TRUE((a.x.theta.array() == b.x.theta.array()).all());
  EXPECT_TRUE((a.x.beta.array() == b.x.beta.array()).all());
}

}  // namespace

namespace {

// ESDIRK4(3)6L[2]SA: c = A 1, the order conditions of b up to order 4 and of the embedded
// b_hat = b - e up to order 3 (Hairer, Norsett and Wanner I, II.2).
TEST(simulation_Esdirk, TableauMeetsTheOrderConditions) {
  using T = soa::Esdirk436;
  Eigen::Matrix<double, 6, 6> A;
  Eigen::Matrix<double, 6, 1> b, bh, c;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) A(i, j) = T::a[std::size_t(i)][std::size_t(j)];
    c[i] = T::c[std::size_t(i)];
  }
  b = A.row(5).transpose();
  bh = b;
  for (int i = 0; i < 6; ++i) bh[i] -= T::e[std::size_t(i)];
  const Eigen::Matrix<double, 6, 1> one = Eigen::Matrix<double, 6, 1>::Ones();
  EXPECT_LE((A * one - c).cwiseAbs().maxCoeff(), 4e-16);
  auto conditions = [&](const Eigen::Matrix<double, 6, 1>& w, int order) {
    std::vector<double> r = {w.sum() - 1, w.dot(c) - 0.5};
    if (order >= 3) {
      r.push_back(w.dot(c.cwiseProduct(c)) - 1.0 / 3);
      r.push_back(w.dot(A * c) - 1.0 / 6);
    }
    if (order >= 4) {
      r.push_back(w.dot(c.cwiseProduct(c).cwiseProduct(c)) - 0.25);
      r.push_back(w.dot(c.cwiseProduct(A * c)) - 1.0 / 8);
      r.push_back(w.dot(A * c.cwiseProduct(c)) - 1.0 / 12);
      r.push_back(w.dot(A * (A * c)) - 1.0 / 24);
    }
    double worst = 0;
    for (double x : r) worst = std::max(worst, std::abs(x));
    return worst;
  };
  EXPECT_LE(conditions(b, 4), 1e-15);
  EXPECT_LE(conditions(bh, 3), 1e-15);
  EXPECT_GT(conditions(bh, 4), 1e-6) << "the embedded solution is of order 3, not 4";
}

// Radau IIA as RadauIIA derives it: collocation C(3), sum_j a_ij c_j^(k-1) = c_i^k / k; b
// of order 5 (B(5), sum_i b_i c_i^(k-1) = 1/k, k = 1 ... 5, and not 6); T^-1 A^-1 T in the
// block form with the eigenvalues' invariants (trace, determinant); the embedded b_hat =
// b + A^* e with b_hat_0 = 1/gamma of order 3 and not 4; the long double derivation agrees.
TEST(simulation_Esdirk, RadauTableauIsDerivedCorrectly) {
  const soa::RadauIIA<double>& R = soa::RadauIIA<double>::get();
  const soa::RadauIIA<long double>& L = soa::RadauIIA<long double>::get();
  const double tol = 64 * std::numeric_limits<double>::epsilon();
  double worst = 0;
  for (int k = 1; k <= 3; ++k)
    for (int i = 0; i < 3; ++i) {
      double s = 0;
      for (int j = 0; j < 3; ++j) s += R.A(i, j) * std::pow(R.c[j], k - 1);
      worst = std::max(worst, std::abs(s - std::pow(R.c[i], k) / k));
    }
  EXPECT_LE(worst, tol) << "C(3)";
  auto quadrature = [&](const Eigen::Vector3d& w, double w0, int k) {
    double s = k == 1 ? w0 : 0;
    for (int i = 0; i < 3; ++i) s += w[i] * std::pow(R.c[i], k - 1);
    return std::abs(s - 1.0 / k);
  };
  for (int k = 1; k <= 5; ++k) EXPECT_LE(quadrature(R.b, 0, k), tol) << "B(5), k = " << k;
  EXPECT_GT(quadrature(R.b, 0, 6), 1e-6) << "Radau IIA is of order 5, not 6";
  const Eigen::Matrix3d A_inv = R.A.inverse();
  const Eigen::Matrix3d Lam = R.T_inv * A_inv * R.T;
  EXPECT_LE((R.T * R.T_inv - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), tol);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if ((i == 0) != (j == 0)) {
        EXPECT_LE(std::abs(Lam(i, j)), tol * 10) << i << "," << j;
      }
  EXPECT_LE(std::abs(Lam(2, 2) - R.alpha), tol * 10);
  EXPECT_LE(std::abs(Lam(2, 1) + R.beta), tol * 10);
  EXPECT_GT(std::abs(R.beta), 1) << "a complex pair";
  EXPECT_LE(std::abs(A_inv.trace() - (R.gamma + 2 * R.alpha)), tol * 10);
  EXPECT_LE(std::abs(A_inv.determinant() - R.gamma * (R.alpha * R.alpha + R.beta * R.beta)),
            tol * 100);
  const Eigen::Vector3d b_hat = R.b + R.A.transpose() * R.e;
  for (int k = 1; k <= 3; ++k)
    EXPECT_LE(quadrature(b_hat, 1 / R.gamma, k), tol * 10) << "embedded, k = " << k;
  EXPECT_GT(quadrature(b_hat, 1 / R.gamma, 4), 1e-6) << "the embedded formula is of order 3";
  EXPECT_LE((R.A - L.A.cast<double>()).cwiseAbs().maxCoeff(), tol);
  EXPECT_LE((R.e - L.e.cast<double>()).cwiseAbs().maxCoeff(), tol * R.e.cwiseAbs().maxCoeff());
  EXPECT_LE(std::abs(R.gamma - double(L.gamma)) + std::abs(R.alpha - double(L.alpha)) +
                std::abs(std::abs(R.beta) - std::abs(double(L.beta))),
            tol * 10);
}

// A fixed step of esdirk() and radau5() (stepper called directly) converges at order 4
// and 5.
TEST(simulation_Esdirk, FixedStepConvergesAtItsOrder) {
  for (const Integrator I : {Integrator::Esdirk, Integrator::Radau5})
    for (bool all_types : {false, true}) {
      const Scene s = chain(101, all_types ? 6 : 3, all_types, true);
      const double T = 0.5;
      const State ref = run(s, Integrator::DormandPrince, 0, 1e-13, T).x;
      const int p = soa::integrator_order(I), n0 = I == Integrator::Radau5 ? 20 : 25;
      std::vector<double> hs, errs;
      for (int k = 0; k < 4; ++k) {
        const int n = n0 << k;
        soa::ChainSystem sys(s.m, {});
        soa::Stepper stepper(sys);
        stepper.set_tolerance(1e-13);  // Newton's error well below the method's
        State x = s.x0, x1 = s.x0;
        soa::VecX<double> err;
        for (int i = 0; i < n; ++i) {
          const double t = i * T / n;
          ASSERT_TRUE(I == Integrator::Radau5 ? stepper.radau5(t, T / n, x, x1, err)
                                              : stepper.esdirk(t, T / n, x, x1, err));
          x = x1;
        }
        hs.push_back(T / n);
        errs.push_back(distance(s.m, x, ref));
      }
      const double q = slope(hs, errs);
      std::printf("[ order    ] %s %s: fitted %.2f (expected %d), errors %.2e %.2e %.2e %.2e\n",
                  soa::integrator_name(I), all_types ? "every hinge" : "revolute", q, p, errs[0],
                  errs[1], errs[2], errs[3]);
      EXPECT_NEAR(q, double(p), 0.3) << soa::integrator_name(I);
    }
}

// The adaptive run: error proportional to a power of the tolerance (local error control with
// an order 3 estimate, O(h^4), of an order p method: global error ~ tol^(p/4), 1 for esdirk4,
// 1.25 for radau5); radau5's (its Newton error held at 3e-5 of the tolerance) within a few
// times the tolerance.
TEST(simulation_Esdirk, ErrorFollowsTheTolerance) {
  const Scene s = chain(101, 4, true, true);
  const double T = 0.5;
  const State ref = run(s, Integrator::DormandPrince, 0, 1e-13, T).x;
  for (const Integrator I : {Integrator::Esdirk, Integrator::Radau5}) {
    const double factor = I == Integrator::Radau5 ? 5 : 100;
    std::vector<double> tols, errs;
    for (double tol : {1e-5, 1e-7, 1e-9}) {
      const Trajectory r = run(s, I, 0, tol, T);
      tols.push_back(tol);
      errs.push_back(distance(s.m, r.x, ref));
      std::printf("[ %-8s ] tol %.0e: error %.2e, %ld steps, %ld rejected, %ld evaluations\n",
                  soa::integrator_name(I), tol, errs.back(), r.sum.steps, r.sum.rejected,
                  r.sum.evaluations);
      EXPECT_LE(errs.back(), factor * tol) << soa::integrator_name(I);
    }
    const double p = slope(tols, errs), expected = soa::integrator_order(I) / 4.0;
    std::printf("[ order    ] %s: error vs tolerance %.2f (expected about %.2f)\n",
                soa::integrator_name(I), p, expected);
    EXPECT_NEAR(p, expected, 0.35) << soa::integrator_name(I);
  }
}

// A stiff, damped spring from its own start (0.1 rad on k = 1e8): esdirk4 reaches t_end at
// an average step far above RK4's stability bound 2.83 / |lambda| (100 x; radau5 50 x: it
// follows the transient in shorter, cheaper steps), and agrees with a tight run; RK4 at that
// average step blows up.
TEST(simulation_Esdirk, StiffSpringFromItsOwnStart) {
  soa::Body b;
  b.name = "stiff";
  b.M = soa::SpatialInertia::from_cm(1, soa::Vec3<double>(0.1, 0, 0),
                                     soa::Mat3<double>::Identity() * 0.01);
  b.hinge.type = soa::HingeType::Revolute;
  b.hinge.axis = soa::Vec3<double>::UnitZ();
  b.stiffness = 1e8;
  b.damping = 1e3;
  Scene s{soa::Model::from_base_first({b}), {}};
  s.m.gravity = soa::Vec3<double>(0, -9.81, 0);
  s.x0 = State::rest(s.m);
  s.x0.theta[0] = 0.1;
  const double T = 1, tol = 1e-6;
  soa::ChainSystem sys(s.m, {});
  soa::Stepper probe(sys);
  const double lambda = soa::stiffness_estimate(probe, 1, 0.0, s.x0);
  const Trajectory ref = run(s, Integrator::Esdirk, 0, 1e-11, T);
  for (const Integrator I : {Integrator::Esdirk, Integrator::Radau5}) {
    const Trajectory r = run(s, I, 0, tol, T);
    const double h_avg = T / double(r.sum.steps), bound = 2.83 / lambda;
    std::printf(
        "[ stiff    ] %s: |lambda| %.3g, %ld steps, average step %.3g = %.0f x RK4's "
        "bound, error %.2e\n",
        soa::integrator_name(I), lambda, r.sum.steps, h_avg, h_avg / bound,
        distance(s.m, r.x, ref.x));
    EXPECT_GE(h_avg / bound, I == Integrator::Radau5 ? 50 : 100) << soa::integrator_name(I);
    EXPECT_LE(distance(s.m, r.x, ref.x), 100 * tol) << soa::integrator_name(I);
    EXPECT_THROW(run(s, Integrator::RK4, h_avg, 0, T), soa::Error);
  }
}

// A first step far too large for Newton: the step is retried smaller (Newton failures
// counted), and the run ends as accurate as one started small.
TEST(simulation_Esdirk, NewtonFailureShrinksTheStep) {
  Scene s = chain(7, 2, false, false);
  s.x0.beta.setConstant(8);
  const double T = 2;
  for (const Integrator I : {Integrator::Esdirk, Integrator::Radau5}) {
    const Trajectory small = run(s, I, 1e-4, 1e-8, T);
    const Trajectory large = run(s, I, T, 1e-8, T);
    std::printf(
        "[ newton   ] %s, first step %g: %ld Newton failures, %ld rejected; difference %.2e\n",
        soa::integrator_name(I), T, large.sum.newton_failures, large.sum.rejected,
        distance(s.m, large.x, small.x));
    EXPECT_GT(large.sum.newton_failures, 0) << soa::integrator_name(I);
    EXPECT_LE(distance(s.m, large.x, small.x), 1e-5) << soa::integrator_name(I);
  }
}

}  // namespace

// dopri5's first step comes from the problem (Hairer, Norsett, Wanner, Solving ODEs I,
// II.4), not from the horizon: on the double pendulum over [0, 1e6] the first trial step is
// that of the starting-step algorithm, far below t_end / 1000, and is accepted.
TEST(simulation_Dopri5, TheFirstStepComesFromTheProblemNotTheHorizon) {
  const soa::Scene sc = soa::load_scene(std::string(SOA_SCENE_DIR) + "/double_pendulum.json");
  soa::ChainSystem sys(sc.model, sc.f_ext);
  soa::StepperT<double> stepper(sys);
  const double h0 = soa::starting_step(stepper, sc.model.nv(), 0.0, sc.state, 1e-8,
                                       soa::embedded_order(Integrator::DormandPrince));
  EXPECT_GT(h0, 1e-8);
  EXPECT_LT(h0, 0.1);
  soa::SimulationOptions opt;
  opt.method = Integrator::DormandPrince;
  opt.tol = 1e-8;
  opt.t_end = 1e6;
  opt.max_steps = 50;
  State x = sc.state;
  std::vector<double> t;
  const soa::SimulationSummary sum =
      soa::simulate(sys, x, opt, [&](double ti, const State&) { t.push_back(ti); });
  ASSERT_GE(t.size(), 2u);
  EXPECT_DOUBLE_EQ(t[1], h0) << "the first step is the starting step, accepted";
  EXPECT_TRUE(sum.budget_spent);
  EXPECT_EQ(sum.steps, 50);
  EXPECT_FALSE(sum.interrupted);
}

// A trial step whose error estimate is not finite (here a first step of 1e3 s, which
// overflows) is rejected and taken again smaller, never reported as a blow-up.
TEST(simulation_Dopri5, ANonFiniteTrialStepIsRetriedSmaller) {
  const soa::Scene sc = soa::load_scene(std::string(SOA_SCENE_DIR) + "/double_pendulum.json");
  soa::ChainSystem sys(sc.model, sc.f_ext);
  soa::SimulationOptions opt;
  opt.method = Integrator::DormandPrince;
  opt.tol = 1e-8;
  opt.dt = 1e3;  // the first trial step
  opt.t_end = 1e6;
  opt.max_steps = 20;
  State x = sc.state;
  soa::SimulationSummary sum;
  ASSERT_NO_THROW(sum = soa::simulate(sys, x, opt, [](double, const State&) {}));
  EXPECT_GE(sum.rejected, 1);
  EXPECT_EQ(sum.steps, 20);
  EXPECT_TRUE(x.beta.allFinite());
}
