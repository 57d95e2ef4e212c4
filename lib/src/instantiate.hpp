// Explicit instantiations of the library's templates in float, double and long double (the
// list is soa/instantiations.hpp): a template that does not compile for float or long
// double fails here. One generated unit per precision and group (instantiate.cpp.in,
// lib/CMakeLists.txt), so that they compile in parallel and each is small enough for GCC to
// inline what the recursions call.
#pragma once

#define SOA_INSTANTIATING
#include "soa/instantiations.hpp"
#include "soa/soa.hpp"
