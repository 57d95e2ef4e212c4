/// \file
/// Hinges: joint maps \f$H^*(k)\f$, joint transforms and configuration rates (lesson 3).
#pragma once

#include <string>

#include "soa/error.hpp"
#include "soa/pose.hpp"
#include "soa/rotation/quaternion.hpp"
#include "soa/spatial_vector.hpp"

namespace soa {

/// The hinge types of the course. `Locked` has no degree of freedom: the model merges its
/// body into the inboard neighbour when it is built.
enum class HingeType { Revolute, Prismatic, Helical, Universal, Spherical, Free, Locked };

/// The name used in scene files and messages ("revolute", ...).
inline const char* hinge_type_name(HingeType t) {
  switch (t) {
    case HingeType::Revolute:
      return "revolute";
    case HingeType::Prismatic:
      return "prismatic";
    case HingeType::Helical:
      return "helical";
    case HingeType::Universal:
      return "universal";
    case HingeType::Spherical:
      return "spherical";
    case HingeType::Free:
      return "free";
    case HingeType::Locked:
      return "locked";
  }
  return "?";
}

/// The 6 x n_k joint map matrix \f$H^*(k)\f$ with at most six columns (no heap).
template <class S>
using JointMap = Eigen::Matrix<S, 6, Eigen::Dynamic, Eigen::ColMajor, 6, 6>;

/// Hinge k between the inboard frame \f$O_k^+\f$ (fixed on body k+1) and the outboard frame
/// \f$O_k\f$ (fixed on body k). Everything of the hinge is expressed in \f$O_k\f$ coordinates:
/// the relative spatial velocity is \f$\Delta_V(k) = H^*(k)\,\beta(k)\f$ (slides 38-41) and
/// the joint transform is \f${}^{O_k^+}T_{O_k}(\theta(k))\f$.
///
/// | type | \f$\theta\f$ | \f$\beta\f$ | \f$H^*(k)\f$ |
/// |---|---|---|---|
/// | revolute about \f$a\f$ | angle (1) | rate (1) | \f$[a; 0]\f$ |
/// | prismatic along \f$a\f$ | offset (1) | rate (1) | \f$[0; a]\f$ |
/// | helical, pitch \f$h\f$ | angle (1) | rate (1) | \f$[a; h a]\f$ |
/// | universal \f$a_1\f$ then \f$a_2\f$ | two angles | two rates | \f$[e^{-\theta_2\tilde a_2}a_1, a_2; 0, 0]\f$ |
/// | spherical | quaternion \f$[q; q_0]\f$ (4) | \f$\omega\f$ (3) | \f$[I; 0]\f$ |
/// | free | quaternion, then \f${}^{O_k^+}l\f$ (7) | \f$[\omega; v]\f$ (6) | \f$I_6\f$ |
///
/// Quaternions are vector part first (lesson 1) and name \f${}^{O_k^+}R_{O_k}\f$.
template <class S>
struct HingeT {
  HingeType type = HingeType::Revolute;
  Vec3<S> axis = Vec3<S>::UnitZ();   ///< unit axis (revolute, prismatic, helical, universal 1st)
  Vec3<S> axis2 = Vec3<S>::UnitY();  ///< universal: the second axis (unit), fixed in \f$O_k\f$
  S pitch = S(0);                    ///< helical: translation per radian

  /// Size of \f$\theta(k)\f$.
  int nq() const {
    switch (type) {
      case HingeType::Universal:
        return 2;
      case HingeType::Spherical:
        return 4;
      case HingeType::Free:
        return 7;
      case HingeType::Locked:
        return 0;
      default:
        return 1;
    }
  }
  /// Size of \f$\beta(k)\f$, the hinge's degrees of freedom \f$n_k\f$.
  int nv() const {
    switch (type) {
      case HingeType::Universal:
        return 2;
      case HingeType::Spherical:
        return 3;
      case HingeType::Free:
        return 6;
      case HingeType::Locked:
        return 0;
      default:
        return 1;
    }
  }

  /// The joint transform \f${}^{O_k^+}T_{O_k}(\theta)\f$.
  PoseT<S> transform(const S* theta) const {
    switch (type) {
      case HingeType::Revolute:
        return PoseT<S>(exp_unit_axis<S>(axis, theta[0]), Vec3<S>::Zero());
      case HingeType::Prismatic:
        return PoseT<S>(Mat3<S>::Identity(), theta[0] * axis);
      case HingeType::Helical:
        return PoseT<S>(exp_unit_axis<S>(axis, theta[0]), (pitch * theta[0]) * axis);
      case HingeType::Universal:
        return PoseT<S>(exp_unit_axis<S>(axis, theta[0]) * exp_unit_axis<S>(axis2, theta[1]),
                        Vec3<S>::Zero());
      case HingeType::Spherical:
        return PoseT<S>(quaternion(theta).matrix(), Vec3<S>::Zero());
      case HingeType::Free:
        return PoseT<S>(quaternion(theta).matrix(), Vec3<S>(theta[4], theta[5], theta[6]));
      case HingeType::Locked:
        break;
    }
    return PoseT<S>();
  }

