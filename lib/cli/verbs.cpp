// The six computations of `soa` (lessons 3-8 and the simulation), from a scene and a state to JSON. Vectors
// over the chain are reordered from the model's order (tip first) to the file's (base first).
#include "verbs.hpp"

#include <unistd.h>
#include <Eigen/Cholesky>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <limits>

#include "soa/chain.hpp"

namespace soa::cli {
namespace {

/// The names of the coordinates of beta in file order: "link3", or "wrist[0]", "wrist[1]".
Json column_names(const Scene& s) {
  Json names = Json::array();
  for (int k : s.file_order) {
    const Body& B = s.model.body(k);
    const int nv = B.hinge.nv();
    for (int i = 0; i < nv; ++i)
      names.push_back(nv == 1 ? B.name : B.name + "[" + std::to_string(i) + "]");
  }
  return names;
}

/// A model-order matrix (tip first) in file order, rows and columns.
MatX<double> in_file_order(const Scene& s, const MatX<double>& A) {
  const std::vector<int> idx = file_v_index(s);
  const int n = int(idx.size());
  MatX<double> out(n, n);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) out(r, c) = A(idx[r], idx[c]);
  return out;
}

/// A model-order configuration (tip first) in file order.
VecX<double> in_file_order_q(const Scene& s, const VecX<double>& theta) {
  const std::vector<int> idx = file_q_index(s);
  VecX<double> out(idx.size());
  for (std::size_t i = 0; i < idx.size(); ++i) out[i] = theta[idx[i]];
  return out;
}

/// A model-order vector (tip first) in file order.
VecX<double> in_file_order(const Scene& s, const VecX<double>& v) {
  const std::vector<int> idx = file_v_index(s);
  VecX<double> out(idx.size());
  for (std::size_t i = 0; i < idx.size(); ++i) out[i] = v[idx[i]];
  return out;
}

}  // namespace

const Scene::Frame& find_frame(const Scene& scene, const std::string& name) {
  for (const Scene::Frame& f : scene.frames)
    if (f.name == name) return f;
  std::string names;
  for (const Scene::Frame& f : scene.frames) names += (names.empty() ? "" : ", ") + f.name;
  throw Error("--body: no body named \"" + name + "\" (the bodies: " + names + ")");
}

Json kinematics(const Scene& scene, const State& x, const VecX<double>& beta_dot,
                const Scene::Frame* only) {
  const Model& m = scene.model;
  Workspace ws(m);
  update_phi(m, x.theta, ws);
  update_poses(m, ws);
  update_velocities(m, x, ws);
  update_accelerations(m, x, beta_dot.data(), Acceleration(), ws);
  Json bodies = Json::object();
  for (const Scene::Frame& f : scene.frames) {
    if (only && only->name != f.name) continue;
    // Frame F fixed on body k at ^{O_k}T_F: V(F) = phi*(O_k, F) V(k), and its acceleration
    // adds the centripetal term of the offset (as jacobian_dot_times_beta() does).
    const Phi phi(f.offset);
    const Pose pose = ws.pose[f.k - 1] * f.offset;
    const Velocity V = phi.transpose_apply(ws.V[f.k - 1]);
    const Vec3<double> w = ws.V[f.k - 1].angular();
    const Acceleration alpha =
        phi.transpose_apply(ws.alpha[f.k - 1]) +
        Acceleration(Vec3<double>::Zero(),
                     f.offset.R().transpose() * w.cross(w.cross(f.offset.l())));
    Json b = Json::object();
    b["position"] = to_json(pose.l());
    b["quaternion"] = to_json(UnitQuaternion::from_matrix(pose.R()).coeffs());
    b["velocity"] = to_json(V.vector());
    b["acceleration"] = to_json(alpha.vector());
    bodies[f.name] = std::move(b);
  }
  Json out = Json::object();
  out["scene"] = scene.title;
  out["bodies"] = std::move(bodies);
  return out;
}

