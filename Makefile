# The two commands of the README: `make demo` and `make test`. Both install what they need.
# ROS tools must see Debian's python3, not a python3 earlier on PATH.
SHELL := /bin/bash
export PATH := /usr/bin:/bin:$(PATH)

WS := $(CURDIR)/.ws
PKG_LINK := $(WS)/src/mrs_vpr
SETUP := source $(WS)/devel/setup.bash

# Debian 12 packages (ROS 1 from Debian itself).
DEB_PACKAGES := build-essential cmake catkin ros-base-dev ros-message-generation ros-message-runtime \
  libroscpp-dev libcv-bridge-dev libimage-transport-dev librosbag-dev librostest-dev libnodeletlib-dev pluginlib-dev \
  libstd-msgs-dev libstd-srvs-dev libsensor-msgs-dev libtf2-ros-dev libtf2-dev libtf2-msgs-dev libgeometry-msgs-dev ros-std-msgs ros-std-srvs ros-sensor-msgs libopencv-dev libeigen3-dev libgtest-dev googletest \
  nlohmann-json3-dev libsqlite3-dev libjpeg-dev libboost-program-options-dev python3-rostest python3-rosbag python3-rosservice python3-rostopic python3-roslaunch \
  python3-sensor-msgs python3-std-msgs python3-std-srvs rosbash topic-tools catkin-lint python3-matplotlib \
  python3-dev python3-pybind11 python3-numpy python3-pytest python3-setuptools python3-opencv

# The real frames of the benchmark: read at run time, never copied into the repository.
DATA ?= $(CURDIR)/../shared/data

.PHONY: all deps link build test test-sanitize fuzz fuzz-deps demo bench bench-real bench-scale lint clean

all: build

