// Lesson 3 exercise tests: each exercise of exercises/03-serial-chain-kinematics/exercises.hpp
// against the library, on soa::test::kCases random chains (every hinge type, random
// placements, axes and states) from the fixed seed. Built against the solutions (ctest) and
// against the students' stubs (make exercises).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "exercises.hpp"
#include "random_chain.hpp"

namespace {

using soa::test::kCases;
using soa::test::Random;
using soa::test::random_chain;
using soa::test::random_state;
using soa::test::Worst;
using V3 = soa::Vec3<double>;
using MatXd = soa::MatX<double>;

constexpr double kEps = soa::eps<double>();

// A chain of 1 to 8 bodies (before locked hinges merge), hinge types cycling through all.
soa::Model chain(Random<double>& rnd) {
  const int n = 1 + int(rnd.uniform(0.0, 8.0));
  return random_chain(rnd, std::min(n, 8));
}

// phi(k+1,k) and the hinge velocities H*(k) beta(k) of a chain at state x.
struct Kinematics {
  soa::Workspace ws;
  std::vector<soa::Phi> phi;
  std::vector<soa::Velocity> dV;
  Kinematics(const soa::Model& m, const soa::State& x) : ws(m) {
    soa::update_phi(m, x.theta, ws);
    soa::update_poses(m, ws);
    soa::update_velocities(m, x, ws);
    phi = ws.phi;
    for (int k = 1; k <= m.n(); ++k) {
      const soa::Body& B = m.body(k);
      dV.push_back(B.hinge.H_star_times(x.theta.data() + B.q_offset, x.beta.data() + B.v_offset));
    }
  }
};

// The scale of the chain's positions: 1 + the sum of its offsets |l|.
double reach(const std::vector<soa::Phi>& phi) {
  double s = 1;
  for (const soa::Phi& p : phi) s += p.l().norm();
  return s;
}

}  // namespace

// 3.1: H*(k) of every hinge type, against soa::Hinge::H_star.
TEST(Exercise3_1_JointMap, MatchesLibrary) {
  Random<double> rnd;
  Worst worst("H*(k) residual");
  for (int i = 0; i < kCases; ++i) {
    soa::Hinge hinge;
    hinge.type = soa::HingeType(i % 7);
    hinge.axis = rnd.unit3();
    hinge.axis2 = rnd.unit3();
    hinge.pitch = rnd.uniform(-0.5, 0.5);
    soa::VecX<double> theta = soa::test::random_vector(rnd, hinge.nq());
    if (hinge.nq() >= 4) theta.head<4>().normalize();
    const soa::ex03::Matrix6X Hs = soa::ex03::joint_map(hinge, theta);
    ASSERT_EQ(Hs.cols(), hinge.nv()) << soa::hinge_type_name(hinge.type);
    worst.add((Hs - hinge.H_star(theta.data())).norm(), i);
  }
  EXPECT_LE(worst.value(), 8 * kEps);
}

// 3.2: the velocity scatter recursion, against soa::update_velocities.
TEST(Exercise3_2_ScatterVelocities, MatchesLibrary) {
  Random<double> rnd;
  Worst worst("max_k |V(k) - library| / scale");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = chain(rnd);
    const soa::State x = random_state(rnd, m);
    const Kinematics kin(m, x);
    const std::vector<soa::Velocity> V = soa::ex03::scatter_velocities(kin.phi, kin.dV);
    ASSERT_EQ(int(V.size()), m.n());
    double res = 0, scale = 1;
    for (int k = 1; k <= m.n(); ++k) {
      res = std::max(res, (V[k - 1] - kin.ws.V[k - 1]).vector().norm());
      scale = std::max(scale, kin.ws.V[k - 1].vector().norm());
    }
    worst.add(res / (scale * reach(kin.phi)), i);
  }
  EXPECT_LE(worst.value(), 16 * kEps);
}

