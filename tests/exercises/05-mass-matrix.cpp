// Lesson 5 exercise tests: each exercise of exercises/05-mass-matrix/exercises.hpp against the
// library, on soa::test::kCases random chains from the fixed seed (1 to 9 bodies, hinge types drawn
// at random unless the exercise is for revolute or prismatic chains). Each check names its
// quantity, and its catalogue of classic mistakes is computed from the reference
// (tests/support/exercise_check.hpp). Built against the solutions (ctest), the students' exercises
// (make exercises) and the solutions with planted mistakes (the "planted mistakes" blocks,
// tests/exercises/plant.cmake).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "exercise_check.hpp"
#include "exercises.hpp"
#include "property.hpp"
#include "random_chain.hpp"

namespace {

using soa::HingeType;
using soa::test::Check;
using soa::test::code;
using soa::test::kCases;
using soa::test::Mistake;
using soa::test::Mistakes;
using soa::test::Random;
using Vec3 = soa::Vec3<double>;
using Mat3 = soa::Mat3<double>;
using Vec6 = soa::Vec6<double>;
using Mat6 = soa::Mat6<double>;
using VecX = soa::VecX<double>;
using MatX = soa::MatX<double>;
using Inertias = std::vector<soa::SpatialInertia>;

constexpr double kEps = soa::eps<double>();
const double kPi = std::acos(-1.0);

// A random chain of lesson 5 at a random configuration, with phi(k+1,k) and the library's
// composite inertias R(k). Case i has 1 + i mod 9 bodies, hinge types drawn at random (or
// every hinge of one type); the tags say what it has (the velocities play no part here).
struct MassCase {
  soa::Model m;
  soa::State x;
  soa::Workspace ws;
  Inertias R;
  unsigned tags = 0;

  explicit MassCase(soa::Model model) : m(std::move(model)), ws(m) {}
  std::string code() const { return soa::test::code("m", m) + soa::test::code("x", x); }
  static std::string composite_code() {
    return "soa::Workspace ws(m);\nsoa::update_phi(m, x.theta, ws);  // ws.phi[k-1] = "
           "phi(k+1,k)\n"
           "std::vector<soa::SpatialInertia> R(m.n());\nsoa::composite_inertias(m, ws, R);  // "
           "R[k-1] = R(k)\n";
  }
};

MassCase draw_mass_case(Random<double>& rnd, int i, bool all_hinge_types = true) {
  soa::test::ChainOptions opt;
  opt.all_hinge_types = all_hinge_types;
  MassCase c(soa::test::random_chain_mixed(rnd, 1 + i % 9, opt));
  c.x = soa::test::random_state(rnd, c.m);
  soa::update_phi(c.m, c.x.theta, c.ws);
  c.R.resize(std::size_t(c.m.n()));
  soa::composite_inertias(c.m, c.ws, c.R);
  c.tags = soa::test::chain_tags(c.m, c.x) & ~unsigned(soa::test::kMoving);
  return c;
}

// R(k), tip to base, with a classic mistake in the recursion (as 6x6 matrices: a mistake need
// not give a rigid body inertia).
enum class Composite { Transposed, Neighbour, Unmoved, NeighbourOnly, FromBase };
std::vector<Mat6> composite_variant(const soa::Model& m, const std::vector<soa::Phi>& phi,
                                    Composite v) {
  const int n = m.n();
  std::vector<Mat6> R(static_cast<std::size_t>(n));
  auto M = [&](int k) { return Mat6(m.body(k).M.matrix()); };
  auto P = [&](int k) { return Mat6(phi[std::size_t(k - 1)].matrix()); };  // phi(k+1,k)
  if (v == Composite::FromBase) {  // R(k) = M(k) + phi(k,k+1) R(k+1) phi*(k,k+1)
    for (int k = n; k >= 1; --k) {
      R[std::size_t(k - 1)] = M(k);
      if (k < n) {
        const Mat6 Q = phi[std::size_t(k - 1)].inverse().matrix();
        R[std::size_t(k - 1)] += Q * R[std::size_t(k)] * Q.transpose();
      }
    }
    return R;
  }
  for (int k = 1; k <= n; ++k) {
    const auto j = std::size_t(k - 1);
    R[j] = M(k);
    if (k == 1) continue;
    switch (v) {
      case Composite::Transposed:
        R[j] += P(k - 1).transpose() * R[j - 1] * P(k - 1);
        break;
      case Composite::Neighbour:
        R[j] += P(k) * R[j - 1] * P(k).transpose();
        break;
      case Composite::Unmoved:
        R[j] += R[j - 1];
        break;
      case Composite::NeighbourOnly:
        R[j] += P(k - 1) * M(k - 1) * P(k - 1).transpose();
        break;
      default:
        break;
    }
  }
  return R;
}

}  // namespace

