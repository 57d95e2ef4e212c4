// The timing lab: error against run time of lesson 8's forward dynamics, run by `make run`
// into build/course/labs/timing/ (`make test` runs it with --quick, ctest lab.timing):
//   lab_timing OUTDIR [--quick]
// 1. Revolute benchmark chains, N = 1 ... 2000: the time per call (Google Benchmark, median
//    CPU time of repeated runs) and the forward error against the long double articulated
//    body result of (a) the O(N) articulated body algorithm, (b) CRB + LDLT, (c) the O(N^2)
//    M^-1 times (T - C), each in float and double, and the round trip ID(FD(T)) - T:
//    l8_work_precision.csv, l8_times.md, l8_errors.md, l8_summary.md and the figures
//    l8_time.png, l8_error.png, l8_work_precision.png.
// 2. The extreme chains of lesson 6 with joint rates, in forward dynamics, n up to 10 000:
//    l8_extreme.csv, l8_extreme.md, l8_extreme.png.
// --quick: N <= 50, n <= 100 and a tiny benchmark time, so that the code path is checked
// in seconds.
#include <benchmark/benchmark.h>
#include <sys/utsname.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "args.hpp"
#include "checklist.hpp"
#include "plot.hpp"
#include "problems.hpp"

namespace {

using namespace soa::lesson::timing;
using soa::lesson::cpu_model;
using soa::lesson::csv_field;
using soa::lesson::num;
using soa::lesson::time_text;
namespace fs = std::filesystem;
constexpr double kEps = soa::eps<double>();

// ---------------------------------------------------------------------------------------
// 1. Error against run time on the benchmark chains.

/// The benchmark chain of one N in the three precisions, and the reference result.
struct ProblemSet {
  explicit ProblemSet(int n) : d(benchmark_chain(n)), f(cast<float>(d)), l(cast<long double>(d)) {}
  Problem<double> d;
  Problem<float> f;
  Problem<long double> l;
  soa::VecX<long double> ref;  ///< the articulated body result in long double
  template <class S>
  const Problem<S>& get() const {
    if constexpr (std::is_same_v<S, float>)
      return f;
    else if constexpr (std::is_same_v<S, double>)
      return d;
    else
      return l;
  }
};

/// One row of l8_work_precision.csv.
struct Row {
  Method method = Method::ABA;
  std::string precision;
  int N = 0;
  double time_ns = NAN, forward_error = NAN, roundtrip = NAN;
  std::string note;  ///< why a number is missing
  std::string key() const {
    return std::string(name(method)) + "/" + precision + "/" + std::to_string(N);
  }
};

/// The results of Google Benchmark: the median CPU time of the repetitions (or the single
/// run), per benchmark name, while the console table is printed as usual.
class Collector : public benchmark::ConsoleReporter {
 public:
  Collector() : ConsoleReporter(OO_Tabular) {}  // no colours: the tour keeps the output
  std::map<std::string, double> ns;
  void ReportRuns(const std::vector<Run>& runs) override {
    ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) {
      if (r.error_occurred) continue;
      const bool median = r.run_type == Run::RT_Aggregate && r.aggregate_name == "median";
      const bool single = r.run_type == Run::RT_Iteration && r.repetitions <= 1;
      if (median || single) ns[r.run_name.function_name] = r.GetAdjustedCPUTime();
    }
  }
};

struct Settings {
  bool quick = false;
  std::vector<int> Ns;
  int crb_max = 0, minv_max = 0;  ///< the largest N for CRB + LDLT and for M^-1
  double min_time = 0;            ///< Google Benchmark's minimum time per repetition [s]
  int repetitions = 1;            ///< for calls under kLongCall
};
constexpr double kLongCall = 0.02;  ///< seconds: one repetition only beyond this

