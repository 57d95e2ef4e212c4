// data.js: the viewer's data as one JSON object assigned to window.SOA_VIEW, in the order
// and with the names of docs/viewer.md. Numbers with 9 significant digits (%.9g: a
// millionth of a millimetre on a metre-sized chain, and a third of the bytes of a full
// double); one frame per line.
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "detail.hpp"

namespace soa::view::detail {
namespace {

/// Text handed to a Sink in pieces of about a megabyte.
class Text {
 public:
  explicit Text(Sink& out) : out_(out) { buf_.reserve(kPiece + 4096); }
  ~Text() = default;
  Text& operator<<(const char* s) {
    buf_ += s;
    return spill();
  }
  Text& operator<<(const std::string& s) {
    buf_ += s;
    return spill();
  }
  /// A number, %.9g (the check made sure it is finite).
  Text& num(double x) {
    char b[32];
    const int n = std::snprintf(b, sizeof b, "%.9g", x);
    buf_.append(b, std::size_t(n));
    return spill();
  }
  /// A JSON string: escaped, non-ASCII as \uXXXX (so U+2028 cannot end a line of script),
  /// invalid UTF-8 replaced.
  Text& str(const std::string& s) {
    buf_ += nlohmann::json(s).dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);
    return spill();
  }
  /// [x, y, z, ...] of \p n numbers.
  Text& array(const double* x, std::size_t n) {
    buf_ += '[';
    for (std::size_t i = 0; i < n; ++i) {
      if (i) buf_ += ',';
      num(x[i]);
    }
    buf_ += ']';
    return spill();
  }
  Text& vec(const Vec3<double>& v) { return array(v.data(), 3); }
  void flush() {
    if (!buf_.empty()) out_.write(buf_.data(), buf_.size());
    buf_.clear();
  }

 private:
  static constexpr std::size_t kPiece = std::size_t(1) << 20;
  Text& spill() {
    if (buf_.size() >= kPiece) flush();
    return *this;
  }
  Sink& out_;
  std::string buf_;
};

void write_body(const Body& b, Text& o) {
  o << "{\"name\":";
  o.str(b.name) << ",\"hinge\":";
  o.str(b.hinge) << ",\"axis\":";
  o.vec(b.axis) << ",\"segment\":";
  o.vec(b.segment) << ",\"com\":";
  o.vec(b.com) << ",\"mass\":";
  o.num(b.mass) << ",\"radii\":";
  o.vec(b.radii) << ",\"axes_quaternion\":";
  o.array(b.axes_quaternion.data(), 4) << "}";
}

/// "name": [ one line per frame ] of a per-frame array member.
template <class Get>
void per_frame(const Run& r, const char* name, Text& o, Get get) {
  o << ",\n\"" << name << "\":[";
  for (std::size_t i = 0; i < r.frames.size(); ++i) {
    o << (i ? ",\n" : "\n");
    get(r.frames[i]);
  }
  o << "]";
}

void write_run(const Run& r, Text& o) {
  o << "{\"label\":";
  o.str(r.label) << ",\n\"t\":[";
  for (std::size_t i = 0; i < r.frames.size(); ++i) (i ? o << "," : o).num(r.frames[i].t);
  o << "],\n\"energy\":[";
  for (std::size_t i = 0; i < r.frames.size(); ++i) (i ? o << "," : o).num(r.frames[i].energy);
  o << "]";
  per_frame(r, "pose", o, [&](const Frame& f) { o.array(f.pose.data(), f.pose.size()); });
  if (!r.frames.empty() && !r.frames[0].V.empty())
    per_frame(r, "V", o, [&](const Frame& f) { o.array(f.V.data(), f.V.size()); });
  if (!r.frames.empty() && !r.frames[0].f.empty())
    per_frame(r, "f", o, [&](const Frame& f) { o.array(f.f.data(), f.f.size()); });
  o << ",\n\"tip\":[";
  for (std::size_t i = 0; i < r.frames.size(); ++i) (i ? o << "," : o).vec(r.frames[i].tip);
  o << "]}";
}

}  // namespace

void write_data_js(const View& v, Sink& out) {
  Text o(out);
  o << "window.SOA_VIEW = {\n\"format\":1,\n\"title\":";
  o.str(v.title) << ",\n\"note\":";
  o.str(v.note) << ",\n\"gravity\":";
  o.vec(v.gravity) << ",\n\"bodies\":[";
  for (std::size_t i = 0; i < v.bodies.size(); ++i) {
    o << (i ? ",\n" : "\n");
    write_body(v.bodies[i], o);
  }
  o << "],\n\"tip\":{\"body\":" << std::to_string(v.tip_body) << ",\"point\":";
  o.vec(v.tip_point) << "},\n\"fixed\":[";
  for (std::size_t i = 0; i < v.fixed.size(); ++i) {
    o << (i ? ",\n" : "\n") << "{\"label\":";
    o.str(v.fixed[i].label) << ",\"origin\":";
    o.vec(v.fixed[i].origin) << ",\"vector\":";
    o.vec(v.fixed[i].vector) << "}";
  }
  o << "],\n\"runs\":[";
  for (std::size_t i = 0; i < v.runs.size(); ++i) {
    o << (i ? ",\n" : "\n");
    write_run(v.runs[i], o);
  }
  o << "]\n};\n";
  o.flush();
}

}  // namespace soa::view::detail
