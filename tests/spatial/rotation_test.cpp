/// \file
/// Property tests of the attitude representations of lesson 1 (slides 15-20,
/// soa/rotation/*): conversions between every pair, agreement with an independent
/// implementation of the convention (Eigen's AngleAxis and Quaternion), composition,
/// exp/log, and the documented behaviour at every singularity: Gibbs/Cayley at
/// \f$\theta = \pi\f$, Euler angles at gimbal lock, the logarithm at \f$\theta \to 0\f$ and
/// \f$\theta \to \pi\f$, non-unit, zero and non-finite input.
#include <Eigen/LU>
#include <limits>
#include <tuple>

#include "spatial_support.hpp"

namespace soa::test {
namespace {

template <class S>
using Representations =
    std::tuple<UnitQuaternionT<S>, AxisAngleT<S>, GibbsT<S>, CayleyT<S>, EulerZYXT<S>>;

/// Calls \p f with a default value of each type of the tuple type \p Tuple.
template <class Tuple, class F>
void for_each_type(F&& f) {
  std::apply([&](auto... x) { (f(x), ...); }, Tuple{});
}

template <class S>
std::string name(const UnitQuaternionT<S>&) {
  return "quaternion";
}
template <class S>
std::string name(const AxisAngleT<S>&) {
  return "axis-angle";
}
template <class S>
std::string name(const GibbsT<S>&) {
  return "Gibbs";
}
template <class S>
std::string name(const CayleyT<S>&) {
  return "Cayley";
}
template <class S>
std::string name(const EulerZYXT<S>&) {
  return "Euler ZYX";
}

template <class S>
S pi() {
  return std::acos(S(-1));
}

/// A uniform random rotation away from the Gibbs/Cayley singularity: \f$|q_0| \ge
/// 4\sqrt\varepsilon\f$ (the documented band is \f$|q_0| < \sqrt\varepsilon\f$).
template <class S>
Mat3<S> regular_rotation(Random<S>& rnd) {
  for (;;) {
    const UnitQuaternionT<S> q(rnd.vec3(), rnd.normal());
    if (std::abs(q.q0()) >= S(4) * std::sqrt(eps<S>())) return q.matrix();
  }
}

/// How far \p R is from a rotation (orthonormality and determinant), infinite when the
/// library's is_rotation() refuses it at 32 epsilons.
template <class S>
double rotation_error(const Mat3<S>& R) {
  if (!is_rotation(R, S(32) * eps<S>())) return INFINITY;
  return std::max(double((R.transpose() * R - Mat3<S>::Identity()).cwiseAbs().maxCoeff()),
                  double(std::abs(R.determinant() - S(1))));
}

/// The difference of two angles, reduced to [-pi, pi].
template <class S>
S angle_difference(S a, S b) {
  return std::remainder(a - b, S(2) * pi<S>());
}

// ---------------------------------------------------------------------------------------
// Conversions: every pair, through the matrix (convention.hpp).

template <class S>
class rotation_Convert : public ::testing::Test {};
TYPED_TEST_SUITE(rotation_Convert, Scalars, ScalarNames);

// For every pair (From, To) of the five representations, convert<To>(From) names the same
// rotation as the matrix it started from, and every matrix produced is a rotation.
TYPED_TEST(rotation_Convert, EveryPairNamesTheSameRotation) {
  using S = TypeParam;
  Random<S> rnd;
  std::vector<Mat3<S>> Rs;
  for (int i = 0; i < kCases; ++i) Rs.push_back(regular_rotation(rnd));
  for_each_type<Representations<S>>([&](auto from_tag) {
    using From = decltype(from_tag);
    Worst worst("convert from " + name(from_tag) + " to all " + scalar_name<S>());
    Worst rotation("is_rotation after " + name(from_tag) + " " + scalar_name<S>());
    for (int i = 0; i < kCases; ++i) {
      const From from = From::from_matrix(Rs[i]);
      worst.add(rel(from.matrix(), Rs[i]), i);
      for_each_type<Representations<S>>([&](auto to_tag) {
        using To = decltype(to_tag);
        const Mat3<S> R = convert<To>(from).matrix();
        worst.add(rel(R, Rs[i]), i);
        rotation.add(rotation_error(R), i);
      });
    }
    EXPECT_LE(worst.value(), tol<S>(64)) << name(from_tag);
    EXPECT_LE(rotation.value(), tol<S>(32)) << name(from_tag);
  });
}

// Round trips of the parameters themselves, rep -> matrix -> rep, inside each
// representation's range: quaternion with q0 > 0, angle in (0, pi), any Gibbs and Cayley
// vector (relative to 1 + |g|^2, the conditioning of g = q/q0), Euler angles with the pitch
// 0.1 away from gimbal lock (error ~ eps / cos(pitch)).
TYPED_TEST(rotation_Convert, ParametersRoundTrip) {
  using S = TypeParam;
  Random<S> rnd;
  Worst quaternion("quaternion round trip " + scalar_name<S>());
  Worst axis_angle("axis-angle round trip " + scalar_name<S>());
  Worst gibbs("Gibbs/Cayley round trip " + scalar_name<S>());
  Worst euler("Euler ZYX round trip " + scalar_name<S>());
  const S p = pi<S>();
  for (int i = 0; i < kCases; ++i) {
    UnitQuaternionT<S> q(rnd.vec3(), rnd.normal());
    if (q.q0() < S(0)) q = UnitQuaternionT<S>(-q.q(), -q.q0());
    quaternion.add(rel(UnitQuaternionT<S>::from_matrix(q.matrix()).coeffs(), q.coeffs()), i);

    const AxisAngleT<S> a{rnd.unit3(), rnd.uniform(S(0.01), p - S(0.01))};
    const AxisAngleT<S> a2 = AxisAngleT<S>::from_matrix(a.matrix());
    axis_angle.add(rel(a2.rotation_vector(), a.rotation_vector()), i);

    const GibbsT<S> g{rnd.vec3()};
    const double cond = 1 + double(g.g.squaredNorm());
    gibbs.add(double((GibbsT<S>::from_matrix(g.matrix()).g - g.g).norm()) / cond, i);
    const CayleyT<S> c{S(2) * rnd.vec3()};
    const double cond_c = 1 + double(c.c.squaredNorm()) / 4;
    gibbs.add(double((CayleyT<S>::from_matrix(c.matrix()).c - c.c).norm()) / (2 * cond_c), i);

    const EulerZYXT<S> e{rnd.uniform(-p, p), rnd.uniform(-p / 2 + S(0.1), p / 2 - S(0.1)),
                         rnd.uniform(-p, p)};
    const EulerZYXT<S> e2 = EulerZYXT<S>::from_matrix(e.matrix());
    euler.add(std::abs(double(angle_difference(e2.yaw, e.yaw))), i);
    euler.add(std::abs(double(e2.pitch - e.pitch)), i);
    euler.add(std::abs(double(angle_difference(e2.roll, e.roll))), i);
  }
  EXPECT_LE(quaternion.value(), tol<S>(8));
  EXPECT_LE(axis_angle.value(), tol<S>(32));
  EXPECT_LE(gibbs.value(), tol<S>(32));
  EXPECT_LE(euler.value(), tol<S>(128));
}

// The convention against an independent implementation: Eigen's AngleAxis and Quaternion
// (active rotations, the same matrices as exp(theta n~) of slide 19), and the explicit
// R = cos(theta) I + (1 - cos(theta)) n n* + sin(theta) n~. Gibbs g and Cayley c name the
// rotation by 2 atan(|g|) = 2 atan(|c|/2) about g/|g|, Euler ZYX the product
// Rz(yaw) Ry(pitch) Rx(roll); the Cayley map is (I - c~/2)^{-1} (I + c~/2) (slide 18).
TYPED_TEST(rotation_Convert, AgreesWithIndependentConvention) {
  using S = TypeParam;
  using AA = Eigen::AngleAxis<S>;
  Random<S> rnd;
  Worst worst("representations vs Eigen/explicit " + scalar_name<S>());
  const S p = pi<S>();
  for (int i = 0; i < kCases; ++i) {
    const Vec3<S> n = rnd.unit3();
    const S theta = rnd.uniform(S(0), p);
    const Mat3<S> R_aa = AA(theta, n).toRotationMatrix();
    const Mat3<S> R_slide = std::cos(theta) * Mat3<S>::Identity() +
                            (S(1) - std::cos(theta)) * n * n.transpose() +
                            std::sin(theta) * tilde(n);
    worst.add(rel(AxisAngleT<S>{n, theta}.matrix(), R_aa), i);
    worst.add(rel(R_slide, R_aa), i);
    worst.add(rel(exp_so3<S>(theta * n), R_aa), i);

    const Vec3<S> v = rnd.vec3();
    const S w = rnd.normal();
    const UnitQuaternionT<S> q(v, w);
    const Eigen::Quaternion<S> qe(q.q0(), q.q().x(), q.q().y(), q.q().z());
    worst.add(rel(q.matrix(), qe.toRotationMatrix()), i);
    worst.add(rel(q.rotate(v), qe * v), i);

    const GibbsT<S> g{rnd.vec3()};
    worst.add(
        rel(g.matrix(), AA(S(2) * std::atan(g.g.norm()), g.g.normalized()).toRotationMatrix()), i);
    const Vec3<S> c = S(2) * rnd.vec3();
    const Mat3<S> C = tilde(c) / S(2);
    worst.add(
        rel(cayley(c), Mat3<S>((Mat3<S>::Identity() - C).inverse() * (Mat3<S>::Identity() + C))),
        i);
    worst.add(rel(CayleyT<S>{c}.matrix(),
                  AA(S(2) * std::atan(c.norm() / S(2)), c.normalized()).toRotationMatrix()),
              i);

    const EulerZYXT<S> e{rnd.uniform(-p, p), rnd.uniform(-p / 2, p / 2), rnd.uniform(-p, p)};
    const Mat3<S> R_e =
        (AA(e.yaw, Vec3<S>::UnitZ()) * AA(e.pitch, Vec3<S>::UnitY()) * AA(e.roll, Vec3<S>::UnitX()))
            .toRotationMatrix();
    worst.add(rel(e.matrix(), R_e), i);
  }
  EXPECT_LE(worst.value(), tol<S>(32));
}

// ---------------------------------------------------------------------------------------
// Composition and the exponential map.

template <class S>
class rotation_Compose : public ::testing::Test {};
TYPED_TEST_SUITE(rotation_Compose, Scalars, ScalarNames);

// R(a b) = R(a) R(b) (slide 15), R(a*) = R(a)*, rotate(x) = R x; and quaternions are
// associative.
TYPED_TEST(rotation_Compose, QuaternionProductIsMatrixProduct) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("R(a b) = R(a)R(b) " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const UnitQuaternionT<S> a(rnd.vec3(), rnd.normal()), b(rnd.vec3(), rnd.normal()),
        c(rnd.vec3(), rnd.normal());
    const Vec3<S> x = rnd.vec3();
    worst.add(rel((a * b).matrix(), Mat3<S>(a.matrix() * b.matrix())), i);
    worst.add(rel(a.conjugate().matrix(), Mat3<S>(a.matrix().transpose())), i);
    worst.add(rel(a.rotate(x), a.matrix() * x), i);
    worst.add(rel(((a * b) * c).coeffs(), (a * (b * c)).coeffs()), i);
    worst.add(rotation_error((a * b).matrix()), i);
  }
  EXPECT_LE(worst.value(), tol<S>(16));
}

// exp of rotation vectors (slide 19): exp_so3 and the quaternion exp name the same rotation;
// rotations about one axis add their angles, exp(s n~) exp(t n~) = exp((s+t) n~); the
// inverse is exp(-w~) = exp(w~)*; and R exp(w~) R* = exp((R w)~).
TYPED_TEST(rotation_Compose, ExponentialOfRotationVectors) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("exp of rotation vectors " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const Vec3<S> w = rnd.vec3(), n = rnd.unit3();
    const S s = rnd.uniform(S(-4), S(4)), t = rnd.uniform(S(-4), S(4));
    const Mat3<S> E = exp_so3<S>(w), R = rnd.rotation();
    worst.add(rel(UnitQuaternionT<S>::exp(w).matrix(), E), i);
    worst.add(rel(Mat3<S>(exp_so3<S>(s * n) * exp_so3<S>(t * n)), exp_so3<S>((s + t) * n)), i);
    worst.add(rel((UnitQuaternionT<S>::exp(s * n) * UnitQuaternionT<S>::exp(t * n)).matrix(),
                  exp_so3<S>((s + t) * n)),
              i);
    worst.add(rel(exp_so3<S>(-w), Mat3<S>(E.transpose())), i);
    worst.add(rel(Mat3<S>(R * E * R.transpose()), exp_so3<S>(R * w)), i);
    worst.add(rotation_error(E), i);
  }
  EXPECT_LE(worst.value(), tol<S>(32));
}

