// Lesson 4 exercise tests: each exercise of exercises/04-serial-chain-dynamics/exercises.hpp
// against the library, on soa::test::kCases random chains (1 to 7 bodies, hinge types drawn at
// random unless the exercise is for revolute chains; at rest or moving, with or without gravity and
// external forces: tests/support/chain_case.hpp) from the fixed seed. Each check names its
// quantity, and its catalogue of classic mistakes is computed from the reference
// (tests/support/exercise_check.hpp). Built against the solutions (ctest), the students' exercises
// (make exercises) and the solutions with planted mistakes (the "planted mistakes" blocks,
// tests/exercises/plant.cmake).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "chain_case.hpp"
#include "exercise_check.hpp"
#include "exercises.hpp"
#include "property.hpp"
#include "random_chain.hpp"

namespace {

using soa::test::CaseOptions;
using soa::test::ChainCase;
using soa::test::Check;
using soa::test::kCases;
using soa::test::Mistake;
using soa::test::Mistakes;
using soa::test::Random;
using VecX = soa::VecX<double>;
using MatX = soa::MatX<double>;
using soa::test::stack;
using Vec3 = soa::Vec3<double>;
using Mat3 = soa::Mat3<double>;

constexpr double kEps = soa::eps<double>();

// The library's inverse dynamics: T, and the inter-body forces f in ws.
VecX library_T(const soa::Model& m, const soa::State& x, const VecX& beta_dot,
               const soa::ExternalForces<double>& f_ext, soa::Workspace& ws) {
  VecX T(m.nv());
  soa::inverse_dynamics(m, x, beta_dot, f_ext, ws, T);
  return T;
}

// The magnitude that rounding errors of T and f scale with: the inter-body forces.
double force_scale(const soa::Workspace& ws) {
  return std::max(1.0, stack(ws.f).norm());
}

// H(k) f for every body: the hinge forces of stacked inter-body forces.
VecX hinge_forces(const soa::Model& m, const VecX& theta, const VecX& f) {
  VecX T(m.nv());
  for (int k = 1; k <= m.n(); ++k) {
    const soa::Body& B = m.body(k);
    B.hinge.H_times(theta.data() + B.q_offset, soa::Force(f.segment<6>(6 * (k - 1))),
                    T.data() + B.v_offset);
  }
  return T;
}

// The gather sweep of 4.1 with a classic mistake in it (or none): the catalogue's variants.
enum class Gather { Right, NeighbourPhi, TransposedPhi, NoB, MinusB, NoInertial };
VecX gather(const soa::Model& m, const std::vector<soa::Phi>& phi,
            const std::vector<soa::Acceleration>& alpha, const std::vector<soa::Force>& b,
            Gather g) {
  VecX f = VecX::Zero(6 * m.n());
  for (int k = 1; k <= m.n(); ++k) {
    const auto i = std::size_t(k - 1);
    soa::Vec6<double> fk =
        g == Gather::NoInertial ? soa::Vec6<double>::Zero() : (m.body(k).M * alpha[i]).vector();
    if (g != Gather::NoB) fk += (g == Gather::MinusB ? -1.0 : 1.0) * b[i].vector();
    if (k > 1) {
      const soa::Vec6<double> child = f.segment<6>(6 * Eigen::Index(i - 1));
      if (g == Gather::NeighbourPhi)
        fk += phi[i].matrix() * child;  // phi(k+1,k): the next body's
      else if (g == Gather::TransposedPhi)
        fk += phi[i - 1].matrix().transpose() * child;
      else
        fk += phi[i - 1].matrix() * child;
    }
    f.segment<6>(6 * Eigen::Index(i)) = fk;
  }
  return f;
}

}  // namespace

