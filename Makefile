# beamid: the commands a user runs. `make test` works on a fresh Debian 12 machine with no step before it.
BUILD      ?= build
SAN_BUILD  ?= build-sanitize
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
BEAMID     := $(BUILD)/beamid

.PHONY: all deps build test test-sanitize bench verify report clean

all: build

deps:
	@bash .ci/deps.sh

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

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

clean:
	rm -rf $(BUILD) $(SAN_BUILD)
