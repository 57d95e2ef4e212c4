// Property tests of the O(N) articulated body forward dynamics (lesson 8;
// soa::forward_dynamics) on soa::test::kCases random chains of every hinge type from the
// fixed seed, with gravity, springs and dampers, external forces and states at rest mixed in:
// - beta_dot agrees with CRB + LDLT, M beta_dot = T - C (error relative to eps cond(M));
// - beta_dot agrees with M^{-1}(T - C) from the dense operator form (lesson 4);
// - the round trip ID(FD(T)) = T;
// - the inter-body forces f(k) = P+(k) alpha+(k) + z+(k) equal Newton-Euler's at beta_dot;
// - float and long double: the float result's error against long double within eps_float
//   cond(M);
// - an empty external-force list gives bitwise the result of explicit zero forces;
// - a singular D(k) and non-finite inputs stop with soa::Error naming the body;
// - the lean storage (ForwardDynamics::lean(), for million-body chains) gives bitwise the
//   result, the accelerations alpha(k) and the errors of the full storage;
// - a lazy workspace (Workspace::lazy()) holds only the parts the functions run fill, with
//   bitwise the results of a full one;
// - the fast paths for hinges about a coordinate axis (Model::fast_paths) against the general
//   path, on chains whose one-dof axes are +-e_i, half of whose placements do not rotate and
//   half of whose offsets lie along a coordinate axis.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "dynamics_support.hpp"

