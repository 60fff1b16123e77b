# Convenience front end: `make demo` and `make check` are the two commands of
# the README.  Everything real is in CMakeLists.txt.
BUILD ?= build
ASAN_BUILD ?= build-asan
JOBS ?= $(shell nproc)

.PHONY: all deps build demo check test asan mutate install clean

all: build

deps:
	@bash scripts/install-deps.sh

build: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release >/dev/null
	@cmake --build $(BUILD) -j$(JOBS)

# Runs the seed's epoxy plate with holes pulled in tension and prints where
# the output is.
demo: build
	@bash scripts/demo.sh $(BUILD)

# Whole test suite: optimised build, then an AddressSanitizer + UBSan build.
# The ctest label `client` opens the output in ParaView (pvbatch) and h5py;
# The label `lammps` compares the state-based PD with Debian's LAMMPS.
# install-test-deps.sh installs those clients when missing (not `make demo`).
check: build
	@bash scripts/install-test-deps.sh
	@cd $(BUILD) && ctest --output-on-failure -j$(JOBS)
	@$(MAKE) --no-print-directory asan

# Tests labelled no_asan in CMakeLists.txt (the heavy validation-gate groups
# validation_pd-fracture and validation_sph-rings, the labels
# client and lammps) run in the optimised build only; the MPI scripts run here
# on 3 ranks, in their light plan (docs/testing.md, "The sanitizer suite").
asan: deps
	@cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSPALL_SANITIZE=ON >/dev/null
	@cmake --build $(ASAN_BUILD) -j$(JOBS)
	@cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp ctest --output-on-failure -j$(JOBS) -LE no_asan

# Mutation score of the Release ctest (scripts/mutate, docs/testing.md): every
# catalogue entry applied alone to a scratch copy, rebuilt and tested.  Not part
# of `make check` (about an hour on 2 cores).  MUTATE_ARGS e.g. --only ID,ID or
# --out docs/notes/mutation.md.
MUTATE_ARGS ?=
mutate: deps
	@nice -n 10 python3 scripts/mutate/mutate.py --jobs $(JOBS) $(MUTATE_ARGS)

# Install the spall binary, libspall (shared and static), the public headers,
# spall.pc and the CMake package config under PREFIX (docs/api.md).
PREFIX ?= /usr/local
install: build
	@cmake --install $(BUILD) --prefix $(PREFIX)

clean:
	rm -rf $(BUILD) $(ASAN_BUILD)
