/// \file
/// Planted mistakes: the test build of the solutions with the classic mistakes of each
/// exercise planted in it (tests/exercises/plant.cmake), each switched on at run time by
/// `SOA_PLANT=<id>` so that one build serves every planted mistake of a lesson.
#pragma once

#include <cstdlib>
#include <cstring>

/// True when the planted mistake \p id is one this run has switched on: `SOA_PLANT` holds
/// one id, or several separated by commas (one per lesson, in one run of make exercises).
inline bool soa_planted(const char* id) {
  const char* on = std::getenv("SOA_PLANT");
  const std::size_t n = std::strlen(id);
  for (const char* p = on; p != nullptr && *p != '\0';) {
    const char* end = std::strchr(p, ',');
    const std::size_t len = end ? std::size_t(end - p) : std::strlen(p);
    if (len == n && std::strncmp(p, id, n) == 0) return true;
    p = end ? end + 1 : nullptr;
  }
  return false;
}
