// The viewer's frames: a scene's motion sampled at most a budget of times, each frame
// computed by the library (lessons 3-4, simulation), in world axes.
//
// For a file body's frame F fixed on model body k at \f${}^{O_k}T_F\f$ (the identity unless
// the body is locked; Scene::Frame::offset()):
//   pose   \f${}^I T_F = {}^I T_{O_k}\, {}^{O_k}T_F\f$ (update_poses(), slides 25-27);
//   V      \f$V(F) = \phi^*(O_k, F)\, V(k)\f$ (slide 41), \f$V(k) = [\omega; v]\f$ at
//          \f$O_k\f$ from update_velocities(), then both parts turned by \f${}^I R_F\f$;
//   f      the inter-body force \f$f(k)\f$ on body k at \f$O_k\f$ from inverse_dynamics() at
//          the forward dynamics' \f$\dot\beta\f$ (or the caller's, for a prescribed motion),
//          turned by \f${}^I R_{O_k}\f$ (zero for a locked body: nothing is transmitted
//          through its hinge apart from body k's motion).
// f(k) does not depend on the hinge forces T (they only enter \f$T = H f - \tau_s\f$), so it
// is the force of the simulated motion whenever \f$\dot\beta\f$ is: ChainSystem's forward
// dynamics with the scene's external forces, springs and dampers; along a prescribed motion
// (lesson 4) it is the force of that motion's own \f$\dot\beta\f$.
#include <cmath>
#include <cstdio>
#include <string>

#include "detail.hpp"
#include "soa/instantiations.hpp"  // extern templates: compiled once, in the library
#include "soa/sim/chain_system.hpp"

namespace soa::view {

struct Recorder::Impl {
  Impl(const Scene& s, double t_end, std::size_t budget, Quantities q)
      : scene(s),
        budget(budget),
        interval(t_end / double(budget - 1)),
        // Within a millionth of the interval "at" a multiple: t = i h rounds either way.
        slack(1e-6 * interval),
        q(q),
        sys(s.model, s.f_ext),
        ws(s.model),
        beta_dot(VecX<double>::Zero(s.model.nv())),
        T(VecX<double>::Zero(s.model.nv())),
        tip_point(s.frames.empty() ? Vec3<double>::Zero()
                                   : detail::segment(s, s.frames.size() - 1)) {
    run.frames.reserve(budget);
  }

  /// The time of sample j: j t_end / (budget - 1).
  double target(std::size_t j) const { return double(j) * interval; }

  /// Appends (or, at the budget, replaces the last frame with) the frame of state \p x;
  /// \p given: the motion's \f$\dot\beta\f$, or null for the forward dynamics'.
  void capture(double t, const State& x, const VecX<double>* given);
  void offer(double t, const State& x, const VecX<double>* given);
  void record(double t, const State& x, const VecX<double>* given);