/// Solves once (for the error), and registers the timing of the same solver.
template <class S>
void measure(const std::shared_ptr<ProblemSet>& set, Row& row, const Settings& cfg) {
  const Problem<S>& p = set->get<S>();
  soa::VecX<S> bd(p.m.nv());
  double seconds = 0;
  try {
    Solver<S> solver(row.method, p);
    const auto t0 = std::chrono::steady_clock::now();
    solver.solve(bd);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  } catch (const soa::Error& e) {
    row.note = std::string("soa::Error: ") + e.what();
    return;
  }
  row.forward_error = forward_error(bd, set->ref);
  row.roundtrip = round_trip(p, bd);
  const Method method = row.method;
  benchmark::internal::Benchmark* b =
      benchmark::RegisterBenchmark(row.key().c_str(), [set, method](benchmark::State& state) {
        Solver<S> solver(method, set->get<S>());
        soa::VecX<S> beta_dot(set->d.m.nv());
        for (auto _ : state) {
          solver.solve(beta_dot);
          benchmark::DoNotOptimize(beta_dot.data());
          benchmark::ClobberMemory();
        }
      });
  b->Unit(benchmark::kNanosecond)->MinTime(cfg.min_time);
  if (cfg.repetitions > 1 && seconds < kLongCall)
    b->Repetitions(cfg.repetitions)->DisplayAggregatesOnly(true);
}

/// True when the method stopped with soa::Error (a singular D(k) in that precision).
bool refused_note(const Row& r) {
  return r.note.rfind("soa::Error", 0) == 0;
}

/// The row of \p method, \p precision and \p N.
const Row* find(const std::vector<Row>& rows, Method method, const std::string& precision, int N) {
  for (const Row& r : rows)
    if (r.method == method && r.precision == precision && r.N == N) return &r;
  return nullptr;
}

/// Where the articulated body algorithm becomes faster than CRB + LDLT for good: the N, by
/// log-log interpolation of the time ratio between the last N where CRB + LDLT was faster
/// and the next; 0 when the ABA is faster at every N measured, NaN when never.
double crossover(const std::vector<Row>& rows, const std::vector<int>& Ns,
                 const std::string& precision, std::string& text) {
  std::vector<std::pair<int, double>> ratio;  // N, t_ABA / t_CRB
  for (int N : Ns) {
    const Row* a = find(rows, Method::ABA, precision, N);
    const Row* c = find(rows, Method::CRB, precision, N);
    if (a && c && a->time_ns > 0 && c->time_ns > 0) ratio.emplace_back(N, a->time_ns / c->time_ns);
  }
  if (ratio.empty()) {
    text = "no N with both times";
    return NAN;
  }
  int last_slower = -1;  // the last index where ABA is not faster
  for (std::size_t i = 0; i < ratio.size(); ++i)
    if (ratio[i].second >= 1) last_slower = int(i);
  if (last_slower < 0) {
    text = "the articulated body algorithm is faster at every N measured (from N = " +
           std::to_string(ratio.front().first) + ")";
    return 0;
  }
  if (last_slower + 1 == int(ratio.size())) {
    text = "CRB + LDLT is still as fast at N = " + std::to_string(ratio.back().first);
    return NAN;
  }
  const auto [n0, r0] = ratio[std::size_t(last_slower)];
  const auto [n1, r1] = ratio[std::size_t(last_slower) + 1];
  const double t = std::log(r0) / (std::log(r0) - std::log(r1));
  const double N =
      std::exp(std::log(double(n0)) + t * (std::log(double(n1)) - std::log(double(n0))));
  text = "N ≈ " + num(N, "%.0f") + " (CRB + LDLT faster up to N = " + std::to_string(n0) +
         ", the articulated body algorithm from N = " + std::to_string(n1) + ")";
  return N;
}

// ---------------------------------------------------------------------------------------
// 2. The extreme chains in forward dynamics.

