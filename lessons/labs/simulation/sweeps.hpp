/// \file
/// Work-precision sweeps of the simulation report: one method (or CVODE) over a range of
/// steps or tolerances, the final-state error of each run, and the cost of a curve at a
/// given error, interpolated.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "cvode.hpp"
#include "support.hpp"

namespace soa::lesson::sim {

/// One point of a work-precision diagram.
struct Point {
  std::string scene;
  Integrator method = Integrator::RK4;  ///< not meaningful for CVODE (name "cvode")
  std::string name;                     ///< integrator_name(method), or "cvode"
  bool adaptive = false;                ///< tolerance-driven (dopri5, esdirk4, cvode)
  double h = kNaN, tol = kNaN;          ///< the step (fixed-step methods) or the tolerance
  Run r;
  double error = kNaN;
};

/// The sweep of one method on one problem: fixed steps \f$h = T / (n_0 2^j)\f$, or
/// tolerances \f$10^{-2} \ldots 10^{-13}\f$ for the adaptive methods (dopri5, esdirk4), until
/// the error reaches \p floor or a run takes longer than \p budget seconds. \p h_first, when
/// given, replaces \f$T / n_0\f$ as the first step (\f$h = h_{\rm first} / 2^j\f$), and the
/// runs go without the stiffness monitor: the caller took the step from the stability bound
/// (its stiffness known), and the diagram shows the method at its largest stable step.
inline std::vector<Point> sweep(const SimProblem& p, const soa::State& ref, Integrator method,
                                double floor, double budget, double min_seconds,
                                double h_first = kNaN) {
  std::vector<Point> points;
  soa::SimulationOptions opt;
  opt.method = method;
  if (!std::isnan(h_first)) opt.stiffness = soa::StiffnessPolicy::Off;
  for (int j = 0; j < 40; ++j) {
    Point pt;
    pt.scene = p.name;
    pt.method = method;
    pt.name = soa::integrator_name(method);
    pt.adaptive = soa::is_adaptive(method);
    if (pt.adaptive) {
      pt.tol = std::pow(10.0, -2 - j);
      if (pt.tol < 1e-13) break;
      opt.tol = pt.tol;
    } else {
      pt.h = (std::isnan(h_first) ? p.t_end / 8.0 : h_first) / std::pow(2.0, j);
      opt.dt = pt.h;
    }
    pt.r = run(p, opt, min_seconds);
    pt.error = pt.r.ok ? state_error(pt.r.x, ref) : kNaN;
    points.push_back(pt);
    if (pt.r.ok && (pt.error < floor || pt.r.seconds > budget)) break;
  }
  return points;
}

/// CVODE's sweep: tolerances \f$10^{-2} \ldots 10^{-12}\f$.
inline std::vector<Point> sweep_cvode(const SimProblem& p, const soa::State& ref, double floor,
                                      double budget, double min_seconds) {
  std::vector<Point> points;
  for (int j = 0; j <= 10; ++j) {
    Point pt;
    pt.scene = p.name;
    pt.name = "cvode";
    pt.adaptive = true;
    pt.tol = std::pow(10.0, -2 - j);
    pt.r = cvode_run(p, pt.tol, min_seconds);
    pt.error = pt.r.ok ? state_error(pt.r.x, ref) : kNaN;
    points.push_back(pt);
    if (!kHaveCvode || (pt.r.ok && (pt.error < floor || pt.r.seconds > budget))) break;
  }
  return points;
}

/// The cost of a work-precision curve at error \p level: seconds and evaluations
/// interpolated linearly in \f$(\log e, \log \text{cost})\f$ between the first two
/// consecutive runs whose errors bracket it, \f$e_i \ge \text{level} \ge e_{i+1}\f$ (NaN
/// when no pair does: the curve does not reach the level, or starts below it).
struct Cost {
  double seconds = kNaN, evaluations = kNaN;
};

inline Cost cost_at(const std::vector<Point>& pts, double level) {
  Cost c;
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    const Point &a = pts[i], &b = pts[i + 1];
    if (!a.r.ok || !b.r.ok || !(a.error >= level && b.error <= level && a.error > b.error) ||
        !(b.error > 0))
      continue;
    const double w = std::log(a.error / level) / std::log(a.error / b.error);
    auto lerp = [w](double u, double v) {
      return std::exp((1 - w) * std::log(u) + w * std::log(v));
    };
    c.seconds = lerp(a.r.seconds, b.r.seconds);
    c.evaluations = lerp(double(a.r.summary.evaluations), double(b.r.summary.evaluations));
    return c;
  }
  return c;
}

}  // namespace soa::lesson::sim
