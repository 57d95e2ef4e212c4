/// \file
/// Scene files (lessons 3-4): the default scenes load into the chains they describe and
/// their inverse dynamics runs; what the format's parts mean (docs/scenes.md), checked on
/// random chains written as scene files by the test's own writer (scene_support.hpp).
///
/// Suites: scene_defaults (the three default scenes), scene_format (the meaning of the
/// format), scene_scale (large, deep and extreme inputs, generated). Tolerances are in units of the machine epsilon: a scene file carries the centre
/// of mass and the inertia about it, and the placement as a quaternion, so the model read
/// back differs from the one written by a few roundings of each conversion.
#include <Eigen/Cholesky>
#include <cstdio>
#include <set>

#include "scene_support.hpp"

namespace soa::test {
namespace {

using nlohmann::json;

/// T from the recursion against the operator form \f$T = H\phi(M\alpha + b)\f$ and against
/// \f$T = \mathcal{M}\dot\beta + \mathcal{C}\f$ (lesson 4), relative to \f$\max(1, |T|)\f$.
double operator_residual(const Scene& s, const VecX<double>& T) {
  const Operators op = Operators::build(s.model, s.state, s.f_ext);
  const VecX<double> T_op = op.T(s.beta_dot);
  const VecX<double> T_mc = op.mass_matrix() * s.beta_dot + op.bias();
  return std::max(rel(T, T_op), rel(T, T_mc));
}

/// The checks every default scene passes: a model, a state of the model's sizes, inverse
/// dynamics that runs and gives finite, non-zero torques equal to the operator form.
void check_default(const Scene& s, int n, int nv, const Vec3<double>& g) {
  EXPECT_EQ(s.model.n(), n);
  EXPECT_EQ(s.model.nv(), nv);
  EXPECT_EQ(s.model.gravity, g);
  EXPECT_EQ(s.state.theta.size(), s.model.nq());
  EXPECT_EQ(s.state.beta.size(), nv);
  EXPECT_EQ(s.beta_dot.size(), nv);
  EXPECT_FALSE(s.state.beta.isZero(0)) << "the default scenes move";
  EXPECT_FALSE(s.beta_dot.isZero(0)) << "the default scenes accelerate";
  const VecX<double> T = scene_torques(s);
  ASSERT_TRUE(T.allFinite());
  EXPECT_GT(T.cwiseAbs().minCoeff(), 0.0) << "every hinge has a non-trivial force";
  Worst worst(s.name + " T vs operators");
  worst.add(operator_residual(s, T), 0);
  EXPECT_LE(worst.value(), 64 * nv * eps<double>());
  // file_order is the file's bodies (base first) as course numbers: n, n-1, ..., 1.
  ASSERT_EQ(int(s.file_order.size()), n);
  for (int i = 0; i < n; ++i) EXPECT_EQ(s.file_order[i], n - i);
}

TEST(scene_defaults, DoublePendulum) {
  const Scene s = load_scene(default_scene("double_pendulum.json"));
  check_default(s, 2, 2, Vec3<double>(0, 0, -9.81));
  EXPECT_EQ(s.title, "double pendulum");
  EXPECT_EQ(s.model.body(2).name, "upper");
  EXPECT_EQ(s.model.body(1).name, "lower");
  for (int k = 1; k <= 2; ++k) EXPECT_EQ(s.model.body(k).hinge.type, HingeType::Revolute);
  EXPECT_TRUE(s.f_ext.empty());
}

TEST(scene_defaults, Arm7) {
  const Scene s = load_scene(default_scene("arm7.json"));
  check_default(s, 7, 7, Vec3<double>(0, 0, -9.81));
  // The gripper is on a locked hinge: merged into link7 (body 1), its frame rides on it.
  ASSERT_EQ(s.frames.size(), 8u);
  const Scene::Frame& gripper = s.frames.back();
  EXPECT_EQ(gripper.name, "gripper");
  EXPECT_TRUE(gripper.locked);
  EXPECT_EQ(gripper.k, 1);
  EXPECT_EQ(s.model.find("gripper"), 1);
  EXPECT_EQ(s.model.body(1).name, "link7");
  EXPECT_DOUBLE_EQ(s.model.body(1).M.mass(), 0.3 + 0.9);
  // The axes alternate z, y, z, y, ... from the base.
  for (int i = 0; i < 7; ++i)
    EXPECT_EQ(s.model.body(s.file_order[i]).hinge.axis,
              i % 2 == 0 ? Vec3<double>::UnitZ() : Vec3<double>::UnitY());
}

TEST(scene_defaults, Chain50) {
  const Scene s = load_scene(default_scene("chain50.json"));
  check_default(s, 50, 50, Vec3<double>(0, 0, -9.81));
  for (int k = 1; k <= 50; ++k) EXPECT_EQ(s.model.body(k).hinge.type, HingeType::Revolute);
}

// Gravity [0, 0, 0] and an explicit zero external force on every body (the locked gripper
// included) give exactly the torques of the same scene without those parts: the skipped
// passes cost nothing and change nothing.
TEST(scene_defaults, ZeroGravityAndZeroForcesAreNoGravityAndNoForces) {
  json without = json::parse(read_text(default_scene("arm7.json")));
  without.erase("gravity");
  without.erase("external_forces");
  json with = without;
  with["gravity"] = {0, 0, 0};
  with["external_forces"] = json::array();
  for (const json& b : with["bodies"])
    with["external_forces"].push_back(
        {{"body", b["name"]}, {"moment", {0, 0, 0}}, {"force", {0.0, 0.0, 0.0}}});
  const Scene a = parse_scene(without.dump(), "without.json");
  const Scene b = parse_scene(with.dump(), "with.json");
  EXPECT_FALSE(a.model.has_gravity());
  EXPECT_FALSE(b.model.has_gravity());
  EXPECT_TRUE(a.f_ext.empty());
  EXPECT_EQ(int(b.f_ext.size()), b.model.n());
  const VecX<double> Ta = scene_torques(a), Tb = scene_torques(b);
  EXPECT_TRUE(Ta == Tb) << "without: " << Ta.transpose() << "\nwith:    " << Tb.transpose();
  // ... and the parts do matter when they are not zero.
  with["gravity"] = {0, 0, -9.81};
  EXPECT_FALSE(scene_torques(parse_scene(with.dump(), "g.json")) == Ta);
}

// tests/scenes/every_hinge.json: one hinge of each type, springs, a locked tool, external
// forces on it and on a free body. Its torques are the operator form's less the springs'.
TEST(scene_format, EveryHingeType) {
  const Scene s = load_scene(std::string(SOA_SOURCE_DIR) + "/tests/scenes/every_hinge.json");
  EXPECT_EQ(s.model.n(), 5);  // the tool is merged into the ball
  EXPECT_EQ(s.model.nq(), 1 + 1 + 2 + 4 + 7);
  EXPECT_EQ(s.model.nv(), 1 + 1 + 2 + 3 + 6);
  EXPECT_EQ(s.frames.size(), 6u);
  EXPECT_TRUE(s.model.has_springs());
  EXPECT_EQ(s.model.body(s.model.find("carriage")).rest[0], 0.1);
  EXPECT_EQ(int(s.f_ext.size()), s.model.n());
  const VecX<double> T = scene_torques(s);
  VecX<double> tau = VecX<double>::Zero(s.model.nv());
  for (int k = 1; k <= s.model.n(); ++k) {
    const Body& B = s.model.body(k);
    add_spring_force(B, s.state.theta.data() + B.q_offset, s.state.beta.data() + B.v_offset,
                     tau.data() + B.v_offset);
  }
  EXPECT_FALSE(tau.isZero(0));
  const Operators op = Operators::build(s.model, s.state, s.f_ext);
  Worst worst("every_hinge T vs operators");
  worst.add(rel(T, op.T(s.beta_dot) - tau), 0);
  EXPECT_LE(worst.value(), 64 * s.model.nv() * eps<double>());
}

// A scene with only what is required: the defaults of docs/scenes.md.
TEST(scene_format, DefaultsWhenAbsent) {
  const Scene s = parse_scene(R"({"bodies": [{"name": "a", "parent": "base", "mass": 2,
      "com": [0, 0, 0], "inertia": {"Ixx": 1, "Iyy": 1, "Izz": 1},
      "hinge": {"type": "spherical"}}]})",
                              "dir/minimal.json");
  EXPECT_EQ(s.name, "dir/minimal.json");
  EXPECT_EQ(s.title, "minimal");
  EXPECT_FALSE(s.model.has_gravity());
  EXPECT_TRUE(s.f_ext.empty());
  EXPECT_TRUE(s.compute.empty());
  EXPECT_EQ(s.state.theta, s.model.neutral());
  EXPECT_TRUE(s.state.beta.isZero(0));
  EXPECT_TRUE(s.beta_dot.isZero(0));
  EXPECT_EQ(s.model.body(1).placement.R(), Mat3<double>::Identity());
  EXPECT_EQ(s.model.body(1).placement.l(), Vec3<double>::Zero());
  EXPECT_EQ(s.model.body(1).stiffness, 0.0);
}

