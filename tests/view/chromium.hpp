/// \file
/// Headless Chromium for the tests of the 3D viewer's page (lib/view, docs/viewer.md): loads a
/// page from `file://` and gives back the DOM after a virtual time budget and the console
/// messages, or a screenshot; reads the page's `data-` attributes and the folder's data.js.
///
/// Chromium renders WebGL in software (SwiftShader: `--use-angle=swiftshader
/// --enable-unsafe-swiftshader`; with `--disable-gpu` or `--use-gl=swiftshader` the canvas
/// stays blank), every host name resolves to nothing (a network load fails loudly), and each
/// load gets a fresh profile. One load takes seconds.
///
/// A test of a folder written by `soa view` is a few lines:
///
///     const auto page = soa::browser::load(dir / "index.html", "frame=3&paused=1");
///     ASSERT_TRUE(page.ok()) << page.why();
///     const auto tip = soa::browser::numbers(page.attribute("data-tip"));
///
/// The configure step passes SOA_CHROMIUM (Chromium's path, "" when not found).
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

extern char** environ;

namespace soa::browser {

namespace fs = std::filesystem;

/// "" when Chromium is there, else the one line that says it is missing.
inline std::string missing() {
  const std::string path = SOA_CHROMIUM;
  if (path.empty())
    return "chromium is missing: install it (apt-get install chromium, or make deps) and "
           "configure again";
  if (::access(path.c_str(), X_OK) != 0) return "chromium is missing: " + path + " is gone";
  return "";
}

inline std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_text(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + p.string());
}

/// The file:// URL of \p page (an absolute path; characters outside [A-Za-z0-9/._~-] are
/// percent-encoded), with `?query` when \p query is not empty.
inline std::string file_url(const fs::path& page, const std::string& query = "") {
  std::string url = "file://";
  for (unsigned char c : fs::absolute(page).lexically_normal().string()) {
    if (std::isalnum(c) || c == '/' || c == '.' || c == '_' || c == '~' || c == '-') {
      url += static_cast<char>(c);
    } else {
      static const char* hex = "0123456789ABCDEF";
      url += '%';
      url += hex[c >> 4];
      url += hex[c & 15];
    }
  }
  return query.empty() ? url : url + "?" + query;
}

/// Undoes the HTML escapes of an attribute value as Chromium serializes it.
inline std::string unescape(std::string s) {
  const std::pair<const char*, const char*> escapes[] = {
      {"&quot;", "\""},       {"&lt;", "<"}, {"&gt;", ">"}, {"&#39;", "'"},
      {"&nbsp;", "\xC2\xA0"}, {"&amp;", "&"}};  // &amp; last: "&amp;lt;" is "&lt;"
  for (const auto& [from, to] : escapes) {
    for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at)) {
      s.replace(at, std::char_traits<char>::length(from), to);
      at += std::char_traits<char>::length(to);
    }
  }
  return s;
}

/// The comma- or space-separated numbers of \p text ("1.5,-2,3e-4").
inline std::vector<double> numbers(const std::string& text) {
  std::vector<double> v;
  std::string item;
  std::istringstream in(text);
  while (std::getline(in, item, ',')) {
    std::istringstream words(item);
    for (std::string w; words >> w;) v.push_back(std::stod(w));
  }
  return v;
}

/// The words of \p text separated by spaces.
inline std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> v;
  std::istringstream in(text);
  for (std::string w; in >> w;) v.push_back(w);
  return v;
}

/// What one run of Chromium gave back.
struct Page {
  int exit_code = -1;
  std::string dom;                   ///< the serialized DOM after the budget (--dump-dom)
  std::string log;                   ///< Chromium's stderr
  std::vector<std::string> console;  ///< the page's console messages (any level)

  /// The page was dumped (Chromium exited normally).
  bool ok() const { return exit_code == 0; }
  std::string why() const {
    return "chromium exited with " + std::to_string(exit_code) + "; its log:\n" + log;
  }

  /// The value of \p name on the element `id="soa-view"` (or \p id), if it has one.
  std::optional<std::string> attribute(const std::string& name,
                                       const std::string& id = "soa-view") const {
    const std::size_t at = dom.find("id=\"" + id + "\"");
    if (at == std::string::npos) return std::nullopt;
    const std::size_t begin = dom.rfind('<', at);
    const std::size_t end = dom.find('>', at);
    const std::string tag = dom.substr(begin, end - begin);
    const std::string key = " " + name + "=\"";
    const std::size_t k = tag.find(key);
    if (k == std::string::npos) return std::nullopt;
    const std::size_t v = k + key.size();
    return unescape(tag.substr(v, tag.find('"', v) - v));
  }
  /// The attribute, or "" when absent.
  std::string attr(const std::string& name) const { return attribute(name).value_or(""); }
};

/// How Chromium loads the page.
struct Options {
  int budget_ms = 3000;  ///< --virtual-time-budget: page time before the dump or the screenshot
  int width = 900, height = 600;
  int timeout_s = 60;  ///< the wall-clock limit of one run (then it is killed)
};

