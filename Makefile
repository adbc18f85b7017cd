# Entry points: `make demo` runs the main job, `make test` runs every test.
# Both install the Debian packages they need first (scripts/install-deps is idempotent).
PRESET ?= release
JOBS   ?= $(shell nproc)
BIN     = build/$(PRESET)/bin

.PHONY: deps configure build test conformance bench demo asan clean

deps:
	@scripts/install-deps

configure: deps
	@cmake --preset $(PRESET) >/dev/null

build: configure
	@cmake --build --preset $(PRESET) -j $(JOBS)

test: build
	@ctest --preset $(PRESET) -j $(JOBS)

conformance: build
	@$(BIN)/jsonld-conformance ../shared/conformance/jsonld/toRdf-manifest.jsonld
	@$(BIN)/jsonld-conformance ../shared/conformance/jsonld/expand-manifest.jsonld

bench: build
	@$(BIN)/mospec-bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true

asan:
	@$(MAKE) test PRESET=asan

demo: build
	@scripts/demo

clean:
	rm -rf build
