// JSON output of `soa`, streamed: a verb's result is a function that writes it through a
// JsonWriter, run twice — once to check every number is finite (nothing is written), then
// into the output. Nothing of a result is held as a document, so the output of a 10^6-body
// chain costs O(1) memory beyond the workspace it comes from.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace soa::cli {

/// Where output text goes.
class Sink {
 public:
  virtual ~Sink() = default;
  virtual void write(const char* data, std::size_t n) = 0;
};

/// A number as JSON writes it: the shortest text that reads back exactly ("0.1", "1.0",
/// "1e-05"; nlohmann's Grisu2, so the output is what nlohmann's dump() gave). \p x must be
/// finite. Returns the end of the text in \p buf (32 bytes suffice).
char* format_number(char* buf, double x);

/// Writes JSON in soa's layout: objects one member per line, indented two spaces a level;
/// arrays of numbers or of strings on one line; arrays of arrays one entry per line. Strings
/// are escaped, invalid UTF-8 replaced by U+FFFD (a file name from the command line need not
/// be UTF-8), so writing never throws. With no sink the writer only checks: finite() turns
/// false at the first NaN or infinite number.
class JsonWriter {
 public:
  explicit JsonWriter(Sink* sink) : sink_(sink) {}

  void begin_object();
  void end_object();
  void begin_array();  ///< an array of structured values (objects, rows)
  void end_array();
  void key(std::string_view k);  ///< the next member's name (inside an object)

  void value(double x);
  void value(long long x);
  void value(long x) { value(static_cast<long long>(x)); }
  void value(int x) { value(static_cast<long long>(x)); }
  void value(bool b);
  void value(std::string_view s);
  void value(const char* s) { value(std::string_view(s)); }
  void value(const std::string& s) { value(std::string_view(s)); }

  /// A member of an object: key(\p k), then value(\p v).
  template <class T>
  void member(std::string_view k, const T& v) {
    key(k);
    value(v);
  }

  /// A vector as an array of numbers on one line.
  template <class Derived>
  void numbers(const Eigen::MatrixBase<Derived>& x) {
    open_value();
    if (!sink_) {
      finite_ = finite_ && x.allFinite();
      return;
    }
    buf_ += '[';
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      if (i) buf_ += ", ";
      append_number(double(x(i)));
    }
    buf_ += ']';
    spill();
  }
  /// A matrix as an array of its rows.
  template <class Derived>
  void rows(const Eigen::MatrixBase<Derived>& M) {
    begin_array();
    for (Eigen::Index r = 0; r < M.rows(); ++r) numbers(M.row(r));
    end_array();
  }
  /// An array of strings on one line.
  void strings(const std::vector<std::string>& s);

  /// Ends the document (a newline) and hands everything to the sink.
  void finish();
  /// False once a number that is not finite was given (checking writer).
  bool finite() const { return finite_; }

 private:
  struct Level {
    bool object;
    bool empty;
  };
  void open_value();  // the separator and indentation before a value
  void close(char bracket);
  void append_number(double x);
  void append_string(std::string_view s);
  void spill();  // hands the buffer to the sink when it is large
  Sink* sink_;
  std::string buf_;
  std::vector<Level> stack_;
  bool after_key_ = false;
  bool finite_ = true;
};

/// A result: writes itself through a JsonWriter (called twice, see above).
using Emit = std::function<void(JsonWriter&)>;

/// True when every number \p emit writes is finite.
bool all_finite(const Emit& emit);

}  // namespace soa::cli