// clang-format off
/* planted mistakes of 4.1
soa_plant(4.1 neighbour-index
  FIND [=[phi[i - 1].apply(g.f[i - 1])]=]
  WRONG [=[phi[i].apply(g.f[i - 1])]=]
  EXPECT [=[likely mistake \(neighbour index\): your f\(k\) takes phi\(k\+1,k\)]=])
*/
// clang-format on
// 4.1: the gather sweep, given phi, alpha and b from the library's scatter sweep, against
// soa::inverse_dynamics (gravity and external forces included).
TEST(Exercise4_1_GatherForces, MatchesInverseDynamics) {
  Random<double> rnd;
  Check f_check("f(k), the inter-body forces", 64 * kEps),
      T_check("T, the hinge forces", 64 * kEps);
  const CaseOptions opt{true, true, true, true, false};
  for (int i = 0; i < kCases; ++i) {
    const ChainCase c = soa::test::draw_chain_case(rnd, i, opt);
    const soa::Model& m = c.m;
    soa::Workspace ws(m);
    soa::update_phi(m, c.x.theta, ws);
    soa::update_velocities(m, c.x, ws);
    soa::update_accelerations(m, c.x, c.beta_dot.data(), soa::gravity_base_acceleration(m), ws);
    std::vector<soa::Force> b;
    for (int k = 1; k <= m.n(); ++k) {
      soa::Force bk = soa::gyroscopic_force(m.body(k).M, ws.V[std::size_t(k - 1)]);
      if (!c.f_ext.empty()) bk -= c.f_ext[std::size_t(k - 1)];
      b.push_back(bk);
    }
    const soa::ex04::Gathered g = soa::ex04::gather_forces(m, c.x.theta, ws.phi, ws.alpha, b);
    soa::Workspace ref(m);
    const VecX T = library_T(m, c.x, c.beta_dot, c.f_ext, ref);
    const double scale = force_scale(ref);
    auto inputs = [&] {
      return c.code() +
             "// phi, alpha and b from the library's scatter sweep:\n"
             "soa::Workspace ws(m);\nsoa::update_phi(m, x.theta, ws);\n"
             "soa::update_velocities(m, x, ws);\nsoa::update_accelerations(m, x, "
             "beta_dot.data(), soa::gravity_base_acceleration(m), ws);\n"
             "// b(k) = soa::gyroscopic_force(m.body(k).M, ws.V[k-1]) - f_ext[k-1]\n"
             "auto g = soa::ex04::gather_forces(m, x.theta, ws.phi, ws.alpha, b);\n";
    };
    struct Variant {
      Gather g;
      const char* kind;
      const char* says;
    };
    static const Variant variants[] = {
        {Gather::NeighbourPhi, "neighbour index",
         "your f(k) takes phi(k+1,k) f(k-1), i.e. phi[k-1]: phi(k,k-1) is phi[k-2]"},
        {Gather::TransposedPhi, "transpose",
         "your f(k) takes phi*(k,k-1) f(k-1), the transpose: forces go inward with phi, not "
         "phi* (phi[k-2].apply(f), lesson 1)"},
        {Gather::NoB, "dropped term", "b(k) is missing from your f(k) (gyroscopic less external)"},
        {Gather::MinusB, "sign", "your f(k) subtracts b(k): f(k) = ... + M(k) alpha(k) + b(k)"},
        {Gather::NoInertial, "dropped term", "M(k) alpha(k) is missing from your f(k)"},
    };
    auto f_mistakes = [&] {
      Mistakes out;
      for (const Variant& v : variants)
        out.push_back(Mistake{v.kind, v.says, gather(m, ws.phi, ws.alpha, b, v.g)});
      return out;
    };
    auto T_mistakes = [&] {
      Mistakes out;
      for (const Variant& v : variants)
        out.push_back(Mistake{v.kind, v.says,
                              hinge_forces(m, c.x.theta, gather(m, ws.phi, ws.alpha, b, v.g))});
      return out;
    };
    if (int(g.f.size()) != m.n()) {
      f_check.add(i, VecX::Zero(6 * Eigen::Index(g.f.size())), stack(ref.f), scale, c.tags, inputs);
      continue;
    }
    f_check.add(i, stack(g.f), stack(ref.f), scale, c.tags, inputs, f_mistakes,
                soa::test::per_body_spatial("f"));
    T_check.add(i, g.T, T, scale, c.tags, inputs, T_mistakes, soa::test::per_dof(m, "T"));
  }
}

// The Newton-Euler sweeps of 4.2 for a revolute chain with a classic mistake in them.
enum class NE { GravitySign, NoCoriolis, NoCentripetal, NoGyroscopic, LinearPart, UnrotatedL };
VecX newton_euler_variant(const soa::Model& m, const soa::State& x, const VecX& beta_dot, NE e) {
  const auto n = std::size_t(m.n());
  std::vector<soa::Phi> phi(n);
  std::vector<soa::Velocity> V(n);
  std::vector<soa::Acceleration> alpha(n);
  soa::Velocity Vp = soa::Velocity::Zero();
  soa::Acceleration ap(Vec3::Zero(), e == NE::GravitySign ? Vec3(m.gravity) : Vec3(-m.gravity));
  for (int k = m.n(); k >= 1; --k) {
    const soa::Body& B = m.body(k);
    const auto i = std::size_t(k - 1);
    const Vec3 a = B.hinge.axis;
    const double th = x.theta[B.q_offset], be = x.beta[B.v_offset], bd = beta_dot[B.v_offset];
    phi[i] = soa::Phi(B.placement * soa::Pose(soa::exp_so3<double>(th * a), Vec3::Zero()));
    const Mat3 Rt = phi[i].R().transpose();
    const Vec3 w = Rt * Vec3(Vp.angular());
    const Vec3 l = e == NE::UnrotatedL ? Vec3(phi[i].l()) : Vec3(Rt * phi[i].l());
    V[i] = phi[i].transpose_apply(Vp) + soa::Velocity(be * a, Vec3::Zero());
    const Vec3 ang = e == NE::NoCoriolis ? Vec3::Zero() : Vec3(w.cross(be * a));
    const Vec3 lin =
        e == NE::NoCoriolis || e == NE::NoCentripetal ? Vec3::Zero() : Vec3(w.cross(w.cross(l)));
    alpha[i] = phi[i].transpose_apply(ap) + soa::Acceleration(bd * a, Vec3::Zero()) +
               soa::Acceleration(ang, lin);
    Vp = V[i];
    ap = alpha[i];
  }
  VecX T(m.nv());
  soa::Force fc = soa::Force::Zero();
  for (int k = 1; k <= m.n(); ++k) {
    const soa::Body& B = m.body(k);
    const auto i = std::size_t(k - 1);
    soa::Force f = B.M * alpha[i];
    if (e != NE::NoGyroscopic) f += soa::gyroscopic_force(B.M, V[i]);
    if (k > 1) f += phi[i - 1].apply(fc);
    T[B.v_offset] = B.hinge.axis.dot(e == NE::LinearPart ? Vec3(f.linear()) : Vec3(f.angular()));
    fc = f;
  }
  return T;
}

