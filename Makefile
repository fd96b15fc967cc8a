# SPDX-License-Identifier: MPL-2.0
# OpenRCX front door.  `make` builds everything, `make test` runs every test, `make firmware` the brick image,
# `make bench` prints the benchmarks.  Each target first installs the Debian packages it needs when missing.
BUILD      ?= build
HOST_DIR   := $(BUILD)/host
ASAN_DIR   := $(BUILD)/asan
TARGET_DIR := $(BUILD)/h8300
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)

# command-or-file:debian-package (installed one target at a time: `make -j` runs the deps targets side by side, and
# apt-get refuses to run while another holds its lock)
HOST_DEPS   := cmake:cmake gcc:gcc clang:clang /usr/include/cmocka.h:libcmocka-dev nqc:nqc firmdl3:brickos \
               /usr/lib/llvm-14/lib/clang/14.0.6/lib/linux/libclang_rt.fuzzer-x86_64.a:libclang-rt-14-dev \
               /usr/include/microhttpd.h:libmicrohttpd-dev chromium:chromium chromedriver:chromium-driver \
               /usr/lib/python3/dist-packages/selenium:python3-selenium \
               groff:groff-base man:man-db gzip:gzip curl:curl dpkg-shlibdeps:dpkg-dev lintian:lintian \
               /usr/include/chipmunk/chipmunk.h:libchipmunk-dev /usr/include/cjson/cJSON.h:libcjson-dev \
               /usr/include/png.h:libpng-dev
TARGET_DEPS := h8300-hms-gcc:gcc-h8300-hms h8300-hms-ld:binutils-h8300-hms
BENCH_DEPS  := valgrind:valgrind

.PHONY: all host asan firmware test test-runs fuzz bench run world size deb install deps-host deps-target deps-bench clean

all: host firmware

define install_missing
	@missing=""; for d in $(1); do what=$${d%%:*}; pkg=$${d##*:}; \
	  if [ "$${what#/}" != "$$what" ]; then [ -e "$$what" ] || missing="$$missing $$pkg"; \
	  else command -v "$$what" >/dev/null 2>&1 || missing="$$missing $$pkg"; fi; done; \
	if [ -n "$$missing" ]; then echo "installing Debian packages:$$missing"; \
	  SUDO=""; [ "$$(id -u)" = 0 ] || SUDO=sudo; \
	  flock /tmp/openrcx-apt.lock sh -c "$$SUDO apt-get update -qq && DEBIAN_FRONTEND=noninteractive \
	    $$SUDO apt-get install -y -qq $$missing >/dev/null"; fi
endef

deps-host:
	$(call install_missing,$(HOST_DEPS))
deps-target:
	$(call install_missing,$(TARGET_DEPS))
deps-bench:
	$(call install_missing,$(BENCH_DEPS))

host: deps-host
	cmake -S . -B $(HOST_DIR) -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
	cmake --build $(HOST_DIR) -j $(JOBS)

# The image with Swan's programs (issue 16), named on the command line: a build folder made when it was not the
# default keeps its cached choice otherwise. (-DRCX_IMAGE_SWAN=OFF in another folder: the image without them.)
firmware: deps-target
	cmake -S . -B $(TARGET_DIR) -DCMAKE_TOOLCHAIN_FILE=$(CURDIR)/linker/h8300-hms.cmake -DRCX_IMAGE_SWAN=ON >/dev/null
	cmake --build $(TARGET_DIR) -j $(JOBS)

# The suite runs twice: as built for speed, and under AddressSanitizer + UndefinedBehaviorSanitizer (clang).
test: host firmware asan
	@$(MAKE) --no-print-directory test-runs

# Both runs of the built folders, the second also when the first failed (its sanitizer findings would stay hidden
# otherwise), each one's result on a line at the end; fails if either failed (issue 23 §6; tests/make).
test-runs:
	@failed=0; results=""; \
	for run in "normal:$(HOST_DIR)" "ASan/UBSan:$(ASAN_DIR)"; do name=$${run%%:*}; dir=$${run#*:}; \
	  echo "== make test: the $$name run ($$dir)"; \
	  if (cd "$$dir" && ctest --output-on-failure -j $(JOBS)); then result=passed; else result=FAILED; failed=1; fi; \
	  results="$$results$$name run ($$dir): $$result;"; done; \
	echo "== make test:"; echo "$$results" | tr ';' '\n' | sed '/^$$/d; s/^/   /'; [ $$failed = 0 ]

asan: deps-host
	CC=clang cmake -S . -B $(ASAN_DIR) -DCMAKE_BUILD_TYPE=Debug -DRCX_SANITIZE=ON >/dev/null
	cmake --build $(ASAN_DIR) -j $(JOBS)

# Each libFuzzer binary for FUZZ_SECONDS on a copy of its stored corpus: executions, coverage, failures.
FUZZ_SECONDS ?= 60
fuzz: asan
	@for f in $(ASAN_DIR)/tests/fuzz/fuzz_*; do n=$${f##*/fuzz_}; \
	  sh tests/fuzz/run.sh $$f tests/fuzz/corpus/$$n $(ASAN_DIR)/fuzz-work/$$n $(FUZZ_SECONDS) || exit 1; done

# Every tests/bench/*.sh prints its own figures; each gets the host and target build folders.
bench: host firmware deps-bench
	@for s in tests/bench/*.sh; do sh "$$s" $(HOST_DIR) $(TARGET_DIR) || exit 1; done

# The virtual RCX demo: a sample program downloaded by nqc over the pseudo-terminal, its trace on the terminal, the
# brick live in the browser (the URL is printed; PANEL_PORT=N for another port than 8330) until Ctrl-C.
run: host
	sh host_sim/demo.sh $(HOST_DIR)

# A robot in a world (issue 22): the scene SCENE (default the test pad), its brick's tower at build/rcx for nqc, the
# world and the brick in the browser at http://127.0.0.1:$(PANEL_PORT)/, in real time until Ctrl-C. Then, in another
# terminal: nqc -Sbuild/rcx -TRCX2 -d tests/world/linefollow.nqc -run
SCENE ?= testpad
PANEL_PORT ?= 8330
world: host
	@echo "rcxsim --world $(SCENE): the tower is $(BUILD)/rcx; the panel: http://127.0.0.1:$(PANEL_PORT)/"
	$(HOST_DIR)/rcxsim --world $(SCENE) --tty $(BUILD)/rcx --panel $(PANEL_PORT)

# Image size, free program memory and ROM checksum of the firmware.
size: firmware
	sh drivers/size.sh $(TARGET_DIR)

# The Debian package, build/openrcx_<version>_<arch>.deb, with CPack from the host build and the firmware image
# (packaging/CMakeLists.txt). `make test` builds and checks its own (tests/package).
deb: host firmware
	rm -rf $(HOST_DIR)/deb
	cd $(HOST_DIR) && cpack -G DEB -B $(CURDIR)/$(HOST_DIR)/deb >/dev/null
	cp $(HOST_DIR)/deb/openrcx_*.deb $(BUILD)/
	@ls $(BUILD)/openrcx_*.deb

# The same files as the package, under PREFIX (default /usr/local), below DESTDIR if given.
PREFIX ?= /usr/local
install: host firmware
	DESTDIR="$(DESTDIR)" cmake --install $(HOST_DIR) --prefix "$(PREFIX)"

clean:
	rm -rf $(BUILD)
