// Lesson 6 exercise tests: each exercise of exercises/06-articulated-body-inertia/exercises.hpp
// against the library, on soa::test::kCases random chains (1 to 7 bodies, hinge types drawn at
// random unless the exercise is for revolute chains; at rest or moving, with or without gravity
// where the exercise allows it: tests/support/chain_case.hpp) from the fixed seed. Each check names
// its quantity, and its catalogue of classic mistakes is computed from the reference
// (tests/support/exercise_check.hpp): the Riccati recursion with a mistake in it
// (riccati_variant()), the composite-body bias and the shaken base likewise. The exercises of one
// Riccati step (6.1, 6.2, 6.8) take each body of each chain as a case of its own. Built against the
// solutions (ctest), the students' exercises (make exercises) and the solutions with planted
// mistakes (the "planted mistakes" blocks, tests/exercises/plant.cmake).
#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "chain_case.hpp"
#include "exercise_check.hpp"
#include "exercises.hpp"
#include "property.hpp"
#include "random_chain.hpp"
#include "soa/chain/force_decompositions.hpp"

namespace {

using soa::test::CaseOptions;
using soa::test::ChainCase;
using soa::test::Check;
using soa::test::kCases;
using soa::test::Mistake;
using soa::test::Mistakes;
using soa::test::Random;
using Mat3 = soa::Mat3<double>;
using Mat6 = soa::Mat6<double>;
using MatX = soa::MatX<double>;
using Vec3 = soa::Vec3<double>;
using Vec6 = soa::Vec6<double>;
using VecX = soa::VecX<double>;
using soa::test::stack;

constexpr double kEps = soa::eps<double>();

// The cases of lesson 6: chains of 1 to 7 bodies (7 is prime to the periods of the other
// features of chain_case.hpp, so that they vary independently of the number of bodies).
CaseOptions lesson6_cases(bool all_hinge_types, bool gravity, bool moving) {
  CaseOptions o;
  o.all_hinge_types = all_hinge_types;
  o.gravity = gravity;
  o.moving = moving;
  o.max_bodies = 7;
  return o;
}

// The library's articulated inertias of a chain at theta.
struct Library {
  soa::Workspace ws;
  soa::Articulated art;
  Library(const soa::Model& m, const VecX& theta) : ws(m), art(m) {
    soa::update_phi(m, theta, ws);
    soa::articulated_inertias(m, soa::State{theta, VecX::Zero(m.nv())}, ws, art);
  }
  // |P(k)| |D^{-1}(k)|, the growth of rounding in G and P+, largest over bodies 1..k.
  double kappa(int k) const {
    double w = 1;
    for (int j = 1; j <= k; ++j)
      w = std::max(w,
                   art.P[std::size_t(j - 1)].norm() * MatX(art.D_inv[std::size_t(j - 1)]).norm());
    return w;
  }
};

MatX H_star(const soa::Model& m, const VecX& theta, int k) {
  const soa::Body& B = m.body(k);
  return B.hinge.H_star(theta.data() + B.q_offset);
}

// The tags of the case of one Riccati step at body k of the chain case c: the chain's hinge
// types (a mistake confined to one type of hinge shows as "it fails only where a hinge is ..."
// without the other types' passing steps crowding the symptoms), and several bodies when the
// step has a body outboard (k > 1: P+(k-1) and phi(k,k-1) are not zero and identity).
unsigned step_tags(const ChainCase& c, int k) {
  const unsigned types = soa::test::kPrismatic | soa::test::kHelical | soa::test::kMultiDof;
  return (c.tags & types) | (k > 1 ? soa::test::kSeveralBodies : 0u);
}

// A matrix as code, row by row even when it has one column (Eigen's nested initializer
// list): `soa::MatX<double> H_star = soa::MatX<double>{{...}, ...};`.
template <class D>
std::string matrix_code(const std::string& type, const std::string& name,
                        const Eigen::MatrixBase<D>& a) {
  std::string rows;
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    rows += (i ? ", " : "") + soa::test::list(a.row(i).transpose().eval());
  }
  return type + " " + name + " = " + type + "{" + rows + "};\n";
}

// A 6 x n_k (or 6 x r) matrix: its rows are the angular or the linear part.
soa::test::Naming six_rows(const std::string& sym) {
  return [sym](Eigen::Index i, Eigen::Index j) {
    const bool ang = i < 3;
    return soa::test::EntryName{
        sym + "(" + std::to_string(i) + "," + std::to_string(j) + ")",
        std::string("the ") + (ang ? "angular" : "linear") + " rows of " + sym};
  };
}

// 6x6 blocks of body k stacked (6n x 6): body k and its four 3x3 blocks.
soa::test::Naming stacked_blocks6(const std::string& sym) {
  return [sym](Eigen::Index i, Eigen::Index j) {
    static const char* rc[2] = {"angular", "linear"};
    const std::string k = std::to_string(i / 6 + 1);
    return soa::test::EntryName{
        sym + "(" + k + ")(" + std::to_string(i % 6) + "," + std::to_string(j) + ")",
        "the " + std::string(rc[i % 6 / 3]) + "-" + rc[j / 3] + " block of " + sym + "(" + k + ")"};
  };
}

// The scale s that makes |got - expected| / s the largest of |got_k - expected_k| / w_k: a
// Check over a whole vector whose entries each have their own scale w_k (rounding grows
// down the chain), as strict as entry by entry, while the message shows the true values.
double per_entry_scale(const VecX& got, const VecX& expected, const VecX& w) {
  if (got.size() != expected.size() || !got.allFinite()) return w.minCoeff();
  const VecX d = got - expected;
  const double worst = d.cwiseAbs().cwiseQuotient(w).maxCoeff();
  return worst > 0 ? d.norm() / worst : w.minCoeff();
}

// P(k) (or any 6x6 per body) stacked tip first: 6n x 6.
MatX stack6(const std::vector<Mat6>& v) {
  MatX s(6 * Eigen::Index(v.size()), 6);
  for (std::size_t i = 0; i < v.size(); ++i) s.block<6, 6>(6 * Eigen::Index(i), 0) = v[i];
  return s;
}

// --- The Riccati recursion with a classic mistake in it (the catalogues of 6.1, 6.3, 6.7) ---

enum class Riccati {
  Right,
  TransposedPhi,  // phi* P+ phi
  NeighbourPhi,   // phi(k+1,k) = ws.phi[k-1] for phi(k,k-1) (a whole sweep only)
  UnmovedP,       // P+(k-1) + M(k), not moved to O_k
  NoM,            // M(k) missing
  GNoInverse,     // G = P H* D
  NoProjection,   // P+ = P (the composite inertia)
  PlusGDG,        // P+ = P + G D G*
  PTauBar,        // P+ = P tau_bar (tau_bar on the wrong side)
};

