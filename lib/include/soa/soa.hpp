/// \file
/// Everything in the `soa` library (scene files, which need nlohmann-json, are apart:
/// soa/scene.hpp, library soa_scene).
#pragma once

#include "soa/chain.hpp"
#include "soa/coriolis.hpp"
#include "soa/error.hpp"
#include "soa/free_body.hpp"
#include "soa/phi.hpp"
#include "soa/pose.hpp"
#include "soa/rigid_body.hpp"
#include "soa/rotation.hpp"
#include "soa/se3.hpp"
#include "soa/sim.hpp"
#include "soa/spatial_cross.hpp"
#include "soa/spatial_inertia.hpp"
#include "soa/spatial_vector.hpp"
#include "soa/tilde.hpp"
#include "soa/types.hpp"

// The templates are compiled in the library (float, double, long double).
#include "soa/instantiations.hpp"
