// The main of every exercise test binary. Each test suite is one exercise, named
// `ExerciseL_K_Name` (lesson L, exercise K). After the run it prints a table, exercise by
// exercise: pass, FAIL, or "not done" (the stub still throws soa::exercise::NotDone).
//
//   (no flag)           exit status of the tests: 0 when every exercise passes (make test)
//   --report            the table, exit 0 whatever the results (make exercises)
//   --expect-all-fail   exit 0 only when every exercise fails (CI's check of the stubs)
//   --header FILE       the lesson's exercises.hpp: each row shows the exercise's level, time
//                       and what it uses, from its statement's second line
//                       (`/// *Level 2 of 3, about 30 min; uses 4.1.*`)
// A failure's message is shown under its row: the exercise checker's (exercise_check.hpp)
// names the check, the likely mistake or the symptom, where the error is and the case.
//
// With --report each exercise runs in a process of its own: an exercise that stops the
// program (a failed Eigen assertion, an AddressSanitizer or UBSan report, a crash) gets its
// row, saying what stopped it and at which line of the student's code, and the others are
// still judged. The full report is kept in $SOA_EXERCISE_CASES/<exercise>-stopped.log.
#include <execinfo.h>
#include <fnmatch.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "property.hpp"

namespace {

struct Row {
  bool failed = false;
  bool not_done = false;
  std::string first_failure;  ///< the failures' messages, each ending in a newline
};

// "4.2" -> "level 2, 30 min, uses 4.1", read from the statements in exercises.hpp.
std::map<std::string, std::string> read_meta(const char* header) {
  std::map<std::string, std::string> meta;
  if (!header) return meta;
  std::ifstream in(header);
  const std::regex title(R"(\*\*Exercise (\d+\.\d+)[: ])");
  const std::regex level(
      R"(\*Level (\d) of 3, about (\d+) min(?:; uses (\d+\.\d+(?:(?:, | and )\d+\.\d+)*))?)");
  std::string line, current;
  int after = 0;
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_search(line, m, title)) {
      current = m[1];
      after = 0;
    }
    if (!current.empty() && after++ < 3 && std::regex_search(line, m, level)) {
      meta[current] = "level " + m[1].str() + ", " + m[2].str() + " min" +
                      (m[3].matched ? ", uses " + m[3].str() : "");
      current.clear();
    }
  }
  return meta;
}

class Table : public testing::EmptyTestEventListener {
 public:
  void OnTestPartResult(const testing::TestPartResult& r) override {
    if (!r.failed()) return;
    Row& row = rows_[current_];
    row.failed = true;
    std::string msg = r.message() ? r.message() : "";
    if (msg.find("not done: exercise") != std::string::npos) row.not_done = true;
    // ADD_FAILURE() << text gives "Failed\ntext": the text is what names the mistake.
    if (msg.rfind("Failed\n", 0) == 0) msg.erase(0, 7);
    // Every failed check of the exercise, in the order reported: gtest's own messages
    // ("Expected: ...") by their first line, the exercise checker's (which start with the
    // check's name) in full.
    const std::string text = msg.rfind("Expected", 0) == 0 || msg.rfind("Value of", 0) == 0
                                 ? msg.substr(0, msg.find('\n'))
                                 : msg;
    if (row.first_failure.find(text) == std::string::npos)
      row.first_failure += text.empty() || text.back() == '\n' ? text : text + "\n";
  }
  void OnTestStart(const testing::TestInfo& info) override {
    current_ = info.test_suite_name();
    if (!rows_.count(current_)) order_.push_back(current_);
    rows_[current_];
  }

  // "Exercise1_3_ParallelAxis" -> "1.3 ParallelAxis".
  static std::string label(const std::string& suite) {
    std::string s = suite.rfind("Exercise", 0) == 0 ? suite.substr(8) : suite;
    const auto a = s.find('_');
    if (a != std::string::npos) s[a] = '.';
    const auto b = s.find('_', a == std::string::npos ? 0 : a + 1);
    if (b != std::string::npos) s[b] = ' ';
    return s;
  }

  void print(const std::map<std::string, std::string>& meta) const {
    std::printf("\n  %-32s %-34s %s\n", "exercise", "", "result");
    for (const auto& name : order_) {
      const Row& r = rows_.at(name);
      const char* status = !r.failed ? "pass" : r.not_done ? "not done" : "FAIL";
      const std::string l = label(name);
      const auto it = meta.find(l.substr(0, l.find(' ')));
      std::printf("  %-32s %-34s %s\n", l.c_str(), it == meta.end() ? "" : it->second.c_str(),
                  status);
      if (r.failed && !r.not_done) {
        std::istringstream text(r.first_failure);
        std::string line;
        int lines = 0;
        while (std::getline(text, line) && lines++ < 80) std::printf("      %s\n", line.c_str());
      }
    }
  }
  int passed() const {
    int n = 0;
    for (const auto& [name, r] : rows_) n += !r.failed;
    return n;
  }
  int total() const { return int(rows_.size()); }

