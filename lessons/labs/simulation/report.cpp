// The simulation lab: the integrators of lesson 8's forward dynamics, run by `make run` into
// build/course/labs/simulation/ (`make test` runs it with --quick, ctest lab.simulation):
//   lab_simulation OUTPUT_DIR [--quick]
// 1. Error against run time: on each default scene (double pendulum, seven-joint arm,
//    50-link chain) and a stiff-spring chain, every integrator over a sweep of steps (or
//    tolerances, dopri5), final-state error against a reference solution, the order of
//    convergence fitted: l8_sim_work_precision.csv, l8_sim_orders.md, and one figure per
//    scene l8_sim_wp_SCENE.png; esdirk4 and SUNDIALS CVODE (cvode.hpp) over the same
//    tolerances as dopri5, their cost at equal error: l8_sim_cvode.md.
// 2. Long-horizon energy of conservative scenes (pendulum, double pendulum, seven-joint
//    arm): symplectic Euler, implicit midpoint, RK4 and the variational integrator:
//    l8_sim_energy.csv, l8_sim_energy_stops.csv, l8_sim_energy.md, l8_sim_energy.png; the
//    double pendulum by RK4 and implicit midpoint side by side in the 3D viewer
//    l8_sim_rk4_vs_midpoint_view/.
// 3. The stiff-spring chains, k = 1 ... 1e8 (stiff.hpp): l8_sim_stiff.csv/.md/.png.
// 3c. The same chains from their own start by esdirk4 and CVODE (stiff_implicit.hpp):
//    l8_sim_stiff_implicit.csv/.md; the stiffest one's work-precision diagram with every
//    method, l8_sim_wp_stiff_own.csv/.png.
// 4. The extreme cases of lessons 5-8 simulated (extreme.hpp): l8_sim_extreme.csv/.md.
// 5. The one-page summary the notes include: l8_sim_summary.md.
// --quick: short horizons and sweeps, so that every code path runs in seconds.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "args.hpp"
#include "checklist.hpp"
#include "cvode.hpp"
#include "extreme.hpp"
#include "plot.hpp"
#include "report.hpp"
#include "scenes.hpp"
#include "stiff.hpp"
#include "stiff_implicit.hpp"
#include "support.hpp"
#include "sweeps.hpp"
#include "viewer.hpp"

