/// \file
/// Property tests of lesson 1's spatial algebra: the rigid body transformation
/// \f$\phi(x,y)\f$ (slides 39-50), the duality of velocities and forces, the propagation
/// and reversal of spatial velocities checked against explicit frame kinematics
/// (slides 40-46), and the spatial cross products (slides 53-57).
///
/// Each test draws kCases random cases from the fixed seed, keeps the worst residual relative
/// to the size of the terms (rel()), and requires it below k machine epsilons of the
/// precision under test; k grows with the number of operations in the identity.
#include <Eigen/LU>

#include "frame_motion.hpp"
#include "spatial_support.hpp"

namespace soa::test {
namespace {

/// A world pose (attitude and origin) of a frame, from which the \f$\phi\f$ between two
/// frames is built explicitly: \f${}^x\phi(x,y)\f$ has \f${}^xR_y = R_x^* R_y\f$ and
/// \f${}^x l(x,y) = R_x^*(o_y - o_x)\f$.
template <class S>
struct Frame {
  Mat3<S> R;
  Vec3<S> o;
};

template <class S>
Frame<S> random_frame(Random<S>& rnd) {
  return {rnd.rotation(), rnd.vec3()};
}

template <class S>
PhiT<S> phi_between(const Frame<S>& x, const Frame<S>& y) {
  return PhiT<S>(x.R.transpose() * y.R, x.R.transpose() * (y.o - x.o));
}

/// A random \f$\phi\f$: coordinate-free (a pure translation, slide 39) for even cases, with
/// rotation (slide 43) for odd ones.
template <class S>
PhiT<S> mixed_phi(Random<S>& rnd, int i) {
  return i % 2 == 0 ? PhiT<S>::translation(rnd.vec3()) : rnd.phi();
}

// ---------------------------------------------------------------------------------------
// phi(x, y): slides 39-50.

template <class S>
class spatial_Phi : public ::testing::Test {};
TYPED_TEST_SUITE(spatial_Phi, Scalars, ScalarNames);

// phi(x,x) = I (slide 44): the default phi, and phi(x,y) phi(y,x) in both orders.
TYPED_TEST(spatial_Phi, IdentityAtOnePoint) {
  using S = TypeParam;
  Random<S> rnd;
  EXPECT_EQ(PhiT<S>().matrix(), (Mat6<S>::Identity()));
  Worst worst("phi(x,y)phi(y,x) = I " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const PhiT<S> phi = mixed_phi(rnd, i);
    worst.add(rel((phi * phi.inverse()).matrix(), Mat6<S>::Identity()), i);
    worst.add(rel((phi.inverse() * phi).matrix(), Mat6<S>::Identity()), i);
  }
  EXPECT_LE(worst.value(), tol<S>(16));
}

// phi(x,z) = phi(x,y) phi(y,z) (slide 45): operator* against the 6x6 product.
TYPED_TEST(spatial_Phi, ProductIsMatrixProduct) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("phi product vs matrix product " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const PhiT<S> a = mixed_phi(rnd, i), b = mixed_phi(rnd, i / 2);
    worst.add(rel((a * b).matrix(), a.matrix() * b.matrix()), i);
  }
  EXPECT_LE(worst.value(), tol<S>(16));
}

// phi(x,z) = phi(x,y) phi(y,z) for three frames given by their world poses: the product
// of the two pairwise phi's is the phi of the outer pair. Coordinate-free, this is
// l(x,y) + l(y,z) = l(x,z) (slide 45).
TYPED_TEST(spatial_Phi, ProductChainsThreeFrames) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("phi(x,y)phi(y,z) = phi(x,z) " + scalar_name<S>());
  Worst free("coordinate-free phi product " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const Frame<S> x = random_frame(rnd), y = random_frame(rnd), z = random_frame(rnd);
    worst.add(rel((phi_between(x, y) * phi_between(y, z)).matrix(), phi_between(x, z).matrix()), i);
    const Vec3<S> l_xy = rnd.vec3(), l_yz = rnd.vec3();
    free.add(rel((PhiT<S>::translation(l_xy) * PhiT<S>::translation(l_yz)).matrix(),
                 PhiT<S>::translation(Vec3<S>(l_xy + l_yz)).matrix()),
             i);
  }
  EXPECT_LE(worst.value(), tol<S>(32));
  EXPECT_LE(free.value(), tol<S>(4));
}

