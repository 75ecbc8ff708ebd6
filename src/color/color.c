/* §1 colour science: quantisation, alpha, colour models, spectra, XYZ/xyY, chromaticity. */
#include "refray/color.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cie_tables.h"

/* ---- §1.1 ---- */

double rf_dynamic_range(double i_min, double i_max, double k)
{
    return (i_max + k) / (i_min + k);
}

double rf_linear_steps(double i_min, double i_max, double step)
{
    return (i_max - i_min) / (step * i_min);
}

double rf_exp_steps(double i_min, double i_max, double step)
{
    /* log1p: ln(1+step) stays accurate for the small steps that matter (2 %) */
    return ceil(log(i_max / i_min) / log1p(step));
}

double rf_steps_bits(double steps)
{
    return steps <= 1.0 ? 0.0 : ceil(log2(steps));
}

double rf_exp_level(double i_min, double n, double step)
{
    return i_min * pow(1.0 + step, n);
}

double rf_power_transfer(double n, double n_max, double gamma, double i_max)
{
    return pow(n / n_max, gamma) * i_max;
}

/* ---- §1.2 ---- */

RfRgba rf_alpha_over(RfRgba a, RfRgba b, int premultiplied)
{
    RfRgba r;
    double wb = 1.0 - a.alpha;
    r.alpha = a.alpha + b.alpha * wb;
    if (premultiplied) {
        r.rgb = rf_vec3_add(a.rgb, rf_vec3_scale(b.rgb, wb));
    } else if (r.alpha > 0.0) {
        RfVec3 s = rf_vec3_add(rf_vec3_scale(a.rgb, a.alpha), rf_vec3_scale(b.rgb, b.alpha * wb));
        r.rgb = rf_vec3_scale(s, 1.0 / r.alpha);
    } else {
        r.rgb = rf_vec3(0.0, 0.0, 0.0); /* fully transparent: no colour */
    }
    return r;
}

/* ---- §1.3 ---- */

double rf_frequency_hz(double lambda_nm)
{
    return RF_SPEED_OF_LIGHT / (lambda_nm * 1e-9);
}

/* ---- §1.4 ---- */

double rf_luminance(RfVec3 c)
{
    return 0.3 * c.x + 0.59 * c.y + 0.11 * c.z;
}

RfVec3 rf_rgb_cmy(RfVec3 v)
{
    return rf_vec3(1.0 - v.x, 1.0 - v.y, 1.0 - v.z);
}

RfVec4 rf_cmy_to_cmyk(RfVec3 c, RfCmykVariant variant)
{
    double k = fmin(c.x, fmin(c.y, c.z));
    if (variant == RF_CMYK_SCRIPT)
        return rf_vec4(c.x - k, c.y - k, c.z - k, k);
    if (k >= 1.0)
        return rf_vec4(0.0, 0.0, 0.0, 1.0); /* black: the normalised form divides by 1-K */
    double s = 1.0 / (1.0 - k);
    return rf_vec4((c.x - k) * s, (c.y - k) * s, (c.z - k) * s, k);
}

RfVec3 rf_cmyk_to_cmy(RfVec4 c, RfCmykVariant variant)
{
    double s = variant == RF_CMYK_SCRIPT ? 1.0 : 1.0 - c.w;
    return rf_vec3(c.x * s + c.w, c.y * s + c.w, c.z * s + c.w);
}

RfVec3 rf_rgb_to_hsv(RfVec3 c)
{
    double mx = fmax(c.x, fmax(c.y, c.z)), mn = fmin(c.x, fmin(c.y, c.z)), d = mx - mn;
    double h = 0.0, s = mx > 0.0 ? d / mx : 0.0;
    if (d > 0.0) {
        if (mx == c.x)
            h = (c.y - c.z) / d;
        else if (mx == c.y)
            h = 2.0 + (c.z - c.x) / d;
        else
            h = 4.0 + (c.x - c.y) / d;
        h *= 60.0;
        if (h < 0.0)
            h += 360.0;
    }
    return rf_vec3(h, s, mx);
}