// log(exp(w)) = w for |w| < pi, exp(log(R)) = R for any R, for log_so3 and the quaternion
// log; log_so3 and the quaternion log agree.
TYPED_TEST(rotation_Compose, ExpLogRoundTrip) {
  using S = TypeParam;
  Random<S> rnd;
  Worst worst("exp/log round trip " + scalar_name<S>());
  for (int i = 0; i < kCases; ++i) {
    const Vec3<S> w = rnd.uniform(S(0), pi<S>() - S(0.01)) * rnd.unit3();
    const Mat3<S> R = rnd.rotation();
    worst.add(rel(log_so3<S>(exp_so3<S>(w)), w), i);
    worst.add(rel(UnitQuaternionT<S>::exp(w).log(), w), i);
    worst.add(rel(exp_so3<S>(log_so3<S>(R)), R), i);
    const UnitQuaternionT<S> q = UnitQuaternionT<S>::from_matrix(R);
    worst.add(rel(UnitQuaternionT<S>::exp(q.log()).matrix(), R), i);
    worst.add(rel(exp_so3<S>(q.log()), R), i);
  }
  EXPECT_LE(worst.value(), tol<S>(64));
}

// ---------------------------------------------------------------------------------------
// Singularities and refused input (double precision, the documented bands).

// Gibbs and Cayley at theta -> pi (gibbs.hpp): refused with soa::Error inside the band
// |q0| < sqrt(eps), finite and accurate just outside it. Just outside, g = q/q0 is
// |g| ~ 1/q0 and carries the inherent relative error ~ eps/q0 of the division (at most half
// the digits at the band's edge); the rotation it names is accurate to rounding.
TEST(rotation_Singular, GibbsAndCayleyNearPi) {
  Random<double> rnd;
  const double band = std::sqrt(eps<double>());
  Worst matrix("Gibbs/Cayley matrix just outside the band");
  Worst param("Gibbs vector error * q0 / eps just outside");
  for (const double k : {0.0, 0.25, 0.5, 0.9}) {
    for (int i = 0; i < kCases; ++i) {
      const double q0 = k * band;
      const UnitQuaternion q(std::sqrt(1 - q0 * q0) * rnd.unit3(), q0);
      ASSERT_THROW(Gibbs::from_quaternion(q), Error) << "q0 = " << q0;
      ASSERT_THROW(Gibbs::from_matrix(q.matrix()), Error) << "q0 = " << q0;
      ASSERT_THROW(Cayley::from_matrix(q.matrix()), Error) << "q0 = " << q0;
      ASSERT_THROW(cayley_inverse<double>(q.matrix()), Error) << "q0 = " << q0;
    }
  }
  for (const double k : {1.1, 2.0, 10.0, 1e3, 1e6}) {
    for (int i = 0; i < kCases; ++i) {
      const double q0 = k * band;
      const UnitQuaternion q(std::sqrt(1 - q0 * q0) * rnd.unit3(), q0);
      const Mat3<double> R = q.matrix();
      const Gibbs g_q = Gibbs::from_quaternion(q), g_R = Gibbs::from_matrix(R);
      const Cayley c_R = Cayley::from_matrix(R);
      ASSERT_TRUE(g_q.g.allFinite() && g_R.g.allFinite() && c_R.c.allFinite());
      matrix.add(rel(g_q.matrix(), R), i);
      matrix.add(rel(g_R.matrix(), R), i);
      matrix.add(rel(c_R.matrix(), R), i);
      const Vec3<double> g = q.q() / q.q0();
      param.add(rel(g_q.g, g) / eps<double>(), i);
      param.add((g_R.g - g).norm() / g.norm() * q0 / eps<double>(), i);
    }
  }
  // Exactly pi: R = exp(pi n~).
  for (int i = 0; i < kCases; ++i) {
    const Mat3<double> R = exp_so3<double>(pi<double>() * rnd.unit3());
    ASSERT_THROW(Gibbs::from_matrix(R), Error);
    ASSERT_THROW(Cayley::from_matrix(R), Error);
  }
  EXPECT_LE(matrix.value(), tol<double>(32));
  EXPECT_LE(param.value(), 16.0);
}

