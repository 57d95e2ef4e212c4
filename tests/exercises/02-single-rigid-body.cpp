// Lesson 2 exercise tests: each exercise of exercises/02-single-rigid-body/exercises.hpp against
// the library, on soa::test::kCases random cases from the fixed seed. Each check names its
// quantity, and its catalogue of classic mistakes is computed from the reference
// (tests/support/exercise_check.hpp). The cases vary the features the symptoms need: the frame at
// the centre of mass or away from it, turning or not, accelerating or not, an attitude that is the
// identity or not, an applied force or none. Built against the solutions (ctest), the students'
// exercises (make exercises) and the solutions with planted mistakes (the "planted mistakes"
// blocks, tests/exercises/plant.cmake).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "exercise_check.hpp"
#include "exercises.hpp"
#include "property.hpp"

namespace {

using soa::test::Check;
using soa::test::code;
using soa::test::kCases;
using soa::test::list;
using soa::test::Mistake;
using soa::test::Mistakes;
using soa::test::Naming;
using soa::test::num;
using soa::test::Random;
using V3 = soa::Vec3<double>;
using M3 = soa::Mat3<double>;
using V6 = soa::Vec6<double>;
using MatX = soa::MatX<double>;
using One = Eigen::Matrix<double, 1, 1>;

constexpr double kEps = soa::eps<double>();

One one(double v) {
  return One::Constant(v);
}

template <class D>
double size_of(const Eigen::MatrixBase<D>& e) {
  return std::max(1.0, double(e.norm()));
}

MatX six(const V3& a, const V3& b) {
  V6 v;
  v << a, b;
  return v;
}

// The condition number of M(x), the amplification of rounding in a solve with it.
double condition(const soa::SpatialInertia& M) {
  const Eigen::SelfAdjointEigenSolver<soa::Mat6<double>> eig(M.matrix());
  return eig.eigenvalues().maxCoeff() / eig.eigenvalues().minCoeff();
}

// The scale of the terms of b(x): |J(x)| |w|^2 + m |w|^2 |p(x)|.
double b_scale(const soa::SpatialInertia& M, const soa::Velocity& V) {
  const double w2 = V.angular().squaredNorm();
  return M.J().norm() * w2 + M.mass() * w2 * M.p().norm();
}

// A body whose frame is at its centre of mass when i mod 3 = 0 (tag kOffsetCom otherwise).
struct Body {
  soa::SpatialInertia M;
  unsigned tags = 0;
};
Body draw_body(Random<double>& rng, int i) {
  const soa::SpatialInertia M = rng.inertia();
  if (i % 3 == 0) return Body{soa::SpatialInertia::from_cm(M.mass(), V3::Zero(), M.J_cm())};
  return Body{M, soa::test::kOffsetCom};
}

// A velocity that does not turn (w = 0) when i mod 7 = 3 and has v = 0 when i mod 6 = 4; tag
// kMoving when it turns (b(x) depends on w only).
soa::Velocity draw_velocity(Random<double>& rng, int i, unsigned& tags) {
  const V3 w = rng.vec3(), v = rng.vec3();
  if (i % 7 != 3) tags |= soa::test::kMoving;
  return soa::Velocity(i % 7 == 3 ? V3::Zero() : w, i % 6 == 4 ? V3::Zero() : v);
}

// An acceleration that is zero when i mod 4 = 1 (tag kAccelerating otherwise).
soa::Acceleration draw_acceleration(Random<double>& rng, int i, unsigned& tags) {
  const soa::Acceleration a = rng.acceleration();
  if (i % 4 == 1) return soa::Acceleration::Zero();
  tags |= soa::test::kAccelerating;
  return a;
}

// A free-body state: the attitude is the identity when i mod 4 = 2 (tag kRotated otherwise),
// any position, the velocity of draw_velocity.
soa::FreeBodyState draw_state(Random<double>& rng, int i, unsigned& tags) {
  soa::FreeBodyState x;
  const soa::UnitQuaternion q(rng.vec3(), rng.normal());
  if (i % 4 != 2) {
    x.q = q;
    tags |= soa::test::kRotated;
  }
  x.r = rng.vec3();
  x.V = draw_velocity(rng, i, tags);
  return x;
}

// An applied force that is zero when i mod 3 = 1 (tag kExternalForces otherwise).
soa::Force draw_force(Random<double>& rng, int i, unsigned& tags) {
  const soa::Force f = rng.force();
  if (i % 3 == 1) return soa::Force::Zero();
  tags |= soa::test::kExternalForces;
  return f;
}

std::string state_code(const std::string& name, const soa::FreeBodyState& x) {
  return "soa::FreeBodyState " + name + ";\n" + name +
         ".q = soa::UnitQuaternion(soa::Vec3<double>" + list(x.q.q()) + ", " + num(x.q.q0()) +
         ");\n" + name + ".r = soa::Vec3<double>" + list(x.r) + ";\n" + name +
         ".V = soa::Velocity(soa::Vec3<double>" + list(V3(x.V.angular())) + ", soa::Vec3<double>" +
         list(V3(x.V.linear())) + ");\n";
}

// The parts of a free-body state compared one by one: the attitude (its sign aligned with
// the reference's: q and -q are one attitude), the position, the velocity.
Eigen::Vector4d aligned(const soa::UnitQuaternion& q, const soa::UnitQuaternion& ref) {
  return q.coeffs().dot(ref.coeffs()) < 0 ? Eigen::Vector4d(-q.coeffs()) : q.coeffs();
}
Naming quaternion_naming(const std::string& sym) {
  return [sym](Eigen::Index i, Eigen::Index) {
    return i < 3 ? soa::test::EntryName{sym + "[" + std::to_string(i) + "]",
                                        "the vector part of " + sym}
                 : soa::test::EntryName{sym + "[3] (q0)", "the scalar part of " + sym};
  };
}
Naming vector_naming(const std::string& sym) {
  return [sym](Eigen::Index i, Eigen::Index) {
    return soa::test::EntryName{sym + "[" + std::to_string(i) + "]", sym};
  };
}

// Three checks of a state against a reference, each with its catalogue taken from states.
struct StateChecks {
  // Reported in the order declared: the attitude first.
  Check q, r, V;
  StateChecks(const std::string& what, double tol)
      : q("the attitude q of " + what, tol),
        r("the position r of " + what, tol),
        V("the velocity V of " + what, tol) {}
  void add(int i, const soa::FreeBodyState& got, const soa::FreeBodyState& ref, double unit,
           unsigned tags, const std::function<std::string()>& inputs,
           const std::function<std::vector<std::pair<Mistake, soa::FreeBodyState>>()>& variants) {
    auto pick = [&](int part) {
      return [&, part] {
        Mistakes out;
        for (const auto& [m, x] : variants()) {
          MatX value = part == 0   ? MatX(aligned(x.q, ref.q))
                       : part == 1 ? MatX(x.r)
                                   : MatX(x.V.vector());
          out.push_back(Mistake{m.kind, m.says, value});
        }
        return out;
      };
    };
    // |q| = 1: the difference is absolute.
    q.add(i, aligned(got.q, ref.q), ref.q.coeffs(), unit, tags, inputs, pick(0),
          quaternion_naming("q1"));
    r.add(i, got.r, ref.r, unit * size_of(ref.r), tags, inputs, pick(1), vector_naming("r1"));
    V.add(i, got.V.vector(), ref.V.vector(), unit * size_of(ref.V.vector()), tags, inputs, pick(2),
          soa::test::spatial("V1"));
  }
};

}  // namespace