// A body with no mass, com and inertia is a frame: locked, it adds nothing to its carrier;
// on a hinge, its hinge moves the mass outboard. Limits and friction are kept, not used.
TEST(scene_format, MasslessBodiesLimitsAndFriction) {
  const std::string head = R"({"bodies": [
      {"name": "a", "parent": "base", "hinge": {"type": "revolute", "axis": [0, 0, 1]},
       "limits": {"lower": -1, "upper": 2, "effort": 30, "velocity": 4}, "friction": 0.5},
      {"name": "b", "parent": "a", "mass": 2, "com": [0.3, 0, 0],
       "inertia": {"Ixx": 1, "Iyy": 1, "Izz": 1},
       "hinge": {"type": "revolute", "axis": [0, 1, 0], "placement": {"position": [0, 0, 1]}}})";
  const Scene s = parse_scene(head + R"(,
      {"name": "tool", "parent": "b", "hinge": {"type": "locked",
       "placement": {"position": [0, 0, 0.2]}}}]})",
                              "massless.json");
  const Scene t = parse_scene(head + "]}", "plain.json");
  ASSERT_EQ(s.model.n(), 2);
  EXPECT_EQ(s.model.body(2).M.mass(), 0.0);
  for (int k = 1; k <= 2; ++k) EXPECT_EQ(s.model.body(k).M.matrix(), t.model.body(k).M.matrix());
  ASSERT_EQ(s.frames.size(), 3u);
  EXPECT_TRUE(s.frames[2].locked);
  EXPECT_EQ(s.frames[2].own_com(), Vec3<double>::Zero());
  EXPECT_EQ(s.frames[2].offset().l(), Vec3<double>(0, 0, 0.2));
  const HingeLimits* l = s.frames[0].limits();
  ASSERT_TRUE(l);
  EXPECT_EQ(l->lower, -1);
  EXPECT_EQ(l->upper, 2);
  EXPECT_EQ(l->effort, 30);
  EXPECT_EQ(l->velocity, 4);
  EXPECT_EQ(l->friction, 0.5);
  EXPECT_FALSE(s.frames[1].limits());
  // The dynamics do not use them: the same hinge forces with and without.
  State x = State::rest(s.model);
  x.theta << 0.4, 0.7;  // tip first
  x.beta << 1.0, -2.0;
  Workspace ws(s.model);
  VecX<double> T(2), U(2);
  const VecX<double> qdd = VecX<double>::Constant(2, 0.5);
  inverse_dynamics(s.model, x, qdd, {}, ws, T);
  inverse_dynamics(t.model, x, qdd, {}, ws, U);
  EXPECT_EQ(T, U);
  const Operators op = Operators::build(s.model, x, {});
  EXPECT_EQ(op.mass_matrix().llt().info(), Eigen::Success);
}

