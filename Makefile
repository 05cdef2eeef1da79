# renderaudit: the two commands a new user needs are `make` and `make test` (see README.md).
BUILD ?= build
# no "Entering directory" lines from the make that cmake --build runs
MAKEFLAGS += --no-print-directory
JOBS ?= $(shell nproc)
# Release: -O2, no debug information (a third less compile time than RelWithDebInfo).
BUILD_TYPE ?= Release
EXPERIMENT ?= experiments/quick.toml
OUT ?= outputs/quick
# When this make began, and the time since as "41 s" or "2 min 41 s" (in a recipe: $$($(ELAPSED))):
# each target's last line says how long it took.
MAKE_START := $(shell date +%s)
ELAPSED = t=$$(( $$(date +%s) - $(MAKE_START) )); \
  if [ $$t -ge 60 ]; then echo "$$((t / 60)) min $$((t % 60)) s"; else echo "$$t s"; fi

.PHONY: all deps check-build-tree build lean bundle gpu-kit install run analyze plot report paper test slurm-test driver-upgrade check-per-view bench investigations nightly watch timing lod regulation docs-check format clean FORCE

# Installs what is missing, builds, runs the default experiment, analyses it, draws its figures
# and ends with its report ($(OUT)/report/report.pdf and .html), printing the path. A run that
# drew nothing new and a program not rebuilt leave the report as it is: its analysis, figures and
# report are made again only when something they are made from changed (REPORT_INPUTS, asked of
# a second make, which reads the run's files as `run` left them). `make report` makes all four.
all: run
	@if $(MAKE) -q $(REPORT_PDF) MAKE_START=$(MAKE_START) 2> /dev/null; then \
	  echo "make: up to date in $$($(ELAPSED)): $(REPORT_PDF) (and report.html): the run and the" \
	    "program are as they were when it was made (\`make report\` makes it again)"; \
	  $(INSTALL_HINT); \
	else $(MAKE) $(REPORT_PDF) MAKE_START=$(MAKE_START); fi

deps:
	@scripts/install-deps.sh

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE)

# A build folder of another source tree (a checkout copied or moved with its build folder keeps
# CMake's absolute paths) would compile that tree: scripts/check-build-tree.sh stops first and
# names it.
check-build-tree:
	@scripts/check-build-tree.sh $(BUILD)

# Silent when there is nothing to build; what is compiled, and its errors, shown (scripts/build.sh).
build: check-build-tree deps $(BUILD)/CMakeCache.txt
	@scripts/build.sh $(BUILD) $(JOBS)

# The lean runner for GPU and cluster nodes (docs/operations.md): renderaudit-lean and the worker in
# build-lean/, configured without VTK, OpenImageIO, cairo or poppler (RA_FIGURES=OFF), so it builds
# where those are not installed. `make bundle` packs it with the libraries it needs into
# dist/renderaudit-lean-VERSION-ARCH.tar.gz, to unpack and run on another Linux with its own drivers.
LEAN_BUILD ?= build-lean
lean:
	@scripts/check-build-tree.sh $(LEAN_BUILD)
	@test -f $(LEAN_BUILD)/CMakeCache.txt || \
	  cmake -S . -B $(LEAN_BUILD) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DRA_FIGURES=OFF > /dev/null
	@scripts/build.sh $(LEAN_BUILD) $(JOBS) --target renderaudit-lean renderaudit-worker

bundle: lean
	@scripts/make-bundle.sh $(LEAN_BUILD)/renderaudit-lean $(LEAN_BUILD)/renderaudit-worker dist

# What bench/gpu-check.sh measures on a GPU node: the lean bundle and the lean build's
# layered_bench, in dist/, with the Khronos validation layer installed here (22 MB) to validate the
# Vulkan paths on the GPU.
gpu-kit: bundle
	@scripts/build.sh $(LEAN_BUILD) $(JOBS) --target layered_bench
	install -m 755 $(LEAN_BUILD)/layered_bench dist/layered_bench
	@scripts/kit-validation-layer.sh dist

