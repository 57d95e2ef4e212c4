// The library's templates instantiated in double (see instantiate.hpp).
#include "instantiate.hpp"

namespace soa {
SOA_TEMPLATES(, double)
}  // namespace soa