// clang-format off
/* planted mistakes of 5.1
soa_plant(5.1 neighbour-index
  FIND [=[transform(phi[i - 1], R[i - 1])]=]
  WRONG [=[transform(phi[i], R[i - 1])]=] TYPE [=[SpatialInertia]=]
  EXPECT [=[likely mistake \(neighbour index\): your R\(k\) moves R\(k-1\) with phi\(k\+1,k\)]=])
soa_plant(5.1 unmoved
  FIND [=[transform(phi[i - 1], R[i - 1])]=]
  WRONG [=[R[i - 1]]=] TYPE [=[SpatialInertia]=]
  EXPECT [=[likely mistake \(wrong frame\): your R\(k\) adds R\(k-1\) as it is]=])
*/
// clang-format on
// 5.1: the composite inertias from phi, against soa::composite_inertias. Each R(k) is held
// to rounding relative to its own size, so every body of every chain is a case of the check.
TEST(Exercise5_1_CompositeInertias, MatchesLibrary) {
  Random<double> rnd;
  Check check("R(k), the composite inertia of bodies 1..k (one case per body of a chain)",
              64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const MassCase c = draw_mass_case(rnd, i);
    const soa::Model& m = c.m;
    const Inertias R = soa::ex05::composite_inertias(m, c.ws.phi);
    auto inputs = [&] {
      return c.code() +
             "soa::Workspace ws(m);\nsoa::update_phi(m, x.theta, ws);  // ws.phi[k-1] = "
             "phi(k+1,k)\n"
             "auto R = soa::ex05::composite_inertias(m, ws.phi);\n";
    };
    if (int(R.size()) != m.n()) {
      check.add(i, MatX::Zero(6 * Eigen::Index(R.size()), 6), MatX::Zero(6 * m.n(), 6), 1.0, c.tags,
                inputs);
      continue;
    }
    std::vector<std::vector<Mat6>> variants;  // computed for the first failing body only
    for (int k = 1; k <= m.n(); ++k) {
      const auto j = std::size_t(k - 1);
      auto mistakes = [&, j] {
        if (variants.empty())
          for (Composite v : {Composite::Transposed, Composite::Neighbour, Composite::Unmoved,
                              Composite::NeighbourOnly, Composite::FromBase})
            variants.push_back(composite_variant(m, c.ws.phi, v));
        auto at = [&](int v) { return MatX(variants[std::size_t(v)][j]); };
        return Mistakes{
            {"transpose",
             "your R(k) moves R(k-1) as phi* R phi: an inertia moves inward as phi R phi* "
             "(soa::transform(phi, R), the parallel axis theorem)",
             at(0)},
            {"neighbour index",
             "your R(k) moves R(k-1) with phi(k+1,k), phi[k-1]: phi(k,k-1) is phi[k-2]", at(1)},
            {"wrong frame",
             "your R(k) adds R(k-1) as it is, about O_{k-1}: move it to O_k first, "
             "phi(k,k-1) R(k-1) phi*(k,k-1)",
             at(2)},
            {"dropped term",
             "your R(k) moves M(k-1), body k-1 alone: R(k-1), the composite of bodies 1..k-1, "
             "carries everything outboard",
             at(3)},
            {"wrong direction",
             "your sum runs from the base (bodies k..n): R(k) welds bodies 1..k, outboard of "
             "hinge k, so the recursion starts at the tip, R(1) = M(1)",
             at(4)},
        };
      };
      check.add(
          i, R[j].matrix(), c.R[j].matrix(), c.R[j].matrix().norm(), c.tags,
          [&, k] {
            return inputs() + "// R(" + std::to_string(k) + ") is R[" + std::to_string(k - 1) +
                   "]\n";
          },
          mistakes, soa::test::blocks6("R(" + std::to_string(k) + ")"));
    }
  }
}

// The diagonal blocks of the mass matrix, H(k) X(k) H*(k), as a block-diagonal nv x nv matrix.
template <class F>
MatX block_diagonal(const soa::Model& m, const VecX& theta, const F& inertia_of) {
  MatX D = MatX::Zero(m.nv(), m.nv());
  for (int k = 1; k <= m.n(); ++k) {
    const soa::Body& B = m.body(k);
    const MatX Hs = B.hinge.H_star(theta.data() + B.q_offset);
    D.block(B.v_offset, B.v_offset, B.hinge.nv(), B.hinge.nv()) =
        Hs.transpose() * inertia_of(k) * Hs;
  }
  return D;
}

