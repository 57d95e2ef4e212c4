// Lesson 1 exercise tests (spatial notation): each exercise of
// exercises/01-spatial-notation/exercises.hpp against the library, and against a second formulation
// (the 6x6 matrices, an identity, a round trip), on soa::test::kCases random cases from the fixed
// seed. Each check names its quantity, and its catalogue of classic mistakes is computed from the
// reference (tests/support/exercise_check.hpp). The cases vary the features the symptoms need:
// phi(x,y) with and without a rotation and an offset, bodies with the centre of mass at the frame's
// origin or away from it, parts of a spatial vector that vanish. Built against the solutions
// (ctest), the students' exercises (make exercises) and the solutions with planted mistakes (the
// "planted mistakes" blocks, tests/exercises/plant.cmake).
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "exercise_check.hpp"
#include "exercises.hpp"
#include "property.hpp"

namespace {

using soa::test::Check;
using soa::test::code;
using soa::test::kCases;
using soa::test::Mistake;
using soa::test::Mistakes;
using soa::test::Naming;
using Random = soa::test::Random<double>;
using Vec3d = soa::Vec3<double>;
using Mat3d = soa::Mat3<double>;
using Vec6d = soa::Vec6<double>;
using Mat6d = soa::Mat6<double>;
using MatX = soa::MatX<double>;
using One = Eigen::Matrix<double, 1, 1>;

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = 3.14159265358979323846;

One one(double v) {
  return One::Constant(v);
}

// max(1, |e|): the scale of a result compared relative to its size, absolute near zero.
template <class D>
double size_of(const Eigen::MatrixBase<D>& e) {
  return std::max(1.0, double(e.norm()));
}

// The stacked 6-vector [a; b].
MatX six(const Vec3d& a, const Vec3d& b) {
  Vec6d v;
  v << a, b;
  return v;
}

// phi(x,y) whose features vary with the case: no rotation when i mod 4 = 1, no offset when
// i mod 5 = 2 (tags kRotated, kTranslated).
struct PhiCase {
  soa::Phi phi;
  unsigned tags = 0;
};
PhiCase draw_phi(Random& rnd, int i) {
  const Mat3d R = rnd.rotation();
  const Vec3d l = rnd.vec3();
  PhiCase c{soa::Phi(i % 4 == 1 ? Mat3d::Identity() : R, i % 5 == 2 ? Vec3d::Zero() : l)};
  if (i % 4 != 1) c.tags |= soa::test::kRotated;
  if (i % 5 != 2) c.tags |= soa::test::kTranslated;
  return c;
}

// A body whose centre of mass is at its frame's origin when i mod 3 = 0 (tag kOffsetCom
// otherwise).
struct BodyCase {
  soa::SpatialInertia M;
  unsigned tags = 0;
};
BodyCase draw_body(Random& rnd, int i) {
  const soa::SpatialInertia M = rnd.inertia();
  if (i % 3 == 0) return BodyCase{soa::SpatialInertia::from_cm(M.mass(), Vec3d::Zero(), M.J_cm())};
  return BodyCase{M, soa::test::kOffsetCom};
}

// ---- 1.1: f(x) = phi(x,y) f(y) from R and l (slides 43, 48-49) -----------------------------

Mistakes apply_phi_mistakes(const soa::Phi& phi, const soa::Force& f) {
  const Mat3d& R = phi.R();
  const Vec3d& l = phi.l();
  const Vec3d N = R * f.angular(), F = R * f.linear();
  const Vec3d Nt = R.transpose() * f.angular(), Ft = R.transpose() * f.linear();
  return Mistakes{
      {"transpose",
       "your result is phi*(x,y) f(y), the transpose: forces move with phi (slide 49), "
       "velocities with phi*",
       phi.matrix().transpose() * f.vector()},
      {"inverse",
       "your result is phi(y,x) f(y) = phi^-1(x,y) f(y): a force at y moves to x with phi(x,y) "
       "itself",
       phi.inverse().matrix() * f.vector()},
      {"sign", "your moment subtracts the offset's: N(x) = R N(y) + l x (R F(y)) (slide 48)",
       six(N - l.cross(F), F)},
      {"wrong frame",
       "your moment takes l x F(y) with F(y) still in y-coordinates: rotate it first, "
       "N(x) = R N(y) + l x (R F(y)); l = x l(x,y) is in x-coordinates",
       six(N + l.cross(f.linear()), F)},
      {"wrong frame",
       "your result is R (N(y) + l x F(y)): the offset l = x l(x,y) is already in x-coordinates, "
       "rotate the force first and then add l x F",
       six(R * (f.angular() + l.cross(f.linear())), F)},
      {"dropped term", "the moment of the offset force, l x F, is missing from your N(x)",
       six(N, F)},
      {"transpose",
       "your rotation is R*, the transpose: R = x R_y takes y-coordinates to x-coordinates",
       six(Nt + l.cross(Ft), Ft)},
  };
}

std::string apply_phi_code(const soa::Phi& phi, const soa::Force& f) {
  return code("phi_xy", phi) + code("f_y", f) +
         "soa::Force f_x = soa::ex01::apply_phi(phi_xy, f_y);\n";
}

// clang-format off
/* planted mistakes of 1.1
soa_plant(1.1 wrong-frame
  FIND [=[phi_xy.l().cross(F)]=]
  WRONG [=[phi_xy.l().cross(f_y.linear())]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(wrong frame\): your moment takes l x F\(y\) with F\(y\) still in y-coordinates]=])
soa_plant(1.1 moment-doubled
  FIND [=[N_y + offset_moment]=]
  WRONG [=[N_y + 2.0 * offset_moment]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[symptom: it fails only where the frames are offset: [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
*/
// clang-format on
TEST(Exercise1_1_ApplyPhi, MatchesPhiApply) {
  Random rnd;
  Check check("f(x) = phi(x,y) f(y)", 16 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const PhiCase c = draw_phi(rnd, i);
    const soa::Force f = rnd.force();
    const Vec6d ref = c.phi.apply(f).vector();
    check.add(
        i, soa::ex01::apply_phi(c.phi, f).vector(), ref, size_of(ref), c.tags,
        [&] { return apply_phi_code(c.phi, f); }, [&] { return apply_phi_mistakes(c.phi, f); },
        soa::test::spatial("f(x)"));
  }
}

TEST(Exercise1_1_ApplyPhi, MatchesThe6x6Matrix) {
  Random rnd(11);
  Check check("f(x) against the 6x6 phi(x,y).matrix() f(y)", 32 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const PhiCase c = draw_phi(rnd, i);
    const soa::Force f = rnd.force();
    const Vec6d ref = c.phi.matrix() * f.vector();
    check.add(
        i, soa::ex01::apply_phi(c.phi, f).vector(), ref, size_of(ref), c.tags,
        [&] { return apply_phi_code(c.phi, f); }, [&] { return apply_phi_mistakes(c.phi, f); },
        soa::test::spatial("f(x)"));
  }
}

TEST(Exercise1_1_ApplyPhi, PowerIsInvariant) {
  // f*(x) V(x) = f*(y) V(y) with V(y) = phi*(x,y) V(x) (slide 50).
  Random rnd(12);
  Check check("the power f*(x) V(x) = f*(y) V(y), V(y) = phi*(x,y) V(x)", 32 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const PhiCase c = draw_phi(rnd, i);
    const soa::Force f_y = rnd.force();
    const soa::Velocity V_x = rnd.velocity();
    const soa::Force f_x = soa::ex01::apply_phi(c.phi, f_y);
    const double expected = soa::dot(f_y, c.phi.transpose_apply(V_x));
    const double scale = std::max(1.0, c.phi.apply(f_y).vector().norm() * V_x.vector().norm());
    check.add(
        i, one(soa::dot(f_x, V_x)), one(expected), scale, c.tags,
        [&] { return apply_phi_code(c.phi, f_y) + code("V_x", V_x); },
        [&] {
          Mistakes out;
          for (Mistake& m : apply_phi_mistakes(c.phi, f_y))
            out.push_back(Mistake{m.kind, m.says, one(m.value.col(0).dot(V_x.vector()))});
          return out;
        });
  }
}

// ---- 1.2: the spatial cross product X~ Y (slide 53) ----------------------------------------

// A motion vector whose parts vanish now and then: x = 0 when i mod 4 = 1, y = 0 when
// i mod 5 = 2.
soa::Velocity draw_motion(Random& rnd, int i) {
  const Vec3d x = rnd.vec3(), y = rnd.vec3();
  return soa::Velocity(i % 4 == 1 ? Vec3d::Zero() : x, i % 5 == 2 ? Vec3d::Zero() : y);
}

Mistakes spatial_cross_mistakes(const soa::Velocity& X, const soa::Velocity& Y) {
  const Vec3d x = X.angular(), y = X.linear(), w = Y.angular(), v = Y.linear();
  return Mistakes{
      {"transpose",
       "your result is X_bar Y = [x x w + y x v; x x v], the cross product of forces (slide "
       "55): on motion vectors X~ = [x~ 0; y~ x~]",
       six(x.cross(w) + y.cross(v), x.cross(v))},
      {"transpose", "your result is X~* Y, the transpose of X~ = [x~ 0; y~ x~]",
       six(-x.cross(w) - y.cross(v), -x.cross(v))},
      soa::test::negated(soa::cross(X, Y).vector(),
                         "your result is Y~ X = -X~ Y: the order matters (X~ Y = -Y~ X, slide 54)"),
      {"dropped term", "the y~ w term of the linear part is missing: X~ Y = [x x w; y x w + x x v]",
       six(x.cross(w), x.cross(v))},
      {"sign", "your linear part has w x y: it is y~ w = y x w (plus x x v)",
       six(x.cross(w), w.cross(y) + x.cross(v))},
  };
}

std::string spatial_cross_code(const soa::Velocity& X, const soa::Velocity& Y) {
  return code("X", X) + code("Y", Y) + "soa::Acceleration XY = soa::ex01::spatial_cross(X, Y);\n";
}

// clang-format off
/* planted mistakes of 1.2
soa_plant(1.2 transpose
  FIND [=[Acceleration(x * w, y * w + x * v)]=]
  WRONG [=[Acceleration(x * w + y * v, x * v)]=]
  EXPECT [=[likely mistake \(transpose\): your result is X_bar Y]=])
*/
// clang-format on
TEST(Exercise1_2_SpatialCross, MatchesLibraryCross) {
  Random rnd;
  Check check("X~ Y, the spatial cross product", 8 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const soa::Velocity X = draw_motion(rnd, i), Y = rnd.velocity();
    const Vec6d ref = soa::cross(X, Y).vector();
    check.add(
        i, soa::ex01::spatial_cross(X, Y).vector(), ref, size_of(ref), 0,
        [&] { return spatial_cross_code(X, Y); }, [&] { return spatial_cross_mistakes(X, Y); },
        soa::test::spatial("X~ Y"));
  }
}

TEST(Exercise1_2_SpatialCross, MatchesThe6x6Tilde) {
  Random rnd(21);
  Check check("X~ Y against the 6x6 soa::tilde(X) Y", 16 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const soa::Velocity X = draw_motion(rnd, i), Y = rnd.velocity();
    const Vec6d ref = soa::tilde(X) * Y.vector();
    check.add(
        i, soa::ex01::spatial_cross(X, Y).vector(), ref, size_of(ref), 0,
        [&] { return spatial_cross_code(X, Y); }, [&] { return spatial_cross_mistakes(X, Y); },
        soa::test::spatial("X~ Y"));
  }
}

TEST(Exercise1_2_SpatialCross, IdentitiesOfSlide54) {
  // X~ X = 0 and X~ Y = -Y~ X, each to half the tolerance their sum had.
  Random rnd(22);
  Check self("X~ X = 0 (slide 54)", 4 * kEps), anti("X~ Y + Y~ X = 0 (slide 54)", 4 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const soa::Velocity X = draw_motion(rnd, i), Y = rnd.velocity();
    const double scale = std::max(1.0, X.vector().norm() * (X.vector().norm() + Y.vector().norm()));
    const Vec6d zero = Vec6d::Zero();
    auto inputs = [&] { return spatial_cross_code(X, Y); };
    self.add(i, soa::ex01::spatial_cross(X, X).vector(), zero, scale, 0, inputs, {},
             soa::test::spatial("X~ X"));
    anti.add(i, (soa::ex01::spatial_cross(X, Y) + soa::ex01::spatial_cross(Y, X)).vector(), zero,
             scale, 0, inputs, {}, soa::test::spatial("X~ Y + Y~ X"));
  }
}

// ---- 1.3: parallel axis theorem in (m, mp, J) form (slides 66, 70) -------------------------

// (m, h, J) of a spatial inertia as 13 numbers [m; h; J column by column], and of a 6x6
// [J h~; -h~ m I].
MatX numbers(const soa::SpatialInertia& M) {
  Eigen::Matrix<double, 13, 1> v;
  v << M.mass(), M.h(), M.J().reshaped();
  return v;
}
MatX numbers(const Mat6d& M) {
  Eigen::Matrix<double, 13, 1> v;
  v << M(3, 3), soa::vee<double>(M.topRightCorner<3, 3>()), M.topLeftCorner<3, 3>().reshaped();
  return v;
}
Naming inertia_naming(const std::string& sym) {
  return [sym](Eigen::Index i, Eigen::Index) {
    if (i == 0) return soa::test::EntryName{"m", "the mass m"};
    if (i < 4)
      return soa::test::EntryName{"h[" + std::to_string(i - 1) + "]",
                                  "h = m p(" + sym + "), the first moment"};
    const Eigen::Index k = i - 4;
    return soa::test::EntryName{"J(" + std::to_string(k % 3) + "," + std::to_string(k / 3) + ")",
                                "J(" + sym + "), the rotational inertia"};
  };
}

// M(x) from M(y) through C with one step changed: the catalogue of 1.3.
enum class Axis { Right, SignAtX, SignAtC, UnrotatedP, UnrotatedJ, TransposedR, NoShift };
MatX parallel_axis_variant(const soa::Phi& phi, const soa::SpatialInertia& M_y, Axis a) {
  const double m = M_y.mass();
  const Mat3d& R = phi.R();
  const Vec3d p_y = M_y.h() / m;
  const Mat3d P_y = soa::tilde(p_y);
  const Mat3d J_C = M_y.J() + (a == Axis::SignAtC ? -1.0 : 1.0) * m * P_y * P_y;
  const Vec3d p_x = phi.l() + (a == Axis::UnrotatedP ? p_y : Vec3d(R * p_y));
  const Mat3d P_x = soa::tilde(p_x);
  const Mat3d J_rot = a == Axis::UnrotatedJ    ? J_C
                      : a == Axis::TransposedR ? Mat3d(R.transpose() * J_C * R)
                                               : Mat3d(R * J_C * R.transpose());
  Mat3d J_x = J_rot + (a == Axis::SignAtX ? 1.0 : -1.0) * m * P_x * P_x;
  if (a == Axis::NoShift) J_x = R * M_y.J() * R.transpose();
  return numbers(soa::SpatialInertia(m, m * p_x, J_x));
}

Mistakes parallel_axis_mistakes(const soa::Phi& phi, const soa::SpatialInertia& M_y) {
  const Mat6d P = phi.matrix();
  return Mistakes{
      {"transpose",
       "your result is phi*(x,y) M(y) phi(x,y): phi and phi* swapped, M(x) = phi(x,y) M(y) "
       "phi*(x,y) (slide 70)",
       numbers(Mat6d(P.transpose() * M_y.matrix() * P))},
      {"inverse",
       "your result is M(y) moved the other way, phi(y,x) M(y) phi*(y,x): M(x) = phi(x,y) M(y) "
       "phi*(x,y)",
       numbers(soa::transform(phi.inverse(), M_y))},
      {"sign",
       "your J(x) adds m p~(x) p~(x): J(x) = J(C) - m p~ p~ (slide 66; -p~ p~ is positive "
       "semi-definite)",
       parallel_axis_variant(phi, M_y, Axis::SignAtX)},
      {"sign", "your J(C) subtracts m p~(y) p~(y): going back to C, J(C) = J(y) + m p~ p~",
       parallel_axis_variant(phi, M_y, Axis::SignAtC)},
      {"wrong frame", "your p(x) = l + p(y) adds p(y) in y-coordinates: p(x) = l(x,y) + R p(y)",
       parallel_axis_variant(phi, M_y, Axis::UnrotatedP)},
      {"wrong frame", "your J(C) is not rotated into x-coordinates: use R J(C) R*",
       parallel_axis_variant(phi, M_y, Axis::UnrotatedJ)},
      {"transpose", "your J(C) is rotated with R* J R: into x-coordinates it is R J(C) R*",
       parallel_axis_variant(phi, M_y, Axis::TransposedR)},
      {"dropped term",
       "your J(x) is R J(y) R*, only rotated: moving the point changes J (slide 66, through C)",
       parallel_axis_variant(phi, M_y, Axis::NoShift)},
  };
}

std::string parallel_axis_code(const soa::Phi& phi, const soa::SpatialInertia& M_y) {
  return code("phi_xy", phi) + code("M_y", M_y) +
         "soa::SpatialInertia M_x = soa::ex01::parallel_axis(phi_xy, M_y);\n";
}

// clang-format off
/* planted mistakes of 1.3
soa_plant(1.3 transpose
  FIND [=[R * J_C * R.transpose()]=]
  WRONG [=[R.transpose() * J_C * R]=] TYPE [=[Mat3<double>]=]
  EXPECT [=[likely mistake \(transpose\): your J\(C\) is rotated with R\* J R]=])
*/
// clang-format on
TEST(Exercise1_3_ParallelAxis, MatchesLibraryTransform) {
  Random rnd;
  Check check("M(x) = phi(x,y) M(y) phi*(x,y) as (m, m p(x), J(x))", 32 * kEps),
      mass("the mass m of M(x), unchanged", 32 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const PhiCase c = draw_phi(rnd, i);
    const BodyCase b = draw_body(rnd, i);
    const soa::SpatialInertia mine = soa::ex01::parallel_axis(c.phi, b.M);
    const soa::SpatialInertia ref = soa::transform(c.phi, b.M);
    auto inputs = [&] { return parallel_axis_code(c.phi, b.M); };
    mass.add(i, one(mine.mass()), one(ref.mass()), ref.mass(), c.tags | b.tags, inputs);
    check.add(
        i, numbers(mine), numbers(ref), std::max(1.0, b.M.matrix().norm()), c.tags | b.tags, inputs,
        [&] { return parallel_axis_mistakes(c.phi, b.M); }, inertia_naming("x"));
  }
}

TEST(Exercise1_3_ParallelAxis, MatchesThe6x6Product) {
  Random rnd(31);
  Check check("M(x) against the 6x6 product phi(x,y) M(y) phi*(x,y)", 32 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const PhiCase c = draw_phi(rnd, i);
    const BodyCase b = draw_body(rnd, i);
    const Mat6d P = c.phi.matrix();
    const Mat6d ref = P * b.M.matrix() * P.transpose();
    check.add(
        i, soa::ex01::parallel_axis(c.phi, b.M).matrix(), ref,
        std::max({1.0, b.M.matrix().norm(), ref.norm()}), c.tags | b.tags,
        [&] { return parallel_axis_code(c.phi, b.M); }, {}, soa::test::blocks6("M(x)"));
  }
}

TEST(Exercise1_3_ParallelAxis, ThereAndBackIsTheIdentity) {
  // phi(y,x) [phi(x,y) M(y) phi*(x,y)] phi*(y,x) = M(y).
  Random rnd(32);
  Check check("M(y) moved to x and back with phi(y,x) = phi^-1(x,y)", 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const PhiCase c = draw_phi(rnd, i);
    const BodyCase b = draw_body(rnd, i);
    const soa::SpatialInertia M_x = soa::ex01::parallel_axis(c.phi, b.M);
    const soa::SpatialInertia back = soa::ex01::parallel_axis(c.phi.inverse(), M_x);
    const double scale =
        std::max({1.0, soa::transform(c.phi, b.M).matrix().norm(), b.M.matrix().norm()});
    check.add(
        i, back.matrix(), b.M.matrix(), scale, c.tags | b.tags,
        [&] {
          return parallel_axis_code(c.phi, b.M) +
                 "soa::SpatialInertia back = soa::ex01::parallel_axis(phi_xy.inverse(), M_x);\n";
        },
        {}, soa::test::blocks6("M(y)"));
  }
}

// ---- 1.4: unit quaternion from axis-angle, vector part first (slide 19) --------------------

Mistakes quaternion_mistakes(const Vec3d& axis, double theta) {
  const Vec3d n = axis.normalized();
  const double s = std::sin(theta / 2), c = std::cos(theta / 2);
  Eigen::Vector4d half, scalar_first, raw;
  half << std::sin(theta) * n, std::cos(theta);
  scalar_first << c, s * n.x(), s * n.y(), s * n.z();
  raw << s * axis, c;
  return Mistakes{
      {"degrees", "your angle is read as degrees (theta pi / 180): theta is in radians already",
       soa::UnitQuaternion::exp(theta * kPi / 180 * n).coeffs()},
      {"half angle",
       "your quaternion is [sin(theta) n; cos(theta)]: it takes the half angle, [sin(theta/2) n; "
       "cos(theta/2)] (slide 19)",
       half},
      {"order",
       "your coefficients are scalar part first: the course stores [q; q0], vector part first "
       "(soa::UnitQuaternion(q, q0))",
       scalar_first},
      soa::test::negated(soa::UnitQuaternion::exp(theta * n).coeffs(),
                         "your quaternion is -q: the same rotation, but the statement asks for "
                         "[sin(theta/2) n; cos(theta/2)] itself (did you make q0 >= 0?)"),
      {"sign",
       "your quaternion is the conjugate [-q; q0], the inverse rotation: [sin(theta/2) n; "
       "cos(theta/2)]",
       soa::UnitQuaternion::exp(-theta * n).coeffs()},
      {"unnormalized axis",
       "your axis is not normalized: [sin(theta/2) n; cos(theta/2)] needs |n| = 1 (the "
       "quaternion's constructor then rescales all four numbers)",
       raw.normalized()},
  };
}

std::string quaternion_code(const Vec3d& axis, double theta) {
  return code("n", axis) + "double theta = " + soa::test::num(theta) +
         ";\nsoa::UnitQuaternion q = soa::ex01::quaternion_from_axis_angle(n, theta);\n";
}

// The first cases of 1.4: small, readable numbers (the simplest failing case is shown in
// full), axes not of unit length.
const Vec3d kSimpleAxis[] = {Vec3d(0, 0, 2), Vec3d(1, 0, 0), Vec3d(1, 2, 2), Vec3d(0, 3, 4)};
const double kSimpleTheta[] = {1.0, 0.5, -2.0, 3.0};

Naming quaternion_naming() {
  return [](Eigen::Index i, Eigen::Index) {
    return i < 3 ? soa::test::EntryName{"q[" + std::to_string(i) + "]",
                                        "the vector part q = sin(theta/2) n"}
                 : soa::test::EntryName{"q0", "the scalar part q0 = cos(theta/2)"};
  };
}

// clang-format off
/* planted mistakes of 1.4
soa_plant(1.4 degrees
  FIND [=[theta / 2]=]
  WRONG [=[theta * 3.14159265358979323846 / 360]=] TYPE [=[double]=]
  EXPECT [=[likely mistake \(degrees\): your angle is read as degrees.*case [0-3] \(the simplest that fails\) as code \(paste into a program\):[^(]*soa::Vec3<double> n = soa::Vec3<double>.[0-9], [0-9], [0-9].;[^(]*double theta = -?[0-9](\.5)?;]=])
*/
// clang-format on
TEST(Exercise1_4_QuaternionFromAxisAngle, MatchesLibraryExp) {
  Random rnd;
  Check check("the quaternion's coefficients [q; q0]", 16 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const Vec3d axis = i < 4 ? kSimpleAxis[i] : rnd.vec3();  // not of unit length
    const double theta = i < 4 ? kSimpleTheta[i] : rnd.uniform(-2 * kPi, 2 * kPi);
    const soa::UnitQuaternion q = soa::ex01::quaternion_from_axis_angle(axis, theta);
    const Eigen::Vector4d ref = soa::UnitQuaternion::exp(theta * axis.normalized()).coeffs();
    check.add(
        i, q.coeffs(), ref, size_of(ref), 0, [&] { return quaternion_code(axis, theta); },
        [&] { return quaternion_mistakes(axis, theta); }, quaternion_naming());
  }
}

TEST(Exercise1_4_QuaternionFromAxisAngle, MatrixIsTheRodriguesFormula) {
  Random rnd(41);
  Check check("the quaternion's rotation matrix against exp_so3 (Rodrigues)", 32 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const Vec3d axis = i < 4 ? kSimpleAxis[i] : rnd.vec3();
    const double theta = i < 4 ? kSimpleTheta[i] : rnd.uniform(-2 * kPi, 2 * kPi);
    const Mat3d R = soa::ex01::quaternion_from_axis_angle(axis, theta).matrix();
    const Mat3d ref = soa::exp_so3<double>(theta * axis.normalized());
    check.add(
        i, R, ref, size_of(ref), 0, [&] { return quaternion_code(axis, theta); },
        [&] {
          Mistakes out;
          for (Mistake& m : quaternion_mistakes(axis, theta))
            out.push_back(
                Mistake{m.kind, m.says,
                        soa::UnitQuaternion(m.value.col(0).head<3>(), m.value(3, 0)).matrix()});
          return out;
        });
  }
}

TEST(Exercise1_4_QuaternionFromAxisAngle, RefusesAZeroOrNonFiniteAxis) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(soa::ex01::quaternion_from_axis_angle(Vec3d::Zero(), 0.5), soa::Error)
      << "quaternion_from_axis_angle(n = 0, theta = 0.5) must throw soa::Error: a zero axis names "
         "no rotation";
  EXPECT_THROW(soa::ex01::quaternion_from_axis_angle(Vec3d(nan, 0, 1), 0.5), soa::Error)
      << "quaternion_from_axis_angle(n = (nan, 0, 1), theta = 0.5) must throw soa::Error";
  EXPECT_THROW(soa::ex01::quaternion_from_axis_angle(Vec3d(0, 0, 1), nan), soa::Error)
      << "quaternion_from_axis_angle(n = (0, 0, 1), theta = nan) must throw soa::Error";
}

