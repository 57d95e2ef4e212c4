// Scale measurement of the `soa` command (make bench): revolute chains of 1e3 ... 1e6 bodies
// written as scene files, each verb run on them as a separate process, its wall time and peak
// memory measured, and the log-log slopes against n fitted (O(n): a slope near 1).
//
//   cli_scale SOA OUTDIR [--sizes 1000,10000,100000,1000000] [--quick] [--timeout S]
//             [--mem-limit-mib M] [--check]
//
// --quick: sizes 1000,10000. --timeout: per run (default 300 s; the run is killed and the row
// says "timeout", and the verb is skipped at larger sizes). --mem-limit-mib: the address
// space of each run (default half the RAM, 0 none; an O(n^2) allocation then fails instead of
// swapping the machine). --check: exit 3 if some run did not exit 0 (for the smoke test).
//
// Writes OUTDIR/cli_scale.csv and OUTDIR/cli_scale.md and prints the table. Scratch files
// (the scene, each verb's stdout and stderr) live in OUTDIR/cli_scale.scratch/ and are
// deleted as soon as they are measured. A run that exits nonzero, is killed by a signal or
// exceeds the timeout is a row of the table, not a failure of this program: the exit code is
// 0 unless the measurement itself cannot be made (bad arguments, unwritable files).
//
// Time and memory have a floor (process start, the C++ runtime): `soa --help`, which reads
// no scene, is measured first and its time and peak memory are subtracted before fitting.
// Only the standard library and POSIX: fork/exec, wait4's rusage (ru_maxrss, KiB on Linux),
// setrlimit to keep a regression from filling the machine's memory or disk.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

const std::vector<std::string> kVerbs = {"inverse-dynamics", "forward-dynamics", "kinematics",
                                         "jacobian"};
constexpr double kSlopeWarning = 1.3;

struct Options {
  std::string soa;
  fs::path out_dir;
  std::vector<long> sizes = {1000, 10000, 100000, 1000000};
  double timeout = 300;     // seconds per run
  long mem_limit_mib = -1;  // address-space limit of each run; -1: half the RAM; 0: none
  bool check = false;       // exit 3 when a run did not exit 0 (the smoke test)
};

[[noreturn]] void usage(const std::string& problem) {
  std::cerr << "cli_scale: " << problem << "\n"
            << "usage: cli_scale SOA OUTDIR [--sizes N,N,...] [--quick] [--timeout SECONDS]\n"
            << "                 [--mem-limit-mib MIB] [--check]\n";
  std::exit(2);
}

long parse_long(const std::string& s, const std::string& what) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);  // accepts 1e6
  if (s.empty() || *end != '\0' || errno != 0 || v != std::floor(v) || v < 0 || v > 1e9)
    usage(what + ": \"" + s + "\" is not a whole number");
  return long(v);
}

Options parse(int argc, char** argv) {
  Options o;
  std::vector<std::string> pos;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i], value;
    const auto eq = a.find('=');
    const bool has_eq = a.rfind("--", 0) == 0 && eq != std::string::npos;
    if (has_eq) value = a.substr(eq + 1), a = a.substr(0, eq);
    auto next = [&]() -> std::string {
      if (has_eq) return value;
      if (i + 1 >= argc) usage(a + " needs a value");
      return argv[++i];
    };
    if (a == "--quick") {
      o.sizes = {1000, 10000};
    } else if (a == "--sizes") {
      o.sizes.clear();
      std::stringstream ss(next());
      for (std::string item; std::getline(ss, item, ',');)
        o.sizes.push_back(parse_long(item, "--sizes"));
      if (o.sizes.empty()) usage("--sizes: no sizes");
      for (long n : o.sizes)
        if (n < 1) usage("--sizes: a chain has at least 1 body");
    } else if (a == "--timeout") {
      o.timeout = std::strtod(next().c_str(), nullptr);
      if (!(o.timeout > 0)) usage("--timeout: expected a positive number of seconds");
    } else if (a == "--mem-limit-mib") {
      o.mem_limit_mib = parse_long(next(), "--mem-limit-mib");
    } else if (a == "--check") {
      o.check = true;
    } else if (a == "--help" || a == "-h") {
      usage("scale measurement of the soa command");
    } else if (a.rfind("--", 0) == 0) {
      usage("unknown option \"" + a + "\"");
    } else {
      pos.push_back(a);
    }
  }
  if (pos.size() != 2) usage("expected the soa program and the output directory");
  o.soa = pos[0];
  o.out_dir = pos[1];
  std::sort(o.sizes.begin(), o.sizes.end());
  o.sizes.erase(std::unique(o.sizes.begin(), o.sizes.end()), o.sizes.end());
  if (o.mem_limit_mib < 0) {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    o.mem_limit_mib = pages > 0 && page > 0 ? long((double(pages) * page / 2) / (1 << 20)) : 0;
  }
  return o;
}

