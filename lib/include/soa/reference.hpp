/// \file
/// The reference tier (namespace soa::reference): each O(N) algorithm of the course as its
/// lesson derives it, with one storage and no fast path, beside its fast form in
/// soa/chain.hpp. Header-only templates: a program compiles the precisions it uses.
#pragma once

#include "soa/reference/articulated.hpp"
#include "soa/reference/composite.hpp"
#include "soa/reference/forward_dynamics.hpp"
#include "soa/reference/innovations.hpp"
#include "soa/reference/inverse_dynamics.hpp"
#include "soa/reference/jacobian.hpp"
#include "soa/reference/kinematics.hpp"
#include "soa/reference/mass_matrix_inverse.hpp"
#include "soa/reference/mass_matrix_inverse_times.hpp"
#include "soa/reference/workspace.hpp"