// clang-format off
/* planted mistakes of 5.2
soa_plant(5.2 own-inertia
  FIND [=[R[std::size_t(k - 1)].matrix() * Hs]=]
  WRONG [=[B.M.matrix() * Hs]=] TYPE [=[MatX<double>]=]
  EXPECT [=[likely mistake \(dropped term\): your M\(k,k\) uses M\(k\), body k alone]=])
# Not in the catalogue: the prismatic joint map doubled. The report gives the symptom.
soa_plant(5.2 prismatic-doubled
  FIND [=[B.hinge.H_star(theta.data() + B.q_offset)]=]
  WRONG [=[B.hinge.type == HingeType::Prismatic ? MatX<double>(2.0 * B.hinge.H_star(theta.data() + B.q_offset)) : MatX<double>(B.hinge.H_star(theta.data() + B.q_offset))]=]
  TYPE [=[MatX<double>]=]
  EXPECT [=[symptom: it fails only where a hinge is prismatic: [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
*/
// clang-format on
// 5.2: the diagonal blocks H(k) R(k) H*(k), against soa::OperatorsT::mass_matrix().
TEST(Exercise5_2_MassMatrixDiagonal, MatchesOperators) {
  Random<double> rnd;
  Check check("M(k,k), the diagonal blocks of the mass matrix", 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const MassCase c = draw_mass_case(rnd, i);
    const soa::Model& m = c.m;
    const MatX M_ref = soa::Operators::build(m, c.x).mass_matrix();
    auto inputs = [&] {
      return c.code() + MassCase::composite_code() +
             "// for k = 1..n:\nauto Mkk = soa::ex05::mass_matrix_diagonal(m, x.theta, R, k);\n";
    };
    MatX got = MatX::Zero(m.nv(), m.nv()), ref = MatX::Zero(m.nv(), m.nv());
    bool shaped = true;
    for (int k = 1; k <= m.n() && shaped; ++k) {
      const soa::Body& B = m.body(k);
      const int nk = B.hinge.nv();
      const MatX Mkk = soa::ex05::mass_matrix_diagonal(m, c.x.theta, c.R, k);
      const MatX ref_k = M_ref.block(B.v_offset, B.v_offset, nk, nk);
      if (Mkk.rows() != nk || Mkk.cols() != nk) {
        check.add(i, Mkk, ref_k, M_ref.norm(), c.tags, inputs);
        shaped = false;
        break;
      }
      got.block(B.v_offset, B.v_offset, nk, nk) = Mkk;
      ref.block(B.v_offset, B.v_offset, nk, nk) = ref_k;
    }
    if (!shaped) continue;
    auto mistakes = [&] {
      return Mistakes{
          soa::test::negated(ref, "your M(k,k) has the opposite sign"),
          {"dropped term",
           "your M(k,k) uses M(k), body k alone: hinge k moves the composite body 1..k, "
           "M(k,k) = H(k) R(k) H*(k)",
           block_diagonal(m, c.x.theta, [&](int k) { return Mat6(m.body(k).M.matrix()); })},
          {"wrong frame",
           "your M(k,k) takes R(k) moved to O_{k+1}: H*(k) acts at O_k, where R(k) = R[k-1] "
           "already is",
           block_diagonal(m, c.x.theta,
                          [&](int k) {
                            return Mat6(soa::transform(c.ws.phi[std::size_t(k - 1)],
                                                       c.R[std::size_t(k - 1)])
                                            .matrix());
                          })},
      };
    };
    check.add(i, got, ref, M_ref.norm(), c.tags, inputs, mistakes, soa::test::dof_blocks(m, "M"));
  }
}