// clang-format off
/* planted mistakes of 2.1
soa_plant(2.1 centripetal-doubled
  FIND [=[M.mass() * w.cross(w.cross(M.p()))]=]
  WRONG [=[2.0 * M.mass() * w.cross(w.cross(M.p()))]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[symptom: it fails only where the centre of mass is off the frame's origin: [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
*/
// clang-format on
// 2.1: b(x) = [w~ J(x) w; m w~ w~ p(x)], against soa::gyroscopic_force.
TEST(Exercise2_1_GyroscopicTerm, MatchesLibrary) {
  Random<double> rng;
  Check check("b(x), the gyroscopic term", 32 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const Body body = draw_body(rng, i);
    unsigned tags = body.tags;
    const soa::Velocity V = draw_velocity(rng, i, tags);
    const soa::SpatialInertia& M = body.M;
    const V6 ref = soa::gyroscopic_force(M, V).vector();
    auto mistakes = [&] {
      const V3 w = V.angular(), v = V.linear();
      const V3 N = w.cross(M.J() * w), F = M.mass() * w.cross(w.cross(M.p()));
      return Mistakes{
          soa::test::negated(ref,
                             "your b(x) has the opposite sign: f = M alpha + b with "
                             "b(x) = [w~ J(x) w; m w~ w~ p(x)]"),
          {"sign", "your moment is (J w) x w = -w x (J w): the moment of b is w~ J(x) w",
           six(-N, F)},
          {"dropped term",
           "the linear part m w x (w x p(x)) is missing (it vanishes only when x is the centre "
           "of mass)",
           six(N, V3::Zero())},
          {"sign",
           "your linear part has the opposite sign: it is m w~ w~ p(x) = m w x (w x p(x)), the "
           "centripetal acceleration of C times m",
           six(N, -F)},
          {"wrong point", "your moment uses J(C): about x it is w x (J(x) w), J(x) = M.J()",
           six(w.cross(M.J_cm() * w), F)},
          {"wrong frame",
           "your linear part is w x (m v(C)), a term of the body-frame form V_bar M V "
           "(exercise 2.5, where V_dot holds the component rates): b(x) goes with the inertial "
           "alpha(x) and does not depend on v",
           six(N, M.mass() * w.cross(v + w.cross(M.p())))},
      };
    };
    check.add(
        i, soa::ex02::gyroscopic_term(M, V).vector(), ref, std::max(1.0, b_scale(M, V)), tags,
        [&] {
          return code("M", M) + code("V", V) + "soa::Force b = soa::ex02::gyroscopic_term(M, V);\n";
        },
        mistakes, soa::test::spatial("b(x)"));
  }
}

