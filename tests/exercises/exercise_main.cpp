// The main of every exercise test binary. Each test suite is one exercise, named
// `ExerciseL_K_Name` (lesson L, exercise K). After the run it prints a table, exercise by
// exercise: pass, FAIL, or "not done" (the stub still throws soa::exercise::NotDone).
//
//   (no flag)           exit status of the tests: 0 when every exercise passes (make test)
//   --report            the table, exit 0 whatever the results (make exercises)
//   --expect-all-fail   exit 0 only when every exercise fails (CI's check of the stubs)
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace {

struct Row {
  bool failed = false;
  bool not_done = false;
  std::string first_failure;
};

class Table : public testing::EmptyTestEventListener {
 public:
  void OnTestPartResult(const testing::TestPartResult& r) override {
    if (!r.failed()) return;
    Row& row = rows_[current_];
    row.failed = true;
    std::string msg = r.message() ? r.message() : "";
    if (msg.find("not done") != std::string::npos) row.not_done = true;
    // ADD_FAILURE() << text gives "Failed\ntext": the text is what names the mistake.
    if (msg.rfind("Failed\n", 0) == 0) msg.erase(0, 7);
    if (row.first_failure.empty()) row.first_failure = msg.substr(0, msg.find('\n'));
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

  void print() const {
    std::printf("\n  %-40s %s\n", "exercise", "result");
    for (const auto& name : order_) {
      const Row& r = rows_.at(name);
      const char* status = !r.failed ? "pass" : r.not_done ? "not done" : "FAIL";
      std::printf("  %-40s %s\n", label(name).c_str(), status);
      if (r.failed && !r.not_done) std::printf("      %s\n", r.first_failure.c_str());
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
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (std::strcmp(argv[i], "--report") == 0)
      report = true;
    else if (std::strcmp(argv[i], "--expect-all-fail") == 0)
      expect_all_fail = true;
    else
      args.push_back(argv[i]);
  }
  int n = int(args.size());
  testing::InitGoogleTest(&n, args.data());
  if (report || expect_all_fail) {
    // Keep the table readable: gtest's own per-test lines are left out.
    auto& listeners = testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  auto* table = new Table;
  testing::UnitTest::GetInstance()->listeners().Append(table);
  const int rc = RUN_ALL_TESTS();
  table->print();
  std::printf("  %d of %d exercises pass\n", table->passed(), table->total());
  if (report) return 0;
  if (expect_all_fail) return table->passed() == 0 && table->total() > 0 ? 0 : 1;
  return rc;
}
