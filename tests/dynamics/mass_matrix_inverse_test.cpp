// Property tests of the O(N^2) mass matrix inverse (lesson 7; soa::mass_matrix_inverse), on
// soa::test::kCases random chains of every hinge type from the fixed seed:
// - against Eigen's dense inverse of the composite-body mass matrix, error relative to
//   eps n cond(M);
// - M Minv = I, and Minv symmetric;
// - Minv (T - C) is the forward dynamics of lesson 8;
// - the fast paths against the general path (column sweep and Upsilon), and the sweep's
//   row kernels for a plane rotation against the general kernels, bit for bit;
// - a singular D(k) throws as the Riccati recursion does.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
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

// The row kernels of the column sweep for a phi turning about the coordinate axis I
// (detail::tip_to_base_rows_plane(), base_to_tip_rows_plane()) against the general kernels,
// for every I, every unit column P of H* (and P = -1, any H*), on random rows, phi and G:
// the same arithmetic less products with exact zeros and ones, so equal bit for bit.
TEST(dynamics_MassMatrixInverse, PlaneRowKernelsAreTheGeneralKernelsBitForBit) {
  std::mt19937 g(43);
  std::normal_distribution<double> N;
  constexpr int kRows = 37;
  int checked = 0, differing = 0;
  for (int trial = 0; trial < 20; ++trial)
    for (int axis = 0; axis < 3; ++axis)
      for (int P = -1; P < 6; ++P) {
        const int J = (axis + 1) % 3, K = (axis + 2) % 3;
        const double th = 4 * N(g);
        soa::Mat3<double> R = soa::Mat3<double>::Identity();
        R(J, J) = std::cos(th), R(J, K) = -std::sin(th);
        R(K, J) = std::sin(th), R(K, K) = std::cos(th);
        ASSERT_EQ(soa::detail::plane_rotation_axis(R), axis);
        const soa::Phi phi(R, soa::Vec3<double>(N(g), N(g), N(g)));
        soa::Vec6<double> s = soa::Vec6<double>::Zero(), gk;
        if (P >= 0)
          s[P] = g() % 2 ? 1.0 : -1.0;
        else
          for (int i = 0; i < 6; ++i) s[i] = N(g);
        for (int i = 0; i < 6; ++i) gk[i] = N(g);
        const double D_inv = std::exp(N(g));
        MatX rows(kRows, 7);  // six columns of the block, then the column of Minv
        for (int i = 0; i < rows.size(); ++i) rows.data()[i] = N(g);
        for (const bool tip_to_base : {true, false}) {
          MatX general = rows, plane = rows;
          auto col = [](MatX& X, int j) { return X.col(j).data(); };
          if (tip_to_base)
            soa::detail::tip_to_base_rows_1dof(kRows, phi, s, D_inv, gk, col(general, 0),
                                               col(general, 1), col(general, 2), col(general, 3),
                                               col(general, 4), col(general, 5), col(general, 6));
          else
            soa::detail::base_to_tip_rows_1dof(kRows, &phi, s, gk, col(general, 0), col(general, 1),
                                               col(general, 2), col(general, 3), col(general, 4),
                                               col(general, 5), col(general, 6));
          soa::detail::with_plane_axis(axis, [&](auto I) {
            soa::detail::with_unit_column(P, [&](auto Pc) {
              constexpr int kI = decltype(I)::value, kP = decltype(Pc)::value;
              if (tip_to_base)
                soa::detail::tip_to_base_rows_plane<kI, kP>(
                    kRows, phi, s, D_inv, gk, col(plane, 0), col(plane, 1), col(plane, 2),
                    col(plane, 3), col(plane, 4), col(plane, 5), col(plane, 6));
              else
                soa::detail::base_to_tip_rows_plane<kI, kP>(
                    kRows, phi, s, gk, col(plane, 0), col(plane, 1), col(plane, 2), col(plane, 3),
                    col(plane, 4), col(plane, 5), col(plane, 6));
            });
          });
          ++checked;
          if (!(plane.array() == general.array()).all()) {
            ++differing;
            ADD_FAILURE() << (tip_to_base ? "tip to base" : "base to tip") << ", axis " << axis
                          << ", P " << P << ": largest difference "
                          << (plane - general).cwiseAbs().maxCoeff();
          }
        }
      }
  EXPECT_EQ(checked, 2 * 20 * 3 * 7);
  EXPECT_EQ(differing, 0);
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