RfVec3 rf_hsv_to_rgb(RfVec3 hsv)
{
    double h = fmod(hsv.x, 360.0), s = hsv.y, v = hsv.z;
    if (h < 0.0)
        h += 360.0;
    h /= 60.0;
    int i = (int)floor(h);
    double f = h - i, p = v * (1.0 - s), q = v * (1.0 - s * f), t = v * (1.0 - s * (1.0 - f));
    switch (i % 6) {
    case 0: return rf_vec3(v, t, p);
    case 1: return rf_vec3(q, v, p);
    case 2: return rf_vec3(p, v, t);
    case 3: return rf_vec3(p, q, v);
    case 4: return rf_vec3(t, p, v);
    default: return rf_vec3(v, p, q);
    }
}

/* ---- spectra ---- */

static const RfCieTable *table(RfCmf cmf)
{
    return cmf == RF_CMF_XYZ_1931 ? &rf_cie1931_xyz
         : cmf == RF_CMF_RGB_1931 ? &rf_cie1931_rgb
                                  : &rf_cie2006_lms;
}

void rf_cmf_range(RfCmf cmf, int *first_nm, int *last_nm)
{
    const RfCieTable *t = table(cmf);
    *first_nm = t->first_nm;
    *last_nm = t->first_nm + t->step_nm * (t->count - 1);
}

const char *rf_cmf_source(RfCmf cmf)
{
    return table(cmf)->publication;
}

RfVec3 rf_cmf_at(RfCmf cmf, double lambda_nm)
{
    const RfCieTable *t = table(cmf);
    double u = (lambda_nm - t->first_nm) / t->step_nm;
    if (!(u >= 0.0 && u <= t->count - 1))
        return rf_vec3(0.0, 0.0, 0.0);
    int i = (int)floor(u);
    if (i >= t->count - 1)
        i = t->count - 2;
    double f = u - i;
    const double *a = t->v[i], *b = t->v[i + 1];
    if (f == 0.0) /* on a table row: its value, exactly */
        return rf_vec3(a[0], a[1], a[2]);
    return rf_vec3(a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2]));
}

RfStatus rf_spectrum_integrate(RfCmf cmf, const double *lambda, const double *power, int n,
                               RfVec3 *out)
{
    int first, last;
    if (n < 1)
        return RF_ERR_DOMAIN;
    for (int i = 0; i < n; i++)
        if (!isfinite(lambda[i]) || !isfinite(power[i]) || (i > 0 && !(lambda[i] > lambda[i - 1])))
            return RF_ERR_DOMAIN;
    rf_cmf_range(cmf, &first, &last);
    RfVec3 sum = rf_vec3(0.0, 0.0, 0.0);
    int j = 0; /* the sample interval [lambda[j], lambda[j+1]] that holds the grid point */
    for (int l = first; l <= last; l++) {
        if (l < lambda[0] || l > lambda[n - 1])
            continue;
        while (j + 1 < n && lambda[j + 1] <= l) /* then lambda[j] <= l: exact at the samples */
            j++;
        double p;
        if (l == lambda[j] || j + 1 >= n)
            p = power[j];
        else
            p = power[j] + (l - lambda[j]) / (lambda[j + 1] - lambda[j]) * (power[j + 1] - power[j]);
        sum = rf_vec3_add(sum, rf_vec3_scale(rf_cmf_at(cmf, l), p));
    }
    *out = sum;
    return RF_OK;
}

/* ---- §1.4.6 ---- */

const RfVec2 rf_srgb_primaries[3] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
const RfVec2 rf_d65_white = {0.3127, 0.3290};

static RfVec3 xy_to_xyz1(RfVec2 c) /* XYZ with Y = 1 */
{
    return rf_vec3(c.x / c.y, 1.0, (1.0 - c.x - c.y) / c.y);
}

RfStatus rf_primaries_matrix(const RfVec2 primaries[3], RfVec2 white, RfMat3 *m)
{
    RfMat3 p, inv;
    if (white.y == 0.0)
        return RF_ERR_DEGENERATE;
    for (int j = 0; j < 3; j++) {
        if (primaries[j].y == 0.0)
            return RF_ERR_DEGENERATE;
        RfVec3 c = xy_to_xyz1(primaries[j]);
        p.m[0][j] = c.x;
        p.m[1][j] = c.y;
        p.m[2][j] = c.z;
    }
    if (rf_mat3_inverse(p, &inv) != RF_OK)
        return RF_ERR_DEGENERATE;
    RfVec3 s = rf_mat3_mul_vec(inv, xy_to_xyz1(white));
    double sc[3] = {s.x, s.y, s.z};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            m->m[i][j] = p.m[i][j] * sc[j];
    return RF_OK;
}