// The CRB mass matrix of a revolute chain (5.3) with a classic mistake in it.
enum class Crb { Transposed, Neighbour, OwnInertia, LowerOnly, Degrees, LinearPart };
MatX crb_variant(const soa::Model& m, const VecX& theta, Crb v) {
  const int n = m.n();
  std::vector<soa::Phi> phi;
  for (int k = 1; k <= n; ++k) {
    const soa::Body& B = m.body(k);
    const double th = v == Crb::Degrees ? theta[B.q_offset] * kPi / 180 : theta[B.q_offset];
    phi.push_back(
        soa::Phi(B.placement * soa::Pose(soa::exp_so3<double>(th * B.hinge.axis), Vec3::Zero())));
  }
  Inertias R;
  for (int k = 1; k <= n; ++k)
    R.push_back(k == 1 ? m.body(1).M
                       : soa::transform(phi[std::size_t(k - 2)], R.back()) + m.body(k).M);
  MatX M = MatX::Zero(n, n);
  for (int j = 1; j <= n; ++j) {
    Vec6 h;
    h << m.body(j).hinge.axis, Vec3::Zero();
    const Mat6 Rj =
        v == Crb::OwnInertia ? Mat6(m.body(j).M.matrix()) : Mat6(R[std::size_t(j - 1)].matrix());
    Vec6 F = Rj * h;
    for (int i = j; i <= n; ++i) {
      if (i > j) {
        const Mat6 P = phi[std::size_t(v == Crb::Neighbour ? i - 1 : i - 2)].matrix();
        F = v == Crb::Transposed ? Vec6(P.transpose() * F) : Vec6(P * F);
      }
      const double Mij =
          m.body(i).hinge.axis.dot(v == Crb::LinearPart ? Vec3(F.tail<3>()) : Vec3(F.head<3>()));
      M(i - 1, j - 1) = Mij;
      if (v != Crb::LowerOnly) M(j - 1, i - 1) = Mij;
    }
  }
  return M;
}

// clang-format off
/* planted mistakes of 5.3
soa_plant(5.3 transpose
  FIND [=[phi[std::size_t(i - 2)].apply(F)]=]
  WRONG [=[Force(Vec6<double>(phi[std::size_t(i-2)].matrix().transpose() * F.vector()))]=]
  TYPE [=[Force]=]
  EXPECT [=[likely mistake \(transpose\): your force R\(j\) H\*\(j\) is carried inboard with phi\*]=])
soa_plant(5.3 degrees
  FIND [=[theta[B.q_offset] * B.hinge.axis]=]
  WRONG [=[theta[B.q_offset] * 3.14159265358979323846 / 180 * B.hinge.axis]=]
  TYPE [=[Vec3<double>]=]
  EXPECT [=[likely mistake \(degrees\): your phi\(k\+1,k\) takes theta in degrees]=])
*/
// clang-format on
// 5.3: the CRB mass matrix of random revolute chains, against
// soa::OperatorsT::mass_matrix().
TEST(Exercise5_3_CrbMassMatrixRevolute, MatchesOperators) {
  Random<double> rnd;
  Check check("M, the mass matrix of a revolute chain", 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const MassCase c = draw_mass_case(rnd, i, false);
    const soa::Model& m = c.m;
    const MatX M = soa::ex05::crb_mass_matrix_revolute(m, c.x.theta);
    const MatX M_ref = soa::Operators::build(m, c.x).mass_matrix();
    auto mistakes = [&] {
      auto v = [&](Crb e) { return crb_variant(m, c.x.theta, e); };
      return Mistakes{
          {"transpose",
           "your force R(j) H*(j) is carried inboard with phi*(i,i-1): forces move inward with "
           "phi, phi[i-2].apply(F)",
           v(Crb::Transposed)},
          {"neighbour index",
           "your force is carried with phi(i+1,i), phi[i-1]: from O_{i-1} to O_i is "
           "phi(i,i-1), phi[i-2]",
           v(Crb::Neighbour)},
          {"dropped term",
           "your columns start from M(j) H*(j), body j alone: hinge j moves the composite body "
           "1..j, R(j) H*(j)",
           v(Crb::OwnInertia)},
          {"dropped term",
           "only the lower triangle of your M is filled: M is symmetric, M(j,i) = M(i,j)",
           v(Crb::LowerOnly)},
          {"degrees",
           "your phi(k+1,k) takes theta in degrees: angles are in radians (exp_so3(theta_k "
           "a_k), no pi/180)",
           v(Crb::Degrees)},
          {"wrong part",
           "your M(i,j) is a_i* F, the linear part of the force: a revolute hinge takes the "
           "moment, the angular part (angular first)",
           v(Crb::LinearPart)},
      };
    };
    check.add(
        i, M, M_ref, M_ref.norm(), c.tags,
        [&] {
          return c.code() +
                 "soa::MatX<double> M = soa::ex05::crb_mass_matrix_revolute(m, x.theta);\n";
        },
        mistakes, soa::test::dof_blocks(m, "M"));
  }
}