namespace {

using soa::test::DynamicsCase;
using soa::test::kCases;
using soa::test::MassAndBias;
using soa::test::Random;
using soa::test::Worst;
using VecX = soa::VecX<double>;
constexpr double kEps = soa::eps<double>();

VecX forward(const DynamicsCase<double>& c, soa::ForwardDynamics* out = nullptr,
             soa::Workspace* ws_out = nullptr, bool lean = false) {
  soa::Workspace ws(c.m);
  soa::ForwardDynamics fd = lean ? soa::ForwardDynamics::lean(c.m) : soa::ForwardDynamics(c.m);
  VecX beta_dot(c.m.nv());
  soa::forward_dynamics(c.m, c.x, c.T, c.f_ext, ws, fd, beta_dot);
  if (out) *out = fd;
  if (ws_out) *ws_out = ws;
  return beta_dot;
}

TEST(dynamics_Forward, AgreesWithCompositeBodiesAndLDLT) {
  Random<double> rnd;
  Worst worst("|bd - bd_crb|/|bd_crb| / (eps n cond(M))");
  for (int i = 0; i < kCases; ++i) {
    const DynamicsCase<double> c(rnd, i);
    const MassAndBias<double> mc(c);
    const VecX ref = mc.M.ldlt().solve(c.T - mc.C);
    const VecX bd = forward(c);
    worst.add(soa::test::rel(bd, ref) / (kEps * c.m.nv() * mc.cond()), i);
  }
  EXPECT_LE(worst.value(), 10.0);
}

// The fast paths (P H* as a column of P, plane rotations of the articulated inertias) give the
// general path's result within rounding: the two differ only in the order of the same sums
// and in products with exact zeros and ones.
TEST(dynamics_Forward, FastPathsAgreeWithTheGeneralPath) {
  Random<double> rnd;
  Worst worst("|bd_fast - bd_general|/|bd_general| / (eps n cond(M))");
  const auto [fast_bodies, axis_offsets] =
      soa::test::for_each_coordinate_axis_case(rnd, [&](DynamicsCase<double>& c, int i) {
        const MassAndBias<double> mc(c);
        const VecX fast = forward(c);
        c.m.fast_paths = false;
        const VecX general = forward(c);
        worst.add(soa::test::rel(fast, general) / (kEps * c.m.nv() * mc.cond()), i);
      });
  EXPECT_GT(fast_bodies, kCases);  // the fast paths were taken
  EXPECT_GT(axis_offsets, kCases);
  EXPECT_LE(worst.value(), 1.0);
}

TEST(dynamics_Forward, AgreesWithTheOperatorForm) {
  Random<double> rnd(7);
  Worst worst("|bd - M^-1(T - C)| / (eps n cond(M)), dense operators");
  for (int i = 0; i < kCases; ++i) {
    const DynamicsCase<double> c(rnd, i % 6);  // n <= 6: the dense operators stay small
    if (c.m.has_springs()) continue;           // the operator form has no springs
    const soa::Operators op = soa::Operators::build(c.m, c.x, c.f_ext);
    const soa::MatX<double> M = op.mass_matrix();
    const VecX ref = M.inverse() * (c.T - op.bias());
    const MassAndBias<double> mc(c);
    worst.add(soa::test::rel(forward(c), ref) / (kEps * c.m.nv() * mc.cond()), i);
  }
  EXPECT_LE(worst.value(), 10.0);
}

TEST(dynamics_Forward, RoundTripThroughInverseDynamics) {
  Random<double> rnd(11);
  Worst worst("|ID(FD(T)) - T| / (eps n (|T| + |C| + |M||bd|))");
  for (int i = 0; i < kCases; ++i) {
    const DynamicsCase<double> c(rnd, i);
    const MassAndBias<double> mc(c);
    const VecX bd = forward(c);
    soa::Workspace ws(c.m);
    VecX T(c.m.nv());
    soa::inverse_dynamics(c.m, c.x, bd, c.f_ext, ws, T);
    const double scale = c.T.norm() + mc.C.norm() + mc.M.norm() * bd.norm();
    worst.add((T - c.T).norm() / (kEps * c.m.nv() * scale), i);
  }
  EXPECT_LE(worst.value(), 10.0);
}

// Lesson 8 derives f(k) = P+(k) alpha+(k) + z+(k); Newton-Euler at beta_dot gives f(k).
TEST(dynamics_Forward, InterBodyForcesMatchNewtonEuler) {
  Random<double> rnd(13);
  Worst worst("|P+ alpha+ + z+ - f_NE| / (eps n cond(M) scale)");
  for (int i = 0; i < kCases; ++i) {
    const DynamicsCase<double> c(rnd, i);
    const MassAndBias<double> mc(c);
    soa::ForwardDynamics fd(c.m);
    soa::Workspace ws(c.m);
    const VecX bd = forward(c, &fd, &ws);
    soa::Workspace ne(c.m);
    VecX T(c.m.nv());
    soa::inverse_dynamics(c.m, c.x, bd, c.f_ext, ne, T);
    for (int k = 1; k <= c.m.n(); ++k) {
      const std::size_t j = std::size_t(k - 1);
      const soa::Vec6<double> f =
          fd.art.P_plus[j] * fd.alpha_plus[j].vector() + fd.z_plus[j].vector();
      const double scale = 1 + ne.f[j].vector().norm() + fd.z_plus[j].vector().norm() +
                           fd.art.P_plus[j].norm() * fd.alpha_plus[j].vector().norm();
      worst.add((f - ne.f[j].vector()).norm() / (kEps * c.m.nv() * mc.cond() * scale), i);
    }
  }
  EXPECT_LE(worst.value(), 10.0);
}

TEST(dynamics_Forward, FloatAgainstLongDouble) {
  Random<double> rnd(17);
  Worst worst("|bd_float - bd_long| / (eps_float n cond(M))");
  for (int i = 0; i < kCases / 4; ++i) {
    const DynamicsCase<double> c(rnd, i);
    if (c.m.has_springs()) continue;  // spring rest angles are not cast
    const MassAndBias<double> mc(c);
    auto run = [&](auto zero) {
      using S = decltype(zero);
      std::vector<soa::BodyT<S>> bodies;
      for (int k = c.m.n(); k >= 1; --k) {
        const soa::Body& B = c.m.body(k);
        soa::BodyT<S> b;
        b.name = B.name;
        b.M = B.M.template cast<S>();
        b.placement = B.placement.template cast<S>();
        b.hinge = B.hinge.template cast<S>();
        bodies.push_back(b);
      }
      soa::ModelT<S> m = soa::ModelT<S>::from_base_first(bodies);
      m.gravity = c.m.gravity.template cast<S>();
      soa::StateT<S> x{c.x.theta.template cast<S>(), c.x.beta.template cast<S>()};
      soa::ExternalForces<S> fe;
      for (const auto& f : c.f_ext) fe.push_back(soa::ForceT<S>(f.vector().template cast<S>()));
      soa::WorkspaceT<S> ws(m);
      soa::ForwardDynamicsT<S> fd(m);
      soa::VecX<S> bd(m.nv());
      soa::forward_dynamics(m, x, soa::VecX<S>(c.T.template cast<S>()), fe, ws, fd, bd);
      return bd.template cast<long double>().eval();
    };
    const auto bf = run(0.0f);
    const auto bl = run(0.0L);
    const double err = double((bf - bl).norm() / bl.norm());
    worst.add(err / (soa::eps<float>() * c.m.nv() * mc.cond()), i);
  }
  EXPECT_LE(worst.value(), 10.0);
}

TEST(dynamics_Forward, NoExternalForcesEqualsExplicitZeros) {
  Random<double> rnd(19);
  for (int i = 0; i < kCases; ++i) {
    DynamicsCase<double> c(rnd, i);
    c.f_ext.clear();
    const VecX without = forward(c);
    c.f_ext.assign(std::size_t(c.m.n()), soa::Force::Zero());
    const VecX with = forward(c);
    ASSERT_TRUE((without.array() == with.array()).all()) << "case " << i;
  }
}

std::string message_of(const DynamicsCase<double>& c, bool lean = false) {
  try {
    forward(c, nullptr, nullptr, lean);
  } catch (const soa::Error& e) {
    return e.what();
  }
  return "(no error)";
}

// A tip with no mass: D(1) = 0.
TEST(dynamics_Forward, SingularDNamesTheBody) {
  Random<double> rnd(23);
  DynamicsCase<double> c(rnd, 3);
  c.m.body(1).M = soa::SpatialInertia(0, soa::Vec3<double>::Zero(), soa::Mat3<double>::Zero());
  c.m.body(1).name = "ghost";
  const std::string msg = message_of(c);
  EXPECT_EQ(msg.rfind("body 'ghost': articulated inertia D(1) singular: ", 0), 0u) << msg;
  EXPECT_EQ(message_of(c, true), msg);
}

// The lean storage keeps G and nu packed and P rolling: the same arithmetic, so bitwise the
// same beta_dot and alpha(k) (every hinge type, gravity, springs, external forces, rest); the
// full storage keeps G and nu per body as well as packed, and the two agree.
TEST(dynamics_Forward, LeanStorageGivesBitwiseTheSameResult) {
  Random<double> rnd(31);
  for (int i = 0; i < kCases; ++i) {
    const DynamicsCase<double> c(rnd, i);
    soa::Workspace ws_full(c.m), ws_lean(c.m);
    soa::ForwardDynamics fd_full(c.m);
    const VecX full = forward(c, &fd_full, &ws_full);
    const VecX lean = forward(c, nullptr, &ws_lean, true);
    ASSERT_TRUE((full.array() == lean.array()).all()) << "case " << i;
    // The full storage's G(k) and nu(k), which the last pass reads packed, are the same.
    for (int k = 1; k <= c.m.n(); ++k) {
      const soa::Body& B = c.m.body(k);
      for (int j = 0; j < B.hinge.nv(); ++j) {
        const int o = B.v_offset + j;
        ASSERT_TRUE(fd_full.art.G[k - 1].col(j) ==
                    Eigen::Map<const soa::Vec6<double>>(fd_full.G_packed.data() + 6 * o))
            << "case " << i << ", G(" << k << ")";
        ASSERT_EQ(fd_full.nu[k - 1][j], fd_full.nu_packed[std::size_t(o)])
            << "case " << i << ", nu(" << k << ")";
      }
    }
    for (int k = 1; k <= c.m.n(); ++k)
      ASSERT_TRUE(ws_full.alpha[k - 1].vector() == ws_lean.alpha[k - 1].vector())
          << "case " << i << ", alpha(" << k << ")";
  }
  // Its size: two bodies of Riccati storage and 7 numbers per revolute coordinate.
  const DynamicsCase<double> c(rnd, 0);
  const soa::ForwardDynamics lean = soa::ForwardDynamics::lean(c.m);
  EXPECT_EQ(lean.art.P.size(), 2u);
  EXPECT_TRUE(lean.z.empty() && lean.nu.empty() && lean.art.R.empty());
  EXPECT_EQ(lean.G_packed.size(), 6u * std::size_t(c.m.nv()));
}

TEST(dynamics_Forward, NonFiniteInputsNameTheBody) {
  Random<double> rnd(29);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const char* what : {"theta", "beta", "T", "f_ext"}) {
    DynamicsCase<double> c(rnd, 7);
    c.m.body(2).name = "victim";
    const soa::Body& B = c.m.body(2);
    const std::string w = what;
    if (w == "theta") c.x.theta[B.q_offset] = nan;
    if (w == "beta") c.x.beta[B.v_offset] = inf;
    if (w == "T") c.T[B.v_offset] = nan;
    if (w == "f_ext") {
      c.f_ext.assign(std::size_t(c.m.n()), soa::Force::Zero());
      c.f_ext[1] = soa::Force(soa::Vec6<double>::Constant(nan));
    }
    const std::string msg = message_of(c);
    EXPECT_NE(msg.find("'victim'"), std::string::npos) << what << ": " << msg;
    EXPECT_NE(msg.find("not finite"), std::string::npos) << what << ": " << msg;
    EXPECT_EQ(message_of(c, true), msg) << what;
  }
}

}  // namespace