// ---- 1.5: kinetic energy about a non-CM point (slides 67-73) -------------------------------

// A velocity with w = 0 when i mod 7 = 3 and v = 0 when i mod 6 = 4.
soa::Velocity draw_velocity(Random& rnd, int i) {
  const Vec3d w = rnd.vec3(), v = rnd.vec3();
  return soa::Velocity(i % 7 == 3 ? Vec3d::Zero() : w, i % 6 == 4 ? Vec3d::Zero() : v);
}

Mistakes kinetic_energy_mistakes(const soa::SpatialInertia& M, const soa::Velocity& V) {
  const Vec3d w = V.angular(), v = V.linear();
  const double rot = 0.5 * w.dot(M.J() * w), coupling = w.dot(M.h().cross(v)),
               lin = 0.5 * M.mass() * v.squaredNorm();
  return Mistakes{
      {"factor", "your energy is V* M V, twice T: T = 1/2 V* M V", one(2 * (rot + coupling + lin))},
      {"sign",
       "your coupling term has the wrong sign: it is + w . (h x v) (the blocks h~ and -h~ of "
       "slide 68)",
       one(rot - coupling + lin)},
      {"dropped term",
       "the term that couples w and v, w . (h x v), is missing (it vanishes only at the centre "
       "of mass)",
       one(rot + lin)},
      {"factor",
       "your coupling term is half what it should be: the two off-diagonal blocks give "
       "1/2 (w* h~ v - v* h~ w) = w . (h x v)",
       one(rot + 0.5 * coupling + lin)},
      {"wrong point",
       "your rotational term uses J(C): M_x.J() is already J(x), the inertia about x",
       one(0.5 * w.dot(M.J_cm() * w) + coupling + lin)},
      {soa::test::kMeasured, "the expected value with 1/2 w* J w taken without its 1/2",
       one(2 * rot + coupling + lin)},
      {soa::test::kMeasured, "the expected value with 1/2 m v* v taken without its 1/2",
       one(rot + coupling + 2 * lin)},
  };
}

