// Benchmarks of the O(N) Newton-Euler inverse dynamics (lesson 4) on revolute chains:
// the time per joint must stay flat as N grows. Variants show what a scene pays for the
// parts it uses: gravity, external forces, motion (at rest the velocity terms are skipped).
// And the composite-body mass matrix (lesson 5), O(N^2): Google Benchmark fits the exponent
// (MassMatrixCRB_BigO). And the hinge angles' sines and cosines, in one batch or one by one.
#include <cmath>

#include "bench_chain.hpp"

namespace {

using soa::bench::Chain;

// What the chain of a variant uses.
enum Variant { kFull, kNoGravity, kExternalForces, kAtRest };

template <Variant v>
void InverseDynamics(benchmark::State& state) {
  const int n = int(state.range(0));
  Chain c(n, v != kNoGravity);
  if (v == kExternalForces) c.f_ext.assign(n, soa::Force::Zero());  // explicit zeros
  if (v == kAtRest) c.x.beta.setZero();  // velocities, Coriolis, gyroscopic terms skipped
  soa::Workspace ws(c.model);
  soa::VecX<double> T(c.model.nv());
  for (auto _ : state) {
    soa::inverse_dynamics(c.model, c.x, c.beta_dot, c.f_ext, ws, T);
    benchmark::DoNotOptimize(T.data());
  }
  soa::bench::report(state, n);
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

// The same mass matrix with the products hoisted to the inertial frame (lesson 5,
// soa::mass_matrix_inertial): one independent 6-term dot product per entry.
void MassMatrixInertial(benchmark::State& state) {
  const int n = int(state.range(0));
  Chain c(n, false);
  soa::Workspace ws(c.model);
  soa::MassMatrixInertial w(c.model);
  soa::MatX<double> M(n, n);
  soa::update_phi(c.model, c.x.theta, ws);
  for (auto _ : state) {
    soa::mass_matrix_inertial(c.model, c.x, ws, w, M);
    benchmark::DoNotOptimize(M.data());
  }
  state.counters["joints"] = n;
  state.SetComplexityN(n);
}

// The sines and cosines of the hinge angles, per joint: soa::hinge_sin_cos() (SLEEF's vector
// sincos in one batch), against one std::sin and one std::cos a joint (glibc), as the
// recursions took them before.
template <bool batched>
void HingeSinCos(benchmark::State& state) {
  const int n = int(state.range(0));
  Chain c(n, false);
  soa::Workspace ws(c.model);
  const double* theta = c.x.theta.data();
  for (auto _ : state) {
    if constexpr (batched) {
      soa::hinge_sin_cos(c.model, theta, ws);
    } else {
      for (int i = 0; i < n; ++i) {
        ws.hinge_sin[std::size_t(i)] = std::sin(theta[i]);
        ws.hinge_cos[std::size_t(i)] = std::cos(theta[i]);
      }
    }
    benchmark::DoNotOptimize(ws.hinge_sin.data());
    benchmark::DoNotOptimize(ws.hinge_cos.data());
    benchmark::ClobberMemory();
  }
  soa::bench::report(state, n);
}

}  // namespace

BENCHMARK_TEMPLATE(HingeSinCos, true)->Name("HingeSinCosBatch")->Arg(7)->Arg(50)->Arg(1000);
BENCHMARK_TEMPLATE(HingeSinCos, false)->Name("HingeSinCosStd")->Arg(7)->Arg(50)->Arg(1000);
BENCHMARK(MassMatrixCRB)->Arg(7)->Arg(50)->Arg(200)->Arg(1000);
BENCHMARK(MassMatrixCRB)->RangeMultiplier(2)->Range(1, 1024)->Complexity();
BENCHMARK(MassMatrixInertial)->Arg(7)->Arg(50)->Arg(200)->Arg(1000);
BENCHMARK(MassMatrixInertial)->RangeMultiplier(2)->Range(1, 1024)->Complexity();
BENCHMARK_TEMPLATE(InverseDynamics, kFull)
    ->Name("InverseDynamics")
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
BENCHMARK_TEMPLATE(InverseDynamics, kNoGravity)
    ->Name("InverseDynamicsNoGravity")
    ->Arg(7)
    ->Arg(100)
    ->Arg(1000);
BENCHMARK_TEMPLATE(InverseDynamics, kExternalForces)
    ->Name("InverseDynamicsExternalForces")
    ->Arg(7)
    ->Arg(100)
    ->Arg(1000);
BENCHMARK_TEMPLATE(InverseDynamics, kAtRest)
    ->Name("InverseDynamicsAtRest")
    ->Arg(7)
    ->Arg(100)
    ->Arg(1000);
