/// \file
/// The extreme chains of lesson 6, section 7 (the start of the stability suite): their
/// construction, the mass matrix from the composite inertias one column at a time, the
/// reference columns by Newton-Euler, the inverse mass matrix by the articulated body recursion
/// at rest, and the evaluation of one case into a row of `l6_extreme.csv`.
#pragma once

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "report.hpp"
#include "soa/chain.hpp"
#include "soa/soa.hpp"

namespace soa::lesson::extreme {

using VecX = soa::VecX<double>;
using MatX = soa::MatX<double>;
using Vec3 = soa::Vec3<double>;
using soa::lesson::csv_field;
using soa::lesson::num;

/// One family of extreme chains at one n: n revolute hinges, every axis along z; hinge k
/// sits on body k+1 one metre out along x; body k is a point-like body of mass m(k) with
/// its centre of mass half a metre out along x and the isotropic rotational inertia J about
/// it. Masses alternate from the base out: the heavier body has mass 1, the lighter
/// 1/|ratio|; \p ratio is the mass of the second body from the base over the first (1e-8:
/// heavy first, 1e8: light first). At \f$\theta = 0\f$ the chain is straight; \p pose_seed
/// > 0 draws every angle uniform in \f$[-\pi, \pi)\f$ instead. \p tip_mass >= 0 replaces the
/// tip's mass (and makes its inertia a point mass), for the case that must be diagnosed.
struct Spec {
  std::string name;
  int n = 10;
  double ratio = 1;
  double J = 1e-3;
  unsigned pose_seed = 0;
  double tip_mass = -1;
};

/// The chain of \p s in precision S, bodies named by their course number (`b1` is the tip).
template <class S = double>
soa::ModelT<S> make_chain(const Spec& s) {
  const S heavy = 1, light = S(1) / S(std::max(s.ratio, 1 / s.ratio));
  std::vector<soa::BodyT<S>> base_first(static_cast<std::size_t>(s.n));
  for (int i = 0; i < s.n; ++i) {  // i = 0 next to the base: course number k = n - i
    const bool first = i % 2 == 0;
    S m = (first == (s.ratio < 1)) ? heavy : light;
    S J = S(s.J);
    if (i == s.n - 1 && s.tip_mass >= 0) {
      m = S(s.tip_mass);
      J = 0;
    }
    soa::BodyT<S>& b = base_first[std::size_t(i)];
    b.name = "b" + std::to_string(s.n - i);
    b.M = m > 0 ? soa::SpatialInertiaT<S>::from_cm(m, soa::Vec3<S>(S(0.5), 0, 0),
                                                   J * soa::Mat3<S>::Identity())
                : soa::SpatialInertiaT<S>();  // massless
    b.placement = soa::PoseT<S>(soa::Mat3<S>::Identity(),
                                i == 0 ? soa::Vec3<S>::Zero() : soa::Vec3<S>(1, 0, 0));
    b.hinge.type = soa::HingeType::Revolute;
    b.hinge.axis = soa::Vec3<S>::UnitZ();
  }
  return soa::ModelT<S>::from_base_first(std::move(base_first));
}

/// The state of \p s: straight (\f$\theta = 0\f$) or random angles, at rest.
template <class S = double>
soa::StateT<S> make_state(const Spec& s, const soa::ModelT<S>& m) {
  soa::StateT<S> x = soa::StateT<S>::rest(m);
  if (s.pose_seed > 0) {
    std::mt19937_64 gen(s.pose_seed);
    std::uniform_real_distribution<double> angle(-M_PI, M_PI);
    for (int i = 0; i < m.nq(); ++i) x.theta[i] = S(angle(gen));
  }
  return x;
}

/// \f$D(k)\f$ (1 x 1, revolute hinges) of the chain of \p s by the Riccati recursion in long
/// double (\f$\varepsilon = 1.1\cdot 10^{-19}\f$), for the bodies 1..\p k_max: the reference
/// that tells whether the double recursion still had correct digits.
inline std::vector<long double> reference_D(const Spec& s, int k_max) {
  using L = long double;
  const soa::ModelT<L> m = make_chain<L>(s);
  const soa::StateT<L> x = make_state<L>(s, m);
  soa::WorkspaceT<L> ws(m);
  soa::update_phi(m, x.theta, ws);
  soa::ArticulatedT<L> art(m);
  try {
    soa::articulated_inertias(m, x, ws, art);
  } catch (const soa::Error&) {  // also singular in long double: D up to there
  }
  std::vector<L> D;
  for (int k = 1; k <= k_max && art.D[std::size_t(k - 1)].size() > 0; ++k)
    D.push_back(art.D[std::size_t(k - 1)](0, 0));
  return D;
}

/// Column j (0-based dof, tip first) of the mass matrix from the composite inertias, O(n):
/// rows of bodies inboard of (or at) the body of dof j from the force column
/// \f$R(j)H^*(j)\f$ carried inboard by \f$\phi(i,i-1)\f$, \f$\mathcal M(i,j) = H(i)\phi(i,j)
/// R(j)H^*(j)\f$; rows of bodies outboard from the velocity \f$H^*(j)\f$ carried outboard by
/// \f$\phi^*(i+1,i)\f$, \f$\mathcal M(i,j) = H(i)R(i)\phi^*(j,i)H^*(j)\f$ (lesson 5,
/// soa::mass_matrix_crb by columns). Needs update_phi() and the composite inertias \p R.
inline void crb_column(const soa::Model& m, const soa::State& x, const soa::Workspace& ws,
                       const std::vector<soa::SpatialInertia>& R, int dof, VecX& col) {
  col.setZero(m.nv());
  int kj = 1;
  while (m.body(kj).v_offset + m.body(kj).hinge.nv() <= dof) ++kj;
  const soa::Body& Bj = m.body(kj);
  const soa::JointMap<double> Hs = Bj.hinge.H_star(x.theta.data() + Bj.q_offset);
  const soa::Velocity Vj(soa::Vec6<double>(Hs.col(dof - Bj.v_offset)));
  soa::Force F((R[std::size_t(kj - 1)] * Vj).vector());
  for (int i = kj; i <= m.n(); ++i) {  // inboard, and body kj itself
    if (i > kj) F = ws.phi[std::size_t(i - 2)].apply(F);
    const soa::Body& Bi = m.body(i);
    Bi.hinge.H_times(x.theta.data() + Bi.q_offset, F, col.data() + Bi.v_offset);
  }
  soa::Velocity V = Vj;
  for (int i = kj - 1; i >= 1; --i) {  // outboard
    V = ws.phi[std::size_t(i - 1)].transpose_apply(V);
    const soa::Body& Bi = m.body(i);
    Bi.hinge.H_times(x.theta.data() + Bi.q_offset, soa::Force((R[std::size_t(i - 1)] * V).vector()),
                     col.data() + Bi.v_offset);
  }
}

/// Column j of the mass matrix by Newton-Euler inverse dynamics (lesson 4): at rest, without
/// gravity, \f$T = \mathcal M\dot\beta\f$, so \f$\dot\beta = e_j\f$ gives \f$\mathcal M e_j =
/// H\phi M\phi^* H^* e_j\f$, the operator form evaluated by its recursions.
inline void newton_euler_column(const soa::Model& m, const soa::State& x, soa::Workspace& ws,
                                int dof, VecX& col) {
  VecX e = VecX::Zero(m.nv());
  e[dof] = 1;
  col.resize(m.nv());
  soa::inverse_dynamics(m, x, e, {}, ws, col);
}

/// \f$\mathcal M^{-1}T\f$ at rest without gravity by the articulated body recursion (a preview
/// of lessons 7-8), O(n): tip to base \f$z(k) = \phi(k,k-1)z^+(k-1)\f$,
/// \f$\epsilon(k) = T(k) - H(k)z(k)\f$, \f$z^+(k) = z(k) + G(k)\epsilon(k)\f$; base to tip
/// \f$\alpha^+(k) = \phi^*(k+1,k)\alpha(k+1)\f$, \f$\dot\beta(k) = D^{-1}(k)\epsilon(k) -
/// G^*(k)\alpha^+(k)\f$, \f$\alpha(k) = \alpha^+(k) + H^*(k)\dot\beta(k)\f$. Its rounding grows
/// with the conditioning of the \f$D(k)\f$, not with that of \f$\mathcal M\f$.
inline void articulated_solve(const soa::Model& m, const soa::State& x, const soa::Workspace& ws,
                              const soa::Articulated& art, const VecX& T, VecX& beta_dot) {
  const int n = m.n();
  std::vector<soa::Vec6<double>> z_plus(static_cast<std::size_t>(n));
  std::vector<Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1>> eps(static_cast<std::size_t>(n));
  soa::Force z;
  for (int k = 1; k <= n; ++k) {
    const soa::Body& B = m.body(k);
    const std::size_t i = std::size_t(k - 1);
    z = k > 1 ? ws.phi[i - 1].apply(soa::Force(z_plus[i - 1])) : soa::Force();
    double Hz[6] = {};
    B.hinge.H_times(x.theta.data() + B.q_offset, z, Hz);
    eps[i].resize(B.hinge.nv());
    for (int r = 0; r < B.hinge.nv(); ++r) eps[i][r] = T[B.v_offset + r] - Hz[r];
    z_plus[i] = z.vector() + art.G[i] * eps[i];
  }
  beta_dot.resize(m.nv());
  soa::Acceleration alpha;
  for (int k = n; k >= 1; --k) {
    const soa::Body& B = m.body(k);
    const std::size_t i = std::size_t(k - 1);
    const soa::Acceleration alpha_plus = ws.phi[i].transpose_apply(alpha);
    const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 6, 1> bd =
        art.D[i].ldlt().solve(eps[i]) - art.G[i].transpose() * alpha_plus.vector();
    beta_dot.segment(B.v_offset, B.hinge.nv()) = bd;
    alpha = soa::Acceleration(
        (alpha_plus.vector() + B.hinge.H_star(x.theta.data() + B.q_offset) * bd).eval());
  }
}

/// What section 7 records of one case: a row of `l6_extreme.csv`.
struct Result {
  Spec spec;
  std::string reference;      ///< what the CRB mass matrix was compared with
  int columns = 0;            ///< how many of its columns
  double error = NAN;         ///< max |M_crb - M_ref| over those columns / max_k M(k,k)
  double tol = NAN;           ///< the tolerance of error
  double lambda_max = NAN;    ///< of M (n <= 500)
  double cond = NAN;          ///< lambda_max(M) lambda_max(M^-1), M^-1 by articulated_solve
  double cond_eig = NAN;      ///< lambda_max(M) / lambda_min(M), both from eig(M)
  double min_D = NAN;         ///< min_k lambda_min(D(k)), over the bodies the recursion reached
  double D_error = NAN;       ///< max_k |D(k) - D_long_double(k)| / D_long_double(k), same bodies
  double column_check = NAN;  ///< crb_column() against mass_matrix_crb() (n <= kDenseMax)
  double min_ratio = NAN;     ///< min_k of soa::singular_D_ratio()
  int min_ratio_body = 0;     ///< where
  bool diagnosed = false;     ///< soa::articulated_inertias refused the chain
  std::string message;        ///< its soa::Error
  std::string status() const {
    if (diagnosed) return "diagnosed: " + message;
    return error <= tol ? "solved" : "FAILED: mass matrix error above tolerance";
  }
};

/// The largest n for which section 7 forms the whole matrix (and cond(M)), and the largest
/// for which it builds the dense 6n x 6n operators.
constexpr int kDenseMax = 500;
constexpr int kOperatorMax = 100;
constexpr int kSampledColumns = 8;

/// Evaluates one case: the mass matrix from R against the operator form (dense for
/// n <= kOperatorMax, by Newton-Euler columns beyond: all of them up to kDenseMax, then
/// kSampledColumns spread from tip to base), cond(M) for n <= kDenseMax, and D(k) along the
/// chain by the Riccati recursion, which may refuse the chain with soa::Error.
inline Result evaluate(const Spec& s) {
  Result r;
  r.spec = s;
  const soa::Model m = make_chain(s);
  const soa::State x = make_state(s, m);
  const int n = m.n(), nv = m.nv();
  soa::Workspace ws(m);
  soa::update_phi(m, x.theta, ws);
  std::vector<soa::SpatialInertia> R(static_cast<std::size_t>(n));
  soa::composite_inertias(m, ws, R);
  // The scale of M: its largest entry is on the diagonal, M(k,k) = H(k) R(k) H*(k).
  double scale = 0;
  for (int k = 1; k <= n; ++k) {
    const soa::Body& B = m.body(k);
    const soa::JointMap<double> Hs = B.hinge.H_star(x.theta.data() + B.q_offset);
    scale = std::max(scale, (Hs.transpose() * R[std::size_t(k - 1)].matrix() * Hs).maxCoeff());
  }
  // Each entry is a sum of at most n terms whose sizes add up to at most max_k M(k,k)
  // (Cauchy-Schwarz in the metric M(j)), each carried through at most n steps of phi; both
  // forms round alike: c n eps relative to the largest entry, with c = 16.
  r.tol = 16 * n * soa::eps<double>();
  MatX M;
  if (n <= kDenseMax) {
    soa::mass_matrix_crb(m, x, ws, R, M);
    MatX M_ref;
    if (n <= kOperatorMax) {
      r.reference = "operator form H phi M phi* H* (dense)";
      M_ref = soa::Operators::build(m, x, {}).mass_matrix();
    } else {
      r.reference = "Newton-Euler M e_j, every column";
      M_ref.resize(nv, nv);
      VecX col;
      for (int j = 0; j < nv; ++j) {
        newton_euler_column(m, x, ws, j, col);
        M_ref.col(j) = col;
      }
    }
    r.columns = nv;
    VecX c;
    for (int i = 0; i < kSampledColumns; ++i) {
      const int j = int(std::lround(double(i) * (nv - 1) / (kSampledColumns - 1)));
      crb_column(m, x, ws, R, j, c);
      r.column_check =
          std::max(i == 0 ? 0.0 : r.column_check, (c - M.col(j)).cwiseAbs().maxCoeff() / scale);
    }
    r.error = (M - M_ref).cwiseAbs().maxCoeff() / scale;
    const VecX lambda =
        Eigen::SelfAdjointEigenSolver<MatX>(M, Eigen::EigenvaluesOnly).eigenvalues();
    r.lambda_max = lambda.maxCoeff();
    if (lambda.minCoeff() > 0) r.cond_eig = r.lambda_max / lambda.minCoeff();
  } else {
    r.reference = "Newton-Euler M e_j, sampled columns";
    VecX crb, ne;
    for (int i = 0; i < kSampledColumns; ++i) {
      const int j = int(std::lround(double(i) * (nv - 1) / (kSampledColumns - 1)));
      crb_column(m, x, ws, R, j, crb);
      newton_euler_column(m, x, ws, j, ne);
      r.error = std::max(i == 0 ? 0.0 : r.error, (crb - ne).cwiseAbs().maxCoeff() / scale);
    }
    r.columns = kSampledColumns;
  }
  // The Riccati recursion, and D(k) along the chain up to where it stops.
  soa::Articulated art(m);
  try {
    soa::articulated_inertias(m, x, ws, art);
  } catch (const soa::Error& e) {
    r.diagnosed = true;
    r.message = e.what();
  }
  // The body where it stopped, from the message "... D(k) singular ...": D(k) is computed
  // again there as the recursion found it (whatever the library left in art).
  int k_stop = n + 1;
  if (r.diagnosed) {
    const std::size_t at = r.message.find("D(");
    k_stop = at == std::string::npos ? 1 : std::max(1, std::atoi(r.message.c_str() + at + 2));
  }
  std::vector<double> D_reached;
  for (int k = 1; k <= std::min(n, k_stop); ++k) {
    const soa::Body& B = m.body(k);
    const std::size_t i = std::size_t(k - 1);
    const soa::JointMap<double> Hs = B.hinge.H_star(x.theta.data() + B.q_offset);
    MatX D;
    if (k < k_stop) {
      D = art.D[i];
    } else {
      soa::Mat6<double> P = B.M.matrix();
      if (k > 1) P += soa::transform_symmetric(ws.phi[i - 1], art.P_plus[i - 1]);
      D = Hs.transpose() * P * Hs;
    }
    const double d =
        Eigen::SelfAdjointEigenSolver<MatX>(D, Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
    const double ratio = soa::singular_D_ratio(m, x, ws, art, k, d);  // the library's test
    D_reached.push_back(D(0, 0));
    if (k == 1 || d < r.min_D) r.min_D = d;
    if (k == 1 || ratio < r.min_ratio) {
      r.min_ratio = ratio;
      r.min_ratio_body = k;
    }
  }
  // The same D(k) in long double.
  const std::vector<long double> D_ld = reference_D(s, int(D_reached.size()));
  for (std::size_t i = 0; i < D_ld.size(); ++i)  // NaN when no D(k) is positive
    if (D_ld[i] > 0) {
      const double e = double(std::abs(D_reached[i] - D_ld[i]) / D_ld[i]);
      r.D_error = std::isnan(r.D_error) ? e : std::max(r.D_error, e);
    }
  // cond(M) = lambda_max(M) lambda_max(M^-1): M^-1 column by column by the articulated body
  // recursion, whose accuracy does not depend on cond(M).
  if (n <= kDenseMax && !r.diagnosed) {
    MatX Minv(nv, nv);
    VecX e = VecX::Zero(nv), col;
    for (int j = 0; j < nv; ++j) {
      e[j] = 1;
      articulated_solve(m, x, ws, art, e, col);
      Minv.col(j) = col;
      e[j] = 0;
    }
    const MatX S = 0.5 * (Minv + Minv.transpose());
    r.cond =
        r.lambda_max *
        Eigen::SelfAdjointEigenSolver<MatX>(S, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
  }
  return r;
}

/// The pose and the masses of a case in words, e.g. "straight, m(k+1)/m(k) = 1e-08".
inline std::string describe(const Spec& s) {
  std::string d = s.pose_seed > 0 ? "random pose" : "straight";
  if (s.ratio != 1) d += ", mass ratio " + num(s.ratio, "%.0e");
  if (s.tip_mass >= 0) d += ", tip mass " + num(s.tip_mass, "%g");
  return d + ", J " + num(s.J, "%.0e");
}

/// `l6_extreme.csv`: one row per case, with a header line.
inline void write_csv(std::ostream& out, const std::vector<Result>& rows) {
  out << "case,pose,n,mass_ratio,J,tip_mass,reference,columns,error,tol,cond,cond_eig,min_D,"
         "min_ratio,min_ratio_body,D_error_vs_long_double,status\n";
  for (const Result& r : rows) {
    const Spec& s = r.spec;
    out << csv_field(s.name) << ',' << (s.pose_seed > 0 ? "random" : "straight") << ',' << s.n
        << ',' << num(s.ratio, "%g") << ',' << num(s.J, "%g") << ','
        << (s.tip_mass >= 0 ? num(s.tip_mass, "%g") : "") << ',' << csv_field(r.reference) << ','
        << r.columns << ',' << num(r.error) << ',' << num(r.tol) << ',' << num(r.cond) << ','
        << num(r.cond_eig) << ',' << num(r.min_D) << ',' << num(r.min_ratio) << ",b"
        << r.min_ratio_body << ',' << num(r.D_error) << ',' << csv_field(r.status()) << '\n';
  }
}

/// `l6_extreme.md`: the short table of the lesson 6 page (Doxygen Markdown, no formulas),
/// the rows of \p rows whose n is in \p ns.
inline void write_markdown(std::ostream& out, const std::vector<Result>& rows,
                           const std::vector<int>& ns) {
  out << "| case | n | error of M from R (tol) | cond(M) | min D(k) | min ratio (body) "
         "| D(k) vs long double | status |\n"
      << "|---|---:|---|---:|---:|---|---:|---|\n";
  for (const Result& r : rows) {
    if (std::find(ns.begin(), ns.end(), r.spec.n) == ns.end()) continue;
    out << "| " << r.spec.name << " | " << r.spec.n << " | " << num(r.error, "%.1e") << " ("
        << num(r.tol, "%.0e") << ") | " << (std::isnan(r.cond) ? "-" : num(r.cond, "%.1e")) << " | "
        << num(r.min_D, "%.2e") << " | " << num(r.min_ratio, "%.1e") << " (b" << r.min_ratio_body
        << ") | " << (std::isnan(r.D_error) ? "-" : num(r.D_error, "%.0e")) << " | " << r.status()
        << " |\n";
  }
}

}  // namespace soa::lesson::extreme
