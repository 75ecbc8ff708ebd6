# refray — build with GNU make. `make demo` and `make test` are the whole set-up on Debian 12:
# a missing dependency runs tools/deps.sh, which installs the Debian packages as root or prints
# the apt-get line to run.
#
#   make            build the library (build/librefray.a) and the commands (build/refray,
#                   build/refray-raster, build/refray-verify)
#   make test       build and run every test; the last line is "N passed, N failed"
#   make demo       renders the default scene (scenes/whitted.rf) to out/whitted.{exr,png}
#   make bench      run times of the tracer on the canonical scenes (tools/bench.sh)
#   make report     tracer vs. OpenGL rasterizer on every scene: report/index.html (docs/compare.md)
#   make stress     the CGAL verifier over every ray class and scene (docs/verify.md)
#   make mutate     plants realistic bugs one at a time: which do the tests miss? (tools/mutate.sh)
#   make install PREFIX=/usr/local   (DESTDIR= for staging; make uninstall removes what it put)
#   make docs       docs/api.md from the public headers (tools/apidoc.sh)
#   make clean
#   Options: BUILD=dir (default build), SAN=1 (AddressSanitizer + UBSan), OPT="-O2 -g",
#            ARCH="-march=native" (ARCH= for the portable scalar build), V=1

BUILD   ?= build
PREFIX  ?= /usr/local
OPT     ?= -O2 -g
# the machine's vector unit (AVX for the BVH's node tests, SSE for its triangle filter) and its
# correctly rounded FMA, without AVX-512 (valgrind cannot run it); -ffp-contract=off below keeps the compiler from fusing anything itself,
# so the images are the same bits with or without it. ARCH= builds the portable scalar path.
ARCH    ?= -march=native -mno-avx512f
SAN     ?=
# the Debian pkg-config modules the library links against (tools/deps.sh installs them)
PKGS    := libcjson cairo fontconfig zlib libpng OpenEXR stb netpbm libtiff-4