// The example of docs/scenes.md (its first code block) is a valid scene, comments and all.
TEST(scene_format, DocumentedExampleLoads) {
  const std::string page = read_text(std::string(SOA_SOURCE_DIR) + "/docs/scenes.md");
  const std::size_t open = page.find("\n```");
  ASSERT_NE(open, std::string::npos);
  const std::size_t start = page.find('\n', open + 1);
  const std::size_t end = page.find("\n```", start);
  ASSERT_NE(end, std::string::npos);
  const Scene s = parse_scene(page.substr(start, end - start), "scenes.md example");
  EXPECT_GT(s.model.n(), 0);
  EXPECT_TRUE(scene_torques(s).allFinite());
}

// The inertia as an object {Ixx, ..., Iyz} is the symmetric matrix with those entries.
TEST(scene_format, InertiaObjectIsTheMatrix) {
  Random<double> rnd;
  Worst worst("object vs matrix inertia");
  for (int i = 0; i < kCases; ++i) {
    const SpatialInertia M = rnd.inertia();
    Body b;
    b.name = "a";
    b.M = M;
    json doc = chain_json({b});
    const Mat3<double> J = M.J_cm();
    const Scene by_matrix = parse_scene(doc.dump(), "m.json");
    doc["bodies"][0]["inertia"] = {{"Ixx", J(0, 0)}, {"Iyy", J(1, 1)}, {"Izz", J(2, 2)},
                                   {"Ixy", J(0, 1)}, {"Ixz", J(0, 2)}, {"Iyz", J(1, 2)}};
    const Scene by_object = parse_scene(doc.dump(), "o.json");
    worst.add(rel(by_matrix.model.body(1).M.matrix(), by_object.model.body(1).M.matrix()), i);
    worst.add(rel(by_object.model.body(1).M.matrix(), M.matrix()), i);
  }
  EXPECT_LE(worst.value(), 64 * eps<double>());
}