/// The results of one extreme case.
struct Extreme {
  Spec spec;
  double cond = NAN;     ///< cond(M) = lambda_max(M) lambda_max(M^-1), n <= kCondMax
  double kappa_D = NAN;  ///< max_k 1 / soa::singular_D_ratio(): conditioning of the pivots
  std::string ref_note;  ///< why there is no reference
  struct Result {
    bool run = false;
    double error = NAN, roundtrip = NAN;
    double bound = NAN;  ///< 16 n eps kappa: kappa_D (ABA) or cond(M) (CRB + LDLT, M^-1)
    std::string status;
  } result[3];  // per Method
};

constexpr int kCondMax = 500;   ///< cond(M) by eigenvalues up to this n
constexpr int kDenseMax = 500;  ///< CRB + LDLT and M^-1 in the extreme cases up to this n
/// The tolerance of every case: six correct digits. A larger error counts as diagnosed when
/// the conditioning explains it, error <= 16 n eps kappa (kappa_D for the articulated body
/// algorithm, cond(M) for CRB + LDLT and M^-1), else as failed.
constexpr double kTol = 1e-6;
constexpr double kBound = 16;

/// The case in words, e.g. "straight, mass ratio 1e-08, J 1e-09".
std::string describe(const Spec& s) {
  std::string d = s.pose_seed > 0 ? "random pose" : "straight";
  if (s.ratio != 1) d += ", mass ratio " + num(s.ratio, "%.0e");
  d += ", J " + num(s.J, "%.0e");
  if (s.rate > 0) d += ", rates up to " + num(s.rate, "%.0e") + " rad/s";
  if (s.tip_mass >= 0) d += ", massless tip";
  return d;
}

/// The soa::Error of a singular D(k) in short: "D(k) singular at body 'bK'".
std::string short_error(const std::string& message) {
  const std::size_t at = message.find("articulated inertia D(");
  if (at == std::string::npos) return message;
  const std::size_t q0 = message.find('\''), q1 = message.find('\'', q0 + 1);
  std::string s = "D(k) singular at body " + message.substr(q0, q1 - q0 + 1);
  const std::size_t r = message.find("RATIO"), eq = message.find("lambda_max(H Q H*) = ");
  if (r == std::string::npos && eq != std::string::npos) {
    const std::size_t v = eq + 21, comma = message.find(',', v);
    s += ", ratio " + message.substr(v, comma - v);
  }
  return s;
}

