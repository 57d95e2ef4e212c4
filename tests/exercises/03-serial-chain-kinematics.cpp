// Lesson 3 exercise tests: each exercise of exercises/03-serial-chain-kinematics/exercises.hpp
// against the library, on soa::test::kCases random cases from the fixed seed: chains of 1 to 7
// bodies whose features vary independently across the cases (hinge types drawn at random; every
// third chain has no offsets, l = 0 and only hinges that turn, so that a mistake in an offset term
// shows as a symptom). Each check names its quantity, and its catalogue of classic mistakes is
// computed from the reference (tests/support/exercise_check.hpp). Built against the solutions
// (ctest), the students' exercises (make exercises) and the solutions with planted mistakes (the
// "planted mistakes" blocks, tests/exercises/plant.cmake).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "exercise_check.hpp"
#include "exercises.hpp"
#include "property.hpp"
#include "random_chain.hpp"

namespace {

using soa::HingeType;
using soa::test::Check;
using soa::test::code;
using soa::test::EntryName;
using soa::test::kCases;
using soa::test::Mistake;
using soa::test::Mistakes;
using soa::test::Naming;
using soa::test::Random;
using Vec3 = soa::Vec3<double>;
using Mat3 = soa::Mat3<double>;
using Mat6 = soa::Mat6<double>;
using Vec6 = soa::Vec6<double>;
using VecX = soa::VecX<double>;
using MatX = soa::MatX<double>;
using soa::test::stack;
using Matrix6X = soa::ex03::Matrix6X;

constexpr double kEps = soa::eps<double>();
const double kPi = std::acos(-1.0);

// A random case of lesson 3: a chain, its state (always moving), and the library's scatter
// sweep (phi, poses, V, a) with the hinge velocities dV(k) = H*(k) beta(k).
struct KinCase {
  soa::Model m;
  soa::State x;
  soa::Workspace ws;
  std::vector<soa::Velocity> dV;
  std::vector<soa::Acceleration> Hdot_beta;
  unsigned tags = 0;

  explicit KinCase(soa::Model model) : m(std::move(model)), ws(m) {}
  std::string code() const { return soa::test::code("m", m) + soa::test::code("x", x); }
  // The lines that build phi and dV from the chain, as the test gives them.
  static std::string scatter_code() {
    return "soa::Workspace ws(m);\nsoa::update_phi(m, x.theta, ws);  // ws.phi[k-1] = "
           "phi(k+1,k)\n"
           "std::vector<soa::Velocity> dV;  // dV[k-1] = H*(k) beta(k)\n"
           "for (int k = 1; k <= m.n(); ++k)\n"
           "  dV.push_back(m.body(k).hinge.H_star_times(x.theta.data() + m.body(k).q_offset,\n"
           "                                            x.beta.data() + m.body(k).v_offset));\n";
  }
};

// Case i: 1 + i mod 7 bodies; when i mod 3 = 0 no offsets (placements with l = 0 and only
// revolute, universal and spherical hinges), else hinge types drawn from the six.
KinCase draw_kin_case(Random<double>& rnd, int i) {
  const int n = 1 + i % 7;
  const bool untranslated = i % 3 == 0;
  static const HingeType turning[3] = {HingeType::Revolute, HingeType::Universal,
                                       HingeType::Spherical};
  std::vector<soa::Body> bodies;
  for (int b = 0; b < n; ++b) {
    const unsigned draw = unsigned(rnd.engine()());
    const HingeType type = untranslated ? turning[draw % 3] : HingeType(draw % 6);
    soa::Body B = soa::test::detail::random_body(rnd, b, type, soa::test::ChainOptions{});
    if (untranslated) B.placement = soa::Pose(B.placement.R(), Vec3::Zero());
    bodies.push_back(B);
  }
  KinCase c(soa::Model::from_base_first(bodies));
  c.x = soa::test::random_state(rnd, c.m);
  soa::update_phi(c.m, c.x.theta, c.ws);
  soa::update_poses(c.m, c.ws);
  soa::update_velocities(c.m, c.x, c.ws);
  for (int k = 1; k <= c.m.n(); ++k) {
    const soa::Body& B = c.m.body(k);
    c.dV.push_back(
        B.hinge.H_star_times(c.x.theta.data() + B.q_offset, c.x.beta.data() + B.v_offset));
    c.Hdot_beta.push_back(
        B.hinge.H_star_dot_times(c.x.theta.data() + B.q_offset, c.x.beta.data() + B.v_offset));
  }
  c.tags = soa::test::chain_tags(c.m, c.x);
  for (const soa::Phi& p : c.ws.phi) {
    if (p.l().norm() > 0) c.tags |= soa::test::kTranslated;
    if (!p.R().isIdentity(0)) c.tags |= soa::test::kRotated;
  }
  return c;
}

// The scale of the chain's positions: 1 + the sum of its offsets |l|.
double reach(const std::vector<soa::Phi>& phi) {
  double s = 1;
  for (const soa::Phi& p : phi) s += p.l().norm();
  return s;
}

// Names the entries of a 6 x n joint map or Jacobian: rows angular / linear, columns by dof.
Naming columns_naming(const std::string& sym, const std::vector<std::string>& column_part) {
  return [sym, column_part](Eigen::Index r, Eigen::Index c) {
    const std::string half = r < 3 ? "angular" : "linear";
    const std::string col =
        c < Eigen::Index(column_part.size()) ? column_part[std::size_t(c)] : "column ?";
    return EntryName{sym + "(" + std::to_string(r) + "," + std::to_string(c) + ") (" + half + ")",
                     col + ", " + half + " rows"};
  };
}

std::vector<std::string> hinge_columns(const soa::Model& m) {
  std::vector<std::string> parts;
  for (int k = 1; k <= m.n(); ++k)
    for (int d = 0; d < m.body(k).hinge.nv(); ++d)
      parts.push_back("the columns of hinge " + std::to_string(k) + " (" +
                      soa::hinge_type_name(m.body(k).hinge.type) + ")");
  return parts;
}

std::string hinge_code(const soa::Hinge& h, const VecX& theta) {
  std::string s = "soa::Hinge hinge;\nhinge.type = soa::HingeType::" +
                  std::string(soa::test::hinge_enum(h.type)) + ";\n" +
                  "hinge.axis = soa::Vec3<double>" + soa::test::list(h.axis) + ";\n";
  if (h.type == HingeType::Universal)
    s += "hinge.axis2 = soa::Vec3<double>" + soa::test::list(h.axis2) + ";\n";
  if (h.type == HingeType::Helical) s += "hinge.pitch = " + soa::test::num(h.pitch) + ";\n";
  return s + code("theta", theta);
}

}  // namespace

