// The six computations of `soa` (lessons 3-8 and the simulation), from a scene and a state
// to JSON. Vectors over the chain are reordered from the model's order (tip first) to the
// file's (base first).
#include "verbs.hpp"

#include <unistd.h>

#include <Eigen/Cholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>

#include "output.hpp"
#include "soa/chain.hpp"
#include "soa/chain/operational_space.hpp"
#include "trajectory.hpp"

namespace soa::cli {
namespace {

std::string& stage_text() {
  static std::string s = "reading the command line";
  return s;
}

/// "%g" of a number, for messages.
std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

/// The names of the coordinates of beta in file order: "link3", or "wrist[0]", "wrist[1]".
std::vector<std::string> column_names(const Scene& s) {
  std::vector<std::string> names;
  for (int k : s.file_order) {
    const Body& B = s.model.body(k);
    const int nv = B.hinge.nv();
    for (int i = 0; i < nv; ++i)
      names.push_back(nv == 1 ? B.name : B.name + "[" + std::to_string(i) + "]");
  }
  return names;
}

/// A model-order vector (tip first) picked in file order by \p idx.
VecX<double> pick(const VecX<double>& v, const std::vector<int>& idx) {
  VecX<double> out(idx.size());
  for (std::size_t i = 0; i < idx.size(); ++i) out[i] = v[idx[i]];
  return out;
}

/// The rows of a model-order matrix in file order, rows and columns.
void file_order_rows(JsonWriter& w, const MatX<double>& A, const std::vector<int>& idx) {
  const int n = int(idx.size());
  VecX<double> row(n);
  w.begin_array();
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) row[c] = A(idx[r], idx[c]);
    w.numbers(row);
  }
  w.end_array();
}

/// A model-order vector over the coordinates twice: per body (`per_body`: {name: [...]}) and
/// whole in file order (`whole`), with the "columns" naming its entries.
void per_body_and_file_order(JsonWriter& w, const Scene& scene, const char* per_body,
                             const char* whole, const VecX<double>& v) {
  w.key(per_body);
  w.begin_object();
  for (int k : scene.file_order) {
    const Body& B = scene.model.body(k);
    w.key(B.name);
    w.numbers(v.segment(B.v_offset, B.hinge.nv()));
  }
  w.end_object();
  w.key("columns");
  w.strings(column_names(scene));
  w.key(whole);
  w.numbers(pick(v, file_v_index(scene)));
}

}  // namespace

const char* signal_name(int sig) {
  return sig == SIGINT ? "SIGINT" : sig == SIGHUP ? "SIGHUP" : "SIGTERM";
}

const std::string& stage() {
  return stage_text();
}
void set_stage(std::string what) {
  stage_text() = std::move(what);
}

const Scene::Frame& find_frame(const Scene& scene, const std::string& name,
                               const std::string& option) {
  for (const Scene::Frame& f : scene.frames)
    if (f.name == name) return f;
  std::string names;
  for (const Scene::Frame& f : scene.frames) names += (names.empty() ? "" : ", ") + f.name;
  throw Error(option + ": no body named \"" + name + "\" (the bodies: " + names + ")");
}

