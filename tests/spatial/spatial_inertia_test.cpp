/// \file
/// Property tests of the spatial inertia (lesson 1, slides 64-77): the parallel axis
/// theorem, the centre-of-mass form, positive definiteness, and the invariance of kinetic
/// energy and the transformation of momentum between points of one body.
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "spatial_support.hpp"

namespace soa::test {
namespace {

template <class S>
class spatial_Inertia : public ::testing::Test {};
TYPED_TEST_SUITE(spatial_Inertia, Scalars, ScalarNames);

/// A random body about a point: its mass, inertia about the centre of mass and p(x) = l(x, C).
template <class S>
struct Body {
  S m;
  Vec3<S> p;
  Mat3<S> J_C;
};

template <class S>
Body<S> random_body(Random<S>& rnd) {
  const SpatialInertiaT<S> M = rnd.inertia();
  return {M.mass(), rnd.vec3(), M.J_cm()};
}

// M(C) = diag(J(C), m I) (slide 66, p = 0), exactly.
TYPED_TEST(spatial_Inertia, CenterOfMassFormIsBlockDiagonal) {
  using S = TypeParam;
  Random<S> rnd;
  for (int i = 0; i < kCases; ++i) {
    const Body<S> b = random_body(rnd);
    Mat6<S> expected = Mat6<S>::Zero();
    expected.template topLeftCorner<3, 3>() = b.J_C;
    expected.template bottomRightCorner<3, 3>() = b.m * Mat3<S>::Identity();
    ASSERT_EQ(SpatialInertiaT<S>::from_cm(b.m, Vec3<S>::Zero(), b.J_C).matrix(), expected)
        << "case " << i;
  }
}

// from_cm: J(x) = J(C) - m p~p~ (slide 66), checked against the classical statement of the
// parallel axis theorem, J(x) = J(C) + m (|p|^2 I - p p*); and M(x) = phi(x,C) M(C) phi*(x,C)
// with the coordinate-free phi(x,C) of l(x,C) = p. J_cm() and p() read the input back.
TYPED_TEST(spatial_Inertia, FromCmIsParallelAxis) {
  using S = TypeParam;
  Random<S> rnd;
  Worst classical("J(x) = J(C) + m(|p|^2 I - pp*) " + scalar_name<S>());
  Worst spatial6("M(x) = phi(x,C)M(C)phi*(x,C) " + scalar_name<S>());
  Worst back("J_cm(), p() read back " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const Body<S> b = random_body(rnd);
    const SpatialInertiaT<S> M_x = SpatialInertiaT<S>::from_cm(b.m, b.p, b.J_C);
    const Mat3<S> J_x =
        b.J_C + b.m * (b.p.squaredNorm() * Mat3<S>::Identity() - b.p * b.p.transpose());
    classical.add(rel(M_x.J(), J_x), i);
    const Mat6<S> P = PhiT<S>::translation(b.p).matrix();
    const Mat6<S> M_C = SpatialInertiaT<S>::from_cm(b.m, Vec3<S>::Zero(), b.J_C).matrix();
    spatial6.add(rel(M_x.matrix(), Mat6<S>(P * M_C * P.transpose())), i);
    // J_cm() subtracts m p~p~ again: the cancellation is relative to the size of J(x).
    back.add(double((M_x.J_cm() - b.J_C).norm()) / std::max(1.0, double(M_x.J().norm())), i);
    back.add(rel(M_x.p(), b.p), i);
  }
  EXPECT_LE(classical.value(), tol<S>(16));
  EXPECT_LE(spatial6.value(), tol<S>(32));
  EXPECT_LE(back.value(), tol<S>(32));
}

// transform(phi, M) == phi M phi* (slide 70) as 6x6 matrices, phi with rotation; and
// transform composes: phi(x,z) = phi(x,y) phi(y,z) moves M(z) to x in one or two steps,
// and back with phi^{-1}.
TYPED_TEST(spatial_Inertia, TransformIsPhiMPhiStar) {
  using S = TypeParam;
  Random<S> rnd;
  Worst matrix("transform(phi,M) = phi M phi* " + scalar_name<S>());
  Worst compose("transform composes and inverts " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const SpatialInertiaT<S> M = rnd.inertia();
    const PhiT<S> a = rnd.phi(), b = rnd.phi();
    const Mat6<S> P = a.matrix();
    matrix.add(rel(transform(a, M).matrix(), Mat6<S>(P * M.matrix() * P.transpose())), i);
    compose.add(rel(transform(a * b, M).matrix(), transform(a, transform(b, M)).matrix()), i);
    compose.add(rel(transform(a.inverse(), transform(a, M)).matrix(), M.matrix()), i);
  }
  EXPECT_LE(matrix.value(), tol<S>(64));
  EXPECT_LE(compose.value(), tol<S>(128));
}

// M(x) is symmetric positive definite about every point (slide 68): the stored form is
// symmetric to rounding, and its smallest eigenvalue is positive by a margin, the condition
// number lambda_max/lambda_min staying far below 1/eps (else rounding could make it
// indefinite). The worst condition number is reported.
TYPED_TEST(spatial_Inertia, SymmetricPositiveDefinite) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("condition number of M(x) " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const SpatialInertiaT<S> M = transform(rnd.phi(), rnd.inertia());
    const Mat6<S> m = M.matrix();
    ASSERT_LE(rel(m, Mat6<S>(m.transpose())), tol<S>(8)) << "case " << i;
    const Eigen::SelfAdjointEigenSolver<Mat6<S>> es(m);
    const S lo = es.eigenvalues().minCoeff(), hi = es.eigenvalues().maxCoeff();
    worst.add(lo > S(0) ? double(hi / lo) : INFINITY, i);
    ASSERT_EQ(m.llt().info(), Eigen::Success) << "case " << i;
  }
  EXPECT_LT(worst.value(), 1.0 / tol<S>(64));
}

// Kinetic energy 1/2 V*(x) M(x) V(x) is the same at every point (slide 72): M(y) =
// transform(phi(y,x), M(x)), V(y) = phi*(x,y) V(x). kinetic_energy() is also 1/2 V* M V
// with the 6x6.
TYPED_TEST(spatial_Inertia, KineticEnergyIsInvariant) {
  using S = TypeParam;
  Random<S> rnd;
  Worst invariant("1/2V*(x)M(x)V(x) = 1/2V*(y)M(y)V(y) " + scalar_name<S>());
  Worst matrix("kinetic_energy vs 1/2 V* M V " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const SpatialInertiaT<S> M_x = rnd.inertia();
    const PhiT<S> phi_xy = rnd.phi();
    const VelocityT<S> V_x = rnd.velocity(), V_y = phi_xy.transpose_apply(V_x);
    const SpatialInertiaT<S> M_y = transform(phi_xy.inverse(), M_x);
    const S E_x = M_x.kinetic_energy(V_x), E_y = M_y.kinetic_energy(V_y);
    // Relative to the magnitude of the terms of the sums, |M||V|^2.
    const double scale = std::max(1.0, double(M_x.matrix().norm() * V_x.vector().squaredNorm()));
    invariant.add(std::abs(double(E_x - E_y)) / scale, i);
    const S E_m = V_x.vector().dot(M_x.matrix() * V_x.vector()) / S(2);
    matrix.add(std::abs(double(E_x - E_m)) / scale, i);
  }
  EXPECT_LE(invariant.value(), tol<S>(64));
  EXPECT_LE(matrix.value(), tol<S>(16));
}

// Spatial momentum h(x) = M(x) V(x) moves like a force (slide 76): h(x) = phi(x,C) h(C),
// with V(C) = phi*(x,C) V(x). Coordinate-free phi(x,C) of p, and a CM frame rotated by Q
// relative to the body frame at x (then M(x) = transform(phi(x,C), M(C))). operator* is
// also M.matrix() * V.
TYPED_TEST(spatial_Inertia, MomentumMovesLikeForce) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("h(x) = phi(x,C)h(C) " + scalar_name<S>());
  Worst matrix("M*V vs matrix " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const Body<S> b = random_body(rnd);
    const SpatialInertiaT<S> M_C = SpatialInertiaT<S>::from_cm(b.m, Vec3<S>::Zero(), b.J_C);
    const PhiT<S> phi_xC = i % 2 == 0 ? PhiT<S>::translation(b.p) : PhiT<S>(rnd.rotation(), b.p);
    const SpatialInertiaT<S> M_x = transform(phi_xC, M_C);
    const VelocityT<S> V_x = rnd.velocity(), V_C = phi_xC.transpose_apply(V_x);
    worst.add(rel((M_x * V_x).vector(), phi_xC.apply(M_C * V_C).vector()), i);
    matrix.add(rel((M_x * V_x).vector(), M_x.matrix() * V_x.vector()), i);
    const AccelerationT<S> a = rnd.acceleration();
    matrix.add(rel((M_x * a).vector(), M_x.matrix() * a.vector()), i);
  }
  EXPECT_LE(worst.value(), tol<S>(64));
  EXPECT_LE(matrix.value(), tol<S>(16));
}