// phi^{-1}(x,y) = phi(y,x) (slide 44): inverse() against the inverse of the 6x6, and
// against the phi built from the reversed pair of frames.
TYPED_TEST(spatial_Phi, InverseIsReversedPair) {
  using S = TypeParam;
  Random<S> rnd;
  Worst matrix("phi inverse vs matrix inverse " + scalar_name<S>());
  Worst frames("phi^-1(x,y) = phi(y,x) " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const PhiT<S> phi = mixed_phi(rnd, i);
    matrix.add(rel(phi.inverse().matrix(), Mat6<S>(phi.matrix().inverse())), i);
    const Frame<S> x = random_frame(rnd), y = random_frame(rnd);
    frames.add(rel(phi_between(x, y).inverse().matrix(), phi_between(y, x).matrix()), i);
  }
  EXPECT_LE(matrix.value(), tol<S>(64));
  EXPECT_LE(frames.value(), tol<S>(32));
}

// apply() is phi times a force-kind vector, transpose_apply() is phi* times a motion-kind
// vector (slides 41, 49, 50), against the 6x6.
TYPED_TEST(spatial_Phi, ApplyAgreesWithMatrix) {
  using S = TypeParam;
  Random<S> rnd;
  Worst force("phi f = matrix * f " + scalar_name<S>());
  Worst motion("phi* V = matrix^T * V " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const PhiT<S> phi = mixed_phi(rnd, i);
    const Mat6<S> P = phi.matrix();
    const ForceT<S> f = rnd.force();
    const MomentumT<S> h = spatial<MomentumKind>(rnd.force().vector());
    const VelocityT<S> V = rnd.velocity();
    const AccelerationT<S> a = rnd.acceleration();
    force.add(rel(phi.apply(f).vector(), P * f.vector()), i);
    force.add(rel(phi.apply(h).vector(), P * h.vector()), i);
    motion.add(rel(phi.transpose_apply(V).vector(), P.transpose() * V.vector()), i);
    motion.add(rel(phi.transpose_apply(a).vector(), P.transpose() * a.vector()), i);
  }
  EXPECT_LE(force.value(), tol<S>(16));
  EXPECT_LE(motion.value(), tol<S>(16));
}

// The coordinate-free phi moves moments and velocities by the lever arm (slides 40, 48):
// N(x) = N(y) + l(x,y) x F(y), F(x) = F(y); and v(y) = v(x) + omega x l(x,y).
TYPED_TEST(spatial_Phi, TranslationIsTheLeverArm) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("lever arm of phi and phi* " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const Vec3<S> l = rnd.vec3(), N = rnd.vec3(), F = rnd.vec3(), w = rnd.vec3(), v = rnd.vec3();
    const PhiT<S> phi = PhiT<S>::translation(l);
    worst.add(rel(phi.apply(ForceT<S>(N, F)).vector(), ForceT<S>(N + l.cross(F), F).vector()), i);
    worst.add(rel(phi.transpose_apply(VelocityT<S>(w, v)).vector(),
                  VelocityT<S>(w, v + w.cross(l)).vector()),
              i);
  }
  EXPECT_LE(worst.value(), tol<S>(8));
}

// Duality (slide 50): with f(x) = phi(x,y) f(y) and V(y) = phi*(x,y) V(x), the power is the
// same at both points, f*(x) V(x) = f*(y) V(y). Relative to |f||V|.
TYPED_TEST(spatial_Phi, PowerIsInvariant) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("f*(x)V(x) = f*(y)V(y) " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const PhiT<S> phi = mixed_phi(rnd, i);
    const ForceT<S> f_y = rnd.force();
    const VelocityT<S> V_x = rnd.velocity();
    const ForceT<S> f_x = phi.apply(f_y);
    const VelocityT<S> V_y = phi.transpose_apply(V_x);
    const double scale = std::max({1.0, double(f_x.vector().norm() * V_x.vector().norm()),
                                   double(f_y.vector().norm() * V_y.vector().norm())});
    worst.add(std::abs(double(dot(f_x, V_x) - dot(f_y, V_y))) / scale, i);
  }
  EXPECT_LE(worst.value(), tol<S>(16));
}

// ---------------------------------------------------------------------------------------
// Velocities of frames: slides 40-46, against explicit kinematics (frame_motion.hpp).