  // One row as text, from a child process to its parent: "<failed> <not done>\n<message>".
  std::string serialize(const std::string& suite) const {
    const auto it = rows_.find(suite);
    if (it == rows_.end()) return "";
    return std::to_string(int(it->second.failed)) + " " + std::to_string(int(it->second.not_done)) +
           "\n" + it->second.first_failure;
  }
  // A forbidden call fails the exercise whatever its numbers, and is said first.
  void forbid(const std::string& suite, const std::string& message) {
    Row& r = rows_[suite];
    r.failed = true;
    r.not_done = false;
    r.first_failure = message + r.first_failure;
  }
  void set(const std::string& suite, const Row& row) {
    if (!rows_.count(suite)) order_.push_back(suite);
    rows_[suite] = row;
  }

 private:
  std::string current_;
  std::vector<std::string> order_;
  std::map<std::string, Row> rows_;
};

// In the child process of one exercise: what stopped it, then the stack (symbolized by the
// sanitizer runtime when there is one) on stderr, which the parent reads.
extern "C" void __sanitizer_print_stack_trace() __attribute__((weak));

extern "C" void on_fatal_signal(int sig) {
  const char* what = sig == SIGABRT   ? "the program aborted (a failed assertion)"
                     : sig == SIGSEGV ? "a bad memory access (segmentation fault)"
                     : sig == SIGFPE  ? "an arithmetic error (integer division by zero?)"
                                      : "a fatal signal";
  dprintf(2, "SOA-STOPPED: %s\n", what);
  if (__sanitizer_print_stack_trace) {
    __sanitizer_print_stack_trace();
  } else {
    void* frames[64];
    backtrace_symbols_fd(frames, backtrace(frames, 64), 2);
  }
  _exit(128 + sig);
}

std::string read_all(std::FILE* f) {
  std::string s;
  std::rewind(f);
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) s.append(buf, n);
  return s;
}

// What stopped an exercise, from its stderr: the reason (assertion, sanitizer report) and
// the first frame in the student's code (a file under exercises/).
std::string stopped_message(const std::string& err, const std::string& log) {
  std::istringstream in(err);
  std::string line, reason, where;
  while (std::getline(in, line)) {
    if (reason.empty()) {
      std::size_t p;
      if ((p = line.find("Assertion `")) != std::string::npos)
        reason = "assertion " + line.substr(p + 10, line.find_last_not_of(". ") - p - 9) +
                 (line.find("index") != std::string::npos ? " (an index out of range)"
                  : line.find("rows") != std::string::npos || line.find("cols") != std::string::npos
                      ? " (sizes that do not match)"
                      : "");
      else if ((p = line.find("ERROR: AddressSanitizer: ")) != std::string::npos)
        reason = "AddressSanitizer: " + line.substr(p + 25, line.find(" on ", p) - p - 25);
      else if ((p = line.find("runtime error: ")) != std::string::npos)
        reason = "UBSan: " + line.substr(p + 15);
    }
    const auto e = line.find("/exercises/");
    if (where.empty() && e != std::string::npos && line.find(".cpp:") != std::string::npos &&
        line.find("/tests/exercises/") == std::string::npos) {
      const auto in_fn = line.find(" in ");
      std::string fn = in_fn == std::string::npos ? "" : line.substr(in_fn + 4, e - in_fn - 4);
      fn = fn.substr(0, fn.rfind(' '));
      if (fn.find('(') != std::string::npos) fn = fn.substr(0, fn.find('('));
      where = line.substr(e + 1);
      if (!fn.empty()) where += " (in " + fn + ")";
    }
  }
  if (reason.empty()) {
    const auto p = err.find("SOA-STOPPED: ");
    reason = p == std::string::npos ? "the program stopped"
                                    : err.substr(p + 13, err.find('\n', p) - p - 13);
  }
  std::string msg = "stopped: " + reason + "\n";
  msg += where.empty() ? "  (no frame in your exercises.cpp: the stack is in the log)\n"
                       : "  at your line " + where + "\n";
  if (!log.empty()) msg += "  the full report: " + log + "\n";
  return msg;
}

// Does the full test name match the --gtest_filter given (positive patterns only)?
bool matches(const std::string& name, const std::string& filter) {
  const std::string positive = filter.substr(0, filter.find('-'));
  std::istringstream in(positive.empty() ? "*" : positive);
  std::string pat;
  while (std::getline(in, pat, ':'))
    if (fnmatch(pat.c_str(), name.c_str(), 0) == 0) return true;
  return false;
}