soa::ex06::RiccatiStep riccati_variant(const Mat6& Pp, const Mat6& phi6, const Mat6& M,
                                       const MatX& Hs, Riccati v) {
  soa::ex06::RiccatiStep s;
  s.P = v == Riccati::NoM ? Mat6(Mat6::Zero()) : M;
  if (v == Riccati::TransposedPhi)
    s.P += phi6.transpose() * Pp * phi6;
  else if (v == Riccati::UnmovedP)
    s.P += Pp;
  else
    s.P += phi6 * Pp * phi6.transpose();
  const MatX PHs = s.P * Hs;
  s.D = Hs.transpose() * PHs;
  s.G = v == Riccati::GNoInverse ? MatX(PHs * s.D) : MatX(PHs * s.D.inverse());
  if (v == Riccati::NoProjection)
    s.P_plus = s.P;
  else if (v == Riccati::PlusGDG)
    s.P_plus = s.P + s.G * s.D * s.G.transpose();
  else if (v == Riccati::PTauBar)
    s.P_plus = s.P * (Mat6::Identity() - s.G * Hs.transpose());
  else
    s.P_plus = s.P - s.G * s.D * s.G.transpose();
  return s;
}

// The whole sweep, tip to base, with the mistake \p v at every step.
std::vector<soa::ex06::RiccatiStep> riccati_sweep_variant(const soa::Model& m, const VecX& theta,
                                                          const soa::Workspace& ws, Riccati v) {
  std::vector<soa::ex06::RiccatiStep> out;
  Mat6 Pp = Mat6::Zero();
  for (int k = 1; k <= m.n(); ++k) {
    Mat6 phi6 = Mat6::Identity();
    if (k > 1) phi6 = ws.phi[std::size_t(v == Riccati::NeighbourPhi ? k - 1 : k - 2)].matrix();
    out.push_back(riccati_variant(Pp, phi6, m.body(k).M.matrix(), H_star(m, theta, k),
                                  v == Riccati::NeighbourPhi ? Riccati::Right : v));
    Pp = out.back().P_plus;
  }
  return out;
}

struct Variant {
  Riccati v;
  const char* kind;
  const char* says;
};

const Variant kPhiVariants[] = {
    {Riccati::TransposedPhi, "transpose",
     "your P(k) carries P+(k-1) as phi*(k,k-1) P+ phi(k,k-1): forces go inboard with phi, so "
     "an inertia moves as phi P+ phi* (the transpose on the right)"},
    {Riccati::UnmovedP, "wrong frame",
     "your P(k) adds P+(k-1) where it is, at O_{k-1} in O_{k-1} coordinates: move it to O_k "
     "first, phi(k,k-1) P+(k-1) phi*(k,k-1)"},
    {Riccati::NoM, "dropped term", "M(k) is missing from your P(k)"},
};
const Variant kNeighbourVariant = {
    Riccati::NeighbourPhi, "neighbour index",
    "your P(k) carries P+(k-1) with phi(k+1,k) = ws.phi[k-1]: phi(k,k-1) is ws.phi[k-2]"};
const Variant kProjectionVariants[] = {
    {Riccati::GNoInverse, "inverse", "your G(k) is P H* D: G(k) = P(k) H*(k) D^-1(k)"},
    {Riccati::NoProjection, "dropped term",
     "your P+(k) is P(k): the free directions of hinge k are not taken out (P(k) - G D G*); "
     "as it is, it is the composite inertia R(k) of lesson 5"},
    {Riccati::PlusGDG, "sign", "your P+(k) adds G D G*: P+(k) = P(k) - G(k) D(k) G*(k)"},
    {Riccati::PTauBar, "wrong side",
     "your P+(k) is P(k) tau_bar(k), tau_bar on the wrong side: P+(k) = tau_bar(k) P(k), "
     "symmetric, with H(k) P+(k) = 0"},
};

}  // namespace

// clang-format off
/* planted mistakes of 6.1
soa_plant(6.1 transpose
  FIND [=[phi6 * P_plus_prev * phi6.transpose()]=]
  WRONG [=[phi6.transpose() * P_plus_prev * phi6]=] TYPE [=[Mat6]=]
  EXPECT [=[likely mistake \(transpose\): your P\(k\) carries P\+\(k-1\) as phi\*\(k,k-1\) P\+ phi\(k,k-1\)]=])
soa_plant(6.1 one-dof-gain
  FIND [=[PHs * s.D.inverse()]=]
  WRONG [=[PHs / s.D(0, 0)]=] TYPE [=[MatX<double>]=]
  EXPECT [=[G\(k\) = P H\* D\^-1: wrong in [0-9]+ of [0-9]+ cases.*symptom: it fails only where a hinge has several degrees of freedom: [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
*/
// clang-format on
// 6.1: one step of the Riccati recursion, given the library's P+(k-1), against
// soa::articulated_inertias; each body of each chain is a case.
TEST(Exercise6_1_RiccatiStep, MatchesLibrary) {
  Random<double> rnd;
  // Declared last to first: the first check's message is the one the table shows.
  Check Pp_check("P+(k) = P - G D G*", 64 * kEps), G_check("G(k) = P H* D^-1", 64 * kEps),
      D_check("D(k) = H P H*", 64 * kEps), P_check("P(k) = phi P+(k-1) phi* + M(k)", 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const ChainCase c = soa::test::draw_chain_case(rnd, i, lesson6_cases(true, false, false));
    const soa::Model& m = c.m;
    const Library lib(m, c.x.theta);
    for (int k = 1; k <= m.n(); ++k) {
      const std::size_t j = std::size_t(k - 1);
      const Mat6 Pp = k > 1 ? lib.art.P_plus[j - 1] : Mat6::Zero();
      const soa::Phi phi = k > 1 ? lib.ws.phi[j - 1] : soa::Phi();
      const MatX Hs = H_star(m, c.x.theta, k);
      const soa::ex06::RiccatiStep s = soa::ex06::riccati_step(Pp, phi, m.body(k).M, Hs);
      const double scale = std::max(1.0, lib.art.P[j].norm()) * lib.kappa(k);
      const unsigned tags = step_tags(c, k);
      auto inputs = [&, k] {
        return "// body " + std::to_string(k) + " (" + soa::hinge_type_name(m.body(k).hinge.type) +
               " hinge)\n" + matrix_code("soa::Mat6<double>", "P_plus_prev", Pp) +
               soa::test::code("phi", phi) + soa::test::code("M", m.body(k).M) +
               matrix_code("soa::MatX<double>", "H_star", Hs) +
               "auto s = soa::ex06::riccati_step(P_plus_prev, phi, M, H_star);\n";
      };
      std::vector<std::pair<const Variant*, soa::ex06::RiccatiStep>> variants;
      auto all_variants = [&] {
        if (variants.empty()) {
          for (const Variant& v : kPhiVariants)
            variants.emplace_back(&v,
                                  riccati_variant(Pp, phi.matrix(), m.body(k).M.matrix(), Hs, v.v));
          for (const Variant& v : kProjectionVariants)
            variants.emplace_back(&v,
                                  riccati_variant(Pp, phi.matrix(), m.body(k).M.matrix(), Hs, v.v));
        }
        return variants;
      };
      auto mistakes = [&](auto field) {
        return [&, field] {
          Mistakes out;
          for (const auto& [v, s_v] : all_variants())
            out.push_back(Mistake{v->kind, v->says, MatX(field(s_v))});
          return out;
        };
      };
      P_check.add(i, s.P, lib.art.P[j], scale, tags, inputs,
                  mistakes([](const soa::ex06::RiccatiStep& r) { return MatX(r.P); }),
                  soa::test::blocks6("P(k)"));
      D_check.add(i, s.D, MatX(lib.art.D[j]), scale, tags, inputs,
                  mistakes([](const soa::ex06::RiccatiStep& r) { return r.D; }));
      G_check.add(i, s.G, MatX(lib.art.G[j]), scale, tags, inputs,
                  mistakes([](const soa::ex06::RiccatiStep& r) { return r.G; }), six_rows("G(k)"));
      Pp_check.add(i, s.P_plus, lib.art.P_plus[j], scale, tags, inputs,
                   mistakes([](const soa::ex06::RiccatiStep& r) { return MatX(r.P_plus); }),
                   soa::test::blocks6("P+(k)"));
    }
  }
}

