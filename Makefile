# SOA Course Companion — the commands students and instructors type.
#   make run        build everything, run the lesson tour (outputs under build/course/)
#   make test       library tests, lesson checks, exercise tests against the solutions
#   make exercises  the exercise tests against exercises/ (a pass/fail table; never fails)
#   make docs       Doxygen course notes (offline math, gnuplot figures) in build/docs/html
#   make bench      Google Benchmark results and the soa command's scale (cli_scale) in build/bench/
# Options: SANITIZE=1 (AddressSanitizer + UBSan, in build/sanitize), BUILD_TYPE=Debug (in
# build/debug), TESTS=regex (make test runs only the ctest tests it matches).

BUILD_TYPE ?= Release
ifeq ($(SANITIZE),1)
  BUILD_DIR ?= build/sanitize
  SAN_FLAG := -DSOA_SANITIZE=ON
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
  libbenchmark-dev nlohmann-json3-dev doxygen graphviz gnuplot-nox libjs-mathjax

.PHONY: all run test exercises docs bench deps configure build clean format

all: build

deps:
	@missing=""; for p in $(PACKAGES); do \
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

# The untouched stubs are checked too (every exercise must fail on them) when exercises/
# has no local changes in git; once a student edits an exercise, only `make exercises`
# looks at it.
CHECK_STUBS := $(shell git diff --quiet HEAD -- exercises 2>/dev/null && \
  test -z "$$(git ls-files --others --exclude-standard exercises 2>/dev/null)" && echo ON || echo OFF)

configure: deps
	@mkdir -p build
	@cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) $(SAN_FLAG) \
	  -DSOA_CHECK_STUBS=$(CHECK_STUBS) -DSOA_OUTPUT_DIR=$(CURDIR)/build >$(BUILD_DIR).cmake.log \
	  || { cat $(BUILD_DIR).cmake.log; exit 1; }

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

run: build
	cmake --build $(BUILD_DIR) --target tour

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure --no-tests=error -j $(JOBS) $(if $(TESTS),-R '$(TESTS)')

# One table per lesson: each exercise pass / FAIL / not done. Never stops the build.
exercises: configure
	@for src in tests/exercises/[0-9][0-9]-*.cpp; do \
	  nn=$$(basename $$src | cut -c1-2); \
	  echo; echo "== Lesson $$nn exercises ($$(ls -d exercises/$$nn-*)) =="; \
	  if cmake --build $(BUILD_DIR) -j $(JOBS) --target ex$$nn-exercises \
	       >$(BUILD_DIR)/ex$$nn-exercises.log 2>&1; then \
	    $(BUILD_DIR)/tests/ex$$nn-exercises --report || echo "  the test program crashed"; \
	  else echo "  does not compile yet: see $(BUILD_DIR)/ex$$nn-exercises.log"; \
	       grep -m5 'error' $(BUILD_DIR)/ex$$nn-exercises.log | sed 's/^/    /'; fi; \
	done; true

docs: build
	cmake --build $(BUILD_DIR) --target docs

bench: configure
	cmake --build $(BUILD_DIR) -j $(JOBS) --target bench

format:
	clang-format -i $$(git ls-files '*.hpp' '*.cpp')

clean:
	rm -rf build
