/* §1 colour science: the formula cases computed independently (tests/data/
 * formula_cases_color.jsonl, made by tools/oracle/gen_color_cases.py with colour-science, mpmath
 * and numpy), the CIE tables against published checkpoints, and the metamerism example. */
#include <cJSON.h>
#include <stdlib.h>
#include <string.h>

#include "refray/color.h"
#include "refray/formula.h"
#include "rf_test.h"

/* Absolute floor of every comparison: expected values that are 0 (or cancel to ~1e-17) are met
 * when the result is within 1e-12; every other value is held to the case's relative tolerance. */
#define ABS_FLOOR 1e-12

/* The ids of FORMULAS.md section 1. */
static const char *const section1_ids[] = {
    "dynamic-range", "linear-steps", "exp-steps", "exp-level", "power-transfer", "gamma-encode",
    "gamma-decode", "srgb-encode", "srgb-decode", "quantize", "alpha-over", "frequency",
    "cone-response", "luminance", "rgb-to-cmy", "cmy-to-rgb", "cmy-to-cmyk", "cmyk-to-cmy",
    "rgb-to-hsv", "hsv-to-rgb", "spectrum-to-rgb", "spectrum-to-xyz", "rgb-to-xyz", "xyz-to-rgb",
    "xyz-to-xyy", "xyy-to-xyz", "locus", "dominant-wavelength", "mix", "in-gamut", "gamut-map",
};
#define N_IDS (sizeof section1_ids / sizeof section1_ids[0])

/* Compares got against want (numbers, booleans, null, nested arrays); reports the first
 * difference with the case's line and the field path. Returns 1 when they agree. */
static int same(const cJSON *want, const cJSON *got, double rel, int line, const char *path)
{
    if (cJSON_IsNumber(want)) {
        if (cJSON_IsNumber(got) && rf_test_near(got->valuedouble, want->valuedouble, rel, ABS_FLOOR))
            return 1;
        rf_test_fail(__FILE__, __LINE__, "case line %d, %s = %.17g, expected %.17g (rel %g)", line,
                     path, cJSON_IsNumber(got) ? got->valuedouble : NAN, want->valuedouble, rel);
        return 0;
    }
    if (cJSON_IsBool(want) || cJSON_IsNull(want)) {
        if ((cJSON_IsTrue(want) && cJSON_IsTrue(got)) || (cJSON_IsFalse(want) && cJSON_IsFalse(got)) ||
            (cJSON_IsNull(want) && cJSON_IsNull(got)))
            return 1;
        char *g = got ? cJSON_PrintUnformatted(got) : NULL;
        rf_test_fail(__FILE__, __LINE__, "case line %d, %s = %s, expected %s", line, path,
                     g ? g : "(missing)", cJSON_IsNull(want) ? "null" : cJSON_IsTrue(want) ? "true" : "false");
        free(g);
        return 0;
    }
    if (cJSON_IsArray(want)) {
        if (!cJSON_IsArray(got) || cJSON_GetArraySize(got) != cJSON_GetArraySize(want)) {
            rf_test_fail(__FILE__, __LINE__, "case line %d, %s: not an array of %d", line, path,
                         cJSON_GetArraySize(want));
            return 0;
        }
        for (int i = 0; i < cJSON_GetArraySize(want); i++) {
            char sub[96];
            snprintf(sub, sizeof sub, "%s[%d]", path, i);
            if (!same(cJSON_GetArrayItem(want, i), cJSON_GetArrayItem(got, i), rel, line, sub))
                return 0;
        }
        return 1;
    }
    rf_test_fail(__FILE__, __LINE__, "case line %d, %s: unsupported expected value", line, path);
    return 0;
}

static char *read_file(const char *path)
{
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return NULL;
    fseek(fp, 0, SEEK_END);
    long n = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    char *s = malloc((size_t)n + 1);
    if (s && fread(s, 1, (size_t)n, fp) != (size_t)n) {
        free(s);
        s = NULL;
    }
    if (s)
        s[n] = 0;
    fclose(fp);
    return s;
}

