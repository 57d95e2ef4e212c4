// The command line of `soa`: verb, scene file and options (see help.cpp for the text).
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace soa::cli {

/// A command line `soa` cannot run: exit code 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

enum class Verb {
  Kinematics,
  Jacobian,
  InverseDynamics,
  ForwardDynamics,
  MassMatrix,
  Simulate,
  View,
  Convert
};

/// "kinematics", "jacobian", "inverse-dynamics", "forward-dynamics", "mass-matrix",
/// "simulate", "view", "convert".
const char* verb_name(Verb v);

struct Args {
  bool help = false;         ///< --help or -h: print the help of the verb (or of soa)
  std::optional<Verb> verb;  ///< absent only with a top-level --help
  std::string scene;         ///< the scene file
  std::optional<std::string> q, qd, qdd, tau, body;  ///< option values as given
  std::optional<std::string> operational;            ///< mass-matrix --operational BODY
  /// A URDF scene: --tip LINK (the chain's last link), --lock J1,J2 (joints taken as fixed)
  std::optional<std::string> tip, lock;
  /// simulate: --integrator, --dt, --tol, --t-end, --out, --every, --out-dt
  std::optional<std::string> integrator, dt, tol, t_end, out, every, out_dt;
  /// simulate, view: --max-steps (the step budget)
  std::optional<std::string> max_steps;
  /// simulate, view: --stiffness stop|warn|off (the monitor of the explicit methods)
  std::optional<std::string> stiffness;
  /// The viewer: simulate --view DIR; view --trajectory FILE; both --frames N
  std::optional<std::string> view, trajectory, frames;
  bool inverse = false;  ///< mass-matrix --inverse
  bool check = false;    ///< forward-dynamics, mass-matrix --check: the dense checks at any size
  bool no_velocity = false, no_force = false;  ///< view, simulate --view: leave V, f out

  /// view: a run is simulated (--integrator, --dt, --tol, --t-end, --stiffness or
  /// --max-steps given).
  bool simulates() const { return integrator || dt || tol || t_end || stiffness || max_steps; }
};

/// True when the verb \p v takes \p option ("--q", "--inverse", ...).
bool takes(Verb v, const std::string& option);

/// Parses the arguments after the program name; throws UsageError, also for options that do
/// not go together (view --trajectory with a simulation's, simulate --frames without --view).
Args parse_args(const std::vector<std::string>& argv);

/// A comma-separated list of numbers ("0.1,-2,3e-1"); throws soa::Error("<option>: ...")
/// for an entry that is not a finite number (bad input, exit code 1).
std::vector<double> parse_numbers(const std::string& text, const std::string& option);

}  // namespace soa::cli
