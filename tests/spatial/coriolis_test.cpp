/// \file
/// Property test of the propagation of spatial accelerations (lesson 1, slides 59-61):
///   alpha_H(A,C) = phi*(B,C) alpha_H(A,B) + alpha_H(B,C) + a_H,   H = A, B, C,
/// with a_H = coriolis(H, V(A,B), V(B,C), l(B,C)), against central finite differences of
/// smooth random motions of three frames (frame_motion.hpp): B moves relative to the
/// inertial frame A, C relative to B, and V(A,C) comes from C's own attitude and origin.
///
/// alpha_H(F,G) = d_H V(F,G) is the derivative of the coordinate-free vector V(F,G) seen
/// from frame H. Every vector is written in A coordinates, where the derivative seen from A
/// is that of the components, and seen from H it is d_H x = d_A x - omega(A,H) x x, with
/// omega(A,A) = 0, omega(A,B) from V(A,B) and omega(A,C) from V(A,C). The differences and
/// their tolerance, kFdTolerance = 1e-8 relative, are those of frame_motion.hpp.
#include "frame_motion.hpp"
#include "spatial_support.hpp"

namespace soa::test {
namespace {

/// d_H V for a spatial vector V(t) written in A coordinates: derivative() of its components
/// (frame_motion.hpp), less omega(A,H) x (each 3-vector part).
template <class GetV>
Acceleration derivative_in(const Vec3<double>& omega_AH, GetV V, double t) {
  const Vec6<double> d = derivative([&](double u) { return V(u).vector(); }, t);
  const Vec6<double> v = V(t).vector();
  return Acceleration(Vec3<double>(d.head<3>()) - omega_AH.cross(Vec3<double>(v.head<3>())),
                      Vec3<double>(d.tail<3>()) - omega_AH.cross(Vec3<double>(v.tail<3>())));
}

/// The residual of the propagation for derivative frame \p H, with the Coriolis term of
/// frame \p term (the library's, which must match when term == H).
double propagation_residual(const ThreeFrames& frames, double t, DerivativeFrame H,
                            DerivativeFrame term) {
  const ThreeFrames::Snapshot s = frames.at(t);
  const Vec3<double> omega_AH = H == DerivativeFrame::A   ? Vec3<double>::Zero()
                                : H == DerivativeFrame::B ? Vec3<double>(s.V_AB.angular())
                                                          : Vec3<double>(s.V_AC.angular());
  const auto V_AB = [&](double u) { return frames.at(u).V_AB; };
  const auto V_BC = [&](double u) { return frames.at(u).V_BC; };
  const auto V_AC = [&](double u) { return frames.at(u).V_AC; };
  const Acceleration alpha_AB = derivative_in(omega_AH, V_AB, t);
  const Acceleration alpha_BC = derivative_in(omega_AH, V_BC, t);
  const Acceleration alpha_AC = derivative_in(omega_AH, V_AC, t);
  const Acceleration a = coriolis(term, s.V_AB, s.V_BC, s.l_BC);
  const Acceleration rhs = Phi::translation(s.l_BC).transpose_apply(alpha_AB) + alpha_BC + a;
  const double scale =
      std::max({1.0, double(alpha_AC.vector().norm()), double(alpha_AB.vector().norm()),
                double(alpha_BC.vector().norm()), double(a.vector().norm())});
  return (alpha_AC - rhs).vector().norm() / scale;
}

const char* frame_name(DerivativeFrame H) {
  return H == DerivativeFrame::A ? "A" : H == DerivativeFrame::B ? "B" : "C";
}

class spatial_Coriolis : public ::testing::TestWithParam<DerivativeFrame> {};

// alpha_H(A,C) = phi*(B,C) alpha_H(A,B) + alpha_H(B,C) + a_H (slide 61) for H = A, B, C.
TEST_P(spatial_Coriolis, AccelerationPropagationMatchesFiniteDifferences) {
  const DerivativeFrame H = GetParam();
  Random<double> rnd;
  Worst worst(std::string("acceleration propagation, H = ") + frame_name(H));
  for (int i = 0; i < kCases; ++i) {
    const ThreeFrames frames = ThreeFrames::random(rnd);
    worst.add(propagation_residual(frames, rnd.uniform(0, 5), H, H), i);
  }
  EXPECT_LE(worst.value(), kFdTolerance);
}

// The test can fail: the Coriolis term of another frame gives an O(1) residual in some case.
TEST_P(spatial_Coriolis, WrongFrameFails) {
  const DerivativeFrame H = GetParam();
  const DerivativeFrame wrong = H == DerivativeFrame::A   ? DerivativeFrame::B
                                : H == DerivativeFrame::B ? DerivativeFrame::C
                                                          : DerivativeFrame::A;
  Random<double> rnd;
  Worst worst(std::string("propagation with a wrong term (must fail), H = ") + frame_name(H));
  for (int i = 0; i < kCases; ++i) {
    const ThreeFrames frames = ThreeFrames::random(rnd);
    worst.add(propagation_residual(frames, rnd.uniform(0, 5), H, wrong), i);
  }
  EXPECT_GT(worst.value(), 0.1);
}

INSTANTIATE_TEST_SUITE_P(Frames, spatial_Coriolis,
                         ::testing::Values(DerivativeFrame::A, DerivativeFrame::B,
                                           DerivativeFrame::C),
                         [](const ::testing::TestParamInfo<DerivativeFrame>& info) {
                           return std::string("H") + frame_name(info.param);
                         });

}  // namespace
}  // namespace soa::test