// Euler ZYX at gimbal lock (euler.hpp): at pitch = +-pi/2 (the nearest double) roll = 0 as
// documented and yaw carries the whole turn about the vertical; at pitch = +-pi/2 +- 1e-9
// and +- 1e-12 the individual angles are ill-conditioned, but the angles returned
// reconstruct R to rounding and the pitch itself is accurate (it is the well-conditioned
// one). Also 1e-6 as a control away from the lock.
TEST(rotation_Singular, EulerAtGimbalLock) {
  Random<double> rnd;
  const double p = pi<double>();
  Worst recon("Euler reconstruction at/near gimbal lock");
  Worst pitch("Euler pitch at/near gimbal lock");
  for (const double sign : {1.0, -1.0}) {
    for (const double offset : {0.0, 1e-12, -1e-12, 1e-9, -1e-9, 1e-6, -1e-6}) {
      for (int i = 0; i < kCases; ++i) {
        const EulerZYX e{rnd.uniform(-p, p), sign * p / 2 + offset, rnd.uniform(-p, p)};
        const Mat3<double> R = e.matrix();
        const EulerZYX f = EulerZYX::from_matrix(R);
        ASSERT_TRUE(std::isfinite(f.yaw) && std::isfinite(f.pitch) && std::isfinite(f.roll));
        if (offset == 0) {
          ASSERT_EQ(f.roll, 0.0) << "roll at lock, case " << i;
        }
        recon.add(rel(f.matrix(), R), i);
        // In range, pitch in [-pi/2, pi/2]: past the lock the same R has pitch mirrored.
        pitch.add(std::abs(f.pitch - sign * (p / 2 - std::abs(offset))), i);
      }
    }
  }
  EXPECT_LE(recon.value(), tol<double>(16));
  EXPECT_LE(pitch.value(), tol<double>(16));
}

