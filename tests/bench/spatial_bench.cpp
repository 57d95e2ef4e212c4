// Benchmarks of the spatial primitives of lesson 1, in float, double and long double:
// phi applied to a force, phi* to a velocity, phi composed, the inertia moved by phi
// (parallel axis theorem), and the 6x6 matrix forms they replace.
#include <benchmark/benchmark.h>

#include <random>

#include "soa/soa.hpp"

namespace {

template <class S>
struct Inputs {
  soa::PhiT<S> phi, psi;
  soa::ForceT<S> f;
  soa::VelocityT<S> V;
  soa::SpatialInertiaT<S> M;
  Inputs() {
    std::mt19937 g(7);
    std::normal_distribution<double> n;
    auto v3 = [&] { return soa::Vec3<S>(S(n(g)), S(n(g)), S(n(g))); };
    phi = soa::PhiT<S>(soa::exp_so3<S>(v3()), v3());
    psi = soa::PhiT<S>(soa::exp_so3<S>(v3()), v3());
    f = soa::ForceT<S>(v3(), v3());
    V = soa::VelocityT<S>(v3(), v3());
    M = soa::SpatialInertiaT<S>::from_cm(S(2), v3(),
                                         soa::Mat3<S>(soa::Vec3<S>(1, 2, 2.5).asDiagonal()));
  }
};

template <class S>
void PhiApply(benchmark::State& state) {
  Inputs<S> in;
  for (auto _ : state) {
    benchmark::DoNotOptimize(in.f = in.phi.apply(in.f));
  }
}
template <class S>
void PhiTransposeApply(benchmark::State& state) {
  Inputs<S> in;
  for (auto _ : state) {
    benchmark::DoNotOptimize(in.V = in.phi.transpose_apply(in.V));
  }
}
template <class S>
void PhiCompose(benchmark::State& state) {
  Inputs<S> in;
  for (auto _ : state) {
    benchmark::DoNotOptimize(in.psi = in.phi * in.psi);
    benchmark::ClobberMemory();
  }
}
template <class S>
void InertiaTransform(benchmark::State& state) {
  Inputs<S> in;
  for (auto _ : state) {
    auto M = soa::transform(in.phi, in.M);
    benchmark::DoNotOptimize(M);
  }
}
// The teaching forms: the dense 6x6 products the recursions avoid.
template <class S>
void PhiApplyDense6x6(benchmark::State& state) {
  Inputs<S> in;
  const soa::Mat6<S> P = in.phi.matrix();
  soa::Vec6<S> f = in.f.vector();
  for (auto _ : state) {
    benchmark::DoNotOptimize(f = P * f);
  }
}
template <class S>
void InertiaTransformDense6x6(benchmark::State& state) {
  Inputs<S> in;
  const soa::Mat6<S> P = in.phi.matrix(), M = in.M.matrix();
  for (auto _ : state) {
    soa::Mat6<S> R = P * M * P.transpose();
    benchmark::DoNotOptimize(R);
  }
}

}  // namespace

#define SOA_BENCH_ALL(fn)         \
  BENCHMARK_TEMPLATE(fn, float);  \
  BENCHMARK_TEMPLATE(fn, double); \
  BENCHMARK_TEMPLATE(fn, long double)

SOA_BENCH_ALL(PhiApply);
SOA_BENCH_ALL(PhiTransposeApply);
SOA_BENCH_ALL(PhiCompose);
SOA_BENCH_ALL(InertiaTransform);
SOA_BENCH_ALL(PhiApplyDense6x6);
SOA_BENCH_ALL(InertiaTransformDense6x6);
