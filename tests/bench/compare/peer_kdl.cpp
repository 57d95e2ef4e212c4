// KDL's side of peer_kdl.hpp: the only unit that includes KDL's headers, compiled without
// the library's -march=native (see peer_kdl.hpp).
#include "peer_kdl.hpp"

#include <kdl/config.h>
#include <kdl/chain.hpp>
#include <kdl/chaindynparam.hpp>
#include <kdl/chainhdsolver_vereshchagin.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <stdexcept>

namespace soa::compare {

namespace {

KDL::Vector kdl_vector(const double v[3]) {
  return KDL::Vector(v[0], v[1], v[2]);
}

/// The KDL joint of a revolute hinge: RotX/RotY/RotZ for a coordinate axis, RotAxis otherwise.
KDL::Joint kdl_joint(const std::string& name, const double a[3]) {
  if (a[0] == 1 && a[1] == 0 && a[2] == 0) return KDL::Joint(name, KDL::Joint::RotX);
  if (a[0] == 0 && a[1] == 1 && a[2] == 0) return KDL::Joint(name, KDL::Joint::RotY);
  if (a[0] == 0 && a[1] == 0 && a[2] == 1) return KDL::Joint(name, KDL::Joint::RotZ);
  return KDL::Joint(name, KDL::Vector::Zero(), kdl_vector(a), KDL::Joint::RotAxis);
}

KDL::Chain kdl_chain(const std::vector<KdlSegment>& segments) {
  KDL::Chain chain;
  for (const KdlSegment& s : segments) {
    const double* R = s.tip_R;
    const KDL::Frame tip(KDL::Rotation(R[0], R[1], R[2], R[3], R[4], R[5], R[6], R[7], R[8]),
                         kdl_vector(s.tip_l));
    const double* J = s.J_cm;
    const KDL::RigidBodyInertia I_O(s.mass, kdl_vector(s.com),
                                    KDL::RotationalInertia(J[0], J[1], J[2], J[3], J[4], J[5]));
    chain.addSegment(KDL::Segment(s.name, kdl_joint(s.name, s.axis), tip, tip.Inverse() * I_O));
  }
  return chain;
}

void check(int code, const char* what) {
  if (code != 0)
    throw std::runtime_error(std::string(what) + " failed (" + std::to_string(code) + ")");
}

}  // namespace

struct KdlPeer::Impl {
  KDL::Chain chain;
  unsigned n;
  KDL::JntArray q, qd, qdd_in, T, tau, qdd, constraint_tau;
  KDL::Wrenches f_ext;
  KDL::JntSpaceInertiaMatrix H;
  KDL::Jacobian alpha;  // 6 x 0: no constraint on the tip
  KDL::JntArray beta;   // 0 entries
  KDL::ChainIdSolver_RNE id;
  KDL::ChainDynParam dyn;
  KDL::ChainHdSolver_Vereshchagin hd;

  Impl(const std::vector<KdlSegment>& segments, const double g[3])
      : chain(kdl_chain(segments)),
        n(chain.getNrOfJoints()),
        q(n),
        qd(n),
        qdd_in(n),
        T(n),
        tau(n),
        qdd(n),
        constraint_tau(n),
        f_ext(chain.getNrOfSegments(), KDL::Wrench::Zero()),
        H(n),
        alpha(0),
        beta(0),
        id(chain, kdl_vector(g)),
        dyn(chain, kdl_vector(g)),
        hd(chain, KDL::Twist(-kdl_vector(g), KDL::Vector::Zero()), 0) {
    alpha.resize(0);
  }
};

KdlPeer::KdlPeer(const std::vector<KdlSegment>& segments, const double g[3])
    : impl_(new Impl(segments, g)) {
  n = impl_->n;
}
KdlPeer::~KdlPeer() = default;

double& KdlPeer::q(int i) {
  return impl_->q(i);
}
double& KdlPeer::qd(int i) {
  return impl_->qd(i);
}
double& KdlPeer::qdd_in(int i) {
  return impl_->qdd_in(i);
}
double& KdlPeer::T(int i) {
  return impl_->T(i);
}
double KdlPeer::tau(int i) const {
  return impl_->tau(i);
}
double KdlPeer::qdd(int i) const {
  return impl_->qdd(i);
}
double KdlPeer::H(int i, int j) const {
  return impl_->H(i, j);
}

void KdlPeer::inverse() {
  Impl& k = *impl_;
  check(k.id.CartToJnt(k.q, k.qd, k.qdd_in, k.f_ext, k.tau), "ChainIdSolver_RNE");
}
void KdlPeer::mass() {
  check(impl_->dyn.JntToMass(impl_->q, impl_->H), "ChainDynParam::JntToMass");
}
void KdlPeer::forward() {
  Impl& k = *impl_;
  check(k.hd.CartToJnt(k.q, k.qd, k.qdd, k.alpha, k.beta, k.f_ext, k.T, k.constraint_tau),
        "ChainHdSolver_Vereshchagin");
}

std::string KdlPeer::version() {
  return KDL_VERSION_STRING;
}

}  // namespace soa::compare