// The logarithm at theta -> 0 (axis_angle.hpp): theta = 0, 1e-300, 1e-12, 1e-8 about
// random axes; log_so3, the quaternion log and AxisAngle::from_matrix are finite and
// accurate relative to theta (exactly 0 at theta = 0).
TEST(rotation_Singular, LogNearZero) {
  Random<double> rnd;
  Worst worst("log near theta = 0, relative to theta");
  for (const double theta : {0.0, 1e-300, 1e-12, 1e-8}) {
    for (int i = 0; i < kCases; ++i) {
      const Vec3<double> w = theta * rnd.unit3();
      const Mat3<double> R = exp_so3<double>(w);
      const Vec3<double> logs[] = {log_so3<double>(R), UnitQuaternion::exp(w).log(),
                                   UnitQuaternion::from_matrix(R).log(),
                                   AxisAngle::from_matrix(R).rotation_vector()};
      for (const Vec3<double>& l : logs) {
        ASSERT_TRUE(l.allFinite()) << "theta = " << theta;
        if (theta == 0) {
          ASSERT_EQ(l, Vec3<double>::Zero());
        } else {
          worst.add((l - w).norm() / theta, i);
        }
      }
    }
  }
  EXPECT_LE(worst.value(), tol<double>(8));
}

// The logarithm at theta -> pi (axis_angle.hpp): theta = pi (the nearest double, where
// either sign of the axis is the same rotation) and pi - 1e-12, pi - 1e-8 about random
// axes. The angle is accurate, the axis is +-n at pi and n below it, and exp(log R) = R.
TEST(rotation_Singular, LogNearPi) {
  Random<double> rnd;
  Worst worst("log near theta = pi");
  for (const double theta : {pi<double>(), pi<double>() - 1e-12, pi<double>() - 1e-8}) {
    for (int i = 0; i < kCases; ++i) {
      const Vec3<double> n = rnd.unit3();
      const Mat3<double> R = exp_so3<double>(theta * n);
      for (const Vec3<double>& l :
           {log_so3<double>(R), Vec3<double>(UnitQuaternion::from_matrix(R).log())}) {
        ASSERT_TRUE(l.allFinite());
        worst.add(rel(exp_so3<double>(l), R), i);
        worst.add(std::abs(l.norm() - theta), i);
        const double off = (l - theta * n).norm();
        worst.add(theta == pi<double>() ? std::min(off, (l + theta * n).norm()) : off, i);
      }
    }
  }
  EXPECT_LE(worst.value(), tol<double>(32));
}

