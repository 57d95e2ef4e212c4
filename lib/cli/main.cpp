// `soa`: serial-chain computations on a scene file, JSON on stdout. This file dispatches:
// command line (args.cpp), scene (soa_scene), state, verb (verbs.cpp), output (json_out.cpp).
// Exit codes: 0 ok, 1 bad scene or input, 2 usage error (help.cpp).
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "args.hpp"
#include "help.hpp"
#include "json_out.hpp"
#include "soa/scene.hpp"
#include "verbs.hpp"

namespace {

using namespace soa;
using namespace soa::cli;

/// Runs \p f; an error gains the name of the option whose value it refused.
template <class F>
VecX<double> for_option(const std::string& option, F&& f) {
  try {
    return f();
  } catch (const Error& e) {
    throw Error(option + ": " + e.what());
  }
}

/// The state of the run: the scene's, with --q, --qd, --qdd replacing its parts; \p tau gets
/// --tau (zero when absent).
State state_of(const Scene& s, const Args& a, VecX<double>& beta_dot, VecX<double>& tau) {
  State x = s.state;
  beta_dot = s.beta_dot;
  tau = VecX<double>::Zero(s.model.nv());
  if (a.tau) {
    const std::vector<double> t = parse_numbers(*a.tau, "--tau");
    tau = for_option("--tau", [&] { return beta_from_file_order(s, t); });
  }
  if (a.q) {
    const std::vector<double> q = parse_numbers(*a.q, "--q");
    x.theta = for_option("--q", [&] { return theta_from_file_order(s, q); });
  }
  if (a.qd) {
    const std::vector<double> qd = parse_numbers(*a.qd, "--qd");
    x.beta = for_option("--qd", [&] { return beta_from_file_order(s, qd); });
  }
  if (a.qdd) {
    const std::vector<double> qdd = parse_numbers(*a.qdd, "--qdd");
    beta_dot = for_option("--qdd", [&] { return beta_from_file_order(s, qdd); });
  }
  return x;
}

/// One number of an option (--dt 1e-3).
double number_of(const std::optional<std::string>& text, const std::string& option, double absent) {
  if (!text) return absent;
  const std::vector<double> v = parse_numbers(*text, option);
  if (v.size() != 1) throw Error(option + ": expected one number, got " + std::to_string(v.size()));
  return v[0];
}

/// The options of simulate: --integrator (rk4 when absent), --dt or --tol, --t-end (1 s).
SimulationOptions simulation_options(const Args& a) {
  SimulationOptions o;
  o.method = a.integrator ? integrator_from_name(*a.integrator) : Integrator::RK4;
  o.dt = number_of(a.dt, "--dt", 0.0);
  o.tol = number_of(a.tol, "--tol", 0.0);
  o.t_end = number_of(a.t_end, "--t-end", 1.0);
  if (o.method == Integrator::DormandPrince && !a.tol)
    throw Error("--tol: dopri5 needs a tolerance (e.g. --tol 1e-8)");
  if (o.method != Integrator::DormandPrince && !a.dt)
    throw Error(std::string("--dt: ") + integrator_name(o.method) +
                " needs a step (e.g. --dt 1e-3)");
  if (a.dt && !(o.dt > 0)) throw Error("--dt: the step must be > 0");
  if (a.tol && !(o.tol > 0)) throw Error("--tol: the tolerance must be > 0");
  if (!(o.t_end >= 0)) throw Error("--t-end: the end time must be >= 0");
  return o;
}

/// Loads the scene and runs the verb. Errors after loading (command-line values, --body)
/// gain the scene file's name, as the scene's own errors have it.
Json run(const Args& a) {
  const Scene s = load_scene(a.scene);
  try {
    VecX<double> beta_dot, tau;
    const State x = state_of(s, a, beta_dot, tau);
    const Scene::Frame* frame = a.body ? &find_frame(s, *a.body) : nullptr;
    Json out;
    switch (*a.verb) {
      case Verb::Kinematics:
        out = kinematics(s, x, beta_dot, frame);
        break;
      case Verb::Jacobian:  // default: the tip, the last body of the file
        out = jacobian(s, x, frame ? *frame : s.frames.back());
        break;
      case Verb::InverseDynamics:
        out = inverse_dynamics(s, x, beta_dot);
        break;
      case Verb::ForwardDynamics:
        out = forward_dynamics(s, x, tau);
        break;
      case Verb::MassMatrix:
        out = mass_matrix(s, x, a.inverse);
        break;
      case Verb::Simulate:
        out = simulate(s, x, simulation_options(a), a.out ? *a.out : "");
        break;
    }
    if (!all_finite(out))  // never a silent NaN: huge values overflow
      throw Error("result: not finite (an overflow: are q, qd, qdd, tau too large?)");
    return out;
  } catch (const Error& e) {
    throw Error(a.scene + ": " + e.what());
  }
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  try {
    a = parse_args(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const UsageError& e) {
    std::cerr << "soa: " << e.what() << " (see soa --help)\n";
    return 2;
  }
  if (a.help) {
    std::cout << help_text(a.verb);
    return 0;
  }
  try {
    write_json(std::cout, run(a));
    return 0;
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
}
