/* refray: a scene written for another renderer (refray export, docs/crosscheck.md), so that an
 * independent renderer can check refray's full ray-traced images: Mitsuba 3 (XML, triangles in
 * OBJ files beside it), pbrt-v4 and POV-Ray 3.7 (SDL).
 *
 * Only what the target represents exactly is written. Everything else (a Phong highlight in
 * Mitsuba, a light without falloff in Mitsuba or pbrt, ambient light, ...) is a note naming the
 * object and its file:line:col; with `lossy` unset any such note refuses the export (nothing is
 * written), with it set the nearest thing is written and the note is a warning. The conversions
 * (refray's kd I cos(theta) / d^2 against a Lambertian albedo / pi, light units, camera window,
 * recursion depth) are written into the header comment of the main file; docs/crosscheck.md
 * derives them. */
#ifndef REFRAY_SCENE_EXPORT_H
#define REFRAY_SCENE_EXPORT_H

#include <stddef.h>

#include "refray/scene.h"
#include "refray/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum { RF_EXPORT_MITSUBA, RF_EXPORT_PBRT, RF_EXPORT_POV } RfExportFormat;

typedef struct {
    RfExportFormat format;
    const char *source;  /* the scene's file name, for notes and the header comment */
    const char *output;  /* the main file's path: names the files beside it (Mitsuba's meshes,
                            pbrt's image) */
    int width, height;   /* the image size (0: the scene's); the field of view is read for it */
    int depth;           /* refray's recursion depth (0: the scene's) */
    int samples;         /* Mitsuba's and pbrt's samples per pixel (0: the scene's) */
    int lossy;           /* 1: write the nearest thing for what cannot be represented, and warn */
    int two_sided;       /* 1: every primitive is visible from both sides (refray --two-sided) */
    int shadows;          /* the shadow rule refray renders with (RfShadowMode; -1: the scene's,
                             RfRenderSettings.shadows): POV-Ray's own is FILTERED; OPAQUE is
                             written for POV-Ray with shadow discs, FILTERED cannot be written
                             for Mitsuba or pbrt where something transmits */
} RfExportOptions;

RfExportOptions rf_export_options_default(void);

/* One file of an export: its path (the main file is files[0]) and its text. */
typedef struct {
    char *path;
    char *text;
    size_t len, cap;
} RfExportFile;

typedef struct {
    RfExportFile *files;
    size_t file_count;
    char *notes;       /* one line per note: "source:line:col: what: why", NUL-terminated */
    size_t notes_len, notes_cap;
    int problems;      /* notes about what the target cannot represent */
    int failed;        /* out of memory while writing */
} RfExport;

/* Writes the scene into ex (nothing on disk; the caller writes ex->files). RF_ERR_DOMAIN when
 * something cannot be represented and opt->lossy is 0 (ex->notes says what, ex->files is
 * empty); RF_ERR_NOMEM. ex is always to be freed. */
RfStatus rf_scene_export(const RfScene *scene, const RfExportOptions *opt, RfExport *ex);
void rf_export_free(RfExport *ex);

const char *rf_export_format_name(RfExportFormat f);

#ifdef __cplusplus
}
#endif

#endif
