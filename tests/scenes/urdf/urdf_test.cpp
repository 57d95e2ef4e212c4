/// \file
/// URDF scenes (docs/scenes.md "URDF input"): each case of the mapping onto the course's chain,
/// checked on small robots written by the test (random numbers from a fixed seed where a case
/// has numbers), each error with its message (the files of tests/scenes/urdf/bad/), urdfdom
/// silent, `soa convert`'s JSON giving the same model bit for bit, and the default scenes' URDF
/// and JSON files agreeing. Suite urdf.
#include <fcntl.h>
#include <unistd.h>

#include <Eigen/Cholesky>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "../scene_support.hpp"

namespace soa::test {
namespace {

namespace fs = std::filesystem;

/// A fresh folder for this test's files.
std::string temp_dir() {
  const testing::TestInfo* t = testing::UnitTest::GetInstance()->current_test_info();
  const fs::path d = fs::path(testing::TempDir()) / (std::string("urdf_") + t->name());
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}
std::string write(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::string num(double x) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", x);
  return b;
}
std::string triple(const Vec3<double>& v) {
  return num(v[0]) + " " + num(v[1]) + " " + num(v[2]);
}

/// The parts of a URDF, as text.
std::string robot(const std::string& body) {
  return "<?xml version=\"1.0\"?>\n<robot name=\"test\">\n" + body + "</robot>\n";
}
std::string massless(const std::string& name) {
  return "  <link name=\"" + name + "\"/>\n";
}
/// A link with an inertial: mass m, centre xyz, frame rpy, inertia (xx, yy, zz, xy, xz, yz).
std::string link(const std::string& name, double m, const Vec3<double>& xyz = Vec3<double>::Zero(),
                 const Vec3<double>& rpy = Vec3<double>::Zero(),
                 const Eigen::Matrix<double, 6, 1>& I =
                     (Eigen::Matrix<double, 6, 1>() << 0.1, 0.2, 0.25, 0, 0, 0).finished()) {
  return "  <link name=\"" + name + "\">\n    <inertial>\n      <origin xyz=\"" + triple(xyz) +
         "\" rpy=\"" + triple(rpy) + "\"/>\n      <mass value=\"" + num(m) +
         "\"/>\n      <inertia ixx=\"" + num(I[0]) + "\" iyy=\"" + num(I[1]) + "\" izz=\"" +
         num(I[2]) + "\" ixy=\"" + num(I[3]) + "\" ixz=\"" + num(I[4]) + "\" iyz=\"" + num(I[5]) +
         "\"/>\n    </inertial>\n  </link>\n";
}
/// A joint; \p extra is put inside it (<axis>, <limit>, <dynamics>, ...).
std::string joint(const std::string& name, const std::string& type, const std::string& parent,
                  const std::string& child, const Vec3<double>& xyz = Vec3<double>::Zero(),
                  const Vec3<double>& rpy = Vec3<double>::Zero(), const std::string& extra = "") {
  const bool limited = type == "revolute" || type == "prismatic";
  return "  <joint name=\"" + name + "\" type=\"" + type + "\">\n    <parent link=\"" + parent +
         "\"/>\n    <child link=\"" + child + "\"/>\n    <origin xyz=\"" + triple(xyz) +
         "\" rpy=\"" + triple(rpy) + "\"/>\n" +
         (limited && extra.find("<limit") == std::string::npos
              ? "    <limit lower=\"-3\" upper=\"3\" effort=\"10\" velocity=\"2\"/>\n"
              : "") +
         extra + "  </joint>\n";
}
std::string axis(const Vec3<double>& a) {
  return "    <axis xyz=\"" + triple(a) + "\"/>\n";
}

/// URDF's rpy: fixed axes x, y, z, R = Rz(yaw) Ry(pitch) Rx(roll) (the test's own).
Mat3<double> rpy_matrix(const Vec3<double>& rpy) {
  using A = Eigen::AngleAxisd;
  return (A(rpy[2], Vec3<double>::UnitZ()) * A(rpy[1], Vec3<double>::UnitY()) *
          A(rpy[0], Vec3<double>::UnitX()))
      .toRotationMatrix();
}

/// A random physical inertia (principal moments obeying the triangle inequality), as entries.
Eigen::Matrix<double, 6, 1> random_inertia(Random<double>& rnd) {
  const double a = rnd.uniform(0.05, 1), b = rnd.uniform(0.05, 1), c = rnd.uniform(0.05, 1);
  const Mat3<double> R = rnd.rotation();
  const Mat3<double> J = R * Vec3<double>(a + b, b + c, a + c).asDiagonal() * R.transpose();
  Eigen::Matrix<double, 6, 1> I;
  I << J(0, 0), J(1, 1), J(2, 2), J(0, 1), J(0, 2), J(1, 2);
  return I;
}
Mat3<double> matrix_of(const Eigen::Matrix<double, 6, 1>& I) {
  Mat3<double> J;
  J << I[0], I[3], I[4], I[3], I[1], I[5], I[4], I[5], I[2];
  return J;
}

/// |A - B| / max(1, |B|) of two spatial inertias' 6x6 matrices.
double inertia_residual(const SpatialInertia& A, const SpatialInertia& B) {
  return (A.matrix() - B.matrix()).norm() / std::max(1.0, B.matrix().norm());
}

/// Two models equal bit for bit: every body's inertia, placement, hinge, spring.
void expect_same_model(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.model.n(), b.model.n());
  EXPECT_EQ(a.model.gravity, b.model.gravity);
  for (int k = 1; k <= a.model.n(); ++k) {
    const Body &A = a.model.body(k), &B = b.model.body(k);
    EXPECT_EQ(A.name, B.name);
    EXPECT_EQ(A.M.mass(), B.M.mass()) << A.name;
    EXPECT_EQ(A.M.h(), B.M.h()) << A.name;
    EXPECT_EQ(A.M.J(), B.M.J()) << A.name;
    EXPECT_EQ(A.placement.R(), B.placement.R()) << A.name;
    EXPECT_EQ(A.placement.l(), B.placement.l()) << A.name;
    EXPECT_EQ(A.hinge.type, B.hinge.type) << A.name;
    EXPECT_EQ(A.hinge.axis, B.hinge.axis) << A.name;
    EXPECT_EQ(A.damping, B.damping) << A.name;
    EXPECT_EQ(A.stiffness, B.stiffness) << A.name;
  }
  ASSERT_EQ(a.frames.size(), b.frames.size());
  for (std::size_t i = 0; i < a.frames.size(); ++i) {
    const Scene::Frame &F = a.frames[i], &G = b.frames[i];
    EXPECT_EQ(F.name, G.name);
    EXPECT_EQ(F.k, G.k);
    EXPECT_EQ(F.locked, G.locked);
    EXPECT_EQ(F.offset().R(), G.offset().R());
    EXPECT_EQ(F.offset().l(), G.offset().l());
    ASSERT_EQ(!F.limits(), !G.limits()) << F.name;
    if (F.limits()) {
      EXPECT_EQ(F.limits()->lower, G.limits()->lower);
      EXPECT_EQ(F.limits()->upper, G.limits()->upper);
      EXPECT_EQ(F.limits()->effort, G.limits()->effort);
      EXPECT_EQ(F.limits()->velocity, G.limits()->velocity);
      EXPECT_EQ(F.limits()->friction, G.limits()->friction);
    }
  }
}

/// load_scene() of the URDF and of the JSON `soa convert` prints, written to a file.
void expect_convert_round_trip(const std::string& urdf, const UrdfOptions& o = {}) {
  const Scene a = load_scene(urdf, o);
  const std::string json = urdf_to_scene_json(urdf, o);
  const std::string path = urdf + ".json";
  std::ofstream(path, std::ios::binary) << json;
  const Scene b = load_scene(path);
  expect_same_model(a, b);
}

const Scene::Frame& frame(const Scene& s, const std::string& name) {
  for (const Scene::Frame& f : s.frames)
    if (f.name == name) return f;
  ADD_FAILURE() << "no frame " << name;
  return s.frames.front();
}

const Eigen::Matrix<double, 6, 1> kI =
    (Eigen::Matrix<double, 6, 1>() << 0.1, 0.2, 0.25, 0, 0, 0).finished();

TEST(urdf, InertialOriginIsTheCentreOfMassAndItsRpyRotatesTheInertia) {
  const std::string dir = temp_dir();
  Random<double> rnd;
  Worst worst("inertia from <inertial> vs from_cm(m, xyz, R J R*)");
  for (int i = 0; i < 40; ++i) {
    const double m = rnd.uniform(0.1, 10);
    const Vec3<double> xyz = rnd.vec3(),
                       rpy(rnd.uniform(-3, 3), rnd.uniform(-1.5, 1.5), rnd.uniform(-3, 3));
    const Eigen::Matrix<double, 6, 1> I = random_inertia(rnd);
    const std::string path = write(dir, "r" + std::to_string(i) + ".urdf",
                                   robot(massless("base") + link("l1", m, xyz, rpy, I) +
                                         joint("j1", "revolute", "base", "l1", Vec3<double>::Zero(),
                                               Vec3<double>::Zero(), axis(Vec3<double>::UnitZ()))));
    const Scene s = load_scene(path);
    const Mat3<double> R = rpy_matrix(rpy);
    const SpatialInertia expected =
        SpatialInertia::from_cm(m, xyz, R * matrix_of(I) * R.transpose());
    worst.add(inertia_residual(s.model.body(1).M, expected), i);
    if (i < 3) expect_convert_round_trip(path);
  }
  EXPECT_LE(worst.value(), 64 * eps<double>());
}

TEST(urdf, JointOriginIsThePlacementAndAxisIsInTheChildFrame) {
  const std::string dir = temp_dir();
  Random<double> rnd;
  Worst worst("placement vs origin xyz rpy");
  for (int i = 0; i < 40; ++i) {
    const Vec3<double> xyz = rnd.vec3(),
                       rpy(rnd.uniform(-3, 3), rnd.uniform(-1.5, 1.5), rnd.uniform(-3, 3));
    const Vec3<double> a = rnd.vec3();
    const std::string path =
        write(dir, "p" + std::to_string(i) + ".urdf",
              robot(massless("base") + link("l1", 1) + link("l2", 2) +
                    joint("j1", "revolute", "base", "l1", Vec3<double>::Zero(),
                          Vec3<double>::Zero(), axis(Vec3<double>::UnitZ())) +
                    joint("j2", i % 2 ? "revolute" : "prismatic", "l1", "l2", xyz, rpy, axis(a))));
    const Scene s = load_scene(path);
    const Body& B = s.model.body(1);  // l2, the tip
    EXPECT_EQ(B.hinge.type, i % 2 ? HingeType::Revolute : HingeType::Prismatic);
    worst.add((B.placement.R() - rpy_matrix(rpy)).norm(), i);
    worst.add((B.placement.l() - xyz).norm() / xyz.norm(), i);
    worst.add((B.hinge.axis - a.normalized()).norm(), i);
  }
  EXPECT_LE(worst.value(), 16 * eps<double>());
}

TEST(urdf, JointTypesMapOntoHinges) {
  const std::string dir = temp_dir();
  const std::string path = write(
      dir, "types.urdf",
      robot(massless("world") + link("float", 1) + link("rev", 1) + link("cont", 1) +
            link("pris", 1) + link("fix", 1) + joint("j_float", "floating", "world", "float") +
            joint("j_rev", "revolute", "float", "rev", Vec3<double>(0, 0, 1), Vec3<double>::Zero(),
                  axis(Vec3<double>::UnitY())) +
            joint("j_cont", "continuous", "rev", "cont", Vec3<double>(0, 0, 1),
                  Vec3<double>::Zero(), axis(Vec3<double>::UnitY())) +
            joint("j_pris", "prismatic", "cont", "pris", Vec3<double>(0, 0, 1),
                  Vec3<double>::Zero(), axis(Vec3<double>::UnitZ())) +
            joint("j_fix", "fixed", "pris", "fix", Vec3<double>(0, 0, 0.5))));
  const Scene s = load_scene(path);
  ASSERT_EQ(s.model.n(), 4);  // the fixed link is merged
  EXPECT_EQ(s.model.body(4).hinge.type, HingeType::Free);
  EXPECT_EQ(s.model.body(3).hinge.type, HingeType::Revolute);
  EXPECT_EQ(s.model.body(2).hinge.type, HingeType::Revolute);  // continuous
  EXPECT_EQ(s.model.body(1).hinge.type, HingeType::Prismatic);
  EXPECT_TRUE(frame(s, "fix").locked);
  EXPECT_EQ(frame(s, "fix").k, 1);
  EXPECT_EQ(s.model.body(1).M.mass(), 2.0);  // pris and the fixed link
  EXPECT_EQ(s.model.nv(), 6 + 3);
  expect_convert_round_trip(path);
}

TEST(urdf, AxisDefaultsToX) {
  const std::string dir = temp_dir();
  const std::string path =
      write(dir, "axis.urdf",
            robot(massless("base") + link("l1", 1) + joint("j1", "revolute", "base", "l1")));
  EXPECT_EQ(load_scene(path).model.body(1).hinge.axis, Vec3<double>::UnitX());
}

TEST(urdf, DampingBecomesTheDamperLimitsAndFrictionAreKept) {
  const std::string dir = temp_dir();
  const std::string path =
      write(dir, "dyn.urdf",
            robot(massless("base") + link("l1", 1) + link("l2", 1) +
                  joint("j1", "revolute", "base", "l1", Vec3<double>::Zero(), Vec3<double>::Zero(),
                        "    <limit lower=\"-1.5\" upper=\"2.5\" effort=\"40\" velocity=\"3\"/>\n"
                        "    <dynamics damping=\"0.75\" friction=\"0.25\"/>\n") +
                  joint("j2", "continuous", "l1", "l2", Vec3<double>(0, 0, 1), Vec3<double>::Zero(),
                        "    <limit effort=\"5\" velocity=\"6\"/>\n")));
  const Scene s = load_scene(path);
  EXPECT_EQ(s.model.body(2).damping, 0.75);
  EXPECT_EQ(s.model.body(2).stiffness, 0.0);
  EXPECT_EQ(s.model.body(1).damping, 0.0);
  const HingeLimits* l1 = frame(s, "l1").limits();
  ASSERT_TRUE(l1);
  EXPECT_EQ(l1->lower, -1.5);
  EXPECT_EQ(l1->upper, 2.5);
  EXPECT_EQ(l1->effort, 40);
  EXPECT_EQ(l1->velocity, 3);
  EXPECT_EQ(l1->friction, 0.25);
  const HingeLimits* l2 = frame(s, "l2").limits();
  ASSERT_TRUE(l2);
  EXPECT_FALSE(l2->has_position()) << "a continuous joint has no position limits";
  EXPECT_EQ(l2->effort, 5);
  EXPECT_EQ(l2->velocity, 6);
  expect_convert_round_trip(path);
}

TEST(urdf, MasslessLinksAreFrames) {
  const std::string dir = temp_dir();
  // A massless link between two joints moves the mass outboard of it; tool0 is a frame.
  const std::string path =
      write(dir, "massless.urdf",
            robot(massless("base_link") + link("l1", 2) + massless("l2") + link("l3", 1.5) +
                  massless("tool0") + joint("j1", "revolute", "base_link", "l1") +
                  joint("j2", "revolute", "l1", "l2", Vec3<double>(0, 0, 0.3), Vec3<double>::Zero(),
                        axis(Vec3<double>::UnitY())) +
                  joint("j3", "revolute", "l2", "l3", Vec3<double>::Zero(), Vec3<double>::Zero(),
                        axis(Vec3<double>::UnitZ())) +
                  joint("j4", "fixed", "l3", "tool0", Vec3<double>(0, 0, 0.1))));
  const Scene s = load_scene(path);
  ASSERT_EQ(s.model.n(), 3);
  EXPECT_EQ(s.model.body(2).M.mass(), 0.0) << "l2 is massless";
  EXPECT_EQ(s.model.body(1).M.mass(), 1.5) << "tool0 adds nothing to l3";
  const Scene::Frame& tool = frame(s, "tool0");
  EXPECT_TRUE(tool.locked);
  EXPECT_EQ(tool.offset().l(), Vec3<double>(0, 0, 0.1));
  // The mass matrix is positive definite: the massless link's hinge moves l3.
  const Operators op = Operators::build(s.model, s.state, {});
  EXPECT_EQ(op.mass_matrix().llt().info(), Eigen::Success);
  expect_convert_round_trip(path);
}

TEST(urdf, LinksFixedToTheRootAreTheGround) {
  const std::string dir = temp_dir();
  Random<double> rnd;
  const Vec3<double> x1 = rnd.vec3(), r1(0.3, -0.2, 1.1), x2 = rnd.vec3(), r2(-0.5, 0.4, 0.2);
  const std::string path = write(dir, "ground.urdf",
                                 robot(link("world", 50) + link("pedestal", 20) + link("l1", 1) +
                                       joint("fix", "fixed", "world", "pedestal", x1, r1) +
                                       joint("j1", "revolute", "pedestal", "l1", x2, r2)));
  const Scene s = load_scene(path);
  ASSERT_EQ(s.model.n(), 1);
  EXPECT_EQ(s.model.body(1).M.mass(), 1.0) << "the ground's masses are not part of the chain";
  const Pose expected = Pose(rpy_matrix(r1), x1) * Pose(rpy_matrix(r2), x2);
  EXPECT_LE((s.model.body(1).placement.R() - expected.R()).norm(), 16 * eps<double>());
  EXPECT_LE((s.model.body(1).placement.l() - expected.l()).norm(),
            16 * eps<double>() * expected.l().norm());
  expect_convert_round_trip(path);
}

/// A side branch fixed to the chain is merged as rigid mass: the body it hangs on, merged by
/// the URDF reader, carries what the same links in line as locked bodies give it (merged by
/// ModelT::from_base_first(), another code).
TEST(urdf, FixedSideBranchesAreRigidMass) {
  const std::string dir = temp_dir();
  Random<double> rnd;
  Worst worst("l1's inertia: side branch merged vs the same links in line");
  for (int i = 0; i < 20; ++i) {
    const Vec3<double> xa = rnd.vec3(), ra(rnd.normal(), rnd.normal(), rnd.normal());
    const Vec3<double> xb = rnd.vec3(), rb(rnd.normal(), rnd.normal(), rnd.normal());
    const auto Ia = random_inertia(rnd), Ib = random_inertia(rnd);
    const double ma = rnd.uniform(0.1, 3), mb = rnd.uniform(0.1, 3);
    const Vec3<double> ca = rnd.vec3(), cb = rnd.vec3();
    const std::string arm = massless("base") + link("l1", 2) + link("l2", 1.5) +
                            joint("j1", "revolute", "base", "l1") +
                            joint("j2", "revolute", "l1", "l2", Vec3<double>(0, 0, 0.4),
                                  Vec3<double>::Zero(), axis(Vec3<double>::UnitY()));
    // Branch: l1 -> a (fixed) -> b (fixed), off the chain l1 -> l2.
    const std::string branch = write(
        dir, "branch" + std::to_string(i) + ".urdf",
        robot(arm + link("a", ma, ca, Vec3<double>::Zero(), Ia) +
              link("b", mb, cb, Vec3<double>::Zero(), Ib) +
              joint("fa", "fixed", "l1", "a", xa, ra) + joint("fb", "fixed", "a", "b", xb, rb)));
    const Scene s = load_scene(branch, UrdfOptions{"l2", {}});
    // In line: l1 -> a -> b as locked bodies of a one-joint chain.
    const std::string line = write(
        dir, "line" + std::to_string(i) + ".urdf",
        robot(massless("base") + link("l1", 2) + link("a", ma, ca, Vec3<double>::Zero(), Ia) +
              link("b", mb, cb, Vec3<double>::Zero(), Ib) + joint("j1", "revolute", "base", "l1") +
              joint("fa", "fixed", "l1", "a", xa, ra) + joint("fb", "fixed", "a", "b", xb, rb)));
    const Scene t = load_scene(line);
    ASSERT_EQ(t.model.n(), 1);
    ASSERT_EQ(s.model.n(), 2);
    // l1 of the branched chain carries exactly what l1 of the in-line chain carries.
    worst.add(inertia_residual(s.model.body(2).M, t.model.body(1).M), i);
  }
  EXPECT_LE(worst.value(), 256 * eps<double>());
}

/// An arm of one joint with a hand and two prismatic fingers, written in \p dir.
std::string gripper(const std::string& dir) {
  return write(
      dir, "gripper.urdf",
      robot(massless("base") + link("l1", 2) + link("hand", 0.7) + link("left", 0.1) +
            link("right", 0.1) + joint("j1", "revolute", "base", "l1") +
            joint("wrist", "fixed", "l1", "hand", Vec3<double>(0, 0, 0.3)) +
            joint("finger_left", "prismatic", "hand", "left", Vec3<double>(0, 0.02, 0.05),
                  Vec3<double>::Zero(), axis(Vec3<double>::UnitY())) +
            joint("finger_right", "prismatic", "hand", "right", Vec3<double>(0, -0.02, 0.05),
                  Vec3<double>::Zero(), axis(-Vec3<double>::UnitY()))));
}

TEST(urdf, MovingSideBranchIsAnErrorAndLockTakesItIn) {
  const std::string path = gripper(temp_dir());
  EXPECT_EQ(error_of([&] { load_scene(path); }),
            path +
                ": a tree, not a chain: no single path from 'base' passes every moving joint "
                "(its ends: 'left', 'right'); choose the tip with --tip LINK, and lock the "
                "joints off its path with --lock JOINT");
  EXPECT_EQ(error_of([&] {
              load_scene(path, UrdfOptions{"left", {}});
            }),
            path +
                ": joint 'finger_right' (prismatic) moves 'right', a branch off the chain at "
                "'hand': the course's chains are serial; lock it with --lock finger_right, or "
                "choose a tip beyond it with --tip LINK");
  const Scene s = load_scene(path, UrdfOptions{"left", {"finger_right"}});
  EXPECT_EQ(s.model.n(), 2);
  // Both fingers locked: they end the chain at 'hand', merged into it.
  const Scene t = load_scene(path, UrdfOptions{"", {"finger_left", "finger_right"}});
  EXPECT_EQ(t.model.n(), 1);
  EXPECT_EQ(t.frames.back().name, "hand");
  EXPECT_DOUBLE_EQ(t.model.body(1).M.mass(), 2 + 0.7 + 0.1 + 0.1);
  expect_convert_round_trip(path, UrdfOptions{"", {"finger_left", "finger_right"}});
  EXPECT_EQ(error_of([&] {
              load_scene(path, UrdfOptions{"hand", {}});
            }),
            path +
                ": joint 'finger_left' (prismatic) moves 'left', beyond the tip 'hand': the "
                "course's chains are serial; lock it with --lock finger_left, or choose a "
                "tip beyond it with --tip LINK");
  EXPECT_EQ(error_of([&] {
              load_scene(path, UrdfOptions{"thumb", {}});
            }),
            path +
                ": --tip: no link named 'thumb' (links: 'base', 'hand', 'l1', 'left', "
                "'right')");
  EXPECT_EQ(error_of([&] {
              load_scene(path, UrdfOptions{"", {"pinky"}});
            }),
            path +
                ": --lock: no joint named 'pinky' (joints: 'finger_left', 'finger_right', "
                "'j1', 'wrist')");
}

/// Several ends fixed to one link: the chain ends at that link, the ends merged into it (their
/// frames are kept only as the chosen tip).
TEST(urdf, SeveralFixedEndsEndTheChainAtTheirCommonLink) {
  const std::string dir = temp_dir();
  const std::string path =
      write(dir, "ends.urdf",
            robot(massless("base") + link("l1", 2) + massless("tool0") + massless("camera") +
                  joint("j1", "revolute", "base", "l1") +
                  joint("t", "fixed", "l1", "tool0", Vec3<double>(0, 0, 0.2)) +
                  joint("c", "fixed", "l1", "camera", Vec3<double>(0.1, 0, 0))));
  const Scene c = load_scene(path);
  EXPECT_EQ(c.frames.size(), 1u);
  EXPECT_EQ(c.frames.back().name, "l1");
  EXPECT_NE(urdf_to_scene_json(path).find("'camera', 'tool0' end the chain, fixed to 'l1'"),
            std::string::npos);
  const Scene s = load_scene(path, UrdfOptions{"tool0", {}});
  EXPECT_EQ(s.frames.back().name, "tool0");
  EXPECT_EQ(s.frames.size(), 2u) << "camera is merged into l1 (massless: nothing to add)";
}

/// A JSON error of the generated scene names the URDF's link or joint.
TEST(urdf, JsonCheckMessagesNameTheLinkOrJoint) {
  const std::string dir = temp_dir();
  const std::string path =
      write(dir, "base.urdf",
            robot(massless("world") + link("base", 1) + joint("j", "revolute", "world", "base")));
  EXPECT_EQ(error_of([&] { load_scene(path); }),
            path + ": link 'base' name: \"base\" names the ground; pick another");
}

/// A line break in a name is a character of the name: the scene has the URDF's two bodies,
/// a message and `soa convert`'s comments show it escaped, and the converted JSON reads back
/// to the same model.
TEST(urdf, ALineBreakInANameStaysInTheName) {
  const std::string path =
      std::string(SOA_SOURCE_DIR) + "/tests/scenes/urdf/name_with_line_break.urdf";
  const Scene s = load_scene(path);
  ASSERT_EQ(s.frames.size(), 2u);
  EXPECT_EQ(s.frames[1].name, "lower\n// injected");
  EXPECT_DOUBLE_EQ(s.model.body(1).M.mass(), 0.8);
  const std::string json = urdf_to_scene_json(path);
  EXPECT_NE(json.find("// link 'lower\\n// injected' on joint"), std::string::npos);
  EXPECT_EQ(json.find("\n// injected"), std::string::npos) << "a comment line was split";
  const std::string dir = temp_dir();
  fs::copy_file(path, dir + "/name_with_line_break.urdf");
  expect_convert_round_trip(dir + "/name_with_line_break.urdf");
}

/// urdfdom's own console output never reaches the user: stderr stays empty on a bad file
/// (its reason is in our message) and on a good one.
TEST(urdf, UrdfdomSaysNothing) {
  const std::string dir = temp_dir();
  const std::string bad = write(dir, "bad.urdf", "<robot name=\"x\"><link name=\"a\"/>");
  const std::string good = default_scene("panda.urdf");
  const std::string err = dir + "/stderr.txt";
  std::fflush(stderr);
  const int saved = dup(2);
  const int fd = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ASSERT_GE(fd, 0);
  dup2(fd, 2);
  const std::string message = error_of([&] { load_scene(bad); });
  const Scene s = load_scene(good);
  std::fflush(stderr);
  dup2(saved, 2);
  close(fd);
  close(saved);
  EXPECT_EQ(read_text(err), "");
  EXPECT_EQ(message.rfind(bad + ": not a valid URDF (urdfdom: ", 0), 0u) << message;
  EXPECT_EQ(s.model.n(), 7);
}

/// urdfdom reads the first of each element that comes once and drops the others without a
/// word: a second one is refused, naming the joint or link and the element.
TEST(urdf, ASecondElementIsRefused) {
  const std::string dir = temp_dir();
  const std::vector<std::pair<std::string, std::string>> in_joint = {
      {"origin", "    <origin xyz=\"0 0 1\"/>\n"},
      {"axis", axis(Vec3<double>::UnitZ()) + axis(Vec3<double>::UnitY())},
      {"limit",
       "    <limit lower=\"-1\" upper=\"1\" effort=\"1\" velocity=\"1\"/>\n"
       "    <limit lower=\"-2\" upper=\"2\" effort=\"1\" velocity=\"1\"/>\n"},
      {"dynamics", "    <dynamics damping=\"1\"/>\n    <dynamics damping=\"2\"/>\n"},
      {"parent", "    <parent link=\"l1\"/>\n"},
      {"child", "    <child link=\"base\"/>\n"},
      {"mimic", "    <mimic joint=\"j0\"/>\n    <mimic joint=\"j2\"/>\n"}};
  for (const auto& [element, extra] : in_joint) {
    SCOPED_TRACE(element);
    const std::string path = write(dir, "joint_" + element + ".urdf",
                                   robot(massless("base") + link("l1", 1) +
                                         joint("j1", "revolute", "base", "l1", Vec3<double>::Zero(),
                                               Vec3<double>::Zero(), extra)));
    const std::string message = error_of([&] { load_scene(path); });
    EXPECT_NE(message.find(": joint 'j1': a second <" + element + "> (the first on line "),
              std::string::npos)
        << message;
  }
  const std::string one = link("l1", 1);
  const std::size_t end_inertial = one.find("    </inertial>"), end_link = one.find("  </link>");
  const std::string inertial = one.substr(one.find("    <inertial>"));
  const std::vector<std::pair<std::string, std::string>> in_link = {
      {"inertial", one.substr(0, end_link) + inertial},
      {"mass",
       one.substr(0, end_inertial) + "      <mass value=\"2\"/>\n" + one.substr(end_inertial)},
      {"inertia",
       one.substr(0, end_inertial) +
           "      <inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/>\n" +
           one.substr(end_inertial)},
      {"origin",
       one.substr(0, end_inertial) + "      <origin xyz=\"0 0 1\"/>\n" + one.substr(end_inertial)}};
  for (const auto& [element, text] : in_link) {
    SCOPED_TRACE(element);
    const std::string path =
        write(dir, "link_" + element + ".urdf",
              robot(massless("base") + text + joint("j1", "revolute", "base", "l1")));
    const std::string message = error_of([&] { load_scene(path); });
    EXPECT_NE(message.find(": link 'l1': a second <" + element + "> (the first on line "),
              std::string::npos)
        << message;
  }
}

/// What real URDF files carry beyond the spec loads: extension elements under <robot> and
/// <link> (their contents unread, a '%' in them too), elements and attributes of a namespace
/// (xacro's, Drake's), in a joint as well, and a mesh file name with URL escapes.
TEST(urdf, ExtensionsLoad) {
  const std::string dir = temp_dir();
  std::string text =
      robot(massless("base") + link("l1", 1) +
            joint("j1", "revolute", "base", "l1", Vec3<double>::Zero(), Vec3<double>::Zero(),
                  "    <drake:rotor_inertia value=\"0.1\"/>\n") +
            "  <gazebo reference=\"l1\"><material>Gazebo/Grey%20</material>"
            "<plugin filename=\"lib%s.so\"/></gazebo>\n"
            "  <transmission name=\"t1\"><type>SimpleTransmission</type><joint name=\"j1\"/>"
            "</transmission>\n"
            "  <ros2_control name=\"arm\" type=\"system\"><joint name=\"j1\"/></ros2_control>\n");
  text.replace(text.find("<robot name=\"test\">"), 19,
               "<robot name=\"test\" xmlns:xacro=\"http://www.ros.org/wiki/xacro\">");
  text.replace(text.find("    <inertial>"), 0,
               "    <self_collision_checking/>\n    <visual><geometry><mesh "
               "filename=\"package://arm/meshes/upper%20arm.stl\"/></geometry></visual>\n");
  const std::string path = write(dir, "extensions.urdf", text);
  EXPECT_EQ(load_scene(path).model.n(), 1);
}

/// A revolute or prismatic joint's <limit> with one of lower and upper: the other is the URDF
/// spec's default, 0, and `soa convert` says so.
TEST(urdf, AMissingLimitBoundIsTheSpecsZero) {
  const std::string dir = temp_dir();
  const std::string path =
      write(dir, "upper_only.urdf",
            robot(massless("base") + link("l1", 1) +
                  joint("j1", "revolute", "base", "l1", Vec3<double>::Zero(), Vec3<double>::Zero(),
                        "    <limit upper=\"1.5\" effort=\"10\" velocity=\"2\"/>\n")));
  const HingeLimits* l = frame(load_scene(path), "l1").limits();
  ASSERT_TRUE(l);
  EXPECT_EQ(l->lower, 0.0);
  EXPECT_EQ(l->upper, 1.5);
  EXPECT_NE(urdf_to_scene_json(path).find("// limit lower: not given, 0 (the URDF spec's default)"),
            std::string::npos);
  expect_convert_round_trip(path);
}

/// A joint --lock fixes is said the same way on the chain and off it (beyond the tip, or a
/// finger on a side branch): "locked at its zero position by --lock".
TEST(urdf, EveryLockedJointIsSaid) {
  const std::string panda = urdf_to_scene_json(
      default_scene("panda.urdf"),
      UrdfOptions{"panda_link3", {"panda_joint4", "panda_joint5", "panda_joint6", "panda_joint7"}});
  for (const char* j : {"panda_joint4", "panda_joint5", "panda_joint6", "panda_joint7"})
    EXPECT_NE(panda.find(std::string("// joint '") + j +
                         "' (revolute) locked at its zero position by --lock"),
              std::string::npos)
        << j;
  const std::string fingers =
      urdf_to_scene_json(gripper(temp_dir()), UrdfOptions{"", {"finger_left", "finger_right"}});
  for (const char* j : {"finger_left", "finger_right"})
    EXPECT_NE(fingers.find(std::string("// joint '") + j +
                           "' (prismatic) locked at its zero position by --lock"),
              std::string::npos)
        << j;
}

/// A tree of 20,000 leaves: refused in a short message when they move (the first few, then
/// how many more), loaded when they are fixed, with a short comment.
TEST(urdf, TwentyThousandLeavesGiveShortMessages) {
  const std::string dir = temp_dir();
  const int n = 20000;
  for (const std::string type : {"revolute", "fixed"}) {
    SCOPED_TRACE(type);
    std::string body = massless("base") + link("hub", 1) + joint("j", "revolute", "base", "hub");
    for (int i = 0; i < n; ++i) {
      const std::string leaf = "leaf" + std::to_string(i);
      body += link(leaf, 0.01) + joint("j" + leaf, type, "hub", leaf);
    }
    const std::string path = write(dir, type + ".urdf", robot(body));
    if (type == "revolute") {
      const std::string message = error_of([&] { load_scene(path); });
      EXPECT_LT(message.size(), 500u) << message.substr(0, 500);
      EXPECT_NE(message.find("and 19994 more"), std::string::npos) << message.substr(0, 500);
    } else {
      EXPECT_EQ(load_scene(path).model.n(), 1);
      const std::string json = urdf_to_scene_json(path);
      for (std::size_t at = 0, end = 0; at < json.size(); at = end + 1) {
        end = std::min(json.find('\n', at), json.size());
        EXPECT_LT(end - at, 500u) << json.substr(at, 500);
      }
    }
  }
}

/// tests/scenes/urdf/bad/NAME.urdf -> the message after "<file>: ".
const std::map<std::string, std::string>& expected_messages() {
  static const std::map<std::string, std::string> table = {
      {"zero_axis", "joint 'j2': axis is zero"},
      {"mass_not_a_number",
       "urdfdom could not read all of it: Inertial: mass [1.0x] is not a float; then: Could "
       "not parse inertial element for Link [upper] (it would go on without what it could not "
       "read)"},
      {"inertia_not_a_number",
       "urdfdom could not read all of it: Inertial: inertia element ixx is not a valid double; "
       "then: Could not parse inertial element for Link [upper] (it would go on without what "
       "it could not read)"},
      {"joint_cycle",
       "joints 'b_to_a', 'a_to_b' form a cycle through link 'a': the links of a URDF form a "
       "tree"},
      {"own_parent",
       "joint 'c_on_c' makes link 'c' its own parent: the links of a URDF form a tree"},
      {"two_parents",
       "link 'lower' is the child of two joints, 'joint_extra' and 'joint_lower': the links of "
       "a URDF form a tree, each below one joint"},
      {"name_not_utf8", "robot 'pend\\xffulum': its name is not UTF-8 text"},
      {"origin_too_far",
       "joint 'joint_lower' placement.position: 1.7e+308 m from the parent's frame, more than "
       "the 1e+150 m a placement may have (its products would overflow)"},
      {"nested_too_deep",
       "line 4: XML nested more than 100 levels deep, the most a URDF file may be"},
      {"planar",
       "joint 'j1': a planar joint (3 dofs in a plane) has no hinge in the course "
       "(revolute, prismatic, helical, universal, spherical, free); lock it with "
       "--lock j1"},
      {"negative_mass", "link 'l1': inertial: mass -1 is negative"},
      {"zero_mass_with_inertia",
       "link 'l1': inertial: mass 0 with a non-zero inertia (a massless link has neither: leave "
       "<inertial> out)"},
      {"inertia_not_positive",
       "link 'l2': inertial: inertia not positive definite (principal moments -0.1, 0.2, 0.3)"},
      {"inertia_triangle",
       "link 'l1': inertial: inertia principal moments 0.1, 0.1, 0.5 break the triangle "
       "inequality (0.1 + 0.1 < 0.5)"},
      {"mimic",
       "joint 'j2': mimics 'j1': the course's hinges have coordinates of their own; "
       "lock it with --lock j2"},
      {"massless_outboard",
       "joint 'j2' (revolute) moves only massless links ('l2', 'tool0'): nothing of mass "
       "outboard of it, its motion is undefined"},
      {"no_moving_joint", "no moving joint: every joint is fixed (or locked), no chain"},
      {"limits_reversed", "joint 'j1': limit lower 2 is above upper -2"},
      {"negative_damping", "joint 'j1': dynamics damping -0.5 is not a finite number >= 0"},
      {"moving_branch",
       "a tree, not a chain: no single path from 'base' passes every moving joint (its ends: "
       "'a', 'b'); choose the tip with --tip LINK, and lock the joints off its path with --lock "
       "JOINT"},
      {"empty_joint_name", "line 12: <joint name=\"\">: an empty name"},
      {"empty_link_name", "line 5: <link name=\"\">: an empty name"},
      {"empty_parent_link", "line 13: joint 'j1': <parent link=\"\">: an empty name"},
      {"empty_robot_name", "line 3: <robot name=\"\">: an empty name"},
      {"limit_without_lower_and_upper",
       "line 17: joint 'j1' (revolute): <limit> without lower and upper: the URDF spec then means "
       "0 and 0, a joint that cannot move; give them, or make the joint continuous"},
      {"near_miss_in_link",
       "line 6: link 'l1': <intertial>: not an element of <link> (URDF: inertial, visual, "
       "collision), which urdfdom would ignore; did you mean <inertial>?"},
      {"near_miss_in_robot",
       "line 12: <jiont>: not an element of <robot> (URDF: link, joint, material), which urdfdom "
       "would ignore; did you mean <joint>?"},
      {"negative_effort", "joint 'j1': limit effort -10 is negative: it bounds |effort|"},
      {"negative_velocity", "joint 'j1': limit velocity -2 is negative: it bounds |velocity|"},
      {"percent_in_name",
       "line 5: <link name=\"a%s\">: a '%' in a value, which urdfdom would use as a printf format "
       "(and crash): leave it out"},
      {"percent_in_value",
       "line 8: link 'l1': <mass value=\"1%s\">: a '%' in a value, which urdfdom would use as a "
       "printf format (and crash): leave it out"},
      {"second_limit",
       "line 18: joint 'j1': a second <limit> (the first on line 17), which urdfdom would ignore: "
       "give one"},
      {"second_mass",
       "line 9: link 'l1': a second <mass> (the first on line 8), which urdfdom would ignore: give "
       "one"},
      {"unknown_attribute",
       "line 17: joint 'j1': <limit lowr>: not an attribute of <limit> (URDF: lower, upper, "
       "effort, velocity), which urdfdom would ignore; did you mean lower?"},
      {"unknown_element_in_inertial",
       "line 9: link 'l1': <density>: not an element of <inertial> (URDF: origin, mass, inertia), "
       "which urdfdom would ignore"},
      {"unknown_element_in_joint",
       "line 15: joint 'j1': <orgin>: not an element of <joint> (URDF: origin, parent, child, "
       "axis, calibration, dynamics, limit, mimic, safety_controller), which urdfdom would ignore; "
       "did you mean <origin>?"},
      {"not_urdf",
       "not a valid URDF (urdfdom: Could not find the 'robot' element in the xml "
       "file)"},
  };
  return table;
}

TEST(urdf, EachBadFileHasItsMessage) {
  const fs::path bad = fs::path(SOA_SOURCE_DIR) / "tests/scenes/urdf/bad";
  std::set<std::string> seen;
  for (const auto& e : fs::directory_iterator(bad)) {
    const std::string name = e.path().stem().string();
    seen.insert(name);
    const auto it = expected_messages().find(name);
    if (it == expected_messages().end()) {
      ADD_FAILURE() << e.path() << " has no expected message in the table";
      continue;
    }
    EXPECT_EQ(error_of([&] { load_scene(e.path().string()); }),
              e.path().string() + ": " + it->second);
  }
  for (const auto& [name, message] : expected_messages())
    EXPECT_TRUE(seen.count(name)) << name << ".urdf is missing";
}

/// The project's URDFs: `soa convert`'s JSON reads back to the same model bit for bit.
TEST(urdf, ConvertGivesTheSameModelBitForBit) {
  const std::string dir = temp_dir();
  for (const char* name :
       {"arm7.urdf", "double_pendulum.urdf", "chain50.urdf", "panda.urdf", "ur5e.urdf"}) {
    SCOPED_TRACE(name);
    const std::string copy = dir + "/" + name;  // the JSON is written beside it
    fs::copy_file(default_scene(name), copy);
    expect_convert_round_trip(copy);
  }
}

/// The default scenes in both formats (arm7, double_pendulum, chain50 .urdf beside .json):
/// the same M, T and accelerations, to 1e-15 relative, at random states of a fixed seed.
TEST(urdf, DefaultScenesAgreeInBothFormats) {
  Random<double> rnd;
  for (const std::string name : {"arm7", "double_pendulum", "chain50"}) {
    SCOPED_TRACE(name);
    const Scene u = load_scene(default_scene(name + ".urdf"));
    const Scene j = load_scene(default_scene(name + ".json"));
    ASSERT_EQ(u.model.nv(), j.model.nv());
    ASSERT_EQ(u.frames.size(), j.frames.size());
    const int nv = j.model.nv();
    Worst wM(name + " URDF vs JSON: M"), wT(name + " URDF vs JSON: T"),
        wA(name + " URDF vs JSON: qdd");
    Workspace wsu(u.model), wsj(j.model);
    ForwardDynamics fu(u.model), fj(j.model);
    for (int i = 0; i < 20; ++i) {
      const State x = random_state(rnd, j.model);
      const VecX<double> qdd = random_vector(rnd, nv), tau = random_vector(rnd, nv);
      const Operators ou = Operators::build(u.model, x, {}), oj = Operators::build(j.model, x, {});
      wM.add(rel(ou.mass_matrix(), oj.mass_matrix()), i);
      VecX<double> Tu(nv), Tj(nv), au(nv), aj(nv);
      inverse_dynamics(u.model, x, qdd, {}, wsu, Tu);
      inverse_dynamics(j.model, x, qdd, {}, wsj, Tj);
      wT.add(rel(Tu, Tj), i);
      forward_dynamics(u.model, x, tau, {}, wsu, fu, au);
      forward_dynamics(j.model, x, tau, {}, wsj, fj, aj);
      wA.add(rel(au, aj), i);
    }
    EXPECT_LE(wM.value(), 1e-15);
    EXPECT_LE(wT.value(), 1e-15);
    EXPECT_LE(wA.value(), 1e-15);
  }
}

/// The real arms: every joint's limits kept, a positive definite mass matrix, inverse
/// dynamics equal to the operator form at random states.
TEST(urdf, RealArmsLoad) {
  Random<double> rnd;
  for (const char* name : {"panda.urdf", "ur5e.urdf"}) {
    SCOPED_TRACE(name);
    const Scene s = load_scene(default_scene(name));
    int limited = 0;
    for (const Scene::Frame& f : s.frames) limited += f.limits() != nullptr;
    EXPECT_EQ(limited, s.model.n()) << "every moving joint keeps its <limit>";
    EXPECT_TRUE(s.frames.back().locked) << "the flange is a massless frame";
    Worst w(std::string(name) + ": T recursion vs operators");
    for (int i = 0; i < 20; ++i) {
      const State x = random_state(rnd, s.model);
      const VecX<double> qdd = random_vector(rnd, s.model.nv());
      const Operators op = Operators::build(s.model, x, {});
      EXPECT_EQ(op.mass_matrix().llt().info(), Eigen::Success);
      Workspace ws(s.model);
      VecX<double> T(s.model.nv());
      inverse_dynamics(s.model, x, qdd, {}, ws, T);
      w.add(rel(T, op.T(qdd)), i);
    }
    EXPECT_LE(w.value(), 64 * s.model.nv() * eps<double>());
  }
}

}  // namespace
}  // namespace soa::test
