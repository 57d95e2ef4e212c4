// Trajectory files: the header simulate --out writes, and the strict reader of view
// --trajectory (every problem one line naming the file, the line and the column).
#include "trajectory.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "output.hpp"

namespace soa::cli {
namespace {

/// The most text kept in memory for a second reading of a file that is not a regular one.
constexpr std::size_t kMaxPipeBytes = std::size_t(1) << 30;

/// \p text in double quotes, escaped so that a message stays on one line; past 60 bytes cut
/// short with "..." (a field of a file that is no trajectory may be long).
std::string in_quotes(const std::string& text) {
  std::string s = text;
  if (s.size() > 60) {
    std::size_t cut = 57;
    while (cut > 0 && (static_cast<unsigned char>(s[cut]) & 0xC0) == 0x80) --cut;  // UTF-8
    s = s.substr(0, cut) + "...";
  }
  std::string q = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      q += '\\';
      q += c;
    } else if (c == '\n') {
      q += "\\n";
    } else if (c == '\r') {
      q += "\\r";
    } else if (c == '\t') {
      q += "\\t";
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", static_cast<unsigned char>(c));
      q += buf;
    } else {
      q += c;
    }
  }
  return q + "\"";
}

/// A file descriptor closed on every path.
struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

/// The characters of the file, read through a buffer with every read checked; or, on the
/// second reading of a pipe, of the text kept from the first (\p tee).
class Chars {
 public:
  Chars(int fd, const std::string& file, std::string* tee) : fd_(fd), file_(file), tee_(tee) {}
  explicit Chars(const std::string& text)
      : fd_(-1), file_(), tee_(nullptr), text_(text.data()), pos_(0), end_(text.size()) {}
  int get() {
    if (pos_ == end_ && !refill()) return EOF;
    return static_cast<unsigned char>(text_[pos_++]);
  }
  int peek() {
    if (pos_ == end_ && !refill()) return EOF;
    return static_cast<unsigned char>(text_[pos_]);
  }

 private:
  bool refill() {
    if (fd_ < 0) return false;
    ssize_t n;
    do n = ::read(fd_, buf_, sizeof buf_);
    while (n < 0 && errno == EINTR);
    if (n < 0) throw FileError(file_ + ": cannot read the file (" + std::strerror(errno) + ")");
    if (n == 0) return false;
    if (tee_) {
      if (tee_->size() + std::size_t(n) > kMaxPipeBytes)
        throw FileError(file_ +
                        ": larger than 1 GiB, the most a trajectory that is not a regular file "
                        "(a pipe) may hold; write it to a file");
      tee_->append(buf_, std::size_t(n));
    }
    text_ = buf_;
    pos_ = 0;
    end_ = std::size_t(n);
    return true;
  }
  int fd_;
  std::string file_;
  std::string* tee_;
  char buf_[1 << 16];
  const char* text_ = buf_;
  std::size_t pos_ = 0, end_ = 0;
};

/// The records of a CSV text as RFC 4180 reads them (fields quoted or not, a quoted field may
/// hold commas, doubled quotes and line breaks; a record ends at "\n" or "\r\n"), with the
/// line each begins on.
class Records {
 public:
  Records(Chars& in, const std::string& file, std::size_t max_bytes)
      : in_(in), file_(file), max_(max_bytes) {}
  /// The next record's fields; false at the end of the text.
  bool next(std::vector<std::string>& fields);
  long line() const { return start_; }  ///< the line the last record began on

 private:
  Chars& in_;
  const std::string& file_;
  std::size_t max_;
  long line_ = 1, start_ = 1;
};

bool Records::next(std::vector<std::string>& fields) {
  fields.assign(1, std::string());
  start_ = line_;
  int c = in_.get();
  if (c == EOF) return false;
  bool quoted_field = false;
  for (std::size_t size = 1;; c = in_.get(), ++size) {
    if (c == EOF) {
      if (quoted_field)
        throw FileError(file_ + ": line " + std::to_string(start_) +
                        ": a quoted field is not closed before the end of the file");
      return true;
    }
    if (size > max_)
      throw FileError(file_ + ": line " + std::to_string(start_) + ": longer than " +
                      std::to_string(max_) +
                      " bytes, which no row of this scene's trajectory needs (is it one?)");
    std::string& field = fields.back();
    if (quoted_field) {
      if (c == '"' && in_.peek() == '"') {
        in_.get();
        field += '"';
      } else if (c == '"') {
        quoted_field = false;
      } else {
        if (c == '\n') ++line_;
        field += char(c);
      }
    } else if (c == '"') {
      quoted_field = true;
    } else if (c == ',') {
      fields.emplace_back();
    } else if (c == '\n') {
      ++line_;
      return true;
    } else if (c == '\r' && in_.peek() == '\n') {
      // "\r\n" ends the record as "\n" does (a file saved on Windows)
    } else {
      field += char(c);
    }
  }
}

