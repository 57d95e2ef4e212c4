/// \file
/// Section 4 of the simulation report: the extreme chains of lessons 5-8 (mass ratios up to
/// \f$10^{\pm 8}\f$, rotational inertias down to \f$10^{-9}\f$, all axes parallel, rates of
/// 100 rad/s, long chains, a massless tip) simulated over a fixed horizon by every
/// integrator: the energy drift and the state error of each run, or the diagnostic that
/// stopped it.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "../timing/problems.hpp"
#include "checklist.hpp"
#include "plot.hpp"
#include "report.hpp"
#include "support.hpp"

namespace soa::lesson::sim {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// One extreme case: a chain of lesson 6 (soa::lesson::timing::extreme_chain(), without its
/// hinge forces, so that the energy is conserved), the fixed step of the fixed-step methods
/// and the number of RK4 steps of the reference (reference()).
struct ExtremeCase {
  soa::lesson::timing::Spec spec;
  double dt = 1e-3;
  long ref_steps = 2000;
};

/// The case as a problem over [0, \p t_end]: the chain, its state, no hinge forces.
inline SimProblem extreme_problem(const ExtremeCase& c, double t_end) {
  const soa::lesson::timing::Problem<double> p = soa::lesson::timing::extreme_chain(c.spec);
  SimProblem q;
  q.name = soa::lesson::timing::short_name(c.spec);
  q.title = q.name;
  q.m = p.m;
  q.x0 = p.x;
  q.t_end = t_end;
  return q;
}

/// The energy scale of the drift: the largest of \f$|E_0|\f$, the kinetic energy
/// \f$\tfrac12\beta^*\mathcal M\beta\f$ at the start, and the potential energy the chain can
/// exchange, \f$\sum_k m_k |g| r_k\f$ with \f$r_k\f$ the distance of body k's centre of mass
/// from the base when the chain is straight (a straight chain at rest starts with
/// \f$E_0 = 0\f$: a relative drift needs a scale that does not vanish).
inline double energy_scale(const SimProblem& p) {
  soa::ChainSystem sys(p.m);
  soa::State x = p.x0;
  const double E0 = sys.energy(x);
  x.beta.setZero();
  const double kinetic = E0 - sys.energy(x);
  double potential = 0, r = 0;
  for (int k = p.m.n(); k >= 1; --k) {  // base to tip, links of 1 m, centre of mass 0.5 m out
    potential += p.m.body(k).M.mass() * p.m.gravity.norm() * (r + 0.5);
    r += 1;
  }
  return std::max({std::abs(E0), kinetic, potential});
}

/// One integrator on one case.
struct ExtremeRun {
  Integrator method = Integrator::RK4;
  bool ran = false;         ///< false: not run (cost)
  Run r;                    ///< the run, or its diagnostic
  double drift = kNaN;      ///< max |E - E0| / energy_scale()
  double error = kNaN;      ///< state_error() against the reference
  double threshold = kNaN;  ///< what the check asks of rk4 and dopri5
};

/// One case: the reference and the five runs.
struct ExtremeResult {
  ExtremeCase c;
  std::string name;
  Reference ref;
  double scale = kNaN;
  double lambda = kNaN;  ///< largest_stiffness()
  std::vector<ExtremeRun> runs;
};

/// The selection: lesson 6's chains of 10 links (equal masses, J = 1e-9, mass ratios
/// \f$10^{\pm3}, 10^{\pm6}, 10^{\pm8}\f$ straight, \f$10^{\pm8}\f$ in a random pose), rates
/// up to 100 rad/s, long chains in a random pose (100 and 1000 links) and the massless tip.
/// The straight chains start at rest with every axis parallel and fall under gravity in their
/// plane. The fixed step is 1 ms; 10 µs at 100 rad/s, where the whip of the chain reaches
/// \f$|\beta| \approx 2\cdot10^3\f$ rad/s within the horizon (\f$h|\beta| \le 0.02\f$),
/// and 0.1 ms on the 1000-link chain, whose tip whips to 300 rad/s (\f$h|\beta| = 0.03\f$). (Rates of 100 rad/s on
/// the chains of mass ratio 1e-3 and 1e-6 whip their light links, up to \f$10^6\f$ rad/s at
/// 1e-6: the two reference solutions part by \f$10^{-2}\f$ within 0.03 s, so they are left
/// out.)
/// The reference's RK4 takes 2000 steps (15 µs, \f$h|\beta| < 10^{-3}\f$ on the slow
/// chains; 1000 on the 1000-link chain, \f$h|\beta| = 0.01\f$), 20000 where light links
/// or high rates make the motion fast.
inline std::vector<ExtremeCase> extreme_cases(bool quick) {
  using soa::lesson::timing::Spec;
  std::vector<ExtremeCase> cases;
  auto add = [&](Spec s, double dt = 1e-3, long ref_steps = 2000) {
    cases.push_back({s, dt, ref_steps});
  };
  add({"", 10, 1, 1e-3});
  if (!quick) add({"", 10, 1, 1e-9});
  for (const double r :
       quick ? std::vector<double>{1e-8} : std::vector<double>{1e-3, 1e3, 1e-6, 1e6, 1e-8, 1e8})
    add({"", 10, r, 1e-9}, 1e-3, std::abs(std::log10(r)) > 3 ? 20000 : 2000);
  for (const double r : quick ? std::vector<double>{1e8} : std::vector<double>{1e-8, 1e8})
    add({"", 10, r, 1e-9, 7});
  if (!quick) add({"", 10, 1, 1e-3, 7, 100}, 1e-5, 20000);
  add({"", quick ? 30 : 100, 1, 1e-3, 7, 1});
  if (!quick) add({"", 1000, 1, 1e-3, 7, 1}, 1e-4, 1000);
  add({"", 10, 1, 1e-3, 0, 0, 0.0});
  if (!quick) add({"", 1000, 1, 1e-3, 7, 1, 0.0});
  return cases;
}

/// Implicit midpoint and the variational integrator form their Jacobian by 2 nv forward
/// dynamics per step and factor it (\f$O(n^3)\f$), and radau5 factors a real and a complex
/// matrix of size 2 nv whenever its step changes: run up to this many links only. esdirk4
/// keeps its Jacobian across steps and runs on every case.
constexpr int kImplicitMaxN = 100;

/// The integrators of the extreme cases: the report's five, esdirk4, radau5 and the
/// variational integrator.
inline std::vector<Integrator> extreme_methods() {
  std::vector<Integrator> m(kMethods.begin(), kMethods.end());
  m.push_back(Integrator::Esdirk);
  m.push_back(Integrator::Radau5);
  m.push_back(Integrator::Variational);
  return m;
}

/// How a run ended, for the summary's counts.
enum class Outcome { NotRun, Finished, Singular, BeyondBound, BlowUp, Newton, Other };

inline const char* outcome_name(Outcome o) {
  switch (o) {
    case Outcome::NotRun:
      return "not run (cost)";
    case Outcome::Finished:
      return "finished";
    case Outcome::Singular:
      return "stopped: singular D (physically singular chain)";
    case Outcome::BeyondBound:
      return "stopped: beyond the stability bound (stiffness monitor)";
    case Outcome::BlowUp:
      return "stopped: blow-up";
    case Outcome::Newton:
      return "stopped: Newton failure";
    case Outcome::Other:
      return "stopped: other";
  }
  return "?";
}

/// The outcome of a run from its diagnostic.
inline Outcome outcome(bool ran, bool ok, const std::string& d) {
  if (!ran) return Outcome::NotRun;
  if (ok) return Outcome::Finished;
  if (d.find("singular") != std::string::npos) return Outcome::Singular;
  if (d.find("beyond the stability bound") != std::string::npos) return Outcome::BeyondBound;
  if (d.find("Newton") != std::string::npos) return Outcome::Newton;
  if (d.find("blow-up at t = ") != std::string::npos) return Outcome::BlowUp;
  return Outcome::Other;
}

/// \p s with every '|' (which would end a markdown table cell) written as '‖'.
inline std::string no_bars(const std::string& s) {
  std::string t;
  for (const char ch : s) t += ch == '|' ? std::string("‖") : std::string(1, ch);
  return t;
}

/// A diagnostic in a few words, for the tables: "refused: singular D(1) of body b1",
/// "beyond its stability bound at t = 0.004 s (h lambda 3.1)" (the stiffness monitor),
/// "blow-up at t = 0.01 s (h lambda 118)", "Newton failed at t = 0.026 s (‖dZ‖ 0.3, h lambda
/// 18.8)", with \f$h\lambda\f$ the estimated stiffness times the step at the last state;
/// any other message whole. Norms as ‖x‖ ('|' would end a table cell).
inline std::string short_diagnostic(const std::string& d) {
  auto after = [&](const std::string& key, const std::string& stop) {
    const std::size_t i = d.find(key);
    if (i == std::string::npos) return std::string();
    const std::size_t j = i + key.size();
    return d.substr(j, d.find(stop, j) - j);
  };
  std::string s;
  if (d.find("singular") != std::string::npos) {
    s = "refused: singular D(" + after("articulated inertia D(", ")") + ") of body " +
        after("body '", "'");
  } else if (d.find("beyond the stability bound at t = ") != std::string::npos) {
    s = "beyond its stability bound at t = " + after("stability bound at t = ", " s") +
        " s (h lambda " + after("|h lambda| = ", " ") + ")";
  } else if (d.find("blow-up at t = ") != std::string::npos) {
    const bool newton = d.find("Newton") != std::string::npos;
    s = newton ? "Newton failed" : "blow-up";
    s += " at t = " + after("blow-up at t = ", " s") + " s";
    if (newton && d.find("|dZ| = ") != std::string::npos) {
      s += " (‖dZ‖ " + after("|dZ| = ", ",") + ")";
    }
    const std::size_t last = d.find(" at the last state");
    if (last != std::string::npos) {
      const std::size_t open = d.rfind('(', last);
      s += " (h lambda " + d.substr(open + 1, last - open - 1) + ")";
    }
  } else {
    s = d;
  }
  return no_bars(s);
}

/// The largest \f$|\lambda|\f$ of the Jacobian of the rate along the motion
/// (soa::stiffness_estimate() at the start and after every eighth of the horizon, on a dopri5
/// run at \p tol): \f$h\lambda\f$ says whether a fixed step h resolves the fastest motion.
/// It must be taken along the way: the light links pulled by heavy ones are fast modes that
/// build up as the chain falls, and a whip peaks halfway. NaN when the run stops.
inline double largest_stiffness(const SimProblem& p, double tol) {
  soa::ChainSystem sys(p.m), probe(p.m);
  soa::Stepper stepper(probe);
  soa::State x = p.x0;
  soa::SimulationOptions opt;
  opt.method = Integrator::DormandPrince;
  opt.tol = tol;
  opt.t_end = p.t_end;
  const double every = p.t_end / 8;
  double lambda = 0, next = 0;
  try {
    soa::simulate(sys, x, opt, [&](double t, const soa::State& y) {
      if (t < next - 1e-12 * p.t_end) return;
      lambda = std::max(lambda, soa::stiffness_estimate(stepper, p.m.nv(), t, y));
      while (next <= t + 1e-12 * p.t_end) next += every;
    });
  } catch (const soa::Error&) {
    return kNaN;
  }
  return lambda;
}

/// The stability bound of \f$h\lambda\f$ on an undamped oscillation (soa::stability_note()):
/// symplectic Euler 2, RK4 2.83; explicit Euler none (it grows at every step, slowly while
/// \f$h\lambda\f$ is small), dopri5 and implicit midpoint not limited here (adaptive,
/// A-stable).
inline double bound(Integrator method) {
  return method == Integrator::SymplecticEuler ? 2.0 : method == Integrator::RK4 ? 2.83 : kInf;
}

/// Each extreme case over a fixed horizon with every integrator: energy drift and state
/// error, or the diagnostic that stopped it. Fills Summary::diagnosed, extreme_solved,
/// extreme_total.
///
/// The horizon is 0.03 s: long enough for the fast modes of the light links to build up as
/// the straight chains fall (the explicit methods at 1 ms blow up after 6 to 22 ms), short
/// enough for the reference to resolve every case kept: at 0.1 s the chain at 100 rad/s and
/// the 1000-link chain whip to \f$|\beta| \approx 2.5\cdot10^3\f$ and
/// \f$1.4\cdot10^3\f$ rad/s and the two reference solutions part by \f$10^{-2}\f$, an error
/// of the reference, not of the integrators.
inline void extreme_section(Checklist& checks, const std::filesystem::path& out, bool quick,
                            Summary& summary) {
  checks.section("4. Extreme cases of lessons 5-8 simulated");
  const auto start = std::chrono::steady_clock::now();
  const double t_end = 0.03;
  const double tol = 1e-8;  // dopri5's tolerance
  std::vector<ExtremeResult> results;
  int nonfinite = 0, refused_named = 0, refused = 0;
  int accurate_checked = 0;
  double worst_agreement = 0, worst_ratio = 0;
  for (const ExtremeCase& c : extreme_cases(quick)) {
    const auto case_start = std::chrono::steady_clock::now();
    ExtremeResult res;
    res.c = c;
    res.name = soa::lesson::timing::short_name(c.spec);
    const SimProblem p = extreme_problem(c, t_end);
    res.scale = energy_scale(p);
    res.ref = reference(p, 1e-13, c.ref_steps);
    if (res.ref.diagnostic.empty()) res.lambda = largest_stiffness(p, tol);
    const bool massless_tip = c.spec.tip_mass >= 0;
    for (const Integrator method : extreme_methods()) {
      ExtremeRun e;
      e.method = method;
      if ((method == Integrator::ImplicitMidpoint || method == Integrator::Variational ||
           method == Integrator::Radau5) &&
          p.m.n() > kImplicitMaxN) {
        res.runs.push_back(e);
        continue;
      }
      e.ran = true;
      soa::SimulationOptions opt;
      opt.method = method;
      opt.dt = soa::is_adaptive(method) ? 0 : c.dt;
      opt.tol = tol;
      e.r = run(p, opt, 2e-3);  // runs under 2 ms repeated, the median time kept
      if (e.r.ok) {
        e.drift = e.r.summary.max_energy_drift / res.scale;
        if (res.ref.diagnostic.empty()) e.error = state_error(e.r.x, res.ref.x);
        if (!e.r.x.theta.allFinite() || !e.r.x.beta.allFinite() || std::isnan(e.drift)) ++nonfinite;
      } else if (e.r.diagnostic.empty()) {
        ++nonfinite;
      }
      if (massless_tip) {
        ++refused;
        if (!e.r.ok && e.r.diagnostic.find("'b1'") != std::string::npos &&
            e.r.diagnostic.find("singular") != std::string::npos)
          ++refused_named;
      }
      // The accurate methods on the runs that finish: RK4's global error on
      // \f$\dot y = \lambda y\f$ is \f$t\,\lambda(h\lambda)^4/120\f$ per unit state
      // (checked where \f$h\lambda \le 0.5\f$, the asymptotic regime); dopri5 keeps each
      // step's local error below tol, so after N steps the error is about N tol (esdirk4 and
      // radau5 likewise, their error estimates of order 3 filtered for stiff modes). RK4 is
      // allowed a factor 100 (the nonlinear chain is not \f$\dot y = \lambda y\f$: the
      // whipping chain at 100 rad/s reaches 8 times the linear estimate; one order less would
      // be 1/(h lambda) = 60 times more), dopri5 a factor 10. Neither can beat the rounding
      // of the forward dynamics (\f$\varepsilon\,{\rm cond}(\mathcal M)\f$ per step,
      // accumulated), which the reference agreement measures (and 1e-10 at least: the
      // rounding of up to 3000 steps of a state of size 1, where a lucky reference agreement
      // of 1e-14 says nothing): the threshold is the largest.
      const double hl = c.dt * res.lambda;
      const bool resolved = soa::is_adaptive(method) || (method == Integrator::RK4 && hl <= 0.5);
      if (resolved && e.r.ok && res.ref.diagnostic.empty()) {
        const double truncation = method == Integrator::RK4
                                      ? 100 * t_end * res.lambda * std::pow(hl, 4) / 120
                                      : 10 * double(e.r.summary.steps) * tol;
        e.threshold = std::max({truncation, 100 * res.ref.agreement, 1e-10});
        ++accurate_checked;
        worst_ratio = std::max(worst_ratio, std::isnan(e.error) ? kInf : e.error / e.threshold);
      }
      res.runs.push_back(e);
    }
    if (!massless_tip)  // a reference stopped by a diagnostic fails the check below
      worst_agreement =
          std::max(worst_agreement, res.ref.diagnostic.empty() ? res.ref.agreement : kInf);
    std::printf(
        "  %-28s %5.2f s h lambda %8s ref agree %8s ", res.name.c_str(),
        std::chrono::duration<double>(std::chrono::steady_clock::now() - case_start).count(),
        num(c.dt * res.lambda, "%.1e").c_str(),
        res.ref.diagnostic.empty() ? num(res.ref.agreement, "%.1e").c_str() : "-");
    for (const ExtremeRun& e : res.runs)
      std::printf(" %s %s", soa::integrator_name(e.method),
                  !e.ran   ? "-"
                  : e.r.ok ? num(e.error, "%.1e").c_str()
                           : "diag");
    std::printf("\n");
    if (!res.ref.diagnostic.empty() && !massless_tip)
      std::printf("    reference: %s\n", res.ref.diagnostic.c_str());
    results.push_back(std::move(res));
  }

  // Summary: runs finished of runs run, and the runs stopped by a diagnostic, per case:
  // "r1 J1e-03 tip0 n10: every method refused: singular D(1) of body b1".
  summary.extreme_solved = summary.extreme_total = summary.extreme_undiagnosed = 0;
  summary.diagnosed.clear();
  summary.extreme_outcomes.clear();
  for (const ExtremeResult& res : results) {
    std::vector<std::string> stopped;
    std::string silent;  // finished beyond the stability bound: not solved, not diagnosed
    int ran = 0;
    for (const ExtremeRun& e : res.runs) {
      const Outcome o = outcome(e.ran, e.r.ok, e.r.diagnostic);
      ++summary.extreme_outcomes[outcome_name(o)];
      MethodSummary& ms = summary.of(e.method);
      ++(o == Outcome::NotRun     ? ms.extreme_not_run
         : o == Outcome::Finished ? ms.extreme_finished
                                  : ms.extreme_diagnosed);
      if (!e.ran) continue;
      ++ran, ++summary.extreme_total;
      if (!e.r.ok)
        stopped.push_back(std::string(soa::integrator_name(e.method)) + " " +
                          short_diagnostic(e.r.diagnostic));
      else
        ++summary.extreme_solved;
      if (e.r.ok && res.c.dt * res.lambda > bound(e.method) && ++summary.extreme_undiagnosed)
        silent += std::string("; ") + soa::integrator_name(e.method) +
                  " finished beyond its stability bound (h lambda " +
                  num(res.c.dt * res.lambda, "%.2g") + ") with error " + num(e.error, "%.1e") +
                  ", undiagnosed";
    }
    if (stopped.empty() && silent.empty()) continue;
    const bool same = std::all_of(res.runs.begin(), res.runs.end(), [&](const ExtremeRun& e) {
      return !e.ran ||
             short_diagnostic(e.r.diagnostic) == short_diagnostic(res.runs[0].r.diagnostic);
    });
    std::string text = res.name + ": ";
    if (int(stopped.size()) == ran && same) {
      text += "every method " + short_diagnostic(res.runs[0].r.diagnostic);
    } else {
      for (std::size_t i = 0; i < stopped.size(); ++i) text += (i ? "; " : "") + stopped[i];
    }
    summary.diagnosed.push_back(stopped.empty() ? res.name + ": " + silent.substr(2)
                                                : text + silent);
  }

  // l8_sim_extreme.csv: one row per case and method.
  std::ofstream csv(out / "l8_sim_extreme.csv");
  csv << "id,case,n,mass_ratio,J,pose,rate,dt,method,status,steps,evaluations,energy_drift,"
         "state_error,threshold,reference_agreement,seconds,h_lambda,diagnostic\n";
  int id = 0;
  for (const ExtremeResult& res : results) {
    ++id;
    const soa::lesson::timing::Spec& s = res.c.spec;
    for (const ExtremeRun& e : res.runs) {
      const std::string status = !e.ran ? "not run (cost)" : e.r.ok ? "finished" : "diagnosed";
      csv << id << ',' << csv_field(res.name) << ',' << s.n << ',' << num(s.ratio, "%g") << ','
          << num(s.J, "%g") << ',' << (s.pose_seed ? "random" : "straight") << ','
          << num(s.rate, "%g") << ',' << (soa::is_adaptive(e.method) ? "" : num(res.c.dt, "%g"))
          << ',' << soa::integrator_name(e.method) << ',' << status << ','
          << (e.r.ok ? std::to_string(e.r.summary.steps) : "") << ','
          << (e.r.ok ? std::to_string(e.r.summary.evaluations) : "") << ',' << num(e.drift) << ','
          << num(e.error) << ',' << num(e.threshold) << ',' << num(res.ref.agreement) << ','
          << num(e.r.seconds) << ','
          << (soa::is_adaptive(e.method) ? "" : num(res.c.dt * res.lambda)) << ','
          << csv_field(e.r.ok ? "" : e.r.diagnostic) << '\n';
    }
  }
  csv.close();

  // l8_sim_extreme.md: one row per case, each method's state error / energy drift.
  std::ofstream md(out / "l8_sim_extreme.md");
  md << "Extreme chains of lesson 6 simulated over " << num(t_end, "%g")
     << " s from rest (straight) or with random rates (bent), no hinge forces, gravity in "
        "the plane of motion. Fixed steps 1 ms (10 µs at 100 rad/s, 0.1 ms on the 1000-link "
        "chain), dopri5, esdirk4 and radau5 at tolerance "
     << num(tol, "%.0e")
     << ". The explicit fixed-step methods run with soa::simulate's stiffness monitor "
        "(h lambda by power iteration at the start, every 100 steps, 25 for rk4, and at the "
        "end): beyond the method's stability bound it stops the run. Each cell: state error "
        "against the reference / relative energy drift (largest "
        "abs(E - E0) over the energy scale), then steps and wall time; or the diagnostic that "
        "stopped the run (h lambda: estimated stiffness times step where it stopped). "
        "Reference: dopri5 at 1e-13; its agreement with RK4 at 2000 or 20000 steps beside "
        "it (1000 steps on the 1000-link chain). h lambda: the fixed step times the largest "
        "estimated stiffness along the motion (dopri5's path, every eighth of the horizon); a "
        "run that finished beyond its method's stability bound by that estimate (symplectic "
        "Euler 2, RK4 2.83) would be marked \"beyond stability\" and counted undiagnosed.\n\n"
        "| case | h lambda | reference agreement |";
  for (const Integrator m : extreme_methods()) md << ' ' << soa::integrator_name(m) << " |";
  md << "\n|---|---|---|";
  for (std::size_t i = 0; i < extreme_methods().size(); ++i) md << "---|";
  md << '\n';
  for (const ExtremeResult& res : results) {
    md << "| " << res.name << " | "
       << (std::isnan(res.lambda) ? "-" : num(res.c.dt * res.lambda, "%.2g")) << " | "
       << (res.ref.diagnostic.empty() ? num(res.ref.agreement, "%.1e") : "-") << " |";
    for (const ExtremeRun& e : res.runs) {
      if (!e.ran)
        md << " not run (cost) |";
      else if (!e.r.ok)
        md << ' ' << short_diagnostic(e.r.diagnostic) << " |";
      else
        md << ' ' << (std::isnan(e.error) ? "-" : num(e.error, "%.1e")) << " / "
           << num(e.drift, "%.1e") << " (" << e.r.summary.steps << ", "
           << time_text(e.r.seconds * 1e9) << ")"
           << (res.c.dt * res.lambda > bound(e.method) ? ", beyond stability" : "") << " |";
    }
    md << '\n';
  }
  md << "\nThe diagnostics in full (l8_sim_extreme.csv has every one):\n\n";
  for (const ExtremeResult& res : results) {
    std::vector<std::string> seen;
    for (const ExtremeRun& e : res.runs) {
      if (!e.ran || e.r.ok) continue;
      if (std::find(seen.begin(), seen.end(), e.r.diagnostic) != seen.end()) continue;
      seen.push_back(e.r.diagnostic);
      const bool every = std::all_of(res.runs.begin(), res.runs.end(), [&](const ExtremeRun& o) {
        return !o.ran || o.r.diagnostic == e.r.diagnostic;
      });
      md << "- " << res.name << ", " << (every ? "every method" : soa::integrator_name(e.method))
         << ": " << no_bars(e.r.diagnostic) << '\n';
    }
  }
  md.close();

  std::printf("  %d of %d runs finished\n", summary.extreme_solved, summary.extreme_total);
  for (const auto& [what, count] : summary.extreme_outcomes)
    std::printf("    %-60s %d\n", what.c_str(), count);
  checks.check("no run finished beyond its stability bound undiagnosed (" +
                   std::to_string(summary.extreme_undiagnosed) + ")",
               summary.extreme_undiagnosed == 0);
  checks.check(
      "every stopped run names its cause (singular D, stability bound, blow-up with h "
      "lambda, Newton failure)",
      summary.extreme_outcomes.count(outcome_name(Outcome::Other)) == 0);
  {
    // esdirk4 finishes every case that is not physically singular, radau5 every one it runs.
    for (const Integrator m : {Integrator::Esdirk, Integrator::Radau5}) {
      int unfinished = 0, ran = 0;
      for (const ExtremeResult& res : results)
        for (const ExtremeRun& e : res.runs) {
          if (e.method != m || !e.ran) continue;
          ++ran;
          if (outcome(e.ran, e.r.ok, e.r.diagnostic) != Outcome::Finished &&
              outcome(e.ran, e.r.ok, e.r.diagnostic) != Outcome::Singular)
            ++unfinished;
        }
      checks.check(std::string(soa::integrator_name(m)) +
                       " finishes every case that is not physically singular (" +
                       std::to_string(unfinished) + " of " + std::to_string(ran) + " runs not)",
                   unfinished == 0);
    }
  }
  checks.check("massless tip: every method stops with 'singular D' naming the tip b1 (" +
                   std::to_string(refused_named) + " of " + std::to_string(refused) + ")",
               refused > 0 && refused_named == refused);
  checks.check("every run finishes with a finite state or stops with soa::Error (never NaN)",
               nonfinite == 0);
  // The reference must resolve the errors it measures: agreement within 1e-8 leaves a factor
  // 100 below the smallest error bound of dopri5 (10 N tol >= 1e-6 for N >= 10 steps).
  checks.check("reference: dopri5 1e-13 and RK4 agree on every case not refused (worst)",
               worst_agreement, 1e-8);
  checks.check(
      "rk4 (h lambda <= 0.5), dopri5, esdirk4 and radau5 within their error bounds (worst "
      "error / "
      "threshold, " +
          std::to_string(accurate_checked) + " runs)",
      worst_ratio, 1.0);
  checks.check("l8_sim_extreme.csv and l8_sim_extreme.md written", bool(csv) && bool(md));
  checks.check("figure written: l8_sim_extreme.png",
               soa::lesson::plot("l8_sim_extreme.gp", out, "l8_sim_extreme.png"));
  std::printf("  extreme cases: %.1f s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace soa::lesson::sim