/// A revolute chain of n bodies, base first, with its state; the bytes written.
std::uintmax_t write_scene(const fs::path& path, long n) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + path.string() + ": " + std::strerror(errno));
  static char buffer[1 << 20];
  std::setvbuf(f, buffer, _IOFBF, sizeof buffer);
  static const char* const axes[] = {"[0, 0, 1]", "[0, 1, 0]", "[0, 0, 1]", "[1, 0, 0]"};
  std::fprintf(f, "{\n  \"name\": \"revolute chain of %ld bodies (cli_scale)\",\n", n);
  std::fprintf(f, "  \"gravity\": [0, 0, -9.81],\n  \"bodies\": [\n");
  for (long i = 0; i < n; ++i) {
    const double m = 1.0 + 0.25 * double((7 * i) % 5);  // 1 ... 2 kg
    const double len = 0.1 + 0.01 * double(i % 4);
    const double k = 0.0001 * double(i % 3);  // principal moments a + b > c for every k
    std::fprintf(f, "    {\"name\": \"b%ld\", \"parent\": ", i);
    if (i == 0)
      std::fprintf(f, "\"base\"");
    else
      std::fprintf(f, "\"b%ld\"", i - 1);
    std::fprintf(f,
                 ", \"mass\": %.6g, \"com\": [%.6g, %.6g, 0],\n"
                 "     \"inertia\": {\"Ixx\": %.6g, \"Iyy\": %.6g, \"Izz\": %.6g},\n"
                 "     \"hinge\": {\"type\": \"revolute\", \"axis\": %s, "
                 "\"placement\": {\"position\": [%.6g, 0, 0]}},\n"
                 "     \"q\": [%.4f], \"qd\": [%.4f], \"qdd\": [%.4f]}%s\n",
                 m, len / 2, 0.002 * double(i % 3 - 1), 0.0004 * m, (0.0030 + k) * m,
                 (0.0032 + k) * m, axes[i % 4], i == 0 ? 0.0 : len, 0.3 * std::sin(0.7 * i),
                 0.2 * std::cos(0.3 * i), 0.5 * std::sin(0.5 * i), i + 1 < n ? "," : "");
  }
  std::fprintf(f, "  ]\n}\n");
  const bool ok = std::ferror(f) == 0;
  if (std::fclose(f) != 0 || !ok)
    throw std::runtime_error("cannot write " + path.string() + " (disk full?)");
  return fs::file_size(path);
}

/// One process run: its outcome, wall time, peak memory and output.
struct Run {
  std::string status;  // "0", "1", ..., "timeout", "signal 9 (Killed)", "skipped"
  double seconds = 0;
  long peak_kib = 0;
  std::uintmax_t out_bytes = 0;
  std::string note;  // the first line of stderr, or why the run was skipped
  bool ok() const { return status == "0"; }
  bool timed_out() const { return status == "timeout"; }
  bool measured() const { return status != "skipped"; }
};

std::string first_line(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  if (line.size() > 300) line = line.substr(0, 300) + "...";
  return line;
}

sigset_t g_blocked_chld, g_old_mask;

