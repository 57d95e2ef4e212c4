// The speed targets, judged from one `make bench` run: reads the target benchmarks' JSON of
// each build configuration (targets_<config>_<program>.json, written by the bench_targets
// target of that build: native = SOA_NATIVE, portable = without it), the recorded "before"
// times (baseline.json), and writes speed.md (also printed).
//
//   speed_report <bench dir> <baseline.json>
//
// Targets (double, the revolute benchmark chain of bench_chain.hpp):
//   inverse dynamics            <= 55 ns per joint                       (N = 7, 50, 200, 1000)
//   forward dynamics (ABA)      <= 1.0 us at N = 7, <= 130 ns per joint  (N = 50, 200, 1000),
//                               full and lean storage (ForwardDynamicsT::lean())
//   mass matrix                 <= 0.8 x the fastest published O(N^2) CRB (N = 7, 200, 1000):
//                               Pinocchio was 1.44x, 3.7x, 5.5x faster than MassMatrixCRB
//                               when the targets were set (`published` below; README
//                               "Speed"), so the bound is 0.8 / r x MassMatrixCRB of the
//                               same run and configuration (conservative: today's CRB is no
//                               slower than the one timed then)
//   M^-1                        <= 0.6 x before (N = 200, 1000), before = baseline.json
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "report.hpp"  // lib/support: cpu_model(), time_text()

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using soa::lesson::cpu_model;
using soa::lesson::time_text;

struct Run {
  std::string config, flags, compiler;
  int repetitions = 0;
  std::map<std::string, double> median_ns;  // run name -> median CPU time, ns
};

[[noreturn]] void fail(const std::string& what) {
  std::cerr << "speed_report: " << what << "\n";
  std::exit(1);
}

json read_json(const fs::path& p) {
  std::ifstream in(p);
  if (!in) fail(p.string() + ": cannot be read");
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    fail(p.string() + ": not JSON (" + e.what() + ")");
  }
}

double to_ns(double t, const std::string& unit) {
  if (unit == "ns") return t;
  if (unit == "us") return t * 1e3;
  if (unit == "ms") return t * 1e6;
  if (unit == "s") return t * 1e9;
  fail("unknown time unit '" + unit + "'");
}

// Every targets_<config>_*.json in dir, grouped by configuration.
std::map<std::string, Run> read_runs(const fs::path& dir) {
  std::map<std::string, Run> runs;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string f = e.path().filename().string();
    if (f.rfind("targets_", 0) != 0 || e.path().extension() != ".json") continue;
    const json j = read_json(e.path());
    if (f.size() > 11 && f.compare(f.size() - 11, 11, "_build.json") == 0) {
      Run& r = runs[j.at("config").get<std::string>()];
      r.config = j.at("config").get<std::string>();
      r.flags = j.at("flags").get<std::string>();
      r.compiler = j.at("compiler").get<std::string>();
      continue;
    }
    const std::string config = j.value("context", json::object()).value("soa_config", "");
    if (config.empty()) fail(e.path().string() + ": context.soa_config missing");
    Run& r = runs[config];
    r.config = config;
    for (const json& b : j.at("benchmarks")) {
      if (b.value("run_type", "") != "aggregate" || b.value("aggregate_name", "") != "median")
        continue;
      r.median_ns[b.at("run_name").get<std::string>()] =
          to_ns(b.at("cpu_time").get<double>(), b.at("time_unit").get<std::string>());
      r.repetitions = std::max(r.repetitions, b.value("repetitions", 0));
    }
  }
  return runs;
}

// One target: a measured quantity of a run and its bound (both in ns).
struct Target {
  std::string what;  // row label
  std::string bench;
  int n;
  bool per_joint;
  std::string rule;  // how the bound is made
  // The bound for a run, or nothing when its inputs are missing.
  std::function<std::optional<double>(const Run&)> bound;
};

}  // namespace

