// The viewer's frames (view::Recorder): poses, velocities, inter-body forces and energy as
// the library computes them, in world axes; and the decimation of a run to a frame budget.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "soa/sim/simulate.hpp"
#include "view_support.hpp"

namespace soa::test {
namespace {

const std::string kEveryHinge = std::string(SOA_SOURCE_DIR) + "/tests/scenes/every_hinge.json";

/// Random scenes of 1 to 8 bodies, and random states of each: \p f(scene, x, case).
template <class F>
void for_random_states(Random<double>& rnd, F f) {
  int c = 0;
  for (int chain = 0; chain < 200; ++chain) {
    const RandomScene r = random_scene(rnd, 1 + int(rnd.engine()() % 8));
    for (int state = 0; state < 5; ++state, ++c) f(r.scene, random_state(rnd, r.scene.model), c);
  }
}

/// Adds to \p err (in eps) how far each frame's f of \p fr is from the inter-body force of
/// \p ws (after inverse_dynamics() and update_poses()) in world axes; zero for a locked body.
void add_force_error(const Scene& s, const view::Frame& fr, const Workspace& ws, Worst& err,
                     int c) {
  for (std::size_t i = 0; i < s.frames.size(); ++i) {
    const Scene::Frame& F = s.frames[i];
    if (F.locked) {
      EXPECT_EQ(part(fr.f, i, 0), Vec3<double>::Zero());
      EXPECT_EQ(part(fr.f, i, 1), Vec3<double>::Zero());
      continue;
    }
    const Mat3<double>& R = ws.pose[F.k - 1].R();
    const Force& f = ws.f[F.k - 1];
    err.add(std::max(rel(part(fr.f, i, 0), Vec3<double>(R * f.angular())),
                     rel(part(fr.f, i, 1), Vec3<double>(R * f.linear()))) /
                eps<double>(),
            c);
  }
}

// Each frame's pose is {}^I T_{O_k} of update_poses() times the frame's offset on body k.
TEST(view_recorder, PosesAreTheLibrarysKinematics) {
  Random<double> rnd;
  Worst pos("pose position vs update_poses (rel, eps)");
  Worst rot("pose rotation vs update_poses (eps)");
  Worst tip_err("tip vs the last pose's far end (rel, eps)");
  for_random_states(rnd, [&](const Scene& s, const State& x, int c) {
    const view::Frame f = frame_of(s, x, {false, false});
    ASSERT_EQ(f.pose.size(), 7 * s.frames.size());
    Workspace ws(s.model);
    update_phi(s.model, x.theta, ws);
    update_poses(s.model, ws);
    for (std::size_t i = 0; i < s.frames.size(); ++i) {
      const Pose T = ws.pose[s.frames[i].k - 1] * s.frames[i].offset();
      const Pose V = pose_of(f, i);
      EXPECT_NEAR(Eigen::Vector4d::Map(f.pose.data() + 7 * i + 3).norm(), 1, 1e-14);
      pos.add(rel(V.l(), T.l()) / eps<double>(), c);
      rot.add((V.R() - T.R()).norm() / eps<double>(), c);
    }
    // The tip: the last body's far end, carried by its pose.
    const Scene::Frame& F = s.frames.back();
    const Vec3<double> tip = (ws.pose[F.k - 1] * F.offset()).apply(view::view_of(s).tip_point);
    tip_err.add(rel(f.tip, tip) / eps<double>(), c);
  });
  EXPECT_LE(pos.value(), 16);
  EXPECT_LE(rot.value(), 64);  // through the quaternion and back
  EXPECT_LE(tip_err.value(), 4);
}

/// \f$\omega\f$ with \f$\dot R = \tilde\omega R\f$ from \f$R(t \pm h)\f$: the axial vector of
/// the skew part of \f$(R_+ - R_-) R^* / 2h\f$.
Vec3<double> angular_rate(const Mat3<double>& Rp, const Mat3<double>& Rm, const Mat3<double>& R,
                          double h) {
  const Mat3<double> W = (Rp - Rm) * R.transpose() / (2 * h);
  return Vec3<double>(W(2, 1) - W(1, 2), W(0, 2) - W(2, 0), W(1, 0) - W(0, 1)) / 2;
}

// V = [omega; v] of each frame's origin in world axes is the rate of its pose along the
// motion (central differences of the recorder's own poses: independent of V's recursion).
TEST(view_recorder, VelocitiesAreTheRatesOfThePoses) {
  Random<double> rnd;
  Worst err("V vs d/dt of the pose (rel)");
  const double h = 1e-5;
  for_random_states(rnd, [&](const Scene& s, const State& x, int c) {
    const view::Frame f = frame_of(s, x, {true, false});
    ASSERT_EQ(f.V.size(), 6 * s.frames.size());
    EXPECT_TRUE(f.f.empty());
    const VecX<double> qd = theta_dot(s.model, x);
    State xp = x, xm = x;
    xp.theta = advance(s.model, x.theta, qd, h);
    xm.theta = advance(s.model, x.theta, qd, -h);
    const view::Frame fp = frame_of(s, xp, {false, false}), fm = frame_of(s, xm, {false, false});
    for (std::size_t i = 0; i < s.frames.size(); ++i) {
      const Vec3<double> w =
          angular_rate(pose_of(fp, i).R(), pose_of(fm, i).R(), pose_of(f, i).R(), h);
      const Vec3<double> v = (pose_of(fp, i).l() - pose_of(fm, i).l()) / (2 * h);
      err.add(std::max(rel(part(f.V, i, 0), w), rel(part(f.V, i, 1), v)), c);
    }
  });
  EXPECT_LE(err.value(), 1e-6);
}

// f(k) of each body is the inter-body force of the library's inverse dynamics at the
// accelerations of the simulated motion (forward dynamics with the scene's external forces,
// springs and dampers), turned into world axes; zero for a locked body. The hinge forces of
// that inverse dynamics are zero: the springs and dampers are counted the same way in both.
TEST(view_recorder, ForcesAreTheInverseDynamicsOfTheSimulatedMotion) {
  Random<double> rnd;
  Worst err("f vs inverse dynamics (rel, eps)");
  Worst hinge("T of inverse dynamics at the simulated motion (rel, eps)");
  for_random_states(rnd, [&](const Scene& s, const State& x, int c) {
    const view::Frame fr = frame_of(s, x, {false, true});
    ASSERT_EQ(fr.f.size(), 6 * s.frames.size());
    EXPECT_TRUE(fr.V.empty());
    const Model& m = s.model;
    ChainSystem sys(m, s.f_ext);
    VecX<double> beta_dot(m.nv()), T(m.nv());
    sys.acceleration(0, x, beta_dot);
    Workspace ws(m);
    inverse_dynamics(m, x, beta_dot, s.f_ext, ws, T);
    update_poses(m, ws);  // phi from inverse_dynamics
    double scale = 1;
    for (const Force& f : ws.f) scale = std::max(scale, f.vector().norm());
    hinge.add(T.norm() / (scale * m.n() * eps<double>()), c);
    add_force_error(s, fr, ws, err, c);
  });
  EXPECT_LE(err.value(), 0);  // the same computation
  EXPECT_LE(hinge.value(), 1e4);
}

// Along a prescribed motion (lesson 4) f(k) is the inverse dynamics at the motion's own
// beta_dot, whatever the forward dynamics would give; the poses, V and the energy are those of
// the state alone; at the forward dynamics' beta_dot it is the simulated motion's frame.
TEST(view_recorder, ForcesOfAPrescribedMotionAreInverseDynamicsAtItsBetaDot) {
  Random<double> rnd;
  Worst err("f vs inverse dynamics at the given beta_dot (rel, eps)");
  for_random_states(rnd, [&](const Scene& s, const State& x, int c) {
    const Model& m = s.model;
    const VecX<double> bd = random_vector(rnd, m.nv());
    view::Recorder rec(s, 1.0, 2);
    rec.record(0, x, bd);
    const view::Frame fr = rec.take("prescribed").frames.at(0);
    const view::Frame free = frame_of(s, x);
    EXPECT_EQ(fr.pose, free.pose);
    EXPECT_EQ(fr.V, free.V);
    EXPECT_EQ(fr.energy, free.energy);
    ASSERT_EQ(fr.f.size(), 6 * s.frames.size());
    Workspace ws(m);
    VecX<double> T(m.nv());
    inverse_dynamics(m, x, bd, s.f_ext, ws, T);
    update_poses(m, ws);
    add_force_error(s, fr, ws, err, c);
    // At the forward dynamics' beta_dot: the frame of the simulated motion.
    ChainSystem sys(m, s.f_ext);
    VecX<double> bd_fd(m.nv());
    sys.acceleration(0, x, bd_fd);
    view::Recorder rec_fd(s, 1.0, 2);
    rec_fd.record(0, x, bd_fd);
    EXPECT_EQ(rec_fd.take("fd").frames.at(0).f, free.f);
  });
  EXPECT_LE(err.value(), 0);  // the same computation
}

// offer(t, x, beta_dot) keeps the same frames as offer(t, x); a beta_dot of the wrong size is
// refused before anything is recorded.
TEST(view_recorder, PrescribedMotionIsDecimatedAlikeAndSized) {
  const Scene s = load_scene(kEveryHinge);
  const VecX<double> bd = VecX<double>::Zero(s.model.nv());
  view::Recorder a(s, 1, 7, {false, true}), b(s, 1, 7, {false, true});
  for (long i = 0; i <= 100; ++i) a.offer(double(i) * 0.013, s.state, bd);
  for (long i = 0; i <= 100; ++i) b.offer(double(i) * 0.013, s.state);
  a.record(1.3, s.state, bd);
  b.record(1.3, s.state);
  std::vector<double> ta, tb;
  for (const view::Frame& f : a.take("a").frames) ta.push_back(f.t);
  for (const view::Frame& f : b.take("b").frames) tb.push_back(f.t);
  EXPECT_EQ(ta, tb);
  EXPECT_EQ(a.offered(), b.offered());
  const VecX<double> wrong = VecX<double>::Zero(s.model.nv() + 1);
  const std::string msg = "view: beta_dot has " + std::to_string(s.model.nv() + 1) +
                          " entries, the chain has " + std::to_string(s.model.nv()) +
                          " degrees of freedom";
  view::Recorder c(s, 1, 7);
  EXPECT_EQ(error_of([&] { c.offer(0, s.state, wrong); }), msg);
  EXPECT_EQ(error_of([&] { c.record(0, s.state, wrong); }), msg);
  EXPECT_EQ(c.offered(), 0);
  EXPECT_EQ(c.kept(), 0u);
}

TEST(view_recorder, EnergyIsTheChainSystemsEnergy) {
  Random<double> rnd;
  for_random_states(rnd, [&](const Scene& s, const State& x, int) {
    ChainSystem sys(s.model, s.f_ext);
    EXPECT_EQ(frame_of(s, x, {false, false}).energy, sys.energy(x));
  });
}

TEST(view_recorder, RefusesABudgetBelowTwoAndABadEndTime) {
  const Scene s = load_scene(kEveryHinge);
  EXPECT_EQ(error_of([&] { view::Recorder(s, 1.0, 1); }),
            "view: a recording needs a budget of at least 2 frames");
  for (double t_end : {-1.0, double(NAN), double(INFINITY)})
    EXPECT_EQ(error_of([&] { view::Recorder(s, t_end); }),
              "view: the end time of a recording must be finite and >= 0");
}

/// The times a recorder of \p budget frames over [0, t_end] must keep of the states at
/// t = i h, i = 0..steps (then the last, forced): for each sample j t_end / (budget - 1), the
/// first time at or after it (a millionth of the interval counts as at).
std::vector<double> expected_times(double t_end, std::size_t budget, long steps, double h) {
  const double interval = t_end / double(budget - 1);
  std::set<long> kept;
  for (std::size_t j = 0; j < budget; ++j) {
    const double s = double(j) * interval - 1e-6 * interval;
    long i = std::max(0L, long(std::ceil(s / h)) - 1);
    while (double(i) * h < s) ++i;
    if (i <= steps) kept.insert(i);
  }
  kept.insert(steps);
  std::vector<double> t;
  for (long i : kept) t.push_back(double(i) * h);
  if (t.size() > budget) t.erase(t.end() - 2);  // the last frame replaced by the final state
  return t;
}

// At most the budget, the first and the last state, and at each multiple of the interval
// the first state at or after it: for steps that divide the interval, that do not, that are
// longer than it, for runs shorter than the budget and runs stopped before t_end.
TEST(view_recorder, DecimationKeepsTheBudgetTheEndsAndTheSpacing) {
  const Scene s = load_scene(kEveryHinge);
  struct Case {
    double t_end, h;
    long steps;
    std::size_t budget;
  };
  const Case cases[] = {{10, 1e-3, 10000, 400}, {10, 1e-3, 10000, 401}, {1, 0.003, 333, 400},
                        {2, 0.01, 200, 400},    {1, 0.07, 14, 5},       {5, 1e-3, 2345, 400},
                        {1, 1.0 / 3, 3, 2},     {0.3, 0.1, 3, 100},     {7, 0.0123, 569, 37}};
  for (const Case& k : cases) {
    view::Recorder rec(s, k.t_end, k.budget, {false, false});
    for (long i = 0; i <= k.steps; ++i) rec.offer(double(i) * k.h, s.state);
    rec.record(double(k.steps) * k.h, s.state);
    const view::Run run = rec.take("run");
    std::vector<double> t;
    for (const view::Frame& f : run.frames) t.push_back(f.t);
    const std::string what = "t_end " + std::to_string(k.t_end) + ", h " + std::to_string(k.h) +
                             ", " + std::to_string(k.steps) + " steps, budget " +
                             std::to_string(k.budget);
    EXPECT_LE(t.size(), k.budget) << what;
    EXPECT_EQ(t.front(), 0) << what;
    EXPECT_EQ(t.back(), double(k.steps) * k.h) << what;
    EXPECT_EQ(t, expected_times(k.t_end, k.budget, k.steps, k.h)) << what;
    EXPECT_EQ(rec.offered(), k.steps + 1) << what;
    EXPECT_EQ(rec.kept(), t.size()) << what;
  }
}

TEST(view_recorder, TheNoteSaysHowManyStatesAreShown) {
  const Scene s = load_scene(kEveryHinge);
  view::Recorder rec(s, 10, view::kDefaultFrames, {false, false});
  for (long i = 0; i <= 10000; ++i) rec.offer(double(i) * 1e-3, s.state);
  rec.record(10, s.state);
  EXPECT_EQ(rec.kept(), 400u);
  EXPECT_DOUBLE_EQ(rec.interval(), 10.0 / 399);
  EXPECT_EQ(rec.note(), "10001 states shown as 400 frames (one every 25.1 ms)");
  EXPECT_EQ(view::decimation_note(51, 51, 0.1), "all 51 states shown");
  EXPECT_EQ(view::decimation_note(100001, 400, 2.5),
            "100001 states shown as 400 frames (one every 2.5 s)");
}

// A run stopped early (a blow-up, an interrupt) still ends on its last state; a forced
// record of a state already kept adds nothing.
TEST(view_recorder, RecordForcesTheLastStateOnce) {
  const Scene s = load_scene(kEveryHinge);
  view::Recorder rec(s, 10, 11, {false, false});
  for (long i = 0; i <= 3456; ++i) rec.offer(double(i) * 1e-3, s.state);
  const double t_last = 3456 * 1e-3;
  rec.record(t_last, s.state);
  rec.record(t_last, s.state);
  const view::Run run = rec.take("stopped");
  ASSERT_EQ(run.frames.size(), 5u);  // 0, 1, 2, 3 and 3.456
  EXPECT_EQ(run.frames.back().t, t_last);
  EXPECT_EQ(run.label, "stopped");
  EXPECT_EQ(rec.offered(), 3457);
  // A state recorded without being offered counts as one.
  view::Recorder one(s, 0, 2);
  one.record(0, s.state);
  EXPECT_EQ(one.offered(), 1);
  EXPECT_EQ(one.note(), "1 state shown");
}

// A simulated run (the double pendulum, RK4): the recorder keeps its first and last states,
// with the simulation's energies.
TEST(view_recorder, SimulatedRunKeepsTheFramesOfTheMotion) {
  const Scene s = load_scene(default_scene("double_pendulum.json"));
  view::Recorder rec(s, 2, 50);
  ChainSystem sys(s.model, s.f_ext);
  State x = s.state;
  SimulationOptions opt;
  opt.dt = 1e-3;
  opt.t_end = 2;
  const SimulationSummary sum =
      simulate(sys, x, opt, [&](double t, const State& xt) { rec.offer(t, xt); });
  rec.record(sum.t, x);
  const view::Run run = rec.take("RK4");
  ASSERT_EQ(run.frames.size(), 50u);
  EXPECT_EQ(run.frames.back().t, sum.t);
  EXPECT_NEAR(run.frames.back().energy, sum.energy1, 1e-12 * std::abs(sum.energy1) + 1e-12);
  EXPECT_NEAR(run.frames.front().energy, sum.energy0, 1e-12 * std::abs(sum.energy0) + 1e-12);
  EXPECT_EQ(rec.offered(), sum.steps + 1);
}

}  // namespace
}  // namespace soa::test