// The Lyapunov recursion of 5.4 on the blocks of E_phi, with its blocks transposed or not.
MatX lyapunov(const soa::Operators& op, bool transposed) {
  const Eigen::Index N = op.M.rows();
  MatX R = MatX::Zero(N, N);
  for (Eigen::Index r = 0; r < N; r += 6) {
    R.block(r, r, 6, 6) = op.M.block(r, r, 6, 6);
    if (r > 0) {
      MatX E = op.E_phi.block(r, r - 6, 6, 6);
      if (transposed) E.transposeInPlace();
      R.block(r, r, 6, 6) += E * R.block(r - 6, r - 6, 6, 6) * E.transpose();
    }
  }
  return R;
}

// clang-format off
/* planted mistakes of 5.4
soa_plant(5.4 sign
  FIND [=[R + phi_t * R + R * phi_t.transpose()]=]
  WRONG [=[R - phi_t * R - R * phi_t.transpose()]=] TYPE [=[MatX<double>]=]
  EXPECT [=[likely mistake \(sign\): your result subtracts phi~ R and R phi~\*]=])
*/
// clang-format on
// 5.4: R + phi~ R + R phi~* from the block Lyapunov recursion, against phi M phi*.
TEST(Exercise5_4_Decomposition, MatchesPhiMPhiStar) {
  Random<double> rnd;
  Check check("R + phi~ R + R phi~*, the decomposition of phi M phi*", 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const MassCase c = draw_mass_case(rnd, i);
    const soa::Operators op = soa::Operators::build(c.m, c.x);
    const MatX D = soa::ex05::decomposition(op);
    const MatX ref = op.phi * op.M * op.phi.transpose();
    auto mistakes = [&] {
      const Eigen::Index N = op.M.rows();
      const MatX I = MatX::Identity(N, N), t = op.phi - I;
      const MatX R = lyapunov(op, false), Rt = lyapunov(op, true);
      return Mistakes{
          {"dropped term",
           "your phi~ is phi itself: phi~ = phi - I, the blocks below the diagonal only",
           MatX(R + op.phi * R + R * op.phi.transpose())},
          {"dropped term", "R phi~* is missing: phi M phi* = R + phi~ R + R phi~*",
           MatX(R + t * R)},
          {"transpose", "your result is R + phi~* R + R phi~: the transposes swapped",
           MatX(R + t.transpose() * R + R * t)},
          {"sign", "your result subtracts phi~ R and R phi~*: all three terms are added",
           MatX(R - t * R - R * t.transpose())},
          {"dropped term",
           "your R is M: R solves R = E_phi R E_phi* + M, block k R(k) = phi(k,k-1) R(k-1) "
           "phi*(k,k-1) + M(k), the composite inertias",
           MatX(op.M + t * op.M + op.M * t.transpose())},
          {"transpose",
           "your Lyapunov recursion takes E* R E with the blocks of E_phi: block (k, k-1) of "
           "E_phi is phi(k,k-1), so R(k) = E R(k-1) E* + M(k)",
           MatX(Rt + t * Rt + Rt * t.transpose())},
      };
    };
    check.add(
        i, D, ref, ref.norm(), c.tags,
        [&] {
          return c.code() +
                 "soa::Operators op = soa::Operators::build(m, x);\n"
                 "soa::MatX<double> D = soa::ex05::decomposition(op);\n";
        },
        mistakes, soa::test::body_blocks("phi M phi*"));
  }
}

// The blocks of phi M phi* from phi(k+1,k) and R (5.5), assembled, with a classic mistake:
// the blocks above the diagonal zero or not transposed, R at the wrong end, or R moved.
enum class Block { Right, UpperZero, UpperUntransposed, WrongEnd, Sandwich };
MatX blocks_variant(const std::vector<soa::Phi>& phi, const Inertias& R, Block v) {
  const int n = int(phi.size());
  MatX out = MatX::Zero(6 * n, 6 * n);
  auto phi_ij = [&](int i, int j) {  // phi(i,j), i >= j
    Mat6 P = Mat6::Identity();
    for (int k = j + 1; k <= i; ++k) P = phi[std::size_t(k - 2)].matrix() * P;
    return P;
  };
  auto Rm = [&](int k) { return Mat6(R[std::size_t(k - 1)].matrix()); };
  for (int i = 1; i <= n; ++i)
    for (int j = 1; j <= i; ++j) {
      const Mat6 P = phi_ij(i, j);
      const Mat6 B = v == Block::WrongEnd   ? Mat6(P * Rm(i))
                     : v == Block::Sandwich ? Mat6(P * Rm(j) * P.transpose())
                                            : Mat6(P * Rm(j));
      out.block<6, 6>(6 * (i - 1), 6 * (j - 1)) = B;
      if (i == j) continue;
      if (v == Block::UpperUntransposed)
        out.block<6, 6>(6 * (j - 1), 6 * (i - 1)) = B;
      else if (v != Block::UpperZero)
        out.block<6, 6>(6 * (j - 1), 6 * (i - 1)) = B.transpose();
    }
  return out;
}