// clang-format off
/* planted mistakes of 3.1
soa_plant(3.1 universal-transpose
  FIND [=[exp_so3<double>(-theta[1] * hinge.axis2) * a]=]
  WRONG [=[exp_so3<double>(theta[1] * hinge.axis2) * a]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(transpose\): your first column is exp\(\+theta_2 a_2~\) a]=])
*/
// clang-format on
// 3.1: H*(k) of every hinge type, against soa::Hinge::H_star.
TEST(Exercise3_1_JointMap, MatchesLibrary) {
  Random<double> rnd;
  Check check("H*(k), the joint map", 8 * kEps);
  for (int i = 0; i < kCases; ++i) {
    soa::Hinge hinge;
    hinge.type = HingeType(i % 7);
    hinge.axis = rnd.unit3();
    hinge.axis2 = rnd.unit3();
    hinge.pitch = rnd.uniform(-0.5, 0.5);
    VecX theta = soa::test::random_vector(rnd, hinge.nq());
    if (hinge.nq() >= 4) theta.head<4>().normalize();
    const Matrix6X Hs = soa::ex03::joint_map(hinge, theta);
    const Matrix6X ref = hinge.H_star(theta.data());
    unsigned tags = 0;
    if (hinge.type == HingeType::Prismatic) tags |= soa::test::kPrismatic;
    if (hinge.type == HingeType::Helical) tags |= soa::test::kHelical;
    if (hinge.nv() > 1) tags |= soa::test::kMultiDof;
    auto mistakes = [&] {
      Mistakes out{soa::test::negated(ref, "your H* has the opposite sign")};
      MatX swapped(6, ref.cols());
      swapped << ref.bottomRows<3>(), ref.topRows<3>();
      out.push_back({"wrong part",
                     "your H* has the angular and linear parts swapped: spatial vectors are "
                     "angular part first, [omega; v], so a revolute column is [a; 0] and a "
                     "prismatic one [0; a]",
                     swapped});
      const Vec3 a = hinge.axis;
      if (hinge.type == HingeType::Helical) {
        MatX no_pitch = ref, per_turn = ref;
        no_pitch.col(0).tail<3>().setZero();
        per_turn.col(0).tail<3>() = 2 * kPi * hinge.pitch * a;
        out.push_back({"dropped term",
                       "the pitch term is missing: a helical hinge advances h a per radian, "
                       "H* = [a; h a]",
                       no_pitch});
        out.push_back({"units",
                       "your linear part is 2 pi h a: h is the advance per radian (one turn, "
                       "2 pi radians, advances 2 pi h), so H* = [a; h a]",
                       per_turn});
      }
      if (hinge.type == HingeType::Universal) {
        const Vec3 a2 = hinge.axis2;
        auto with_first = [&](const Vec3& c1) {
          MatX H = ref;
          H.col(0).head<3>() = c1;
          return H;
        };
        out.push_back({"transpose",
                       "your first column is exp(+theta_2 a_2~) a, turned the wrong way: a is "
                       "fixed in O_k+, and in O_k coordinates it is R* a = exp(-theta_2 a_2~) a "
                       "(the transpose)",
                       with_first(soa::exp_so3<double>(theta[1] * a2) * a)});
        out.push_back({"wrong frame",
                       "your first column is a, the first axis in O_k+ coordinates: H* is in "
                       "O_k coordinates, where it is exp(-theta_2 a_2~) a",
                       with_first(a)});
        out.push_back({"degrees",
                       "your rotation takes theta_2 in degrees: angles are in radians "
                       "(exp_so3(-theta_2 a_2), no pi/180)",
                       with_first(soa::exp_so3<double>(-theta[1] * kPi / 180 * a2) * a)});
        MatX order(6, 2);
        order << ref.col(1), ref.col(0);
        out.push_back({"order",
                       "your columns are in the wrong order: column 1 belongs to theta_1 (the "
                       "turn about a), column 2 to theta_2 (about a_2)",
                       order});
      }
      return out;
    };
    std::vector<std::string> cols;
    for (int c = 0; c < hinge.nv(); ++c)
      cols.push_back(std::string("column ") + std::to_string(c + 1) + " (" +
                     soa::hinge_type_name(hinge.type) + ")");
    check.add(
        i, Hs, ref, 1.0, tags,
        [&] {
          return hinge_code(hinge, theta) +
                 "soa::ex03::Matrix6X Hs = soa::ex03::joint_map(hinge, theta);\n";
        },
        mistakes, columns_naming("H*", cols));
  }
}