// Non-unit quaternions are normalized (quaternion.hpp): any non-zero finite 4-vector, of
// any sign and scale, names the rotation of its direction; the result is unit to rounding.
// Scales from 1e-300 to 1e300, where the sum of squares would under- or overflow, and a
// subnormal quaternion.
TEST(rotation_Singular, QuaternionInputIsNormalized) {
  Random<double> rnd;
  Worst worst("non-unit quaternion normalized");
  for (int i = 0; i < kCases; ++i) {
    const Vec3<double> q = rnd.vec3();
    const double q0 = rnd.normal();
    const UnitQuaternion u(q, q0);
    const double sign = i % 2 == 0 ? 1.0 : -1.0;
    for (const double s : {std::pow(10.0, rnd.uniform(-3, 3)), 1e-300, 1e300}) {
      const UnitQuaternion v(sign * s * q, sign * s * q0);
      worst.add(std::abs(v.coeffs().norm() - 1), i);
      worst.add(rel(v.matrix(), u.matrix()), i);
    }
  }
  EXPECT_LE(worst.value(), tol<double>(8));
  // The smallest subnormal along x: the half turn about x.
  const Mat3<double> half_turn_x = Vec3<double>(1, -1, -1).asDiagonal();
  EXPECT_EQ(UnitQuaternion(Vec3<double>(5e-324, 0, 0), 0.0).matrix(), half_turn_x);
}