namespace {

using namespace soa::lesson::sim;
using soa::lesson::Checklist;
using soa::lesson::csv_field;
using soa::lesson::num;
namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------
// 1. Error against run time.

/// The observed order: the slope of \f$\log e\f$ against \f$\log h\f$ (fixed steps), or
/// against \f$-\log(\text{evaluations})\f$ (dopri5: work grows as \f$h^{-1}\f$), fitted to
/// the three smallest errors above \p lo (the reference's accuracy) and below 1: the
/// asymptotic range, where the leading error term dominates (at coarser steps the arm's RK4
/// error still falls as \f$h^{4.8}\f$). The range ends at the run of smallest error: after
/// it the method's own rounding floor (radau5 on the arm at tolerance 1e-13, 28 563 steps:
/// 9e-11, against 2e-11 at 1e-12).
double observed_order(const std::vector<Point>& pts, double lo) {
  std::vector<double> x, y;
  for (const Point& pt : pts) {
    // dopri5 at loose tolerances takes the few steps its start and growth limit allow,
    // whatever the tolerance: only runs of at least 16 steps are in its asymptotic range
    // (the same for every adaptive method).
    if (!pt.r.ok || !(pt.error > lo && pt.error < 1) || (pt.adaptive && pt.r.summary.steps < 16))
      continue;
    x.push_back(pt.adaptive ? 1.0 / double(pt.r.summary.evaluations) : pt.h);
    y.push_back(pt.error);
  }
  const std::size_t end = std::size_t(std::min_element(y.begin(), y.end()) - y.begin()) + 1;
  x.resize(std::min(x.size(), end));
  y.resize(x.size());
  if (x.size() > 3) {
    x.erase(x.begin(), x.end() - 3);
    y.erase(y.begin(), y.end() - 3);
  }
  return fitted_slope(x, y, lo, 1);
}

/// Whether dopri5's steps were set by stability rather than accuracy: its work grew less
/// than four-fold from the loosest tolerance to the tightest (on the stiff chain the
/// controller holds \f$h|\lambda|_{\max}\f$ near the stability boundary at any tolerance).
bool stability_limited(const std::vector<Point>& pts) {
  long first = 0, last = 0;
  for (const Point& pt : pts)
    if (pt.r.ok) (first == 0 ? first : last) = pt.r.summary.evaluations;
  return first > 0 && last > 0 && double(last) < 4.0 * double(first);
}

/// The smallest error among the runs that took at most \p seconds.
double error_within(const std::vector<Point>& pts, double seconds) {
  double best = kNaN;
  for (const Point& pt : pts)
    if (pt.r.ok && pt.r.seconds <= seconds && !(pt.error >= best)) best = pt.error;
  return best;
}

/// Rows of l8_sim_work_precision.csv.
void write_points(std::ofstream& csv, const std::vector<Point>& pts) {
  for (const Point& pt : pts) {
    const soa::SimulationSummary& s = pt.r.summary;
    const double drift = s.max_energy_drift / std::max(1.0, std::abs(s.energy0));
    csv << pt.scene << "," << pt.name << "," << num(pt.h) << "," << num(pt.tol) << ","
        << (pt.r.ok ? std::to_string(s.steps) : "") << ","
        << (pt.r.ok ? std::to_string(s.evaluations) : "") << "," << num(pt.r.seconds) << ","
        << num(pt.error) << "," << (pt.r.ok ? num(drift) : "") << ","
        << csv_field(pt.r.ok ? "" : pt.r.diagnostic) << "\n";
  }
}

/// The cost of the adaptive methods at one error level on one scene.
struct CvodeComparison {
  std::string scene;
  double level = kNaN;
  Cost dopri5, esdirk4, cvode;
};

/// l8_sim_cvode.md: the table of costs at equal error and, per scene, CVODE's time as a
/// multiple of dopri5's and esdirk4's.
bool write_cvode_comparison(const fs::path& out, const std::vector<CvodeComparison>& cs) {
  std::ofstream md(out / "l8_sim_cvode.md");
  if (!kHaveCvode) md << "**" << cvode_status() << ".**\n\n";
  md << "| Scene | error | dopri5: time, evaluations | esdirk4: time, evaluations | CVODE: time, "
        "evaluations | fastest | fewest evaluations |\n|---|---|---|---|---|---|---|\n";
  const char* names[3] = {"dopri5", "esdirk4", "CVODE"};
  int fastest[3] = {0, 0, 0}, compared = 0;
  for (const CvodeComparison& c : cs) {
    const Cost* v[3] = {&c.dopri5, &c.esdirk4, &c.cvode};
    md << "| " << c.scene << " | " << num(c.level, "%.0e") << " |";
    int best_t = -1, best_e = -1;
    for (int i = 0; i < 3; ++i) {
      if (std::isnan(v[i]->seconds)) {
        md << " - |";
        continue;
      }
      md << " " << soa::lesson::time_text(v[i]->seconds * 1e9) << ", "
         << num(v[i]->evaluations, "%.0f") << " |";
      if (best_t < 0 || v[i]->seconds < v[best_t]->seconds) best_t = i;
      if (best_e < 0 || v[i]->evaluations < v[best_e]->evaluations) best_e = i;
    }
    md << " " << (best_t < 0 ? "-" : names[best_t]) << " | " << (best_e < 0 ? "-" : names[best_e])
       << " |\n";
    const int reached = int(!std::isnan(c.dopri5.seconds)) + int(!std::isnan(c.esdirk4.seconds)) +
                        int(!std::isnan(c.cvode.seconds));
    if (reached == 3) ++compared, ++fastest[best_t];
  }
  md << "\nCost at equal error: seconds and evaluations (forward dynamics calls, CVODE's "
        "difference-quotient Jacobian included) interpolated in log-log between the two runs of "
        "a sweep whose errors bracket the level; - where a sweep does not bracket it (it stops "
        "at the reference's resolution and at a time budget per run, and a loose tolerance can "
        "already be below 1e-4).\n\n";
  if (compared > 0)
    md << "Of the " << compared << " comparisons where all three reach the error, CVODE is the "
       << "fastest in " << fastest[2] << ", dopri5 in " << fastest[0] << ", esdirk4 in "
       << fastest[1] << ".";
  // Per scene: CVODE's time over dopri5's and over esdirk4's at each level.
  auto ratio = [](double a, double b) {
    return std::isnan(a / b) ? std::string("-") : num(a / b, "%.2g");
  };
  std::string scene;
  for (const CvodeComparison& c : cs) {
    if (c.scene != scene) {
      md << (scene.empty() ? "\n\nCVODE's time over dopri5's / over esdirk4's at equal error:\n"
                           : ".\n")
         << "\n- " << c.scene << ": ";
      scene = c.scene;
    } else {
      md << "; ";
    }
    md << num(c.level, "%.0e") << ": " << ratio(c.cvode.seconds, c.dopri5.seconds) << " / "
       << ratio(c.cvode.seconds, c.esdirk4.seconds);
  }
  if (!scene.empty()) md << ".\n";
  return bool(md);
}

/// The tolerance of the order fits' reference: the tightest that simulate accepts (100 ε),
/// rounded up. The fits use only errors above ten times the reference's agreement with RK4,
/// so the reference is as accurate as dopri5 can make it.
constexpr double kOrderReferenceTol = 3e-14;

void work_precision_section(Checklist& checks, const fs::path& out, bool quick, Summary& summary) {
  checks.section("1. Error against run time (work-precision)");
  /// The problems: the default scenes from the states their files give, and the stiff-spring
  /// chain of section 3 at a moderate stiffness ratio (its fastest mode ~380 rad/s, so the
  /// explicit methods are stable only below a step set by stiffness, not accuracy).
  std::vector<SimProblem> problems;
  try {
    problems.push_back(default_scene("double_pendulum", "double pendulum", quick ? 0.5 : 2));
    problems.push_back(default_scene("arm7", "seven-joint arm", quick ? 0.25 : 1));
    problems.push_back(default_scene("chain50", "50-link chain", quick ? 0.05 : 0.5));
  } catch (const std::exception& e) {
    checks.check(std::string("default scenes load (") + e.what() + ")", false);
  }
  problems.push_back(stiff_chain(1e4, 6, 0.02, quick ? 0.05 : 0.2));
  const double budget = quick ? 0.02 : 0.5, min_seconds = quick ? 0 : 0.02;

  std::ofstream csv(out / "l8_sim_work_precision.csv");
  csv << "scene,method,h,tol,steps,evaluations,seconds,error,energy_drift,diagnostic\n";
  std::ofstream orders_gp(out / "l8_sim_orders.gp");
  orders_gp << "# written by lab_simulation: the fitted orders, o_SCENE_METHODINDEX\n";
  std::ofstream md(out / "l8_sim_orders.md");
  md << "| Scene | horizon | reference agreement |";
  for (Integrator m : kMethods) md << " " << soa::integrator_name(m) << " |";
  md << " esdirk4 | radau5 | cvode (slope) |\n|---|---|---|";
  for (std::size_t i = 0; i < kMethods.size() + 3; ++i) md << "---|";
  md << "\n";
  orders_gp << "cvode_built = " << (kHaveCvode ? 1 : 0) << "\n";
  std::printf("  %s\n", cvode_status().c_str());
  std::vector<CvodeComparison> comparisons;
  const auto section_start = std::chrono::steady_clock::now();
  double seconds_new = 0;  // esdirk4's and CVODE's sweeps

  for (const SimProblem& p : problems) {
    /// The reference: dopri5 at kOrderReferenceTol, checked against RK4 at 20 000 and 40 000
    /// steps extrapolated; errors below 10 times their agreement are not used in the fits.
    const Reference ref = reference(p, kOrderReferenceTol, quick ? 4000 : 20000);
    if (!ref.diagnostic.empty()) {
      checks.check(p.name + ": reference solution (" + ref.diagnostic + ")", false);
      continue;
    }
    std::printf(
        "  %-16s T = %g s, n = %d: reference dopri5(%g) %ld steps, agrees with RK4 "
        "to %.2e\n",
        p.name.c_str(), p.t_end, p.m.n(), kOrderReferenceTol, ref.steps, ref.agreement);
    checks.check(p.name + ": reference agrees with a second method (RK4)", ref.agreement, 1e-8);
    const double lo = std::max(10 * ref.agreement, 1e-12);
    md << "| " << p.title << " | " << num(p.t_end, "%g") << " s | " << num(ref.agreement, "%.1e")
       << " |";
    std::vector<Point> dopri5_pts;
    for (std::size_t i = 0; i < kMethods.size(); ++i) {
      const Integrator method = kMethods[i];
      const std::vector<Point> pts = sweep(p, ref.x, method, lo, budget, min_seconds);
      write_points(csv, pts);
      if (method == Integrator::DormandPrince) dopri5_pts = pts;
      const bool limited = method == Integrator::DormandPrince && stability_limited(pts);
      const double order = limited ? kNaN : observed_order(pts, lo);
      const int expected = method == Integrator::DormandPrince ? 5 : soa::integrator_order(method);
      summary.of(method).orders.emplace_back(p.name, order);
      if (p.name == summary.cost_scene)
        summary.of(method).error_at_cost = error_within(pts, summary.cost_seconds);
      orders_gp << "o_" << p.name << "_" << i + 1 << " = "
                << (std::isnan(order) ? std::string("NaN") : num(order, "%.2f")) << "\n";
      md << " " << (limited ? std::string("stability-limited") : num(order, "%.2f")) << " |";
      std::printf("    %-17s %2zu runs, order %5.2f (expected %d)\n", soa::integrator_name(method),
                  pts.size(), order, expected);
      /// The order found must be the method's: within 0.3 for the fixed-step methods, 4.5 to
      /// 5.7 for dopri5 (its controller also adapts the step to the solution). On the stiff
      /// chain explicit Euler is stable only at steps too small for the time budget to reach
      /// its asymptotic range, and dopri5's step is set by stability (no fit: not checked).
      if (quick) continue;
      const bool fits = method == Integrator::DormandPrince ? order >= 4.5 && order <= 5.7
                                                            : std::abs(order - expected) <= 0.3;
      if (p.name == "stiff_chain" && (std::isnan(order) || method == Integrator::Euler)) continue;
      checks.check(p.name + ": " + soa::integrator_name(method) + " converges at its order (" +
                       num(order, "%.2f") + ")",
                   fits);
    }
    // esdirk4 and CVODE beside the methods of kMethods, over the same tolerances as dopri5.
    const auto new_start = std::chrono::steady_clock::now();
    const std::vector<Point> esdirk_pts =
        sweep(p, ref.x, Integrator::Esdirk, lo, budget, min_seconds);
    const std::vector<Point> radau_pts =
        sweep(p, ref.x, Integrator::Radau5, lo, budget, min_seconds);
    const std::vector<Point> cvode_pts = sweep_cvode(p, ref.x, lo, budget, min_seconds);
    const std::vector<Point> variational_pts =
        sweep(p, ref.x, Integrator::Variational, lo, budget, min_seconds);
    seconds_new +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - new_start).count();
    write_points(csv, esdirk_pts);
    write_points(csv, radau_pts);
    if (kHaveCvode) write_points(csv, cvode_pts);
    write_points(csv, variational_pts);
    {
      /// The variational integrator (implicit midpoint in (theta, p)) at fixed steps: order 2
      /// within 0.3, as the fixed-step methods above.
      const double order = observed_order(variational_pts, lo);
      MethodSummary& ms = summary.of(Integrator::Variational);
      ms.orders.emplace_back(p.name, order);
      if (p.name == summary.cost_scene)
        ms.error_at_cost = error_within(variational_pts, summary.cost_seconds);
      orders_gp << "o_" << p.name << "_variational = "
                << (std::isnan(order) ? std::string("NaN") : num(order, "%.2f")) << "\n";
      std::printf("    %-17s %2zu runs, order %5.2f (expected 2)\n", "variational",
                  variational_pts.size(), order);
      // Its step costs a dense Jacobian of 2 n_v columns: on the 50-link chain the time
      // budget can end the sweep before three runs reach the asymptotic range (no fit: not
      // checked, reported as "-").
      if (!quick && !std::isnan(order))
        checks.check(p.name + ": variational converges at its order (" + num(order, "%.2f") + ")",
                     std::abs(order - 2) <= 0.3);
    }
    for (const std::vector<Point>* pts : {&esdirk_pts, &radau_pts, &cvode_pts}) {
      if (pts == &cvode_pts && !kHaveCvode) {
        orders_gp << "o_" << p.name << "_cvode = NaN\n";
        md << " not built |";
        continue;
      }
      const std::string name = pts->front().name;
      const double slope = observed_order(*pts, lo);
      MethodSummary& ms = pts == &cvode_pts ? summary.of(name) : summary.of(pts->front().method);
      ms.orders.emplace_back(p.name, slope);
      if (p.name == summary.cost_scene) ms.error_at_cost = error_within(*pts, summary.cost_seconds);
      orders_gp << "o_" << p.name << "_" << name << " = "
                << (std::isnan(slope) ? std::string("NaN") : num(slope, "%.2f")) << "\n";
      md << " " << num(slope, "%.2f") << " |";
      std::printf("    %-17s %2zu runs, slope %5.2f against 1/evaluations%s\n", name.c_str(),
                  pts->size(), slope,
                  pts == &esdirk_pts  ? " (order 4)"
                  : pts == &radau_pts ? " (order 5)"
                                      : " (BDF orders 1-5: not one order)");
    }
    if (kHaveCvode) {
      /// CVODE converges: its error at the tightest tolerance reached (the sweep stops at the
      /// reference's resolution) is below 1e-6 and below 1e-3 times its error at the loosest.
      const Point* loose = nullptr;
      const Point* tight = nullptr;
      for (const Point& pt : cvode_pts) {
        if (!pt.r.ok) continue;
        if (!loose) loose = &pt;
        tight = &pt;
      }
      const bool all_ok =
          std::all_of(cvode_pts.begin(), cvode_pts.end(), [](const Point& pt) { return pt.r.ok; });
      checks.check(p.name + ": cvode reaches t_end at every tolerance" +
                       (all_ok ? std::string() : " (" + cvode_pts.back().r.diagnostic + ")"),
                   all_ok);
      /// With --quick the sweep stops at a run time of milliseconds, which the machine's load
      /// sets: the two are printed, not checked.
      if (loose && tight && quick) {
        std::printf("    cvode: %.1e at tol %.0e, %.1e at tol %.0e (not checked with --quick)\n",
                    loose->error, loose->tol, tight->error, tight->tol);
      } else if (loose && tight) {
        checks.check(p.name + ": cvode error falls as its tolerance tightens (" +
                         num(loose->error, "%.1e") + " at tol " + num(loose->tol, "%.0e") + ", " +
                         num(tight->error, "%.1e") + " at " + num(tight->tol, "%.0e") + ")",
                     tight->error <= 1e-3 * loose->error);
        checks.check(p.name + ": cvode error at its tightest tolerance below 1e-6", tight->error,
                     1e-6);
      }
    } else {
      std::printf("    cvode: %s\n", cvode_status().c_str());
    }
    // The cost at equal error: l8_sim_cvode.md.
    for (double level : {1e-4, 1e-6, 1e-8}) {
      if (level < lo) continue;
      CvodeComparison c;
      c.scene = p.title;
      c.level = level;
      c.dopri5 = cost_at(dopri5_pts, level);
      c.esdirk4 = cost_at(esdirk_pts, level);
      c.cvode = cost_at(cvode_pts, level);
      comparisons.push_back(c);
    }
    md << "\n";
  }
  md << "\nOrder found: slope of log(error) against log(h); for the adaptive methods (dopri5, "
        "esdirk4, radau5, cvode) against log(1/evaluations). Expected: euler 1, symplectic-euler "
        "1, rk4 4, dopri5 5, implicit-midpoint 2, esdirk4 4, radau5 5 (the implicit ones not "
        "checked: their Jacobians and Newton iterations are part of the evaluations). CVODE "
        "changes its BDF order (1 to 5) with the "
        "step: its slope is reported, not compared with an order. "
     << cvode_status() << ".\n";
  std::printf(
      "  (esdirk4, radau5 and cvode sweeps: %.2f s of the section's %.2f s)\n", seconds_new,
      std::chrono::duration<double>(std::chrono::steady_clock::now() - section_start).count());
  checks.check("l8_sim_cvode.md written", write_cvode_comparison(out, comparisons));
  checks.check("l8_sim_work_precision.csv, l8_sim_orders.md written", bool(csv) && bool(md));
  csv.close();  // gnuplot reads them next
  orders_gp.close();
  checks.check("figures written: l8_sim_wp_*.png",
               soa::lesson::plot("l8_sim_work_precision.gp", out, "l8_sim_wp_arm7.png"));
}