/* Every case of the file, through the registry; also counts the cases per id. */
static void test_color_formula_cases(void)
{
    const char *path = rf_test_data("formula_cases_color.jsonl");
    char *text = read_file(path);
    int per_id[N_IDS] = {0}, cases = 0, line = 0;
    RF_CHECK(text != NULL);
    if (!text)
        return;
    for (char *p = text, *nl; *p; p = nl + 1) {
        nl = strchr(p, '\n');
        if (!nl)
            nl = p + strlen(p) - 1;
        else
            *nl = 0;
        line++;
        cJSON *c = cJSON_Parse(p);
        RF_CHECK(c != NULL);
        if (!c)
            continue;
        const cJSON *id = cJSON_GetObjectItemCaseSensitive(c, "id");
        const cJSON *expect = cJSON_GetObjectItemCaseSensitive(c, "expect");
        const cJSON *rel = cJSON_GetObjectItemCaseSensitive(c, "rel");
        const RfFormula *f = cJSON_IsString(id) ? rf_formula_find(id->valuestring) : NULL;
        rf_test_checks++;
        if (!f) {
            rf_test_fail(__FILE__, __LINE__, "case line %d: unknown id", line);
            cJSON_Delete(c);
            continue;
        }
        for (size_t i = 0; i < N_IDS; i++)
            per_id[i] += strcmp(section1_ids[i], f->id) == 0;
        char *in = cJSON_PrintUnformatted(cJSON_GetObjectItemCaseSensitive(c, "in"));
        char *out = NULL;
        int rc = rf_formula_run_json(f, in, &out);
        if (!expect) { /* an error case: must be refused with a message */
            rf_test_checks++;
            if (rc == 0 || !out || !*out)
                rf_test_fail(__FILE__, __LINE__, "case line %d (%s %s): accepted: %s", line, f->id,
                             in, out ? out : "");
        } else if (rc != 0) {
            rf_test_fail(__FILE__, __LINE__, "case line %d (%s): error %s", line, f->id, out);
        } else {
            cJSON *got = cJSON_Parse(out);
            const cJSON *e;
            cJSON_ArrayForEach(e, expect) {
                rf_test_checks++;
                same(e, cJSON_GetObjectItemCaseSensitive(got, e->string), cJSON_IsNumber(rel) ? rel->valuedouble : 1e-9,
                     line, e->string);
            }
            cJSON_Delete(got);
        }
        cases++;
        free(in);
        free(out);
        cJSON_Delete(c);
    }
    free(text);
    RF_CHECK(cases >= 150);
    for (size_t i = 0; i < N_IDS; i++) { /* every §1 id has independent cases */
        rf_test_checks++;
        if (per_id[i] < 2)
            rf_test_fail(__FILE__, __LINE__, "%s has %d cases", section1_ids[i], per_id[i]);
    }
}

static void test_color_ids_registered(void)
{
    for (size_t i = 0; i < N_IDS; i++) {
        const RfFormula *f = rf_formula_find(section1_ids[i]);
        RF_CHECK(f != NULL);
        RF_CHECK(f && (f->section[0] == '1' || strcmp(f->section, "beyond") == 0));
    }
}

static int argmax(RfCmf cmf, int channel)
{
    int first, last, best = 0;
    double mx = -1.0;
    rf_cmf_range(cmf, &first, &last);
    for (int l = first; l <= last; l++) {
        RfVec3 v = rf_cmf_at(cmf, l);
        double c = channel == 0 ? v.x : channel == 1 ? v.y : v.z;
        if (c > mx)
            mx = c, best = l;
    }
    return best;
}

/* CIE 015:2018 (CIE 1931 2°): ȳ(555) = 1, x̄(600) = 1.0622, z̄(445) = 1.7826, the peaks of
 * x̄ ȳ z̄ at 599, 555, 446 nm in the 1 nm table; Σȳ = 106.856895 (the normalisation constant
 * used e.g. by pbrt-v3, CIE_Y_integral) and Σx̄ ≈ Σȳ ≈ Σz̄ (equal-energy white). */
static void test_color_cie1931_checkpoints(void)
{
    int first, last;
    rf_cmf_range(RF_CMF_XYZ_1931, &first, &last);
    RF_CHECK_EQ_INT(first, 360);
    RF_CHECK_EQ_INT(last, 830);
    RF_CHECK(rf_cmf_at(RF_CMF_XYZ_1931, 555).y == 1.0);
    RF_CHECK_NEAR(rf_cmf_at(RF_CMF_XYZ_1931, 600).x, 1.0622, 1e-9, 0);
    RF_CHECK_NEAR(rf_cmf_at(RF_CMF_XYZ_1931, 445).z, 1.7826, 1e-9, 0);
    RF_CHECK_EQ_INT(argmax(RF_CMF_XYZ_1931, 0), 599);
    RF_CHECK_EQ_INT(argmax(RF_CMF_XYZ_1931, 1), 555);
    RF_CHECK_EQ_INT(argmax(RF_CMF_XYZ_1931, 2), 446);
    RfVec3 sum = rf_vec3(0, 0, 0);
    for (int l = first; l <= last; l++)
        sum = rf_vec3_add(sum, rf_cmf_at(RF_CMF_XYZ_1931, l));
    RF_CHECK_NEAR(sum.y, 106.856895, 1e-6, 0);
    RF_CHECK_NEAR(sum.x, sum.y, 5e-4, 0);
    RF_CHECK_NEAR(sum.z, sum.y, 5e-4, 0);
    RF_CHECK(rf_cmf_at(RF_CMF_XYZ_1931, 359.9).y == 0.0); /* 0 outside the table */
    RF_CHECK(rf_cmf_source(RF_CMF_XYZ_1931) && strstr(rf_cmf_source(RF_CMF_XYZ_1931), "CIE 015"));
}

