# refray.mk: make rules for reference images, for a course repository's Makefile. `make install`
# puts it in PREFIX/share/refray/refray.mk; use it as
#
#     include /usr/local/share/refray/refray.mk
#     REFS := $(patsubst %.rf,%.exr,$(wildcard scenes/*.rf))
#     all: $(REFS)
#
# Every render writes a dependency file beside its image (NAME.exr.d, by refray render --deps):
# the scene and every file the scene read (OBJ meshes, MTL libraries), as a compiler's -MD does.
# Those files are included below, so an image is rebuilt when, and only when, one of its inputs
# changed. examples/course/ is a small course repository that uses it (and the tests run it).

REFRAY ?= refray
# options of every render (size, samples, ...); REFRAY_FLAGS_NAME adds some for the scene NAME
REFRAY_FLAGS ?=

# one render makes both images of a scene: NAME.exr (linear, the reference) and NAME.png (the
# display image, gamma 2.2, or --srgb in REFRAY_FLAGS), and NAME.exr.d
refray_render = $(REFRAY) render $< -o $*.exr --png $*.png --deps $*.exr.d --quiet $(REFRAY_FLAGS) \
                $(REFRAY_FLAGS_$(notdir $*))

%.exr %.png: %.rf
	$(refray_render)
%.exr %.png: %.nff
	$(refray_render)
%.exr %.png: %.obj
	$(refray_render)

# Grading: `make grade STUDENT=dir` grades dir/NAME.png (or .exr) against each reference
# NAME.exr of REFRAY_REFS with refray grade (one line per image; a report per reference in
# $(REFRAY_GRADE_DIR)/NAME: index.html, grades.csv, grades.json); the exit status is non-zero
# when an image fails, has the wrong size or is missing. REFRAY_GRADE_FLAGS: refray grade's
# options (--fail, --failpercent, --edge-tolerant, ...).
REFRAY_REFS ?=
REFRAY_GRADE_FLAGS ?=
REFRAY_GRADE_DIR ?= grade-report
.PHONY: grade
grade: $(REFRAY_REFS)
	@test -n "$(STUDENT)" || { echo "make grade STUDENT=dir (the student's images, named as the references)" >&2; exit 2; }
	@mkdir -p "$(REFRAY_GRADE_DIR)"; fail=0; for ref in $(REFRAY_REFS); do \
	    name=$$(basename $$ref .exr); \
	    img=$$(ls "$(STUDENT)/$$name.png" "$(STUDENT)/$$name.exr" 2>/dev/null | head -n 1); \
	    out=$$($(REFRAY) grade $(REFRAY_GRADE_FLAGS) -o "$(REFRAY_GRADE_DIR)/$$name" $$ref \
	                            "$${img:-$(STUDENT)/$$name.png}"); st=$$?; \
	    printf '%s\n' "$$out" | grep -v '^[0-9]* submissions:'; [ $$st -le 1 ] || fail=1; \
	done; exit $$fail

-include $(shell find . -name '*.exr.d' -o -name '*.png.d' 2>/dev/null)