Emit kinematics(const Scene& scene, const State& x, const VecX<double>& beta_dot,
                const Scene::Frame* only) {
  const Model& m = scene.model;
  auto ws = std::make_shared<Workspace>(Workspace::lazy());  // phi, pose, V, a, alpha
  update_phi(m, x.theta, *ws);
  update_poses(m, *ws);
  update_velocities(m, x, *ws);
  update_accelerations(m, x, beta_dot.data(), Acceleration(), *ws);
  return [&scene, ws, only](JsonWriter& w) {
    w.begin_object();
    w.member("scene", scene.title);
    w.key("bodies");
    w.begin_object();
    for (const Scene::Frame& f : scene.frames) {
      if (only && only->name != f.name) continue;
      // Frame F fixed on body k at ^{O_k}T_F: V(F) = phi*(O_k, F) V(k), and its acceleration
      // adds the centripetal term of the offset (as jacobian_dot_times_beta() does).
      const Phi phi(f.offset());
      const Pose pose = ws->pose[f.k - 1] * f.offset();
      const Velocity V = phi.transpose_apply(ws->V[f.k - 1]);
      const Vec3<double> om = ws->V[f.k - 1].angular();
      const Acceleration alpha =
          phi.transpose_apply(ws->alpha[f.k - 1]) +
          Acceleration(Vec3<double>::Zero(),
                       f.offset().R().transpose() * om.cross(om.cross(f.offset().l())));
      w.key(f.name);
      w.begin_object();
      w.key("position");
      w.numbers(pose.l());
      w.key("quaternion");
      w.numbers(UnitQuaternion::from_matrix(pose.R()).coeffs());
      w.key("velocity");
      w.numbers(V.vector());
      w.key("acceleration");
      w.numbers(alpha.vector());
      w.end_object();
    }
    w.end_object();
    w.end_object();
  };
}

Emit jacobian(const Scene& scene, const State& x, const Scene::Frame& frame) {
  const Model& m = scene.model;
  Workspace ws = Workspace::lazy();  // phi and pose only
  update_phi(m, x.theta, ws);
  update_poses(m, ws);
  auto J = std::make_shared<Eigen::Matrix<double, 6, Eigen::Dynamic>>();
  set_stage("building the Jacobian (6 x " + std::to_string(m.nv()) + ")");
  soa::jacobian(m, x.theta, ws, frame.k, frame.offset(), *J);
  return [&scene, &frame, J](JsonWriter& w) {
    const std::vector<int> idx = file_v_index(scene);
    w.begin_object();
    w.member("scene", scene.title);
    w.member("body", frame.name);
    w.key("rows");
    w.strings({"wx", "wy", "wz", "vx", "vy", "vz"});
    w.key("columns");
    w.strings(column_names(scene));
    w.key("J");
    w.begin_array();
    VecX<double> row(idx.size());
    for (int r = 0; r < 6; ++r) {
      for (std::size_t i = 0; i < idx.size(); ++i) row[i] = (*J)(r, idx[i]);
      w.numbers(row);
    }
    w.end_array();
    w.end_object();
  };
}

Emit inverse_dynamics(const Scene& scene, const State& x, const VecX<double>& beta_dot) {
  const Model& m = scene.model;
  auto T = std::make_shared<VecX<double>>(m.nv());
  {
    Workspace ws = Workspace::lazy();  // no poses
    soa::inverse_dynamics(m, x, beta_dot, scene.f_ext, ws, *T);
  }
  return [&scene, T](JsonWriter& w) {
    w.begin_object();
    w.member("scene", scene.title);
    per_body_and_file_order(w, scene, "hinge_forces", "T", *T);
    w.end_object();
  };
}

