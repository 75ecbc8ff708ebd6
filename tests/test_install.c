/* The installable library (issue 17): librefray.so exports the public API and nothing else,
 * the examples build against the headers and the in-tree library and print the right numbers,
 * `make install` (tools/install.sh) into a temporary prefix gives a refray.pc with which a
 * 20-line program builds by pkg-config alone (shared and --static), man pages that man renders
 * and a bash completion that completes, and uninstall removes every file it put; docs/api.md
 * lists every public function; refray render --deps and refray.mk rebuild exactly what changed. */
#define _XOPEN_SOURCE 700
#include "rf_test.h"

#include <limits.h>
#include <stdlib.h>
#include <unistd.h>

#include "refray/image.h"
#include "refray/vec.h"
#include "refray/version.h"

/* the shell commands of this file are made here (several long paths each) */
static char cmd[1 << 17], want[1 << 15];

/* the build folder (beside rf_test_bin) into out */
static int build_dir(char *out, size_t size)
{
    char bin[PATH_MAX];
    if (!rf_test_tool("refray", bin, sizeof bin)) {
        rf_test_fail(__FILE__, __LINE__, "cannot resolve %s", rf_test_bin());
        return 0;
    }
    snprintf(out, size, "%.*s", (int)(strrchr(bin, '/') - bin), bin);
    return 1;
}

/* the compiler of the build (with its sanitizer flags: a sanitized library needs them) */
static const char *cc(void)
{
    const char *c = getenv("RF_CC");
    return c && *c ? c : "cc";
}

/* runs cmd (stderr into stdout); fails the test with the output when the exit code is not 0 */
static const char *run_ok(const char *command, int line)
{
    int code;
    static char full[sizeof cmd + 8];
    snprintf(full, sizeof full, "%s 2>&1", command);
    const char *out = rf_test_run(full, &code);
    rf_test_checks++;
    if (code != 0)
        rf_test_fail(__FILE__, line, "exit %d: %s\n%s", code, command, out);
    return code == 0 ? out : NULL;
}

static int temp_dir(char *dir, size_t size)
{
    snprintf(dir, size, "%s/refray-install-XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(dir)) {
        rf_test_fail(__FILE__, __LINE__, "mkdtemp");
        return 0;
    }
    return 1;
}

static void rm_tree(const char *dir)
{
    char rm[PATH_MAX + 16];
    int code;
    snprintf(rm, sizeof rm, "rm -rf '%s'", dir);
    rf_test_run(rm, &code);
}

/* The shared library: named by the version of version.h, soname librefray.so.MAJOR, the dev
 * links; exports the functions of the public headers (spot checks) and none of the internal
 * ones (rf__*, the readers' lexer, the I/O helpers). */
