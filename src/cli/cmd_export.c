/* `refray export --mitsuba OUT.xml | --pbrt OUT.pbrt | --pov OUT.pov SCENE`: the scene for
 * another renderer, so that it can check refray's full ray-traced images (make crosscheck,
 * docs/crosscheck.md). The writers are in src/scene/export*.c. */
#include <stdio.h>

#include "args.h"
#include "cli.h"
#include "exit_codes.h"
#include "refray/image.h"
#include "refray/scene.h"
#include "refray/scene_export.h"
#include "refray/scene_io.h"

enum { OPT_MITSUBA = RF_OPT_ID, OPT_PBRT, OPT_POV, OPT_WIDTH, OPT_HEIGHT, OPT_DEPTH, OPT_SAMPLES, OPT_TWO, OPT_SHADOWS,
       OPT_LOSSY, OPT_QUIET };

static const RfOpt export_opts[] = {
    {"mitsuba", OPT_MITSUBA, "OUT.xml", "Mitsuba 3 XML (triangles go to OUT-meshK.obj beside it)", NULL},
    {"pbrt", OPT_PBRT, "OUT.pbrt", "pbrt-v4", NULL},
    {"pov", OPT_POV, "OUT.pov", "POV-Ray 3.7 SDL (render with +FE -A; `// resolution W H` names the size)", NULL},
    {"width", OPT_WIDTH, "W", "the image width (default: the scene's; the field of view is read for it)",
     "a whole number in [1, 65536]"},
    {"height", OPT_HEIGHT, "H", "the image height (default: the scene's)", "a whole number in [1, 65536]"},
    {"depth", OPT_DEPTH, "D", "refray's recursion depth to match (default: the scene's)", "a whole number in [1, 1000]"},
    {"samples", OPT_SAMPLES, "N", "samples per pixel for Mitsuba and pbrt (default: the scene's)",
     "a whole number in [1, 1048576]"},
    {"two-sided", OPT_TWO, NULL, "every surface visible from both sides (as refray render --two-sided)", NULL},
    {"shadows", OPT_SHADOWS, "MODE", "opaque or filtered: the shadow rule refray renders with (default: the "
     "scene's)", "opaque or filtered"},
    {"lossy", OPT_LOSSY, NULL, "write the nearest thing for what cannot be represented, with a warning", NULL},
    {"quiet", OPT_QUIET, NULL, "no notes on stderr (a refusal's are still printed)", NULL},
    RF_OPT_TABLE_END,
};

static const RfOpt *const export_tables[] = {export_opts, rf_opts_load, NULL};

static const RfCommand export_cmd = {
    "refray export",
    "refray export (--mitsuba OUT.xml | --pbrt OUT.pbrt | --pov OUT.pov) [options] SCENE\n",
    "Writes SCENE (.nff, .rf, .obj) for another renderer: what it can represent exactly (Lambertian\n"
    "diffuse, mirrors, Fresnel glass, point/spot/directional lights, pinhole and thin-lens cameras,\n"
    "spheres, triangles, polygons, planes, cylinders, instances (flattened; an ellipsoid or a sheared\n"
    "cylinder with its placement's matrix for POV-Ray and pbrt); area lights where the target hides\n"
    "them as refray does), with the conversions in the file's header comment (docs/crosscheck.md).\n"
    "Anything else (a Phong highlight in Mitsuba, ambient light, a light without falloff in\n"
    "Mitsuba, ...) is named with its file:line:col and refuses the export (nothing written) unless\n"
    "--lossy.\n",
    export_tables,
    "exit: 0 written, 2 refused (what the target cannot represent), 4 the scene cannot be read or an\n"
    "output cannot be written, 5 usage (README: Exit codes)\n",
};

