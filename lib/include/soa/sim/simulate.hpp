/// \file
/// The simulation loop: fixed or adaptive steps, energy bookkeeping, and blow-up detection.
#pragma once

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>

#include "soa/sim/integrators.hpp"
#include "soa/sim/stiffness.hpp"

namespace soa {

namespace detail {
/// \p v as printf's `%.<digits>g`, for the messages of simulate().
inline std::string format_g(double v, int digits = 3) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}
}  // namespace detail

/// The message of a run of \p method that blew up at time \p t in step \p step of size \p h,
/// for the reason \p what (whole, however long: it may quote a body's name), with
/// \f$|h\lambda|\f$ estimated at the start (\p h_lambda0) and at the last state
/// (\p h_lambda).
inline std::string blow_up_message(Integrator method, double t, long step, double h,
                                   const std::string& what, double h_lambda0, double h_lambda) {
  return std::string("simulate (") + integrator_name(method) +
         "): blow-up at t = " + detail::format_g(t, 6) + " s, step " + std::to_string(step) +
         " (h = " + detail::format_g(h) + "): " + what +
         "; estimated stiffness x step = " + detail::format_g(h_lambda0) + " at t = 0 (" +
         detail::format_g(h_lambda) + " at the last state) (" + stability_note(method) + ")";
}

/// What to integrate and how.
template <class S>
struct SimulationOptionsT {
  Integrator method = Integrator::RK4;
  S dt = S(0);     ///< fixed step (every method but dopri5); dopri5's first step if set
  S tol = S(0);    ///< dopri5, esdirk4, radau5: tolerance of the local error
  S t_end = S(1);  ///< integrate over [0, t_end]
  /// A run whose \f$\|\beta\|_\infty\f$ exceeds this factor times \f$\max(1,
  /// \|\beta_0\|_\infty)\f$, or whose state is not finite, has blown up.
  S blowup_factor = S(1e6);
  /// When set, the run stops at the first step boundary after `*stop` becomes non-zero (a
  /// signal handler sets it): SimulationSummary::interrupted, the state is the last step's.
  const volatile std::sig_atomic_t* stop = nullptr;
  /// The stiffness monitor of the explicit fixed-step methods (euler, symplectic-euler,
  /// rk4): \f$h\lambda\f$ by DominantEigenvalueT at the start (24 Arnoldi steps, 25
  /// evaluations), every `stiffness_every` steps after (4 steps from the last Ritz vector, 5
  /// evaluations) and at the end; beyond the method's bound (beyond_stability_bound()) the
  /// run stops, or notes it (Warn).
  StiffnessPolicy stiffness = StiffnessPolicy::Stop;
  /// Steps between two checks; 0: as many as make a check (5 evaluations) cost 5 % of the
  /// steps' evaluations: every 100 steps of euler and symplectic-euler, 25 of rk4.
  long stiffness_every = 0;
  /// The variational integrator: the most a hinge angle may turn in one piece of a step
  /// (rad; variational_turn()). A step that turns one further, at the start or the end of
  /// a piece, or whose Newton iteration fails, is taken again as 2, 4, ...,
  /// kVariationalPieces pieces of h/m (SimulationSummary::subdivided). 0: every step in one
  /// piece, the map of StepperT::variational() itself. The default leaves a resolved run
  /// alone: the seven-joint arm at h = 0.002 s is not split once in 2000 s, where 0.25 rad
  /// splits 3558 of its steps in two and, a state-dependent split not being exactly
  /// symmetric, makes its energy error drift (at most 1.4 J over the run in one piece; split,
  /// 4.5 J in its first half and 6.8 J in its second).
  S max_turn = S(0.5);
  /// The most steps the run takes (accepted steps; 0: no limit): the run stops there with
  /// SimulationSummary::budget_spent, the state the last step's, as CVODE's mxstep bounds
  /// its steps (Hindmarsh et al., SUNDIALS, ACM TOMS 31(3), 2005).
  long max_steps = 0;
};

/// The most pieces a variational step is split into (SimulationOptionsT::max_turn).
inline constexpr int kVariationalPieces = 64;