// The route of 2.2 through C with one step changed: the catalogue's variants.
enum class ViaC { NoCentripetal, NoTangential, AlphaX, NoGyroscopic, Transposed, MinusMoment };
V6 via_c(double m, const M3& J_C, const V3& p, const soa::Velocity& V, const soa::Acceleration& a,
         ViaC e) {
  const V3 w = V.angular(), w_dot = a.angular();
  V3 v_dot_C = a.linear();
  if (e != ViaC::NoTangential && e != ViaC::AlphaX) v_dot_C += w_dot.cross(p);
  if (e != ViaC::NoCentripetal && e != ViaC::AlphaX) v_dot_C += w.cross(w.cross(p));
  V3 N_C = J_C * w_dot;
  if (e != ViaC::NoGyroscopic) N_C += w.cross(J_C * w);
  const V3 F_C = m * v_dot_C;
  V6 f;
  if (e == ViaC::Transposed)
    f << N_C, F_C - p.cross(N_C);
  else if (e == ViaC::MinusMoment)
    f << N_C - p.cross(F_C), F_C;
  else
    f << N_C + p.cross(F_C), F_C;
  return f;
}

// clang-format off
/* planted mistakes of 2.2
soa_plant(2.2 dropped-gyroscopic
  FIND [=[w.cross(J_C * w)]=]
  WRONG [=[Vec3<double>::Zero()]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(dropped term\): the gyroscopic moment w x J\(C\) w is missing]=])
soa_plant(2.2 transpose
  FIND [=[Force(N_C + p.cross(F_C), F_C)]=]
  WRONG [=[Force(N_C, Vec3<double>(F_C - p.cross(N_C)))]=] TYPE [=[Force]=]
  EXPECT [=[likely mistake \(transpose\): your f\(x\) is phi\*\(x,C\) f\(C\)]=])
*/
// clang-format on
// 2.2: f(x) through C, against soa::rigid_body_force = M(x) alpha(x) + b(x).
TEST(Exercise2_2_SpatialForce, MatchesLibrary) {
  Random<double> rng;
  Check check("f(x), the spatial force computed through C", 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const Body body = draw_body(rng, i);
    unsigned tags = body.tags;
    const soa::SpatialInertia& M = body.M;
    const soa::Velocity V = draw_velocity(rng, i, tags);
    const soa::Acceleration alpha = draw_acceleration(rng, i, tags);
    const double m = M.mass();
    const M3 J_C = M.J_cm();
    const V3 p = M.p();
    const V6 ref = soa::rigid_body_force(M, V, alpha).vector();
    const double scale = M.matrix().norm() * alpha.vector().norm() + b_scale(M, V);
    auto mistakes = [&] {
      auto v = [&](ViaC e) { return MatX(via_c(m, J_C, p, V, alpha, e)); };
      return Mistakes{
          {"dropped term",
           "the centripetal term w x (w x p) is missing from your alpha(C): p is fixed in the "
           "body and turns with it",
           v(ViaC::NoCentripetal)},
          {"dropped term",
           "w_dot x p is missing from your v_dot(C): phi*(x,C) alpha(x) = [w_dot; v_dot(x) + "
           "w_dot x p]",
           v(ViaC::NoTangential)},
          {"dropped term",
           "your alpha(C) is alpha(x): the acceleration must be moved to C first, "
           "alpha(C) = phi*(x,C) alpha(x) + [0; w x (w x p)]",
           v(ViaC::AlphaX)},
          {"dropped term", "the gyroscopic moment w x J(C) w is missing from your N(C) (Euler)",
           v(ViaC::NoGyroscopic)},
          {"transpose",
           "your f(x) is phi*(x,C) f(C): forces move with phi(x,C) = [I p~; 0 I], "
           "N(x) = N(C) + p x F(C)",
           v(ViaC::Transposed)},
          {"sign", "your N(x) subtracts p x F(C): N(x) = N(C) + p x F(C), p = l(x, C)",
           v(ViaC::MinusMoment)},
      };
    };
    check.add(
        i, soa::ex02::spatial_force(m, J_C, p, V, alpha).vector(), ref, std::max(1.0, scale), tags,
        [&] {
          return "double m = " + num(m) + ";\n" + code("J_C", J_C) + code("p", p) + code("V", V) +
                 code("alpha", alpha) +
                 "soa::Force f = soa::ex02::spatial_force(m, J_C, p, V, alpha);\n";
        },
        mistakes, soa::test::spatial("f(x)"));
  }
}