int rf_cmd_export(int argc, char **argv)
{
    RfExportOptions eo = rf_export_options_default();
    RfLoadOptions lo = rf_load_options_default();
    const char *output = NULL, *path = NULL;
    int formats = 0, quiet = 0, key;
    RfOptParser p;
    rf_opt_init(&p, &export_cmd, argc, argv);
    while ((key = rf_opt_next(&p)) != RF_OPT_DONE) {
        const char *v = p.value;
        int ok = 1;
        switch (key) {
        case RF_OPT_EXIT:
            return p.exit_code;
        case OPT_MITSUBA: case OPT_PBRT: case OPT_POV:
            eo.format = key == OPT_MITSUBA ? RF_EXPORT_MITSUBA : key == OPT_PBRT ? RF_EXPORT_PBRT : RF_EXPORT_POV;
            output = v;
            formats++;
            break;
        case OPT_WIDTH: ok = rf_arg_int(v, 1, 65536, &eo.width); break;
        case OPT_HEIGHT: ok = rf_arg_int(v, 1, 65536, &eo.height); break;
        case OPT_DEPTH: ok = rf_arg_int(v, 1, 1000, &eo.depth); break;
        case OPT_SAMPLES: ok = rf_arg_int(v, 1, 1 << 20, &eo.samples); break;
        case OPT_TWO: eo.two_sided = 1; break;
        case OPT_SHADOWS: ok = (eo.shadows = rf_shadow_mode_parse(v)) >= 0; break;
        case OPT_LOSSY: eo.lossy = 1; break;
        case OPT_QUIET: quiet = 1; break;
        default: ok = rf_arg_shared(key, v, &lo, NULL) > 0; break;
        }
        if (!ok)
            return rf_opt_bad_value(&p);
    }
    if (formats != 1)
        return rf_opt_usage_error(&export_cmd, "give exactly one of --mitsuba, --pbrt, --pov");
    int bad = rf_opt_operand(&p, "the scene file", &path);
    if (bad)
        return bad;
    const char *outs[1] = {output}, *ins[1] = {path};
    if ((bad = rf_arg_outputs_check("refray export", outs, 1, ins, 1)) != 0)
        return bad;
    char err[1024];
    RfScene scene;
    if (rf_scene_load(path, &lo, &scene, err, sizeof err) != RF_OK) {
        rf_arg_report("refray export", err);
        return RF_EXIT_FILE;
    }
    eo.source = path;
    eo.output = output;
    RfExport ex;
    RfStatus st = rf_scene_export(&scene, &eo, &ex);
    rf_scene_free(&scene);
    if (st == RF_ERR_NOMEM) {
        fprintf(stderr, "refray export: out of memory\n");
        rf_export_free(&ex);
        return RF_EXIT_FAIL;
    }
    if (ex.notes && (!quiet || st != RF_OK))
        fputs(ex.notes, stderr);
    if (st != RF_OK) {
        fprintf(stderr, "refray export: %d feature%s of %s cannot be written for %s; nothing written%s\n",
                ex.problems, ex.problems == 1 ? "" : "s", path, rf_export_format_name(eo.format),
                eo.lossy ? "" : " (--lossy writes the nearest thing)");
        rf_export_free(&ex);
        return RF_EXIT_FAIL;
    }
    /* every file or none */
    RfWriteBatch *batch = rf_write_batch_new();
    if (!batch) {
        rf_export_free(&ex);
        fprintf(stderr, "refray export: out of memory\n");
        return RF_EXIT_FAIL;
    }
    for (size_t i = 0; i < ex.file_count; i++)
        if (rf_write_text(ex.files[i].path, ex.files[i].text, ex.files[i].len, batch, err, sizeof err) != RF_OK) {
            fprintf(stderr, "%s\n", err);
            rf_write_batch_abort(batch);
            rf_export_free(&ex);
            return RF_EXIT_FILE;
        }
    if (rf_write_batch_commit(batch, err, sizeof err) != RF_OK) {
        fprintf(stderr, "%s\n", err);
        rf_export_free(&ex);
        return RF_EXIT_FILE;
    }
    if (!quiet)
        fprintf(stderr, "refray export: %s -> %s (%s%s%zu file%s)\n", path, output, rf_export_format_name(eo.format),
                ex.problems ? ", approximated: see the notes; " : ", ", ex.file_count, ex.file_count == 1 ? "" : "s");
    rf_export_free(&ex);
    return RF_EXIT_OK;
}