/// A finite number, the whole of \p text but for spaces around it.
bool parse_number(const std::string& text, double& x, std::string& problem) {
  const std::size_t a = text.find_first_not_of(" \t");
  if (a == std::string::npos) {
    problem = "is empty";
    return false;
  }
  const std::string s = text.substr(a, text.find_last_not_of(" \t") - a + 1);
  char* end = nullptr;
  errno = 0;
  x = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size()) {
    problem = in_quotes(text) + " is not a number";
    return false;
  }
  if (!std::isfinite(x)) {
    problem = in_quotes(text) + " is not a finite number";
    return false;
  }
  return true;
}

/// |c| of four numbers without overflow (a quaternion read from the file).
double norm4(const double* c) {
  double m = 0;
  for (int i = 0; i < 4; ++i) m = std::max(m, std::abs(c[i]));
  if (!(m > 0)) return m;
  double s = 0;
  for (int i = 0; i < 4; ++i) s += (c[i] / m) * (c[i] / m);
  return m * std::sqrt(s);
}

/// One reading of the file: the header, then every row checked; \p row (when not null)
/// gets each state.
TrajectoryInfo scan(const Scene& scene, const std::vector<std::string>& columns,
                    const std::string& path, Chars& in,
                    const std::function<void(double, const State&)>* row) {
  const std::size_t nq = file_q_index(scene).size(), nv = file_v_index(scene).size();
  std::size_t header_bytes = 0;
  for (const std::string& c : columns) header_bytes += 2 * c.size() + 3;
  // A row is numbers: 64 bytes each is far more than the 24 a double needs at most.
  Records records(in, path, 4096 + header_bytes + 64 * columns.size());
  std::vector<std::string> f;
  // "the header soa simulate --out writes for arm7.json: t, 7 q and 7 qd in ..."
  const std::string header = "the header soa simulate --out writes for " +
                             std::filesystem::path(scene.name).filename().string() + ": t, " +
                             std::to_string(nq) + " q and " + std::to_string(nv) +
                             " qd in the scene's order, energy, quaternion_norm_error";
  if (!records.next(f)) throw FileError(path + ": line 1: empty file, expected " + header);
  if (f[0].rfind("\xEF\xBB\xBF", 0) == 0) f[0].erase(0, 3);  // a byte order mark
  if (f != columns) {
    for (std::size_t c = 0; c < std::min(f.size(), columns.size()); ++c)
      if (f[c] != columns[c])
        throw FileError(path + ": line 1, column " + std::to_string(c + 1) + ": " +
                        in_quotes(f[c]) + ", expected " + in_quotes(columns[c]) + " (" + header +
                        ")");
    throw FileError(path + ": line 1: " + std::to_string(f.size()) + " columns, expected " +
                    std::to_string(columns.size()) + " (" + header + ")");
  }
  // Where each quaternion sits among the q columns (spherical and free hinges: the first
  // four coordinates of the body's), to name the columns of one that is not of unit norm.
  struct Quaternion {
    std::size_t column;  // of its x, in the q values (0 = the first q column)
    std::string body;
  };
  std::vector<Quaternion> quaternions;
  std::size_t at = 0;
  for (int k : scene.file_order) {
    const Body& B = scene.model.body(k);
    if (B.hinge.type == HingeType::Spherical || B.hinge.type == HingeType::Free)
      quaternions.push_back({at, B.name});
    at += std::size_t(B.hinge.nq());
  }

  TrajectoryInfo info;
  std::vector<double> values(columns.size()), q(nq), v(nv);
  std::string t_text;  // the previous row's t as the file writes it
  State x;
  while (records.next(f)) {
    const std::string line = path + ": line " + std::to_string(records.line());
    auto column = [&](std::size_t c) { return line + ", column " + in_quotes(columns[c]) + ": "; };
    if (f.size() == 1 && f[0].empty())
      throw FileError(line + ": an empty line where a row of " + std::to_string(columns.size()) +
                      " numbers should be");
    if (f.size() != columns.size())
      throw FileError(line + ": " + std::to_string(f.size()) + " fields, where the header has " +
                      std::to_string(columns.size()));
    std::string problem;
    for (std::size_t c = 0; c < f.size(); ++c)
      if (!parse_number(f[c], values[c], problem)) throw FileError(column(c) + problem);
    const double t = values[0];
    if (t < 0)
      throw FileError(column(0) + in_quotes(f[0]) +
                      " is negative; a trajectory begins at t = 0 (or later)");
    if (info.rows > 0 && !(t > info.t_last))
      throw FileError(column(0) + in_quotes(f[0]) + " is not after the previous row's " +
                      in_quotes(t_text) + " (times must increase)");
    std::copy(values.begin() + 1, values.begin() + 1 + long(nq), q.begin());
    std::copy(values.begin() + 1 + long(nq), values.begin() + 1 + long(nq + nv), v.begin());
    try {
      x.theta = theta_from_file_order(scene, q);
    } catch (const Error& e) {
      // Counts and finiteness are checked above: a quaternion that is not of unit norm, the
      // first in file order as the library checks them.
      std::string where = line + ", column " + in_quotes(columns[1]);
      for (const Quaternion& u : quaternions)
        if (!(std::abs(norm4(q.data() + u.column) - 1) <= 1e-6)) {
          where = line + ", columns " + in_quotes(columns[1 + u.column]) + " to " +
                  in_quotes(columns[4 + u.column]);
          break;
        }
      throw FileError(where + ": " + e.what());
    }
    x.beta = beta_from_file_order(scene, v);
    if (row) (*row)(t, x);
    ++info.rows;
    info.t_last = t;
    t_text = f[0];
  }
  if (info.rows == 0)
    throw FileError(path + ": line " + std::to_string(records.line()) +
                    ": no rows after the header");
  return info;
}

