/* refray export (issue 16): the writers' numbers against hand-derived values (docs/crosscheck.md),
 * refusals with their file:line, the command's exit codes and files, and, where Mitsuba 3 is
 * importable, a small cross-render (tools/crosscheck.py). POV-Ray's renders of exported scenes
 * are checked in tests/test_povray.c. */
#include "rf_test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "refray/scene.h"
#include "refray/scene_export.h"
#include "refray/scene_io.h"

#define PI 3.14159265358979323846

/* The number after `key` and the next '"' or '[' or '<' (the first number of a value). */
static double num_after(const char *text, const char *key, int nth)
{
    const char *p = strstr(text, key);
    if (!p)
        return NAN;
    p += strlen(key);
    while (*p && !(*p == '-' || (*p >= '0' && *p <= '9')))
        p++;
    char *end;
    double x = strtod(p, &end);
    for (int i = 0; i < nth; i++) {
        p = end;
        while (*p && !(*p == '-' || (*p >= '0' && *p <= '9')))
            p++;
        x = strtod(p, &end);
    }
    return x;
}

/* export_text's flags: 1 --lossy, 2 --two-sided */
enum { EX_LOSSY = 1, EX_TWO_SIDED = 2 };

static int export_text(const char *text, RfExportFormat f, int flags, RfExport *ex, RfStatus *st)
{
    RfScene s;
    char err[512];
    if (rf_scene_read_rf("t.rf", text, strlen(text), &s, err, sizeof err) != RF_OK) {
        rf_test_fail(__FILE__, __LINE__, "scene: %s", err);
        return 0;
    }
    RfExportOptions o = rf_export_options_default();
    o.format = f;
    o.source = "t.rf";
    o.output = "/tmp/out.x";
    o.lossy = (flags & EX_LOSSY) != 0;
    o.two_sided = (flags & EX_TWO_SIDED) != 0;
    *st = rf_scene_export(&s, &o, ex);
    rf_scene_free(&s);
    return 1;
}

static const char *SCENE =
    "camera eye 0 0 5  target 0 0 0  up 0 1 0  fov 40\n"
    "resolution 160 120\n"
    "depth 3\n"
    "light point 1 2 3  intensity 2\n"
    "light directional 0 -1 0  intensity 0.5\n"
    "light spot 0 4 0  axis 0 -1 0  cutoff 30  intensity 3\n"
    "material dif  kd 0.25 0.5 0.75\n"
    "sphere 0 0 0  1\n"
    "material mir  kr 0.8\n"
    "sphere 2 0 0  0.5\n"
    "material glass  kr 1  kt 1  ior 1.5  fresnel\n"
    "sphere -2 0 0  0.5\n"
    "material mix  kd 0.2  kr 0.3\n"
    "polygon 4  0 0 0  1 0 0  1 1 0  0 1 0\n";

