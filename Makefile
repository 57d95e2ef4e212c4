# SOA Course Companion — the commands students and instructors type.
#   make run        build and run the lesson tour, lesson by lesson (outputs under build/course/)
#   make test       library tests, lesson checks, exercise tests against the solutions
#   make exercises  the exercise tests against exercises/ (a pass/fail table; never fails);
#                   LESSON=4 or EX=4.2 for one lesson or one exercise, HINT=4.7 for the
#                   exercise's next hint
#   make docs       Doxygen course notes (offline math, gnuplot figures) in build/docs/html
#   make bench      Google Benchmark results and the soa command's scale (cli_scale) in build/bench/,
#                   the speed targets in both configurations judged in build/bench/speed.md
#   make compare    the library beside Orocos KDL and MuJoCo (agreement, time, error) in
#                   build/bench/compare.md (not part of make test; installs those two)
#   make release    OUT=DIR: the student's repository, without the answers (instructors)
#   make grade      SUBMISSIONS=DIR OUT=DIR [WEIGHTS=FILE] [LESSONS=1,2] [SEEDS=FILE]: a
#                   class's submissions judged by the checker, in a sandbox, SEEDS adding
#                   cases the students never drew: gradebook, feedback, Gradescope results,
#                   class report (instructors)
# Options: SANITIZE=1 (AddressSanitizer + UBSan, in build/sanitize), SANITIZE=clang (the same
# with clang, in build/sanitize-clang: its AddressSanitizer also finds uses after scope that
# GCC's misses), BUILD_TYPE=Debug (in build/debug), TESTS=regex (make test runs only the ctest
# tests it matches).

BUILD_TYPE ?= Release
ifeq ($(SANITIZE),1)
  BUILD_DIR ?= build/sanitize
  SAN_FLAG := -DSOA_SANITIZE=ON
else ifeq ($(SANITIZE),clang)
  BUILD_DIR ?= build/sanitize-clang
  SAN_FLAG := -DSOA_SANITIZE=ON -DCMAKE_CXX_COMPILER=clang++
else ifeq ($(BUILD_TYPE),Debug)
  BUILD_DIR ?= build/debug
  SAN_FLAG := -DSOA_SANITIZE=OFF
else
  BUILD_DIR ?= build/release
  SAN_FLAG := -DSOA_SANITIZE=OFF
endif
JOBS ?= $(shell nproc 2>/dev/null || echo 2)

# Debian packages the project needs (see README.md). Checked with dpkg-query; only the
# missing ones are installed.
PACKAGES := cmake g++ ninja-build libeigen3-dev libgtest-dev libgmock-dev \
  libbenchmark-dev nlohmann-json3-dev doxygen graphviz gnuplot-nox libjs-mathjax \
  libjs-three chromium pkgconf liburdfdom-dev libtinyxml-dev libsundials-dev libsleef-dev \
  ccache bubblewrap
ifeq ($(SANITIZE),clang)
  PACKAGES += clang
endif
# The peers of `make compare` (tests/bench/compare/), only for that target.
COMPARE_PACKAGES := liborocos-kdl-dev libmujoco-dev

.PHONY: all run test exercises exercise-tree stubs stub-sums docs bench compare deps compare-deps configure \
  grade build clean format release

all: build

# One recipe for both lists: the packages in DEPS_PACKAGES that are missing, installed as root
# or through sudo, else the apt-get line to type and a stop.
deps: DEPS_PACKAGES = $(PACKAGES)
compare-deps: DEPS_PACKAGES = $(PACKAGES) $(COMPARE_PACKAGES)
deps compare-deps:
	@missing=""; for p in $(DEPS_PACKAGES); do \
	  dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q '^install ok installed$$' \
	    || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  line="apt-get install -y --no-install-recommends -o DPkg::Lock::Timeout=300$$missing"; \
	  if [ "$$(id -u)" = 0 ]; then sudo=""; \
	  elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then sudo="sudo"; \
	  else echo "Missing Debian packages:$$missing"; \
	       echo "Install them with:  sudo apt-get update && sudo $$line"; exit 1; fi; \
	  echo "Installing missing Debian packages:$$missing"; \
	  $$sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $$sudo $$line; \
	fi

configure: deps
	@mkdir -p build
	@cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) $(SAN_FLAG) \
	  -DSOA_OUTPUT_DIR=$(CURDIR)/build >$(BUILD_DIR).cmake.log \
	  || { cat $(BUILD_DIR).cmake.log; exit 1; }

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

