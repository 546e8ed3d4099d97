# The two commands of the README:
#   make demo   installs dependencies, builds, renders the screening scenario into out/demo/
#   make test   installs dependencies, builds, runs the whole test suite
# Other targets: build, bench, asan (sanitizer build + tests, without the
# label gpu), gpu-check (scripts/gpu-check: the GPU check, on a machine with a
# CUDA device), fuzz (libFuzzer
# harnesses, FUZZ_SECONDS each, default 60; FUZZ_RUNS caps executions), clean, demo-quick
# (the demo at low resolution, as CI runs it), puff-example, animated-example,
# smoke-screen-example.
PRESET ?= release
BUILD  := build/$(PRESET)
JOBS   ?= $(shell nproc)

.PHONY: all deps configure build test demo bench asan fuzz gpu-check clean animated-example smoke-screen-example puff-example demo-quick

all: build

deps:
	@scripts/install-deps

configure: deps
	@cmake --preset $(PRESET) >/dev/null

build: configure
	@cmake --build --preset $(PRESET) -j $(JOBS)

# The label gpu needs a CUDA device (docs/gpu.md): scripts/gpu-check runs it.
test: build
	@ctest --preset $(PRESET) -j $(JOBS) -LE gpu

demo: build
	@OBSCURA=$(BUILD)/apps/obscura/obscura scripts/demo

demo-quick: build
	@OBSCURA=$(BUILD)/apps/obscura/obscura scripts/demo --quick

bench: build
	@$(BUILD)/bench/bench_emission_absorption

asan:
	@$(MAKE) test PRESET=asan

FUZZ_SECONDS ?= 60
FUZZ_RUNS ?= 0
fuzz:
	@scripts/install-deps --fuzz
	@cmake --preset fuzz >/dev/null
	@cmake --build --preset fuzz -j $(JOBS)
	@scripts/fuzz $(FUZZ_SECONDS) $(FUZZ_RUNS)

gpu-check:
	@scripts/gpu-check

clean:
	@rm -rf build out

animated-example: build
	@OBSCURA=$(BUILD)/apps/obscura/obscura scripts/animated-example

puff-example: build
	@OBSCURA=$(BUILD)/apps/obscura/obscura scripts/puff-example

smoke-screen-example: build
	@OBSCURA=$(BUILD)/apps/obscura/obscura scripts/smoke-screen-example