// V(A,C) = phi*(B,C) V(A,B) + V(B,C) (slide 42). The left side is differentiated directly
// from C's attitude R_AB R_BC and origin l(A,B) + R_AB l(B,C); the right side uses the
// library's phi*. Coordinate-free (all in A), and with rotations (each velocity in the
// coordinates of its frame, phi*(B,C) taking B coordinates to C coordinates).
TEST(spatial_Kinematics, VelocityAccumulationMatchesFrameMotion) {
  Random<double> rnd;
  Worst free("V(A,C) accumulation, coordinate-free");
  Worst frames("V(A,C) accumulation, frame coordinates");
  for (int i = 0; i < kCases; ++i) {
    const ThreeFrames motion = ThreeFrames::random(rnd);
    const ThreeFrames::Snapshot s = motion.at(rnd.uniform(0, 5));
    const Velocity V_AC = Phi::translation(s.l_BC).transpose_apply(s.V_AB) + s.V_BC;
    free.add(rel(V_AC.vector(), s.V_AC.vector()), i);
    // In frame coordinates: B-coordinates of V(A,B), C-coordinates of V(B,C) and V(A,C).
    const Mat3<double> R_AC = s.R_AB * s.R_BC;
    const Phi phi_BC(s.R_BC, s.R_AB.transpose() * s.l_BC);
    const Velocity C_V_AC =
        phi_BC.transpose_apply(rotated(Mat3<double>(s.R_AB.transpose()), s.V_AB)) +
        rotated(Mat3<double>(R_AC.transpose()), s.V_BC);
    frames.add(rel(C_V_AC.vector(), rotated(Mat3<double>(R_AC.transpose()), s.V_AC).vector()), i);
  }
  EXPECT_LE(free.value(), tol<double>(32));
  EXPECT_LE(frames.value(), tol<double>(32));
}

// V(y,x) = -phi*(y,x) V(x,y) (slide 46), for x = A, y = B: V(B,A) is differentiated
// directly from A's attitude R_AB* and origin l(B,A) = -R_AB* l(A,B) seen from B.
TEST(spatial_Kinematics, VelocityReversalMatchesFrameMotion) {
  Random<double> rnd;
  Worst free("V(B,A) reversal, coordinate-free");
  Worst frames("V(B,A) reversal, frame coordinates");
  for (int i = 0; i < kCases; ++i) {
    const ThreeFrames motion = ThreeFrames::random(rnd);
    const ThreeFrames::Snapshot s = motion.at(rnd.uniform(0, 5));
    free.add(rel((-Phi::translation(-s.l_AB).transpose_apply(s.V_AB)).vector(), s.V_BA.vector()),
             i);
    // phi(B,A) with B's coordinates on the left: ^B R_A = R_AB*, ^B l(B,A) = -R_AB* l(A,B).
    const Mat3<double> Rt = s.R_AB.transpose();
    const Phi phi_BA(Rt, -Rt * s.l_AB);
    frames.add(rel((-phi_BA.transpose_apply(rotated(Rt, s.V_AB))).vector(), s.V_BA.vector()), i);
  }
  EXPECT_LE(free.value(), tol<double>(32));
  EXPECT_LE(frames.value(), tol<double>(32));
}

// ---------------------------------------------------------------------------------------
// Spatial cross products: slides 53-55.

template <class S>
class spatial_CrossProduct : public ::testing::Test {};
TYPED_TEST_SUITE(spatial_CrossProduct, Scalars, ScalarNames);

// The block forms of slides 53 and 55, built here from the 3x3 tilde: X~ = [x~ 0; y~ x~],
// X¯ = [x~ y~; 0 x~] = -(X~)*.
TYPED_TEST(spatial_CrossProduct, BlockForms) {
  using S = TypeParam;
  Random<S> rnd;
  for (int i = 0; i < kCases; ++i) {
    const Vec3<S> x = rnd.vec3(), y = rnd.vec3();
    const VelocityT<S> X(x, y);
    Mat6<S> T = Mat6<S>::Zero(), B = Mat6<S>::Zero();
    T << tilde(x), Mat3<S>::Zero(), tilde(y), tilde(x);
    B << tilde(x), tilde(y), Mat3<S>::Zero(), tilde(x);
    ASSERT_EQ(tilde(X), T) << "case " << i;
    ASSERT_EQ(bar(X), B) << "case " << i;
    ASSERT_EQ(bar(X), Mat6<S>(-tilde(X).transpose())) << "case " << i;
  }
}

// cross() and cross_bar() apply the matrices tilde() and bar() without forming them.
TYPED_TEST(spatial_CrossProduct, AgreesWithMatrices) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("cross/cross_bar vs tilde/bar " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const VelocityT<S> X = rnd.velocity(), Y = rnd.velocity();
    const ForceT<S> f = rnd.force();
    worst.add(rel(cross(X, Y).vector(), tilde(X) * Y.vector()), i);
    worst.add(rel(cross_bar(X, f).vector(), bar(X) * f.vector()), i);
  }
  EXPECT_LE(worst.value(), tol<S>(8));
}

