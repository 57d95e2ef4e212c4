// Benchmarks of the forward dynamics (lesson 8) and of the mass matrix inverse (lesson 7) on
// revolute chains: the O(N) articulated body algorithm against CRB + LDLT (O(N^3)), and the
// O(N^2) inverse without forming the mass matrix, by the column sweep and by Upsilon (lesson 7,
// section 7), their exponents fitted (MassMatrixInverse_BigO, MassMatrixInverseUpsilon_BigO).
#include <Eigen/Cholesky>

#include "bench_chain.hpp"
#include "soa/chain/mass_matrix_inverse_upsilon.hpp"

namespace {

using soa::bench::Chain;

void ForwardDynamicsABA(benchmark::State& state) {
  const int n = int(state.range(0));
  Chain c(n, true);
  soa::Workspace ws(c.model);
  soa::ForwardDynamics fd(c.model);
  soa::VecX<double> beta_dot(c.model.nv());
  for (auto _ : state) {
    soa::forward_dynamics(c.model, c.x, c.T, c.f_ext, ws, fd, beta_dot);
    benchmark::DoNotOptimize(beta_dot.data());
  }
  soa::bench::report(state, n);
}

// The same with the lean storage (ForwardDynamicsT::lean()): what soa::simulate and `soa
// forward-dynamics` use; same result bit for bit, G(k) and nu(k) (seven numbers a revolute
// body) kept instead of every per-body quantity of the full storage.
void ForwardDynamicsABALean(benchmark::State& state) {
  const int n = int(state.range(0));
  Chain c(n, true);
  soa::Workspace ws(c.model);
  soa::ForwardDynamics fd = soa::ForwardDynamics::lean(c.model);
  soa::VecX<double> beta_dot(c.model.nv());
  for (auto _ : state) {
    soa::forward_dynamics(c.model, c.x, c.T, c.f_ext, ws, fd, beta_dot);
    benchmark::DoNotOptimize(beta_dot.data());
  }
  soa::bench::report(state, n);
}

// M beta_dot = T - C with M from the composite bodies (lesson 5), C from inverse dynamics
// at beta_dot = 0 and Eigen's LDLT.
void ForwardDynamicsCRB(benchmark::State& state) {
  const int n = int(state.range(0));
  Chain c(n, true);
  soa::Workspace ws(c.model);
  std::vector<soa::SpatialInertia> R(n);
  soa::MatX<double> M(n, n);
  soa::VecX<double> C(n), zero = soa::VecX<double>::Zero(n), beta_dot(n);
  Eigen::LDLT<soa::MatX<double>> ldlt(n);
  for (auto _ : state) {
    soa::inverse_dynamics(c.model, c.x, zero, c.f_ext, ws, C);
    soa::mass_matrix_crb(c.model, c.x, ws, R, M);
    ldlt.compute(M);
    beta_dot = c.T - C;
    ldlt.solveInPlace(beta_dot);
    benchmark::DoNotOptimize(beta_dot.data());
  }
  soa::bench::report(state, n);
}

// The O(N^2) mass matrix inverse (lesson 7), kinematics included.
void MassMatrixInverse(benchmark::State& state) {
  const int n = int(state.range(0));
  Chain c(n, false);
  soa::Workspace ws(c.model);
  soa::MassMatrixInverse w(c.model);
  soa::MatX<double> Minv(n, n);
  for (auto _ : state) {
    soa::update_phi(c.model, c.x.theta, ws);
    soa::mass_matrix_inverse(c.model, c.x, ws, w, Minv);
    benchmark::DoNotOptimize(Minv.data());
  }
  state.counters["joints"] = n;
  state.SetComplexityN(n);
}

// The O(N^2) mass matrix inverse built on Upsilon (lesson 7, section 7), kinematics included.
void MassMatrixInverseUpsilon(benchmark::State& state) {
  const int n = int(state.range(0));
  Chain c(n, false);
  soa::Workspace ws(c.model);
  soa::MassMatrixInverseUpsilon w(c.model);
  soa::MatX<double> Minv(n, n);
  for (auto _ : state) {
    soa::update_phi(c.model, c.x.theta, ws);
    soa::mass_matrix_inverse_upsilon(c.model, c.x, ws, w, Minv);
    benchmark::DoNotOptimize(Minv.data());
  }
  state.counters["joints"] = n;
  state.SetComplexityN(n);
}

}  // namespace

BENCHMARK(ForwardDynamicsABA)
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
    ->Arg(1000)
    ->Arg(2000);
BENCHMARK(ForwardDynamicsABALean)->Arg(7)->Arg(50)->Arg(200)->Arg(1000);
BENCHMARK(ForwardDynamicsCRB)
    ->Arg(1)
    ->Arg(2)
    ->Arg(4)
    ->Arg(7)
    ->Arg(12)
    ->Arg(20)
    ->Arg(50)
    ->Arg(100)
    ->Arg(200);
BENCHMARK(MassMatrixInverse)->Arg(7)->Arg(50)->Arg(200)->Arg(1000);
BENCHMARK(MassMatrixInverse)->RangeMultiplier(2)->Range(1, 1024)->Complexity();
BENCHMARK(MassMatrixInverseUpsilon)->Arg(7)->Arg(1000);
BENCHMARK(MassMatrixInverseUpsilon)->RangeMultiplier(2)->Range(1, 1024)->Complexity();
