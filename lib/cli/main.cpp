// `soa`: serial-chain computations on a scene file, JSON on stdout. This file dispatches:
// command line (args.cpp), scene (soa_scene), state, verb (verbs.cpp), output (json_out.cpp).
// Exit codes: 0 ok, 1 bad scene or input, 2 usage error (help.cpp), 130/143/129 a simulation
// stopped by SIGINT/SIGTERM/SIGHUP. Results are computed, then checked (every number finite), then
// written; every write is checked.
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <iostream>
#include <limits>
#include <new>
#include <string>
#include <vector>

#include "args.hpp"
#include "help.hpp"
#include "json_out.hpp"
#include "output.hpp"
#include "soa/printable.hpp"
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

/// A short number for messages.
std::string brief(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
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
  if (is_adaptive(o.method) && !a.tol)
    throw Error(std::string("--tol: ") + integrator_name(o.method) +
                " needs a tolerance (e.g. --tol 1e-8)");
  if (!is_adaptive(o.method) && !a.dt)
    throw Error(std::string("--dt: ") + integrator_name(o.method) +
                " needs a step (e.g. --dt 1e-3)");
  if (a.dt && !(o.dt > 0)) throw Error("--dt: the step must be > 0");
  if (a.tol && !(o.tol > 0)) throw Error("--tol: the tolerance must be > 0");
  if (a.tol && !(o.tol < 1))
    throw Error("--tol: a relative tolerance must be below 1 (got " + *a.tol + ")");
  // A step's own arithmetic rounds each component by about eps = 2^-52 relative, and its
  // error estimate, a difference of stage sums, carries rounding of a few eps: a tolerance
  // below 100 eps is under the rounding the control measures (RADAU5 refuses rtol <= 10
  // uround, Hairer and Wanner, Solving ODEs II, IV.8).
  constexpr double kMinTol = 100 * std::numeric_limits<double>::epsilon();
  if (a.tol && o.tol < kMinTol)
    throw Error("--tol: " + *a.tol + " is below " + brief(kMinTol) +
                " = 100 eps (eps = 2.2e-16, the spacing of doubles at 1): the rounding of a "
                "step's own arithmetic is of that order, and no error control meets a "
                "tolerance under it");
  o.max_steps = kDefaultMaxSteps;
  if (a.max_steps) {
    const double k = number_of(a.max_steps, "--max-steps", 0);
    if (!(k >= 1 && k == std::floor(k) && k <= 1e15))
      throw Error("--max-steps: expected a whole number of steps >= 1, got " + *a.max_steps);
    o.max_steps = long(k);
  }
  if (!(o.t_end >= 0)) throw Error("--t-end: the end time must be >= 0");
  if (a.stiffness) {
    const std::string& p = *a.stiffness;
    if (p != "stop" && p != "warn" && p != "off")
      throw Error("--stiffness: expected stop, warn or off (got \"" + p + "\")");
    o.stiffness = p == "stop"   ? StiffnessPolicy::Stop
                  : p == "warn" ? StiffnessPolicy::Warn
                                : StiffnessPolicy::Off;
  }
  return o;
}

/// --out, --every, --out-dt of simulate.
OutputOptions output_options(const Args& a) {
  OutputOptions o;
  if (a.out && a.out->empty()) throw Error("--out: an empty file name");
  if (a.out) o.csv_path = *a.out;
  if (a.every && a.out_dt) throw Error("--every, --out-dt: give one of them, not both");
  if ((a.every || a.out_dt) && !a.out)
    throw Error(std::string(a.every ? "--every" : "--out-dt") +
                ": needs --out, the trajectory file it thins out");
  if (a.every) {
    const double k = number_of(a.every, "--every", 1);
    if (!(k >= 1 && k == std::floor(k) && k <= 1e15))
      throw Error("--every: expected a whole number of steps >= 1, got " + *a.every);
    o.every = long(k);
  }
  if (a.out_dt) {
    o.out_dt = number_of(a.out_dt, "--out-dt", 0);
    if (!(o.out_dt > 0)) throw Error("--out-dt: the interval must be > 0");
  }
  return o;
}