// The velocity scatter of 3.2 with a classic mistake in it.
enum class Scatter { Applied, RotationOnly, NoParent, MinusHinge, FromTip };
VecX scatter_variant(const std::vector<soa::Phi>& phi, const std::vector<soa::Velocity>& dV,
                     Scatter s) {
  const int n = int(phi.size());
  std::vector<soa::Velocity> V(phi.size());
  soa::Velocity Vp;
  auto step = [&](int k) {
    const soa::Phi& p = phi[std::size_t(k - 1)];
    soa::Velocity moved;
    switch (s) {
      case Scatter::Applied:
        moved = soa::Velocity(Vec6(p.matrix() * Vp.vector()));
        break;
      case Scatter::RotationOnly:
        moved = soa::Velocity(Vec3(p.R().transpose() * Vp.angular()),
                              Vec3(p.R().transpose() * Vp.linear()));
        break;
      case Scatter::NoParent:
        break;
      default:
        moved = p.transpose_apply(Vp);
    }
    const soa::Velocity d = dV[std::size_t(k - 1)];
    V[std::size_t(k - 1)] = s == Scatter::MinusHinge ? moved - d : moved + d;
    Vp = V[std::size_t(k - 1)];
  };
  if (s == Scatter::FromTip)
    for (int k = 1; k <= n; ++k) step(k);
  else
    for (int k = n; k >= 1; --k) step(k);
  return stack(V);
}

// clang-format off
/* planted mistakes of 3.2
soa_plant(3.2 transpose
  FIND [=[phi[k - 1].transpose_apply(V_parent)]=]
  WRONG [=[Velocity(Vec6<double>(phi[k-1].matrix() * V_parent.vector()))]=]
  TYPE [=[Velocity]=]
  EXPECT [=[likely mistake \(transpose\): your V\(k\) takes phi\(k\+1,k\) V\(k\+1\)]=])
soa_plant(3.2 rotation-only
  FIND [=[phi[k - 1].transpose_apply(V_parent)]=]
  WRONG [=[Velocity(Vec3<double>(phi[k-1].R().transpose() * V_parent.angular()), Vec3<double>(phi[k-1].R().transpose() * V_parent.linear()))]=]
  TYPE [=[Velocity]=]
  EXPECT [=[likely mistake \(dropped term\): your V\(k\) turns V\(k\+1\) by R\* but leaves out the offset]=])
*/
// clang-format on
// 3.2: the velocity scatter recursion, against soa::update_velocities.
TEST(Exercise3_2_ScatterVelocities, MatchesLibrary) {
  Random<double> rnd;
  Check check("V(k), the body velocities", 16 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const KinCase c = draw_kin_case(rnd, i);
    const std::vector<soa::Velocity> V = soa::ex03::scatter_velocities(c.ws.phi, c.dV);
    double scale = 1;
    for (const soa::Velocity& Vk : c.ws.V) scale = std::max(scale, Vk.vector().norm());
    auto mistakes = [&] {
      auto v = [&](Scatter s) { return scatter_variant(c.ws.phi, c.dV, s); };
      return Mistakes{
          {"transpose",
           "your V(k) takes phi(k+1,k) V(k+1): velocities move outward with phi*, "
           "phi[k-1].transpose_apply(V), forces inward with phi",
           v(Scatter::Applied)},
          {"dropped term",
           "your V(k) turns V(k+1) by R* but leaves out the offset: phi* V = [R* w; R*(v + w x "
           "l)], the velocity of the point O_k of body k+1 (transpose_apply does it)",
           v(Scatter::RotationOnly)},
          {"dropped term",
           "your V(k) is the hinge velocity H*(k) beta(k) alone: body k also moves with body "
           "k+1, phi*(k+1,k) V(k+1)",
           v(Scatter::NoParent)},
          {"sign", "your V(k) subtracts H*(k) beta(k): V(k) = phi*(k+1,k) V(k+1) + H*(k) beta(k)",
           v(Scatter::MinusHinge)},
          {"wrong direction",
           "your sweep runs from the tip (k = 1 first): V(n+1) = 0 is at the base, so the "
           "scatter runs k = n, n-1, ..., 1",
           v(Scatter::FromTip)},
      };
    };
    check.add(
        i, stack(V), stack(c.ws.V), scale * reach(c.ws.phi), c.tags,
        [&] {
          return c.code() + KinCase::scatter_code() +
                 "auto V = soa::ex03::scatter_velocities(ws.phi, dV);\n";
        },
        mistakes, soa::test::per_body_spatial("V"));
  }
}

// E_phi with a classic mistake: blocks transposed, the whole transposed, the neighbour's
// phi, or the blocks on the diagonal.
enum class Shift { BlocksTransposed, Transposed, Neighbour, Diagonal };
MatX shift_variant(const std::vector<soa::Phi>& phi, Shift s) {
  const int n = int(phi.size());
  MatX E = MatX::Zero(6 * n, 6 * n);
  for (int k = 1; k < n; ++k) {
    const Mat6 P = phi[std::size_t(s == Shift::Neighbour ? k : k - 1)].matrix();
    if (s == Shift::BlocksTransposed)
      E.block<6, 6>(6 * k, 6 * (k - 1)) = P.transpose();
    else if (s == Shift::Transposed)
      E.block<6, 6>(6 * (k - 1), 6 * k) = P.transpose();
    else if (s == Shift::Diagonal)
      E.block<6, 6>(6 * (k - 1), 6 * (k - 1)) = P;
    else
      E.block<6, 6>(6 * k, 6 * (k - 1)) = P;
  }
  return E;
}