/// Runs args (args[0] the program) with stdout to out, stderr to err, stdin from /dev/null,
/// under the time limit and the address-space (mem_bytes, 0: none) and file-size limits.
Run run(const std::vector<std::string>& args, const fs::path& out, const fs::path& err,
        double timeout, std::uint64_t mem_bytes, std::uint64_t fsize_bytes) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const std::string out_s = out.string(), err_s = err.string();

  const Clock::time_point start = Clock::now();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {  // the child: async-signal-safe calls only, up to exec
    const int o = open(out_s.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = open(err_s.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int i = open("/dev/null", O_RDONLY);
    if (o < 0 || e < 0 || i < 0 || dup2(i, 0) < 0 || dup2(o, 1) < 0 || dup2(e, 2) < 0) _exit(126);
    if (mem_bytes > 0) {
      const rlimit as{rlim_t(mem_bytes), rlim_t(mem_bytes)};
      setrlimit(RLIMIT_AS, &as);
    }
    const rlimit fsize{rlim_t(fsize_bytes), rlim_t(fsize_bytes)};
    setrlimit(RLIMIT_FSIZE, &fsize);
    sigprocmask(SIG_SETMASK, &g_old_mask, nullptr);
    execv(argv[0], argv.data());
    const char msg[] = "cli_scale: exec failed\n";
    if (write(2, msg, sizeof msg - 1) < 0) _exit(127);
    _exit(127);
  }

  Run r;
  int status = 0;
  rusage ru{};
  const Clock::time_point deadline =
      start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout));
  for (;;) {
    const pid_t w = wait4(pid, &status, WNOHANG, &ru);
    if (w == pid) break;
    if (w < 0 && errno != EINTR) throw std::runtime_error(std::string("wait4: ") + strerror(errno));
    const Clock::duration left = deadline - Clock::now();
    if (left <= Clock::duration::zero()) {
      kill(pid, SIGKILL);
      while (wait4(pid, &status, 0, &ru) < 0 && errno == EINTR) {
      }
      r.status = "timeout";
      break;
    }
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(left).count();
    const timespec ts{time_t(ns / 1000000000), long(ns % 1000000000)};
    sigtimedwait(&g_blocked_chld, nullptr, &ts);  // a SIGCHLD, or the deadline
  }
  r.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  r.peak_kib = ru.ru_maxrss;
  std::error_code ec;
  r.out_bytes = fs::exists(out, ec) ? fs::file_size(out, ec) : 0;
  r.note = first_line(err);
  if (r.status.empty()) {
    if (WIFEXITED(status)) {
      r.status = std::to_string(WEXITSTATUS(status));
    } else if (WIFSIGNALED(status)) {
      const int sig = WTERMSIG(status);
      r.status = "signal " + std::to_string(sig);
      if (sig == SIGXFSZ) r.note = "output over the file-size limit; " + r.note;
      if (const char* name = strsignal(sig)) r.status += std::string(" (") + name + ")";
    }
  }
  if (r.timed_out()) r.note = "killed after " + std::to_string(int(timeout)) + " s";
  return r;
}

struct Row {
  std::string verb;
  long n;
  std::uintmax_t file_bytes;
  Run run;
};

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