/// The largest angle a hinge of \p m turns in a step \p h at velocities \p beta,
/// \f$|h|\max_i|\beta_i|\f$ over the coordinates that are angles (revolute, helical and
/// universal hinges; not a prismatic offset). The midpoint rule resolves a rotation whose
/// angle per step is small: at \f$h|\beta| \approx 0.5\f$ to 0.9 rad the seven-joint arm's
/// energy jumps by 2 to 47 J of 116 J in one step (test
/// simulation_Variational.NewtonGetsThroughTheArmsFastPhases).
template <class S>
S variational_turn(const ModelT<S>& m, S h, const VecX<S>& beta) {
  S w = S(0);
  for (const BodyT<S>& B : m.bodies()) {
    if (B.hinge.type == HingeType::Prismatic) continue;
    for (int i = 0; i < B.hinge.nv(); ++i) w = std::max(w, std::abs(beta[B.v_offset + i]));
  }
  return std::abs(h) * w;
}

/// The most fixed steps a run takes: step counts are exact in a double up to \f$2^{53}\f$.
inline constexpr double kMaxSteps = 9007199254740992.0;
using SimulationOptions = SimulationOptionsT<double>;

/// What a run did.
struct SimulationSummary {
  long steps = 0;               ///< accepted steps
  long rejected = 0;            ///< rejected steps (adaptive methods), Newton failures included
  long newton_failures = 0;     ///< esdirk4, radau5: steps retried smaller after Newton failed
  long jacobians = 0;           ///< esdirk4, radau5: Jacobians (2 n_v evaluations each)
  long evaluations = 0;         ///< forward dynamics calls
  double wall_seconds = 0;      ///< wall time of the loop
  double energy0 = 0;           ///< energy at t = 0
  double energy1 = 0;           ///< energy at the end
  double max_energy_drift = 0;  ///< max |E(t) - E(0)| over the steps
  double t = 0;                 ///< the time reached (t_end unless interrupted)
  bool interrupted = false;     ///< stopped by SimulationOptionsT::stop before t_end
  bool budget_spent = false;    ///< stopped by SimulationOptionsT::max_steps before t_end
  long stiffness_checks = 0;    ///< checks of the stiffness monitor
  double max_h_lambda = 0;      ///< the largest \f$h|\lambda|\f$ it found
  /// variational: steps taken in pieces (SimulationOptionsT::max_turn), and the most pieces
  /// one took
  long subdivided = 0;
  int max_pieces = 1;
  /// StiffnessPolicy::Warn: what the first check beyond the bound found, else empty.
  std::string stiffness_warning;
};

/// Rejected trial steps in a row whose error estimate or state is not finite (an overflow)
/// before the run is reported as blown up, and the factor each one shrinks the step by: the
/// values CVODE gives a recoverable failure of the right-hand side (MXNCF = 10, ETACF =
/// 0.25; Hindmarsh et al., SUNDIALS, ACM TOMS 31(3), 2005).
inline constexpr int kNonFiniteRetries = 10;
inline constexpr double kNonFiniteShrink = 0.25;

