/// \file
/// What every section of the simulation report uses: a scene as a problem, one timed run of an
/// integrator, the reference solution, the error of a final state, the fitted order of
/// convergence, and the summary the last section writes.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "soa/scene.hpp"
#include "soa/soa.hpp"

namespace soa::lesson::sim {

using soa::Integrator;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The five integrators, in the order of the tables.
constexpr std::array<Integrator, 5> kMethods = {Integrator::Euler, Integrator::SymplecticEuler,
                                                Integrator::RK4, Integrator::DormandPrince,
                                                Integrator::ImplicitMidpoint};

/// A simulation problem: the chain, its external forces, the initial state, the horizon.
struct SimProblem {
  std::string name;  ///< file-name friendly: double_pendulum, arm7, chain50, stiff_chain
  std::string title;
  soa::Model m;
  soa::ExternalForces<double> f_ext;
  soa::State x0;
  double t_end = 1;
};

/// Calls \p job(i) for every i of \p order, in that order, on as many threads as the machine
/// has cores; each job writes its own result. Listing the longest jobs first keeps every core
/// busy to the end. For runs whose time is not measured: a timed run has the machine to
/// itself. The first exception a job throws is thrown again here, after every thread ends.
template <class Job>
void on_every_core(const std::vector<std::size_t>& order, const Job& job) {
  const std::size_t threads =
      std::min<std::size_t>(std::max(1u, std::thread::hardware_concurrency()), order.size());
  std::atomic<std::size_t> next{0};
  std::mutex guard;
  std::exception_ptr failure;
  const auto work = [&] {
    for (std::size_t k; (k = next++) < order.size();) {
      try {
        job(order[k]);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(guard);
        if (!failure) failure = std::current_exception();
      }
    }
  };
  std::vector<std::thread> others;
  for (std::size_t t = 1; t < threads; ++t) others.emplace_back(work);
  work();
  for (std::thread& t : others) t.join();
  if (failure) std::rethrow_exception(failure);
}

/// One run of one integrator over [0, t_end]: the final state, or the diagnostic that
/// stopped it.
struct Run {
  bool ok = false;
  std::string diagnostic;  ///< soa::Error's message when !ok
  soa::State x;            ///< the state at t_end
  soa::SimulationSummary summary;
  double seconds = kNaN;  ///< wall time of one run (the median of the repeats)
};

/// Integrates \p p with \p opt (t_end taken from \p p). Runs shorter than \p min_seconds in
/// all are repeated and the median time kept (a work-precision diagram of runs of a few
/// microseconds needs it).
inline Run run(const SimProblem& p, soa::SimulationOptions opt, double min_seconds = 0) {
  opt.t_end = p.t_end;
  Run r;
  std::vector<double> times;
  double total = 0;
  do {
    soa::ChainSystemT<double> sys(p.m, p.f_ext);
    soa::State x = p.x0;
    try {
      r.summary = soa::simulate(sys, x, opt, [](double, const soa::State&) {});
    } catch (const soa::Error& e) {
      r.ok = false;
      r.diagnostic = e.what();
      return r;
    }
    r.ok = true;
    r.x = x;
    times.push_back(r.summary.wall_seconds);
    total += r.summary.wall_seconds;
  } while (total < min_seconds && times.size() < 1000);
  std::sort(times.begin(), times.end());
  r.seconds = times[times.size() / 2];
  return r;
}

/// The error of a final state against the reference:
/// \f$\max(\|\theta - \theta_{\rm ref}\|_\infty, \|\beta - \beta_{\rm ref}\|_\infty /
/// \max(1, \|\beta_{\rm ref}\|_\infty))\f$ (unit quaternions compared component-wise, which
/// for nearby unit quaternions is half the rotation angle between them).
inline double state_error(const soa::State& x, const soa::State& ref) {
  if (!x.theta.allFinite() || !x.beta.allFinite()) return kNaN;
  const double dq = (x.theta - ref.theta).lpNorm<Eigen::Infinity>();
  const double scale = std::max(1.0, ref.beta.lpNorm<Eigen::Infinity>());
  return std::max(dq, (x.beta - ref.beta).lpNorm<Eigen::Infinity>() / scale);
}

/// The reference solution of a problem: Dormand–Prince at a tolerance near machine
/// precision, checked against a second method: RK4 at \p rk4_steps and twice as many steps,
/// Richardson-extrapolated, \f$x_{2N} + (x_{2N} - x_N)/15\f$ (fifth order). \p agreement is
/// the state error between the two, which bounds the errors the report can resolve.
struct Reference {
  soa::State x;
  double agreement = kNaN;
  long steps = 0;
  std::string diagnostic;  ///< non-empty when either run failed
};

inline Reference reference(const SimProblem& p, double tol = 1e-13, long rk4_steps = 20000) {
  Reference ref;
  soa::SimulationOptions opt;
  opt.method = Integrator::DormandPrince;
  opt.tol = tol;
  const Run a = run(p, opt);
  opt.method = Integrator::RK4;
  // A mode beyond RK4's bound that the motion does not excite leaves its run as good as the
  // agreement below says: the stiffness monitor would stop it (chain r1e-08, |h lambda| 6).
  opt.stiffness = soa::StiffnessPolicy::Off;
  opt.dt = p.t_end / double(rk4_steps);
  const Run b = run(p, opt);
  opt.dt = p.t_end / double(2 * rk4_steps);
  const Run c = run(p, opt);
  if (!a.ok || !b.ok || !c.ok) {
    ref.diagnostic = !a.ok ? a.diagnostic : !b.ok ? b.diagnostic : c.diagnostic;
    return ref;
  }
  ref.x = a.x;
  ref.steps = a.summary.steps;
  soa::State r = c.x;
  r.theta += (c.x.theta - b.x.theta) / 15;
  r.beta += (c.x.beta - b.x.beta) / 15;
  ref.agreement = state_error(r, a.x);
  return ref;
}

/// The least-squares slope of \f$\log y\f$ against \f$\log x\f$ over the points with
/// \p lo < y < \p hi (NaN when fewer than three points qualify).
inline double fitted_slope(const std::vector<double>& x, const std::vector<double>& y, double lo,
                           double hi) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(y[i] > lo && y[i] < hi) || !(x[i] > 0)) continue;
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly, ++n;
  }
  if (n < 3) return kNaN;
  const double d = n * sxx - sx * sx;
  return d > 0 ? (n * sxy - sx * sy) / d : kNaN;
}

