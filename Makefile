# knitforge — the two commands of the quick start are `make demo` and `make test`.
# Both install what they need (scripts/setup), configure and build first.

BUILD      ?= build
ASAN_BUILD ?= build-asan
JOBS       ?= $(shell nproc)
DEMO_OUT   ?= out/demo
CMAKE_FLAGS = -G Ninja -DCMAKE_CXX_COMPILER_LAUNCHER=ccache

# ccache: key on paths relative to the checkout so fresh clones (CI) reuse
# objects compiled in any other checkout on the same machine.
export CCACHE_BASEDIR   := $(CURDIR)
export CCACHE_NOHASHDIR := 1

FUZZ_SECONDS ?= 60

.PHONY: all setup configure build demo test test-release test-asan bench fuzz clean

all: build

setup:
	@scripts/setup

$(BUILD)/build.ninja:
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS) -DCMAKE_BUILD_TYPE=Release

configure: setup $(BUILD)/build.ninja

build: configure
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	scripts/demo $(BUILD)/bin/knitforge $(DEMO_OUT)

test: test-release test-asan

test-release: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS) --timeout 600

$(ASAN_BUILD)/build.ninja:
	cmake -S . -B $(ASAN_BUILD) $(CMAKE_FLAGS) -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS=-O1 \
	  -DKNITFORGE_SANITIZE=ON -DKNITFORGE_BUILD_BENCH=OFF

test-asan: setup $(ASAN_BUILD)/build.ninja
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(JOBS) --timeout 900

bench: build
	scripts/bench $(BUILD)

# Every reader's libFuzzer target for FUZZ_SECONDS each (docs/fuzzing.md);
# make test runs them for 4 s each.
fuzz: setup
	scripts/fuzz --seconds $(FUZZ_SECONDS) --out $(BUILD)/fuzz

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) out