namespace {

template <class T>
bool same(const std::vector<T>& a, const std::vector<T>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!(a[i].vector() == b[i].vector())) return false;
  return true;
}

TEST(dynamics_Workspace, LazyHoldsOnlyTheUsedPartsWithTheSameResults) {
  Random<double> rnd(37);
  for (int i = 0; i < kCases; ++i) {
    const DynamicsCase<double> c(rnd, i);
    const soa::Model& m = c.m;
    const VecX qdd = soa::test::random_vector(rnd, m.nv());
    VecX T_full(m.nv()), T_lazy(m.nv());
    {  // inverse dynamics: no poses, no b
      soa::Workspace full(m), lazy = soa::Workspace::lazy();
      soa::inverse_dynamics(m, c.x, qdd, c.f_ext, full, T_full);
      soa::inverse_dynamics(m, c.x, qdd, c.f_ext, lazy, T_lazy);
      ASSERT_TRUE((T_full.array() == T_lazy.array()).all()) << "case " << i;
      EXPECT_TRUE(same(full.f, lazy.f) && same(full.alpha, lazy.alpha)) << "case " << i;
      EXPECT_TRUE(lazy.pose.empty() && lazy.b.empty()) << "case " << i;
    }
    {  // forward dynamics: no poses, no f
      soa::Workspace full(m), lazy = soa::Workspace::lazy();
      soa::ForwardDynamics fd(m);
      soa::forward_dynamics(m, c.x, c.T, c.f_ext, full, fd, T_full);
      soa::forward_dynamics(m, c.x, c.T, c.f_ext, lazy, fd, T_lazy);
      ASSERT_TRUE((T_full.array() == T_lazy.array()).all()) << "case " << i;
      EXPECT_TRUE(same(full.alpha, lazy.alpha) && same(full.b, lazy.b)) << "case " << i;
      EXPECT_TRUE(lazy.pose.empty() && lazy.f.empty()) << "case " << i;
    }
    {  // kinematics: phi, poses, V, a, alpha only
      soa::Workspace full(m), lazy = soa::Workspace::lazy();
      for (soa::Workspace* ws : {&full, &lazy}) {
        soa::update_phi(m, c.x.theta, *ws);
        soa::update_poses(m, *ws);
        soa::update_velocities(m, c.x, *ws);
        soa::update_accelerations(m, c.x, qdd.data(), soa::Acceleration(), *ws);
      }
      EXPECT_TRUE(same(full.V, lazy.V) && same(full.alpha, lazy.alpha)) << "case " << i;
      for (int k = 1; k <= m.n(); ++k)
        ASSERT_TRUE(full.pose[k - 1].matrix() == lazy.pose[k - 1].matrix()) << "case " << i;
      EXPECT_TRUE(lazy.b.empty() && lazy.f.empty()) << "case " << i;
    }
  }
}

}  // namespace