# Puts the program on PATH, so that the commands the docs and the tool print paste as they are:
# PREFIX/bin/renderaudit (default ~/.local/bin, which Debian's ~/.profile puts on PATH once it
# exists) and the paper's table values it reads by default.
PREFIX ?= $(HOME)/.local
install: build
	install -D -m 755 $(BUILD)/renderaudit $(PREFIX)/bin/renderaudit
	install -D -m 644 experiments/papers/nist2008-tables.toml \
	  $(PREFIX)/share/renderaudit/experiments/papers/nist2008-tables.toml
	@case ":$$PATH:" in *":$(PREFIX)/bin:"*) echo "renderaudit: installed $(PREFIX)/bin/renderaudit";; \
	  *) echo "renderaudit: installed $(PREFIX)/bin/renderaudit; put it on PATH with:" \
	       "export PATH=\"$(PREFIX)/bin:\$$PATH\"";; esac

# The embedded default is osmesa-llvmpipe; where OSMesa is missing (Mesa >= 25.1) the same driver
# is drawn through EGL (experiments/quick-egl.toml), and the line below says so. `run` names the
# experiment's own platforms; each stage prints a line or two, the tables stay in their files. An
# error about the run folder (not one in the experiment file) ends with RENDERAUDIT_OUT_HINT: with
# make, the folder is OUT=DIR, not --out.
run: build
	@platform=$$($(BUILD)/renderaudit platforms --embedded-default) || exit 2; \
	experiment=$(EXPERIMENT); \
	if [ "$$platform" = egl-llvmpipe ] && [ "$$experiment" = experiments/quick.toml ]; then \
	  experiment=experiments/quick-egl.toml; \
	  echo "renderaudit: no OSMesa here: the embedded default draws llvmpipe through EGL ($$experiment)"; fi; \
	RENDERAUDIT_OUT_HINT="with make, OUT=DIR names the run folder (now $(OUT))" \
	  $(BUILD)/renderaudit run $$experiment --out $(OUT) --brief

ANALYZE_STAGE = $(BUILD)/renderaudit analyze $(OUT) --quiet
analyze: run
	@$(ANALYZE_STAGE)

# Figures and report need no display: a private Xvfb is started when DISPLAY is unset.
PLOT_STAGE = $(BUILD)/renderaudit plot $(OUT)
plot: analyze
	@$(PLOT_STAGE)

# `report` ends with what the run found (its violations of GL's rules, from the data); the last
# line says where the report is and how long it all took, and, until `make install` has put the
# program in PREFIX/bin, how to. FAIL_ON_VIOLATIONS=1 makes a violation of GL's rules fail it
# (renderaudit exits 5; make says "Error 5" and exits 2), EXPECTATIONS=FILE all but those FILE
# lists (docs/conformance.md#conformance-in-ci).
FAIL_ON_VIOLATIONS ?=
EXPECTATIONS ?=
CONFORMANCE_FLAGS = $(if $(FAIL_ON_VIOLATIONS),--fail-on-violations) \
  $(if $(EXPECTATIONS),--expectations $(EXPECTATIONS))
INSTALL_HINT = command -v renderaudit > /dev/null || [ -x $(PREFIX)/bin/renderaudit ] || \
  echo "The program is $(BUILD)/renderaudit; \`make install\` puts it on PATH as renderaudit" \
    "(the name the docs use)"
REPORT_STAGE = rc=0; $(BUILD)/renderaudit report $(OUT) $(CONFORMANCE_FLAGS) || rc=$$?; \
  echo "make report: done in $$($(ELAPSED)): $(OUT)/report/report.pdf (and report.html)"; \
  $(INSTALL_HINT); \
  exit $$rc
report: plot
	@$(REPORT_STAGE)

