# beamid: the commands a user runs. `make test` works on a fresh Debian 12 machine with no step before it.
BUILD      ?= build
SAN_BUILD  ?= build-sanitize
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
# Extra CMake settings for the build folder's first configuration, e.g. -DBEAMID_ARCH=x86-64-v3 (CMakeLists.txt).
CMAKE_ARGS ?=
BEAMID     := $(BUILD)/beamid

.PHONY: fuzz all deps build binary test test-unit test-slurm test-sanitize bench verify report report-check clean study study-tuning study-smoke plots golden install

# The studies of `make study`, in the order REPORT.md presents them (studies/*.toml; smoke is CI's miniature): issue
# 35's design (the comparison files) and the earlier studies REPORT.md's appendix C keeps, every one rerun at one
# commit so that `make report-check` passes. TUNING_STUDIES are the tuning step the design's settings come from
# (windows and continuation, measured on other seeds than the design's records): REPORT.md names them and the commit
# of their committed results but quotes none of their numbers; `make study-tuning` reruns them. On a cluster, any
# study runs as shards (README.md).
STUDIES      ?= comparison comparison-control comparison-n48 comparison-damping comparison-sensor comparison-thick comparison-thick-control comparison-thick-n48 comparison-thick-damping comparison-thick-sensor comparison-coloured comparison-thick-coloured paper thick modes landscape landscape-thick efficiency efficiency-coloured efficiency-coloured-thick efficiency-powerlaw errors-in-variables bias
REAL_STUDIES ?= real-steel real-steel-candidates synthetic-strip real-unb-tipmass
TUNING_STUDIES ?= start-distance windows windows-thick
STUDY_JOBS ?= 0

all: build

deps:
	@bash .ci/deps.sh

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_ARGS)

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

# Only the beamid program (what the studies need; the tests and benchmarks are left for make build / make test).
binary: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS) --target beamid

# Builds only what the tests run (the program, the test suite and the Python package; not the benchmarks), then
# runs the unit tier (ctest label unit: the GoogleTest cases) first, so that a broken computation fails in minutes,
# then everything else (integration, python, slow). `make test-unit` runs the first tier alone.
test: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS) --target beamid beamid_tests beamid_python
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -L unit
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -LE unit

test-unit: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS) --target beamid_tests
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS) -L unit

# Copies the program to $(PREFIX)/bin (default ~/.local/bin), so that `beamid` runs as the README writes it.
PREFIX ?= $(HOME)/.local
install: binary
	install -D -m 755 $(BEAMID) $(PREFIX)/bin/beamid
	@echo "installed $(PREFIX)/bin/beamid; make sure $(PREFIX)/bin is on PATH"

# A real single-node Slurm (Debian's slurm-wlm and munge, set up in a temporary folder and stopped afterwards): the
# smoke study as a job array of shards with an afterok merge, equal to a single run byte for byte, and a killed shard
# resubmitted to the same tables (tests/slurm/slurm_test.sh; about a minute; root or sudo).
test-slurm: deps $(BUILD)/CMakeCache.txt
	@bash .ci/deps.sh slurm
	cmake --build $(BUILD) -j $(JOBS) --target beamid
	SRC=$(CURDIR) BUILD=$(abspath $(BUILD)) bash tests/slurm/slurm_test.sh

# Unit tests once more under AddressSanitizer and UndefinedBehaviorSanitizer (benchmarks not built).
test-sanitize: deps
	cmake -S . -B $(SAN_BUILD) -DCMAKE_BUILD_TYPE=Debug -DBEAMID_SANITIZE=ON -DBEAMID_BENCHMARKS=OFF \
	      -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g"
	cmake --build $(SAN_BUILD) -j $(JOBS)
	cd $(SAN_BUILD) && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j $(JOBS)

# libFuzzer on every reader (beam and geometry TOML, study TOML, CSV, LVM, .npy, UFF 58, the command line, the study
# store's records, the report's generated blocks) for FUZZ_SECONDS each,
# under ASan and UBSan, from the seeds and regressions in tests/fuzz/corpus/<target>/. A finding is written to
# build-fuzz/crash-<target>-*: add it to the corpus (it then runs in `make test`) and fix the reader.
FUZZ_BUILD   ?= build-fuzz
FUZZ_SECONDS ?= 60
# FUZZ_SEED=0 draws a new random seed each run (exploration); CI passes a fixed seed and FUZZ_RUNS so that its pass is
# reproducible: the same binary, seed and corpus mutate the same inputs, and a shorter run is a prefix of a longer one.
# The slow targets get a share of FUZZ_RUNS (command line 1/40, LVM 1/3: about 20 s each here), so that the run count,
# not the clock, ends every target.
FUZZ_SEED    ?= 0
FUZZ_RUNS    ?= -1
FUZZ_TARGETS := beam_file study_file csv_record lvm_record npy_record uff_record command_line store_record report_blocks
fuzz:
	@bash .ci/deps.sh fuzz
	cmake -S . -B $(FUZZ_BUILD) -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
	      -DBEAMID_FUZZ=ON -DBEAMID_BENCHMARKS=OFF
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target $(addprefix fuzz_,$(FUZZ_TARGETS))
	@set -e; for t in $(FUZZ_TARGETS); do \
	  mkdir -p $(FUZZ_BUILD)/corpus/$$t; \
	  runs=$(FUZZ_RUNS); \
	  if [ $$runs -gt 0 ]; then case $$t in \
	    command_line) runs=$$((runs / 40));; \
	    lvm_record) runs=$$((runs / 3));; \
	  esac; fi; \
	  echo "== fuzz $$t ($(FUZZ_SECONDS) s at most, runs $$runs)"; \
	  $(FUZZ_BUILD)/fuzz_$$t $(FUZZ_BUILD)/corpus/$$t tests/fuzz/corpus/$$t -max_total_time=$(FUZZ_SECONDS) \
	    -seed=$(FUZZ_SEED) -runs=$$runs \
	    -max_len=8192 -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix=$(FUZZ_BUILD)/crash-$$t- \
	    2>$(FUZZ_BUILD)/fuzz-$$t.log || { tail -40 $(FUZZ_BUILD)/fuzz-$$t.log; exit 1; }; \
	  grep -E "stat::number_of_executed_units|Done" $(FUZZ_BUILD)/fuzz-$$t.log | tail -2; \
	done