/// Writes the state \p x, \p beta_dot (model order) and external forces \p f (one per model
/// body) of the scene \p s read from \p doc into \p doc, in file order.
void write_state(json& doc, const Scene& s, const State& x, const VecX<double>& beta_dot,
                 const ExternalForces<double>& f) {
  doc["external_forces"] = json::array();
  for (std::size_t i = 0; i < s.frames.size(); ++i) {
    const Scene::Frame& fr = s.frames[i];
    if (fr.locked) continue;
    const Body& B = s.model.body(fr.k);
    json& jb = doc["bodies"][i];
    jb["q"] = json::array();
    jb["qd"] = json::array();
    jb["qdd"] = json::array();
    for (int j = 0; j < B.hinge.nq(); ++j) jb["q"].push_back(x.theta[B.q_offset + j]);
    for (int j = 0; j < B.hinge.nv(); ++j) {
      jb["qd"].push_back(x.beta[B.v_offset + j]);
      jb["qdd"].push_back(beta_dot[B.v_offset + j]);
    }
    if (!f.empty())
      doc["external_forces"].push_back({{"body", fr.name},
                                        {"moment", to_json(f[fr.k - 1].angular())},
                                        {"force", to_json(f[fr.k - 1].linear())}});
  }
}

// Random chains of every hinge type (locked ones merged), with springs and gravity in half
// the cases, written as scene files and read back: the same model, state and torques.
TEST(scene_format, RandomChainsRoundTrip) {
  Random<double> rnd;
  Worst worst_model("model read back"), worst_state("state read back"),
      worst_T("torques of the scene vs the model");
  for (int c = 0; c < kCases; ++c) {
    ChainOptions opt;
    opt.gravity = opt.springs = c % 2 == 1;
    const int n = 1 + c % 9;
    std::vector<Body> bodies;
    for (int i = 0; i < n; ++i)
      bodies.push_back(detail::random_body(rnd, i, HingeType((i + c) % 7), opt));
    const Model m = detail::finish_chain(bodies, opt);
    const State x = random_state(rnd, m);
    const VecX<double> qdd = random_vector(rnd, m.nv());
    const ExternalForces<double> f = random_forces(rnd, m);

    json doc = chain_json(bodies);
    if (opt.gravity) doc["gravity"] = to_json(m.gravity);
    write_state(doc, parse_scene(doc.dump(), "shape.json"), x, qdd, f);
    const Scene s = parse_scene(doc.dump(), "random.json");

    ASSERT_EQ(s.model.n(), m.n()) << "case " << c;
    ASSERT_EQ(s.model.nq(), m.nq());
    ASSERT_EQ(s.model.nv(), m.nv());
    EXPECT_EQ(s.model.gravity, m.gravity);
    for (int k = 1; k <= m.n(); ++k) {
      const Body &A = s.model.body(k), &B = m.body(k);
      ASSERT_EQ(A.name, B.name);
      ASSERT_EQ(A.hinge.type, B.hinge.type);
      ASSERT_EQ(A.q_offset, B.q_offset);
      ASSERT_EQ(A.stiffness, B.stiffness);
      ASSERT_EQ(A.damping, B.damping);
      double r = rel(A.M.matrix(), B.M.matrix()) + rel(A.placement.matrix(), B.placement.matrix());
      if (B.hinge.nv() == 1 || B.hinge.type == HingeType::Universal)
        r += rel(A.hinge.axis, B.hinge.axis);
      if (B.hinge.type == HingeType::Universal) r += rel(A.hinge.axis2, B.hinge.axis2);
      if (B.hinge.type == HingeType::Helical) r += std::abs(A.hinge.pitch - B.hinge.pitch);
      worst_model.add(r, c);
    }
    // File order: the i-th kept body of the file is s.file_order[i]; the index maps put the
    // file's values where the model keeps them.
    std::vector<std::string> kept;
    for (const Body& b : bodies)
      if (b.hinge.type != HingeType::Locked) kept.push_back(b.name);
    ASSERT_EQ(s.file_order.size(), kept.size());
    for (std::size_t i = 0; i < kept.size(); ++i)
      EXPECT_EQ(s.model.body(s.file_order[i]).name, kept[i]);
    const std::vector<int> qi = file_q_index(s), vi = file_v_index(s);
    EXPECT_EQ(std::set<int>(qi.begin(), qi.end()).size(), std::size_t(m.nq()));
    EXPECT_EQ(std::set<int>(vi.begin(), vi.end()).size(), std::size_t(m.nv()));
    std::vector<double> q_file, v_file;
    for (int i : qi) q_file.push_back(x.theta[i]);
    for (int i : vi) v_file.push_back(x.beta[i]);
    EXPECT_EQ(theta_from_file_order(s, q_file), s.state.theta);
    EXPECT_EQ(beta_from_file_order(s, v_file), x.beta);

    worst_state.add(rel(s.state.theta, x.theta), c);
    EXPECT_EQ(s.state.beta, x.beta);
    EXPECT_EQ(s.beta_dot, qdd);

    Workspace ws(m);
    VecX<double> T(m.nv());
    inverse_dynamics(m, x, qdd, f, ws, T);
    worst_T.add(rel(scene_torques(s), T), c);
  }
  EXPECT_LE(worst_model.value(), 64 * eps<double>());
  EXPECT_LE(worst_state.value(), 4 * eps<double>());
  EXPECT_LE(worst_T.value(), 1024 * eps<double>());
}

