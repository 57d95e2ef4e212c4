// The JSON writer of `soa`: numbers and strings as nlohmann writes them, laid out one
// member per line, vectors and matrix rows on one line each.
#include "json_out.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

namespace soa::cli {

char* format_number(char* buf, double x) {
  // nlohmann's own float printer (what json::dump() calls): shortest round-trip digits.
  return nlohmann::detail::to_chars(buf, buf + 32, x);
}

void JsonWriter::open_value() {
  if (after_key_) {
    after_key_ = false;
    return;
  }
  if (stack_.empty() || !sink_) {
    if (!stack_.empty()) stack_.back().empty = false;
    return;
  }
  Level& l = stack_.back();  // an element of a structured array
  buf_ += l.empty ? "\n" : ",\n";
  buf_.append(2 * stack_.size(), ' ');
  l.empty = false;
}

void JsonWriter::begin_object() {
  open_value();
  if (sink_) buf_ += '{';
  stack_.push_back({true, true});
}

void JsonWriter::begin_array() {
  open_value();
  if (sink_) buf_ += '[';
  stack_.push_back({false, true});
}

void JsonWriter::close(char bracket) {
  const bool empty = stack_.back().empty;
  stack_.pop_back();
  if (!sink_) return;
  if (!empty) {
    buf_ += '\n';
    buf_.append(2 * stack_.size(), ' ');
  }
  buf_ += bracket;
  spill();
}

void JsonWriter::end_object() {
  close('}');
}
void JsonWriter::end_array() {
  close(']');
}

void JsonWriter::key(std::string_view k) {
  Level& l = stack_.back();
  if (sink_) {
    buf_ += l.empty ? "\n" : ",\n";
    buf_.append(2 * stack_.size(), ' ');
    append_string(k);
    buf_ += ": ";
  }
  l.empty = false;
  after_key_ = true;
}

void JsonWriter::value(double x) {
  open_value();
  if (!sink_) {
    finite_ = finite_ && std::isfinite(x);
    return;
  }
  append_number(x);
  spill();
}

void JsonWriter::value(long long x) {
  open_value();
  if (sink_) buf_ += std::to_string(x);
}

void JsonWriter::value(bool b) {
  open_value();
  if (sink_) buf_ += b ? "true" : "false";
}

void JsonWriter::value(std::string_view s) {
  open_value();
  if (sink_) append_string(s);
}

void JsonWriter::strings(const std::vector<std::string>& s) {
  open_value();
  if (!sink_) return;
  buf_ += '[';
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (i) buf_ += ", ";
    append_string(s[i]);
  }
  buf_ += ']';
  spill();
}

void JsonWriter::append_number(double x) {
  if (!std::isfinite(x)) {  // checked before writing; never reached on a checked result
    buf_ += "null";
    return;
  }
  char text[32];
  buf_.append(text, format_number(text, x));
}

void JsonWriter::append_string(std::string_view s) {
  bool plain = true;  // the common case: printable ASCII needing no escape
  for (const char c : s)
    plain = plain && static_cast<unsigned char>(c) >= 0x20 &&
            static_cast<unsigned char>(c) < 0x7f && c != '"' && c != '\\';
  if (plain) {
    buf_ += '"';
    buf_.append(s.data(), s.size());
    buf_ += '"';
    return;
  }
  buf_ +=
      nlohmann::json(std::string(s)).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

void JsonWriter::spill() {
  if (buf_.size() >= (std::size_t(1) << 16)) {
    sink_->write(buf_.data(), buf_.size());
    buf_.clear();
  }
}

void JsonWriter::finish() {
  if (!sink_) return;
  buf_ += '\n';
  sink_->write(buf_.data(), buf_.size());
  buf_.clear();
}

bool all_finite(const Emit& emit) {
  JsonWriter check(nullptr);
  emit(check);
  return check.finite();
}

}  // namespace soa::cli
