# photonfarm: `make demo` and `make test` set everything up on a fresh Debian 12 machine (as
# root): missing packages, a Release build with Ninja, then the demo render or the test suite.
BUILD ?= build
JOBS ?= $(shell nproc)
DEMO_SECONDS ?= 60
# Where the first render's dashboard listens (port 0: a free one; the render prints the URL).
DEMO_WEB_LISTEN ?= 127.0.0.1:0

.PHONY: all deps configure build demo test bench clean

all: build

deps:
	@bash deploy/install-deps.sh

configure: deps
	@if [ ! -f $(BUILD)/build.ninja ]; then \
		cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release; fi

build: configure
	cmake --build $(BUILD) -j $(JOBS)

# Renders the Cornell box with a glass and a mirror sphere for about a minute on all cores,
# with its dashboard served at the URL it prints (the image converging, its error falling),
# then for a quarter of that with the Vulkan backend (on the best GPU; lavapipe without one),
# then the Cornell box from its pbrt-v4 form for a sixth.
demo: build
	@mkdir -p out
	./$(BUILD)/client/photonfarm render scenes/cornell-glass.gltf --width 512 --height 512 \
		--seconds $(DEMO_SECONDS) --out out/cornell-glass.exr --png out/cornell-glass.png \
		--snapshot-every 15 --snapshot-dir out/snapshots --report out/convergence \
		--web-listen $(DEMO_WEB_LISTEN)
	./$(BUILD)/worker/photonfarm-worker --list-devices
	./$(BUILD)/client/photonfarm render scenes/cornell-glass.gltf --width 256 --height 256 --backend vulkan --photons-per-batch 131072 \
		--seconds $$(( $(DEMO_SECONDS) / 4 )) --out out/cornell-glass-vulkan.exr --png out/cornell-glass-vulkan.png \
		|| echo "demo: the Vulkan render did not run (see the line above); the CPU images are written"
	./$(BUILD)/client/photonfarm render scenes/pbrt/cornell-box.pbrt --width 256 --seconds $$(( $(DEMO_SECONDS) / 6 )) \
		--out out/cornell-box-pbrt.exr --png out/cornell-box-pbrt.png
	@echo "demo: wrote out/cornell-glass.exr, out/cornell-glass.png and out/convergence/ (error against time)"
	@echo "demo: and out/cornell-glass-vulkan.exr, .png from the Vulkan backend"
	@echo "demo: and out/cornell-box-pbrt.exr, .png from the pbrt-v4 scene scenes/pbrt/cornell-box.pbrt"

# The whole suite through CTest, then what it skipped and why (CI=true turns every skip for a
# missing prerequisite into a failure; docs/testing.md), then its ten slowest tests and each
# label's time against its budget (bench/suite_times.py).
test: build
	@status=0; ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS) \
		--output-junit "$(abspath $(BUILD))/Testing/junit.xml" || status=$$?; \
	python3 tests/suite/skip_summary.py "$(abspath $(BUILD))/Testing/junit.xml"; \
	python3 bench/suite_times.py "$(abspath $(BUILD))" --top 10 || true; exit $$status

bench: build
	./$(BUILD)/bench/photon_bench
	./$(BUILD)/bench/merge_bench
	./$(BUILD)/bench/backend_bench --seconds 3
	./$(BUILD)/bench/numerics_report
	bench/farm_vs_render.sh $(BUILD)
	./$(BUILD)/bench/farm_load --workers 50 --jobs 8 --watchers 8 --seconds 30

clean:
	rm -rf $(BUILD) out