// ---------------------------------------------------------------------------------------
// 2. Energy over a long horizon.

/// A pendulum of one link (the double pendulum's upper link alone): its mass matrix is
/// constant, so symplectic Euler in \f$(\theta, \beta)\f$ is a symplectic map.
SimProblem pendulum(double t_end) {
  SimProblem p = default_scene("double_pendulum", "pendulum", t_end);
  std::vector<soa::Body> one = {p.m.body(p.m.n())};
  one[0].name = "link";
  p.m = soa::Model::from_base_first(one);
  p.m.gravity = soa::Vec3<double>(0, 0, -9.81);
  p.x0 = soa::State{soa::VecX<double>::Constant(1, 1.0), soa::VecX<double>::Zero(1)};
  p.name = "pendulum";
  return p;
}

/// \f$|E(t) - E(0)|\f$ along one run, sampled as the maximum over windows that grow
/// geometrically in time (so that a log-log plot shows both the bounded oscillation and a
/// drift).
struct EnergyTrace {
  std::vector<double> t, drift;
  double first_half = 0, second_half = 0;  ///< max |E - E0| over each half of the horizon
  std::string diagnostic;
  double stopped_at = kNaN;  ///< the time of the blow-up the diagnostic gives
  /// The median of \f$E - E_0\f$ over the first and the last tenth of the horizon: a drift
  /// moves it, the spikes of a chaotic motion's fastest passages (which set the maxima) do
  /// not.
  double median_first = kNaN, median_last = kNaN;
};

