// The chain in MuJoCo (Debian libmujoco-dev): an MJCF model written from a soa::Model of
// revolute hinges, loaded from memory (MuJoCo's virtual file system), and the three calls the
// comparison times, on MuJoCo's coordinates (base first, the order of the nested bodies).
//
// Each body: pos and quat of its placement, one hinge at its origin about our axis, an
// `inertial` with mass, centre of mass and the inertia about it (diaginertia when diagonal,
// fullinertia otherwise). No geoms, no damping, no armature; contacts, constraints and passive
// forces disabled. Debian's tinyxml2 (9.0) refuses elements nested deeper than 100, and the
// MJCF kinematic tree is its nesting: the chain is written in files of kBodiesPerFile nested
// bodies, each including the next one inside its innermost body (MuJoCo expands includes
// after parsing each file, so the depth limit applies per file).
#pragma once

#include <mujoco/mujoco.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "soa/chain.hpp"

namespace soa::compare {

inline std::string mj_num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

inline std::string mj_vec(const Vec3<double>& v) {
  return mj_num(v.x()) + " " + mj_num(v.y()) + " " + mj_num(v.z());
}

/// The MJCF files of \p m (main file first), each with at most \p per_file nested bodies.
inline std::vector<std::string> mjcf_files(const Model& m, const Vec3<double>& g, int per_file) {
  const int n = m.n();
  std::vector<std::string> files;
  for (int lo = 0; lo < n; lo += per_file) {
    const int hi = std::min(n, lo + per_file);
    std::string s = "<mujoco model=\"soa_chain\">\n";
    if (lo == 0) {
      s += "<compiler angle=\"radian\" inertiafromgeom=\"false\"/>\n";
      s += "<option gravity=\"" + mj_vec(g) + "\">\n";
      s += "  <flag contact=\"disable\" constraint=\"disable\" passive=\"disable\"/>\n";
      s += "</option>\n<worldbody>\n";
    }
    for (int i = lo; i < hi; ++i) {  // base first: our body k = n - i
      const Body& B = m.body(n - i);
      if (B.hinge.type != HingeType::Revolute)
        throw std::runtime_error("MJCF: body '" + B.name + "' is not revolute");
      s += "<body name=\"" + B.name + "\" pos=\"" + mj_vec(B.placement.l()) + "\"";
      if (B.placement.R() != Mat3<double>::Identity()) {
        const Eigen::Quaterniond qt(B.placement.R());
        s += " quat=\"" + mj_num(qt.w()) + " " + mj_vec(qt.vec()) + "\"";
      }
      s += ">\n  <joint name=\"" + B.name + "\" type=\"hinge\" pos=\"0 0 0\" axis=\"" +
           mj_vec(B.hinge.axis) + "\"/>\n";
      const Mat3<double> J = B.M.J_cm();
      s += "  <inertial pos=\"" + mj_vec(B.M.p()) + "\" mass=\"" + mj_num(B.M.mass()) + "\" ";
      if (J(0, 1) == 0 && J(0, 2) == 0 && J(1, 2) == 0)
        s += "diaginertia=\"" + mj_vec(J.diagonal()) + "\"/>\n";
      else
        s += "fullinertia=\"" + mj_vec(J.diagonal()) + " " + mj_num(J(0, 1)) + " " +
             mj_num(J(0, 2)) + " " + mj_num(J(1, 2)) + "\"/>\n";
    }
    if (hi < n) s += "<include file=\"chain" + std::to_string(files.size() + 1) + ".xml\"/>\n";
    for (int i = lo; i < hi; ++i) s += "</body>";
    s += lo == 0 ? "\n</worldbody>\n</mujoco>\n" : "\n</mujoco>\n";
    files.push_back(s);
  }
  return files;
}

/// MuJoCo's errors end the program with one line (its default handler would too, after
/// writing MUJOCO_LOG.TXT in the working directory); warnings go to stderr.
inline void mujoco_handlers() {
  mju_user_error = [](const char* msg) {
    std::fprintf(stderr, "compare: MuJoCo error: %s\n", msg);
    std::exit(1);
  };
  mju_user_warning = [](const char* msg) {
    std::fprintf(stderr, "compare: MuJoCo warning: %s\n", msg);
  };
}

/// \p m loaded into MuJoCo from memory.
inline mjModel* mujoco_model(const Model& m, const Vec3<double>& g) {
  constexpr int kBodiesPerFile = 40;
  const std::vector<std::string> files = mjcf_files(m, g, kBodiesPerFile);
  auto vfs = std::make_unique<mjVFS>();  // ~ 2 MB of names: not on the stack
  mj_defaultVFS(vfs.get());
  for (std::size_t f = 0; f < files.size(); ++f) {
    const std::string name = "chain" + std::to_string(f) + ".xml";
    if (mj_makeEmptyFileVFS(vfs.get(), name.c_str(), int(files[f].size())) != 0)
      throw std::runtime_error("MuJoCo: the virtual file system is full (" +
                               std::to_string(files.size()) + " files)");
    std::memcpy(vfs->filedata[vfs->nfile - 1], files[f].data(), files[f].size());
  }
  char error[1000] = "";
  mjModel* model = mj_loadXML("chain0.xml", vfs.get(), error, sizeof error);
  mj_deleteVFS(vfs.get());
  if (!model) {
    std::string e = error;
    for (char& c : e)
      if (c == '\n') c = ' ';
    throw std::runtime_error("MuJoCo could not load the chain's MJCF: " + e);
  }
  return model;
}

/// MuJoCo's calls on one chain and state (base-first coordinates): the minimal pipelines the
/// comparison times on `d`, and mj_inverse / mj_forward on a second mjData `full` as a check
/// that those pipelines are what MuJoCo's own entry points compute.
struct MujocoPeer {
  mjModel* m;
  mjData* d;
  mjData* full;
  int n;
  std::vector<double> tau, M, qacc, rhs, T;

