// Property tests of the O(N^2) mass matrix inverse (lesson 7; soa::mass_matrix_inverse), on
// soa::test::kCases random chains of every hinge type from the fixed seed:
// - against Eigen's dense inverse of the composite-body mass matrix, error relative to
//   eps n cond(M);
// - M Minv = I, and Minv symmetric;
// - Minv (T - C) is the forward dynamics of lesson 8;
// - the fast paths against the general path (column sweep and Upsilon);
// - a singular D(k) throws as the Riccati recursion does.
#include <gtest/gtest.h>

#include <string>

#include "dynamics_support.hpp"

namespace {

using soa::test::DynamicsCase;
using soa::test::kCases;
using soa::test::MassAndBias;
using soa::test::Random;
using soa::test::Worst;
using MatX = soa::MatX<double>;
using VecX = soa::VecX<double>;
constexpr double kEps = soa::eps<double>();

MatX inverse(const DynamicsCase<double>& c) {
  soa::Workspace ws(c.m);
  soa::update_phi(c.m, c.x.theta, ws);
  soa::MassMatrixInverse w(c.m);
  MatX Minv;
  soa::mass_matrix_inverse(c.m, c.x, ws, w, Minv);
  return Minv;
}

TEST(dynamics_MassMatrixInverse, AgreesWithTheDenseInverse) {
  Random<double> rnd(31);
  Worst worst("|Minv - inv(M)| / (|inv(M)| eps n cond(M))");
  Worst identity("|M Minv - I| / (eps n cond(M))");
  for (int i = 0; i < kCases; ++i) {
    const DynamicsCase<double> c(rnd, i);
    const MassAndBias<double> mc(c);
    const MatX Minv = inverse(c);
    ASSERT_TRUE(Minv.isApprox(Minv.transpose(), 0)) << "Minv not symmetric, case " << i;
    const MatX ref = mc.M.inverse();
    const double scale = kEps * c.m.nv() * mc.cond();
    worst.add((Minv - ref).norm() / ref.norm() / scale, i);
    identity.add((mc.M * Minv - MatX::Identity(c.m.nv(), c.m.nv())).norm() / scale, i);
  }
  EXPECT_LE(worst.value(), 10.0);
  EXPECT_LE(identity.value(), 10.0);
}

// The fast paths (Model::fast_paths) of the Riccati recursion, and of the Upsilon recursion
// of lesson 7 (section 7), against the general path, on chains where they apply.
TEST(dynamics_MassMatrixInverse, FastPathsAgreeWithTheGeneralPath) {
  Random<double> rnd(37);
  Worst sweep("column sweep: |Minv_fast - Minv_general| / (|Minv| eps n cond(M))");
  Worst upsilon("Upsilon: |Minv_fast - Minv_general| / (|Minv| eps n cond(M))");
  const auto [fast_bodies, axis_offsets] =
      soa::test::for_each_coordinate_axis_case(rnd, [&](DynamicsCase<double>& c, int i) {
        const MassAndBias<double> mc(c);
        soa::Workspace ws(c.m);
        soa::update_phi(c.m, c.x.theta, ws);
        soa::MassMatrixInverseUpsilon wu(c.m);
        MatX ups_fast, ups_general;
        soa::mass_matrix_inverse_upsilon(c.m, c.x, ws, wu, ups_fast);
        const MatX sweep_fast = inverse(c);
        c.m.fast_paths = false;
        soa::mass_matrix_inverse_upsilon(c.m, c.x, ws, wu, ups_general);
        const MatX sweep_general = inverse(c);
        const double scale = kEps * c.m.nv() * mc.cond();
        sweep.add((sweep_fast - sweep_general).norm() / sweep_general.norm() / scale, i);
        upsilon.add((ups_fast - ups_general).norm() / ups_general.norm() / scale, i);
      });
  EXPECT_GT(fast_bodies, kCases);  // the fast paths were taken
  EXPECT_GT(axis_offsets, kCases);
  EXPECT_LE(sweep.value(), 1.0);
  EXPECT_LE(upsilon.value(), 1.0);
}

TEST(dynamics_MassMatrixInverse, TimesTMinusCIsTheForwardDynamics) {
  Random<double> rnd(37);
  Worst worst("|Minv (T - C) - FD(T)| / (eps n cond(M))");
  for (int i = 0; i < kCases; ++i) {
    const DynamicsCase<double> c(rnd, i);
    const MassAndBias<double> mc(c);
    const VecX a = inverse(c) * (c.T - mc.C);
    soa::Workspace ws(c.m);
    soa::ForwardDynamics fd(c.m);
    VecX bd(c.m.nv());
    soa::forward_dynamics(c.m, c.x, c.T, c.f_ext, ws, fd, bd);
    worst.add(soa::test::rel(a, bd) / (kEps * c.m.nv() * mc.cond()), i);
  }
  EXPECT_LE(worst.value(), 10.0);
}

TEST(dynamics_MassMatrixInverse, SingularDNamesTheBody) {
  Random<double> rnd(41);
  DynamicsCase<double> c(rnd, 5);
  c.m.body(1).M = soa::SpatialInertia(0, soa::Vec3<double>::Zero(), soa::Mat3<double>::Zero());
  c.m.body(1).name = "ghost";
  std::string msg = "(no error)";
  try {
    inverse(c);
  } catch (const soa::Error& e) {
    msg = e.what();
  }
  EXPECT_EQ(msg.rfind("body 'ghost': articulated inertia D(1) singular: ", 0), 0u) << msg;
}

}  // namespace
