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
// program (a failed Eigen or std::vector assertion, an AddressSanitizer or UBSan report, a
// crash) gets its row, saying what stopped it and in whose code (the student's line, or the
// checker's function that was reading the student's result), and the others are still
// judged. The full report, its stack symbolized, is kept in
// $SOA_EXERCISE_CASES/<exercise>-stopped.log. Each exercise runs under limits: a time limit
// (SOA_EXERCISE_TIME_LIMIT seconds, 10 by default: "stopped after 10 s: an endless loop?")
// and a cap on what it prints (the first lines are shown under its row, the rest is in
// $SOA_EXERCISE_CASES/<exercise>-output.log).
//   --warnings FILE     the compiler's diagnostics of the student's code (repeatable): each
//                       warning is shown under the row of the exercise whose function it is
//                       in, and that row never says a bare "pass"
//   --results FILE      with --report, also one line per exercise for a program (make grade,
//                       tests/grade/grade.sh): "<id>\t<name>\t<status>\t<message>", status one
//                       of pass, fail, not-done, timed-out, crashed[:SIGNAME], out-of-memory,
//                       forbidden-call; the message (the row's warnings, failures and notes)
//                       with backslash, newline and tab written \\, \n and \t, other control
//                       characters as '?'. Written by this process, the parent of the
//                       exercises' runs, into FILE.tmp then renamed. The student's code is
//                       linked into this process too: its results are make grade's first
//                       run only (--record), the verdict is the judge's (--replay).
//   --record DIR        with --report, each exercise's calls of the student's functions and
//                       what they returned, in DIR/<exercise>.rec (a program linked with the
//                       recorders: make exercises' and make grade's, which watch the calls)
//   --replay DIR        with --report, in the judge (exNN-judge: the checker linked with no
//                       student code): each call answered from DIR/<exercise>.rec; an exercise
//                       whose record ends early or does not match the calls gets the status
//                       "unjudged" (tests/support/recording.hpp)
//   --seed N            every case drawn with N mixed into its seed (seed_salt() of
//                       tests/support/property.hpp): cases the students' own runs never
//                       draw, for an instructor's grading (make grade SEEDS=FILE)
#include <execinfo.h>
#include <fcntl.h>
#include <fnmatch.h>
#include <gtest/gtest.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
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
#include "recording.hpp"

namespace {

struct Row {
  bool failed = false;
  bool not_done = false;
  bool forbidden = false;     ///< calls the library function the exercise reproduces
  std::string stopped;        ///< how the run stopped, as a --results status, or ""
  bool unjudged = false;      ///< --replay: the record does not answer the checker's calls
  std::string first_failure;  ///< the failures' messages, each ending in a newline
  std::string notes;          ///< what the exercise printed, or a note on it
};

// What the statements in exercises.hpp say: "4.2" -> "level 2, 30 min, uses 4.1", and the
// function each exercise asks for ("newton_euler" -> "4.2": its declaration is the first
// line under the title that is not a comment).
struct Statements {
  std::map<std::string, std::string> meta;
  std::map<std::string, std::string> exercise_of;
};

Statements read_statements(const char* header) {
  Statements st;
  if (!header) return st;
  std::ifstream in(header);
  const std::regex title(R"(\*\*Exercise (\d+\.\d+)[: ])");
  const std::regex level(
      R"(\*Level (\d) of 3, about (\d+) min(?:; uses (\d+\.\d+(?:(?:, | and )\d+\.\d+)*))?)");
  const std::regex declaration(R"(([A-Za-z_]\w*)\s*\()");
  std::string line, current, owner;
  int after = 0;
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_search(line, m, title)) {
      current = owner = m[1];
      after = 0;
    }
    if (!current.empty() && after++ < 3 && std::regex_search(line, m, level)) {
      st.meta[current] = "level " + m[1].str() + ", " + m[2].str() + " min" +
                         (m[3].matched ? ", uses " + m[3].str() : "");
      current.clear();
    }
    const auto first = line.find_first_not_of(" \t");
    if (!owner.empty() && first != std::string::npos && line.compare(first, 2, "//") != 0 &&
        std::regex_search(line, m, declaration)) {
      st.exercise_of[m[1]] = owner;
      owner.clear();
    }
  }
  return st;
}

