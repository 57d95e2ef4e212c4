/// \file
/// The `soa` command as a hostile user drives it: nothing lost, nothing silent.
/// Each test runs the program (fork/exec) and checks what it left behind:
/// - `--out` that is the scene (other spelling, symbolic or hard link) is refused, the
///   scene intact; a full disk (`/dev/full`) on --out or stdout is exit 1 with the reason;
/// - SIGINT/SIGTERM stop a run at a step boundary: complete rows, the summary says so,
///   exit 130/143, no temporary file left; a blow-up keeps the finite rows before it;
/// - CSV fields and JSON strings survive names with commas, quotes, line breaks and file
///   names that are not UTF-8; --every/--out-dt thin the trajectory;
/// - the dense cross-checks are skipped above their size and say so; a mass matrix too
///   large is refused, and running out of memory is one line naming what was being built;
/// - the viewer (view, simulate --view): a state, a run, a trajectory file read back (every
///   bad one refused with its line and column, nothing written), a folder of the user's
///   refused, a blow-up and Ctrl-C keep the viewer of what was computed;
/// - each verb's --help lists only the options it takes.
/// Suite cli_robustness.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

// AddressSanitizer: GCC defines __SANITIZE_ADDRESS__, clang answers __has_feature.
#if defined(__SANITIZE_ADDRESS__)
#define SOA_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SOA_TEST_ASAN 1
#endif
#endif

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

std::string scene_path(const std::string& name) {
  return std::string(SOA_SCENE_DIR) + "/" + name;
}
std::string test_scene(const std::string& name) {
  return std::string(SOA_SOURCE_DIR) + "/tests/scenes/" + name;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

/// A scratch folder per test, removed at the end.
class Scratch {
 public:
  Scratch() {
    std::string t = (fs::temp_directory_path() / "soa-cli-XXXXXX").string();
    dir_ = ::mkdtemp(t.data());
  }
  ~Scratch() { fs::remove_all(dir_); }
  std::string operator/(const std::string& name) const { return dir_ + "/" + name; }
  const std::string& dir() const { return dir_; }
  /// The files in the folder, hidden ones included.
  std::vector<std::string> files() const {
    std::vector<std::string> f;
    for (const auto& e : fs::directory_iterator(dir_)) f.push_back(e.path().filename().string());
    return f;
  }

 private:
  std::string dir_;
};

struct Outcome {
  int rc = -1;
  std::string out, err;
};

struct Options {
  std::string stdout_path;   ///< where stdout goes (a temporary file when empty)
  rlim_t address_space = 0;  ///< RLIMIT_AS for the child, when non-zero
  rlim_t file_size = 0;      ///< RLIMIT_FSIZE (ulimit -f) for the child, when non-zero
};

/// Starts soa with \p args; stdout and stderr go to files in \p s.
pid_t start(const Scratch& s, const std::vector<std::string>& args, const Options& o = {}) {
  const std::string out = o.stdout_path.empty() ? s / "stdout.txt" : o.stdout_path;
  const std::string err = s / "stderr.txt";
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fo = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int fe = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fo, 1);
    ::dup2(fe, 2);
    if (o.address_space) {
      const rlimit l{o.address_space, o.address_space};
      ::setrlimit(RLIMIT_AS, &l);
    }
    if (o.file_size) {
      const rlimit l{o.file_size, o.file_size};
      ::setrlimit(RLIMIT_FSIZE, &l);
    }
    std::vector<char*> argv{const_cast<char*>(SOA_CLI)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(SOA_CLI, argv.data());
    ::_exit(127);
  }
  return pid;
}

Outcome wait_for(const Scratch& s, pid_t pid, const Options& o = {}) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  Outcome r;
  r.rc = WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
  if (o.stdout_path.empty()) r.out = read_file(s / "stdout.txt");
  r.err = read_file(s / "stderr.txt");
  return r;
}

Outcome soa(const Scratch& s, const std::vector<std::string>& args, const Options& o = {}) {
  return wait_for(s, start(s, args, o), o);
}

/// Exactly one line on stderr.
void expect_one_line(const Outcome& r) {
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_TRUE(!r.err.empty() && r.err.back() == '\n') << r.err;
}

/// The records of a CSV file as RFC 4180 reads them.
std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows(1, std::vector<std::string>(1));
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    std::string& field = rows.back().back();
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"')
        field += '"', ++i;
      else if (c == '"')
        quoted = false;
      else
        field += c;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      rows.back().emplace_back();
    } else if (c == '\n') {
      rows.emplace_back(1);
    } else {
      field += c;
    }
  }
  if (rows.back().size() == 1 && rows.back()[0].empty()) rows.pop_back();
  return rows;
}

/// Every data row has the header's number of fields, all finite numbers.
void expect_complete_rows(const std::string& csv, std::size_t min_rows) {
  const auto rows = parse_csv(read_file(csv));
  ASSERT_GE(rows.size(), min_rows + 1) << csv;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    ASSERT_EQ(rows[r].size(), rows[0].size()) << csv << " row " << r;
    for (const std::string& f : rows[r]) {
      char* end = nullptr;
      const double v = std::strtod(f.c_str(), &end);
      ASSERT_TRUE(end == f.c_str() + f.size() && !f.empty() && std::isfinite(v))
          << csv << " row " << r << ": \"" << f << "\"";
    }
  }
}

/// The data of a viewer folder: data.js is `window.SOA_VIEW = {...};`.
json view_data(const std::string& dir) {
  const std::string text = read_file(dir + "/data.js");
  const std::string head = "window.SOA_VIEW = ", tail = ";\n";
  EXPECT_EQ(text.rfind(head, 0), 0u) << dir;
  EXPECT_GE(text.size(), head.size() + tail.size()) << dir;
  if (text.size() < head.size() + tail.size()) return json();
  EXPECT_EQ(text.substr(text.size() - tail.size()), tail) << dir;
  return json::parse(text.substr(head.size(), text.size() - head.size() - tail.size()));
}