// Forbidden calls (tests/exercises/watch.cmake): defined only when make exercises watches the
// student's code.
extern "C" {
extern unsigned char soa_watch_hit[] __attribute__((weak));
extern const int soa_watch_count __attribute__((weak));
extern const char* const soa_watch_name[] __attribute__((weak));
extern const char* const soa_watch_exercise[] __attribute__((weak));
}

// The library functions exercise \p id called that its statement forbids.
std::string forbidden_calls(const std::string& id) {
  if (&soa_watch_count == nullptr) return "";
  std::string names;
  for (int i = 0; i < soa_watch_count; ++i)
    if (soa_watch_hit[i] &&
        std::string(soa_watch_exercise[i]).find(" " + id + " ") != std::string::npos &&
        names.find(soa_watch_name[i]) == std::string::npos)
      names += std::string(names.empty() ? "" : ", ") + soa_watch_name[i];
  if (names.empty()) return "";
  return "your code calls " + names + ", which exercise " + id +
         " reproduces (its statement says: do not call it): the exercise is to compute it "
         "yourself\n";
}

// --report: every exercise (test suite) in a child process of its own.
void run_isolated(Table& table) {
  const std::string filter = GTEST_FLAG_GET(filter);
  testing::UnitTest& unit = *testing::UnitTest::GetInstance();
  std::vector<std::string> suites;
  for (int i = 0; i < unit.total_test_suite_count(); ++i) {
    const testing::TestSuite& ts = *unit.GetTestSuite(i);
    for (int j = 0; j < ts.total_test_count(); ++j)
      if (matches(std::string(ts.name()) + "." + ts.GetTestInfo(j)->name(), filter)) {
        suites.push_back(ts.name());
        break;
      }
  }
  const char* cases = std::getenv("SOA_EXERCISE_CASES");
  for (const std::string& suite : suites) {
    std::FILE* err = std::tmpfile();
    std::FILE* out = std::tmpfile();
    std::fflush(stdout);
    const pid_t pid = fork();
    if (pid == 0) {
      dup2(fileno(err), 2);
      for (int sig : {SIGABRT, SIGSEGV, SIGFPE, SIGBUS, SIGILL}) std::signal(sig, on_fatal_signal);
      GTEST_FLAG_SET(filter, suite + ".*");
      const int failed = RUN_ALL_TESTS();  // the row says it
      (void)failed;
      const std::string label = Table::label(suite);
      const std::string calls = forbidden_calls(label.substr(0, label.find(' ')));
      if (!calls.empty()) table.forbid(suite, calls);
      const std::string row = table.serialize(suite);
      std::fwrite(row.data(), 1, row.size(), out);
      std::fflush(out);
      _exit(0);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    const std::string row = read_all(out);
    Row r;
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && !row.empty()) {
      r.failed = row[0] == '1';
      r.not_done = row.size() > 2 && row[2] == '1';
      r.first_failure = row.substr(std::min(row.size(), row.find('\n') + 1));
    } else {
      const std::string text = read_all(err);
      std::string log;
      if (cases && *cases) {
        std::string name = suite.rfind("Exercise", 0) == 0 ? suite.substr(8) : suite;
        log = std::string(cases) + "/" + name + "-stopped.log";
        if (std::FILE* f = std::fopen(log.c_str(), "w")) {
          std::fwrite(text.data(), 1, text.size(), f);
          std::fclose(f);
        } else {
          log.clear();
        }
      }
      r.failed = true;
      r.first_failure = stopped_message(text, log);
    }
    std::fclose(err);
    std::fclose(out);
    table.set(suite, r);
  }
}

}  // namespace

int main(int argc, char** argv) {
  bool report = false, expect_all_fail = false;
  const char* header = nullptr;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (std::strcmp(argv[i], "--report") == 0)
      report = true;
    else if (std::strcmp(argv[i], "--header") == 0 && i + 1 < argc)
      header = argv[++i];
    else if (std::strcmp(argv[i], "--expect-all-fail") == 0)
      expect_all_fail = true;
    else
      args.push_back(argv[i]);
  }
  int n = int(args.size());
  args.push_back(nullptr);  // argv[argc] is null: gtest shifts the arguments it takes
  testing::InitGoogleTest(&n, args.data());
  if (report || expect_all_fail) {
    // Keep the table readable: gtest's own per-test lines are left out.
    auto& listeners = testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  auto* table = new Table;
  testing::UnitTest::GetInstance()->listeners().Append(table);
  soa::test::quiet() = report || expect_all_fail;
  int rc = 0;
  if (report)
    run_isolated(*table);
  else
    rc = RUN_ALL_TESTS();
  table->print(read_meta(header));
  std::printf("  %d of %d exercises pass\n", table->passed(), table->total());
  if (report) return 0;
  if (expect_all_fail) return table->passed() == 0 && table->total() > 0 ? 0 : 1;
  return rc;
}
