// Lesson 8 exercise tests: each exercise of exercises/08-recursive-forward-dynamics/exercises.hpp
// against the library (soa::forward_dynamics, soa::inverse_dynamics, soa::mass_matrix_crb), on
// soa::test::kCases random cases from the fixed seed: chains of 1 to 7 bodies of the hinge types
// the exercise allows, drawn at random, random states and hinge forces, with the features the
// exercise allows varying independently across the cases (at rest, gravity, external forces,
// springs: draw() below). Each check names its quantity, and its catalogue of classic mistakes is
// computed from the reference by the small parameterized sweeps of this file
// (tests/support/exercise_check.hpp). Built against the solutions (ctest), the students' exercises
// (make exercises) and the solutions with planted mistakes (the "planted mistakes" blocks,
// tests/exercises/plant.cmake).
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "chain_case.hpp"
#include "exercise_check.hpp"
#include "exercises.hpp"
#include "property.hpp"
#include "random_chain.hpp"

namespace {

using soa::HingeType;
using soa::test::ChainCase;
using soa::test::Check;
using soa::test::kCases;
using soa::test::Mistake;
using soa::test::Mistakes;
using soa::test::Random;
using Vec6 = soa::Vec6<double>;
using Mat6 = soa::Mat6<double>;
using MatX = soa::MatX<double>;
using VecX = soa::VecX<double>;
using soa::test::stack;

constexpr double kEps = soa::eps<double>();

const std::vector<HingeType> kAllTypes = {HingeType::Revolute,  HingeType::Prismatic,
                                          HingeType::Helical,   HingeType::Universal,
                                          HingeType::Spherical, HingeType::Free};

// What the cases of an exercise may have.
struct Opts {
  std::vector<HingeType> types = kAllTypes;
  bool gravity = true;
  bool external = false;
  bool springs = false;
};

// Case i of an exercise: 1 + i mod 7 bodies with hinge types drawn from o.types, at rest when
// i mod 5 = 0, gravity when i mod 2 = 1, external forces when i mod 3 = 0, springs and dampers
// when i mod 3 = 2, each where the exercise allows it (as tests/support/chain_case.hpp, with
// the hinge types of the exercise and springs in some cases only).
ChainCase draw(Random<double>& rnd, int i, const Opts& o) {
  soa::test::ChainOptions co;
  co.all_hinge_types = false;
  co.gravity = o.gravity && i % 2 == 1;
  co.springs = o.springs && i % 3 == 2;
  std::vector<soa::Body> bodies;
  for (int b = 0; b < 1 + i % 7; ++b) {
    const HingeType t = o.types[rnd.engine()() % o.types.size()];
    bodies.push_back(soa::test::detail::random_body(rnd, b, t, co));
  }
  ChainCase c;
  c.m = soa::test::detail::finish_chain(std::move(bodies), co);
  c.x = soa::test::random_state(rnd, c.m);
  if (i % 5 == 0) c.x.beta.setZero();
  c.beta_dot = VecX::Zero(c.m.nv());
  if (o.external && i % 3 == 0) c.f_ext = soa::test::random_forces(rnd, c.m);
  c.tags = soa::test::chain_tags(c.m, c.x);
  if (!c.f_ext.empty()) c.tags |= soa::test::kExternalForces;
  return c;
}

// A case with its hinge forces T and the library's forward dynamics (phi, V, a, alpha in ws;
// P, D, G, z, z+, nu, alpha+ in fd).
struct Case {
  ChainCase c;
  VecX T;
  soa::Workspace ws;
  soa::ForwardDynamics fd;
  VecX beta_dot;
  Case(ChainCase cc, Random<double>& rnd)
      : c(std::move(cc)),
        T(soa::test::random_vector(rnd, c.m.nv())),
        ws(c.m),
        fd(c.m),
        beta_dot(c.m.nv()) {
    soa::forward_dynamics(c.m, c.x, T, c.f_ext, ws, fd, beta_dot);
  }
  const soa::Model& m() const { return c.m; }
  // |P(k)| |D^{-1}(k)|, the growth of rounding in the sweeps, largest over the bodies.
  double kappa() const {
    double w = 1;
    for (std::size_t j = 0; j < fd.art.P.size(); ++j)
      w = std::max(w, fd.art.P[j].norm() * MatX(fd.art.D_inv[j]).norm());
    return w;
  }
  // The case as code, with T.
  std::string code() const { return c.code() + soa::test::code("T", T); }
};

// The mass matrix by composite bodies (lesson 5), the bias C (inverse dynamics at beta_dot =
// 0: gravity, external forces, springs) and the 2-norm condition number of M.
struct MassAndBias {
  MatX M;
  VecX C;
  double cond = 1;
  MassAndBias(const soa::Model& m, const soa::State& x, const soa::ExternalForces<double>& f_ext) {
    soa::Workspace w(m);
    C.resize(m.nv());
    const VecX zero = VecX::Zero(m.nv());
    soa::inverse_dynamics(m, x, zero, f_ext, w, C);
    std::vector<soa::SpatialInertia> R(std::size_t(m.n()));
    soa::mass_matrix_crb(m, x, w, R, M);
    const VecX ev = Eigen::SelfAdjointEigenSolver<MatX>(M, Eigen::EigenvaluesOnly).eigenvalues();
    cond = ev.maxCoeff() / ev.minCoeff();
  }
};

// Per-body vectors stacked tip first: 6 per body (soa::test::stack), or n_k per body.
template <class V>
VecX stack_dofs(const std::vector<V>& v) {
  Eigen::Index size = 0;
  for (const auto& x : v) size += x.size();
  VecX s(size);
  Eigen::Index at = 0;
  for (const auto& x : v) s.segment(at, x.size()) = x, at += x.size();
  return s;
}
// The largest 6-block of a stacked 6n-vector.
double max_block(const VecX& s) {
  double w = 0;
  for (Eigen::Index i = 0; i + 6 <= s.size(); i += 6) w = std::max(w, s.segment<6>(i).norm());
  return w;
}

// The scale for a Check of a hinge quantity whose criterion is entry by entry,
// |got_k - expected_k| <= tol kappa max(1, |expected_k|): with it, |got - expected| / scale is
// the worst entry's error relative to kappa max(1, |expected_k|).
double entrywise_scale(const VecX& got, const VecX& expected, double kappa) {
  const double fallback = kappa * std::max(1.0, expected.lpNorm<Eigen::Infinity>());
  if (got.size() != expected.size() || !got.allFinite()) return fallback;
  double worst = 0;
  for (Eigen::Index k = 0; k < got.size(); ++k)
    worst = std::max(worst, std::abs(got[k] - expected[k]) / std::max(1.0, std::abs(expected[k])));
  return worst > 0 ? (got - expected).norm() / worst : fallback;
}

// The variants of a sweep in the catalogue: what the variant is, the kind of mistake and what
// the checker says when the student's result equals it.
template <class E>
struct Variant {
  E v;
  const char* kind;
  const char* says;
};

// A forward dynamics case (8.3, 8.6): the student's beta_dot \p bd from soa::ex08::\p fn
// against the case's, to rounding scaled by nv cond(M) |beta_dot|, with the catalogue
// \p variants computed by \p wrong(c, variant).
template <class E, std::size_t K, class Wrong>
void add_forward_dynamics(Check& check, int i, const Case& c, const VecX& bd, const char* fn,
                          const Variant<E> (&variants)[K], Wrong wrong) {
  const soa::Model& m = c.m();
  const MassAndBias mb(m, c.c.x, c.c.f_ext);
  check.add(
      i, bd, c.beta_dot, m.nv() * mb.cond * std::max(1.0, c.beta_dot.norm()), c.c.tags,
      [&] { return c.code() + "soa::VecX<double> bd = soa::ex08::" + fn + "(m, x, T, f_ext);\n"; },
      [&] {
        Mistakes out;
        for (const auto& v : variants) out.push_back({v.kind, v.says, wrong(c, v.v)});
        return out;
      },
      soa::test::per_dof(m, "beta_dot"));
}

// --- 8.1 ----------------------------------------------------------------------------------------

// Sweep 2 of a revolute chain (exercise 8.1) with a classic mistake in it (or none), from the
// library's phi, V, a (c.ws) and P, D, G (c.fd.art).
enum class Tip {
  Right,
  NeighbourPhi,
  TransposedPhi,
  NoPa,
  BodyInertia,
  NoB,
  ZNotPlus,
  EpsSign,
  NuTimesD
};
struct TipSweep {
  VecX z, z_plus, eps, nu;
};
TipSweep tip_sweep(const Case& c, Tip v) {
  const soa::Model& m = c.m();
  const int n = m.n();
  TipSweep r{VecX::Zero(6 * n), VecX::Zero(6 * n), VecX::Zero(n), VecX::Zero(n)};
  for (int k = 1; k <= n; ++k) {
    const std::size_t j = std::size_t(k - 1);
    const soa::Body& B = m.body(k);
    Vec6 s = Vec6::Zero();
    s.head<3>() = B.hinge.axis;
    Vec6 z = Vec6::Zero();
    if (v != Tip::NoB) z += soa::gyroscopic_force(B.M, c.ws.V[j]).vector();
    if (v != Tip::NoPa)
      z += (v == Tip::BodyInertia ? B.M.matrix() : c.fd.art.P[j]) * c.ws.a[j].vector();
    if (k > 1) {
      const Vec6 child = (v == Tip::ZNotPlus ? r.z : r.z_plus).segment<6>(6 * (k - 2));
      const Mat6 phi = v == Tip::NeighbourPhi    ? c.ws.phi[j].matrix()
                       : v == Tip::TransposedPhi ? Mat6(c.ws.phi[j - 1].matrix().transpose())
                                                 : c.ws.phi[j - 1].matrix();
      z += phi * child;
    }
    double eps = c.T[B.v_offset] - s.dot(z);
    if (v == Tip::EpsSign) eps = -eps;
    const double D = c.fd.art.D[j](0, 0);
    r.z.segment<6>(6 * (k - 1)) = z;
    r.eps[k - 1] = eps;
    r.nu[k - 1] = v == Tip::NuTimesD ? eps * D : eps / D;
    r.z_plus.segment<6>(6 * (k - 1)) = z + c.fd.art.G[j].col(0) * eps;
  }
  return r;
}

// clang-format off
/* planted mistakes of 8.1
soa_plant(8.1 neighbour-index
  FIND [=[ws.phi[j - 1].apply(Force(r.z_plus[j - 1]))]=]
  WRONG [=[ws.phi[j].apply(Force(r.z_plus[j - 1]))]=]
  EXPECT [=[likely mistake \(neighbour index\): your z\(k\) takes phi\(k\+1,k\) z\+\(k-1\)]=])
soa_plant(8.1 coriolis-doubled
  FIND [=[art.P[j] * ws.a[j].vector() + gyroscopic_force(B.M, ws.V[j]).vector()]=]
  WRONG [=[2.0 * art.P[j] * ws.a[j].vector() + gyroscopic_force(B.M, ws.V[j]).vector()]=]
  TYPE [=[Vec6]=]
  EXPECT [=[symptom: it fails only where it moves \(the velocities are not zero\): [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
*/
// clang-format on
// 8.1: z, z+, epsilon, nu of a revolute chain (no gravity, external forces or springs) against
// soa::forward_dynamics's, to rounding scaled by |P(k)| |D^{-1}(k)|.
TEST(Exercise8_1_TipToBase, MatchesLibrary) {
  Random<double> rnd;
  const double tol = 64 * 8 * kEps;
  // The checks report in the order they are declared, the sweep's: the table shows the first.
  Check z_check("z(k), the bias force of articulated body k", tol),
      zp_check("z+(k), the bias force carried across hinge k", tol),
      eps_check("epsilon(k) = T(k) - H(k) z(k), the innovations", tol),
      nu_check("nu(k) = epsilon(k) / D(k)", tol);
  Opts o;
  o.types = {HingeType::Revolute};
  o.gravity = false;
  static const Variant<Tip> variants[] = {
      {Tip::NeighbourPhi, "neighbour index",
       "your z(k) takes phi(k+1,k) z+(k-1), ws.phi[k-1]: body k-1's z+ moves inward with "
       "phi(k,k-1) = ws.phi[k-2]"},
      {Tip::TransposedPhi, "transpose",
       "your z(k) takes phi*(k,k-1) z+(k-1): forces move inward with phi, not phi* "
       "(ws.phi[k-2].apply(...))"},
      {Tip::NoPa, "dropped term", "P(k) a(k) is missing from your z(k): the Coriolis term"},
      {Tip::BodyInertia, "wrong inertia",
       "your z(k) has M(k) a(k): the Coriolis term acts on the articulated body, P(k) a(k)"},
      {Tip::NoB, "dropped term", "b(k), the gyroscopic force, is missing from your z(k)"},
      {Tip::ZNotPlus, "dropped term",
       "your z(k) carries z(k-1) inward, not z+(k-1) = z(k-1) + G(k-1) epsilon(k-1)"},
      {Tip::EpsSign, "sign", "your epsilon(k) is H(k) z(k) - T(k): it is T(k) - H(k) z(k)"},
      {Tip::NuTimesD, "inverse", "your nu(k) is epsilon(k) D(k): it is epsilon(k) / D(k)"},
  };
  for (int i = 0; i < kCases; ++i) {
    const Case c(draw(rnd, i, o), rnd);
    const soa::Model& m = c.m();
    const soa::ex08::TipToBase r = soa::ex08::tip_to_base(m, c.c.x, c.T);
    const VecX z = stack(c.fd.z), z_plus = stack(c.fd.z_plus), nu = stack_dofs(c.fd.nu);
    VecX eps(m.n());
    for (int k = 1; k <= m.n(); ++k) eps[k - 1] = c.fd.art.D[std::size_t(k - 1)](0, 0) * nu[k - 1];
    const double kappa = c.kappa();
    auto inputs = [&] {
      return c.code() + "soa::ex08::TipToBase r = soa::ex08::tip_to_base(m, x, T);\n";
    };
    auto mistakes = [&](VecX TipSweep::*part) {
      return [&c, part] {
        Mistakes out;
        for (const auto& v : variants) out.push_back({v.kind, v.says, tip_sweep(c, v.v).*part});
        return out;
      };
    };
    z_check.add(i, stack(r.z), z, kappa * std::max(1.0, max_block(z)), c.c.tags, inputs,
                mistakes(&TipSweep::z), soa::test::per_body_spatial("z"));
    zp_check.add(i, stack(r.z_plus), z_plus, kappa * std::max(1.0, max_block(z_plus)), c.c.tags,
                 inputs, mistakes(&TipSweep::z_plus), soa::test::per_body_spatial("z+"));
    eps_check.add(i, r.eps, eps, entrywise_scale(r.eps, eps, kappa), c.c.tags, inputs,
                  mistakes(&TipSweep::eps), soa::test::per_dof(m, "epsilon"));
    nu_check.add(i, r.nu, nu, entrywise_scale(r.nu, nu, kappa), c.c.tags, inputs,
                 mistakes(&TipSweep::nu), soa::test::per_dof(m, "nu"));
  }
}

// --- 8.2 ----------------------------------------------------------------------------------------

// Sweep 3 (exercise 8.2) with a classic mistake in it (or none), from the library's phi, a
// (c.ws), G and nu (c.fd).
enum class Base { Right, PhiNotStar, ZeroStart, NoA, PlusG, Unmoved, HNu };
struct BaseSweep {
  VecX beta_dot, alpha;
};
BaseSweep base_sweep(const Case& c, Base v) {
  const soa::Model& m = c.m();
  BaseSweep r{VecX::Zero(m.nv()), VecX::Zero(6 * m.n())};
  Vec6 next = v == Base::ZeroStart ? Vec6::Zero() : soa::gravity_base_acceleration(m).vector();
  for (int k = m.n(); k >= 1; --k) {
    const std::size_t j = std::size_t(k - 1);
    const soa::Body& B = m.body(k);
    const Mat6 phi = c.ws.phi[j].matrix();
    const Vec6 ap = v == Base::PhiNotStar ? Vec6(phi * next) : Vec6(phi.transpose() * next);
    const VecX nu = c.fd.nu[j];
    const VecX bd = v == Base::PlusG     ? VecX(nu + c.fd.art.G[j].transpose() * ap)
                    : v == Base::Unmoved ? VecX(nu - c.fd.art.G[j].transpose() * next)
                                         : VecX(nu - c.fd.art.G[j].transpose() * ap);
    r.beta_dot.segment(B.v_offset, B.hinge.nv()) = bd;
    const MatX Hs = B.hinge.H_star(c.c.x.theta.data() + B.q_offset);
    next = ap + Hs * (v == Base::HNu ? nu : bd);
    if (v != Base::NoA) next += c.ws.a[j].vector();
    r.alpha.segment<6>(6 * (k - 1)) = next;
  }
  return r;
}

// clang-format off
/* planted mistakes of 8.2
soa_plant(8.2 transpose
  FIND [=[ws.phi[j].transpose_apply(next)]=]
  WRONG [=[Acceleration(ws.phi[j].matrix() * next.vector())]=]
  EXPECT [=[likely mistake \(transpose\): your alpha\+\(k\) is phi\(k\+1,k\) alpha\(k\+1\)]=])
soa_plant(8.2 wrong-frame
  FIND [=[G.transpose() * alpha_plus.vector()]=]
  WRONG [=[G.transpose() * next.vector()]=] TYPE [=[VecX<double>]=]
  EXPECT [=[likely mistake \(wrong frame\): your beta_dot\(k\) takes G\*\(k\) alpha\(k\+1\)]=])
*/
// clang-format on
// 8.2: beta_dot and alpha from the library's phi, a, G, nu and the base acceleration, against
// soa::forward_dynamics's, to rounding scaled by |P(k)| |D^{-1}(k)|.
TEST(Exercise8_2_BaseToTip, MatchesLibrary) {
  Random<double> rnd;
  const double tol = 64 * 8 * kEps;
  Check alpha_check("alpha(k), the spatial accelerations", tol),
      bd_check("beta_dot, the hinge accelerations", tol);  // reported first
  Opts o;
  o.external = true;
  static const Variant<Base> variants[] = {
      {Base::PhiNotStar, "transpose",
       "your alpha+(k) is phi(k+1,k) alpha(k+1): accelerations move outward with phi*, "
       "ws.phi[k-1].transpose_apply(...)"},
      {Base::ZeroStart, "dropped term",
       "your sweep starts from alpha(n+1) = 0: it starts from alpha_base ([0; -g] for gravity)"},
      {Base::NoA, "dropped term", "a(k), the Coriolis term, is missing from your alpha(k)"},
      {Base::PlusG, "sign",
       "your beta_dot(k) is nu(k) + G*(k) alpha+(k): it is nu(k) - G*(k) alpha+(k)"},
      {Base::Unmoved, "wrong frame",
       "your beta_dot(k) takes G*(k) alpha(k+1), in O_{k+1} coordinates: move it to O_k first, "
       "alpha+(k) = phi*(k+1,k) alpha(k+1)"},
      {Base::HNu, "wrong term",
       "your alpha(k) adds H*(k) nu(k): the hinge's acceleration is beta_dot(k) = nu(k) - "
       "G*(k) alpha+(k)"},
  };
  for (int i = 0; i < kCases; ++i) {
    const Case c(draw(rnd, i, o), rnd);
    const soa::Model& m = c.m();
    soa::Workspace ws = c.ws;  // phi, V, a of the library's forward dynamics; no alpha
    for (auto& a : ws.alpha) a = soa::Acceleration();
    const std::vector<VecX> nu(c.fd.nu.begin(), c.fd.nu.end());
    std::vector<soa::Acceleration> alpha;
    const VecX bd = soa::ex08::base_to_tip(m, c.c.x, ws, c.fd.art, nu,
                                           soa::gravity_base_acceleration(m), alpha);
    const VecX alpha_ref = stack(c.ws.alpha);
    const double kappa = c.kappa();
    auto inputs = [&] {
      return c.code() +
             "soa::Workspace ws(m);\nsoa::ForwardDynamics fd(m);\n"
             "soa::VecX<double> bd_lib(m.nv());\n"
             "soa::forward_dynamics(m, x, T, f_ext, ws, fd, bd_lib);  // phi, a, G, nu\n"
             "std::vector<soa::VecX<double>> nu(fd.nu.begin(), fd.nu.end());\n"
             "std::vector<soa::Acceleration> alpha;\n"
             "soa::VecX<double> bd = soa::ex08::base_to_tip(m, x, ws, fd.art, nu,\n"
             "    soa::gravity_base_acceleration(m), alpha);\n";
    };
    auto mistakes = [&](VecX BaseSweep::*part) {
      return [&c, part] {
        Mistakes out;
        for (const auto& v : variants) out.push_back({v.kind, v.says, base_sweep(c, v.v).*part});
        return out;
      };
    };
    bd_check.add(i, bd, c.beta_dot, kappa * std::max(1.0, c.beta_dot.norm()), c.c.tags, inputs,
                 mistakes(&BaseSweep::beta_dot), soa::test::per_dof(m, "beta_dot"));
    alpha_check.add(i, stack(alpha), alpha_ref, kappa * std::max(1.0, max_block(alpha_ref)),
                    c.c.tags, inputs, mistakes(&BaseSweep::alpha),
                    soa::test::per_body_spatial("alpha"));
  }
}

// --- 8.3 ----------------------------------------------------------------------------------------

// The forward dynamics of a chain of one-dof hinges (exercise 8.3), written out with a classic
// mistake in it (or none), from the library's phi, V, a (c.ws).
enum class FD1 {
  Right,
  TransposedRiccati,
  NoProjection,
  GravitySign,
  ExternalSign,
  NoGyroscopic,
  NoPa,
  NoPitch,
  PrismaticRotates
};
VecX fd_1dof(const Case& c, FD1 v) {
  const soa::Model& m = c.m();
  const int n = m.n();
  const std::size_t N = std::size_t(n);
  std::vector<Mat6> P_plus(N);
  std::vector<Vec6> g(N), z_plus(N), s(N);
  std::vector<double> nu(N);
  for (int k = 1; k <= n; ++k) {
    const std::size_t j = std::size_t(k - 1);
    const soa::Body& B = m.body(k);
    Mat6 P = B.M.matrix();
    Vec6 z = Vec6::Zero();
    if (v != FD1::NoGyroscopic) z += soa::gyroscopic_force(B.M, c.ws.V[j]).vector();
    if (!c.c.f_ext.empty()) z += (v == FD1::ExternalSign ? 1.0 : -1.0) * c.c.f_ext[j].vector();
    if (k > 1) {
      const Mat6 phi = c.ws.phi[j - 1].matrix();  // phi(k,k-1)
      const Mat6& Pp = P_plus[j - 1];
      P += v == FD1::TransposedRiccati ? Mat6(phi.transpose() * Pp * phi)
                                       : Mat6(phi * Pp * phi.transpose());
      z += phi * z_plus[j - 1];
    }
    if (v != FD1::NoPa) z += P * c.ws.a[j].vector();
    s[j] = soa::one_dof_map(B.hinge);
    if (v == FD1::NoPitch && B.hinge.type == HingeType::Helical) s[j].tail<3>().setZero();
    if (v == FD1::PrismaticRotates && B.hinge.type == HingeType::Prismatic)
      s[j] << B.hinge.axis, 0, 0, 0;
    const Vec6 Ps = P * s[j];
    const double D = s[j].dot(Ps);
    g[j] = Ps / D;
    P_plus[j] = v == FD1::NoProjection ? P : Mat6(P - g[j] * Ps.transpose());
    const double eps = c.T[B.v_offset] - s[j].dot(z);
    nu[j] = eps / D;
    z_plus[j] = z + g[j] * eps;
  }
  VecX bd(m.nv());
  Vec6 next = soa::gravity_base_acceleration(m).vector();
  if (v == FD1::GravitySign) next = -next;
  for (int k = n; k >= 1; --k) {
    const std::size_t j = std::size_t(k - 1);
    const Vec6 ap = c.ws.phi[j].matrix().transpose() * next;
    bd[m.body(k).v_offset] = nu[j] - g[j].dot(ap);
    next = ap + s[j] * bd[m.body(k).v_offset] + c.ws.a[j].vector();
  }
  return bd;
}

// clang-format off
/* planted mistakes of 8.3
soa_plant(8.3 transpose
  FIND [=[phi * P_plus[j - 1] * phi.transpose()]=]
  WRONG [=[phi.transpose() * P_plus[j - 1] * phi]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(transpose\): your P\(k\) takes phi\*\(k,k-1\) P\+\(k-1\)]=])
soa_plant(8.3 external-sign
  FIND [=[f_ext[j].vector()]=]
  WRONG [=[-f_ext[j].vector()]=] TYPE [=[Vec6]=]
  EXPECT [=[likely mistake \(sign\): your b\(k\) adds f_ext\(k\)]=])
soa_plant(8.3 no-projection
  FIND [=[P - g[j] * Ps.transpose()]=]
  WRONG [=[P]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(dropped term\): your P\(k\) takes phi P\(k-1\) phi\*]=])
soa_plant(8.3 pitch-doubled
  FIND [=[h.pitch * h.axis]=]
  WRONG [=[2 * h.pitch * h.axis]=] TYPE [=[Vec3<double>]=]
  EXPECT [=[symptom: it fails only where a hinge is helical: [0-9]+ of those [0-9]+ [a-z]+s fail, and every other [a-z]+ passes]=])
*/
// clang-format on
// 8.3: the whole algorithm for revolute, prismatic and helical hinges with gravity and
// external forces, against soa::forward_dynamics, to n eps cond(M).
TEST(Exercise8_3_ForwardDynamics1Dof, MatchesLibrary) {
  Random<double> rnd;
  Check check("beta_dot, the hinge accelerations", 16 * kEps);
  Opts o;
  o.types = {HingeType::Revolute, HingeType::Prismatic, HingeType::Helical};
  o.external = true;
  static const Variant<FD1> variants[] = {
      {FD1::TransposedRiccati, "transpose",
       "your P(k) takes phi*(k,k-1) P+(k-1) phi(k,k-1): inertias move inward as phi P+ phi*"},
      {FD1::NoProjection, "dropped term",
       "your P(k) takes phi P(k-1) phi*: what crosses hinge k-1 is P+(k-1) = P(k-1) - G D G*"},
      {FD1::GravitySign, "sign",
       "your base acceleration is alpha(n+1) = [0; +g]: gravity enters as [0; -g]"},
      {FD1::ExternalSign, "sign",
       "your b(k) adds f_ext(k): an external force enters as b(k) = b_gyro(k) - f_ext(k)"},
      {FD1::NoGyroscopic, "dropped term",
       "the gyroscopic term b_gyro(k) is missing (soa::gyroscopic_force)"},
      {FD1::NoPa, "dropped term", "P(k) a(k), the Coriolis term, is missing from your z(k)"},
      {FD1::NoPitch, "dropped term",
       "your helical H*(k) is [a; 0]: the screw also slides, H*(k) = [a; h a]"},
      {FD1::PrismaticRotates, "wrong part",
       "your prismatic H*(k) is [a; 0], a rotation: a prismatic hinge slides, H*(k) = [0; a]"},
  };
  for (int i = 0; i < kCases; ++i) {
    const Case c(draw(rnd, i, o), rnd);
    const soa::Model& m = c.m();
    add_forward_dynamics(check, i, c, soa::ex08::forward_dynamics_1dof(m, c.c.x, c.T, c.c.f_ext),
                         "forward_dynamics_1dof", variants, fd_1dof);
  }
}

// --- 8.4 ----------------------------------------------------------------------------------------

// clang-format off
/* planted mistakes of 8.4
soa_plant(8.4 wrong-inertia
  FIND [=[fd.art.P_plus[j]]=]
  WRONG [=[fd.art.P[j]]=] TYPE [=[Mat6<double>]=]
  EXPECT [=[likely mistake \(wrong inertia\): your f\(k\) is P\(k\) alpha\+\(k\) \+ z\+\(k\)]=])
*/
// clang-format on
// 8.4: f(k) = P+(k) alpha+(k) + z+(k) and H(k) f(k) against Newton-Euler inverse dynamics at
// the library's beta_dot (f(k), and T + tau_s), to n eps cond(M).
TEST(Exercise8_4_InterBodyForces, MatchNewtonEuler) {
  Random<double> rnd;
  Check T_check("H(k) f(k), the hinge forces T + tau_s", 16 * kEps),
      f_check("f(k), the force across hinge k", 16 * kEps);  // reported first
  Opts o;
  o.external = true;
  o.springs = true;
  for (int i = 0; i < kCases; ++i) {
    const Case c(draw(rnd, i, o), rnd);
    const soa::Model& m = c.m();
    VecX T_hinge;
    const std::vector<soa::Force> f = soa::ex08::inter_body_forces(m, c.c.x, c.fd, T_hinge);
    soa::Workspace ne(m);
    VecX T_ne(m.nv());
    soa::inverse_dynamics(m, c.c.x, c.beta_dot, c.c.f_ext, ne, T_ne);
    VecX T_s = c.T;  // T + tau_s
    for (const soa::Body& B : m.bodies())
      soa::add_spring_force(B, c.c.x.theta.data() + B.q_offset, c.c.x.beta.data() + B.v_offset,
                            T_s.data() + B.v_offset);
    double scale = 1;
    std::vector<Vec6> wrong_P, no_G, no_z, minus_z;
    for (int k = 1; k <= m.n(); ++k) {
      const std::size_t j = std::size_t(k - 1);
      const Vec6 Pa = c.fd.art.P_plus[j] * c.fd.alpha_plus[j].vector();
      scale = std::max({scale, ne.f[j].vector().norm(), c.fd.z_plus[j].vector().norm(),
                        c.fd.art.P_plus[j].norm() * c.fd.alpha_plus[j].vector().norm()});
      wrong_P.push_back(c.fd.art.P[j] * c.fd.alpha_plus[j].vector() + c.fd.z_plus[j].vector());
      no_G.push_back(Pa + c.fd.z[j].vector());
      no_z.push_back(Pa);
      minus_z.push_back(Pa - c.fd.z_plus[j].vector());
    }
    const double unit = m.nv() * MassAndBias(m, c.c.x, c.c.f_ext).cond * scale;
    // H(k) f(k) of stacked forces.
    auto H = [&](const std::vector<Vec6>& fs) {
      VecX t(m.nv());
      for (int k = 1; k <= m.n(); ++k) {
        const soa::Body& B = m.body(k);
        B.hinge.H_times(c.c.x.theta.data() + B.q_offset, soa::Force(fs[std::size_t(k - 1)]),
                        t.data() + B.v_offset);
      }
      return t;
    };
    struct Wrong {
      const char* kind;
      const char* says;
      const std::vector<Vec6>* f;
    };
    const Wrong wrong[] = {
        {"wrong inertia",
         "your f(k) is P(k) alpha+(k) + z+(k): across the hinge the inertia is P+(k) = P(k) - G D "
         "G*",
         &wrong_P},
        {"dropped term",
         "your f(k) is P+(k) alpha+(k) + z(k): the bias across the hinge is z+(k) = z(k) + G(k) "
         "epsilon(k)",
         &no_G},
        {"dropped term", "z+(k) is missing from your f(k)", &no_z},
        {"sign", "your f(k) subtracts z+(k): f(k) = P+(k) alpha+(k) + z+(k)", &minus_z},
    };
    auto inputs = [&] {
      return c.code() +
             "soa::Workspace ws(m);\nsoa::ForwardDynamics fd(m);\nsoa::VecX<double> bd(m.nv());\n"
             "soa::forward_dynamics(m, x, T, f_ext, ws, fd, bd);\nsoa::VecX<double> T_hinge;\n"
             "auto f = soa::ex08::inter_body_forces(m, x, fd, T_hinge);\n";
    };
    f_check.add(
        i, stack(f), stack(ne.f), unit, c.c.tags, inputs,
        [&] {
          Mistakes out;
          for (const Wrong& w : wrong) out.push_back({w.kind, w.says, stack(*w.f)});
          return out;
        },
        soa::test::per_body_spatial("f"));
    T_check.add(
        i, T_hinge, T_s, unit, c.c.tags, inputs,
        [&] {
          Mistakes out;
          for (const Wrong& w : wrong) out.push_back({w.kind, w.says, H(*w.f)});
          out.push_back({"dropped term",
                         "your H(k) f(k) leaves out the springs' force: it equals T, the given "
                         "hinge forces, where f(k) holds T + tau_s",
                         c.T});
          return out;
        },
        soa::test::per_dof(m, "H f"));
  }
}

// --- 8.5 ----------------------------------------------------------------------------------------

// One step of RK4 with soa::forward_dynamics (exercise 8.5), with a classic mistake in it (or
// none): theta and beta after the step, stacked.
enum class RK { Right, Euler, EqualWeights, FullStages, ThetaByBeta, StagesAtTheta };
VecX rk4(const Case& c, double h, RK v) {
  const soa::Model& m = c.m();
  soa::Workspace ws(m);
  soa::ForwardDynamics fd(m);
  const auto F = [&](const VecX& theta, const VecX& beta) {
    VecX bd(m.nv());
    soa::forward_dynamics(m, soa::State{theta, beta}, c.T, {}, ws, fd, bd);
    return bd;
  };
  const soa::State& x = c.c.x;
  const double hs = v == RK::FullStages ? h : h / 2;
  const auto at = [&](const VecX& dq) {
    return v == RK::StagesAtTheta ? x.theta : VecX(x.theta + dq);
  };
  const VecX k1q = x.beta, k1v = F(x.theta, x.beta);
  VecX out(2 * m.nv());
  if (v == RK::Euler) {
    out << x.theta + h * k1q, x.beta + h * k1v;
    return out;
  }
  const VecX k2q = x.beta + hs * k1v, k2v = F(at(hs * k1q), k2q);
  const VecX k3q = x.beta + hs * k2v, k3v = F(at(hs * k2q), k3q);
  const VecX k4q = x.beta + h * k3v, k4v = F(at(h * k3q), k4q);
  if (v == RK::EqualWeights) {
    out << x.theta + h / 4 * (k1q + k2q + k3q + k4q), x.beta + h / 4 * (k1v + k2v + k3v + k4v);
    return out;
  }
  const VecX dq = v == RK::ThetaByBeta ? VecX(6 * x.beta) : VecX(k1q + 2 * k2q + 2 * k3q + k4q);
  out << x.theta + h / 6 * dq, x.beta + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
  return out;
}

// clang-format off
/* planted mistakes of 8.5
soa_plant(8.5 equal-weights
  FIND [=[h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v)]=]
  WRONG [=[h / 4 * (k1v + k2v + k3v + k4v)]=] TYPE [=[VecX<double>]=]
  EXPECT [=[likely mistake \(wrong weights\)]=])
*/
// clang-format on
// 8.5: one RK4 step on chains of hinges with theta_dot = beta (gravity and springs in some),
// against RK4 built on soa::forward_dynamics, to n eps cond(M) of the step's size.
TEST(Exercise8_5_Rk4Step, MatchesReferenceRK4) {
  Random<double> rnd;
  const double h = 0.01;
  Check beta_check("beta after the step", 8 * kEps),
      theta_check("theta after the step", 8 * kEps);  // reported first
  Opts o;
  o.types = {HingeType::Revolute, HingeType::Prismatic, HingeType::Helical, HingeType::Universal};
  o.springs = true;
  static const Variant<RK> variants[] = {
      {RK::Euler, "wrong method",
       "your step is Euler's, y + h F(y): RK4 takes four stages, weighted 1, 2, 2, 1 over 6"},
      {RK::EqualWeights, "wrong weights",
       "your stages are weighted 1/4 each: RK4 weights them h/6 (k1 + 2 k2 + 2 k3 + k4)"},
      {RK::FullStages, "wrong step",
       "your k2 and k3 are taken a full step h ahead: they are at y + h/2 k1 and y + h/2 k2"},
      {RK::ThetaByBeta, "dropped term",
       "your theta moves by h beta: its stages are the stages' beta, k_i = beta + ... (theta_dot "
       "= beta at each stage)"},
      {RK::StagesAtTheta, "dropped term",
       "your stages evaluate FD at the old theta: k2 is F(theta + h/2 k1_theta, beta + h/2 "
       "k1_beta), theta moves too"},
  };
  for (int i = 0; i < kCases; ++i) {
    const Case c(draw(rnd, i, o), rnd);
    const soa::Model& m = c.m();
    const soa::State& x = c.c.x;
    const VecX ref = rk4(c, h, RK::Right);
    const soa::State y = soa::ex08::rk4_step(m, x, c.T, h);
    const MassAndBias mb(m, x, {});
    const VecX k1v = c.beta_dot;  // FD at x, no external forces: the case has none
    const double scale =
        (x.theta.norm() + x.beta.norm() + h * (x.beta.norm() + k1v.norm())) * m.nv() * mb.cond;
    auto inputs = [&] { return c.code() + "soa::State y = soa::ex08::rk4_step(m, x, T, 0.01);\n"; };
    auto mistakes = [&](bool theta) {
      return [&c, h, theta] {
        const Eigen::Index nv = c.m().nv();
        Mistakes out;
        for (const auto& v : variants) {
          const VecX w = rk4(c, h, v.v);
          out.push_back({v.kind, v.says, theta ? VecX(w.head(nv)) : VecX(w.tail(nv))});
        }
        return out;
      };
    };
    const Eigen::Index nv = m.nv();
    theta_check.add(i, y.theta, ref.head(nv), scale, c.c.tags, inputs, mistakes(true),
                    soa::test::per_dof(m, "theta"));
    beta_check.add(i, y.beta, ref.tail(nv), scale, c.c.tags, inputs, mistakes(false),
                   soa::test::per_dof(m, "beta"));
  }
}

// --- 8.6 ----------------------------------------------------------------------------------------

// The forward dynamics of exercise 8.6 (any hinges, gravity, external forces, springs) from
// the library's phi, V, a (c.ws) and P, D, G (c.fd.art), with the given code's bug and other
// changes a student may make while hunting for it.
enum Aba : unsigned { kGivenBug = 1, kPlusG = 2, kNeighbourPhi = 4, kNoA = 8, kPhiNotStar = 16 };
VecX aba(const Case& c, unsigned v) {
  const soa::Model& m = c.m();
  const int n = m.n();
  std::vector<Vec6> z_plus(static_cast<std::size_t>(n));
  std::vector<VecX> nu(static_cast<std::size_t>(n));
  for (int k = 1; k <= n; ++k) {
    const std::size_t j = std::size_t(k - 1);
    const soa::Body& B = m.body(k);
    const double* th = c.c.x.theta.data() + B.q_offset;
    Vec6 z = c.fd.art.P[j] * c.ws.a[j].vector() + soa::gyroscopic_force(B.M, c.ws.V[j]).vector();
    if (!c.c.f_ext.empty()) z -= c.c.f_ext[j].vector();
    if (k > 1) z += c.ws.phi[v & kNeighbourPhi ? j : j - 1].matrix() * z_plus[j - 1];
    VecX eps = c.T.segment(B.v_offset, B.hinge.nv());
    soa::add_spring_force(B, th, c.c.x.beta.data() + B.v_offset, eps.data());
    eps -= B.hinge.H_star(th).transpose() * z;
    nu[j] = MatX(c.fd.art.D_inv[j]) * eps;
    z_plus[j] = z + c.fd.art.G[j] * eps;
  }
  VecX bd(m.nv());
  Vec6 next = soa::gravity_base_acceleration(m).vector();
  for (int k = n; k >= 1; --k) {
    const std::size_t j = std::size_t(k - 1);
    const soa::Body& B = m.body(k);
    const Mat6 phi = c.ws.phi[j].matrix();
    const Vec6 ap = v & kPhiNotStar ? Vec6(phi * next) : Vec6(phi.transpose() * next);
    const VecX bk = nu[j] + (v & kPlusG ? 1.0 : -1.0) * (c.fd.art.G[j].transpose() * ap);
    bd.segment(B.v_offset, B.hinge.nv()) = bk;
    next = ap + B.hinge.H_star(c.c.x.theta.data() + B.q_offset) * (v & kGivenBug ? nu[j] : bk);
    if (!(v & kNoA)) next += c.ws.a[j].vector();
  }
  return bd;
}

// clang-format off
/* planted mistakes of 8.6
soa_plant(8.6 bug-kept
  FIND [=[Hs * bd]=]
  WRONG [=[Hs * nu[j]]=] TYPE [=[Vec6]=]
  EXPECT [=[the checker knows this mistake: it names it after 3 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|your beta_dot is the given code's]=]
  NAMED [=[likely mistake \(bug still there\): your beta_dot is the given code's]=])
*/
// clang-format on
// 8.6: the given code with its bug fixed, against soa::forward_dynamics, to n eps cond(M).
TEST(Exercise8_6_FindTheBug, MatchesLibrary) {
  Random<double> rnd;
  Check check("beta_dot, the hinge accelerations", 16 * kEps);
  Opts o;
  o.external = true;
  o.springs = true;
  static const Variant<unsigned> variants[] = {
      {kGivenBug, "bug still there",
       "your beta_dot is the given code's: the bug is still in it. Cases with one body pass: "
       "what does body k hand on to body k-1 in the base-to-tip sweep?"},
      {kGivenBug | kPlusG, "bug still there",
       "you changed the sign of G*(k) alpha+(k) (it was right: beta_dot(k) = nu(k) - G*(k) "
       "alpha+(k)), and the bug is still there"},
      {kGivenBug | kNeighbourPhi, "bug still there",
       "you changed phi(k,k-1) = ws.phi[k-2] into ws.phi[k-1] (it was right), and the bug is "
       "still there"},
      {kGivenBug | kPhiNotStar, "bug still there",
       "you changed alpha+(k) to phi alpha(k+1) (phi* was right), and the bug is still there"},
      {kPlusG, "sign",
       "your beta_dot(k) is nu(k) + G*(k) alpha+(k): the bug is fixed but the sign you changed "
       "was right, beta_dot(k) = nu(k) - G*(k) alpha+(k)"},
      {kNoA, "dropped term", "a(k) is missing from your alpha(k): the bug is fixed, put a(k) back"},
  };
  for (int i = 0; i < kCases; ++i) {
    const Case c(draw(rnd, i, o), rnd);
    const soa::Model& m = c.m();
    add_forward_dynamics(check, i, c, soa::ex08::forward_dynamics_fixed(m, c.c.x, c.T, c.c.f_ext),
                         "forward_dynamics_fixed", variants, aba);
  }
}

// --- 8.7 ----------------------------------------------------------------------------------------

// Hybrid dynamics (exercise 8.7) by the sweeps, with a classic mistake in it (or none): beta_dot
// and T stacked, from the library's phi, V, a (c.ws).
enum class Hyb { Right, Projected, NoPHbd, MinusPHbd, BiasOnlyT, Ignored };
VecX hybrid(const Case& c, const std::vector<bool>& pres, const VecX& T, const VecX& bd_in, Hyb v) {
  const soa::Model& m = c.m();
  const int n = m.n();
  const std::size_t N = std::size_t(n);
  std::vector<Mat6> P_plus(N);
  std::vector<Vec6> z_plus(N);
  std::vector<MatX> G(N);
  std::vector<VecX> nu(N);
  VecX bd = bd_in, Tout = T;
  const auto prescribed = [&](std::size_t j) { return v != Hyb::Ignored && pres[j]; };
  for (int k = 1; k <= n; ++k) {
    const std::size_t j = std::size_t(k - 1);
    const soa::Body& B = m.body(k);
    const int nk = B.hinge.nv();
    const MatX Hs = B.hinge.H_star(c.c.x.theta.data() + B.q_offset);
    Mat6 P = B.M.matrix();
    Vec6 z = soa::gyroscopic_force(B.M, c.ws.V[j]).vector();
    if (k > 1) {
      const Mat6 phi = c.ws.phi[j - 1].matrix();
      P += phi * P_plus[j - 1] * phi.transpose();
      z += phi * z_plus[j - 1];
    }
    z += P * c.ws.a[j].vector();
    const MatX PH = P * Hs, D = Hs.transpose() * PH;
    G[j] = PH * D.inverse();
    if (prescribed(j)) {
      const Vec6 PHb = PH * bd_in.segment(B.v_offset, nk);
      P_plus[j] = v == Hyb::Projected ? Mat6(P - G[j] * PH.transpose()) : P;
      z_plus[j] = v == Hyb::NoPHbd ? z : v == Hyb::MinusPHbd ? Vec6(z - PHb) : Vec6(z + PHb);
    } else {
      const VecX eps = T.segment(B.v_offset, nk) - Hs.transpose() * z;
      nu[j] = D.inverse() * eps;
      P_plus[j] = P - G[j] * PH.transpose();
      z_plus[j] = z + G[j] * eps;
    }
  }
  Vec6 next = soa::gravity_base_acceleration(m).vector();
  for (int k = n; k >= 1; --k) {
    const std::size_t j = std::size_t(k - 1);
    const soa::Body& B = m.body(k);
    const int nk = B.hinge.nv();
    const MatX Hs = B.hinge.H_star(c.c.x.theta.data() + B.q_offset);
    const Vec6 ap = c.ws.phi[j].matrix().transpose() * next;
    if (prescribed(j))
      Tout.segment(B.v_offset, nk) =
          Hs.transpose() * (v == Hyb::BiasOnlyT ? z_plus[j] : Vec6(P_plus[j] * ap + z_plus[j]));
    else
      bd.segment(B.v_offset, nk) = nu[j] - G[j].transpose() * ap;
    next = ap + Hs * bd.segment(B.v_offset, nk) + c.ws.a[j].vector();
  }
  VecX out(2 * m.nv());
  out << bd, Tout;
  return out;
}

// clang-format off
/* planted mistakes of 8.7
soa_plant(8.7 dropped-term
  FIND [=[z + P * (Hs * beta_dot.segment(B.v_offset, nk))]=]
  WRONG [=[z]=] TYPE [=[Vec6]=]
  EXPECT [=[the checker knows this mistake: it names it after 5 failed runs]=]
  REJECT [=[likely mistake|perhaps \(|across a prescribed hinge your z\+\(k\) is z\(k\)]=]
  NAMED [=[likely mistake \(dropped term\): across a prescribed hinge your z\+\(k\) is z\(k\)]=])
*/
// clang-format on
// 8.7: hybrid dynamics with random hinges prescribed, against the dense solution with the
// composite-body mass matrix: M_ff beta_dot_f = T_f - C_f - M_fp beta_dot_p, T_p = M_p.
// beta_dot + C_p, to n eps cond(M).
TEST(Exercise8_7_HybridDynamics, MatchesMassMatrix) {
  Random<double> rnd;
  Check bd_check("beta_dot of the free hinges", 16 * kEps),
      T_check("T of the prescribed hinges", 16 * kEps);
  Opts o;
  static const Variant<Hyb> variants[] = {
      {Hyb::Projected, "wrong inertia",
       "across a prescribed hinge your P+(k) is P(k) - G D G*: that projection is for a hinge "
       "free to move; one held on its motion passes P(k) on whole"},
      {Hyb::NoPHbd, "dropped term",
       "across a prescribed hinge your z+(k) is z(k): the known beta_dot(k) adds a force, write "
       "f(k) with alpha(k) = alpha+(k) + H*(k) beta_dot(k) + a(k)"},
      {Hyb::MinusPHbd, "sign",
       "across a prescribed hinge your z+(k) subtracts P(k) H*(k) beta_dot(k): check the sign in "
       "f(k) = P(k) (alpha(k) - a(k)) + z(k)"},
      {Hyb::BiasOnlyT, "dropped term",
       "your T(k) of a prescribed hinge is H(k) z+(k): the force across the hinge is f(k) = "
       "P+(k) alpha+(k) + z+(k)"},
      {Hyb::Ignored, "wrong model",
       "your result is the plain forward dynamics with every hinge free: prescribed hinges take "
       "their beta_dot as given"},
  };
  for (int i = 0; i < kCases; ++i) {
    const Case c(draw(rnd, i, o), rnd);
    const soa::Model& m = c.m();
    const int nv = m.nv();
    std::vector<bool> pres(std::size_t(m.n()));
    for (auto&& p : pres) p = rnd.engine()() % 2 == 0;
    const VecX bd_given = soa::test::random_vector(rnd, nv);
    // The entries that are not given hold noise: the student must not use them.
    VecX T_in = c.T, bd_in = bd_given;
    std::vector<int> free_dofs, pres_dofs;
    for (int k = 1; k <= m.n(); ++k) {
      const soa::Body& B = m.body(k);
      for (int d = 0; d < B.hinge.nv(); ++d)
        (pres[std::size_t(k - 1)] ? pres_dofs : free_dofs).push_back(B.v_offset + d);
    }
    for (int d : pres_dofs) T_in[d] = 1e3 * rnd.normal();
    for (int d : free_dofs) bd_in[d] = 1e3 * rnd.normal();
    const soa::ex08::Hybrid r = soa::ex08::hybrid_dynamics(m, c.c.x, pres, T_in, bd_in);
    // The reference by the mass matrix.
    const MassAndBias mb(m, c.c.x, {});
    VecX bd_ref = bd_in, T_ref = T_in;
    const Eigen::Index nf = Eigen::Index(free_dofs.size()), np = Eigen::Index(pres_dofs.size());
    MatX Mff(nf, nf), Mfp(nf, np);
    VecX rhs(nf), bp(np);
    for (Eigen::Index a = 0; a < np; ++a) bp[a] = bd_in[pres_dofs[std::size_t(a)]];
    for (Eigen::Index a = 0; a < nf; ++a) {
      const int r_ = free_dofs[std::size_t(a)];
      rhs[a] = T_in[r_] - mb.C[r_];
      for (Eigen::Index b = 0; b < nf; ++b) Mff(a, b) = mb.M(r_, free_dofs[std::size_t(b)]);
      for (Eigen::Index b = 0; b < np; ++b) Mfp(a, b) = mb.M(r_, pres_dofs[std::size_t(b)]);
    }
    if (nf > 0) {
      const VecX bf = Mff.ldlt().solve(rhs - Mfp * bp);
      for (Eigen::Index a = 0; a < nf; ++a) bd_ref[free_dofs[std::size_t(a)]] = bf[a];
    }
    const VecX T_all = mb.M * bd_ref + mb.C;
    for (int d : pres_dofs) T_ref[d] = T_all[d];
    const double bd_scale =
        nv * mb.cond * (std::max(1.0, bd_ref.norm()) + (T_ref.norm() + mb.C.norm()) / mb.M.norm());
    const double T_scale =
        nv * mb.cond * (T_ref.norm() + mb.C.norm() + mb.M.norm() * bd_ref.norm());
    auto inputs = [&] {
      std::string p = "std::vector<bool> prescribed = {";
      for (std::size_t j = 0; j < pres.size(); ++j)
        p += std::string(j ? ", " : "") + (pres[j] ? "true" : "false");
      return c.c.code() + soa::test::code("T", T_in) + soa::test::code("beta_dot_given", bd_in) +
             p + "};  // body 1 first\n" +
             "soa::ex08::Hybrid r = soa::ex08::hybrid_dynamics(m, x, prescribed, T, "
             "beta_dot_given);\n";
    };
    auto mistakes = [&](bool T_part) {
      return [&c, &pres, &T_in, &bd_in, T_part, nv] {
        Mistakes out;
        for (const auto& v : variants) {
          const VecX w = hybrid(c, pres, T_in, bd_in, v.v);
          out.push_back({v.kind, v.says, T_part ? VecX(w.tail(nv)) : VecX(w.head(nv))});
        }
        return out;
      };
    };
    bd_check.add(i, r.beta_dot, bd_ref, bd_scale, c.c.tags, inputs, mistakes(false),
                 soa::test::per_dof(m, "beta_dot"));
    T_check.add(i, r.T, T_ref, T_scale, c.c.tags, inputs, mistakes(true),
                soa::test::per_dof(m, "T"));
  }
}

}  // namespace