std::string phi_list_code() {
  return "soa::Workspace ws(m);\nsoa::update_phi(m, x.theta, ws);  // ws.phi[k-1] = "
         "phi(k+1,k)\n";
}

// clang-format off
/* planted mistakes of 3.3
soa_plant(3.3 neighbour-index
  FIND [=[phi[k - 1].matrix()]=]
  WRONG [=[phi[k].matrix()]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(neighbour index\): block \(k\+1, k\) of yours holds phi\(k\+2,k\+1\)]=])
*/
// clang-format on
// 3.3: the shift operator E_phi, against soa::Operators::E_phi.
TEST(Exercise3_3_ShiftOperator, MatchesLibrary) {
  Random<double> rnd;
  Check check("E_phi, the shift operator", 4 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const KinCase c = draw_kin_case(rnd, i);
    const MatX E = soa::ex03::shift_operator(c.ws.phi);
    const soa::Operators op = soa::Operators::build(c.m, c.x);
    auto mistakes = [&] {
      auto v = [&](Shift s) { return shift_variant(c.ws.phi, s); };
      return Mistakes{
          {"transpose",
           "your blocks are phi*(k+1,k), the transposes: block (k+1, k) of E_phi is the 6x6 "
           "phi(k+1,k) itself, phi[k-1].matrix()",
           v(Shift::BlocksTransposed)},
          {"transpose",
           "your result is E_phi*: phi*(k+1,k) at block (k, k+1), above the diagonal; E_phi "
           "has phi(k+1,k) at block row k+1, column k, below it",
           v(Shift::Transposed)},
          {"neighbour index",
           "block (k+1, k) of yours holds phi(k+2,k+1), phi[k]: phi(k+1,k) is phi[k-1]",
           v(Shift::Neighbour)},
          {"neighbour index",
           "your phi(k+1,k) sits on the diagonal, block (k, k): it belongs at block row k+1, "
           "column k (rows 6k ... 6k+5)",
           v(Shift::Diagonal)},
      };
    };
    check.add(
        i, E, op.E_phi, std::max(1.0, op.E_phi.norm()), c.tags,
        [&] {
          return c.code() + phi_list_code() +
                 "soa::MatX<double> E = soa::ex03::shift_operator(ws.phi);\n";
        },
        mistakes, soa::test::body_blocks("E_phi"));
  }
}

// phi block by block with a classic mistake: transposed, the products in reverse order,
// without the identity blocks, or only its first two terms I + E_phi.
enum class PhiOp { Transposed, Reversed, NoIdentity, FirstOrder };
MatX phi_variant(const std::vector<soa::Phi>& phi, PhiOp v) {
  const int n = int(phi.size());
  MatX P = MatX::Zero(6 * n, 6 * n);
  for (int j = 1; j <= n; ++j) {
    Mat6 block = Mat6::Identity();
    if (v != PhiOp::NoIdentity) P.block<6, 6>(6 * (j - 1), 6 * (j - 1)) = block;
    for (int i = j; i < n; ++i) {
      const Mat6 step = phi[std::size_t(i - 1)].matrix();
      block = v == PhiOp::Reversed ? Mat6(block * step) : Mat6(step * block);
      if (v == PhiOp::FirstOrder && i > j) break;
      P.block<6, 6>(6 * i, 6 * (j - 1)) = block;
    }
  }
  return v == PhiOp::Transposed
             ? MatX(phi_variant(phi, PhiOp::NoIdentity).transpose() + MatX::Identity(6 * n, 6 * n))
             : P;
}

// clang-format off
/* planted mistakes of 3.4
soa_plant(3.4 order
  FIND [=[phi[i - 1].matrix() * block]=]
  WRONG [=[block * phi[i - 1].matrix()]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(order\): your products run the wrong way]=])
*/
// clang-format on
// 3.4: phi block by block, against soa::Operators::phi = (I - E_phi)^-1, and (I - E_phi) phi = I.
TEST(Exercise3_4_PhiOperator, MatchesLibrary) {
  Random<double> rnd;
  Check check("phi = (I - E_phi)^-1, block by block", 64 * kEps);
  Check check_inverse("(I - E_phi) phi - I, the inverse's residual", 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const KinCase c = draw_kin_case(rnd, i);
    const MatX P = soa::ex03::phi_operator(c.ws.phi);
    const soa::Operators op = soa::Operators::build(c.m, c.x);
    const double scale = std::max(1.0, op.phi.norm());
    const Eigen::Index N = 6 * c.m.n();
    const MatX I = MatX::Identity(N, N);
    auto inputs = [&] {
      return c.code() + phi_list_code() +
             "soa::MatX<double> P = soa::ex03::phi_operator(ws.phi);\n";
    };
    auto variants = [&](bool residual) {
      auto v = [&](PhiOp o) {
        const MatX Pv = phi_variant(c.ws.phi, o);
        return residual ? MatX((I - op.E_phi) * Pv - I) : Pv;
      };
      return Mistakes{
          {"transpose",
           "your result is phi*: phi(i,j) belongs below the diagonal, at block row i > j "
           "(block (i,j) is phi(i,i-1) ... phi(j+1,j))",
           v(PhiOp::Transposed)},
          {"order",
           "your products run the wrong way, phi(j+1,j) ... phi(i,i-1): phi(i+1,j) = "
           "phi(i+1,i) phi(i,j), the new factor on the left",
           v(PhiOp::Reversed)},
          {"dropped term", "your diagonal blocks are zero: phi(i,i) = I", v(PhiOp::NoIdentity)},
          {"dropped term",
           "your phi stops at I + E_phi: every block below the first sub-diagonal, phi(i,j) "
           "for i > j + 1, is a product phi(i,i-1) ... phi(j+1,j) too",
           v(PhiOp::FirstOrder)},
      };
    };
    // The library inverts I - E_phi: its own rounding grows like the condition, |phi|^2.
    check.add(
        i, P, op.phi, scale * scale, c.tags, inputs, [&] { return variants(false); },
        soa::test::body_blocks("phi"));
    if (P.rows() == N && P.cols() == N)
      check_inverse.add(
          i, MatX((I - op.E_phi) * P - I), MatX::Zero(N, N), scale, c.tags, inputs,
          [&] { return variants(true); }, soa::test::body_blocks("(I - E_phi) phi - I"));
  }
}

