/// \file
/// All attitude representations of lesson 1 (slides 15-20) and the convention they share.
#pragma once

#include "soa/rotation/axis_angle.hpp"
#include "soa/rotation/cayley.hpp"
#include "soa/rotation/convention.hpp"
#include "soa/rotation/euler.hpp"
#include "soa/rotation/gibbs.hpp"
#include "soa/rotation/quaternion.hpp"