RfMat3 rf_rgb_to_xyz_matrix(RfRgbSpace space)
{
    /* §1.4.6: the script's M (rounded); the exact CIE 1931 matrix, whose second row holds the
     * relative luminances of the CIE primaries 700, 546.1, 435.8 nm; the factor 1/0.17697 scales
     * it so that the r̄ḡb̄ functions map onto ȳ = V(λ) with ȳ(555) = 1 */
    static const double script[3][3] = {{0.49, 0.31, 0.20}, {0.18, 0.81, 0.01}, {0.00, 0.01, 0.99}};
    static const double cie[3][3] = {{0.49, 0.31, 0.20}, {0.17697, 0.81240, 0.01063}, {0.00, 0.01, 0.99}};
    RfMat3 m;
    if (space == RF_RGB_SRGB) {
        rf_primaries_matrix(rf_srgb_primaries, rf_d65_white, &m);
        return m;
    }
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            m.m[i][j] = space == RF_RGB_SCRIPT ? script[i][j] : cie[i][j] / 0.17697;
    return m;
}

/* ---- §1.4.7 ---- */

RfStatus rf_xyz_to_xyy(RfVec3 v, RfVec3 *out)
{
    double s = v.x + v.y + v.z;
    if (v.x == 0.0 && v.y == 0.0 && v.z == 0.0) {
        *out = rf_vec3(1.0 / 3.0, 1.0 / 3.0, 0.0);
        return RF_OK;
    }
    if (s == 0.0)
        return RF_ERR_DOMAIN;
    *out = rf_vec3(v.x / s, v.y / s, v.y);
    return RF_OK;
}

RfStatus rf_xyy_to_xyz(RfVec3 v, RfVec3 *out)
{
    if (v.y == 0.0) {
        if (v.z != 0.0)
            return RF_ERR_DOMAIN;
        *out = rf_vec3(0.0, 0.0, 0.0);
        return RF_OK;
    }
    double k = v.z / v.y;
    *out = rf_vec3(k * v.x, v.z, k * (1.0 - v.x - v.y));
    return RF_OK;
}

/* ---- §1.5 ---- */

static RfVec2 chromaticity(RfVec3 v)
{
    double s = v.x + v.y + v.z;
    return rf_vec2(v.x / s, v.y / s);
}

RfStatus rf_locus(double lambda_nm, RfVec2 *xy)
{
    if (!(lambda_nm >= RF_LOCUS_FIRST_NM && lambda_nm <= RF_LOCUS_LAST_NM))
        return RF_ERR_DOMAIN;
    *xy = chromaticity(rf_cmf_at(RF_CMF_XYZ_1931, lambda_nm));
    return RF_OK;
}

static double cross2(RfVec2 a, RfVec2 b)
{
    return a.x * b.y - a.y * b.x;
}

static RfVec2 sub2(RfVec2 a, RfVec2 b)
{
    return rf_vec2(a.x - b.x, a.y - b.y);
}

/* Where the ray o + t d (t > 0) first meets the segment a-b: returns t (or -1) and u in [0,1]. */
static double ray_segment(RfVec2 o, RfVec2 d, RfVec2 a, RfVec2 b, double *u)
{
    RfVec2 e = sub2(b, a), w = sub2(a, o);
    double den = cross2(d, e);
    if (den == 0.0)
        return -1.0; /* parallel (or a degenerate segment): the neighbours are met instead */
    double t = cross2(w, e) / den, s = cross2(w, d) / den;
    if (t <= 0.0 || s < 0.0 || s > 1.0)
        return -1.0;
    *u = s;
    return t;
}

/* First crossing of the ray from w along d with the locus polyline (360..830 nm at 1 nm) or the
 * purple line. Returns the parameter t and the wavelength (or -1 on the purple line). */
static double locus_crossing(RfVec2 w, RfVec2 d, double *lambda, int *purple)
{
    const int n = RF_LOCUS_LAST_NM - RF_LOCUS_FIRST_NM + 1;
    double best = INFINITY, u;
    RfVec2 prev, cur, first;
    *lambda = -1.0;
    *purple = 0;
    rf_locus(RF_LOCUS_FIRST_NM, &first);
    prev = first;
    for (int i = 1; i < n; i++) {
        rf_locus(RF_LOCUS_FIRST_NM + i, &cur);
        double t = ray_segment(w, d, prev, cur, &u);
        if (t > 0.0 && t < best) {
            best = t;
            *lambda = RF_LOCUS_FIRST_NM + i - 1 + u;
        }
        prev = cur;
    }
    double t = ray_segment(w, d, prev, first, &u); /* the purple line: 830 nm back to 360 nm */
    if (t > 0.0 && t < best) {
        best = t;
        *lambda = -1.0;
        *purple = 1;
    }
    return best;
}

