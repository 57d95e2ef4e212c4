/// \file
/// What an exercise stub throws until the student completes it.
#pragma once

#include <stdexcept>
#include <string>

namespace soa::exercise {

/// Thrown by every stub in `exercises/`: the exercise tests report it as "not done".
class NotDone : public std::logic_error {
 public:
  explicit NotDone(const std::string& which)
      : std::logic_error("not done: exercise " + which + " (its statement is in exercises.hpp)") {}
};

}  // namespace soa::exercise
