/// \file
/// Section 3c of the simulation report: the stiff-spring chains from their own start (fast
/// modes excited), integrated by the adaptive implicit methods, esdirk4 and radau5
/// (soa::simulate, L-stable) and CVODE's BDF (cvode.hpp), and the work-precision diagram of
/// the stiffest chain with every method.
///
/// From the scene's start the fast modes oscillate at \f$\omega_{\max}\f$ and decay as
/// \f$e^{-\zeta\omega_{\max} t}\f$: an accurate method follows them with small steps while
/// their amplitude exceeds the tolerance; after that an L-stable method damps what it no longer
/// resolves and its step can follow the slow motion. An explicit method's step stays below its
/// stability bound \f$h^*\f$ throughout.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "checklist.hpp"
#include "cvode.hpp"
#include "plot.hpp"
#include "report.hpp"
#include "scenes.hpp"
#include "stiff.hpp"
#include "support.hpp"
#include "sweeps.hpp"

namespace soa::lesson::sim {

namespace stiff_implicit {

/// One row of l8_sim_stiff_implicit.csv.
struct Row {
  double k_max = kNaN, omega_max = kNaN, h_rk4 = kNaN;
  std::string method;  ///< esdirk4, radau5 or cvode
  double tol = kNaN;
  Run r;
  double error = kNaN;
  double mean_step() const { return r.ok ? r.summary.t / double(r.summary.steps) : kNaN; }
};

/// The reference of a chain from its own start: Dormand-Prince at tolerance 1e-13 (its step
/// held near its stability bound on the stiff chains), checked against a second method,
/// esdirk4 at 1e-12 (Reference::agreement). RK4 Richardson-extrapolated, the second method of
/// section 1, is not one here: at steps inside its bound, \f$h\omega_{\max} \le 2.8\f$, the
/// excited fast modes are far from its asymptotic range.
inline Reference chain_reference(const SimProblem& p) {
  Reference ref;
  soa::SimulationOptions opt;
  opt.method = Integrator::DormandPrince;
  opt.tol = 1e-13;
  const Run a = run(p, opt);
  opt.method = Integrator::Esdirk;
  opt.tol = 1e-12;
  const Run b = run(p, opt);
  if (!a.ok || !b.ok) {
    ref.diagnostic = !a.ok ? a.diagnostic : b.diagnostic;
    return ref;
  }
  ref.x = a.x;
  ref.steps = a.summary.steps;
  ref.agreement = state_error(b.x, a.x);
  return ref;
}

/// The work-precision diagram of one chain from its own start (l8_sim_wp_stiff_own.csv, .png):
/// every method of kMethods, esdirk4, radau5 and CVODE. The explicit fixed-step methods from
/// just inside their stability bound \f$0.99\,h^*\f$ downward, the implicit midpoint rule
/// from \f$T/8\f$ (A-stable: no bound), the adaptive ones over tolerances \f$10^{-2} \ldots
/// 10^{-12}\f$ (\f$10^{-13}\f$ for ours). At esdirk4's and radau5's errors down to 1e-8 it
/// compares their time with each other method's at the same error (the curves interpolated
/// in log-log; an explicit method whose run at \f$0.99\,h^*\f$ is already more accurate
/// costs at least that run) and checks that radau5 is faster than every explicit method at
/// every error above 1e-8, esdirk4 above 1e-6. Below that, dopri5 (order 5, its cost set by
/// its stability bound, growing little as its tolerance tightens) catches up with the order-4
/// esdirk4: reported (l8_sim_wp_stiff_own.md), not checked.
inline void wp_figure(Checklist& checks, const std::filesystem::path& out, const SimProblem& p,
                      const stiff::Linear& L, const Reference& ref, bool quick) {
  const double lo = std::max(10 * ref.agreement, 1e-12);
  const double budget = quick ? 0.05 : 1, min_seconds = quick ? 0 : 0.02;
  std::ofstream csv(out / "l8_sim_wp_stiff_own.csv");
  csv << "scene,method,h,tol,steps,evaluations,seconds,error,energy_drift,diagnostic\n";
  std::ofstream gp(out / "l8_sim_wp_stiff_own.gp");
  gp << "# written by lab_simulation: the curves of l8_sim_wp_stiff_own.png\n"
     << "title_text = '" << p.title << ", from its own start, T = " << num(p.t_end, "%g")
     << " s'\ncvode_built = " << (kHaveCvode ? 1 : 0) << "\nmethods = '";
  std::vector<std::vector<Point>> curves;
  std::vector<bool> is_explicit;
  for (Integrator m : kMethods) {
    const bool expl = m != Integrator::ImplicitMidpoint && !soa::is_adaptive(m);
    const double h_first = expl ? 0.99 * stiff::stability_bound(m, L) : kNaN;
    curves.push_back(sweep(p, ref.x, m, lo, budget, min_seconds, h_first));
    is_explicit.push_back(m != Integrator::ImplicitMidpoint);
  }
  curves.push_back(sweep(p, ref.x, Integrator::Esdirk, lo, budget, min_seconds));
  is_explicit.push_back(false);
  const std::size_t i_esdirk = curves.size() - 1;
  curves.push_back(sweep(p, ref.x, Integrator::Radau5, lo, budget, min_seconds));
  is_explicit.push_back(false);
  const std::size_t i_radau = curves.size() - 1;
  curves.push_back(sweep_cvode(p, ref.x, lo, budget, min_seconds));
  is_explicit.push_back(false);
  const std::size_t i_cvode = curves.size() - 1;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    if (c == i_cvode && !kHaveCvode) continue;
    for (const Point& pt : curves[c]) {
      const soa::SimulationSummary& s = pt.r.summary;
      csv << "stiff_own," << pt.name << "," << num(pt.h) << "," << num(pt.tol) << ","
          << (pt.r.ok ? std::to_string(s.steps) : "") << ","
          << (pt.r.ok ? std::to_string(s.evaluations) : "") << "," << num(pt.r.seconds) << ","
          << num(pt.error) << ","
          << (pt.r.ok ? num(s.max_energy_drift / std::max(1.0, std::abs(s.energy0))) : "") << ","
          << csv_field(pt.r.ok ? "" : pt.r.diagnostic) << "\n";
    }
    gp << (c ? " " : "") << curves[c].front().name;
  }
  gp << "'\n";
  csv.close();
  gp.close();

