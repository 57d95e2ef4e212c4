// The viewer's folder (view::write()): data.js in the format of docs/viewer.md, the page and
// three.js beside it, and nothing of the user's lost on bad input.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>

#include "soa/sim/simulate.hpp"
#include "view_support.hpp"

namespace soa::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kEveryHinge = std::string(SOA_SOURCE_DIR) + "/tests/scenes/every_hinge.json";
const std::set<std::string> kViewerFiles = {"index.html",   "viewer.js",        "viewer.css",
                                            "three.min.js", "OrbitControls.js", "data.js"};

/// The names in folder \p dir.
std::set<std::string> entries(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

/// data.js as JSON: `window.SOA_VIEW = ` and `;` stripped.
json read_data(const fs::path& dir) {
  const std::string text = read_text((dir / "data.js").string());
  const std::string prefix = "window.SOA_VIEW = ";
  EXPECT_EQ(text.compare(0, prefix.size(), prefix), 0) << text.substr(0, 40);
  EXPECT_EQ(text.substr(text.size() - 3), "};\n");
  return json::parse(text.substr(prefix.size(), text.size() - prefix.size() - 2));
}

/// The keys of a JSON object.
std::set<std::string> keys(const json& j) {
  std::set<std::string> k;
  for (const auto& item : j.items()) k.insert(item.key());
  return k;
}

/// A view of every_hinge.json: two runs of random states (the second without V and f) and a
/// fixed vector.
view::View sample_view() {
  const Scene s = load_scene(kEveryHinge);
  view::View v = view::view_of(s);
  v.note = "a note with \"quotes\", a backslash \\ and \xe2\x80\xa8 (U+2028)";
  v.fixed.push_back({"angular momentum", Vec3<double>(0, 0, 0.5), Vec3<double>(0.1, 0.2, 0.3)});
  Random<double> rnd;
  for (const view::Quantities q : {view::Quantities{}, view::Quantities{false, false}}) {
    view::Recorder rec(s, 1.0, 11, q);
    for (int i = 0; i <= 10; ++i) rec.offer(0.1 * i, random_state(rnd, s.model));
    v.runs.push_back(rec.take(q.velocity ? "RK4, h = 0.1 s" : "poses only"));
  }
  return v;
}

/// A fresh folder for a test, removed after it.
class view_write : public testing::Test {
 protected:
  void SetUp() override {
    root_ =
        fs::temp_directory_path() / ("soa-view-test-" + std::to_string(::getpid()) + "-" +
                                     testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  fs::path root_;
};

TEST_F(view_write, DataJsIsTheDocumentedJson) {
  const view::View v = sample_view();
  const fs::path dir = root_ / "viewer";
  view::write(v, dir);
  const json d = read_data(dir);
  EXPECT_EQ(keys(d), (std::set<std::string>{"format", "title", "note", "gravity", "bodies", "tip",
                                            "fixed", "runs"}));
  EXPECT_EQ(d["format"], 1);
  EXPECT_EQ(d["title"], "every hinge type");
  EXPECT_EQ(d["note"], v.note);
  EXPECT_EQ(d["gravity"], json({0, -9.81, 0}));
  ASSERT_EQ(d["bodies"].size(), 6u);
  for (std::size_t i = 0; i < 6; ++i) {
    const json& b = d["bodies"][i];
    EXPECT_EQ(keys(b), (std::set<std::string>{"name", "hinge", "axis", "segment", "com", "mass",
                                              "radii", "axes_quaternion"}));
    EXPECT_EQ(b["name"], v.bodies[i].name);
    EXPECT_EQ(b["hinge"], v.bodies[i].hinge);
    for (const char* k : {"axis", "segment", "com", "radii"}) EXPECT_EQ(b[k].size(), 3u) << k;
    EXPECT_EQ(b["axes_quaternion"].size(), 4u);
    EXPECT_NEAR(b["mass"].get<double>(), v.bodies[i].mass, 1e-9 * v.bodies[i].mass);
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(b["segment"][j].get<double>(), v.bodies[i].segment[j], 1e-9);
  }
  EXPECT_EQ(d["tip"]["body"], 5);
  EXPECT_EQ(d["tip"]["point"].size(), 3u);
  ASSERT_EQ(d["fixed"].size(), 1u);
  EXPECT_EQ(
      d["fixed"][0],
      json({{"label", "angular momentum"}, {"origin", {0, 0, 0.5}}, {"vector", {0.1, 0.2, 0.3}}}));
  ASSERT_EQ(d["runs"].size(), 2u);
  const json& r0 = d["runs"][0];
  EXPECT_EQ(keys(r0), (std::set<std::string>{"label", "t", "energy", "pose", "V", "f", "tip"}));
  EXPECT_EQ(keys(d["runs"][1]), (std::set<std::string>{"label", "t", "energy", "pose", "tip"}));
  EXPECT_EQ(r0["label"], "RK4, h = 0.1 s");
  const std::size_t n = v.runs[0].frames.size();
  ASSERT_EQ(n, 11u);
  for (const char* k : {"t", "energy", "pose", "V", "f", "tip"}) EXPECT_EQ(r0[k].size(), n) << k;
  // Every number as the view has it, to 9 significant digits.
  double worst = 0;
  auto compare = [&](const json& a, const std::vector<double>& b) {
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < b.size(); ++i)
      worst =
          std::max(worst, std::abs(a[i].get<double>() - b[i]) / std::max(1e-300, std::abs(b[i])));
  };
  for (std::size_t i = 0; i < n; ++i) {
    const view::Frame& f = v.runs[0].frames[i];
    EXPECT_EQ(r0["pose"][i].size(), 7u * 6);
    EXPECT_EQ(r0["V"][i].size(), 6u * 6);
    EXPECT_EQ(r0["f"][i].size(), 6u * 6);
    EXPECT_EQ(r0["tip"][i].size(), 3u);
    compare(r0["pose"][i], f.pose);
    compare(r0["V"][i], f.V);
    compare(r0["f"][i], f.f);
    compare(r0["tip"][i], {f.tip[0], f.tip[1], f.tip[2]});
    compare(json({r0["t"][i], r0["energy"][i]}), {f.t, f.energy});
  }
  EXPECT_LE(worst, 5e-9);
  // U+2028 would end a line of script in an old browser: written as \u2028.
  EXPECT_NE(read_text((dir / "data.js").string()).find("\\u2028"), std::string::npos);
}

TEST_F(view_write, WritesTheSixFilesAndNoTemporaries) {
  const fs::path dir = root_ / "a" / "b" / "viewer";  // parents created too
  view::write(sample_view(), dir);
  EXPECT_EQ(entries(dir), kViewerFiles);
  // The page as in lib/view/, byte for byte; three.js as Debian's.
  for (const char* page : {"index.html", "viewer.js", "viewer.css"})
    EXPECT_EQ(read_text((dir / page).string()),
              read_text(std::string(SOA_SOURCE_DIR) + "/lib/view/" + page))
        << page;
  const fs::path three = view::three_dir();
  EXPECT_EQ(read_text((dir / "three.min.js").string()),
            read_text((three / "build/three.min.js").string()));
  EXPECT_EQ(read_text((dir / "OrbitControls.js").string()),
            read_text((three / "examples/js/controls/OrbitControls.js").string()));
}

TEST_F(view_write, ReplacesAViewerWrittenBefore) {
  const fs::path dir = root_ / "viewer";
  view::View v = sample_view();
  view::write(v, dir);
  // A left-over temporary of a killed write is the viewer's too.
  std::ofstream(dir / ".data.js.soa-view-tmp") << "half a file";
  v.title = "second";
  view::write(v, dir);
  EXPECT_EQ(read_data(dir)["title"], "second");
  EXPECT_EQ(entries(dir), kViewerFiles);
}

TEST_F(view_write, RefusesAFolderWithAnythingElseInIt) {
  const fs::path dir = root_ / "mine";
  fs::create_directories(dir);
  std::ofstream(dir / "index.html") << "my page";
  std::ofstream(dir / "notes.txt") << "my notes";
  EXPECT_EQ(error_of([&] { view::write(sample_view(), dir); }),
            dir.string() +
                ": holds \"notes.txt\", which is not a file of the viewer; give a new "
                "folder, an empty one, or one the viewer was written to before");
  EXPECT_EQ(entries(dir), (std::set<std::string>{"index.html", "notes.txt"}));
  EXPECT_EQ(read_text((dir / "index.html").string()), "my page");
  // A viewer's name that is not a plain file (a folder called data.js) is refused too.
  const fs::path odd = root_ / "odd";
  fs::create_directories(odd / "data.js");
  EXPECT_EQ(error_of([&] { view::write(sample_view(), odd); }),
            odd.string() + ": \"data.js\" is not a plain file; give another folder");
  EXPECT_EQ(entries(odd), (std::set<std::string>{"data.js"}));
}

TEST_F(view_write, RefusesAPathThatIsAFile) {
  const fs::path file = root_ / "scene.json";
  std::ofstream(file) << "{}";
  EXPECT_EQ(error_of([&] { view::write(sample_view(), file); }),
            file.string() + ": exists and is not a folder (the viewer is a folder of files)");
  EXPECT_EQ(read_text(file.string()), "{}");
  EXPECT_EQ(error_of([&] {
              view::write(sample_view(), file / "viewer");
            }).rfind((file / "viewer").string() + ": cannot create the folder (", 0),
            0u);
  EXPECT_EQ(entries(root_), (std::set<std::string>{"scene.json"}));
}

// A number that is not finite names the run, the frame and the quantity; nothing is written.
TEST_F(view_write, RefusesANumberThatIsNotFinite) {
  const fs::path dir = root_ / "viewer";
  struct Case {
    std::function<void(view::View&)> spoil;
    std::string message;
  };
  const std::vector<Case> cases = {
      {[](view::View& v) { v.runs[0].frames[3].V[6 * 2 + 4] = NAN; },
       "view: run 0 \"RK4, h = 0.1 s\", frame 3 (t = 0.3): V of body \"wrist\" is not finite"},
      {[](view::View& v) { v.runs[1].frames[10].pose[7 * 5] = INFINITY; },
       "view: run 1 \"poses only\", frame 10 (t = 1): pose of body \"drone\" is not finite"},
      {[](view::View& v) { v.runs[0].frames[0].f[0] = -INFINITY; },
       "view: run 0 \"RK4, h = 0.1 s\", frame 0 (t = 0): f of body \"carriage\" is not finite"},
      {[](view::View& v) { v.runs[0].frames[1].energy = NAN; },
       "view: run 0 \"RK4, h = 0.1 s\", frame 1 (t = 0.1): the energy is not finite"},
      {[](view::View& v) { v.runs[0].frames[2].tip[1] = NAN; },
       "view: run 0 \"RK4, h = 0.1 s\", frame 2 (t = 0.2): the tip is not finite"},
      {[](view::View& v) { v.bodies[3].radii[0] = NAN; },
       "view: body 3 \"ball\": radii is not finite"},
      {[](view::View& v) { v.gravity[2] = NAN; }, "view: gravity is not finite"},
      {[](view::View& v) { v.fixed[0].vector[2] = INFINITY; },
       "view: fixed vector 0 \"angular momentum\": vector is not finite"},
      {[](view::View& v) { v.runs[0].frames[4].pose.pop_back(); },
       "view: run 0 \"RK4, h = 0.1 s\", frame 4 (t = 0.4): pose has 41 numbers, expected 42 (7 "
       "for each of 6 bodies)"},
      {[](view::View& v) { v.runs[1].frames[2].V.assign(36, 0.0); },
       "view: run 1 \"poses only\", frame 2 (t = 0.2): has V where the run's first frame has "
       "none"},
      {[](view::View& v) { v.tip_body = 6; }, "view: tip body 6 is not a body (there are 6)"},
  };
  for (const Case& c : cases) {
    view::View v = sample_view();
    c.spoil(v);
    EXPECT_EQ(error_of([&] { view::write(v, dir); }), c.message);
    EXPECT_FALSE(fs::exists(dir)) << c.message;
  }
}

/// Sets the environment variable SOA_THREE_DIR for a scope.
class ThreeDir {
 public:
  explicit ThreeDir(const std::string& dir) {
    if (const char* old = std::getenv("SOA_THREE_DIR")) old_ = old, had_ = true;
    ::setenv("SOA_THREE_DIR", dir.c_str(), 1);
  }
  ~ThreeDir() {
    if (had_)
      ::setenv("SOA_THREE_DIR", old_.c_str(), 1);
    else
      ::unsetenv("SOA_THREE_DIR");
  }

 private:
  std::string old_;
  bool had_ = false;
};

TEST_F(view_write, ThreeJsFromTheEnvironmentOrNothingWritten) {
  const fs::path dir = root_ / "viewer";
  {
    const ThreeDir env((root_ / "nowhere").string());
    EXPECT_EQ(error_of([&] { view::write(sample_view(), dir); }),
              "three.js not found: " + (root_ / "nowhere/build/three.min.js").string() +
                  " (Debian package libjs-three)");
    EXPECT_FALSE(fs::exists(dir));
  }
  // A copy elsewhere: taken from there; without OrbitControls.js, refused.
  const fs::path copy = root_ / "three";
  fs::create_directories(copy / "build");
  std::ofstream(copy / "build/three.min.js") << "// three";
  const ThreeDir env(copy.string());
  EXPECT_EQ(error_of([&] { view::write(sample_view(), dir); }),
            "three.js not found: " + (copy / "examples/js/controls/OrbitControls.js").string() +
                " (Debian package libjs-three)");
  EXPECT_FALSE(fs::exists(dir));
  fs::create_directories(copy / "examples/js/controls");
  std::ofstream(copy / "examples/js/controls/OrbitControls.js") << "// orbit";
  view::write(sample_view(), dir);
  EXPECT_EQ(read_text((dir / "three.min.js").string()), "// three");
  EXPECT_EQ(read_text((dir / "OrbitControls.js").string()), "// orbit");
}

// The built-in folder is the one CMake was given (SOA_THREE_DIR), unless the environment says.
TEST_F(view_write, ThreeDirIsTheConfiguredOneByDefault) {
  const char* env = std::getenv("SOA_THREE_DIR");
  if (env && *env) GTEST_SKIP() << "SOA_THREE_DIR is set in the environment";
  EXPECT_EQ(view::three_dir(), fs::path(SOA_THREE_DIR_BUILT));
  const ThreeDir empty("");
  EXPECT_EQ(view::three_dir(), fs::path(SOA_THREE_DIR_BUILT));
}

/// Limits the size of files this process writes (RLIMIT_FSIZE) for a scope: a write past it
/// fails (EFBIG) as on a full disk.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &old_);
    old_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit r = old_;
    r.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &r);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &old_);
    std::signal(SIGXFSZ, old_handler_);
  }

 private:
  rlimit old_;
  void (*old_handler_)(int);
};