/// Opens \p path for reading; FileError with the reason.
int open_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw FileError(path + ": cannot open the file (" + std::strerror(errno) + ")");
  return fd;
}

}  // namespace

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string q = "\"";
  for (const char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::vector<std::string> trajectory_columns(const Scene& scene) {
  const Model& m = scene.model;
  std::vector<std::string> c = {"t"};
  auto name = [](const Body& B, int i, int n) {
    return n == 1 ? B.name : B.name + "[" + std::to_string(i) + "]";
  };
  for (int k : scene.file_order) {
    const Body& B = m.body(k);
    for (int i = 0; i < B.hinge.nq(); ++i) c.push_back("q:" + name(B, i, B.hinge.nq()));
  }
  for (int k : scene.file_order) {
    const Body& B = m.body(k);
    for (int i = 0; i < B.hinge.nv(); ++i) c.push_back("qd:" + name(B, i, B.hinge.nv()));
  }
  c.push_back("energy");
  c.push_back("quaternion_norm_error");
  return c;
}

void read_trajectory(const Scene& scene, const std::string& path,
                     const std::function<void(const TrajectoryInfo&)>& begin,
                     const std::function<void(double t, const State& x)>& row) {
  const std::vector<std::string> columns = trajectory_columns(scene);
  struct stat st;
  if (::stat(path.c_str(), &st) != 0)
    throw FileError(path + ": cannot open the file (" + std::strerror(errno) + ")");
  if (S_ISDIR(st.st_mode)) throw FileError(path + ": is a directory, not a trajectory file");
  const bool regular = S_ISREG(st.st_mode);
  std::string kept;  // a pipe's text, for the second reading
  TrajectoryInfo first;
  {
    Fd fd{open_file(path)};
    Chars in(fd.fd, path, regular ? nullptr : &kept);
    first = scan(scene, columns, path, in, nullptr);
  }
  begin(first);
  TrajectoryInfo second;
  if (regular) {
    Fd fd{open_file(path)};
    Chars in(fd.fd, path, nullptr);
    second = scan(scene, columns, path, in, &row);
  } else {
    Chars in(kept);
    second = scan(scene, columns, path, in, &row);
  }
  if (second.rows != first.rows || second.t_last != first.t_last)
    throw FileError(path + ": changed while it was read (" + std::to_string(first.rows) +
                    " rows, then " + std::to_string(second.rows) + ")");
}

}  // namespace soa::cli