# Lesson by lesson (lessons/tour.sh): the library and lesson 1, then the rest in one build
# while each lesson runs as soon as its program is linked; the labs last.
run: configure
	@sh lessons/tour.sh $(BUILD_DIR) $(JOBS)

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure --no-tests=error -j $(JOBS) $(if $(TESTS),-R '$(TESTS)')

# One table per lesson: each exercise pass / FAIL (with what went wrong) / not done. Never
# stops the build. Its own build, build/exercises: the library (without the simulation
# group, which no exercise uses) and the exercise tests, at -O1 with line tables (-g1) and
# Eigen's assertions on; the student's code also with AddressSanitizer + UBSan where the
# compiler has them, so that a mistake stops at the student's own line, and with the
# student's warnings (kept by tests/exercises/keep_diagnostics.sh, shown in the rows). Lesson
# by lesson: the first lesson's table comes after the library and that lesson's checker are
# built. make test runs this same recipe on the solutions (exercises.student-config).
EX_DIR ?= build/exercises
# The folder holding the student's NN-topic/*.cpp: exercises/ itself. The test of this
# configuration (tests/exercises/student_config.sh) points it at the solutions.
EXERCISES ?= exercises
EX_SRC_DIR := $(abspath $(EXERCISES))
EX_LESSON := $(if $(EX),$(word 1,$(subst ., ,$(EX))),$(LESSON))
EX_NN := $(if $(EX_LESSON),$(shell printf '%02d' $(EX_LESSON)),)
EX_FILTER := $(if $(EX),--gtest_filter=Exercise$(subst .,_,$(EX))_*,)
EX_SRCS := $(sort $(wildcard tests/exercises/$(if $(EX_NN),$(EX_NN),[0-9][0-9])-*.cpp))
EX_NNS := $(foreach f,$(EX_SRCS),$(shell basename $(f) | cut -c1-2))

