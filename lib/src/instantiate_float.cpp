// The library's templates instantiated in float (see instantiate.hpp).
#include "instantiate.hpp"

namespace soa {
SOA_TEMPLATES(, float)
}  // namespace soa