// clang-format off
/* planted mistakes of 6.2
soa_plant(6.2 transpose
  FIND [=[Mat6::Identity() - G * H_star.transpose()]=]
  WRONG [=[Mat6::Identity() - H_star * G.transpose()]=] TYPE [=[Mat6]=]
  EXPECT [=[likely mistake \(transpose\): your result is tau_bar\* = I - H\* G\*]=])
*/
// clang-format on
// 6.2: tau_bar of each body's library P(k), against soa::ArticulatedT::tau_bar, and its two
// properties: a projection, and H tau_bar P = 0.
TEST(Exercise6_2_TauBar, ProjectionMatchesLibrary) {
  Random<double> rnd;
  Check hp("H tau_bar P = 0", 64 * kEps), proj("tau_bar^2 = tau_bar", 64 * kEps),
      lib_check("tau_bar = I - G H", 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const ChainCase c = soa::test::draw_chain_case(rnd, i, lesson6_cases(true, false, false));
    const soa::Model& m = c.m;
    const Library lib(m, c.x.theta);
    for (int k = 1; k <= m.n(); ++k) {
      const Mat6& P = lib.art.P[std::size_t(k - 1)];
      const MatX Hs = H_star(m, c.x.theta, k);
      const Mat6 t = soa::ex06::tau_bar(P, Hs);
      const Mat6 t_ref = lib.art.tau_bar(m, c.x.theta, k);
      const double kappa = lib.kappa(k);
      const unsigned tags = step_tags(c, k);
      auto inputs = [&] {
        return matrix_code("soa::Mat6<double>", "P", P) +
               matrix_code("soa::MatX<double>", "H_star", Hs) +
               "soa::Mat6<double> t = soa::ex06::tau_bar(P, H_star);\n";
      };
      auto mistakes = [&] {
        const MatX PHs = P * Hs;
        const MatX D = Hs.transpose() * PHs;
        const MatX GH = PHs * D.inverse() * Hs.transpose();
        return Mistakes{
            {"transpose", "your result is tau_bar* = I - H* G*, the transpose: tau_bar = I - G H",
             t_ref.transpose()},
            {"dropped term",
             "your result is G H, what tau_bar takes away: tau_bar = I - G H (the identity less "
             "G H)",
             GH},
            soa::test::negated(t_ref, "your result is G H - I: tau_bar = I - G H"),
            {"inverse", "your G is P H* D, not P H* D^-1 (D = H P H*)",
             Mat6::Identity() - PHs * D * Hs.transpose()},
        };
      };
      lib_check.add(i, t, t_ref, kappa, tags, inputs, mistakes, soa::test::blocks6("tau_bar"));
      proj.add(i, t * t - t, Mat6::Zero(), kappa, tags, inputs, {},
               soa::test::blocks6("tau_bar^2 - tau_bar"));
      hp.add(i, Hs.transpose() * t * P, MatX::Zero(Hs.cols(), 6), std::max(1.0, P.norm()) * kappa,
             tags, inputs);
    }
  }
}

// clang-format off
/* planted mistakes of 6.3
soa_plant(6.3 neighbour-index
  FIND [=[soa::transform_symmetric(ws.phi[std::size_t(k - 2)], P_plus)]=]
  WRONG [=[soa::transform_symmetric(ws.phi[std::size_t(k - 1)], P_plus)]=] TYPE [=[Mat6]=]
  EXPECT [=[likely mistake \(neighbour index\): your P\(k\) carries P\+\(k-1\) with phi\(k\+1,k\)]=])
*/
// clang-format on
// 6.3: D(k) of random revolute chains, against soa::articulated_inertias. Each entry is held
// to its own body's scale: D(k) - library over max(1, |P(k)|) kappa(k), at most 64 eps.
TEST(Exercise6_3_RevoluteD, MatchesLibrary) {
  Random<double> rnd;
  Check check("D(k), the articulated hinge inertias", 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const ChainCase c = soa::test::draw_chain_case(rnd, i, lesson6_cases(false, false, false));
    const soa::Model& m = c.m;
    const Library lib(m, c.x.theta);
    const VecX D = soa::ex06::revolute_D(m, c.x.theta);
    VecX D_ref(m.n()), weight(m.n());
    for (int k = 1; k <= m.n(); ++k) {
      D_ref[k - 1] = lib.art.D[std::size_t(k - 1)](0, 0);
      weight[k - 1] = std::max(1.0, lib.art.P[std::size_t(k - 1)].norm()) * lib.kappa(k);
    }
    auto mistakes = [&] {
      Mistakes out;
      auto D_of = [&](Riccati v) {
        const auto s = riccati_sweep_variant(m, c.x.theta, lib.ws, v);
        VecX d(m.n());
        for (int k = 1; k <= m.n(); ++k) d[k - 1] = s[std::size_t(k - 1)].D(0, 0);
        return d;
      };
      out.push_back(
          Mistake{kNeighbourVariant.kind, kNeighbourVariant.says, D_of(Riccati::NeighbourPhi)});
      for (const Variant& v : kPhiVariants) out.push_back(Mistake{v.kind, v.says, D_of(v.v)});
      for (const Variant& v : kProjectionVariants)
        if (v.v != Riccati::GNoInverse) out.push_back(Mistake{v.kind, v.says, D_of(v.v)});
      return out;
    };
    check.add(
        i, D, D_ref, per_entry_scale(D, D_ref, weight), c.tags,
        [&] { return c.code() + "soa::VecX<double> D = soa::ex06::revolute_D(m, x.theta);\n"; },
        mistakes, soa::test::per_dof(m, "D"));
  }
}

