/// \file
/// The checks a lesson program runs as it goes, and its closing line.
///
/// Each identity the lecture states is computed on concrete numbers and checked: the
/// residual is printed beside the tolerance, and the program ends with
/// `N passed, M failed`, exiting non-zero when M > 0.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace soa::lesson {

class Checklist {
 public:
  /// Prints a section heading of the lecture.
  void section(const std::string& title) { std::printf("\n== %s ==\n", title.c_str()); }

  /// A check that \p residual (a norm of a difference, already scaled as the lesson says)
  /// is at most \p tolerance. NaN fails.
  bool check(const std::string& what, double residual, double tolerance) {
    const bool ok = residual <= tolerance;  // false for NaN
    std::printf("  [%s] %-60s residual %.3e (tol %.1e)\n", ok ? "pass" : "FAIL", what.c_str(),
                residual, tolerance);
    (ok ? passed_ : failed_) += 1;
    return ok;
  }

  /// A check of a yes/no fact.
  bool check(const std::string& what, bool ok) {
    std::printf("  [%s] %s\n", ok ? "pass" : "FAIL", what.c_str());
    (ok ? passed_ : failed_) += 1;
    return ok;
  }

  /// Prints the closing line and returns the exit status.
  int finish() const {
    std::printf("\n%d passed, %d failed\n", passed_, failed_);
    return failed_ == 0 ? 0 : 1;
  }

  int passed() const { return passed_; }
  int failed() const { return failed_; }

 private:
  int passed_ = 0;
  int failed_ = 0;
};

}  // namespace soa::lesson
