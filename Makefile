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
	@$(BIN)/shacl-conformance ../shared/conformance/shacl/tests/core/manifest.ttl

BENCHES = mospec-bench mospec-validate-bench mospec-runtime-bench mospec-runtime-base-bench mospec-sim-bench mospec-codegen-bench
bench: build
	@for b in $(BENCHES); do \
	  if [ -x $(BIN)/$$b ]; then echo "== $$b"; \
	    $(BIN)/$$b --benchmark_repetitions=5 --benchmark_report_aggregates_only=true; fi; \
	done

asan:
	@$(MAKE) test PRESET=asan

demo: build
	@scripts/demo

clean:
	rm -rf build
