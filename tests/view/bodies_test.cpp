// The viewer's bodies (view_of()): names, hinges, the segments that connect the drawn chain,
// and the inertia ellipsoids.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "view_support.hpp"

namespace soa::test {
namespace {

const std::string kEveryHinge = std::string(SOA_SOURCE_DIR) + "/tests/scenes/every_hinge.json";

TEST(view_bodies, EveryHingeSceneInFileOrderWithTheScenesNames) {
  const Scene s = load_scene(kEveryHinge);
  const view::View v = view::view_of(s);
  EXPECT_EQ(v.title, "every hinge type");
  EXPECT_EQ(v.gravity, Vec3<double>(0, -9.81, 0));
  const char* names[] = {"carriage", "screw", "wrist", "ball", "tool", "drone"};
  const char* hinges[] = {"prismatic", "helical", "universal", "spherical", "locked", "free"};
  ASSERT_EQ(v.bodies.size(), 6u);
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(v.bodies[i].name, names[i]);
    EXPECT_EQ(v.bodies[i].hinge, hinges[i]);
  }
  // Axes for revolute and prismatic hinges only.
  EXPECT_EQ(v.bodies[0].axis, Vec3<double>(1, 0, 0));
  for (int i = 1; i < 6; ++i) EXPECT_EQ(v.bodies[i].axis, Vec3<double>::Zero()) << names[i];
  // The ball carries the locked tool: 0.5 + 0.2 kg, the tool none of its own.
  EXPECT_DOUBLE_EQ(v.bodies[3].mass, 0.7);
  EXPECT_EQ(v.bodies[4].mass, 0);
  EXPECT_EQ(v.bodies[4].radii, Vec3<double>::Zero());
  EXPECT_EQ(v.bodies[4].com, Vec3<double>(0, 0, 0.03));  // the tool's own
  EXPECT_DOUBLE_EQ(v.bodies[5].mass, 1.5);
  // Segments: the next hinge's placement; the ball's reaches the tool, the tool's the drone.
  EXPECT_EQ(v.bodies[0].segment, Vec3<double>(0, 0.1, 0));
  EXPECT_EQ(v.bodies[1].segment, Vec3<double>(0, 0.2, 0));
  EXPECT_EQ(v.bodies[2].segment, Vec3<double>(0, 0, 0.2));
  EXPECT_TRUE(v.bodies[3].segment.isApprox(Vec3<double>(0, 0, 0.15)));
  EXPECT_TRUE(v.bodies[4].segment.isApprox(Vec3<double>(0, 0, 0.5)));
  EXPECT_EQ(v.bodies[5].segment, Vec3<double>::Zero());  // twice its centre of mass
  EXPECT_EQ(v.tip_body, 5);
  EXPECT_EQ(v.tip_point, v.bodies[5].segment);
  EXPECT_TRUE(v.fixed.empty());
  EXPECT_TRUE(v.runs.empty());
}

// The drawn chain is connected: the far end of body i's segment, carried by body i's pose,
// is the hinge point of body i + 1, O^+ = {}^I T_{O} T_h(theta)^{-1} of its own pose and
// hinge (its origin for a locked body), at random states of random chains.
TEST(view_bodies, SegmentEndIsTheNextHingePointInTheWorld) {
  Random<double> rnd;
  Worst world("segment end vs next hinge point (world, rel, n eps)");
  Worst file("segment vs the file's placement (rel, n eps)");
  Worst last("last segment vs twice its own com (rel, eps)");
  int c = 0;
  for (int chain = 0; chain < 200; ++chain) {
    const int n = 2 + int(rnd.engine()() % 9);
    const RandomScene r = random_scene(rnd, n);
    const Scene& s = r.scene;
    const view::View v = view::view_of(s);
    ASSERT_EQ(v.bodies.size(), std::size_t(n));
    for (int i = 0; i + 1 < n; ++i)
      file.add(rel(v.bodies[i].segment, r.base_first[i + 1].placement.l()) / (n * eps<double>()),
               c);
    last.add(
        rel(v.bodies.back().segment, Vec3<double>(2 * r.base_first.back().M.p())) / eps<double>(),
        c);
    EXPECT_EQ(v.tip_point, v.bodies.back().segment);
    for (int state = 0; state < 5; ++state, ++c) {
      const State x = random_state(rnd, s.model);
      const view::Frame f = frame_of(s, x, {false, false});
      for (int i = 0; i + 1 < n; ++i) {
        const Vec3<double> end = pose_of(f, i).apply(v.bodies[i].segment);
        const Scene::Frame& next = s.frames[i + 1];
        Pose Th;  // the next body's hinge transform, {}^{O^+}T_{O}
        if (!next.locked) {
          const Body& B = s.model.body(next.k);
          Th = B.hinge.transform(x.theta.data() + B.q_offset);
        }
        const Vec3<double> hinge = (pose_of(f, i + 1) * Th.inverse()).l();
        world.add(rel(end, hinge) / (n * eps<double>()), c);
      }
    }
  }
  EXPECT_LE(file.value(), 4);
  EXPECT_LE(last.value(), 4);
  EXPECT_LE(world.value(), 32);
}

// A locked last body: its own centre of mass makes its segment, not the merged one's.
TEST(view_bodies, LockedLastBodyHasItsOwnCentreOfMass) {
  Random<double> rnd;
  for (int chain = 0; chain < 50; ++chain) {
    std::vector<Body> bodies;
    for (int i = 0; i < 4; ++i)
      bodies.push_back(detail::random_body(rnd, i, i < 2 ? HingeType::Revolute : HingeType::Locked,
                                           ChainOptions{}));
    const Scene s = parse_scene(chain_json(bodies).dump(), "locked_tip.json");
    const view::View v = view::view_of(s);
    ASSERT_EQ(v.bodies.size(), 4u);
    EXPECT_TRUE(v.bodies[3].com.isApprox(bodies[3].M.p(), 1e-14));
    EXPECT_TRUE(v.bodies[3].segment.isApprox(2 * bodies[3].M.p(), 1e-14));
    EXPECT_EQ(v.bodies[2].mass, 0);
    EXPECT_EQ(v.bodies[3].mass, 0);
    EXPECT_DOUBLE_EQ(v.bodies[1].mass,
                     bodies[1].M.mass() + bodies[2].M.mass() + bodies[3].M.mass());
  }
}

/// The inertia about the centre of mass of the uniform solid ellipsoid of mass \p m with
/// semi-axes \p a along the columns of \p Q: \f$Q\,\mathrm{diag}(m (a_j^2 + a_k^2)/5)\,Q^*\f$.
Mat3<double> ellipsoid_inertia(double m, const Vec3<double>& a, const Mat3<double>& Q) {
  Vec3<double> J;
  for (int i = 0; i < 3; ++i) {
    const double aj = a[(i + 1) % 3], ak = a[(i + 2) % 3];
    J[i] = m * (aj * aj + ak * ak) / 5;
  }
  return Q * J.asDiagonal() * Q.transpose();
}

// The ellipsoid's radii and axes give back the body's inertia about its centre of mass; its
// mass and centre are model body k's (merged bodies included).
TEST(view_bodies, EllipsoidReproducesTheInertia) {
  Random<double> rnd;
  Worst J_err("ellipsoid inertia vs J(C) (rel, eps)");
  int c = 0;
  for (int chain = 0; chain < 300; ++chain) {
    const RandomScene r = random_scene(rnd, 2 + int(rnd.engine()() % 7));
    const view::View v = view::view_of(r.scene);
    for (std::size_t i = 0; i < v.bodies.size(); ++i, ++c) {
      const view::Body& b = v.bodies[i];
      const Scene::Frame& F = r.scene.frames[i];
      if (F.locked) {
        EXPECT_EQ(b.mass, 0);
        continue;
      }
      const SpatialInertia& M = r.scene.model.body(F.k).M;
      EXPECT_EQ(b.mass, M.mass());
      EXPECT_EQ(b.com, M.p());
      const auto& q = b.axes_quaternion;
      EXPECT_NEAR(Eigen::Vector4d(q[0], q[1], q[2], q[3]).norm(), 1, 1e-14);
      const Mat3<double> Q = UnitQuaternion(Vec3<double>(q[0], q[1], q[2]), q[3]).matrix();
      EXPECT_GT(Q.determinant(), 0);
      const Mat3<double> J = M.J_cm();
      J_err.add((ellipsoid_inertia(b.mass, b.radii, Q) - J).norm() / (J.norm() * eps<double>()), c);
    }
  }
  EXPECT_LE(J_err.value(), 64);
}

// A flat body (J3 = J1 + J2, a plate) has a zero radius (rounding may make J1 + J2 - J3
// slightly negative), not NaN.
TEST(view_bodies, FlatBodiesHaveAZeroRadiusNotNaN) {
  for (const char* inertia : {"{\"Ixx\": 0.1, \"Iyy\": 0.2, \"Izz\": 0.3}",
                              "[[0.3, 0.1, 0], [0.1, 0.3, 0], [0, 0, 0.6]]"}) {
    const std::string text =
        std::string("{\"bodies\": [{\"name\": \"plate\", \"parent\": \"base\", \"mass\": 2, ") +
        "\"com\": [0, 0, -0.5], \"inertia\": " + inertia +
        ", \"hinge\": {\"type\": \"revolute\", \"axis\": [0, 1, 0]}}]}";
    const view::View v = view::view_of(parse_scene(text, "plate.json"));
    const view::Body& b = v.bodies.at(0);
    EXPECT_TRUE(b.radii.allFinite()) << inertia;
    EXPECT_LT(b.radii.minCoeff(), 1e-7) << inertia;
    const auto& q = b.axes_quaternion;
    const Mat3<double> Q = UnitQuaternion(Vec3<double>(q[0], q[1], q[2]), q[3]).matrix();
    const Mat3<double> J = parse_scene(text, "plate.json").model.body(1).M.J_cm();
    EXPECT_LT((ellipsoid_inertia(2, b.radii, Q) - J).norm(), 1e-14) << inertia;
  }
}

}  // namespace
}  // namespace soa::test
