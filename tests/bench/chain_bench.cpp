// Benchmarks of the O(N) Newton-Euler inverse dynamics (lesson 4) on revolute chains:
// the time per joint must stay flat as N grows. Variants show what a scene pays for the
// parts it uses: gravity, external forces, motion (at rest the velocity terms are skipped).
// And the composite-body mass matrix (lesson 5), O(N^2): Google Benchmark fits the exponent
// (MassMatrixCRB_BigO).
#include <benchmark/benchmark.h>

#include <random>

#include "soa/chain.hpp"

namespace {

// A revolute chain of n links, alternating axes, with a random state (fixed seed).
struct Chain {
  soa::Model model;
  soa::State x;
  soa::VecX<double> beta_dot;
  soa::ExternalForces<double> f_ext;

  Chain(int n, bool gravity) {
    std::mt19937 g(11);
    std::normal_distribution<double> N;
    std::vector<soa::Body> bodies(n);
    for (int i = 0; i < n; ++i) {
      soa::Body& b = bodies[i];
      b.name = "link" + std::to_string(i);
      b.M = soa::SpatialInertia::from_cm(
          1.0 + 0.1 * (i % 3), soa::Vec3<double>(0.15, 0, 0.01),
          soa::Mat3<double>(soa::Vec3<double>(0.01, 0.02, 0.02).asDiagonal()));
      b.placement =
          soa::Pose(soa::Mat3<double>::Identity(), soa::Vec3<double>(i == 0 ? 0 : 0.3, 0, 0));
      b.hinge.type = soa::HingeType::Revolute;
      b.hinge.axis = i % 2 ? soa::Vec3<double>::UnitY() : soa::Vec3<double>::UnitZ();
    }
    model = soa::Model::from_base_first(bodies);
    if (gravity) model.gravity = soa::Vec3<double>(0, 0, -9.81);
    x = soa::State::rest(model);
    beta_dot.resize(model.nv());
    for (int i = 0; i < model.nq(); ++i) x.theta[i] = N(g);
    for (int i = 0; i < model.nv(); ++i) x.beta[i] = N(g), beta_dot[i] = N(g);
  }
};

void report(benchmark::State& state, int n) {
  state.counters["joints"] = n;
  state.counters["ns_per_joint"] =
      benchmark::Counter(double(n) * double(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  // kIsRate | kInvert gives seconds per joint; the JSON reader scales it to ns.
}

void InverseDynamics(benchmark::State& state) {
  const int n = int(state.range(0));
  Chain c(n, true);
  soa::Workspace ws(c.model);
  soa::VecX<double> T(c.model.nv());
  for (auto _ : state) {
    soa::inverse_dynamics(c.model, c.x, c.beta_dot, c.f_ext, ws, T);
    benchmark::DoNotOptimize(T.data());
  }
  report(state, n);
}

// The same chain without gravity: no gravity pass at all.
void InverseDynamicsNoGravity(benchmark::State& state) {
  const int n = int(state.range(0));
  Chain c(n, false);
  soa::Workspace ws(c.model);
  soa::VecX<double> T(c.model.nv());
  for (auto _ : state) {
    soa::inverse_dynamics(c.model, c.x, c.beta_dot, c.f_ext, ws, T);
    benchmark::DoNotOptimize(T.data());
  }
  report(state, n);
}

// With an (explicit, all-zero) external force on every body: the term a scene without
// external forces does not pay for.
void InverseDynamicsExternalForces(benchmark::State& state) {
  const int n = int(state.range(0));
  Chain c(n, true);
  c.f_ext.assign(n, soa::Force::Zero());
  soa::Workspace ws(c.model);
  soa::VecX<double> T(c.model.nv());
  for (auto _ : state) {
    soa::inverse_dynamics(c.model, c.x, c.beta_dot, c.f_ext, ws, T);
    benchmark::DoNotOptimize(T.data());
  }
  report(state, n);
}

// At rest (beta = 0): velocities, Coriolis and gyroscopic terms are skipped.
void InverseDynamicsAtRest(benchmark::State& state) {
  const int n = int(state.range(0));
  Chain c(n, true);
  c.x.beta.setZero();
  soa::Workspace ws(c.model);
  soa::VecX<double> T(c.model.nv());
  for (auto _ : state) {
    soa::inverse_dynamics(c.model, c.x, c.beta_dot, c.f_ext, ws, T);
    benchmark::DoNotOptimize(T.data());
  }
  report(state, n);
}

// The O(N^2) mass matrix from composite rigid body inertias (lesson 5).
void MassMatrixCRB(benchmark::State& state) {
  const int n = int(state.range(0));
  Chain c(n, false);
  soa::Workspace ws(c.model);
  std::vector<soa::SpatialInertia> R(n);
  soa::MatX<double> M(n, n);
  soa::update_phi(c.model, c.x.theta, ws);
  for (auto _ : state) {
    soa::mass_matrix_crb(c.model, c.x, ws, R, M);
    benchmark::DoNotOptimize(M.data());
  }
  state.counters["joints"] = n;
  state.SetComplexityN(n);
}

}  // namespace

BENCHMARK(MassMatrixCRB)->RangeMultiplier(2)->Range(1, 1024)->Complexity();
BENCHMARK(InverseDynamics)
    ->Arg(1)
    ->Arg(2)
    ->Arg(4)
    ->Arg(7)
    ->Arg(12)
    ->Arg(20)
    ->Arg(50)
    ->Arg(100)
    ->Arg(200)
    ->Arg(500)
    ->Arg(1000);
BENCHMARK(InverseDynamicsNoGravity)->Arg(7)->Arg(100)->Arg(1000);
BENCHMARK(InverseDynamicsExternalForces)->Arg(7)->Arg(100)->Arg(1000);
BENCHMARK(InverseDynamicsAtRest)->Arg(7)->Arg(100)->Arg(1000);