/// What the last section prints and writes (`l8_sim_summary.md`): per method, the order
/// found on each scene, the error reached at a given cost, and the largest stable step on
/// the stiff chain; the cases diagnosed rather than solved.
struct MethodSummary {
  Integrator method = Integrator::RK4;
  std::string name;  ///< integrator_name(), or a method of another library ("cvode")
  int order = 0;     ///< its order (0: variable, as CVODE's BDF)
  std::vector<std::pair<std::string, double>> orders;  ///< scene, fitted order
  double error_at_cost = kNaN;  ///< error reached within Summary::cost_seconds (arm7)
  double h_stable = kNaN;       ///< largest stable step found on the stiffest chain
  double h_theory = kNaN;       ///< its theoretical bound (linear stability)
  std::string stiff_note;       ///< e.g. the implicit method's error far beyond the bound
  int extreme_finished = 0, extreme_diagnosed = 0, extreme_not_run = 0;  ///< section 4
};

struct Summary {
  double cost_seconds = 1e-2;
  std::string cost_scene = "arm7";
  std::vector<MethodSummary> methods;  ///< kMethods first, then the others as they report
  std::string stiff_chain;             ///< which chain the stable steps are for
  std::vector<std::string> diagnosed;  ///< "case: diagnostic" of the extreme cases
  int extreme_solved = 0, extreme_total = 0;
  int extreme_undiagnosed = 0;                  ///< finished beyond the stability bound
  std::map<std::string, int> extreme_outcomes;  ///< runs per outcome (extreme.hpp)
  Summary() {
    for (Integrator i : kMethods) of(i);
  }
  /// The summary of integrator \p i (added when new).
  MethodSummary& of(Integrator i) {
    MethodSummary& s = of(soa::integrator_name(i));
    s.method = i;
    s.order = i == Integrator::DormandPrince ? 5 : soa::integrator_order(i);
    return s;
  }
  /// The summary of the method called \p name (added when new).
  MethodSummary& of(const std::string& name) {
    for (MethodSummary& s : methods)
      if (s.name == name) return s;
    methods.emplace_back();
    methods.back().name = name;
    return methods.back();
  }
};

}  // namespace soa::lesson::sim