Json jacobian(const Scene& scene, const State& x, const Scene::Frame& frame) {
  const Model& m = scene.model;
  Workspace ws(m);
  update_phi(m, x.theta, ws);
  update_poses(m, ws);
  Eigen::Matrix<double, 6, Eigen::Dynamic> J;
  soa::jacobian(m, x.theta, ws, frame.k, frame.offset, J);
  const std::vector<int> idx = file_v_index(scene);
  MatX<double> J_file(6, idx.size());
  for (std::size_t i = 0; i < idx.size(); ++i) J_file.col(i) = J.col(idx[i]);
  Json out = Json::object();
  out["scene"] = scene.title;
  out["body"] = frame.name;
  out["rows"] = Json::array({"wx", "wy", "wz", "vx", "vy", "vz"});
  out["columns"] = column_names(scene);
  out["J"] = rows_to_json(J_file);
  return out;
}

Json inverse_dynamics(const Scene& scene, const State& x, const VecX<double>& beta_dot) {
  const Model& m = scene.model;
  Workspace ws(m);
  VecX<double> T(m.nv());
  soa::inverse_dynamics(m, x, beta_dot, scene.f_ext, ws, T);
  Json per_body = Json::object();
  for (int k : scene.file_order) {
    const Body& B = m.body(k);
    per_body[B.name] = to_json(T.segment(B.v_offset, B.hinge.nv()));
  }
  Json out = Json::object();
  out["scene"] = scene.title;
  out["hinge_forces"] = std::move(per_body);
  out["columns"] = column_names(scene);
  out["T"] = to_json(in_file_order(scene, T));
  return out;
}

Json forward_dynamics(const Scene& scene, const State& x, const VecX<double>& tau) {
  const Model& m = scene.model;
  Workspace ws(m);
  ForwardDynamics fd(m);
  VecX<double> beta_dot(m.nv());
  soa::forward_dynamics(m, x, tau, scene.f_ext, ws, fd, beta_dot);
  // The second way (lessons 4-5): M beta_dot = tau - C, M by the composite bodies, C by
  // inverse dynamics at beta_dot = 0, Eigen's LDLT.
  VecX<double> C(m.nv());
  soa::inverse_dynamics(m, x, VecX<double>::Zero(m.nv()).eval(), scene.f_ext, ws, C);
  std::vector<SpatialInertia> R(m.n());
  MatX<double> M;
  update_phi(m, x.theta, ws);
  mass_matrix_crb(m, x, ws, R, M);
  const VecX<double> ref = M.ldlt().solve(tau - C);
  const double scale = std::max(ref.norm(), beta_dot.norm());
  Json per_body = Json::object();
  for (int k : scene.file_order) {
    const Body& B = m.body(k);
    per_body[B.name] = to_json(beta_dot.segment(B.v_offset, B.hinge.nv()));
  }
  Json check = Json::object();
  check["method"] = "M qdd = tau - C, M by composite bodies, Eigen LDLT";
  check["relative_difference"] = scale > 0 ? (beta_dot - ref).norm() / scale : 0.0;
  Json out = Json::object();
  out["scene"] = scene.title;
  out["method"] = "articulated body forward dynamics, O(N)";
  out["accelerations"] = std::move(per_body);
  out["columns"] = column_names(scene);
  out["qdd"] = to_json(in_file_order(scene, beta_dot));
  out["check"] = std::move(check);
  return out;
}