std::string kinetic_energy_code(const soa::SpatialInertia& M, const soa::Velocity& V) {
  return code("M_x", M) + code("V_x", V) + "double T = soa::ex01::kinetic_energy(M_x, V_x);\n";
}

// clang-format off
/* planted mistakes of 1.5
soa_plant(1.5 dropped-coupling
  FIND [=[w.dot(h.cross(v))]=]
  WRONG [=[0.0]=] TYPE [=[double]=]
  EXPECT [=[likely mistake \(dropped term\): the term that couples w and v]=])
# Not in the catalogue: the 1/2 of the linear term left out. The report says what it
# measured (the variant the result equals; where it fails), and guesses no cause.
soa_plant(1.5 half-missing
  FIND [=[0.5 * M_x.mass() * v.squaredNorm()]=]
  WRONG [=[M_x.mass() * v.squaredNorm()]=] TYPE [=[double]=]
  EXPECT [=[T = 1/2 V\*\(x\) M\(x\) V\(x\), the kinetic energy: wrong in [0-9]+ of [0-9]+ cases.*symptom: in every failing case, your result matches the expected value with 1/2 m v\* v taken without its 1/2.*T about x = T about y \(slides 72-73\): wrong in [0-9]+ of [0-9]+ cases.*symptom: it fails only where the frames are offset: [0-9]+ of those [0-9]+ cases fail, and every other case passes]=]
  REJECT [=[offset l|is wrong|likely mistake]=])
*/
// clang-format on
TEST(Exercise1_5_KineticEnergy, MatchesLibrary) {
  Random rnd;
  Check check("T = 1/2 V*(x) M(x) V(x), the kinetic energy", 16 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const BodyCase b = draw_body(rnd, i);
    const soa::Velocity V = draw_velocity(rnd, i);
    const double scale = std::max(1.0, b.M.matrix().norm() * V.vector().squaredNorm());
    check.add(
        i, one(soa::ex01::kinetic_energy(b.M, V)), one(b.M.kinetic_energy(V)), scale, b.tags,
        [&] { return kinetic_energy_code(b.M, V); },
        [&] { return kinetic_energy_mistakes(b.M, V); });
  }
}

