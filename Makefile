# yfdem: build, demo, tests, benchmarks.
#
#   make          build ./yfdem
#   make mpi      build ./yfdem_mpi (MPI ranks, src/par; OpenMPI: tools/install-deps --mpi)
#   make demo     install what is missing (tools/install-deps), build, run the main example deck
#   make check    install what tests need, build, run every Check suite through one runner, then
#                 the dumps in a real ParaView (tests/paraview/run) and the script tests (tests/*/run)
#   make bench    element-steps per second, thread scaling, bytes per element
#   make bench-mpi the same on 1 and 2 MPI ranks x 1 and 2 threads at 1e5 and 1e6 (./yfdem_mpi)
#   make bench-cost what a scene that models little costs (fixed costs of the step, unused contact)
#   make asan     the whole test suite under AddressSanitizer + UBSan (build-asan/; CI runs it)
#   make fuzz     libFuzzer on the deck interpreter and the .y, .msh and restart readers (clang;
#                 tools/fuzz/README.md), FUZZ_RUNS inputs each
#                 or FUZZ_TIME seconds in all
#   make valgrind the example decks under valgrind: no definite leaks (tools/valgrind-decks)
#
# Required flags live in YF_CFLAGS so that `make CFLAGS=-O0` changes optimisation only.
# -ffp-contract=off: no fused multiply-add, so results do not depend on the CPU (and match the
# Y2D references, which were computed without FMA).

