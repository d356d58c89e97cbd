# The two commands of the README:
#   make demo   installs what is missing, builds, runs the main job on the bundled Cornell box
#   make test   installs what is missing, builds, runs the whole test suite
BUILD_DIR ?= build
BUILD_TYPE ?= Release
JOBS ?= 2
MAKEFLAGS += --no-print-directory
DEMO_OUT ?= out/cornell-box
RADIOSITY = $(BUILD_DIR)/cli/radiosity

.PHONY: all deps deps-run configure configure-run executable build demo demo-glass demo-glossy readme test bench results stability docs docs-check format format-check clean sanitize fuzz fuzz-build fuzz-campaign

all: build

# Two sets of packages (scripts/install-deps.sh): what the executable needs to build and run
# (make demo), and that with what the tests, benchmarks, formatting and fuzzing need.
deps-run:
	@bash scripts/install-deps.sh run
deps:
	@bash scripts/install-deps.sh all

# One build folder. make demo configures it without the tests and benchmarks (whose packages
# it does not install) and builds the executable alone; make test (build) turns them on. A new
# folder is made with Ninja and unity builds of the modules (RAD_UNITY in CMakeLists.txt): from
# scratch, the executable builds in about half the time (bench/results/fresh_machine.md).
NEW_BUILD = cmake -S . -B $(BUILD_DIR) -G Ninja -DRAD_UNITY=ON -DCMAKE_BUILD_TYPE=$(BUILD_TYPE)
configure-run: deps-run
	@test -f $(BUILD_DIR)/CMakeCache.txt || $(NEW_BUILD) -DRAD_BUILD_TESTS=OFF -DRAD_BUILD_BENCH=OFF
configure: deps
	@if [ ! -f $(BUILD_DIR)/CMakeCache.txt ]; then $(NEW_BUILD) -DRAD_BUILD_TESTS=ON -DRAD_BUILD_BENCH=ON; \
	elif ! grep -qs '^RAD_BUILD_TESTS:BOOL=ON' $(BUILD_DIR)/CMakeCache.txt; then \
	  cmake -S . -B $(BUILD_DIR) -DRAD_BUILD_TESTS=ON -DRAD_BUILD_BENCH=ON; fi

executable: configure-run
	@cmake --build $(BUILD_DIR) -j$(JOBS) --target radiosity

build: configure
	@cmake --build $(BUILD_DIR) -j$(JOBS)

demo: executable
	@mkdir -p $(DEMO_OUT)
	$(RADIOSITY) info data/cornell-box/scene.json
	$(RADIOSITY) render data/cornell-box/scene.json --method albedo -o $(DEMO_OUT)/albedo.exr
	$(RADIOSITY) render data/cornell-box/scene.json --method facing -o $(DEMO_OUT)/facing.exr
	$(RADIOSITY) solve data/cornell-box/scene.json -o $(DEMO_OUT)/solution.vtp
	$(RADIOSITY) render data/cornell-box/scene.json --method patches --solution $(DEMO_OUT)/solution.vtp \
	  -o $(DEMO_OUT)/patches.exr
	$(RADIOSITY) render data/cornell-box/scene.json --method hemisphere --solution $(DEMO_OUT)/solution.vtp \
	  --width 256 --height 256 -o $(DEMO_OUT)/local-pass.exr
	$(RADIOSITY) export data/cornell-box/scene.json --solution $(DEMO_OUT)/solution.vtp --stats $(DEMO_OUT)/local-pass.stats.json \
	  -o $(DEMO_OUT)/paraview
	@echo "demo: in $(DEMO_OUT)/: solution.vtp, local-pass.exr/.png/.stats.json (the exact local pass at the default tolerance), patches.exr/.png, albedo, facing; paraview/ (patch mesh, octree, per-pixel stats of local-pass; open in ParaView) and paraview/patch_mesh.png"

