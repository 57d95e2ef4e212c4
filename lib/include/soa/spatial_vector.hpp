/// \file
/// Spatial velocities, accelerations, forces and momenta as distinct types (slides 5, 39, 48).
#pragma once

#include <type_traits>

#include "soa/types.hpp"

namespace soa {

/// Kinds of spatial vector. Motion kinds (velocity, acceleration) transform with
/// \f$\phi^*\f$; force kinds (force, momentum) with \f$\phi\f$ (slide 50).
struct VelocityKind {
  static constexpr bool is_motion = true;
};
struct AccelerationKind {
  static constexpr bool is_motion = true;
};
struct ForceKind {
  static constexpr bool is_motion = false;
};
struct MomentumKind {
  static constexpr bool is_motion = false;
};

/// A spatial (6D) vector with the angular part first (\ref conventions): \f$V = [\omega; v]\f$
/// for a velocity, \f$f = [N; F]\f$ for a force (moment first).
///
/// The kind is part of the type: a force cannot be added to a velocity, and the pairing of
/// a force with a motion (power, slide 50) is the only product between the two families.
template <class S, class Kind>
class SpatialVector {
 public:
  using Scalar = S;
  using KindType = Kind;
  static constexpr bool is_motion = Kind::is_motion;

  SpatialVector() : v_(Vec6<S>::Zero()) {}
  /// From the angular part (\f$\omega\f$ or the moment \f$N\f$) and the linear part
  /// (\f$v\f$ or the force \f$F\f$).
  SpatialVector(const Vec3<S>& angular, const Vec3<S>& linear) {
    v_.template head<3>() = angular;
    v_.template tail<3>() = linear;
  }
  /// From the six coefficients, angular first.
  explicit SpatialVector(const Vec6<S>& v) : v_(v) {}
  static SpatialVector Zero() { return SpatialVector(); }

  auto angular() const { return v_.template head<3>(); }
  auto angular() { return v_.template head<3>(); }
  auto linear() const { return v_.template tail<3>(); }
  auto linear() { return v_.template tail<3>(); }
  /// The coefficients as a 6-vector, angular first.
  const Vec6<S>& vector() const { return v_; }
  Vec6<S>& vector() { return v_; }

  SpatialVector operator+(const SpatialVector& b) const { return SpatialVector(v_ + b.v_); }
  SpatialVector operator-(const SpatialVector& b) const { return SpatialVector(v_ - b.v_); }
  SpatialVector operator-() const { return SpatialVector(-v_); }
  SpatialVector& operator+=(const SpatialVector& b) {
    v_ += b.v_;
    return *this;
  }
  SpatialVector& operator-=(const SpatialVector& b) {
    v_ -= b.v_;
    return *this;
  }
  SpatialVector operator*(S s) const { return SpatialVector(v_ * s); }
  friend SpatialVector operator*(S s, const SpatialVector& a) { return a * s; }

  template <class T>
  SpatialVector<T, Kind> cast() const {
    return SpatialVector<T, Kind>(v_.template cast<T>());
  }

 private:
  Vec6<S> v_;
};

template <class S>
using VelocityT = SpatialVector<S, VelocityKind>;  ///< \f$V = [\omega; v]\f$
template <class S>
using AccelerationT = SpatialVector<S, AccelerationKind>;  ///< \f$\alpha = [\dot\omega; \dot v]\f$
template <class S>
using ForceT = SpatialVector<S, ForceKind>;  ///< \f$f = [N; F]\f$
template <class S>
using MomentumT = SpatialVector<S, MomentumKind>;  ///< \f$h = M V\f$
using Velocity = VelocityT<double>;
using Acceleration = AccelerationT<double>;
using Force = ForceT<double>;
using Momentum = MomentumT<double>;

/// The pairing of a force-kind vector with a motion-kind vector, \f$f^* V\f$: power for a
/// force and a velocity (slide 50), twice the kinetic energy for momentum and velocity.
template <class S, class KF, class KM>
S dot(const SpatialVector<S, KF>& f, const SpatialVector<S, KM>& V) {
  static_assert(!KF::is_motion && KM::is_motion,
                "dot pairs a force (or momentum) with a velocity (or acceleration)");
  return f.vector().dot(V.vector());
}

}  // namespace soa
