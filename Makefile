# wrenchd -- build, test, run.  `make help` lists the targets.
CC      ?= cc
CFLAGS  ?= -O2 -g
WARN     = -std=c11 -Wall -Wextra -Werror -D_POSIX_C_SOURCE=200809L
SAN      = -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all
BUILD    = build
PYTHON   = /usr/bin/python3

LIB_SRC  = $(wildcard lib/*.c)
LIB_HDR  = $(wildcard lib/*.h)
PROTO_SRC = $(wildcard proto/*.c)
PROTO_HDR = $(wildcard proto/*.h)
DAEMON_SRC = $(filter-out daemon/wd_main.c,$(wildcard daemon/*.c))
DAEMON_HDR = $(wildcard daemon/*.h)
INCLUDES = -Ilib -Iproto -Idaemon
UNIT_SRC = $(wildcard tests/unit/test_*.c)
UNIT_BIN = $(patsubst tests/unit/%.c,$(BUILD)/tests/%,$(UNIT_SRC))
ASAN_BIN = $(patsubst tests/unit/%.c,$(BUILD)/asan/tests/%,$(UNIT_SRC))
LIBS     = -lglpk -lm
SERVER_LIBS = -levent_pthreads -levent -lcjson -lglpk -lpthread -lm
TEST_LIBS = -lcmocka -lpthread

.PHONY: all check unit unit-asan e2e e2e-asan check-valgrind deps clean help run demo pictures \
        physics-check validate load-check soak bench install uninstall fuzz fuzz-smoke \
        fuzz-build FORCE

all: $(BUILD)/libwrench.a $(BUILD)/wrenchd $(BUILD)/wrenchctl $(BUILD)/libwrenchclient.a \
     $(BUILD)/wrenchclient-example $(BUILD)/wrenchclient-bench $(BUILD)/libwrench-example

help:
	@echo "make            build build/libwrench.a"
	@echo "make demo       build, start wrenchd, put the examples, classify, stop"
	@echo "make run        wrenchd in the foreground on ./run/, the examples loaded"
	@echo "make pictures   redraw docs/pictures (the README's figures)"
	@echo "make check      every test: unit (plain, ASan+UBSan), physics, load, fuzz smoke, end to end"
	@echo "make check-valgrind  the end-to-end tests with the daemon under valgrind"
	@echo "make validate   the full physics validation against Box2D (docs/VALIDATION.md)"
	@echo "make fuzz       each libFuzzer target for FUZZ_SECONDS (tests/fuzz/README.md)"
	@echo "make soak       ten minutes of mixed load, resident memory (bench/README.md)"
	@echo "make bench      the benchmarks, one table (docs/PERFORMANCE.md)"
	@echo "make install    install under PREFIX (default /usr/local), honouring DESTDIR;"
	@echo "                the configuration in SYSCONFDIR (default PREFIX/etc)"
	@echo "make uninstall  remove what make install installed"
	@echo "make deps       install the Debian packages the project needs"
	@echo "make clean      remove build/"

# ---- the library ----------------------------------------------------------
$(BUILD)/lib/%.o: lib/%.c $(LIB_HDR)
	@mkdir -p $(dir $@)
	$(CC) $(WARN) $(CFLAGS) -c $< -o $@

$(BUILD)/libwrench.a: $(patsubst lib/%.c,$(BUILD)/lib/%.o,$(LIB_SRC))
	rm -f $@ && ar rcs $@ $^

$(BUILD)/asan/lib/%.o: lib/%.c $(LIB_HDR)
	@mkdir -p $(dir $@)
	$(CC) $(WARN) -O1 -g $(SAN) -c $< -o $@

$(BUILD)/asan/libwrench.a: $(patsubst lib/%.c,$(BUILD)/asan/lib/%.o,$(LIB_SRC))
	rm -f $@ && ar rcs $@ $^

# ---- the protocol layer and the daemon --------------------------------------
$(BUILD)/proto/%.o: proto/%.c $(PROTO_HDR) $(LIB_HDR)
	@mkdir -p $(dir $@)
	$(CC) $(WARN) $(CFLAGS) $(INCLUDES) -c $< -o $@

$(BUILD)/daemon/%.o: daemon/%.c $(DAEMON_HDR) $(PROTO_HDR) $(LIB_HDR)
	@mkdir -p $(dir $@)
	$(CC) $(WARN) $(CFLAGS) $(INCLUDES) -c $< -o $@

$(BUILD)/libwrenchproto.a: $(patsubst %.c,$(BUILD)/%.o,$(PROTO_SRC))
	rm -f $@ && ar rcs $@ $^

# Everything of the daemon but main(): tests and fuzzers link it too.
$(BUILD)/libwrenchd.a: $(patsubst %.c,$(BUILD)/%.o,$(DAEMON_SRC))
	rm -f $@ && ar rcs $@ $^

$(BUILD)/wrenchd: $(BUILD)/daemon/wd_main.o $(BUILD)/libwrenchd.a $(BUILD)/libwrenchproto.a $(BUILD)/libwrench.a
	$(CC) $(CFLAGS) $^ $(SERVER_LIBS) -o $@

# ---- clients -----------------------------------------------------------------
$(BUILD)/clients/%.o: clients/c/%.c clients/c/wrenchclient.h
	@mkdir -p $(dir $@)
	$(CC) $(WARN) $(CFLAGS) -Iclients/c -c $< -o $@

$(BUILD)/libwrenchclient.a: $(BUILD)/clients/wrenchclient.o
	rm -f $@ && ar rcs $@ $^

WRENCHCTL_SRC = $(wildcard clients/wrenchctl/*.c)
WRENCHCTL_HDR = $(wildcard clients/wrenchctl/*.h)

$(BUILD)/clients/wrenchctl/%.o: clients/wrenchctl/%.c $(WRENCHCTL_HDR) clients/c/wrenchclient.h $(PROTO_HDR) $(LIB_HDR)
	@mkdir -p $(dir $@)
	$(CC) $(WARN) $(CFLAGS) $(INCLUDES) -Iclients/c -c $< -o $@

$(BUILD)/wrenchctl: $(patsubst clients/%.c,$(BUILD)/clients/%.o,$(WRENCHCTL_SRC)) $(BUILD)/libwrenchclient.a $(BUILD)/libwrenchproto.a $(BUILD)/libwrench.a
	$(CC) $(CFLAGS) $^ -lcjson -lglpk -lm -o $@

$(BUILD)/wrenchclient-example: clients/c/example.c $(BUILD)/libwrenchclient.a
	$(CC) $(WARN) $(CFLAGS) -Iclients/c $^ -lm -o $@

$(BUILD)/wrenchclient-bench: clients/c/bench.c $(BUILD)/libwrenchclient.a
	$(CC) $(WARN) $(CFLAGS) -Iclients/c $^ -lm -o $@

$(BUILD)/asan/proto/%.o: proto/%.c $(PROTO_HDR) $(LIB_HDR)
	@mkdir -p $(dir $@)
	$(CC) $(WARN) -O1 -g $(SAN) $(INCLUDES) -c $< -o $@

$(BUILD)/asan/daemon/%.o: daemon/%.c $(DAEMON_HDR) $(PROTO_HDR) $(LIB_HDR)
	@mkdir -p $(dir $@)
	$(CC) $(WARN) -O1 -g $(SAN) $(INCLUDES) -c $< -o $@

$(BUILD)/asan/libwrenchproto.a: $(patsubst %.c,$(BUILD)/asan/%.o,$(PROTO_SRC))
	rm -f $@ && ar rcs $@ $^

$(BUILD)/asan/libwrenchd.a: $(patsubst %.c,$(BUILD)/asan/%.o,$(DAEMON_SRC))
	rm -f $@ && ar rcs $@ $^

# The daemon reads $(SYSCONFDIR)/wrenchd/wrenchd.conf when no --config is
# given (SYSCONFDIR: see install below), so the path is compiled into
# wd_main.o, which $(BUILD)/sysconfdir rebuilds whenever SYSCONFDIR changes:
# a build reads the configuration of the prefix it was built for.
$(BUILD)/daemon/wd_main.o $(BUILD)/asan/daemon/wd_main.o: $(BUILD)/sysconfdir
$(BUILD)/daemon/wd_main.o $(BUILD)/asan/daemon/wd_main.o: WARN += -DWD_SYSCONFDIR='"$(SYSCONFDIR)"'

$(BUILD)/sysconfdir: FORCE
	@mkdir -p $(dir $@)
	@echo '$(SYSCONFDIR)' | cmp -s - $@ || echo '$(SYSCONFDIR)' > $@

FORCE:

$(BUILD)/asan/wrenchd: $(BUILD)/asan/daemon/wd_main.o $(BUILD)/asan/libwrenchd.a $(BUILD)/asan/libwrenchproto.a $(BUILD)/asan/libwrench.a
	$(CC) $(SAN) $^ $(SERVER_LIBS) -o $@

$(BUILD)/libwrench-example: examples/libwrench_example.c $(BUILD)/libwrench.a
	$(CC) $(WARN) $(CFLAGS) -Ilib $< $(BUILD)/libwrench.a $(LIBS) -o $@

# ---- unit tests (cmocka) -------------------------------------------------
TEST_HDR = $(wildcard tests/unit/*.h)

TEST_LINK = libwrenchd.a libwrenchproto.a libwrench.a

$(BUILD)/tests/%: tests/unit/%.c $(TEST_HDR) $(addprefix $(BUILD)/,$(TEST_LINK))
	@mkdir -p $(dir $@)
	$(CC) $(WARN) $(CFLAGS) $(INCLUDES) $< $(addprefix $(BUILD)/,$(TEST_LINK)) $(SERVER_LIBS) $(TEST_LIBS) -o $@

$(BUILD)/asan/tests/%: tests/unit/%.c $(TEST_HDR) $(addprefix $(BUILD)/asan/,$(TEST_LINK))
	@mkdir -p $(dir $@)
	$(CC) $(WARN) -O1 -g $(SAN) $(INCLUDES) $< $(addprefix $(BUILD)/asan/,$(TEST_LINK)) $(SERVER_LIBS) $(TEST_LIBS) -o $@

# The client's tests count heap allocations by wrapping malloc at link time.
WRAP_ALLOC = -Wl,--wrap=malloc,--wrap=realloc,--wrap=calloc

$(BUILD)/tests/test_client: tests/unit/test_client.c $(BUILD)/libwrenchclient.a
	@mkdir -p $(dir $@)
	$(CC) $(WARN) $(CFLAGS) -Iclients/c $< $(BUILD)/libwrenchclient.a $(WRAP_ALLOC) -lcmocka -lpthread -lm -o $@

$(BUILD)/asan/libwrenchclient.a: clients/c/wrenchclient.c clients/c/wrenchclient.h
	@mkdir -p $(BUILD)/asan/clients
	$(CC) $(WARN) -O1 -g $(SAN) -Iclients/c -c $< -o $(BUILD)/asan/clients/wrenchclient.o
	ar rcs $@ $(BUILD)/asan/clients/wrenchclient.o

$(BUILD)/asan/tests/test_client: tests/unit/test_client.c $(BUILD)/asan/libwrenchclient.a
	@mkdir -p $(dir $@)
	$(CC) $(WARN) -O1 -g $(SAN) -Iclients/c $< $(BUILD)/asan/libwrenchclient.a $(WRAP_ALLOC) -lcmocka -lpthread -lm -o $@

# An LD_PRELOAD library the fault tests use to fail writes to a directory.
$(BUILD)/tests/libfail_storage.so: tests/faults/fail_storage.c
	@mkdir -p $(dir $@)
	$(CC) -std=c11 -Wall -Wextra -Werror -O2 -fPIC -shared $< -ldl -o $@

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

# The last line printed is the test runner's closing line (CI reads it).
check: unit unit-asan physics-check load-check fuzz-smoke e2e-asan e2e

# ---- running it ------------------------------------------------------------

demo: all
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

# ---- load and soak (bench) ----
# bench/README.md says what these measure and how to read their output.
BENCH_LOAD = $(BUILD)/bench/load

$(BENCH_LOAD): bench/load.c $(BUILD)/libwrenchproto.a $(BUILD)/libwrench.a $(PROTO_HDR) $(LIB_HDR)
	@mkdir -p $(dir $@)
	$(CC) $(WARN) $(CFLAGS) $(INCLUDES) bench/load.c $(BUILD)/libwrenchproto.a $(BUILD)/libwrench.a \
	    -lcjson -lglpk -lpthread -lm -o $@

# The cost of writing a number, old (snprintf + strtod) against new
# (proto/wp_number.c): prints figures, asserts nothing.
BENCH_NUMBER = $(BUILD)/bench/number

$(BENCH_NUMBER): bench/number.c bench/bench_util.h $(BUILD)/libwrenchproto.a $(PROTO_HDR)
	@mkdir -p $(dir $@)
	$(CC) $(WARN) $(CFLAGS) $(INCLUDES) bench/number.c $(BUILD)/libwrenchproto.a -lm -o $@

BENCH_MICRO = $(BUILD)/bench/micro

$(BENCH_MICRO): bench/micro.c bench/bench_util.h $(BUILD)/libwrenchproto.a $(BUILD)/libwrench.a $(PROTO_HDR) $(LIB_HDR)
	@mkdir -p $(dir $@)
	$(CC) $(WARN) $(CFLAGS) $(INCLUDES) bench/micro.c $(BUILD)/libwrenchproto.a $(BUILD)/libwrench.a \
	    -lcjson -lglpk -lm -o $@

BENCH_SOCKET = $(BUILD)/bench/socket

$(BENCH_SOCKET): bench/socket.c bench/bench_util.h
	@mkdir -p $(dir $@)
	$(CC) $(WARN) $(CFLAGS) bench/socket.c -lpthread -lm -o $@

# Issue 9's benchmarks, one table (docs/PERFORMANCE.md); figures, never a
# test.  Run it on a quiet machine.
bench: all $(BENCH_MICRO) $(BENCH_SOCKET) $(BUILD)/bench/number
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
# libFuzzer targets (clang, -fsanitize=fuzzer,address,undefined) over the
# sources of lib/, proto/ and daemon/ (but main) rebuilt with coverage
# instrumentation in build/fuzz/.  tests/fuzz/README.md says what each
# target checks.  make fuzz: each target for FUZZ_SECONDS on a copy of the
# corpus (build/fuzz/corpus-work); make fuzz-smoke: the committed corpus and
# regressions, then FUZZ_SMOKE_RUNS mutations of each, seed 1.
FUZZ_CC       = clang
FUZZ_SAN      = -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
FUZZ_CFLAGS   = -std=c11 -Wall -Wextra -Werror -D_POSIX_C_SOURCE=200809L -g -O1 $(INCLUDES) \
                -fsanitize=fuzzer-no-link $(FUZZ_SAN)
FUZZ_DIR      = $(BUILD)/fuzz
FUZZ_TARGETS  = request fixture parse
FUZZ_BIN      = $(addprefix $(FUZZ_DIR)/fuzz_,$(FUZZ_TARGETS))
FUZZ_OBJ      = $(patsubst %.c,$(FUZZ_DIR)/%.o,$(LIB_SRC) $(PROTO_SRC) $(DAEMON_SRC))
FUZZ_SECONDS ?= 60
FUZZ_SMOKE_RUNS ?= 10000

$(FUZZ_DIR)/lib/%.o: lib/%.c $(LIB_HDR)
	@mkdir -p $(dir $@)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -c $< -o $@

$(FUZZ_DIR)/proto/%.o: proto/%.c $(PROTO_HDR) $(LIB_HDR)
	@mkdir -p $(dir $@)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -c $< -o $@

$(FUZZ_DIR)/daemon/%.o: daemon/%.c $(DAEMON_HDR) $(PROTO_HDR) $(LIB_HDR)
	@mkdir -p $(dir $@)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -c $< -o $@

$(FUZZ_DIR)/libwrench-fuzz.a: $(FUZZ_OBJ)
	rm -f $@ && ar rcs $@ $^

$(FUZZ_DIR)/fuzz_%: tests/fuzz/fuzz_%.c tests/fuzz/fuzz_util.h tests/unit/test_util.h $(FUZZ_DIR)/libwrench-fuzz.a
	$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer $< $(FUZZ_DIR)/libwrench-fuzz.a $(SERVER_LIBS) -o $@

fuzz-build: $(FUZZ_BIN)

fuzz: $(FUZZ_BIN)
	@FUZZ_DIR=$(FUZZ_DIR) tests/fuzz/run-fuzz fuzz $(FUZZ_SECONDS) $(FUZZ_TARGETS)

fuzz-smoke: $(FUZZ_BIN)
	@FUZZ_DIR=$(FUZZ_DIR) tests/fuzz/run-fuzz smoke $(FUZZ_SMOKE_RUNS) $(FUZZ_TARGETS)
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
PUBLIC_HEADERS = lib/wrench.h lib/wr_status.h lib/wr_fixture.h lib/wr_cone.h lib/wr_plan.h \
                 lib/wr_lp.h lib/wr_classify.h lib/wr_regions.h clients/c/wrenchclient.h
INSTALLED = $(PREFIX)/sbin/wrenchd $(PREFIX)/bin/wrenchctl \
    $(PREFIX)/lib/libwrench.a $(PREFIX)/lib/libwrenchclient.a \
    $(addprefix $(PREFIX)/include/wrench/,$(notdir $(PUBLIC_HEADERS))) \
    $(PREFIX)/lib/pkgconfig/wrench.pc $(PREFIX)/lib/pkgconfig/wrenchclient.pc \
    $(PREFIX)/lib/systemd/system/wrenchd.service $(PREFIX)/lib/systemd/system/wrenchd.socket \
    $(PREFIX)/lib/sysusers.d/wrenchd.conf \
    $(PREFIX)/share/man/man1/wrenchctl.1 $(PREFIX)/share/man/man8/wrenchd.8 \
    $(PYTHONDIR)/wrenchd.py \
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
	install -m 0644 clients/python/wrenchd.py $(DESTDIR)$(PYTHONDIR)/
	install -m 0644 examples/*.json $(DESTDIR)$(PREFIX)/share/wrenchd/examples/
	@# The configuration is the administrator's: never overwritten.
	test -e $(DESTDIR)$(CONFIG_FILE) || { sed $(CONFIG_PATHS) systemd/wrenchd.conf \
	    > $(DESTDIR)$(CONFIG_FILE) && chmod 0644 $(DESTDIR)$(CONFIG_FILE); }
	@# MemoryMax= from the limits in that file (systemd/memory-max says how).
	memory_max=$$(systemd/memory-max $(BUILD)/wrenchd $(DESTDIR)$(CONFIG_FILE)) && \
	sed -e 's|@SBINDIR@|$(PREFIX)/sbin|' -e "s|@MEMORY_MAX@|$$memory_max|" $(CONFIG_PATHS) \
	    systemd/wrenchd.service > $(DESTDIR)$(PREFIX)/lib/systemd/system/wrenchd.service

uninstall:
	rm -f $(addprefix $(DESTDIR),$(INSTALLED))
	-rmdir $(DESTDIR)$(PREFIX)/include/wrench $(DESTDIR)$(PREFIX)/share/wrenchd/examples \
	    $(DESTDIR)$(PREFIX)/share/wrenchd 2>/dev/null
	@# The configuration goes only if it is still the one shipped.
	-sed $(CONFIG_PATHS) systemd/wrenchd.conf | cmp -s - $(DESTDIR)$(CONFIG_FILE) && \
	    rm -f $(DESTDIR)$(CONFIG_FILE) && rmdir $(DESTDIR)$(SYSCONFDIR)/wrenchd

# ---- physics validation (tests/physics) ----
# wrenchd's answers against Box2D (docs/VALIDATION.md).  physics-check is the
# quick run make check includes; validate is the full one, with the table.
PHYSICS_FIXTURES = $(wildcard examples/*.json) $(wildcard tests/physics/fixtures/*.json)
PHYSICS_CXXFLAGS = -std=c++17 -Wall -Wextra -Werror -O2 -g

$(BUILD)/physics-validate: tests/physics/validate.cpp $(LIB_HDR) $(PROTO_HDR) $(BUILD)/libwrenchproto.a $(BUILD)/libwrench.a
	@mkdir -p $(dir $@)
	$(CXX) $(PHYSICS_CXXFLAGS) $(INCLUDES) $$(pkg-config --cflags box2d) $< \
	    $(BUILD)/libwrenchproto.a $(BUILD)/libwrench.a $$(pkg-config --libs box2d) -lcjson -lglpk -lm -o $@

physics-check: $(BUILD)/physics-validate
	$(BUILD)/physics-validate --quick $(PHYSICS_FIXTURES)

validate: $(BUILD)/physics-validate
	$(BUILD)/physics-validate --full $(PHYSICS_FIXTURES)
# ---- end of physics validation ----

# ---- dependencies --------------------------------------------------------
DEB_PACKAGES = build-essential pkg-config libglpk-dev libevent-dev libcjson-dev \
               libcmocka-dev python3 python3-pytest libbox2d-dev systemd clang libclang-rt-14-dev python3-scipy

deps:
	@missing=""; for p in $(DEB_PACKAGES); do \
	    dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "install ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -z "$$missing" ]; then echo "make deps: every Debian package is present"; exit 0; fi; \
	echo "make deps: installing$$missing"; \
	sudo=""; [ "$$(id -u)" -eq 0 ] || sudo=sudo; \
	$$sudo apt-get install -y $$missing || { $$sudo apt-get update && $$sudo apt-get install -y $$missing; }

clean:
	rm -rf $(BUILD)