static void t_export_mitsuba_numbers(void)
{
    RfExport ex;
    RfStatus st;
    if (!export_text(SCENE, RF_EXPORT_MITSUBA, 0, &ex, &st))
        return;
    RF_CHECK(st == RF_OK);
    RF_CHECK_EQ_INT(ex.file_count, 2); /* the XML and one OBJ (the polygon) */
    if (st != RF_OK || ex.file_count != 2) {
        rf_export_free(&ex);
        return;
    }
    const char *x = ex.files[0].text;
    /* light at the hits 1 .. depth: Mitsuba's max_depth = depth + 1 */
    RF_CHECK_NEAR(num_after(x, "name=\"max_depth\"", 0), 4.0, 0, 0);
    /* the vertical field of view edge to edge: 2 atan(t / d) = 40 */
    RF_CHECK_NEAR(num_after(x, "name=\"fov\"", 0), 40.0, 1e-13, 0);
    /* rho = kd, I' = pi I: point 2 -> 2 pi, directional 0.5 -> pi / 2, spot 3 -> 3 pi */
    RF_CHECK_NEAR(num_after(x, "<emitter type=\"point\">", 3), 2.0 * PI, 1e-15, 0);
    RF_CHECK_NEAR(num_after(x, "name=\"irradiance\"", 0), 0.5 * PI, 1e-15, 0);
    RF_CHECK_NEAR(num_after(strstr(x, "type=\"spot\""), "name=\"intensity\"", 0), 3.0 * PI, 1e-15, 0);
    RF_CHECK_NEAR(num_after(x, "name=\"cutoff_angle\"", 0), 30.0, 0, 0);
    RF_CHECK_NEAR(num_after(x, "name=\"beam_width\"", 0), 30.0, 0, 0);
    /* diffuse reflectance kd as it is */
    const char *d = strstr(x, "'dif'");
    RF_CHECK(d && num_after(d, "name=\"reflectance\"", 0) == 0.25 && num_after(d, "name=\"reflectance\"", 2) == 0.75);
    /* the mirror: a conductor of reflectance kr */
    const char *m = strstr(x, "'mir'");
    RF_CHECK(m && strstr(m, "type=\"conductor\"") && num_after(m, "specular_reflectance", 0) == 0.8);
    /* Fresnel glass: a dielectric with ior 1.5, reflectance kr and transmittance kt */
    const char *g = strstr(x, "'glass'");
    RF_CHECK(g && strstr(g, "type=\"dielectric\"") && num_after(g, "int_ior", 0) == 1.5 &&
             num_after(g, "specular_transmittance", 0) == 1.0);
    /* kd 0.2 + kr 0.3 as a blend of weight 1/2 of diffuse 0.4 and conductor 0.6 */
    const char *b = strstr(x, "'mix'");
    RF_CHECK(b && strstr(b, "blendbsdf") && num_after(b, "name=\"weight\"", 0) == 0.5 &&
             num_after(b, "name=\"reflectance\"", 0) == 0.4 && num_after(b, "specular_reflectance", 0) == 0.6);
    /* the .rf default is two-sided: the diffuse BSDF wrapped */
    RF_CHECK(strstr(x, "<bsdf type=\"twosided\" id=\"m0t\">") != NULL);
    /* the polygon as two triangles of the fan in the OBJ beside it */
    RF_CHECK(strstr(ex.files[1].path, "/tmp/out-mesh0.obj") != NULL);
    RF_CHECK(strstr(ex.files[1].text, "f 1 2 3\nf 1 3 4\n") != NULL);
    RF_CHECK(strstr(x, "value=\"out-mesh0.obj\"") != NULL);
    /* no "--" inside the XML comment */
    const char *c0 = strstr(x, "<!--"), *c1 = strstr(x, "-->");
    RF_CHECK(c0 && c1);
    if (c0 && c1) {
        int dashes = 0;
        for (const char *p = c0 + 4; p < c1; p++)
            dashes |= p[0] == '-' && p[1] == '-';
        RF_CHECK(!dashes);
    }
    rf_export_free(&ex);
}

