// The viewer's bodies: what each body of a scene looks like, in its own frame (View::Body).
//
// A body with a hinge is drawn as model body k (the bodies merged into it through locked
// hinges included, ModelT::from_base_first()): its mass, centre of mass and inertia ellipsoid.
// A locked body is only a frame on body k at Scene::Frame::offset(), with its segment.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "detail.hpp"

namespace soa::view {
namespace detail {

Vec3<double> segment(const Scene& scene, std::size_t i) {
  const Scene::Frame& F = scene.frames[i];
  if (i + 1 == scene.frames.size()) {
    // The last body: its own centre of mass (a body with a hinge carries nothing further
    // out, so M(k)'s centre is its own).
    const SpatialInertia& M = scene.model.body(F.k).M;
    return 2.0 * (F.locked || !(M.mass() > 0) ? F.own_com() : Vec3<double>(M.p()));
  }
  // The next body's hinge point on body k (the carrier of both F and the next frame):
  // O_{k'}^+ = placement(k') for a next body k' with a hinge (k' = k - 1, hinge k' sits on
  // body k' + 1 = k), or the next locked frame's origin; then in F's coordinates.
  const Scene::Frame& next = scene.frames[i + 1];
  const Vec3<double> on_k =
      next.locked ? next.offset().l() : Vec3<double>(scene.model.body(next.k).placement.l());
  return F.offset().inverse().apply(on_k);
}

}  // namespace detail

namespace {

/// The inertia ellipsoid of a body of mass \p m and inertia \p J_cm about its centre of mass:
/// the uniform solid ellipsoid with the same inertia, \f$J_i = m (a_j^2 + a_k^2)/5\f$, so
/// \f$a_i = \sqrt{5 (J_j + J_k - J_i) / (2m)}\f$ along the principal axes (rounding may make a
/// flat body's \f$J_j + J_k - J_i\f$ slightly negative: 0).
void set_ellipsoid(double m, const Mat3<double>& J_cm, Body& b) {
  const Eigen::SelfAdjointEigenSolver<Mat3<double>> es(J_cm);
  const Vec3<double> J = es.eigenvalues();
  Mat3<double> R = es.eigenvectors();             // columns: the principal axes in the body frame
  if (R.determinant() < 0) R.col(2) = -R.col(2);  // right-handed: a rotation
  for (int i = 0; i < 3; ++i) {
    const double d = J[(i + 1) % 3] + J[(i + 2) % 3] - J[i];
    b.radii[i] = std::sqrt(std::max(0.0, 5 * d / (2 * m)));
  }
  const Eigen::Matrix<double, 4, 1> q = UnitQuaternion::from_matrix(R).coeffs();
  b.axes_quaternion = {q[0], q[1], q[2], q[3]};
}

}  // namespace

View view_of(const Scene& scene) {
  View v;
  v.title = scene.title;
  v.gravity = scene.model.gravity;
  const std::size_t n = scene.frames.size();
  v.bodies.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Scene::Frame& F = scene.frames[i];
    const soa::Body& B = scene.model.body(F.k);
    Body b;
    b.name = F.name;
    b.segment = detail::segment(scene, i);
    if (F.locked) {
      b.hinge = hinge_type_name(HingeType::Locked);
      b.com = F.own_com();
    } else {
      b.hinge = hinge_type_name(B.hinge.type);
      if (B.hinge.type == HingeType::Revolute || B.hinge.type == HingeType::Prismatic)
        b.axis = B.hinge.axis;  // in O_k^+ and in O_k alike: the hinge moves along it
      b.mass = B.M.mass();
      if (b.mass > 0) {  // a massless body (a frame on a hinge) has no ellipsoid
        b.com = B.M.p();
        set_ellipsoid(b.mass, B.M.J_cm(), b);
      }
    }
    v.bodies.push_back(std::move(b));
  }
  if (n > 0) {
    v.tip_body = int(n) - 1;
    v.tip_point = v.bodies.back().segment;
  }
  return v;
}

}  // namespace soa::view
