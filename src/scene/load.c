/* refray: loading a scene file: the format by extension or content, then its reader (the steps
 * every reader shares are reader.c, below the readers). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "reader.h"
#include "refray/hash.h"
#include "refray/scene_io.h"

/* Without a known extension: NFF when the first keyword is one of NFF's. */
static int looks_like_nff(const char *text, size_t len)
{
    static const char *const nff[] = {"v", "b", "l", "f", "c", "s", "p", "pp"};
    RfLexer lx;
    rf_lex_init(&lx, "", text, len, NULL, 0);
    for (size_t i = 0; i < sizeof nff / sizeof nff[0]; i++)
        if (rf_lex_is(&lx.tok, nff[i]))
            return 1;
    return 0;
}

RfStatus rf_scene_load(const char *path, const RfLoadOptions *opt, RfScene *scene, char *err,
                       size_t errsz)
{
    size_t n = strlen(path);
    size_t base = rf__ends_with(path, n, ".gz") ? n - 3 : n;
    char *text = NULL;
    size_t len = 0;
    rf_scene_init(scene);
    RfStatus st = rf__reader_read_file(NULL, path, &text, &len, err, errsz);
    if (st)
        return st;
    int nff = rf__ends_with(path, base, ".nff") ||
              (!rf__ends_with(path, base, ".rf") && !rf__ends_with(path, base, ".obj") &&
               looks_like_nff(text, len));
    if (rf__ends_with(path, base, ".obj"))
        st = rf_scene_read_obj(path, text, len, opt, scene, err, errsz);
    else
        st = nff ? rf_scene_read_nff(path, text, len, opt, scene, err, errsz)
                 : rf__scene_read_rf(path, text, len, opt, scene, err, errsz);
    if (st == RF_OK) /* after the files it included, which the readers hashed as they read them */
        scene->source_hash = rf_hash_bytes(scene->source_hash, text, len);
    if (st == RF_OK && (st = rf__reader_add_file(scene, path, err, errsz)))
        rf_scene_free(scene);
    free(text);
    return st;
}