// clang-format off
/* planted mistakes of 4.2
soa_plant(4.2 gravity-sign
  FIND [=[-m.gravity]=]
  WRONG [=[m.gravity]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(sign\): your base acceleration is alpha\(n\+1\) = \[0; \+g\]]=])
soa_plant(4.2 unrotated-l
  FIND [=[Rt * phi[i].l()]=]
  WRONG [=[phi[i].l()]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(wrong frame\)]=])
soa_plant(4.2 coriolis-doubled
  FIND [=[w_parent.cross(be * a)]=]
  WRONG [=[2.0 * w_parent.cross(be * a)]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[symptom: it fails only where it moves \(the velocities are not zero\): [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
*/
// clang-format on
// 4.2: Newton-Euler inverse dynamics of random revolute chains with gravity, against
// soa::inverse_dynamics.
TEST(Exercise4_2_NewtonEuler, MatchesInverseDynamics) {
  Random<double> rnd;
  Check check("T, the hinge forces", 64 * kEps);
  const CaseOptions opt{false, true, true, false, false};
  for (int i = 0; i < kCases; ++i) {
    const ChainCase c = soa::test::draw_chain_case(rnd, i, opt);
    const VecX T = soa::ex04::newton_euler(c.m, c.x, c.beta_dot);
    soa::Workspace ref(c.m);
    const VecX T_ref = library_T(c.m, c.x, c.beta_dot, {}, ref);
    auto mistakes = [&] {
      auto v = [&](NE e) { return newton_euler_variant(c.m, c.x, c.beta_dot, e); };
      return Mistakes{
          {"sign", "your base acceleration is alpha(n+1) = [0; +g]: gravity enters as [0; -g]",
           v(NE::GravitySign)},
          {"dropped term", "the Coriolis term a(k) is missing from your alpha(k)",
           v(NE::NoCoriolis)},
          {"dropped term",
           "the linear part of a(k), omega' x (omega' x l), is missing from your alpha(k)",
           v(NE::NoCentripetal)},
          {"dropped term",
           "the gyroscopic term b(k) is missing from your f(k) (soa::gyroscopic_force)",
           v(NE::NoGyroscopic)},
          {"wrong part",
           "your T(k) is a* F(k), the linear part: a revolute hinge takes the moment N(k), the "
           "angular part (angular first)",
           v(NE::LinearPart)},
          {"wrong frame",
           "your l is phi(k+1,k).l(), in O_{k+1} coordinates: a(k) needs l = R* l, in O_k "
           "coordinates",
           v(NE::UnrotatedL)},
      };
    };
    check.add(
        i, T, T_ref, force_scale(ref), c.tags,
        [&] {
          return c.code() + "soa::VecX<double> T = soa::ex04::newton_euler(m, x, beta_dot);\n";
        },
        mistakes, soa::test::per_dof(c.m, "T"));
  }
}

// phi = (I - E)^{-1} of a stacked shift operator, and the first-order (I + E) of a mistake.
MatX phi_of(const MatX& E) {
  const Eigen::Index N = E.rows();
  return (MatX::Identity(N, N) - E).triangularView<Eigen::UnitLower>().solve(MatX::Identity(N, N));
}

// The operators of a chain case as code (they are built by the library from the chain).
std::string operators_code(const ChainCase& c) {
  return c.code() +
         "soa::Operators op = soa::Operators::build(m, x, f_ext);\n"
         "op.phi.setZero();  // the exercise computes it\n";
}