// The Jacobian of 3.5 with a classic mistake: columns of hinges first..n, with phi(O_i,F)
// transposed or not, of the frame \p F on body k.
MatX jacobian_variant(const KinCase& c, int k, const soa::Pose& F, int first, bool transposed) {
  const soa::Model& m = c.m;
  MatX J = MatX::Zero(6, m.nv());
  const soa::Pose T_F = c.ws.pose[std::size_t(k - 1)] * F;
  for (int i = std::max(first, 1); i <= m.n(); ++i) {
    const soa::Body& B = m.body(i);
    const Mat6 P = soa::Phi(c.ws.pose[std::size_t(i - 1)].inverse() * T_F).matrix();
    J.middleCols(B.v_offset, B.hinge.nv()) =
        (transposed ? Mat6(P.transpose()) : P) * B.hinge.H_star(c.x.theta.data() + B.q_offset);
  }
  return J;
}

// clang-format off
/* planted mistakes of 3.5
soa_plant(3.5 transpose
  FIND [=[phi_iF.transpose() * B.hinge.H_star(theta.data() + B.q_offset)]=]
  WRONG [=[phi_iF * B.hinge.H_star(theta.data() + B.q_offset)]=] TYPE [=[MatX<double>]=]
  EXPECT [=[likely mistake \(transpose\): your columns are phi\(O_i, F\) H\*\(i\)]=])
soa_plant(3.5 frame-ignored
  FIND [=[ws.pose[k - 1] * frame]=]
  WRONG [=[ws.pose[k - 1]]=] TYPE [=[Pose]=]
  EXPECT [=[likely mistake \(wrong frame\): your J is the Jacobian of O_k]=])
*/
// clang-format on
// 3.5: the Jacobian of a random frame on a random body, against soa::jacobian.
TEST(Exercise3_5_FrameJacobian, MatchesLibrary) {
  Random<double> rnd;
  Check check("J, the Jacobian of the frame F", 32 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const KinCase c = draw_kin_case(rnd, i);
    const soa::Model& m = c.m;
    const int k = 1 + (i % m.n());
    const soa::Pose frame(rnd.rotation(), rnd.vec3());
    const Matrix6X J = soa::ex03::frame_jacobian(m, c.x.theta, k, frame);
    Eigen::Matrix<double, 6, Eigen::Dynamic> ref;
    soa::jacobian(m, c.x.theta, c.ws, k, frame, ref);
    auto mistakes = [&] {
      const Mat3 R_F = (c.ws.pose[std::size_t(k - 1)] * frame).R();
      Mat6 to_inertial = Mat6::Zero();
      to_inertial.topLeftCorner<3, 3>() = R_F;
      to_inertial.bottomRightCorner<3, 3>() = R_F;
      return Mistakes{
          soa::test::negated(ref, "your J has the opposite sign"),
          {"transpose",
           "your columns are phi(O_i, F) H*(i): a velocity moves to F with phi*(O_i, F) (the "
           "transpose), J = B* phi* H*",
           jacobian_variant(c, k, frame, k, false)},
          {"wrong frame",
           "your J is the Jacobian of O_k, the frame of body k: the frame F = O_k T_F is "
           "missing",
           jacobian_variant(c, k, soa::Pose(), k, true)},
          {"wrong frame",
           "your J leaves out the rotation of F: O_k T_F turns the axes too, not only the "
           "origin",
           jacobian_variant(c, k, soa::Pose(Mat3::Identity(), frame.l()), k, true)},
          {"wrong frame",
           "your J gives V(F) in inertial coordinates: V(F) = J beta is in F coordinates",
           to_inertial * ref},
          {"wrong range",
           "your J has columns for the hinges outboard of body k (i < k): they do not move F, "
           "their columns are zero",
           jacobian_variant(c, k, frame, 1, true)},
          {"dropped term",
           "your J has no columns for hinge k itself: the hinges i >= k, body k's own "
           "included, move F",
           jacobian_variant(c, k, frame, k + 1, true)},
      };
    };
    check.add(
        i, J, ref, std::max(1.0, ref.norm()) * (reach(c.ws.phi) + frame.l().norm()), c.tags,
        [&] {
          return c.code() + code("F_R", frame.R()) + code("F_l", frame.l()) +
                 "soa::Pose frame(F_R, F_l);\nint k = " + std::to_string(k) +
                 ";\nauto J = soa::ex03::frame_jacobian(m, x.theta, k, frame);\n";
        },
        mistakes, columns_naming("J", hinge_columns(m)));
  }
}