RfStatus rf_dominant_wavelength(RfVec2 c, RfVec2 white, RfDominant *out)
{
    RfVec2 d = sub2(c, white);
    double lam, lamc;
    int purple, purple_c;
    if (d.x == 0.0 && d.y == 0.0)
        return RF_ERR_DEGENERATE;
    double t = locus_crossing(white, d, &lam, &purple);
    double tc = locus_crossing(white, rf_vec2(-d.x, -d.y), &lamc, &purple_c);
    if (!isfinite(t) || !isfinite(tc))
        return RF_ERR_DOMAIN; /* the white point lies outside the locus */
    memset(out, 0, sizeof *out);
    out->boundary = rf_vec2(white.x + t * d.x, white.y + t * d.y);
    out->complementary_point = rf_vec2(white.x - tc * d.x, white.y - tc * d.y);
    out->purity = 1.0 / t; /* |W C| / |W B| with B = W + t (C - W) */
    out->on_purple_line = purple;
    out->has_complementary = !purple_c;
    out->complementary_nm = purple_c ? 0.0 : lamc;
    if (purple) {
        if (purple_c)
            return RF_ERR_DOMAIN; /* cannot happen for a white point inside the locus */
        out->lambda_nm = -lamc; /* CIE convention */
    } else {
        out->lambda_nm = lam;
    }
    return RF_OK;
}

RfStatus rf_mix_xyy(RfVec3 a, RfVec3 b, RfVec3 *out)
{
    RfVec3 xa, xb;
    if (rf_xyy_to_xyz(a, &xa) != RF_OK || rf_xyy_to_xyz(b, &xb) != RF_OK)
        return RF_ERR_DOMAIN;
    return rf_xyz_to_xyy(rf_vec3_add(xa, xb), out);
}

RfStatus rf_gamut_barycentric(RfVec2 c, const RfVec2 p[3], double bary[3])
{
    double area = cross2(sub2(p[1], p[0]), sub2(p[2], p[0]));
    if (area == 0.0)
        return RF_ERR_DEGENERATE;
    for (int i = 0; i < 3; i++) /* the sub-triangle opposite corner i, with c in its place */
        bary[i] = cross2(sub2(p[(i + 1) % 3], c), sub2(p[(i + 2) % 3], c)) / area;
    return RF_OK;
}

static RfVec2 closest_on_segment(RfVec2 c, RfVec2 a, RfVec2 b)
{
    RfVec2 e = sub2(b, a), w = sub2(c, a);
    double ee = e.x * e.x + e.y * e.y;
    double u = ee > 0.0 ? (w.x * e.x + w.y * e.y) / ee : 0.0;
    u = u < 0.0 ? 0.0 : u > 1.0 ? 1.0 : u;
    return rf_vec2(a.x + u * e.x, a.y + u * e.y);
}

RfStatus rf_gamut_map(RfVec2 c, const RfVec2 p[3], RfVec2 white, RfGamutMethod method,
                      RfVec2 *out)
{
    double b[3], bw[3];
    RfStatus st = rf_gamut_barycentric(c, p, b);
    if (st != RF_OK)
        return st;
    if (method == RF_GAMUT_TOWARD_WHITE) {
        rf_gamut_barycentric(white, p, bw);
        if (bw[0] < 0.0 || bw[1] < 0.0 || bw[2] < 0.0)
            return RF_ERR_DOMAIN;
    }
    if (b[0] >= 0.0 && b[1] >= 0.0 && b[2] >= 0.0) {
        *out = c;
        return RF_OK;
    }
    if (method == RF_GAMUT_TOWARD_WHITE) {
        /* barycentrics are affine along the line W + s (C - W): the first one to reach 0 */
        double s = 1.0;
        for (int i = 0; i < 3; i++)
            if (b[i] < 0.0)
                s = fmin(s, bw[i] / (bw[i] - b[i]));
        *out = rf_vec2(white.x + s * (c.x - white.x), white.y + s * (c.y - white.y));
        return RF_OK;
    }
    double best = INFINITY;
    for (int i = 0; i < 3; i++) {
        RfVec2 q = closest_on_segment(c, p[i], p[(i + 1) % 3]);
        double dd = hypot(q.x - c.x, q.y - c.y);
        if (dd < best) {
            best = dd;
            *out = q;
        }
    }
    return RF_OK;
}