// X~ X = 0 and X~ Y = -Y~ X (slide 54).
TYPED_TEST(spatial_CrossProduct, SkewSymmetry) {
  using S = TypeParam;
  Random<S> rnd;
  Worst self("X~X = 0 " + scalar_name<S>());
  Worst skew("X~Y = -Y~X " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const VelocityT<S> X = rnd.velocity(), Y = rnd.velocity();
    const double n = std::max(1.0, double(X.vector().squaredNorm()));
    self.add(double(cross(X, X).vector().norm()) / n, i);
    skew.add(rel(cross(X, Y).vector(), Vec6<S>(-cross(Y, X).vector())), i);
  }
  EXPECT_LE(self.value(), tol<S>(4));
  EXPECT_LE(skew.value(), tol<S>(4));
}

// Jacobi (slide 54): X~(Y~Z) + Y~(Z~X) + Z~(X~Y) = 0, relative to |X||Y||Z|.
TYPED_TEST(spatial_CrossProduct, JacobiIdentity) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("Jacobi identity " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const VelocityT<S> X = rnd.velocity(), Y = rnd.velocity(), Z = rnd.velocity();
    const Vec6<S> sum =
        (cross(X, cross(Y, Z)) + cross(Y, cross(Z, X)) + cross(Z, cross(X, Y))).vector();
    const double n =
        std::max(1.0, double(X.vector().norm() * Y.vector().norm() * Z.vector().norm()));
    worst.add(double(sum.norm()) / n, i);
  }
  EXPECT_LE(worst.value(), tol<S>(16));
}

// Commutator (slide 54): (X~Y)~ = X~Y~ - Y~X~.
TYPED_TEST(spatial_CrossProduct, CommutatorIsTildeOfCross) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("(X~Y)~ = X~Y~ - Y~X~ " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const VelocityT<S> X = rnd.velocity(), Y = rnd.velocity();
    worst.add(rel(tilde(cross(X, Y)), Mat6<S>(tilde(X) * tilde(Y) - tilde(Y) * tilde(X))), i);
  }
  EXPECT_LE(worst.value(), tol<S>(16));
}

// X¯ = -(X~)*: the force cross product is minus the adjoint of the motion one, so
// (X¯ f)* Y = -f* (X~ Y) (slide 55).
TYPED_TEST(spatial_CrossProduct, BarIsMinusTildeAdjoint) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("(X-bar f)*Y = -f*(X~Y) " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const VelocityT<S> X = rnd.velocity(), Y = rnd.velocity();
    const ForceT<S> f = rnd.force();
    const double n =
        std::max(1.0, double(X.vector().norm() * Y.vector().norm() * f.vector().norm()));
    worst.add(std::abs(double(dot(cross_bar(X, f), Y) + dot(f, cross(X, Y)))) / n, i);
  }
  EXPECT_LE(worst.value(), tol<S>(16));
}

// ---------------------------------------------------------------------------------------
// phi and the spatial cross products: slides 56-57.

template <class S>
class spatial_PhiCross : public ::testing::Test {};
TYPED_TEST_SUITE(spatial_PhiCross, Scalars, ScalarNames);

// Slide 56, for points x, y of one body and V(y) = phi*(x,y) V(x):
// phi*(x,y) V~(x) = V~(y) phi*(x,y). Coordinate-free (even cases) and with rotation (odd).
TYPED_TEST(spatial_PhiCross, Slide56_PhiStarVTildeIsVTildePhiStar) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("phi*(x,y)V~(x) = V~(y)phi*(x,y) " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const PhiT<S> phi = mixed_phi(rnd, i);
    const VelocityT<S> V_x = rnd.velocity(), V_y = phi.transpose_apply(V_x);
    const Mat6<S> Pt = phi.matrix().transpose();
    worst.add(rel(Mat6<S>(Pt * tilde(V_x)), Mat6<S>(tilde(V_y) * Pt)), i);
  }
  EXPECT_LE(worst.value(), tol<S>(32));
}