TEST(Exercise1_5_KineticEnergy, EqualsTheCentreOfMassForm) {
  // T = 1/2 w* J(C) w + 1/2 m v(C)* v(C), v(C) = v(x) + w x p(x) (slide 67).
  Random rnd(51);
  Check check("T against the centre-of-mass form 1/2 w* J(C) w + 1/2 m |v(C)|^2", 32 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const BodyCase b = draw_body(rnd, i);
    const soa::Velocity V = draw_velocity(rnd, i);
    const Vec3d w = V.angular();
    const Vec3d v_C = V.linear() + w.cross(b.M.p());
    const double ref = 0.5 * w.dot(b.M.J_cm() * w) + 0.5 * b.M.mass() * v_C.squaredNorm();
    const double scale = std::max(1.0, b.M.matrix().norm() * V.vector().squaredNorm());
    check.add(
        i, one(soa::ex01::kinetic_energy(b.M, V)), one(ref), scale, b.tags,
        [&] { return kinetic_energy_code(b.M, V); },
        [&] { return kinetic_energy_mistakes(b.M, V); });
  }
}

TEST(Exercise1_5_KineticEnergy, IsTheSameAboutEveryPoint) {
  // 1/2 V*(x) M(x) V(x) = 1/2 V*(y) M(y) V(y), V(y) = phi*(x,y) V(x) (slides 72-73).
  Random rnd(52);
  Check check("T about x = T about y (slides 72-73)", 32 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const BodyCase b = draw_body(rnd, i);
    const soa::Velocity V_x = draw_velocity(rnd, i);
    const PhiCase c = draw_phi(rnd, i);
    const soa::SpatialInertia M_y = soa::transform(c.phi.inverse(), b.M);
    const soa::Velocity V_y = c.phi.transpose_apply(V_x);
    const double scale = std::max(1.0, M_y.matrix().norm() * V_y.vector().squaredNorm());
    check.add(i, one(soa::ex01::kinetic_energy(b.M, V_x) - soa::ex01::kinetic_energy(M_y, V_y)),
              one(0.0), scale, b.tags | c.tags, [&] {
                return kinetic_energy_code(b.M, V_x) + code("M_y", M_y) + code("V_y", V_y) +
                       "double T_y = soa::ex01::kinetic_energy(M_y, V_y);  // must equal T\n";
              });
  }
}