static void t_lib_shared_exports(void)
{
    char b[PATH_MAX];
    char major[16];
    if (!build_dir(b, sizeof b))
        return;
    snprintf(major, sizeof major, "%.*s", (int)strcspn(RF_VERSION, "."), RF_VERSION);
    snprintf(cmd, sizeof cmd, "readelf -d '%s/librefray.so.%s' | sed -n 's/.*SONAME.*\\[\\(.*\\)\\]/\\1/p'", b, RF_VERSION);
    const char *out = run_ok(cmd, __LINE__);
    if (out) {
        snprintf(want, sizeof want, "librefray.so.%s\n", major);
        RF_CHECK_STR(out, want);
    }
    snprintf(cmd, sizeof cmd, "readlink '%s/librefray.so' '%s/librefray.so.%s'", b, b, major);
    if ((out = run_ok(cmd, __LINE__))) {
        snprintf(want, sizeof want, "librefray.so.%s\nlibrefray.so.%s\n", major, RF_VERSION);
        RF_CHECK_STR(out, want);
    }
    snprintf(cmd, sizeof cmd, "nm -D --defined-only '%s/librefray.so' | awk '{print $3}' | sort", b);
    if (!(out = run_ok(cmd, __LINE__)))
        return;
    static const char *const public_names[] = {"\nrf_scene_load\n", "\nrf_render\n", "\nrf_exr_write\n",
                                               "\nrf_formula_run_json\n", "\nrf_snell\n", "\nrf_status_str\n"};
    for (size_t i = 0; i < sizeof public_names / sizeof public_names[0]; i++)
        if (!strstr(out, public_names[i]))
            rf_test_fail(__FILE__, __LINE__, "%.*s not exported", (int)strlen(public_names[i]) - 2,
                         public_names[i] + 1);
    RF_CHECK(strstr(out, "\nrf__") == NULL && strncmp(out, "rf__", 4) != 0);
    RF_CHECK(strstr(out, "\nrf_lex_") == NULL);
    RF_CHECK(strstr(out, "\nrf_io_fail") == NULL);
    /* every exported symbol is refray's (rf_); nothing of the dependencies leaks */
    int n = 0;
    for (const char *p = out; *p; p = strchr(p, '\n') + 1) {
        if (strncmp(p, "rf_", 3) != 0)
            rf_test_fail(__FILE__, __LINE__, "exported: %.*s", (int)strcspn(p, "\n"), p);
        n++;
        if (!strchr(p, '\n'))
            break;
    }
    RF_CHECK(n > 200);
}

/* examples/formulas.c against the in-tree shared library: the registry's answers and the C
 * functions, each against a value derived by hand. */
static void t_lib_example_formulas(void)
{
    char b[PATH_MAX], dir[PATH_MAX];
    if (!build_dir(b, sizeof b) || !temp_dir(dir, sizeof dir))
        return;
    snprintf(cmd, sizeof cmd,
             "%s -std=c99 -Wall -Wextra -Wpedantic -Werror -Iinclude examples/formulas.c -o '%s/formulas' "
             "-L'%s' -lrefray -lm && LD_LIBRARY_PATH='%s' '%s/formulas'",
             cc(), dir, b, b, dir);
    const char *out = run_ok(cmd, __LINE__);
    if (out) {
        /* reflect d = (1,-1,0) at n = (0,1,0): (1,1,0); luminance 0.3 + 0.59/2 + 0.11/4 */
        RF_CHECK(strstr(out, "reflect: {\"r\":[1,1,0]}\n") != NULL);
        const char *y = strstr(out, "luminance: {\"y\":");
        RF_CHECK(y != NULL);
        if (y)
            RF_CHECK_NEAR(strtod(y + strlen("luminance: {\"y\":"), NULL), 0.3 + 0.59 * 0.5 + 0.11 * 0.25, 1e-15, 0);
        /* normal incidence from air into glass: ((1.5 - 1)/(1.5 + 1))^2 = 0.04 */
        const char *r = strstr(out, "fresnel: {\"r\":");
        RF_CHECK(r != NULL);
        if (r)
            RF_CHECK_NEAR(strtod(r + strlen("fresnel: {\"r\":"), NULL), 0.04, 1e-14, 0);
        RF_CHECK(strstr(out, "cross: 0 0 1\n") != NULL);
        /* sin theta_t = sin 30 deg / 1.5 = 1/3 */
        const char *s = strstr(out, "snell: theta_t ");
        RF_CHECK(s != NULL);
        if (s)
            RF_CHECK_NEAR(strtod(s + strlen("snell: theta_t "), NULL), asin(1.0 / 3.0) * 180.0 / RF_PI, 1e-14, 0);
    }
    rm_tree(dir);
}

/* examples/render_scene.c, linked against librefray.a this time: its EXR is refray render's
 * image of the same scene and size, bit for bit. */