// clang-format off
/* planted mistakes of 4.3
soa_plant(4.3 transpose
  FIND [=[phi.transpose() * op.H.transpose()]=]
  WRONG [=[phi * op.H.transpose()]=] TYPE [=[MatX<double>]=]
  EXPECT [=[likely mistake \(transpose\): your result is H phi\* M phi H\*]=])
*/
// clang-format on
// 4.3: H phi M phi* H* with phi computed from E_phi (op.phi is zeroed), against
// soa::OperatorsT::mass_matrix().
TEST(Exercise4_3_MassMatrixOperators, MatchesOperators) {
  Random<double> rnd;
  Check check("the mass matrix M = H phi M phi* H*", 64 * kEps);
  const CaseOptions opt{true, true, true, false, false};
  for (int i = 0; i < kCases; ++i) {
    const ChainCase c = soa::test::draw_chain_case(rnd, i, opt);
    soa::Operators op = soa::Operators::build(c.m, c.x);
    const MatX M_ref = op.mass_matrix();
    const MatX phi = op.phi, E = op.E_phi, H = op.H, M = op.M;
    op.phi.setZero();
    const MatX M_student = soa::ex04::mass_matrix_operators(op);
    auto mistakes = [&] {
      const Eigen::Index N = E.rows();
      const MatX first = MatX::Identity(N, N) + E;
      const MatX plus = (MatX::Identity(N, N) + E).inverse();
      return Mistakes{
          {"transpose",
           "your result is H phi* M phi H*: phi and phi* swapped (B = phi* H*, M = B* M B)",
           H * phi.transpose() * M * phi * H.transpose()},
          {"dropped term",
           "your phi is I + E_phi, the first term of the series: phi = (I - E_phi)^{-1} = I + "
           "E_phi + E_phi^2 + ...",
           H * first * M * first.transpose() * H.transpose()},
          {"sign", "your phi is (I + E_phi)^{-1}: phi = (I - E_phi)^{-1}",
           H * plus * M * plus.transpose() * H.transpose()},
      };
    };
    check.add(
        i, M_student, M_ref, M_ref.norm(), c.tags,
        [&] {
          return operators_code(c) +
                 "soa::MatX<double> M = soa::ex04::mass_matrix_operators(op);\n";
        },
        mistakes, soa::test::dof_blocks(c.m, "M"));
  }
}

// 4.4: the mass matrix from nv + 1 inverse dynamics calls (gravity and springs in the model),
// against soa::OperatorsT::mass_matrix().
TEST(Exercise4_4_MassMatrixColumns, MatchesOperators) {
  Random<double> rnd;
  Check check("the mass matrix, column j = T(e_j) - T(0)", 64 * kEps);
  const CaseOptions opt{true, true, true, false, true};
  for (int i = 0; i < kCases; ++i) {
    const ChainCase c = soa::test::draw_chain_case(rnd, i, opt);
    const soa::Model& m = c.m;
    const MatX M = soa::ex04::mass_matrix_columns(m, c.x.theta);
    const soa::State rest{c.x.theta, VecX::Zero(m.nv())};
    const MatX M_ref = soa::Operators::build(m, rest).mass_matrix();
    // Column j is a difference of two inverse dynamics results: rounding scales with the
    // forces of the static part T(0) (gravity, springs) as well as with M.
    soa::Workspace ws(m);
    const VecX T0 = library_T(m, rest, VecX::Zero(m.nv()), {}, ws);
    auto mistakes = [&] {
      const VecX Tb = library_T(m, c.x, VecX::Zero(m.nv()), {}, ws);
      return Mistakes{
          {"dropped term",
           "your column j is T(beta_dot = e_j) without subtracting T(beta_dot = 0): gravity "
           "and springs are left in",
           M_ref + T0 * VecX::Ones(m.nv()).transpose()},
          {"wrong state",
           "your columns are taken at the moving state, without subtracting its T(0): use beta "
           "= 0 (or subtract T at beta_dot = 0 at the same beta)",
           M_ref + Tb * VecX::Ones(m.nv()).transpose()},
      };
    };
    check.add(
        i, M, M_ref, M_ref.norm() + force_scale(ws), c.tags,
        [&] {
          return c.code() + "soa::MatX<double> M = soa::ex04::mass_matrix_columns(m, x.theta);\n";
        },
        mistakes, soa::test::dof_blocks(m, "M"));
  }
}

// clang-format off
/* planted mistakes of 4.5
soa_plant(4.5 dropped-b
  FIND [=[op.M * (phi.transpose() * op.a) + op.b]=]
  WRONG [=[op.M * (phi.transpose() * op.a)]=] TYPE [=[VecX<double>]=]
  EXPECT [=[likely mistake \(dropped term\): b \(gyroscopic less external forces\) is missing]=])
*/
// clang-format on
// 4.5: C = H phi (M phi* a + b) with phi from E_phi (op.phi zeroed), against the O(N)
// soa::inverse_dynamics at beta_dot = 0 (gravity and external forces included).
TEST(Exercise4_5_BiasOperators, MatchesInverseDynamics) {
  Random<double> rnd;
  Check check("C, the hinge forces at beta_dot = 0", 64 * kEps);
  const CaseOptions opt{true, true, true, true, false};
  for (int i = 0; i < kCases; ++i) {
    const ChainCase c = soa::test::draw_chain_case(rnd, i, opt);
    soa::Operators op = soa::Operators::build(c.m, c.x, c.f_ext);
    const MatX phi = op.phi, H = op.H, M = op.M;
    const VecX a = op.a, b = op.b;
    op.phi.setZero();
    const VecX C = soa::ex04::bias_operators(op);
    soa::Workspace ref(c.m);
    const VecX C_ref = library_T(c.m, c.x, VecX::Zero(c.m.nv()), c.f_ext, ref);
    auto mistakes = [&] {
      return Mistakes{
          {"dropped term",
           "b (gyroscopic less external forces) is missing: C = H phi (M phi* a + b)",
           H * phi * (M * (phi.transpose() * a))},
          {"dropped term", "the M phi* a part (Coriolis and gravity) is missing", H * phi * b},
          {"transpose", "your result is H phi* (M phi a + b): phi and phi* swapped",
           H * phi.transpose() * (M * (phi * a) + b)},
          {"sign", "your result subtracts b: C = H phi (M phi* a + b)",
           H * phi * (M * (phi.transpose() * a) - b)},
      };
    };
    check.add(
        i, C, C_ref, force_scale(ref), c.tags,
        [&] {
          return operators_code(c) + "soa::VecX<double> C = soa::ex04::bias_operators(op);\n";
        },
        mistakes, soa::test::per_dof(c.m, "C"));
  }
}