// clang-format off
/* planted mistakes of 6.4
soa_plant(6.4 sign
  FIND [=[A + L * B.transpose() - B * L - L * C * L]=]
  WRONG [=[A + L * B.transpose() - B * L + L * C * L]=] TYPE [=[Mat3<double>]=]
  EXPECT [=[likely mistake \(sign\): your top-left block adds L C' L]=])
soa_plant(6.4 wrong-frame
  FIND [=[tilde(phi.l())]=]
  WRONG [=[tilde(Vec3<double>(R * phi.l()))]=] TYPE [=[Mat3<double>]=]
  EXPECT [=[likely mistake \(wrong frame\): your L is the cross-product matrix of R l]=])
*/
// clang-format on
// 6.4: phi P phi* by blocks, against the dense product with phi.matrix(). The cases vary
// phi (rotated or not, offset or not) and P (off-diagonal block B zero or not).
TEST(Exercise6_4_TransformSymmetric, MatchesDense) {
  Random<double> rnd;
  Check check("phi P phi*", 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const Mat3 R0 = rnd.rotation();
    const Vec3 l0 = rnd.vec3();
    const Mat3 R = i % 4 == 0 ? Mat3(Mat3::Identity()) : R0;
    const Vec3 l = i % 3 == 0 ? Vec3(Vec3::Zero()) : l0;
    const soa::Phi phi(R, l);
    Mat6 A;
    for (int r = 0; r < 6; ++r)
      for (int s = 0; s < 6; ++s) A(r, s) = rnd.normal();
    Mat6 P = A + A.transpose();
    if (i % 5 == 0) P.topRightCorner<3, 3>().setZero(), P.bottomLeftCorner<3, 3>().setZero();
    unsigned tags = 0;
    if (i % 4 != 0) tags |= soa::test::kRotated;
    if (i % 3 != 0) tags |= soa::test::kTranslated;
    if (i % 5 != 0) tags |= soa::test::kOffsetCom;
    const Mat6 dense = phi.matrix() * P * phi.matrix().transpose();
    const Mat6 got = soa::ex06::transform_symmetric(phi, P);
    auto mistakes = [&] {
      auto via = [&](const soa::Phi& p) { return Mat6(p.matrix() * P * p.matrix().transpose()); };
      // By blocks, with the top-left block's terms chosen.
      const Mat3 Ap = R * P.topLeftCorner<3, 3>() * R.transpose();
      const Mat3 Bp = R * P.topRightCorner<3, 3>() * R.transpose();
      const Mat3 Cp = R * P.bottomRightCorner<3, 3>() * R.transpose();
      const Mat3 L = soa::tilde(l);
      auto blocks = [&](const Mat3& top_left, const Mat3& top_right, const Mat3& bottom_left) {
        Mat6 o;
        o << top_left, top_right, bottom_left, Cp;
        return o;
      };
      const Mat3 BLC = Bp + L * Cp;
      return Mistakes{
          {"transpose",
           "your result is phi* P phi: an inertia moves as phi P phi* (forces inboard with phi)",
           phi.matrix().transpose() * P * phi.matrix()},
          {"transpose", "your blocks are rotated as R* A R: A' = R A R* (R = phi.R())",
           via(soa::Phi(R.transpose(), l))},
          {"wrong frame",
           "your blocks are not rotated: rotate first, A' = R A R*, B' = R B R*, C' = R C R*",
           via(soa::Phi(Mat3::Identity(), l))},
          {"wrong frame",
           "your L is the cross-product matrix of R l: l = phi.l() is already in the new frame's "
           "coordinates, L = tilde(phi.l())",
           via(soa::Phi(R, R * l))},
          {"sign", "your shift has the opposite sign: L = tilde(l), l = phi.l(), not -l",
           via(soa::Phi(R, -l))},
          {"sign", "your top-left block adds L C' L: it is A' + L B'* - B' L - L C' L",
           blocks(Ap + L * Bp.transpose() - Bp * L + L * Cp * L, BLC, BLC.transpose())},
          {"dropped term", "the term - L C' L is missing from your top-left block",
           blocks(Ap + L * Bp.transpose() - Bp * L, BLC, BLC.transpose())},
          {"dropped term", "the terms L B'* - B' L are missing from your top-left block",
           blocks(Ap - L * Cp * L, BLC, BLC.transpose())},
          {"transpose",
           "your bottom-left block is B' + L C', not its transpose (B' + L C')*: phi P phi* is "
           "symmetric",
           blocks(Ap + L * Bp.transpose() - Bp * L - L * Cp * L, BLC, BLC)},
      };
    };
    check.add(
        i, got, dense, std::max(1.0, dense.norm()), tags,
        [&] {
          return soa::test::code("phi", phi) + matrix_code("soa::Mat6<double>", "P", P) +
                 "soa::Mat6<double> out = soa::ex06::transform_symmetric(phi, P);\n";
        },
        mistakes, soa::test::blocks6("phi P phi*"));
  }
}

// The library's f = R alpha+ + y at the state the Newton-Euler pass in ws left (lesson 6,
// section 8): R(k) alpha+(k) + y(k) for every k, stacked.
VecX composite_forces(const soa::Model& m, const soa::Workspace& ws, std::vector<soa::Force>& y) {
  std::vector<soa::SpatialInertia> R(std::size_t(m.n()));
  soa::composite_inertias(m, ws, R);
  std::vector<soa::Acceleration> ap(std::size_t(m.n()));
  soa::alpha_plus(m, ws, ap);
  y.resize(std::size_t(m.n()));
  soa::composite_bias(m, ws, R, ap, {}, y);
  VecX f(6 * m.n());
  for (int k = 1; k <= m.n(); ++k)
    f.segment<6>(6 * (k - 1)) =
        (R[std::size_t(k - 1)] * ap[std::size_t(k - 1)]).vector() + y[std::size_t(k - 1)].vector();
  return f;
}

