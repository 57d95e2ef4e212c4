// The benchmark chain (soa::bench::Chain, lib/support/benchmark_chain.hpp) and the counters of
// a benchmark on it.
#pragma once

#include <benchmark/benchmark.h>

#include "benchmark_chain.hpp"

namespace soa::bench {

/// Counters: the chain's size and the time per joint.
inline void report(benchmark::State& state, int n) {
  state.counters["joints"] = n;
  state.counters["ns_per_joint"] =
      benchmark::Counter(double(n) * double(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  // kIsRate | kInvert gives seconds per joint; the JSON reader scales it to ns.
}

}  // namespace soa::bench