// clang-format off
/* planted mistakes of 2.3
soa_plant(2.3 wrong-frame
  FIND [=[x.q.matrix() * v]=]
  WRONG [=[v]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(wrong frame\): your r_dot is v in body coordinates]=])
*/
// clang-format on
// 2.3: the free-body rates, against soa::free_body_rate (with an applied force).
TEST(Exercise2_3_BodyRates, MatchesLibrary) {
  Random<double> rng;
  Check c_omega("omega, the rate that drives the attitude", 0.0),
      c_r("r_dot = R v, the rate of the position", 16 * kEps),
      c_V("V_dot = [w_dot; v_dot], the component rates of V", 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const Body body = draw_body(rng, i);
    unsigned tags = body.tags;
    const soa::SpatialInertia& M = body.M;
    const soa::FreeBodyState x = draw_state(rng, i, tags);
    const soa::Force f = draw_force(rng, i, tags);
    const auto d = soa::ex02::body_rates(M, x, f);
    const auto ref = soa::free_body_rate(M, x, f);
    auto inputs = [&] {
      return code("M", M) + state_code("x", x) + code("f", f) +
             "soa::FreeBodyRateT<double> d = soa::ex02::body_rates(M, x, f);\n";
    };
    const V3 w = x.V.angular(), v = x.V.linear();
    c_omega.add(i, d.omega, ref.omega, 1.0, tags, inputs, {}, vector_naming("omega"));
    c_r.add(
        i, d.r_dot, ref.r_dot, size_of(ref.r_dot), tags, inputs,
        [&] {
          return Mistakes{
              {"wrong frame",
               "your r_dot is v in body coordinates: r is in inertial coordinates, r_dot = R v "
               "(x.q.rotate(v) or x.q.matrix() * v)",
               v},
              {"transpose", "your r_dot is R* v: R = I R_B takes body to inertial coordinates",
               MatX(x.q.matrix().transpose() * v)},
          };
        },
        vector_naming("r_dot"));
    c_V.add(
        i, d.V_dot, ref.V_dot, condition(M) * size_of(ref.V_dot), tags, inputs,
        [&] {
          const soa::Mat6<double> Mm = M.matrix();
          const V6 b = soa::gyroscopic_force(M, x.V).vector();
          auto rates = [&](const V6& alpha, double sign) {
            return six(alpha.head<3>(), V3(alpha.tail<3>()) - sign * w.cross(v));
          };
          const V6 alpha = Mm.llt().solve(f.vector() - b);
          return Mistakes{
              {"dropped term",
               "your V_dot is alpha, the inertial derivative: the body-frame rates are "
               "[w_dot; v_dot] with v_dot = alpha_v - w x v",
               rates(alpha, 0)},
              {"sign",
               "your v_dot adds w x v: alpha = [w_dot; v_dot + w x v], so v_dot = alpha_v - "
               "w x v",
               rates(alpha, -1)},
              {"dropped term",
               "the gyroscopic term b(x) is missing: alpha = M^-1 (f - b), b(x) = [w~ J(x) w; "
               "m w~ w~ p(x)]",
               rates(Mm.llt().solve(f.vector()), 1)},
              {"sign", "your alpha adds b: alpha = M^-1 (f - b)",
               rates(Mm.llt().solve(f.vector() + b), 1)},
          };
        },
        soa::test::spatial("V_dot"));
  }
}

