// The O(N) and O(N^2) algorithms allocate nothing per call once their workspaces are sized
// (the developers' guide): global operator new is counted around each call.
#include <gtest/gtest.h>

#include <complex>
#include <cstdlib>
#include <vector>

#include "count_allocations.hpp"
#include "property.hpp"
#include "random_chain.hpp"
#include "soa/chain.hpp"
#include "soa/sim.hpp"

namespace {

using soa::test::Random;

using soa::test::allocations_in;

TEST(dynamics_Allocation, NoneInTheRecursions) {
  // The counter sees allocations at all (else this test could not fail).
  ASSERT_GT(allocations_in([] { soa::test::allocate_something(); }), 0);
  Random<double> rnd(43);
  soa::test::ChainOptions opt;
  opt.gravity = true;
  opt.springs = true;
  for (int i = 0; i < 20; ++i) {
    const soa::Model m = soa::test::random_chain(rnd, 1 + i % 12, opt);
    const soa::State x = soa::test::random_state(rnd, m);
    const soa::VecX<double> v = soa::test::random_vector(rnd, m.nv());
    const soa::ExternalForces<double> f_ext = soa::test::random_forces(rnd, m);
    soa::Workspace ws(m);
    soa::VecX<double> out(m.nv());
    EXPECT_EQ(allocations_in([&] { soa::inverse_dynamics(m, x, v, f_ext, ws, out); }), 0)
        << "inverse_dynamics, case " << i;
    soa::ForwardDynamics fd(m);
    EXPECT_EQ(allocations_in([&] { soa::forward_dynamics(m, x, v, f_ext, ws, fd, out); }), 0)
        << "forward_dynamics, case " << i;
    soa::ForwardDynamics lean = soa::ForwardDynamics::lean(m);
    EXPECT_EQ(allocations_in([&] { soa::forward_dynamics(m, x, v, f_ext, ws, lean, out); }), 0)
        << "forward_dynamics (lean storage), case " << i;
    soa::Workspace lazy = soa::Workspace::lazy();  // sized by its first use, then none
    EXPECT_EQ(allocations_in([&] { soa::forward_dynamics(m, x, v, f_ext, lazy, lean, out); }), 0)
        << "forward_dynamics (lazy workspace), case " << i;
    EXPECT_EQ(allocations_in([&] { soa::inverse_dynamics(m, x, v, f_ext, lazy, out); }), 0)
        << "inverse_dynamics (lazy workspace), case " << i;
    soa::MassMatrixInverse w(m);
    soa::MatX<double> M(m.nv(), m.nv());
    EXPECT_EQ(allocations_in([&] { soa::mass_matrix_inverse(m, x, ws, w, M); }), 0)
        << "mass_matrix_inverse, case " << i;
    std::vector<soa::SpatialInertia> R(std::size_t(m.n()));
    EXPECT_EQ(allocations_in([&] { soa::mass_matrix_crb(m, x, ws, R, M); }), 0)
        << "mass_matrix_crb, case " << i;
    soa::MassMatrixInertial mi(m);
    EXPECT_EQ(allocations_in([&] { soa::mass_matrix_inertial(m, x, ws, mi, M); }), 0)
        << "mass_matrix_inertial, case " << i;
    soa::Articulated art(m);
    EXPECT_EQ(allocations_in([&] { soa::articulated_inertias(m, x, ws, art); }), 0)
        << "articulated_inertias, case " << i;
  }
}

// The implicit integrators' steps: nothing per step once the first step has sized the
// workspace, the Jacobian and its factorization included, on chains of every hinge type with
// gravity and springs.
TEST(dynamics_Allocation, NoneInAnImplicitStep) {
  Random<double> rnd(44);
  soa::test::ChainOptions opt;
  opt.gravity = true;
  opt.springs = true;
  opt.all_hinge_types = true;
  for (int i = 0; i < 10; ++i) {
    const soa::Model m = soa::test::random_chain(rnd, 1 + i % 6, opt);
    const soa::State x0 = soa::test::random_state(rnd, m);
    soa::ChainSystem sys(m, {});
    soa::Stepper stepper(sys);
    stepper.set_tolerance(1e-6);
    soa::State x1 = x0;
    soa::VecX<double> err;
    double h = 1e-3;
    bool ok = true;
    // Each call with another h refactorizes; every few a Jacobian may be refreshed.
    EXPECT_EQ(allocations_in([&] { ok = stepper.esdirk(0.0, h *= 1.1, x0, x1, err) && ok; }), 0)
        << "esdirk, case " << i;
    EXPECT_TRUE(ok) << "case " << i;
    // radau5: steps that follow each other (the last step's polynomial starts Newton), a
    // retried start, a new step size each time
    soa::Stepper radau(sys);
    soa::State xa = x0, xb = x0;
    double t = 0, hr = 1e-3;
    EXPECT_EQ(allocations_in([&] {
                for (int k = 0; k < 3; ++k) {
                  ok = radau.radau5(t, hr, xa, xb, err) && ok;
                  ok = radau.radau5(t, hr * 0.5, xa, xb, err) && ok;  // retried smaller
                  t += hr * 0.5, hr *= 1.3;
                  xa = xb;
                }
              }),
              0)
        << "radau5, case " << i;
    EXPECT_TRUE(ok) << "case " << i;
    soa::Stepper midpoint(sys);
    EXPECT_EQ(allocations_in([&] { ok = midpoint.implicit_midpoint(0.0, 1e-3, x0, x1) && ok; }), 0)
        << "implicit_midpoint, case " << i;
    EXPECT_TRUE(ok) << "case " << i;
  }
}

// The variational step (implicit midpoint in (theta, p)): nothing per step once sized, on
// chains of the hinges whose coordinates add, with gravity, springs, dampers and external
// forces; its O(N) parts, p and dT/dtheta, M^-1 T and p_dot, nothing per call.
TEST(dynamics_Allocation, NoneInAVariationalStep) {
  Random<double> rnd(45);
  soa::test::ChainOptions opt;
  opt.gravity = true;
  opt.springs = true;
  const soa::HingeType types[] = {soa::HingeType::Revolute, soa::HingeType::Prismatic,
                                  soa::HingeType::Helical, soa::HingeType::Universal};
  for (int i = 0; i < 10; ++i) {
    std::vector<soa::Body> bodies;
    for (int j = 0; j < 1 + i % 6; ++j)
      bodies.push_back(soa::test::detail::random_body(rnd, j, types[(i + j) % 4], opt));
    const soa::Model m = soa::test::detail::finish_chain(std::move(bodies), opt);
    const soa::State x0 = soa::test::random_state(rnd, m);
    soa::ChainSystem sys(m, soa::test::random_forces(rnd, m));
    soa::VecX<double> p(m.nv()), g(m.nv()), b(m.nv());
    soa::Workspace ws(m);
    EXPECT_EQ(allocations_in([&] { soa::kinetic_gradient(m, x0, ws, p, g); }), 0)
        << "kinetic_gradient, case " << i;
    EXPECT_EQ(allocations_in([&] { sys.velocity(x0, p, b); }), 0) << "velocity, case " << i;
    EXPECT_EQ(allocations_in([&] { sys.momentum_rate(0.0, x0, g); }), 0)
        << "momentum_rate, case " << i;
    soa::Stepper stepper(sys);
    soa::State x1 = x0;
    bool ok = true;
    EXPECT_EQ(allocations_in([&] { ok = stepper.variational(0.0, 1e-3, x0, x1) && ok; }), 0)
        << "variational, case " << i;
    EXPECT_TRUE(ok) << "case " << i;
  }
}

// The stiffness monitor of soa::simulate: an Arnoldi estimate of the dominant eigenvalue, first
// and later checks, allocates nothing once built.
TEST(dynamics_Allocation, NoneInAStiffnessCheck) {
  Random<double> rnd(45);
  soa::test::ChainOptions opt;
  opt.gravity = true;
  opt.springs = true;
  opt.all_hinge_types = true;
  for (int i = 0; i < 10; ++i) {
    const soa::Model m = soa::test::random_chain(rnd, 1 + i % 6, opt);
    const soa::State x = soa::test::random_state(rnd, m);
    soa::ChainSystem sys(m, {});
    soa::Stepper stepper(sys);
    soa::DominantEigenvalueT<double> dominant(m.nv());
    std::complex<double> l;
    EXPECT_EQ(allocations_in([&] { l = dominant(stepper, 0.0, x, 24); }), 0) << "first, case " << i;
    EXPECT_EQ(allocations_in([&] { l = dominant(stepper, 0.0, x, 4); }), 0) << "later, case " << i;
    EXPECT_GT(std::abs(l), 0) << "case " << i;
  }
}

}  // namespace