// clang-format off
/* planted mistakes of 5.5
soa_plant(5.5 transpose
  FIND [=[phi_M_phi_star_block(phi, R, j, i).transpose()]=]
  WRONG [=[phi_M_phi_star_block(phi, R, j, i)]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[the checker knows this mistake: it names it after 4 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your block \(i,j\), i < j, is block \(j,i\) itself]=]
  NAMED [=[likely mistake \(transpose\): your block \(i,j\), i < j, is block \(j,i\) itself]=])
*/
// clang-format on
// 5.5: block (i, j) of phi M phi* for every i, j, assembled, against the dense phi M phi*.
TEST(Exercise5_5_PhiMPhiStarBlock, MatchesPhiMPhiStar) {
  Random<double> rnd;
  Check check("block (i, j) of phi M phi*, for every i and j", 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const MassCase c = draw_mass_case(rnd, i);
    const int n = c.m.n();
    const soa::Operators op = soa::Operators::build(c.m, c.x);
    const MatX ref = op.phi * op.M * op.phi.transpose();
    MatX got(6 * n, 6 * n);
    for (int r = 1; r <= n; ++r)
      for (int s = 1; s <= n; ++s)
        got.block<6, 6>(6 * (r - 1), 6 * (s - 1)) =
            soa::ex05::phi_M_phi_star_block(c.ws.phi, c.R, r, s);
    auto mistakes = [&] {
      auto v = [&](Block b) { return blocks_variant(c.ws.phi, c.R, b); };
      return Mistakes{
          {"dropped term",
           "your blocks above the diagonal (i < j) are zero: phi M phi* is symmetric, block "
           "(i,j) = block (j,i)* = R(i) phi*(j,i)",
           v(Block::UpperZero)},
          {"transpose",
           "your block (i,j), i < j, is block (j,i) itself: phi M phi* is symmetric as a "
           "matrix, so block (i,j) is the transpose of block (j,i)",
           v(Block::UpperUntransposed)},
          {"wrong index",
           "your block (i,j), i > j, uses R(i): the bodies that both O_i and O_j carry are "
           "those outboard of the outer one, 1..j, so R(j): phi(i,j) R(j)",
           v(Block::WrongEnd)},
          {"wrong frame",
           "your block (i,j) is phi(i,j) R(j) phi*(i,j), R(j) moved to O_i: block (i,j) takes "
           "a velocity at O_j to a force at O_i, phi(i,j) R(j) (one phi, from phi~ R)",
           v(Block::Sandwich)},
      };
    };
    check.add(
        i, got, ref, ref.norm(), c.tags,
        [&] {
          return c.code() + MassCase::composite_code() +
                 "// for i, j = 1..n:\n"
                 "soa::Mat6<double> B = soa::ex05::phi_M_phi_star_block(ws.phi, R, i, j);\n";
        },
        mistakes, soa::test::body_blocks("phi M phi*"));
  }
}