/// The viewer of view (--out DIR) or simulate (--view DIR): --frames (2 to kMaxFrames),
/// --no-velocity, --no-force.
ViewOptions view_options(const Args& a) {
  ViewOptions o;
  o.option = *a.verb == Verb::View ? "--out" : "--view";
  o.dir = *a.verb == Verb::View ? *a.out : *a.view;
  if (o.dir.empty()) throw Error(o.option + ": an empty folder name");
  if (a.frames) {
    const double n = number_of(a.frames, "--frames", 0);
    if (!(n >= 2 && n == std::floor(n)))
      throw Error("--frames: expected a whole number of frames >= 2, got " + *a.frames);
    if (n > double(kMaxFrames))
      throw Error("--frames: " + *a.frames + " is over the limit of " + std::to_string(kMaxFrames) +
                  " frames (each holds every body's pose, V and f: 11.5 kB of data.js a "
                  "frame for 50 bodies; the default is " +
                  std::to_string(soa::view::kDefaultFrames) + ")");
    o.frames = std::size_t(n);
  }
  o.quantities.velocity = !a.no_velocity;
  o.quantities.force = !a.no_force;
  return o;
}

/// Refuses --out FILE and --view DIR that are the same path, or FILE inside DIR (the
/// folder is to hold nothing but the viewer's files), before the run.
void check_apart(const std::string& csv, const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path f = fs::weakly_canonical(fs::absolute(csv, ec), ec);
  const fs::path d = fs::weakly_canonical(fs::absolute(dir, ec), ec);
  if (ec) return;  // the run's own checks name the path that cannot be used
  if (f == d || same_file(csv, dir))
    throw Error("--out " + csv + ", --view " + dir +
                ": the same path; the trajectory file and the viewer folder need two");
  if (f.parent_path() == d)
    throw Error("--out " + csv + ": is in the viewer folder --view " + dir +
                ", which holds nothing but the viewer's files; give a path outside it");
}

/// "a,b,c" as names (--lock).
std::vector<std::string> parse_names(const std::string& text, const std::string& option) {
  std::vector<std::string> names;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    const std::string name = text.substr(start, comma - start);
    if (name.empty()) throw Error(option + ": entry " + std::to_string(names.size()) + " is empty");
    names.push_back(name);
    if (comma == std::string::npos) return names;
    start = comma + 1;
  }
}

/// convert: the URDF's JSON scene on stdout.
Result convert(const std::string& path, const UrdfOptions& urdf) {
  if (!is_urdf(path))
    throw Error(path +
                ": not a URDF file (convert reads a URDF robot description, *.urdf, "
                "and writes its JSON scene)");
  const std::string text = urdf_to_scene_json(path, urdf);
  set_stage("writing the result");
  FdSink out(STDOUT_FILENO, "stdout");
  out.write(text.data(), text.size());
  out.finish();
  return Result();
}

std::string join_notes(const std::string& a, const std::string& b) {
  return a.empty() ? b : b.empty() ? a : a + "; " + b;
}

/// The hinges the state puts outside the limits their file gives (URDF <limit>): reported,
/// not enforced (the course's dynamics have no limits). "" when none.
std::string outside_limits(const Scene& s, const State& x) {
  std::string out;
  int n = 0;
  for (const Scene::Frame& f : s.frames) {
    const HingeLimits* l = f.limits();
    if (!l || f.locked) continue;
    const Body& B = s.model.body(f.k);
    const double q = x.theta[B.q_offset], qd = x.beta[B.v_offset];
    std::vector<std::string> what;  // every violation of the hinge
    if (q < l->lower)
      what.push_back("q = " + brief(q) + " below its lower limit " + brief(l->lower));
    if (q > l->upper)
      what.push_back("q = " + brief(q) + " above its upper limit " + brief(l->upper));
    if (qd < -l->velocity)
      what.push_back("qd = " + brief(qd) + " below its limit -" + brief(l->velocity));
    if (qd > l->velocity)
      what.push_back("qd = " + brief(qd) + " above its limit " + brief(l->velocity));
    if (what.empty()) continue;
    std::string who = l->hinge.empty() ? "the hinge of '" + printable(f.name) + "'"
                                       : "joint '" + printable(l->hinge) + "'";
    for (std::size_t i = 0; i < what.size(); ++i) who += (i ? ", " : ": ") + what[i];
    if (n++ < 3) out += (out.empty() ? "" : "; ") + who;
  }
  if (n == 0) return "";
  if (n > 3) out += ", and " + std::to_string(n - 3) + " more";
  return "the state is outside the joint limits the file gives (" + out +
         "): reported, not enforced (the course's dynamics have no joint limits)";
}

