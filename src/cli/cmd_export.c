/* `refray export --mitsuba OUT.xml | --pbrt OUT.pbrt | --pov OUT.pov SCENE`: the scene for
 * another renderer, so that it can check refray's full ray-traced images (make crosscheck,
 * docs/crosscheck.md). The writers are in src/scene/export*.c. */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "exit_codes.h"
#include "refray/image.h"
#include "refray/scene.h"
#include "refray/scene_export.h"
#include "refray/scene_io.h"

static void usage(FILE *out)
{
    fprintf(out,
            "usage: refray export (--mitsuba OUT.xml | --pbrt OUT.pbrt | --pov OUT.pov) [options] SCENE\n\n"
            "Writes SCENE (.nff, .rf, .obj) for another renderer: what it can represent exactly (Lambertian\n"
            "diffuse, mirrors, Fresnel glass, point/spot/directional lights, pinhole cameras, spheres,\n"
            "triangles, polygons, planes, cylinders; area lights and thin lenses where the target has them),\n"
            "with the conversions in the file's header comment (docs/crosscheck.md). Anything else (a Phong\n"
            "highlight in Mitsuba, ambient light, a light without falloff in Mitsuba, ...) is named with its\n"
            "file:line:col and refuses the export (exit 2, nothing written) unless --lossy.\n"
            "  --mitsuba OUT.xml   Mitsuba 3 XML (triangles go to OUT-meshK.obj beside it)\n"
            "  --pbrt OUT.pbrt     pbrt-v4\n"
            "  --pov OUT.pov       POV-Ray 3.7 SDL (render with +FE -A; `// resolution W H` names the size)\n"
            "  --width W --height H  the image size (default: the scene's; the field of view is read for it)\n"
            "  --depth D           refray's recursion depth to match (default: the scene's)\n"
            "  --samples N         samples per pixel for Mitsuba and pbrt (default: the scene's)\n"
            "  --two-sided         every surface visible from both sides (as refray render --two-sided)\n"
            "  --shadows opaque|filtered  the shadow rule refray renders with (default: the scene's)\n"
            "  --nff-fov centres|edges    how NFF's angle is read (as refray render)\n"
            "  --lossy             write the nearest thing for what cannot be represented, with a warning\n"
            "  --quiet             no notes on stderr (refusals are still printed)\n"
            "exit: 0 written, 2 refused (what the target cannot represent), 4 unreadable scene or unwritable\n"
            "output, 5 usage\n");
}

static int int_arg(const char *v, int lo, int hi, int *out)
{
    char *end;
    long x = strtol(v, &end, 10);
    if (*v == '\0' || *end != '\0' || x < lo || x > hi)
        return 0;
    *out = (int)x;
    return 1;
}

int rf_cmd_export(int argc, char **argv)
{
    enum { O_MITSUBA = 256, O_PBRT, O_POV, O_WIDTH, O_HEIGHT, O_DEPTH, O_SAMPLES, O_TWO, O_SHADOWS, O_FOV, O_LOSSY,
           O_QUIET, O_HELP };
    static const struct option longs[] = {
        {"mitsuba", required_argument, NULL, O_MITSUBA}, {"pbrt", required_argument, NULL, O_PBRT},
        {"pov", required_argument, NULL, O_POV},         {"width", required_argument, NULL, O_WIDTH},
        {"height", required_argument, NULL, O_HEIGHT},  {"depth", required_argument, NULL, O_DEPTH},
        {"samples", required_argument, NULL, O_SAMPLES}, {"two-sided", no_argument, NULL, O_TWO},
        {"shadows", required_argument, NULL, O_SHADOWS}, {"nff-fov", required_argument, NULL, O_FOV},
        {"lossy", no_argument, NULL, O_LOSSY},           {"quiet", no_argument, NULL, O_QUIET},
        {"help", no_argument, NULL, O_HELP},             {NULL, 0, NULL, 0},
    };
    RfExportOptions eo = rf_export_options_default();
    RfLoadOptions lo = rf_load_options_default();
    const char *output = NULL;
    int formats = 0, quiet = 0, c;
    opterr = 0;
    optind = 1;
    while ((c = getopt_long(argc, argv, "h", longs, NULL)) != -1) {
        const char *v = optarg;
        switch (c) {
        case O_MITSUBA: case O_PBRT: case O_POV:
            eo.format = c == O_MITSUBA ? RF_EXPORT_MITSUBA : c == O_PBRT ? RF_EXPORT_PBRT : RF_EXPORT_POV;
            output = v;
            formats++;
            break;
        case O_WIDTH: case O_HEIGHT: case O_DEPTH: case O_SAMPLES: {
            int *dst = c == O_WIDTH ? &eo.width : c == O_HEIGHT ? &eo.height : c == O_DEPTH ? &eo.depth : &eo.samples;
            if (!int_arg(v, 1, c == O_DEPTH ? 1000 : c == O_SAMPLES ? 1 << 20 : 65536, dst)) {
                fprintf(stderr, "refray export: bad value '%s' for %s: a whole number in range (see: refray export "
                        "--help)\n", v, argv[optind - 1]);
                return RF_EXIT_USAGE;
            }
            break;
        }
        case O_TWO: eo.two_sided = 1; break;
        case O_LOSSY: eo.lossy = 1; break;
        case O_QUIET: quiet = 1; break;
        case O_SHADOWS:
            if (strcmp(v, "opaque") != 0 && strcmp(v, "filtered") != 0) {
                fprintf(stderr, "refray export: bad value '%s' for --shadows: opaque or filtered\n", v);
                return RF_EXIT_USAGE;
            }
            eo.shadows = strcmp(v, "filtered") == 0 ? RF_SHADOWS_FILTERED : RF_SHADOWS_OPAQUE;
            break;
        case O_FOV:
            if (strcmp(v, "centres") != 0 && strcmp(v, "edges") != 0) {
                fprintf(stderr, "refray export: bad value '%s' for --nff-fov: centres or edges\n", v);
                return RF_EXIT_USAGE;
            }
            lo.nff_fov = strcmp(v, "edges") == 0 ? RF_FOV_EDGES : RF_FOV_PIXEL_CENTRES;
            break;
        case 'h': case O_HELP:
            usage(stdout);
            return RF_EXIT_OK;
        default:
            fprintf(stderr, "refray export: unknown option or missing value '%s' (see: refray export --help)\n",
                    argv[optind - 1]);
            return RF_EXIT_USAGE;
        }
    }
    if (formats != 1 || optind != argc - 1) {
        fprintf(stderr, "refray export: %s (see: refray export --help)\n",
                formats != 1 ? "give exactly one of --mitsuba, --pbrt, --pov" : "give one scene");
        return RF_EXIT_USAGE;
    }
    const char *path = argv[optind];
    char err[1024];
    RfScene scene;
    if (rf_scene_load(path, &lo, &scene, err, sizeof err) != RF_OK) {
        fprintf(stderr, "%s\n", err);
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
        fprintf(stderr, "refray export: %d feature%s of %s cannot be written for %s; nothing written (--lossy "
                "writes the nearest thing)\n", ex.problems, ex.problems == 1 ? "" : "s", path,
                rf_export_format_name(eo.format));
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