// A write that fails (the disk full) names the file, leaves no temporary, and leaves the
// viewer written before as it was.
TEST_F(view_write, AFailedWriteLeavesThePreviousViewer) {
  const fs::path dir = root_ / "viewer";
  view::View v = sample_view();
  view::write(v, dir);
  const std::string before = read_text((dir / "data.js").string());
  v.title = "second";
  for (rlim_t limit : {rlim_t(100), rlim_t(64 * 1024)}) {  // in the page, in three.min.js
    std::string message;
    {
      const FileSizeLimit small(limit);
      message = error_of([&] { view::write(v, dir); });
    }
    EXPECT_NE(message.find(dir.string() + "/"), std::string::npos) << message;
    EXPECT_NE(message.find(": cannot write the file (File too large)"), std::string::npos)
        << message;
    EXPECT_EQ(entries(dir), kViewerFiles);
    EXPECT_EQ(read_text((dir / "data.js").string()), before);
  }
  // A new folder is removed again, parents included.
  {
    const FileSizeLimit small(100);
    EXPECT_NE(error_of([&] { view::write(v, root_ / "new" / "viewer"); }), "");
  }
  EXPECT_FALSE(fs::exists(root_ / "new"));
}

// The size of a real case: 10 000 RK4 steps of the 50-link chain at the default 400 frames,
// with V and f: a few megabytes.
TEST_F(view_write, Chain50RunIsAFewMegabytes) {
  const Scene s = load_scene(default_scene("chain50.json"));
  ChainSystem sys(s.model, s.f_ext);
  State x = s.state;
  SimulationOptions opt;
  opt.dt = 1e-3;
  opt.t_end = 10;
  view::Recorder rec(s, opt.t_end);
  const SimulationSummary sum =
      simulate(sys, x, opt, [&](double t, const State& xt) { rec.offer(t, xt); });
  rec.record(sum.t, x);
  view::View v = view::view_of(s);
  v.note = rec.note();
  v.runs.push_back(rec.take("RK4, h = 1 ms"));
  EXPECT_EQ(sum.steps, 10000);
  EXPECT_EQ(v.runs[0].frames.size(), view::kDefaultFrames);
  EXPECT_EQ(v.note, "10001 states shown as 400 frames (one every 25.1 ms)");
  const fs::path dir = root_ / "chain50";
  view::write(v, dir);
  const auto bytes = fs::file_size(dir / "data.js");
  std::printf("[ size     ] chain50, 10000 steps, 400 frames with V and f: data.js %.2f MB\n",
              double(bytes) / 1e6);
  RecordProperty("data_js_bytes", std::to_string(bytes));
  EXPECT_LT(bytes, 6e6);
  EXPECT_EQ(read_data(dir)["runs"][0]["pose"].size(), 400u);
}

}  // namespace
}  // namespace soa::test