/// True when \p a and \p b are the same JSON but for numbers within \p tol (relative to
/// max(1, |a|, |b|)); the first difference is printed.
bool near(const json& a, const json& b, double tol, const std::string& where = "") {
  if (a.is_number() && b.is_number()) {
    const double x = a.get<double>(), y = b.get<double>();
    if (std::abs(x - y) <= tol * std::max({1.0, std::abs(x), std::abs(y)})) return true;
  } else if (a.type() == b.type() && (a.is_array() || a.is_object()) && a.size() == b.size()) {
    for (auto i = a.begin(), j = b.begin(); i != a.end(); ++i, ++j)
      if ((a.is_object() && i.key() != j.key()) ||
          !near(*i, *j, tol, where + "/" + (a.is_object() ? i.key() : "[]")))
        return false;
    return true;
  } else if (a == b) {
    return true;
  }
  ADD_FAILURE() << where << ": " << a.dump().substr(0, 200) << " vs " << b.dump().substr(0, 200);
  return false;
}

/// A revolute chain of n bodies as scene JSON.
std::string chain_scene(int n) {
  std::string s = "{\"gravity\": [0, 0, -9.81], \"bodies\": [\n";
  for (int i = 0; i < n; ++i) {
    s += std::string(i ? ",\n" : "") + "{\"name\": \"b" + std::to_string(i) + "\", \"parent\": \"" +
         (i ? "b" + std::to_string(i - 1) : std::string("base")) +
         "\", \"mass\": 1, \"com\": [0.5, 0, 0], \"inertia\": {\"Ixx\": 0.01, \"Iyy\": 0.1, "
         "\"Izz\": 0.1}, \"hinge\": {\"type\": \"revolute\", \"axis\": [0, " +
         (i % 2 ? "1" : "0") + ", " + (i % 2 ? "0" : "1") +
         "], \"placement\": {\"position\": [1, 0, 0]}}, \"q\": [0.01]}";
  }
  return s + "]}\n";
}

// --- output files ---------------------------------------------------------------------

TEST(cli_robustness, OutThatIsTheSceneIsRefusedAndTheSceneKept) {
  Scratch s;
  const std::string scene = s / "arm7.json";
  fs::copy_file(scene_path("arm7.json"), scene);
  const std::string before = read_file(scene);
  fs::create_symlink(scene, s / "link.json");
  ASSERT_EQ(::link(scene.c_str(), (s / "hard.json").c_str()), 0);
  for (const std::string& out : {scene, s.dir() + "/./arm7.json", s.dir() + "//arm7.json",
                                 s / "link.json", s / "hard.json"}) {
    const Outcome r = soa(s, {"simulate", scene, "--dt", "0.01", "--t-end", "0.05", "--out", out});
    EXPECT_EQ(r.rc, 1) << out;
    EXPECT_EQ(r.err,
              "--out " + out + ": is the scene file " + scene + "; refusing to overwrite it\n");
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(read_file(scene), before) << out;
  }
  const Outcome dir = soa(s, {"simulate", scene, "--dt", "0.01", "--out", s.dir()});
  EXPECT_EQ(dir.rc, 1);
  EXPECT_EQ(dir.err, "--out " + s.dir() + ": is a directory\n");
}

TEST(cli_robustness, AFullDiskIsAnErrorWithTheReason) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  Scratch s;
  const Outcome csv = soa(s, {"simulate", scene_path("arm7.json"), "--dt", "0.01", "--t-end",
                              "0.05", "--out", "/dev/full"});
  EXPECT_EQ(csv.rc, 1);
  EXPECT_EQ(csv.err, "--out /dev/full: No space left on device\n");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"kinematics", scene_path("arm7.json")},
        {"simulate", scene_path("arm7.json"), "--dt", "0.01", "--t-end", "0.05"},
        {"mass-matrix", scene_path("chain50.json"), "--inverse"},
        {"--help"}}) {
    Options o;
    o.stdout_path = "/dev/full";
    const Outcome r = soa(s, args, o);
    EXPECT_EQ(r.rc, 1) << args[0];
    EXPECT_EQ(r.err, "stdout: No space left on device\n") << args[0];
  }
}

TEST(cli_robustness, ACompleteRunReplacesTheFileAndLeavesNoTemporaryFile) {
  Scratch s;
  const std::string csv = s / "traj.csv";
  write_file(csv, "old contents\n");
  const Outcome r = soa(s, {"simulate", scene_path("double_pendulum.json"), "--dt", "0.01",
                            "--t-end", "0.1", "--out", csv});
  ASSERT_EQ(r.rc, 0) << r.err;
  expect_complete_rows(csv, 11);
  std::vector<std::string> files = s.files();
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"stderr.txt", "stdout.txt", "traj.csv"}));
  struct stat st;
  ASSERT_EQ(::stat(csv.c_str(), &st), 0);
  EXPECT_NE(st.st_mode & 0044, 0u) << "a new trajectory file is readable as any new file";
}

