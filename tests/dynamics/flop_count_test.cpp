// The counting scalar of the flop counts (lesson 8's report `work`): it counts known kernels
// exactly, its results are double's to rounding, and the counts show the fast paths doing less
// work than the general path.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "flop_count.hpp"
#include "soa/soa.hpp"

namespace {

using soa::HingeType;
using namespace soa::test;
using C = Counted;

const HingeType kTypes[] = {HingeType::Revolute,  HingeType::Prismatic, HingeType::Helical,
                            HingeType::Universal, HingeType::Spherical, HingeType::Free};

TEST(dynamics_FlopCount, ScalarOperations) {
  const C a = 1.5, b = -2.0, c = 0.25;
  const OpCounts n = count_ops([&] {
    C x = a * b + c / a - b;  // 1 mul, 1 div, 2 add
    x += a;                   // 1 add
    x *= -x;                  // 1 mul: the sign change is free
    EXPECT_EQ(double(x), -std::pow(1.5 * -2.0 + 0.25 / 1.5 + 2.0 + 1.5, 2));
    EXPECT_TRUE(x < a);  // 1 comparison
    (void)sqrt(c), (void)sin(a), (void)cos(a), (void)atan2(a, b);
  });
  EXPECT_EQ(n.add, 3);
  EXPECT_EQ(n.mul, 2);
  EXPECT_EQ(n.div, 1);
  EXPECT_EQ(n.flops(), 6);
  EXPECT_EQ(n.cmp, 1);
  EXPECT_EQ(n.sqrt, 1);
  EXPECT_EQ(n.trig, 2);
  EXPECT_EQ(n.other, 1);
}

// Eigen's kernels run coefficient by coefficient on Counted: a k-term dot product is k
// multiplies and k - 1 adds, a 6 x 6 by 6 product six of them.
TEST(dynamics_FlopCount, EigenKernels) {
  const Eigen::Matrix<C, 6, 1> u = Eigen::Matrix<double, 6, 1>::LinSpaced(1, 6).cast<C>();
  const Eigen::Matrix<C, 6, 1> v = Eigen::Matrix<double, 6, 1>::LinSpaced(-2, 3).cast<C>();
  Eigen::Matrix<double, 6, 6> Ad;
  for (int i = 0; i < 36; ++i) Ad(i) = 0.1 * i - 1;
  const Eigen::Matrix<C, 6, 6> A = Ad.cast<C>();
  C d;
  OpCounts n = count_ops([&] { d = u.dot(v); });
  EXPECT_EQ(n.mul, 6);
  EXPECT_EQ(n.add, 5);
  EXPECT_EQ(n.flops(), 11);
  EXPECT_EQ(double(d), u.cast<double>().dot(v.cast<double>()));
  Eigen::Matrix<C, 6, 1> w;
  n = count_ops([&] { w.noalias() = A * v; });
  EXPECT_EQ(n.mul, 36);
  EXPECT_EQ(n.add, 30);
  EXPECT_EQ(n.div, 0);
  Eigen::Matrix<C, 6, 6> B;
  n = count_ops([&] { B.noalias() = A * A; });
  EXPECT_EQ(n.mul, 216);
  EXPECT_EQ(n.add, 180);
  n = count_ops([&] { w = u + v; });
  EXPECT_EQ(n.flops(), 6);
  for (int i = 0; i < 6; ++i)
    EXPECT_LE(std::abs(double(w[i]) - (double(u[i]) + double(v[i]))), 0.0);
}

// transform_symmetric()'s shift by an offset along a coordinate axis (detail::shift_on_axis())
// does 32 flops where the general shift does 108, as the notes say; the rotation, general
// here, is the same in both.
TEST(dynamics_FlopCount, ShiftOnAnAxis) {
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.3, -1, 2).normalized()).toRotationMatrix();
  Eigen::Matrix<double, 6, 6> A;
  for (int i = 0; i < 36; ++i) A(i) = 0.1 * i - 1;
  const Eigen::Matrix<C, 6, 6> P = (A + A.transpose()).cast<C>();
  for (int axis = 0; axis < 3; ++axis) {
    soa::Vec3<C> l = soa::Vec3<C>::Zero(), l_general = soa::Vec3<C>::Constant(C(0.1));
    l[axis] = C(0.3);
    const soa::PhiT<C> phi(R.cast<C>(), l), phi_general(R.cast<C>(), l_general);
    Eigen::Matrix<C, 6, 6> out;
    const OpCounts fast = count_ops([&] { soa::transform_symmetric(phi, P, out, true); });
    const OpCounts slow = count_ops([&] { soa::transform_symmetric(phi, P, out, false); });
    const OpCounts general = count_ops([&] { soa::transform_symmetric(phi_general, P, out); });
    EXPECT_EQ(slow.flops() - fast.flops(), 108 - 32) << "axis " << axis;
    EXPECT_EQ(general.flops(), slow.flops()) << "axis " << axis;
  }
}