// The compiler's warnings about the student's code, from the diagnostics of its compile
// (--warnings): exercise -> its warnings, one a line; "" for those outside the exercises'
// functions.
std::map<std::string, std::string> read_warnings(const std::vector<std::string>& files,
                                                 const Statements& st) {
  std::map<std::string, std::string> out;
  // GCC quotes with ' or, in a UTF-8 locale, with ‘ ’.
  const std::regex in_function(R"(: In (?:member |static member )?function (?:'|‘)(.*)(?:'|’):$)");
  // The student's file, or a header in which the compiler saw the student's code go wrong.
  const std::regex warning(R"(^(.*/)?([^/:]+\.[a-z]+):(\d+):\d+: warning: (.*)$)");
  for (const std::string& file : files) {
    std::ifstream in(file);
    std::string line, function;
    while (std::getline(in, line)) {
      std::smatch m;
      if (std::regex_search(line, m, in_function)) {
        // "soa::Force soa::ex01::apply_phi(const Phi&, ...)" -> "apply_phi"
        std::string sig = m[1].str();
        sig = sig.substr(0, sig.find('('));
        function = sig.substr(
            sig.find_last_of(": ") == std::string::npos ? 0 : sig.find_last_of(": ") + 1);
      } else if (std::regex_search(line, m, warning)) {
        const auto it = st.exercise_of.find(function);
        const std::string ex = it == st.exercise_of.end() ? "" : it->second;
        const std::string text = "warning at your line " + m[3].str() + " of " + m[2].str() +
                                 (function.empty() ? "" : " (in " + function + ")") + ": " +
                                 m[4].str() + "\n";
        if (out[ex].find(text) == std::string::npos) out[ex] += text;
      }
    }
  }
  return out;
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

  void print(const Statements& st, const std::map<std::string, std::string>& warnings) const {
    const auto loose = warnings.find("");
    if (loose != warnings.end()) {
      std::printf("\n  Your code outside the exercises' functions:\n");
      print_lines(loose->second);
    }
    std::printf("\n  %-32s %-34s %s\n", "exercise", "", "result");
    for (const auto& name : order_) {
      const Row& r = rows_.at(name);
      const std::string l = label(name);
      const std::string id = l.substr(0, l.find(' '));
      const auto w = warnings.find(id);
      const int n_warnings =
          w == warnings.end() ? 0 : int(std::count(w->second.begin(), w->second.end(), '\n'));
      // A warning is a likely bug that the cases may not reach: never a bare "pass".
      const std::string status =
          r.failed     ? (r.not_done ? "not done" : "FAIL")
          : n_warnings ? "pass, but " + std::to_string(n_warnings) +
                             (n_warnings == 1 ? " compiler warning" : " compiler warnings")
                       : "pass";
      const auto it = st.meta.find(id);
      std::printf("  %-32s %-34s %s\n", l.c_str(), it == st.meta.end() ? "" : it->second.c_str(),
                  status.c_str());
      if (w != warnings.end()) print_lines(w->second);
      if (r.failed && !r.not_done) print_lines(r.first_failure);
      print_lines(r.notes);
    }
  }
  static void print_lines(const std::string& s) {
    std::istringstream text(s);
    std::string line;
    int lines = 0;
    while (std::getline(text, line) && lines++ < 80) std::printf("      %s\n", line.c_str());
  }
  // --results: each exercise's status and message, a line each (see the top of this file).
  bool write_results(const std::string& path,
                     const std::map<std::string, std::string>& warnings) const {
    const std::string tmp = path + ".tmp";
    std::FILE* f = std::fopen(tmp.c_str(), "w");
    if (!f) return false;
    for (const auto& name : order_) {
      const Row& r = rows_.at(name);
      const std::string l = label(name);
      const std::string id = l.substr(0, l.find(' '));
      const auto w = warnings.find(id);
      const std::string status = r.unjudged           ? "unjudged"
                                 : r.forbidden        ? "forbidden-call"
                                 : !r.stopped.empty() ? r.stopped
                                 : !r.failed          ? "pass"
                                 : r.not_done         ? "not-done"
                                 : r.first_failure.find("std::bad_alloc") != std::string::npos
                                     ? "out-of-memory"
                                     : "fail";
      const std::string message = (w == warnings.end() ? "" : w->second) +
                                  (r.failed && !r.not_done ? r.first_failure : "") + r.notes;
      const std::string line = id + "\t" + l.substr(std::min(l.size(), id.size() + 1)) + "\t" +
                               status + "\t" + escaped(message) + "\n";
      std::fwrite(line.data(), 1, line.size(), f);
    }
    const bool ok = std::fclose(f) == 0;
    return ok && std::rename(tmp.c_str(), path.c_str()) == 0;
  }
  static std::string escaped(const std::string& text) {
    std::string s;
    for (const char c : text) {
      if (c == '\\')
        s += "\\\\";
      else if (c == '\n')
        s += "\\n";
      else if (c == '\t')
        s += "\\t";
      else if ((unsigned char)c < 0x20 || c == 0x7f)
        s += '?';
      else
        s += c;
    }
    return s;
  }
  int passed() const {
    int n = 0;
    for (const auto& [name, r] : rows_) n += !r.failed;
    return n;
  }
  int total() const { return int(rows_.size()); }

  // One row as text, from a child process to its parent:
  // "<failed> <not done> <forbidden> <unjudged>\n<message>".
  std::string serialize(const std::string& suite) const {
    const auto it = rows_.find(suite);
    if (it == rows_.end()) return "";
    const Row& r = it->second;
    return std::to_string(int(r.failed)) + " " + std::to_string(int(r.not_done)) + " " +
           std::to_string(int(r.forbidden)) + " " + std::to_string(int(r.unjudged)) + "\n" +
           r.first_failure;
  }
  // --replay: the record could not answer the checker's calls; no verdict.
  void unjudge(const std::string& suite, const std::string& why) {
    Row& r = rows_[suite];
    r.failed = true;
    r.not_done = false;
    r.unjudged = true;
    r.first_failure = "not judged: " + why + "\n";
  }
  // A forbidden call fails the exercise whatever its numbers, and is said first.
  void forbid(const std::string& suite, const std::string& message) {
    Row& r = rows_[suite];
    r.failed = true;
    r.not_done = false;
    r.forbidden = true;
    r.first_failure = message + r.first_failure;
  }
  void note(const std::string& suite, const std::string& text) { rows_[suite].notes += text; }
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

// A failed assertion's condition, in words: Eigen's (eigen_assert) and libstdc++'s
// (_GLIBCXX_ASSERTIONS, in the student's code) name indexes, blocks and sizes.
std::string assertion_kind(const std::string& condition) {
  if (condition.find("__n < this->size()") != std::string::npos ||
      condition.find("index >= 0") != std::string::npos ||
      condition.find("row >= 0") != std::string::npos ||
      condition.find("i>=0") != std::string::npos)
    return " (an index out of range)";
  if (condition.find("startRow") != std::string::npos ||
      condition.find("start >= 0") != std::string::npos)
    return " (an index out of range: a block or segment that reaches past the end)";
  if (condition.find("rows()") != std::string::npos ||
      condition.find("cols()") != std::string::npos ||
      condition.find("size()") != std::string::npos)
    return " (sizes that do not match)";
  return "";
}

// One frame of a sanitizer's stack, "    #3 0x55d0 in Check::add<...>(int, ...) /src/x.cpp:216"
// (or "(binary+0x1f2)" where there is no debug information): the function without its
// template arguments and parameters, and the file:line when there is one.
struct Frame {
  std::string function, where;
  bool found() const { return !function.empty() || !where.empty(); }
};

Frame parse_frame(const std::string& line) {
  Frame f;
  static const std::regex frame(
      R"(^ *#[0-9]+ 0x[0-9a-f]+ in (.*?)(?: (/[^ ]*:[0-9]+(?::[0-9]+)?)| \([^()]*\))?$)");
  std::smatch m;
  if (!std::regex_match(line, m, frame)) return f;
  std::string fn = m[1].str();
  for (std::string before; before != fn;) {  // drop template arguments, innermost first
    before = fn;
    fn = std::regex_replace(fn, std::regex("<[^<>]*>"), "");
  }
  fn = fn.substr(0, fn.find('('));
  f.function = fn.substr(fn.rfind(' ') == std::string::npos ? 0 : fn.rfind(' ') + 1);
  // The student's exercise functions are soa_student_<name> in the program (watch.cmake, for
  // the recorders): the student knows them by <name>.
  f.function = std::regex_replace(f.function, std::regex("::soa_student_"), "::");
  f.where = m[2].str();
  return f;
}

// The project-relative part of a frame's file:line, from the match of \p tail on (and its
// parent folder with \p parent: "exercises/03-x/exercises.cpp:12").
std::string shorter(const std::string& where, const std::regex& tail, bool parent) {
  std::smatch m;
  if (!std::regex_search(where, m, tail)) return where;
  const std::size_t at = std::size_t(m.position(0));
  const auto dir = parent && at > 0 ? where.rfind('/', at - 1) : std::string::npos;
  return where.substr(dir == std::string::npos ? at + 1 : dir + 1);
}

// What stopped an exercise, from its stderr: the reason (assertion, sanitizer report) and
// whose code it stopped in: the first frame in the student's code (a file under exercises/),
// else the checker's (tests/), whose stack then holds no line of the student's.
std::string stopped_message(const std::string& err, const std::string& log) {
  std::istringstream in(err);
  std::string line, reason;
  Frame student, checker;
  static const std::regex student_file(R"(/[0-9][0-9]-[A-Za-z0-9-]+/[^/ ]+\.[ch]pp:[0-9])");
  static const std::regex checker_file(R"(/tests/(exercises|support)/[^/ ]+\.[ch]pp:[0-9])");
  static const std::regex student_function("^soa::ex[0-9]+::");
  static const std::regex checker_function("^soa::test::|^Exercise[0-9]+_[0-9]+_.*::TestBody$");
  while (std::getline(in, line)) {
    if (reason.empty()) {
      std::size_t p;
      if ((p = line.find("Assertion `")) != std::string::npos ||
          (p = line.find("Assertion '")) != std::string::npos) {
        const std::string condition = line.substr(p + 11, line.rfind(" failed") == std::string::npos
                                                              ? std::string::npos
                                                              : line.rfind(" failed") - p - 12);
        reason = "assertion '" + condition + "' failed" + assertion_kind(condition);
      } else if ((p = line.find("ERROR: AddressSanitizer: ")) != std::string::npos) {
        reason = "AddressSanitizer: " + line.substr(p + 25, line.find(" on ", p) - p - 25);
      } else if ((p = line.find("runtime error: ")) != std::string::npos) {
        reason = "UBSan: " + line.substr(p + 15);
        // UBSan prints no stack; its line begins with the place, "FILE:LINE:COLUMN: ".
        const std::string place = line.substr(0, p >= 2 ? p - 2 : 0);
        if (std::regex_search(place, student_file))
          student.where = shorter(place, student_file, true);
      }
    }
    // The student's code: its functions (namespace soa::exNN) in a lesson's folder NN-topic/
    // (exercises/, or the solutions when the checker itself is tested). The checker's: the
    // tests (ExerciseL_K_*::TestBody) and soa::test, in tests/exercises/ and tests/support/.
    // The runner's own frames (this file: the signal handler) are neither's.
    const Frame f = parse_frame(line);
    if (!f.found() || student.found() || f.function == "on_fatal_signal" ||
        f.where.find("/exercise_main.cpp:") != std::string::npos)
      continue;
    if (std::regex_search(f.where, student_file) ||
        std::regex_search(f.function, student_function)) {
      student = f;
      student.where = shorter(f.where, student_file, true);
    } else if (!checker.found() && (std::regex_search(f.where, checker_file) ||
                                    std::regex_search(f.function, checker_function))) {
      checker = f;
      checker.where = shorter(f.where, std::regex("/tests/"), false);
    }
  }
  if (reason.empty()) {
    const auto p = err.find("SOA-STOPPED: ");
    reason = p == std::string::npos ? "the program stopped"
                                    : err.substr(p + 13, err.find('\n', p) - p - 13);
  }
  std::string msg = "stopped: " + reason + "\n";
  if (student.found())
    msg += "  at your line " + (student.where.empty() ? "(no line information)" : student.where) +
           (student.function.empty() ? "" : " (in " + student.function + ")") + "\n";
  else if (checker.found())
    msg += "  the checker stopped in " + checker.function + " while reading your result" +
           (checker.where.empty() ? "" : " (" + checker.where + ")") +
           ": no line of your code is on the stack\n";
  else
    msg += "  no line of your code or of the checker is on the stack\n";
  if (!log.empty()) msg += "  the full report, with the stack: " + log + "\n";
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

// The limits of one exercise's run.
struct Limits {
  int seconds = 10;                         ///< wall time (SOA_EXERCISE_TIME_LIMIT)
  rlim_t output_bytes = 64L * 1024 * 1024;  ///< what it may print (RLIMIT_FSIZE)
  int shown_lines = 12;                     ///< printed lines shown under its row
};

// Waits for the child \p pid, the leader of its own process group, at most \p seconds; kills
// it after that. Then every process left in its group (what the exercise's code started and
// left running, a fork bomb's) is killed, so that the next exercise runs alone. False if the
// child was killed.
bool wait_for(pid_t pid, int seconds, int& status) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  bool in_time = true;
  while (true) {
    const pid_t r = waitpid(pid, &status, WNOHANG);
    if (r == pid || (r < 0 && errno != EINTR)) break;
    if (std::chrono::steady_clock::now() >= end) {
      kill(-pid, SIGKILL);
      waitpid(pid, &status, 0);
      in_time = false;
      break;
    }
    usleep(2000);
  }
  kill(-pid, SIGKILL);
  return in_time;
}

// What the exercise printed, under its row: the first lines, and the rest in a file.
std::string printed_note(const std::string& text, const std::string& log, int shown) {
  if (text.empty()) return "";
  const int lines = int(std::count(text.begin(), text.end(), '\n')) + (text.back() != '\n');
  std::string note = "your code printed " + std::to_string(lines) +
                     (lines == 1 ? " line" : " lines") + (lines > shown ? ", the first:" : ":") +
                     "\n";
  std::istringstream in(text);
  std::string line;
  for (int i = 0; i < shown && std::getline(in, line); ++i)
    note += "  | " + (line.size() > 160 ? line.substr(0, 160) + " ..." : line) + "\n";
  if (lines > shown && !log.empty()) note += "  all of it: " + log + "\n";
  return note;
}

// Writes \p text to \p dir/<name>; the path, or "" when there is no such folder.
std::string keep(const char* dir, const std::string& name, const std::string& text) {
  if (!dir || !*dir) return "";
  const std::string path = std::string(dir) + "/" + name;
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) return "";
  std::fwrite(text.data(), 1, text.size(), f);
  std::fclose(f);
  return path;
}