// clang-format off
/* planted mistakes of 5.6
soa_plant(5.6 no-angle
  FIND [=[axis[std::size_t(i - 1)].dot(axis[std::size_t(j - 1)])]=]
  WRONG [=[1.0]=] TYPE [=[double]=]
  EXPECT [=[the checker knows this mistake: it names it after 3 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your M\(i,j\) leaves out a_i \. a_j]=]
  NAMED [=[likely mistake \(dropped term\): your M\(i,j\) leaves out a_i \. a_j]=])
*/
// clang-format on
// 5.6: the mass matrix of random chains of sliders (every hinge prismatic), predicted from the
// masses and the axes in inertial coordinates, against soa::mass_matrix_crb. Every fourth
// chain has all its axes parallel.
TEST(Exercise5_6_SliderMassMatrix, MatchesCrb) {
  Random<double> rnd;
  Check check("M, the mass matrix of a chain of sliders", 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const int n = 1 + i % 9;
    soa::Model m = soa::test::random_chain_of_type(rnd, n, HingeType::Prismatic);
    if (i % 4 == 0) {  // parallel axes: every placement unturned, one axis
      std::vector<soa::Body> base_first;
      const Vec3 u = rnd.unit3();
      for (int k = n; k >= 1; --k) {
        soa::Body B = m.body(k);
        B.placement = soa::Pose(Mat3::Identity(), B.placement.l());
        B.hinge.axis = u;
        base_first.push_back(B);
      }
      m = soa::Model::from_base_first(base_first);
    }
    const soa::State x = soa::test::random_state(rnd, m);
    soa::Workspace ws(m);
    soa::update_phi(m, x.theta, ws);
    soa::update_poses(m, ws);
    std::vector<double> mass;
    std::vector<Vec3> axis;
    for (int k = 1; k <= n; ++k) {
      mass.push_back(m.body(k).M.mass());
      axis.push_back(ws.pose[std::size_t(k - 1)].R() * m.body(k).hinge.axis);
    }
    Inertias R(static_cast<std::size_t>(n));
    MatX M_ref;
    soa::mass_matrix_crb(m, x, ws, R, M_ref);
    const MatX M = soa::ex05::slider_mass_matrix(mass, axis);
    unsigned tags = soa::test::chain_tags(m, x) & ~unsigned(soa::test::kMoving);
    if (i % 4 != 0) tags |= soa::test::kRotated;  // the axes are not parallel
    auto mistakes = [&] {
      MatX own(n, n), inboard(n, n), both(n, n), no_dot(n, n);
      for (int r = 1; r <= n; ++r)
        for (int s = 1; s <= n; ++s) {
          const double d = axis[std::size_t(r - 1)].dot(axis[std::size_t(s - 1)]);
          double out_min = 0, out_max = 0, in_max = 0;
          for (int k = 1; k <= n; ++k) {
            const double mk = mass[std::size_t(k - 1)];
            if (k <= std::min(r, s)) out_min += mk;
            if (k <= std::max(r, s)) out_max += mk;
            if (k >= std::max(r, s)) in_max += mk;
          }
          own(r - 1, s - 1) = mass[std::size_t(std::min(r, s) - 1)] * d;
          inboard(r - 1, s - 1) = in_max * d;
          both(r - 1, s - 1) = out_max * d;
          no_dot(r - 1, s - 1) = out_min;
        }
      return Mistakes{
          {"dropped term",
           "your M(i,j) has the mass of body min(i,j) alone: sliding hinge j moves every body "
           "outboard of it, m_1 + ... + m_j",
           own},
          {"wrong direction",
           "your M(i,j) sums the bodies inboard of the hinges (max(i,j) .. n): hinge j carries "
           "the bodies outboard of it, on the tip's side (1 .. j)",
           inboard},
          {"wrong index",
           "your M(i,j) sums the bodies 1..max(i,j): only the bodies outboard of both hinges, "
           "1..min(i,j), move with both",
           both},
          {"dropped term",
           "your M(i,j) leaves out a_i . a_j: hinge i sees the force of hinge j along its own "
           "axis, so the angle between the axes enters",
           no_dot},
          {"dropped term",
           "your M is diagonal: hinges i and j move the bodies outboard of both, M(i,j) != 0",
           MatX(M_ref.diagonal().asDiagonal())},
      };
    };
    check.add(
        i, M, M_ref, M_ref.norm(), tags,
        [&] {
          std::string s = "std::vector<double> mass = {";
          std::string a = "std::vector<soa::Vec3<double>> axis = {";
          for (int k = 0; k < n; ++k) {
            s += (k ? ", " : "") + soa::test::num(mass[std::size_t(k)]);
            a += (k ? ", soa::Vec3<double>" : "soa::Vec3<double>") +
                 soa::test::list(axis[std::size_t(k)]);
          }
          return s + "};\n" + a +
                 "};\nsoa::MatX<double> M = soa::ex05::slider_mass_matrix(mass, axis);\n";
        },
        mistakes, soa::test::dof_blocks(m, "M"));
  }
}

