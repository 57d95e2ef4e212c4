// The work lab: the flops of lesson 8's algorithms, run by `make run` after the timing lab
// into build/course/labs/work/ (`make test` runs it with --quick, ctest lab.work):
//   lab_work OUTDIR [--quick]
// The work of each algorithm, counted from the code as it runs: the algorithms called on
// the scalar soa::test::Counted (lib/support/counted_scalar.hpp), a double that counts
// every +, -, *, / done on it (and sqrt, sin, cos apart). Eigen has no vector type for it,
// so every kernel runs coefficient by coefficient: a vectorized multiply of the double build
// counts once per lane.
// 1. Per body, per hinge type, of inverse dynamics and the articulated body algorithm: the
//    count on 16 bodies less the count on 8, over 8 (what a call does once drops out), on
//    chains whose axes are coordinate axes (fast paths), the same with Model::fast_paths
//    off, and oblique axes with rotated placements: l8_flops.md.
// 2. The O(N^2) mass matrix (carried columns; products hoisted) and M^-1 as a N^2 + b N,
//    fitted exactly on 8, 16, 24 bodies and checked on 32: l8_flops_n2.md.
// 3. The four solvers of the timing lab on its revolute chains (N = 7, 50, 200, 1000),
//    counted per call, beside the times that lab measured (l8_work_precision.csv in the
//    timing lab's folder beside OUTDIR, OUTDIR/../timing/): l8_flops_rate.md, and the
//    summary the notes quote, l8_flops_summary.md.
// Everything also in l8_flops.csv.
// --quick: section 3 on N = 7 and 50 only (the timing lab's --quick chains); sections 1
// and 2 in full, seconds already.
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "../timing/problems.hpp"
#include "args.hpp"
#include "checklist.hpp"
#include "flop_count.hpp"
#include "report.hpp"

