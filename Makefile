# zview: make builds ./zview; make test runs every test; make asan runs
# them under AddressSanitizer + UBSan; make bench prints the benchmark.
CC      ?= cc
PREFIX  ?= /usr/local
PKGS    := ncursesw libpng libjpeg zlib libseccomp
# feature macros are set per file (term.c needs the wide-char curses ones)
PKG_CFLAGS := $(filter-out -D%,$(shell pkg-config --cflags $(PKGS) 2>/dev/null))
PKG_LIBS   := $(shell pkg-config --libs $(PKGS) 2>/dev/null || echo -lncursesw -ltinfo -lpng16 -ljpeg -lz -lseccomp)

# Optional: assimp for the long tail of formats (glTF, FBX, 3DS, ...).
# On when pkg-config finds it; `make ASSIMP=0` builds without.
ASSIMP  ?= $(shell pkg-config --exists assimp 2>/dev/null && echo 1 || echo 0)
# The library is opened at run time (dlopen, by its soname), not linked:
# see src/mesh/assimp.c.
ifeq ($(ASSIMP),1)
AI_SONAME := $(shell objdump -p $$(pkg-config --variable=libdir assimp)/libassimp.so 2>/dev/null | awk '/SONAME/ { print $$2 }')
AI_CFLAGS := -DZV_ASSIMP $(if $(AI_SONAME),-DZV_ASSIMP_SONAME='"$(AI_SONAME)"') \
             $(filter-out -D%,$(shell pkg-config --cflags assimp 2>/dev/null))
AI_LIBS   := -ldl
endif

# Optional: OpenCASCADE for STEP, IGES and BREP. OCCT has no C API: a
# C++ shim (src/mesh/occt/occtshim.cpp) is built into its own shared
# library beside the binary, which src/mesh/step.c opens at run time, so
# the binary neither links OCCT nor needs it. On when OCCT's headers are
# found; `make OCCT=0` builds without the shim (zview then says, for
# these files, that OpenCASCADE is not installed for it).
OCCT_INC ?= /usr/include/opencascade
OCCT    ?= $(shell test -f $(OCCT_INC)/STEPCAFControl_Reader.hxx && echo 1 || echo 0)
CXX     ?= g++
OCCT_LIBS := -lTKXDESTEP -lTKXDEIGES -lTKSTEP -lTKSTEPBase -lTKIGES -lTKXCAF -lTKLCAF -lTKCAF -lTKCDF -lTKVCAF \
             -lTKXSBase -lTKMesh -lTKShHealing -lTKTopAlgo -lTKBRep -lTKG3d -lTKGeomBase -lTKMath -lTKernel
OCCT_CXXFLAGS := -O2 -g -std=c++17 -Wall -Wextra -fPIC -isystem $(OCCT_INC)
OCCT_SHIM := $(dir $(BIN))libzview-occt.so
LIBDIR  ?= $(PREFIX)/lib/zview

OPT     ?= -O2
EXTRA_CFLAGS ?=
# -ffp-contract=off: no fused multiply-add where the source has a multiply
# then an add. The SIMD paths (SSE2/AVX2, no FMA) and the scalar
# reference must round every operation alike to give the same bits, and
# the exactness tests compare them byte for byte; a compiler free to fuse
# would round the scalar path differently on CPUs with FMA.
COMMON_CFLAGS := -std=c11 -Wall -Wextra -ffp-contract=off -Iinclude $(PKG_CFLAGS) -MMD -MP -pthread
CFLAGS  ?= $(OPT) -g
CFLAGS  += $(EXTRA_CFLAGS) $(COMMON_CFLAGS) $(AI_CFLAGS)
LDLIBS  += $(PKG_LIBS) $(AI_LIBS) -lm -pthread
# -z now: zview's symbols bound once at its start, not again in every
# sandboxed child: the fork server is a copy of zview before it called
# most functions, and lazy binding made each child look them up anew
# (the dynamic linker's lookups and the copied pages of its table: 1.9 ms
# of CPU a child, 10.1 to 8.2 s over 1,000 cubes --check; issue 34)
BIN_LDFLAGS := -Wl,-z,now