Emit forward_dynamics(const Scene& scene, const State& x, const VecX<double>& tau, bool check) {
  const Model& m = scene.model;
  const int nv = m.nv();
  auto qdd = std::make_shared<VecX<double>>(nv);
  struct Checks {
    double round_trip = 0;
    bool dense = false;
    double dense_difference = 0, dense_cond = 0;
  };
  auto c = std::make_shared<Checks>();
  {
    Workspace ws = Workspace::lazy();  // no poses
    {
      ForwardDynamics fd = ForwardDynamics::lean(m);  // G(k) and nu(k) only, not the full storage
      soa::forward_dynamics(m, x, tau, scene.f_ext, ws, fd, *qdd);
    }
    // The round trip through inverse dynamics (O(N)): T(q, qd, qdd) = tau within rounding,
    // measured against the size of the terms, |tau| + |C(q, qd)|.
    VecX<double> T(nv), C(nv);
    soa::inverse_dynamics(m, x, *qdd, scene.f_ext, ws, T);
    soa::inverse_dynamics(m, x, VecX<double>::Zero(nv).eval(), scene.f_ext, ws, C);
    const double scale = tau.norm() + C.norm();
    c->round_trip = scale > 0 ? (T - tau).norm() / scale : (T - tau).norm();
    if (check || nv <= kDenseCheckMax) {
      // The second way (lessons 4-5): M qdd = tau - C, M by the composite bodies, Eigen's
      // LDLT. Its own error is about eps cond(M), often far above the O(N) result's.
      set_stage("building the dense cross-check (the " + std::to_string(nv) + " x " +
                std::to_string(nv) + " mass matrix)");
      std::vector<SpatialInertia> R(m.n());
      MatX<double> M;
      update_phi(m, x.theta, ws);
      mass_matrix_crb(m, x, ws, R, M);
      const Eigen::LDLT<MatX<double>> ldlt(M);
      const VecX<double> ref = ldlt.solve(tau - C);
      const double s = std::max(ref.norm(), qdd->norm());
      c->dense = true;
      c->dense_difference = s > 0 ? (*qdd - ref).norm() / s : 0.0;
      const double rcond = ldlt.rcond();
      c->dense_cond = rcond > 0 ? 1 / rcond : std::numeric_limits<double>::infinity();
    }
  }
  return [&scene, qdd, c](JsonWriter& w) {
    const Model& m = scene.model;
    w.begin_object();
    w.member("scene", scene.title);
    w.member("method", "articulated body forward dynamics, O(N)");
    per_body_and_file_order(w, scene, "accelerations", "qdd", *qdd);
    w.key("check");
    w.begin_object();
    w.member("round_trip_residual", c->round_trip);
    w.member("round_trip",
             "|ID(q, qd, qdd) - tau| / (|tau| + |C(q, qd)|), ID the inverse dynamics of lesson 4: "
             "how far qdd is from satisfying the equations of motion");
    if (c->dense) {
      w.member("dense_difference", c->dense_difference);
      if (std::isfinite(c->dense_cond)) {
        w.key("dense_cond_estimate");  // 1 / Eigen's rcond() of the LDLT
        w.value(c->dense_cond);
      }
      w.member("dense",
               "|qdd - qdd_dense| / |qdd|, qdd_dense solving M qdd = tau - C (M by composite "
               "bodies, Eigen LDLT): a difference between two methods, of which the dense one "
               "alone errs by up to about eps cond(M)");
    } else {
      w.key("dense_skipped");
      w.value("n_v = " + std::to_string(m.nv()) + " is over " + std::to_string(kDenseCheckMax) +
              "; --check runs the dense cross-check (O(n_v^3) time, O(n_v^2) memory)");
    }
    w.end_object();
    w.end_object();
  };
}

namespace {

volatile std::sig_atomic_t g_signal = 0;
/// The first stop signal asks the run to stop at a step boundary; a second one ends the
/// program at once, by that signal, once the temporary output files are removed.
void on_stop_signal(int s) {
  if (g_signal != 0) {
    remove_temporaries();
    ::signal(s, SIG_DFL);
    ::raise(s);  // delivered when the handler returns
    return;
  }
  g_signal = s;
}

/// The signals that stop a simulation: SIGINT (Ctrl-C), SIGTERM, and SIGHUP (the terminal
/// closed), which set g_signal while it runs.
constexpr int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP};

class StopSignals {
 public:
  StopSignals() {
    g_signal = 0;
    struct sigaction sa {};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0;
    for (std::size_t i = 0; i < std::size(kStopSignals); ++i)
      sigaction(kStopSignals[i], &sa, &old_[i]);
  }
  ~StopSignals() {
    for (std::size_t i = 0; i < std::size(kStopSignals); ++i)
      sigaction(kStopSignals[i], &old_[i], nullptr);
  }

