/// \file
/// Counts every heap allocation of the program: replaces the global operator new (include
/// it in exactly one file of a test or benchmark program). The recursions must allocate
/// nothing per call; soa::test::allocations() before and after a call tells.
#pragma once

#include <atomic>
#include <cstdlib>
#include <new>

namespace soa::test {
inline std::atomic<long> g_allocations{0};
/// The number of allocations so far.
inline long allocations() {
  return g_allocations.load();
}
}  // namespace soa::test

void* operator new(std::size_t n) {
  ++soa::test::g_allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
