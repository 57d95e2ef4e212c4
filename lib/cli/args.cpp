// The command line of `soa`: verb, scene file and options.
#include "args.hpp"

#include <cmath>
#include <cstdlib>

#include "soa/error.hpp"

namespace soa::cli {
namespace {

struct VerbInfo {
  Verb verb;
  const char* name;
  const char* options;  // the options the verb takes, as the help shows them
};
constexpr VerbInfo kVerbs[] = {
    {Verb::Kinematics, "kinematics", "--q, --qd, --qdd, --body, --tip, --lock"},
    {Verb::Jacobian, "jacobian", "--q, --body, --tip, --lock"},
    {Verb::InverseDynamics, "inverse-dynamics", "--q, --qd, --qdd, --tip, --lock"},
    {Verb::ForwardDynamics, "forward-dynamics", "--q, --qd, --tau, --check, --tip, --lock"},
    {Verb::MassMatrix, "mass-matrix", "--q, --inverse, --operational, --check, --tip, --lock"},
    {Verb::Simulate, "simulate",
     "--q, --qd, --integrator, --dt, --tol, --t-end, --max-steps, --stiffness, --out, --every, "
     "--out-dt, --view, --frames, --no-velocity, --no-force, --tip, --lock"},
    {Verb::View, "view",
     "--out, --q, --qd, --integrator, --dt, --tol, --t-end, --max-steps, --stiffness, "
     "--trajectory, "
     "--frames, --no-velocity, --no-force, --tip, --lock"},
    {Verb::Convert, "convert", "--tip, --lock"},
};

/// The options that do not go together, and the ones that need another (exit code 2).
void check_combinations(const Args& a) {
  const Verb v = *a.verb;
  auto given = [](const char* name, bool present) { return present ? name : nullptr; };
  // The first of the options that only apply to a viewer.
  const char* viewer_option = a.frames        ? "--frames"
                              : a.no_velocity ? "--no-velocity"
                              : a.no_force    ? "--no-force"
                                              : nullptr;
  if (v == Verb::Simulate && viewer_option && !a.view)
    throw UsageError(std::string("simulate: ") + viewer_option +
                     " needs --view DIR, the viewer folder it applies to");
  if (v != Verb::View) return;
  if (!a.out) throw UsageError("view: missing --out DIR, the folder to write the viewer to");
  if (a.trajectory) {
    // A trajectory is a run already: the options that start one have nothing to do.
    for (const char* o :
         {given("--integrator", bool(a.integrator)), given("--dt", bool(a.dt)),
          given("--tol", bool(a.tol)), given("--t-end", bool(a.t_end)),
          given("--max-steps", bool(a.max_steps)), given("--stiffness", bool(a.stiffness)),
          given("--q", bool(a.q)), given("--qd", bool(a.qd))})
      if (o)
        throw UsageError(std::string("view: --trajectory and ") + o +
                         " do not go together (a trajectory file is a run already; " + o +
                         " starts another)");
  } else if (a.frames && !a.simulates()) {
    throw UsageError(
        "view: --frames needs --trajectory FILE or a simulation (--integrator, --dt, --tol); "
        "a scene's state is one frame");
  }
}

std::string trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

}  // namespace

bool takes(Verb v, const std::string& option) {
  for (const VerbInfo& i : kVerbs) {
    if (i.verb != v) continue;
    const std::string list = ", " + std::string(i.options) + ",";
    return list.find(", " + option + ",") != std::string::npos;
  }
  return false;
}

const char* verb_name(Verb v) {
  for (const VerbInfo& i : kVerbs)
    if (i.verb == v) return i.name;
  return "?";
}

Args parse_args(const std::vector<std::string>& argv) {
  Args a;
  if (argv.empty()) throw UsageError("missing the verb");
  if (argv[0] == "--help" || argv[0] == "-h") {
    a.help = true;
    return a;
  }
  for (const VerbInfo& i : kVerbs)
    if (argv[0] == i.name) a.verb = i.verb;
  if (!a.verb) {
    if (!argv[0].empty() && argv[0][0] == '-')
      throw UsageError("expected a verb before \"" + argv[0] + "\"");
    throw UsageError("unknown verb \"" + argv[0] +
                     "\" (kinematics, jacobian, inverse-dynamics, forward-dynamics, "
                     "mass-matrix, simulate, view or convert)");
  }
  const Verb v = *a.verb;
  const std::string verb = verb_name(v);
  for (std::size_t i = 1; i < argv.size(); ++i) {
    const std::string& arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      a.help = true;
      return a;
    }
    if (arg.size() > 1 && arg[0] == '-') {
      const std::size_t eq = arg.find('=');
      const std::string option = arg.substr(0, eq);
      auto refuse = [&] {
        std::string options;
        for (const VerbInfo& info : kVerbs)
          if (info.verb == v) options = info.options;
        throw UsageError(verb + " does not take " + option + " (it takes " + options + ")");
      };
      bool* flag = option == "--inverse"       ? &a.inverse
                   : option == "--check"       ? &a.check
                   : option == "--no-velocity" ? &a.no_velocity
                   : option == "--no-force"    ? &a.no_force
                                               : nullptr;
      if (flag) {
        if (!takes(v, option)) refuse();
        if (eq != std::string::npos) throw UsageError(option + " takes no value");
        *flag = true;
        continue;
      }
      std::optional<std::string>* slot = option == "--q"             ? &a.q
                                         : option == "--qd"          ? &a.qd
                                         : option == "--qdd"         ? &a.qdd
                                         : option == "--tau"         ? &a.tau
                                         : option == "--integrator"  ? &a.integrator
                                         : option == "--dt"          ? &a.dt
                                         : option == "--tol"         ? &a.tol
                                         : option == "--t-end"       ? &a.t_end
                                         : option == "--max-steps"   ? &a.max_steps
                                         : option == "--stiffness"   ? &a.stiffness
                                         : option == "--out"         ? &a.out
                                         : option == "--every"       ? &a.every
                                         : option == "--out-dt"      ? &a.out_dt
                                         : option == "--body"        ? &a.body
                                         : option == "--operational" ? &a.operational
                                         : option == "--view"        ? &a.view
                                         : option == "--trajectory"  ? &a.trajectory
                                         : option == "--frames"      ? &a.frames
                                         : option == "--tip"         ? &a.tip
                                         : option == "--lock"        ? &a.lock
                                                                     : nullptr;
      if (!slot) throw UsageError("unknown option \"" + option + "\"");
      if (!takes(v, option)) refuse();
      if (*slot) throw UsageError(option + " given twice");
      if (eq != std::string::npos) {
        *slot = arg.substr(eq + 1);
      } else {
        if (i + 1 == argv.size()) throw UsageError(option + " needs a value");
        *slot = argv[++i];
      }
      continue;
    }
    if (!a.scene.empty())
      throw UsageError("unexpected argument \"" + arg + "\" (" + verb + " takes one scene file)");
    a.scene = arg;
  }
  if (a.scene.empty()) throw UsageError(verb + ": missing the scene file");
  check_combinations(a);
  return a;
}

std::vector<double> parse_numbers(const std::string& text, const std::string& option) {
  std::vector<double> x;
  if (trim(text).empty()) return x;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string item = trim(text.substr(start, comma - start));
    const std::string where = option + ": entry " + std::to_string(x.size());
    if (item.empty()) throw Error(where + " is empty");
    char* end = nullptr;
    const double value = std::strtod(item.c_str(), &end);
    if (end != item.c_str() + item.size())
      throw Error(where + ": \"" + item + "\" is not a number");
    if (!std::isfinite(value)) throw Error(where + ": \"" + item + "\" is not a finite number");
    x.push_back(value);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return x;
}

}  // namespace soa::cli
