# wrenchd -- build, test, run.  `make help` lists the targets.
CC      ?= cc
CFLAGS  ?= -O2 -g
WARN     = -std=c11 -Wall -Wextra -Werror -D_POSIX_C_SOURCE=200809L
SAN      = -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all
BUILD    = build
PYTHON   = /usr/bin/python3

LIB_SRC  = $(wildcard lib/*.c)
PROTO_SRC = $(wildcard proto/*.c proto/methods/*.c)
DAEMON_SRC = $(filter-out daemon/wd_main.c,$(wildcard daemon/*.c))
WRENCHCTL_SRC = $(wildcard clients/wrenchctl/*.c)
# Each layer sees its own headers and those of the layers below it, no
# others: proto cannot include a daemon header, even by accident.  (lib/
# compiles alone: it sees no other directory's headers.)  The tests, the
# fuzzers and the physics checks see every layer; a client or a benchmark
# what it uses (proto's in-process host, wp_local.h, and below).
LIB_INCLUDES    = -Ilib
PROTO_INCLUDES  = $(LIB_INCLUDES) -Iproto
DAEMON_INCLUDES = $(PROTO_INCLUDES) -Idaemon
INCLUDES = $(DAEMON_INCLUDES)
# The unit tests, a directory per layer they test (tests/unit/LAYER/test_X.c
# -> build/tests/test_X); test_util.h, beside them, is shared.
UNIT_LAYERS = lib proto daemon client
UNIT_SRC = $(wildcard $(UNIT_LAYERS:%=tests/unit/%/test_*.c))
# Where the tests were before (build/*/tests/*.d of an older build may
# name them): nothing to make, the test is rebuilt from its new place.
tests/unit/test_%.c: ;
LIBS     = -lglpk -lm
SERVER_LIBS = -levent_pthreads -levent -lcjson -lglpk -lpthread -lm
TEST_LIBS = -lcmocka -lpthread
# The client's tests count heap allocations by wrapping malloc at link time.
WRAP_ALLOC = -Wl,--wrap=malloc,--wrap=realloc,--wrap=calloc
# Everything of the daemon but main(), in link order: wrenchd, the unit
# tests and the fuzzers link it.
DAEMON_LINK = libwrenchd.a libwrenchproto.a libwrench.a

.PHONY: layers all check check-tests unit unit-asan e2e e2e-asan check-valgrind deps clean help run demo pictures \
        physics-check validate load-check soak bench install uninstall fuzz fuzz-smoke \
        fuzz-build links check-cluster deps-freecad check-freecad freecad-link freecad-picture FORCE

all: $(BUILD)/clients/python/explain.stamp $(BUILD)/libwrench.a $(BUILD)/wrenchd $(BUILD)/wrenchctl $(BUILD)/libwrenchclient.a \
     $(BUILD)/wrenchclient-example $(BUILD)/wrenchclient-bench $(BUILD)/libwrench-example

help:
	@echo "make            build the library, wrenchd, wrenchctl, the C client and the examples in build/"
	@echo "make demo       install what is missing (deps), build, start wrenchd, put the examples,"
	@echo "                classify, stop"
	@echo "make run        wrenchd in the foreground on ./run/, the examples loaded"
	@echo "make pictures   redraw docs/pictures (the README's figures)"
	@echo "make check      install what is missing (deps), then every test: links, layers, unit (plain,"
	@echo "                ASan+UBSan), physics, load, fuzz smoke, end to end (make check-tests: the tests alone)"
	@echo "make links      every relative link of the Markdown files resolves (also in make check)"
	@echo "make layers     calls between lib, proto and daemon objects point down, no cycles (also in make check)"
	@echo "make unit       the unit tests (build/tests/); make unit-asan: under ASan+UBSan (build/asan/tests/)"
	@echo "make e2e        the end-to-end tests; make e2e-asan: against build/asan/wrenchd"
	@echo "make check-valgrind  the end-to-end tests with the daemon under valgrind"
	@echo "make check-cluster   a design as a Slurm job array on a one-node cluster it starts (root)"
	@echo "make check-freecad   the FreeCAD workbench's tests in freecadcmd, and FreeCAD's GUI under"
	@echo "                Xvfb (clients/freecad; make deps-freecad installs FreeCAD and Xvfb)"
	@echo "make validate   the full physics validation against Box2D (docs/VALIDATION.md)"
	@echo "make fuzz       each libFuzzer target for FUZZ_SECONDS (tests/fuzz/README.md);"
	@echo "                make fuzz-build builds them (build/fuzz/), make fuzz-smoke runs them briefly"
	@echo "make soak       ten minutes of mixed load, resident memory (bench/README.md)"
	@echo "make bench      the benchmarks, one table (docs/PERFORMANCE.md)"
	@echo "make install    install under PREFIX (default /usr/local), honouring DESTDIR;"
	@echo "                the configuration in SYSCONFDIR (default PREFIX/etc); the FreeCAD"
	@echo "                workbench in FREECAD_MODDIR/Wrench (default FreeCAD's own Mod directory;"
	@echo "                for a PREFIX other than /usr and /usr/local, PREFIX/share/FreeCAD/Mod)"
	@echo "make freecad-link    the checkout's workbench linked into FreeCAD's user Mod directory"
	@echo "make freecad-picture redraw docs/pictures/freecad-workbench.png and"
	@echo "                freecad-rest-buttons.png (FreeCAD under Xvfb)"
	@echo "make uninstall  remove what make install installed"
	@echo "make deps       install the Debian packages the project needs (demo and check do it first)"
	@echo "make deps-freecad    and those of check-freecad: FreeCAD (no recommends), Xvfb"
	@echo "make clean      remove build/"

# ---- variants ------------------------------------------------------------------
# The libraries, the daemon, wrenchctl and the unit tests are built in each
# variant, a directory of its own with its compiler and flags:
#   plain  $(BUILD)/        $(CC) $(CFLAGS)
#   asan   $(BUILD)/asan/   $(CC) -O1 -g, ASan + UBSan
#   fuzz   $(BUILD)/fuzz/   $(FUZZ_CC), ASan + UBSan + libFuzzer's coverage
#                           instrumentation (the fuzzers, tests/fuzz, below)
# The rules are written once, in `variant', and $(eval)ed for each.  Every
# compile writes the headers its output depends on beside it (-MMD -MP: x.o
# -> x.d, a program -> program.d), read back at the end of this file.
VARIANTS    = plain asan fuzz
plain_DIR   = $(BUILD)
plain_CC    = $(CC)
plain_FLAGS = $(CFLAGS)
asan_DIR    = $(BUILD)/asan
asan_CC     = $(CC)
asan_FLAGS  = -O1 -g $(SAN)
FUZZ_CC     = clang
fuzz_DIR    = $(BUILD)/fuzz
fuzz_CC     = $(FUZZ_CC)
fuzz_FLAGS  = -g -O1 -fsanitize=fuzzer-no-link $(SAN)
# libwrench's comparisons are of doubles and loop counts, which libFuzzer's
# comparison tracing cannot steer (the input's bytes are compared in proto/
# and the harnesses, which keep it; the constraint letters it parses are in
# the dictionary); traced, they were a quarter of the fixture target's time.
# Its edges are still counted.
$(fuzz_DIR)/lib/%.o: fuzz_FLAGS += -fno-sanitize-coverage=trace-cmp

# $(call compile,VARIANT): the compiler and flags of VARIANT; the command
# writes the header dependencies of its output.
compile = $($(1)_CC) $(WARN) $($(1)_FLAGS) -MMD -MP

# The words both clients explain a verdict with: one data file,
# clients/explain_words.txt, from which clients/explain_gen.py makes
# wrenchctl's header (for every variant's wrenchctl) and writes the Python
# client's table in place (wrenchd.py stays one standard-library file; it
# changes only when the words do).
WC_EXPLAIN = $(BUILD)/clients/wrenchctl/wc_explain.h
EXPLAIN_WORDS = clients/explain_words.txt clients/explain_gen.py
$(WC_EXPLAIN): $(EXPLAIN_WORDS)
	@mkdir -p $(dir $@)
	$(PYTHON) clients/explain_gen.py clients/explain_words.txt --c $@.tmp && mv $@.tmp $@
PY_EXPLAIN = $(BUILD)/clients/python/explain.stamp
$(PY_EXPLAIN): $(EXPLAIN_WORDS) clients/python/wrenchd.py
	@mkdir -p $(dir $@)
	$(PYTHON) clients/explain_gen.py clients/explain_words.txt --python clients/python/wrenchd.py
	@touch $@

# $(call variant,VARIANT): the rules of VARIANT, one pattern rule a kind of
# source, each with its layer's include flags (above).
define variant
$$($(1)_DIR)/lib/%.o: lib/%.c
	@mkdir -p $$(@D)
	$$(call compile,$(1)) -c $$< -o $$@

$$($(1)_DIR)/proto/%.o: proto/%.c
	@mkdir -p $$(@D)
	$$(call compile,$(1)) $$(PROTO_INCLUDES) -c $$< -o $$@

$$($(1)_DIR)/daemon/%.o: daemon/%.c
	@mkdir -p $$(@D)
	$$(call compile,$(1)) $$(DAEMON_INCLUDES) -c $$< -o $$@

$$($(1)_DIR)/clients/%.o: clients/c/%.c
	@mkdir -p $$(@D)
	$$(call compile,$(1)) -Iclients/c -c $$< -o $$@

$$($(1)_DIR)/clients/wrenchctl/%.o: clients/wrenchctl/%.c $$(WC_EXPLAIN)
	@mkdir -p $$(@D)
	$$(call compile,$(1)) $$(PROTO_INCLUDES) -Iclients/c -I$$(dir $$(WC_EXPLAIN)) -c $$< -o $$@

$$($(1)_DIR)/libwrench.a: $$(LIB_SRC:%.c=$$($(1)_DIR)/%.o)
$$($(1)_DIR)/libwrenchproto.a: $$(PROTO_SRC:%.c=$$($(1)_DIR)/%.o)
$$($(1)_DIR)/libwrenchd.a: $$(DAEMON_SRC:%.c=$$($(1)_DIR)/%.o)
$$($(1)_DIR)/libwrenchclient.a: $$($(1)_DIR)/clients/wrenchclient.o

$$($(1)_DIR)/wrenchd: $$($(1)_DIR)/daemon/wd_main.o $$(addprefix $$($(1)_DIR)/,$$(DAEMON_LINK))
	$$($(1)_CC) $$($(1)_FLAGS) $$^ $$(SERVER_LIBS) -o $$@

$$($(1)_DIR)/wrenchctl: $$(WRENCHCTL_SRC:%.c=$$($(1)_DIR)/%.o) \
        $$(addprefix $$($(1)_DIR)/,libwrenchclient.a libwrenchproto.a libwrench.a)
	$$($(1)_CC) $$($(1)_FLAGS) $$^ -lcjson -lglpk -lm -o $$@

# The unit tests (cmocka), compiled and linked in one step, each layer's
# with what that layer sees: lib's tests lib alone; proto's and the
# daemon's every layer (test_proto drives proto through the daemon's host).
$$($(1)_DIR)/tests/%: tests/unit/lib/%.c $$($(1)_DIR)/libwrench.a
	@mkdir -p $$(@D)
	$$(call compile,$(1)) $$(LIB_INCLUDES) -Itests/unit $$< $$(filter %.a,$$^) $$(LIBS) $$(TEST_LIBS) -o $$@

$$($(1)_DIR)/tests/%: tests/unit/proto/%.c $$(addprefix $$($(1)_DIR)/,$$(DAEMON_LINK))
	@mkdir -p $$(@D)
	$$(call compile,$(1)) $$(DAEMON_INCLUDES) -Itests/unit $$< $$(filter %.a,$$^) $$(SERVER_LIBS) $$(TEST_LIBS) -o $$@

$$($(1)_DIR)/tests/%: tests/unit/daemon/%.c $$(addprefix $$($(1)_DIR)/,$$(DAEMON_LINK))
	@mkdir -p $$(@D)
	$$(call compile,$(1)) $$(DAEMON_INCLUDES) -Itests/unit $$< $$(filter %.a,$$^) $$(SERVER_LIBS) $$(TEST_LIBS) -o $$@

# The client's tests link the client alone (WRAP_ALLOC above).
$$($(1)_DIR)/tests/test_client: tests/unit/client/test_client.c $$($(1)_DIR)/libwrenchclient.a
	@mkdir -p $$(@D)
	$$(call compile,$(1)) -Iclients/c $$< $$(filter %.a,$$^) $$(WRAP_ALLOC) -lcmocka -lpthread -lm -o $$@
endef

$(foreach v,$(VARIANTS),$(eval $(call variant,$(v))))


# Each library, in any variant: its objects, listed above.
$(BUILD)/%.a:
	rm -f $@ && ar rcs $@ $^

# The daemon reads $(SYSCONFDIR)/wrenchd/wrenchd.conf when no --config is
# given (SYSCONFDIR: see install below), so the path is compiled into
# wd_main.o, which $(BUILD)/sysconfdir rebuilds whenever SYSCONFDIR changes:
# a build reads the configuration of the prefix it was built for.
WD_MAIN_OBJ = $(foreach v,$(VARIANTS),$($(v)_DIR)/daemon/wd_main.o)
$(WD_MAIN_OBJ): $(BUILD)/sysconfdir
$(WD_MAIN_OBJ): WARN += -DWD_SYSCONFDIR='"$(SYSCONFDIR)"'

$(BUILD)/sysconfdir: FORCE
	@mkdir -p $(dir $@)
	@echo '$(SYSCONFDIR)' | cmp -s - $@ || echo '$(SYSCONFDIR)' > $@

FORCE:

# ---- the examples (plain only) ------------------------------------------------
# build/wrenchclient-example and build/wrenchclient-bench, from clients/c/.
$(BUILD)/wrenchclient-%: clients/c/%.c $(BUILD)/libwrenchclient.a
	$(call compile,plain) -Iclients/c $< $(filter %.a,$^) -lm -o $@

$(BUILD)/libwrench-example: examples/libwrench_example.c $(BUILD)/libwrench.a
	$(call compile,plain) -Ilib $< $(BUILD)/libwrench.a $(LIBS) -o $@

# ---- unit tests ------------------------------------------------------------------
UNIT_BIN = $(patsubst %.c,$(plain_DIR)/tests/%,$(notdir $(UNIT_SRC)))
ASAN_BIN = $(patsubst %.c,$(asan_DIR)/tests/%,$(notdir $(UNIT_SRC)))

# An LD_PRELOAD library the fault tests use to fail writes to a directory.
$(BUILD)/tests/libfail_storage.so: tests/faults/fail_storage.c
	@mkdir -p $(dir $@)
	$(CC) -std=c11 -Wall -Wextra -Werror -O2 -fPIC -shared -MMD -MP $< -ldl -o $@

unit: $(UNIT_BIN)
	@tests/run-unit $(UNIT_BIN)

unit-asan: $(ASAN_BIN)
	@ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
	    tests/run-unit $(ASAN_BIN)

# ---- end-to-end tests (pytest; each test starts its own daemon) ----------
PYTEST = $(PYTHON) -m pytest -q -p no:cacheprovider

# tests/e2e/test_access.py runs the ASan daemon even here: a write past a
# buffer the kernel fills is seen only by ASan's interceptor.
e2e: all $(BUILD)/asan/wrenchd $(BUILD)/tests/libfail_storage.so
	$(PYTEST) tests/e2e

e2e-asan: all $(BUILD)/asan/wrenchd $(BUILD)/tests/libfail_storage.so
	ASAN_OPTIONS=detect_leaks=1 WRENCHD=$(CURDIR)/$(BUILD)/asan/wrenchd $(PYTEST) tests/e2e

# The end-to-end tests with the daemon under valgrind memcheck: zero errors,
# zero leaks (minutes; not part of make check).
check-valgrind: all $(BUILD)/tests/libfail_storage.so
	WRENCHD_WRAPPER="valgrind --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite,indirect --show-leak-kinds=definite,indirect" \
	    $(PYTEST) tests/e2e

# Every relative link (and #anchor) of the tracked Markdown files resolves
# inside the repository; a fraction of a second.
links:
	@$(PYTHON) tests/check-links

# Calls between lib's, proto's and daemon's objects point only downwards,
# with no cycle inside a layer (docs/ARCHITECTURE.md); read from the build.
layers: all
	@$(PYTHON) tests/check-layers $(BUILD)

# make check installs what is missing first (deps), then runs every test;
# the last line printed is the test runner's closing line (CI reads it).
check: deps
	@$(MAKE) --no-print-directory check-tests

check-tests: links layers unit unit-asan physics-check load-check fuzz-smoke e2e-asan e2e

# A single-node Slurm cluster started by the test itself runs a design as a
# job array (examples/design-array.sbatch); the merged shards must equal one
# unsharded run.  As root, with slurm-wlm and munge (make deps).
check-cluster: $(plain_DIR)/wrenchctl
	@tests/cluster/check-cluster

# The FreeCAD workbench (clients/freecad): its tests run in FreeCAD's own
# Python (freecadcmd) against build/wrenchd, and one starts FreeCAD's GUI
# under Xvfb (tests/freecad).  make deps-freecad installs FreeCAD and Xvfb.
# The last line printed is pytest's.
FREECADCMD ?= freecadcmd

check-freecad: $(BUILD)/wrenchd
	@command -v $(FREECADCMD) >/dev/null || { \
	    echo "make check-freecad: no $(FREECADCMD): make deps-freecad installs FreeCAD"; exit 2; }
	$(FREECADCMD) tests/freecad/run.py

# The README's screenshots of the workbench, from the GUI test.
freecad-picture: $(BUILD)/wrenchd
	WRENCH_PICTURE=$(CURDIR)/docs/pictures/freecad-workbench.png \
	    WRENCH_PICTURE_BUTTONS=$(CURDIR)/docs/pictures/freecad-rest-buttons.png WRENCH_PYTEST_ARGS="-k gui" \
	    $(FREECADCMD) tests/freecad/run.py

# The checkout's workbench in FreeCAD's user Mod directory (FreeCAD 0.20:
# ~/.local/share/FreeCAD/Mod), as a symbolic link: FreeCAD then loads it
# from here at every start.
FREECAD_USER_MODDIR ?= $(HOME)/.local/share/FreeCAD/Mod

freecad-link:
	@mkdir -p $(FREECAD_USER_MODDIR)
	@if [ -e $(FREECAD_USER_MODDIR)/Wrench ] && [ ! -L $(FREECAD_USER_MODDIR)/Wrench ]; then \
	    echo "make freecad-link: $(FREECAD_USER_MODDIR)/Wrench exists and is no link: remove it first"; \
	    exit 1; fi
	ln -sfn $(CURDIR)/clients/freecad $(FREECAD_USER_MODDIR)/Wrench

# ---- running it ------------------------------------------------------------

# make demo installs what is missing first (deps), so that it is the one
# command a fresh checkout needs.
demo: deps
	@$(MAKE) --no-print-directory all
	@$(PYTHON) examples/demo.py

run: all
	$(BUILD)/wrenchd --socket ./run/wrenchd.sock --state-dir ./run \
	    $(addprefix --load ,$(wildcard examples/*.json))

# The README's pictures, drawn by wrenchctl (tests/e2e/test_pictures.py
# checks they are current).
pictures: $(BUILD)/wrenchctl
	@mkdir -p docs/pictures
	$(BUILD)/wrenchctl --local push examples/plate-3-2-1.json --set strong --svg docs/pictures/plate-3-2-1-push-strong.svg >/dev/null
	$(BUILD)/wrenchctl --local push examples/plate-chamfered.json --set both --svg docs/pictures/plate-chamfered-push-both.svg >/dev/null
	$(BUILD)/wrenchctl --local push examples/disc-corner.json --set goal --svg docs/pictures/disc-corner-push-goal.svg >/dev/null
	$(BUILD)/wrenchctl --local push examples/bracket.json --set both --push-on all --svg docs/pictures/bracket-push-both.svg >/dev/null
	$(BUILD)/wrenchctl --local push examples/notched-plate.json --set strong --finger-radius 4 --svg docs/pictures/notched-plate-push-strong-r4.svg >/dev/null
	$(BUILD)/wrenchctl --local sweep examples/plate-chamfered.json --push both --range 0:1 --svg docs/pictures/plate-chamfered-sweep-both.svg >/dev/null
	$(BUILD)/wrenchctl --local design examples/bracket.json --spacing 10 --top 3 --svg docs/pictures/bracket-designs.svg >/dev/null
	$(BUILD)/wrenchctl --local locate examples/bracket.json --tolerance 0.02 --feature hole=30,30 --feature slot=85,30 --feature drill=110,50 --svg docs/pictures/bracket-locate.svg >/dev/null
	@# the README's walk-through from a DXF sheet (ezdxf)
	$(PYTHON) examples/sheet_dxf.py $(BUILD)/sheet.dxf
	$(PYTHON) examples/dxf_fixture.py $(BUILD)/sheet.dxf $(BUILD)/bracket.json 2>/dev/null
	cd $(BUILD) && ./wrenchctl --local design bracket.json --spacing 10 --top 3 \
	    --emit-fixture 1 bracket-design.json >/dev/null
	$(BUILD)/wrenchctl --local push $(BUILD)/bracket-design.json --set both --svg docs/pictures/sheet-bracket-push-both.svg >/dev/null
	$(BUILD)/wrenchctl --local push-force examples/bracket-upright.json $(foreach x,20 40 60 80 100,--case 'x$(x):gravity=9810@180;force=30,-40@$(x),60') --push-on all --svg docs/pictures/bracket-upright-push-force.svg >/dev/null
	$(BUILD)/wrenchctl --local force examples/plate-3-2-1-buttons.json --push 2.4663,2@-0.42262,-0.90631 --case none:wrench=0,0,0 --sets goal --svg docs/pictures/plate-3-2-1-buttons.svg >/dev/null

# ---- load and soak (bench) ----
# bench/README.md says what these measure and how to read their output.
BENCH_LOAD   = $(BUILD)/bench/load

# The load generator is four files: the driver (load.c), the table of
# requests (load_requests.c), one client (load_client.c) and what they share
# (load_util.c); bench/README.md says what each does.  One program from
# several sources, so its headers are its directory's and the layers'.
BENCH_LOAD_SRC = bench/load.c bench/load_requests.c bench/load_client.c bench/load_util.c
$(BENCH_LOAD): $(BENCH_LOAD_SRC) $(wildcard bench/*.h proto/*.h lib/*.h)
	@mkdir -p $(dir $@)
	$(CC) $(WARN) $(CFLAGS) $(PROTO_INCLUDES) $(BENCH_LOAD_SRC) $(filter %.a,$^) $(BENCH_LIBS) -o $@

BENCH_NUMBER = $(BUILD)/bench/number
BENCH_MICRO  = $(BUILD)/bench/micro
BENCH_SOCKET = $(BUILD)/bench/socket
BENCH_LOCATE = $(BUILD)/bench/locate
BENCH_TOLERANCE = $(BUILD)/bench/tolerance
BENCH_SEGMENTS = $(BUILD)/bench/segments
BENCH_ANSWER = $(BUILD)/bench/answer
BENCH_REGIONS = $(BUILD)/bench/regions
BENCH_LATTICE = $(BUILD)/bench/lattice

# bench/X.c -> build/bench/X, linked with the libraries it lists below.
# number: the cost of writing a number, old (snprintf + strtod) against new
# (proto/wp_number.c): prints figures, asserts nothing.
$(BUILD)/bench/%: bench/%.c
	@mkdir -p $(dir $@)
	$(call compile,plain) $(PROTO_INCLUDES) $< $(filter %.a,$^) $(BENCH_LIBS) -o $@

$(BENCH_LOAD) $(BENCH_MICRO) $(BENCH_LOCATE) $(BENCH_ANSWER) $(BENCH_TOLERANCE): $(BUILD)/libwrenchproto.a $(BUILD)/libwrench.a
$(BENCH_SEGMENTS) $(BENCH_REGIONS) $(BENCH_LATTICE): $(BUILD)/libwrench.a
$(BENCH_SEGMENTS) $(BENCH_REGIONS) $(BENCH_LATTICE): BENCH_LIBS = -lglpk -lm
$(BENCH_NUMBER): $(BUILD)/libwrenchproto.a
$(BENCH_LOAD): BENCH_LIBS = -lcjson -lglpk -lpthread -lm
$(BENCH_MICRO) $(BENCH_LOCATE) $(BENCH_ANSWER) $(BENCH_TOLERANCE): BENCH_LIBS = -lcjson -lglpk -lm
$(BENCH_NUMBER): BENCH_LIBS = -lm
$(BENCH_SOCKET): BENCH_LIBS = -lpthread -lm

# The baseline the sweep figures are set beside (bench/sweep.py) and the
# answers compared with (bench/compare_sweeps.py): the revision
# BASELINE_REVISION built from git in build/baseline/, with bench/answer.c
# linked against its libraries.
BASELINE_REVISION = a296b40
BASELINE_ANSWER = $(BUILD)/baseline/answer
BASELINE_DAEMON = $(BUILD)/baseline/src/build/wrenchd
$(BUILD)/baseline/src/Makefile:
	rm -rf $(BUILD)/baseline/src && mkdir -p $(BUILD)/baseline/src
	git archive $(BASELINE_REVISION) | tar -x -C $(BUILD)/baseline/src
$(BASELINE_DAEMON): $(BUILD)/baseline/src/Makefile
	$(MAKE) -C $(BUILD)/baseline/src build/wrenchd
$(BASELINE_ANSWER): bench/answer.c bench/bench_util.h $(BUILD)/baseline/src/Makefile
	$(MAKE) -C $(BUILD)/baseline/src build/libwrench.a build/libwrenchproto.a
	$(call compile,plain) -I$(BUILD)/baseline/src/lib -I$(BUILD)/baseline/src/proto -Ibench bench/answer.c \
	    $(BUILD)/baseline/src/build/libwrenchproto.a $(BUILD)/baseline/src/build/libwrench.a \
	    -lcjson -lglpk -lm -o $@

# The benchmarks, one table (docs/PERFORMANCE.md); figures, never a
# test.  Run it on a quiet machine.
bench: all $(BENCH_MICRO) $(BENCH_SOCKET) $(BENCH_NUMBER) $(BENCH_SEGMENTS) $(BENCH_LOCATE) \
       $(BENCH_ANSWER) $(BASELINE_ANSWER) $(BASELINE_DAEMON) $(BENCH_REGIONS) $(BENCH_LATTICE) \
       $(BENCH_TOLERANCE)
	@bench/run


# A fresh daemon, 32 clients x 1000 lines, every answer checked: nothing lost,
# nothing wrong, exit status 0 on SIGTERM.  The last lines are the summary.
load-check: $(BUILD)/wrenchd $(BENCH_LOAD)
	@bench/load-check $(BUILD)/wrenchd $(BENCH_LOAD)

# A benchmark, not a test: SOAK_SECONDS (default 600) of mixed load on an
# 8 MiB cache; resident memory at start, peak and end.
soak: $(BUILD)/wrenchd $(BENCH_LOAD)
	@$(PYTHON) bench/soak --wrenchd $(BUILD)/wrenchd --load $(BENCH_LOAD)
# ---- end of load and soak ----

# ---- fuzzing (tests/fuzz) ----
# libFuzzer targets (clang, -fsanitize=fuzzer,address,undefined) linking
# the fuzz variant of lib/, proto/ and daemon/ (but main), built with
# coverage instrumentation in build/fuzz/ (see variants above).
# tests/fuzz/README.md says what each target checks.  make fuzz: each target
# for FUZZ_SECONDS on a copy of the corpus (build/fuzz/corpus-work); make
# fuzz-smoke: the committed corpus and regressions, then FUZZ_SMOKE_RUNS
# mutations of each, seed 1.
FUZZ_TARGETS  = request fixture parse
FUZZ_BIN      = $(addprefix $(fuzz_DIR)/fuzz_,$(FUZZ_TARGETS))
FUZZ_SECONDS ?= 60
FUZZ_SMOKE_RUNS ?= 10000

$(fuzz_DIR)/fuzz_%: tests/fuzz/fuzz_%.c $(addprefix $(fuzz_DIR)/,$(DAEMON_LINK))
	$(call compile,fuzz) $(INCLUDES) -fsanitize=fuzzer $< $(filter %.a,$^) $(SERVER_LIBS) -o $@

fuzz-build: $(FUZZ_BIN)

fuzz: $(FUZZ_BIN)
	@FUZZ_DIR=$(fuzz_DIR) tests/fuzz/run-fuzz fuzz $(FUZZ_SECONDS) $(FUZZ_TARGETS)

fuzz-smoke: $(FUZZ_BIN)
	@FUZZ_DIR=$(fuzz_DIR) tests/fuzz/run-fuzz smoke $(FUZZ_SMOKE_RUNS) $(FUZZ_TARGETS)
# ---- end of fuzzing ----

# ---- install -------------------------------------------------------------------
# Everything goes under $(DESTDIR)$(PREFIX), the configuration too: it is
# $(SYSCONFDIR)/wrenchd/wrenchd.conf, and the daemon built here reads it by
# default.  For the system's /etc: make install PREFIX=/usr SYSCONFDIR=/etc.
PREFIX    ?= /usr/local
SYSCONFDIR ?= $(PREFIX)/etc
DESTDIR   ?=
VERSION    = $(shell sed -n 's/^\#define WR_VERSION "\(.*\)"/\1/p' lib/wrench.h)
PYVERSION  = $(shell $(PYTHON) -c 'import sys; print("%d.%d" % sys.version_info[:2])')
# Where Debian's python3 looks: /usr/lib/python3/dist-packages for /usr,
# /usr/local/lib/python3.X/dist-packages for /usr/local.
PYTHONDIR ?= $(if $(filter /usr,$(PREFIX)),$(PREFIX)/lib/python3/dist-packages,$(PREFIX)/lib/python$(PYVERSION)/dist-packages)
# The FreeCAD workbench goes to FREECAD_MODDIR/Wrench.  For PREFIX /usr or
# /usr/local, by default the Mod directory of the FreeCAD installed here (its
# FreeCAD.getResourceDir(); Debian's: /usr/share/freecad/Mod), where it looks
# whatever the prefix; for any other PREFIX, PREFIX/share/FreeCAD/Mod, which
# for PREFIX=~/.local is FreeCAD's user Mod directory.  The workbench holds
# its own copy of wrenchd.py, so that it works whichever Python directory
# PREFIX gives.
FREECAD_SYSTEM_MODDIR = $(or $(shell $(FREECADCMD) -c \
    'import FreeCAD; print(FreeCAD.getResourceDir() + "Mod")' 2>/dev/null | tail -n 1),/usr/share/freecad/Mod)
FREECAD_MODDIR ?= $(if $(filter /usr /usr/local,$(PREFIX)),$(FREECAD_SYSTEM_MODDIR),$(PREFIX)/share/FreeCAD/Mod)
# The Python client's modules; the workbench's copy holds those it imports
# (wrenchd_arcs.py: the bulges and curves by arcs it shares with the DXF
# reader).
PYTHON_MODULES = wrenchd.py wrenchd_dxf.py wrenchd_arcs.py
WORKBENCH_CLIENT = wrenchd.py wrenchd_arcs.py
WORKBENCH_FILES = Init.py InitGui.py wrench_freecad.py wrench_outline.py wrench_objects.py \
                  wrench_view.py wrench_supports.py wrench_commands.py \
                  $(patsubst clients/freecad/%,%,$(wildcard clients/freecad/Resources/icons/*.svg))
# Every lib header but the internal one: wrench.h includes them all, so a
# header left out of the install breaks every program that uses the lib.
PUBLIC_HEADERS = lib/wrench.h $(filter-out lib/wr_internal.h,$(wildcard lib/wr_*.h)) \
                 clients/c/wrenchclient.h
INSTALLED = $(PREFIX)/sbin/wrenchd $(PREFIX)/bin/wrenchctl \
    $(PREFIX)/lib/libwrench.a $(PREFIX)/lib/libwrenchclient.a \
    $(addprefix $(PREFIX)/include/wrench/,$(notdir $(PUBLIC_HEADERS))) \
    $(PREFIX)/lib/pkgconfig/wrench.pc $(PREFIX)/lib/pkgconfig/wrenchclient.pc \
    $(PREFIX)/lib/systemd/system/wrenchd.service $(PREFIX)/lib/systemd/system/wrenchd.socket \
    $(PREFIX)/lib/sysusers.d/wrenchd.conf \
    $(PREFIX)/share/man/man1/wrenchctl.1 $(PREFIX)/share/man/man8/wrenchd.8 \
    $(addprefix $(PYTHONDIR)/,$(PYTHON_MODULES)) \
    $(addprefix $(PREFIX)/share/wrenchd/examples/,$(notdir $(wildcard examples/*.json)))
# The installed configuration file, and the shipped one with its paths.
CONFIG_FILE = $(SYSCONFDIR)/wrenchd/wrenchd.conf
CONFIG_PATHS = -e 's|@CONFIG_FILE@|$(CONFIG_FILE)|' -e 's|@PREFIX@|$(PREFIX)|'

install: all
	install -d $(DESTDIR)$(PREFIX)/sbin $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/lib/pkgconfig \
	    $(DESTDIR)$(PREFIX)/include/wrench $(DESTDIR)$(PREFIX)/lib/systemd/system \
	    $(DESTDIR)$(PREFIX)/lib/sysusers.d $(DESTDIR)$(PREFIX)/share/man/man1 \
	    $(DESTDIR)$(PREFIX)/share/man/man8 $(DESTDIR)$(PYTHONDIR) \
	    $(DESTDIR)$(PREFIX)/share/wrenchd/examples $(DESTDIR)$(SYSCONFDIR)/wrenchd
	install -m 0755 $(BUILD)/wrenchd $(DESTDIR)$(PREFIX)/sbin/wrenchd
	install -m 0755 $(BUILD)/wrenchctl $(DESTDIR)$(PREFIX)/bin/wrenchctl
	install -m 0644 $(BUILD)/libwrench.a $(BUILD)/libwrenchclient.a $(DESTDIR)$(PREFIX)/lib/
	install -m 0644 $(PUBLIC_HEADERS) $(DESTDIR)$(PREFIX)/include/wrench/
	for pc in lib/wrench.pc.in clients/c/wrenchclient.pc.in; do \
	    sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(VERSION)|' $$pc \
	        > $(DESTDIR)$(PREFIX)/lib/pkgconfig/$$(basename $$pc .in); done
	install -m 0644 systemd/wrenchd.socket $(DESTDIR)$(PREFIX)/lib/systemd/system/
	install -m 0644 systemd/wrenchd.sysusers $(DESTDIR)$(PREFIX)/lib/sysusers.d/wrenchd.conf
	install -m 0644 clients/wrenchctl/wrenchctl.1 $(DESTDIR)$(PREFIX)/share/man/man1/
	install -m 0644 daemon/wrenchd.8 $(DESTDIR)$(PREFIX)/share/man/man8/
	install -m 0644 $(addprefix clients/python/,$(PYTHON_MODULES)) $(DESTDIR)$(PYTHONDIR)/
	install -m 0644 examples/*.json $(DESTDIR)$(PREFIX)/share/wrenchd/examples/
	@# The configuration is the administrator's: never overwritten.
	test -e $(DESTDIR)$(CONFIG_FILE) || { sed $(CONFIG_PATHS) systemd/wrenchd.conf \
	    > $(DESTDIR)$(CONFIG_FILE) && chmod 0644 $(DESTDIR)$(CONFIG_FILE); }
	@# MemoryMax= from the limits in that file (systemd/memory-max says how).
	memory_max=$$(systemd/memory-max $(BUILD)/wrenchd $(DESTDIR)$(CONFIG_FILE)) && \
	sed -e 's|@SBINDIR@|$(PREFIX)/sbin|' -e "s|@MEMORY_MAX@|$$memory_max|" $(CONFIG_PATHS) \
	    systemd/wrenchd.service > $(DESTDIR)$(PREFIX)/lib/systemd/system/wrenchd.service
	@# The FreeCAD workbench, with its copy of the Python client's modules.
	workbench="$(DESTDIR)$(FREECAD_MODDIR)/Wrench" && \
	install -d "$$workbench/Resources/icons" && \
	for f in $(WORKBENCH_FILES); do install -m 0644 clients/freecad/$$f "$$workbench/$$f"; done && \
	for f in $(WORKBENCH_CLIENT); do install -m 0644 clients/python/$$f "$$workbench/$$f"; done

uninstall:
	rm -f $(addprefix $(DESTDIR),$(INSTALLED))
	workbench="$(DESTDIR)$(FREECAD_MODDIR)/Wrench" && \
	for f in $(WORKBENCH_FILES) $(WORKBENCH_CLIENT); do rm -f "$$workbench/$$f"; done && \
	rm -rf "$$workbench/__pycache__" && \
	{ rmdir "$$workbench/Resources/icons" "$$workbench/Resources" "$$workbench" 2>/dev/null || true; }
	-rmdir $(DESTDIR)$(PREFIX)/include/wrench $(DESTDIR)$(PREFIX)/share/wrenchd/examples \
	    $(DESTDIR)$(PREFIX)/share/wrenchd 2>/dev/null
	@# The configuration goes only if it is still the one shipped.
	-sed $(CONFIG_PATHS) systemd/wrenchd.conf | cmp -s - $(DESTDIR)$(CONFIG_FILE) && \
	    rm -f $(DESTDIR)$(CONFIG_FILE) && rmdir $(DESTDIR)$(SYSCONFDIR)/wrenchd

# ---- physics validation (tests/physics) ----
# wrenchd's answers against Box2D (docs/VALIDATION.md).  physics-check is the
# quick run make check includes; validate is the full one, with the table.
# A fixture on supports is left out: this simulation floats the part, and
# its buttons' friction (docs/MODEL.md section 11) is not simulated here.
PHYSICS_FIXTURES = $(filter-out examples/plate-3-2-1-buttons.json,$(wildcard examples/*.json)) \
                   $(wildcard tests/physics/fixtures/*.json)
PHYSICS_CXXFLAGS = -std=c++17 -Wall -Wextra -Werror -O2 -g

$(BUILD)/physics-validate: tests/physics/validate.cpp $(BUILD)/libwrenchproto.a $(BUILD)/libwrench.a
	@mkdir -p $(dir $@)
	$(CXX) $(PHYSICS_CXXFLAGS) -MMD -MP $(INCLUDES) $$(pkg-config --cflags box2d) $< \
	    $(BUILD)/libwrenchproto.a $(BUILD)/libwrench.a $$(pkg-config --libs box2d) -lcjson -lglpk -lm -o $@

# A part on a base plate: each support a b2FrictionJoint (tests/physics/supports.cpp).
$(BUILD)/physics-supports: tests/physics/supports.cpp $(BUILD)/libwrench.a
	@mkdir -p $(dir $@)
	$(CXX) $(PHYSICS_CXXFLAGS) -MMD -MP $(LIB_INCLUDES) $$(pkg-config --cflags box2d) $< \
	    $(BUILD)/libwrench.a $$(pkg-config --libs box2d) -lglpk -lm -o $@

physics-check: $(BUILD)/physics-validate $(BUILD)/physics-supports
	$(BUILD)/physics-validate --quick $(PHYSICS_FIXTURES)
	$(BUILD)/physics-validate --quick --tolerance 0.03,0.5 examples/plate-chamfered.json
	$(BUILD)/physics-validate --quick --tolerance 0.05,0.2 examples/bracket.json
	$(BUILD)/physics-supports

validate: $(BUILD)/physics-validate
	$(BUILD)/physics-validate --full $(PHYSICS_FIXTURES)
# ---- end of physics validation ----

# ---- dependencies --------------------------------------------------------
DEB_PACKAGES = build-essential pkg-config libglpk-dev libevent-dev libcjson-dev \
               libcmocka-dev python3 python3-pytest libbox2d-dev systemd clang libclang-rt-14-dev python3-scipy \
               python3-ezdxf slurm-wlm munge

# FreeCAD for make check-freecad, apart: make check does not need it.
# freecadcmd and the GUI need no recommended package (about 1.5 minutes to
# install); xvfb-run gives the GUI a display, xauth is what it needs.
FREECAD_PACKAGES = freecad-python3 xvfb xauth

# $(call apt_install,PACKAGES,APT-GET OPTIONS): install those missing, with
# sudo unless root; on failure once more after apt-get update.  One
# dpkg-query asks for all of them (when all are present, that is all it
# costs: make demo and make check begin with it).  Without dpkg-query (not
# Debian) it says what to install and goes on.
define apt_install
	@if ! command -v dpkg-query >/dev/null; then \
	    echo "make $@: no dpkg-query (not Debian): install the equivalents of $(strip $(1))"; exit 0; fi; \
	installed=" $$(dpkg-query -W -f='$${Package} $${Status}\n' $(1) 2>/dev/null | \
	    awk '/ install ok installed$$/ {print $$1}' | tr '\n' ' ') "; \
	missing=""; for p in $(1); do \
	    case "$$installed" in *" $$p "*) ;; *) missing="$$missing $$p";; esac; \
	done; \
	if [ -z "$$missing" ]; then echo "make $@: every Debian package is present"; exit 0; fi; \
	echo "make $@: installing$$missing"; \
	sudo=""; [ "$$(id -u)" -eq 0 ] || sudo=sudo; \
	$$sudo apt-get install -y $(2) $$missing || { $$sudo apt-get update && $$sudo apt-get install -y $(2) $$missing; }
endef

deps:
	$(call apt_install,$(DEB_PACKAGES))

deps-freecad:
	$(call apt_install,$(FREECAD_PACKAGES),--no-install-recommends)

clean:
	rm -rf $(BUILD)

# ---- header dependencies -----------------------------------------------------
# What each compile wrote (-MMD -MP above), in every variant's directory.
-include $(wildcard $(addsuffix *.d,$(BUILD)/ $(BUILD)/*/ $(BUILD)/*/*/ $(BUILD)/*/*/*/))