static void t_lib_example_render(void)
{
    char b[PATH_MAX], dir[PATH_MAX];
    const char *pkgs = getenv("RF_PKGS");
    if (!build_dir(b, sizeof b) || !temp_dir(dir, sizeof dir))
        return;
    snprintf(cmd, sizeof cmd,
             "%s -std=c99 -Wall -Wextra -Wpedantic -Werror -Iinclude examples/render_scene.c -o '%s/render_scene' "
             "'%s/librefray.a' $(pkg-config --libs %s) -lm -pthread && '%s/render_scene' scenes/whitted.rf '%s/lib.exr' 40 30"
             " && %s render scenes/whitted.rf -o '%s/cli.exr' --width 40 --height 30 --quiet",
             cc(), dir, b, pkgs ? pkgs : "libcjson zlib libpng OpenEXR", dir, dir, rf_test_bin(), dir);
    const char *out = run_ok(cmd, __LINE__);
    if (out) {
        RF_CHECK(strncmp(out, "40x30, 1200 primary rays, centre ", 33) == 0);
        RfImage a, c;
        char err[512], pa[PATH_MAX + 16], pc[PATH_MAX + 16];
        snprintf(pa, sizeof pa, "%s/lib.exr", dir);
        snprintf(pc, sizeof pc, "%s/cli.exr", dir);
        if (rf_exr_read(pa, &a, err, sizeof err) == RF_OK) {
            if (rf_exr_read(pc, &c, err, sizeof err) == RF_OK) {
                RF_CHECK(a.width == 40 && a.height == 30 && c.width == 40 && c.height == 30);
                RF_CHECK(a.channels == c.channels &&
                         memcmp(a.data, c.data, sizeof(float) * 40 * 30 * (size_t)a.channels) == 0);
                /* the centre pixel it printed is the image's */
                const float *m = c.data + (15 * 40 + 20) * c.channels;
                char want[128];
                snprintf(want, sizeof want, "centre %.9g %.9g %.9g\n", m[0], m[1], m[2]);
                RF_CHECK(strstr(out, want) != NULL);
                rf_image_free(&c);
            }
            rf_image_free(&a);
        } else {
            rf_test_fail(__FILE__, __LINE__, "%s", err);
        }
    }
    rm_tree(dir);
}

/* The "done when": install into a temporary prefix, build examples/hello.c with
 * pkg-config alone (PKG_CONFIG_PATH into the prefix), shared and --static (the .so taken away),
 * run both: refray render's pixel; man renders the pages from the prefix; the completion
 * completes; uninstall leaves no file. The same with DESTDIR (refray.pc keeps the real prefix). */