// The Coriolis term of 3.6 with a classic mistake in it.
enum class Coriolis { Right, NoFreeTerm, NoHdot, Unrotated, Transposed, Sign, MovedParent };
soa::Acceleration coriolis_variant(const soa::Phi& phi, const soa::Velocity& Vp,
                                   const soa::Velocity& dV, const soa::Acceleration& Hdot,
                                   Coriolis e) {
  const soa::Velocity V = phi.transpose_apply(Vp) + dV;
  Mat3 Rt = phi.R().transpose();
  if (e == Coriolis::Unrotated) Rt.setIdentity();
  if (e == Coriolis::Transposed) Rt = phi.R();
  const Vec3 w_p = Rt * Vp.angular();
  const Vec3 v_p =
      e == Coriolis::MovedParent ? Vec3(phi.transpose_apply(Vp).linear()) : Vec3(Rt * Vp.linear());
  const Vec3 w = V.angular(), v = V.linear(), dw = dV.angular(), dv = dV.linear();
  const Vec3 rel = e == Coriolis::Sign ? Vec3(v_p - v) : Vec3(v - v_p);
  const Vec3 lin = (e == Coriolis::NoFreeTerm ? w_p : w).cross(dv) + w_p.cross(rel);
  soa::Acceleration a(w_p.cross(dw), lin);
  if (e != Coriolis::NoHdot) a += Hdot;
  return a;
}

// clang-format off
/* planted mistakes of 3.6
soa_plant(3.6 unrotated-parent
  FIND [=[phi.R().transpose()]=]
  WRONG [=[Mat3<double>::Identity()]=] TYPE [=[Mat3<double>]=]
  EXPECT [=[likely mistake \(wrong frame\): your omega\(k\+1\) and v\(k\+1\) are V_parent's halves as given]=])
soa_plant(3.6 no-free-term
  FIND [=[w.cross(dv)]=]
  WRONG [=[w_p.cross(dv)]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(dropped term\): your linear part has omega\(k\+1\) x dv]=])
soa_plant(3.6 relative-sign
  FIND [=[v - v_p]=]
  WRONG [=[v_p - v]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(sign\): your relative velocity is v\(k\+1\) - v\(k\)]=])
# Not in the catalogue: the angular part doubled. Zero for a single body (V(n+1) = 0), so
# the report gives the symptom.
soa_plant(3.6 angular-doubled
  FIND [=[w_p.cross(dw)]=]
  WRONG [=[2.0 * w_p.cross(dw)]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[symptom: it fails only where there is more than one body: [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
*/
// clang-format on
// 3.6: the Coriolis term a(k) of every body of random chains, against soa::coriolis_term (as
// soa::update_velocities computes it).
TEST(Exercise3_6_CoriolisAcceleration, MatchesLibrary) {
  Random<double> rnd;
  Check check("a(k), the Coriolis terms", 32 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const KinCase c = draw_kin_case(rnd, i);
    const soa::Model& m = c.m;
    std::vector<soa::Acceleration> a;
    double scale = 1;
    auto parent = [&](int k) { return k < m.n() ? c.ws.V[std::size_t(k)] : soa::Velocity(); };
    for (int k = 1; k <= m.n(); ++k) {
      const auto j = std::size_t(k - 1);
      a.push_back(
          soa::ex03::coriolis_acceleration(c.ws.phi[j], parent(k), c.dV[j], c.Hdot_beta[j]));
      scale = std::max({scale, c.ws.V[j].vector().squaredNorm(), parent(k).vector().squaredNorm()});
    }
    auto mistakes = [&] {
      auto v = [&](Coriolis e) {
        std::vector<soa::Acceleration> out;
        for (int k = 1; k <= m.n(); ++k) {
          const auto j = std::size_t(k - 1);
          out.push_back(coriolis_variant(c.ws.phi[j], parent(k), c.dV[j], c.Hdot_beta[j], e));
        }
        return MatX(stack(out));
      };
      return Mistakes{
          {"dropped term",
           "your linear part has omega(k+1) x dv where the statement has omega(k) x dv: the "
           "difference, dw x dv, is non-zero only for free hinges",
           v(Coriolis::NoFreeTerm)},
          {"dropped term",
           "the rate of the joint map, Hdot* beta (the Hdot_beta argument), is missing: it is "
           "non-zero for universal hinges",
           v(Coriolis::NoHdot)},
          {"wrong frame",
           "your omega(k+1) and v(k+1) are V_parent's halves as given, in O_{k+1} coordinates: "
           "bring them to O_k by R* = phi.R().transpose()",
           v(Coriolis::Unrotated)},
          {"transpose",
           "your omega(k+1) and v(k+1) are turned by R = phi.R(): O_{k+1} to O_k coordinates "
           "is R* = phi.R().transpose()",
           v(Coriolis::Transposed)},
          {"sign", "your relative velocity is v(k+1) - v(k): the statement has v(k) - v(k+1)",
           v(Coriolis::Sign)},
          {"wrong frame",
           "your v(k+1) is phi* V(k+1), the velocity of body k+1 at the point O_k: v(k+1) is "
           "the velocity of the point O_{k+1}, turned by the rotation alone (R* v)",
           v(Coriolis::MovedParent)},
      };
    };
    check.add(
        i, stack(a), stack(c.ws.a), scale * reach(c.ws.phi), c.tags,
        [&] {
          return c.code() + KinCase::scatter_code() +
                 "soa::update_velocities(m, x, ws);  // ws.V[k-1] = V(k)\n"
                 "// for each k: V_parent = k < m.n() ? ws.V[k] : soa::Velocity(), Hdot_beta = "
                 "m.body(k).hinge.H_star_dot_times(...)\n"
                 "auto a_k = soa::ex03::coriolis_acceleration(ws.phi[k-1], V_parent, dV[k-1], "
                 "Hdot_beta);\n";
        },
        mistakes, soa::test::per_body_spatial("a"));
  }
}

