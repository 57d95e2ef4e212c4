// A soa::Model of revolute hinges as the plain KDL segments of peer_kdl.hpp (base first).
#pragma once

#include <stdexcept>
#include <vector>

#include "peer_kdl.hpp"
#include "soa/chain.hpp"

namespace soa::compare {

/// \p m as KDL segments (revolute hinges only; std::runtime_error otherwise).
inline std::vector<KdlSegment> kdl_segments(const Model& m) {
  std::vector<KdlSegment> segments;
  const int n = m.n();
  for (int i = 0; i < n; ++i) {  // base first: our body k = n - i
    const Body& B = m.body(n - i);
    if (B.hinge.type != HingeType::Revolute)
      throw std::runtime_error("KDL chain: body '" + B.name + "' is not revolute");
    if (i == 0 &&
        (B.placement.l() != Vec3<double>::Zero() || B.placement.R() != Mat3<double>::Identity()))
      throw std::runtime_error("KDL chain: the first hinge must sit at the base origin");
    KdlSegment s;
    s.name = B.name;
    const Pose tip = i + 1 < n ? m.body(n - i - 1).placement : Pose();
    for (int r = 0; r < 3; ++r) {
      s.axis[r] = B.hinge.axis[r];
      s.tip_l[r] = tip.l()[r];
      s.com[r] = B.M.p()[r];
      for (int c = 0; c < 3; ++c) s.tip_R[3 * r + c] = tip.R()(r, c);
    }
    s.mass = B.M.mass();
    const Mat3<double> Jc = B.M.J_cm();
    const double J[6] = {Jc(0, 0), Jc(1, 1), Jc(2, 2), Jc(0, 1), Jc(0, 2), Jc(1, 2)};
    for (int k = 0; k < 6; ++k) s.J_cm[k] = J[k];
    segments.push_back(s);
  }
  return segments;
}

}  // namespace soa::compare
