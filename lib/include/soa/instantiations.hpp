// The library's templates, compiled once in lib/src in each precision: double (soa), float
// (soa_float) and long double (soa_long_double). SOA_TEMPLATES(extern, S) below declares them `extern` for
// every program that includes the library's headers, which then links the library's copy
// instead of compiling the algorithms' Eigen code again (most of a test's compile time);
// lib/src/instantiate.hpp expands the same list without `extern` to define them.
#pragma once

#include "soa/chain.hpp"
#include "soa/coriolis.hpp"
#include "soa/free_body.hpp"
#include "soa/phi.hpp"
#include "soa/pose.hpp"
#include "soa/rigid_body.hpp"
#include "soa/rotation.hpp"
#include "soa/sim.hpp"
#include "soa/spatial_inertia.hpp"
#include "soa/spatial_vector.hpp"

// clang-format off
// The list in six groups, each compiled as its own translation unit per precision
// (lib/CMakeLists.txt, lib/src/instantiate.cpp.in), which declares the other groups extern:
// each template is compiled once, in the small unit of its group. In one unit of everything
// GCC's inlining limits for the whole unit left the recursions' small Eigen functions out of
// line, and the linker kept that copy (forward dynamics measurably slower in make bench).
#define SOA_TEMPLATES_CORE(PREFIX, S)                                                            \
  PREFIX template class PoseT<S>;                                                                \
  PREFIX template class PhiT<S>;                                                                 \
  PREFIX template class SpatialInertiaT<S>;                                                      \
  PREFIX template class UnitQuaternionT<S>;                                                      \
  PREFIX template struct AxisAngleT<S>;                                                          \
  PREFIX template struct GibbsT<S>;                                                              \
  PREFIX template struct CayleyT<S>;                                                             \
  PREFIX template struct EulerZYXT<S>;                                                           \
  PREFIX template class SpatialVector<S, VelocityKind>;                                          \
  PREFIX template class SpatialVector<S, AccelerationKind>;                                      \
  PREFIX template class SpatialVector<S, ForceKind>;                                             \
  PREFIX template class SpatialVector<S, MomentumKind>;                                          \
  PREFIX template Vec3<S> log_so3<S>(const Mat3<S>&);                                            \
  PREFIX template Mat3<S> exp_so3<S>(const Vec3<S>&);                                            \
  PREFIX template FreeBodyStateT<S> rk4_step<S>(const SpatialInertiaT<S>&,                       \
                                                const FreeBodyStateT<S>&, S);                    \
  PREFIX template struct HingeT<S>;                                                              \
  PREFIX template class ModelT<S>;                                                               \
  PREFIX template struct WorkspaceT<S>;                                                          \
  PREFIX template void update_phi<S>(const ModelT<S>&, const VecX<S>&, WorkspaceT<S>&);          \
  PREFIX template void update_poses<S>(const ModelT<S>&, WorkspaceT<S>&);                        \
  PREFIX template void update_velocities<S>(const ModelT<S>&, const StateT<S>&, WorkspaceT<S>&); \
  PREFIX template void update_accelerations<S>(const ModelT<S>&, const StateT<S>&, const S*,     \
                                               const AccelerationT<S>&, WorkspaceT<S>&);         \
  PREFIX template void jacobian<S>(const ModelT<S>&, const VecX<S>&, const WorkspaceT<S>&, int,  \
                                   const PoseT<S>&, Eigen::Matrix<S, 6, Eigen::Dynamic>&);       \
  PREFIX template AccelerationT<S> jacobian_dot_times_beta<S>(                                   \
      const ModelT<S>&, const StateT<S>&, WorkspaceT<S>&, int, const PoseT<S>&);                 \
  PREFIX template MatX<S> composite_inertia_operator<S>(const ModelT<S>&, const WorkspaceT<S>&); \
  PREFIX template struct ArticulatedT<S>;                                                        \
  PREFIX template Mat6<S> transform_symmetric<S>(const PhiT<S>&, const Mat6<S>&);                \
  PREFIX template S singular_D_ratio<S>(const ModelT<S>&, const StateT<S>&,                      \
                                        const WorkspaceT<S>&, const ArticulatedT<S>&, int, S);   \
  PREFIX template S singular_D_ratio<S>(const ModelT<S>&, const StateT<S>&,                      \
                                        const WorkspaceT<S>&, const ArticulatedT<S>&, int);      \
  PREFIX template void articulated_inertias<S>(const ModelT<S>&, const StateT<S>&,               \
                                               const WorkspaceT<S>&, ArticulatedT<S>&);
#define SOA_TEMPLATES_DENSE(PREFIX, S)                                                           \
  PREFIX template struct OperatorsT<S>;                                                          \
  PREFIX template struct InnovationsOperatorsT<S>;
#define SOA_TEMPLATES_ID(PREFIX, S)                                                              \
  PREFIX template void inverse_dynamics<S>(const ModelT<S>&, const StateT<S>&, const VecX<S>&,   \
                                           const ExternalForces<S>&, WorkspaceT<S>&, VecX<S>&);  \
  PREFIX template void composite_inertias<S>(const ModelT<S>&, const WorkspaceT<S>&,             \
                                             std::vector<SpatialInertiaT<S>>&);                  \
  PREFIX template struct MassMatrixInertialT<S>;                                                 \
  PREFIX template void mass_matrix_inertial<S>(const ModelT<S>&, const StateT<S>&,               \
                                               const WorkspaceT<S>&, MassMatrixInertialT<S>&,    \
                                               MatX<S>&);                                        \
  PREFIX template void mass_matrix_crb<S>(const ModelT<S>&, const StateT<S>&,                    \
                                          const WorkspaceT<S>&,                                  \
                                          std::vector<SpatialInertiaT<S>>&, MatX<S>&);           \
  PREFIX template void inverse_dynamics_composite<S>(                                            \
      const ModelT<S>&, const StateT<S>&, const VecX<S>&, const ExternalForces<S>&,              \
      WorkspaceT<S>&, std::vector<SpatialInertiaT<S>>&, VecX<S>&);
