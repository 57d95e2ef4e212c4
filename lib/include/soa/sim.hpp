/// \file
/// Simulation of serial chains: the chain as an ODE, the integrators, the loop.
#pragma once

#include "soa/sim/chain_system.hpp"
#include "soa/sim/integrators.hpp"
#include "soa/sim/simulate.hpp"
#include "soa/sim/stiffness.hpp"

// The templates are compiled in the library (float, double, long double).
#include "soa/instantiations.hpp"