/// The median of \p v (reordered); NaN when empty.
double median(std::vector<double>& v) {
  if (v.empty()) return kNaN;
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
  return v[v.size() / 2];
}

/// The time in a diagnostic of soa::simulate() that stopped a run ("... blow-up at t = 73.12
/// s, ...", "... beyond the stability bound at t = 2 s, ..."), NaN when there is none.
double blow_up_time(const std::string& diagnostic) {
  for (const std::string key : {"blow-up at t = ", "stability bound at t = "}) {
    const std::size_t at = diagnostic.find(key);
    if (at != std::string::npos) return std::atof(diagnostic.c_str() + at + key.size());
  }
  return kNaN;
}

EnergyTrace energy_trace(const SimProblem& p, Integrator method, double h) {
  EnergyTrace tr;
  soa::ChainSystemT<double> sys(p.m, p.f_ext);
  soa::ChainSystemT<double> meter(p.m, p.f_ext);  // energy evaluations, not counted as work
  soa::State x = p.x0;
  soa::SimulationOptions opt;
  opt.method = method;
  opt.dt = h;
  opt.t_end = p.t_end;
  const double E0 = meter.energy(x);
  double window_end = 10 * h, window_max = 0;
  std::vector<double> first_tenth, last_tenth;
  try {
    soa::simulate(sys, x, opt, [&](double t, const soa::State& xs) {
      const double e = meter.energy(xs) - E0, d = std::abs(e);
      if (t <= p.t_end / 10) first_tenth.push_back(e);
      if (t > 0.9 * p.t_end) last_tenth.push_back(e);
      window_max = std::max(window_max, d);
      (t <= p.t_end / 2 ? tr.first_half : tr.second_half) =
          std::max(t <= p.t_end / 2 ? tr.first_half : tr.second_half, d);
      if (t >= window_end) {
        tr.t.push_back(t);
        tr.drift.push_back(window_max);
        window_max = 0;
        window_end *= 1.1;
      }
    });
  } catch (const soa::Error& e) {
    tr.diagnostic = e.what();
    tr.stopped_at = blow_up_time(tr.diagnostic);
    if (window_max > 0) {  // the last, unfinished window: the growth up to the stop
      tr.t.push_back(tr.stopped_at);
      tr.drift.push_back(window_max);
    }
  }
  tr.median_first = median(first_tenth);
  tr.median_last = median(last_tenth);
  return tr;
}