// How a run that stopped stopped, as a --results status: out of memory (an allocation the
// sanitizer or the C++ runtime refused, or a kill the time limit did not send: the kernel's
// out-of-memory killer), else crashed, with the signal when there is one (the runner's
// handler exits with 128 + the signal; a sanitizer's report exits with 1).
std::string stopped_status(int status, const std::string& report) {
  for (const char* oom :
       {"out of memory", "out-of-memory", "allocation-size-too-big",
        "exceeds maximum supported size", "rss limit exhausted", "std::bad_alloc"})
    if (report.find(oom) != std::string::npos) return "out-of-memory";
  int sig = 0;
  if (WIFSIGNALED(status))
    sig = WTERMSIG(status);
  else if (WIFEXITED(status) && WEXITSTATUS(status) > 128)
    sig = WEXITSTATUS(status) - 128;
  if (sig == SIGKILL) return "out-of-memory";
  const char* abbrev = sig > 0 ? sigabbrev_np(sig) : nullptr;
  return abbrev ? std::string("crashed:SIG") + abbrev : "crashed";
}

// --record DIR, --replay DIR: where each exercise's record is.
struct Recording {
  const char* record = nullptr;
  const char* replay = nullptr;
};

// In the child process of one exercise: its record started, written or read at
// <dir>/<exercise>.rec.
void start_recording(const Recording& rec, const std::string& name) {
  if (rec.record) {
    const std::string path = std::string(rec.record) + "/" + name + ".rec";
    const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    if (fd < 0) {
      std::fprintf(stderr, "%s: %s\n", path.c_str(), std::strerror(errno));
      _exit(3);
    }
    soa::test::recording::start_recording(fd);
  } else if (rec.replay) {
    std::ifstream in(std::string(rec.replay) + "/" + name + ".rec", std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    soa::test::recording::start_replay(bytes.str());
  }
}

// --report: every exercise (test suite) in a child process of its own, under Limits.
void run_isolated(Table& table, const Limits& limits, const Recording& rec) {
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
    const std::string name = suite.rfind("Exercise", 0) == 0 ? suite.substr(8) : suite;
    std::FILE* err = std::tmpfile();
    std::FILE* out = std::tmpfile();
    std::FILE* printed = std::tmpfile();
    std::fflush(stdout);
    const pid_t pid = fork();
    if (pid == 0) {
      // A process group of its own (wait_for() ends it whole), and killed if the runner dies
      // (Ctrl-C reaches the runner's group, not this one).
      setpgid(0, 0);
      prctl(PR_SET_PDEATHSIG, SIGKILL);
      dup2(fileno(err), 2);
      dup2(fileno(printed), 1);
      setvbuf(stdout, nullptr, _IOLBF, 0);
      const rlimit fsize{limits.output_bytes, limits.output_bytes};
      setrlimit(RLIMIT_FSIZE, &fsize);
      for (int sig : {SIGABRT, SIGSEGV, SIGFPE, SIGBUS, SIGILL}) std::signal(sig, on_fatal_signal);
      GTEST_FLAG_SET(filter, suite + ".*");
      start_recording(rec, name);
      const int failed = RUN_ALL_TESTS();  // the row says it
      (void)failed;
      std::fflush(stdout);
      if (rec.replay) {
        const std::string why = soa::test::recording::replay_verdict();
        if (!why.empty()) table.unjudge(suite, why);
      }
      const std::string label = Table::label(suite);
      const std::string calls = forbidden_calls(label.substr(0, label.find(' ')));
      if (!calls.empty()) table.forbid(suite, calls);
      const std::string row = table.serialize(suite);
      std::fwrite(row.data(), 1, row.size(), out);
      std::fflush(out);
      _exit(0);
    }
    if (pid < 0) {
      Row r;
      r.failed = true;
      r.stopped = "crashed";
      r.first_failure = std::string("not run: no process could be started for it (") +
                        std::strerror(errno) + "): too many processes still running?\n";
      std::fclose(err);
      std::fclose(out);
      std::fclose(printed);
      table.set(suite, r);
      continue;
    }
    setpgid(pid, pid);
    int status = 0;
    const bool in_time = wait_for(pid, limits.seconds, status);
    const std::string row = read_all(out);
    const std::string text = read_all(printed);
    const std::string output_log = keep(cases, name + "-output.log", text);
    Row r;
    if (in_time && WIFEXITED(status) && WEXITSTATUS(status) == 0 && !row.empty()) {
      r.failed = row[0] == '1';
      r.not_done = row.size() > 2 && row[2] == '1';
      r.forbidden = row.size() > 4 && row[4] == '1';
      r.unjudged = row.size() > 6 && row[6] == '1';
      r.first_failure = row.substr(std::min(row.size(), row.find('\n') + 1));
    } else {
      r.failed = true;
      if (!in_time) {
        r.stopped = "timed-out";
        r.first_failure = "stopped after " + std::to_string(limits.seconds) +
                          " s: an endless loop? (a loop whose condition never changes, or an "
                          "index that never reaches its end)\n";
      } else if (WIFSIGNALED(status) && WTERMSIG(status) == SIGXFSZ) {
        r.stopped = "crashed:SIGXFSZ";
        r.first_failure = "stopped: your code printed more than " +
                          std::to_string(limits.output_bytes >> 20) +
                          " MB (an endless loop that prints?)\n";
      } else {
        const std::string report_text = read_all(err);
        r.first_failure =
            stopped_message(report_text, keep(cases, name + "-stopped.log", report_text));
        r.stopped = stopped_status(status, report_text);
      }
    }
    r.notes = printed_note(text, output_log, limits.shown_lines);
    std::fclose(err);
    std::fclose(out);
    std::fclose(printed);
    table.set(suite, r);
  }
}

}  // namespace