// Ctrl-C, SIGTERM or SIGHUP part way: complete rows renamed to the target, the summary,
// 130/143/129.
TEST(cli_robustness, SignalsStopAtAStepBoundaryAndKeepTheRows) {
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
    Scratch s;
    const std::string csv = s / "traj.csv";
    // With --view for SIGINT: the viewer of the run so far is written too.
    std::vector<std::string> args = {
        "simulate", scene_path("chain50.json"), "--dt", "1e-4", "--t-end", "1e6", "--out", csv};
    if (sig == SIGINT) args.insert(args.end(), {"--view", s / "view"});
    const pid_t pid = start(s, args);
    // Wait until the run has written rows (its temporary file grows), then signal.
    const auto t0 = std::chrono::steady_clock::now();
    bool growing = false;
    while (!growing && std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      for (const std::string& f : s.files())
        if (f.rfind(".traj.csv.", 0) == 0 && fs::file_size(s / f) > 0) growing = true;
    }
    ASSERT_TRUE(growing) << "no temporary trajectory file appeared";
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    ::kill(pid, sig);
    const Outcome r = wait_for(s, pid);
    EXPECT_EQ(r.rc, 128 + sig) << r.err;
    expect_one_line(r);
    const std::string name = sig == SIGINT ? "SIGINT" : sig == SIGHUP ? "SIGHUP" : "SIGTERM";
    EXPECT_NE(r.err.find("simulate: interrupted by " + name + " at t = "), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find("the trajectory up to there is in " + csv), std::string::npos) << r.err;
    const json j = json::parse(r.out);
    EXPECT_EQ(j["interrupted"]["signal"], name);
    const double t = j["interrupted"]["t"].get<double>();
    EXPECT_GT(t, 0);
    EXPECT_LT(t, 1e6);
    expect_complete_rows(csv, 2);
    const auto rows = parse_csv(read_file(csv));
    EXPECT_EQ(long(rows.size()) - 1, j["rows"].get<long>());
    EXPECT_EQ(std::stod(rows.back()[0]), t) << "the last row is the state at the stop";
    for (const std::string& f : s.files()) EXPECT_EQ(f.rfind(".traj", 0), std::string::npos) << f;
    if (sig == SIGINT) {
      EXPECT_NE(r.err.find(", its viewer in " + s / "view"), std::string::npos) << r.err;
      const json v = view_data(s / "view");
      EXPECT_NE(v["note"].get<std::string>().find("; interrupted by SIGINT at t = "),
                std::string::npos)
          << v["note"];
      EXPECT_NEAR(v["runs"][0]["t"].back().get<double>(), t, 1e-8 * t);
      EXPECT_EQ(j["view"]["frames"].get<std::size_t>(), v["runs"][0]["t"].size());
    }
  }
}

// Past the file size limit (ulimit -f) the write fails with EFBIG: one line naming the
// file, exit code 1, no temporary file left (not a silent death by SIGXFSZ).
TEST(cli_robustness, AFileSizeLimitIsAnErrorNamingTheFile) {
  Scratch s;
  const std::string csv = s / "t.csv";
  Options o;
  o.file_size = 50 * 1024;
  o.stdout_path = "/dev/null";
  const Outcome r = soa(s,
                        {"simulate", scene_path("double_pendulum.json"), "--dt", "1e-5", "--t-end",
                         "10", "--out", csv},
                        o);
  EXPECT_EQ(r.rc, 1) << r.err;
  EXPECT_EQ(r.err, "--out " + csv + ": File too large\n");
  std::vector<std::string> files = s.files();
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"stderr.txt"}));
}

// --out-dt below every step: each step is the first at or after a multiple of it, so every
// step is written (t / out_dt overflowed to 3 rows).
TEST(cli_robustness, AnOutDtBelowTheStepWritesEveryStep) {
  Scratch s;
  const std::string csv = s / "t.csv";
  for (const char* out_dt : {"5e-324", "1e-300"}) {
    const Outcome r = soa(s, {"simulate", scene_path("double_pendulum.json"), "--dt", "0.01",
                              "--t-end", "0.1", "--out", csv, "--out-dt", out_dt});
    ASSERT_EQ(r.rc, 0) << r.err;
    const json j = json::parse(r.out);
    EXPECT_EQ(j["rows"].get<long>(), j["steps"].get<long>() + 1) << out_dt;
    expect_complete_rows(csv, 11);
  }
}

// Two views written into one folder at once: both succeed (writers take turns) and the
// folder holds the complete viewer of one of them, its data.js that run's.
TEST(cli_robustness, TwoViewsIntoOneFolderAtOnceLeaveOneCompleteViewer) {
  Scratch s;
  const std::string scene = scene_path("chain50.json");
  auto args = [&](const std::string& dir, const char* t_end) {
    return std::vector<std::string>{"view", scene,     "--out", dir,        "--dt",
                                    "1e-3", "--t-end", t_end,   "--frames", "2000"};
  };
  ASSERT_EQ(soa(s, args(s / "a", "0.5")).rc, 0);
  ASSERT_EQ(soa(s, args(s / "b", "0.6")).rc, 0);
  const std::string data_a = read_file(s / "a/data.js"), data_b = read_file(s / "b/data.js");
  ASSERT_NE(data_a, data_b);
  for (int round = 0; round < 4; ++round) {
    const std::string dir = s / ("both" + std::to_string(round));
    Options o1, o2;
    o1.stdout_path = o2.stdout_path = "/dev/null";
    const pid_t p1 = start(s, args(dir, "0.5"), o1);
    const pid_t p2 = start(s, args(dir, "0.6"), o2);
    const Outcome r1 = wait_for(s, p1, o1), r2 = wait_for(s, p2, o2);
    EXPECT_EQ(r1.rc, 0) << r1.err;
    EXPECT_EQ(r2.rc, 0) << r2.err;
    const std::string data = read_file(dir + "/data.js");
    EXPECT_TRUE(data == data_a || data == data_b) << "round " << round << ": data.js of neither";
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) {
      const std::string name = e.path().filename().string();
      names.push_back(name);
      if (name != "data.js") {
        EXPECT_EQ(read_file(e.path().string()), read_file(s / ("a/" + name))) << name;
      }
    }
    std::vector<std::string> expected;
    for (const auto& e : fs::directory_iterator(s / "a"))
      expected.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(names, expected) << "round " << round;
  }
}