  /// \f$\Delta_V = H^*(k)\,\beta(k)\f$, the velocity of \f$O_k\f$ relative to \f$O_k^+\f$.
  VelocityT<S> H_star_times(const S* theta, const S* beta) const {
    switch (type) {
      case HingeType::Revolute:
        return VelocityT<S>(beta[0] * axis, Vec3<S>::Zero());
      case HingeType::Prismatic:
        return VelocityT<S>(Vec3<S>::Zero(), beta[0] * axis);
      case HingeType::Helical:
        return VelocityT<S>(beta[0] * axis, (pitch * beta[0]) * axis);
      case HingeType::Universal:
        return VelocityT<S>(beta[0] * universal_c1(theta) + beta[1] * axis2, Vec3<S>::Zero());
      case HingeType::Spherical:
        return VelocityT<S>(Vec3<S>(beta[0], beta[1], beta[2]), Vec3<S>::Zero());
      case HingeType::Free:
        return VelocityT<S>(Vec3<S>(beta[0], beta[1], beta[2]), Vec3<S>(beta[3], beta[4], beta[5]));
      case HingeType::Locked:
        break;
    }
    return VelocityT<S>();
  }

  /// \f$T(k) = H(k)\, f(k)\f$ (slide: hinge force), written into \p T (n_k entries).
  void H_times(const S* theta, const ForceT<S>& f, S* T) const {
    const Vec3<S> N = f.angular(), F = f.linear();
    switch (type) {
      case HingeType::Revolute:
        T[0] = axis.dot(N);
        break;
      case HingeType::Prismatic:
        T[0] = axis.dot(F);
        break;
      case HingeType::Helical:
        T[0] = axis.dot(N) + pitch * axis.dot(F);
        break;
      case HingeType::Universal:
        T[0] = universal_c1(theta).dot(N);
        T[1] = axis2.dot(N);
        break;
      case HingeType::Spherical:
        for (int i = 0; i < 3; ++i) T[i] = N[i];
        break;
      case HingeType::Free:
        for (int i = 0; i < 3; ++i) T[i] = N[i], T[i + 3] = F[i];
        break;
      case HingeType::Locked:
        break;
    }
  }

  /// The dense \f$H^*(k)\f$ (6 x n_k), for operator forms, Jacobians and tests.
  JointMap<S> H_star(const S* theta) const {
    JointMap<S> Hs = JointMap<S>::Zero(6, nv());
    switch (type) {
      case HingeType::Revolute:
        Hs.col(0).template head<3>() = axis;
        break;
      case HingeType::Prismatic:
        Hs.col(0).template tail<3>() = axis;
        break;
      case HingeType::Helical:
        Hs.col(0).template head<3>() = axis;
        Hs.col(0).template tail<3>() = pitch * axis;
        break;
      case HingeType::Universal:
        Hs.col(0).template head<3>() = universal_c1(theta);
        Hs.col(1).template head<3>() = axis2;
        break;
      case HingeType::Spherical:
        Hs.template topRows<3>().setIdentity();
        break;
      case HingeType::Free:
        Hs.setIdentity();
        break;
      case HingeType::Locked:
        break;
    }
    return Hs;
  }

  /// \f$\mathring H^*(k)\,\beta(k)\f$: the rate of \f$H^*(k)\f$ seen from \f$O_k\f$ times
  /// \f$\beta\f$. Zero but for the universal hinge, whose first column
  /// \f$c_1 = e^{-\theta_2\tilde a_2}a_1\f$ turns with \f$\dot c_1 = \beta_2\, c_1 \times
  /// a_2\f$.
  AccelerationT<S> H_star_dot_times(const S* theta, const S* beta) const {
    if (type != HingeType::Universal) return AccelerationT<S>();
    return AccelerationT<S>((beta[0] * beta[1]) * universal_c1(theta).cross(axis2),
                            Vec3<S>::Zero());
  }

  /// \f$\dot\theta(k)\f$ from \f$\beta(k)\f$ (equal but for quaternion hinges:
  /// \f$\dot{\mathfrak q} = \tfrac12\,\mathfrak q \otimes [\omega; 0]\f$, and for the free
  /// hinge \f$\dot l = R\, v\f$).
  void theta_dot(const S* theta, const S* beta, S* out) const {
    switch (type) {
      case HingeType::Spherical:
      case HingeType::Free: {
        const UnitQuaternionT<S> q = quaternion(theta);
        const Vec3<S> w(beta[0], beta[1], beta[2]);
        const Eigen::Matrix<S, 4, 1> qd = q.rate(w);
        for (int i = 0; i < 4; ++i) out[i] = qd[i];
        if (type == HingeType::Free) {
          const Vec3<S> ld = q.rotate(Vec3<S>(beta[3], beta[4], beta[5]));
          for (int i = 0; i < 3; ++i) out[4 + i] = ld[i];
        }
        break;
      }
      default:
        for (int i = 0; i < nv(); ++i) out[i] = beta[i];
    }
  }

  /// The unit quaternion stored at \p theta (vector part first), normalized.
  static UnitQuaternionT<S> quaternion(const S* theta) {
    return UnitQuaternionT<S>(Vec3<S>(theta[0], theta[1], theta[2]), theta[3]);
  }

  /// The universal hinge's first axis seen in \f$O_k\f$: \f$e^{-\theta_2\tilde a_2} a_1\f$.
  Vec3<S> universal_c1(const S* theta) const { return exp_unit_axis<S>(axis2, -theta[1]) * axis; }

  template <class T>
  HingeT<T> cast() const {
    return HingeT<T>{type, axis.template cast<T>(), axis2.template cast<T>(), T(pitch)};
  }
};
using Hinge = HingeT<double>;

}  // namespace soa