// clang-format off
/* planted mistakes of 6.5
soa_plant(6.5 dropped-z
  FIND [=[fd.art.P_plus[j] * fd.alpha_plus[j].vector() + fd.z_plus[j].vector()]=]
  WRONG [=[fd.art.P_plus[j] * fd.alpha_plus[j].vector()]=] TYPE [=[Vec6<double>]=]
  EXPECT [=[likely mistake \(dropped term\): z\+\(k\) is missing from your f\(k\)]=])
*/
// clang-format on
// 6.5: P+ alpha+ + z+ from soa::forward_dynamics, against the Newton-Euler f at the
// beta_dot it found and against R alpha+ + y of the composite inertias.
TEST(Exercise6_5_ArticulatedForces, MatchNewtonEulerAndComposite) {
  Random<double> rnd;
  Check comp("f(k) against R(k) alpha+(k) + y(k)", 16 * kEps),
      ne("f(k), the inter-body forces, against Newton-Euler", 16 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const ChainCase c = soa::test::draw_chain_case(rnd, i, lesson6_cases(true, true, true));
    const soa::Model& m = c.m;
    const VecX T = soa::test::random_vector(rnd, m.nv());
    soa::Workspace ws(m);
    soa::ForwardDynamics fd(m);
    VecX bd(m.nv()), T_back(m.nv());
    soa::forward_dynamics(m, c.x, T, {}, ws, fd, bd);
    const std::vector<soa::Acceleration> alpha = ws.alpha;
    soa::inverse_dynamics(m, c.x, bd, {}, ws, T_back);
    std::vector<soa::Force> y;
    const VecX f_comp = composite_forces(m, ws, y);
    const VecX f_ne = stack(ws.f);
    const std::vector<Vec6> f = soa::ex06::articulated_forces(m, c.x, T);
    double scale = 1;
    for (int k = 1; k <= m.n(); ++k) {
      const std::size_t j = std::size_t(k - 1);
      scale = std::max({scale, ws.f[j].vector().norm(), f_comp.segment<6>(6 * int(j)).norm(),
                        y[j].vector().norm()});
    }
    const Library lib(m, c.x.theta);
    scale *= 6 * m.n() * lib.kappa(m.n());
    auto inputs = [&] {
      return c.code() + soa::test::code("T", T) +
             "auto f = soa::ex06::articulated_forces(m, x, T);\n";
    };
    auto mistakes = [&] {
      VecX no_z(6 * m.n()), z(6 * m.n()), P_not_plus(6 * m.n()), minus(6 * m.n()),
          with_alpha(6 * m.n());
      for (int k = 1; k <= m.n(); ++k) {
        const std::size_t j = std::size_t(k - 1);
        const Vec6 Pa = fd.art.P_plus[j] * fd.alpha_plus[j].vector();
        no_z.segment<6>(6 * int(j)) = Pa;
        z.segment<6>(6 * int(j)) = Pa + fd.z[j].vector();
        P_not_plus.segment<6>(6 * int(j)) =
            fd.art.P[j] * fd.alpha_plus[j].vector() + fd.z_plus[j].vector();
        minus.segment<6>(6 * int(j)) = Pa - fd.z_plus[j].vector();
        with_alpha.segment<6>(6 * int(j)) =
            fd.art.P_plus[j] * alpha[j].vector() + fd.z_plus[j].vector();
      }
      return Mistakes{
          {"dropped term", "z+(k) is missing from your f(k) = P+(k) alpha+(k) + z+(k)", no_z},
          {"wrong quantity",
           "your f(k) takes z(k) (fd.z), the bias before hinge k's innovation: z+(k) = z(k) + "
           "G(k) epsilon(k) (fd.z_plus)",
           z},
          {"wrong quantity",
           "your f(k) takes P(k) (fd.art.P), not P+(k) (fd.art.P_plus): with alpha+ the hinge "
           "is free, its inertia is projected",
           P_not_plus},
          {"sign", "your f(k) subtracts z+(k): f(k) = P+(k) alpha+(k) + z+(k)", minus},
          {"wrong quantity",
           "your f(k) takes alpha(k) (ws.alpha), not alpha+(k) (fd.alpha_plus) = phi*(k+1,k) "
           "alpha(k+1)",
           with_alpha},
      };
    };
    if (int(f.size()) != m.n()) {
      ne.add(i, VecX::Zero(6 * Eigen::Index(f.size())), f_ne, scale, c.tags, inputs);
      continue;
    }
    ne.add(i, stack(f), f_ne, scale, c.tags, inputs, mistakes, soa::test::per_body_spatial("f"));
    comp.add(i, stack(f), f_comp, scale, c.tags, inputs, {}, soa::test::per_body_spatial("f"));
  }
}

// The composite-body bias of 6.6 with a classic mistake in it (or none).
enum class Bias {
  Right,
  NeighbourPhi,         // phi(k+1,k) y(k-1)
  TransposedPhi,        // phi*(k,k-1) y(k-1)
  NoB,                  // b(k) missing
  RAlpha,               // R(k) alpha(k): alpha+ not subtracted
  MassNotComposite,     // M(k) for R(k)
  NoGravity,            // alpha(n+1) = 0
  GravitySign,          // alpha(n+1) = [0; +g]
  AlphaPlusTransposed,  // alpha+ = phi(k+1,k) alpha(k+1)
  AlphaPlusUnmoved,     // alpha+ = alpha(k+1)
};
VecX bias_variant(const soa::Model& m, const soa::Workspace& ws,
                  const std::vector<soa::SpatialInertia>& R, Bias v) {
  Vec6 base = Vec6::Zero();
  if (v != Bias::NoGravity) base.tail<3>() = v == Bias::GravitySign ? m.gravity : Vec3(-m.gravity);
  VecX y = VecX::Zero(6 * m.n());
  for (int k = 1; k <= m.n(); ++k) {
    const std::size_t j = std::size_t(k - 1);
    const Mat6 phi = ws.phi[j].matrix();
    const Vec6 next = k < m.n() ? ws.alpha[j + 1].vector() : base;
    const Vec6 ap = v == Bias::AlphaPlusTransposed ? Vec6(phi * next)
                    : v == Bias::AlphaPlusUnmoved  ? next
                                                   : Vec6(phi.transpose() * next);
    const Mat6 Rk = v == Bias::MassNotComposite ? m.body(k).M.matrix() : R[j].matrix();
    Vec6 yk = Rk * (v == Bias::RAlpha ? ws.alpha[j].vector() : Vec6(ws.alpha[j].vector() - ap));
    if (v != Bias::NoB) yk += soa::gyroscopic_force(m.body(k).M, ws.V[j]).vector();
    if (k > 1) {
      const Vec6 yc = y.segment<6>(6 * int(j - 1));
      yk += v == Bias::NeighbourPhi    ? Vec6(phi * yc)
            : v == Bias::TransposedPhi ? Vec6(ws.phi[j - 1].matrix().transpose() * yc)
                                       : Vec6(ws.phi[j - 1].matrix() * yc);
    }
    y.segment<6>(6 * int(j)) = yk;
  }
  return y;
}

