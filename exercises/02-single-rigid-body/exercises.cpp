// Lesson 2 exercises: replace each body with your code (statements in exercises.hpp).
#include <Eigen/Cholesky>

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

SpinStability spin_stability(const Vec3<double>& J, int axis, double spin) {
  (void)J, (void)axis, (void)spin;
  throw exercise::NotDone("2.6 spin_stability");
}

FreeBodyState lie_euler_step(const SpatialInertia& M, const FreeBodyState& x0, const Force& f,
                             double h) {
  throw exercise::NotDone("2.7 lie_euler_step");
  // The step as given: it has exactly one bug. Find it, fix it, and delete the throw above.
  const Vec3<double> w = x0.V.angular(), v = x0.V.linear();
  // The rates at x0 (exercise 2.3): alpha = M^-1 (f - b), w_dot = alpha_w,
  // v_dot = alpha_v - w x v, r_dot = R v.
  const Force b(Vec3<double>(w.cross(M.J() * w)), Vec3<double>(w.cross(w.cross(M.h()))));
  const Vec6<double> alpha = M.matrix().llt().solve((f - b).vector());
  Vec6<double> V_dot;
  V_dot << alpha.head<3>(), alpha.tail<3>() - w.cross(v);
  const Vec3<double> r_dot = x0.q.rotate(v);
  // One step of length h with the rates held constant.
  FreeBodyState x1;
  x1.q = UnitQuaternion::exp(h * w) * x0.q;
  x1.r = x0.r + h * r_dot;
  x1.V = Velocity(Vec6<double>(x0.V.vector() + h * V_dot));
  return x1;
}

}  // namespace soa::ex02
