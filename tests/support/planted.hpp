/// \file
/// Planted mistakes: the test build of the solutions with the classic mistakes of each
/// exercise planted in it (tests/exercises/plant.cmake), each switched on at run time by
/// `SOA_PLANT=<id>` so that one build serves every planted mistake of a lesson.
#pragma once

#include <cstdlib>
#include <cstring>

/// True when the planted mistake \p id is the one this run has switched on.
inline bool soa_planted(const char* id) {
  const char* on = std::getenv("SOA_PLANT");
  return on != nullptr && std::strcmp(on, id) == 0;
}
