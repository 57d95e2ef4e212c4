/// \file
/// Counts every heap allocation of the program: replaces the global operator new (include
/// it in exactly one file of a test or benchmark program). The recursions must allocate
/// nothing per call; soa::test::allocations() before and after a call tells.
#pragma once

#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>

namespace soa::test {
inline std::atomic<long> g_allocations{0};
/// The number of allocations so far.
inline long allocations() {
  return g_allocations.load();
}
/// Something that allocates, out of the optimizer's sight: allocations_in() of it is not 0,
/// which shows that the counter sees allocations (else a test of none could not fail).
__attribute__((noinline)) inline void allocate_something() {
  std::vector<double>* v = new std::vector<double>(100);
  delete v;
}
/// The allocations made by \p f, run twice (the first call may size its outputs).
template <class F>
long allocations_in(F&& f) {
  f();
  const long before = allocations();
  f();
  return allocations() - before;
}
}  // namespace soa::test

void* operator new(std::size_t n) {
  ++soa::test::g_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
// GCC takes free() in the replaced operator delete for a new/delete mismatch once it has
// inlined both: it is the replacement's own pair (malloc/free).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
#pragma GCC diagnostic pop