// clang-format off
/* planted mistakes of 4.6
soa_plant(4.6 wrong-frame
  FIND [=[ws.pose[std::size_t(k - 1)].R().transpose() * m.gravity]=]
  WRONG [=[m.gravity]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(wrong frame\)]=])
*/
// clang-format on
// 4.6: gravity torques from the Jacobians of the centres of mass, against
// soa::inverse_dynamics at rest with gravity.
TEST(Exercise4_6_GravityTorques, MatchesInverseDynamics) {
  Random<double> rnd;
  Check check("G, the hinge forces that hold the chain against gravity", 64 * kEps);
  const CaseOptions opt{true, true, false, false, false};
  for (int i = 0; i < kCases; ++i) {
    ChainCase c = soa::test::draw_chain_case(rnd, i, opt);
    c.m.gravity = Vec3(0, 0, -9.81);  // always: without it G = 0
    c.tags |= soa::test::kGravity;
    const soa::Model& m = c.m;
    const VecX G = soa::ex04::gravity_torques(m, c.x.theta);
    soa::Workspace ref(m);
    const VecX G_ref =
        library_T(m, soa::State{c.x.theta, VecX::Zero(m.nv())}, VecX::Zero(m.nv()), {}, ref);
    auto mistakes = [&] {
      // -sum J*(P) f with the force at P in P's axes: P at C_k or O_k, g rotated or not.
      soa::Workspace ws(m);
      soa::update_phi(m, c.x.theta, ws);
      soa::update_poses(m, ws);
      VecX unrotated = VecX::Zero(m.nv()), at_origin = VecX::Zero(m.nv());
      Eigen::Matrix<double, 6, Eigen::Dynamic> J(6, m.nv());
      for (int k = 1; k <= m.n(); ++k) {
        const soa::SpatialInertia& Mk = m.body(k).M;
        const Mat3 R = ws.pose[std::size_t(k - 1)].R();
        soa::Vec6<double> f;
        soa::jacobian(m, c.x.theta, ws, k, soa::Pose(Mat3::Identity(), Mk.p()), J);
        f << Vec3::Zero(), Mk.mass() * m.gravity;
        unrotated -= J.transpose() * f;
        soa::jacobian(m, c.x.theta, ws, k, soa::Pose(), J);
        f << Vec3::Zero(), Mk.mass() * (R.transpose() * m.gravity);
        at_origin -= J.transpose() * f;
      }
      return Mistakes{
          soa::test::negated(G_ref,
                             "your G has the opposite sign: it is the force that holds "
                             "the chain, -sum J* [0; m g], not gravity's"),
          {"wrong frame",
           "your force m_k g is in inertial coordinates: the Jacobian at C_k has the axes of O_k, "
           "so the force is [0; m_k R_k* g]",
           unrotated},
          {"wrong point", "your Jacobian is at O_k, not at the centre of mass C_k", at_origin},
      };
    };
    check.add(
        i, G, G_ref, force_scale(ref), c.tags,
        [&] {
          return c.code() + "soa::VecX<double> G = soa::ex04::gravity_torques(m, x.theta);\n";
        },
        mistakes, soa::test::per_dof(m, "G"));
  }
}