static void t_export_pov_numbers(void)
{
    RfExport ex;
    RfStatus st;
    if (!export_text(SCENE, RF_EXPORT_POV, 0, &ex, &st))
        return;
    RF_CHECK(st == RF_OK && ex.file_count == 1);
    if (st != RF_OK || ex.file_count != 1) {
        rf_export_free(&ex);
        return;
    }
    const char *x = ex.files[0].text;
    RF_CHECK(strstr(x, "// resolution 160 120\n") != NULL);
    RF_CHECK(strstr(x, "max_trace_level 3 adc_bailout 0 ") != NULL);
    /* eye (0,0,5) looking at the origin, up y: u = up x w = x, v = y; the window of fov 40 at
     * d = 1: t = tan(20 deg), r = t 160/120. direction -z, right 2r x, up 2t y */
    double t = tan(20.0 * PI / 180.0);
    const char *cam = strstr(x, "camera {");
    RF_CHECK(cam != NULL);
    if (cam) {
        RF_CHECK_NEAR(num_after(cam, "direction", 2), -1.0, 1e-15, 0);
        RF_CHECK_NEAR(num_after(cam, "right", 0), 2.0 * t * 160.0 / 120.0, 1e-15, 0);
        RF_CHECK_NEAR(num_after(cam, "up <", 1), 2.0 * t, 1e-15, 0);
    }
    /* inverse-square by the fade: colour I / (2 fd^2) with fade_distance fd */
    const char *l = strstr(x, "light_source { <1, 2, 3>");
    RF_CHECK(l != NULL);
    if (l) {
        double col = num_after(l, "color rgb", 0), fd = num_after(l, "fade_distance", 0);
        RF_CHECK_NEAR(col * 2.0 * fd * fd, 2.0, 1e-14, 0);
        RF_CHECK(fd > 0.0 && fd < 1e-3);
    }
    /* spot: radius = falloff = cutoff, tightness = exponent (0) */
    RF_CHECK(strstr(x, "radius 30 falloff 30 tightness 0") != NULL);
    /* directional: parallel */
    RF_CHECK(strstr(x, " parallel point_at") != NULL);
    /* glass: filter 1, Fresnel reflection, conserve_energy, ior; and its shadow discs (2 lights
     * with a position) */
    RF_CHECK(strstr(x, "rgbf <1, 1, 1, 1>") && strstr(x, "reflection { 0, rgb <1, 1, 1> fresnel on } conserve_energy") &&
             strstr(x, "interior { ior 1.5 }"));
    int discs = 0;
    for (const char *p = x; (p = strstr(p, "disc {")) != NULL; p++)
        discs++;
    RF_CHECK_EQ_INT(discs, 2);
    rf_export_free(&ex);

    /* the scene's threshold is POV-Ray's adc_bailout (the same rule: a ray whose weight falls
     * below it is left out) */
    char with[4096];
    snprintf(with, sizeof with, "threshold 0.004\n%s", SCENE);
    if (export_text(with, RF_EXPORT_POV, 0, &ex, &st)) {
        RF_CHECK(st == RF_OK && ex.file_count == 1 &&
                 strstr(ex.files[0].text, "max_trace_level 3 adc_bailout 0.004 ") != NULL);
        rf_export_free(&ex);
    }

    /* NFF's angle between the outermost pixel centres: half-height tan(A/2) H / (H - 1) */
    const char *nff = "v\nfrom 0 0 5\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0\nresolution 160 120\n"
                      "l 1 1 1\nf 1 0 0 1 0 0 0 0\ns 0 0 0 1\n";
    RfScene s;
    char err[256];
    if (rf_scene_read_nff("t.nff", nff, strlen(nff), NULL, &s, err, sizeof err) != RF_OK) {
        rf_test_fail(__FILE__, __LINE__, "%s", err);
        return;
    }
    RfExportOptions o = rf_export_options_default();
    o.format = RF_EXPORT_POV;
    RF_CHECK(rf_scene_export(&s, &o, &ex) == RF_OK);
    if (ex.file_count == 1) {
        RF_CHECK_NEAR(num_after(strstr(ex.files[0].text, "camera {"), "up <", 1), 2.0 * t * 120.0 / 119.0, 1e-15, 0);
        /* NFF lights: no falloff, no fade; intensity 1/sqrt(1) */
        RF_CHECK(strstr(ex.files[0].text, "light_source { <1, 1, 1> color rgb <1, 1, 1> }") != NULL);
    }
    rf_export_free(&ex);
    rf_scene_free(&s);
}