// A body on a locked hinge is the same as the body on a revolute hinge held at zero
// (q = qd = qdd = 0): the same torques at every other hinge, the same pose of its frame,
// with an external force on it, for random chains.
TEST(scene_format, LockedBodyRidesOnItsParent) {
  Random<double> rnd;
  Worst worst_T("torques, locked vs held"), worst_pose("pose of the locked frame");
  for (int c = 0; c < kCases; ++c) {
    const int n = 2 + c % 7;
    const int j = 1 + c % (n - 1);  // the body to lock (not next to the base)
    std::vector<Body> bodies;
    for (int i = 0; i < n; ++i)
      bodies.push_back(detail::random_body(rnd, i, HingeType((i + c) % 6), ChainOptions{}));
    bodies[j].hinge.type = HingeType::Revolute;
    json held = chain_json(bodies);
    held["gravity"] = {0, 0, -9.81};
    const Scene shape = parse_scene(held.dump(), "held.json");
    State x = random_state(rnd, shape.model);
    VecX<double> qdd = random_vector(rnd, shape.model.nv());
    const Body& J = shape.model.body(shape.frames[j].k);
    x.theta[J.q_offset] = x.beta[J.v_offset] = qdd[J.v_offset] = 0;
    write_state(held, shape, x, qdd, random_forces(rnd, shape.model));
    json locked = held;
    locked["bodies"][j]["hinge"] = {{"type", "locked"},
                                    {"placement", held["bodies"][j]["hinge"]["placement"]}};
    for (const char* key : {"q", "qd", "qdd"}) locked["bodies"][j].erase(key);
    const Scene a = parse_scene(held.dump(), "held.json");
    const Scene b = parse_scene(locked.dump(), "locked.json");
    ASSERT_EQ(b.model.n(), n - 1);
    ASSERT_TRUE(b.frames[j].locked);
    ASSERT_EQ(b.frames[j].k, b.frames[j - 1].k);

    // Torques in file order, the held hinge's left out.
    const VecX<double> Ta = scene_torques(a), Tb = scene_torques(b);
    const std::vector<int> va = file_v_index(a), vb = file_v_index(b);
    VecX<double> Ta_file(vb.size()), Tb_file(vb.size());
    for (std::size_t i = 0, r = 0; i < va.size(); ++i)
      if (va[i] != J.v_offset) Ta_file[r++] = Ta[va[i]];
    for (std::size_t i = 0; i < vb.size(); ++i) Tb_file[i] = Tb[vb[i]];
    worst_T.add(rel(Ta_file, Tb_file), c);

    Workspace wa(a.model), wb(b.model);
    update_phi(a.model, a.state.theta, wa);
    update_poses(a.model, wa);
    update_phi(b.model, b.state.theta, wb);
    update_poses(b.model, wb);
    const Pose pa = wa.pose[a.frames[j].k - 1];
    const Pose pb = wb.pose[b.frames[j].k - 1] * b.frames[j].offset();
    worst_pose.add(rel(pa.matrix(), pb.matrix()), c);
  }
  EXPECT_LE(worst_T.value(), 1024 * eps<double>());
  EXPECT_LE(worst_pose.value(), 256 * eps<double>());
}