// clang-format off
/* planted mistakes of 6.6
soa_plant(6.6 neighbour-index
  FIND [=[ws.phi[j - 1].matrix() * y.back()]=]
  WRONG [=[ws.phi[j].matrix() * y.back()]=] TYPE [=[Vec6<double>]=]
  EXPECT [=[likely mistake \(neighbour index\): your y\(k\) takes phi\(k\+1,k\) y\(k-1\)]=])
soa_plant(6.6 dropped-b
  FIND [=[gyroscopic_force(m.body(k).M, ws.V[j]).vector()]=]
  WRONG [=[Vec6<double>::Zero()]=] TYPE [=[Vec6<double>]=]
  EXPECT [=[likely mistake \(dropped term\): b\(k\), the gyroscopic force, is missing]=])
soa_plant(6.6 gravity-doubled
  FIND [=[gravity_base_acceleration(m).vector()]=]
  WRONG [=[2.0 * gravity_base_acceleration(m).vector()]=] TYPE [=[Vec6<double>]=]
  EXPECT [=[y\(k\), the composite-body bias: wrong in [0-9]+ of [0-9]+ cases.*symptom: it fails only where gravity is on: [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
*/
// clang-format on
// 6.6: y(k) against soa::composite_bias, and R alpha+ + y against the Newton-Euler f.
TEST(Exercise6_6_CompositeBias, MatchesNewtonEulerAndLibrary) {
  Random<double> rnd;
  Check ne("R(k) alpha+(k) + y(k) against the Newton-Euler f(k)", 16 * kEps),
      lib("y(k), the composite-body bias", 16 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const ChainCase c = soa::test::draw_chain_case(rnd, i, lesson6_cases(true, true, true));
    const soa::Model& m = c.m;
    soa::Workspace ws(m);
    VecX T(m.nv());
    soa::inverse_dynamics(m, c.x, c.beta_dot, {}, ws, T);
    std::vector<soa::SpatialInertia> R(std::size_t(m.n()));
    soa::composite_inertias(m, ws, R);
    std::vector<soa::Acceleration> ap(std::size_t(m.n()));
    soa::alpha_plus(m, ws, ap);
    std::vector<soa::Force> y_lib(std::size_t(m.n()));
    soa::composite_bias(m, ws, R, ap, {}, y_lib);
    const std::vector<Vec6> y = soa::ex06::composite_bias(m, c.x, c.beta_dot);
    VecX Ra(6 * m.n());
    double scale = 1;
    for (int k = 1; k <= m.n(); ++k) {
      const std::size_t j = std::size_t(k - 1);
      Ra.segment<6>(6 * int(j)) = (R[j] * ap[j]).vector();
      scale = std::max({scale, ws.f[j].vector().norm(), Ra.segment<6>(6 * int(j)).norm(),
                        y_lib[j].vector().norm()});
    }
    scale *= 6 * m.n();
    auto inputs = [&] {
      return c.code() + "auto y = soa::ex06::composite_bias(m, x, beta_dot);\n";
    };
    auto mistakes = [&] {
      auto v = [&](Bias b) { return bias_variant(m, ws, R, b); };
      return Mistakes{
          {"neighbour index",
           "your y(k) takes phi(k+1,k) y(k-1), i.e. ws.phi[k-1]: phi(k,k-1) is ws.phi[k-2]",
           v(Bias::NeighbourPhi)},
          {"transpose",
           "your y(k) takes phi*(k,k-1) y(k-1): forces go inboard with phi (phi[k-2].apply(y))",
           v(Bias::TransposedPhi)},
          {"dropped term", "b(k), the gyroscopic force, is missing from your y(k)", v(Bias::NoB)},
          {"dropped term",
           "your y(k) takes R(k) alpha(k): it is R(k) (alpha(k) - alpha+(k)), the relative "
           "acceleration across hinge k",
           v(Bias::RAlpha)},
          {"wrong inertia",
           "your y(k) takes M(k) (m.body(k).M) where R(k), the composite inertia, belongs",
           v(Bias::MassNotComposite)},
          {"dropped term",
           "gravity is missing: alpha+(n) = phi*(n+1,n) alpha(n+1), alpha(n+1) = [0; -g] "
           "(soa::gravity_base_acceleration)",
           v(Bias::NoGravity)},
          {"sign", "your base acceleration is [0; +g]: alpha(n+1) = [0; -g]", v(Bias::GravitySign)},
          {"transpose",
           "your alpha+(k) is phi(k+1,k) alpha(k+1): accelerations go outward with phi*, "
           "alpha+(k) = phi*(k+1,k) alpha(k+1) (transpose_apply)",
           v(Bias::AlphaPlusTransposed)},
          {"wrong frame",
           "your alpha+(k) is alpha(k+1) as it is, at O_{k+1} in its coordinates: carry it to "
           "O_k, alpha+(k) = phi*(k+1,k) alpha(k+1)",
           v(Bias::AlphaPlusUnmoved)},
      };
    };
    if (int(y.size()) != m.n()) {
      lib.add(i, VecX::Zero(6 * Eigen::Index(y.size())), stack(y_lib), scale, c.tags, inputs);
      continue;
    }
    lib.add(i, stack(y), stack(y_lib), scale, c.tags, inputs, mistakes,
            soa::test::per_body_spatial("y"));
    ne.add(i, Ra + stack(y), stack(ws.f), scale, c.tags, inputs, {},
           soa::test::per_body_spatial("R alpha+ + y"));
  }
}

// clang-format off
/* planted mistakes of 6.7
soa_plant(6.7 the-given-bug
  FIND [=[tau_bar * Pk]=]
  WRONG [=[Pk * tau_bar]=] TYPE [=[Mat6]=]
  EXPECT [=[the checker knows this mistake: it names it after 3 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your P\(k\) is the given code's]=]
  NAMED [=[likely mistake \(the given bug\): your P\(k\) is the given code's]=])
*/
// clang-format on
// 6.7: the stub's Riccati sweep with its bug fixed, against soa::articulated_inertias.
TEST(Exercise6_7_RiccatiSweepBug, MatchesLibrary) {
  Random<double> rnd;
  Check check("P(k), the articulated inertias", 64 * kEps);
  for (int i = 0; i < kCases; ++i) {
    const ChainCase c = soa::test::draw_chain_case(rnd, i, lesson6_cases(true, false, false));
    const soa::Model& m = c.m;
    const Library lib(m, c.x.theta);
    const std::vector<Mat6> P = soa::ex06::riccati_sweep(m, c.x.theta);
    double P_max = 1;
    for (const Mat6& Pk : lib.art.P) P_max = std::max(P_max, Pk.norm());
    auto mistakes = [&] {
      auto P_of = [&](Riccati v) {
        std::vector<Mat6> out;
        for (const auto& s : riccati_sweep_variant(m, c.x.theta, lib.ws, v)) out.push_back(s.P);
        return stack6(out);
      };
      Mistakes out{
          {"the given bug",
           "your P(k) is the given code's: its bug is still there. Compute, in the code, the "
           "properties of lesson 6, section 3 of each P+(k) (symmetric, H(k) P+(k) = 0): which "
           "fails, and which line makes it?",
           P_of(Riccati::PTauBar)},
          {kNeighbourVariant.kind, kNeighbourVariant.says, P_of(Riccati::NeighbourPhi)}};
      for (const Variant& v : kPhiVariants) out.push_back(Mistake{v.kind, v.says, P_of(v.v)});
      for (const Variant& v : kProjectionVariants)
        if (v.v != Riccati::PTauBar) out.push_back(Mistake{v.kind, v.says, P_of(v.v)});
      return out;
    };
    check.add(
        i, stack6(P), stack6(lib.art.P), P_max * lib.kappa(m.n()), c.tags,
        [&] { return c.code() + "auto P = soa::ex06::riccati_sweep(m, x.theta);\n"; }, mistakes,
        stacked_blocks6("P"));
  }
}

