// The 3D viewer's page (lib/view, docs/viewer.md) in headless Chromium, on the sample data
// (tests/view/sample/data.js: a double pendulum, RK4 and Euler runs side by side):
// - it loads nothing but files of its folder, with no console message and no uncaught error,
//   and draws something (the canvas is not the background);
// - the first and the last frame, paused, give different screenshots, and at each the tip
//   point the page computes from the pose it draws is the tip of the data's pose (so the page
//   applies the quaternions [x, y, z, w] as the library does);
// - `t=` shows the last frame at or before that time;
// - a data.js of another format, or none, gives one clear message and no uncaught error.
// Each test copies the page, three.js and a data.js into a folder of the build tree.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "chromium.hpp"

namespace {

namespace fs = std::filesystem;
namespace browser = soa::browser;

/// A viewer's folder for this test: the page (lib/view), three.js and OrbitControls.js, and
/// \p data_js as data.js (none when empty). Replaces what the folder held.
fs::path viewer_folder(const std::string& data_js) {
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir =
      fs::path(SOA_VIEW_TEST_DIR) / (std::string(test->test_suite_name()) + "." + test->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const auto& e : fs::directory_iterator(SOA_VIEW_PAGE_DIR))
    fs::copy_file(e.path(), dir / e.path().filename());
  fs::copy_file(SOA_THREE_JS, dir / "three.min.js");  // copy_file follows Debian's symlink
  fs::copy_file(SOA_ORBIT_CONTROLS_JS, dir / "OrbitControls.js");
  if (!data_js.empty()) browser::write_text(dir / "data.js", data_js);
  return dir;
}

fs::path sample_folder() {
  return viewer_folder(browser::read_text(SOA_VIEW_SAMPLE));
}

/// "" when Chromium and three.js are there, else the one line that says what is missing.
std::string missing() {
  if (std::string(SOA_THREE_JS).empty() || std::string(SOA_ORBIT_CONTROLS_JS).empty())
    return "three.js is missing: install it (apt-get install libjs-three) and configure again";
  return browser::missing();
}

/// Fails the test with one line when Chromium or three.js is not there.
#define REQUIRE_CHROMIUM() \
  if (const std::string why = missing(); !why.empty()) FAIL() << why

using browser::expect_clean;
using browser::expect_drawn;

TEST(browser_view, LoadsOnlyItsOwnFilesAndDraws) {
  REQUIRE_CHROMIUM();
  const fs::path dir = sample_folder();
  const auto page = browser::load(dir / "index.html");  // playing from the start
  ASSERT_TRUE(page.ok()) << page.why();
  expect_clean(page);
  const auto urls = browser::words(page.attr("data-resources"));
  for (const char* file : {"three.min.js", "OrbitControls.js", "data.js", "viewer.js"}) {
    const std::string url = browser::file_url(dir / file);
    EXPECT_NE(std::find(urls.begin(), urls.end(), url), urls.end()) << url << " not loaded";
  }
  expect_drawn(page);
}

/// The page shows frame \p k of run 0, with the tip of the data's pose there.
void expect_frame(const browser::Page& page, const nlohmann::json& view, int k) {
  expect_clean(page);
  expect_drawn(page);
  EXPECT_EQ(page.attr("data-frame"), std::to_string(k));
  const double t = view.at("runs").at(0).at("t").at(k).get<double>();
  EXPECT_EQ(std::stod(page.attr("data-time")), t);
  const auto tip = browser::numbers(page.attr("data-tip"));
  const auto expected = browser::tip_from_pose(view, 0, k);
  ASSERT_EQ(tip.size(), 3u) << page.attr("data-tip");
  const double norm = std::hypot(expected[0], expected[1], expected[2]);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(tip[i], expected[i], 1e-9 * norm) << "frame " << k << ", coordinate " << i;
}

TEST(browser_view, FirstAndLastFramesWithTheirTips) {
  REQUIRE_CHROMIUM();
  const fs::path dir = sample_folder();
  const auto view = browser::read_view_data(dir / "data.js");
  const int last = static_cast<int>(view.at("runs").at(0).at("t").size()) - 1;
  std::string png[2];
  for (const int k : {0, last}) {
    const fs::path file = dir / ("frame-" + std::to_string(k) + ".png");
    const auto page =
        browser::screenshot(dir / "index.html", "frame=" + std::to_string(k) + "&paused=1", file);
    ASSERT_TRUE(page.ok()) << page.why();
    expect_frame(page, view, k);
    png[k == 0 ? 0 : 1] = browser::read_text(file);
    // an empty 900 x 600 window compresses to far below this bound, the page with its chain to
    // far above it
    EXPECT_GT(png[k == 0 ? 0 : 1].size(), 20000u) << file;
  }
  EXPECT_NE(png[0], png[1]) << "frames 0 and " << last << " look the same";
}

TEST(browser_view, TimeShowsTheLastFrameAtOrBeforeIt) {
  REQUIRE_CHROMIUM();
  const fs::path dir = sample_folder();
  const auto view = browser::read_view_data(dir / "data.js");
  const auto& t = view.at("runs").at(0).at("t");
  const double half = 0.5 * (t.at(20).get<double>() + t.at(21).get<double>());
  // with every toggle on: the arrows of V and f and the ellipsoids draw without error
  const auto page =
      browser::load(dir / "index.html", "t=" + std::to_string(half) +
                                            "&paused=1&show=frames,axes,ellipsoids,V,f,tip,fixed");
  ASSERT_TRUE(page.ok()) << page.why();
  expect_frame(page, view, 20);
}

/// The page's message box (#soa-message) with its text, or "" when it is not shown.
std::string message_of(const browser::Page& page) {
  const std::size_t at = page.dom.find("<div id=\"soa-message\">");
  if (at == std::string::npos) return "";
  return page.dom.substr(at, page.dom.find("</div>", at) - at);
}

/// One message naming the problem, counted as the one error; no frame drawn, nothing
/// uncaught (the only console line is the message).
void expect_message(const browser::Page& page, const std::string& says) {
  EXPECT_NE(message_of(page).find(says), std::string::npos) << page.dom;
  EXPECT_EQ(page.attr("data-errors"), "1");
  EXPECT_FALSE(page.attribute("data-ready").has_value());
  ASSERT_EQ(page.console.size(), 1u) << page.log;
  EXPECT_NE(page.console[0].find("SOA viewer: "), std::string::npos) << page.console[0];
}

TEST(browser_view, DataOfAnotherFormatIsOneMessage) {
  REQUIRE_CHROMIUM();
  const fs::path dir = viewer_folder("window.SOA_VIEW = {\"format\": 2, \"runs\": []};\n");
  const auto page = browser::load(dir / "index.html", "", {1000});
  ASSERT_TRUE(page.ok()) << page.why();
  expect_message(page, "data.js is in format 2, and this page reads format 1");
}

TEST(browser_view, MissingDataIsOneMessage) {
  REQUIRE_CHROMIUM();
  const fs::path dir = viewer_folder("");
  const auto page = browser::load(dir / "index.html", "", {1000});
  ASSERT_TRUE(page.ok()) << page.why();
  expect_message(page, "data.js is missing");
}

}  // namespace