 private:
  struct sigaction old_[std::size(kStopSignals)]{};
};

}  // namespace

Result simulate(const Scene& scene, const State& x0, const SimulationOptions& opt_in,
                const OutputOptions& out, const ViewOptions* view, const char* verb) {
  const Model& m = scene.model;
  const std::vector<int> qi = file_q_index(scene), vi = file_v_index(scene);
  ChainSystem sys(m, scene.f_ext);
  std::unique_ptr<OutputFile> file;
  std::string line;
  long rows = 0;
  if (!out.csv_path.empty()) {
    file = std::make_unique<OutputFile>(out.csv_path, "--out " + out.csv_path, scene.name);
    for (const std::string& c : trajectory_columns(scene))
      line += (line.empty() ? "" : ",") + csv_field(c);
    line += "\n";
    file->sink().write(line.data(), line.size());
  }
  // The fixed step as the run takes it: [0, T] divided evenly.
  const double dt =
      is_adaptive(opt_in.method)
          ? 0.0
          : opt_in.t_end /
                std::max(1.0, std::ceil(double(opt_in.t_end) / double(opt_in.dt) - 1e-9));
  std::unique_ptr<soa::view::Recorder> recorder;
  std::string label;  // the viewer's run: "rk4, h = 0.001 s"
  if (view) {
    recorder =
        std::make_unique<soa::view::Recorder>(scene, opt_in.t_end, view->frames, view->quantities);
    label = std::string(integrator_name(opt_in.method)) +
            (is_adaptive(opt_in.method) ? ", tol = " + num(opt_in.tol) : ", h = " + num(dt) + " s");
  }
  std::shared_ptr<const ViewWritten> written;
  // The viewer of what was computed, the last state (at \p t) recorded whatever the budget.
  auto write_viewer = [&](double t, const State& s, const std::string& why) {
    recorder->record(t, s);
    set_stage("writing the viewer");
    written = std::make_shared<const ViewWritten>(
        write_view(scene, *view, *recorder, label,
                   why.empty() ? recorder->note() : recorder->note() + "; " + why));
  };
  double written_t = -1;  // the time of the last row written
  auto write_row = [&](double t, const State& s) {
    char text[32];
    line.clear();
    line.append(text, format_number(text, t));
    for (int i : qi) line.append(1, ',').append(text, format_number(text, s.theta[i]));
    for (int i : vi) line.append(1, ',').append(text, format_number(text, s.beta[i]));
    double qerr = 0;
    for (const Body& B : m.bodies())
      if (B.hinge.type == HingeType::Spherical || B.hinge.type == HingeType::Free)
        qerr = std::max(qerr, std::abs(s.theta.segment<4>(B.q_offset).norm() - 1.0));
    line.append(1, ',').append(text, format_number(text, sys.energy(s)));
    line.append(1, ',').append(text, format_number(text, qerr)).append(1, '\n');
    file->sink().write(line.data(), line.size());
    if (file->sink().failed()) file->sink().fail();  // a full disk stops the run at once
    written_t = t;
    ++rows;
  };
  // A progress bar on stderr for runs longer than a second, when stderr is a terminal.
  const bool tty = isatty(STDERR_FILENO) == 1;
  const auto start = std::chrono::steady_clock::now();
  auto last = start;
  bool drew = false;
  long step = -1;
  double last_t = 0, next_out = 0;
  State x = x0;
  SimulationOptions opt = opt_in;
  StopSignals signals;
  opt.stop = &g_signal;
  auto observe = [&](double t, const State& s) {
    ++step;
    last_t = t;
    if (recorder) {
      // The first call comes once soa::simulate() has checked the options: a folder that
      // cannot be used (not a viewer's, three.js missing) stops the command now, not after
      // the run, and nothing is written before the run ends.
      if (step == 0) check_view_destination(*view);
      recorder->offer(t, s);
    }
    if (file) {
      bool due = out.out_dt > 0 ? t >= next_out - 1e-9 * out.out_dt : step % out.every == 0;
      if (due) {
        write_row(t, s);
        if (out.out_dt > 0) {
          // The next multiple of out_dt after t. Beyond 2^53 intervals (t / out_dt inexact
          // or infinite) the multiples are closer together than the doubles near t: every
          // step is due.
          const double k = t / out.out_dt;
          next_out = k < kMaxSteps ? (std::floor(k + 1e-9) + 1) * out.out_dt : t;
        }
      }
    }
    if (tty) {
      const auto now = std::chrono::steady_clock::now();
      if (now - start > std::chrono::seconds(1) && now - last > std::chrono::milliseconds(200)) {
        last = now;
        const int done = opt.t_end > 0 ? int(40 * t / opt.t_end) : 40;
        std::fprintf(stderr, "\r[%-40s] t = %.4g / %.4g s", std::string(done, '#').c_str(), t,
                     opt.t_end);
        drew = true;
      }
    }
  };
  auto clear_bar = [&] {
    if (drew) std::fprintf(stderr, "\r%70s\r", "");
  };
  // A run stopped before its end (a blow-up, the step budget): the rows so far are kept,
  // complete, and the viewer of them written; x is the last accepted state. The error to
  // throw: \p what and where the kept rows and viewer are.
  auto stopped = [&](const std::string& what, const std::string& why) {
    std::string kept;
    if (file) {
      if (written_t != last_t) write_row(last_t, x);
      file->commit();
      kept = "; the trajectory up to t = " + num(last_t) + " s (" + std::to_string(rows) +
             " rows) is in " + out.csv_path;
    }
    if (recorder) {
      write_viewer(last_t, x, why);
      const std::string frames = " (" + std::to_string(written->frames) + " frames)";
      kept += file
                  ? ", its viewer" + frames + " in " + view->dir
                  : "; the viewer up to t = " + num(last_t) + " s" + frames + " is in " + view->dir;
    }
    return Error(what + kept);
  };
  SimulationSummary sum;
  try {
    sum = soa::simulate(sys, x, opt, observe);
  } catch (const FileError&) {  // an output, the viewer's folder
    clear_bar();
    throw;
  } catch (const Error& e) {
    // A blow-up (or a singular D(k)) part way.
    clear_bar();
    if ((!file && !recorder) || step < 0) throw;
    throw stopped(e.what(), "stopped by a blow-up after t = " + num(last_t) + " s");
  }
  clear_bar();
  if (sum.budget_spent) {
    const std::string budget = "--max-steps " + std::to_string(opt.max_steps);
    const std::string what = std::string("simulate (") + integrator_name(opt.method) +
                             "): the step budget (" + budget + ") is spent at step " +
                             std::to_string(sum.steps) + ", t = " + num(sum.t) + " s of [0, " +
                             num(opt.t_end) + "]";
    if (!file && !recorder) throw Error(what);
    throw stopped(what, "stopped by the step budget (" + budget + ") at t = " + num(sum.t) + " s");
  }
  if (file) {
    if (written_t != sum.t) write_row(sum.t, x);
    file->commit();
  }
  const int sig = sum.interrupted ? int(g_signal) : 0;
  const char* sig_name = signal_name(sig);
  if (recorder)
    write_viewer(sum.t, x,
                 sum.interrupted ? std::string("interrupted by ") + sig_name +
                                       " at t = " + num(sum.t) + " s of " + num(opt.t_end)
                                 : std::string());
  Result r;
  if (sum.interrupted) {
    r.exit_code = 128 + sig;
    r.note =
        std::string(verb) + ": interrupted by " + sig_name + " at t = " + num(sum.t) + " s, step " +
        std::to_string(sum.steps) + " of [0, " + num(opt.t_end) + "]" +
        (file ? "; the trajectory up to there is in " + out.csv_path : std::string()) +
        (recorder ? std::string(file ? ", its viewer in " : "; the viewer up to there is in ") +
                        view->dir
                  : std::string());
  }
  r.view = written;
  r.summary = std::make_shared<const SimulationSummary>(sum);
  auto xf = std::make_shared<State>(std::move(x));
  r.emit = [&scene, opt, sum, dt, xf, out, rows, sig_name, written](JsonWriter& w) {
    w.begin_object();
    w.member("scene", scene.title);
    w.member("integrator", integrator_name(opt.method));
    w.member("order", integrator_order(opt.method));
    if (is_adaptive(opt.method)) {
      w.member("tol", opt.tol);
    } else {
      w.member("dt", dt);
    }
    w.member("t_end", opt.t_end);
    if (sum.interrupted) {
      w.key("interrupted");
      w.begin_object();
      w.member("signal", sig_name);
      w.member("t", sum.t);
      w.end_object();
    }
    w.member("steps", sum.steps);
    w.member("rejected_steps", sum.rejected);
    if (soa::is_adaptive_implicit(opt.method)) {
      w.member("newton_failures", sum.newton_failures);
      w.member("jacobians", sum.jacobians);
    }
    if (opt.method == soa::Integrator::Variational) {
      w.member("subdivided_steps", sum.subdivided);
      w.member("max_pieces", sum.max_pieces);
    }
    w.member("evaluations", sum.evaluations);
    if (sum.stiffness_checks > 0) {
      w.key("stiffness");
      w.begin_object();
      w.member("checks", sum.stiffness_checks);
      w.member("max_h_lambda", sum.max_h_lambda);
      if (!sum.stiffness_warning.empty()) w.member("warning", sum.stiffness_warning);
      w.end_object();
    }
    w.member("wall_seconds", sum.wall_seconds);
    w.member("energy_start", sum.energy0);
    w.member("energy_end", sum.energy1);
    w.member("max_energy_drift", sum.max_energy_drift);
    w.key("columns");
    w.strings(column_names(scene));
    w.key("q");
    w.numbers(pick(xf->theta, file_q_index(scene)));
    w.key("qd");
    w.numbers(pick(xf->beta, file_v_index(scene)));
    if (!out.csv_path.empty()) {
      w.member("trajectory", out.csv_path);
      w.member("rows", rows);
    }
    if (written) {
      w.key("view");
      w.begin_object();
      emit_view(w, *written);
      w.end_object();
    }
    w.end_object();
  };
  return r;
}