Json simulate(const Scene& scene, const State& x0, const SimulationOptions& opt,
              const std::string& csv_path) {
  const Model& m = scene.model;
  std::ofstream csv;
  const std::vector<int> qi = file_q_index(scene), vi = file_v_index(scene);
  if (!csv_path.empty()) {
    csv.open(csv_path);
    if (!csv) throw Error("--out: cannot write " + csv_path);
    csv << std::setprecision(std::numeric_limits<double>::max_digits10) << "t";
    const Json names = column_names(scene);
    for (int k : scene.file_order) {  // q names: "link1", or "ball[0]".."ball[3]"
      const Body& B = m.body(k);
      for (int i = 0; i < B.hinge.nq(); ++i)
        csv << ",q:" << (B.hinge.nq() == 1 ? B.name : B.name + "[" + std::to_string(i) + "]");
    }
    for (const auto& n : names) csv << ",qd:" << n.get<std::string>();
    csv << ",energy,quaternion_norm_error\n";
  }
  // A progress bar on stderr for runs longer than a second, when stderr is a terminal.
  const bool tty = isatty(STDERR_FILENO) == 1;
  const auto start = std::chrono::steady_clock::now();
  auto last = start;
  bool drew = false;
  ChainSystem sys(m, scene.f_ext);
  State x = x0;
  const SimulationSummary sum = soa::simulate(sys, x, opt, [&](double t, const State& s) {
    if (csv.is_open()) {
      csv << t;
      for (int i : qi) csv << ',' << s.theta[i];
      for (int i : vi) csv << ',' << s.beta[i];
      double qerr = 0;
      for (const Body& B : m.bodies())
        if (B.hinge.type == HingeType::Spherical || B.hinge.type == HingeType::Free)
          qerr = std::max(qerr, std::abs(s.theta.segment<4>(B.q_offset).norm() - 1.0));
      csv << ',' << sys.energy(s) << ',' << qerr << '\n';
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
  });
  if (drew) std::fprintf(stderr, "\r%70s\r", "");
  Json out = Json::object();
  out["scene"] = scene.title;
  out["integrator"] = integrator_name(opt.method);
  out["order"] = integrator_order(opt.method);
  if (opt.method == Integrator::DormandPrince)
    out["tol"] = opt.tol;
  else
    out["dt"] = opt.t_end / double(std::max(1L, sum.steps));
  out["t_end"] = opt.t_end;
  out["steps"] = sum.steps;
  out["rejected_steps"] = sum.rejected;
  out["evaluations"] = sum.evaluations;
  out["wall_seconds"] = sum.wall_seconds;
  out["energy_start"] = sum.energy0;
  out["energy_end"] = sum.energy1;
  out["max_energy_drift"] = sum.max_energy_drift;
  out["columns"] = column_names(scene);
  out["q"] = to_json(in_file_order_q(scene, x.theta));
  out["qd"] = to_json(in_file_order(scene, x.beta));
  if (!csv_path.empty()) out["trajectory"] = csv_path;
  return out;
}

Json mass_matrix(const Scene& scene, const State& x, bool inverse) {
  // O(N^2) from the composite rigid body inertias (lesson 5).
  Workspace ws(scene.model);
  update_phi(scene.model, x.theta, ws);
  std::vector<SpatialInertia> R(scene.model.n());
  MatX<double> M;
  mass_matrix_crb(scene.model, x, ws, R, M);
  const MatX<double> M_file = in_file_order(scene, M);
  const int n = int(M_file.rows());
  const double scale = n > 0 ? M_file.cwiseAbs().maxCoeff() : 0.0;
  const bool symmetric =
      n == 0 || (M_file - M_file.transpose()).cwiseAbs().maxCoeff() <= 1e-12 * scale;
  const Eigen::LLT<MatX<double>> llt(0.5 * (M_file + M_file.transpose()));
  Json out = Json::object();
  out["scene"] = scene.title;
  out["columns"] = column_names(scene);
  out["M"] = rows_to_json(M_file);
  out["symmetric"] = symmetric;
  out["positive_definite"] = llt.info() == Eigen::Success;
  if (inverse) {  // O(N^2) without M (lesson 7), checked by |M Minv - I|
    MassMatrixInverse w(scene.model);
    MatX<double> Minv;
    mass_matrix_inverse(scene.model, x, ws, w, Minv);
    const MatX<double> Minv_file = in_file_order(scene, Minv);
    out["Minv"] = rows_to_json(Minv_file);
    out["identity_residual"] =
        n > 0 ? (M_file * Minv_file - MatX<double>::Identity(n, n)).cwiseAbs().maxCoeff() : 0.0;
  }
  return out;
}

}  // namespace soa::cli