/// The first step of an explicit adaptive method whose error estimate is of order \p p
/// (local error \f$O(h^{p+1})\f$), from \p x at \p t: the starting step algorithm of
/// Hairer, Norsett and Wanner, Solving Ordinary Differential Equations I, 2nd ed., section
/// II.4 ("Starting Step Size"), as their code DOPRI5 computes it (HINIT, IORD = 5 for its
/// fourth order estimate), in the norm of the step control: the RMS of \f$y_i/s_i\f$ over
/// \f$y = (u, \beta)\f$ in local coordinates around \p x, \f$s_i = \mathrm{tol}\f$ for
/// \f$u\f$, \f$\mathrm{tol}(1 + |\beta_{0,i}|)\f$ for \f$\beta\f$:
/// \f[ d_0 = \|y_0\|,\quad d_1 = \|f(t_0, y_0)\|,\quad h_0 = 0.01\,d_0/d_1 \f]
/// (\f$10^{-6}\f$ when \f$d_0\f$ or \f$d_1 < 10^{-5}\f$); the explicit Euler step
/// \f$y_1 = y_0 + h_0 f(t_0, y_0)\f$, \f$d_2 = \|f(t_0 + h_0, y_1) - f(t_0, y_0)\|/h_0\f$;
/// \f[ h_1 = \left(\frac{0.01}{\max(d_1, d_2)}\right)^{1/(p+1)} \f]
/// (\f$\max(10^{-6}, 10^{-3}h_0)\f$ when \f$\max(d_1, d_2) \le 10^{-15}\f$), and
/// \f$h = \min(100\,h_0, h_1)\f$. Two evaluations of the dynamics.
template <class S>
S starting_step(StepperT<S>& stepper, int nv, S t, const StateT<S>& x, S tol, int p) {
  auto norm = [&](const VecX<S>& y) {
    S e2 = S(0);
    for (int i = 0; i < nv; ++i) {
      const S su = tol, sb = tol * (S(1) + std::abs(x.beta[i]));
      e2 += (y[i] / su) * (y[i] / su) + (y[nv + i] / sb) * (y[nv + i] / sb);
    }
    return nv > 0 ? std::sqrt(e2 / S(2 * nv)) : S(0);
  };
  VecX<S> y0 = VecX<S>::Zero(2 * nv), f0, f1;
  y0.tail(nv) = x.beta;
  stepper.rate_at(t, x, VecX<S>::Zero(2 * nv), f0);
  const S d0 = norm(y0), d1 = norm(f0);
  S h0 = d0 < S(1e-5) || d1 < S(1e-5) ? S(1e-6) : S(0.01) * d0 / d1;
  if (!(h0 > S(0) && h0 < std::numeric_limits<S>::infinity())) h0 = S(1e-6);
  const VecX<S> z1 = h0 * f0;  // the explicit Euler step, as a change of (u, beta)
  try {
    stepper.rate_at(t + h0, x, z1, f1);
  } catch (const Error&) {
    return h0;  // the dynamics fail at y1: the first trial step's control takes over
  }
  const S d2 = norm(f1 - f0) / h0;
  const S d12 = std::max(d1, d2);
  const S h1 =
      d12 <= S(1e-15) ? std::max(S(1e-6), S(1e-3) * h0) : std::pow(S(0.01) / d12, S(1) / S(p + 1));
  const S h = std::min(S(100) * h0, h1);
  return h > S(0) && h < std::numeric_limits<S>::infinity() ? h : h0;
}

/// What simulate() calls with the time and the state at t = 0 and after every accepted step.
template <class S>
using SimulationObserverT = std::function<void(S, const StateT<S>&)>;

namespace detail {
/// simulate() with its observer behind one type, so that the loop is compiled once per
/// precision, in the library (soa/instantiations.hpp), and not in every program that
/// simulates with an observer of its own.
template <class S>
SimulationSummary simulate_observed(ChainSystemT<S>& sys, StateT<S>& x,
                                    const SimulationOptionsT<S>& opt,
                                    const SimulationObserverT<S>& observe);
}  // namespace detail

/// Integrates \p sys from the state \p x (overwritten by the final state) over
/// [0, opt.t_end]. \p observe(t, x) is called at t = 0 and after every accepted step. A run
/// that blows up stops with soa::Error giving the time, the step, and the estimated
/// stiffness times the step (stiffness_estimate()) — never a state full of NaN.
template <class S, class Observer>
SimulationSummary simulate(ChainSystemT<S>& sys, StateT<S>& x, const SimulationOptionsT<S>& opt,
                           Observer&& observe) {
  return detail::simulate_observed<S>(sys, x, opt, SimulationObserverT<S>(std::ref(observe)));
}