// Slide 56: V¯(x) phi(x,y) = phi(x,y) V¯(y), for V(y) = phi*(x,y) V(x).
TYPED_TEST(spatial_PhiCross, Slide56_VBarPhiIsPhiVBar) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("V-bar(x)phi(x,y) = phi(x,y)V-bar(y) " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const PhiT<S> phi = mixed_phi(rnd, i);
    const VelocityT<S> V_x = rnd.velocity(), V_y = phi.transpose_apply(V_x);
    const Mat6<S> P = phi.matrix();
    worst.add(rel(Mat6<S>(bar(V_x) * P), Mat6<S>(P * bar(V_y))), i);
  }
  EXPECT_LE(worst.value(), tol<S>(32));
}

// Slide 57, as it holds numerically for ANY motion vector X (not only the body's velocity):
// [phi*(x,y) X]~ = phi*(x,y) X~ phi*(y,x), i.e. phi* is a conjugation of the cross product
// (the adjoint action of SE(3), slide 63). Slide 56 is the case X = V(x).
TYPED_TEST(spatial_PhiCross, Slide57_TildeOfPhiStarXIsPhiStarXTildePhiStarInverse) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("[phi*X]~ = phi*(x,y) X~ phi*(y,x) " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const PhiT<S> phi = mixed_phi(rnd, i);
    const VelocityT<S> X = rnd.velocity();
    const Mat6<S> Pt = phi.matrix().transpose(), Pt_inv = phi.inverse().matrix().transpose();
    worst.add(rel(tilde(phi.transpose_apply(X)), Mat6<S>(Pt * tilde(X) * Pt_inv)), i);
  }
  EXPECT_LE(worst.value(), tol<S>(64));
}

// Slide 57, the force form: [phi*(x,y) X]¯ = phi(y,x) X¯ phi(x,y).
TYPED_TEST(spatial_PhiCross, Slide57_BarOfPhiStarXIsPhiInverseXBarPhi) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("[phi*X]-bar = phi(y,x) X-bar phi(x,y) " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const PhiT<S> phi = mixed_phi(rnd, i);
    const VelocityT<S> X = rnd.velocity();
    const Mat6<S> P = phi.matrix(), P_inv = phi.inverse().matrix();
    worst.add(rel(bar(phi.transpose_apply(X)), Mat6<S>(P_inv * bar(X) * P)), i);
  }
  EXPECT_LE(worst.value(), tol<S>(64));
}

// The same two identities applied to vectors, without 6x6 matrices: motion cross products
// move with phi*, force cross products with phi,
// phi*(X~Y) = (phi*X)~(phi*Y) and phi(x,y) [(phi*X)¯ f(y)] = X¯ (phi(x,y) f(y)).
TYPED_TEST(spatial_PhiCross, Slide57_CrossProductsMoveWithPhi) {
  using S = TypeParam;
  Random<S> rnd;
  Worst motion("phi*(X~Y) = (phi*X)~(phi*Y) " + scalar_name<S>());
  Worst force("phi((phi*X)-bar f) = X-bar(phi f) " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const PhiT<S> phi = mixed_phi(rnd, i);
    const VelocityT<S> X = rnd.velocity(), Y = rnd.velocity();
    const ForceT<S> f_y = rnd.force();
    motion.add(rel(phi.transpose_apply(cross(X, Y)).vector(),
                   cross(phi.transpose_apply(X), phi.transpose_apply(Y)).vector()),
               i);
    force.add(rel(phi.apply(cross_bar(phi.transpose_apply(X), f_y)).vector(),
                  cross_bar(X, phi.apply(f_y)).vector()),
              i);
  }
  EXPECT_LE(motion.value(), tol<S>(64));
  EXPECT_LE(force.value(), tol<S>(64));
}

// What does NOT hold (the OCR of slide 57 is ambiguous about phi versus phi*): phi itself,
// acting on a motion vector, is no conjugation, [phi X]~ != phi X~ phi^{-1} once l != 0.
// The residual is of the order of |l||X|, far from rounding.
TYPED_TEST(spatial_PhiCross, Slide57_PhiWithoutStarIsNoConjugation) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("[phi X]~ vs phi X~ phi^-1 (must differ) " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const PhiT<S> phi = mixed_phi(rnd, i);
    const VelocityT<S> X = rnd.velocity();
    const Mat6<S> P = phi.matrix();
    const VelocityT<S> PX = spatial<VelocityKind>(Vec6<S>(P * X.vector()));
    worst.add(rel(tilde(PX), Mat6<S>(P * tilde(X) * phi.inverse().matrix())), i);
  }
  EXPECT_GT(worst.value(), 0.1);
}

}  // namespace
}  // namespace soa::test