// The planar hinge of 3.7, by the derivation of its solution (checked against finite
// differences below): H* = [a 0 0; 0 R*b R*c], Hdot beta = [0; beta_1 v x a] with
// v = R*(beta_2 b + beta_3 c). \p Rt stands for R* (variants pass another rotation).
Matrix6X planar_H(const Vec3& a, const Vec3& b, const Mat3& Rt) {
  Matrix6X H = Matrix6X::Zero(6, 3);
  H.col(0).head<3>() = a;
  H.col(1).tail<3>() = Rt * b;
  H.col(2).tail<3>() = Rt * a.cross(b);
  return H;
}
Vec6 planar_Hdot(const Vec3& a, const Vec3& b, const Mat3& Rt, const Vec3& beta) {
  const Vec3 v = Rt * (beta[1] * b + beta[2] * a.cross(b));
  Vec6 out;
  out << Vec3::Zero(), beta[0] * v.cross(a);
  return out;
}

struct PlanarCase {
  Vec3 a, b, theta, beta;
  unsigned tags = 0;
  std::string code() const {
    return soa::test::code("a", a) + soa::test::code("b", b) + soa::test::code("theta", theta) +
           soa::test::code("beta", beta) +
           "auto J = soa::ex03::planar_joint_map(a, b, theta, beta);\n";
  }
};

// Case i: a random axis and in-plane direction; no turn (theta_1 = 0) when i mod 5 = 0.
PlanarCase draw_planar_case(Random<double>& rnd, int i) {
  PlanarCase c;
  c.a = rnd.unit3();
  const Vec3 r = rnd.vec3();
  c.b = (r - r.dot(c.a) * c.a).normalized();
  c.theta = 2 * rnd.vec3();
  c.beta = rnd.vec3();
  if (i % 5 == 0) c.theta[0] = 0;
  if (c.theta[0] != 0) c.tags |= soa::test::kRotated;
  c.tags |= soa::test::kMoving | soa::test::kMultiDof;
  return c;
}

// clang-format off
/* planted mistakes of 3.7
soa_plant(3.7 degrees
  FIND [=[theta[0] * a]=]
  WRONG [=[theta[0] * 3.14159265358979323846 / 180 * a]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[H\*\(theta\), the joint map of the planar hinge: wrong in [0-9]+ of [0-9]+ cases.*symptom: it fails only where the frames are rotated.*the checker knows this mistake: it names it after 4 failed runs.*where, in case [0-9]+ \(the simplest that fails\): column [23]]=]
  REJECT [=[likely mistake|perhaps \(|your rotation takes theta_1 in degrees|R\* ?b|R\* ?c|a~ R\*|pi/180]=]
  NAMED [=[likely mistake \(degrees\): your rotation takes theta_1 in degrees]=])
*/
// clang-format on
// 3.7: the joint map of a planar hinge and the rate of its entries, against the derivation.
TEST(Exercise3_7_PlanarJointMap, MatchesDerivation) {
  Random<double> rnd;
  Check check_H("H*(theta), the joint map of the planar hinge", 16 * kEps);
  Check check_Hdot("Hdot* beta, the rate of the joint map", 16 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const PlanarCase c = draw_planar_case(rnd, i);
    const soa::ex03::PlanarJointMap got = soa::ex03::planar_joint_map(c.a, c.b, c.theta, c.beta);
    const Mat3 R = soa::exp_so3<double>(c.theta[0] * c.a);
    const Mat3 R_deg = soa::exp_so3<double>(c.theta[0] * kPi / 180 * c.a);
    const Matrix6X H = planar_H(c.a, c.b, R.transpose());
    const Vec6 Hdot = planar_Hdot(c.a, c.b, R.transpose(), c.beta);
    const std::vector<std::string> cols = {"column 1 (theta_1, the turn)",
                                           "column 2 (theta_2, along b)",
                                           "column 3 (theta_3, along c)"};
    auto inputs = [&] { return c.code(); };
    auto H_mistakes = [&] {
      Matrix6X wrong_part = H;
      wrong_part.col(0) << Vec3::Zero(), c.a;
      Matrix6X c_sign = H;
      c_sign.col(2) *= -1;
      return Mistakes{
          {"wrong frame",
           "your sliding columns are [0; b] and [0; c], in O_k+ coordinates: Delta_V is in O_k "
           "coordinates, v = R* l_dot",
           planar_H(c.a, c.b, Mat3::Identity())},
          {"transpose",
           "your sliding columns are R b and R c: from O_k+ to O_k coordinates is R* = "
           "R.transpose()",
           planar_H(c.a, c.b, R)},
          {"degrees",
           "your rotation takes theta_1 in degrees: angles are in radians (exp_so3(theta_1 a), "
           "no pi/180)",
           planar_H(c.a, c.b, R_deg.transpose())},
          {"wrong part",
           "your turning column is [0; a]: a turn about a is an angular velocity, [a; 0] "
           "(angular part first)",
           wrong_part},
          {"sign", "your third column has the opposite sign: c = a x b, not b x a", c_sign},
      };
    };
    auto Hdot_mistakes = [&] {
      const Vec6 deg = planar_Hdot(c.a, c.b, R_deg.transpose(), c.beta);
      Vec6 turned;
      const Vec3 v = R * (c.beta[1] * c.b + c.beta[2] * c.a.cross(c.b));
      turned << Vec3::Zero(), c.beta[0] * c.a.cross(v);
      return Mistakes{
          {"dropped term",
           "your rate is zero: the columns R*b and R*c of H* turn with the hinge (theta_1 "
           "changes), so H* changes even at constant beta",
           Vec6::Zero()},
          soa::test::negated(Hdot,
                             "your rate has the opposite sign: d/dt R* = (R a~ beta_1)* = "
                             "-beta_1 a~ R*"),
          {"transpose",
           "your rate is that of R b and R c: the columns are R* b and R* c, in O_k coordinates",
           turned},
          {"degrees", "your rate takes theta_1 in degrees: angles are in radians", deg},
      };
    };
    check_H.add(i, got.H_star, H, 1.0, c.tags, inputs, H_mistakes, columns_naming("H*", cols));
    check_Hdot.add(i, got.Hdot_beta.vector(), Hdot, std::max(1.0, c.beta.squaredNorm()), c.tags,
                   inputs, Hdot_mistakes, soa::test::spatial("Hdot* beta"));
  }
}