/* ---- metamerism ---- */

/* Solves the n x n system a x = b (row-major, destroyed) by Gaussian elimination with partial
 * pivoting; returns 0 when singular. */
static int solve_small(int n, double *a, double *b)
{
    for (int k = 0; k < n; k++) {
        int piv = k;
        for (int i = k + 1; i < n; i++)
            if (fabs(a[i * n + k]) > fabs(a[piv * n + k]))
                piv = i;
        if (a[piv * n + k] == 0.0)
            return 0;
        for (int j = 0; j < n; j++) {
            double t = a[k * n + j];
            a[k * n + j] = a[piv * n + j];
            a[piv * n + j] = t;
        }
        double t = b[k];
        b[k] = b[piv];
        b[piv] = t;
        for (int i = k + 1; i < n; i++) {
            double f = a[i * n + k] / a[k * n + k];
            for (int j = k; j < n; j++)
                a[i * n + j] -= f * a[k * n + j];
            b[i] -= f * b[k];
        }
    }
    for (int k = n - 1; k >= 0; k--) {
        for (int j = k + 1; j < n; j++)
            b[k] -= a[k * n + j] * b[j];
        b[k] /= a[k * n + k];
    }
    return 1;
}

#define RF_METAMER_BUMPS 7

RfStatus rf_metamer(int first_nm, int n, const double *p1, double fraction, double *p2)
{
    double resp[6][RF_METAMER_BUMPS], a[36], rhs[6], coef[RF_METAMER_BUMPS];
    if (n < 3 || !(fraction > 0.0 && fraction <= 1.0))
        return RF_ERR_DOMAIN;
    double *bump = malloc(sizeof(double) * (size_t)n * RF_METAMER_BUMPS);
    double *lam = malloc(sizeof(double) * (size_t)n);
    if (!bump || !lam) {
        free(bump);
        free(lam);
        return RF_ERR_NOMEM;
    }
    for (int i = 0; i < n; i++)
        lam[i] = first_nm + i;
    /* the responses of XYZ and LMS to each bump */
    for (int k = 0; k < RF_METAMER_BUMPS; k++) {
        RfVec3 x, l;
        for (int i = 0; i < n; i++)
            bump[k * n + i] = sin((k + 1) * RF_PI * i / (n - 1));
        RfStatus si = rf_spectrum_integrate(RF_CMF_XYZ_1931, lam, bump + k * n, n, &x);
        if (si == RF_OK)
            si = rf_spectrum_integrate(RF_CMF_LMS_2006, lam, bump + k * n, n, &l);
        if (si != RF_OK) {
            free(bump);
            free(lam);
            return si;
        }
        double r[6] = {x.x, x.y, x.z, l.x, l.y, l.z};
        for (int j = 0; j < 6; j++)
            resp[j][k] = r[j];
    }
    /* the null vector with the last coefficient 1: resp[:, 0..5] c = -resp[:, 6] */
    for (int j = 0; j < 6; j++) {
        for (int k = 0; k < 6; k++)
            a[j * 6 + k] = resp[j][k];
        rhs[j] = -resp[j][6];
    }
    RfStatus st = RF_ERR_DEGENERATE;
    if (solve_small(6, a, rhs)) {
        memcpy(coef, rhs, sizeof rhs);
        coef[6] = 1.0;
        double smax = INFINITY;
        for (int i = 0; i < n; i++) {
            double b = 0.0;
            for (int k = 0; k < RF_METAMER_BUMPS; k++)
                b += coef[k] * bump[k * n + i];
            p2[i] = b;
            if (b < 0.0)
                smax = fmin(smax, p1[i] / -b);
        }
        if (isfinite(smax) && smax > 0.0) {
            for (int i = 0; i < n; i++)
                p2[i] = p1[i] + fraction * smax * p2[i];
            st = RF_OK;
        }
    }
    free(bump);
    free(lam);
    return st;
}