// ---- 1.6: velocity reversal V(y,x) = -phi*(y,x) V(x,y) (slides 36, 46) ---------------------

Mistakes reverse_velocity_mistakes(const soa::Phi& phi, const soa::Velocity& V) {
  const Mat3d& R = phi.R();
  const Vec3d& l = phi.l();
  const Vec3d w = R * V.angular(), v = R * V.linear();
  const Vec3d wt = R.transpose() * V.angular(), vt = R.transpose() * V.linear();
  const Vec6d ref = (-phi.inverse().transpose_apply(V)).vector();
  return Mistakes{
      {"dropped term",
       "your v(y,x) is -v(x,y): the linear velocity reverses only without rotation; "
       "w(x,y) x l(x,y) is missing",
       six(-w, -v)},
      {"sign", "your v(y,x) subtracts w(x,y) x l(x,y): v(y,x) = -v(x,y) + w(x,y) x l(x,y)",
       six(-w, -v - w.cross(l))},
      {"wrong frame",
       "your w(x,y), v(x,y) are still in y-coordinates: rotate them with R first, then l(x,y) is "
       "in the same frame",
       six(-V.angular(), -V.linear() + Vec3d(V.angular()).cross(l))},
      {"transpose",
       "you rotated with R*, the transpose: R = x R_y takes y-coordinates to x-coordinates",
       six(-wt, -vt + wt.cross(l))},
      soa::test::negated(ref,
                         "your result is phi*(y,x) V(x,y): the minus sign of "
                         "V(y,x) = -phi*(y,x) V(x,y) is missing"),
      {"wrong frame",
       "your result is in y-coordinates: V(y,x) is asked in x-coordinates (R times yours)",
       six(R.transpose() * ref.head<3>(), R.transpose() * ref.tail<3>())},
  };
}

