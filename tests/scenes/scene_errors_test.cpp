/// \file
/// Bad scene files: each file under tests/scenes/bad/ is refused with exactly the one-line
/// message of the table below, `<file>: <json path>: <problem>`; and every file there has
/// its line in the table. Then what cannot be a file there: a directory, a read error, the
/// size limit (an endless input included), running out of memory. Suite scene_errors.
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <new>
#include <set>
#include <thread>

#include "scene_support.hpp"

#if defined(__unix__)
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

// Out of memory on demand: while g_fail_in > 0, the g_fail_in-th allocation from now throws
// std::bad_alloc (only that one). The replaced operator new serves the whole test program.
std::atomic<long> g_fail_in{0};

void* operator new(std::size_t n) {
  if (g_fail_in.load(std::memory_order_relaxed) > 0 && g_fail_in.fetch_sub(1) == 1)
    throw std::bad_alloc();
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
// Not inlined: GCC would see free() meet a pointer from operator new (-Wmismatched-new-delete).
#if defined(__GNUC__)
#define SOA_NOINLINE __attribute__((noinline))
#else
#define SOA_NOINLINE
#endif
SOA_NOINLINE void operator delete(void* p) noexcept {
  std::free(p);
}
SOA_NOINLINE void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}

namespace soa::test {
namespace {

/// File (without .json) -> the message after "<file>: ".
const std::map<std::string, std::string>& expected_messages() {
  static const std::map<std::string, std::string> table = {
      // JSON itself
      {"invalid_json",
       "line 4, column 53: invalid JSON: syntax error while parsing object - unexpected string "
       "literal; expected '}'"},
      {"empty_file",
       "line 1, column 1: invalid JSON: syntax error while parsing value - unexpected end of "
       "input; expected '[', '{', or a literal"},
      {"top_level_array", "top level: expected an object, got an array"},
      {"duplicate_key", "bodies[0]: field \"mass\" given twice"},
      {"duplicate_bodies", "top level: field \"bodies\" given twice"},
      {"body_not_object", "bodies[1]: expected an object, got an array"},
      {"nested_too_deep",
       "bodies[1].com[0] ... (92 levels) ... [0][0][0][0]: nested more than 100 levels deep"},
      {"unknown_field", "bodies[1].spring: unknown field \"stifness\""},
      // values
      {"missing_mass", "bodies[1]: missing field \"mass\""},
      {"mass_nan_string", "bodies[1].mass: expected a number, got the string \"NaN\""},
      {"zero_mass", "bodies[1].mass: must be positive (got 0)"},
      {"infinite_number",
       "bodies[1].com[1]: not a finite number (1e999 is out of the range of a double)"},
      {"gravity_wrong_size", "gravity: expected 3 numbers, got 2"},
      {"negative_damping", "bodies[1].spring.damping: must not be negative (got -0.5)"},
      // inertia
      {"inertia_wrong_shape", "bodies[1].inertia: expected 3 rows, got 2"},
      {"inertia_not_symmetric",
       "bodies[1].inertia: not symmetric ([0][1] = 0.01 but [1][0] = 0.02)"},
      {"inertia_not_positive_definite",
       "bodies[1].inertia: not positive definite (principal moments -0.1, 0.1, 0.3)"},
      {"inertia_triangle",
       "bodies[1].inertia: principal moments 0.1, 0.1, 0.3 break the triangle inequality "
       "(0.1 + 0.1 < 0.3)"},
      {"inertia_entry_wrong_type",
       "bodies[1].inertia.Iyy: expected a number, got the string \"x\""},
      {"inertia_overflow",
       "bodies[1].inertia: overflows (entries up to 1.7e+308; the principal moments are out of "
       "the range of a double)"},
      {"mass_com_overflow",
       "bodies[1]: the inertia about the hinge frame overflows (mass 1e+300, com at 1e+10 from "
       "it)"},
      // hinges
      {"unknown_hinge_type",
       "bodies[1].hinge.type: unknown hinge type \"rotary\" (expected revolute, prismatic, "
       "helical, universal, spherical, free or locked)"},
      {"zero_axis", "bodies[1].hinge.axis: zero axis; an axis needs a direction"},
      {"axis_on_spherical", "bodies[1].hinge: field \"axis\" does not apply to a spherical hinge"},
      // massless bodies, limits and friction (what URDF scenes bring)
      {"massless_moving_tip",
       "bodies[1]: massless, and so is every body outboard of it: its revolute hinge moves "
       "nothing of mass (give a body a mass, or lock the hinge)"},
      {"limits_on_spherical",
       "bodies[1].limits: applies to revolute, prismatic and helical hinges only, not to a "
       "spherical hinge"},
      {"limits_reversed", "bodies[0].limits: lower 2 is above upper 1"},
      {"limits_unknown_field", "bodies[0].limits: unknown field \"max\""},
      {"friction_negative", "bodies[0].friction: must not be negative (got -1)"},
      {"universal_parallel_axes",
       "bodies[1].hinge.axis2: parallel to axis; a universal hinge needs two different axes"},
      {"non_unit_quaternion",
       "bodies[1].hinge.placement.rotation: not a unit quaternion (norm 0.99999; the norm "
       "must be 1 within 1e-6)"},
      {"huge_quaternion",
       "bodies[1].hinge.placement.rotation: not a unit quaternion (norm 1.73205e+200; the norm "
       "must be 1 within 1e-6)"},
      // a huge axis is a direction (the q after it is the problem)
      {"huge_axis", "bodies[1].q: expected 2 numbers for a universal hinge, got 1"},
      {"huge_axis2", "bodies[1].q: expected 2 numbers for a universal hinge, got 3"},
      {"locked_at_base",
       "bodies[0].hinge.type: a locked hinge next to the base fixes the body to the ground; "
       "remove the body or give it another hinge"},
      {"locked_merge_overflow",
       "bodies[1]: merged into bodies[0] through its locked hinge, its inertia about that "
       "body's frame overflows"},
      // the chain
      {"empty_bodies", "bodies: empty; a scene needs at least one body"},
      {"unknown_parent",
       "bodies[1].parent: no body named \"aa\" (a parent is \"base\" or a body's name)"},
      {"duplicate_name", "bodies[1].name: duplicate name \"a\" (bodies[0] has it too)"},
      {"branch",
       "bodies[2].parent: \"a\" already has a child (bodies[1]); serial chains only, no "
       "branches"},
      {"loop", "bodies[1].parent: loop (b -> c -> b, following parents) never reaches \"base\""},
      {"not_base_first",
       "bodies[0].parent: \"a\" is listed after this body (bodies[1]); list the bodies base "
       "first, each after its parent"},
      // state, forces, compute
      {"state_wrong_size", "bodies[1].q: expected 1 number for a revolute hinge, got 2"},
      {"state_quaternion_not_unit",
       "bodies[1].q: not a unit quaternion in entries 0-3 (norm 0.707107; the norm must be 1 "
       "within 1e-6)"},
      {"external_force_unknown_body", "external_forces[0].body: no body named \"c\""},
      {"unknown_compute",
       "compute[1]: unknown computation \"dynamics\" (expected kinematics, jacobian, "
       "inverse-dynamics or mass-matrix)"},
  };
  return table;
}

/// The message load_scene() throws for \p path ("" when it does not throw).
std::string message_of(const std::string& path, std::uint64_t max_bytes = kMaxSceneBytes) {
  return error_of([&] { load_scene(path, max_bytes); });
}

/// A path for a scratch file of this test.
std::string scratch(const std::string& name) {
#if defined(__unix__)
  const std::string id = std::to_string(::getpid());
#else
  const std::string id = "test";
#endif
  return (std::filesystem::temp_directory_path() / ("soa_scene_errors_" + id + "_" + name))
      .string();
}

TEST(scene_errors, EachBadSceneHasItsMessage) {
  for (const auto& [name, expected] : expected_messages()) {
    const std::string path = bad_scene(name + ".json");
    const std::string got = message_of(path);
    EXPECT_EQ(got, path + ": " + expected) << name;
    EXPECT_EQ(got.find('\n'), std::string::npos) << name << ": one line";
  }
}

// A bad scene without a line in the table would go unchecked.
TEST(scene_errors, EveryBadFileIsInTheTable) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(bad_scene(""))) {
    if (entry.path().extension() != ".json") continue;
    ++files;
    EXPECT_EQ(expected_messages().count(entry.path().stem().string()), 1u)
        << entry.path() << " has no expected message";
  }
  EXPECT_EQ(files, int(expected_messages().size()));
}