deps:
	@missing=$$(for p in $(DEB_PACKAGES); do \
	  dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q 'install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = 0 ]; then \
	    echo "Installing: $$missing"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $$missing; \
	  else \
	    echo "Missing Debian packages. Run:"; \
	    echo "  sudo apt-get install -y --no-install-recommends" $$missing; exit 1; \
	  fi; \
	fi

# The workspace links each top-level entry of the package rather than the package folder itself, so
# that `rosrun` (which searches the package with `find -L`) never walks back into .ws/.
$(PKG_LINK):
	@mkdir -p $(PKG_LINK)

# $(call link_package,FOLDER): FOLDER holds a link to each top-level entry of the package.
link_package = mkdir -p $(1) && find $(1) -maxdepth 1 -type l -delete && \
  for f in $(CURDIR)/*; do ln -sfn "$$f" "$(1)/$$(basename "$$f")"; done

link: $(PKG_LINK)
	@$(call link_package,$(PKG_LINK))

build: deps link
	@cd $(WS) && catkin_make -DCMAKE_BUILD_TYPE=Release -DCATKIN_ENABLE_TESTING=ON >/dev/null \
	  || (cd $(WS) && catkin_make -DCMAKE_BUILD_TYPE=Release)
	@echo "Built. Run: source $(WS)/devel/setup.bash"

# The tests talk to nodes on this machine only: name it localhost, so that they also run where the
# host name does not resolve (containers, chroots).
test: build lint
	@cd $(WS) && rm -rf build/test_results && ROS_HOSTNAME=localhost catkin_make run_tests -j2 >$(WS)/test.log 2>&1; \
	  status=$$?; grep -E '^\[  FAILED  \] [A-Za-z]' $(WS)/test.log | sort -u || true; \
	  echo "Test output: $(WS)/test.log"; \
	  if [ $$status -ne 0 ]; then tail -50 $(WS)/test.log; exit $$status; fi
	@$(SETUP) && scripts/test_summary.sh $(WS)/build/test_results

# Sanitizers and fuzzing, each in a workspace of its own that links the same package (.ws is not
# touched) and builds only the targets it needs: .ws-sanitize (the compiler of .ws) the core's,
# evaluation's and store's tests and the failed-allocation tests, .ws-fuzz (clang, for libFuzzer) the
# map loader's fuzzer.
SANITIZE_WS := $(CURDIR)/.ws-sanitize
FUZZ_WS := $(CURDIR)/.ws-fuzz
SANITIZE_FLAGS := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
SANITIZED_TESTS := mrs_vpr_core_test mrs_vpr_evaluation_test mrs_vpr_store_test mrs_vpr_allocation_failure_test
FUZZ_SECONDS ?= 60
# Installed by `make fuzz` only: the README's two commands do not need a second compiler.
# libclang-rt-14-dev holds the fuzzer's and sanitizers' runtimes, only recommended by clang-14.
FUZZ_DEB_PACKAGES := clang-14 libfuzzer-14-dev libclang-rt-14-dev
FUZZ_CMAKE_ARGUMENTS := -DCMAKE_C_COMPILER=clang-14 -DCMAKE_CXX_COMPILER=clang++-14 -DCATKIN_ENABLE_TESTING=ON \
  -DMRS_VPR_FUZZ=ON

# $(call sanitized_build,WORKSPACE,CMAKE_ARGUMENTS,TARGETS). A shell that sourced .ws must not lead
# this build to .ws's libraries.
sanitized_build = $(call link_package,$(1)/src/mrs_vpr) && cd $(1) && \
  env -u LD_LIBRARY_PATH -u CMAKE_PREFIX_PATH catkin_make -j2 -DCMAKE_BUILD_TYPE=RelWithDebInfo $(2) \
    "-DCMAKE_C_FLAGS=$(SANITIZE_FLAGS)" "-DCMAKE_CXX_FLAGS=$(SANITIZE_FLAGS)" \
    "-DCMAKE_EXE_LINKER_FLAGS=$(SANITIZE_FLAGS)" "-DCMAKE_SHARED_LINKER_FLAGS=$(SANITIZE_FLAGS)" \
    $(3) >$(1)/build.log 2>&1 || { tail -40 $(1)/build.log; exit 1; }

# The core's, evaluation's and store's tests under AddressSanitizer and UndefinedBehaviorSanitizer;
# a failed test or any report (leaks included) fails.
test-sanitize: deps
	@$(call sanitized_build,$(SANITIZE_WS),-DCATKIN_ENABLE_TESTING=ON,$(SANITIZED_TESTS))
	@scripts/run_sanitized_tests.sh $(SANITIZE_WS)/devel/lib/mrs_vpr $(SANITIZED_TESTS)

fuzz-deps:
	@$(MAKE) --no-print-directory deps DEB_PACKAGES="$(DEB_PACKAGES) $(FUZZ_DEB_PACKAGES)"

# The map loader's libFuzzer target for FUZZ_SECONDS, from seeds written by the store at run time.
fuzz: fuzz-deps
	@$(call sanitized_build,$(FUZZ_WS),$(FUZZ_CMAKE_ARGUMENTS),map_database_fuzz_test map_database_fuzz_test_seeds)
	@bash scripts/fuzz_map_loader.sh $(FUZZ_WS)/devel/lib/mrs_vpr $(FUZZ_WS)/fuzz $(FUZZ_SECONDS)

demo: build
	@$(SETUP) && scripts/demo.sh

bench: build
	@$(SETUP) && rosrun mrs_vpr mrs_vpr_benchmark

# Both methods on real frames: the figures of doc/results.md.
bench-real: build
	@test -d "$(DATA)/nordland" || { echo "No real data at $(DATA): run make bench-real DATA=/path/to/data"; exit 1; }
	@$(SETUP) && rosrun mrs_vpr mrs_vpr_real_benchmark --data "$(DATA)" --part check --diagnose

# Maps of 10k, 100k and 1M real frames: load time, memory, query times (writes ~2.5 GB into /tmp).
bench-scale: build
	@test -d "$(DATA)/nordland" || { echo "No real data at $(DATA): run make bench-scale DATA=/path/to/data"; exit 1; }
	@$(SETUP) && rosrun mrs_vpr mrs_vpr_map_scale_benchmark --data "$(DATA)" --sizes 10k,100k,1M --queries 5 --brute-queries 1

# The package's own folder, not the workspace's links to it, whose folders catkin_lint does not enter;
# the checkout's folder name is the user's to choose (catkin_lint expects the package's name).
lint: deps
	@catkin_lint --strict -W2 --ignore package_path_name $(CURDIR) --skip-path $(WS) --skip-path $(SANITIZE_WS) \
	  --skip-path $(FUZZ_WS) 2>&1 | grep -v -e rosdep -e 'unknown dependencies will be ignored'; \
	  test $${PIPESTATUS[0]} -eq 0

clean:
	rm -rf $(WS) $(SANITIZE_WS) $(FUZZ_WS)