static void t_export_pbrt_numbers(void)
{
    RfExport ex;
    RfStatus st;
    /* pbrt-v4's dielectric and diffuse only: the mirror and the blend are noted */
    if (!export_text(SCENE, RF_EXPORT_PBRT, EX_LOSSY, &ex, &st))
        return;
    RF_CHECK(st == RF_OK && ex.file_count == 1);
    if (ex.file_count == 1) {
        const char *x = ex.files[0].text;
        double t = tan(20.0 * PI / 180.0);
        RF_CHECK(strstr(x, "Scale -1 1 1\nLookAt 0 0 5  0 0 0  0 1 0\n") != NULL);
        RF_CHECK_NEAR(num_after(x, "\"float screenwindow\"", 0), -t * 160.0 / 120.0, 1e-15, 0);
        RF_CHECK_NEAR(num_after(x, "\"float screenwindow\"", 3), t, 1e-15, 0);
        RF_CHECK_NEAR(num_after(x, "\"integer maxdepth\"", 0), 3.0, 0, 0);
        RF_CHECK_NEAR(num_after(x, "\"rgb I\"", 0), 2.0 * PI, 1e-15, 0);
        RF_CHECK(strstr(x, "\"dielectric\" \"float eta\" [ 1.5 ]") != NULL);
    }
    RF_CHECK(ex.notes && strstr(ex.notes, "t.rf:9:1: material 'mir': mirror kr"));
    rf_export_free(&ex);
    /* a material's note once, not once per shape (a mesh has thousands) */
    if (!export_text("camera eye 0 0 5  target 0 0 0  up 0 1 0  fov 40\nlight point 0 3 3\n"
                     "material p  kd 0.5  ks 0.5  shininess 20\ntriangle 0 0 0  1 0 0  0 1 0\n"
                     "triangle 0 0 1  1 0 1  0 1 1\ntriangle 0 0 2  1 0 2  0 1 2\n",
                     RF_EXPORT_PBRT, EX_LOSSY, &ex, &st))
        return;
    int notes = 0;
    for (const char *n = ex.notes; n && (n = strstr(n, "material 'p': Phong highlight")) != NULL; n++)
        notes++;
    RF_CHECK_EQ_INT(notes, 1);
    int shapes = 0;
    for (const char *t = ex.file_count == 1 ? ex.files[0].text : NULL; t && (t = strstr(t, "Material \"diffuse\"")) != NULL; t++)
        shapes++;
    RF_CHECK(st == RF_OK);
    RF_CHECK_EQ_INT(shapes, 3); /* each shape still has its material */
    rf_export_free(&ex);
}