// clang-format off
/* planted mistakes of 6.8
soa_plant(6.8 wrong-part
  FIND [=[MatX<double>(m.body(k).hinge.H_star(theta.data() + m.body(k).q_offset))]=]
  WRONG [=[(MatX<double>(6, m.body(k).hinge.nv())
              << m.body(k).hinge.H_star(theta.data() + m.body(k).q_offset).bottomRows(3),
          m.body(k).hinge.H_star(theta.data() + m.body(k).q_offset).topRows(3)).finished()]=]
  TYPE [=[MatX<double>]=]
  EXPECT [=[the checker knows this mistake: it names it after 3 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your columns have the angular and the linear rows swapped]=]
  NAMED [=[likely mistake \(wrong part\): your columns have the angular and the linear rows swapped]=])
*/
// clang-format on
// 6.8: the predicted null spaces of P+(k), against the library's P+(k): as many columns as
// 6 - rank P+(k), in its null space, independent. Each body of each chain is a case.
TEST(Exercise6_8_PPlusNullSpace, MatchesLibrary) {
  Random<double> rnd;
  Check independent(
      "the columns of X(k) are independent (smallest singular value of the "
      "unit columns > 1e-6)",
      0.5),
      in_null_space(
          "X(k) in the null space of P+(k) (columns scaled to unit length; expected: "
          "their part in it)",
          64 * kEps),
      count("r_k, the number of columns of X(k) (6 - rank P+(k))", 0.5),
      size("X, one matrix X(k) per body", 0.5);
  for (int i = 0; i < kCases; ++i) {
    const ChainCase c = soa::test::draw_chain_case(rnd, i, lesson6_cases(true, false, false));
    const soa::Model& m = c.m;
    const Library lib(m, c.x.theta);
    const std::vector<MatX> X = soa::ex06::P_plus_null_spaces(m, c.x.theta);
    auto inputs = [&] {
      return c.code() + "auto X = soa::ex06::P_plus_null_spaces(m, x.theta);\n";
    };
    if (!size.add(i, MatX::Constant(1, 1, double(X.size())), MatX::Constant(1, 1, m.n()), 1, c.tags,
                  inputs))
      continue;
    for (int k = 1; k <= m.n(); ++k) {
      const std::size_t j = std::size_t(k - 1);
      const Mat6& Pp = lib.art.P_plus[j];
      const MatX Hs = H_star(m, c.x.theta, k);
      const int nk = int(Hs.cols());
      const Eigen::JacobiSVD<MatX> svd_P(Pp, Eigen::ComputeFullU);
      const VecX sv = svd_P.singularValues();
      int rank = 0;
      for (Eigen::Index r = 0; r < sv.size(); ++r) rank += sv[r] > 1e-8 * std::max(1.0, sv[0]);
      const unsigned tags = step_tags(c, k);
      const std::string which = "// body " + std::to_string(k) + ": X[" + std::to_string(k - 1) +
                                "], " + soa::hinge_type_name(m.body(k).hinge.type) + " hinge\n";
      auto inputs_k = [&] { return inputs() + which; };
      MatX cnt(1, 1), cnt_ref(1, 1);
      cnt(0, 0) = double(X[j].cols());
      cnt_ref(0, 0) = double(6 - rank);
      auto count_mistakes = [&] {
        return Mistakes{
            {"rank for nullity",
             "your X(k) has 6 - n_k columns: that is the rank of P+(k), the directions it does "
             "feel; its null space has the rest",
             MatX::Constant(1, 1, double(6 - nk))},
            {"nothing lost",
             "your X(k) has no columns: P+(k) = tau_bar(k) P(k) is singular, the projection "
             "tau_bar(k) takes directions out",
             MatX::Zero(1, 1)},
        };
      };
      if (!count.add(i, cnt, cnt_ref, 1, tags, inputs_k, count_mistakes)) continue;
      if (X[j].rows() != 6) {
        in_null_space.add(i, X[j], MatX::Zero(6, X[j].cols()), 1, tags, inputs_k);
        continue;
      }
      // Unit columns (the basis' scale is free), against their part in the null space of
      // the library's P+(k): N N* X with N an orthonormal basis of it. A column off the null
      // space by d has |P+ x| >= sigma d, sigma the smallest nonzero singular value of P+:
      // the scale is that of P+ X (|P| kappa) over sigma.
      MatX Xn = X[j];
      for (Eigen::Index col = 0; col < Xn.cols(); ++col)
        if (Xn.col(col).norm() > 0) Xn.col(col).normalize();
      const MatX N = svd_P.matrixU().rightCols(6 - rank);
      const MatX in_null = N * (N.transpose() * Xn);
      const double sigma = rank > 0 ? sv[rank - 1] : 1.0;
      auto zero_mistakes = [&] {
        auto unit = [](MatX a) {
          for (Eigen::Index col = 0; col < a.cols(); ++col)
            if (a.col(col).norm() > 0) a.col(col).normalize();
          return a;
        };
        MatX swapped(6, nk);
        swapped << Hs.bottomRows(3), Hs.topRows(3);
        return Mistakes{
            {"wrong quantity",
             "your columns are G(k) = P H* D^-1, the gain: P+(k) G(k) is not zero; which "
             "accelerations does hinge k let through without a force?",
             unit(MatX(lib.art.G[j]))},
            {"wrong part",
             "your columns have the angular and the linear rows swapped (angular part first: a "
             "revolute axis a is [a; 0])",
             unit(swapped)},
        };
      };
      if (!in_null_space.add(i, Xn, in_null,
                             std::max(1.0, lib.art.P[j].norm()) * lib.kappa(k) / sigma, tags,
                             inputs_k, zero_mistakes, six_rows("X(k)")))
        continue;
      const double s_min =
          Xn.cols() == 0 ? 1.0 : Eigen::JacobiSVD<MatX>(Xn).singularValues().minCoeff();
      independent.add(i, MatX::Constant(1, 1, s_min > 1e-6 ? 0.0 : 1.0), MatX::Zero(1, 1), 1, tags,
                      inputs_k);
    }
  }
}