comma := ,
SANFLAGS := $(if $(SAN),-fsanitize=address$(comma)undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
# -ffp-contract=off: results must not depend on the compiler fusing a*b+c (DESIGN.md)
CFLAGS_ALL = -std=c99 -D_POSIX_C_SOURCE=200809L $(OPT) $(ARCH) -Wall -Wextra -Wpedantic -Werror \
             -ffp-contract=off -pthread -Iinclude -I$(BUILD)/gen $(PKG_CFLAGS) $(SANFLAGS) $(CFLAGS)
# -fPIC: the objects go into the shared library too (compiled once; the tracer is as fast, README);
# -fno-semantic-interposition: the library's own calls are not interposable (its version script
# exports the public names only), so the compiler may inline them as it does without -fPIC
# -fno-math-errno: no libm function's errno is read anywhere, so sqrt is the bare instruction,
# not a compare and a library call for a negative argument: the same results, 1-4 % fewer
# instructions in the tracer (docs/performance.md)
OBJ_FLAGS := -fPIC -fno-semantic-interposition -fno-math-errno
CFLAGS_ALL += $(OBJ_FLAGS)
# the flags that decide numeric results, recorded in every EXR the renderer writes
NUMERIC_FLAGS = -std=c99 $(OPT) $(ARCH) -ffp-contract=off $(SANFLAGS) $(CFLAGS)
LDFLAGS_ALL = -pthread $(SANFLAGS) $(LDFLAGS)
LDLIBS_ALL  = $(PKG_LIBS) -lm $(LDLIBS)

LIB_SRC  := $(wildcard src/core/*.c src/color/*.c src/geom/*.c src/scene/*.c src/render/*.c \
                       src/io/*.c src/formula/*.c)
CLI_SRC  := $(wildcard src/cli/*.c)
TEST_SRC := $(wildcard tests/*.c)
# the comparator (issue 5): OpenGL through OSMesa, linked into refray-raster and the tests only
RASTER_SRC := $(filter-out compare/verify% compare/mesh_bench.c compare/view_main.c,$(wildcard compare/*.c))
RASTER_LIB_SRC := $(filter-out compare/raster_main.c,$(RASTER_SRC))
OSMESA_LIBS = $(shell pkg-config --libs osmesa 2>/dev/null || echo -lOSMesa) $(shell pkg-config --libs egl 2>/dev/null || echo -lEGL)
obj = $(patsubst %.c,$(BUILD)/obj/%.o,$(1))
# the CGAL verifier (issue 7, docs/verify.md): C++17, its own binary refray-verify
VERIFY_SRC := $(wildcard compare/verify*.cpp)
cxxobj = $(patsubst %.cpp,$(BUILD)/obj/%.o,$(1))
# -frounding-math: CGAL's interval filters switch the rounding mode (CGAL's own build sets it)
CXXFLAGS_ALL = -std=c++17 $(OPT) $(ARCH) -Wall -Wextra -Werror -ffp-contract=off -frounding-math -pthread \
               -Iinclude $(SANFLAGS) $(CXXFLAGS)

# the mesh benchmark against Embree (issue 10, docs/performance.md): Embree's column only when
# Debian's libembree-dev is installed; the bunny is made with CGAL (compare/make_mesh.cpp)
EMBREE := $(if $(wildcard /usr/include/embree3/rtcore.h),1,)
MESHBENCH := $(BUILD)/refray-mesh-bench
MAKEMESH := $(BUILD)/refray-make-mesh

LIB  := $(BUILD)/librefray.a
# the shared library: its version is RF_VERSION of include/refray/version.h (the one source), its
# soname librefray.so.MAJOR
RF_VERSION := $(shell sed -n 's/.*define RF_VERSION "\([0-9.]*\)".*/\1/p' include/refray/version.h)
SONAME := librefray.so.$(firstword $(subst ., ,$(RF_VERSION)))
SO   := $(BUILD)/librefray.so.$(RF_VERSION)
LIBDIR ?= $(PREFIX)/lib
BIN  := $(BUILD)/refray
TEST := $(BUILD)/refray-tests
RASTER := $(BUILD)/refray-raster
VERIFY := $(BUILD)/refray-verify
VIEW := $(BUILD)/refray-view
GLFW_LIBS = $(shell pkg-config --libs glfw3 2>/dev/null || echo -lglfw)

.PHONY: all test demo bench bench-run install uninstall docs clean report crosscheck stress mutate FORCE
all: $(LIB) $(SO) $(BIN) $(RASTER) $(VERIFY) $(VIEW) $(BUILD)/man/refray.1 $(BUILD)/completion/refray

# Dependencies: checked (and installed) once per build folder, then the flags are cached.
NO_CONFIG_GOALS := clean uninstall docs
ifneq ($(filter-out $(NO_CONFIG_GOALS),$(or $(MAKECMDGOALS),all)),)
include $(BUILD)/config.mk
endif
$(BUILD)/config.mk: tools/deps.sh Makefile
	@mkdir -p $(BUILD)
	@sh tools/deps.sh
	@{ echo "PKG_CFLAGS := $$(pkg-config --cflags $(PKGS))"; \
	   echo "PKG_LIBS := $$(pkg-config --libs $(PKGS))"; } > $@.tmp && mv $@.tmp $@

# V=1 shows the full commands
Q := $(if $(V),,@)

# rewritten only when the flags change, and every object depends on it: a change of OPT, ARCH,
# SAN, CFLAGS or OBJ_FLAGS rebuilds everything (the flags decide numeric results, DESIGN.md)
$(BUILD)/gen/build_info.h: $(BUILD)/config.mk FORCE
	@mkdir -p $(dir $@)
	@echo '#define RF_BUILD_FLAGS "$(strip $(NUMERIC_FLAGS))" /* objects: $(OBJ_FLAGS) */' > $@.tmp
	@cmp -s $@.tmp $@ && rm -f $@.tmp || mv $@.tmp $@
FORCE:

$(BUILD)/obj/%.o: %.c $(BUILD)/gen/build_info.h
	@mkdir -p $(dir $@)
	@$(if $(Q),echo "  CC      $<")
	$(Q)$(CC) $(CFLAGS_ALL) -MMD -MP -c $< -o $@

$(LIB): $(call obj,$(LIB_SRC))
	@rm -f $@
	@$(if $(Q),echo "  AR      $@")
	$(Q)$(AR) rcs $@ $^

# only what the public headers declare is exported (a version script of those names,
# tools/exports.sh); the rf__ and other internal functions stay inside
$(BUILD)/gen/refray.map: $(call obj,$(LIB_SRC)) $(wildcard include/refray/*.h) tools/exports.sh
	$(Q)sh tools/exports.sh $(call obj,$(LIB_SRC)) > $@.tmp && mv $@.tmp $@

$(SO): $(call obj,$(LIB_SRC)) $(BUILD)/gen/refray.map
	@$(if $(Q),echo "  LINK    $@")
	$(Q)$(CC) -shared -Wl,-soname,$(SONAME) -Wl,--version-script=$(BUILD)/gen/refray.map -Wl,--no-undefined \
	    $(LDFLAGS_ALL) -o $@ $(call obj,$(LIB_SRC)) $(LDLIBS_ALL)
	$(Q)ln -sf $(notdir $@) $(BUILD)/$(SONAME) && ln -sf $(SONAME) $(BUILD)/librefray.so

# the man pages and the bash completion, made from the commands' --help (one source)
$(BUILD)/man/refray.1: $(BIN) $(RASTER) $(VERIFY) $(VIEW) tools/manpages.sh
	@$(if $(Q),echo "  MAN     $(BUILD)/man")
	$(Q)rm -rf $(BUILD)/man && sh tools/manpages.sh $(BUILD) $(BUILD)/man
$(BUILD)/completion/refray: $(BIN) $(RASTER) $(VERIFY) $(VIEW) tools/completion.sh
	@mkdir -p $(dir $@)
	$(Q)sh tools/completion.sh $(BUILD) > $@.tmp && mv $@.tmp $@

$(BIN): $(call obj,$(CLI_SRC)) $(LIB)
	@$(if $(Q),echo "  LINK    $@")
	$(Q)$(CC) $(LDFLAGS_ALL) -o $@ $^ $(LDLIBS_ALL)

$(TEST): $(call obj,$(TEST_SRC)) $(call obj,$(RASTER_LIB_SRC)) $(BUILD)/obj/src/cli/farm.o $(LIB)
	@$(if $(Q),echo "  LINK    $@")
	$(Q)$(CC) $(LDFLAGS_ALL) -o $@ $^ $(LDLIBS_ALL) $(OSMESA_LIBS)

$(RASTER): $(call obj,$(RASTER_SRC)) $(BUILD)/obj/src/cli/args.o $(BUILD)/obj/src/cli/opt.o $(LIB)
	@$(if $(Q),echo "  LINK    $@")
	$(Q)$(CC) $(LDFLAGS_ALL) -o $@ $^ $(LDLIBS_ALL) $(OSMESA_LIBS)

# refray-view: the GLFW viewer (compare/view_main.c), with the rasterizer for its GL views
$(VIEW): $(call obj,compare/view_main.c $(RASTER_LIB_SRC)) $(BUILD)/obj/src/cli/args.o $(BUILD)/obj/src/cli/opt.o $(LIB)
	@$(if $(Q),echo "  LINK    $@")
	$(Q)$(CC) $(LDFLAGS_ALL) -o $@ $^ $(LDLIBS_ALL) $(OSMESA_LIBS) $(GLFW_LIBS)

# relinked when Embree appears or goes (the stamp's name says which)
$(BUILD)/gen/embree-$(if $(EMBREE),yes,no):
	@mkdir -p $(dir $@) && rm -f $(BUILD)/gen/embree-* && touch $@
$(MESHBENCH): compare/mesh_bench.c $(LIB) $(BUILD)/gen/build_info.h $(BUILD)/gen/embree-$(if $(EMBREE),yes,no)
	@mkdir -p $(dir $@)
	@$(if $(Q),echo "  LINK    $@$(if $(EMBREE), (with Embree))")
	$(Q)$(CC) $(CFLAGS_ALL) $(if $(EMBREE),-DRF_HAVE_EMBREE) $(LDFLAGS_ALL) -o $@ $< $(LIB) $(LDLIBS_ALL) $(if $(EMBREE),-lembree3)

$(MAKEMESH): compare/make_mesh.cpp
	@mkdir -p $(dir $@)
	@$(if $(Q),echo "  CXX     $@")
	$(Q)$(CXX) $(CXXFLAGS_ALL) -o $@ $< $(LDFLAGS_ALL) -lgmp -lmpfr

$(BUILD)/obj/compare/%.o: compare/%.cpp
	@mkdir -p $(dir $@)
	@$(if $(Q),echo "  CXX     $<")
	$(Q)$(CXX) $(CXXFLAGS_ALL) -MMD -MP -c $< -o $@

$(VERIFY): $(call cxxobj,$(VERIFY_SRC)) $(BUILD)/obj/src/cli/opt.o $(LIB)
	@$(if $(Q),echo "  LINK    $@")
	$(Q)$(CXX) $(LDFLAGS_ALL) -o $@ $^ $(LDLIBS_ALL) -lgmp -lmpfr

test: all $(TEST)
	LSAN_OPTIONS=suppressions=$(CURDIR)/compare/lsan.supp:print_suppressions=0 RF_BIN=$(BIN) RF_VERIFY=$(VERIFY) RF_TEST_DATA=tests/data \
	    RF_CC="$(CC) $(SANFLAGS)" RF_VERSION=$(RF_VERSION) RF_PKGS="$(PKGS)" $(TEST)

# the numerical stress suite (issue 7, docs/verify.md): every verifier class, the acne and leak
# measurements, the optics sweep, the stress renders and the SPD scenes, one table; non-zero
# exit on a real disagreement. CI size by default; the full size is STRESS_RAYS=10000000.
STRESS_RAYS ?= 150000
STRESS_SCENES ?= $(wildcard scenes/spd/*.nff) scenes/spd/gears.nff.gz scenes/whitted.rf scenes/instances.rf scenes/mesh.rf
stress: $(VERIFY)
	$(VERIFY) --stress --rays $(STRESS_RAYS) --jobs 2 $(STRESS_SCENES)

# the cross-validation report: every scene through `refray render --local` and refray-raster,
# diffed; writes report/index.html (docs/compare.md). REPORT_SIZE = longest side in pixels
REPORT_SIZE ?= 512
REPORT_DIR ?= report
report: $(BIN) $(RASTER)
	@sh compare/report.sh $(BIN) $(RASTER) $(REPORT_DIR) $(REPORT_SIZE)

# full ray-traced images against Mitsuba 3 and POV-Ray (issue 16, docs/crosscheck.md): the scenes
# of scenes/crosscheck/ exported by `refray export`, diffed (z-tests against Mitsuba, half-float
# bounds against POV-Ray); writes $(REPORT_DIR)/crosscheck/index.html. A renderer that is missing
# is skipped and named; CROSSCHECK_INSTALL=1 pip-installs Mitsuba first.
CROSSCHECK_SAMPLES ?= 1024
crosscheck: $(BIN)
	@python3 tools/crosscheck.py --refray $(BIN) --out $(REPORT_DIR)/crosscheck --samples $(CROSSCHECK_SAMPLES) $(if $(CROSSCHECK_INSTALL),--install)

demo: $(BIN)
	@sh tools/demo.sh $(BIN)

# the anchors (Embree, POV-Ray, the CGAL demo data) are installed first when missing (as root),
# then make runs again so that the harness is built with what is there
bench:
	@sh tools/deps.sh bench
	@$(MAKE) --no-print-directory bench-run
bench-run: $(BIN) $(MESHBENCH) $(MAKEMESH)
	@sh tools/bench.sh $(BIN) $(MESHBENCH) $(MAKEMESH)

# plants one realistic bug at a time in a copy of the sources and reports which ones the tests
# miss (tools/mutate.sh; about a minute per bug)
mutate: $(BIN) $(TEST)
	@sh tools/mutate.sh

# tools/install.sh: the file list in one place, written to PREFIX/share/refray/installed-files,
# which uninstall removes exactly; refray.pc gets the real prefix. After installing into a
# system folder as root, run ldconfig.
install: all
	@RF_VERSION=$(RF_VERSION) RF_PKGS="$(PKGS)" sh tools/install.sh install $(BUILD) "$(DESTDIR)" $(PREFIX) $(LIBDIR)
uninstall:
	@sh tools/install.sh uninstall "$(DESTDIR)" $(PREFIX) $(LIBDIR)

docs:
	sh tools/apidoc.sh > docs/api.md

clean:
	rm -rf build build-san $(filter-out build build-san,$(BUILD))

-include $(shell find $(BUILD)/obj -name '*.d' 2>/dev/null)

# fuzzing (fuzz/README.md): each reader under libFuzzer for FUZZ_SECONDS seconds, two at a time,
# built with clang into build-fuzz/; CI's short round is FUZZ_SECONDS=10. Without clang's
# libFuzzer it prints the apt-get line and exits 0.
FUZZ_SECONDS ?= 60
.PHONY: fuzz
fuzz:
	@FUZZ_SECONDS=$(FUZZ_SECONDS) MAKE="$(MAKE)" sh fuzz/run.sh