/* What the target cannot represent refuses the export, naming the object and its line. */
static void t_export_refusals(void)
{
    static const struct {
        RfExportFormat f;
        const char *scene, *note;
    } cases[] = {
        {RF_EXPORT_MITSUBA, "material red  kd 0.7 0 0  ks 0.5  shininess 20\nsphere 0 0 0 1\n",
         "t.rf:3:1: material 'red': Phong highlight"},
        {RF_EXPORT_MITSUBA, "light point 0 5 0  falloff none\nmaterial w kd 1\nsphere 0 0 0 1\n",
         "t.rf:3:1: point light without falloff"},
        {RF_EXPORT_MITSUBA, "material g  kt 1  ior 1.5\nsphere 0 0 0 1\n", "t.rf:3:1: material 'g': kt without `fresnel`"},
        {RF_EXPORT_MITSUBA, "light spot 0 5 0  axis 0 -1 0  cutoff 20  exponent 4\nmaterial w kd 1\nsphere 0 0 0 1\n",
         "t.rf:3:1: spot light with exponent 4"},
        {RF_EXPORT_MITSUBA, "light rect 0 2 0  1 0 0  0 0 1  radiance 2\nmaterial w kd 1\nsphere 0 0 0 1\n",
         "t.rf:3:1: rect area light: Mitsuba's area emitter is a shape"},
        {RF_EXPORT_POV, "ambient 0.1\nmaterial w kd 1  ka 1\nsphere 0 0 0 1\n", "t.rf:4:1: material 'w': ambient term"},
        {RF_EXPORT_POV, "material g  kr 0.5  kt 1  ior 1.5  fresnel\nsphere 0 0 0 1\n",
         "t.rf:3:1: material 'g': Fresnel glass with kr"},
        {RF_EXPORT_PBRT, "material e  kd 1  emission 2\nsphere 0 0 0 1\n", "t.rf:3:1: material 'e': emission"},
        {RF_EXPORT_POV, "material w kd 1\nsphere 0 0 0 1  inside\n", "t.rf:4:1: inside-only sphere: POV-Ray's sphere"},
        {RF_EXPORT_MITSUBA, "material w kd 1\nobject b\nsphere 0 0 0 1\nend\ninstance b scale 1 2 1\n",
         "t.rf:5:1: sphere under a non-similarity transform: Mitsuba's sphere takes no non-uniform scale"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char text[512];
        snprintf(text, sizeof text, "camera eye 0 0 5  target 0 0 0  up 0 1 0  fov 40\nlight point 0 3 3\n%s",
                 cases[i].scene);
        RfExport ex;
        RfStatus st;
        if (!export_text(text, cases[i].f, 0, &ex, &st))
            continue;
        RF_CHECK(st == RF_ERR_DOMAIN && ex.file_count == 0 && ex.problems >= 1);
        if (!(ex.notes && strstr(ex.notes, cases[i].note)))
            rf_test_fail(__FILE__, __LINE__, "case %zu: notes '%s', expected '%s'", i, ex.notes ? ex.notes : "",
                         cases[i].note);
        rf_test_checks++;
        rf_export_free(&ex);
        /* --lossy writes it anyway, the note kept */
        if (!export_text(text, cases[i].f, EX_LOSSY, &ex, &st))
            continue;
        if (!(st == RF_OK && ex.file_count >= 1 && ex.notes && strstr(ex.notes, cases[i].note)))
            rf_test_fail(__FILE__, __LINE__, "case %zu with --lossy: status %d, %zu files, notes '%s'", i, (int)st,
                         ex.file_count, ex.notes ? ex.notes : "");
        rf_test_checks++;
        rf_export_free(&ex);
    }
    /* --two-sided: refray then sees an inside-only sphere from outside too, as every target does */
    static const char inside[] = "camera eye 0 0 5  target 0 0 0  up 0 1 0  fov 40\nlight point 0 3 3\n"
                                 "material w kd 1\nsphere 0 0 0 1  inside\n";
    static const RfExportFormat formats[] = {RF_EXPORT_MITSUBA, RF_EXPORT_PBRT, RF_EXPORT_POV};
    for (size_t f = 0; f < 3; f++) {
        RfExport ex;
        RfStatus st;
        if (!export_text(inside, formats[f], EX_TWO_SIDED, &ex, &st))
            continue;
        RF_CHECK_EQ_INT(st, RF_OK);
        RF_CHECK(!ex.notes || !strstr(ex.notes, "inside-only"));
        rf_export_free(&ex);
    }
}

/* Quadrics under non-similarity transforms (scenes/crosscheck/placed.rf's kind): POV-Ray and pbrt
 * get the quadric in its object's space with the placement's matrix, by hand: the instance's
 * `scale 1 2 1 translate 0 1 0` and the `matrix` rows (1 0.5 0 1.6 / 0 1.6 0 0 / 0 0 1 -0.4) as
 * POV-Ray's rows (the matrix's columns) and pbrt's column-major ConcatTransform. Mitsuba with
 * --lossy gets meshes whose every vertex lies on the placed surface with its normal there, and
 * whose every triangle winds around those normals. */
static const char *PLACED =
    "camera eye 0 1 6  target 0 1 0  up 0 1 0  fov 40\n"
    "light point 2 4 4  intensity 10\n"
    "material w kd 0.5\n"
    "object b\nsphere 0 0 0 1\nend\n"
    "instance b scale 1 2 1  translate 0 1 0\n"
    "object c\ncylinder 0 0 0  0 1 0  0.4\nend\n"
    "instance c matrix 1 0.5 0 1.6  0 1.6 0 0  0 0 1 -0.4\n";

/* PLACED's ellipsoid and sheared cylinder: how far x is from the surface, and the unit normal
 * there by (M^-1)^T (§4.9). The cylinder: object point p = M^-1 x = (x - 1.6 - 0.5 p.y, y / 1.6,
 * z + 0.4) on p.x^2 + p.z^2 = 0.16, 0 <= p.y <= 1; normal (M^-1)^T (p.x, 0, p.z) = (p.x,
 * -0.3125 p.x, p.z). */
static double ellipsoid_at(RfVec3 x, RfVec3 *normal)
{
    *normal = rf_vec3_normalize(rf_vec3(x.x, (x.y - 1) / 4, x.z));
    return fabs(x.x * x.x + (x.y - 1) * (x.y - 1) / 4 + x.z * x.z - 1);
}

static double sheared_cylinder_at(RfVec3 x, RfVec3 *normal)
{
    double py = x.y / 1.6, px = x.x - 1.6 - 0.5 * py, pz = x.z + 0.4;
    *normal = rf_vec3_normalize(rf_vec3(px, -0.3125 * px, pz));
    return fmax(fabs(px * px + pz * pz - 0.16), fmax(-py, py - 1));
}

/* A placed quadric's mesh (Mitsuba --lossy): its vertex count, every vertex on the surface with
 * the surface's normal, the face count, and every face wound around those normals. */
static void check_placed_obj(const char *text, double (*surface)(RfVec3, RfVec3 *), int want_v, int want_faces)
{
    static RfVec3 v[97 * 49], vn[97 * 49];
    int nv = 0, nn = 0, faces = 0, bad_winding = 0;
    double worst_v = 0.0, worst_n = 0.0;
    for (const char *l = text; l && *l; l = strchr(l, '\n') ? strchr(l, '\n') + 1 : NULL) {
        double a, b, c;
        int i[3];
        RfVec3 want;
        if (sscanf(l, "v %lf %lf %lf", &a, &b, &c) == 3 && nv < 97 * 49) {
            v[nv++] = rf_vec3(a, b, c);
            worst_v = fmax(worst_v, surface(v[nv - 1], &want));
        } else if (sscanf(l, "vn %lf %lf %lf", &a, &b, &c) == 3 && nn < nv) {
            surface(v[nn], &want);
            vn[nn++] = rf_vec3(a, b, c);
            worst_n = fmax(worst_n, rf_vec3_length(rf_vec3_sub(rf_vec3(a, b, c), want)));
        } else if (sscanf(l, "f %d//%*d %d//%*d %d//%*d", &i[0], &i[1], &i[2]) == 3) {
            faces++;
            if (i[0] < 1 || i[1] < 1 || i[2] < 1 || i[0] > nv || i[1] > nv || i[2] > nv) {
                bad_winding++;
                continue;
            }
            RfVec3 a0 = v[i[0] - 1], g = rf_vec3_cross(rf_vec3_sub(v[i[1] - 1], a0), rf_vec3_sub(v[i[2] - 1], a0));
            bad_winding += !(rf_vec3_dot(g, rf_vec3_add(vn[i[0] - 1], rf_vec3_add(vn[i[1] - 1], vn[i[2] - 1]))) > 0.0);
        }
    }
    RF_CHECK_EQ_INT(nv, want_v);
    RF_CHECK_EQ_INT(nn, want_v);
    RF_CHECK_EQ_INT(faces, want_faces);
    RF_CHECK_EQ_INT(bad_winding, 0);
    RF_CHECK(worst_v < 1e-14);
    RF_CHECK(worst_n < 1e-14);
}

static void t_export_placed_quadrics(void)
{
    RfExport ex;
    RfStatus st;
    if (!export_text(PLACED, RF_EXPORT_POV, 0, &ex, &st))
        return;
    RF_CHECK(st == RF_OK && ex.file_count == 1);
    if (ex.file_count == 1) {
        RF_CHECK(strstr(ex.files[0].text, "sphere { <0, 0, 0>, 1\n  matrix <1, 0, 0,  0, 2, 0,  0, 0, 1,  0, 1, 0>\n"));
        RF_CHECK(strstr(ex.files[0].text, "cone { <0, 0, 0>, 0.4, <0, 1, 0>, 0.4 open\n"
                                          "  matrix <1, 0, 0,  0.5, 1.6, 0,  0, 0, 1,  1.6, 0, -0.4>\n"));
    }
    rf_export_free(&ex);
    if (!export_text(PLACED, RF_EXPORT_PBRT, 0, &ex, &st))
        return;
    RF_CHECK(st == RF_OK && ex.file_count == 1);
    if (ex.file_count == 1) {
        RF_CHECK(strstr(ex.files[0].text, "  ConcatTransform [ 1 0 0 0  0 2 0 0  0 0 1 0  0 1 0 1 ]\n"
                                          "  Translate 0 0 0\n  Shape \"sphere\" \"float radius\" [ 1 ]\n"));
        RF_CHECK(strstr(ex.files[0].text, "  ConcatTransform [ 1 0 0 0  0.5 1.6 0 0  0 0 1 0  1.6 0 -0.4 1 ]\n"
                                          "  ConcatTransform [ "));
    }
    rf_export_free(&ex);
    /* Mitsuba: refused without --lossy (the earlier case of t_export_refusals), a mesh with it */
    if (!export_text(PLACED, RF_EXPORT_MITSUBA, EX_LOSSY, &ex, &st))
        return;
    RF_CHECK(st == RF_OK && ex.file_count == 3);
    if (ex.file_count == 3) {
        RF_CHECK(strstr(ex.files[0].text, "value=\"out-placed0.obj\"") && strstr(ex.files[0].text, "value=\"out-placed1.obj\""));
        RF_CHECK(strcmp(ex.files[1].path, "/tmp/out-placed0.obj") == 0);
        check_placed_obj(ex.files[1].text, ellipsoid_at, 97 * 49, 96 * 48 * 2 - 2 * 96); /* the poles' degenerate triangles left out */
        check_placed_obj(ex.files[2].text, sheared_cylinder_at, 97 * 2, 96 * 2);
    }
    rf_export_free(&ex);
}

/* The command: files written together, nothing on refusal, exit codes. */
static void t_export_cli(void)
{
    char dir[] = "/tmp/rf_export_XXXXXX";
    if (!mkdtemp(dir)) {
        rf_test_fail(__FILE__, __LINE__, "mkdtemp failed");
        return;
    }
    char cmd[8192], bin[1024];
    int code;
    if (!rf_test_tool("refray", bin, sizeof bin)) {
        rf_test_fail(__FILE__, __LINE__, "cannot resolve %s", bin);
        return;
    }
    snprintf(cmd, sizeof cmd,
             "cd %s && printf 'camera eye 0 0 5 target 0 0 0 up 0 1 0 fov 40\\nlight point 0 3 3\\n"
             "material red kd 0.7 0 0 ks 0.5 shininess 20\\nsphere 0 0 0 1\\ntriangle 0 0 0 1 0 0 0 1 0\\n' > s.rf && "
             "%s export --mitsuba s.xml s.rf 2>err.txt; echo \"exit=$?\"; cat err.txt; ls",
             dir, bin);
    const char *out = rf_test_run(cmd, &code);
    RF_CHECK(strstr(out, "exit=2") != NULL);
    RF_CHECK(strstr(out, "s.rf:3:1: material 'red': Phong highlight") != NULL);
    RF_CHECK(strstr(out, "nothing written") != NULL);
    RF_CHECK(strstr(out, "s.xml") == NULL && strstr(out, "s-mesh0.obj") == NULL);
    snprintf(cmd, sizeof cmd, "cd %s && %s export --lossy --quiet --mitsuba s.xml s.rf; echo \"exit=$?\"; ls", dir,
             bin);
    out = rf_test_run(cmd, &code);
    RF_CHECK(strstr(out, "exit=0") && strstr(out, "s.xml") && strstr(out, "s-mesh0.obj"));
    snprintf(cmd, sizeof cmd, "cd %s && %s export s.rf 2>&1; echo \"exit=$?\"; %s export --pov a.pov --pbrt b.pbrt s.rf 2>&1; "
             "echo \"exit=$?\"; %s export --pov a.pov missing.rf 2>&1; echo \"exit=$?\"",
             dir, bin, bin, bin);
    out = rf_test_run(cmd, &code);
    RF_CHECK(strstr(out, "exit=5\n") != NULL && strstr(out, "give exactly one of --mitsuba, --pbrt, --pov") != NULL);
    RF_CHECK(strstr(out, "exit=4") != NULL && strstr(out, "missing.rf") != NULL);
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    rf_test_run(cmd, &code);
}

/* Where Mitsuba 3 is importable: the mirror scene rendered by both and z-tested (64 samples). */
static void t_export_mitsuba_crosscheck(void)
{
    int code;
    rf_test_run("python3 -c 'import mitsuba, numpy' 2>/dev/null", &code);
    if (code != 0) {
        fprintf(stderr, "  skipped: Mitsuba 3 is not importable (pip install mitsuba==3.5.2 numpy)\n");
        return;
    }
    char dir[] = "/tmp/rf_crosscheck_XXXXXX", cmd[1024];
    if (!mkdtemp(dir)) {
        rf_test_fail(__FILE__, __LINE__, "mkdtemp failed");
        return;
    }
    snprintf(cmd, sizeof cmd, "python3 tools/crosscheck.py --refray %s --out %s --samples 64 scenes/crosscheck/mirror.rf "
             "2>&1; echo \"exit=$?\"", rf_test_bin(), dir);
    const char *out = rf_test_run(cmd, &code);
    RF_CHECK(strstr(out, "mirror: Mitsuba: ") && strstr(out, "PASS") && strstr(out, "exit=0"));
    if (!strstr(out, "exit=0"))
        fprintf(stderr, "%s\n", out);
    /* a planted bias must fail: refray's light 5 % brighter than the one Mitsuba renders (the
     * export of the scene as it is); the image mean's z-test sees it (docs/crosscheck.md: 1 %
     * gives |z| > 20 at 1024 samples, 5 % at 64 is beyond 20 too) */
    snprintf(cmd, sizeof cmd,
             "d=%s; sed 's/^light point -3 5 4  intensity 30$/light point -3 5 4  intensity 31.5/' "
             "scenes/crosscheck/mirror.rf > $d/biased.rf && grep -q 'intensity 31.5' $d/biased.rf && "
             "%s render $d/biased.rf --samples 64 --sampler random --seed 1 -o $d/rf.exr --variance $d/rfv.exr --quiet && "
             "%s export --quiet --mitsuba $d/mi.xml scenes/crosscheck/mirror.rf --samples 1 && "
             "python3 -c \"import sys; sys.path.insert(0, 'tools'); import crosscheck as cc; "
             "m, v = cc.mitsuba_render('$d/mi.xml', 64, '$d/mi.exr', '$d/miv.exr', '$d/mi.png'); "
             "d, se, z, ref = cc.global_test(m, v, cc.read_exr('$d/rf.exr'), cc.read_exr('$d/rfv.exr')); "
             "print('z=%%.1f' %% min(z))\" 2>&1; rm -rf $d",
             dir, rf_test_bin(), rf_test_bin());
    out = rf_test_run(cmd, &code);
    const char *z = strstr(out, "z=");
    double zv = z ? strtod(z + 2, NULL) : 0.0;
    if (!(zv < -10.0))
        rf_test_fail(__FILE__, __LINE__, "a 5 %% brighter light in refray: image mean z = %g, expected below -10 "
                     "(output: %s)", zv, out);
    rf_test_checks++;
    fprintf(stderr, "  crosscheck: a 5 %% brighter light in refray gives image mean z = %.1f\n", zv);
}

const RfTest rf_tests_export[] = {
    {"export_mitsuba_numbers", t_export_mitsuba_numbers},
    {"export_pov_numbers", t_export_pov_numbers},
    {"export_pbrt_numbers", t_export_pbrt_numbers},
    {"export_refusals", t_export_refusals},
    {"export_placed_quadrics", t_export_placed_quadrics},
    {"export_cli", t_export_cli},
    {"export_mitsuba_crosscheck", t_export_mitsuba_crosscheck},
    RF_TEST_END,
};