  // esdirk4, then radau5, against each explicit method and CVODE, at the method's own errors
  // above 1e-8: the time of the other curve at the same error (interpolated), or bounds on
  // it where the curve does not bracket the error. An explicit method whose run at 0.99 h*
  // (its largest stable step) is already below the error costs at least that run; one whose
  // sweep ends above the error (time budget) costs more than its last run.
  std::ofstream md(out / "l8_sim_wp_stiff_own.md");
  for (const std::size_t i_impl : {i_esdirk, i_radau}) {
    const std::string self = curves[i_impl].front().name;
    // Checked at the errors above 1e-6 for esdirk4 (order 4: below, dopri5, whose cost is set
    // by its stability bound, catches up) and above 1e-8 for radau5; below, reported.
    const double kChecked = i_impl == i_radau ? 1e-8 : 1e-6;
    md << (i_impl == i_esdirk ? "" : "\n") << "| " << self << " tol | error | " << self
       << " time | CVODE at that error | fastest explicit method at that error |\n"
          "|---|---|---|---|---|\n";
    double worst = 0;  // the largest time / explicit time at equal error, checked range
    std::string worst_what = "-";
    int undecided = 0, compared = 0, cvode_faster = 0, cvode_compared = 0;
    int points = 0, won = 0;  // the method's errors above 1e-8; those where it beat every one
    std::string not_won;      // "method at error (x ratio)" where an explicit method is faster
    for (const Point& e : curves[i_impl]) {
      if (!e.r.ok || !(e.error > 1e-8)) continue;
      const bool checked = e.error > kChecked;
      bool beat_all = true;
      ++points;
      std::printf("    %s tol %.0e: error %.2e in %s;", self.c_str(), e.tol, e.error,
                  time_text(e.r.seconds * 1e9).c_str());
      std::string best_name = "-", cvode_text = "-";
      double best_t = kNaN;
      bool best_lower = false;  // best_t is a lower bound
      for (std::size_t c = 0; c < curves.size(); ++c) {
        if (c == i_impl || (c == i_cvode && !kHaveCvode)) continue;
        const std::string& name = curves[c].front().name;
        double t = cost_at(curves[c], e.error).seconds;
        bool lower = false;  // t is a lower bound on the method's time at this error
        if (std::isnan(t)) {
          const Point *first = nullptr, *last = nullptr;
          for (const Point& pt : curves[c]) {
            if (!pt.r.ok) continue;
            if (!first) first = &pt;
            last = &pt;
          }
          if (first && is_explicit[c] && first->error <= e.error)
            t = first->r.seconds, lower = true;
          else if (last && last->error > e.error)
            t = last->r.seconds, lower = true;
        }
        std::printf(" %s %s%s", name.c_str(), lower ? "<" : "",
                    std::isnan(t) ? "-" : ("x" + num(e.r.seconds / t, "%.2g")).c_str());
        if (c == i_cvode) {
          cvode_text = std::isnan(t) ? "-" : (lower ? "> " : "") + time_text(t * 1e9);
          if (!std::isnan(t) && !lower) ++cvode_compared, cvode_faster += t < e.r.seconds;
        }
        if (!is_explicit[c]) continue;
        if (checked) ++compared;
        if (std::isnan(t) || (lower && t <= e.r.seconds)) {
          // no run of the method, or a bound that does not decide
          if (checked) ++undecided;
          beat_all = false;
          not_won +=
              (not_won.empty() ? "" : "; ") + name + " at " + num(e.error, "%.1e") + " (undecided)";
          continue;
        }
        if (!(t > e.r.seconds)) {
          beat_all = false;
          not_won += (not_won.empty() ? "" : "; ") + name + " at " + num(e.error, "%.1e") + " (" +
                     self + " x " + num(e.r.seconds / t, "%.2g") + ")";
        }
        if (checked && e.r.seconds / t > worst) {
          worst = e.r.seconds / t;
          worst_what = name + " at error " + num(e.error, "%.1e");
        }
        if (std::isnan(best_t) || t < best_t) best_t = t, best_name = name, best_lower = lower;
      }
      std::printf("\n");
      won += beat_all;
      md << "| " << num(e.tol, "%.0e") << " | " << num(e.error, "%.2e") << " | "
         << time_text(e.r.seconds * 1e9) << " | " << cvode_text << " | " << best_name << ", "
         << (std::isnan(best_t) ? std::string("-")
                                : (best_lower ? "> " : "") + time_text(best_t * 1e9))
         << " |\n";
    }
    std::printf(
        "    (x: %s's time over the method's at the same error; <x: the method needs "
        "more time than that bound says)\n",
        self.c_str());
    md << "\nTimes at equal error: the other curves (the other implicit method among them) "
          "interpolated in log-log at "
       << self
       << "'s error; \"> t\": the curve does not reach that error within its sweep and t "
          "bounds its time from below. "
       << (kHaveCvode ? "CVODE is faster than " + self + " at " + std::to_string(cvode_faster) +
                            " of " + std::to_string(cvode_compared) + " of these errors."
                      : cvode_status() + ".")
       << " " << self << " is faster than every explicit method at " << won << " of these "
       << points << " errors"
       << (not_won.empty() ? std::string(".")
                           : "; where it is not (its time over theirs): " + not_won + ".")
       << "\n";
    // Timings of a few tens of milliseconds decide it: --quick (short sweeps) prints it only.
    const std::string beat = "stiff chain from its own start: " + self +
                             " faster than every explicit method at every error above " +
                             num(kChecked, "%.0e") + " (" + std::to_string(compared - undecided) +
                             " of " + std::to_string(compared) +
                             " comparisons decided; worst time ratio, " + worst_what + ")";
    if (quick)
      std::printf("    %s: %.3g\n", beat.c_str(), undecided == 0 ? worst : kNaN);
    else
      checks.check(beat, undecided == 0 ? worst : kNaN, 1.0 - 1e-12);
    std::printf("    %s against CVODE at equal error: CVODE faster at %d of %d errors\n",
                self.c_str(), cvode_faster, cvode_compared);
  }
  checks.check("l8_sim_wp_stiff_own.md written", bool(md));
  checks.check("l8_sim_wp_stiff_own.png drawn",
               plot("l8_sim_wp_stiff_own.gp", out, "l8_sim_wp_stiff_own.png"));
}

}  // namespace stiff_implicit

