/* refray: the steps every scene reader shares (internal; reader.c), above the model's own
 * helpers (scene_internal.h), which scene.c, scene_graph.c and scene_check.c use without the
 * readers. */
#ifndef RF_SCENE_READER_H
#define RF_SCENE_READER_H

#include "lexer.h"
#include "refray/scene_io.h"
#include "scene_internal.h"

/* Where a token stands, as the scene model records it (RfSrcLoc). */
static inline RfSrcLoc rf__token_loc(const RfToken *t)
{
    RfSrcLoc l;
    l.line = t->line;
    l.col = t->col;
    return l;
}

/* Checks and appends a primitive; a failure is reported at p->loc. */
RfStatus rf__reader_add_prim(RfLexer *lx, RfScene *scene, const RfPrimitive *p);
/* Appends one vertex (and its normal when n != NULL); *first gets its index when first_too. */
RfStatus rf__reader_add_vertex(RfLexer *lx, RfScene *scene, RfVec3 v, const RfVec3 *n,
                               size_t *first, size_t *nfirst);
/* Checks the camera just read; a failure is reported at the statement to blame. */
RfStatus rf__reader_check_camera(RfLexer *lx, const RfSceneCamera *cam);
/* Makes sure a current material exists: objects before any material get a white diffuse one
 * named "default" (neither format defines them otherwise). */
RfStatus rf__reader_default_material(RfLexer *lx, RfScene *scene, const RfToken *kw,
                                     int *current);
/* The end of every reader: given the parse status st, requires a camera, validates the whole
 * scene, and frees it on any failure. */
RfStatus rf__reader_finish(RfLexer *lx, RfScene *scene, RfStatus st);

/* A whole file (a trailing .gz decompressed) into a malloc'd buffer; on failure err gets
 * "cannot open path: why" or "path: why", no line and column (there is no line to point at). */
RfStatus rf__reader_read_file(RfScene *scene, const char *path, char **text, size_t *len, char *err,
                              size_t errsz);
/* Appends path to scene->files: rf__reader_read_file does for every file it reads into a scene
 * (scene != NULL), rf_scene_load for the scene file, which is read before the scene exists. */
RfStatus rf__reader_add_file(RfScene *scene, const char *path, char *err, size_t errsz);
/* Do the first n bytes of s end with suffix? */
int rf__ends_with(const char *s, size_t n, const char *suffix);
/* rel resolved against the folder of the file `base` (rel itself when absolute); 0 when it
 * does not fit into n bytes. */
int rf__reader_relative_path(const char *base, const char *rel, size_t rel_len, char *out, size_t n);

/* How the faces of an OBJ file enter a scene (obj.c): the refray-format `mesh` statement and
 * rf_scene_read_obj. */
typedef struct {
    double crease_deg;   /* edges sharper than this keep separate normals per corner (§3.6.3) */
    int material;        /* material of faces before any usemtl; -1: a white "default" one */
    unsigned prim_flags; /* added to every face (RF_PRIM_IN_OBJECT inside an object) */
    int threads;         /* the file read and its faces put into the scene on this many threads
                            (0: every processor) */
    int *chunked;        /* when not NULL, set to whether the file was read in chunks on several
                            threads (obj.c, parse_chunks) or line by line: for the tests */
} RfObjPlacement;
/* rf_scene_read_rf with load options (their thread count reaches its `mesh` statements). */
RfStatus rf__scene_read_rf(const char *name, const char *text, size_t len, const RfLoadOptions *opt,
                           RfScene *scene, char *err, size_t errsz);
/* Appends the faces of OBJ text (materials of its mtllib files too). */
RfStatus rf__obj_read(const char *name, const char *text, size_t len, const RfObjPlacement *pl,
                      RfScene *scene, char *err, size_t errsz);

#endif