/* CIE 170-1:2006 2° (CVRL linss2_10e_1): first row at 390 nm 4.15003e-4, 3.68349e-4,
 * 9.54729e-3; each function peak-normalised, with peaks at 570 (L), 543 (M), 442 nm (S). */
static void test_color_lms2006_checkpoints(void)
{
    int first, last;
    rf_cmf_range(RF_CMF_LMS_2006, &first, &last);
    RF_CHECK_EQ_INT(first, 390);
    RF_CHECK_EQ_INT(last, 830);
    RfVec3 v = rf_cmf_at(RF_CMF_LMS_2006, 390);
    RF_CHECK_NEAR(v.x, 4.15003e-4, 1e-4, 0);
    RF_CHECK_NEAR(v.y, 3.68349e-4, 1e-4, 0);
    RF_CHECK_NEAR(v.z, 9.54729e-3, 1e-5, 0);
    RF_CHECK_EQ_INT(argmax(RF_CMF_LMS_2006, 0), 570);
    RF_CHECK_EQ_INT(argmax(RF_CMF_LMS_2006, 1), 543);
    RF_CHECK_EQ_INT(argmax(RF_CMF_LMS_2006, 2), 442);
    RF_CHECK_NEAR(rf_cmf_at(RF_CMF_LMS_2006, 570).x, 1.0, 1e-4, 0);
    RF_CHECK_NEAR(rf_cmf_at(RF_CMF_LMS_2006, 543).y, 1.0, 1e-4, 0);
    RF_CHECK_NEAR(rf_cmf_at(RF_CMF_LMS_2006, 442).z, 1.0, 1e-4, 0);
}

/* The CIE 1931 r̄ḡb̄ turned into x̄ȳz̄ by the exact CIE matrix agree with the x̄ȳz̄ table (two
 * tables from different sources, within the 5-decimal rounding of r̄ḡb̄ times 1/0.17697);
 * negative lobes are kept; Σr̄ = Σḡ = Σb̄ (equal-energy white); 5 nm -> 1 nm is linear. */
static void test_color_rgb1931_checkpoints(void)
{
    RfMat3 m = rf_rgb_to_xyz_matrix(RF_RGB_CIE1931);
    double worst = 0.0;
    for (int l = 380; l <= 780; l += 5) {
        RfVec3 x = rf_mat3_mul_vec(m, rf_cmf_at(RF_CMF_RGB_1931, l)), t = rf_cmf_at(RF_CMF_XYZ_1931, l);
        worst = fmax(worst, fmax(fabs(x.x - t.x), fmax(fabs(x.y - t.y), fabs(x.z - t.z))));
    }
    RF_CHECK(worst < 1.5e-3);
    RF_CHECK(rf_cmf_at(RF_CMF_RGB_1931, 520).x < -0.09); /* the negative lobe of r̄ */
    RF_CHECK_NEAR(rf_cmf_at(RF_CMF_RGB_1931, 700).x, 0.0041, 1e-9, 0);
    RfVec3 a = rf_cmf_at(RF_CMF_RGB_1931, 520), b = rf_cmf_at(RF_CMF_RGB_1931, 525),
           c = rf_cmf_at(RF_CMF_RGB_1931, 522);
    RF_CHECK_NEAR(c.y, 0.6 * a.y + 0.4 * b.y, 1e-12, 1e-15);
    double lam[2] = {380, 780}, pw[2] = {1, 1};
    RfVec3 s;
    RF_CHECK(rf_spectrum_integrate(RF_CMF_RGB_1931, lam, pw, 2, &s) == RF_OK);
    RF_CHECK_NEAR(s.x, s.y, 1e-3, 0);
    RF_CHECK_NEAR(s.z, s.y, 1e-3, 0);
}

/* IEC 61966-2-1 publishes the sRGB matrix to 4 decimals; ours is derived from the primaries and
 * D65 and must agree within 1e-4 (FORMULAS.md); its middle row sums to Y(white) = 1. */
