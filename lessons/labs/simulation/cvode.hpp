/// \file
/// SUNDIALS CVODE as the field's reference integrator of the simulation report.
///
/// CVODE (Hindmarsh et al., "SUNDIALS: Suite of nonlinear and differential/algebraic equation
/// solvers", ACM TOMS 31(3), 2005) integrates \f$\dot y = f(t, y)\f$ by the backward
/// differentiation formulas of orders 1 to 5 in fixed-leading-coefficient form with variable
/// step and order, each step's implicit equation solved by Newton's method with the matrix
/// \f$I - h\gamma J\f$. Here: CV_BDF, a dense direct linear solver (SUNDenseMatrix,
/// SUNLinSol_Dense) with CVODE's own difference-quotient Jacobian, scalar tolerances
/// \f$\mathrm{rtol} = \mathrm{atol} = \mathrm{tol}\f$, maximum order 5, stop time exactly
/// \f$t_{\rm end}\f$. The state is \f$y = (\theta, \beta)\f$ with \f$f = (\beta,
/// \dot\beta)\f$, \f$\dot\beta\f$ by soa::ChainSystemT::acceleration(): valid when
/// \f$\theta\f$ is a vector space (no spherical or free hinge, \f$n_q = n_v\f$).
///
/// Built with SOA_HAVE_CVODE=1 when CMake finds SUNDIALS (libsundials-dev); without it
/// cvode_run() returns a Run with ok = false and cvode_status() says so.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "support.hpp"

#if SOA_HAVE_CVODE
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_config.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#endif

namespace soa::lesson::sim {

#if SOA_HAVE_CVODE
constexpr bool kHaveCvode = true;
#else
constexpr bool kHaveCvode = false;
#endif

/// The line the report prints and writes beside CVODE's results.
inline std::string cvode_status() {
#if SOA_HAVE_CVODE
  return std::string("CVODE: SUNDIALS ") + SUNDIALS_VERSION +
         " (BDF orders 1-5, dense Newton, difference-quotient Jacobian)";
#else
  return "CVODE: not built (libsundials-dev missing)";
#endif
}

/// Why \p m cannot be integrated as \f$\dot y = (\beta, \dot\beta)\f$ (empty when it can):
/// a spherical or free hinge's quaternion is not a vector space.
inline std::string cvode_unsupported(const soa::Model& m) {
  for (const soa::Body& b : m.bodies())
    if (b.hinge.type == soa::HingeType::Spherical || b.hinge.type == soa::HingeType::Free)
      return std::string("cvode: theta is not a vector space (") +
             soa::hinge_type_name(b.hinge.type) + " hinge of " + b.name +
             "): y = (theta, beta) with y' = (beta, beta') needs n_q = n_v";
  if (m.nq() != m.nv()) return "cvode: n_q != n_v";
  return "";
}

#if SOA_HAVE_CVODE
namespace cvode_detail {

/// What the right-hand side needs: the chain, a state to fill, and the first error it met.
struct Data {
  soa::ChainSystemT<double>* sys = nullptr;
  soa::State x;
  soa::VecX<double> beta_dot;
  int nv = 0;
  std::string error;  ///< soa::Error from the forward dynamics, or CVODE's last message
};

/// \f$f(t, y) = (\beta, \dot\beta(t, \theta, \beta))\f$. Returns 1 (recoverable: CVODE
/// retries with a smaller step) for a non-finite rate, -1 for a soa::Error.
inline int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  Data& d = *static_cast<Data*>(user);
  const double* Y = N_VGetArrayPointer(y);
  double* F = N_VGetArrayPointer(ydot);
  d.x.theta = Eigen::Map<const Eigen::VectorXd>(Y, d.nv);
  d.x.beta = Eigen::Map<const Eigen::VectorXd>(Y + d.nv, d.nv);
  try {
    d.sys->acceleration(t, d.x, d.beta_dot);
  } catch (const soa::Error& e) {
    d.error = e.what();
    return -1;
  }
  Eigen::Map<Eigen::VectorXd>(F, d.nv) = d.x.beta;
  Eigen::Map<Eigen::VectorXd>(F + d.nv, d.nv) = d.beta_dot;
  return d.beta_dot.allFinite() ? 0 : 1;
}

/// Keeps CVODE's messages (it prints them to stderr by default) for the diagnostic.
inline void on_error(int, const char* module, const char* function, char* msg, void* user) {
  Data& d = *static_cast<Data*>(user);
  if (d.error.empty() || d.error.rfind("cvode:", 0) == 0)
    d.error = std::string("cvode: ") + module + "/" + function + ": " + msg;
}

/// CVODE's name of a return flag (CVodeGetReturnFlagName() allocates it with malloc).
inline std::string flag_name(int flag) {
  char* name = CVodeGetReturnFlagName(flag);
  const std::string s = name ? name : "?";
  std::free(name);
  return s;
}

/// The SUNDIALS objects of one run, freed in reverse order of creation.
struct Session {
  SUNContext ctx = nullptr;
  N_Vector y = nullptr;
  SUNMatrix A = nullptr;
  SUNLinearSolver ls = nullptr;
  void* mem = nullptr;
  Session() = default;
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  ~Session() {
    if (mem) CVodeFree(&mem);
    if (ls) SUNLinSolFree(ls);
    if (A) SUNMatDestroy(A);
    if (y) N_VDestroy(y);
    if (ctx) SUNContext_Free(&ctx);
  }
};

}  // namespace cvode_detail
#endif

