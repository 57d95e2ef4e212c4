// `make compare`: the library side by side with Orocos KDL and MuJoCo (Debian's packages) on
// the benchmark chains of bench_chain.hpp, N = 7, 50, 200, 1000 by default.
//
//   compare OUTDIR [--sizes 7,50,200,1000] [--passes 9] [--min-ms 20] [--check-only]
//
// For each N: the same chain and random state in the three libraries; first the check that
// they agree on T (inverse dynamics at the random accelerations), M (mass matrix) and qdd
// (forward dynamics at the random hinge forces), as a relative norm difference to ours below
// a stated tolerance (else one line naming the library, the quantity and N, exit 1); then the
// timing, interleaved passes (ours, KDL, MuJoCo, ours, ...), each pass at least --min-ms of
// repeated calls, the median over --passes; then the forward error of each library's result
// against a long double reference computed by our library. Writes OUTDIR/compare.md and
// OUTDIR/compare.csv.
//
// The timed calls, each from joint positions and rates to the result, kinematics included:
//   T    ours: soa::inverse_dynamics; KDL: ChainIdSolver_RNE::CartToJnt; MuJoCo: mj_kinematics,
//        mj_comPos, mj_comVel, mj_rne (with acceleration).
//   M    ours: soa::update_phi + soa::mass_matrix_inertial; KDL: ChainDynParam::JntToMass; MuJoCo:
//        mj_kinematics, mj_comPos, mj_crb, mj_fullM (to dense, as the others give it).
//   qdd  ours: soa::forward_dynamics (articulated bodies, O(N)); KDL:
//        ChainHdSolver_Vereshchagin::CartToJnt with no constraint (O(N)); MuJoCo: what
//        mj_forward does for a chain without constraints: mj_kinematics, mj_comPos, mj_comVel,
//        mj_crb, mj_factorM, mj_rne (bias), mj_solveM (O(N^3) on a chain: M is dense).
#include <sys/utsname.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../bench_chain.hpp"
#include "kdl_chain.hpp"
#include "peer_mujoco.hpp"
#include "soa/soa.hpp"

#ifndef SOA_COMPARE_FLAGS
#define SOA_COMPARE_FLAGS "unknown"
#endif
#ifndef SOA_COMPARE_KDL_DEB
#define SOA_COMPARE_KDL_DEB "unknown"
#endif
#ifndef SOA_COMPARE_MUJOCO_DEB
#define SOA_COMPARE_MUJOCO_DEB "unknown"
#endif
#ifndef SOA_COMPARE_VERSION
#define SOA_COMPARE_VERSION "unknown"
#endif

