// A viewer written by the `soa` command, opened in headless Chromium: what the page shows at a
// frame is what `soa kinematics` computes at that frame's state.
//   soa simulate SCENE --integrator rk4 ... --out traj.csv --view DIR
// then, at paused frames of DIR/index.html: the page's data-time is a row of traj.csv, and the
// tip the page draws (data-tip, from the pose it renders) is the tip of `soa kinematics SCENE
// --q <that row>`: the last body's position p and quaternion q, and its far end p + q (2c) q^-1
// (c its centre of mass in the scene file; docs/viewer.md). Also: the page is clean (no
// console message, only local files, something drawn), and two frames look different.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "chromium.hpp"

namespace {

namespace fs = std::filesystem;
namespace browser = soa::browser;

/// Runs a shell command; its stdout into \p out. The exit status (0 = success).
int shell(const std::string& command, std::string* out = nullptr) {
  const fs::path tmp = fs::path(SOA_VIEW_TEST_DIR) / "soa_page_stdout.txt";
  const int rc = std::system((command + " >'" + tmp.string() + "' 2>&1").c_str());
  if (out) *out = browser::read_text(tmp);
  return rc;
}

/// The rows of a CSV of numbers (header skipped), as soa simulate --out writes them.
std::vector<std::vector<double>> csv_rows(const fs::path& file, std::vector<std::string>& header) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  header.clear();
  std::stringstream h(line);
  for (std::string cell; std::getline(h, cell, ',');) header.push_back(cell);
  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

std::string joined(const std::vector<double>& v, std::size_t from, std::size_t to) {
  std::ostringstream s;
  s.precision(17);
  for (std::size_t i = from; i < to; ++i) s << (i > from ? "," : "") << v[i];
  return s.str();
}

class SoaPage : public ::testing::TestWithParam<const char*> {};

TEST_P(SoaPage, ShowsWhatSoaKinematicsComputes) {
  if (const std::string why = browser::missing(); !why.empty()) FAIL() << why;
  const std::string name = GetParam();
  const fs::path scene = fs::path(SOA_SCENE_DIR) / (name + ".json");
  const fs::path dir = fs::path(SOA_VIEW_TEST_DIR) / ("soa_" + name);
  const fs::path csv = dir.string() + ".csv";
  fs::remove_all(dir);
  std::string out;
  ASSERT_EQ(shell(std::string("'") + SOA_CLI + "' simulate '" + scene.string() +
                      "' --integrator rk4 --dt 1e-3 --t-end 1 --out '" + csv.string() +
                      "' --view '" + dir.string() + "' --frames 41",
                  &out),
            0)
      << out;
  std::vector<std::string> header;
  const std::vector<std::vector<double>> rows = csv_rows(csv, header);
  std::size_t nq = 0, nv = 0;
  for (const std::string& h : header) nq += h.rfind("q:", 0) == 0, nv += h.rfind("qd:", 0) == 0;
  ASSERT_GT(nq, 0u);
  std::ifstream scene_in(scene);
  const nlohmann::json scene_json = nlohmann::json::parse(scene_in);
  const auto c = scene_json.at("bodies").back().value("com", std::array<double, 3>{0, 0, 0});
  const std::array<double, 3> far_end{2 * c[0], 2 * c[1], 2 * c[2]};

  std::vector<std::string> shots;
  double worst = 0;
  for (const int k : {0, 23}) {
    const fs::path png = dir.string() + "_" + std::to_string(k) + ".png";
    const browser::Page page =
        browser::screenshot(dir / "index.html", "frame=" + std::to_string(k) + "&paused=1", png);
    ASSERT_TRUE(page.ok()) << page.why();
    browser::expect_clean(page);
    browser::expect_drawn(page);
    shots.push_back(browser::read_text(png));

    // The frame's state: the CSV row at the page's time.
    const double t = std::stod(page.attr("data-time"));
    const std::vector<double>* row = nullptr;
    for (const auto& r : rows)
      if (std::abs(r[0] - t) <= 1e-9 * std::max(1.0, std::abs(t))) row = &r;
    ASSERT_NE(row, nullptr) << "frame " << k << ": t = " << t << " is no row of " << csv;
    ASSERT_EQ(shell(std::string("'") + SOA_CLI + "' kinematics '" + scene.string() + "' --q " +
                        joined(*row, 1, 1 + nq) + " --qd " + joined(*row, 1 + nq, 1 + nq + nv),
                    &out),
              0)
        << out;
    const nlohmann::json kin = nlohmann::json::parse(out);
    const std::string tip_body = scene_json.at("bodies").back().at("name");
    const auto& body = kin.at("bodies").at(tip_body);
    const std::array<double, 3> expected =
        browser::place(body.at("position").get<std::array<double, 3>>(),
                       body.at("quaternion").get<std::array<double, 4>>(), far_end);
    const std::vector<double> shown = browser::numbers(page.attr("data-tip"));
    ASSERT_EQ(shown.size(), 3u) << page.attr("data-tip");
    double scale = 1;
    for (int i = 0; i < 3; ++i) scale = std::max(scale, std::abs(expected[i]));
    for (int i = 0; i < 3; ++i) worst = std::max(worst, std::abs(shown[i] - expected[i]) / scale);
  }
  // data.js keeps 9 significant digits of each pose.
  EXPECT_LT(worst, 1e-7) << "the tip the page draws vs soa kinematics";
  std::printf("  %s: worst relative difference of the tip, page vs soa kinematics: %.2e\n",
              name.c_str(), worst);
  EXPECT_NE(shots[0], shots[1]) << "frames 0 and 23 look the same";
}

// The double pendulum (its tip the lower body's far end) and the arm (its tip the welded
// gripper's far end: a locked last body).
INSTANTIATE_TEST_SUITE_P(Scenes, SoaPage, ::testing::Values("double_pendulum", "arm7"));

}  // namespace