static void t_install_pkgconfig_man_completion(void)
{
    char b[PATH_MAX], dir[PATH_MAX], env[1024], cwd[PATH_MAX];
    const char *out;
    if (!build_dir(b, sizeof b) || !getcwd(cwd, sizeof cwd) || !temp_dir(dir, sizeof dir))
        return;
    snprintf(env, sizeof env, "RF_VERSION=%s RF_PKGS='%s'", RF_VERSION,
             getenv("RF_PKGS") ? getenv("RF_PKGS") : "libcjson cairo fontconfig zlib libpng OpenEXR");
    snprintf(cmd, sizeof cmd, "%s sh tools/install.sh install '%s' '' '%s/usr' '%s/usr/lib'", env, b, dir, dir);
    if (!(out = run_ok(cmd, __LINE__))) {
        rm_tree(dir);
        return;
    }
    RF_CHECK(strncmp(out, "installed ", 10) == 0);
    want[0] = 0;
    {
        /* pixel (16, 12) of refray render at 32 x 24 */
        char pe[PATH_MAX + 16], c2[PATH_MAX * 2], err[512];
        int code;
        RfImage img;
        snprintf(pe, sizeof pe, "%s/cli.exr", dir);
        snprintf(c2, sizeof c2, "%s render scenes/whitted.rf -o '%s' --width 32 --height 24 --quiet", rf_test_bin(), pe);
        rf_test_run(c2, &code);
        if (code == 0 && rf_exr_read(pe, &img, err, sizeof err) == RF_OK) {
            const float *p = img.data + (12 * 32 + 16) * img.channels;
            snprintf(want, sizeof want, "refray %s: pixel (16, 12) = %.9g %.9g %.9g\n", RF_VERSION, p[0], p[1], p[2]);
            rf_image_free(&img);
        } else {
            rf_test_fail(__FILE__, __LINE__, "refray render failed");
        }
    }
    /* shared: pkg-config alone; the rpath comes from LD_LIBRARY_PATH as after ldconfig */
    snprintf(cmd, sizeof cmd,
             "export PKG_CONFIG_PATH='%s/usr/lib/pkgconfig'; cd '%s' && cp '%s/examples/hello.c' . && "
             "%s hello.c -o hello $(pkg-config --cflags --libs refray) && "
             "readelf -d hello | grep -c 'NEEDED.*librefray.so.%.*s' && LD_LIBRARY_PATH='%s/usr/lib' ./hello '%s/scenes/whitted.rf'",
             dir, dir, cwd, cc(), (int)strcspn(RF_VERSION, "."), RF_VERSION, dir, cwd);
    out = run_ok(cmd, __LINE__);
    if (out) { /* one NEEDED librefray.so.MAJOR, then the pixel */
        RF_CHECK(strncmp(out, "1\n", 2) == 0);
        RF_CHECK_STR(out + (out[0] ? 2 : 0), want);
    }
    /* --static: the same program from librefray.a and Libs.private/Requires.private, with the
     * shared library out of the way */
    snprintf(cmd, sizeof cmd,
             "export PKG_CONFIG_PATH='%s/usr/lib/pkgconfig'; cd '%s' && mkdir -p so && mv usr/lib/librefray.so* so/ && "
             "%s hello.c -o hello-static $(pkg-config --static --cflags --libs refray); st=$?; mv so/* usr/lib/; "
             "[ $st = 0 ] && readelf -d hello-static | grep -c 'NEEDED.*librefray'; ./hello-static '%s/scenes/whitted.rf'",
             dir, dir, cc(), cwd);
    int code;
    static char full[sizeof cmd + 8];
    snprintf(full, sizeof full, "%s 2>&1", cmd);
    out = rf_test_run(full, &code);
    RF_CHECK(strncmp(out, "0\n", 2) == 0); /* no librefray.so needed, the same pixel */
    RF_CHECK_STR(out + (out[0] ? 2 : 0), want);
    /* man: the pages of the prefix, one per command (refray --help's list) and program */
    int have_man = rf_test_have("man");
    if (!have_man)
        fprintf(stderr, "  skipped rendering the man pages: man is not installed (apt-get install man-db)\n");
    snprintf(cmd, sizeof cmd, "MANPATH='%s/usr/share/man' MANWIDTH=100 man -P cat refray-render | sed -n '1,5p' | tr -s ' '", dir);
    if (have_man && (out = run_ok(cmd, __LINE__)))
        RF_CHECK(strstr(out, "NAME\n refray-render - ray trace a scene") != NULL);
    snprintf(cmd, sizeof cmd,
             "d='%s/usr/share/man/man1'; "
             "for c in $(%s --help | awk '/^[Cc]ommands:/ {on=1; next} on && /^$/ {exit} on {print $1}') ; do "
             "test -f \"$d/refray-$c.1\" || echo missing $c; done; "
             "for p in refray refray-raster refray-verify refray-view; do %s; done",
             dir, rf_test_bin(),
             have_man ? "MANWIDTH=100 man -l \"$d/$p.1\" 2>&1 | grep -c '^SYNOPSIS'"
                      : "grep -c '^.SH SYNOPSIS' \"$d/$p.1\"");
    if ((out = run_ok(cmd, __LINE__)))
        RF_CHECK_STR(out, "1\n1\n1\n1\n");
    /* completion: `refray re<TAB>` -> render; options of a command; an option's values; a
     * formula id; the link for refray-raster */
    snprintf(cmd, sizeof cmd,
             "bash -c 'source \"%s/usr/share/bash-completion/completions/refray\"; "
             "c() { COMP_WORDS=(\"$@\"); COMP_CWORD=$(($# - 1)); COMPREPLY=(); _refray; echo \"${COMPREPLY[*]}\"; }; "
             "c refray re; c refray render --samp; c refray render --sampler so; c refray render --sampler = so; "
             "c refray-raster --gl=e; c refray formula fres; "
             "c refray di; readlink \"%s/usr/share/bash-completion/completions/refray-raster\"'",
             dir, dir);
    if ((out = run_ok(cmd, __LINE__)))
        RF_CHECK_STR(out, "render\n--sampler --samples\nsobol\nsobol\negl\nfresnel\ndiff\nrefray\n");
    /* uninstall: every file, link and folder install made gone (the prefix too: install made it) */
    snprintf(cmd, sizeof cmd, "sh tools/install.sh uninstall '' '%s/usr' '%s/usr/lib' && { test -e '%s/usr' || echo gone; }",
             dir, dir, dir);
    if ((out = run_ok(cmd, __LINE__)))
        RF_CHECK(strstr(out, "removed ") == out && strstr(out, "\ngone\n") != NULL);
    /* DESTDIR: staged under it, the .pc names the real prefix; uninstall with it */
    snprintf(cmd, sizeof cmd,
             "%s sh tools/install.sh install '%s' '%s/stage' /opt/refray /opt/refray/lib >/dev/null && "
             "sed -n 's/^prefix=//p' '%s/stage/opt/refray/lib/pkgconfig/refray.pc' && "
             "test -x '%s/stage/opt/refray/bin/refray' && test -f '%s/stage/opt/refray/share/refray/refray.mk' && "
             "touch '%s/stage/opt/refray/lib/other.so' && "
             "sh tools/install.sh uninstall '%s/stage' /opt/refray /opt/refray/lib >/dev/null && "
             "find '%s/stage' | sort",
             env, b, dir, dir, dir, dir, dir, dir, dir);
    /* a file of someone else's keeps its folders; the staging folder is not install's to remove */
    snprintf(want, sizeof want, "/opt/refray\n%s/stage\n%s/stage/opt\n%s/stage/opt/refray\n%s/stage/opt/refray/lib\n"
             "%s/stage/opt/refray/lib/other.so\n", dir, dir, dir, dir, dir);
    if ((out = run_ok(cmd, __LINE__)))
        RF_CHECK_STR(out, want);
    rm_tree(dir);
}

