// The help texts of `soa` (soa --help, soa VERB --help).
#pragma once

#include <optional>

#include "args.hpp"

namespace soa::cli {

/// The help of one verb, or of the whole command when \p verb is empty.
const char* help_text(std::optional<Verb> verb);

}  // namespace soa::cli