Emit mass_matrix(const Scene& scene, const State& x, bool inverse, bool check,
                 const Scene::Frame* operational) {
  const Model& m = scene.model;
  const int n = m.nv();
  if (n > kMassMatrixMax)
    throw Error("mass-matrix: n_v = " + std::to_string(n) + " is over " +
                std::to_string(kMassMatrixMax) + ": the n_v x n_v matrix would take " +
                num(8.0 * n * n) +
                " bytes and its text about 20 times that; forward-dynamics and "
                "inverse-dynamics need no mass matrix");
  // O(N^2) from the composite rigid body inertias (lesson 5).
  set_stage("building the " + std::to_string(n) + " x " + std::to_string(n) + " mass matrix");
  Workspace ws(m);
  update_phi(m, x.theta, ws);
  std::vector<SpatialInertia> R(m.n());
  auto M = std::make_shared<MatX<double>>();
  mass_matrix_crb(m, x, ws, R, *M);
  struct Checks {
    double scale = 0;
    bool symmetric = true, dense = false, positive_definite = false;
    double identity_residual = 0, probe_residual = 0;
    Mat6<double> op_inv = Mat6<double>::Zero();  // J M^-1 J* of --operational
    double op_residual = 0;                      // vs the dense J M^-1 J*
  };
  auto c = std::make_shared<Checks>();
  c->scale = n > 0 ? M->cwiseAbs().maxCoeff() : 0.0;
  for (int i = 0; i < n && c->symmetric; ++i)
    for (int j = i + 1; j < n; ++j)
      if (std::abs((*M)(i, j) - (*M)(j, i)) > 1e-12 * c->scale) c->symmetric = false;
  c->dense = check || n <= kDenseCheckMax;
  if (c->dense) {
    const Eigen::LLT<MatX<double>> llt(0.5 * (*M + M->transpose()));
    c->positive_definite = llt.info() == Eigen::Success;
  }
  auto Minv = std::make_shared<MatX<double>>();
  if (inverse) {  // O(N^2) without M (lesson 7), checked on random vectors and by M Minv - I
    set_stage("building the " + std::to_string(n) + " x " + std::to_string(n) +
              " inverse mass matrix");
    MassMatrixInverse wi(m);
    mass_matrix_inverse(m, x, ws, wi, *Minv);
    std::mt19937 g(11);
    std::normal_distribution<double> N;
    for (int probe = 0; probe < 3 && n > 0; ++probe) {
      VecX<double> v(n);
      for (int i = 0; i < n; ++i) v[i] = N(g);
      c->probe_residual = std::max(c->probe_residual, (*M * (*Minv * v) - v).norm() / v.norm());
    }
    if (c->dense && n > 0)
      c->identity_residual = (*M * *Minv - MatX<double>::Identity(n, n)).cwiseAbs().maxCoeff();
  }
  if (operational) {  // O(N) from Upsilon (lesson 7, section 8); dense J M^-1 J* as the check
    set_stage("computing the operational-space inverse inertia of " + operational->name);
    Upsilon u(m);
    operational_space_inverse_inertia(m, x, ws, u, operational->k, operational->offset(),
                                      c->op_inv);
    if (c->dense && n > 0) {
      update_poses(m, ws);
      Eigen::Matrix<double, 6, Eigen::Dynamic> J;
      soa::jacobian(m, x.theta, ws, operational->k, operational->offset(), J);
      const MatX<double> X = Eigen::LDLT<MatX<double>>(*M).solve(MatX<double>(J.transpose()));
      const Mat6<double> ref = J * X;
      const double scale = std::max(ref.cwiseAbs().maxCoeff(), 1e-300);
      c->op_residual = (c->op_inv - ref).cwiseAbs().maxCoeff() / scale;
    }
  }
  return [&scene, M, Minv, c, inverse, operational](JsonWriter& w) {
    const std::vector<int> idx = file_v_index(scene);
    const int n = int(idx.size());
    w.begin_object();
    w.member("scene", scene.title);
    w.key("columns");
    w.strings(column_names(scene));
    w.key("M");
    file_order_rows(w, *M, idx);
    w.member("symmetric", c->symmetric);
    if (c->dense) {
      w.member("positive_definite", c->positive_definite);
    }
    if (inverse) {
      w.key("Minv");
      file_order_rows(w, *Minv, idx);
      w.member("probe_residual", c->probe_residual);
      if (c->dense) {
        w.member("identity_residual", c->identity_residual);
      }
    }
    if (operational) {
      w.key("operational");
      w.begin_object();
      w.member("body", operational->name);
      w.key("rows");
      w.strings({"wx", "wy", "wz", "vx", "vy", "vz"});
      w.key("Lambda_inv");
      w.rows(c->op_inv);
      if (c->dense) w.member("dense_residual", c->op_residual);
      w.end_object();
    }
    if (!c->dense) {
      w.key("skipped");
      w.value("n_v = " + std::to_string(n) + " is over " + std::to_string(kDenseCheckMax) +
              ": positive_definite (a Cholesky factorization)" +
              (inverse ? std::string(" and identity_residual (M Minv - I)") : std::string()) +
              (operational ? std::string(" and operational.dense_residual") : std::string()) +
              " cost O(n_v^3) and were not computed; --check computes them");
    }
    w.end_object();
  };
}

}  // namespace soa::cli