# Paper 000's exact extensions on a Cornell box with a stained-glass pane under the light and a
# mirror on the green wall: solve (filters tint the shadow rays, the mirror shoots images), the
# exact local pass by vertex tracing (the hemisphere method refuses filters), a Monte Carlo
# gather from the same solution through the same filters and mirror, and the error map between;
# then the path-traced reference of the scene itself and the whole pipeline's error against it.
GLASS_OUT ?= out/cornell-glass-mirror
GLASS = data/cornell-glass-mirror/scene.json
GLASS_SIZE ?= 192
demo-glass: executable
	@mkdir -p $(GLASS_OUT)
	$(RADIOSITY) info $(GLASS)
	$(RADIOSITY) solve $(GLASS) -o $(GLASS_OUT)/solution.vtp
	$(RADIOSITY) render $(GLASS) --method vertex --solution $(GLASS_OUT)/solution.vtp \
	  --width $(GLASS_SIZE) --height $(GLASS_SIZE) -o $(GLASS_OUT)/local-pass.exr
	$(RADIOSITY) render $(GLASS) --method montecarlo --samples 16384 --solution $(GLASS_OUT)/solution.vtp \
	  --width $(GLASS_SIZE) --height $(GLASS_SIZE) -o $(GLASS_OUT)/montecarlo.exr
	$(RADIOSITY) compare $(GLASS_OUT)/local-pass.exr $(GLASS_OUT)/montecarlo.exr \
	  -o $(GLASS_OUT)/error-map.exr --max 0.1
	$(RADIOSITY) render $(GLASS) --method pathtrace --samples 8192 \
	  --width $(GLASS_SIZE) --height $(GLASS_SIZE) -o $(GLASS_OUT)/pathtrace.exr
	$(RADIOSITY) compare $(GLASS_OUT)/local-pass.exr $(GLASS_OUT)/pathtrace.exr \
	  -o $(GLASS_OUT)/error-map-pathtrace.exr --max 0.1

# Paper 003's glossy transfer: a ring of brushed gold under a point light on a white floor
# (data/glossy-ring/), then the Cornell box with a roughened pane under its lamp
# (data/cornell-glossy-pane/): solve, the local pass with the glossy beams kept apart, the
# path-traced reference and the error map between (the pictures of the README;
# docs/images/glossy/README.md). About 5 minutes on 2 cores, most of it the path tracer.
GLOSSY_OUT ?= out/glossy-ring
GLOSSY = data/glossy-ring/scene.json
PANE = data/cornell-glossy-pane/scene.json
demo-glossy: executable
	@mkdir -p $(GLOSSY_OUT)
	$(RADIOSITY) info $(GLOSSY)
	$(RADIOSITY) solve $(GLOSSY) -o $(GLOSSY_OUT)/solution.vtp
	$(RADIOSITY) render $(GLOSSY) --method vertex --tolerance 0.01 --solution $(GLOSSY_OUT)/solution.vtp \
	  -o $(GLOSSY_OUT)/ring-vertex.exr
	$(RADIOSITY) render $(GLOSSY) --method pathtrace --samples 8192 -o $(GLOSSY_OUT)/ring-pathtraced.exr
	$(RADIOSITY) compare $(GLOSSY_OUT)/ring-vertex.exr $(GLOSSY_OUT)/ring-pathtraced.exr \
	  --floor 0.05 --max 0.5 -o $(GLOSSY_OUT)/ring-error.exr
	$(RADIOSITY) solve $(PANE) -o $(GLOSSY_OUT)/pane.vtp
	$(RADIOSITY) render $(PANE) --method vertex --solution $(GLOSSY_OUT)/pane.vtp --width 192 --height 192 \
	  -o $(GLOSSY_OUT)/pane-vertex.exr
	$(RADIOSITY) render $(PANE) --method pathtrace --samples 2048 --width 192 --height 192 \
	  -o $(GLOSSY_OUT)/pane-pathtraced.exr
	$(RADIOSITY) compare $(GLOSSY_OUT)/pane-vertex.exr $(GLOSSY_OUT)/pane-pathtraced.exr \
	  --floor 0.05 --max 0.5 -o $(GLOSSY_OUT)/pane-error.exr

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j$(JOBS)

bench: build
	@bash bench/run_all.sh $(BUILD_DIR)
	@python3 scripts/results_md.py > docs/results.md  # it shows the stability table

# The README's demo section: the real output of `make demo`, spliced in by scripts/readme_demo.py.
readme: executable
	@mkdir -p out
	@$(MAKE) demo 2>&1 | tee out/demo.log
	@python3 scripts/readme_demo.py out/demo.log
	@for image in local-pass patches facing; do cp $(DEMO_OUT)/$$image.png docs/images/cornell-box-$$image.png; done
	@echo "readme: README.md and docs/images/cornell-box-*.png show this run of make demo"