// (--stiffness off: the stiffness monitor would stop this run at its first step.)
TEST(cli_robustness, ABlowUpKeepsTheFiniteRowsBeforeIt) {
  Scratch s;
  const std::string csv = s / "traj.csv";
  const Outcome r = soa(s, {"simulate", test_scene("stiff_pendulum.json"), "--integrator", "rk4",
                            "--dt", "0.001", "--t-end", "1", "--stiffness", "off", "--out", csv});
  EXPECT_EQ(r.rc, 1);
  expect_one_line(r);
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find("blow-up at t = "), std::string::npos) << r.err;
  const std::size_t at = r.err.find("; the trajectory up to t = ");
  ASSERT_NE(at, std::string::npos) << r.err;
  expect_complete_rows(csv, 2);
  const auto rows = parse_csv(read_file(csv));
  double t_kept = 0;
  ASSERT_EQ(std::sscanf(r.err.c_str() + at, "; the trajectory up to t = %lf", &t_kept), 1);
  EXPECT_NEAR(std::stod(rows.back()[0]), t_kept, 1e-6 * std::max(1.0, t_kept));
}

// --- what is written ------------------------------------------------------------------

TEST(cli_robustness, NamesWithCommasQuotesAndLineBreaksSurviveTheCsv) {
  Scratch s;
  std::string scene = chain_scene(3);
  const std::vector<std::string> names = {"a,b", "say \"hi\"", "two\nlines"};
  const std::vector<std::string> escaped = {"a,b", "say \\\"hi\\\"", "two\\nlines"};
  for (int i = 0; i < 3; ++i) {
    const std::string old = "\"b" + std::to_string(i) + "\"";
    for (std::size_t at = scene.find(old); at != std::string::npos; at = scene.find(old))
      scene.replace(at, old.size(), "\"" + escaped[i] + "\"");
  }
  write_file(s / "names.json", scene);
  const std::string csv = s / "traj.csv";
  const Outcome r =
      soa(s, {"simulate", s / "names.json", "--dt", "0.01", "--t-end", "0.02", "--out", csv});
  ASSERT_EQ(r.rc, 0) << r.err;
  const auto rows = parse_csv(read_file(csv));
  ASSERT_EQ(rows.size(), 4u);
  std::vector<std::string> header = {"t"};
  for (const std::string& n : names) header.push_back("q:" + n);
  for (const std::string& n : names) header.push_back("qd:" + n);
  header.push_back("energy");
  header.push_back("quaternion_norm_error");
  EXPECT_EQ(rows[0], header);
  EXPECT_EQ(json::parse(r.out)["columns"], json(names));
  // ... and view --trajectory reads them back (quoted fields across lines), and names one in
  // a message on one line.
  const Outcome v = soa(s, {"view", s / "names.json", "--out", s / "v", "--trajectory", csv});
  ASSERT_EQ(v.rc, 0) << v.err;
  EXPECT_EQ(json::parse(v.out)["rows"], 3);
  auto bad = rows;
  bad[3][3] = "y";  // the last row's q of "two\nlines"; the header takes lines 1 to 3
  std::string text;
  for (const auto& row : bad) {
    for (std::size_t c = 0; c < row.size(); ++c) {
      const std::string& f = row[c];
      text += c ? "," : "";
      if (f.find_first_of(",\"\n") == std::string::npos) {
        text += f;
        continue;
      }
      text += '"';
      for (const char ch : f) text += ch == '"' ? std::string("\"\"") : std::string(1, ch);
      text += '"';
    }
    text += "\n";
  }
  write_file(s / "bad.csv", text);
  const Outcome e =
      soa(s, {"view", s / "names.json", "--out", s / "w", "--trajectory", s / "bad.csv"});
  EXPECT_EQ(e.rc, 1);
  expect_one_line(e);
  EXPECT_EQ(e.err, s / "bad.csv" + ": line 6, column \"q:two\\nlines\": \"y\" is not a number\n");
}

// --- mass-matrix --operational (lesson 7, section 8) ---------------------------------------

/// The rows of a JSON array of arrays as a matrix.
std::vector<std::vector<double>> matrix_of(const json& rows) {
  std::vector<std::vector<double>> a;
  for (const json& r : rows) a.push_back(r.get<std::vector<double>>());
  return a;
}

TEST(cli_robustness, OperationalInverseInertiaIsJMinvJStarOfTheVerbsOutputs) {
  // For every body of the arm (the locked gripper too) and of every_hinge.json: Lambda_inv of
  // --operational against J (soa jacobian --body) times Minv (soa mass-matrix --inverse)
  // times J*, all three read back from the JSON, and its own dense_residual (--check).
  Scratch s;
  for (const std::string& scene : {scene_path("arm7.json"), test_scene("every_hinge.json")}) {
    const Outcome mi = soa(s, {"mass-matrix", scene, "--inverse"});
    ASSERT_EQ(mi.rc, 0) << mi.err;
    const auto Minv = matrix_of(json::parse(mi.out)["Minv"]);
    const std::size_t nv = Minv.size();
    const Outcome kin = soa(s, {"kinematics", scene});
    ASSERT_EQ(kin.rc, 0) << kin.err;
    const json kinematics = json::parse(kin.out);  // items() is a view: the document must live
    for (const auto& body : kinematics["bodies"].items()) {
      const Outcome jac = soa(s, {"jacobian", scene, "--body", body.key()});
      ASSERT_EQ(jac.rc, 0) << jac.err;
      const auto J = matrix_of(json::parse(jac.out)["J"]);
      const Outcome op = soa(s, {"mass-matrix", scene, "--operational", body.key(), "--check"});
      ASSERT_EQ(op.rc, 0) << op.err;
      const json o = json::parse(op.out)["operational"];
      EXPECT_EQ(o["body"], body.key());
      EXPECT_LT(o["dense_residual"].get<double>(), 1e-12) << body.key();
      const auto L = matrix_of(o["Lambda_inv"]);
      ASSERT_EQ(L.size(), 6u);
      double scale = 0, diff = 0;
      for (int r = 0; r < 6; ++r) {
        ASSERT_EQ(L[r].size(), 6u);
        for (int c = 0; c < 6; ++c) {
          double ref = 0;  // (J Minv J*)(r, c)
          for (std::size_t i = 0; i < nv; ++i)
            for (std::size_t j = 0; j < nv; ++j) ref += J[r][i] * Minv[i][j] * J[c][j];
          scale = std::max(scale, std::abs(ref));
          diff = std::max(diff, std::abs(L[r][c] - ref));
        }
      }
      // The JSON's 17 significant digits and M^-1 to about cond(M) eps: 1e-10 relative.
      EXPECT_LT(diff, 1e-10 * scale) << scene << " " << body.key();
    }
  }
}