/// The double pendulum from its file's state over 60 s at h = 0.02 s, by RK4 and by implicit
/// midpoint, side by side in one viewer (notes page "Viewing a chain in 3D"): every second
/// state of each run (1501 frames), with \f$V(k)\f$, \f$f(k)\f$, the lower link's path and
/// the energy of each frame, whose drift the page shows per run. The two runs stay close (the
/// largest distance between their tips is printed): what tells them apart is the energy. At
/// this step RK4's energy error is the smaller (order 4 against 2), but it drifts: its largest
/// \f$|E - E_0|\f$ over the frames of the second half is at least 1.5 times that of the
/// first, while implicit midpoint's stays within 1.3 times (the criteria of the long runs
/// above, checked on the frames).
void energy_viewer(Checklist& checks, const fs::path& out) {
  const soa::Scene sc = soa::load_scene(std::string(SOA_SCENE_DIR) + "/double_pendulum.json");
  const double T = 60, h = 0.02;
  soa::view::View view = soa::view::view_of(sc);
  view.title = "Double pendulum over 60 s at h = 0.02 s: RK4 and implicit midpoint";
  std::vector<double> first_half, second_half;
  for (Integrator method : {Integrator::RK4, Integrator::ImplicitMidpoint}) {
    soa::ChainSystemT<double> sys(sc.model, sc.f_ext);
    soa::State x = sc.state;
    soa::SimulationOptions opt;
    opt.method = method;
    opt.dt = h;
    opt.t_end = T;
    soa::view::Recorder rec(sc, T, 1501);
    const soa::SimulationSummary sum =
        soa::simulate(sys, x, opt, [&](double t, const soa::State& xs) { rec.offer(t, xs); });
    rec.record(sum.t, x);
    view.note = rec.note() + " per run";
    view.runs.push_back(rec.take(std::string(soa::integrator_name(method)) + ", h = 0.02 s"));
    // |E - E0| over each half of the frames, and at the end
    const std::vector<soa::view::Frame>& fr = view.runs.back().frames;
    double a = 0, b = 0;
    for (const soa::view::Frame& f : fr)
      (f.t <= T / 2 ? a : b) = std::max(f.t <= T / 2 ? a : b, std::abs(f.energy - fr[0].energy));
    first_half.push_back(a);
    second_half.push_back(b);
    std::printf(
        "  viewer, %-17s max |E - E0| over the frames: first half %.3e J, second half "
        "%.3e J, E0 = %.6f J\n",
        soa::integrator_name(method), a, b, fr[0].energy);
  }
  double tip_gap = 0;
  for (std::size_t i = 0; i < view.runs[0].frames.size(); ++i)
    tip_gap = std::max(tip_gap, (view.runs[0].frames[i].tip - view.runs[1].frames[i].tip).norm());
  std::printf("  viewer: the tips of the two runs at most %.3f m apart\n", tip_gap);
  checks.check("viewer: rk4 energy error drifts over 60 s (x " +
                   num(second_half[0] / first_half[0], "%.2f") + ")",
               second_half[0] >= 1.5 * first_half[0]);
  checks.check("viewer: implicit-midpoint energy error bounded over 60 s (x " +
                   num(second_half[1] / first_half[1], "%.2f") + ")",
               second_half[1] <= 1.3 * first_half[1]);
  // The page's paragraph on this viewer, from these numbers (docs/simulation.md includes it).
  const auto drift = [&](int r) {
    const std::vector<soa::view::Frame>& fr = view.runs[r].frames;
    return (fr.back().energy - fr[0].energy) / std::abs(fr[0].energy);
  };
  std::ofstream md(out / "l8_sim_view.md");
  md << "The two runs stay close (their tips at most " << num(tip_gap, "%.2f")
     << " m apart): watch the energy drift `(E - E0)/|E0|` printed beside the view for each "
        "run. At 60 s RK4's is "
     << num(drift(0), "%.2g") << " and implicit midpoint's " << num(drift(1), "%.2g")
     << "; over the frames, the largest |E - E0| of the second half is "
     << num(second_half[0] / first_half[0], "%.2f") << " times the first half's for RK4 and "
     << num(second_half[1] / first_half[1], "%.2f")
     << " times for implicit midpoint (the report checks: at least 1.5 for a drift, at most "
        "1.3 for a bounded error).\n";
  checks.check("l8_sim_view.md written", bool(md));
  soa::lesson::check_viewer(checks, out, "l8_sim_rk4_vs_midpoint_view", view,
                            "paused=1&t=60&show=frames,tip");
}