// One torque-free Lie-group RK4 step of 2.4 with one step changed: the catalogue's variants.
enum class RK { FirstStageOnly, NoDexp, LeftMultiply, StagesAtQ0, EqualWeights };
soa::FreeBodyState rk4_variant(const soa::SpatialInertia& M, const soa::FreeBodyState& x0, double h,
                               RK e) {
  struct Stage {
    V3 e;
    soa::FreeBodyRateT<double> d;
  };
  auto turn = [&](const V3& delta) {
    return e == RK::LeftMultiply ? soa::UnitQuaternion::exp(delta) * x0.q
                                 : x0.q * soa::UnitQuaternion::exp(delta);
  };
  auto stage = [&](const V3& delta, const V3& r, const V6& V) {
    soa::FreeBodyState x;
    x.q = e == RK::StagesAtQ0 ? x0.q : turn(delta);
    x.r = r;
    x.V = soa::Velocity(V);
    Stage s;
    s.d = soa::free_body_rate(M, x, soa::Force::Zero());
    s.e = e == RK::NoDexp ? s.d.omega : soa::dexp_inv_right(delta, s.d.omega);
    return s;
  };
  const V6 V0 = x0.V.vector();
  const Stage k1 = stage(V3::Zero(), x0.r, V0);
  const Stage k2 = stage(h / 2 * k1.e, x0.r + h / 2 * k1.d.r_dot, V0 + h / 2 * k1.d.V_dot);
  const Stage k3 = stage(h / 2 * k2.e, x0.r + h / 2 * k2.d.r_dot, V0 + h / 2 * k2.d.V_dot);
  const Stage k4 = stage(h * k3.e, x0.r + h * k3.d.r_dot, V0 + h * k3.d.V_dot);
  const double a = e == RK::EqualWeights ? 1.0 / 4 : 1.0 / 6, b = e == RK::EqualWeights ? 1 : 2;
  soa::FreeBodyState x1;
  x1.q =
      e == RK::FirstStageOnly ? turn(h * k1.e) : turn(h * a * (k1.e + b * k2.e + b * k3.e + k4.e));
  x1.r = x0.r + h * a * (k1.d.r_dot + b * k2.d.r_dot + b * k3.d.r_dot + k4.d.r_dot);
  x1.V =
      soa::Velocity(V6(V0 + h * a * (k1.d.V_dot + b * k2.d.V_dot + b * k3.d.V_dot + k4.d.V_dot)));
  return x1;
}

// clang-format off
/* planted mistakes of 2.4
soa_plant(2.4 no-dexp
  FIND [=[dexp_inv_right(delta, s.d.omega)]=]
  WRONG [=[s.d.omega]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(dropped term\): your delta rates are the angular velocities themselves]=])
*/
// clang-format on
// 2.4: one torque-free Lie-group RK4 step, against soa::rk4_step. The steps are large enough
// (h |w| up to ~0.5) that a different fourth-order scheme would differ by far more than rounding.
TEST(Exercise2_4_Rk4Step, MatchesLibrary) {
  Random<double> rng;
  StateChecks checks("one RK4 step (x1)", 64 * kEps);
  Check unit("|q1| = 1, the attitude stays a unit quaternion", 4 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const Body body = draw_body(rng, i);
    unsigned tags = body.tags;
    const soa::SpatialInertia& M = body.M;
    const soa::FreeBodyState x0 = draw_state(rng, i, tags);
    const double h = rng.uniform(0.05, 0.2);
    const soa::FreeBodyState x1 = soa::ex02::rk4_torque_free(M, x0, h);
    const soa::FreeBodyState ref = soa::rk4_step(M, x0, h);
    auto inputs = [&] {
      return code("M", M) + state_code("x0", x0) + "double h = " + num(h) +
             ";\nsoa::FreeBodyState x1 = soa::ex02::rk4_torque_free(M, x0, h);\n";
    };
    checks.add(i, x1, ref, condition(M), tags, inputs, [&] {
      auto v = [&](RK e) { return rk4_variant(M, x0, h, e); };
      return std::vector<std::pair<Mistake, soa::FreeBodyState>>{
          {{"dropped term",
            "your attitude moves with the first stage's rate only, q0 (x) exp(h e1): RK4 "
            "combines all four, exp(h/6 (e1 + 2 e2 + 2 e3 + e4))",
            {}},
           v(RK::FirstStageOnly)},
          {{"dropped term",
            "your delta rates are the angular velocities themselves: e_i = dexp^-1_{-delta_i} "
            "w_i (soa::dexp_inv_right(delta_i, d_i.omega))",
            {}},
           v(RK::NoDexp)},
          {{"wrong frame",
            "your attitudes are exp(delta) (x) q0: delta is a body-frame rotation vector, "
            "q0 (x) exp(delta)",
            {}},
           v(RK::LeftMultiply)},
          {{"dropped term",
            "your stages all use the attitude q0: stage i has q0 (x) exp(delta_i) (it turns "
            "r_dot = R v)",
            {}},
           v(RK::StagesAtQ0)},
          {{"wrong weights",
            "your combination has equal weights: RK4 takes h/6 (k1 + 2 k2 + 2 k3 + k4)",
            {}},
           v(RK::EqualWeights)},
      };
    });
    unit.add(i, one(x1.q.coeffs().norm() - 1), one(0.0), 1.0, tags, inputs);
  }
}