// clang-format off
/* planted mistakes of 4.7
soa_plant(4.7 transpose
  FIND [=[B.transpose() * (es.op.M * B_dot + es.h_breve * B)]=]
  WRONG [=[(B.transpose() * (es.op.M * B_dot + es.h_breve * B)).transpose()]=]
  TYPE [=[MatX<double>]=]
  EXPECT [=[likely mistake \(transpose\): your result is C_v\*]=])
*/
// clang-format on
// 4.7: the Coriolis matrix from the operators, against soa::EnergyStructureT::coriolis_matrix()
// and, independently, C_v beta against the O(N) inverse dynamics at beta_dot = 0 without
// gravity. Rounding scales with the terms |B|^2 (|M| |Delta_bar| |phi| + |h_breve|).
TEST(Exercise4_7_CoriolisMatrixOperators, MatchesLibraryAndInverseDynamics) {
  Random<double> rnd;
  Check check("C_v, the Coriolis matrix", 64 * kEps);
  Check check_beta("C_v beta against inverse dynamics at beta_dot = 0", 64 * kEps);
  const CaseOptions opt{true, false, true, false, false};
  for (int i = 0; i < kCases; ++i) {
    const ChainCase c = soa::test::draw_chain_case(rnd, i, opt);
    const soa::Model& m = c.m;
    const soa::EnergyStructure es = soa::EnergyStructure::build(m, c.x);
    const MatX C = soa::ex04::coriolis_matrix_operators(es);
    const MatX B = es.B();
    const double terms = std::max(
        1e-300, B.squaredNorm() * (es.op.M.norm() * es.Delta_bar.norm() * es.op.phi.norm() +
                                   es.op.M.norm() * es.H_dot.norm() / std::max(1e-300, B.norm()) +
                                   es.h_breve.norm()));
    const MatX C_ref = es.coriolis_matrix();
    auto inputs = [&] {
      return c.code() +
             "soa::EnergyStructure es = soa::EnergyStructure::build(m, x);\n"
             "soa::MatX<double> C = soa::ex04::coriolis_matrix_operators(es);\n";
    };
    auto mistakes = [&] {
      const MatX& phi = es.op.phi;
      const MatX phi_dot = (phi - MatX::Identity(phi.rows(), phi.cols())) * es.Delta_bar * phi;
      const MatX Ht = es.op.H.transpose(), Hdt = es.H_dot.transpose();
      const MatX Bd = phi_dot.transpose() * Ht + phi.transpose() * Hdt;
      return Mistakes{
          {"dropped term", "the h_breve B term is missing: C_v = B* (M B_dot + h_breve B)",
           B.transpose() * es.op.M * Bd},
          {"dropped term", "phi_dot* H* is missing from your B_dot (the body-to-body rates)",
           B.transpose() * (es.op.M * (phi.transpose() * Hdt) + es.h_breve * B)},
          {"dropped term", "phi* H_dot* is missing from your B_dot (the hinge map's rate)",
           B.transpose() * (es.op.M * (phi_dot.transpose() * Ht) + es.h_breve * B)},
          {"transpose", "your result is C_v*, the transpose", C_ref.transpose()},
          {"sign",
           "your phi_dot has the opposite sign: phi_tilde = phi - I, phi_dot = phi_tilde "
           "Delta_bar phi",
           B.transpose() *
               (es.op.M * (-phi_dot.transpose() * Ht + phi.transpose() * Hdt) + es.h_breve * B)},
      };
    };
    if (check.add(i, C, C_ref, terms, c.tags, inputs, mistakes, soa::test::dof_blocks(m, "C_v"))) {
      soa::Workspace ws(m);
      const VecX C0 = library_T(m, c.x, VecX::Zero(m.nv()), {}, ws);
      check_beta.add(i, C * c.x.beta, C0, std::max(1e-300, terms * c.x.beta.norm()), c.tags,
                     inputs);
    }
  }
}

// The Coriolis term of a helical hinge (exercise 4.8) with a classic mistake in it (or none),
// from w' = R* omega(k+1), l = R* ell, the axis a, the pitch h and beta.
enum class Screw { Right, Revolute, SlideOnce, SlideSign, BodyOmega, AngularOrder };
soa::Acceleration helical_variant(const Vec3& w, const Vec3& l, const Vec3& a, double h, double b,
                                  Screw e) {
  const Vec3 wk = w + b * a;  // omega(k)
  const Vec3& u = e == Screw::BodyOmega ? wk : w;
  const Vec3 ang = e == Screw::AngularOrder ? Vec3((b * a).cross(w)) : Vec3(u.cross(b * a));
  const double slide = e == Screw::Revolute    ? 0.0
                       : e == Screw::SlideOnce ? 1.0
                       : e == Screw::SlideSign ? -2.0
                                               : 2.0;
  return soa::Acceleration(ang, u.cross(u.cross(l)) + slide * b * h * u.cross(a));
}