TEST(cli_robustness, FileNamesThatAreNotUtf8GiveValidJson) {
  Scratch s;
  const std::string scene = s / "sc\xff\xfe.json";
  fs::copy_file(scene_path("double_pendulum.json"), scene);
  const std::string stem_scene = s / "noname\xc3.json";  // a title from the file name
  std::string text = read_file(scene_path("double_pendulum.json"));
  text.erase(text.find("\"name\": \"double pendulum\","), 26);
  write_file(stem_scene, text);
  const Outcome id = soa(s, {"inverse-dynamics", stem_scene});
  ASSERT_EQ(id.rc, 0) << id.err;
  json j;
  ASSERT_NO_THROW(j = json::parse(id.out)) << id.out;
  EXPECT_EQ(j["scene"], "noname\xef\xbf\xbd");  // U+FFFD for the stray byte
  const std::string csv = s / "tr\xff.csv";
  const Outcome sim = soa(s, {"simulate", scene, "--dt", "0.01", "--t-end", "0.02", "--out", csv});
  ASSERT_EQ(sim.rc, 0) << sim.err;
  ASSERT_NO_THROW(j = json::parse(sim.out)) << sim.out;
  EXPECT_EQ(j["trajectory"], s.dir() + "/tr\xef\xbf\xbd.csv");
  EXPECT_TRUE(fs::exists(csv));
}

TEST(cli_robustness, EveryAndOutDtThinTheTrajectory) {
  Scratch s;
  const std::string csv = s / "traj.csv";
  struct Case {
    std::vector<std::string> extra;
    std::vector<double> times;
  };
  auto range = [](int n, double h) {
    std::vector<double> t;
    for (int i = 0; i <= n; ++i) t.push_back(i * h);
    return t;
  };
  std::vector<double> every7 = {};
  for (int i = 0; i <= 98; i += 7) every7.push_back(i * 0.01);
  every7.push_back(1.0);
  for (const Case& c : {Case{{"--every", "10"}, range(10, 0.1)}, Case{{"--every", "7"}, every7},
                        Case{{"--out-dt", "0.05"}, range(20, 0.05)},
                        Case{{"--out-dt", "0.3"}, {0, 0.3, 0.6, 0.9, 1.0}}}) {
    std::vector<std::string> args = {
        "simulate", scene_path("double_pendulum.json"), "--dt", "0.01", "--t-end", "1", "--out",
        csv};
    args.insert(args.end(), c.extra.begin(), c.extra.end());
    const Outcome r = soa(s, args);
    ASSERT_EQ(r.rc, 0) << r.err;
    const auto rows = parse_csv(read_file(csv));
    ASSERT_EQ(rows.size(), c.times.size() + 1) << c.extra[0] << " " << c.extra[1];
    for (std::size_t i = 0; i < c.times.size(); ++i)
      EXPECT_NEAR(std::stod(rows[i + 1][0]), c.times[i], 1e-9) << c.extra[1] << " row " << i;
    EXPECT_EQ(json::parse(r.out)["rows"].get<std::size_t>(), c.times.size());
  }
  const Outcome both = soa(s, {"simulate", scene_path("arm7.json"), "--dt", "0.01", "--out", csv,
                               "--every", "2", "--out-dt", "0.1"});
  EXPECT_EQ(both.rc, 1);
  const Outcome alone =
      soa(s, {"simulate", scene_path("arm7.json"), "--dt", "0.01", "--every", "2"});
  EXPECT_EQ(alone.rc, 1);
  EXPECT_EQ(alone.err,
            scene_path("arm7.json") + ": --every: needs --out, the trajectory file it thins out\n");
}

// --- sizes ----------------------------------------------------------------------------

TEST(cli_robustness, DenseCrossChecksAreSkippedAboveTheirSizeAndSaySo) {
  Scratch s;
  write_file(s / "chain.json", chain_scene(2001));
  const Outcome fd = soa(s, {"forward-dynamics", s / "chain.json"});
  ASSERT_EQ(fd.rc, 0) << fd.err;
  const json j = json::parse(fd.out);
  EXPECT_FALSE(j["check"].contains("dense_difference"));
  EXPECT_EQ(j["check"]["dense_skipped"].get<std::string>().rfind("n_v = 2001 is over 2000", 0), 0u);
  EXPECT_LT(j["check"]["round_trip_residual"].get<double>(), 1e-12);
  const Outcome small = soa(s, {"forward-dynamics", scene_path("chain50.json"), "--check"});
  ASSERT_EQ(small.rc, 0) << small.err;
  EXPECT_TRUE(json::parse(small.out)["check"].contains("dense_difference"));
  write_file(s / "huge.json", chain_scene(20001));
  const Outcome mm = soa(s, {"mass-matrix", s / "huge.json"});
  EXPECT_EQ(mm.rc, 1);
  expect_one_line(mm);
  EXPECT_EQ(mm.err.rfind(s / "huge.json" + ": mass-matrix: n_v = 20001 is over 20000", 0), 0u)
      << mm.err;
}