# Google Benchmark, JSON under results/benchmarks/ (medians over repetitions); then, in the same invocation, the
# NumPy/SciPy peers of the forward run side by side with beamid (tests/benchmarks/peers.py -> peers.json), the scaling
# exponents in N and Nbar (tests/benchmarks/scaling.py -> scaling.json), and the peak memory of the smoke study.
# Debian's python3 (/usr/bin/python3) with python3-numpy and python3-scipy: `make deps` installs them for bench.
PYTHON ?= /usr/bin/python3
bench: $(BUILD)/CMakeCache.txt
	@bash .ci/deps.sh bench
	cmake --build $(BUILD) -j $(JOBS) --target beamid beamid_bench beamid_identification_bench
	@mkdir -p results/benchmarks
	$(BUILD)/beamid_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
	    --benchmark_filter=-Cvode --benchmark_out=results/benchmarks/forward_model.json --benchmark_out_format=json
	$(BUILD)/beamid_identification_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
	    --benchmark_out=results/benchmarks/identification.json --benchmark_out_format=json
	$(PYTHON) tests/benchmarks/peers.py --beamid $(BEAMID) --bench $(BUILD)/beamid_bench \
	    --output results/benchmarks/peers.json
	$(PYTHON) tests/benchmarks/scaling.py results/benchmarks
	rm -rf $(BUILD)/bench-smoke
	$(BEAMID) study studies/smoke.toml --output $(BUILD)/bench-smoke 2>&1 >/dev/null | grep "peak memory" \
	    | tee results/benchmarks/study_peak_memory.txt

# Forward-model verification tables (results/verification/) and the REPORT.md blocks made from them.
verify: binary
	$(BEAMID) verify --output results/verification
	$(BEAMID) report --update REPORT.md --results results

report: binary
	@if [ -f results/comparison/start_distance/reference.csv ]; then /usr/bin/python3 tools/design_tables.py results; fi
	$(BEAMID) report --update REPORT.md --results results
	/usr/bin/python3 tools/report_html.py REPORT.md REPORT.html
	@$(MAKE) --no-print-directory report-check

# The one-commit rule (issue 35): fails with one line naming the blocks of REPORT.md when they come from more than
# one commit, a dirty tree, name none, or come from a commit older than the program's (results older than the code
# that writes them); `python3 tools/report_commits.py REPORT.md` lists them by commit.
report-check: binary
	/usr/bin/python3 tools/report_commits.py REPORT.md --check --code \
	  $$($(BEAMID) --version | sed -n 's/.*(commit \([0-9a-f]*\).*/\1/p')

# The verification tables, every study (each resumes from its results/<study>/store/ if interrupted), then plots and
# REPORT.md, checked by the one-commit rule. Tables are byte-identical run to run; only results/*/timings.csv changes.
study: binary
	$(BEAMID) verify --output results/verification
	@set -e; for s in $(STUDIES); do \
	  echo "== beamid study studies/$$s.toml"; \
	  $(BEAMID) study studies/$$s.toml --jobs $(STUDY_JOBS); \
	done
	@set -e; for s in $(REAL_STUDIES); do \
	  echo "== beamid real studies/$$s.toml"; \
	  $(BEAMID) real studies/$$s.toml; \
	done
	$(MAKE) --no-print-directory plots
	$(MAKE) --no-print-directory report

# The tuning step (TUNING_STUDIES): the studies that fixed the design's windows and globalisation, on their own seeds.
study-tuning: binary
	@set -e; for s in $(TUNING_STUDIES); do \
	  echo "== beamid study studies/$$s.toml"; \
	  $(BEAMID) study studies/$$s.toml --jobs $(STUDY_JOBS); \
	done

# The smoke study (about 20 s): the whole pipeline in miniature, then whether it matches CI's golden table.
study-smoke: binary
	$(BEAMID) study studies/smoke.toml --jobs $(STUDY_JOBS)
	bash plots/make_plots.sh results/smoke plots/smoke
	python3 tests/golden/make_golden.py --check results/smoke/cases.csv tests/golden/smoke_cases.csv

# gnuplot, from the CSVs alone (plots/make_plots.sh), for every study that has results.
plots: deps
	@set -e; for s in $(STUDIES) $(TUNING_STUDIES) $(REAL_STUDIES) smoke; do \
	  if [ -f results/$$s/provenance.csv ]; then bash plots/make_plots.sh results/$$s plots/$$s; fi; \
	done
	@if [ -f results/comparison/start_distance/reach.csv ]; then bash plots/make_design_summary.sh results plots/design; fi

# Regenerates CI's golden table (tests/golden/smoke_cases.csv) from a fresh smoke run of the beamid program (the test
# only reads the table). Review the diff before committing: the golden test (ctest GoldenSmoke.*) fails on any
# estimate that moves by more than 1e-4.
golden: binary
	rm -rf $(BUILD)/golden-smoke
	$(BEAMID) study studies/smoke.toml --output $(BUILD)/golden-smoke
	python3 tests/golden/make_golden.py $(BUILD)/golden-smoke/cases.csv tests/golden/smoke_cases.csv