// clang-format off
/* planted mistakes of 2.5
soa_plant(2.5 transpose
  FIND [=[(Vec6<double>() << w.cross(h_w) + v.cross(h_v), w.cross(h_v)).finished()]=]
  WRONG [=[(Vec6<double>() << w.cross(h_w), v.cross(h_w) + w.cross(h_v)).finished()]=]
  TYPE [=[Vec6<double>]=]
  EXPECT [=[likely mistake \(transpose\): your V_bar is V~]=])
*/
// clang-format on
// 2.5: the body-frame form f = M V_dot + V-bar M V, against soa::rigid_body_force at the
// inertial derivative alpha = [w_dot; v_dot + w x v] (lesson 2, section 4).
TEST(Exercise2_5_BodyFrameForce, MatchesLibrary) {
  Random<double> rng;
  Check check("f(x) = M(x) V_dot + V_bar M(x) V, the body-frame form", 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const Body body = draw_body(rng, i);
    unsigned tags = body.tags;
    const soa::SpatialInertia& M = body.M;
    const soa::Velocity V = draw_velocity(rng, i, tags);
    const soa::Acceleration V_dot = draw_acceleration(rng, i, tags);
    const V3 w = V.angular(), v = V.linear();
    const soa::Acceleration alpha(V_dot.angular(), V3(V_dot.linear()) + w.cross(v));
    const V6 ref = soa::rigid_body_force(M, V, alpha).vector();
    // The terms: M V_dot, and V-bar M V with |V-bar| <= |V| (w x v moves into alpha).
    const double scale = M.matrix().norm() * (V_dot.vector().norm() + V.vector().squaredNorm());
    auto mistakes = [&] {
      const V6 h = M.matrix() * V.vector(), f0 = M.matrix() * V_dot.vector();
      const V3 hw = h.head<3>(), hv = h.tail<3>();
      return Mistakes{
          {"transpose",
           "your V_bar is V~ = [w~ 0; v~ w~], the cross product of motion vectors: on the "
           "momentum it is V_bar = -V~* = [w~ v~; 0 w~]",
           f0 + six(w.cross(hw), v.cross(hw) + w.cross(hv))},
          {"sign", "your V_bar M V term has the wrong sign: f = M V_dot + V_bar M V",
           f0 - six(w.cross(hw) + v.cross(hv), w.cross(hv))},
          {"dropped term",
           "V_bar M V is missing: V_dot holds the component rates, not the inertial "
           "acceleration",
           MatX(f0)},
          {"dropped term", "the v~ block of V_bar (v x h_v in the moment) is missing",
           f0 + six(w.cross(hw), w.cross(hv))},
          {"wrong frame",
           "your force is M V_dot + b(x), the inertial form with V_dot taken for alpha: here "
           "V_dot holds the body-frame rates, alpha = [w_dot; v_dot + w x v]",
           f0 + soa::gyroscopic_force(M, V).vector()},
      };
    };
    check.add(
        i, soa::ex02::body_frame_force(M, V, V_dot).vector(), ref, std::max(1.0, scale), tags,
        [&] {
          return code("M", M) + code("V", V) + code("V_dot", V_dot) +
                 "soa::Force f = soa::ex02::body_frame_force(M, V, V_dot);\n";
        },
        mistakes, soa::test::spatial("f(x)"));
  }
}

// 2.6: the prediction against the linearization of soa::rigid_body_acceleration about the
// spin: A = d(w_dot)/dw by central differences (exact for w_dot, a quadratic form in w, up to
// rounding), whose eigenvalues are 0 and +-mu with mu^2 = trace(A^2) / 2. Each case is one
// body and one spin rate, predicted about each of its three principal axes in turn (so that
// a mistaken rule shows against the right one in every case).
double linearized_mu2(const V3& J, int axis, double spin) {
  const soa::SpatialInertia M = soa::SpatialInertia::from_cm(1.0, V3::Zero(), M3(J.asDiagonal()));
  const V3 w0 = spin * V3::Unit(axis);
  auto w_dot = [&](const V3& w) {
    return V3(soa::rigid_body_acceleration(M, soa::Velocity(w, V3::Zero()), soa::Force::Zero())
                  .angular());
  };
  M3 A;
  const double step = std::abs(spin);
  for (int j = 0; j < 3; ++j)
    A.col(j) = (w_dot(w0 + step * V3::Unit(j)) - w_dot(w0 - step * V3::Unit(j))) / (2 * step);
  return (A * A).trace() / 2;
}

