// The chain in Orocos KDL (Debian liborocos-kdl-dev), behind a plain interface: KDL's
// solvers hold fixed-size Eigen members, whose layout depends on the vector width, and
// Debian's libkdl is built for generic x86-64. Code that includes KDL's headers must then be
// compiled without the library's -march=native (SOA_NATIVE), or the two see different
// objects (heap corruption, seen as a crash in ~KdlPeer). So KDL is only included by
// peer_kdl.cpp, compiled in its own target that does not link soa; this header has neither
// KDL nor soa types, and kdl_chain.hpp turns a soa::Model into the segments below.
//
// A KDL::Segment is a joint at its root, then a fixed frame f_tip to its tip; its inertia is
// expressed in the tip frame. Our body i (base first) is O_i, the hinge frame after its
// rotation; its hinge sits at the placement P_i in O_{i-1}. So segment i is: joint about our
// axis, f_tip = P_{i+1} (identity for the last), inertia = our M(O_i) carried into the tip
// frame by KDL's own Frame * RigidBodyInertia. The first placement must be the identity
// (KDL's Vereshchagin solver wants one joint per segment: no leading fixed segment).
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace soa::compare {

/// One revolute segment, base first, in plain numbers.
struct KdlSegment {
  std::string name;
  double axis[3];   ///< the hinge axis in O_i
  double tip_R[9];  ///< f_tip's rotation, row-major
  double tip_l[3];  ///< f_tip's origin
  double mass;      ///< the body's mass
  double com[3];    ///< its centre of mass in O_i
  double J_cm[6];   ///< its inertia about the centre of mass: xx, yy, zz, xy, xz, yz
};

/// KDL's solvers on one chain and state (base-first coordinates), every buffer allocated
/// once. The inputs and outputs are KDL's own arrays (q(i), ..., H(i, j)).
class KdlPeer {
 public:
  /// \p g is the gravity vector: the RNE and ChainDynParam take it as is, the Vereshchagin
  /// solver as the base's acceleration, -g (its header: "gravity acceleration with opposite
  /// sign compared to the KDL's FD and RNE solvers").
  KdlPeer(const std::vector<KdlSegment>& segments, const double g[3]);
  ~KdlPeer();
  KdlPeer(const KdlPeer&) = delete;
  KdlPeer& operator=(const KdlPeer&) = delete;

  unsigned n = 0;  ///< joints
  double& q(int i);
  double& qd(int i);
  double& qdd_in(int i);  ///< the accelerations of inverse()
  double& T(int i);       ///< the hinge forces of forward()
  double tau(int i) const;
  double qdd(int i) const;
  double H(int i, int j) const;

  /// Inverse dynamics: tau = M qdd_in + C (gravity included), kinematics included.
  void inverse();
  /// The mass matrix, composite rigid bodies (ChainDynParam::JntToMass).
  void mass();
  /// Forward dynamics, O(N): Vereshchagin's solver with no constraint, T as the feed-forward
  /// torques.
  void forward();

  /// KDL's version (KDL_VERSION_STRING).
  static std::string version();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace soa::compare