// clang-format off
/* planted mistakes of 4.8
soa_plant(4.8 slide-once
  FIND [=[2.0 * beta * pitch * w.cross(axis)]=]
  WRONG [=[beta * pitch * w.cross(axis)]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[the checker knows this mistake: it names it after 4 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your linear part has h beta omega' x a once]=]
  NAMED [=[likely mistake \(dropped term\): your linear part has h beta omega' x a once]=])
*/
// clang-format on
// 4.8: a(k) of a helical hinge against soa::coriolis_term, on random single hinges: the
// inboard body's velocity V(k+1) = [omega; v] (v random: the result must not depend on it),
// phi(k+1,k) rotated or not, offset or not, the hinge turning or not, a screw or a plain
// revolute (h = 0), each varying independently.
TEST(Exercise4_8_HelicalCoriolis, MatchesCoriolisTerm) {
  Random<double> rnd;
  Check check("a(k), the Coriolis term of the screw", 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const Mat3 R = i % 2 == 1 ? rnd.rotation() : Mat3::Identity();
    const Vec3 ell = i % 3 != 0 ? rnd.vec3() : Vec3::Zero();
    const Vec3 wp = rnd.vec3(), vp = rnd.vec3();  // V(k+1), O_{k+1} coordinates
    const Vec3 axis = rnd.unit3();
    const double pitch = i % 4 == 1 ? 0.0 : rnd.uniform(-0.5, 0.5);
    const double beta = i % 5 == 0 ? 0.0 : rnd.normal();
    const soa::Phi phi(R, ell);
    const soa::Velocity Vp(wp, vp), dV(beta * axis, beta * pitch * axis);
    const soa::Velocity V = phi.transpose_apply(Vp) + dV;
    const soa::Acceleration a_ref = soa::coriolis_term(phi, Vp, V, dV, soa::Acceleration());
    const Vec3 w = R.transpose() * wp, l = R.transpose() * ell;
    const soa::Acceleration a = soa::ex04::helical_coriolis(w, l, axis, pitch, beta);
    unsigned tags = 0;
    if (i % 2 == 1) tags |= soa::test::kRotated;
    if (i % 3 != 0) tags |= soa::test::kTranslated;
    if (beta != 0) tags |= soa::test::kMoving;
    if (pitch != 0) tags |= soa::test::kHelical;
    // Rounding of the reference grows with the velocities it multiplies, v(k+1) included.
    const double scale =
        std::max(1.0, (wp.norm() + std::abs(beta)) * (vp.norm() + wp.norm() * ell.norm() +
                                                      std::abs(beta) * (1 + std::abs(pitch))));
    auto mistakes = [&] {
      auto v = [&](Screw e) { return MatX(helical_variant(w, l, axis, pitch, beta, e).vector()); };
      return Mistakes{
          {"dropped term",
           "your a(k) is the revolute hinge's of exercise 4.2: the screw also slides, Delta_v = "
           "h beta a, and the turning of body k+1 changes that velocity too: what does omega' "
           "do to it?",
           v(Screw::Revolute)},
          {"dropped term",
           "your linear part has h beta omega' x a once: the slide enters twice, as omega(k) x "
           "Delta_v (the sliding velocity turns with the bodies) and in omega' x (v(k) - "
           "v(k+1)) (the lever arm grows along the axis)",
           v(Screw::SlideOnce)},
          {"sign",
           "your slide term has the opposite sign: write v(k) - v(k+1) = omega' x l + Delta_v "
           "and keep the order of the cross products",
           v(Screw::SlideSign)},
          {"neighbour index",
           "your a(k) uses omega(k) = omega' + beta a where the formula has omega' = omega(k+1) "
           "(the Coriolis term comes from the inboard body's rotation)",
           v(Screw::BodyOmega)},
          {"sign", "your angular part is beta a x omega': it is omega' x beta a",
           v(Screw::AngularOrder)},
      };
    };
    check.add(
        i, a.vector(), a_ref.vector(), scale, tags,
        [&] {
          return soa::test::code("omega_parent", w) + soa::test::code("l", l) +
                 soa::test::code("axis", axis) + "double pitch = " + soa::test::num(pitch) +
                 ", beta = " + soa::test::num(beta) +
                 ";\nsoa::Acceleration a = soa::ex04::helical_coriolis(omega_parent, l, axis, "
                 "pitch, beta);\n";
        },
        mistakes, soa::test::spatial("a(k)"));
  }
}

// The signs of exercise 4.9 from the statics of the hinges, with a classic mistake in it (or
// none): G(k) = -a_k* sum_{i carried} l(P, C_i) x m_i g, 0 when |G(k)| <= 1e-9 W_k.
enum class Statics { Right, OwnBody, Inboard, AllBodies, AxisUnrotated, AboutOrigin };
VecX statics_signs(const soa::Model& m, const soa::Workspace& ws, Statics e) {
  VecX s(m.nv());
  for (int k = 1; k <= m.n(); ++k) {
    const soa::Pose& O = ws.pose[std::size_t(k - 1)];
    const Vec3 a = e == Statics::AxisUnrotated ? Vec3(m.body(k).hinge.axis)
                                               : Vec3(O.R() * m.body(k).hinge.axis);
    const Vec3 P = e == Statics::AboutOrigin ? Vec3::Zero() : Vec3(O.l());
    const int first = e == Statics::OwnBody || e == Statics::Inboard ? k : 1;
    const int last = e == Statics::Inboard || e == Statics::AllBodies ? m.n() : k;
    Vec3 moment = Vec3::Zero();
    double W = 0;
    for (int i = first; i <= last; ++i) {
      const soa::SpatialInertia& Mi = m.body(i).M;
      const Vec3 c = ws.pose[std::size_t(i - 1)].apply(Mi.p());
      moment += (c - P).cross(Mi.mass() * m.gravity);
      W += Mi.mass() * (1 + (c - Vec3(O.l())).norm());
    }
    const double G = -a.dot(moment);
    s[m.body(k).v_offset] = std::abs(G) <= 1e-9 * W * m.gravity.norm() ? 0.0 : G > 0 ? 1.0 : -1.0;
  }
  return s;
}