TEST(cli_robustness, OutOfMemoryIsOneLineNamingWhatWasBeingBuilt) {
#if defined(SOA_TEST_ASAN)
  GTEST_SKIP() << "AddressSanitizer reserves more address space than the limit";
#else
  Scratch s;
  write_file(s / "chain.json", chain_scene(15000));
  Options o;
  o.address_space = rlim_t(1) << 30;  // 1 GiB; the 15000 x 15000 matrix needs 1.8 GB
  const Outcome r = soa(s, {"mass-matrix", s / "chain.json"}, o);
  EXPECT_EQ(r.rc, 1);
  expect_one_line(r);
  EXPECT_EQ(r.err,
            s / "chain.json" + ": out of memory while building the 15000 x 15000 mass matrix\n");
  EXPECT_EQ(r.out, "");
#endif
}

TEST(cli_robustness, InputsThatAreNotSceneFilesAreRefusedPromptly) {
  Scratch s;
  for (const std::string dev : {"/dev/zero", "/dev/urandom"}) {
    const Outcome r = soa(s, {"kinematics", dev});
    EXPECT_EQ(r.rc, 1) << dev;
    expect_one_line(r);
    EXPECT_EQ(r.err.rfind(dev + ": ", 0), 0u) << r.err;
  }
  const Outcome dir = soa(s, {"kinematics", s.dir()});
  EXPECT_EQ(dir.rc, 1);
  EXPECT_EQ(dir.err, s.dir() + ": is a directory, not a scene file\n");
}

// --- the 3D viewer --------------------------------------------------------------------

TEST(cli_robustness, ViewOfAStateIsOneFrameAtThatState) {
  // --q, --qd in file order reach the viewer: its poses are the kinematics verb's positions.
  Scratch s;
  const std::string scene = test_scene("every_hinge.json");
  const std::vector<std::string> state = {
      "--q", "0.3,0.7,0.2,-0.3,0.1,0.2,0.0,0.9746794,0,0,0.3826834,0.9238795,0.1,0.2,0.3", "--qd",
      "0.2,-1.0,0.4,0.1,0.3,-0.2,0.5,0,0,0.2,1,0,0"};
  std::vector<std::string> args = {"view", scene, "--out", s / "v"};
  args.insert(args.end(), state.begin(), state.end());
  const Outcome r = soa(s, args);
  ASSERT_EQ(r.rc, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["source"], "state");
  EXPECT_EQ(j["run"], "state of --q, --qd");
  EXPECT_EQ(j["frames"], 1);
  EXPECT_EQ(j["open"], s / "v/index.html");
  const json v = view_data(s / "v");
  const json& run = v["runs"][0];
  ASSERT_EQ(run["t"].size(), 1u);
  EXPECT_TRUE(run.contains("V") && run.contains("f"));
  args = {"kinematics", scene};
  args.insert(args.end(), state.begin(), state.end());
  const Outcome kin = soa(s, args);
  ASSERT_EQ(kin.rc, 0) << kin.err;
  const json bodies = json::parse(kin.out)["bodies"];
  ASSERT_EQ(v["bodies"].size(), bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const std::string name = v["bodies"][i]["name"];
    for (int c = 0; c < 3; ++c)  // data.js has 9 significant digits
      EXPECT_NEAR(run["pose"][0][7 * i + c].get<double>(),
                  bodies[name]["position"][c].get<double>(), 1e-8)
          << name;
  }
  // --no-velocity, --no-force: the page gets poses only.
  const Outcome bare = soa(s, {"view", scene, "--out", s / "v", "--no-velocity", "--no-force"});
  ASSERT_EQ(bare.rc, 0) << bare.err;
  const json b = view_data(s / "v");
  EXPECT_FALSE(b["runs"][0].contains("V") || b["runs"][0].contains("f"));
  EXPECT_EQ(b["runs"][0]["label"], "state of the scene");
}

TEST(cli_robustness, ViewOfATrajectoryFileIsTheViewOfTheRunThatWroteIt) {
  // simulate --out --view and view --trajectory of its CSV: the same frames (quaternions
  // included: the file's are renormalized as --q's are), at times that are rows of the file.
  Scratch s;
  const std::string scene = test_scene("every_hinge.json"), csv = s / "traj.csv";
  const Outcome sim = soa(s, {"simulate", scene, "--dt", "0.01", "--t-end", "1", "--out", csv,
                              "--view", s / "run", "--frames", "25"});
  ASSERT_EQ(sim.rc, 0) << sim.err;
  const json js = json::parse(sim.out);
  EXPECT_EQ(js["view"]["frames"], 25);
  EXPECT_EQ(js["view"]["states"], 101);
  EXPECT_EQ(js["view"]["run"], "rk4, h = 0.01 s");
  const Outcome r =
      soa(s, {"view", scene, "--out", s / "file", "--trajectory", csv, "--frames", "25"});
  ASSERT_EQ(r.rc, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["source"], "trajectory");
  EXPECT_EQ(j["rows"], 101);
  EXPECT_EQ(j["states"], 101);
  EXPECT_EQ(j["note"], "101 states shown as 25 frames (one every 41.7 ms)");
  EXPECT_EQ(j["note"], js["view"]["note"]);
  json from_run = view_data(s / "run"), from_file = view_data(s / "file");
  EXPECT_EQ(from_file["runs"][0]["label"], "traj.csv");
  from_run["runs"][0].erase("label");
  from_file["runs"][0].erase("label");
  // The same but for rounding: a renormalized quaternion may differ in its last bit, and
  // forces that are zero in exact arithmetic show it (1e-13 N against 10 N).
  EXPECT_TRUE(near(from_run, from_file, 1e-9));
  std::vector<double> rows;
  const auto csv_rows = parse_csv(read_file(csv));
  for (std::size_t i = 1; i < csv_rows.size(); ++i) rows.push_back(std::stod(csv_rows[i][0]));
  const json& t = from_file["runs"][0]["t"];
  ASSERT_EQ(t.size(), 25u);
  for (const json& ti : t) {
    const double x = ti.get<double>();
    EXPECT_TRUE(std::any_of(rows.begin(), rows.end(),
                            [&](double row) { return std::abs(row - x) <= 1e-9; }))
        << "frame at t = " << x << " is no row of the file";
  }
  EXPECT_EQ(t.back().get<double>(), rows.back()) << "the last row is always shown";
}

