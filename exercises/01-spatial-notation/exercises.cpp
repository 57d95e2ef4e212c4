// Lesson 1 exercises: write each function here (the statements are in exercises.hpp), then
// run `make exercises`. Delete the `throw` line of an exercise when you start it.
#include "exercises.hpp"

#include "not_done.hpp"

namespace soa::ex01 {

Force apply_phi(const Phi& phi_xy, const Force& f_y) {
  (void)phi_xy;
  (void)f_y;
  throw exercise::NotDone("1.1 apply_phi");
}

Acceleration spatial_cross(const Velocity& X, const Velocity& Y) {
  (void)X;
  (void)Y;
  throw exercise::NotDone("1.2 spatial_cross");
}

SpatialInertia parallel_axis(const Phi& phi_xy, const SpatialInertia& M_y) {
  (void)phi_xy;
  (void)M_y;
  throw exercise::NotDone("1.3 parallel_axis");
}

UnitQuaternion quaternion_from_axis_angle(const Vec3<double>& n, double theta) {
  (void)n;
  (void)theta;
  throw exercise::NotDone("1.4 quaternion_from_axis_angle");
}

double kinetic_energy(const SpatialInertia& M_x, const Velocity& V_x) {
  (void)M_x;
  (void)V_x;
  throw exercise::NotDone("1.5 kinetic_energy");
}

Velocity reverse_velocity(const Phi& phi_xy, const Velocity& V_xy) {
  (void)phi_xy;
  (void)V_xy;
  throw exercise::NotDone("1.6 reverse_velocity");
}

Pose exp_twist(const Velocity& xi) {
  (void)xi;
  throw exercise::NotDone("1.7 exp_twist");
}

Force force_cross(const Velocity& X, const Force& f) {
  (void)X;
  (void)f;
  throw exercise::NotDone("1.8 force_cross");
}

int spatial_cross_rank(const Velocity& X) {
  (void)X;
  throw exercise::NotDone("1.9 spatial_cross_rank");
}

}  // namespace soa::ex01