/// The stiff-spring chains k_max = 1, 1e2, 1e4, 1e6, 1e8 (--quick: 1, 1e4, 1e8) from their
/// own start over 1 s (--quick 0.25 s): esdirk4, radau5 and CVODE at tolerances 1e-4, 1e-6, 1e-8,
/// against Dormand-Prince at 1e-13; then the work-precision diagram of the stiffest chain.
/// Writes l8_sim_stiff_implicit.csv, .md, l8_sim_wp_stiff_own.csv, .png.
inline void stiff_cvode_table(Checklist& checks, const std::filesystem::path& out, bool quick,
                              Summary& summary) {
  using namespace stiff_implicit;
  checks.section("3c. Stiff-spring chains from their own start: esdirk4, radau5 and CVODE");
  const auto start = std::chrono::steady_clock::now();
  std::printf("  %s\n", cvode_status().c_str());
  const std::vector<double> ks =
      quick ? std::vector<double>{1, 1e4, 1e8} : std::vector<double>{1, 1e2, 1e4, 1e6, 1e8};
  const std::vector<double> tols = {1e-4, 1e-6, 1e-8};
  const double t_end = quick ? 0.25 : 1, min_seconds = quick ? 0 : 0.02;
  std::vector<Row> rows;
  std::vector<double> agreements;
  for (double k : ks) {
    SimProblem p = stiff_chain(k);
    p.t_end = t_end;
    const stiff::Linear L = stiff::linearize(p);
    const double h_rk4 = stiff::stability_bound(Integrator::RK4, L);
    const auto ref_start = std::chrono::steady_clock::now();
    const Reference ref = chain_reference(p);
    char what[200];
    if (!ref.diagnostic.empty()) {
      std::snprintf(what, sizeof what, "k_max %.0e: reference solution", k);
      checks.check(what + (" (" + ref.diagnostic + ")"), false);
      continue;
    }
    std::printf(
        "  k_max = %.0e: omega_max = %.3g rad/s, RK4's bound %.3e s; reference dopri5(1e-13) "
        "%ld steps, agrees with esdirk4(1e-12) to %.1e (%.2f s)\n",
        k, L.omega_max, h_rk4, ref.steps, ref.agreement,
        std::chrono::duration<double>(std::chrono::steady_clock::now() - ref_start).count());
    std::snprintf(what, sizeof what, "k_max %.0e: reference agrees with esdirk4 at 1e-12", k);
    /// The errors the table resolves are those above ten times the agreement: 1e-7 keeps
    /// every error at tolerance 1e-8 and above resolvable on the chains that reach it.
    checks.check(what, ref.agreement, 1e-7);
    agreements.push_back(ref.agreement);
    std::map<std::string, double> worst;  // error / tol, worst over the tolerances
    for (double tol : tols)
      for (const std::string method : {"esdirk4", "radau5", "cvode"}) {
        Row r;
        r.k_max = k, r.omega_max = L.omega_max, r.h_rk4 = h_rk4, r.method = method, r.tol = tol;
        const bool ours = method != "cvode";
        if (ours) {
          soa::SimulationOptions opt;
          opt.method = soa::integrator_from_name(method);
          opt.tol = tol;
          r.r = run(p, opt, min_seconds);
        } else {
          r.r = cvode_run(p, tol, min_seconds);
        }
        r.error = r.r.ok ? state_error(r.r.x, ref.x) : kNaN;
        const soa::SimulationSummary& s = r.r.summary;
        if (r.r.ok)
          std::printf(
              "    %-7s tol %.0e: %6ld steps, %7ld evaluations, %5ld Jacobians, %s, error "
              "%.2e (%.2g tol), mean step %.2f x RK4's bound\n",
              method.c_str(), tol, s.steps, s.evaluations, s.jacobians,
              time_text(r.r.seconds * 1e9).c_str(), r.error, r.error / tol, r.mean_step() / h_rk4);
        else
          std::printf("    %-7s tol %.0e: %s\n", method.c_str(), tol, r.r.diagnostic.c_str());
        if (ours) {
          std::snprintf(what, sizeof what, "k_max %.0e: %s at tol %.0e reaches t_end", k,
                        method.c_str(), tol);
          checks.check(what + (r.r.ok ? std::string() : " (" + r.r.diagnostic + ")"), r.r.ok);
          worst[method] = std::max(worst[method], r.r.ok ? r.error / tol : kNaN);
        } else if (kHaveCvode) {
          std::snprintf(what, sizeof what, "k_max %.0e: cvode at tol %.0e reaches t_end", k, tol);
          checks.check(what + (r.r.ok ? std::string() : " (" + r.r.diagnostic + ")"), r.r.ok);
        }
        rows.push_back(r);
      }
    /// esdirk4 and radau5 converge: the error at the tightest tolerance at most 1e-2 times
    /// the error at the loosest (tolerances 1e4 apart). esdirk4's global error is not bounded
    /// by its tolerance, a bound on the local error: error / tol is reported (worst over the
    /// tolerances). radau5's, whose Newton error is held at 3e-5 of the tolerance and whose
    /// order-3 estimate is pessimistic for an order-5 method, is checked within 10 x tol.
    for (const std::string method : {"esdirk4", "radau5"}) {
      double e_loose = kNaN, e_tight = kNaN;
      for (const Row& r : rows) {
        if (r.k_max != k || r.method != method) continue;
        if (r.tol == tols.front()) e_loose = r.error;
        if (r.tol == tols.back()) e_tight = r.error;
      }
      std::printf("    %s: worst error / tol %.3g\n", method.c_str(), worst[method]);
      std::snprintf(what, sizeof what,
                    "k_max %.0e: %s's error falls as its tolerance tightens (%.1e at %.0e, "
                    "%.1e at %.0e)",
                    k, method.c_str(), e_loose, tols.front(), e_tight, tols.back());
      checks.check(what, e_tight <= 1e-2 * e_loose);
    }
    std::snprintf(what, sizeof what, "k_max %.0e: radau5's error within 10 x its tolerance", k);
    checks.check(what, worst["radau5"], 10);
    if (k == ks.back()) {
      /// On the stiffest chain esdirk4's mean step at the loosest tolerance is at least 10
      /// times RK4's bound: once the excited fast modes have decayed (time constant
      /// 1/(zeta omega_max)), its step follows the slow motion.
      double ratio = kNaN;
      for (const Row& r : rows)
        if (r.k_max == k && r.method == "esdirk4" && r.tol == tols.front())
          ratio = r.mean_step() / h_rk4;
      std::snprintf(what, sizeof what,
                    "k_max %.0e: esdirk4's mean step at tol %.0e >= 10 x RK4's bound (x %.3g)", k,
                    tols.front(), ratio);
      checks.check(what, ratio >= 10);
    }
    if (k == ks.back()) {
      std::printf("  work-precision, k_max = %.0e from its own start (T = %g s):\n", k, t_end);
      wp_figure(checks, out, p, L, ref, quick);
    }
  }

  // The summary's "largest stable step" of the implicit adaptive methods: none (L-stable and
  // A(alpha)-stable BDF), and what they did on the stiffest chain from its own start.
  for (const std::string method : {"esdirk4", "radau5", "cvode"}) {
    if (method == "cvode" && !kHaveCvode) continue;
    for (const Row& r : rows)
      if (r.k_max == ks.back() && r.method == method && r.tol == tols.front() && r.r.ok) {
        MethodSummary& ms =
            method == "cvode" ? summary.of(method) : summary.of(soa::integrator_from_name(method));
        ms.stiff_note = "no bound; from the chain's own start (k_max " + num(r.k_max, "%.0e") +
                        ", tol " + num(r.tol, "%.0e") + ") mean step " +
                        num(r.mean_step() / r.h_rk4, "%.3g") + " x RK4's bound, error " +
                        num(r.error, "%.1e");
      }
  }

  std::ofstream csv(out / "l8_sim_stiff_implicit.csv");
  csv << "k_max,omega_max,rk4_bound,method,tol,steps,rejected,evaluations,jacobians,seconds,"
         "error,mean_step,mean_step_over_rk4_bound,diagnostic\n";
  for (const Row& r : rows) {
    const soa::SimulationSummary& s = r.r.summary;
    csv << num(r.k_max, "%.0e") << ',' << num(r.omega_max, "%.6g") << ',' << num(r.h_rk4, "%.6e")
        << ',' << r.method << ',' << num(r.tol, "%.0e") << ',' << s.steps << ',' << s.rejected
        << ',' << s.evaluations << ',' << s.jacobians << ',' << num(r.r.seconds) << ','
        << num(r.error) << ',' << num(r.mean_step()) << ',' << num(r.mean_step() / r.h_rk4) << ','
        << csv_field(r.r.ok ? "" : r.r.diagnostic) << '\n';
  }
  csv.close();
  std::ofstream md(out / "l8_sim_stiff_implicit.md");
  if (!kHaveCvode) md << "**" << cvode_status() << ".**\n\n";
  md << "| k_max (N m/rad) | omega_max (rad/s) | method | tol | steps | rejected | evaluations | "
        "Jacobians | time | error at t = "
     << num(t_end, "%g")
     << " s | error / tol | mean step / RK4's bound |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    if (r.method == "cvode" && !kHaveCvode) continue;
    const soa::SimulationSummary& s = r.r.summary;
    md << "| " << num(r.k_max, "%.0e") << " | " << num(r.omega_max, "%.3g") << " | " << r.method
       << " | " << num(r.tol, "%.0e") << " | ";
    if (!r.r.ok) {
      md << r.r.diagnostic << " | | | | | | | |\n";
      continue;
    }
    md << s.steps << " | " << s.rejected << " | " << s.evaluations << " | " << s.jacobians << " | "
       << time_text(r.r.seconds * 1e9) << " | " << num(r.error, "%.2e") << " | "
       << num(r.error / r.tol, "%.2g") << " | " << num(r.mean_step() / r.h_rk4, "%.3g") << " |\n";
  }
  const double worst_agreement =
      agreements.empty() ? kNaN : *std::max_element(agreements.begin(), agreements.end());
  md << "\nThe chains of section 3 from their own start (random angles within 0.1 rad of rest "
        "and rates up to 1 rad/s on every joint: the fast modes excited) over "
     << num(t_end, "%g")
     << " s. Error: state error at the end against Dormand-Prince at tolerance 1e-13 (checked "
        "against esdirk4 at tolerance 1e-12: agreement at most "
     << num(worst_agreement, "%.1e")
     << "). Evaluations: forward dynamics calls, those of the Jacobians by differences "
        "included (esdirk4, radau5: 2 n_v per Jacobian, forward differences; CVODE: its "
        "difference-quotient dense Jacobian, 2 n_v per Jacobian, counted by "
        "CVodeGetNumLinRhsEvals). Rejected: esdirk4's and radau5's error-test and Newton "
        "failures; CVODE's "
        "error-test and nonlinear-solver convergence failures. Mean step: T / steps, against "
        "RK4's stability bound on the chain linearized at rest. "
     << cvode_status() << ".\n";
  md.close();
  checks.check("l8_sim_stiff_implicit.csv, l8_sim_stiff_implicit.md written",
               bool(csv) && bool(md));
  std::printf("  (section 3c: %.2f s)\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace soa::lesson::sim
