// Explicit instantiations of the library's templates in the three precisions the course
// uses (the list is soa/instantiations.hpp): a template that does not compile for float or
// long double fails here. One file per precision, so that the three compile in parallel.
#pragma once

#define SOA_INSTANTIATING
#include "soa/instantiations.hpp"
#include "soa/soa.hpp"