// Zero and non-finite quaternions are refused with soa::Error, and from_coeffs_checked
// refuses input whose norm is not 1 within its tolerance (and takes input that is).
TEST(rotation_Singular, QuaternionRefusesInvalidInput) {
  Random<double> rnd;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(UnitQuaternion(Vec3<double>::Zero(), 0.0), Error);
  EXPECT_THROW(UnitQuaternion(Vec3<double>(nan, 0, 0), 1.0), Error);
  EXPECT_THROW(UnitQuaternion(Vec3<double>::Zero(), nan), Error);
  EXPECT_THROW(UnitQuaternion(Vec3<double>(0, inf, 0), 1.0), Error);
  EXPECT_THROW(UnitQuaternion(Vec3<double>::Zero(), -inf), Error);
  const double unit_tol = 1e-9;
  for (int i = 0; i < kCases; ++i) {
    const UnitQuaternion u(rnd.vec3(), rnd.normal());
    const double off = rnd.uniform(2, 1e6) * unit_tol * (i % 2 == 0 ? 1 : -1);
    ASSERT_THROW(
        UnitQuaternion::from_coeffs_checked(u.q() * (1 + off), u.q0() * (1 + off), unit_tol),
        Error);
    const double small = rnd.uniform(-0.5, 0.5) * unit_tol;
    const UnitQuaternion v =
        UnitQuaternion::from_coeffs_checked(u.q() * (1 + small), u.q0() * (1 + small), unit_tol);
    ASSERT_LE(rel(v.coeffs(), u.coeffs()), tol<double>(4));
  }
  EXPECT_THROW(UnitQuaternion::from_coeffs_checked(Vec3<double>(nan, 0, 0), 1.0, 1e-9), Error);
}

// from_matrix of every representation, and log_so3, refuse a matrix with a NaN or an
// infinity in any entry (never a silent NaN).
TEST(rotation_Singular, FromMatrixRefusesNonFinite) {
  Random<double> rnd;
  const double bad[] = {std::numeric_limits<double>::quiet_NaN(),
                        std::numeric_limits<double>::infinity(),
                        -std::numeric_limits<double>::infinity()};
  for (int i = 0; i < kCases; ++i) {
    Mat3<double> R = rnd.rotation();
    R(i % 3, (i / 3) % 3) = bad[i % 3];
    ASSERT_THROW(UnitQuaternion::from_matrix(R), Error);
    ASSERT_THROW(AxisAngle::from_matrix(R), Error);
    ASSERT_THROW(Gibbs::from_matrix(R), Error);
    ASSERT_THROW(Cayley::from_matrix(R), Error);
    ASSERT_THROW(EulerZYX::from_matrix(R), Error);
    ASSERT_THROW(log_so3<double>(R), Error);
  }
  EXPECT_THROW(AxisAngle::from(Vec3<double>::Zero(), 1.0), Error);
  EXPECT_THROW(AxisAngle::from(Vec3<double>::UnitX(), bad[0]), Error);
}

}  // namespace
}  // namespace soa::test