namespace {

using soa::VecX;
using L = long double;

constexpr int kLibs = 3;
const char* const kLibName[kLibs] = {"ours", "KDL", "MuJoCo"};
constexpr int kQuantities = 3;
const char* const kQuantityName[kQuantities] = {"T", "M", "qdd"};
const char* const kQuantityTitle[kQuantities] = {"Inverse dynamics T", "Mass matrix M",
                                                 "Forward dynamics qdd"};

/// The agreement tolerance on a relative norm difference to ours: 1e-9 for T and M, whose
/// rounding errors are a few eps times a slowly growing function of N (a modelling mistake,
/// a sign or a frame, gives 1e-3 to 1). For qdd, max(1e-9, 10 eps cond(M)) with cond(M) from
/// the long double M: a backward stable forward dynamics is only accurate to about
/// eps cond(M) (cond(M) passes 1e9 on the 1000-link chain).
double tolerance(int quantity, double cond_M) {
  return quantity == 2 ? std::max(1e-9, 10 * soa::eps<double>() * cond_M) : 1e-9;
}

struct Options {
  std::string out;
  std::vector<int> sizes{7, 50, 200, 1000};
  int passes = 9;
  double min_ms = 20;
  bool check_only = false;
};

/// Stops with one line.
[[noreturn]] void fail(const std::string& msg, int code = 2) {
  std::fprintf(stderr, "compare: %s\n", msg.c_str());
  std::exit(code);
}

int parse_int(const std::string& s, const char* what, int lo, int hi) {
  std::size_t used = 0;
  long v = 0;
  try {
    v = std::stol(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != s.size() || s.empty() || v < lo || v > hi)
    fail(std::string(what) + ": '" + s + "' is not an integer in [" + std::to_string(lo) + ", " +
         std::to_string(hi) + "]");
  return int(v);
}

Options parse(int argc, char** argv) {
  const std::string usage =
      "usage: compare OUTDIR [--sizes 7,50,200,1000] [--passes 9] [--min-ms 20] [--check-only]";
  Options o;
  std::vector<std::string> a(argv + 1, argv + argc);
  for (std::size_t i = 0; i < a.size(); ++i) {
    auto value = [&]() -> std::string {
      if (i + 1 >= a.size()) fail(a[i] + " needs a value; " + usage);
      return a[++i];
    };
    if (a[i] == "--sizes") {
      o.sizes.clear();
      std::stringstream ss(value());
      std::string item;
      while (std::getline(ss, item, ',')) o.sizes.push_back(parse_int(item, "--sizes", 1, 5000));
      if (o.sizes.empty()) fail("--sizes: no size given");
    } else if (a[i] == "--passes") {
      o.passes = parse_int(value(), "--passes", 1, 99);
    } else if (a[i] == "--min-ms") {
      o.min_ms = parse_int(value(), "--min-ms", 1, 10000);
    } else if (a[i] == "--check-only") {
      o.check_only = true;
    } else if (a[i] == "-h" || a[i] == "--help") {
      std::puts(usage.c_str());
      std::exit(0);
    } else if (!a[i].empty() && a[i][0] == '-') {
      fail("unknown option '" + a[i] + "'; " + usage);
    } else if (o.out.empty()) {
      o.out = a[i];
    } else {
      fail("one output folder only; " + usage);
    }
  }
  if (o.out.empty()) fail(usage);
  return o;
}

// ---- coordinates: ours tip first, KDL's and MuJoCo's base first ----

/// bf[i]: where the i-th joint from the base sits in our vectors.
std::vector<int> base_first_index(const soa::Model& m) {
  std::vector<int> bf(std::size_t(m.n()));
  for (int i = 0; i < m.n(); ++i) bf[std::size_t(i)] = m.body(m.n() - i).v_offset;
  return bf;
}

template <class Vec>
std::vector<double> to_base_first(const Vec& ours, const std::vector<int>& bf) {
  std::vector<double> v(bf.size());
  for (std::size_t i = 0; i < bf.size(); ++i) v[i] = double(ours[bf[i]]);
  return v;
}

template <class Get>
VecX<double> vec_to_ours(Get get, const std::vector<int>& bf) {
  VecX<double> v(Eigen::Index(bf.size()));
  for (std::size_t i = 0; i < bf.size(); ++i) v[bf[i]] = get(int(i));
  return v;
}

template <class Get>
soa::MatX<double> mat_to_ours(Get get, const std::vector<int>& bf) {
  const auto n = Eigen::Index(bf.size());
  soa::MatX<double> M(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) M(bf[std::size_t(i)], bf[std::size_t(j)]) = get(i, j);
  return M;
}

/// ||a - b|| / ||b||, in long double (Frobenius norm for matrices).
template <class A, class B>
double rel_diff(const A& a, const B& b) {
  const auto d = (a.template cast<L>() - b.template cast<L>()).norm();
  const auto r = b.template cast<L>().norm();
  return double(r > 0 ? d / r : d);
}

// ---- the long double reference ----

soa::ModelT<L> cast_model(const soa::Model& m) {
  std::vector<soa::BodyT<L>> base_first;
  for (int k = m.n(); k >= 1; --k) {
    const soa::Body& B = m.body(k);
    soa::BodyT<L> b;
    b.name = B.name;
    b.M = B.M.cast<L>();
    b.placement = B.placement.cast<L>();
    b.hinge = B.hinge.cast<L>();
    base_first.push_back(b);
  }
  soa::ModelT<L> mL = soa::ModelT<L>::from_base_first(base_first);
  mL.gravity = m.gravity.cast<L>();
  return mL;
}

struct Reference {
  VecX<L> T, qdd;
  soa::MatX<L> M;
  double cond_M = 1;         ///< of the long double M, from its eigenvalues (double)
  double self_residual = 0;  ///< ||ID(qdd) - T|| / ||T||, the reference's own check
};

Reference reference(const soa::bench::Chain& c) {
  Reference r;
  const soa::ModelT<L> m = cast_model(c.model);
  const soa::StateT<L> x{c.x.theta.cast<L>(), c.x.beta.cast<L>()};
  const VecX<L> bd = c.beta_dot.cast<L>(), T = c.T.cast<L>();
  soa::WorkspaceT<L> ws(m);
  const soa::ExternalForces<L> none;
  const Eigen::Index n = m.nv();
  r.T.resize(n), r.qdd.resize(n), r.M.resize(n, n);  // the calls write into sized outputs
  soa::inverse_dynamics(m, x, bd, none, ws, r.T);
  soa::update_phi(m, x.theta, ws);
  std::vector<soa::SpatialInertiaT<L>> R(std::size_t(m.n()));
  soa::mass_matrix_crb(m, x, ws, R, r.M);
  soa::ForwardDynamicsT<L> fd(m);
  soa::forward_dynamics(m, x, T, none, ws, fd, r.qdd);
  VecX<L> back(n);
  soa::inverse_dynamics(m, x, r.qdd, none, ws, back);
  r.self_residual = double((back - T).norm() / T.norm());
  const Eigen::SelfAdjointEigenSolver<soa::MatX<double>> eig(r.M.cast<double>(),
                                                             Eigen::EigenvaluesOnly);
  const auto& ev = eig.eigenvalues();
  r.cond_M = ev[0] > 0 ? ev[ev.size() - 1] / ev[0] : HUGE_VAL;
  return r;
}

// ---- timing ----

using Clock = std::chrono::steady_clock;

/// Keeps the compiler from dropping or merging the timed calls.
inline void clobber() {
  asm volatile("" : : : "memory");
}

/// A timed loop around \p f: runs it reps times, returns the elapsed nanoseconds.
template <class F>
std::function<double(long)> timed(F f) {
  return [f](long reps) mutable {
    const auto t0 = Clock::now();
    for (long r = 0; r < reps; ++r) {
      f();
      clobber();
    }
    return std::chrono::duration<double, std::nano>(Clock::now() - t0).count();
  };
}

struct Timing {
  double median = 0, min = 0, max = 0;  ///< ns per call over the passes
  long reps = 0;                        ///< calls per pass
};

/// Interleaved passes over \p runs: each pass runs every library once, each for its reps
/// (calibrated first so that one pass of it takes at least min_ms).
std::vector<Timing> time_interleaved(std::vector<std::function<double(long)>>& runs,
                                     const Options& o) {
  const double min_ns = o.min_ms * 1e6;
  std::vector<Timing> t(runs.size());
  for (std::size_t k = 0; k < runs.size(); ++k) {
    long reps = 1;
    for (;;) {
      const double ns = runs[k](reps);
      if (ns >= min_ns) break;
      const double grow = ns > 0 ? 1.2 * min_ns / ns : 100;
      reps = std::max(reps + 1, long(double(reps) * std::min(grow, 100.0)));
    }
    t[k].reps = reps;
  }
  std::vector<std::vector<double>> per_call(runs.size());
  for (int p = 0; p < o.passes; ++p)
    for (std::size_t k = 0; k < runs.size(); ++k)
      per_call[k].push_back(runs[k](t[k].reps) / double(t[k].reps));
  for (std::size_t k = 0; k < runs.size(); ++k) {
    std::vector<double>& v = per_call[k];
    std::sort(v.begin(), v.end());
    const std::size_t h = v.size() / 2;
    t[k].median = v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
    t[k].min = v.front();
    t[k].max = v.back();
  }
  return t;
}

// ---- one chain ----

struct Result {
  int n = 0;
  double agree[kQuantities][kLibs] = {};  ///< relative difference to ours (ours: 0)
  double agree_full[2] = {};              ///< MuJoCo's mj_inverse / mj_forward to ours
  double error[kQuantities][kLibs] = {};  ///< relative error against the long double result
  double tol[kQuantities] = {};
  Timing time[kQuantities][kLibs];
  double cond_M = 0, self_residual = 0;
};

Result run_chain(int n, const Options& o) {
  Result res;
  res.n = n;
  soa::bench::Chain c(n, true);
  const soa::Model& model = c.model;
  const std::vector<int> bf = base_first_index(model);

  // Ours.
  soa::Workspace ws(model);
  soa::ForwardDynamics fd(model);
  soa::MassMatrixInertial mw(model);
  VecX<double> T_ours(n), qdd_ours(n);
  soa::MatX<double> M_ours(n, n);
  auto ours_inverse = [&] { soa::inverse_dynamics(model, c.x, c.beta_dot, c.f_ext, ws, T_ours); };
  auto ours_mass = [&] {
    soa::update_phi(model, c.x.theta, ws);
    soa::mass_matrix_inertial(model, c.x, ws, mw, M_ours);
  };
  auto ours_forward = [&] { soa::forward_dynamics(model, c.x, c.T, c.f_ext, ws, fd, qdd_ours); };
  ours_inverse();
  ours_mass();
  ours_forward();

  // KDL.
  const double g[3] = {model.gravity[0], model.gravity[1], model.gravity[2]};
  soa::compare::KdlPeer kdl(soa::compare::kdl_segments(model), g);
  if (int(kdl.n) != n)
    fail("KDL: the chain has " + std::to_string(kdl.n) + " joints, not " + std::to_string(n), 1);
  {
    const auto q = to_base_first(c.x.theta, bf), qd = to_base_first(c.x.beta, bf),
               qdd = to_base_first(c.beta_dot, bf), T = to_base_first(c.T, bf);
    for (int i = 0; i < n; ++i)
      kdl.q(i) = q[i], kdl.qd(i) = qd[i], kdl.qdd_in(i) = qdd[i], kdl.T(i) = T[i];
  }
  auto kdl_inverse = [&] { kdl.inverse(); };
  auto kdl_mass = [&] { kdl.mass(); };
  auto kdl_forward = [&] { kdl.forward(); };
  kdl.inverse();
  kdl.mass();
  kdl.forward();

  // MuJoCo.
  soa::compare::MujocoPeer mj(model, model.gravity);
  mj.set_state(to_base_first(c.x.theta, bf), to_base_first(c.x.beta, bf),
               to_base_first(c.beta_dot, bf));
  mj.T = to_base_first(c.T, bf);
  auto mj_inverse_call = [&] { mj.inverse(); };
  auto mj_mass_call = [&] { mj.mass(); };
  auto mj_forward_call = [&] { mj.forward(); };
  mj.inverse();
  mj.mass();
  mj.forward();

  // The results in our coordinates.
  const VecX<double> T_kdl = vec_to_ours([&](int i) { return kdl.tau(i); }, bf);
  const VecX<double> qdd_kdl = vec_to_ours([&](int i) { return kdl.qdd(i); }, bf);
  const soa::MatX<double> M_kdl =
      mat_to_ours([&](Eigen::Index i, Eigen::Index j) { return kdl.H(i, j); }, bf);
  const VecX<double> T_mj = vec_to_ours([&](int i) { return mj.tau[i]; }, bf);
  const VecX<double> qdd_mj = vec_to_ours([&](int i) { return mj.qacc[i]; }, bf);
  const soa::MatX<double> M_mj =
      mat_to_ours([&](Eigen::Index i, Eigen::Index j) { return mj.M[std::size_t(i * n + j)]; }, bf);
  const std::vector<double> inv_full = mj.full_inverse(), fwd_full = mj.full_forward();
  const VecX<double> T_mj_full = vec_to_ours([&](int i) { return inv_full[i]; }, bf);
  const VecX<double> qdd_mj_full = vec_to_ours([&](int i) { return fwd_full[i]; }, bf);

  const Reference ref = reference(c);
  res.cond_M = ref.cond_M;
  res.self_residual = ref.self_residual;
  for (int q = 0; q < kQuantities; ++q) res.tol[q] = tolerance(q, ref.cond_M);

  const VecX<double>* vecs[kQuantities][kLibs] = {
      {&T_ours, &T_kdl, &T_mj}, {nullptr, nullptr, nullptr}, {&qdd_ours, &qdd_kdl, &qdd_mj}};
  const soa::MatX<double>* mats[kLibs] = {&M_ours, &M_kdl, &M_mj};
  for (int l = 0; l < kLibs; ++l) {
    res.agree[0][l] = rel_diff(*vecs[0][l], T_ours);
    res.agree[1][l] = rel_diff(*mats[l], M_ours);
    res.agree[2][l] = rel_diff(*vecs[2][l], qdd_ours);
    res.error[0][l] = rel_diff(*vecs[0][l], ref.T);
    res.error[1][l] = rel_diff(*mats[l], ref.M);
    res.error[2][l] = rel_diff(*vecs[2][l], ref.qdd);
  }
  res.agree_full[0] = rel_diff(T_mj_full, T_ours);
  res.agree_full[1] = rel_diff(qdd_mj_full, qdd_ours);

  // The check: every library within the tolerance of ours, and ours within it of the
  // long double reference (so that "agreeing with ours" means agreeing with the truth).
  auto check = [&](const char* lib, int q, double value) {
    if (!(value <= res.tol[q])) {
      char line[300];
      std::snprintf(line, sizeof line,
                    "%s disagrees on %s at N = %d: relative difference %.3g > tolerance %.3g", lib,
                    kQuantityName[q], n, value, res.tol[q]);
      fail(line, 1);
    }
  };
  for (int q = 0; q < kQuantities; ++q) {
    check("ours (against the long double reference)", q, res.error[q][0]);
    for (int l = 1; l < kLibs; ++l) check(kLibName[l], q, res.agree[q][l]);
  }
  check("MuJoCo's mj_inverse", 0, res.agree_full[0]);
  check("MuJoCo's mj_forward", 2, res.agree_full[1]);
  std::printf(
      "N = %4d  agree: T %.1e %.1e  M %.1e %.1e  qdd %.1e %.1e  (KDL, MuJoCo; cond M %.1e)\n", n,
      res.agree[0][1], res.agree[0][2], res.agree[1][1], res.agree[1][2], res.agree[2][1],
      res.agree[2][2], res.cond_M);
  std::fflush(stdout);
  if (o.check_only) return res;

  std::vector<std::function<double(long)>> runs[kQuantities] = {
      {timed(ours_inverse), timed(kdl_inverse), timed(mj_inverse_call)},
      {timed(ours_mass), timed(kdl_mass), timed(mj_mass_call)},
      {timed(ours_forward), timed(kdl_forward), timed(mj_forward_call)}};
  for (int q = 0; q < kQuantities; ++q) {
    const std::vector<Timing> t = time_interleaved(runs[q], o);
    for (int l = 0; l < kLibs; ++l) res.time[q][l] = t[std::size_t(l)];
    std::printf("         %-3s ns/joint: ours %.0f  KDL %.0f  MuJoCo %.0f\n", kQuantityName[q],
                t[0].median / n, t[1].median / n, t[2].median / n);
    std::fflush(stdout);
  }
  return res;
}

// ---- the machine and the report ----

std::string trim(std::string s) {
  const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

std::string machine() {
  std::ifstream in("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  int logical = 0;
  std::set<std::string> cores;
  std::string phys;
  while (std::getline(in, line)) {
    const auto colon = line.find(':');
    if (colon == std::string::npos) continue;
    const std::string key = trim(line.substr(0, colon)), value = trim(line.substr(colon + 1));
    if (key == "processor") ++logical;
    if (key == "model name" && model == "unknown CPU") model = value;
    if (key == "physical id") phys = value;
    if (key == "core id") cores.insert(phys + "/" + value);
  }
  if (logical == 0) logical = int(std::thread::hardware_concurrency());
  std::string s = model + ", " + std::to_string(logical) + " logical CPUs";
  if (!cores.empty()) s += " (" + std::to_string(cores.size()) + " cores)";
  utsname u{};
  if (uname(&u) == 0) s += ", " + std::string(u.sysname) + " " + u.release;
  return s;
}

std::string compiler() {
#if defined(__clang__)
  return std::string("Clang ") + __clang_version__;
#elif defined(__GNUC__)
  return std::string("GCC ") + __VERSION__;
#else
  return "unknown compiler";
#endif
}

std::string fmt(const char* f, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}

void write_reports(const std::vector<Result>& results, const Options& o) {
  const std::string csv_path = o.out + "/compare.csv", md_path = o.out + "/compare.md";
  std::ofstream csv(csv_path), md(md_path);
  if (!csv || !md) fail("cannot write " + md_path + " and " + csv_path, 1);
  csv << "quantity,n,library,ns_per_call,ns_per_call_min,ns_per_call_max,ns_per_joint,"
         "ratio_to_ours,calls_per_pass,passes,rel_diff_to_ours,tolerance,rel_error_long_double\n";
  csv.precision(6);
  for (const Result& r : results)
    for (int q = 0; q < kQuantities; ++q)
      for (int l = 0; l < kLibs; ++l) {
        const Timing& t = r.time[q][l];
        csv << kQuantityName[q] << ',' << r.n << ',' << kLibName[l] << ',' << t.median << ','
            << t.min << ',' << t.max << ',' << t.median / r.n << ','
            << t.median / r.time[q][0].median << ',' << t.reps << ',' << o.passes << ','
            << r.agree[q][l] << ',' << r.tol[q] << ',' << r.error[q][l] << '\n';
      }

  char date[64];
  const std::time_t now = std::time(nullptr);
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  md << "Written by `tests/bench/compare/compare.cpp` (`make compare`) on " << date << ".\n\n";
  md << "- Machine: " << machine() << "\n";
  md << "- Compiler: " << compiler() << "; flags of ours and of the calling code: `"
     << SOA_COMPARE_FLAGS << "`. KDL and MuJoCo are Debian's shared libraries, built with "
     << "Debian's flags; the one unit that calls KDL (peer_kdl.cpp) is compiled without "
     << "-march=native, as libkdl is (its Eigen members' layout).\n";
  md << "- Libraries: soa " << SOA_COMPARE_VERSION << " with Eigen " << EIGEN_WORLD_VERSION << '.'
     << EIGEN_MAJOR_VERSION << '.' << EIGEN_MINOR_VERSION << "; Orocos KDL "
     << soa::compare::KdlPeer::version() << " (Debian liborocos-kdl-dev " << SOA_COMPARE_KDL_DEB
     << "); MuJoCo " << mj_versionString() << " (Debian libmujoco-dev " << SOA_COMPARE_MUJOCO_DEB
     << ").\n";
  md << "- Timing: " << o.passes << " interleaved passes (ours, KDL, MuJoCo, ours, ...), each "
     << "at least " << o.min_ms << " ms of repeated calls; the median time per call, divided "
     << "by N. Ratios are theirs / ours (above 1: ours is faster).\n";
  md << "- Errors: relative norm of the difference to our result computed in `long double` "
     << "(the model written in double and cast).\n\n";

  md << "Agreement before timing: relative norm difference of each peer's result to ours "
     << "(Frobenius norm for M), and the tolerance it must stay under: 1e-9 for T and M, "
     << "max(1e-9, 10 eps cond(M)) for qdd (cond(M) of the long double M). MuJoCo's own "
        "`mj_inverse` and `mj_forward` are checked too.\n\n";
  md << "| N | cond(M) | T: KDL | T: MuJoCo | T: mj_inverse | tol | M: KDL | M: MuJoCo | tol "
        "| qdd: KDL | qdd: MuJoCo | qdd: mj_forward | tol |\n";
  md << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Result& r : results) {
    md << "| " << r.n << " | " << fmt("%.1e", r.cond_M);
    md << " | " << fmt("%.1e", r.agree[0][1]) << " | " << fmt("%.1e", r.agree[0][2]) << " | "
       << fmt("%.1e", r.agree_full[0]) << " | " << fmt("%.0e", r.tol[0]);
    md << " | " << fmt("%.1e", r.agree[1][1]) << " | " << fmt("%.1e", r.agree[1][2]) << " | "
       << fmt("%.0e", r.tol[1]);
    md << " | " << fmt("%.1e", r.agree[2][1]) << " | " << fmt("%.1e", r.agree[2][2]) << " | "
       << fmt("%.1e", r.agree_full[1]) << " | " << fmt("%.0e", r.tol[2]) << " |\n";
  }
  const char* calls[kQuantities] = {
      "ours `soa::inverse_dynamics`; KDL `ChainIdSolver_RNE::CartToJnt`; MuJoCo "
      "`mj_kinematics`, `mj_comPos`, `mj_comVel`, `mj_rne` (with acceleration).",
      "ours `soa::update_phi` + `soa::mass_matrix_inertial`; KDL `ChainDynParam::JntToMass`; "
      "MuJoCo "
      "`mj_kinematics`, `mj_comPos`, `mj_crb`, `mj_fullM` (dense, as the others give it).",
      "ours `soa::forward_dynamics` (articulated bodies, O(N)); KDL "
      "`ChainHdSolver_Vereshchagin::CartToJnt` with no constraint (O(N)); MuJoCo `mj_kinematics`, "
      "`mj_comPos`, `mj_comVel`, `mj_crb`, `mj_factorM`, `mj_rne` (bias), `mj_solveM`: "
      "`mj_forward` without its constraint, sensor and actuator stages (O(N^3) on a chain, "
      "whose M is dense)."};
  for (int q = 0; q < kQuantities; ++q) {
    md << "\n**" << kQuantityTitle[q] << ".** Timed: " << calls[q] << "\n\n";
    md << "| N | ours ns/joint | KDL ns/joint | MuJoCo ns/joint | KDL / ours | MuJoCo / ours | "
          "error ours | error KDL | error MuJoCo |\n";
    md << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const Result& r : results) {
      const double t0 = r.time[q][0].median;
      md << "| " << r.n;
      for (int l = 0; l < kLibs; ++l) md << " | " << fmt("%.1f", r.time[q][l].median / r.n);
      for (int l = 1; l < kLibs; ++l) md << " | " << fmt("%.2f", r.time[q][l].median / t0);
      for (int l = 0; l < kLibs; ++l) md << " | " << fmt("%.1e", r.error[q][l]);
      md << " |\n";
    }
  }
  md << "\nThe long double reference checks itself: our inverse dynamics of its qdd gives "
        "back T within";
  for (const Result& r : results)
    md << " " << fmt("%.0e", r.self_residual) << " (N = " << r.n << ")";
  md << ", relative.\n";
  if (!csv || !md) fail("writing " + md_path + " and " + csv_path + " failed", 1);
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  soa::compare::mujoco_handlers();
  if (!o.check_only && !std::filesystem::is_directory(o.out))
    fail("the output folder '" + o.out + "' does not exist");
  try {
    std::vector<Result> results;
    for (int n : o.sizes) results.push_back(run_chain(n, o));
    if (!o.check_only) {
      write_reports(results, o);
      std::printf("compare: wrote %s/compare.md and compare.csv\n", o.out.c_str());
    }
  } catch (const std::exception& e) {
    fail(e.what(), 1);
  }
  return 0;
}