/// A scene of one body on \p hinge (a JSON object) with inertia \p inertia.
std::string one_body(const std::string& hinge,
                     const std::string& inertia = R"({"Ixx": 1, "Iyy": 1, "Izz": 1})") {
  return R"({"bodies": [{"name": "a", "parent": "base", "mass": 1, "com": [0, 0, 0], "inertia": )" +
         inertia + R"(, "hinge": )" + hinge + "}]}";
}

// A huge axis is a direction: normalized without overflow in its norm (which made it zero).
TEST(scene_scale, HugeAxesAreDirections) {
  Scene s = parse_scene(one_body(R"({"type": "revolute", "axis": [2e154, 0, 0]})"), "h.json");
  EXPECT_EQ(s.model.body(1).hinge.axis, Vec3<double>(1, 0, 0));
  s = parse_scene(
      one_body(R"({"type": "universal", "axis": [0, 0, 1.7e308], "axis2": [0, -1e300, 0]})"),
      "h.json");
  EXPECT_EQ(s.model.body(1).hinge.axis, Vec3<double>(0, 0, 1));
  EXPECT_EQ(s.model.body(1).hinge.axis2, Vec3<double>(0, -1, 0));
  s = parse_scene(one_body(R"({"type": "prismatic", "axis": [1.7e308, 1.7e308, 1.7e308]})"),
                  "h.json");
  EXPECT_LE((s.model.body(1).hinge.axis - Vec3<double>::Constant(1 / std::sqrt(3.0))).norm(),
            4 * eps<double>());
  // Ordinary axes are normalized as before, to the last bit.
  const Vec3<double> a(0.3, -0.4, 1.2);
  s = parse_scene(one_body(R"({"type": "revolute", "axis": [0.3, -0.4, 1.2]})"), "h.json");
  EXPECT_EQ(s.model.body(1).hinge.axis, a.normalized());
}

// An inertia with entries near 1e308 is read (0.5 J + 0.5 J*, and its principal moments, do
// not overflow; J + J* did, and the moments read as -nan).
TEST(scene_scale, HugeInertiaIsRead) {
  const Scene s = parse_scene(one_body(R"({"type": "revolute", "axis": [0, 0, 1]})",
                                       R"({"Ixx": 1e308, "Iyy": 1e308, "Izz": 1e308})"),
                              "big.json");
  EXPECT_EQ(s.model.body(1).M.J(), Mat3<double>(Vec3<double>::Constant(1e308).asDiagonal()));
}