static void test_color_srgb_matrix_iec(void)
{
    static const double iec[3][3] = {{0.4124, 0.3576, 0.1805}, {0.2126, 0.7152, 0.0722}, {0.0193, 0.1192, 0.9505}};
    RfMat3 m = rf_rgb_to_xyz_matrix(RF_RGB_SRGB);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            RF_CHECK(fabs(m.m[i][j] - iec[i][j]) <= 1e-4);
    RF_CHECK_NEAR(m.m[1][0] + m.m[1][1] + m.m[1][2], 1.0, 1e-15, 0);
}

/* §1.3.1 metamerism, built constructively: a flat spectrum and a second one that differs by a
 * combination of sine bumps with zero response in all six functions have the same XYZ and LMS. */
static void test_color_metamers(void)
{
    enum { N = 301 };
    double lam[N], p1[N], p2[N];
    for (int i = 0; i < N; i++)
        lam[i] = 400 + i, p1[i] = 1.0;
    RF_CHECK(rf_metamer(400, N, p1, 0.9, p2) == RF_OK);
    double diff = 0.0, mn = 1.0;
    for (int i = 0; i < N; i++)
        diff = fmax(diff, fabs(p2[i] - p1[i])), mn = fmin(mn, p2[i]);
    RF_CHECK(diff > 0.5); /* clearly different */
    RF_CHECK(mn >= 0.0);  /* physical */
    RfVec3 x1, x2, l1, l2;
    rf_spectrum_integrate(RF_CMF_XYZ_1931, lam, p1, N, &x1);
    rf_spectrum_integrate(RF_CMF_XYZ_1931, lam, p2, N, &x2);
    rf_spectrum_integrate(RF_CMF_LMS_2006, lam, p1, N, &l1);
    rf_spectrum_integrate(RF_CMF_LMS_2006, lam, p2, N, &l2);
    RF_CHECK_NEAR(x2.x, x1.x, 1e-9, 0);
    RF_CHECK_NEAR(x2.y, x1.y, 1e-9, 0);
    RF_CHECK_NEAR(x2.z, x1.z, 1e-9, 0);
    RF_CHECK_NEAR(l2.x, l1.x, 1e-9, 0);
    RF_CHECK_NEAR(l2.y, l1.y, 1e-9, 0);
    RF_CHECK_NEAR(l2.z, l1.z, 1e-9, 0);
    /* but the CIE 1931 RGB functions are a different observer: they tell the two apart */
    RfVec3 r1, r2;
    rf_spectrum_integrate(RF_CMF_RGB_1931, lam, p1, N, &r1);
    rf_spectrum_integrate(RF_CMF_RGB_1931, lam, p2, N, &r2);
    RF_CHECK(!rf_test_near(r1.x, r2.x, 1e-6, 0) || !rf_test_near(r1.z, r2.z, 1e-6, 0));
    RF_CHECK(rf_metamer(400, N, p1, 1.5, p2) == RF_ERR_DOMAIN);
}

/* The gamut map toward white keeps the hue: the result lies on the line white -> C and on an
 * edge (one barycentric coordinate 0); the dominant wavelength of a locus point is its own. */
static void test_color_geometry_properties(void)
{
    RfVec2 w = rf_vec2(1.0 / 3, 1.0 / 3), c = rf_vec2(0.1, 0.8), r;
    double b[3];
    RF_CHECK(rf_gamut_map(c, rf_srgb_primaries, w, RF_GAMUT_TOWARD_WHITE, &r) == RF_OK);
    RF_CHECK_NEAR((r.x - w.x) * (c.y - w.y), (r.y - w.y) * (c.x - w.x), 1e-12, 1e-15);
    rf_gamut_barycentric(r, rf_srgb_primaries, b);
    RF_CHECK(fmin(b[0], fmin(b[1], b[2])) > -1e-12 && fmin(b[0], fmin(b[1], b[2])) < 1e-12);
    RfVec2 p;
    RfDominant d;
    RF_CHECK(rf_locus(530, &p) == RF_OK);
    RF_CHECK(rf_dominant_wavelength(p, w, &d) == RF_OK);
    RF_CHECK_NEAR(d.lambda_nm, 530, 1e-9, 0);
    RF_CHECK_NEAR(d.purity, 1.0, 1e-9, 0);
    RF_CHECK(rf_locus(831, &p) == RF_ERR_DOMAIN);
}