// A block column of the mass matrix (5.7) with a classic mistake in it, as the whole nv x nv
// matrix of its columns.
enum class Column { OutboardPhi, InboardPhiStar, UpperDropped, OuterInertia };
MatX column_variant(const MassCase& c, Column v) {
  const soa::Model& m = c.m;
  auto Hs = [&](int k) {
    const soa::Body& B = m.body(k);
    return MatX(B.hinge.H_star(c.x.theta.data() + B.q_offset));
  };
  auto P = [&](int k) { return Mat6(c.ws.phi[std::size_t(k - 1)].matrix()); };  // phi(k+1,k)
  auto R = [&](int k) { return Mat6(c.R[std::size_t(k - 1)].matrix()); };
  MatX M = MatX::Zero(m.nv(), m.nv());
  for (int j = 1; j <= m.n(); ++j) {
    const soa::Body& Bj = m.body(j);
    auto column = M.middleCols(Bj.v_offset, Bj.hinge.nv());
    MatX F = R(j) * Hs(j);
    for (int i = j; i <= m.n(); ++i) {
      if (i > j)
        F = v == Column::InboardPhiStar ? MatX(P(i - 1).transpose() * F) : MatX(P(i - 1) * F);
      column.middleRows(m.body(i).v_offset, m.body(i).hinge.nv()) = Hs(i).transpose() * F;
    }
    if (v == Column::UpperDropped) continue;
    MatX V = Hs(j);
    for (int i = j - 1; i >= 1; --i) {
      V = v == Column::OutboardPhi ? MatX(P(i) * V) : MatX(P(i).transpose() * V);
      const Mat6 Ri = v == Column::OuterInertia ? R(j) : R(i);
      column.middleRows(m.body(i).v_offset, m.body(i).hinge.nv()) = Hs(i).transpose() * Ri * V;
    }
  }
  return M;
}

// clang-format off
/* planted mistakes of 5.7
soa_plant(5.7 transpose
  FIND [=[phi[std::size_t(i - 1)].matrix().transpose() * V]=]
  WRONG [=[phi[std::size_t(i - 1)].matrix() * V]=] TYPE [=[MatX<double>]=]
  EXPECT [=[likely mistake \(transpose\): your motions H\*\(j\) are carried outboard with phi\(i\+1,i\)]=])
*/
// clang-format on
// 5.7: every block column j of the mass matrix, against soa::OperatorsT::mass_matrix().
TEST(Exercise5_7_MassMatrixColumn, MatchesOperators) {
  Random<double> rnd;
  Check check("M(., j), the block columns of the mass matrix", 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const MassCase c = draw_mass_case(rnd, i);
    const soa::Model& m = c.m;
    const MatX M_ref = soa::Operators::build(m, c.x).mass_matrix();
    auto inputs = [&] {
      return c.code() + MassCase::composite_code() +
             "// for j = 1..n:\nauto column = soa::ex05::mass_matrix_column(m, x.theta, ws.phi, "
             "R, j);\n";
    };
    MatX got = MatX::Zero(m.nv(), m.nv());
    bool shaped = true;
    for (int j = 1; j <= m.n() && shaped; ++j) {
      const soa::Body& B = m.body(j);
      const MatX column = soa::ex05::mass_matrix_column(m, c.x.theta, c.ws.phi, c.R, j);
      if (column.rows() != m.nv() || column.cols() != B.hinge.nv()) {
        check.add(i, column, M_ref.middleCols(B.v_offset, B.hinge.nv()), M_ref.norm(), c.tags,
                  inputs);
        shaped = false;
        break;
      }
      got.middleCols(B.v_offset, B.hinge.nv()) = column;
    }
    if (!shaped) continue;
    auto mistakes = [&] {
      auto v = [&](Column e) { return column_variant(c, e); };
      return Mistakes{
          soa::test::negated(M_ref, "your columns have the opposite sign"),
          {"transpose",
           "your motions H*(j) are carried outboard with phi(i+1,i): motions move outward "
           "with phi*, phi[i-1].matrix().transpose()",
           v(Column::OutboardPhi)},
          {"transpose",
           "your forces R(j) H*(j) are carried inboard with phi*(i,i-1): forces move inward "
           "with phi, phi[i-2]",
           v(Column::InboardPhiStar)},
          {"dropped term",
           "the rows of your column above body j are zero: M(i,j) = H(i) R(i) phi*(j,i) H*(j) "
           "for i < j",
           v(Column::UpperDropped)},
          {"wrong frame",
           "above body j your M(i,j) uses R(j): the motion phi*(j,i) H*(j) is at O_i, where "
           "the composite body 1..i has R(i)",
           v(Column::OuterInertia)},
      };
    };
    check.add(i, got, M_ref, M_ref.norm(), c.tags, inputs, mistakes, soa::test::dof_blocks(m, "M"));
  }
}
