/// \file
/// Building a chain in code, body by body from the base out (lessons 6 and 8): a body with its
/// spatial inertia, its placement on the inboard body and its hinge.
#pragma once

#include <string>

#include "soa/chain.hpp"
#include "soa/soa.hpp"

namespace soa::lesson {

/// A body of a chain, placed on its inboard body at \f${}^{O_{k+1}}T_{O_k^+}\f$, with its
/// hinge (lesson 3).
inline Body make_body(const std::string& name, const SpatialInertia& M, const Pose& placement,
                      const Hinge& hinge) {
  Body b;
  b.name = name;
  b.M = M;
  b.placement = placement;
  b.hinge = hinge;
  return b;
}

/// The spatial inertia of mass \p m, centre of mass \p p, principal moments \p J_principal
/// about it (lesson 2).
inline SpatialInertia inertia(double m, const Vec3<double>& p, const Vec3<double>& J_principal) {
  return SpatialInertia::from_cm(m, p, J_principal.asDiagonal().toDenseMatrix());
}

/// A hinge of type \p type about \p axis (\p axis2: a universal joint's second axis; \p pitch:
/// a helical joint's).
inline Hinge hinge(HingeType type, const Vec3<double>& axis,
                   const Vec3<double>& axis2 = Vec3<double>::UnitY(), double pitch = 0) {
  Hinge h;
  h.type = type;
  h.axis = axis.normalized();
  h.axis2 = axis2.normalized();
  h.pitch = pitch;
  return h;
}

/// The pose rotated by \f$\exp(\tilde r)\f$ and offset by \p offset.
inline Pose at(const Vec3<double>& rotation_vector, const Vec3<double>& offset) {
  return Pose(exp_so3<double>(rotation_vector), offset);
}

}  // namespace soa::lesson