int main(int argc, char** argv) {
  bool report = false, expect_all_fail = false;
  const char* header = nullptr;
  const char* results = nullptr;
  Recording rec;
  std::vector<std::string> warning_files;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (std::strcmp(argv[i], "--report") == 0)
      report = true;
    else if (std::strcmp(argv[i], "--header") == 0 && i + 1 < argc)
      header = argv[++i];
    else if (std::strcmp(argv[i], "--warnings") == 0 && i + 1 < argc)
      warning_files.push_back(argv[++i]);
    else if (std::strcmp(argv[i], "--results") == 0 && i + 1 < argc)
      results = argv[++i];
    else if (std::strcmp(argv[i], "--record") == 0 && i + 1 < argc)
      rec.record = argv[++i];
    else if (std::strcmp(argv[i], "--replay") == 0 && i + 1 < argc)
      rec.replay = argv[++i];
    else if (std::strcmp(argv[i], "--expect-all-fail") == 0)
      expect_all_fail = true;
    else if (std::strcmp(argv[i], "--seed") == 0 && i + 1 < argc) {
      char* end = nullptr;
      const unsigned long long seed = std::strtoull(argv[++i], &end, 10);
      if (seed == 0 || *end != '\0' || argv[i][0] == '-') {
        std::fprintf(stderr, "--seed %s: a positive whole number is expected\n", argv[i]);
        return 2;
      }
      soa::test::seed_salt() = seed;
    } else
      args.push_back(argv[i]);
  }
  if ((rec.record || rec.replay) && !report) {
    std::fprintf(stderr, "--record and --replay need --report\n");
    return 2;
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
  Limits limits;
  if (const char* t = std::getenv("SOA_EXERCISE_TIME_LIMIT"); t && std::atoi(t) > 0)
    limits.seconds = std::atoi(t);
  int rc = 0;
  if (report)
    run_isolated(*table, limits, rec);
  else
    rc = RUN_ALL_TESTS();
  const Statements statements = read_statements(header);
  const auto warnings = read_warnings(warning_files, statements);
  table->print(statements, warnings);
  std::printf("  %d of %d exercises pass\n", table->passed(), table->total());
  if (results && report) {
    const bool written = table->write_results(results, warnings);
    if (!written) std::fprintf(stderr, "%s: could not be written\n", results);
    // Ended here, without exit(): a student's static destructor or atexit() handler would
    // run after the results are written, and could write them again.
    std::fflush(nullptr);
    _exit(written ? 0 : 1);
  }
  if (report) return 0;
  if (expect_all_fail) return table->passed() == 0 && table->total() > 0 ? 0 : 1;
  return rc;
}