/* The commands: `refray chromaticity` writes a PNG or SVG and prints the numbers it drew (the
 * dominant wavelength of (0.2, 0.6) is the oracle's 521.1203913 nm); bad options fail without
 * leaving a file; `refray metamers` prints two equal rows of XYZ and LMS. */
static int file_starts_with(const char *path, const char *magic, size_t n, long *size)
{
    char buf[16] = {0};
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return 0;
    size_t got = fread(buf, 1, n, fp);
    fseek(fp, 0, SEEK_END);
    *size = ftell(fp);
    fclose(fp);
    return got == n && memcmp(buf, magic, n) == 0;
}

static void test_color_cli_chromaticity(void)
{
    char png[512], svg[512], bad[512], cmd[2048];
    int rc;
    long size = 0;
    snprintf(png, sizeof png, "%s.test-chroma.png", rf_test_bin());
    snprintf(svg, sizeof svg, "%s.test-chroma.svg", rf_test_bin());
    snprintf(bad, sizeof bad, "%s.test-chroma.jpg", rf_test_bin());
    remove(png);
    remove(svg);
    snprintf(cmd, sizeof cmd, "%s chromaticity -o %s --point 0.2,0.6 --point 0.3,0.15 --map 0.2,0.7 --size 400",
             rf_test_bin(), png);
    const char *out = rf_test_run(cmd, &rc);
    RF_CHECK_EQ_INT(rc, 0);
    RF_CHECK(strstr(out, "C1 (0.2000, 0.6000): dominant 521.1204 nm") != NULL);
    RF_CHECK(strstr(out, "C2 (0.3000, 0.1500): dominant -561.5662 nm") != NULL);
    RF_CHECK(strstr(out, "M1 (0.2000, 0.7000) -> (0.272441, 0.500787)") != NULL);
    RF_CHECK(file_starts_with(png, "\x89PNG\r\n\x1a\n", 8, &size));
    RF_CHECK(size > 10000);
    snprintf(cmd, sizeof cmd, "%s chromaticity -o %s --primaries '0.708,0.292;0.170,0.797;0.131,0.046' "
             "--white 0.3127,0.329 --map 0.05,0.5 --method nearest", rf_test_bin(), svg);
    out = rf_test_run(cmd, &rc);
    RF_CHECK_EQ_INT(rc, 0);
    RF_CHECK(strstr(out, "-> (0.154295, 0.494584), nearest") != NULL);
    RF_CHECK(file_starts_with(svg, "<?xml", 5, &size));
    snprintf(cmd, sizeof cmd, "%s chromaticity -o %s 2>/dev/null", rf_test_bin(), bad);
    rf_test_run(cmd, &rc);
    RF_CHECK_EQ_INT(rc, 5); /* usage: the name says no format (README: Exit codes) */
    RF_CHECK(!file_starts_with(bad, "", 0, &size));
    snprintf(cmd, sizeof cmd, "%s chromaticity -o %s --primaries 0.1,0.1 2>/dev/null", rf_test_bin(), png);
    rf_test_run(cmd, &rc);
    RF_CHECK_EQ_INT(rc, 5);
    remove(png);
    remove(svg);
}

static void test_color_cli_metamers(void)
{
    char cmd[1024], r1[256] = "", r2[256] = "";
    int rc;
    snprintf(cmd, sizeof cmd, "%s metamers", rf_test_bin());
    const char *out = rf_test_run(cmd, &rc);
    RF_CHECK_EQ_INT(rc, 0);
    const char *a = strstr(out, "\nP1 "), *b = strstr(out, "\nP2 ");
    RF_CHECK(a && b);
    if (a && b) {
        sscanf(a + 4, "%255[^\n]", r1);
        sscanf(b + 4, "%255[^\n]", r2);
        RF_CHECK(strlen(r1) > 50 && strcmp(r1, r2) == 0); /* the same XYZ and LMS, all 6 printed */
    }
}

const RfTest rf_tests_color[] = {
    {"color_formula_cases", test_color_formula_cases},
    {"color_ids_registered", test_color_ids_registered},
    {"color_cie1931_checkpoints", test_color_cie1931_checkpoints},
    {"color_lms2006_checkpoints", test_color_lms2006_checkpoints},
    {"color_rgb1931_checkpoints", test_color_rgb1931_checkpoints},
    {"color_srgb_matrix_iec", test_color_srgb_matrix_iec},
    {"color_metamers", test_color_metamers},
    {"color_geometry_properties", test_color_geometry_properties},
    {"color_cli_chromaticity", test_color_cli_chromaticity},
    {"color_cli_metamers", test_color_cli_metamers},
    RF_TEST_END,
};