# docs/results.md: the sweep on the Cornell box at 256x256 (the bench's uniform
# 2,948-element solution), its error maps and charts, the exports, and the figures it shows.
RESULTS_OUT ?= out/results
CORNELL = data/cornell-box/scene.json
results: build
	@mkdir -p $(RESULTS_OUT) docs/images/results
	@printf 'machine: %s cores, %s\ncommit: %s\ndate: %s\n' "$$(nproc)" \
	  "$$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')" \
	  "$$(git rev-parse --short HEAD)$$(git diff --quiet HEAD -- . ':!docs' || echo ' (with uncommitted changes)')" \
	  "$$(date -u +%Y-%m-%d)" > $(RESULTS_OUT)/run.txt
	$(RADIOSITY) solve $(CORNELL) --patch-size 0.07 --refine-threshold 0 -o $(RESULTS_OUT)/solution.vtp
	$(RADIOSITY) sweep $(CORNELL) --solution $(RESULTS_OUT)/solution.vtp --width 256 --height 256 \
	  -o $(RESULTS_OUT)/sweep
	$(RADIOSITY) compare $(RESULTS_OUT)/sweep/images/hemisphere_T0.2.exr $(RESULTS_OUT)/sweep/reference.exr \
	  -o $(RESULTS_OUT)/error_map_hemisphere_T0.2.exr --max 0.25
	$(RADIOSITY) compare $(RESULTS_OUT)/sweep/images/montecarlo_N1024.exr $(RESULTS_OUT)/sweep/reference.exr \
	  -o $(RESULTS_OUT)/error_map_montecarlo_N1024.exr --max 0.25
	$(RADIOSITY) export $(CORNELL) --solution $(RESULTS_OUT)/solution.vtp -o $(RESULTS_OUT)/export
	cp $(RESULTS_OUT)/sweep/reference.png $(RESULTS_OUT)/sweep/results.csv $(RESULTS_OUT)/sweep/error_vs_time.png \
	  $(RESULTS_OUT)/sweep/error_vs_tolerance.png $(RESULTS_OUT)/sweep/time_vs_tolerance.png \
	  $(RESULTS_OUT)/export/patch_mesh.png docs/images/results/
	cp $(RESULTS_OUT)/error_map_hemisphere_T0.2.png $(RESULTS_OUT)/error_map_montecarlo_N1024.png docs/images/results/
	cp $(RESULTS_OUT)/run.txt docs/images/results/
	python3 scripts/results_md.py > docs/results.md

# The stability report: the degenerate scene families through both exact gatherers and Monte
# Carlo (bench/results/stability.md).
stability: build
	@bash bench/stability.sh $(BUILD_DIR)
	@python3 scripts/results_md.py > docs/results.md  # it shows the stability table
	@cat bench/results/stability.md

# The manual's generated pages: the command reference from the executable's --help, and the
# results page from the committed measurements. docs-check (CI) fails when either is stale.
docs: build
	@bash scripts/cli-reference.sh $(RADIOSITY) > docs/cli.md.tmp && mv docs/cli.md.tmp docs/cli.md
	@python3 scripts/results_md.py > docs/results.md.tmp && mv docs/results.md.tmp docs/results.md
	@bash scripts/robustness_md.sh $(BUILD_DIR) > docs/robustness.md.tmp && mv docs/robustness.md.tmp docs/robustness.md
	@echo "docs: wrote docs/cli.md, docs/results.md, docs/robustness.md"

docs-check: build
	@bash scripts/cli-reference.sh $(RADIOSITY) | diff -u docs/cli.md - >/dev/null || \
	  { echo "docs/cli.md is not the current --help text: run make docs" >&2; exit 1; }
	@python3 scripts/results_md.py | diff -u docs/results.md - >/dev/null || \
	  { echo "docs/results.md is not what the committed measurements give: run make docs" >&2; exit 1; }
	@echo "docs-check: docs/cli.md and docs/results.md are current"

# clang-format (.clang-format) over every tracked C++ file; format-check (CI) changes nothing.
FORMATTED = git ls-files '*.h' '*.cpp'
format: deps
	@$(FORMATTED) | xargs clang-format -i