// clang-format off
/* planted mistakes of 4.9
soa_plant(4.9 sign
  FIND [=[-a.dot(moment)]=]
  WRONG [=[a.dot(moment)]=] TYPE [=[double]=]
  EXPECT [=[the checker knows this mistake: it names it after 4 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your signs are those of gravity's torque]=]
  NAMED [=[likely mistake \(sign\): your signs are those of gravity's torque]=])
soa_plant(4.9 pose-of-hinge
  FIND [=[ws.pose[std::size_t(i - 1)].apply(Mi.p())]=]
  WRONG [=[O.apply(Mi.p())]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[symptom: it fails only where there is more than one body: [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
*/
// clang-format on
// 4.9: the signs against those of soa::inverse_dynamics at rest, on revolute chains under
// gravity along -z; in every third case one or two hinges have their axis turned vertical
// (no gravity torque, whatever the pose). An entry whose torque is within a factor 1000 of the
// threshold either way is not judged.
TEST(Exercise4_9_GravityTorqueSigns, MatchesInverseDynamics) {
  Random<double> rnd;
  Check check("the signs of G(k), the hinge forces that hold the chain", 1e-4);
  const CaseOptions opt{false, true, false, false, false};
  int zeros = 0;  // hinges without gravity torque among the cases
  for (int i = 0; i < kCases; ++i) {
    ChainCase c = soa::test::draw_chain_case(rnd, i, opt);
    soa::Model& m = c.m;
    m.gravity = Vec3(0, 0, -9.81);
    c.tags |= soa::test::kGravity;
    soa::Workspace ws(m);
    if (i % 3 == 0)  // axes turned vertical, base to tip: the inboard poses stay as they are
      for (int k = m.n(); k >= 1; --k) {
        if (rnd.engine()() % 2 == 0 && k != 1 + i % m.n()) continue;
        soa::update_phi(m, c.x.theta, ws);
        soa::update_poses(m, ws);
        const Mat3 R_in = k < m.n() ? Mat3(ws.pose[std::size_t(k)].R()) : Mat3::Identity();
        m.body(k).hinge.axis = (R_in * m.body(k).placement.R()).transpose() * Vec3::UnitZ();
      }
    soa::update_phi(m, c.x.theta, ws);
    soa::update_poses(m, ws);
    const VecX s = soa::ex04::gravity_torque_signs(m, c.x.theta);
    soa::Workspace ref(m);
    const VecX G = library_T(m, c.x, VecX::Zero(m.nv()), {}, ref);
    // The reference signs, and the entries too close to the threshold to judge.
    VecX expected(m.nv()), got = s;
    for (int k = 1; k <= m.n(); ++k) {
      double W = 0;
      for (int b = 1; b <= k; ++b)
        W += m.body(b).M.mass() * (1 + (ws.pose[std::size_t(b - 1)].apply(m.body(b).M.p()) -
                                        ws.pose[std::size_t(k - 1)].l())
                                           .norm());
      W *= m.gravity.norm();
      const int d = m.body(k).v_offset;
      const double g = G[d];
      expected[d] = std::abs(g) <= 1e-9 * W ? 0.0 : g > 0 ? 1.0 : -1.0;
      zeros += expected[d] == 0;
      if (std::abs(g) > 1e-12 * W && std::abs(g) <= 1e-6 * W && got.size() == expected.size())
        got[d] = expected[d];
    }
    auto mistakes = [&] {
      auto v = [&](Statics e) { return MatX(statics_signs(m, ws, e)); };
      return Mistakes{
          soa::test::negated(expected,
                             "your signs are those of gravity's torque: G(k) is the force of the "
                             "hinge that holds the chain, which pushes the other way"),
          {"dropped term",
           "you took body k's weight alone: hinge k holds up everything outboard of it, bodies "
           "1 ... k (the tip is body 1)",
           v(Statics::OwnBody)},
          {"neighbour index",
           "you took the bodies inboard of hinge k (k ... n): hinge k carries the bodies outboard "
           "of it, 1 ... k (the tip is body 1)",
           v(Statics::Inboard)},
          {"neighbour index",
           "you took every body of the chain: hinge k carries only bodies 1 ... k, the inboard "
           "ones rest on the hinges nearer the base",
           v(Statics::AllBodies)},
          {"wrong frame",
           "your axis a_k is in O_k coordinates while the moment is in inertial ones: turn it, "
           "R_k a_k (ws.pose[k-1].R())",
           v(Statics::AxisUnrotated)},
          {"wrong point",
           "your moment is about the inertial origin: a hinge turns about its own axis, take "
           "moments about a point of it (O_k)",
           v(Statics::AboutOrigin)},
      };
    };
    check.add(
        i, got, expected, 1.0, c.tags,
        [&] {
          return c.code() + "soa::VecX<double> s = soa::ex04::gravity_torque_signs(m, x.theta);\n";
        },
        mistakes, soa::test::per_dof(m, "sign G"));
  }
  EXPECT_GT(zeros, kCases / 5) << "the cases should have hinges with a vertical axis";
}