// The shaken base of 6.9 with a classic mistake in it (or none).
enum class Shaken {
  Right,
  PlusG,          // beta_dot = +G* alpha+
  Locked,         // alpha(k) = alpha+(k): H* beta_dot not added going out
  Transposed,     // alpha+ = phi(k+1,k) alpha(k+1)
  Unmoved,        // alpha+(k) = alpha(k+1), not carried by phi*
  BaseUnrotated,  // alpha+(n) = [0; a0], a0 taken in O_n coordinates
  Composite,      // R(k) for P(k): beta_dot = -(H R H*)^-1 H R alpha+
};
VecX shaken_variant(const soa::Model& m, const VecX& theta, const Library& lib, const Vec3& a0,
                    Shaken v) {
  VecX bd(m.nv());
  Vec6 alpha;
  alpha << Vec3::Zero(), a0;
  for (int k = m.n(); k >= 1; --k) {
    const soa::Body& B = m.body(k);
    const std::size_t j = std::size_t(k - 1);
    const Mat6 phi = lib.ws.phi[j].matrix();
    Vec6 ap = v == Shaken::Transposed ? Vec6(phi * alpha)
              : v == Shaken::Unmoved  ? alpha
                                      : Vec6(phi.transpose() * alpha);
    if (v == Shaken::BaseUnrotated && k == m.n()) ap = alpha;
    const MatX Hs = H_star(m, theta, k);
    VecX b;
    if (v == Shaken::Composite) {
      const Mat6 R = lib.art.R[j].matrix();
      const MatX HR = Hs.transpose() * R;
      b = -(HR * Hs).ldlt().solve(HR * ap);
    } else {
      b = (v == Shaken::PlusG ? 1.0 : -1.0) * (lib.art.G[j].transpose() * ap);
    }
    bd.segment(B.v_offset, B.hinge.nv()) = b;
    alpha = v == Shaken::Locked ? ap : Vec6(ap + Hs * b);
  }
  return bd;
}

// clang-format off
/* planted mistakes of 6.9
soa_plant(6.9 sign
  FIND [=[-art.G[j].transpose() * alpha_plus]=]
  WRONG [=[art.G[j].transpose() * alpha_plus]=] TYPE [=[VecX<double>]=]
  EXPECT [=[beta_dot, the hinge accelerations: wrong in [0-9]+ of [0-9]+ cases.*the checker knows this mistake: it names it after 4 failed runs.*where, in case [0-9]+ \(the simplest that fails\): beta_dot of body]=]
  REJECT [=[likely mistake|perhaps \(|G\*\(k\) alpha|phi\*\(k\+1,k\) alpha|your beta_dot\(k\) is \+G\*\(k\) alpha\+\(k\)]=]
  NAMED [=[likely mistake \(sign\): your beta_dot\(k\) is \+G\*\(k\) alpha\+\(k\)]=])
soa_plant(6.9 wrong-frame
  FIND [=[ws.phi[j].matrix().transpose() * alpha]=]
  WRONG [=[alpha]=] TYPE [=[Vec6<double>]=]
  EXPECT [=[beta_dot, the hinge accelerations: wrong in [0-9]+ of [0-9]+ cases.*the checker knows this mistake: it names it after 4 failed runs.*where, in case [0-9]+ \(the simplest that fails\): beta_dot of body]=]
  REJECT [=[likely mistake|perhaps \(|G\*\(k\) alpha|phi\*\(k\+1,k\) alpha|your alpha\+\(k\) is alpha\(k\+1\) as it is]=]
  NAMED [=[likely mistake \(wrong frame\): your alpha\+\(k\) is alpha\(k\+1\) as it is]=])
*/
// clang-format on
// 6.9: beta_dot of the chain at rest when the base accelerates, against
// soa::forward_dynamics with gravity -a0 (gravity is the base acceleration [0; -g]).
TEST(Exercise6_9_ShakenBase, MatchesForwardDynamics) {
  Random<double> rnd;
  Check check("beta_dot, the hinge accelerations", 16 * kEps);
  for (int i = 0; i < kCases; ++i) {
    ChainCase c = soa::test::draw_chain_case(rnd, i, lesson6_cases(true, false, false));
    const soa::Model& m = c.m;
    const Vec3 a0 = 5.0 * rnd.vec3();
    const VecX bd = soa::ex06::shaken_base(m, c.x.theta, a0);
    soa::Model shaken = m;
    shaken.gravity = -a0;
    soa::Workspace ws(shaken);
    soa::ForwardDynamics fd(shaken);
    const soa::State rest{c.x.theta, VecX::Zero(m.nv())};
    const VecX T = VecX::Zero(m.nv());
    VecX bd_ref(m.nv());
    soa::forward_dynamics(shaken, rest, T, {}, ws, fd, bd_ref);
    const Library lib(m, c.x.theta);
    const double scale = std::max(1.0, bd_ref.norm()) * 6 * m.n() * lib.kappa(m.n());
    auto mistakes = [&] {
      auto v = [&](Shaken s) { return shaken_variant(m, c.x.theta, lib, a0, s); };
      return Mistakes{
          soa::test::negated(bd_ref,
                             "your beta_dot has the opposite sign: did you take the base "
                             "acceleration as gravity's [0; -a0]? alpha(n+1) = [0; a0]"),
          {"sign",
           "your beta_dot(k) is +G*(k) alpha+(k): with T(k) = 0 and z(k) = 0, what does H(k) "
           "f(k) = 0 give for beta_dot(k)?",
           v(Shaken::PlusG)},
          {"dropped term",
           "your alpha(k) is alpha+(k): going out, body k moves also by its own hinge, "
           "alpha(k) = alpha+(k) + H*(k) beta_dot(k)",
           v(Shaken::Locked)},
          {"transpose",
           "your alpha+(k) is phi(k+1,k) alpha(k+1): accelerations go outward with phi*, "
           "alpha+(k) = phi*(k+1,k) alpha(k+1)",
           v(Shaken::Transposed)},
          {"wrong frame",
           "your alpha+(k) is alpha(k+1) as it is: carry it to O_k, in O_k coordinates, with "
           "phi*(k+1,k) = ws.phi[k-1]",
           v(Shaken::Unmoved)},
          {"wrong frame",
           "your a0 is taken in O_n coordinates: it is in inertial coordinates, alpha+(n) = "
           "phi*(n+1,n) [0; a0]",
           v(Shaken::BaseUnrotated)},
          {"wrong inertia",
           "your hinges respond with the composite inertias R(k) (the outboard hinges locked): "
           "they are free, the articulated P(k), D(k), G(k) belong",
           v(Shaken::Composite)},
      };
    };
    check.add(
        i, bd, bd_ref, scale, c.tags,
        [&] {
          return c.code() + soa::test::code("a0", a0) +
                 "soa::VecX<double> shaken = soa::ex06::shaken_base(m, x.theta, a0);\n";
        },
        mistakes, soa::test::per_dof(m, "beta_dot"));
  }
}