# What the default target's analysis, figures and report are made from: the program, the run's
# experiment and records (a shard is renamed into records/ when drawn: the folder's time moves;
# `run` rewrites only its manifest and summary when it draws nothing), a study's study.json
# (rewritten by each run of a study) and the paper's values that `analyze` compares with. A
# missing analysis, figures folder or report, or FAIL_ON_VIOLATIONS / EXPECTATIONS (a verdict
# asked for), makes them again whatever the times.
REPORT_PDF = $(OUT)/report/report.pdf
REPORT_OUTPUTS = $(OUT)/analysis $(OUT)/figures $(OUT)/report/report.html
REPORT_INPUTS = $(BUILD)/renderaudit $(wildcard $(OUT)/experiment.toml $(OUT)/study.json \
  $(OUT)/records $(OUT)/records/* experiments/papers/nist2008-tables.toml) \
  $(if $(strip $(CONFORMANCE_FLAGS))$(filter-out $(wildcard $(REPORT_OUTPUTS)),$(REPORT_OUTPUTS)),FORCE)
$(REPORT_PDF): $(REPORT_INPUTS)
	@$(ANALYZE_STAGE)
	@$(PLOT_STAGE)
	@$(REPORT_STAGE)
FORCE:

# The NIST paper's experiment on both Mesa drivers, read two ways (docs/reproduce-paper.md): as its
# text gives it, and with the near plane at 1e-5, which its Table 10 needs. Both are analysed with
# the paper's point convention (a half-pixel margin outside the window, which its Table 2 needs)
# and end in a report that sets every cell beside the paper's. PAPER_EXPERIMENTS and PAPER_OUT
# choose other files and another folder.
PAPER_EXPERIMENTS ?= experiments/nist2008.toml experiments/papers/nist2008-near-1e-5.toml
PAPER_OUT ?= outputs/paper
PAPER_PLATFORMS ?= --platform osmesa-llvmpipe --platform osmesa-softpipe
paper: build
	@set -e; for experiment in $(PAPER_EXPERIMENTS); do \
	  out=$(PAPER_OUT)/$$(basename $$experiment .toml); \
	  $(BUILD)/renderaudit run $$experiment --out $$out --jobs $(JOBS) $(PAPER_PLATFORMS); \
	  $(BUILD)/renderaudit analyze $$out --point-margin-px 0.5 --quiet; \
	  $(BUILD)/renderaudit plot $$out; \
	  $(BUILD)/renderaudit report $$out; \
	done; \
	for experiment in $(PAPER_EXPERIMENTS); do \
	  out=$(PAPER_OUT)/$$(basename $$experiment .toml); \
	  echo "Paper comparison: $$out/analysis/paper_comparison.md; report: $$out/report/report.pdf"; \
	done

# The whole test suite (CTest). CI runs exactly this.
test: build
	@scripts/build.sh $(BUILD) $(JOBS) --target test_programs
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# `run --slurm` on a one-machine Slurm (scripts/slurm-local.sh; needs root, installs slurm-wlm and
# munge): a job array against a local run, then a cancelled and a requeued task. Also in `make test`
# (skipped there, loudly, where no Slurm can be started).
slurm-test: build
	tests/scripts/slurm-test.sh $(BUILD)

# The installed Mesa against the newest Mesa of Debian's bookworm-backports on the nist2008 views
# (scripts/driver-upgrade.sh): fetch, run, audit, report (outputs/driver-upgrade/upgrade-report.md).
# Needs the Debian registry for the fetch; says so and stops where it cannot be reached.
# MESA_SOURCE=DIR [MESA_REF=REF] adds a Mesa built from source (docs/driver-builds.md).
# PER_VIEW=N: N primitives per kind and view instead of the experiment's 10,000, in a copy of it
# (scripts/cut-experiment.sh; of EXPERIMENT=FILE where given) written beside its own run folder:
# outputs/driver-upgrade-N.toml and outputs/driver-upgrade-N/, or OUT=DIR. N is checked before
# anything is built or fetched.
PER_VIEW ?=
DRIVER_UPGRADE_EXPERIMENT = $(if $(filter command line,$(origin EXPERIMENT)),$(EXPERIMENT),experiments/driver-upgrade.toml)
DRIVER_UPGRADE_OUT = $(if $(filter command line,$(origin OUT)),$(OUT),outputs/driver-upgrade-$(PER_VIEW))
driver-upgrade: $(if $(strip $(PER_VIEW)),check-per-view) build
	@$(if $(strip $(PER_VIEW)),scripts/cut-experiment.sh $(DRIVER_UPGRADE_EXPERIMENT) \
	  '$(PER_VIEW)' $(DRIVER_UPGRADE_OUT).toml && \
	  EXPERIMENT=$(DRIVER_UPGRADE_OUT).toml OUT=$(DRIVER_UPGRADE_OUT)) \
	  scripts/driver-upgrade.sh $(BUILD)
check-per-view:
	@scripts/cut-experiment.sh --check '$(PER_VIEW)'

# Benchmarks: side-by-side medians, printed as tables and written as JSON under outputs/bench/.
bench: build
	@scripts/build.sh $(BUILD) $(JOBS) --target benchmarks
	$(BUILD)/readback_bench --primitives 300 --rounds 3 --json outputs/bench/readback.json
	$(BUILD)/analysis_bench --records 2400000 --platforms 2
	$(BUILD)/run_overhead_bench --rounds 3 --jobs 2 --json outputs/bench/run_overhead.json
	$(BUILD)/layered_bench --platform osmesa-llvmpipe --primitives 2000
	$(BUILD)/layered_bench --platform vk-lavapipe --primitives 2000
	$(BUILD)/layered_bench --platform osmesa-llvmpipe --primitives 2000 --versus scan
	$(BUILD)/layered_bench --platform vk-lavapipe --primitives 2000 --versus scan

# Investigations: programs whose output a finding of docs/method.md quotes ("Where we differ from the
# paper and why": the paper's method under candidate readings, on the reference rasterizer).
investigations: build
	@scripts/build.sh $(BUILD) $(JOBS) --target paper_readings
	$(BUILD)/paper_readings

# The nightly driver audit (docs/nightly-audit.md): run, audit against the baseline, history,
# report. Exit code: 0 unchanged, 1 changed, 2 failed.
nightly: build
	@BUILD=$(BUILD) JOBS=$(JOBS) scripts/nightly.sh

# One night following a Mesa branch (docs/nightly-audit.md, "Following a Mesa branch"): the git
# tree MESA_SOURCE is fetched, its branch head built (scripts/install-mesa-build-deps.sh installs
# what that needs) and audited against last night's build, and every change is named to its
# commit. Exit code: 0 nothing new or unchanged, 1 changed, 2 failed.
WATCH_EXPERIMENT ?= experiments/watch-llvmpipe.toml
WATCH_STATE ?= outputs/watch
watch: build
	@test -n "$(MESA_SOURCE)" || { echo "make watch: MESA_SOURCE=DIR names the Mesa git clone to follow (docs/nightly-audit.md)" >&2; exit 2; }
	$(BUILD)/renderaudit watch $(MESA_SOURCE) --experiment $(WATCH_EXPERIMENT) --state $(WATCH_STATE) --jobs $(JOBS)

# The rendering-time study (Wimmer & Wonka 2003): experiments/timing.toml -> outputs/timing/
# (timing.json, timing.md, CSV files, figures) and its report. About 28 minutes on an idle 2-core
# machine (llvmpipe 7, softpipe 22); work running beside it inflates softpipe's c.
timing: build
	$(BUILD)/renderaudit timing experiments/timing.toml --out outputs/timing
	$(BUILD)/renderaudit report outputs/timing
	@echo "Timing report: outputs/timing/report/report.pdf (and report.html)"

# The terrain level-of-detail study and the regulation study: run, analyze,
# plot, report, like any experiment; a few minutes each.
lod: build
	$(BUILD)/renderaudit run experiments/lod.toml --out outputs/lod
	$(BUILD)/renderaudit analyze outputs/lod
	$(BUILD)/renderaudit plot outputs/lod
	$(BUILD)/renderaudit report outputs/lod
	@echo "LOD report: outputs/lod/report/report.pdf (and report.html)"

regulation: build
	$(BUILD)/renderaudit run experiments/regulation.toml --out outputs/regulation
	$(BUILD)/renderaudit analyze outputs/regulation
	$(BUILD)/renderaudit plot outputs/regulation
	$(BUILD)/renderaudit report outputs/regulation
	@echo "Regulation report: outputs/regulation/report/report.pdf (and report.html)"

# The numbers and names the README and docs quote that a command regenerates (scripts/docs-check.sh):
# the test count against ctest -N, the command table against renderaudit --help, the quick
# experiment's figure count against what `renderaudit plot --list` plans for $(OUT). Fails naming
# file and line. The first two are also the ctest docs_check, part of `make test`.
docs-check: analyze
	@cmake --build $(BUILD) -j $(JOBS) --target test_programs > /dev/null
	@scripts/docs-check.sh $(BUILD) $(OUT)

format:
	clang-format -i $$(git ls-files '*.cpp' '*.h')

clean:
	rm -rf $(BUILD) $(LEAN_BUILD) dist