int report(int argc, char** argv) {
  if (argc != 3) fail("usage: speed_report <bench dir> <baseline.json>");
  const fs::path dir = argv[1];
  const json base = read_json(argv[2]);
  const auto runs = read_runs(dir);
  if (runs.empty()) fail(dir.string() + ": no targets_*.json (run the bench_targets target)");
  std::map<std::string, double> before;
  for (const auto& [k, v] : base.at("median_ns").items()) before[k] = v.get<double>();

  auto fixed = [](double ns) { return [ns](const Run&) { return std::optional<double>(ns); }; };
  auto crb = [](int n, double r) {
    return [n, r](const Run& run) -> std::optional<double> {
      const auto it = run.median_ns.find("MassMatrixCRB/" + std::to_string(n));
      if (it == run.median_ns.end()) return std::nullopt;
      return 0.8 / r * it->second;
    };
  };
  auto was = [&before](const std::string& b, double f) {
    return [&before, b, f](const Run&) -> std::optional<double> {
      const auto it = before.find(b);
      if (it == before.end()) return std::nullopt;
      return f * it->second;
    };
  };
  std::vector<Target> targets;
  for (int n : {7, 50, 200, 1000})
    targets.push_back({"inverse dynamics", "InverseDynamics/" + std::to_string(n), n, true,
                       "≤ 55 ns per joint", fixed(55.0 * n)});
  // Both storages of ForwardDynamicsT: the full one keeps every per-body quantity of
  // lesson 8 (its size a body: README "Speed"), the lean one what soa::simulate reads.
  for (const char* storage : {"", "Lean"}) {
    const std::string what = *storage ? "forward dynamics, lean storage (soa::simulate)"
                                      : "forward dynamics, full storage";
    const std::string b = std::string("ForwardDynamicsABA") + storage + "/";
    targets.push_back({what, b + "7", 7, false, "≤ 1.0 µs", fixed(1000.0)});
    for (int n : {50, 200, 1000})
      targets.push_back(
          {what, b + std::to_string(n), n, true, "≤ 130 ns per joint", fixed(130.0 * n)});
  }
  const std::pair<int, double> published[] = {{7, 1.44}, {200, 3.7}, {1000, 5.5}};
  for (const auto& [n, r] : published) {
    char rule[96];
    std::snprintf(rule, sizeof rule, "≤ 0.8 / %.2f × CRB (fastest published)", r);
    targets.push_back(
        {"mass matrix", "MassMatrixInertial/" + std::to_string(n), n, false, rule, crb(n, r)});
  }
  for (int n : {200, 1000}) {
    const std::string b = "MassMatrixInverse/" + std::to_string(n);
    targets.push_back({"M⁻¹", b, n, false, "≤ 0.6 × before", was(b, 0.6)});
  }

  std::ostringstream md;
  md << "# Speed targets, one `make bench` run\n\n";
  md << "Machine: " << cpu_model() << ", " << std::thread::hardware_concurrency()
     << " logical CPUs. Benchmark chain: revolute, alternating axes (tests/bench/"
        "bench_chain.hpp), double. Each time is the median CPU time of the repetitions "
        "(interleaved at random by Google Benchmark).\n\n";
  md << "| configuration | compiler | flags | repetitions |\n|---|---|---|---|\n";
  for (const auto& [name, r] : runs)
    md << "| " << name << " | " << r.compiler << " | `" << r.flags << "` | " << r.repetitions
       << " |\n";
  md << "\n\"Before\" is the recorded time of " << base.value("commit", std::string("?")) << " ("
     << base.value("what", std::string("")) << ") on " << base.value("cpu", std::string("?"))
     << "; a ratio to it means something only on that CPU.\n\n";

  md << "| quantity | benchmark | target |";
  for (const auto& [name, r] : runs) md << " " << name << " | met |";
  md << " before |\n|---|---|---|";
  for (std::size_t i = 0; i < runs.size(); ++i) md << "---|---|";
  md << "---|\n";
  int missed = 0, judged = 0;
  for (const Target& t : targets) {
    md << "| " << t.what << " | " << t.bench << " | " << t.rule << " |";
    for (const auto& [name, r] : runs) {
      const auto it = r.median_ns.find(t.bench);
      const auto bound = t.bound(r);
      if (it == r.median_ns.end() || !bound) {
        md << " – | – |";
        continue;
      }
      const double v = it->second;
      char cell[96];
      if (t.per_joint)
        std::snprintf(cell, sizeof cell, "%.1f ns/joint (bound %.1f)", v / t.n, *bound / t.n);
      else
        std::snprintf(cell, sizeof cell, "%s (bound %s)", time_text(v).c_str(),
                      time_text(*bound).c_str());
      const bool met = v <= *bound;
      ++judged;
      if (!met) ++missed;
      md << " " << cell << " | " << (met ? "yes" : "**no**") << " |";
    }
    const auto b = before.find(t.bench);
    md << " " << (b == before.end() ? std::string("–") : time_text(b->second)) << " |\n";
  }
  md << "\n" << judged - missed << " of " << judged << " met.\n";
  const fs::path out = dir / "speed.md";
  const fs::path tmp = dir / "speed.md.part";
  {
    std::ofstream f(tmp);
    f << md.str();
    if (!f) fail(tmp.string() + ": cannot be written");
  }
  fs::rename(tmp, out);
  std::cout << md.str() << "(written to " << out.string() << ")\n";
  return 0;
}

int main(int argc, char** argv) {
  try {
    return report(argc, argv);
  } catch (const std::exception& e) {  // a JSON file without the fields it should have
    fail(std::string("a result or baseline file lacks a field: ") + e.what());
  }
}