/// Loads the scene and runs the verb. Errors after loading (command-line values, --body)
/// gain the scene file's name, as the scene's own errors have it; so does running out of
/// memory, with what was being built.
Result run(const Args& a) {
  set_stage("reading the scene");
  UrdfOptions urdf;
  if (a.tip) urdf.tip = *a.tip;
  if (a.lock) urdf.lock = parse_names(*a.lock, "--lock");
  if (*a.verb == Verb::Convert) return convert(a.scene, urdf);
  const Scene s = load_scene(a.scene, urdf);
  try {
    set_stage("setting up the state");
    VecX<double> beta_dot, tau;
    const State x = state_of(s, a, beta_dot, tau);
    const Scene::Frame* frame = a.body ? &find_frame(s, *a.body) : nullptr;
    const Scene::Frame* operational =
        a.operational ? &find_frame(s, *a.operational, "--operational") : nullptr;
    set_stage(std::string("computing ") + verb_name(*a.verb) + " (" + std::to_string(s.model.n()) +
              " bodies)");
    Result r;
    switch (*a.verb) {
      case Verb::Kinematics:
        r.emit = kinematics(s, x, beta_dot, frame);
        break;
      case Verb::Jacobian:  // default: the tip, the last body of the file
        r.emit = jacobian(s, x, frame ? *frame : s.frames.back());
        break;
      case Verb::InverseDynamics:
        r.emit = inverse_dynamics(s, x, beta_dot);
        break;
      case Verb::ForwardDynamics:
        r.emit = forward_dynamics(s, x, tau, a.check);
        break;
      case Verb::MassMatrix:
        r.emit = mass_matrix(s, x, a.inverse, a.check, operational);
        break;
      case Verb::Simulate:
        if (a.view) {
          const ViewOptions v = view_options(a);
          const OutputOptions o = output_options(a);
          if (!o.csv_path.empty()) check_apart(o.csv_path, v.dir);
          r = simulate(s, x, simulation_options(a), o, &v);
        } else {
          r = simulate(s, x, simulation_options(a), output_options(a));
        }
        break;
      case Verb::Convert:  // handled before the scene is loaded
        break;
      case Verb::View: {
        const ViewOptions v = view_options(a);
        std::optional<SimulationOptions> sim;
        if (a.simulates()) sim = simulation_options(a);
        r = soa::cli::view(s, x, a.q || a.qd, v, sim, a.trajectory);
        break;
      }
    }
    set_stage("checking the result");
    if (!all_finite(r.emit))  // never a silent NaN: huge values overflow
      throw Error("result: not finite (an overflow: are q, qd, qdd, tau too large?)");
    if (r.summary && !r.summary->stiffness_warning.empty())
      r.note = join_notes(r.note, r.summary->stiffness_warning);
    r.note = join_notes(r.note, outside_limits(s, x));
    set_stage("writing the result");
    FdSink out(STDOUT_FILENO, "stdout");
    JsonWriter w(&out);
    r.emit(w);
    w.finish();
    out.finish();
    if (!r.note.empty()) r.note = a.scene + ": " + r.note;
    return r;
  } catch (const FileError&) {  // an output, the trajectory: named already
    throw;
  } catch (const Error& e) {
    throw Error(a.scene + ": " + e.what());
  } catch (const std::bad_alloc&) {
    throw Error(a.scene + ": out of memory while " + stage());
  }
}

}  // namespace

int main(int argc, char** argv) {
  // Past the file size limit (ulimit -f) a write fails with EFBIG and is reported, naming
  // the file, instead of the signal ending the program without a word.
  std::signal(SIGXFSZ, SIG_IGN);
  Args a;
  try {
    a = parse_args(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const UsageError& e) {
    std::cerr << "soa: " << e.what() << " (see soa --help)\n";
    return 2;
  }
  try {
    if (a.help) {
      FdSink out(STDOUT_FILENO, "stdout");
      const std::string text = help_text(a.verb);
      out.write(text.data(), text.size());
      out.finish();
      return 0;
    }
    const Result r = run(a);
    if (!r.note.empty()) std::cerr << r.note << "\n";
    return r.exit_code;
  } catch (const std::bad_alloc&) {
    std::cerr << a.scene << ": out of memory while " << stage() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
}