CC      ?= gcc
# ./yfdem links Debian's serial HDF5; ./yfdem_mpi (make mpi) its MPI build (libhdf5-openmpi-dev),
# for frames written by every rank into one file (parallel HDF5, src/io/output.c).
H5PKG   := hdf5-serial
ifeq ($(YF_MPI),1)
H5PKG   := hdf5-openmpi
ifeq ($(shell pkg-config --exists hdf5-openmpi && echo yes),)
$(error make mpi needs Debian's libhdf5-openmpi-dev (pkg-config hdf5-openmpi): tools/install-deps --mpi)
endif
endif
PKGS    := $(H5PKG) gsl
PKGCF   := $(shell pkg-config --cflags $(PKGS) 2>/dev/null)
# HDF5 is linked from its static archive when the system has one (Debian's libhdf5-dev does):
# the shared libhdf5 loads curl, TLS and Kerberos for its S3 driver, which yfdem never uses, and
# their start-up code makes 6 MB of every process resident (10.0 -> 3.7 MB for an empty deck;
# PERF.md's problem at 1e4 triangles: 30.6 -> 25.0 MB peak).  The archive pulls in only the
# objects yfdem calls; szip and zlib are its filters.
H5LIBDIR := $(patsubst -L%,%,$(shell pkg-config --libs-only-L $(H5PKG) 2>/dev/null))
H5ARCHIVE := $(firstword $(wildcard $(addsuffix /libhdf5.a,$(H5LIBDIR))))
ifneq ($(H5ARCHIVE),)
PKGLIB  := $(H5ARCHIVE) -lsz -lz -ldl $(shell pkg-config --libs gsl 2>/dev/null)
else
PKGLIB  := $(shell pkg-config --libs $(PKGS) 2>/dev/null)
endif
CFLAGS  ?= -O3 -g
# src/ is split into layer folders (README, Source layout); every folder is on the include path so
# that a file names a header by its bare name.
LAYERS  := $(sort $(dir $(wildcard src/*/*.c src/*/*.h)))
YF_INC  := $(patsubst %/,-I%,$(LAYERS))
YF_CFLAGS := -std=c11 -D_GNU_SOURCE -fopenmp -ffp-contract=off -Wall -Wextra -Wshadow \
             -Wno-unused-parameter $(YF_INC) $(PKGCF)
LDLIBS  := $(PKGLIB) -lmetis -lm
CHECKLIB := $(shell pkg-config --libs check 2>/dev/null)

BUILD   := build
SRC     := $(filter-out src/par/%,$(wildcard src/*/*.c))
# `make mpi`: the same sources with -DYF_MPI (the hooks of src/step/par.h become MPI calls) plus
# src/par, compiled by mpicc into build-mpi/; ./yfdem never links MPI.
ifeq ($(YF_MPI),1)
YF_CFLAGS += -DYF_MPI
SRC     += $(wildcard src/par/*.c)
endif
OBJ     := $(SRC:src/%.c=$(BUILD)/%.o)
HDR     := $(wildcard src/*/*.h src/*/*.def)
TSRC    := $(wildcard tests/check_*.c)
TOBJ    := $(TSRC:tests/%.c=$(BUILD)/tests/%.o)

.PHONY: all demo check test deps deps-test bench bench-cost bench-mpi clean asan asan-mpi fuzz valgrind mpi

BIN     ?= yfdem

all: $(BIN)

$(BUILD)/%.o: src/%.c $(HDR) | $(BUILD)
	@mkdir -p $(dir $@)
	$(CC) $(YF_CFLAGS) $(CFLAGS) -MMD -MP -MF $(@:.o=.dep) -c $< -o $@

$(BUILD)/libyf.a: $(OBJ)
	$(AR) rcs $@ $^

$(BIN): $(BUILD)/main.o $(BUILD)/libyf.a
	$(CC) $(YF_CFLAGS) $(CFLAGS) $^ -o $@ $(LDLIBS)

$(BUILD):
	mkdir -p $(BUILD)/tests

# The runner calls every `Suite *NAME_suite(void)` defined in tests/check_*.c.
$(BUILD)/tests/suites.h: $(TSRC) | $(BUILD)
	grep -ho '^Suite \*[a-z0-9_]*_suite(void)' $(TSRC) | sed 's/^Suite \*\([a-z0-9_]*\)_suite(void)/YF_SUITE(\1)/' > $@.tmp
	mv $@.tmp $@

$(BUILD)/tests/%.o: tests/%.c $(BUILD)/tests/suites.h $(HDR) $(wildcard tests/*.h)
	$(CC) $(YF_CFLAGS) $(CFLAGS) -I$(BUILD)/tests -Itests -c $< -o $@

$(BUILD)/check_yfdem: $(TOBJ) $(BUILD)/libyf.a
	$(CC) $(YF_CFLAGS) $(CFLAGS) $^ -o $@ $(CHECKLIB) $(LDLIBS)

deps:
	tools/install-deps

MPICC ?= mpicc
mpi:
	$(MAKE) BUILD=build-mpi BIN=yfdem_mpi CC=$(MPICC) YF_MPI=1 yfdem_mpi

deps-test:
	tools/install-deps --test

# The seed paper's beam on the default coarse mesh (nx 60, 12000 steps = 1.85 ms, more than one
# bending period): 19.5 s in all on 2 cores at load 0.8, about 30-40 s on 2 loaded cores.  Outputs
# land in the working directory (README, Files).
demo: deps
	$(MAKE) yfdem
	./yfdem -in decks/beam.deck -summary demo_summary.json
	@echo "demo: summary (first_crack, midspan_crack_time, symmetry, ...) in demo_summary.json;"
	@echo "      frames beam.xmf (ParaView) + beam_NNNNNN.h5, cracks beam_breaks.csv and beam_opened.csv,"
	@echo "      history beam_metrics.csv (outputs go to the working directory); pictures: README, The seed paper's scenes"

# Tests run at most 2 threads (the machines have 2 cores).
check: deps-test
	$(MAKE) yfdem $(BUILD)/check_yfdem
	if command -v $(MPICC) >/dev/null; then $(MAKE) mpi; fi
	CK_TIMEOUT_MULTIPLIER=$${CK_TIMEOUT_MULTIPLIER:-3} OMP_NUM_THREADS=2 YFDEM=./yfdem YFDEM_MPI=./yfdem_mpi $(BUILD)/check_yfdem
	YFDEM=./yfdem tests/paraview/run
	YFDEM=./yfdem tests/convert/run
	YFDEM=./yfdem tests/readme/run
	YFDEM=./yfdem tests/failure_mode/run
	YFDEM=./yfdem tests/ym_compare/run
	YFDEM=./yfdem tests/yfplot/run

test: yfdem $(BUILD)/check_yfdem
	OMP_NUM_THREADS=2 YFDEM=./yfdem $(BUILD)/check_yfdem

bench: yfdem
	tools/bench

# What a scene that models little costs (docs/PERFORMANCE.md, What a scene costs): the step's fixed
# costs at 16 and 1000 triangles (1 thread, and the 2-thread default that times its steps), and a
# contact rule between bodies that never meet.
bench-cost: yfdem
	tools/bench --cases elastic --sizes 16,1e3 --threads 1,2 --work 2e7 --repeat 3
	tools/bench --cases elastic,contact_far --sizes 2e4 --threads 1 --work 4e8 --repeat 3

bench-mpi: yfdem mpi
	tools/bench --cases elastic,y2d_perf --sizes 1e5,1e6 --ranks 1,2 --threads 1,2

# Sanitizers: a separate build (build-asan/yfdem + runner), the same suite, LeakSanitizer on (a
# leak ends the test's child or the binary with exit 1, which fails the test; libhdf5's own blocks
# left when it refuses a damaged file are suppressed, tools/lsan.supp); a longer timeout
# covers the 2-3x slowdown.  asan-mpi leaves leaks out: OpenMPI keeps allocations of its own
# past MPI_Finalize.
ASAN_FLAGS := -O1 -g -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
asan: deps-test
	$(MAKE) BUILD=build-asan BIN=build-asan/yfdem CFLAGS="$(ASAN_FLAGS)" build-asan/yfdem build-asan/check_yfdem
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 LSAN_OPTIONS=suppressions=$(CURDIR)/tools/lsan.supp \
	UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	CK_TIMEOUT_MULTIPLIER=4 OMP_NUM_THREADS=2 YFDEM=build-asan/yfdem build-asan/check_yfdem

# The MPI suite under the same sanitizers: ./yfdem_mpi built with them (build-mpi-asan/), the
# suite's runner and ./yfdem (the reference it compares with) as make check builds them.
asan-mpi: deps-test
	$(MAKE) BUILD=build-mpi-asan BIN=build-mpi-asan/yfdem_mpi CC=$(MPICC) YF_MPI=1 CFLAGS="$(ASAN_FLAGS)" \
	  build-mpi-asan/yfdem_mpi
	$(MAKE) yfdem $(BUILD)/check_yfdem
	ASAN_OPTIONS=detect_leaks=0:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	CK_RUN_SUITE=mpi CK_TIMEOUT_MULTIPLIER=4 OMP_NUM_THREADS=2 YFDEM=./yfdem YFDEM_MPI=build-mpi-asan/yfdem_mpi \
	  $(BUILD)/check_yfdem

# FUZZ_TIME=S: stop after S seconds (CI: .ci/run), whichever of the two limits comes first.
FUZZ_RUNS ?= 1000000
FUZZ_TIME ?= 0
fuzz:
	tools/install-deps --dev
	tools/fuzz/run $(FUZZ_RUNS) $(FUZZ_TIME)

valgrind: yfdem
	tools/valgrind-decks

clean:
	rm -rf $(BUILD) build-asan build-fuzz build-mpi build-mpi-asan yfdem yfdem_mpi

# Header dependencies (.dep, with -MP: a header that moves or goes away is no error; the .d files
# of the flat src/ layout are ignored).
-include $(wildcard $(BUILD)/*.dep $(BUILD)/*/*.dep)
