// The chain in Orocos KDL (Debian liborocos-kdl-dev): a KDL::Chain built from a soa::Model of
// revolute hinges, and the three calls the comparison times, on KDL's coordinates (base first).
//
// A KDL::Segment is a joint at its root, then a fixed frame f_tip to its tip; its inertia is
// expressed in the tip frame. Our body i (base first) is O_i, the hinge frame after its
// rotation; its hinge sits at the placement P_i in O_{i-1}. So segment i is: joint about our
// axis, f_tip = P_{i+1} (identity for the last), inertia = our M(O_i) carried into the tip
// frame by KDL's own Frame * RigidBodyInertia. The first placement must be the identity
// (KDL's Vereshchagin solver wants one joint per segment: no leading fixed segment).
#pragma once

#include <kdl/config.h>
#include <kdl/chain.hpp>
#include <kdl/chaindynparam.hpp>
#include <kdl/chainhdsolver_vereshchagin.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#include "soa/chain.hpp"

namespace soa::compare {

inline KDL::Vector kdl_vector(const Vec3<double>& v) {
  return KDL::Vector(v.x(), v.y(), v.z());
}

inline KDL::Frame kdl_frame(const Pose& P) {
  const Mat3<double>& R = P.R();
  return KDL::Frame(KDL::Rotation(R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0),
                                  R(2, 1), R(2, 2)),
                    kdl_vector(P.l()));
}

/// The KDL joint of a revolute hinge: RotX/RotY/RotZ for a coordinate axis, RotAxis otherwise.
inline KDL::Joint kdl_joint(const std::string& name, const Vec3<double>& a) {
  if (a == Vec3<double>::UnitX()) return KDL::Joint(name, KDL::Joint::RotX);
  if (a == Vec3<double>::UnitY()) return KDL::Joint(name, KDL::Joint::RotY);
  if (a == Vec3<double>::UnitZ()) return KDL::Joint(name, KDL::Joint::RotZ);
  return KDL::Joint(name, KDL::Vector::Zero(), kdl_vector(a), KDL::Joint::RotAxis);
}

/// \p m as a KDL::Chain (revolute hinges only; std::runtime_error otherwise).
inline KDL::Chain kdl_chain(const Model& m) {
  KDL::Chain chain;
  const int n = m.n();
  for (int i = 0; i < n; ++i) {  // base first: our body k = n - i
    const Body& B = m.body(n - i);
    if (B.hinge.type != HingeType::Revolute)
      throw std::runtime_error("KDL chain: body '" + B.name + "' is not revolute");
    if (i == 0 &&
        (B.placement.l() != Vec3<double>::Zero() || B.placement.R() != Mat3<double>::Identity()))
      throw std::runtime_error("KDL chain: the first hinge must sit at the base origin");
    const KDL::Frame tip = i + 1 < n ? kdl_frame(m.body(n - i - 1).placement) : KDL::Frame();
    const Mat3<double> Jc = B.M.J_cm();
    const KDL::RigidBodyInertia I_O(
        B.M.mass(), kdl_vector(B.M.p()),
        KDL::RotationalInertia(Jc(0, 0), Jc(1, 1), Jc(2, 2), Jc(0, 1), Jc(0, 2), Jc(1, 2)));
    chain.addSegment(
        KDL::Segment(B.name, kdl_joint(B.name, B.hinge.axis), tip, tip.Inverse() * I_O));
  }
  return chain;
}

/// KDL's solvers on one chain and state (base-first coordinates), every buffer allocated once.
struct KdlPeer {
  KDL::Chain chain;
  unsigned n;
  KDL::JntArray q, qd, qdd_in, T, tau, qdd, ff, constraint_tau;
  KDL::Wrenches f_ext;
  KDL::JntSpaceInertiaMatrix H;
  KDL::Jacobian alpha;  // 6 x 0: no constraint on the tip
  KDL::JntArray beta;   // 0 entries
  KDL::ChainIdSolver_RNE id;
  KDL::ChainDynParam dyn;
  KDL::ChainHdSolver_Vereshchagin hd;

  /// \p g is the gravity vector: the RNE and ChainDynParam take it as is, the Vereshchagin
  /// solver as the base's acceleration, -g (its header: "gravity acceleration with opposite
  /// sign compared to the KDL's FD and RNE solvers").
  KdlPeer(const Model& m, const Vec3<double>& g)
      : chain(kdl_chain(m)),
        n(chain.getNrOfJoints()),
        q(n),
        qd(n),
        qdd_in(n),
        T(n),
        tau(n),
        qdd(n),
        ff(n),
        constraint_tau(n),
        f_ext(chain.getNrOfSegments(), KDL::Wrench::Zero()),
        H(n),
        alpha(0),
        beta(0),
        id(chain, kdl_vector(g)),
        dyn(chain, kdl_vector(g)),
        hd(chain, KDL::Twist(kdl_vector(-g), KDL::Vector::Zero()), 0) {
    alpha.resize(0);
  }

  /// Inverse dynamics: tau = M qdd_in + C (gravity included), kinematics included.
  void inverse() { check(id.CartToJnt(q, qd, qdd_in, f_ext, tau), "ChainIdSolver_RNE"); }
  /// The mass matrix, composite rigid bodies (ChainDynParam::JntToMass).
  void mass() { check(dyn.JntToMass(q, H), "ChainDynParam::JntToMass"); }
  /// Forward dynamics, O(N): Vereshchagin's solver with no constraint, T as the feed-forward
  /// torques.
  void forward() {
    check(hd.CartToJnt(q, qd, qdd, alpha, beta, f_ext, T, constraint_tau),
          "ChainHdSolver_Vereshchagin");
  }

  static void check(int code, const char* what) {
    if (code != 0)
      throw std::runtime_error(std::string(what) + " failed (" + std::to_string(code) + ")");
  }
};

}  // namespace soa::compare