/// One scene of section 2 and its step.
struct EnergyScene {
  SimProblem p;
  double h;
};

/// The sentence on a run that stopped: its time and its diagnostic's reason.
std::string stop_sentence(const EnergyTrace& tr) {
  const std::size_t colon = tr.diagnostic.find("beyond the stability bound") != std::string::npos
                                ? std::string::npos  // the monitor's message, whole
                                : tr.diagnostic.find("): ", tr.diagnostic.find("blow-up at t = "));
  const std::size_t semi = tr.diagnostic.find("; estimated", colon);
  const std::string why =
      colon == std::string::npos
          ? tr.diagnostic
          : tr.diagnostic.substr(colon + 3,
                                 semi == std::string::npos ? std::string::npos : semi - colon - 3);
  std::string reason = why;  // "|beta|" would end a table cell
  for (std::size_t at; (at = reason.find("|beta|")) != std::string::npos;)
    reason.replace(at, 6, "max abs(beta)");
  return "stopped at t = " + num(tr.stopped_at, "%.5g") + " s (" + reason + ")";
}

void energy_section(Checklist& checks, const fs::path& out, bool quick) {
  checks.section("2. Energy over a long horizon");
  /// The pendulum, the double pendulum and the seven-joint arm released from their files'
  /// states, over 2000 s. Symplectic Euler is a symplectic map where the mass matrix is
  /// constant (the pendulum); implicit midpoint in \f$(\theta, \beta)\f$ is symmetric; the
  /// variational integrator (implicit midpoint in \f$(\theta, p)\f$) is symplectic and
  /// symmetric for any mass matrix. RK4 is neither: its energy error accumulates, about
  /// linearly in time. h = 0.02 s, but for the arm, whose wrist whips at up to about 90
  /// rad/s after it falls: at h = 0.02 s every method but the variational one, which takes
  /// the steps that turn a joint by over 0.5 rad in pieces, stops there long before the end
  /// (each such run is reported), so its figure is at h = 0.002 s.
  const double T = quick ? 20 : 2000, h = 0.02, h_arm = 0.002;
  const std::vector<EnergyScene> scenes = {
      {pendulum(T), h},
      {default_scene("double_pendulum", "double pendulum", T), h},
      {default_scene("arm7", "seven-joint arm", T), h_arm}};
  const std::vector<Integrator> methods = {Integrator::SymplecticEuler,
                                           Integrator::ImplicitMidpoint, Integrator::RK4,
                                           Integrator::Variational};
  std::ofstream csv(out / "l8_sim_energy.csv");
  csv << "scene,method,t,energy_drift\n";
  std::ofstream stops(out / "l8_sim_energy_stops.csv");
  stops << "scene,method,t,energy_drift\n";
  std::ofstream md(out / "l8_sim_energy.md");
  md << "| scene | h [s] | method | max abs(E - E0), first half [J] | second half [J] | ratio | "
        "median E - E0, first tenth [J] | last tenth [J] | run |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
  // Every run of the section (the scenes at their steps, then the arm at h), none timed: on
  // every core, the most steps first, the results read in this order below.
  const SimProblem& arm = scenes.back().p;
  struct Job {
    const SimProblem* p;
    Integrator method;
    double h;
  };
  std::vector<Job> jobs;
  for (const EnergyScene& sc : scenes)
    for (Integrator method : methods) jobs.push_back({&sc.p, method, sc.h});
  for (Integrator method : methods) jobs.push_back({&arm, method, h});
  std::vector<std::size_t> order(jobs.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto steps = [&](std::size_t i) {
    return jobs[i].p->m.nv() * jobs[i].p->t_end / jobs[i].h;
  };
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return steps(a) > steps(b); });
  std::vector<EnergyTrace> traces(jobs.size());
  on_every_core(order, [&](std::size_t i) {
    traces[i] = energy_trace(*jobs[i].p, jobs[i].method, jobs[i].h);
  });
  std::size_t next_trace = 0;
  std::vector<std::string> stopped;
  for (const EnergyScene& sc : scenes) {
    const SimProblem& p = sc.p;
    for (Integrator method : methods) {
      const EnergyTrace& tr = traces[next_trace++];
      for (std::size_t i = 0; i < tr.t.size(); ++i)
        csv << p.name << "," << soa::integrator_name(method) << "," << num(tr.t[i], "%.6g") << ","
            << num(tr.drift[i]) << "\n";
      if (!tr.diagnostic.empty() && !tr.t.empty())
        stops << p.name << "," << soa::integrator_name(method) << "," << num(tr.t.back(), "%.6g")
              << "," << num(tr.drift.back()) << "\n";
      const double growth = tr.second_half / std::max(tr.first_half, 1e-300);
      std::printf(
          "  %-16s %-17s max |E - E0|: first half %.3e J, second half %.3e J (x %.2f); median E - "
          "E0: first tenth %+.3e J, last %+.3e J%s\n",
          p.name.c_str(), soa::integrator_name(method), tr.first_half, tr.second_half, growth,
          tr.median_first, tr.median_last,
          tr.diagnostic.empty() ? "" : (" " + tr.diagnostic).c_str());
      md << "| " << p.title << " | " << num(sc.h, "%g") << " | " << soa::integrator_name(method)
         << " | " << num(tr.first_half, "%.2e") << " | "
         << (tr.diagnostic.empty() ? num(tr.second_half, "%.2e") : "-") << " | "
         << (tr.diagnostic.empty() ? num(growth, "%.2f") : "-") << " | "
         << num(tr.median_first, "%+.2e") << " | "
         << (tr.diagnostic.empty() ? num(tr.median_last, "%+.2e") : "-") << " | "
         << (tr.diagnostic.empty() ? "to " + num(p.t_end, "%g") + " s" : stop_sentence(tr))
         << " |\n";
      if (!tr.diagnostic.empty())
        stopped.push_back(std::string(soa::integrator_name(method)) + " on the " + p.title + " " +
                          stop_sentence(tr));
      if (quick) continue;
      /// Bounded: the second half's largest error at most 1.3 times the first half's (a
      /// drift linear in time doubles it). Drifting: at least 1.5 times. Symplectic Euler
      /// is checked on the pendulum only; implicit midpoint on the pendulum and the double
      /// pendulum; the variational integrator and RK4 on every scene.
      const bool bounded = method != Integrator::RK4;
      if (method == Integrator::SymplecticEuler && p.name != "pendulum") continue;
      if (method == Integrator::ImplicitMidpoint && p.name == "arm7") continue;
      checks.check(p.name + ": " + soa::integrator_name(method) + " energy error " +
                       (bounded ? "bounded" : "drifts") + " (x " + num(growth, "%.2f") + ")",
                   tr.diagnostic.empty() && (bounded ? growth <= 1.3 : growth >= 1.5));
    }
  }
  // The arm at the step of the other scenes: where each method stops.
  md << "\nThe seven-joint arm at h = " << num(h, "%g") << " s, the step of the other scenes:";
  bool as_said = true;  // what docs/simulation.md says: only the variational run goes on
  for (Integrator method : methods) {
    const EnergyTrace& tr = traces[next_trace++];
    as_said = as_said && tr.diagnostic.empty() == (method == Integrator::Variational);
    md << (method == methods.front() ? " " : "; ") << soa::integrator_name(method) << " "
       << (tr.diagnostic.empty() ? "ran to " + num(arm.t_end, "%g") + " s" : stop_sentence(tr));
  }
  md << ".\n";
  if (!quick)
    checks.check("arm7 at h = " + num(h, "%g") +
                     " s: every method stops with a diagnostic but the variational one, in "
                     "pieces",
                 as_said);
  if (!stopped.empty()) {
    md << "\nRuns stopped by a diagnostic in the figure (their last window marked):\n\n";
    for (const std::string& line : stopped) md << "- " << line << "\n";
  }
  checks.check("l8_sim_energy.csv, l8_sim_energy_stops.csv, l8_sim_energy.md written",
               bool(csv) && bool(stops) && bool(md));
  csv.close();
  stops.close();
  checks.check("figure written: l8_sim_energy.png",
               soa::lesson::plot("l8_sim_energy.gp", out, "l8_sim_energy.png"));
  energy_viewer(checks, out);
}

