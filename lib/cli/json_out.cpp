// The printer of `soa`'s JSON output: nlohmann writes the values (numbers in their shortest
// form that reads back exactly), this file only lays them out.
#include "json_out.hpp"

#include <cmath>
#include <string>

namespace soa::cli {
namespace {

bool is_flat(const Json& j) {
  for (const Json& e : j)
    if (e.is_structured()) return false;
  return true;
}

void write(std::ostream& out, const Json& j, int indent) {
  const std::string pad(indent + 2, ' ');
  if (j.is_object() && !j.empty()) {
    out << "{\n";
    bool first = true;
    for (const auto& item : j.items()) {
      out << (first ? "" : ",\n") << pad << Json(item.key()).dump() << ": ";
      write(out, item.value(), indent + 2);
      first = false;
    }
    out << "\n" << std::string(indent, ' ') << "}";
  } else if (j.is_array() && !j.empty() && !is_flat(j)) {
    out << "[\n";
    for (std::size_t i = 0; i < j.size(); ++i) {
      out << (i ? ",\n" : "") << pad;
      write(out, j[i], indent + 2);
    }
    out << "\n" << std::string(indent, ' ') << "]";
  } else if (j.is_array()) {
    out << "[";
    for (std::size_t i = 0; i < j.size(); ++i) out << (i ? ", " : "") << j[i].dump();
    out << "]";
  } else {
    out << j.dump();
  }
}

}  // namespace

bool all_finite(const Json& j) {
  if (j.is_number_float()) return std::isfinite(j.get<double>());
  for (const Json& e : j)  // the members of an object, the entries of an array
    if (e.is_structured() || e.is_number_float())
      if (!all_finite(e)) return false;
  return true;
}

void write_json(std::ostream& out, const Json& j) {
  write(out, j, 0);
  out << "\n";
}

}  // namespace soa::cli
