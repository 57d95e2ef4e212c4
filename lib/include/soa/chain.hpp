/// \file
/// Serial chains (lessons 3-8): model, state, workspace, kinematics, inverse dynamics, the
/// operator forms, composite and articulated bodies, forward dynamics and the inverse of the
/// mass matrix.
#pragma once

#include "soa/chain/articulated.hpp"
#include "soa/chain/composite.hpp"
#include "soa/chain/energy_structure.hpp"
#include "soa/chain/force_decompositions.hpp"
#include "soa/chain/forward_dynamics.hpp"
#include "soa/chain/hinge.hpp"
#include "soa/chain/innovations.hpp"
#include "soa/chain/inverse_dynamics.hpp"
#include "soa/chain/jacobian.hpp"
#include "soa/chain/kinematics.hpp"
#include "soa/chain/kinetic_gradient.hpp"
#include "soa/chain/mass_matrix_inertial.hpp"
#include "soa/chain/mass_matrix_inverse.hpp"
#include "soa/chain/mass_matrix_inverse_times.hpp"
#include "soa/chain/mass_matrix_inverse_upsilon.hpp"
#include "soa/chain/model.hpp"
#include "soa/chain/operational_space.hpp"
#include "soa/chain/operators.hpp"
#include "soa/chain/workspace.hpp"

// The templates are compiled in the library (float, double, long double).
#include "soa/instantiations.hpp"