// ---------------------------------------------------------------------------------------
// 5. The summary page.

void summary_section(Checklist& checks, const fs::path& out, const Summary& s) {
  checks.section("5. Summary");
  std::ofstream md(out / "l8_sim_summary.md");
  md << "| Method | order | order found (double pendulum, arm, chain, stiff chain) | error within "
     << num(s.cost_seconds * 1e3, "%g") << " ms (" << s.cost_scene
     << ") | largest stable step, stiff chain: found / theory | extreme runs: finished / "
        "diagnosed |\n|---|---|---|---|---|---|\n";
  for (const MethodSummary& m : s.methods) {
    md << "| " << m.name << " | " << (m.order > 0 ? std::to_string(m.order) : "variable") << " | ";
    for (std::size_t i = 0; i < m.orders.size(); ++i)
      md << (i ? ", " : "")
         << (std::isnan(m.orders[i].second) ? "-" : num(m.orders[i].second, "%.2f"));
    if (m.orders.empty()) md << "-";
    md << " | " << (std::isnan(m.error_at_cost) ? "-" : num(m.error_at_cost, "%.1e")) << " | ";
    if (!m.stiff_note.empty())
      md << m.stiff_note;
    else if (!std::isnan(m.h_stable))
      md << num(m.h_stable, "%.3g") << " s / " << num(m.h_theory, "%.3g") << " s";
    else
      md << "-";
    md << " | ";
    if (m.extreme_finished + m.extreme_diagnosed + m.extreme_not_run == 0)
      md << "-";
    else
      md << m.extreme_finished << " / " << m.extreme_diagnosed
         << (m.extreme_not_run ? " (" + std::to_string(m.extreme_not_run) + " not run)" : "");
    md << " |\n";
  }
  if (!s.stiff_chain.empty()) md << "\nStable steps on the " << s.stiff_chain << ".\n";
  md << "\nExtreme cases of lessons 5-8 simulated: " << s.extreme_solved << " of "
     << s.extreme_total << " runs finished, " << s.extreme_total - s.extreme_solved
     << " stopped by a diagnostic that names the cause, " << s.extreme_undiagnosed
     << " finished beyond a stability bound undiagnosed:\n\n";
  for (const auto& [what, count] : s.extreme_outcomes) md << "- " << what << ": " << count << "\n";
  md << "\nDiagnosed rather than solved:\n\n";
  if (s.diagnosed.empty()) md << "- none\n";
  for (const std::string& d : s.diagnosed) md << "- " << d << "\n";
  checks.check("l8_sim_summary.md written", bool(md));
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  const fs::path out = soa::lesson::output_dir(argc, argv, &quick);
  std::printf("Lesson 8: simulation report%s (flags: %s)\n", quick ? " (--quick)" : "",
              SOA_TIMING_FLAGS);
  Checklist checks;
  Summary summary;
  try {
    work_precision_section(checks, out, quick, summary);
    energy_section(checks, out, quick);
    stiff_section(checks, out, quick, summary);
    stiff_cvode_table(checks, out, quick, summary);
    extreme_section(checks, out, quick, summary);
    summary_section(checks, out, summary);
  } catch (const std::exception& e) {
    checks.check(std::string("the report ran through (") + e.what() + ")", false);
  }
  return checks.finish();
}
