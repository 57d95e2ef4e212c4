/// \file
/// Numbers, CSV fields, times and the CPU's name as the lessons, the labs and the speed report
/// write them in their CSV files and markdown tables.
#pragma once

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

namespace soa::lesson {

/// A number for a CSV file or a table ("" for NaN: not computed).
inline std::string num(double v, const char* format = "%.3e") {
  if (std::isnan(v)) return "";
  char buf[48];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

/// A CSV field, quoted when it holds a comma or a quote (RFC 4180).
inline std::string csv_field(const std::string& f) {
  if (f.find_first_of(",\"") == std::string::npos) return f;
  std::string q = "\"";
  for (char c : f) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

/// A time for a table: ns, µs, ms or s.
inline std::string time_text(double ns) {
  if (std::isnan(ns)) return "-";
  if (ns < 1e3) return num(ns, "%.0f ns");
  if (ns < 1e6) return num(ns / 1e3, "%.3g µs");
  if (ns < 1e9) return num(ns / 1e6, "%.4g ms");
  return num(ns / 1e9, "%.4g s");
}

/// The CPU's model name from /proc/cpuinfo ("unknown CPU" elsewhere), for the machine line
/// of a timing report.
inline std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown CPU";
}

}  // namespace soa::lesson
