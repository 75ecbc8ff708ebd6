/* refray: helpers shared by the scene readers (internal; implemented in load.c). */
#ifndef RF_SCENE_READER_H
#define RF_SCENE_READER_H

#include "lexer.h"
#include "refray/scene.h"

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

#endif