// Sum of inertias about one point (slide 74): the 6x6 of the sum is the sum of the 6x6s,
// transform() distributes over the sum, the zero inertia is neutral, and the mass centre
// of the sum is the mass-weighted mean (m1 p1 + m2 p2)/(m1 + m2).
TYPED_TEST(spatial_Inertia, SumOfInertias) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("sum of inertias " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const SpatialInertiaT<S> M1 = transform(rnd.phi(), rnd.inertia());
    const SpatialInertiaT<S> M2 = transform(rnd.phi(), rnd.inertia());
    const PhiT<S> phi = rnd.phi();
    const SpatialInertiaT<S> sum = M1 + M2;
    worst.add(rel(sum.matrix(), Mat6<S>(M1.matrix() + M2.matrix())), i);
    worst.add(rel(transform(phi, sum).matrix(),
                  Mat6<S>(transform(phi, M1).matrix() + transform(phi, M2).matrix())),
              i);
    worst.add(rel((SpatialInertiaT<S>() + M1).matrix(), M1.matrix()), i);
    const Vec3<S> p = (M1.mass() * M1.p() + M2.mass() * M2.p()) / (M1.mass() + M2.mass());
    worst.add(rel(sum.p(), p), i);
  }
  EXPECT_LE(worst.value(), tol<S>(64));
}

// from_cm refuses what is no body: a mass that is not positive, non-finite input, a J(C)
// that is not symmetric.
TEST(spatial_Inertia, FromCmRefusesInvalidBodies) {
  const Mat3<double> J = Vec3<double>(1, 2, 2.5).asDiagonal();
  const Vec3<double> p(0.1, 0.2, 0.3);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(SpatialInertia::from_cm(0.0, p, J), Error);
  EXPECT_THROW(SpatialInertia::from_cm(-1.0, p, J), Error);
  EXPECT_THROW(SpatialInertia::from_cm(nan, p, J), Error);
  EXPECT_THROW(SpatialInertia::from_cm(1.0, Vec3<double>(nan, 0, 0), J), Error);
  Mat3<double> J_inf = J;
  J_inf(1, 1) = std::numeric_limits<double>::infinity();
  EXPECT_THROW(SpatialInertia::from_cm(1.0, p, J_inf), Error);
  Mat3<double> J_asym = J;
  J_asym(0, 1) = 0.1;
  EXPECT_THROW(SpatialInertia::from_cm(1.0, p, J_asym), Error);
  EXPECT_NO_THROW(SpatialInertia::from_cm(1.0, p, J));
}

}  // namespace
}  // namespace soa::test
