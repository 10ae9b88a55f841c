# beamid: the commands a user runs. `make test` works on a fresh Debian 12 machine with no step before it.
BUILD      ?= build
SAN_BUILD  ?= build-sanitize
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
BEAMID     := $(BUILD)/beamid

.PHONY: all deps build binary test test-sanitize bench verify report clean study study-smoke plots golden

# The studies of `make study`, in the order REPORT.md presents them (studies/*.toml; smoke is CI's miniature).
STUDIES    ?= paper thick modes landscape
STUDY_JOBS ?= 0

all: build

deps:
	@bash .ci/deps.sh

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

# Only the beamid program (what the studies need; the tests and benchmarks are left for make build / make test).
binary: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS) --target beamid

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# Unit tests once more under AddressSanitizer and UndefinedBehaviorSanitizer (benchmarks not built).
test-sanitize: deps
	cmake -S . -B $(SAN_BUILD) -DCMAKE_BUILD_TYPE=Debug -DBEAMID_SANITIZE=ON -DBEAMID_BENCHMARKS=OFF \
	      -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g"
	cmake --build $(SAN_BUILD) -j $(JOBS)
	cd $(SAN_BUILD) && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j $(JOBS)

# Google Benchmark, JSON under results/benchmarks/ (medians over repetitions).
bench: build
	@mkdir -p results/benchmarks
	$(BUILD)/beamid_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
	    --benchmark_out=results/benchmarks/forward_model.json --benchmark_out_format=json
	$(BUILD)/beamid_identification_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
	    --benchmark_out=results/benchmarks/identification.json --benchmark_out_format=json

# Forward-model verification tables (results/verification/) and the REPORT.md blocks made from them.
verify: build
	$(BEAMID) verify --output results/verification
	$(BEAMID) report --update REPORT.md --results results

report: build
	$(BEAMID) report --update REPORT.md --results results

# Every study (each resumes from its results/<study>/store/ if interrupted), then plots and REPORT.md. Tables are
# byte-identical run to run; only results/*/timings.csv changes.
study: binary
	@set -e; for s in $(STUDIES); do \
	  echo "== beamid study studies/$$s.toml"; \
	  $(BEAMID) study studies/$$s.toml --jobs $(STUDY_JOBS); \
	done
	@echo "== beamid real studies/real-steel.toml"
	$(BEAMID) real studies/real-steel.toml
	$(MAKE) --no-print-directory plots
	$(BEAMID) report --update REPORT.md --results results

study-smoke: binary
	$(BEAMID) study studies/smoke.toml --jobs $(STUDY_JOBS)
	bash plots/make_plots.sh results/smoke plots/smoke

# gnuplot, from the CSVs alone (plots/make_plots.sh), for every study that has results.
plots: deps
	@set -e; for s in $(STUDIES) real-steel smoke; do \
	  if [ -f results/$$s/provenance.csv ]; then bash plots/make_plots.sh results/$$s plots/$$s; fi; \
	done

# Regenerates CI's golden table (tests/golden/smoke_cases.csv) from a fresh smoke run. Review the diff before
# committing: the golden test (ctest GoldenSmoke.*) fails on any estimate that moves by more than 1e-4.
golden: build
	BEAMID_UPDATE_GOLDEN=1 $(BUILD)/beamid_tests --gtest_filter='GoldenSmoke.*'
