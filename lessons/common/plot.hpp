/// \file
/// Drawing a lesson's figures with gnuplot.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>

namespace soa::lesson {

/// Runs gnuplot on \p script, kept beside the lesson program (SOA_LESSON_SOURCE_DIR), with
/// the output directory passed as `outdir`. The figure counts as written when gnuplot exits
/// with 0 and \p png is not empty.
inline bool plot(const std::string& script, const std::filesystem::path& out,
                 const std::string& png) {
  const std::filesystem::path file = out / png;
  std::error_code ec;
  std::filesystem::remove(file, ec);
  const std::string command = "gnuplot -e \"outdir='" + out.string() + "'\" '" +
                              std::string(SOA_LESSON_SOURCE_DIR) + "/" + script + "'";
  const int rc = std::system(command.c_str());
  return rc == 0 && std::filesystem::exists(file) && std::filesystem::file_size(file, ec) > 0;
}

}  // namespace soa::lesson