/* docs/api.md (made by `make docs`, tools/apidoc.sh) names every function a public header
 * declares (found here independently of the generator: a line at column 0, outside comments,
 * with rf_NAME( after its return type). */
static void t_docs_api_complete(void)
{
    int code;
    const char *out;
    FILE *f = fopen("docs/api.md", "rb");
    static char doc[1 << 20];
    size_t n = f ? fread(doc, 1, sizeof doc - 1, f) : 0;
    if (f)
        fclose(f);
    doc[n] = 0;
    RF_CHECK(n > 0);
    out = rf_test_run("ls include/refray/*.h", &code);
    char list[8192];
    snprintf(list, sizeof list, "%s", out);
    int functions = 0;
    for (char *h = strtok(list, "\n"); h; h = strtok(NULL, "\n")) {
        FILE *hf = fopen(h, "r");
        char line[1024];
        int comment = 0;
        while (hf && fgets(line, sizeof line, hf)) {
            char *p = line;
            if (comment) { /* inside a block comment: skip to its end */
                char *e = strstr(p, "*/");
                if (!e)
                    continue;
                comment = 0;
                p = e + 2;
                if (*p == '\n' || *p == 0)
                    continue;
            }
            if (strncmp(p, "/*", 2) == 0 && !strstr(p, "*/")) {
                comment = 1;
                continue;
            }
            if (p != line || *p == ' ' || *p == '\t' || *p == '#' || *p == '/' || *p == '}' || *p == '\n')
                continue;
            char *cut = strstr(p, "/*"); /* a trailing comment */
            if (cut)
                *cut = 0;
            char *name = strstr(p, "rf_");
            if (!name || (name > p && (name[-1] == '_' || (name[-1] >= 'a' && name[-1] <= 'z'))))
                continue;
            size_t len = strspn(name, "abcdefghijklmnopqrstuvwxyz0123456789_");
            if (name[len] != '(' || strncmp(p, "typedef", 7) == 0)
                continue;
            char want[128];
            snprintf(want, sizeof want, " %.*s(", (int)len, name);
            functions++;
            if (!strstr(doc, want) && !strstr(doc, want + 1))
                rf_test_fail(__FILE__, __LINE__, "%s: %.*s is not in docs/api.md (make docs remakes it)", h,
                             (int)len, name);
        }
        if (hf)
            fclose(hf);
    }
    RF_CHECK(functions > 250);
}

