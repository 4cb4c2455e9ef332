# zview: make builds ./zview; make test runs every test; make asan runs
# them under AddressSanitizer + UBSan; make bench prints the benchmark.
CC      ?= cc
PREFIX  ?= /usr/local
PKGS    := ncursesw libpng
# feature macros are set per file (term.c needs the wide-char curses ones)
PKG_CFLAGS := $(filter-out -D%,$(shell pkg-config --cflags $(PKGS) 2>/dev/null))
PKG_LIBS   := $(shell pkg-config --libs $(PKGS) 2>/dev/null || echo -lncursesw -ltinfo -lpng16)

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

OPT     ?= -O2
EXTRA_CFLAGS ?=
CFLAGS  ?= $(OPT) -g
CFLAGS  += $(EXTRA_CFLAGS) -std=c11 -Wall -Wextra -ffp-contract=off -Iinclude $(PKG_CFLAGS) $(AI_CFLAGS) -MMD -MP -pthread
LDLIBS  += $(PKG_LIBS) $(AI_LIBS) -lm -pthread

BUILD   ?= build
SRCS    := $(wildcard src/*/*.c)
ifneq ($(ASSIMP),1)
SRCS    := $(filter-out src/mesh/assimp.c,$(SRCS))
endif
LIBSRCS := $(filter-out src/app/main.c,$(SRCS))
OBJS    := $(SRCS:%.c=$(BUILD)/%.o)
LIBOBJS := $(LIBSRCS:%.c=$(BUILD)/%.o)
TSRCS   := $(wildcard tests/test_*.c) tests/testlib.c tests/writers.c
TOBJS   := $(TSRCS:%.c=$(BUILD)/%.o)
TESTBIN := $(BUILD)/zview-tests
BIN     ?= zview

.PHONY: all test unit e2e asan run bench bench-formats install clean assets test-models noassimp

all: $(BIN)

# The build's configuration, rewritten only when it changes, so that
# switching ASSIMP rebuilds what depends on it and relinks.
CONFIG  := $(BUILD)/config
$(shell mkdir -p $(BUILD); echo 'ASSIMP=$(ASSIMP)' | cmp -s - $(CONFIG) || echo 'ASSIMP=$(ASSIMP)' > $(CONFIG))
$(BUILD)/src/mesh/format.o: $(CONFIG)

$(BIN): $(OBJS) $(CONFIG)
	$(CC) $(CFLAGS) -o $@ $(filter %.o,$^) $(LDLIBS)

$(BUILD)/%.o: %.c
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -c -o $@ $<

$(TESTBIN): $(LIBOBJS) $(TOBJS) $(CONFIG)
	$(CC) $(CFLAGS) -o $@ $(filter %.o,$^) $(LDLIBS) -lcriterion

# The whole suite: unit tests (Criterion) then end-to-end shell tests.
test: $(BIN) $(TESTBIN)
	ZVIEW=$(abspath $(BIN)) $(TESTBIN) --jobs 2
	ZVIEW=$(abspath $(BIN)) sh tests/e2e/run.sh

unit: $(TESTBIN)
	ZVIEW=$(abspath $(BIN)) $(TESTBIN) --jobs 2

# Every algorithm against the z-buffer on every model of ../shared/models.
test-models: $(TESTBIN)
	ZV_MODELS=1 $(TESTBIN) --jobs 2 --filter 'models/*'

e2e: $(BIN)
	ZVIEW=$(abspath $(BIN)) sh tests/e2e/run.sh

# Sanitized build in its own folder, same tests.
asan:
	$(MAKE) BUILD=build-asan BIN=build-asan/zview \
	    OPT="-O1 -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined" test

# The build without assimp, in its own folder (both must compile).
noassimp:
	$(MAKE) ASSIMP=0 BUILD=build-noassimp BIN=build-noassimp/zview

run: $(BIN)
	./$(BIN)

bench: $(BIN)
	sh tools/bench.sh

# Load speed and peak memory of every format (the README's table).
bench-formats: $(BIN) $(TESTBIN)
	ZVIEW=$(abspath $(BIN)) sh tools/bench-formats.sh

# Regenerate the bundled models (they are committed; this is how they were made).
assets: $(BUILD)/genassets
	$(BUILD)/genassets assets

$(BUILD)/genassets: tools/genassets.c
	@mkdir -p $(BUILD)
	$(CC) $(CFLAGS) -o $@ $< -lm

install: $(BIN)
	install -d $(DESTDIR)$(PREFIX)/bin $(DESTDIR)$(PREFIX)/share/man/man1 $(DESTDIR)$(PREFIX)/share/zview \
	    $(DESTDIR)$(PREFIX)/share/bash-completion/completions $(DESTDIR)$(PREFIX)/share/zsh/site-functions
	install -m 755 $(BIN) $(DESTDIR)$(PREFIX)/bin/zview
	install -m 644 doc/zview.1 $(DESTDIR)$(PREFIX)/share/man/man1/zview.1
	install -m 644 tools/completion/zview.bash $(DESTDIR)$(PREFIX)/share/bash-completion/completions/zview
	install -m 644 tools/completion/_zview $(DESTDIR)$(PREFIX)/share/zsh/site-functions/_zview
	install -m 644 assets/demo.obj assets/demo.mtl $(DESTDIR)$(PREFIX)/share/zview/

clean:
	rm -rf build build-asan build-noassimp $(BIN)

-include $(OBJS:.o=.d) $(TOBJS:.o=.d)