std::string reverse_velocity_code(const soa::Phi& phi, const soa::Velocity& V) {
  return code("phi_xy", phi) + code("V_xy", V) +
         "soa::Velocity V_yx = soa::ex01::reverse_velocity(phi_xy, V_xy);\n";
}

// clang-format off
/* planted mistakes of 1.6
soa_plant(1.6 sign
  FIND [=[-v_xy + w_xy.cross(phi_xy.l())]=]
  WRONG [=[-v_xy - w_xy.cross(phi_xy.l())]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(sign\): your v\(y,x\) subtracts w\(x,y\) x l\(x,y\)]=])
*/
// clang-format on
TEST(Exercise1_6_ReverseVelocity, MatchesLibraryPhi) {
  Random rnd;
  Check check("V(y,x) = -phi*(y,x) V(x,y)", 16 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const PhiCase c = draw_phi(rnd, i);
    const soa::Velocity V_xy = rnd.velocity();
    const Vec6d ref = (-c.phi.inverse().transpose_apply(V_xy)).vector();
    check.add(
        i, soa::ex01::reverse_velocity(c.phi, V_xy).vector(), ref, size_of(ref), c.tags,
        [&] { return reverse_velocity_code(c.phi, V_xy); },
        [&] { return reverse_velocity_mistakes(c.phi, V_xy); }, soa::test::spatial("V(y,x)"));
  }
}

TEST(Exercise1_6_ReverseVelocity, MatchesThe6x6Matrix) {
  Random rnd(61);
  Check check("V(y,x) against the 6x6 -phi^-*(x,y) V(x,y)", 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const PhiCase c = draw_phi(rnd, i);
    const soa::Velocity V_xy = rnd.velocity();
    const Mat6d phi_yx = c.phi.matrix().inverse();
    const Vec6d ref = -(phi_yx.transpose() * V_xy.vector());
    check.add(
        i, soa::ex01::reverse_velocity(c.phi, V_xy).vector(), ref, size_of(ref), c.tags,
        [&] { return reverse_velocity_code(c.phi, V_xy); },
        [&] { return reverse_velocity_mistakes(c.phi, V_xy); }, soa::test::spatial("V(y,x)"));
  }
}

TEST(Exercise1_6_ReverseVelocity, ReversingTwiceGivesBackTheVelocity) {
  Random rnd(62);
  Check check("V(x,y) reversed twice (with phi(y,x) the second time)", 32 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const PhiCase c = draw_phi(rnd, i);
    const soa::Velocity V_xy = rnd.velocity();
    const soa::Velocity V_yx = soa::ex01::reverse_velocity(c.phi, V_xy);
    const soa::Velocity back = soa::ex01::reverse_velocity(c.phi.inverse(), V_yx);
    check.add(
        i, back.vector(), V_xy.vector(), size_of(V_xy.vector()), c.tags,
        [&] {
          return reverse_velocity_code(c.phi, V_xy) +
                 "soa::Velocity back = soa::ex01::reverse_velocity(phi_xy.inverse(), V_yx);\n";
        },
        {}, soa::test::spatial("V(x,y)"));
  }
}

// ---- 1.7: the exponential of SE(3) (slide 63) ----------------------------------------------

// Against the library's exp_se3 (series near zero) and against the dense 4x4 exponential in
// long double (scaling and squaring), at angles from 0 to 3, with a band of small angles
// 1e-9 ... 1e-2 where the closed forms cancel: a closed form used there fails that check.
soa::Pose expm_ld(const soa::Velocity& xi) {
  using M4 = Eigen::Matrix<long double, 4, 4>;
  M4 A = soa::hat(xi).cast<long double>();
  int s = 0;
  long double nrm = A.cwiseAbs().rowwise().sum().maxCoeff();
  while (nrm > 0.5L) nrm /= 2, ++s;
  A /= std::ldexp(1.0L, s);
  M4 sum = M4::Identity(), term = M4::Identity();
  for (int k = 1; k < 40; ++k) term = (term * A) / (long double)k, sum += term;
  for (int k = 0; k < s; ++k) sum = sum * sum;
  const Eigen::Matrix4d d = sum.cast<double>();
  return soa::Pose(d.topLeftCorner<3, 3>(), d.topRightCorner<3, 1>());
}