TEST(cli_robustness, ViewRefusesEveryBadTrajectoryWithItsLineAndColumnAndWritesNothing) {
  Scratch s;
  const std::string pendulum = scene_path("double_pendulum.json");
  const std::string good = s / "good.csv";
  ASSERT_EQ(soa(s, {"simulate", pendulum, "--dt", "0.01", "--t-end", "0.2", "--out", good}).rc, 0);
  const std::string text = read_file(good);
  std::vector<std::string> lines;  // the file's lines, without their "\n"
  for (std::size_t a = 0, b; (b = text.find('\n', a)) != std::string::npos; a = b + 1)
    lines.push_back(text.substr(a, b - a));
  ASSERT_EQ(lines.size(), 22u);
  ASSERT_EQ(lines[0], "t,q:upper,q:lower,qd:upper,qd:lower,energy,quaternion_norm_error");
  auto field = [&](std::size_t line, std::size_t c) {
    std::stringstream in(lines[line - 1]);
    std::string f;
    for (std::size_t i = 0; i <= c; ++i) std::getline(in, f, ',');
    return f;
  };
  // The file with line \p line's field \p c (0 = t) replaced by \p value.
  auto with = [&](std::size_t line, std::size_t c, const std::string& value) {
    std::string out;
    for (std::size_t l = 1; l <= lines.size(); ++l) {
      std::string row = lines[l - 1];
      if (l == line) {
        std::size_t a = 0;
        for (std::size_t i = 0; i < c; ++i) a = row.find(',', a) + 1;
        row.replace(a, row.find(',', a) - a, value);
      }
      out += row + "\n";
    }
    return out;
  };
  const std::string header =
      "the header soa simulate --out writes for double_pendulum.json: t, 2 q and 2 qd in the "
      "scene's order, energy, quaternion_norm_error";
  std::string short_row = text;
  short_row.replace(short_row.find(",0.0\n", short_row.find(lines[3])), 4, "");
  const std::string arm = s / "arm7.csv";
  ASSERT_EQ(
      soa(s, {"simulate", scene_path("arm7.json"), "--dt", "0.01", "--t-end", "0.02", "--out", arm})
          .rc,
      0);
  struct Case {
    std::string name, contents, message;  // message: after "<file>: "
  };
  const std::vector<Case> cases = {
      {"header.csv", with(1, 2, "q:elbow"),
       "line 1, column 3: \"q:elbow\", expected \"q:lower\" (" + header + ")"},
      {"arm7.csv", read_file(arm),
       "line 1, column 2: \"q:link1\", expected \"q:upper\" (" + header + ")"},
      {"columns.csv", with(1, 6, "quaternion_norm_error,more"),
       "line 1: 8 columns, expected 7 (" + header + ")"},
      {"word.csv", with(17, 3, "abc"), "line 17, column \"qd:upper\": \"abc\" is not a number"},
      {"nan.csv", with(5, 2, "nan"), "line 5, column \"q:lower\": \"nan\" is not a finite number"},
      {"huge.csv", with(6, 4, "1e999"),
       "line 6, column \"qd:lower\": \"1e999\" is not a finite number"},
      {"empty-field.csv", with(7, 5, ""), "line 7, column \"energy\": is empty"},
      {"time.csv", with(9, 0, field(8, 0)),
       "line 9, column \"t\": \"" + field(8, 0) + "\" is not after the previous row's \"" +
           field(8, 0) + "\" (times must increase)"},
      {"negative.csv", with(2, 0, "-0.5"),
       "line 2, column \"t\": \"-0.5\" is negative; a trajectory begins at t = 0 (or later)"},
      {"short.csv", short_row, "line 4: 6 fields, where the header has 7"},
      {"blank.csv", lines[0] + "\n" + lines[1] + "\n\n" + lines[2] + "\n",
       "line 3: an empty line where a row of 7 numbers should be"},
      {"empty.csv", "", "line 1: empty file, expected " + header},
      {"header-only.csv", lines[0] + "\n", "line 2: no rows after the header"},
      {"open-quote.csv", lines[0] + "\n\"0.0,1\n",
       "line 2: a quoted field is not closed before "
       "the end of the file"},
  };
  for (const Case& c : cases) {
    const std::string file = s / c.name;
    write_file(file, c.contents);
    const Outcome r = soa(s, {"view", pendulum, "--out", s / "view", "--trajectory", file});
    EXPECT_EQ(r.rc, 1) << c.name;
    EXPECT_EQ(r.err, file + ": " + c.message + "\n") << c.name;
    EXPECT_EQ(r.out, "") << c.name;
    EXPECT_FALSE(fs::exists(s / "view")) << c.name << ": a folder written";
  }
  // A quaternion that is not of unit norm names its four columns; a file that is not there,
  // or a folder.
  const std::string eh = test_scene("every_hinge.json"), eh_csv = s / "eh.csv";
  ASSERT_EQ(soa(s, {"simulate", eh, "--dt", "0.01", "--t-end", "0.03", "--out", eh_csv}).rc, 0);
  auto rows = parse_csv(read_file(eh_csv));
  const std::size_t ball = std::find(rows[0].begin(), rows[0].end(), "q:ball[0]") - rows[0].begin();
  ASSERT_LT(ball + 3, rows[0].size());
  for (int i = 0; i < 4; ++i) rows[3][ball + i] = i == 3 ? "2" : "0";
  std::string bad;
  for (const auto& row : rows) {
    for (std::size_t i = 0; i < row.size(); ++i) bad += (i ? "," : "") + row[i];
    bad += "\n";
  }
  write_file(s / "ball.csv", bad);
  for (const auto& [file, message] : std::vector<std::pair<std::string, std::string>>{
           {s / "ball.csv",
            "line 4, columns \"q:ball[0]\" to \"q:ball[3]\": the quaternion of body \"ball\" is "
            "not of unit norm (norm 2; the norm must be 1 within 1e-6)"},
           {s / "no_such.csv", "cannot open the file (No such file or directory)"},
           {s.dir(), "is a directory, not a trajectory file"}}) {
    const Outcome r = soa(s, {"view", eh, "--out", s / "view", "--trajectory", file});
    EXPECT_EQ(r.rc, 1) << file;
    EXPECT_EQ(r.err, file + ": " + message + "\n");
    EXPECT_FALSE(fs::exists(s / "view")) << file << ": a folder written";
  }
}

