/* refray: scene readers. NFF (shared/NFF.md, the SPD scenes as they are) and refray's own
 * text format (docs/scene-format.md) both fill the model of scene.h.
 *
 * Errors: the reader returns a status and writes one line "file:line:col: message" to err
 * (1-based line, 1-based byte column; a file that cannot be opened reports 1:1). The scene
 * is freed and left empty on failure. */
#ifndef REFRAY_SCENE_IO_H
#define REFRAY_SCENE_IO_H

#include <stddef.h>

#include "refray/scene.h"
#include "refray/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    /* how NFF's `angle` is read (NFF.md): RF_FOV_PIXEL_CENTRES (default, the NFF text) or
     * RF_FOV_EDGES (the SPD's POV-Ray converter) */
    RfFovReading nff_fov;
    /* OBJ faces without `vn`: the crease angle in degrees (default 60). Adjacent faces of one
     * smoothing group meeting at a sharper angle keep separate normals per corner (§3.6.3). */
    double crease_angle;
    /* OBJ files (.obj files and the refray format's `mesh`) are read and their faces put into
     * the scene on this many threads (0, the default: one per processor); the scene and any
     * error are the same for any count */
    int threads;
} RfLoadOptions;

RfLoadOptions rf_load_options_default(void);

/* The largest scene, OBJ or MTL file the readers take (decompressed): larger ones, devices and
 * pipes are refused with a message instead of read without end. */
#define RF_SCENE_MAX_FILE_BYTES (2040 << 20)

/* Reads a scene file: ".nff" -> NFF, ".rf" -> refray's format, ".obj" -> a Wavefront OBJ
 * mesh with a default camera and headlight (rf_scene_read_obj), a trailing ".gz" is
 * decompressed first (zlib); any other name is recognised by its first keyword.
 * opt may be NULL (defaults). */
RfStatus rf_scene_load(const char *path, const RfLoadOptions *opt, RfScene *scene, char *err,
                       size_t errsz);

/* The readers on text in memory (len bytes, need not be NUL-terminated); name is used in
 * messages. */
RfStatus rf_scene_read_nff(const char *name, const char *text, size_t len,
                           const RfLoadOptions *opt, RfScene *scene, char *err, size_t errsz);
RfStatus rf_scene_read_rf(const char *name, const char *text, size_t len, RfScene *scene,
                          char *err, size_t errsz);
/* A Wavefront OBJ file as a whole scene: its faces (mtllib paths relative to name's folder),
 * a camera framing the bounds from the front (+z, a little above and to the right, vfov 40
 * edge to edge) and a headlight (a point light at the eye, intensity 1, no falloff). */
RfStatus rf_scene_read_obj(const char *name, const char *text, size_t len,
                           const RfLoadOptions *opt, RfScene *scene, char *err, size_t errsz);
/* Appends the materials of MTL text to scene (docs/scene-format.md has the illum table); a
 * name already in the scene keeps its first definition. */
RfStatus rf_scene_read_mtl(const char *name, const char *text, size_t len, RfScene *scene,
                           char *err, size_t errsz);

#ifdef __cplusplus
}
#endif

#endif