namespace {

using soa::HingeType;
using soa::lesson::num;
using soa::lesson::time_text;
using namespace soa::test;
namespace fs = std::filesystem;
namespace timing = soa::lesson::timing;

const HingeType kTypes[] = {HingeType::Revolute,  HingeType::Prismatic, HingeType::Helical,
                            HingeType::Universal, HingeType::Spherical, HingeType::Free};

/// The three chains of a hinge type: coordinate axes, the same with the fast paths off,
/// oblique axes.
struct Config {
  const char* name;
  Axes axes;
  bool fast_paths;
};
const Config kConfigs[] = {{"coordinate axes", Axes::Coordinate, true},
                           {"fast paths off", Axes::Coordinate, false},
                           {"general axes", Axes::General, true}};

/// A count: exact, as an integer or with its one decimal (a half from a symmetric fill);
/// else an average that varies with the data, "≈" and no decimals.
std::string count_text(double v, bool exact = true) {
  if (!exact) return "≈" + num(v, "%.0f");
  return v == double((long long)v) ? num(v, "%.0f") : num(v, "%.1f");
}

/// One degree of freedom: nothing in the counts depends on the values.
bool one_dof(HingeType t) {
  return soa::HingeT<double>{t}.nv() == 1;
}
constexpr double kSpread = 0.1;  ///< several dofs: the two per-body counts agree within 10 %

/// "a N² + b N" (c, the once-per-call part, left out).
std::string quadratic_text(const Quadratic& q) {
  return count_text(q.a, q.exact) + " N² " + (q.b < 0 ? "− " : "+ ") +
         count_text(std::abs(q.b), q.exact) + " N";
}

/// The median CPU time per call (ns) of lab_timing, by "method/precision/N".
std::map<std::string, double> read_times(const fs::path& csv) {
  std::map<std::string, double> t;
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);  // method,precision,N,time_ns,...
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::string method, precision, N, ns;
    std::getline(s, method, ',');
    std::getline(s, precision, ',');
    std::getline(s, N, ',');
    std::getline(s, ns, ',');
    if (!ns.empty()) t[method + "/" + precision + "/" + N] = std::stod(ns);
  }
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  const fs::path out = soa::lesson::output_dir(argc, argv, &quick);
  soa::lesson::Checklist checks;
  std::ofstream csv(out / "l8_flops.csv");
  csv << "algorithm,hinge,chain,flops_per_body,sqrt_per_body,sincos_per_body,other_per_body,"
         "comparisons_per_body,flops_N2,flops_N,flops_1,flops_per_call\n";

  // 1. The O(N) recursions, per body.
  checks.section("Flops per body of the O(N) recursions, counted");
  const Algorithm linear[] = {Algorithm::InverseDynamics, Algorithm::ForwardDynamics};
  std::map<std::string, PerBody> per;  // "algorithm/type/config"
  bool all_linear = true;
  double worst_spread = 0;
  for (const Algorithm a : linear)
    for (const HingeType t : kTypes)
      for (const Config& c : kConfigs) {
        const PerBody p = per_body(a, t, c.axes, c.fast_paths);
        per[std::string(algorithm_name(a)) + "/" + soa::hinge_type_name(t) + "/" + c.name] = p;
        if (one_dof(t))
          all_linear = all_linear && p.linear;
        else
          worst_spread = std::max(worst_spread, p.spread);
        csv << soa::lesson::csv_field(algorithm_name(a)) << ',' << soa::hinge_type_name(t) << ','
            << c.name << ',' << num(p.flops, "%.6g") << ',' << num(p.sqrt, "%.6g") << ','
            << num(p.trig, "%.6g") << ',' << num(p.other, "%.6g") << ',' << num(p.cmp, "%.6g")
            << ",,,,\n";
      }
  checks.check(
      "1-dof hinges: every count grows by the same amount from 8 to 16 and from 16 "
      "to 24 bodies",
      all_linear);
  checks.check(
      "several dofs (eigenvalues iterated in the singularity guard): the two "
      "per-body flop counts agree",
      worst_spread, kSpread);
  const auto at = [&](Algorithm a, HingeType t, const char* config) {
    return per.at(std::string(algorithm_name(a)) + "/" + soa::hinge_type_name(t) + "/" + config);
  };
  for (const Algorithm a : linear) {
    const double fast = at(a, HingeType::Revolute, "coordinate axes").flops;
    const double off = at(a, HingeType::Revolute, "fast paths off").flops;
    std::printf(
        "  %s, revolute: %s flops per body on coordinate axes, %s with the fast paths "
        "off\n",
        algorithm_name(a), count_text(fast).c_str(), count_text(off).c_str());
  }
  checks.check("articulated body algorithm, revolute: the fast paths do fewer flops per body",
               at(Algorithm::ForwardDynamics, HingeType::Revolute, "coordinate axes").flops <
                   at(Algorithm::ForwardDynamics, HingeType::Revolute, "fast paths off").flops);
  std::ofstream md(out / "l8_flops.md");
  md << "| hinge (dofs) | inverse dynamics: coordinate axes | fast paths off | general axes | "
        "articulated body: coordinate axes | fast paths off | general axes | sqrt, sin + cos "
        "per body (ID; ABA) |\n"
     << "|---|---:|---:|---:|---:|---:|---:|---|\n";
  for (const HingeType t : kTypes) {
    md << "| " << soa::hinge_type_name(t) << " (" << soa::HingeT<double>{t}.nv() << ")";
    for (const Algorithm a : linear)
      for (const Config& c : kConfigs) {
        const PerBody& p = at(a, t, c.name);
        md << " | " << count_text(p.flops, p.linear);
      }
    const PerBody& i = at(Algorithm::InverseDynamics, t, "coordinate axes");
    const PerBody& f = at(Algorithm::ForwardDynamics, t, "coordinate axes");
    md << " | " << count_text(i.sqrt, i.linear) << ", " << count_text(i.trig, i.linear) << "; "
       << count_text(f.sqrt, f.linear) << ", " << count_text(f.trig, f.linear) << " |\n";
  }
  md.close();

  // 2. The O(N^2) algorithms, a N^2 + b N + c.
  checks.section("Flops of the O(N^2) mass matrix and inverse, counted");
  const Algorithm quadratic[] = {Algorithm::MassMatrixCRB, Algorithm::MassMatrixInertial,
                                 Algorithm::MassMatrixInverse};
  bool all_exact = true, fast_no_dearer = true;
  double worst_miss = 0;
  std::ofstream md2(out / "l8_flops_n2.md");
  md2 << "| hinge (dofs) | carried columns: coordinate axes | general axes | products hoisted: "
         "coordinate axes | general axes | M^-1: coordinate axes | fast paths off | general "
         "axes |\n"
      << "|---|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const HingeType t : kTypes) {
    md2 << "| " << soa::hinge_type_name(t) << " (" << soa::HingeT<double>{t}.nv() << ")";
    for (const Algorithm a : quadratic)
      for (const Config& c : kConfigs) {
        const Quadratic q = quadratic_flops(a, t, c.axes, c.fast_paths);
        if (one_dof(t))
          all_exact = all_exact && q.exact;
        else if (a != Algorithm::MassMatrixInertial)  // its loops change form above 32 dofs,
          worst_miss = std::max(worst_miss, q.miss);  // within the fit's 8-32 bodies
        if (a != Algorithm::MassMatrixInverse && !c.fast_paths) {  // checked, not shown
          const Quadratic on = quadratic_flops(a, t, c.axes, true);
          auto at16 = [](const Quadratic& x) { return x.a * 256 + x.b * 16 + x.c; };
          fast_no_dearer = fast_no_dearer && at16(on) <= at16(q);
          continue;
        }
        md2 << " | " << quadratic_text(q);
        csv << soa::lesson::csv_field(algorithm_name(a)) << ',' << soa::hinge_type_name(t) << ','
            << c.name << ",,,,,," << num(q.a, "%.6g") << ',' << num(q.b, "%.6g") << ','
            << num(q.c, "%.6g") << ",\n";
      }
    md2 << " |\n";
  }
  md2.close();
  checks.check(
      "1-dof hinges: every count is a N^2 + b N + c exactly (fitted on 8, 16, 24 "
      "bodies, checked on 32)",
      all_exact);
  checks.check(
      "several dofs: the fit predicts the count on 32 bodies (the hoisted mass matrix "
      "aside: it mirrors its lower triangle up to 32 dofs)",
      worst_miss, kSpread);
  checks.check("the mass matrices' fast paths do no more flops than the general path (N = 16)",
               fast_no_dearer);

  // 3. The timing report's solvers on its chains, beside its times.
  checks.section("Flops per call beside the measured time (lab_timing's chains)");
  const fs::path times_csv = fs::canonical(out).parent_path() / "timing" / "l8_work_precision.csv";
  const bool have_times = fs::exists(times_csv);
  const std::map<std::string, double> ns = read_times(times_csv);
  std::printf("  times: %s\n", have_times ? times_csv.c_str()
                                          : "none (no l8_work_precision.csv in the timing lab's "
                                            "folder beside OUTDIR: run lab_timing first)");
  const timing::Method methods[] = {timing::Method::ABA, timing::Method::CRB, timing::Method::Minv,
                                    timing::Method::MinvUpsilon};
  std::ofstream md3(out / "l8_flops_rate.md");
  md3 << "| N | ABA: flops per joint | ns per joint | flops per ns | CRB + LDLT: flops per "
         "call | flops per ns | M^-1 (T - C): flops per call | flops per ns | M^-1 by Upsilon "
         "(T - C): flops per call | flops per ns |\n"
      << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  double worst_agreement = 0;
  const int N_big = quick ? 50 : 1000;
  double aba_big_flops = NAN, aba_big_ns = NAN;  // per call at N_big
  for (const int N : quick ? std::vector<int>{7, N_big} : std::vector<int>{7, 50, 200, N_big}) {
    const timing::Problem<double> pd = timing::benchmark_chain(N);
    const timing::Problem<Counted> pc = timing::cast<Counted>(pd);
    md3 << "| " << N;
    for (const timing::Method m : methods) {
      timing::Solver<Counted> solver(m, pc);
      soa::VecX<Counted> bc(N);
      solver.solve(bc);  // the workspace warmed up, as in the timing loop
      const OpCounts n = count_ops([&] { solver.solve(bc); });
      if (m == timing::Method::ABA) {  // the counted result against double's
        soa::VecX<double> bd(N);
        timing::Solver<double>(m, pd).solve(bd);
        soa::VecX<double> b(N);
        for (int i = 0; i < N; ++i) b[i] = double(bc[i]);
        worst_agreement = std::max(worst_agreement, (b - bd).norm() / bd.norm());
      }
      const auto it = ns.find(std::string(timing::name(m)) + "/double/" + std::to_string(N));
      const double t = it == ns.end() ? NAN : it->second;
      const double flops = double(n.flops());
      csv << timing::name(m) << ",revolute,benchmark chain N = " << N << ",,,,,,,,,"
          << num(flops, "%.0f") << '\n';
      if (m == timing::Method::ABA && N == N_big) aba_big_flops = flops, aba_big_ns = t;
      if (m == timing::Method::ABA)
        md3 << " | " << num(flops / N, "%.0f") << " | "
            << (std::isnan(t) ? "-" : num(t / N, "%.0f"));
      else
        md3 << " | " << num(flops, "%.4g");
      md3 << " | " << (std::isnan(t) ? "-" : num(flops / t, "%.2f"));
    }
    md3 << " |\n";
  }
  if (!have_times)
    md3 << "\n*No times: `l8_work_precision.csv` was not in the timing lab's folder (lab_timing "
           "writes it).*\n";
  md3.close();
  // The summary the notes quote: the revolute counts and the rate at N_big.
  std::ofstream sum(out / "l8_flops_summary.md");
  for (const Algorithm a : linear)
    sum << "- " << char(std::toupper(*algorithm_name(a))) << algorithm_name(a) + 1
        << ", revolute hinge about a coordinate axis: **"
        << count_text(at(a, HingeType::Revolute, "coordinate axes").flops) << " flops per body** ("
        << count_text(at(a, HingeType::Revolute, "fast paths off").flops)
        << " with the fast paths off, "
        << count_text(at(a, HingeType::Revolute, "general axes").flops) << " on general axes).\n";
  sum << "- The articulated body algorithm on the timing chain of " << N_big
      << " bodies: " << num(aba_big_flops / N_big, "%.0f") << " flops per joint";
  if (std::isnan(aba_big_ns))
    sum << "; no time measured in this output folder.\n";
  else
    sum << " in " << num(aba_big_ns / N_big, "%.0f") << " ns per joint, "
        << num(aba_big_flops / aba_big_ns, "%.2f") << " flops per ns.\n";
  sum.close();
  checks.check("the counted articulated body result equals double's to rounding", worst_agreement,
               1e-12);
  csv.close();
  checks.check(
      "l8_flops.csv, l8_flops.md, l8_flops_n2.md, l8_flops_rate.md, l8_flops_summary.md written",
      bool(csv) && bool(md) && bool(md2) && bool(md3) && bool(sum));
  return checks.finish();
}
