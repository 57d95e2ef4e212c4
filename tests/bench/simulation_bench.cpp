// "Pay only for what the scene uses": the forward dynamics (lesson 8) and one simulation step
// (soa::StepperT::rk4, ::symplectic_euler on a soa::ChainSystemT) on the
// benchmark chain of bench_chain.hpp, N = 7 and 50, with every part of a scene ("full":
// gravity, an external force on every body, a spring and damper on every hinge, random
// rates), then each part left out in turn, all of them ("bare"), and each part present as
// explicit zeros (gravity (0, 0, 0), a list of zero forces, stiffness and damping 0). Names
// read as a table: BM_ForwardDynamics/<configuration>/<N>. The counter allocs_per_call
// counts global operator new inside the timed loop (0: buffers are allocated once).
//
// What decides each skip: ModelT::has_gravity() (|g|^2 > 0), an empty ExternalForces list,
// a hinge's stiffness and damping both zero, beta exactly zero (at rest). Gravity (0, 0, 0)
// and stiffness = damping = 0 are therefore the left-out path itself (the model's defaults
// are zero); a list of zero forces is not: it runs the subtraction of each force. At rest
// only the first stage of an RK4 step skips the velocity terms (the later stages move).
#include <cstdlib>
#include <random>
#include <string>

#include "../support/count_allocations.hpp"
#include "bench_chain.hpp"
#include "soa/sim.hpp"

namespace {

using soa::bench::Chain;

/// Which parts of the scene a configuration uses, and which it gives as explicit zeros.
struct Config {
  const char* name;
  bool gravity, forces, springs, moving;
  bool zero_gravity = false, zero_forces = false, zero_springs = false;
};

const Config kConfigs[] = {
    {"full", true, true, true, true},
    {"no_gravity", false, true, true, true},
    {"no_fext", true, false, true, true},
    {"no_springs", true, true, false, true},
    {"at_rest", true, true, true, false},
    {"bare", false, false, false, false},
    {"zero_gravity", false, true, true, true, true, false, false},
    {"zero_fext", true, false, true, true, false, true, false},
    {"zero_springs", true, true, false, true, false, false, true},
};

/// The benchmark chain of \p n links set up as \p cfg says.
struct Scene : Chain {
  Scene(int n, const Config& cfg) : Chain(n, cfg.gravity) {
    if (cfg.zero_gravity) model.gravity = soa::Vec3<double>(0, 0, 0);
    std::mt19937 g(12);
    std::normal_distribution<double> N;
    for (int k = 1; k <= n; ++k) {
      soa::Body& B = model.body(k);
      B.stiffness = cfg.springs ? 2.0 : 0.0;  // zero_springs: set, to zero
      B.damping = cfg.springs ? 0.3 : 0.0;
      B.rest[0] = 0.1 * N(g);
    }
    if (cfg.forces)
      for (int k = 1; k <= n; ++k)
        f_ext.push_back(
            soa::Force(soa::Vec3<double>(N(g), N(g), N(g)), soa::Vec3<double>(N(g), N(g), N(g))));
    if (cfg.zero_forces) f_ext.assign(std::size_t(n), soa::Force::Zero());
    if (!cfg.moving) x.beta.setZero();
  }
};

/// Allocations per iteration of the timed loop, as a counter.
void report(benchmark::State& state, int n, long allocations) {
  soa::bench::report(state, n);
  state.counters["allocs_per_call"] = double(allocations) / double(state.iterations());
}

void ForwardDynamics(benchmark::State& state, Config cfg) {
  const int n = int(state.range(0));
  Scene c(n, cfg);
  soa::Workspace ws(c.model);
  soa::ForwardDynamics fd(c.model);
  soa::VecX<double> beta_dot(c.model.nv());
  const long before = soa::test::allocations();
  for (auto _ : state) {
    soa::forward_dynamics(c.model, c.x, c.T, c.f_ext, ws, fd, beta_dot);
    benchmark::DoNotOptimize(beta_dot.data());
  }
  report(state, n, soa::test::allocations() - before);
}

/// One step from the same state each iteration (no control law: T = 0).
template <void (soa::StepperT<double>::*step)(double, double, const soa::State&, soa::State&)>
void Step(benchmark::State& state, Config cfg) {
  const int n = int(state.range(0));
  Scene c(n, cfg);
  soa::ChainSystem sys(c.model, c.f_ext);
  soa::Stepper stepper(sys);
  soa::State x1 = c.x;
  const long before = soa::test::allocations();
  for (auto _ : state) {
    (stepper.*step)(0.0, 1e-3, c.x, x1);
    benchmark::DoNotOptimize(x1.beta.data());
    benchmark::DoNotOptimize(x1.theta.data());
  }
  report(state, n, soa::test::allocations() - before);
}

const int kRegistered = [] {
  for (const Config& cfg : kConfigs) {
    const std::string name = std::string("/") + cfg.name;
    benchmark::RegisterBenchmark(("BM_ForwardDynamics" + name).c_str(), ForwardDynamics, cfg)
        ->Arg(7)
        ->Arg(50);
    benchmark::RegisterBenchmark(("BM_StepRK4" + name).c_str(), Step<&soa::Stepper::rk4>, cfg)
        ->Arg(7)
        ->Arg(50);
    benchmark::RegisterBenchmark(("BM_StepSymplecticEuler" + name).c_str(),
                                 Step<&soa::Stepper::symplectic_euler>, cfg)
        ->Arg(7)
        ->Arg(50);
  }
  return 0;
}();

}  // namespace