/* refray render --deps: the outputs depend on the scene and every file it read, as the scene
 * names them -- for scenes/mesh.rf its two meshes (`mesh gem.obj`, `mesh torus.obj`) and
 * gem.obj's `mtllib gem.mtl` -- with a rule per file (make -MP); names with a space escaped; a
 * gzip scene is its .gz file; a render that fails writes none. */
static void t_render_deps_file(void)
{
    char dir[PATH_MAX];
    if (!temp_dir(dir, sizeof dir))
        return;
    snprintf(cmd, sizeof cmd,
             "%s render scenes/mesh.rf -o '%s/m.exr' --png '%s/a b.png' --deps '%s/m.d' --width 8 --height 6 --quiet"
             " && cat '%s/m.d'", rf_test_bin(), dir, dir, dir, dir);
    const char *out = run_ok(cmd, __LINE__);
    snprintf(want, sizeof want,
             "%s/m.exr %s/a\\ b.png: scenes/gem.obj scenes/gem.mtl scenes/torus.obj scenes/mesh.rf\n"
             "\nscenes/gem.obj:\n\nscenes/gem.mtl:\n\nscenes/torus.obj:\n\nscenes/mesh.rf:\n", dir, dir);
    if (out)
        RF_CHECK_STR(out, want);
    snprintf(cmd, sizeof cmd,
             "%s render scenes/spd/gears.nff.gz -o '%s/g.exr' --deps '%s/g.d' --width 4 --height 3 --quiet"
             " && head -n 1 '%s/g.d'", rf_test_bin(), dir, dir, dir);
    snprintf(want, sizeof want, "%s/g.exr: scenes/spd/gears.nff.gz\n", dir);
    if ((out = run_ok(cmd, __LINE__)))
        RF_CHECK_STR(out, want);
    /* a missing mesh: the render fails, no dependency file (nor image) */
    snprintf(cmd, sizeof cmd,
             "printf 'camera eye 0 0 5 target 0 0 0 up 0 1 0 fov 40\\nmesh nowhere.obj\\n' > '%s/bad.rf';"
             " %s render '%s/bad.rf' -o '%s/bad.exr' --deps '%s/bad.d' --quiet 2>/dev/null; echo $?;"
             " ls '%s' | grep -c '^bad\\.[de]'", dir, rf_test_bin(), dir, dir, dir, dir);
    int code;
    out = rf_test_run(cmd, &code);
    RF_CHECK(strncmp(out, "0\n", 2) != 0 && strstr(out, "\n0\n") != NULL);
    rm_tree(dir);
}

/* examples/course/: a course repository using refray.mk. make builds every reference; with
 * nothing touched nothing is rebuilt; touching the pyramid's mesh or its material library
 * rebuilds the pyramid's images only; make grade (refray grade) passes the references themselves
 * and fails a missing image. */