  const Scene& scene;
  const std::size_t budget;
  const double interval, slack;
  const Quantities q;
  ChainSystem sys;  // forward dynamics and energy, workspaces allocated once
  Workspace ws;     // kinematics and inverse dynamics
  VecX<double> beta_dot, T;
  const Vec3<double> tip_point;  // on the last file body
  std::size_t next = 0;          // the next sample j
  long offered = 0;
  double last_offered = NAN;  // the time of the last state offered
  std::size_t kept = 0;
  Run run;
};

void Recorder::Impl::capture(double t, const State& x, const VecX<double>* given) {
  const Model& m = scene.model;
  const std::size_t nb = scene.frames.size();
  Frame fr;
  fr.t = t;
  fr.pose.resize(7 * nb);
  update_phi(m, x.theta, ws);
  update_poses(m, ws);
  if (q.velocity) {
    update_velocities(m, x, ws);
    fr.V.resize(6 * nb);
  }
  for (std::size_t i = 0; i < nb; ++i) {
    const Scene::Frame& F = scene.frames[i];
    const Pose pose = ws.pose[F.k - 1] * F.offset();
    const Eigen::Matrix<double, 4, 1> c = UnitQuaternion::from_matrix(pose.R()).coeffs();
    for (int j = 0; j < 3; ++j) fr.pose[7 * i + j] = pose.l()[j];
    for (int j = 0; j < 4; ++j) fr.pose[7 * i + 3 + j] = c[j];
    if (q.velocity) {
      const Velocity V = Phi(F.offset()).transpose_apply(ws.V[F.k - 1]);  // at F, F axes
      const Vec3<double> w = pose.R() * V.angular(), v = pose.R() * V.linear();
      for (int j = 0; j < 3; ++j) fr.V[6 * i + j] = w[j], fr.V[6 * i + 3 + j] = v[j];
    }
    if (i + 1 == nb) fr.tip = pose.apply(tip_point);
  }
  if (q.force) {
    if (!given) sys.acceleration(t, x, beta_dot);
    // ws.f; ws.pose is left as it was
    inverse_dynamics(m, x, given ? *given : beta_dot, scene.f_ext, ws, T);
    fr.f.assign(6 * nb, 0.0);
    for (std::size_t i = 0; i < nb; ++i) {
      const Scene::Frame& F = scene.frames[i];
      if (F.locked) continue;
      const Mat3<double>& R = ws.pose[F.k - 1].R();
      const Vec3<double> N = R * ws.f[F.k - 1].angular(), Fo = R * ws.f[F.k - 1].linear();
      for (int j = 0; j < 3; ++j) fr.f[6 * i + j] = N[j], fr.f[6 * i + 3 + j] = Fo[j];
    }
  }
  fr.energy = sys.energy(x);
  if (run.frames.size() < budget) {
    run.frames.push_back(std::move(fr));
    ++kept;
  } else {
    run.frames.back() = std::move(fr);
  }
}

Recorder::Recorder(const Scene& scene, double t_end, std::size_t budget, Quantities q) {
  if (!(t_end >= 0) || !std::isfinite(t_end))
    throw Error("view: the end time of a recording must be finite and >= 0");
  if (budget < 2) throw Error("view: a recording needs a budget of at least 2 frames");
  impl_ = new Impl(scene, t_end, budget, q);
}

Recorder::~Recorder() {
  delete impl_;
}

void Recorder::Impl::offer(double t, const State& x, const VecX<double>* given) {
  ++offered;
  last_offered = t;
  if (next >= budget || t < target(next) - slack) return;
  capture(t, x, given);
  // Past every sample this state stood for (steps longer than the interval skip some).
  while (next < budget && target(next) - slack <= t) ++next;
}

void Recorder::Impl::record(double t, const State& x, const VecX<double>* given) {
  if (!run.frames.empty() && run.frames.back().t == t) return;  // offered and kept
  if (t != last_offered) ++offered;  // else offered and skipped: counted already
  last_offered = t;
  capture(t, x, given);
  while (next < budget && target(next) - slack <= t) ++next;
}

namespace {

/// Refuses a \f$\dot\beta\f$ of the wrong size before anything is computed.
const VecX<double>& sized(const VecX<double>& beta_dot, const Model& m) {
  if (beta_dot.size() != m.nv())
    throw Error("view: beta_dot has " + std::to_string(beta_dot.size()) +
                " entries, the chain has " + std::to_string(m.nv()) + " degrees of freedom");
  return beta_dot;
}

}  // namespace

void Recorder::offer(double t, const State& x) {
  impl_->offer(t, x, nullptr);
}
void Recorder::record(double t, const State& x) {
  impl_->record(t, x, nullptr);
}
void Recorder::offer(double t, const State& x, const VecX<double>& beta_dot) {
  impl_->offer(t, x, &sized(beta_dot, impl_->scene.model));
}
void Recorder::record(double t, const State& x, const VecX<double>& beta_dot) {
  impl_->record(t, x, &sized(beta_dot, impl_->scene.model));
}

Run Recorder::take(const std::string& label) {
  Run run;
  run.label = label;
  run.frames = std::move(impl_->run.frames);
  impl_->run.frames.clear();
  return run;
}

long Recorder::offered() const {
  return impl_->offered;
}
std::size_t Recorder::kept() const {
  return impl_->kept;
}
double Recorder::interval() const {
  return impl_->interval;
}
std::string Recorder::note() const {
  return decimation_note(offered(), kept(), interval());
}

std::string decimation_note(long states, std::size_t frames, double interval) {
  char buf[160];
  if (states >= 0 && std::size_t(states) == frames) {
    if (states == 1) return "1 state shown";
    std::snprintf(buf, sizeof buf, "all %ld states shown", states);
    return buf;
  }
  const bool ms = interval < 1;
  std::snprintf(buf, sizeof buf, "%ld states shown as %zu frames (one every %.3g %s)", states,
                frames, ms ? 1000 * interval : interval, ms ? "ms" : "s");
  return buf;
}

}  // namespace soa::view
