// The four computations of `soa` (lessons 3-4), from a scene and a state to JSON. Vectors
// over the chain are reordered from the model's order (tip first) to the file's (base first).
#include "verbs.hpp"

#include <Eigen/Cholesky>

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

Json mass_matrix(const Scene& scene, const State& x) {
  // O(N^2) from the composite rigid body inertias (lesson 5).
  Workspace ws(scene.model);
  update_phi(scene.model, x.theta, ws);
  std::vector<SpatialInertia> R(scene.model.n());
  MatX<double> M;
  mass_matrix_crb(scene.model, x, ws, R, M);
  const std::vector<int> idx = file_v_index(scene);
  const int n = int(idx.size());
  MatX<double> M_file(n, n);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) M_file(r, c) = M(idx[r], idx[c]);
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
  return out;
}

}  // namespace soa::cli