format-check: deps
	@$(FORMATTED) | xargs clang-format --dry-run --Werror && echo "format-check: clean"

# The whole suite built with AddressSanitizer and UndefinedBehaviorSanitizer (CI runs it after
# the normal suite), in its own build folder. -Werror is off there (GCC 12 warns falsely of
# uninitialized values in std::regex under the sanitizers; the normal build keeps it on). Leak
# detection is off here: Mesa's OpenGL driver, which VTK's offscreen rendering loads, leaks from
# a module it unloads, which LeakSanitizer cannot attribute or suppress. The fuzz runs check
# leaks in every reader (make fuzz). SANITIZE_EXCLUDE leaves out the tests that only repeat
# default solves of whole scenes to check numbers (mesh independence, accuracy against the
# reference, the hierarchical solver's too; determinism across thread counts, no NaN in any
# output): under the sanitizers they took 12 of CI's minutes, and every code path they run is
# run by the shorter solver, probe and render tests that stay in (ConservesEnergyOnThreeScenes,
# the furnace, the hierarchical solver's own, the CLI and durability tests). Likewise the vertex
# tracer's and the occlusion culling's agreement checks over whole solved scenes (7 minutes of
# CPU under the sanitizers; CI had reached 59 of its 60): their
# random-scene and degenerate-family versions stay in; so does the cells' bound test on a room of
# shadow edges and degenerate polygons (the Cornell box's is left out). And the MPI runs (MpiRun.*, issue 21): a
# minute and a half of separate processes under mpirun, run in the normal build; the pieces
# that one process can check (the inputs' bundle, a job of one) stay in. make sanitize SANITIZE_EXCLUDE= runs all.
SANITIZE_DIR ?= build-sanitize
SANITIZE_EXCLUDE ?= CornellBoxIsMeshIndependent|EveryInterpolatedPixelOfTheCornellBox|GlobalAccuracy\.TheDefaultSolve|GlobalAccuracy\.TheHierarchicalSolver|Determinism\.|NoNaNOrInfinityReaches|AgreesWithHemisphereInRadiosityEnvironments|ChangesNothingOnTheCornellSolution|MpiRun\.
sanitize: deps
	@test -f $(SANITIZE_DIR)/CMakeCache.txt || cmake -S . -B $(SANITIZE_DIR) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DRAD_SANITIZE=ON -DRAD_BUILD_BENCH=OFF -DRAD_WERROR=OFF
	@cmake --build $(SANITIZE_DIR) -j$(JOBS)
	@cd $(SANITIZE_DIR) && ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --output-on-failure -j$(JOBS) $(if $(SANITIZE_EXCLUDE),-E '$(SANITIZE_EXCLUDE)')

# The libFuzzer targets (fuzz/, clang): each runs FUZZ_SECONDS (default 60) on its seeded corpus
# after replaying its regression set, JOBS targets at a time; the table of executions goes to
# stdout. Only the targets (and the modules they read with) are built with clang; the normal
# build makes the seed files.
FUZZ_DIR ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_TARGETS = fuzz_scene fuzz_mesh_obj fuzz_mesh_ply fuzz_mesh_off fuzz_mesh_stl fuzz_mtl \
  fuzz_points fuzz_solution fuzz_exr
fuzz: fuzz-build
	@FUZZ_JOBS=$(JOBS) bash fuzz/run.sh $(FUZZ_DIR) $(FUZZ_SECONDS) $(RADIOSITY)

fuzz-build: build
	@test -f $(FUZZ_DIR)/CMakeCache.txt || CC=clang CXX=clang++ cmake -S . -B $(FUZZ_DIR) \
	  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRAD_FUZZ=ON -DRAD_BUILD_TESTS=OFF -DRAD_BUILD_BENCH=OFF
	@cmake --build $(FUZZ_DIR) -j$(JOBS) --target $(FUZZ_TARGETS)

# The long campaign: every target to FUZZ_RUNS executions (default 1,000,000) or FUZZ_SECONDS
# (default 3600), two at a time; writes fuzz/results/campaign.md (hours on 2 cores: not in CI).
fuzz-campaign: fuzz-build
	@bash fuzz/campaign.sh $(FUZZ_DIR) $(RADIOSITY)

clean:
	rm -rf $(BUILD_DIR) $(SANITIZE_DIR) $(FUZZ_DIR) out
