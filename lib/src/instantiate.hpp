// Explicit instantiations of the library's templates in the three precisions the course
// uses: a template that does not compile for float or long double fails here. One file per
// precision, so that the three compile in parallel.
#pragma once

#include "soa/chain.hpp"
#include "soa/soa.hpp"

namespace soa {

#define SOA_INSTANTIATE(S)                                                                        \
  template class PoseT<S>;                                                                        \
  template class PhiT<S>;                                                                         \
  template class SpatialInertiaT<S>;                                                              \
  template class UnitQuaternionT<S>;                                                              \
  template struct AxisAngleT<S>;                                                                  \
  template struct GibbsT<S>;                                                                      \
  template struct CayleyT<S>;                                                                     \
  template struct EulerZYXT<S>;                                                                   \
  template class SpatialVector<S, VelocityKind>;                                                  \
  template class SpatialVector<S, AccelerationKind>;                                              \
  template class SpatialVector<S, ForceKind>;                                                     \
  template class SpatialVector<S, MomentumKind>;                                                  \
  template Vec3<S> log_so3<S>(const Mat3<S>&);                                                    \
  template Mat3<S> exp_so3<S>(const Vec3<S>&);                                                    \
  template FreeBodyStateT<S> rk4_step<S>(const SpatialInertiaT<S>&, const FreeBodyStateT<S>&, S); \
  template struct HingeT<S>;                                                                      \
  template class ModelT<S>;                                                                       \
  template struct WorkspaceT<S>;                                                                  \
  template struct OperatorsT<S>;                                                                  \
  template void inverse_dynamics<S>(const ModelT<S>&, const StateT<S>&, const VecX<S>&,           \
                                    const ExternalForces<S>&, WorkspaceT<S>&, VecX<S>&);          \
  template void jacobian<S>(const ModelT<S>&, const VecX<S>&, const WorkspaceT<S>&, int,          \
                            const PoseT<S>&, Eigen::Matrix<S, 6, Eigen::Dynamic>&);               \
  template struct ArticulatedT<S>;                                                                \
  template void articulated_inertias<S>(const ModelT<S>&, const StateT<S>&, const WorkspaceT<S>&, \
                                        ArticulatedT<S>&);                                        \
  template void mass_matrix_crb<S>(const ModelT<S>&, const StateT<S>&, const WorkspaceT<S>&,      \
                                   std::vector<SpatialInertiaT<S>>&, MatX<S>&);                   \
  template AccelerationT<S> jacobian_dot_times_beta<S>(const ModelT<S>&, const StateT<S>&,        \
                                                       WorkspaceT<S>&, int, const PoseT<S>&);     \
  template struct ForwardDynamicsT<S>;                                                            \
  template void forward_dynamics<S>(const ModelT<S>&, const StateT<S>&, const VecX<S>&,           \
                                    const ExternalForces<S>&, WorkspaceT<S>&,                     \
                                    ForwardDynamicsT<S>&, VecX<S>&);                              \
  template struct InnovationsOperatorsT<S>;                                                       \
  template struct MassMatrixInverseT<S>;                                                          \
  template void mass_matrix_inverse<S>(const ModelT<S>&, const StateT<S>&, const WorkspaceT<S>&,  \
                                       MassMatrixInverseT<S>&, MatX<S>&);                         \
  template class ChainSystemT<S>;                                                                 \
  template class StepperT<S>;

}  // namespace soa