// 3.3: the shift operator E_phi, against soa::Operators::E_phi.
TEST(Exercise3_3_ShiftOperator, MatchesLibrary) {
  Random<double> rnd;
  Worst worst("|E_phi - library| / |E_phi|");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = chain(rnd);
    const soa::State x = random_state(rnd, m);
    const Kinematics kin(m, x);
    const MatXd E = soa::ex03::shift_operator(kin.phi);
    const soa::Operators op = soa::Operators::build(m, x);
    ASSERT_EQ(E.rows(), 6 * m.n());
    ASSERT_EQ(E.cols(), 6 * m.n());
    worst.add((E - op.E_phi).norm() / std::max(1.0, op.E_phi.norm()), i);
  }
  EXPECT_LE(worst.value(), 4 * kEps);
}

// 3.4: phi block by block, against soa::Operators::phi = (I - E_phi)^-1, and (I - E_phi) phi = I.
TEST(Exercise3_4_PhiOperator, MatchesLibrary) {
  Random<double> rnd;
  Worst w_lib("|phi - library| / |phi|^2"), w_inv("|(I - E_phi) phi - I| / |phi|");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = chain(rnd);
    const soa::State x = random_state(rnd, m);
    const Kinematics kin(m, x);
    const MatXd P = soa::ex03::phi_operator(kin.phi);
    const soa::Operators op = soa::Operators::build(m, x);
    ASSERT_EQ(P.rows(), 6 * m.n());
    ASSERT_EQ(P.cols(), 6 * m.n());
    const double scale = std::max(1.0, op.phi.norm());
    // The library inverts I - E_phi: its own rounding grows like the condition, |phi|^2.
    w_lib.add((P - op.phi).norm() / (scale * scale), i);
    const MatXd I = MatXd::Identity(6 * m.n(), 6 * m.n());
    w_inv.add(((I - op.E_phi) * P - I).norm() / scale, i);
  }
  EXPECT_LE(w_lib.value(), 64 * kEps);
  EXPECT_LE(w_inv.value(), 64 * kEps);
}

// 3.5: the Jacobian of a random frame on a random body, against soa::jacobian.
TEST(Exercise3_5_FrameJacobian, MatchesLibrary) {
  Random<double> rnd;
  Worst worst("|J - library| / (|J| reach)");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = chain(rnd);
    const soa::State x = random_state(rnd, m);
    const Kinematics kin(m, x);
    const int k = 1 + (i % m.n());
    const soa::Pose frame(rnd.rotation(), rnd.vec3());
    const soa::ex03::Matrix6X J = soa::ex03::frame_jacobian(m, x.theta, k, frame);
    Eigen::Matrix<double, 6, Eigen::Dynamic> ref;
    soa::jacobian(m, x.theta, kin.ws, k, frame, ref);
    ASSERT_EQ(J.cols(), m.nv());
    worst.add((J - ref).norm() / (std::max(1.0, ref.norm()) * (reach(kin.phi) + frame.l().norm())),
              i);
  }
  EXPECT_LE(worst.value(), 32 * kEps);
}

// 3.6: the Coriolis term a(k) of every body of random chains, against soa::coriolis_term (as
// soa::update_velocities computes it).
TEST(Exercise3_6_CoriolisAcceleration, MatchesLibrary) {
  Random<double> rnd;
  Worst worst("max_k |a(k) - library| / scale");
  for (int i = 0; i < kCases; ++i) {
    const soa::Model m = chain(rnd);
    const soa::State x = random_state(rnd, m);
    const Kinematics kin(m, x);
    double res = 0, scale = 1;
    for (int k = 1; k <= m.n(); ++k) {
      const soa::Body& B = m.body(k);
      const soa::Velocity V_parent = k < m.n() ? kin.ws.V[k] : soa::Velocity();
      const soa::Acceleration Hdot_beta =
          B.hinge.H_star_dot_times(x.theta.data() + B.q_offset, x.beta.data() + B.v_offset);
      const soa::Acceleration a =
          soa::ex03::coriolis_acceleration(kin.phi[k - 1], V_parent, kin.dV[k - 1], Hdot_beta);
      res = std::max(res, (a - kin.ws.a[k - 1]).vector().norm());
      scale = std::max(scale, kin.ws.V[k - 1].vector().squaredNorm());
      scale = std::max(scale, V_parent.vector().squaredNorm());
    }
    worst.add(res / (scale * reach(kin.phi)), i);
  }
  EXPECT_LE(worst.value(), 32 * kEps);
}