// Counted arithmetic is double arithmetic: the algorithms give double's results to
// rounding (the order of a vectorized sum may differ), for every hinge type: T and M within
// 64 eps, beta_dot and M^-1 within 64 eps cond(M), the rounding amplified by the solve.
TEST(dynamics_FlopCount, CountedResultsAreDoubleResults) {
  const double tol = 64 * soa::eps<double>();
  for (const HingeType t : kTypes)
    for (const Axes axes : {Axes::Coordinate, Axes::General}) {
      SCOPED_TRACE(std::string(soa::hinge_type_name(t)) +
                   (axes == Axes::Coordinate ? ", coordinate axes" : ", general axes"));
      const CountChain<C> cc(t, 7, axes);
      const CountChain<double> cd(t, 7, axes);
      soa::Workspace ws(cd.m);
      soa::VecX<double> T(cd.m.nv()), beta_dot(cd.m.nv());
      soa::inverse_dynamics(cd.m, cd.x, cd.beta_dot, {}, ws, T);
      soa::ForwardDynamics fd(cd.m);
      soa::forward_dynamics(cd.m, cd.x, cd.T, {}, ws, fd, beta_dot);
      soa::MassMatrixInverse w(cd.m);
      soa::MatX<double> Minv(cd.m.nv(), cd.m.nv());
      soa::mass_matrix_inverse(cd.m, cd.x, ws, w, Minv);
      std::vector<soa::SpatialInertia> R(std::size_t(cd.m.n()));
      soa::MatX<double> M(cd.m.nv(), cd.m.nv());
      soa::mass_matrix_crb(cd.m, cd.x, ws, R, M);
      const Eigen::VectorXd lambda =
          Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M, Eigen::EigenvaluesOnly).eigenvalues();
      const double cond = lambda.maxCoeff() / lambda.minCoeff();
      const std::pair<Algorithm, soa::MatX<double>> expected[] = {
          {Algorithm::InverseDynamics, T},
          {Algorithm::ForwardDynamics, beta_dot},
          {Algorithm::MassMatrixCRB, M},
          {Algorithm::MassMatrixInertial, M},
          {Algorithm::MassMatrixInverse, Minv}};
      for (const auto& [a, ref] : expected) {
        soa::MatX<C> got;
        const OpCounts n = count_call(a, cc, &got);
        EXPECT_GT(n.flops(), 0) << algorithm_name(a);
        ASSERT_EQ(got.rows(), ref.rows()) << algorithm_name(a);
        ASSERT_EQ(got.cols(), ref.cols()) << algorithm_name(a);
        const soa::MatX<double> g = got.unaryExpr([](C x) { return double(x); });
        const bool solve = a == Algorithm::ForwardDynamics || a == Algorithm::MassMatrixInverse;
        EXPECT_LE((g - ref).norm(), tol * (solve ? cond : 1) * ref.norm()) << algorithm_name(a);
      }
    }
}

// The counts are those of the code, not of the values, for a 1-dof hinge: per body the
// same from 8 to 16 as from 16 to 24 bodies, and the O(N^2) ones a polynomial of degree two.
// A hinge of several dofs iterates the eigenvalues of its pivot in the singularity guard (a
// number of steps that depends on the values): its counts per body agree within 10 %.
TEST(dynamics_FlopCount, CountsArePolynomialsInN) {
  const Algorithm linear[] = {Algorithm::InverseDynamics, Algorithm::ForwardDynamics};
  const Algorithm quadratic[] = {Algorithm::MassMatrixCRB, Algorithm::MassMatrixInertial,
                                 Algorithm::MassMatrixInverse};
  for (const HingeType t : {HingeType::Revolute, HingeType::Prismatic, HingeType::Helical})
    for (const Axes axes : {Axes::Coordinate, Axes::General}) {
      SCOPED_TRACE(soa::hinge_type_name(t));
      for (const Algorithm a : linear)
        EXPECT_TRUE(per_body(a, t, axes, true).linear) << algorithm_name(a);
      for (const Algorithm a : quadratic)
        EXPECT_TRUE(quadratic_flops(a, t, axes, true).exact) << algorithm_name(a);
    }
  for (const HingeType t : {HingeType::Universal, HingeType::Spherical, HingeType::Free}) {
    SCOPED_TRACE(soa::hinge_type_name(t));
    for (const Algorithm a : linear)
      EXPECT_LE(per_body(a, t, Axes::General, true).spread, 0.1) << algorithm_name(a);
  }
}

// The fast paths of a revolute hinge about a coordinate axis do less work per body than
// the general path on the same chain (and a general axis takes the general path); the same
// in M^-1, built on the same Riccati recursion, on a chain of 16 bodies.
TEST(dynamics_FlopCount, FastPathsDoFewerFlops) {
  const Algorithm aba = Algorithm::ForwardDynamics;
  const double fast = per_body(aba, HingeType::Revolute, Axes::Coordinate, true).flops;
  const double off = per_body(aba, HingeType::Revolute, Axes::Coordinate, false).flops;
  const double general = per_body(aba, HingeType::Revolute, Axes::General, true).flops;
  EXPECT_GT(fast, 0);
  EXPECT_LT(fast, off);
  EXPECT_LT(fast, general);
  const Algorithm minv = Algorithm::MassMatrixInverse;
  EXPECT_LT(count_chain(minv, HingeType::Revolute, 16, Axes::Coordinate, true).flops(),
            count_chain(minv, HingeType::Revolute, 16, Axes::Coordinate, false).flops());
}

}  // namespace