namespace detail {

/// Runs Chromium on \p url with \p extra flags; stdout (the dumped DOM) and stderr are read
/// back. A fresh profile in a temporary folder, removed afterwards.
inline Page run(const std::string& url, const std::vector<std::string>& extra, const Options& o) {
  if (!missing().empty()) throw std::runtime_error(missing());
  std::string tmp = (fs::temp_directory_path() / "soa-chromium-XXXXXX").string();
  if (::mkdtemp(tmp.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  const fs::path dir = tmp;
  const std::string out = (dir / "stdout.txt").string();
  const std::string err = (dir / "stderr.txt").string();
  std::vector<std::string> args = {
      SOA_CHROMIUM,
      "--headless=new",
      "--no-sandbox",
      "--use-angle=swiftshader",
      "--enable-unsafe-swiftshader",
      "--disable-background-networking",
      "--disable-component-update",
      "--disable-sync",
      "--no-first-run",
      "--disable-quic",
      "--host-resolver-rules=MAP * ~NOTFOUND",
      "--enable-logging=stderr",
      "--v=0",
      "--user-data-dir=" + (dir / "profile").string(),
      "--virtual-time-budget=" + std::to_string(o.budget_ms),
      "--window-size=" + std::to_string(o.width) + "," + std::to_string(o.height)};
  args.insert(args.end(), extra.begin(), extra.end());
  args.push_back(url);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&files, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&files, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETPGROUP);  // its own group: killed as a whole
  posix_spawnattr_setpgroup(&attr, 0);
  pid_t pid = -1;
  const int started = posix_spawn(&pid, argv[0], &files, &attr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  posix_spawnattr_destroy(&attr);
  Page page;
  if (started != 0) {
    fs::remove_all(dir);
    throw std::runtime_error(std::string("cannot start ") + SOA_CHROMIUM);
  }
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(o.timeout_s);
  while (::waitpid(pid, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(-pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  page.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
  page.dom = read_text(out);
  page.log = read_text(err);
  fs::remove_all(dir);
  // console lines: [pid:tid:date:INFO:CONSOLE:12] "message", source: file:///... (12)
  std::istringstream lines(page.log);
  for (std::string line; std::getline(lines, line);)
    if (line.find(":CONSOLE") != std::string::npos) page.console.push_back(line);
  return page;
}

}  // namespace detail

/// Loads \p page (an .html file) with the URL query \p query, lets it run for the virtual
/// time budget, and returns its DOM and console.
inline Page load(const fs::path& page, const std::string& query = "", const Options& o = {}) {
  return detail::run(file_url(page, query), {"--dump-dom"}, o);
}

/// Loads \p page like load() (DOM and console too) and writes a PNG screenshot of the window
/// to \p png.
inline Page screenshot(const fs::path& page, const std::string& query, const fs::path& png,
                       const Options& o = {}) {
  fs::remove(png);
  return detail::run(file_url(page, query),
                     {"--dump-dom", "--screenshot=" + fs::absolute(png).string()}, o);
}

/// The object of a data.js (`window.SOA_VIEW = {...};`) as JSON.
inline nlohmann::json read_view_data(const fs::path& data_js) {
  const std::string text = read_text(data_js);
  const std::size_t begin = text.find('=');
  const std::size_t end = text.rfind(';');
  if (begin == std::string::npos || end == std::string::npos || end < begin)
    throw std::runtime_error(data_js.string() + ": not window.SOA_VIEW = {...};");
  return nlohmann::json::parse(text.substr(begin + 1, end - begin - 1));
}

/// p + q v q^-1: the body-frame point \p v of a body at position \p p with orientation
/// \p q = [x, y, z, w], in world coordinates (v' = v + 2 w (u x v) + 2 u x (u x v), u = (x, y, z)).
inline std::array<double, 3> place(const std::array<double, 3>& p, const std::array<double, 4>& q,
                                   const std::array<double, 3>& v) {
  const auto cross = [](const std::array<double, 3>& a, const std::array<double, 3>& c) {
    return std::array<double, 3>{a[1] * c[2] - a[2] * c[1], a[2] * c[0] - a[0] * c[2],
                                 a[0] * c[1] - a[1] * c[0]};
  };
  const std::array<double, 3> u{q[0], q[1], q[2]};
  const auto uv = cross(u, v);
  const auto uuv = cross(u, uv);
  std::array<double, 3> r{};
  for (int i = 0; i < 3; ++i) r[i] = p[i] + v[i] + 2 * (q[3] * uv[i] + uuv[i]);
  return r;
}

/// The page drew a frame, counted no uncaught error, loaded nothing but files, and the
/// console is silent.
inline void expect_clean(const Page& page) {
  EXPECT_EQ(page.attr("data-ready"), "1");
  EXPECT_EQ(page.attr("data-errors"), "0");
  for (const std::string& line : page.console) ADD_FAILURE() << "console: " << line;
  EXPECT_EQ(page.log.find("net::ERR"), std::string::npos) << page.log;
  for (const std::string& url : words(page.attr("data-resources")))
    EXPECT_EQ(url.rfind("file://", 0), 0u) << "a resource not from the folder: " << url;
}

/// The canvas is not (nearly) all background.
inline void expect_drawn(const Page& page) {
  const std::string drawn = page.attr("data-drawn");
  ASSERT_FALSE(drawn.empty()) << "no data-drawn";
  EXPECT_GT(std::stod(drawn), 0.02) << "the canvas is (nearly) blank";
}

/// The world position of the tip (`tip.point` in body `tip.body`) at frame \p k of run \p r,
/// from the pose of the data: p + q point q^-1, q = [x, y, z, w].
inline std::array<double, 3> tip_from_pose(const nlohmann::json& view, int r, int k) {
  const int b = view.at("tip").at("body").get<int>();
  const auto point = view.at("tip").at("point").get<std::array<double, 3>>();
  const auto& pose = view.at("runs").at(r).at("pose").at(k);
  const std::array<double, 3> at{pose.at(7 * b), pose.at(7 * b + 1), pose.at(7 * b + 2)};
  const std::array<double, 4> q{pose.at(7 * b + 3), pose.at(7 * b + 4), pose.at(7 * b + 5),
                                pose.at(7 * b + 6)};
  return place(at, q, point);
}

}  // namespace soa::browser