TEST(scene_errors, MissingFile) {
  const std::string path = bad_scene("no_such_scene.json");
  EXPECT_EQ(message_of(path), path + ": cannot open the file (No such file or directory)");
}

// parse_scene() names the file as given; the errors of values given in file order.
TEST(scene_errors, ValuesInFileOrder) {
  const Scene s = parse_scene(R"({"bodies": [
      {"name": "a", "parent": "base", "mass": 1, "com": [0, 0, 0],
       "inertia": {"Ixx": 1, "Iyy": 1, "Izz": 1}, "hinge": {"type": "revolute", "axis": [0, 0, 1]}},
      {"name": "b", "parent": "a", "mass": 1, "com": [0, 0, 0],
       "inertia": {"Ixx": 1, "Iyy": 1, "Izz": 1}, "hinge": {"type": "spherical"}}]})",
                              "two.json");
  auto message = [](auto f) -> std::string {
    try {
      f();
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(message([&] {
              theta_from_file_order(s, {0.1, 0, 0, 0});
            }),
            "expected 5 numbers, got 4");
  EXPECT_EQ(message([&] {
              theta_from_file_order(s, {0.1, 0, 0, 0, 2});
            }),
            "the quaternion of body \"b\" is not of unit norm (norm 2; the norm must be 1 "
            "within 1e-6)");
  EXPECT_EQ(message([&] {
              beta_from_file_order(s, {0.1, 0, 0, INFINITY});
            }),
            "entry 3 is not finite");
  // File order: a's angle first, then b's quaternion, though the model keeps b (k = 1) first.
  const VecX<double> theta = theta_from_file_order(s, {0.5, 0, 0, 0, 1});
  EXPECT_EQ(theta[s.model.body(2).q_offset], 0.5);
  EXPECT_EQ(theta[s.model.body(1).q_offset + 3], 1.0);
  EXPECT_EQ(message([&] {
              theta_from_file_order(s, {0.1, 1e200, 1e200, 1e200, 0});
            }),
            "the quaternion of body \"b\" is not of unit norm (norm 1.73205e+200; the norm must "
            "be 1 within 1e-6)");
  EXPECT_EQ(message([&] { parse_scene("{", "x.json"); }),
            "x.json: line 1, column 2: invalid JSON: syntax error while parsing object key - "
            "unexpected end of input; expected string literal");
}

// A directory; a file that cannot be read (/proc/self/mem opens, but reading at 0 fails).
TEST(scene_errors, DirectoryAndReadError) {
  const std::string dir = bad_scene("");
  EXPECT_EQ(message_of(dir), dir + ": is a directory, not a scene file");
#if defined(__linux__)
  EXPECT_EQ(message_of("/proc/self/mem"),
            "/proc/self/mem: cannot read the file (Input/output error)");
#endif
}

// The size limit: a file of exactly the limit is read, one byte more is refused before
// reading (its size says so); a sparse file over 1 GiB for the default limit.
TEST(scene_errors, SizeLimit) {
  const std::string arm7 = default_scene("arm7.json");
  const std::uint64_t size = std::filesystem::file_size(arm7);
  EXPECT_EQ(message_of(arm7, size), "");
  EXPECT_EQ(message_of(arm7, size - 1),
            arm7 + ": larger than the " + std::to_string(size - 1) + "-byte limit of a scene file");
  const std::string big = scratch("big.json");
  { std::ofstream(big) << "{}"; }
  std::filesystem::resize_file(big, kMaxSceneBytes + 1);
  EXPECT_EQ(message_of(big), big + ": larger than the 1 GiB limit of a scene file");
  std::filesystem::remove(big);
  EXPECT_EQ(kMaxSceneBytes, std::uint64_t(1) << 30);
}

#if defined(__unix__)
// Inputs that never end: /dev/zero and /dev/urandom stop at their first bytes (not JSON);
// an endless string through a FIFO (valid JSON so far) stops at the limit.
TEST(scene_errors, EndlessInputStops) {
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(message_of("/dev/zero"),
            "/dev/zero: line 1, column 1: invalid JSON: syntax error while parsing value - "
            "unexpected end of input; expected '[', '{', or a literal");
  EXPECT_EQ(message_of("/dev/urandom").rfind("/dev/urandom: ", 0), 0u);

  const std::string fifo = scratch("endless.json");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto old_handler = std::signal(SIGPIPE, SIG_IGN);  // the writer outlives the reader
  std::thread writer([&] {
    const int fd = ::open(fifo.c_str(), O_WRONLY);
    if (fd < 0) return;
    const std::string head = "{\"bodies\": [], \"name\": \"", x(4096, 'x');
    bool ok = ::write(fd, head.data(), head.size()) > 0;
    while (ok) ok = ::write(fd, x.data(), x.size()) > 0;
    ::close(fd);
  });
  const std::string got = message_of(fifo, 1 << 20);
  ::close(::open(fifo.c_str(), O_RDONLY | O_NONBLOCK));  // frees a writer still waiting
  writer.join();
  std::signal(SIGPIPE, old_handler);
  std::filesystem::remove(fifo);
  EXPECT_EQ(got, fifo + ": larger than the 1 MiB limit of a scene file");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 5.0);
}
#endif