TEST(cli_robustness, ViewRefusesAFolderThatHoldsAnythingElseAndNamesTheOption) {
  Scratch s;
  const std::string scene = scene_path("arm7.json"), dir = s / "mine";
  fs::create_directory(dir);
  write_file(dir + "/notes.txt", "mine\n");
  const std::string why =
      ": holds \"notes.txt\", which is not a file of the viewer; give a new folder, an empty "
      "one, or one the viewer was written to before\n";
  const Outcome v = soa(s, {"view", scene, "--out", dir});
  EXPECT_EQ(v.rc, 1);
  EXPECT_EQ(v.err, "--out " + dir + why);
  // simulate --view: refused before the run, and the trajectory not written either.
  const Outcome sim = soa(s, {"simulate", scene, "--dt", "0.01", "--t-end", "0.05", "--out",
                              s / "traj.csv", "--view", dir});
  EXPECT_EQ(sim.rc, 1);
  EXPECT_EQ(sim.err, "--view " + dir + why);
  EXPECT_EQ(sim.out, "");
  std::vector<std::string> files = s.files();
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"mine", "stderr.txt", "stdout.txt"}));
  EXPECT_EQ(read_file(dir + "/notes.txt"), "mine\n");
  // A viewer's folder is written again.
  ASSERT_EQ(soa(s, {"view", scene, "--out", s / "v"}).rc, 0);
  const Outcome again = soa(s, {"simulate", scene, "--dt", "0.01", "--view", s / "v"});
  EXPECT_EQ(again.rc, 0) << again.err;
  EXPECT_EQ(view_data(s / "v")["runs"][0]["label"], "rk4, h = 0.01 s");
}

TEST(cli_robustness, ViewOfARunThatBlowsUpShowsItUpToTheBlowUp) {
  Scratch s;
  const Outcome r = soa(s, {"view", test_scene("stiff_pendulum.json"), "--out", s / "v",
                            "--integrator", "rk4", "--dt", "0.001", "--t-end", "1"});
  EXPECT_EQ(r.rc, 1);
  expect_one_line(r);
  EXPECT_EQ(r.out, "");
  const std::size_t at = r.err.find("; the viewer up to t = ");
  ASSERT_NE(at, std::string::npos) << r.err;
  EXPECT_NE(r.err.find("frames) is in " + s / "v" + "\n", at), std::string::npos) << r.err;
  const json v = view_data(s / "v");
  EXPECT_NE(v["note"].get<std::string>().find("; stopped by a blow-up after t = "),
            std::string::npos)
      << v["note"];
  double t_kept = 0;
  ASSERT_EQ(std::sscanf(r.err.c_str() + at, "; the viewer up to t = %lf", &t_kept), 1);
  EXPECT_NEAR(v["runs"][0]["t"].back().get<double>(), t_kept, 1e-6);
}

// --- help -----------------------------------------------------------------------------

TEST(cli_robustness, EachVerbsHelpListsOnlyItsOptions) {
  Scratch s;
  const std::vector<std::string> options = {
      "--q",           "--qd",         "--qdd",         "--tau",  "--body",   "--inverse",
      "--check",       "--integrator", "--dt",          "--tol",  "--t-end",  "--out",
      "--every",       "--out-dt",     "--operational", "--view", "--frames", "--trajectory",
      "--no-velocity", "--no-force",   "--tip",         "--lock"};
  const std::vector<std::pair<std::string, std::vector<std::string>>> verbs = {
      {"kinematics", {"--q", "--qd", "--qdd", "--body", "--tip", "--lock"}},
      {"jacobian", {"--q", "--body", "--tip", "--lock"}},
      {"inverse-dynamics", {"--q", "--qd", "--qdd", "--tip", "--lock"}},
      {"forward-dynamics", {"--q", "--qd", "--tau", "--check", "--tip", "--lock"}},
      {"mass-matrix", {"--q", "--inverse", "--operational", "--check", "--tip", "--lock"}},
      {"simulate",
       {"--q", "--qd", "--integrator", "--dt", "--tol", "--t-end", "--out", "--every", "--out-dt",
        "--view", "--frames", "--no-velocity", "--no-force", "--tip", "--lock"}},
      {"view",
       {"--out", "--q", "--qd", "--integrator", "--dt", "--tol", "--t-end", "--trajectory",
        "--frames", "--no-velocity", "--no-force", "--tip", "--lock"}},
      {"convert", {"--tip", "--lock"}}};
  for (const auto& [verb, takes] : verbs) {
    const Outcome r = soa(s, {verb, "--help"});
    ASSERT_EQ(r.rc, 0);
    for (const std::string& o : options) {
      bool found = false;  // as a whole option: not followed by a letter, digit or '-'
      for (std::size_t at = r.out.find(o); at != std::string::npos && !found;
           at = r.out.find(o, at + 1)) {
        const char next = at + o.size() < r.out.size() ? r.out[at + o.size()] : ' ';
        found = !std::isalnum(static_cast<unsigned char>(next)) && next != '-';
      }
      const bool expected = std::find(takes.begin(), takes.end(), o) != takes.end();
      EXPECT_EQ(found, expected) << verb << " --help and " << o << ":\n" << r.out;
    }
  }
}

}  // namespace
