# The two commands of the README:
#   make demo   installs what is missing, builds, runs the main job on the bundled Cornell box
#   make test   installs what is missing, builds, runs the whole test suite
BUILD_DIR ?= build
BUILD_TYPE ?= Release
JOBS ?= 2
MAKEFLAGS += --no-print-directory
DEMO_OUT ?= out/cornell-box
RADIOSITY = $(BUILD_DIR)/cli/radiosity

.PHONY: all deps configure build demo test bench clean

all: build

deps:
	@bash scripts/install-deps.sh

configure: deps
	@test -f $(BUILD_DIR)/CMakeCache.txt || cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE)

build: configure
	@cmake --build $(BUILD_DIR) -j$(JOBS)

demo: build
	@mkdir -p $(DEMO_OUT)
	$(RADIOSITY) info data/cornell-box/scene.json
	$(RADIOSITY) render data/cornell-box/scene.json --method albedo -o $(DEMO_OUT)/albedo.exr
	$(RADIOSITY) render data/cornell-box/scene.json --method facing -o $(DEMO_OUT)/facing.exr
	$(RADIOSITY) solve data/cornell-box/scene.json -o $(DEMO_OUT)/solution.vtp
	$(RADIOSITY) render data/cornell-box/scene.json --method patches --solution $(DEMO_OUT)/solution.vtp \
	  -o $(DEMO_OUT)/patches.exr
	$(RADIOSITY) render data/cornell-box/scene.json --method hemisphere --solution $(DEMO_OUT)/solution.vtp \
	  --width 64 --height 64 -o $(DEMO_OUT)/local-pass.exr
	@echo "demo: in $(DEMO_OUT)/: solution.vtp (open in ParaView), local-pass.exr/.png/.stats.json (the exact local pass at the default tolerance), patches.exr/.png, albedo, facing"

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j$(JOBS)

bench: build
	@bash bench/run_all.sh $(BUILD_DIR)

clean:
	rm -rf $(BUILD_DIR) out