// Out of memory anywhere while reading is one soa::Error naming the file and what was being
// read: the n-th allocation fails, for every n until reading needs fewer.
TEST(scene_errors, OutOfMemoryIsOneError) {
  const std::string text =
      read_text(std::string(SOA_SOURCE_DIR) + "/tests/scenes/every_hinge.json");
  const std::string name = "every_hinge.json";  // no allocation of the test's own counts
  std::set<std::string> doing;
  long n = 1;
  for (;; ++n) {
    std::string got;
    g_fail_in = n;
    try {
      parse_scene(text, name);
    } catch (const Error& e) {
      got = e.what();
    } catch (const std::bad_alloc&) {
      got = "std::bad_alloc";
    }
    const bool failed = g_fail_in.exchange(0) == 0;
    if (!failed) {
      EXPECT_EQ(got, "") << "allocation " << n;
      break;
    }
    const std::string prefix = "every_hinge.json: out of memory ";
    ASSERT_EQ(got.rfind(prefix, 0), 0u) << "allocation " << n << ": " << got;
    EXPECT_EQ(got.find('\n'), std::string::npos);
    doing.insert(got.substr(prefix.size()));
  }
  EXPECT_GT(n, 100);
  EXPECT_TRUE(doing.count("while reading bodies[2]")) << "the body read is named";
  EXPECT_TRUE(doing.count("while reading bodies[3].hinge.placement")) << "and where in it";
  EXPECT_TRUE(doing.count("while building the scene (6 bodies)"));
  std::printf("[ memory   ] allocations 1 ... %ld failed in turn: %zu places named\n", n - 1,
              doing.size());
}

}  // namespace
}  // namespace soa::test