template <class S>
SimulationSummary detail::simulate_observed(ChainSystemT<S>& sys, StateT<S>& x,
                                            const SimulationOptionsT<S>& opt,
                                            const SimulationObserverT<S>& observe) {
  const bool adaptive = is_adaptive(opt.method);
  if (adaptive && !(opt.tol > S(0)))
    throw Error(std::string("simulate: ") + integrator_name(opt.method) +
                " needs a tolerance (--tol)");
  if (!adaptive && !(opt.dt > S(0))) throw Error("simulate: a fixed-step method needs --dt > 0");
  if (!(opt.t_end >= S(0))) throw Error("simulate: the end time must be >= 0");
  if (opt.method == Integrator::Variational) require_coordinates_add(sys.model());
  if (!adaptive && !(double(opt.t_end) / double(opt.dt) <= kMaxSteps)) {
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "simulate: t_end / dt = %.6g / %.6g = %.3g steps, more than a run can count "
                  "(%.4g); take a larger step or a shorter run",
                  double(opt.t_end), double(opt.dt), double(opt.t_end) / double(opt.dt), kMaxSteps);
    throw Error(buf);
  }
  const int nv = sys.model().nv();
  StepperT<S> stepper(sys);
  stepper.set_tolerance(opt.tol);
  // The step control's exponent: the local error estimate is O(h^(q+1)).
  const S exponent = adaptive ? S(-1) / S(embedded_order(opt.method) + 1) : S(0);
  SimulationSummary sum;
  const long evals0 = sys.evaluations();
  const auto start = std::chrono::steady_clock::now();
  const S E0 = sys.energy(x);
  sum.energy0 = sum.energy1 = double(E0);
  const S v_ref = std::max(S(1), x.beta.template lpNorm<Eigen::Infinity>());
  S t = S(0);
  S h = opt.dt > S(0) ? opt.dt
        : opt.method == Integrator::DormandPrince
            ? starting_step(stepper, nv, t, x, opt.tol, embedded_order(opt.method))
            : S(1e-3) * std::max(opt.t_end, S(1e-3));
  // Fixed steps divide [0, t_end] evenly: h = t_end / ceil(t_end / dt).
  const long n_fixed =
      adaptive ? 0 : std::max(1L, long(std::ceil(double(opt.t_end) / double(opt.dt) - 1e-9)));
  if (!adaptive) h = opt.t_end / S(n_fixed);
  observe(t, x);
  StateT<S> x1 = x;
  VecX<S> err;
  int non_finite = 0;  // trial steps rejected in a row for an overflow
  // The stiffness is estimated at the start: by the time a run has blown up, its last
  // state's rates are large and the estimate there says more about them than about the
  // scene (it is given too).
  const StateT<S> x_start = x;
  auto blow_up = [&](const std::string& what, S h_step) {
    const S lambda0 = stiffness_estimate(stepper, nv, S(0), x_start);
    const S lambda = stiffness_estimate(stepper, nv, t, x);
    throw Error(blow_up_message(opt.method, double(t), sum.steps + 1, double(h_step), what,
                                double(lambda0 * h_step), double(lambda * h_step)));
  };
  // The variational step in m = 1, 2, 4, ..., kVariationalPieces pieces of h/m: the fewest
  // whose Newton iterations converge and in which no angle turns by more than opt.max_turn
  // at a piece's start or end (variational_turn()). In one piece it is the step itself; the
  // stepper keeps nothing from one call to the next, so the m pieces are m variational()
  // steps of h/m (tested).
  StateT<S> piece0 = x, piece1 = x;
  int pieces = 1;  // of the last variational step
  auto variational_step = [&](S h_step) {
    const ModelT<S>& m = sys.model();
    for (pieces = 1;; pieces *= 2) {
      const S hm = h_step / S(pieces);
      const bool last = pieces == kVariationalPieces || !(opt.max_turn > S(0));
      const auto resolved = [&](const StateT<S>& y) {
        return last || variational_turn(m, hm, y.beta) <= opt.max_turn;
      };
      piece0 = x;
      bool ok = resolved(piece0);
      for (int j = 0; j < pieces && ok; ++j) {
        ok = stepper.variational(t + S(j) * hm, hm, piece0, piece1) && resolved(piece1);
        if (ok) piece0 = piece1;
      }
      if (ok) {
        x1 = piece0;
        if (pieces > 1) {
          ++sum.subdivided;
          sum.max_pieces = std::max(sum.max_pieces, pieces);
        }
        return true;
      }
      if (last) return false;
    }
  };
  // The stiffness monitor (explicit fixed-step methods).
  const bool monitored =
      opt.stiffness != StiffnessPolicy::Off &&
      (opt.method == Integrator::Euler || opt.method == Integrator::SymplecticEuler ||
       opt.method == Integrator::RK4);
  const long every = opt.stiffness_every > 0         ? opt.stiffness_every
                     : opt.method == Integrator::RK4 ? 25
                                                     : 100;
  DominantEigenvalueT<S> dominant(monitored ? nv : 0);
  long checked_at = -1;
  auto check_stiffness = [&](int iterations) {
    const std::complex<double> z = double(h) * dominant(stepper, t, x, iterations);
    checked_at = sum.steps;
    ++sum.stiffness_checks;
    sum.max_h_lambda = std::max(sum.max_h_lambda, std::abs(z));
    if (!beyond_stability_bound(opt.method, z)) return;
    const double R = std::abs(explicit_stability_function(opt.method, z));
    char amp[64] = "";
    if (!std::isnan(R)) std::snprintf(amp, sizeof amp, ", |R(h lambda)| = %.3g > 1", R);
    char buf[480];
    std::snprintf(buf, sizeof buf,
                  "beyond the stability bound at t = %.6g s, step %ld (h = %.3g): h lambda = "
                  "%.3g%+.3gi, |h lambda| = %.3g (lambda: Arnoldi on the Jacobian)%s",
                  double(t), sum.steps, double(h), z.real(), z.imag(), std::abs(z), amp);
    const std::string what = std::string("simulate (") + integrator_name(opt.method) + "): " + buf +
                             " (" + stability_note(opt.method) + ")";
    if (opt.stiffness == StiffnessPolicy::Stop) throw Error(what);
    if (sum.stiffness_warning.empty()) sum.stiffness_warning = what;
  };
  while (adaptive ? t < opt.t_end : sum.steps < n_fixed) {
    if (monitored && sum.steps % every == 0) check_stiffness(sum.steps == 0 ? 24 : 4);
    if (opt.stop && *opt.stop) {
      sum.interrupted = true;
      break;
    }
    if (opt.max_steps > 0 && sum.steps >= opt.max_steps) {
      sum.budget_spent = true;
      break;
    }
    if (adaptive) h = std::min(h, opt.t_end - t);
    const S h_step = h;  // the step being taken (dopri5 changes h once it is accepted)
    bool ok = true;
    std::string trial_failure;  // an adaptive trial step whose dynamics failed (an overflow)
    try {
      switch (opt.method) {
        case Integrator::Euler:
          stepper.euler(t, h, x, x1);
          break;
        case Integrator::SymplecticEuler:
          stepper.symplectic_euler(t, h, x, x1);
          break;
        case Integrator::RK4:
          stepper.rk4(t, h, x, x1);
          break;
        case Integrator::DormandPrince:
          stepper.dopri5(t, h, x, x1, err);
          break;
        case Integrator::ImplicitMidpoint:
          ok = stepper.implicit_midpoint(t, h, x, x1);
          break;
        case Integrator::Esdirk:
          ok = stepper.esdirk(t, h, x, x1, err);
          break;
        case Integrator::Radau5:
          ok = stepper.radau5(t, h, x, x1, err);
          break;
        case Integrator::Variational:
          ok = variational_step(h);
          break;
      }
    } catch (const Error& e) {
      const std::string msg = e.what();
      if (msg.find("singular") != std::string::npos) throw;
      if (!adaptive) blow_up(msg, h);
      trial_failure = msg;
    }
    // An adaptive trial step that overflowed (its dynamics failed, its error estimate or
    // its state not finite) is rejected and taken again smaller, as CVODE does with a
    // recoverable failure (kNonFiniteRetries, kNonFiniteShrink); only a run of such
    // rejections is a blow-up.
    auto reject_non_finite = [&](const std::string& what) {
      ++sum.rejected;
      if (++non_finite >= kNonFiniteRetries)
        blow_up(what + " (" + std::to_string(kNonFiniteRetries) +
                    " trial steps in a row, each smaller by " + detail::format_g(kNonFiniteShrink) +
                    ")",
                h_step);
      h = h_step * S(kNonFiniteShrink);
    };
    if (!trial_failure.empty()) {
      reject_non_finite(trial_failure);
      continue;
    }
    if (!ok && is_adaptive_implicit(opt.method)) {
      ++sum.rejected;
      ++sum.newton_failures;
      h *= opt.method == Integrator::Radau5 ? S(0.5) : S(0.25);  // a smaller step
      if (h < S(16) * eps<S>() * std::max(S(1), t)) {
        const auto& f = stepper.newton_failure();
        char what[200];
        std::snprintf(what, sizeof what,
                      "Newton's method did not converge at stage %d even at the smallest step "
                      "(last correction %.3g in units of the tolerance, %s)",
                      f.stage, double(f.residual), f.diverged ? "diverging" : "too slow");
        blow_up(what, h);
      }
      continue;
    }
    if (!ok) {
      const auto& f = stepper.newton_failure();
      std::string what = "Newton's method did not converge (last correction |dZ| = " +
                         detail::format_g(double(f.residual)) +
                         (f.diverged ? ", diverging)" : ", too slow)");
      if (f.reached > S(0))
        what += "; continued in the step, its equation solved up to h = " +
                detail::format_g(double(f.reached)) + " only";
      if (opt.method == Integrator::Variational && pieces > 1)
        what += "; the step was split into up to " + std::to_string(pieces) + " pieces";
      blow_up(what, h);
    }
    if (adaptive) {
      // RMS norm of the local error scaled by tol (1 + |y|), y = (u, beta).
      S e2 = S(0);
      for (int i = 0; i < nv; ++i) {
        const S su = opt.tol;  // local coordinates: angles and offsets, absolute
        const S sb = opt.tol * (S(1) + std::max(std::abs(x.beta[i]), std::abs(x1.beta[i])));
        e2 += (err[i] / su) * (err[i] / su) + (err[nv + i] / sb) * (err[nv + i] / sb);
      }
      const S e = nv > 0 ? std::sqrt(e2 / S(2 * nv)) : S(0);
      const S factor =
          std::min(S(5), std::max(S(0.2), S(0.9) * std::pow(std::max(e, S(1e-10)), exponent)));
      if (!std::isfinite(double(e)) || !x1.theta.allFinite() || !x1.beta.allFinite()) {
        reject_non_finite(std::isfinite(double(e)) ? "the state is not finite"
                                                   : "the error estimate is not finite");
        continue;
      }
      non_finite = 0;
      if (!(e <= S(1))) {
        ++sum.rejected;
        h *= factor;
        if (h < S(16) * eps<S>() * std::max(S(1), t)) blow_up("the step size underflowed", h);
        continue;
      }
      t += h;
      // esdirk4 and radau5 keep their step (and so their LU factorizations, O(n_v^3)) when
      // the controller would grow it by less than 20 % (as RADAU5: Hairer and Wanner, Solving
      // ODEs II, IV.8).
      if (!(is_adaptive_implicit(opt.method) && factor >= S(1) && factor <= S(1.2))) h *= factor;
    } else {
      t = S(sum.steps + 1) * h;
    }
    if (!x1.theta.allFinite() || !x1.beta.allFinite()) {
      t = adaptive ? t - h_step : S(sum.steps) * h;
      blow_up("the state is not finite", h_step);
    }
    if (x1.beta.template lpNorm<Eigen::Infinity>() > opt.blowup_factor * v_ref) {
      char what[120];
      std::snprintf(what, sizeof what, "|beta| = %.3g, over %.3g times its start",
                    double(x1.beta.template lpNorm<Eigen::Infinity>()), double(opt.blowup_factor));
      t = adaptive ? t - h_step : S(sum.steps) * h;
      blow_up(what, h_step);
    }
    const S E = sys.energy(x1);
    if (!std::isfinite(double(E))) {
      t = adaptive ? t - h_step : S(sum.steps) * h;
      blow_up("the energy is not finite", h_step);
    }
    x = x1;
    ++sum.steps;
    sum.energy1 = double(E);
    sum.max_energy_drift = std::max(sum.max_energy_drift, double(std::abs(E - E0)));
    observe(t, x);
  }
  if (monitored && checked_at != sum.steps && !sum.interrupted) check_stiffness(4);
  sum.t = double(t);
  sum.jacobians = stepper.jacobians();
  sum.evaluations = sys.evaluations() - evals0;
  sum.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return sum;
}

}  // namespace soa
