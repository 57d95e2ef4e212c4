// Lesson 2 exercises: replace each body with your code (statements in exercises.hpp).
#include "exercises.hpp"

#include "not_done.hpp"

namespace soa::ex02 {

Force gyroscopic_term(const SpatialInertia& M, const Velocity& V) {
  (void)M, (void)V;
  throw exercise::NotDone("2.1 gyroscopic_term");
}

Force spatial_force(double m, const Mat3<double>& J_C, const Vec3<double>& p, const Velocity& V,
                    const Acceleration& alpha) {
  (void)m, (void)J_C, (void)p, (void)V, (void)alpha;
  throw exercise::NotDone("2.2 spatial_force");
}

FreeBodyRateT<double> body_rates(const SpatialInertia& M, const FreeBodyState& x, const Force& f) {
  (void)M, (void)x, (void)f;
  throw exercise::NotDone("2.3 body_rates");
}

FreeBodyState rk4_torque_free(const SpatialInertia& M, const FreeBodyState& x0, double h) {
  (void)M, (void)x0, (void)h;
  throw exercise::NotDone("2.4 rk4_torque_free");
}

Force body_frame_force(const SpatialInertia& M, const Velocity& V, const Acceleration& V_dot) {
  (void)M, (void)V, (void)V_dot;
  throw exercise::NotDone("2.5 body_frame_force");
}

}  // namespace soa::ex02