# The exercise tree configured (the first step of make exercises; make test's exercise tree,
# tests/exercises/student_config.cmake, builds it whole before its runs). EX_CMAKE_ARGS: more
# options for its CMake.
exercise-tree: deps
	@mkdir -p $(EX_DIR)
	@if [ ! -f $(EX_DIR)/build.ninja ] || [ Makefile -nt $(EX_DIR)/CMakeCache.txt ] \
	     || ! grep -qx 'SOA_EXERCISES_DIR:PATH=$(EX_SRC_DIR)' $(EX_DIR)/CMakeCache.txt; then \
	  san=OFF; t=$$(mktemp -d); \
	  echo 'int main() { return 0; }' >$$t/a.cpp; \
	  c++ -fsanitize=address,undefined $$t/a.cpp -o $$t/a 2>/dev/null && $$t/a && san=ON; \
	  rm -rf $$t; \
	  cmake -S . -B $(EX_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DSOA_SANITIZE_STUDENT=$$san \
	    "-DSOA_GROUPS=CORE;DENSE;ID;FD;MINV" \
	    -DSOA_CHECK_STUBS=OFF -DSOA_WATCH_CALLS=ON \
	    -DSOA_EXERCISES_DIR=$(EX_SRC_DIR) $(EX_CMAKE_ARGS) \
	    -DSOA_OUTPUT_DIR=$(CURDIR)/build >$(EX_DIR).cmake.log \
	    || { cat $(EX_DIR).cmake.log; exit 1; }; \
	fi

exercises: $(if $(HINT),deps,exercise-tree)
ifneq ($(HINT),)
	@sh tests/exercises/hint.sh $(HINT) $(EX_DIR)/hints
else
	@test -n "$(EX_NNS)" || { echo "no lesson $(EX_LESSON): lessons are 1 to 8"; exit 0; }
	@[ -f $(EX_DIR)/lib/libsoa.a ] \
	  || echo "Building the library and the exercise tests in $(EX_DIR), lesson by lesson (the first time takes a few minutes)"
	@for nn in $(EX_NNS); do \
	  dir=$$(ls -d exercises/$$nn-*); \
	  cmake --build $(EX_DIR) -j $(JOBS) --target soa_exercise_main ex$$nn-tests \
	    >$(EX_DIR)/common.log 2>&1 || { tail -30 $(EX_DIR)/common.log; exit 1; }; \
	  echo; echo "== Lesson $$nn exercises ($$dir) =="; \
	  rm -f $(EX_DIR)/tests/ex$$nn-exercises; \
	  if cmake --build $(EX_DIR) -j $(JOBS) --target ex$$nn-exercises \
	       >$(EX_DIR)/ex$$nn-exercises.log 2>&1; then \
	    mkdir -p $(EX_DIR)/cases; SOA_EXERCISE_CASES=$(EX_DIR)/cases \
	    ASAN_OPTIONS=detect_leaks=0 $(EX_DIR)/tests/ex$$nn-exercises --report \
	      --header $$dir/exercises.hpp $(EX_FILTER) \
	      $$(find $(EX_DIR)/exercises/CMakeFiles/exercises_$$nn.dir -name '*.diag' \
	           -exec printf -- '--warnings %s ' {} \;) \
	      || echo "  the test program stopped: the message above names the line (see also $(EX_DIR)/ex$$nn-exercises.log)"; \
	  else echo "  does not compile yet (all of $(EX_DIR)/ex$$nn-exercises.log):"; \
	       grep -m8 -E 'error|note: +candidate' $(EX_DIR)/ex$$nn-exercises.log | sed 's/^/    /'; fi; \
	done; true
endif

# After adding or changing a statement (exercises/NN-topic/exercises.hpp) or a stub: the stubs
# the statements lack, the lessons' README tables and the checksums of the pristine stubs
# (tests/exercises/stubs.sh; docs/adding_an_exercise.md). stub-sums is its old name.
stubs stub-sums:
	sh tests/exercises/stubs.sh write $(CURDIR)

docs: build
	cmake --build $(BUILD_DIR) --target docs

# Then the speed targets in both configurations: this build (SOA_NATIVE, on by default) and
# build/portable (SOA_NATIVE=OFF), judged in build/bench/speed.md.
PORT_DIR := build/portable
bench: configure
	@rm -f build/bench/targets_*.json build/bench/speed.md
	@cmake -S . -B $(PORT_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release -DSOA_NATIVE=OFF \
	  -DSOA_OUTPUT_DIR=$(CURDIR)/build >$(PORT_DIR).cmake.log \
	  || { cat $(PORT_DIR).cmake.log; exit 1; }
	cmake --build $(PORT_DIR) -j $(JOBS) --target chain_bench forward_bench
	cmake --build $(BUILD_DIR) -j $(JOBS) --target bench
	cmake --build $(BUILD_DIR) -j $(JOBS) --target bench_targets
	cmake --build $(PORT_DIR) --target bench_targets
	cmake --build $(BUILD_DIR) --target bench_report

# The library side by side with Orocos KDL and MuJoCo (tests/bench/compare/): its own build,
# build/compare (SOA_COMPARE=ON), then the program writes
# build/bench/compare.md and compare.csv.
CMP_DIR := build/compare
compare: compare-deps
	@mkdir -p build
	@cmake -S . -B $(CMP_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release -DSOA_COMPARE=ON \
	  -DSOA_OUTPUT_DIR=$(CURDIR)/build \
	  >$(CMP_DIR).cmake.log || { cat $(CMP_DIR).cmake.log; exit 1; }
	cmake --build $(CMP_DIR) -j $(JOBS) --target compare_report

# The student's repository, without the answers, into OUT: a new or empty folder
# (tests/release/release.sh; the notes' page "Instructors").
release:
	@sh tests/release/release.sh "$(CURDIR)" "$(OUT)"

# Every submission in SUBMISSIONS graded by the exercise checker into OUT (tests/grade/grade.sh;
# the notes' page "Instructors"): the library and the checkers compiled once, in OUT/.work/tree
# (make exercise-tree's flags; TREE=DIR: an exercise tree already built), then only each
# submission's code. Student code runs in a bubblewrap sandbox; UNSAFE=1 runs it without.
grade:
	@UNSAFE="$(UNSAFE)" LESSONS="$(LESSONS)" TREE="$(TREE)" JOBS="$(JOBS)" SEEDS="$(SEEDS)" \
	  sh tests/grade/grade.sh "$(CURDIR)" "$(SUBMISSIONS)" "$(OUT)" "$(WEIGHTS)"

format:
	clang-format -i $$(git ls-files '*.hpp' '*.cpp')

clean:
	rm -rf build