Naming axis_naming(const V3& J, const std::string& what) {
  return [J, what](Eigen::Index i, Eigen::Index) {
    char moment[32];
    std::snprintf(moment, sizeof moment, "%.4g", J[i]);
    const std::string a = "axis " + std::to_string(i) + " (J = " + moment + ")";
    return soa::test::EntryName{what + ", " + a, "the spin about " + a};
  };
}

// clang-format off
/* planted mistakes of 2.6
soa_plant(2.6 sign
  FIND [=[s < 0.0]=]
  WRONG [=[s > 0.0]=] TYPE [=[bool]=]
  EXPECT [=[the checker knows this mistake: it names it after 4 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your prediction is the opposite about every axis]=]
  NAMED [=[likely mistake \(sign\): your prediction is the opposite about every axis]=])
*/
// clang-format on
TEST(Exercise2_6_SpinStability, MatchesTheLinearizedLibrary) {
  Random<double> rng(26);
  Check predicted("the prediction, about each principal axis: stable (+1) or unstable (-1)", 0.0),
      rate(
          "the rate, about each principal axis: lambda (1/s) when unstable, nu (rad/s) when "
          "stable",
          64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    // Positive moments that satisfy the triangle inequality, each two at least 0.05 apart,
    // in any order.
    V3 J;
    do {
      J.x() = rng.uniform(0.2, 2);
      J.y() = rng.uniform(0.2, 2);
      J.z() = rng.uniform(std::abs(J.x() - J.y()) + 0.05, J.x() + J.y());
    } while (std::min({std::abs(J.x() - J.y()), std::abs(J.y() - J.z()), std::abs(J.z() - J.x())}) <
             0.05);
    const double spin = (rng.uniform(0, 1) < 0.5 ? -1 : 1) * rng.uniform(0.5, 20);
    V3 got_sign, got_rate, ref_sign, ref_rate, largest, smallest, mu2;
    for (int axis = 0; axis < 3; ++axis) {
      const soa::ex02::SpinStability got = soa::ex02::spin_stability(J, axis, spin);
      got_sign[axis] = got.stable ? 1 : -1;
      got_rate[axis] = got.rate;
      mu2[axis] = linearized_mu2(J, axis, spin);
      ref_sign[axis] = mu2[axis] < 0 ? 1 : -1;
      ref_rate[axis] = std::sqrt(std::abs(mu2[axis]));
      const int j = (axis + 1) % 3, k = (axis + 2) % 3;
      largest[axis] = J[axis] > J[j] && J[axis] > J[k] ? -1 : 1;
      smallest[axis] = J[axis] < J[j] && J[axis] < J[k] ? -1 : 1;
    }
    auto inputs = [&] {
      return code("J", J) + "double spin = " + num(spin) +
             ";\nsoa::ex02::SpinStability s0 = soa::ex02::spin_stability(J, 0, spin);  // and "
             "axis 1, 2\n";
    };
    predicted.add(
        i, got_sign, ref_sign, 1.0, 0, inputs,
        [&] {
          return Mistakes{
              soa::test::negated(ref_sign,
                                 "your prediction is the opposite about every axis: the spin "
                                 "about the intermediate axis is the unstable one, about the "
                                 "largest and the smallest moments it is stable"),
              {"misconception",
               "your unstable spin is about the axis of the largest moment: that one is stable, "
               "like the smallest; the intermediate axis is unstable (lesson 2, section 7)",
               largest},
              {"misconception",
               "your unstable spin is about the axis of the smallest moment: that one is stable "
               "(for a rigid body without dissipation); the intermediate axis is unstable",
               smallest},
              {"missed case",
               "every spin is stable in your prediction: the spin about the intermediate axis is "
               "not (the Dzhanibekov flip of lesson 2, section 7)",
               V3::Ones()},
          };
        },
        axis_naming(J, "stable?"));
    rate.add(
        i, got_rate, ref_rate, std::abs(spin), 0, inputs,
        [&] {
          V3 no_spin = ref_rate / std::abs(spin), squared = ref_rate.cwiseProduct(ref_rate),
             zero_if_stable, wrong_moments;
          for (int axis = 0; axis < 3; ++axis) {
            const int j = (axis + 1) % 3, k = (axis + 2) % 3;
            zero_if_stable[axis] = ref_sign[axis] > 0 ? 0.0 : ref_rate[axis];
            wrong_moments[axis] =
                std::abs(spin) * std::sqrt(std::abs((J[k] - J[axis]) * (J[axis] - J[j]))) / J[axis];
          }
          return Mistakes{
              {"dropped term",
               "your rate lacks the factor |spin|: the linearized equations are proportional to "
               "Omega, so the nudge d obeys d'' = Omega^2 (...) d",
               no_spin},
              {"squared", "your rate is lambda^2 (or nu^2): take the square root", squared},
              {"dropped term",
               "your rate is 0 for a stable spin: it still wobbles, at the frequency nu",
               zero_if_stable},
              {"wrong moments",
               "your denominator is J_axis^2: eliminating one of the two equations divides by "
               "the other two moments, J_j J_k",
               wrong_moments},
          };
        },
        axis_naming(J, "rate"));
  }
}