// 10^5 bodies read in O(n) (a DOM parser with a callback that re-scans the bodies array after
// every body is O(n^2); make bench measures the time), and a field given twice in the last
// one is still found.
TEST(scene_scale, LargeSceneIsReadWhole) {
  const std::size_t n = 100000;
  const Scene s = parse_scene(revolute_chain_text(n), "large.json");
  ASSERT_EQ(s.model.n(), int(n));
  EXPECT_EQ(s.frames.size(), n);
  EXPECT_EQ(s.frames.back().name, "b99999");
  EXPECT_EQ(s.model.body(1).name, "b99999");
  EXPECT_TRUE(s.state.theta.isConstant(0.1));
  EXPECT_EQ(error_of([&] { parse_scene(revolute_chain_text(n, R"(, "mass": 2)"), "dup.json"); }),
            "dup.json: bodies[99999]: field \"mass\" given twice");
  // Its time is measured by make bench (tests/bench/scale/cli_scale.cpp), not here.
}

// Nesting 10^6 levels deep is refused at once, at kMaxSceneDepth, with a shortened path;
// 97 levels below the body (100 in all) are still read.
TEST(scene_scale, DeepNestingIsRefused) {
  const std::string deep(1000000, '['), end(1000000, ']');
  const std::string body = R"({"bodies": [{"name": "a", "parent": "base", "mass": 1, "com": )";
  EXPECT_EQ(error_of([&] { parse_scene(body + deep + end + "}]}", "deep.json"); }),
            "deep.json: bodies[0].com[0] ... (92 levels) ... [0][0][0][0]: nested more than 100 "
            "levels deep");
  EXPECT_EQ(error_of([&] {
              parse_scene(body + deep.substr(0, 97) + end.substr(0, 97) + "}]}", "deep.json");
            }),
            "deep.json: bodies[0].com: expected 3 numbers, got 1");
  EXPECT_EQ(error_of([&] { parse_scene(R"({"bodies": )" + deep + end + "}", "deep.json"); }),
            "deep.json: bodies[0]: expected an object, got an array");
  EXPECT_EQ(error_of([&] { parse_scene(deep + end, "deep.json"); }),
            "deep.json: top level: expected an object, got an array");
  std::string objects;
  for (int i = 0; i < 1000000; ++i) objects += R"({"x": )";
  EXPECT_EQ(error_of([&] { parse_scene(R"({"gravity": )" + objects, "deep.json"); }),
            "deep.json: gravity.x.x.x ... (92 levels) ... x.x.x.x: nested more than 100 levels "
            "deep");
}

// Errors found while parsing, deep down: the path shows its first and last levels.
TEST(scene_scale, DeepPathsAreShortened) {
  std::string open, close;
  for (int i = 0; i < 60; ++i) open += "[0, ", close += "]";
  EXPECT_EQ(
      error_of([&] { parse_scene(R"({"gravity": )" + open + "1e999" + close + "}", "p.json"); }),
      "p.json: gravity[1][1][1] ... (53 levels) ... [1][1][1][1]: not a finite number "
      "(1e999 is out of the range of a double)");
  EXPECT_EQ(error_of([&] {
              parse_scene(R"({"gravity": )" + open + R"({"a": 1, "a": 2})" + close + "}", "p.json");
            }),
            "p.json: gravity[1][1][1] ... (53 levels) ... [1][1][1][1]: field \"a\" given twice");
}

// A loop through many bodies is named by its ends.
TEST(scene_scale, LongLoopIsShortened) {
  json doc = chain_json({});
  for (int i = 0; i < 1000; ++i) {
    Body b;
    b.name = "b" + std::to_string(i);
    b.M = SpatialInertia::from_cm(1, Vec3<double>::Zero(), Mat3<double>::Identity());
    doc["bodies"].push_back(body_json(b, "b" + std::to_string(i == 0 ? 999 : i - 1)));
  }
  EXPECT_EQ(error_of([&] { parse_scene(doc.dump(), "loop.json"); }),
            "loop.json: bodies[0].parent: loop (b0 -> b999 -> b998 -> b997 -> ... (994 bodies) "
            "... -> b2 -> b1 -> b0, following parents) never reaches \"base\"");
}

}  // namespace
}  // namespace soa::test
