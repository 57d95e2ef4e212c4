/// \file
/// A lesson's 3D viewers (soa::view, notes page "Viewing a chain in 3D"): the page and its
/// data in a folder of the lesson's output, listed in `views.txt` with the query of its
/// still image, which the tour (lessons/tour.cmake) takes with Chromium as `<folder>.png`.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "checklist.hpp"
#include "soa/view.hpp"

namespace soa::lesson {

/// Writes \p view into `out/name/` and records `name query` in `out/views.txt` (replacing an
/// earlier line of the same name). \p query is the still image's URL query, e.g.
/// `paused=1&t=1.5&show=ellipsoids,fixed`. Returns false, with the reason in \p why, when
/// the folder could not be written.
inline bool write_viewer(const std::filesystem::path& out, const std::string& name,
                         const soa::view::View& view, const std::string& query, std::string& why) {
  try {
    soa::view::write(view, out / name);
  } catch (const std::exception& e) {
    why = e.what();
    return false;
  }
  const std::filesystem::path list = out / "views.txt";
  std::vector<std::string> lines;
  {
    std::ifstream in(list);
    for (std::string line; std::getline(in, line);)
      if (!line.empty() && line.rfind(name + " ", 0) != 0 && line != name) lines.push_back(line);
  }
  lines.push_back(name + " " + query);
  std::ofstream o(list, std::ios::trunc);
  for (const std::string& line : lines) o << line << "\n";
  o.close();
  if (!o) {
    why = "cannot write " + list.string();
    return false;
  }
  return true;
}

/// write_viewer() as the lesson check "viewer written: <name>" (with the reason when it fails).
inline bool check_viewer(Checklist& checks, const std::filesystem::path& out,
                         const std::string& name, const soa::view::View& view,
                         const std::string& query) {
  std::string why;
  const bool ok = write_viewer(out, name, view, query, why);
  return checks.check("viewer written: " + name + (ok ? "" : " (" + why + ")"), ok);
}

}  // namespace soa::lesson