// The Euler step of 2.7 with a classic mistake in it (the stub's bug among them).
enum class LE { LeftMultiply, UnrotatedR, NoWxV, HalfTurn };
soa::FreeBodyState lie_euler_variant(const soa::SpatialInertia& M, const soa::FreeBodyState& x0,
                                     const soa::Force& f, double h, LE e) {
  const soa::FreeBodyRateT<double> d = soa::free_body_rate(M, x0, f);
  const V3 w = x0.V.angular(), v = x0.V.linear();
  V6 V_dot = d.V_dot;
  if (e == LE::NoWxV) V_dot.tail<3>() += w.cross(v);
  soa::FreeBodyState x1;
  x1.q = e == LE::LeftMultiply ? soa::UnitQuaternion::exp(h * w) * x0.q
         : e == LE::HalfTurn   ? x0.q * soa::UnitQuaternion::exp(h / 2 * w)
                               : x0.q * soa::UnitQuaternion::exp(h * w);
  x1.r = x0.r + h * (e == LE::UnrotatedR ? v : d.r_dot);
  x1.V = soa::Velocity(V6(x0.V.vector() + h * V_dot));
  return x1;
}

// clang-format off
/* planted mistakes of 2.7
soa_plant(2.7 the-bug
  FIND [=[x0.q * UnitQuaternion::exp(h * w)]=]
  WRONG [=[UnitQuaternion::exp(h * w) * x0.q]=] TYPE [=[UnitQuaternion]=]
  EXPECT [=[the checker knows this mistake: it names it after 3 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your attitude is exp\(h w\) \(x\) q0, the given code's bug]=]
  NAMED [=[likely mistake \(wrong frame\): your attitude is exp\(h w\) \(x\) q0, the given code's bug]=])
*/
// clang-format on
// 2.7: the Euler step, fixed, against the same step built from the library's rates
// (soa::free_body_rate) and the exact turn q0 (x) exp(h w).
TEST(Exercise2_7_LieEulerStep, MatchesTheLibraryRates) {
  Random<double> rng(27);
  StateChecks checks("one Euler step (x1)", 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const Body body = draw_body(rng, i);
    unsigned tags = body.tags;
    const soa::SpatialInertia& M = body.M;
    const soa::FreeBodyState x0 = draw_state(rng, i, tags);
    const soa::Force f = draw_force(rng, i, tags);
    const double h = rng.uniform(0.01, 0.2);
    const soa::FreeBodyState x1 = soa::ex02::lie_euler_step(M, x0, f, h);
    const soa::FreeBodyRateT<double> d = soa::free_body_rate(M, x0, f);
    soa::FreeBodyState ref;
    ref.q = x0.q * soa::UnitQuaternion::exp(h * d.omega);
    ref.r = x0.r + h * d.r_dot;
    ref.V = soa::Velocity(V6(x0.V.vector() + h * d.V_dot));
    auto inputs = [&] {
      return code("M", M) + state_code("x0", x0) + code("f", f) + "double h = " + num(h) +
             ";\nsoa::FreeBodyState x1 = soa::ex02::lie_euler_step(M, x0, f, h);\n";
    };
    checks.add(i, x1, ref, condition(M), tags, inputs, [&] {
      auto v = [&](LE e) { return lie_euler_variant(M, x0, f, h, e); };
      return std::vector<std::pair<Mistake, soa::FreeBodyState>>{
          {{"wrong frame",
            "your attitude is exp(h w) (x) q0, the given code's bug: w is the body-frame "
            "angular velocity, R_dot = R w~, so the turn multiplies on the right, q0 (x) "
            "exp(h w)",
            {}},
           v(LE::LeftMultiply)},
          {{"wrong frame",
            "your position moves along v in body coordinates: r is inertial, r_dot = R v",
            {}},
           v(LE::UnrotatedR)},
          {{"dropped term",
            "your V_dot is alpha: the body-frame rates have v_dot = alpha_v - w x v",
            {}},
           v(LE::NoWxV)},
          {{"half angle",
            "your attitude turns by h w / 2: UnitQuaternion::exp takes the rotation vector "
            "itself (the half angle is inside it)",
            {}},
           v(LE::HalfTurn)},
      };
    });
  }
}