#define SOA_TEMPLATES_FD(PREFIX, S)                                                              \
  PREFIX template void transform_symmetric<S>(const PhiT<S>&, const Mat6<S>&, Mat6<S>&, bool);   \
  PREFIX template S riccati_step<S>(const ModelT<S>&, const StateT<S>&, const WorkspaceT<S>&,    \
                                    int, ArticulatedT<S>&, CompositeTraceT<S>&);                 \
  PREFIX template struct ForwardDynamicsT<S>;                                                    \
  PREFIX template void forward_dynamics<S>(const ModelT<S>&, const StateT<S>&, const VecX<S>&,   \
                                           const ExternalForces<S>&, WorkspaceT<S>&,             \
                                           ForwardDynamicsT<S>&, VecX<S>&);                      \
  PREFIX template void mass_matrix_inverse_times<S>(const ModelT<S>&, const StateT<S>&,          \
                                                    const VecX<S>&, WorkspaceT<S>&,              \
                                                    ForwardDynamicsT<S>&, VecX<S>&);             \
  PREFIX template void kinetic_gradient<S>(const ModelT<S>&, const StateT<S>&, WorkspaceT<S>&,   \
                                           VecX<S>&, VecX<S>&);
#define SOA_TEMPLATES_MINV(PREFIX, S)                                                            \
  PREFIX template struct MassMatrixInverseT<S>;                                                  \
  PREFIX template void mass_matrix_inverse<S>(const ModelT<S>&, const StateT<S>&,                \
                                              const WorkspaceT<S>&, MassMatrixInverseT<S>&,      \
                                              MatX<S>&);
#define SOA_TEMPLATES_SIM(PREFIX, S)                                                             \
  PREFIX template void retract<S>(const ModelT<S>&, const VecX<S>&, const VecX<S>&, VecX<S>&);   \
  PREFIX template class ChainSystemT<S>;                                                         \
  PREFIX template class StepperT<S>;                                                             \
  PREFIX template struct RadauIIA<S>;                                                            \
  PREFIX template class DominantEigenvalueT<S>;                                                  \
  PREFIX template S stiffness_estimate<S>(StepperT<S>&, int, S, const StateT<S>&);               \
  PREFIX template SimulationSummary detail::simulate_observed<S>(                                \
      ChainSystemT<S>&, StateT<S>&, const SimulationOptionsT<S>&, const SimulationObserverT<S>&);
#define SOA_TEMPLATES(PREFIX, S) \
  SOA_TEMPLATES_CORE(PREFIX, S)  \
  SOA_TEMPLATES_DENSE(PREFIX, S) \
  SOA_TEMPLATES_ID(PREFIX, S)    \
  SOA_TEMPLATES_FD(PREFIX, S)    \
  SOA_TEMPLATES_MINV(PREFIX, S)  \
  SOA_TEMPLATES_SIM(PREFIX, S)
// clang-format on

// All three precisions are declared extern: a program computing in float or long double
// links soa_float or soa_long_double (lib/CMakeLists.txt), one in double soa alone. A group
// left out of the library (SOA_GROUPS: `make exercises` leaves out SIM, which no exercise
// uses) is not declared extern (SOA_LIB_LACKS_<group>): a program using it compiles the
// templates itself.
#ifndef SOA_INSTANTIATING
#ifdef SOA_LIB_LACKS_CORE
#define SOA_EXTERN_CORE(S)
#else
#define SOA_EXTERN_CORE(S) SOA_TEMPLATES_CORE(extern, S)
#endif
#ifdef SOA_LIB_LACKS_DENSE
#define SOA_EXTERN_DENSE(S)
#else
#define SOA_EXTERN_DENSE(S) SOA_TEMPLATES_DENSE(extern, S)
#endif
#ifdef SOA_LIB_LACKS_ID
#define SOA_EXTERN_ID(S)
#else
#define SOA_EXTERN_ID(S) SOA_TEMPLATES_ID(extern, S)
#endif
#ifdef SOA_LIB_LACKS_FD
#define SOA_EXTERN_FD(S)
#else
#define SOA_EXTERN_FD(S) SOA_TEMPLATES_FD(extern, S)
#endif
#ifdef SOA_LIB_LACKS_MINV
#define SOA_EXTERN_MINV(S)
#else
#define SOA_EXTERN_MINV(S) SOA_TEMPLATES_MINV(extern, S)
#endif
#ifdef SOA_LIB_LACKS_SIM
#define SOA_EXTERN_SIM(S)
#else
#define SOA_EXTERN_SIM(S) SOA_TEMPLATES_SIM(extern, S)
#endif
#define SOA_EXTERN_NUMERICS(S) \
  SOA_EXTERN_CORE(S)           \
  SOA_EXTERN_DENSE(S)          \
  SOA_EXTERN_ID(S)             \
  SOA_EXTERN_FD(S)             \
  SOA_EXTERN_MINV(S)
// The simulation group is compiled in double only (lib/CMakeLists.txt): a program simulating in
// float or long double compiles those templates itself.
namespace soa {
SOA_EXTERN_NUMERICS(float)
SOA_EXTERN_NUMERICS(double)
SOA_EXTERN_SIM(double)
SOA_EXTERN_NUMERICS(long double)
}  // namespace soa
#endif