std::string csv_quote(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

/// Least-squares slope of log y against log x; NaN with fewer than 2 points.
double loglog_fit(const std::vector<std::pair<double, double>>& pts) {
  if (pts.size() < 2) return std::nan("");
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (auto [x, y] : pts) {
    const double lx = std::log(x), ly = std::log(y);
    sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly;
  }
  const double k = double(pts.size());
  return (k * sxy - sx * sy) / (k * sxx - sx * sx);
}

struct Slopes {
  std::string text;                    // one line for the report
  std::vector<std::string> too_steep;  // the slopes above kSlopeWarning
};

/// The log-log slopes of one verb's time and memory above the floors, between consecutive
/// sizes and fitted over all sizes that ran. A timeout after a run that finished gives a lower
/// bound (">1.85"): the time was at least the timeout.
Slopes slopes(const std::string& verb, const std::vector<Row>& rows, double t_floor,
              double kib_floor, double timeout) {
  std::vector<const Row*> rs;
  for (const Row& r : rows)
    if (r.verb == verb && r.run.measured()) rs.push_back(&r);
  Slopes s;
  std::vector<std::pair<double, double>> t_pts, m_pts;
  std::string t_pairs, m_pairs;
  auto note = [&](const std::string& what, double v) {
    if (std::isfinite(v) && v > kSlopeWarning) s.too_steep.push_back(verb + " " + what);
  };
  for (const Row* r : rs) {
    if (!r->run.ok()) continue;
    if (r->run.seconds - t_floor > 0) t_pts.push_back({double(r->n), r->run.seconds - t_floor});
    if (r->run.peak_kib - kib_floor > 0)
      m_pts.push_back({double(r->n), r->run.peak_kib - kib_floor});
  }
  for (std::size_t i = 0; i + 1 < rs.size(); ++i) {
    const Row &a = *rs[i], &b = *rs[i + 1];
    const std::string range = std::to_string(a.n) + "->" + std::to_string(b.n);
    const double ln = std::log(double(b.n) / double(a.n));
    std::string t = "n/a", m = "n/a";
    if (a.run.ok() && (b.run.ok() || b.run.timed_out())) {
      const double ta = a.run.seconds - t_floor;
      const double tb = (b.run.ok() ? b.run.seconds : timeout) - t_floor;
      if (ta > 0 && tb > 0) {
        const double v = std::log(tb / ta) / ln;
        t = (b.run.ok() ? "" : ">") + fmt("%.2f", v);
        note("time " + range + " = " + t, v);
      }
    }
    if (a.run.ok() && b.run.ok()) {
      const double ma = a.run.peak_kib - kib_floor, mb = b.run.peak_kib - kib_floor;
      if (ma > 0 && mb > 0) {
        const double v = std::log(mb / ma) / ln;
        m = fmt("%.2f", v);
        note("memory " + range + " = " + m, v);
      }
    }
    t_pairs += (t_pairs.empty() ? "" : ", ") + range + " " + t;
    m_pairs += (m_pairs.empty() ? "" : ", ") + range + " " + m;
  }
  const double tf = loglog_fit(t_pts), mf = loglog_fit(m_pts);
  note("time fit = " + fmt("%.2f", tf), tf);
  note("memory fit = " + fmt("%.2f", mf), mf);
  auto fit = [](double v, std::size_t k) {
    return std::isfinite(v) ? fmt("%.2f", v) + " (" + std::to_string(k) + " sizes)"
                            : std::string("n/a");
  };
  s.text = verb + ": time slope " + (t_pairs.empty() ? "n/a" : t_pairs) + "; fit " +
           fit(tf, t_pts.size()) +
           ". Memory above the floor: " + (m_pairs.empty() ? "n/a" : m_pairs) + "; fit " +
           fit(mf, m_pts.size()) + ".";
  return s;
}

std::string mib(double kib) {
  return fmt("%.1f", kib / 1024);
}
std::string mib2(std::uintmax_t bytes) {
  return fmt("%.2f", double(bytes) / (1 << 20));
}

/// The table, as aligned text (markdown = false) or as a Markdown table.
std::string table(const std::vector<Row>& rows, bool markdown) {
  const std::vector<std::string> head = {"verb",    "n",        "file MiB", "output MiB",
                                         "seconds", "peak MiB", "exit",     "stderr"};
  std::vector<std::vector<std::string>> cells;
  for (const Row& r : rows) {
    const bool m = r.run.measured();
    cells.push_back({r.verb, std::to_string(r.n), mib2(r.file_bytes),
                     m ? mib2(r.run.out_bytes) : "", m ? fmt("%.3f", r.run.seconds) : "",
                     m ? mib(double(r.run.peak_kib)) : "", r.run.status, r.run.note});
  }
  std::vector<std::size_t> w(head.size());
  for (std::size_t c = 0; c < head.size(); ++c) {
    w[c] = head[c].size();
    for (const auto& row : cells) w[c] = std::max(w[c], row[c].size());
  }
  std::ostringstream o;
  auto line = [&](const std::vector<std::string>& row) {
    for (std::size_t c = 0; c < row.size(); ++c) {
      const bool last = c + 1 == row.size();
      const bool right = c >= 1 && c <= 5;
      std::string cell = row[c];
      if (markdown) {
        std::string esc;
        for (char ch : cell) esc += ch == '|' ? std::string("\\|") : std::string(1, ch);
        o << (c == 0 ? "| " : " ") << esc << " |";
        continue;
      }
      const std::string pad(w[c] - cell.size(), ' ');
      o << (right ? pad + cell : last ? cell : cell + pad) << (last ? "" : "  ");
    }
    o << '\n';
  };
  line(head);
  if (markdown) {
    o << '|';
    for (std::size_t c = 0; c < head.size(); ++c) o << (c >= 1 && c <= 5 ? "---:|" : "---|");
    o << '\n';
  } else {
    std::size_t total = 0;
    for (std::size_t c = 0; c < w.size(); ++c) total += w[c] + (c + 1 < w.size() ? 2 : 0);
    o << std::string(std::min<std::size_t>(total, 120), '-') << '\n';
  }
  for (const auto& row : cells) line(row);
  return o.str();
}

std::uint64_t free_bytes(const fs::path& dir) {
  struct statvfs v {};
  if (statvfs(dir.c_str(), &v) != 0) return std::numeric_limits<std::uint64_t>::max();
  return std::uint64_t(v.f_bavail) * v.f_frsize;
}

// What a size needs on disk: the scene (330 bytes a body, above its measured size) and one
// verb's output at a time, at most its file-size limit.
std::uint64_t scene_estimate(long n) {
  return 330ull * std::uint64_t(n) + (1 << 20);
}
std::uint64_t output_limit(long n) {
  return (64ull << 20) + 2048ull * std::uint64_t(n);
}

int main_(int argc, char** argv) {
  const Options opt = parse(argc, argv);
  if (access(opt.soa.c_str(), X_OK) != 0) {
    std::cerr << "cli_scale: " << opt.soa << ": not an executable program\n";
    return 1;
  }
  const fs::path scratch = opt.out_dir / "cli_scale.scratch";
  fs::create_directories(scratch);
  const std::uint64_t mem_bytes = std::uint64_t(opt.mem_limit_mib) << 20;

  // SIGCHLD blocked and waited for with sigtimedwait (a handler, so that it is not discarded).
  struct sigaction sa {};
  sa.sa_handler = [](int) {};
  sigemptyset(&sa.sa_mask);
  sigaction(SIGCHLD, &sa, nullptr);
  sigemptyset(&g_blocked_chld);
  sigaddset(&g_blocked_chld, SIGCHLD);
  sigprocmask(SIG_BLOCK, &g_blocked_chld, &g_old_mask);

  std::cout << "cli_scale: " << opt.soa << ", sizes";
  for (long n : opt.sizes) std::cout << ' ' << n;
  std::cout << ", timeout " << opt.timeout << " s, memory limit "
            << (mem_bytes ? std::to_string(opt.mem_limit_mib) + " MiB" : std::string("none"))
            << "\n";

  // The floor: soa --help reads no scene (best of 5).
  double t_floor = 1e30, kib_floor = 1e30;
  for (int i = 0; i < 5; ++i) {
    const Run h = run({opt.soa, "--help"}, scratch / "help.out", scratch / "help.err", opt.timeout,
                      mem_bytes, output_limit(1));
    if (!h.ok()) {
      std::cout << "soa --help: exit " << h.status << " " << h.note << "; no floor subtracted\n";
      t_floor = kib_floor = 0;
      break;
    }
    t_floor = std::min(t_floor, h.seconds);
    kib_floor = std::min(kib_floor, double(h.peak_kib));
  }
  std::cout << "floor (soa --help): " << fmt("%.4f", t_floor) << " s, " << mib(kib_floor)
            << " MiB\n";

  std::vector<Row> rows;
  std::vector<std::string> skipped;
  std::map<std::string, long> timed_out_at;  // verb -> the size it timed out at
  for (long n : opt.sizes) {
    const std::uint64_t need = scene_estimate(n) + output_limit(n) + (64ull << 20);
    const std::uint64_t have = free_bytes(scratch);
    if (have < need) {
      const std::string why = "not enough disk: needs about " + mib(double(need) / 1024) +
                              " MiB in " + scratch.string() + ", " + mib(double(have) / 1024) +
                              " MiB free";
      std::cout << "n = " << n << ": skipped, " << why << "\n";
      skipped.push_back("n = " + std::to_string(n) + ": " + why);
      for (const std::string& v : kVerbs) rows.push_back({v, n, 0, Run{"skipped", 0, 0, 0, why}});
      continue;
    }
    const fs::path scene = scratch / ("chain_" + std::to_string(n) + ".json");
    const std::uintmax_t bytes = write_scene(scene, n);
    for (const std::string& verb : kVerbs) {
      Run r;
      if (timed_out_at.count(verb)) {
        r = Run{"skipped", 0, 0, 0, "timed out at n = " + std::to_string(timed_out_at[verb])};
      } else {
        const fs::path out = scratch / (verb + ".out"), err = scratch / (verb + ".err");
        // Best time of up to 5 runs while they are short (noise at small n); the peak memory
        // is the largest seen.
        double spent = 0;
        for (int k = 0; k < 5 && (k == 0 || (spent < 1.0 && r.ok())); ++k) {
          Run once = run({opt.soa, verb, scene.string()}, out, err, opt.timeout, mem_bytes,
                         output_limit(n));
          spent += once.seconds;
          if (k == 0 || !once.ok()) {
            r = once;
          } else {
            r.seconds = std::min(r.seconds, once.seconds);
            r.peak_kib = std::max(r.peak_kib, once.peak_kib);
          }
        }
        std::error_code ec;
        fs::remove(out, ec);
        fs::remove(err, ec);
        if (r.timed_out()) timed_out_at[verb] = n;
      }
      std::cout << "n = " << n << " " << verb << ": exit " << r.status;
      if (r.measured())
        std::cout << ", " << fmt("%.3f", r.seconds) << " s, " << mib(double(r.peak_kib))
                  << " MiB peak, " << mib(double(r.out_bytes) / 1024) << " MiB out";
      if (!r.note.empty()) std::cout << " (" << r.note << ")";
      std::cout << std::endl;
      rows.push_back({verb, n, bytes, r});
    }
    std::error_code ec;
    fs::remove(scene, ec);
  }
  std::error_code ec;
  fs::remove_all(scratch, ec);

  std::vector<std::string> lines, steep;
  for (const std::string& v : kVerbs) {
    Slopes s = slopes(v, rows, t_floor, kib_floor, opt.timeout);
    lines.push_back(s.text);
    steep.insert(steep.end(), s.too_steep.begin(), s.too_steep.end());
  }

  const fs::path csv_path = opt.out_dir / "cli_scale.csv", md_path = opt.out_dir / "cli_scale.md";
  {
    std::ofstream csv(csv_path);
    csv << "verb,n,file_bytes,output_bytes,seconds,peak_mib,exit_code,stderr\n";
    for (const Row& r : rows) {
      csv << r.verb << ',' << r.n << ',' << r.file_bytes << ',' << r.run.out_bytes << ','
          << fmt("%.6f", r.run.seconds) << ',' << fmt("%.3f", r.run.peak_kib / 1024.0) << ','
          << r.run.status << ',' << csv_quote(r.run.note) << '\n';
    }
    if (!csv) throw std::runtime_error("cannot write " + csv_path.string());
  }
  const std::string warning =
      steep.empty() ? std::string()
                    : "SLOPE ABOVE " + fmt("%.1f", kSlopeWarning) + " (not O(n)): " + [&] {
                        std::string s;
                        for (const std::string& x : steep) s += (s.empty() ? "" : "; ") + x;
                        return s;
                      }();
  {
    std::ofstream md(md_path);
    md << "# Scale of the soa command\n\n"
       << "Revolute chains of n bodies (scene files written by tests/bench/scale/cli_scale.cpp), "
       << "each verb one process: `" << opt.soa << " VERB chain.json > out`. Wall time "
       << "(best of up to 5 runs while a run takes under 1 s), peak resident memory (wait4 "
       << "ru_maxrss), the sizes of the scene and of the output. Per run: timeout " << opt.timeout
       << " s, address-space limit "
       << (mem_bytes ? std::to_string(opt.mem_limit_mib) + " MiB" : std::string("none"))
       << ", output limit 64 MiB + 2 KiB per body.\n\n"
       << table(rows, true) << "\n"
       << "Log-log slopes against n (O(n): near 1), of the time and of the peak memory above the "
       << "floor of `soa --help` (" << fmt("%.4f", t_floor) << " s, " << mib(kib_floor)
       << " MiB); \">\" after a timeout is a lower bound.\n\n";
    for (const std::string& l : lines) md << "- " << l << "\n";
    for (const std::string& s : skipped) md << "- skipped " << s << "\n";
    if (!warning.empty()) md << "\n**" << warning << "**\n";
    if (!md) throw std::runtime_error("cannot write " + md_path.string());
  }

  std::cout << "\n" << table(rows, false) << "\n";
  for (const std::string& l : lines) std::cout << l << "\n";
  if (!warning.empty()) std::cout << warning << "\n";
  std::cout << "Written: " << csv_path.string() << ", " << md_path.string() << "\n";
  if (opt.check)
    for (const Row& r : rows)
      if (!r.run.ok()) {
        std::cout << "--check: " << r.verb << " at n = " << r.n << ": exit " << r.run.status
                  << "\n";
        return 3;
      }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return main_(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "cli_scale: " << e.what() << "\n";
    return 1;
  }
}