// The 3x4 [R l] of a pose: what is compared (the last row of the 4x4 is [0 0 0 1]).
Eigen::Matrix<double, 3, 4> rows(const soa::Pose& T) {
  Eigen::Matrix<double, 3, 4> m;
  m << T.R(), T.l();
  return m;
}
Naming pose_naming() {
  return [](Eigen::Index i, Eigen::Index j) {
    return j < 3 ? soa::test::EntryName{"R(" + std::to_string(i) + "," + std::to_string(j) + ")",
                                        "the rotation R"}
                 : soa::test::EntryName{"l[" + std::to_string(i) + "]", "the offset l"};
  };
}

// exp(xi^) with one part of the closed form changed: the catalogue of 1.7.
enum class Exp { TransposedR, LIsV, NoG3, SwappedG, SignG2, LIsRv };
MatX exp_variant(const soa::Velocity& xi, Exp e) {
  const Vec3d w = xi.angular(), v = xi.linear();
  const double t = w.norm();
  const double g1 = soa::g_series(1, t), g2 = soa::g_series(2, t), g3 = soa::g_series(3, t);
  const Mat3d W = soa::tilde(w), W2 = W * W, I = Mat3d::Identity();
  const Mat3d R = I + g1 * W + g2 * W2;
  Vec3d l = (I + g2 * W + g3 * W2) * v;
  Mat3d Rv = R;
  switch (e) {
    case Exp::TransposedR:
      Rv = R.transpose();
      break;
    case Exp::LIsV:
      l = v;
      break;
    case Exp::NoG3:
      l = (I + g2 * W) * v;
      break;
    case Exp::SwappedG:
      l = (I + g3 * W + g2 * W2) * v;
      break;
    case Exp::SignG2:
      l = (I - g2 * W + g3 * W2) * v;
      break;
    case Exp::LIsRv:
      l = R * v;
      break;
  }
  return rows(soa::Pose(Rv, l));
}

Mistakes exp_mistakes(const soa::Velocity& xi) {
  auto v = [&](Exp e) { return exp_variant(xi, e); };
  return Mistakes{
      {"transpose", "your R is the transpose of exp(w~) = I + g1 w~ + g2 w~^2",
       v(Exp::TransposedR)},
      {"dropped term",
       "your l is v: the series of the offset block is (I + g2 w~ + g3 w~^2) v, "
       "not v alone",
       v(Exp::LIsV)},
      {"dropped term", "the g3 w~^2 v term of l is missing", v(Exp::NoG3)},
      {"swapped", "g2 and g3 are swapped in l: l = (I + g2 w~ + g3 w~^2) v", v(Exp::SwappedG)},
      {"sign", "your l has - g2 w~ v: l = (I + g2 w~ + g3 w~^2) v", v(Exp::SignG2)},
      {"wrong formula",
       "your l is R v, a rotation then the translation v: the offset block of the series is "
       "(I + g2 w~ + g3 w~^2) v",
       v(Exp::LIsRv)},
  };
}

std::string exp_code(const soa::Velocity& xi) {
  return code("xi", xi) + "soa::Pose T = soa::ex01::exp_twist(xi);\n";
}

unsigned twist_tags(const soa::Velocity& xi) {
  return (xi.angular().isZero(0.0) ? 0u : unsigned(soa::test::kRotated)) |
         (xi.linear().isZero(0.0) ? 0u : unsigned(soa::test::kTranslated));
}

// clang-format off
/* planted mistakes of 1.7
soa_plant(1.7 closed-form-at-small-angles
  FIND [=[t < 1e-2]=]
  WRONG [=[t < 0.0]=] TYPE [=[bool]=]
  EXPECT [=[exp\(xi\^\) at small angles, theta from 1e-9 to 1e-2 \(where the closed forms of g2 and g3 cancel\): wrong in]=])
*/
// clang-format on
TEST(Exercise1_7_ExpTwist, MatchesTheMatrixExponentialAtEveryAngle) {
  Random rnd(71);
  Check check("exp(xi^) = (R, l) at angles theta = |w| from 0 to 3", 64 * kEps),
      small(
          "exp(xi^) at small angles, theta from 1e-9 to 1e-2 (where the closed forms of g2 "
          "and g3 cancel)",
          64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const bool tiny = i % 2 == 1;
    const double theta = tiny ? std::pow(10.0, rnd.uniform(-9, -2)) : rnd.uniform(0, 3);
    const Vec3d n = rnd.unit3();
    const Vec3d v = rnd.vec3();
    // The big-angle half has no rotation when i mod 14 = 0 and no translation when i mod 10 = 4.
    const soa::Velocity xi(i % 14 == 0 ? Vec3d::Zero() : Vec3d(theta * n),
                           i % 10 == 4 ? Vec3d::Zero() : v);
    const soa::Pose ref = expm_ld(xi);
    (tiny ? small : check)
        .add(
            i, rows(soa::ex01::exp_twist(xi)), rows(ref), ref.matrix().norm(), twist_tags(xi),
            [&] { return exp_code(xi); }, [&] { return exp_mistakes(xi); }, pose_naming());
  }
}

TEST(Exercise1_7_ExpTwist, ZeroAngleAndLibrary) {
  Check zero("exp(xi^) of a pure translation xi = [0; v] is (I, v)", 4 * kEps);
  const soa::Velocity pure(Vec3d::Zero(), Vec3d(0.3, -1.0, 2.0));
  const soa::Pose ref(Mat3d::Identity(), Vec3d(0.3, -1.0, 2.0));
  zero.add(
      0, rows(soa::ex01::exp_twist(pure)), rows(ref), ref.matrix().norm(), twist_tags(pure),
      [&] { return exp_code(pure); }, [&] { return exp_mistakes(pure); }, pose_naming());
  Random rnd(72);
  Check check("exp(xi^) against soa::exp_se3", 64 * kEps),
      back("log_se3(exp(xi^)) = xi, the round trip", 16 * 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const soa::Velocity xi((rnd.uniform(0, 3) * rnd.unit3()).eval(), rnd.vec3());
    const soa::Pose T = soa::ex01::exp_twist(xi);
    const soa::Pose ref = soa::exp_se3(xi);
    auto inputs = [&] { return exp_code(xi); };
    check.add(
        i, rows(T), rows(ref), ref.matrix().norm(), twist_tags(xi), inputs,
        [&] { return exp_mistakes(xi); }, pose_naming());
    back.add(i, soa::log_se3(T).vector(), xi.vector(), size_of(xi.vector()), twist_tags(xi), inputs,
             {}, soa::test::spatial("log(exp(xi^))"));
  }
}

