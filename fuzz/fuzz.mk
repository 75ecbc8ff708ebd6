# refray fuzzing: builds the libFuzzer targets (fuzz/README.md). Used by `make fuzz` through
# fuzz/run.sh; on its own: make -f fuzz/fuzz.mk [FUZZ_BUILD=build-fuzz] [FUZZ_CC=clang-14]
#
# The library's sources are compiled again with clang into $(FUZZ_BUILD) (never into build/),
# with coverage for libFuzzer, AddressSanitizer and UndefinedBehaviorSanitizer (every UB report
# is a crash), and linked with each harness fuzz/fuzz_<target>.c into $(FUZZ_BUILD)/fuzz-<target>.

FUZZ_BUILD   ?= build-fuzz
FUZZ_CC      ?= $(firstword $(shell command -v clang-14 clang 2>/dev/null))
FUZZ_OPT     ?= -O1 -g
# the default build's vector kernels (AVX, SSE, FMA), so the code that is fuzzed is the code
# that runs; FUZZ_ARCH= fuzzes the portable scalar path
FUZZ_ARCH    ?= -march=native -mno-avx512f
FUZZ_TARGETS ?= nff rf obj mtl exr png formula

FUZZ_PKGS := libcjson cairo fontconfig zlib libpng OpenEXR stb netpbm libtiff-4
FUZZ_PKG_CFLAGS := $(shell pkg-config --cflags $(FUZZ_PKGS))
FUZZ_PKG_LIBS := $(shell pkg-config --libs $(FUZZ_PKGS))

FUZZ_SAN := -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer
FUZZ_CFLAGS := -std=c99 -D_POSIX_C_SOURCE=200809L $(FUZZ_OPT) $(FUZZ_ARCH) -Wall -Wextra \
               -ffp-contract=off -pthread -Iinclude -I$(FUZZ_BUILD)/gen $(FUZZ_PKG_CFLAGS) $(FUZZ_SAN)

FUZZ_LIB_SRC := $(wildcard src/core/*.c src/color/*.c src/geom/*.c src/scene/*.c src/render/*.c \
                           src/io/*.c src/formula/*.c)
FUZZ_LIB_OBJ := $(patsubst %.c,$(FUZZ_BUILD)/obj/%.o,$(FUZZ_LIB_SRC))
FUZZ_BINS := $(patsubst %,$(FUZZ_BUILD)/fuzz-%,$(FUZZ_TARGETS))

.PHONY: all
all: $(FUZZ_BINS) $(FUZZ_BUILD)/mkseeds

# the library: coverage-instrumented, without libFuzzer's main
$(FUZZ_BUILD)/obj/src/%.o: src/%.c
	@mkdir -p $(dir $@)
	@echo "  CC      $< (fuzz)"
	@$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer-no-link -MMD -MP -c $< -o $@

$(FUZZ_BUILD)/obj/fuzz/%.o: fuzz/%.c
	@mkdir -p $(dir $@)
	@echo "  CC      $<"
	@$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer-no-link -MMD -MP -c $< -o $@

# the library opens files through the sandbox's checks (fuzz/sandbox.c): its fopen and gzopen
# calls, and only its own, are renamed
$(FUZZ_BUILD)/librefray-fuzz.a: $(FUZZ_LIB_OBJ)
	@rm -f $@
	@ar rcs $@ $^
	@objcopy --redefine-sym fopen=rf_fuzz_fopen --redefine-sym gzopen=rf_fuzz_gzopen $@

$(FUZZ_BUILD)/fuzz-%: $(FUZZ_BUILD)/obj/fuzz/fuzz_%.o $(FUZZ_BUILD)/obj/fuzz/sandbox.o $(FUZZ_BUILD)/librefray-fuzz.a
	@echo "  LINK    $@"
	@$(FUZZ_CC) -fsanitize=fuzzer $(FUZZ_SAN) -pthread -o $@ $^ $(FUZZ_PKG_LIBS) -lm

$(FUZZ_BUILD)/mkseeds: $(FUZZ_BUILD)/obj/fuzz/mkseeds.o $(FUZZ_BUILD)/obj/fuzz/sandbox.o $(FUZZ_BUILD)/librefray-fuzz.a
	@echo "  LINK    $@"
	@$(FUZZ_CC) $(FUZZ_SAN) -pthread -o $@ $^ $(FUZZ_PKG_LIBS) -lm

-include $(shell find $(FUZZ_BUILD)/obj -name '*.d' 2>/dev/null)
.SECONDARY:
