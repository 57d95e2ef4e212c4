/// \file
/// "A part the scene leaves out costs nothing" (lesson 4): inverse_dynamics() skips the
/// external forces when there are none, gravity when it is zero, the velocity terms at
/// rest and the springs of hinges without any; the skipped result must be the result with
/// the part present and zero. On random chains of up to 12 bodies with every hinge type:
/// - an empty f_ext list gives exactly (EXPECT_EQ, 0 ulp) the T and f of a list of zero
///   forces;
/// - gravity never set, set to (0, 0, 0) and to (-0, -0, -0) give exactly the same T;
/// - at rest (beta = 0) the velocities and Coriolis terms are exactly zero and T is the
///   operator form M beta_dot + C (C = H phi (M phi* a + b) with a = 0 but for gravity), to
///   the tolerance of operators_test.cpp;
/// - springs and dampers of zero stiffness and damping, about any rest position, give
///   exactly the T of a chain without them; and non-zero ones add exactly their hinge force
///   to T: T_springs - T_none = k delta + c beta (delta as in BodyT), to rounding.
#include "chain_support.hpp"

namespace soa::test {
namespace {

constexpr int kMaxBodies = 12;

/// The largest |a_i - b_i| (0 when the vectors are bitwise equal but for the sign of 0).
double max_difference(const VecX<double>& a, const VecX<double>& b) {
  return a.size() == 0 ? 0.0 : double((a - b).cwiseAbs().maxCoeff());
}

/// A random chain with gravity, springs and dampers, every hinge type.
Model full_chain(Random<double>& rnd, int i) {
  ChainOptions opt;
  opt.gravity = true;
  opt.springs = true;
  return random_chain(rnd, chain_size(i, kMaxBodies), opt);
}

TEST(chain_SkippedParts, NoExternalForcesEqualsZeroForces) {
  Random<double> rnd;
  Worst wT("|T(no f_ext) - T(zero forces)|"), wf("|f(no f_ext) - f(zero forces)|");
  for (int i = 0; i < kCases; ++i) {
    const Model m = full_chain(rnd, i);
    const State x = random_state(rnd, m);
    const VecX<double> beta_dot = random_vector(rnd, m.nv());
    const ExternalForces<double> zeros(m.n(), Force());
    Workspace ws1(m), ws2(m);
    VecX<double> T1(m.nv()), T2(m.nv());
    inverse_dynamics(m, x, beta_dot, {}, ws1, T1);
    inverse_dynamics(m, x, beta_dot, zeros, ws2, T2);
    wT.add(max_difference(T1, T2), i);
    wf.add(max_difference(stack(ws1.f), stack(ws2.f)), i);
    EXPECT_EQ(T1, T2) << "case " << i;
  }
  EXPECT_EQ(wT.value(), 0.0);
  EXPECT_EQ(wf.value(), 0.0);
}

TEST(chain_SkippedParts, NoGravityEqualsZeroGravity) {
  Random<double> rnd;
  Worst w("|T(gravity unset) - T(gravity 0 or -0)|");
  for (int i = 0; i < kCases; ++i) {
    Model m = random_chain(rnd, chain_size(i, kMaxBodies));  // gravity never set
    const State x = random_state(rnd, m);
    const VecX<double> beta_dot = random_vector(rnd, m.nv());
    const ExternalForces<double> f_ext = random_forces(rnd, m);
    Workspace ws(m);
    VecX<double> T0(m.nv()), T1(m.nv()), T2(m.nv());
    inverse_dynamics(m, x, beta_dot, f_ext, ws, T0);
    m.gravity = Vec3<double>(0, 0, 0);
    inverse_dynamics(m, x, beta_dot, f_ext, ws, T1);
    m.gravity = Vec3<double>(-0.0, -0.0, -0.0);
    inverse_dynamics(m, x, beta_dot, f_ext, ws, T2);
    w.add(std::max(max_difference(T0, T1), max_difference(T0, T2)), i);
  }
  EXPECT_EQ(w.value(), 0.0);
}

TEST(chain_SkippedParts, AtRestEqualsOperatorForm) {
  Random<double> rnd;
  Worst wV("|V|, |a| at rest"), wT("T at rest = M beta_dot + C [N eps]");
  for (int i = 0; i < kCases; ++i) {
    ChainOptions opt;
    opt.gravity = true;
    const Model m = random_chain(rnd, chain_size(i, kMaxBodies), opt);
    const int n = m.n();
    State x = random_state(rnd, m);
    x.beta.setZero();
    const VecX<double> beta_dot = random_vector(rnd, m.nv());
    const ExternalForces<double> f_ext = random_forces(rnd, m);
    Workspace ws(m);
    VecX<double> T(m.nv());
    inverse_dynamics(m, x, beta_dot, f_ext, ws, T);
    wV.add(std::max(stack(ws.V).cwiseAbs().maxCoeff(), stack(ws.a).cwiseAbs().maxCoeff()), i);

    const Operators op = Operators::build(m, x, f_ext);
    const double nphi = op.phi.norm(), nH = op.H.norm(), nM = op.M.norm();
    const double s = nH * nphi * (nM * nphi * (nH * beta_dot.norm() + op.a.norm()) + op.b.norm());
    wT.add(residual(T, op.mass_matrix() * beta_dot + op.bias(), s) / (6 * n * eps<double>()), i);
  }
  EXPECT_EQ(wV.value(), 0.0);
  EXPECT_LE(wT.value(), 2.0);  // kTol of operators_test.cpp
}

TEST(chain_SkippedParts, ZeroSpringsEqualNone) {
  Random<double> rnd;
  Worst w0("|T(k = c = 0, any rest) - T(no springs)|"),
      wS("T(springs) - T(none) = k delta + c beta");
  for (int i = 0; i < kCases; ++i) {
    ChainOptions opt;
    opt.gravity = true;
    const Model m = random_chain(rnd, chain_size(i, kMaxBodies), opt);  // no springs
    Model zero = m, springs = m;
    for (int k = 1; k <= m.n(); ++k) {
      for (int j = 0; j < m.body(k).rest.size(); ++j) {
        zero.body(k).rest[j] = rnd.normal();
        springs.body(k).rest[j] = zero.body(k).rest[j];
      }
      zero.body(k).stiffness = zero.body(k).damping = 0;
      springs.body(k).stiffness = rnd.uniform(0.5, 5);
      springs.body(k).damping = rnd.uniform(0, 1);
    }
    const State x = random_state(rnd, m);
    const VecX<double> beta_dot = random_vector(rnd, m.nv());
    const ExternalForces<double> f_ext = random_forces(rnd, m);
    Workspace ws(m);
    VecX<double> T(m.nv()), T0(m.nv()), TS(m.nv());
    inverse_dynamics(m, x, beta_dot, f_ext, ws, T);
    inverse_dynamics(zero, x, beta_dot, f_ext, ws, T0);
    inverse_dynamics(springs, x, beta_dot, f_ext, ws, TS);
    w0.add(max_difference(T, T0), i);
    EXPECT_FALSE(zero.has_springs());

    // The hinge force the springs and dampers need from the actuators: k delta + c beta.
    VecX<double> expected(m.nv());
    for (int k = 1; k <= m.n(); ++k) {
      const Body& B = springs.body(k);
      const double* th = x.theta.data() + B.q_offset;
      const int nv = B.hinge.nv();
      VecX<double> delta(nv);
      const Pose Tk = B.hinge.transform(th);
      if (B.hinge.type == HingeType::Spherical) {
        delta = log_so3<double>(Tk.R());
      } else if (B.hinge.type == HingeType::Free) {
        delta << log_so3<double>(Tk.R()), Tk.R().transpose() * Tk.l();
      } else {
        delta = Eigen::Map<const VecX<double>>(th, nv) - B.rest;
      }
      expected.segment(B.v_offset, nv) =
          B.stiffness * delta + B.damping * x.beta.segment(B.v_offset, nv);
    }
    const double s = std::max({1.0, double(T.norm()), double(TS.norm()), double(expected.norm())});
    wS.add(residual(TS - T, expected, s), i);
  }
  EXPECT_EQ(w0.value(), 0.0);
  EXPECT_LE(wS.value(), 64 * eps<double>());
}

}  // namespace
}  // namespace soa::test
