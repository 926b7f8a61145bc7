# rktsph — top-level commands. Quick start: `make run`, then `make test`.
BUILD_DIR ?= build
BUILD_TYPE ?= Release
CMAKE_FLAGS ?=
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
CASE ?= cases/bar1d-elastic/case.yaml
RESULTS ?= results

# Debian packages the build and the tests need (Debian 12).
DEB_PACKAGES := build-essential cmake libeigen3-dev libyaml-cpp-dev libcli11-dev libfmt-dev \
                libgtest-dev libgmock-dev libbenchmark-dev python3 libcgal-dev
# Extra packages for the validation report (plots, browser check).
DEB_REPORT_PACKAGES := python3-matplotlib chromium
# Extra packages for `make test`: the report tools' tests (tests/app/report_tools_test.cpp) are
# skipped without matplotlib, and the browser check of the report without chromium; `make test`
# on a fresh machine must skip nothing (issue 30).
DEB_TEST_PACKAGES := python3-matplotlib chromium
# Extra packages for the sanitizer build with the libFuzzer targets (`make fuzz`, .ci/run): clang,
# its sanitizer and libFuzzer runtimes, and its OpenMP.
# The peer code of `make bench-peers` (bench/README.md): PySPH, from Debian.
DEB_PEERS_PACKAGES := python3-pysph
# The mesher and array library of `make bench-fe-triangles` (bench/README.md), from Debian.
DEB_FE_TRIANGLES_PACKAGES := gmsh python3-numpy
# The format check of CI (`make format-check`).
DEB_FORMAT_PACKAGES := clang-format
DEB_FUZZ_PACKAGES := clang-14 libclang-rt-14-dev libfuzzer-14-dev libomp-14-dev
FUZZ_BUILD_DIR ?= build-fuzz
FUZZ_SECONDS ?= 60

SUDO := $(shell [ "$$(id -u)" = 0 ] || echo sudo)

.PHONY: deps deps-test deps-report deps-format deps-fuzz deps-peers deps-fe-triangles format-check configure build run test bench bench-peers bench-fe-triangles validate fuzz format clean

deps:
	@missing=""; for p in $(DEB_PACKAGES); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  echo "Installing Debian packages:$$missing"; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing; \
	else echo "All build dependencies present."; fi

deps-test: deps
	@missing=""; for p in $(DEB_TEST_PACKAGES); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  echo "Installing Debian packages for the tests:$$missing"; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing; fi

deps-report: deps
	@missing=""; for p in $(DEB_REPORT_PACKAGES); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing; fi

deps-peers: deps
	@missing=""; for p in $(DEB_PEERS_PACKAGES); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing; fi

deps-fe-triangles: deps
	@missing=""; for p in $(DEB_FE_TRIANGLES_PACKAGES); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing; fi

deps-format:
	@missing=""; for p in $(DEB_FORMAT_PACKAGES); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing; fi

deps-fuzz: deps
	@missing=""; for p in $(DEB_FUZZ_PACKAGES); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; \
	if [ -n "$$missing" ]; then \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing; fi

# On a fresh machine the first failure is a missing library (Eigen3): say how to get them all.
configure:
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) $(CMAKE_FLAGS) || { \
	  missing=""; if command -v dpkg >/dev/null 2>&1; then \
	    for p in $(DEB_PACKAGES); do dpkg -s $$p >/dev/null 2>&1 || missing="$$missing $$p"; done; fi; \
	  echo; echo "make: configuring failed. If a library was not found, run 'make deps' first"; \
	  echo "      (it installs the Debian packages the build needs$${missing:+; missing here:$$missing})."; \
	  exit 1; }

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

run: deps build
	$(BUILD_DIR)/rktsph run $(CASE) --overwrite -o $(RESULTS)/$(notdir $(patsubst %/,%,$(dir $(CASE))))
	@echo
	@echo "Results are in $(RESULTS)/$(notdir $(patsubst %/,%,$(dir $(CASE)))) (open series.pvd in ParaView)."

test: deps-test build
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

bench: deps build
	tools/run_benchmarks.sh $(BUILD_DIR)

# rktsph against PySPH on BAR-WAVE-2D S and L, interleaved in one run: accuracy and speed
# (bench/README.md, "Against PySPH").
bench-peers: deps-peers build
	/usr/bin/python3 bench/peers/run_peers.py --build $(BUILD_DIR)

bench-fe-triangles: deps-fe-triangles build
	/usr/bin/python3 bench/peers/fe_triangles_bar_wave_2d.py --build $(BUILD_DIR)

# The validation report: every case in full, its plots and field pictures, and a check in a
# headless browser that the page shows them. The report is checked even when a case failed, and
# the target then fails with the validation's status.
REPORT ?= validation-report
validate: deps-report build
	@status=0; $(BUILD_DIR)/rktsph validate --all --report $(REPORT) || status=$$?; \
	tools/check_report.sh $(REPORT) && \
	echo "Report: $(REPORT)/index.html (and index.md)" && exit $$status

# The case-file fuzzer under ASan + UBSan (clang), for FUZZ_SECONDS (README.md, "Fuzzing"). The
# same build holds the unit tests: `cd build-fuzz && ctest -E Slow` runs them under the sanitizers.
fuzz: deps-fuzz
	$(MAKE) build BUILD_DIR=$(FUZZ_BUILD_DIR) BUILD_TYPE=RelWithDebInfo \
	  CMAKE_FLAGS="-DCMAKE_CXX_COMPILER=clang++-14 -DRKTSPH_FUZZ=ON -DRKTSPH_BENCHMARKS=OFF $(CMAKE_FLAGS)"
	fuzz/run.sh $(FUZZ_BUILD_DIR) $(FUZZ_SECONDS)

format:
	clang-format -i $$(git ls-files '*.cpp' '*.hpp')

# Fails, naming the files, if any tracked source differs from what .clang-format makes of it.
format-check:
	clang-format --dry-run --Werror $$(git ls-files '*.cpp' '*.hpp')

clean:
	rm -rf $(BUILD_DIR)