// ---- 1.8: the cross product of forces, from duality (slides 53-55) -------------------------

Mistakes force_cross_mistakes(const soa::Velocity& X, const soa::Force& f) {
  const Vec3d x = X.angular(), y = X.linear(), N = f.angular(), F = f.linear();
  return Mistakes{
      {"transpose",
       "your result is X~ f = [x x N; y x N + x x F], the cross product of motion vectors: on "
       "forces the y~ block moves to the top right",
       six(x.cross(N), y.cross(N) + x.cross(F))},
      soa::test::negated(soa::cross_bar(X, f).vector(),
                         "your result is X~* f, without the minus sign: the definition gives "
                         "X_bar = -X~*"),
      {"sign",
       "the sign of your y x F term is off: transposing X~ transposes the blocks too, "
       "y~* = -y~, so -X~* = [x~ y~; 0 x~]",
       six(x.cross(N) - y.cross(F), x.cross(F))},
      {"dropped term", "the y x F term of the moment part is missing: X_bar = [x~ y~; 0 x~]",
       six(x.cross(N), x.cross(F))},
      {"wrong part",
       "your y~ acts on the moment N: the top right block of X_bar = [x~ y~; 0 x~] acts on the "
       "force F",
       six(x.cross(N) + y.cross(N), x.cross(F))},
  };
}

std::string force_cross_code(const soa::Velocity& X, const soa::Force& f) {
  return code("X", X) + code("f", f) + "soa::Force Xf = soa::ex01::force_cross(X, f);\n";
}

// clang-format off
/* planted mistakes of 1.8
soa_plant(1.8 dropped-term
  FIND [=[x.cross(N) + y.cross(F)]=]
  WRONG [=[x.cross(N)]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[the checker knows this mistake: it names it after 3 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|the y x F term of the moment part is missing]=]
  NAMED [=[likely mistake \(dropped term\): the y x F term of the moment part is missing]=])
*/
// clang-format on
TEST(Exercise1_8_ForceCross, MatchesLibraryCrossBar) {
  Random rnd(81);
  Check check("X_bar f, the cross product of forces", 8 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const soa::Velocity X = draw_motion(rnd, i);
    const soa::Force f = rnd.force();
    const Vec6d ref = soa::cross_bar(X, f).vector();
    check.add(
        i, soa::ex01::force_cross(X, f).vector(), ref, size_of(ref), 0,
        [&] { return force_cross_code(X, f); }, [&] { return force_cross_mistakes(X, f); },
        soa::test::spatial("X_bar f"));
  }
}

TEST(Exercise1_8_ForceCross, IsDualToTheMotionCrossProduct) {
  // (X_bar f)* Y = -f* (X~ Y) for random Y: the definition itself.
  Random rnd(82);
  Check check("the definition (X_bar f)* Y = -f* (X~ Y), on random Y", 16 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const soa::Velocity X = draw_motion(rnd, i), Y = rnd.velocity();
    const soa::Force f = rnd.force();
    const double expected = -soa::dot(f, soa::cross(X, Y));
    const double scale = std::max(1.0, X.vector().norm() * f.vector().norm() * Y.vector().norm());
    check.add(
        i, one(soa::ex01::force_cross(X, f).vector().dot(Y.vector())), one(expected), scale, 0,
        [&] { return force_cross_code(X, f) + code("Y", Y); },
        [&] {
          Mistakes out;
          for (Mistake& m : force_cross_mistakes(X, f))
            out.push_back(Mistake{m.kind, m.says, one(m.value.col(0).dot(Y.vector()))});
          return out;
        });
  }
}

// ---- 1.9: the rank of X~, predicted (slides 53-54) -----------------------------------------

// clang-format off
/* planted mistakes of 1.9
soa_plant(1.9 missed-case
  FIND [=[y_zero ? 0 : 2]=]
  WRONG [=[4]=] TYPE [=[int]=]
  EXPECT [=[the checker knows this mistake: it names it after 3 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your rank is 4 for every X]=]
  NAMED [=[likely mistake \(missed case\): your rank is 4 for every X]=])
*/
// clang-format on
TEST(Exercise1_9_SpatialCrossRank, MatchesTheRankOfTheMatrix) {
  // The kinds of X in turn: general, x = 0, y = 0, X = 0, y parallel to x.
  Random rnd(91);
  Check check("the rank of X~", 0.0);
  for (int i = 0; i < kCases; ++i) {
    Vec3d x = rnd.vec3(), y = rnd.vec3();
    const int kind = i % 5;
    if (kind == 1 || kind == 3) x.setZero();
    if (kind == 2 || kind == 3) y.setZero();
    if (kind == 4) y = rnd.normal() * x;
    const soa::Velocity X(x, y);
    const int ref = int(Eigen::FullPivLU<Mat6d>(soa::tilde(X)).rank());
    const bool x0 = x.isZero(0.0), y0 = y.isZero(0.0);
    auto mistakes = [&] {
      const int diag = x0 ? 0 : 4, blocks = (x0 ? 0 : 2) + (y0 ? 0 : 2);
      return Mistakes{
          {"missed case",
           "your rank is 4 for every X: with x = 0 only the block y~ is left, and with X = 0 "
           "nothing",
           one(4)},
          {"wrong count", "your rank is 6 for X != 0: X~ is never invertible, X~ X = 0 (slide 54)",
           one(x0 && y0 ? 0 : 6)},
          {"wrong count",
           "your rank is 5: the kernel of X~ holds more than the multiples of X (for x != 0, "
           "try Y = [0; x])",
           one(x0 && y0 ? 0 : 5)},
          {"dropped term",
           "you counted only the diagonal blocks x~: with x = 0 the block y~ still acts on w",
           one(diag)},
          {"wrong count",
           "you added the ranks of the blocks x~ and y~: with y = 0, X~ = diag(x~, x~) has rank 4",
           one(blocks)},
      };
    };
    check.add(
        i, one(soa::ex01::spatial_cross_rank(X)), one(ref), 1.0, 0,
        [&] { return code("X", X) + "int rank = soa::ex01::spatial_cross_rank(X);\n"; }, mistakes);
  }
}

}  // namespace
