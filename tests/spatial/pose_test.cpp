/// \file
/// Property tests of homogeneous transforms (lesson 1, slides 22-28): composition,
/// inverse and the action on points, against the 4x4 matrices and against frames given by
/// their poses in a common world frame.
#include <Eigen/LU>

#include "spatial_support.hpp"

namespace soa::test {
namespace {

template <class S>
class rotation_Pose : public ::testing::Test {};
TYPED_TEST_SUITE(rotation_Pose, Scalars, ScalarNames);

template <class S>
PoseT<S> random_pose(Random<S>& rnd) {
  return PoseT<S>(rnd.rotation(), rnd.vec3());
}

/// The homogeneous coordinates [p; 1] of a point.
template <class S>
Eigen::Matrix<S, 4, 1> homogeneous(const Vec3<S>& p) {
  return Eigen::Matrix<S, 4, 1>(p.x(), p.y(), p.z(), S(1));
}

// ^A T_C = ^A T_B ^B T_C (slides 25-27): operator* is the 4x4 product, and associative.
TYPED_TEST(rotation_Pose, ComposeIsMatrixProduct) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("pose compose vs 4x4 product " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const PoseT<S> a = random_pose(rnd), b = random_pose(rnd), c = random_pose(rnd);
    worst.add(rel((a * b).matrix(), Mat4<S>(a.matrix() * b.matrix())), i);
    worst.add(rel(((a * b) * c).matrix(), (a * (b * c)).matrix()), i);
  }
  EXPECT_LE(worst.value(), tol<S>(16));
}

// ^A T_B^{-1} = ^B T_A (slide 24): inverse() is the 4x4 inverse, and T T^{-1} = T^{-1} T = I.
TYPED_TEST(rotation_Pose, InverseIsMatrixInverse) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("pose inverse vs 4x4 inverse " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const PoseT<S> a = random_pose(rnd);
    worst.add(rel(a.inverse().matrix(), Mat4<S>(a.matrix().inverse())), i);
    worst.add(rel((a * a.inverse()).matrix(), Mat4<S>::Identity()), i);
    worst.add(rel((a.inverse() * a).matrix(), Mat4<S>::Identity()), i);
  }
  EXPECT_LE(worst.value(), tol<S>(32));
}

// ^A p = ^A T_B ^B p (slide 28): apply() is the 4x4 acting on [p; 1], and applying a
// composition is applying its factors in turn.
TYPED_TEST(rotation_Pose, ApplyIsHomogeneousProduct) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("pose apply vs 4x4 on [p;1] " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const PoseT<S> a = random_pose(rnd), b = random_pose(rnd);
    const Vec3<S> p = rnd.vec3();
    const Eigen::Matrix<S, 4, 1> h = a.matrix() * homogeneous(p);
    worst.add(rel(a.apply(p), Vec3<S>(h.template head<3>())), i);
    worst.add(rel((a * b).apply(p), a.apply(b.apply(p))), i);
  }
  EXPECT_LE(worst.value(), tol<S>(16));
}

// Frames A, B, C and a point given in a world frame W: ^A T_B = ^W T_A^{-1} ^W T_B, built
// from the world poses (^A R_B = R_A* R_B, ^A l(A,B) = R_A*(o_B - o_A)). Then
// ^A T_B ^B T_C = ^A T_C, and the point's A coordinates are ^A T_B applied to its B ones.
TYPED_TEST(rotation_Pose, FramesComposeLikeTheirPoses) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("frames A,B,C from world poses " + scalar_name<S>());
  const auto relative = [](const PoseT<S>& W_A, const PoseT<S>& W_B) {
    return PoseT<S>(W_A.R().transpose() * W_B.R(), W_A.R().transpose() * (W_B.l() - W_A.l()));
  };
  const auto coordinates_in = [](const PoseT<S>& W_F, const Vec3<S>& p_W) {
    return Vec3<S>(W_F.R().transpose() * (p_W - W_F.l()));
  };
  for (int i = 0; i < kCases; ++i) {
    const PoseT<S> W_A = random_pose(rnd), W_B = random_pose(rnd), W_C = random_pose(rnd);
    const PoseT<S> A_B = relative(W_A, W_B), B_C = relative(W_B, W_C), A_C = relative(W_A, W_C);
    worst.add(rel((A_B * B_C).matrix(), A_C.matrix()), i);
    worst.add(rel(A_B.inverse().matrix(), relative(W_B, W_A).matrix()), i);
    const Vec3<S> p_W = rnd.vec3();
    worst.add(rel(A_B.apply(coordinates_in(W_B, p_W)), coordinates_in(W_A, p_W)), i);
  }
  EXPECT_LE(worst.value(), tol<S>(32));
}

}  // namespace
}  // namespace soa::test