static void t_course_makefile(void)
{
    char dir[PATH_MAX], cwd[PATH_MAX], bin[PATH_MAX], mk[1 << 14];
    const char *out;
    int code;
    if (!getcwd(cwd, sizeof cwd) || !realpath(rf_test_bin(), bin) || !temp_dir(dir, sizeof dir))
        return;
    /* a make of its own: not a sub-make of make test's (its -j, jobserver and variables) */
    snprintf(mk, sizeof mk, "env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL -u MAKEOVERRIDES make -C '%s/course' "
             "--no-print-directory REFRAY='%s' REFRAY_MK='%s/tools/refray.mk'",
             dir, bin, cwd);
    snprintf(cmd, sizeof cmd, "cp -r examples/course '%s/' && rm -f '%s'/course/scenes/*.exr* '%s'/course/scenes/*.png"
             " && %s -s && ls '%s/course/scenes' | grep -c '\\.exr$\\|\\.png$\\|\\.exr\\.d$'", dir, dir, dir, mk, dir);
    if (!(out = run_ok(cmd, __LINE__))) {
        rm_tree(dir);
        return;
    }
    RF_CHECK_STR(out, "9\n"); /* 3 scenes: EXR, PNG, .d each */
    snprintf(cmd, sizeof cmd, "%s -q; echo $?; %s -n", mk, mk);
    if ((out = run_ok(cmd, __LINE__)))
        RF_CHECK_STR(out, "0\nmake: Nothing to be done for 'all'.\n");
    /* make compares times: the touched file must be newer than the images, so wait a second */
    static const char *const inputs[] = {"pyramid.obj", "pyramid.mtl", "pyramid.rf"};
    for (int i = 0; i < 3; i++) {
        snprintf(cmd, sizeof cmd,
                 "cd '%s/course/scenes' && stat -c %%Y.%%y cube.exr spheres.exr > before && sleep 1 && touch %s && "
                 "%s -n | grep -c 'render' && %s -n | grep -c 'render scenes/pyramid.rf' && %s -s && "
                 "stat -c %%Y.%%y cube.exr spheres.exr | cmp - before && test pyramid.exr -nt %s && test pyramid.png -nt %s"
                 " && %s -q && echo ok", dir, inputs[i], mk, mk, mk, inputs[i], inputs[i], mk);
        if ((out = run_ok(cmd, __LINE__)))
            RF_CHECK_STR(out, "1\n1\nok\n");
    }
    /* make grade: refray grade per reference, "NAME VERDICT SCORE ..." lines, a report each */
    snprintf(cmd, sizeof cmd,
             "cd '%s/course' && mkdir -p student && cp scenes/*.png student/ && g=$(%s grade STUDENT=student 2>/dev/null);"
             " st=$?; printf '%%s\\n' \"$g\" | awk '{print $1, $2}'; echo $st; ls grade-report/*/grades.csv | wc -l;"
             " rm student/cube.png && %s grade STUDENT=student 2>/dev/null; echo $?",
             dir, mk, mk);
    out = rf_test_run(cmd, &code);
    if (strncmp(out, "pyramid pass\nspheres pass\ncube pass\n0\n3\n", 40) != 0)
        rf_test_fail(__FILE__, __LINE__, "make grade printed:\n%s", out);
    rf_test_checks++;
    const char *second = strstr(out, "\n3\n"); /* the run without cube.png */
    RF_CHECK(second && strstr(second, "\ncube ") && strstr(second, "unreadable"));
    RF_CHECK(strlen(out) > 2 && strcmp(out + strlen(out) - 2, "2\n") == 0);
    rm_tree(dir);
}

const RfTest rf_tests_install[] = {
    {"lib_shared_exports", t_lib_shared_exports},
    {"lib_example_formulas", t_lib_example_formulas},
    {"lib_example_render", t_lib_example_render},
    {"install_pkgconfig_man_completion", t_install_pkgconfig_man_completion},
    {"docs_api_complete", t_docs_api_complete},
    {"render_deps_file", t_render_deps_file},
    {"course_makefile", t_course_makefile},
    RF_TEST_END,
};
