/* The `refray` command: dispatches to the subcommands. */
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "cli.h"
#include "exit_codes.h"
#include "opt.h"
#include "refray/version.h"

typedef struct {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
} Command;

static const Command commands[] = {
    {"render", rf_cmd_render, "ray trace a scene (.nff, .rf, .obj) to a linear EXR and a PNG (§3)"},
    {"merge", rf_cmd_merge, "put the tiles of one render (render --crop, --tiles) together, checked"},
    {"trace", rf_cmd_trace, "every ray of one pixel as the renderer computes it: hits, lights, Phong terms, Fresnel"},
    {"formula", rf_cmd_formula, "compute a formula of the lecture script (list, ID key=value, --batch)"},
    {"chromaticity", rf_cmd_chromaticity, "draw the CIE 1931 xy chromaticity diagram (PNG/SVG, §1.5)"},
    {"metamers", rf_cmd_metamers, "two different spectra with the same XYZ and LMS (§1.3.1)"},
    {"diff", rf_cmd_diff, "compare two images (EXR/PNG): errors, silhouettes, heatmap; exits like idiff"},
    {"grade", rf_cmd_grade, "grade a class of student images (PPM/PNG/JPEG/TIFF/BMP/HDR/EXR) against one reference"},
    {"bench", rf_cmd_bench, "run time against error: samplers x sample counts, time to relMSE 1e-3"},
    {"info", rf_cmd_info, "load a scene (.nff, .rf, .obj): counts, materials, lights, features used"},
    {"export", rf_cmd_export, "write a scene for Mitsuba 3, pbrt-v4 or POV-Ray, conversions documented (make crosscheck)"},
};

static void usage(FILE *out)
{
    fprintf(out, "refray %s, a reference renderer for computer-graphics teaching\n\n"
                 "usage: refray COMMAND ...\n\ncommands:\n", RF_VERSION);
    for (size_t i = 0; i < sizeof commands / sizeof commands[0]; i++)
        fprintf(out, "  %-13s %s\n", commands[i].name, commands[i].summary);
    fprintf(out, "\n'refray COMMAND --help' tells more.\n");
}

/* Large blocks from the heap, and memory freed kept there for the next ones: a render frees
 * the OBJ reader's arrays and then the BVH build's records just before it asks for as much
 * again, and every fresh page costs a fault and clearing (glibc hands blocks over 32 MB out as
 * their own mappings and unmaps them when freed). The process's peak grows by what it holds
 * freed; docs/performance.md measures both. */
static void reuse_freed_memory(void)
{
#if defined(__GLIBC__)
    mallopt(M_MMAP_MAX, 0);
    mallopt(M_TRIM_THRESHOLD, INT_MAX);
#endif
}

int main(int argc, char **argv)
{
    reuse_freed_memory();
    /* a file-size limit fails the write (EFBIG), which cleans up, instead of killing the process
     * with a temporary file left behind */
    signal(SIGXFSZ, SIG_IGN);
    enum { N = sizeof commands / sizeof commands[0] };
    if (argc < 2) {
        usage(stderr);
        fprintf(stderr, "refray: missing the command\n");
        return RF_EXIT_USAGE;
    }
    const char *a = argv[1];
    if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0 || strcmp(a, "help") == 0) {
        usage(stdout);
        return RF_EXIT_OK;
    }
    if (strcmp(a, "--version") == 0 || strcmp(a, "-V") == 0) {
        printf("refray %s\n", RF_VERSION);
        return RF_EXIT_OK;
    }
    const char *names[N];
    for (size_t i = 0; i < N; i++) {
        names[i] = commands[i].name;
        if (strcmp(a, commands[i].name) == 0)
            return commands[i].run(argc - 1, argv + 1);
    }
    int s = a[0] == '-' ? -1 : rf_suggest(a, names, N);
    fprintf(stderr, "refray: unknown %s '%s'", a[0] == '-' ? "option" : "command", a);
    if (s >= 0)
        fprintf(stderr, "; did you mean '%s'?", names[s]);
    fprintf(stderr, " (see: refray --help)\n");
    return RF_EXIT_USAGE;
}