BUILD   ?= build
SRCS    := $(wildcard src/*/*.c)
ifneq ($(ASSIMP),1)
SRCS    := $(filter-out src/mesh/assimp.c src/mesh/assimpio.c,$(SRCS))
endif
LIBSRCS := $(filter-out src/main/main.c,$(SRCS))
OBJS    := $(SRCS:%.c=$(BUILD)/%.o)
LIBOBJS := $(LIBSRCS:%.c=$(BUILD)/%.o)
TSRCS   := $(wildcard tests/test_*.c) tests/testlib.c tests/writers.c tests/nocerts.c
TOBJS   := $(TSRCS:%.c=$(BUILD)/%.o)
TESTBIN := $(BUILD)/zview-tests
BIN     ?= zview

.PHONY: all help test unit e2e mutate mutate-rooms asan run bench bench-formats views install clean assets test-models test-long noassimp nosimd colour-error fuzz fuzz-run fuzz-run-mesh fuzz-run-check fuzz-run-tex fuzz-run-repair fuzz-run-dist fuzz-seeds replay bench-check bench-repair bench-repair-cli bench-points bench-order bench-textures bench-pixels bench-sandbox bench-load bench-memory bench-preview bench-diff bench-printq bench-step bench-gallery bench-folder bench-speed

all: $(BIN) $(if $(filter 1,$(OCCT)),$(OCCT_SHIM))

# make help: the targets, what each is for, and how long it takes here.
help:
	@echo 'Build and run'
	@echo '  make               ./zview (warning-free with -Wall -Wextra; EXTRA_CFLAGS=-Werror in CI)'
	@echo '  make run           build, then open the bundled demo scene'
	@echo '  make install       to $$(PREFIX) (default /usr/local), with the man page and completions'
	@echo '  make noassimp      the build without assimp, in build-noassimp/'
	@echo '  make OCCT=0        without the OpenCASCADE shim (libzview-occt.so: STEP, IGES, BREP)'
	@echo '  make nosimd        SIMD compiled out (-DZV_NO_SIMD), in build-nosimd/, and its unit tests'
	@echo 'Tests'
	@echo '  make test          every test: unit (Criterion), fuzz replays, end-to-end; about 2.9 min of CPU'
	@echo '                     (1 min 53 s warm on 2 quiet cores, median of 4 runs from 1 min 47 s to 2 min 1 s;'
	@echo '                     the e2e scripts 4 at a time: E2E_JOBS;'
	@echo '                     7 min at load 14)'
	@echo '                     a check skipped for want of a tool fails it; ZV_ALLOW_SKIPS=1 allows that outside CI'
	@echo '  make unit          the unit tests alone; make e2e the end-to-end ones alone'
	@echo '  make asan          make test under AddressSanitizer + UBSan, in build-asan/ (about 3 minutes;'
	@echo '                     ASAN_GOALS="test test-long" adds the long runs, as CI does)'
	@echo '  make test-models   every algorithm against the z-buffer on ../shared/models'
	@echo '  make test-long     what make test leaves out: the second half of the agreement and SIMD matrices,'
	@echo '                     the assimp corpus, kitty, mlterm and tmux in xterm under Xvfb (tests/e2e/long_*.sh);'
	@echo '                     CI runs it, under ASan too'
	@echo '  make replay        every input that ever failed, through the normal build'
	@echo '  make mutate        each mutant of tests/mutants.txt must fail make test (about 15 minutes)'
	@echo '  make mutate-rooms  mechanical mutants, PER_ROOM=10 lines of each room (SEED=1): the kill rate per room (hours;'
	@echo '                     PER_ROOM=5 SEED=1: 115 run, 86 of 86 killed, 29 equivalent; doc/design.md)'
	@echo 'Fuzzing (clang + libFuzzer: sh tools/deps.sh installs them)'
	@echo '  make fuzz          build-fuzz/fuzz-obj, fuzz-diff, fuzz-mesh, fuzz-check, fuzz-tex (the image decoders),'
	@echo '                     fuzz-repair, fuzz-dist (--diff against a brute-force reference)'
	@echo '  make fuzz-run SECONDS=N   run each for N seconds; failures go to build-fuzz/artifacts/'
	@echo '  make fuzz-run-mesh, fuzz-run-check, fuzz-run-tex, fuzz-run-repair, fuzz-run-dist   one of them alone'
	@echo '  make fuzz-seeds    rewrite the differential fuzzer seed scenes'
	@echo 'Benchmarks (never timed tests: compare medians and ratios within one run)'
	@echo '  make bench         the speed table (tools/bench.sh), single-thread rows pinned to a core'
	@echo '  make bench-formats load speed and peak memory of every format'
	@echo '  make views         doc/views.md: the first view of 29 models (../shared/models, assimp-testmodels)'
	@echo '  make bench-memory  resident memory after frame 100 and frame 10,000 of a turning view'
	@echo '  make bench-load    big OBJ files (31M triangles): first picture against wc -l, bytes per triangle'
	@echo '  make bench-preview the viewer on a 31M-triangle OBJ: first partial picture, keys while loading'
	@echo '  make bench-points  a 10M-point scan: load and frames'
	@echo '  make bench-order   hzb and hzb-octree under each --order'
	@echo '  make bench-textures textured frames against untextured; the first picture of a 16k image'
	@echo '  make bench-pixels  bytes a picture costs in sixel, kitty and iTerm2 images against text'
	@echo '  make bench-check   --check of the dragon and the 5.2M model beyond loading, and its peak memory'
	@echo '  make bench-repair  the repair of the dragon and the 5.2M model beyond loading, and its peak memory'
	@echo '  make bench-repair-cli the whole zview --repair IN -o OUT, writing included: wall, CPU, peak, phases'
	@echo '  make bench-diff    --diff of the dragon and the 5.2M model against edited copies, 1 and 2 threads, memory'
	@echo '  make bench-printq  --thickness on the dragon (the BVH and a ray a face), 1 and 2 threads; --check with it'
	@echo '  make bench-sandbox the loading sandbox against --no-sandbox on the dragon'
	@echo '  make bench-folder  --check --jsonl over 10,000 cubes, sandboxed and not (target 60 s)'
	@echo '  make bench-step    a 1 MB STEP part to its first picture, against f3d (needs OCCT and f3d)'
	@echo '  make bench-gallery zview DIR on 100 bunnies: the first screen of tiles (target 1 s), the verdicts, all checked'
	@echo '  make bench-speed   issue 35'"'"'s targets, one row each with its goal: load against wc -l, sandbox, textures, check, llvmpipe, threads, f3d'
	@echo '  make colour-error  how far 256/16/8-colour pictures are from truecolor'
	@echo 'Other'
	@echo '  make assets        regenerate the bundled models (they are committed)'
	@echo '  make clean         remove every build folder'

# The build's configuration, rewritten only when it changes, so that
# switching ASSIMP rebuilds what depends on it and relinks.
CONFIG  := $(BUILD)/config
$(shell mkdir -p $(BUILD); echo 'ASSIMP=$(ASSIMP)' | cmp -s - $(CONFIG) || echo 'ASSIMP=$(ASSIMP)' > $(CONFIG))
$(BUILD)/src/mesh/format.o: $(CONFIG)

$(BIN): $(OBJS) $(CONFIG)
	$(CC) $(CFLAGS) $(BIN_LDFLAGS) -o $@ $(filter %.o,$^) $(LDLIBS)

$(BUILD)/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -c -o $@ $<

# where an installed zview finds the shim (step.c)
$(BUILD)/src/mesh/step.o: CFLAGS += -DZV_OCCT_LIBDIR='"$(LIBDIR)"'

# The OpenCASCADE shim, and the generator of the STEP, IGES and BREP
# test files (tests/e2e/test_step.sh), both in C++ against OCCT.
$(OCCT_SHIM): src/mesh/occt/occtshim.cpp src/mesh/occt/occtshim.h
	$(CXX) $(OCCT_CXXFLAGS) -shared -Wl,--as-needed -o $@ $< $(OCCT_LIBS)

$(BUILD)/occtgen: tools/occtgen.cpp
	@mkdir -p $(BUILD)
	$(CXX) $(OCCT_CXXFLAGS) -Wl,--as-needed -o $@ $< -lTKPrim -lTKBO $(OCCT_LIBS)
OCCTGEN := $(if $(filter 1,$(OCCT)),$(BUILD)/occtgen)

# The unit tests' binary: Criterion starts it again for every test, and
# on this VM each start's page faults are most of a small test's cost;
# linked as a fixed-address executable (-no-pie), a start has 7,500
# fewer relocations to write, 10% less CPU a test (tests/nocerts.c
# saves another 15%: its header says why the symbol is exported).
$(TESTBIN): $(LIBOBJS) $(TOBJS) $(CONFIG)
	$(CC) $(CFLAGS) -no-pie -o $@ $(filter %.o,$^) $(LDLIBS) -lcriterion -Wl,--export-dynamic-symbol=mbedtls_x509_crt_parse_file

# The fuzz harnesses (tests/fuzz/) linked with a plain main() instead of
# libFuzzer: they replay the seed and regression corpora in every build.
FUZZ_OBJ_SRCS  := tests/fuzz/fuzz_obj.c tests/testlib.c
FUZZ_DIFF_SRCS := tests/fuzz/fuzz_diff.c tests/fuzz/scenecode.c tests/fuzz/scenebig.c tests/testlib.c
FUZZ_MESH_SRCS := tests/fuzz/fuzz_mesh.c tests/testlib.c
FUZZ_CHECK_SRCS := tests/fuzz/fuzz_check.c
FUZZ_TEX_SRCS  := tests/fuzz/fuzz_tex.c
FUZZ_REPAIR_SRCS := tests/fuzz/fuzz_repair.c tests/testlib.c
FUZZ_DIST_SRCS := tests/fuzz/fuzz_dist.c tests/fuzz/scenebig.c tests/testlib.c
REPLAY_OBJS    := $(sort $(FUZZ_OBJ_SRCS:%.c=$(BUILD)/%.o) $(FUZZ_DIFF_SRCS:%.c=$(BUILD)/%.o) \
                  $(FUZZ_MESH_SRCS:%.c=$(BUILD)/%.o) $(FUZZ_CHECK_SRCS:%.c=$(BUILD)/%.o) \
                  $(FUZZ_TEX_SRCS:%.c=$(BUILD)/%.o) $(FUZZ_REPAIR_SRCS:%.c=$(BUILD)/%.o) \
                  $(FUZZ_DIST_SRCS:%.c=$(BUILD)/%.o) $(BUILD)/tests/fuzz/replay.o)
REPLAYS        := $(BUILD)/replay-obj $(BUILD)/replay-diff $(BUILD)/replay-mesh $(BUILD)/replay-check \
                  $(BUILD)/replay-tex $(BUILD)/replay-repair $(BUILD)/replay-dist

$(BUILD)/tests/fuzz/%.o: CFLAGS += -Itests

$(BUILD)/replay-obj: $(LIBOBJS) $(FUZZ_OBJ_SRCS:%.c=$(BUILD)/%.o) $(BUILD)/tests/fuzz/replay.o
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/replay-diff: $(LIBOBJS) $(FUZZ_DIFF_SRCS:%.c=$(BUILD)/%.o) $(BUILD)/tests/fuzz/replay.o
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/replay-mesh: $(LIBOBJS) $(FUZZ_MESH_SRCS:%.c=$(BUILD)/%.o) $(BUILD)/tests/fuzz/replay.o
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/replay-check: $(LIBOBJS) $(FUZZ_CHECK_SRCS:%.c=$(BUILD)/%.o) $(BUILD)/tests/fuzz/replay.o
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/replay-tex: $(LIBOBJS) $(FUZZ_TEX_SRCS:%.c=$(BUILD)/%.o) $(BUILD)/tests/fuzz/replay.o
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/replay-repair: $(LIBOBJS) $(FUZZ_REPAIR_SRCS:%.c=$(BUILD)/%.o) $(BUILD)/tests/fuzz/replay.o
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/replay-dist: $(LIBOBJS) $(FUZZ_DIST_SRCS:%.c=$(BUILD)/%.o) $(BUILD)/tests/fuzz/replay.o
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

# Every input that ever failed, and the seeds (tests/fuzz/replay.sh).
replay: $(REPLAYS)
	sh tests/fuzz/replay.sh $(BUILD)

# The stand-in assimp library of the sandbox's tests (tests/standin):
# its import tries what an exploited parser would. Named as the real one
# is, so that LD_LIBRARY_PATH=$(BUILD)/standin puts it in its place. (Defined before the
# rules that list it: a rule's prerequisites are expanded as it is read.)
STANDIN := $(BUILD)/standin/$(if $(AI_SONAME),$(AI_SONAME),libassimp.so.5)
$(STANDIN): tests/standin/fakeassimp.c
	@mkdir -p $(dir $@)
	$(CC) -O1 -g -Wall -Wextra -fPIC -shared -Wl,-soname,$(notdir $@) $(filter-out -D%,$(shell pkg-config --cflags assimp 2>/dev/null)) -o $@ $<

# The whole suite: unit tests (Criterion), the fuzz corpora and the
# end-to-end shell tests, the first two beside the third at a lower
# priority (tests/suite.sh: the scripts mostly wait). Both runners count
# the checks that skipped themselves (no tmux, no python3, no assimp)
# and fail on them: the run has not tested what it says.
# ZV_ALLOW_SKIPS=1 lets a local run pass with them; under CI=true
# nothing does (tests/skips.sh). The unit suites "models" (needs
# ../shared/models: make test-models), "tools" (run by tools/
# scripts) and "long" (make test-long) are not part of it.
UNIT_FILTER := !(models/*|tools/*|long/*)
test: all $(TESTBIN) $(REPLAYS) $(STANDIN) $(OCCTGEN)
	ZVIEW=$(abspath $(BIN)) ZV_STANDIN_LIB=$(abspath $(dir $(STANDIN))) ZV_OCCTGEN=$(abspath $(OCCTGEN)) \
	    sh tests/suite.sh $(TESTBIN) '$(UNIT_FILTER)' $(BUILD)

unit: $(TESTBIN)
	ZVIEW=$(abspath $(BIN)) sh tests/unit.sh $(TESTBIN) --jobs 2 --filter '$(UNIT_FILTER)'

# Every algorithm against the z-buffer on every model of ../shared/models,
# and the loaders on them (the unit suite "models").
test-models: $(TESTBIN)
	ZV_MODELS=1 sh tests/unit.sh $(TESTBIN) --jobs 2 --filter 'models/*'

# The long runs make test leaves out so that it stays within two
# minutes (.ci/run runs both): the second half of the seeded views of the
# agreement matrix and of the SIMD levels' comparisons on the assets
# (suite "long"; make test runs the first half), and the end-to-end
# scripts tests/e2e/long_*.sh: every file of the assimp test models, and
# the real terminals that cost most to start under Xvfb (kitty with its
# software OpenGL, mlterm, tmux inside xterm -ti vt340: 16 s of CPU
# together); make test keeps test_xterm.sh, a real xterm and its sixel.
test-long: all $(TESTBIN)
	sh tests/unit.sh $(TESTBIN) --jobs 2 --filter 'long/*'
	ZVIEW=$(abspath $(BIN)) E2E_PREFIX=long_ E2E_TIMES=$(abspath $(BUILD))/e2e-times-long sh tests/e2e/run.sh

# Mutation testing: each mutant of tests/mutants.txt (a small meaningful
# change to src/) applied alone to a copy of the tree, then make test's
# checks in the copy; prints what killed each and the kill rate, and
# fails when one survives (a test we lack). A mutant costs what it takes
# to kill it (tools/mutate.sh: the unit suites that killed its room's
# mutants first, each stage stopping at its first failure, e2e only for
# what the unit tests let through); a survivor has passed every check of
# make test. Long, so not part of make test, which only checks that
# every mutant still applies. MUTANTS="a b" runs only those; see
# tools/mutate.sh for the rest.
mutate:
	sh tools/mutate.sh tests/mutants.txt

# The mechanical mutants (tools/mutagen.py): PER_ROOM lines of each room
# drawn at random (SEED), one operator or constant changed on each, run
# as make mutate runs its list; then per room the mutants run, killed,
# survived and equivalent (the same code, or explained in
# tests/equivalents.txt), and the kill rate. Hours (doc/design.md:
# Mutation testing has the last run's table and time).
PER_ROOM ?= 10
SEED ?= 1
mutate-rooms:
	python3 tools/mutagen.py --per-room $(PER_ROOM) --seed $(SEED) >$(BUILD)/mutants-auto.txt
	-MUTATE_LOGS=$(BUILD)/mutate-rooms sh tools/mutate.sh $(BUILD)/mutants-auto.txt | tee $(BUILD)/mutate-rooms.log
	python3 tools/mutagen.py --summary $(BUILD)/mutate-rooms.log --list $(BUILD)/mutants-auto.txt --equivalent tests/equivalents.txt

e2e: all $(STANDIN) $(OCCTGEN)
	ZVIEW=$(abspath $(BIN)) ZV_STANDIN_LIB=$(abspath $(dir $(STANDIN))) ZV_OCCTGEN=$(abspath $(OCCTGEN)) \
	    sh tests/e2e/run.sh

# Sanitized build in its own folder, same tests, with the invariants
# on (-DZV_CHECKS turns ZV_ASSERT on: include/invariant.h).
ASAN_GOALS ?= test
asan:
	LSAN_OPTIONS=suppressions=$(CURDIR)/tests/lsan.supp:print_suppressions=0 $(MAKE) BUILD=build-asan BIN=build-asan/zview \
	    OPT="-O1 -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined -DZV_CHECKS" $(ASAN_GOALS)

# The build without assimp, in its own folder (both must compile).
noassimp:
	$(MAKE) ASSIMP=0 BUILD=build-noassimp BIN=build-noassimp/zview

# SIMD compiled out (include/simd.h), in its own folder: the scalar
# fallbacks must compile, and the unit tests pass on them alone (the
# binary first: some of them run it).
NOSIMD := BUILD=build-nosimd BIN=build-nosimd/zview EXTRA_CFLAGS="$(EXTRA_CFLAGS) -DZV_NO_SIMD"
nosimd:
	$(MAKE) $(NOSIMD) all
	$(MAKE) $(NOSIMD) unit

run: $(BIN)
	./$(BIN)

# tools/subdiv writes the many-triangle models into /tmp at bench time;
# memframes measures memory over 10,000 frames (issue 21's targets)
bench: $(BIN) $(BUILD)/subdiv $(BUILD)/memframes $(BUILD)/perturb $(BUILD)/checkbench
	SUBDIV=$(BUILD)/subdiv MEMFRAMES=$(BUILD)/memframes PERTURB=$(BUILD)/perturb sh tools/bench.sh

# What --check costs beyond loading, and its peak memory against loading
# alone (issue 19; doc/benchmarks.md: The check).
bench-check: $(BIN) $(BUILD)/checkbench $(BUILD)/subdiv
	ZVIEW=$(abspath $(BIN)) CHECKBENCH=$(BUILD)/checkbench SUBDIV=$(BUILD)/subdiv sh tools/bench-check.sh

# What the repair costs beyond loading, and its peak memory against
# loading alone (issue 30; doc/benchmarks.md: The repair).
bench-repair: $(BIN) $(BUILD)/repairbench $(BUILD)/subdiv
	ZVIEW=$(abspath $(BIN)) REPAIRBENCH=$(BUILD)/repairbench SUBDIV=$(BUILD)/subdiv sh tools/bench-repair.sh

# The whole command, writing included: zview --repair of the dragon to
# OBJ and STL and of the 5.2M model on two threads, against the goals
# (1.5 s, 10 s, 3x the memory of loading alone; doc/benchmarks.md).
bench-repair-cli: $(BIN) $(BUILD)/checkbench $(BUILD)/subdiv
	ZVIEW=$(abspath $(BIN)) CHECKBENCH=$(BUILD)/checkbench SUBDIV=$(BUILD)/subdiv sh tools/bench-repair-cli.sh

# Memory while the view turns (issue 21): resident and malloc'd bytes
# after frame 100 and after frame 10,000 of the dragon (the bundled
# models without it), each algorithm (doc/benchmarks.md: Memory over frames).
bench-memory: $(BUILD)/memframes
	MEMFRAMES=$(BUILD)/memframes sh tools/bench-memory.sh

$(BUILD)/memframes: tools/memframes.c $(LIBOBJS)
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/checkbench: tools/checkbench.c $(LIBOBJS)
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/repairbench: tools/repairbench.c $(LIBOBJS)
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

# Loading big OBJ files (issue 21): the first picture against wc -l, and
# memory per triangle, for the dragon and its 5.2M and 31M subdivisions
# (written to a temporary folder and deleted). BEFORE=path/to/zview adds
# the rows of another build, in the same run.
bench-load: $(BIN) $(BUILD)/subdiv
	SUBDIV=$(BUILD)/subdiv sh tools/bench-load.sh

# the picture while a big file loads, and keys meanwhile, in tmux (issue 21)
bench-gallery: $(BIN)
	ZVIEW=$(abspath $(BIN)) sh tools/bench-gallery.sh

bench-preview: $(BIN) $(BUILD)/subdiv
	ZVIEW=$(abspath $(BIN)) SUBDIV=$(BUILD)/subdiv sh tools/bench-preview.sh

$(BUILD)/subdiv: tools/subdiv.c
	@mkdir -p $(BUILD)
	$(CC) $(CFLAGS) -o $@ $<

# --diff against edited copies of the dragon and its 5.2M subdivision
# (issue 31; doc/benchmarks.md: The diff); tools/perturb writes them
bench-diff: $(BIN) $(BUILD)/subdiv $(BUILD)/perturb $(BUILD)/checkbench
	ZVIEW=$(abspath $(BIN)) SUBDIV=$(BUILD)/subdiv PERTURB=$(BUILD)/perturb CHECKBENCH=$(BUILD)/checkbench \
	    sh tools/bench-diff.sh

# A STEP part's first picture against f3d's on the same 1 MB file
# (issue 34; doc/benchmarks.md: STEP). Needs OCCT (build/occtgen) and f3d.
bench-step: all $(OCCTGEN)
	ZVIEW=$(abspath $(BIN)) OCCTGEN=$(OCCTGEN) sh tools/bench-step.sh

# --thickness and --overhang on the dragon (issue 32; doc/benchmarks.md)
bench-printq: $(BIN)
	ZVIEW=$(abspath $(BIN)) sh tools/bench-printq.sh

$(BUILD)/perturb: tools/perturb.c
	@mkdir -p $(BUILD)
	$(CC) $(CFLAGS) -o $@ $< -lm

# How far 256/16/8-colour pictures are from truecolor, before and after
# the perceptual quantizer (README: Colour).
COLOURERR_MODELS ?= assets/demo.obj assets/knot.obj $(wildcard ../shared/models/spot.obj ../shared/models/cornell_box.obj ../shared/models/stanford-bunny.obj)
colour-error: $(BUILD)/colourerr
	@sh tools/stamp.sh "make colour-error"
	$(BUILD)/colourerr $(COLOURERR_MODELS)

$(BUILD)/colourerr: tools/colourerr.c $(LIBOBJS)
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

# Load speed and peak memory of every format (the README's table).
bench-formats: $(BIN) $(TESTBIN)
	ZVIEW=$(abspath $(BIN)) sh tools/bench-formats.sh

# doc/views.md: the automatic first view of models of ../shared/models
# and assimp-testmodels, with what each choice measured
views: $(BIN)
	ZVIEW=$(abspath $(BIN)) sh tools/views.sh

# The point-cloud figures: a 10M-point scan sampled from the dragon
# (POINTS=N for another size), its load and frames (README: Points and
# lines).
# the face-order table of the README: hzb and hzb-octree under each --order
bench-order: $(BIN)
	ZVIEW=$(abspath $(BIN)) sh tools/bench-order.sh

bench-points: $(BIN) $(BUILD)/mkcloud
	ZVIEW=$(abspath $(BIN)) MKCLOUD=$(BUILD)/mkcloud sh tools/bench-points.sh

$(BUILD)/mkcloud: tools/mkcloud.c $(LIBOBJS)
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

# The texture targets of issue 18: the dragon and the bunny with texture
# coordinates and an image (tools/uvmodel), textured against not, and a
# 16k x 16k image's first picture (doc/benchmarks.md: Textures).
bench-pixels: $(BIN)
	ZVIEW=$(abspath $(BIN)) sh tools/bench-pixels.sh

bench-textures: $(BIN) $(BUILD)/uvmodel
	ZVIEW=$(abspath $(BIN)) UVMODEL=$(BUILD)/uvmodel sh tools/bench-textures.sh

$(BUILD)/uvmodel: tools/uvmodel.c $(LIBOBJS)
	$(CC) $(CFLAGS) -o $@ $^ $(LDLIBS)

# The loading sandbox's cost on the dragon (README: Security): sandboxed
# against --no-sandbox, medians, pinned to one core.
bench-sandbox: $(BIN)
	ZVIEW=$(abspath $(BIN)) sh tools/bench-sandbox.sh

# Issue 35's targets, one row each with its goal (doc/benchmarks.md:
# Issue 35 targets): the rows of bench-load, bench-sandbox,
# bench-textures, bench-check and bench-threads, the z-buffer against
# llvmpipe (tools/glref.c, built here only: it needs EGL and OpenGL's
# headers, tools/deps.sh's benchmark part) and zview -o against f3d.
$(BUILD)/glref: tools/glref.c
	@mkdir -p $(BUILD)
	$(CC) $(OPT) -g -std=c11 -Wall -Wextra -o $@ $< -lEGL -lGL -lm

bench-speed: $(BIN) $(BUILD)/subdiv $(BUILD)/checkbench $(BUILD)/uvmodel $(BUILD)/glref
	ZVIEW=$(abspath $(BIN)) SUBDIV=$(BUILD)/subdiv CHECKBENCH=$(BUILD)/checkbench UVMODEL=$(BUILD)/uvmodel \
	    GLREF=$(BUILD)/glref sh tools/bench-speed.sh

# The sandbox's cost a file: --check --jsonl over a folder of 10,000
# cubes (issue 34), sandboxed against --no-sandbox, wall and CPU.
bench-folder: $(BIN)
	ZVIEW=$(abspath $(BIN)) sh tools/bench-folder.sh

# Regenerate the bundled models (they are committed; this is how they were made).
assets: $(BUILD)/genassets
	$(BUILD)/genassets assets

$(BUILD)/genassets: tools/genassets.c
	@mkdir -p $(BUILD)
	$(CC) $(CFLAGS) -o $@ $< -lm

install: all
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/share/man/man1 $(DESTDIR)$(PREFIX)/share/zview \
	    $(DESTDIR)$(PREFIX)/share/bash-completion/completions $(DESTDIR)$(PREFIX)/share/zsh/site-functions
	install -m 755 $(BIN) $(DESTDIR)$(PREFIX)/bin/zview
	install -m 644 doc/zview.1 $(DESTDIR)$(PREFIX)/share/man/man1/zview.1
	install -m 644 tools/completion/zview.bash $(DESTDIR)$(PREFIX)/share/bash-completion/completions/zview
	install -m 644 tools/completion/_zview $(DESTDIR)$(PREFIX)/share/zsh/site-functions/_zview
	install -m 644 assets/demo.obj assets/demo.mtl $(DESTDIR)$(PREFIX)/share/zview/
	if [ -f $(OCCT_SHIM) ]; then install -d $(DESTDIR)$(LIBDIR) && install -m 755 $(OCCT_SHIM) $(DESTDIR)$(LIBDIR)/; fi

# ==== Fuzzing: clang + libFuzzer (sh tools/deps.sh installs both) ====
# make fuzz builds build-fuzz/fuzz-obj, fuzz-diff and fuzz-mesh; make
# fuzz-run SECONDS=N runs each for N seconds on the seeds and regression
# inputs, growing its corpus in build-fuzz/corpus/ and writing failing
# inputs to build-fuzz/artifacts/. FUZZ_FLAGS adds libFuzzer options
# (e.g. -jobs=2 -workers=2; the machine is shared, so one by default).
FUZZ_CC     ?= clang
FUZZ_BUILD  := build-fuzz
FUZZ_SAN    := -fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer
FUZZ_CFLAGS := -O1 -g $(EXTRA_CFLAGS) $(COMMON_CFLAGS) -Itests $(FUZZ_SAN)
FUZZ_LIBOBJS := $(LIBSRCS:%.c=$(FUZZ_BUILD)/%.o)
FUZZ_OBJS   := $(sort $(FUZZ_OBJ_SRCS:%.c=$(FUZZ_BUILD)/%.o) $(FUZZ_DIFF_SRCS:%.c=$(FUZZ_BUILD)/%.o) \
                      $(FUZZ_MESH_SRCS:%.c=$(FUZZ_BUILD)/%.o) $(FUZZ_CHECK_SRCS:%.c=$(FUZZ_BUILD)/%.o) \
                      $(FUZZ_TEX_SRCS:%.c=$(FUZZ_BUILD)/%.o) $(FUZZ_REPAIR_SRCS:%.c=$(FUZZ_BUILD)/%.o) \
                      $(FUZZ_DIST_SRCS:%.c=$(FUZZ_BUILD)/%.o))
SECONDS     ?= 60
FUZZ_FLAGS  ?=
# the invariants (ZV_ASSERT, include/invariant.h) are on here as in make asan:
# a fuzz input that breaks one stops where it broke
FUZZ_CFLAGS += -DZV_CHECKS

fuzz: $(FUZZ_BUILD)/fuzz-obj $(FUZZ_BUILD)/fuzz-diff $(FUZZ_BUILD)/fuzz-mesh $(FUZZ_BUILD)/fuzz-check $(FUZZ_BUILD)/fuzz-tex \
      $(FUZZ_BUILD)/fuzz-repair \
      $(FUZZ_BUILD)/fuzz-dist

# Rewrite the differential fuzzer's seed scenes (they are committed).
fuzz-seeds: $(BUILD)/mkseeds
	$(BUILD)/mkseeds tests/fuzz/seeds/diff

$(BUILD)/mkseeds: tests/fuzz/mkseeds.c tests/fuzz/scenecode.h
	@mkdir -p $(BUILD)
	$(CC) $(CFLAGS) -Itests/fuzz -o $@ $< -lm

# the library instrumented for coverage, the harnesses linked with
# libFuzzer; testlib's per-pixel compares would only flood the coverage
# maps (and cost most of the time), so it is left uninstrumented
FUZZ_COV := -fsanitize=fuzzer-no-link
$(FUZZ_BUILD)/tests/testlib.o: FUZZ_COV :=
# span's inner loops (a row's crossings kept sorted) run millions of
# compares on a large scene's wireframe: traced, each input took a
# minute. Its edges are still covered, its compares not traced.
$(FUZZ_BUILD)/src/hsr/span.o: FUZZ_COV := -fsanitize=fuzzer-no-link -fno-sanitize-coverage=trace-cmp
$(FUZZ_BUILD)/%.o: %.c
	@mkdir -p $(dir $@)
	$(FUZZ_CC) $(FUZZ_CFLAGS) $(FUZZ_COV) -c -o $@ $<

$(FUZZ_BUILD)/fuzz-obj: $(FUZZ_LIBOBJS) $(FUZZ_OBJ_SRCS:%.c=$(FUZZ_BUILD)/%.o)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer -o $@ $^ $(LDLIBS)

$(FUZZ_BUILD)/fuzz-diff: $(FUZZ_LIBOBJS) $(FUZZ_DIFF_SRCS:%.c=$(FUZZ_BUILD)/%.o)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer -o $@ $^ $(LDLIBS)

$(FUZZ_BUILD)/fuzz-mesh: $(FUZZ_LIBOBJS) $(FUZZ_MESH_SRCS:%.c=$(FUZZ_BUILD)/%.o)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer -o $@ $^ $(LDLIBS)

$(FUZZ_BUILD)/fuzz-tex: $(FUZZ_LIBOBJS) $(FUZZ_TEX_SRCS:%.c=$(FUZZ_BUILD)/%.o)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer -o $@ $^ $(LDLIBS)

$(FUZZ_BUILD)/fuzz-check: $(FUZZ_LIBOBJS) $(FUZZ_CHECK_SRCS:%.c=$(FUZZ_BUILD)/%.o)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer -o $@ $^ $(LDLIBS)

$(FUZZ_BUILD)/fuzz-repair: $(FUZZ_LIBOBJS) $(FUZZ_REPAIR_SRCS:%.c=$(FUZZ_BUILD)/%.o)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer -o $@ $^ $(LDLIBS)

$(FUZZ_BUILD)/fuzz-dist: $(FUZZ_LIBOBJS) $(FUZZ_DIST_SRCS:%.c=$(FUZZ_BUILD)/%.o)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer -o $@ $^ $(LDLIBS)

# fuzz-obj's, fuzz-mesh's and fuzz-check's stderr is closed
# (-close_fd_mask=2): the loaders' warnings would drown their output;
# crash reports still get through. make fuzz-run-mesh runs fuzz-mesh
# alone, make fuzz-run-check fuzz-check (the --check analysis on what
# the loaders make of the bytes; the mesh dictionary serves it too).
fuzz-run: fuzz fuzz-run-mesh fuzz-run-check fuzz-run-tex fuzz-run-repair fuzz-run-dist
	@mkdir -p $(FUZZ_BUILD)/corpus/obj $(FUZZ_BUILD)/corpus/diff $(FUZZ_BUILD)/artifacts/obj $(FUZZ_BUILD)/artifacts/diff
	nice $(FUZZ_BUILD)/fuzz-obj -max_total_time=$(SECONDS) -timeout=20 -print_final_stats=1 -max_len=16384 -close_fd_mask=2 \
	    -dict=tests/fuzz/obj.dict -artifact_prefix=$(FUZZ_BUILD)/artifacts/obj/ $(FUZZ_FLAGS) \
	    $(FUZZ_BUILD)/corpus/obj tests/fuzz/seeds/obj tests/fuzz/regress/obj
	nice $(FUZZ_BUILD)/fuzz-diff -max_total_time=$(SECONDS) -timeout=20 -print_final_stats=1 -max_len=8192 \
	    -artifact_prefix=$(FUZZ_BUILD)/artifacts/diff/ $(FUZZ_FLAGS) \
	    $(FUZZ_BUILD)/corpus/diff tests/fuzz/seeds/diff tests/fuzz/regress/diff

fuzz-run-mesh: $(FUZZ_BUILD)/fuzz-mesh
	@mkdir -p $(FUZZ_BUILD)/corpus/mesh $(FUZZ_BUILD)/artifacts/mesh
	nice $(FUZZ_BUILD)/fuzz-mesh -max_total_time=$(SECONDS) -timeout=20 -print_final_stats=1 -max_len=16384 -close_fd_mask=2 \
	    -dict=tests/fuzz/mesh.dict -artifact_prefix=$(FUZZ_BUILD)/artifacts/mesh/ $(FUZZ_FLAGS) \
	    $(FUZZ_BUILD)/corpus/mesh tests/fuzz/seeds/mesh tests/fuzz/regress/mesh

fuzz-run-check: $(FUZZ_BUILD)/fuzz-check
	@mkdir -p $(FUZZ_BUILD)/corpus/check $(FUZZ_BUILD)/artifacts/check
	nice $(FUZZ_BUILD)/fuzz-check -max_total_time=$(SECONDS) -timeout=20 -print_final_stats=1 -max_len=16384 -close_fd_mask=2 \
	    -dict=tests/fuzz/mesh.dict -artifact_prefix=$(FUZZ_BUILD)/artifacts/check/ $(FUZZ_FLAGS) \
	    $(FUZZ_BUILD)/corpus/check tests/fuzz/seeds/check tests/fuzz/regress/check

# the repair (issue 30): make fuzz-run-repair runs fuzz-repair alone
fuzz-run-repair: $(FUZZ_BUILD)/fuzz-repair
	@mkdir -p $(FUZZ_BUILD)/corpus/repair $(FUZZ_BUILD)/artifacts/repair
	nice $(FUZZ_BUILD)/fuzz-repair -max_total_time=$(SECONDS) -timeout=20 -print_final_stats=1 -max_len=8192 -close_fd_mask=2 \
	    -dict=tests/fuzz/mesh.dict -artifact_prefix=$(FUZZ_BUILD)/artifacts/repair/ $(FUZZ_FLAGS) \
	    $(FUZZ_BUILD)/corpus/repair tests/fuzz/seeds/repair tests/fuzz/regress/repair

# the image decoders: make fuzz-run-tex runs fuzz-tex alone
fuzz-run-tex: $(FUZZ_BUILD)/fuzz-tex
	@mkdir -p $(FUZZ_BUILD)/corpus/tex $(FUZZ_BUILD)/artifacts/tex
	nice $(FUZZ_BUILD)/fuzz-tex -max_total_time=$(SECONDS) -timeout=20 -print_final_stats=1 -max_len=65536 \
	    -artifact_prefix=$(FUZZ_BUILD)/artifacts/tex/ $(FUZZ_FLAGS) \
	    $(FUZZ_BUILD)/corpus/tex tests/fuzz/seeds/tex tests/fuzz/regress/tex

# --diff's measure against a brute-force reference: make fuzz-run-dist
fuzz-run-dist: $(FUZZ_BUILD)/fuzz-dist
	@mkdir -p $(FUZZ_BUILD)/corpus/dist $(FUZZ_BUILD)/artifacts/dist
	nice $(FUZZ_BUILD)/fuzz-dist -max_total_time=$(SECONDS) -timeout=20 -print_final_stats=1 -max_len=64 \
	    -artifact_prefix=$(FUZZ_BUILD)/artifacts/dist/ $(FUZZ_FLAGS) \
	    $(FUZZ_BUILD)/corpus/dist tests/fuzz/seeds/dist tests/fuzz/regress/dist

clean:
	rm -rf build build-asan build-noassimp build-nosimd $(FUZZ_BUILD) $(BIN) $(OCCT_SHIM)

-include $(OBJS:.o=.d) $(TOBJS:.o=.d) $(REPLAY_OBJS:.o=.d) $(FUZZ_LIBOBJS:.o=.d) $(FUZZ_OBJS:.o=.d)