Extreme evaluate(const Spec& s) {
  Extreme e;
  e.spec = s;
  const Problem<double> pd = extreme_chain(s);
  const Problem<long double> pl = cast<long double>(pd);
  const int n = pd.m.n();
  // The reference: the articulated body algorithm in long double.
  soa::VecX<long double> ref(n);
  bool have_ref = true;
  try {
    Solver<long double>(Method::ABA, pl).solve(ref);
  } catch (const soa::Error& err) {
    have_ref = false;
    e.ref_note = std::string("no reference: long double ABA refused: ") + err.what();
  }
  // kappa_D from the Riccati recursion in double (the library's singularity ratio).
  {
    soa::Workspace ws(pd.m);
    soa::update_phi(pd.m, pd.x.theta, ws);
    soa::Articulated art(pd.m);
    try {
      soa::articulated_inertias(pd.m, pd.x, ws, art);
      double k = 0;
      for (int b = 1; b <= n; ++b)
        k = std::max(k, 1 / soa::singular_D_ratio(pd.m, pd.x, ws, art, b));
      e.kappa_D = k;
    } catch (const soa::Error&) {
    }
  }
  // cond(M) = lambda_max(M) lambda_max(M^-1), M^-1 in long double (O(n^2), no M formed):
  // a largest eigenvalue is well conditioned, a smallest one from M is lost past 1/eps.
  if (n <= kCondMax) {
    Solver<double> crb(Method::CRB, pd);
    soa::VecX<double> tmp(n);
    crb.solve(tmp);
    const double lmax =
        Eigen::SelfAdjointEigenSolver<soa::MatX<double>>(crb.matrix(), Eigen::EigenvaluesOnly)
            .eigenvalues()
            .maxCoeff();
    try {
      Solver<long double> minv(Method::Minv, pl);
      soa::VecX<long double> t(n);
      minv.solve(t);
      const soa::MatX<double> Mi = minv.matrix().cast<double>();
      const soa::MatX<double> sym = 0.5 * (Mi + Mi.transpose());
      e.cond = lmax * Eigen::SelfAdjointEigenSolver<soa::MatX<double>>(sym, Eigen::EigenvaluesOnly)
                          .eigenvalues()
                          .maxCoeff();
    } catch (const soa::Error&) {
      e.cond = INFINITY;  // singular to long double precision
    }
  }
  for (const Method method : {Method::ABA, Method::CRB, Method::Minv}) {
    Extreme::Result& r = e.result[int(method)];
    if (method != Method::ABA && n > kDenseMax) continue;
    r.run = true;
    r.bound = kBound * n * kEps * (method == Method::ABA ? e.kappa_D : e.cond);
    soa::VecX<double> bd(n);
    try {
      Solver<double>(method, pd).solve(bd);
    } catch (const soa::Error& err) {
      r.status = std::string("diagnosed: ") + short_error(err.what());
      continue;
    }
    if (!bd.allFinite()) {
      r.status = "diagnosed: non-finite result (M singular in double)";
      continue;
    }
    r.roundtrip = round_trip(pd, bd);
    if (!have_ref) {
      r.status = "unchecked: the long double reference refused the chain";
      continue;
    }
    r.error = forward_error(bd, ref);
    if (r.error <= kTol)
      r.status = "solved";
    else if (r.error <= r.bound)  // the conditioning is the diagnostic
      r.status = std::string("diagnosed: ") + (method == Method::ABA ? "kappa_D" : "cond(M)") +
                 " bound 16 n eps kappa = " + num(r.bound, "%.0e");
    else
      r.status = "FAILED: error above the tolerance and the conditioning bound";
  }
  return e;
}

/// l8_extreme.csv: one row per case, the three methods side by side (empty where a method
/// did not run or gave no number).
void write_extreme_csv(std::ostream& out, const std::vector<Extreme>& rows) {
  out << "id,case,short,pose,n,mass_ratio,J,rate,tip_mass,cond,kappa_D";
  for (const char* m : {"ABA", "CRB", "Minv"})
    out << ',' << m << "_error," << m << "_roundtrip," << m << "_bound," << m << "_status";
  out << ",reference\n";
  int id = 0;
  for (const Extreme& e : rows) {
    const Spec& s = e.spec;
    out << ++id << ',' << csv_field(describe(s)) << ',' << csv_field(short_name(s)) << ','
        << (s.pose_seed ? "random" : "straight") << ',' << s.n << ',' << num(s.ratio, "%g") << ','
        << num(s.J, "%g") << ',' << num(s.rate, "%g") << ','
        << (s.tip_mass >= 0 ? num(s.tip_mass, "%g") : "") << ',' << num(e.cond) << ','
        << num(e.kappa_D);
    for (const Method m : {Method::ABA, Method::CRB, Method::Minv}) {
      const Extreme::Result& r = e.result[int(m)];
      out << ',' << num(r.error) << ',' << num(r.roundtrip) << ',' << num(r.bound) << ','
          << csv_field(r.run ? r.status : "not run: n > " + std::to_string(kDenseMax));
    }
    out << ',' << csv_field(e.ref_note.empty() ? "long double ABA" : e.ref_note) << '\n';
  }
}

/// One cell of the extreme table: "3.1e-15 solved", "2.0e+00 diagnosed: cond(M) ...".
std::string cell(const Extreme::Result& r) {
  if (!r.run) return "-";
  return (std::isnan(r.error) ? std::string() : num(r.error, "%.1e") + " ") + r.status;
}