/// Integrates \p p over [0, p.t_end] by CVODE at \p tol: the same Run as run() (final state;
/// summary: accepted steps, rejected = error test failures + nonlinear convergence failures,
/// evaluations = CVodeGetNumRhsEvals + CVodeGetNumLinRhsEvals (the difference-quotient
/// Jacobian's), jacobians = CVodeGetNumJacEvals, energy sampled after each internal step
/// (CV_ONE_STEP), wall time from creating the SUNDIALS objects to t_end). Runs shorter than
/// \p min_seconds in all are repeated and the median time kept, as run() does.
inline Run cvode_run(const SimProblem& p, double tol, double min_seconds = 0) {
  Run r;
#if !SOA_HAVE_CVODE
  (void)p, (void)tol, (void)min_seconds;
  r.diagnostic = cvode_status();
  return r;
#else
  r.diagnostic = cvode_unsupported(p.m);
  if (!r.diagnostic.empty()) return r;
  using namespace cvode_detail;
  const int nv = p.m.nv();
  std::vector<double> times;
  double total = 0;
  do {
    soa::ChainSystemT<double> sys(p.m, p.f_ext);
    soa::ChainSystemT<double> meter(p.m, p.f_ext);  // energy evaluations, not counted as work
    Data d;
    d.sys = &sys;
    d.x = p.x0;
    d.beta_dot = soa::VecX<double>::Zero(nv);
    d.nv = nv;
    soa::SimulationSummary s;
    const auto start = std::chrono::steady_clock::now();
    Session ses;
    int flag = SUNContext_Create(nullptr, &ses.ctx);
    if (flag == 0) ses.y = N_VNew_Serial(2 * nv, ses.ctx);
    if (ses.y) ses.A = SUNDenseMatrix(2 * nv, 2 * nv, ses.ctx);
    if (ses.A) ses.ls = SUNLinSol_Dense(ses.y, ses.A, ses.ctx);
    if (ses.ls) ses.mem = CVodeCreate(CV_BDF, ses.ctx);
    if (!ses.mem) {
      r.ok = false;
      r.diagnostic = "cvode: SUNDIALS objects could not be created";
      return r;
    }
    double* Y = N_VGetArrayPointer(ses.y);
    Eigen::Map<Eigen::VectorXd>(Y, nv) = p.x0.theta;
    Eigen::Map<Eigen::VectorXd>(Y + nv, nv) = p.x0.beta;
    // Setup: each call returns CV_SUCCESS (0) or a negative flag.
    const int setup[] = {CVodeSetErrHandlerFn(ses.mem, on_error, &d),
                         CVodeInit(ses.mem, rhs, 0.0, ses.y),
                         CVodeSStolerances(ses.mem, tol, tol),
                         CVodeSetUserData(ses.mem, &d),
                         CVodeSetLinearSolver(ses.mem, ses.ls, ses.A),
                         CVodeSetMaxNumSteps(ses.mem, 100000000L),
                         CVodeSetStopTime(ses.mem, p.t_end)};
    for (int f : setup)
      if (f < 0) {
        r.ok = false;
        r.diagnostic = std::string("cvode: setup failed (") + flag_name(f) + ")";
        return r;
      }
    const double E0 = meter.energy(p.x0);
    s.energy0 = s.energy1 = E0;
    soa::State x = p.x0;
    double t = 0;
    flag = CV_SUCCESS;
    while (t < p.t_end && p.t_end > 0) {
      flag = CVode(ses.mem, p.t_end, ses.y, &t, CV_ONE_STEP);
      if (flag < 0) break;
      x.theta = Eigen::Map<const Eigen::VectorXd>(Y, nv);
      x.beta = Eigen::Map<const Eigen::VectorXd>(Y + nv, nv);
      s.energy1 = meter.energy(x);
      s.max_energy_drift = std::max(s.max_energy_drift, std::abs(s.energy1 - E0));
      if (flag == CV_TSTOP_RETURN) break;
    }
    long nst = 0, nfe = 0, nfeLS = 0, nje = 0, netf = 0, ncfn = 0;
    CVodeGetNumSteps(ses.mem, &nst);
    CVodeGetNumRhsEvals(ses.mem, &nfe);
    CVodeGetNumLinRhsEvals(ses.mem, &nfeLS);
    CVodeGetNumJacEvals(ses.mem, &nje);
    CVodeGetNumErrTestFails(ses.mem, &netf);
    CVodeGetNumNonlinSolvConvFails(ses.mem, &ncfn);
    s.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    s.steps = nst;
    s.rejected = netf + ncfn;
    s.evaluations = nfe + nfeLS;
    s.jacobians = nje;
    s.t = t;
    r.summary = s;
    if (flag < 0) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "cvode: %s at t = %.6g s after %ld steps",
                    flag_name(flag).c_str(), t, nst);
      r.ok = false;
      r.diagnostic = buf + (d.error.empty() ? std::string() : " (" + d.error + ")");
      return r;
    }
    r.ok = true;
    r.diagnostic.clear();
    r.x = x;
    times.push_back(s.wall_seconds);
    total += s.wall_seconds;
  } while (total < min_seconds && times.size() < 1000);
  std::sort(times.begin(), times.end());
  r.seconds = times[times.size() / 2];
  return r;
#endif
}

}  // namespace soa::lesson::sim
