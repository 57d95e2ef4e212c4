/// \file
/// The command line of the lesson programs and reports: `PROGRAM OUTPUT_DIR [--quick]`.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace soa::lesson {

/// The output folder of `PROGRAM OUTPUT_DIR [--quick]`, created if absent; \p quick (when
/// not null) tells whether --quick was given, which only the programs that pass it accept.
/// `--help` or `-h` prints the usage and exits 0; no folder, an unknown option, a second
/// folder or a folder that cannot be created prints one line and exits 2. An argument that
/// starts with '-' is never taken for the folder.
inline std::filesystem::path output_dir(int argc, char** argv, bool* quick = nullptr) {
  const char* prog = argc > 0 ? argv[0] : "lesson";
  const std::string usage =
      std::string("usage: ") + prog + " OUTPUT_DIR" + (quick ? " [--quick]" : "");
  std::filesystem::path out;
  if (quick) *quick = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::printf("%s\n", usage.c_str());
      std::exit(0);
    }
    if (quick && a == "--quick") {
      *quick = true;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "%s: unknown option '%s' (%s)\n", prog, a.c_str(), usage.c_str());
      std::exit(2);
    } else if (!out.empty()) {
      std::fprintf(stderr, "%s: one output folder only, '%s' and '%s' given (%s)\n", prog,
                   out.string().c_str(), a.c_str(), usage.c_str());
      std::exit(2);
    } else {
      out = a;
    }
  }
  if (out.empty()) {
    std::fprintf(stderr, "%s\n", usage.c_str());
    std::exit(2);
  }
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec || !std::filesystem::is_directory(out)) {
    std::fprintf(stderr, "%s: cannot use '%s' as the output folder (%s)\n", prog,
                 out.string().c_str(), ec ? ec.message().c_str() : "not a folder");
    std::exit(2);
  }
  return out;
}

}  // namespace soa::lesson