// The test's own reference for 3.7 against the definitions, by finite differences along
// theta(t) = theta + t beta: Delta_V = [vee(R* R_dot); R* l_dot] and the rate of H*(theta(t)).
TEST(Exercise3_7_PlanarJointMap, ReferenceIsTheDerivative) {
  Random<double> rnd(7);
  double worst_V = 0, worst_Hdot = 0;
  const double h = 1e-4;
  for (int i = 0; i < 100; ++i) {
    const PlanarCase c = draw_planar_case(rnd, i);
    auto R_at = [&](double t) { return soa::exp_so3<double>((c.theta[0] + t * c.beta[0]) * c.a); };
    auto l_at = [&](double t) {
      return Vec3((c.theta[1] + t * c.beta[1]) * c.b +
                  (c.theta[2] + t * c.beta[2]) * c.a.cross(c.b));
    };
    auto H_at = [&](double t) { return Matrix6X(planar_H(c.a, c.b, R_at(t).transpose())); };
    auto d = [&](auto f) {
      using T = decltype(f(0.0));
      return T((f(-2 * h) - 8 * f(-h) + 8 * f(h) - f(2 * h)) / (12 * h));
    };
    const Mat3 Rt = R_at(0).transpose();
    const Mat3 W = Rt * d([&](double t) { return Mat3(R_at(t)); });
    Vec6 dV;
    dV << W(2, 1), W(0, 2), W(1, 0), Rt * d([&](double t) { return Vec3(l_at(t)); });
    worst_V = std::max(worst_V, (dV - planar_H(c.a, c.b, Rt) * c.beta).norm());
    const Vec6 Hdot_fd = d([&](double t) { return Matrix6X(H_at(t)); }) * c.beta;
    worst_Hdot = std::max(worst_Hdot, (Hdot_fd - planar_Hdot(c.a, c.b, Rt, c.beta)).norm());
  }
  EXPECT_LE(worst_V, 1e-8);
  EXPECT_LE(worst_Hdot, 1e-8);
}

// clang-format off
/* planted mistakes of 3.8
soa_plant(3.8 the-bug
  FIND [=[w.cross(R * p)]=]
  WRONG [=[w.cross(p)]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[the checker knows this mistake: it names it after 3 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your result is the given code's]=]
  NAMED [=[likely mistake \(the given bug\): your result is the given code's]=])
*/
// clang-format on
// 3.8: the velocity of a point of body k in inertial coordinates, against the library's
// velocities and poses, R_k (v(k) + omega(k) x p).
TEST(Exercise3_8_PointVelocity, MatchesLibrary) {
  Random<double> rnd;
  Check check("v(P), the point's velocity in inertial coordinates", 32 * kEps);
  for (int i = 0; i < kCases; ++i) {
    KinCase c = draw_kin_case(rnd, i);
    const int k = 1 + (i % c.m.n());
    const Vec3 p = i % 5 == 0 ? Vec3::Zero() : Vec3(rnd.vec3());
    // The tags that matter here: the point off O_k, body k's axes turned.
    c.tags &= ~unsigned(soa::test::kTranslated | soa::test::kRotated);
    if (p.norm() > 0) c.tags |= soa::test::kTranslated;
    const Mat3 R = c.ws.pose[std::size_t(k - 1)].R();
    if (!R.isIdentity(0)) c.tags |= soa::test::kRotated;
    const Vec3 got = soa::ex03::point_velocity(c.m, c.x, k, p);
    const soa::Velocity& V = c.ws.V[std::size_t(k - 1)];
    const Vec3 w = V.angular(), v = V.linear();
    const Vec3 ref = R * (v + w.cross(p));
    auto mistakes = [&] {
      return Mistakes{
          {"the given bug",
           "your result is the given code's: the bug is still there (which coordinates is "
           "each vector of the last line in?)",
           R * v + (R * w).cross(p)},
          {"wrong frame",
           "your v(P) is in O_k coordinates: turn it to inertial coordinates with R_k = "
           "ws.pose[k-1].R()",
           v + w.cross(p)},
          {"transpose", "your v(P) is turned by R_k*: from O_k to inertial coordinates is R_k",
           R.transpose() * (v + w.cross(p))},
          {"dropped term", "your v(P) is the velocity of O_k: the point adds omega x p", R * v},
          {"sign", "your v(P) has p x omega: v(P) = v(O_k) + omega x l(O_k, P)",
           R * (v - w.cross(p))},
      };
    };
    check.add(
        i, got, ref, std::max(1.0, V.vector().norm()) * (reach(c.ws.phi) + p.norm()), c.tags,
        [&] {
          return c.code() + code("p", p) + "int k = " + std::to_string(k) +
                 ";\nsoa::Vec3<double> v_P = soa::ex03::point_velocity(m, x, k, p);\n";
        },
        mistakes,
        [](Eigen::Index r, Eigen::Index) {
          static const char* xyz[3] = {"x", "y", "z"};
          return EntryName{std::string("v(P)[") + std::to_string(r) + "] (" + xyz[r % 3] + ")", ""};
        });
  }
}