  MujocoPeer(const Model& model, const Vec3<double>& g)
      : m(mujoco_model(model, g)),
        d(mj_makeData(m)),
        full(mj_makeData(m)),
        n(m->nv),
        tau(n),
        M(std::size_t(n) * n),
        qacc(n),
        rhs(n),
        T(n) {
    if (n != model.nv()) throw std::runtime_error("MuJoCo: the chain has the wrong nv");
  }
  ~MujocoPeer() {
    mj_deleteData(full);
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  MujocoPeer(const MujocoPeer&) = delete;
  MujocoPeer& operator=(const MujocoPeer&) = delete;

  /// Sets qpos, qvel and the inverse dynamics' qacc in both mjData.
  void set_state(const std::vector<double>& q, const std::vector<double>& qd,
                 const std::vector<double>& qdd) {
    for (mjData* x : {d, full}) {
      std::copy(q.begin(), q.end(), x->qpos);
      std::copy(qd.begin(), qd.end(), x->qvel);
      std::copy(qdd.begin(), qdd.end(), x->qacc);
    }
  }

  /// Inverse dynamics M qacc + C (gravity included): positions, com frame, velocities, RNE.
  void inverse() {
    mj_kinematics(m, d);
    mj_comPos(m, d);
    mj_comVel(m, d);
    mj_rne(m, d, 1, tau.data());
  }
  /// The mass matrix: positions, com frame, composite rigid bodies (sparse qM), then dense.
  void mass() {
    mj_kinematics(m, d);
    mj_comPos(m, d);
    mj_crb(m, d);
    mj_fullM(m, M.data(), d->qM);
  }
  /// Forward dynamics as mj_forward does it without constraints: M by mj_crb, its sparse
  /// L'DL factorization, the bias C by mj_rne without acceleration, qacc = M^-1 (T - C).
  void forward() {
    mj_kinematics(m, d);
    mj_comPos(m, d);
    mj_comVel(m, d);
    mj_crb(m, d);
    mj_factorM(m, d);
    mj_rne(m, d, 0, d->qfrc_bias);
    for (int i = 0; i < n; ++i) rhs[i] = T[i] - d->qfrc_bias[i];
    mj_solveM(m, d, qacc.data(), rhs.data(), 1);
  }

  /// MuJoCo's own entry points: mj_inverse's qfrc_inverse, mj_forward's qacc (T applied).
  std::vector<double> full_inverse() {
    mj_inverse(m, full);
    return std::vector<double>(full->qfrc_inverse, full->qfrc_inverse + n);
  }
  std::vector<double> full_forward() {
    std::vector<double> keep(full->qacc, full->qacc + n);
    std::copy(T.begin(), T.end(), full->qfrc_applied);
    mj_forward(m, full);
    std::vector<double> out(full->qacc, full->qacc + n);
    std::copy(keep.begin(), keep.end(), full->qacc);
    return out;
  }
};

}  // namespace soa::compare