void write_extreme_md(std::ostream& out, const std::vector<Extreme>& rows,
                      const std::vector<int>& ns) {
  out << "| case | n | cond(M) | kappa_D | ABA: error, status | CRB + LDLT: error, status | "
         "M^-1 (T - C): error, status | ABA round trip |\n"
      << "|---|---:|---:|---:|---|---|---|---:|\n";
  for (const Extreme& e : rows) {
    if (std::find(ns.begin(), ns.end(), e.spec.n) == ns.end()) continue;
    const Extreme::Result& a = e.result[int(Method::ABA)];
    out << "| " << describe(e.spec) << " | " << e.spec.n << " | "
        << (std::isnan(e.cond) ? "-" : num(e.cond, "%.1e")) << " | "
        << (std::isnan(e.kappa_D) ? "-" : num(e.kappa_D, "%.1e")) << " | " << cell(a) << " | "
        << cell(e.result[int(Method::CRB)]) << " | " << cell(e.result[int(Method::Minv)]) << " | "
        << (std::isnan(a.roundtrip) ? "-" : num(a.roundtrip, "%.1e")) << " |\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  Settings cfg;
  const fs::path out = soa::lesson::output_dir(argc, argv, &cfg.quick);
  if (cfg.quick) {
    cfg.Ns = {1, 2, 4, 7, 12, 20, 50};
    cfg.min_time = 1e-4;
    cfg.repetitions = 1;
  } else {
    cfg.Ns = {1, 2, 4, 7, 12, 20, 50, 100, 200, 500, 1000, 2000};
    cfg.min_time = 0.1;
    cfg.repetitions = 5;
  }
  cfg.crb_max = 2000;
  cfg.minv_max = 2000;
  int bm_argc = 1;
  benchmark::Initialize(&bm_argc, argv);
  soa::lesson::Checklist checks;
  const auto start = std::chrono::steady_clock::now();

  checks.section(std::string("Error against run time: revolute chains") +
                 (cfg.quick ? " (quick mode)" : ""));
  std::vector<Row> rows;
  for (const int N : cfg.Ns) {
    auto set = std::make_shared<ProblemSet>(N);
    set->ref.resize(N);
    Solver<long double>(Method::ABA, set->l).solve(set->ref);
    for (const Method method : {Method::ABA, Method::CRB, Method::Minv, Method::MinvUpsilon})
      for (const std::string precision : {"double", "float"}) {
        Row row;
        row.method = method;
        row.precision = precision;
        row.N = N;
        const int limit = method == Method::CRB                                     ? cfg.crb_max
                          : method == Method::Minv || method == Method::MinvUpsilon ? cfg.minv_max
                                                                                    : N;
        if (N > limit)
          row.note = "skipped: N > " + std::to_string(limit);
        else if (precision == "double")
          measure<double>(set, row, cfg);
        else
          measure<float>(set, row, cfg);
        rows.push_back(row);
      }
  }
  Collector collector;
  benchmark::RunSpecifiedBenchmarks(&collector);
  benchmark::Shutdown();
  for (Row& r : rows) {
    const auto it = collector.ns.find(r.key());
    if (it != collector.ns.end()) r.time_ns = it->second;
  }

  // The CSV (one method and precision after the other, N increasing) and the tables.
  std::stable_sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) {
    return a.method != b.method ? a.method < b.method : a.precision < b.precision;
  });
  std::ofstream csv(out / "l8_work_precision.csv");
  csv << "method,precision,N,time_ns,forward_error,roundtrip,note\n";
  for (const Row& r : rows)
    csv << name(r.method) << ',' << r.precision << ',' << r.N << ',' << num(r.time_ns, "%.1f")
        << ',' << num(r.forward_error) << ',' << num(r.roundtrip) << ',' << csv_field(r.note)
        << '\n';
  csv.close();
  const Method methods[] = {Method::ABA, Method::CRB, Method::Minv, Method::MinvUpsilon};
  std::ofstream times(out / "l8_times.md");
  times << "| N | ABA double | ABA double per joint | ABA float | CRB + LDLT double | "
           "CRB + LDLT float | M^-1 (T - C) double | M^-1 (T - C) float | "
           "M^-1 by Upsilon double | M^-1 by Upsilon float |\n"
        << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  std::ofstream errors(out / "l8_errors.md");
  errors << "| N | ABA double | ABA float | CRB + LDLT double | CRB + LDLT float | "
            "M^-1 (T - C) double | M^-1 (T - C) float | M^-1 by Upsilon double | "
            "M^-1 by Upsilon float |\n"
         << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const int N : cfg.Ns) {
    times << "| " << N;
    errors << "| " << N;
    for (const Method m : methods)
      for (const std::string precision : {"double", "float"}) {
        const Row* r = find(rows, m, precision, N);
        times << " | " << (refused_note(*r) ? "refused" : time_text(r->time_ns));
        if (m == Method::ABA && precision == "double")
          times << " | " << num(r->time_ns / N, "%.0f ns");
        errors << " | "
               << (std::isnan(r->forward_error)
                       ? std::string(refused_note(*r) ? "refused" : "-")
                       : num(r->forward_error, "%.1e") + " (" + num(r->roundtrip, "%.0e") + ")");
      }
    times << " |\n";
    errors << " |\n";
  }
  times.close();
  errors.close();

  // The crossover, the figures' marks, the summary.
  std::string cross_text_d, cross_text_f;
  const double cross_d = crossover(rows, cfg.Ns, "double", cross_text_d);
  const double cross_f = crossover(rows, cfg.Ns, "float", cross_text_f);
  {
    std::ofstream marks(out / "l8_marks.gp");  // read by l8_time.gp
    marks << "# written by lab_timing: the ABA / CRB + LDLT crossover N (0: none)\n"
          << "cross_double = " << (cross_d > 0 ? num(cross_d, "%.3f") : "0") << "\n"
          << "cross_float = " << (cross_f > 0 ? num(cross_f, "%.3f") : "0") << "\n";
  }
  const Row* aba7 = find(rows, Method::ABA, "double", 7);
  double per_joint_min = INFINITY, per_joint_max = 0;
  for (const Row& r : rows)
    if (r.method == Method::ABA && r.precision == "double" && r.N >= 200 && r.time_ns > 0) {
      per_joint_min = std::min(per_joint_min, r.time_ns / r.N);
      per_joint_max = std::max(per_joint_max, r.time_ns / r.N);
    }
  const int N_big = cfg.quick ? 50 : 1000;
  const Row* aba_big = find(rows, Method::ABA, "double", N_big);
  // The round trip beside the forward error: how far apart they fall, and why (the bias
  // forces C of the largest chain against the applied T).
  const Row *rt_low = nullptr, *rt_high = nullptr;  // round trip most below / above the error
  for (const Row& r : rows) {
    if (!(r.forward_error > 0) || !(r.roundtrip > 0)) continue;
    const double q = r.roundtrip / r.forward_error;
    if (!rt_low || q < rt_low->roundtrip / rt_low->forward_error) rt_low = &r;
    if (!rt_high || q > rt_high->roundtrip / rt_high->forward_error) rt_high = &r;
  }
  double C_over_T = NAN;
  {
    const Problem<double> p = benchmark_chain(N_big);
    soa::Workspace ws(p.m);
    soa::VecX<double> C(p.m.nv());
    const soa::VecX<double> zero = soa::VecX<double>::Zero(p.m.nv());
    soa::inverse_dynamics(p.m, p.x, zero, {}, ws, C);
    C_over_T = C.norm() / p.T.norm();
  }
  {
    std::ofstream sum(out / "l8_summary.md");
    utsname u{};
    uname(&u);
    double load[3] = {NAN, NAN, NAN};
    std::ifstream("/proc/loadavg") >> load[0] >> load[1] >> load[2];
    const std::time_t now = std::time(nullptr);
    char date[64];
    std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
    sum << "- Measured on " << date << ": " << cpu_model() << ", "
        << benchmark::CPUInfo::Get().num_cpus << " logical CPUs, " << u.sysname << " " << u.release
        << ", load average " << num(load[0], "%.2f") << " at the start; g++ " << __VERSION__
        << ", flags `" << SOA_TIMING_FLAGS << "`"
        << (cfg.quick ? "; **quick mode** (N ≤ 50, tiny benchmark time)" : "") << ".\n"
        << "- Times: median CPU time per call of " << cfg.repetitions
        << " Google Benchmark repetitions (one for calls over " << num(kLongCall * 1e3, "%.0f")
        << " ms), each of at least " << num(cfg.min_time, "%g") << " s.\n"
        << "- Articulated body algorithm, double: " << time_text(aba7 ? aba7->time_ns : NAN)
        << " at N = 7";
    if (per_joint_max > 0)
      sum << ", " << num(per_joint_min, "%.0f") << "–" << num(per_joint_max, "%.0f")
          << " ns per joint for N ≥ 200";
    sum << ".\n- Crossover, double: " << cross_text_d << "; float: " << cross_text_f << ".\n"
        << "- Forward error at N = " << N_big << " (round trip in parentheses):";
    for (const Method m : methods)
      for (const std::string precision : {"double", "float"}) {
        const Row* r = find(rows, m, precision, N_big);
        sum << " " << name(m) << " " << precision << " "
            << (r && !std::isnan(r->forward_error)
                    ? num(r->forward_error, "%.1e") + " (" + num(r->roundtrip, "%.0e") + ")"
                    : std::string(r && refused_note(*r) ? "refused" : "-"))
            << (m == Method::MinvUpsilon && precision == "float" ? "." : ";");
      }
    for (const Row& r : rows)
      if (r.N == N_big && refused_note(r))
        sum << " " << name(r.method) << " " << r.precision << " refused: " << r.note.substr(12)
            << ".";
    sum << "\n- The report's target, ABA forward error on the 1000-link chain ≤ 1e-12: "
        << (cfg.quick ? std::string("not measured in quick mode")
                      : (aba_big && aba_big->forward_error <= 1e-12 ? "met, " : "NOT met, ") +
                            num(aba_big ? aba_big->forward_error : NAN, "%.1e"))
        << ".\n";
    auto describe_row = [](const Row* r) {
      return std::string(name(r->method)) + " " + r->precision + " at N = " + std::to_string(r->N) +
             ": round trip " + num(r->roundtrip, "%.1e") + ", forward error " +
             num(r->forward_error, "%.1e");
    };
    if (rt_low && rt_high)
      sum << "- The round trip against the forward error: from " << describe_row(rt_low) << ", to "
          << describe_row(rt_high) << ". On the " << N_big
          << "-link chain the bias forces are |C| / |T| = " << num(C_over_T, "%.1e")
          << " times the applied hinge forces.\n";
  }

  int missing = 0, nonfinite = 0, refused = 0;
  double worst_aba = 0;
  for (const Row& r : rows) {
    if (r.note.rfind("skipped", 0) == 0) continue;
    if (refused_note(r)) {
      ++refused;
      continue;
    }
    if (!(r.time_ns > 0)) ++missing;
    if (!std::isfinite(r.forward_error) || !std::isfinite(r.roundtrip)) ++nonfinite;
    if (r.method == Method::ABA && r.precision == "double")
      worst_aba = std::max(worst_aba, r.forward_error / (r.N * kEps));
  }
  checks.check("every method x precision x N that ran timed by Google Benchmark", missing == 0);
  checks.check(
      "every result finite, or refused with soa::Error (" + std::to_string(refused) + " refused)",
      nonfinite == 0);
  checks.check("ABA double forward error, every N (worst / N eps)", worst_aba, 16.0);
  if (!cfg.quick)
    checks.check("ABA double forward error on the 1000-link chain (the report's target)",
                 aba_big ? aba_big->forward_error : NAN, 1e-12);
  checks.check("ABA / CRB + LDLT crossover found (double)", !std::isnan(cross_d));
  checks.check("l8_work_precision.csv, l8_times.md, l8_errors.md, l8_summary.md written",
               bool(csv) && bool(times) && bool(errors));
  for (const char* fig : {"l8_time", "l8_error", "l8_work_precision"})
    checks.check(std::string("figure written: ") + fig + ".png",
                 soa::lesson::plot(std::string(fig) + ".gp", out, std::string(fig) + ".png"));
  std::printf("  crossover (double): %s\n", cross_text_d.c_str());

  // 2. The extreme chains.
  checks.section("Extreme chains in forward dynamics");
  std::vector<Spec> specs;
  const std::vector<int> ns =
      cfg.quick ? std::vector<int>{10, 100} : std::vector<int>{10, 100, 500, 2000, 10000};
  for (const int n : ns) {
    std::vector<Spec> family = {{"", n, 1, 1e-3}, {"", n, 1, 1e-9}};
    for (const double r : {1e-3, 1e3, 1e-6, 1e6, 1e-8, 1e8}) family.push_back({"", n, r, 1e-9});
    for (const double r : {1e-8, 1e8}) family.push_back({"", n, r, 1e-9, 7});
    family.push_back({"", n, 1, 1e-3, 7, 1e3});
    family.push_back({"", n, 1e-6, 1e-9, 7, 1e3});
    if (n == 10 || n == ns.back()) family.push_back({"", n, 1, 1e-3, 0, 0, 0.0});
    for (Spec& s : family) {
      s.name = short_name(s);
      specs.push_back(s);
    }
  }
  std::vector<Extreme> extremes;
  int solved = 0, diagnosed = 0, failed = 0, unchecked = 0;
  bool tip_diagnosed = true;
  for (const Spec& s : specs) {
    extremes.push_back(evaluate(s));
    const Extreme& e = extremes.back();
    std::printf("  %-28s cond %9s  kappa_D %9s", s.name.c_str(), num(e.cond, "%.1e").c_str(),
                num(e.kappa_D, "%.1e").c_str());
    for (const Method m : {Method::ABA, Method::CRB, Method::Minv}) {  // Extreme::result[3]
      const Extreme::Result& r = e.result[int(m)];
      if (!r.run) continue;
      std::printf("  %s %s", name(m),
                  r.status == "solved" ? num(r.error, "%.1e").c_str()
                                       : r.status.substr(0, r.status.find(':')).c_str());
      if (r.status == "solved")
        ++solved;
      else if (r.status.rfind("diagnosed", 0) == 0)
        ++diagnosed;
      else if (r.status.rfind("unchecked", 0) == 0)
        ++unchecked;
      else
        ++failed;
    }
    std::printf("\n");
    if (s.tip_mass >= 0)
      tip_diagnosed = tip_diagnosed && e.result[0].status.rfind("diagnosed", 0) == 0;
  }
  std::printf("  %d results solved, %d diagnosed, %d unchecked, %d failed\n", solved, diagnosed,
              unchecked, failed);
  std::ofstream ecsv(out / "l8_extreme.csv");
  write_extreme_csv(ecsv, extremes);
  ecsv.close();
  std::ofstream emd(out / "l8_extreme.md");
  write_extreme_md(emd, extremes, cfg.quick ? std::vector<int>{100} : std::vector<int>{500, 10000});
  emd.close();
  checks.check("every extreme case solved within its tolerance or diagnosed", failed == 0);
  checks.check("massless tip: the articulated body algorithm stops with soa::Error", tip_diagnosed);
  checks.check("l8_extreme.csv and l8_extreme.md written", bool(ecsv) && bool(emd));
  checks.check("figure written: l8_extreme.png",
               soa::lesson::plot("l8_extreme.gp", out, "l8_extreme.png"));
  std::printf("  total %.1f s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return checks.finish();
}
