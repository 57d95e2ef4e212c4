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
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Row {
  bool failed = false;
  bool not_done = false;
  std::string first_failure;
};

// "4.2" -> "level 2, 30 min, uses 4.1", read from the statements in exercises.hpp.
std::map<std::string, std::string> read_meta(const char* header) {
  std::map<std::string, std::string> meta;
  if (!header) return meta;
  std::ifstream in(header);
  const std::regex title(R"(\*\*Exercise (\d+\.\d+):)");
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
    // gtest's own messages ("Expected: ...") are shown by their first line; the exercise
    // checker's (which start with the check's name) in full.
    if (row.first_failure.empty())
      row.first_failure = msg.rfind("Expected", 0) == 0 || msg.rfind("Value of", 0) == 0
                              ? msg.substr(0, msg.find('\n'))
                              : msg;
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
    std::printf("\n  %-34s %-28s %s\n", "exercise", "", "result");
    for (const auto& name : order_) {
      const Row& r = rows_.at(name);
      const char* status = !r.failed ? "pass" : r.not_done ? "not done" : "FAIL";
      const std::string l = label(name);
      const auto it = meta.find(l.substr(0, l.find(' ')));
      std::printf("  %-34s %-28s %s\n", l.c_str(), it == meta.end() ? "" : it->second.c_str(),
                  status);
      if (r.failed && !r.not_done) {
        std::istringstream text(r.first_failure);
        std::string line;
        int lines = 0;
        while (std::getline(text, line) && lines++ < 60) std::printf("      %s\n", line.c_str());
      }
    }
  }
  int passed() const {
    int n = 0;
    for (const auto& [name, r] : rows_) n += !r.failed;
    return n;
  }
  int total() const { return int(rows_.size()); }

 private:
  std::string current_;
  std::vector<std::string> order_;
  std::map<std::string, Row> rows_;
};

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
  const int rc = RUN_ALL_TESTS();
  table->print(read_meta(header));
  std::printf("  %d of %d exercises pass\n", table->passed(), table->total());
  if (report) return 0;
  if (expect_all_fail) return table->passed() == 0 && table->total() > 0 ? 0 : 1;
  return rc;
}
