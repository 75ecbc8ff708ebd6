/* `refray formula` entries of §1 (images, colour and perception). */
#include "refray/color.h"
#include "refray/formula.h"
#include "refray/transfer.h"

#include <math.h>
#include <stdlib.h>

#define SRGB_PRIMARIES "[[0.64,0.33],[0.3,0.6],[0.15,0.06]]"
#define WHITE_THIRD "0.33333333333333331,0.33333333333333331"

static int in_rgb(RfFormulaCall *c, const char *name, RfVec3 *v)
{
    double a[3];
    if (rf_in_vec(c, name, 0, a, NULL))
        return 1;
    *v = rf_vec3(a[0], a[1], a[2]);
    return 0;
}

static void out_v3(RfFormulaCall *c, const char *name, RfVec3 v)
{
    double a[3] = {v.x, v.y, v.z};
    rf_out_vec(c, name, a, 3);
}

static int in_positive(RfFormulaCall *c, const char *name, double *v)
{
    if (rf_in_num(c, name, v))
        return 1;
    if (!(*v > 0.0))
        return rf_call_error(c, "%s must be > 0", name);
    return 0;
}

/* ---- §1.1 ---- */

static int f_dynamic_range(RfFormulaCall *c)
{
    double lo, hi, k;
    if (rf_in_num(c, "i_min", &lo) || rf_in_num(c, "i_max", &hi) || rf_in_num(c, "k", &k))
        return 1;
    if (!(lo + k > 0.0) || lo < 0.0 || k < 0.0)
        return rf_call_error(c, "need i_min >= 0, k >= 0 and i_min + k > 0");
    rf_out_num(c, "r_d", rf_dynamic_range(lo, hi, k));
    return 0;
}

/* i_min > 0, i_max > i_min, step > 0: the common domain of the quantisation formulas. */
static int in_range_step(RfFormulaCall *c, double *lo, double *hi, double *step)
{
    if (in_positive(c, "i_min", lo) || rf_in_num(c, "i_max", hi) || in_positive(c, "step", step))
        return 1;
    if (!(*hi > *lo))
        return rf_call_error(c, "need i_max > i_min");
    return 0;
}

static int f_linear_steps(RfFormulaCall *c)
{
    double lo, hi, step;
    if (in_range_step(c, &lo, &hi, &step))
        return 1;
    double n = rf_linear_steps(lo, hi, step);
    rf_out_num(c, "steps", n);
    rf_out_num(c, "bits", rf_steps_bits(n));
    return 0;
}

static int f_exp_steps(RfFormulaCall *c)
{
    double lo, hi, step;
    if (in_range_step(c, &lo, &hi, &step))
        return 1;
    double n = rf_exp_steps(lo, hi, step);
    rf_out_num(c, "steps", n);
    rf_out_num(c, "bits", rf_steps_bits(n));
    rf_out_num(c, "steps_script", log10(hi / lo) * 120.0); /* log10(1.02) ~ 1/120 */
    return 0;
}

static int f_exp_level(RfFormulaCall *c)
{
    double lo, n, step;
    if (in_positive(c, "i_min", &lo) || rf_in_num(c, "n", &n) || in_positive(c, "step", &step))
        return 1;
    rf_out_num(c, "i", rf_exp_level(lo, n, step));
    return 0;
}

static int f_power_transfer(RfFormulaCall *c)
{
    double n, nmax, gamma, imax;
    if (rf_in_num(c, "n", &n) || in_positive(c, "n_max", &nmax) || in_positive(c, "gamma", &gamma) ||
        rf_in_num(c, "i_max", &imax))
        return 1;
    if (n < 0.0 || n > nmax)
        return rf_call_error(c, "n must lie in [0, n_max]");
    rf_out_num(c, "i", rf_power_transfer(n, nmax, gamma, imax));
    return 0;
}

/* One routine for the four per-channel curves. */
typedef enum { CURVE_GAMMA_ENC, CURVE_GAMMA_DEC, CURVE_SRGB_ENC, CURVE_SRGB_DEC } Curve;

static int per_channel(RfFormulaCall *c, Curve curve)
{
    RfVec3 v;
    double gamma = 0.0, a[3], r[3];
    if (in_rgb(c, "rgb", &v))
        return 1;
    if ((curve == CURVE_GAMMA_ENC || curve == CURVE_GAMMA_DEC) && in_positive(c, "gamma", &gamma))
        return 1;
    a[0] = v.x, a[1] = v.y, a[2] = v.z;
    for (int i = 0; i < 3; i++)
        r[i] = curve == CURVE_GAMMA_ENC ? rf_gamma_encode(a[i], gamma)
             : curve == CURVE_GAMMA_DEC ? rf_gamma_decode(a[i], gamma)
             : curve == CURVE_SRGB_ENC  ? rf_srgb_encode(a[i])
                                        : rf_srgb_decode(a[i]);
    rf_out_vec(c, "rgb", r, 3);
    return 0;
}

static int f_gamma_encode(RfFormulaCall *c) { return per_channel(c, CURVE_GAMMA_ENC); }
static int f_gamma_decode(RfFormulaCall *c) { return per_channel(c, CURVE_GAMMA_DEC); }
static int f_srgb_encode(RfFormulaCall *c) { return per_channel(c, CURVE_SRGB_ENC); }
static int f_srgb_decode(RfFormulaCall *c) { return per_channel(c, CURVE_SRGB_DEC); }

static int f_quantize(RfFormulaCall *c)
{
    double v;
    long bits;
    if (rf_in_num(c, "value", &v) || rf_in_int(c, "bits", &bits))
        return 1;
    if (bits < 1 || bits > 16)
        return rf_call_error(c, "bits must lie in 1..16");
    rf_out_num(c, "code", (double)rf_quantize(v, (int)bits));
    return 0;
}

/* ---- §1.2 ---- */

static int in_alpha(RfFormulaCall *c, const char *name, double *a)
{
    if (rf_in_num(c, name, a))
        return 1;
    if (*a < 0.0 || *a > 1.0)
        return rf_call_error(c, "%s must lie in [0, 1]", name);
    return 0;
}

static int f_alpha_over(RfFormulaCall *c)
{
    RfRgba a, b;
    int pre;
    if (in_rgb(c, "rgb_a", &a.rgb) || in_alpha(c, "alpha_a", &a.alpha) || in_rgb(c, "rgb_b", &b.rgb) ||
        in_alpha(c, "alpha_b", &b.alpha) || rf_in_bool(c, "premultiplied", &pre))
        return 1;
    RfRgba r = rf_alpha_over(a, b, pre);
    out_v3(c, "rgb", r.rgb);
    rf_out_num(c, "alpha", r.alpha);
    return 0;
}

/* ---- §1.3 ---- */

static int f_frequency(RfFormulaCall *c)
{
    double l;
    if (in_positive(c, "lambda_nm", &l))
        return 1;
    rf_out_num(c, "nu_hz", rf_frequency_hz(l));
    return 0;
}

/* Reads lambda_nm[] and power[] and sums them against a table; outputs three names. */
static int spectrum_sums(RfFormulaCall *c, RfCmf cmf, const char *n0, const char *n1, const char *n2)
{
    double *lam = NULL, *pw = NULL;
    int nl = 0, np = 0, rc = 1;
    RfVec3 r;
    if (rf_in_nums(c, "lambda_nm", &lam, &nl) || rf_in_nums(c, "power", &pw, &np))
        goto done;
    if (nl != np) {
        rf_call_error(c, "lambda_nm and power must have the same length (%d vs %d)", nl, np);
        goto done;
    }
    if (rf_spectrum_integrate(cmf, lam, pw, nl, &r) != RF_OK) {
        rf_call_error(c, "lambda_nm must increase strictly");
        goto done;
    }
    rf_out_num(c, n0, r.x);
    rf_out_num(c, n1, r.y);
    rf_out_num(c, n2, r.z);
    rc = 0;
done:
    free(lam);
    free(pw);
    return rc;
}

static int f_cone_response(RfFormulaCall *c)
{
    /* the table is ordered L, M, S */
    double *lam = NULL, *pw = NULL;
    int nl = 0, np = 0, rc = 1;
    RfVec3 r;
    if (rf_in_nums(c, "lambda_nm", &lam, &nl) || rf_in_nums(c, "power", &pw, &np))
        goto done;
    if (nl != np) {
        rf_call_error(c, "lambda_nm and power must have the same length (%d vs %d)", nl, np);
        goto done;
    }
    if (rf_spectrum_integrate(RF_CMF_LMS_2006, lam, pw, nl, &r) != RF_OK) {
        rf_call_error(c, "lambda_nm must increase strictly");
        goto done;
    }
    rf_out_num(c, "s", r.z);
    rf_out_num(c, "m", r.y);
    rf_out_num(c, "l", r.x);
    rc = 0;
done:
    free(lam);
    free(pw);
    return rc;
}

static int f_spectrum_to_rgb(RfFormulaCall *c) { return spectrum_sums(c, RF_CMF_RGB_1931, "r", "g", "b"); }
static int f_spectrum_to_xyz(RfFormulaCall *c) { return spectrum_sums(c, RF_CMF_XYZ_1931, "x", "y", "z"); }

/* ---- §1.4 ---- */

static int f_luminance(RfFormulaCall *c)
{
    RfVec3 v;
    if (in_rgb(c, "rgb", &v))
        return 1;
    rf_out_num(c, "y", rf_luminance(v));
    return 0;
}

static int f_rgb_to_cmy(RfFormulaCall *c)
{
    RfVec3 v;
    if (in_rgb(c, "rgb", &v))
        return 1;
    out_v3(c, "cmy", rf_rgb_cmy(v));
    return 0;
}

static int f_cmy_to_rgb(RfFormulaCall *c)
{
    RfVec3 v;
    if (in_rgb(c, "cmy", &v))
        return 1;
    out_v3(c, "rgb", rf_rgb_cmy(v));
    return 0;
}

static int f_cmy_to_cmyk(RfFormulaCall *c)
{
    RfVec3 v;
    int variant;
    if (in_rgb(c, "cmy", &v) || rf_in_choice(c, "variant", &variant))
        return 1;
    RfVec4 k = rf_cmy_to_cmyk(v, (RfCmykVariant)variant);
    double a[4] = {k.x, k.y, k.z, k.w};
    rf_out_vec(c, "cmyk", a, 4);
    return 0;
}

static int f_cmyk_to_cmy(RfFormulaCall *c)
{
    double a[4];
    int variant;
    if (rf_in_vec(c, "cmyk", 0, a, NULL) || rf_in_choice(c, "variant", &variant))
        return 1;
    out_v3(c, "cmy", rf_cmyk_to_cmy(rf_vec4(a[0], a[1], a[2], a[3]), (RfCmykVariant)variant));
    return 0;
}

static int f_rgb_to_hsv(RfFormulaCall *c)
{
    RfVec3 v;
    if (in_rgb(c, "rgb", &v))
        return 1;
    RfVec3 h = rf_rgb_to_hsv(v);
    rf_out_num(c, "h_deg", h.x);
    rf_out_num(c, "s", h.y);
    rf_out_num(c, "v", h.z);
    return 0;
}

static int f_hsv_to_rgb(RfFormulaCall *c)
{
    double h, s, v;
    if (rf_in_num(c, "h_deg", &h) || rf_in_num(c, "s", &s) || rf_in_num(c, "v", &v))
        return 1;
    out_v3(c, "rgb", rf_hsv_to_rgb(rf_vec3(h, s, v)));
    return 0;
}

static int in_matrix(RfFormulaCall *c, RfMat3 *m)
{
    int i;
    if (rf_in_choice(c, "matrix", &i))
        return 1;
    *m = rf_rgb_to_xyz_matrix((RfRgbSpace)i);
    return 0;
}

static int f_rgb_to_xyz(RfFormulaCall *c)
{
    RfVec3 v;
    RfMat3 m;
    if (in_rgb(c, "rgb", &v) || in_matrix(c, &m))
        return 1;
    out_v3(c, "xyz", rf_mat3_mul_vec(m, v));
    rf_out_mat(c, "matrix", &m.m[0][0], 3);
    return 0;
}

static int f_xyz_to_rgb(RfFormulaCall *c)
{
    RfVec3 v;
    RfMat3 m, inv;
    if (in_rgb(c, "xyz", &v) || in_matrix(c, &m))
        return 1;
    if (rf_mat3_inverse(m, &inv) != RF_OK)
        return rf_call_error(c, "the matrix is singular");
    out_v3(c, "rgb", rf_mat3_mul_vec(inv, v));
    rf_out_mat(c, "matrix", &inv.m[0][0], 3);
    return 0;
}

static int f_xyz_to_xyy(RfFormulaCall *c)
{
    RfVec3 v, r;
    if (in_rgb(c, "xyz", &v))
        return 1;
    if (rf_xyz_to_xyy(v, &r) != RF_OK)
        return rf_call_error(c, "X + Y + Z = 0 for a colour that is not black: no chromaticity");
    rf_out_num(c, "x", r.x);
    rf_out_num(c, "y", r.y);
    rf_out_num(c, "Y", r.z);
    return 0;
}

static int f_xyy_to_xyz(RfFormulaCall *c)
{
    double x, y, Y;
    RfVec3 r;
    if (rf_in_num(c, "x", &x) || rf_in_num(c, "y", &y) || rf_in_num(c, "Y", &Y))
        return 1;
    if (rf_xyy_to_xyz(rf_vec3(x, y, Y), &r) != RF_OK)
        return rf_call_error(c, "y = 0 with Y != 0: X = (Y/y) x does not exist");
    out_v3(c, "xyz", r);
    return 0;
}

/* ---- §1.5 ---- */

static int f_locus(RfFormulaCall *c)
{
    double l;
    RfVec2 p;
    if (rf_in_num(c, "lambda_nm", &l))
        return 1;
    if (rf_locus(l, &p) != RF_OK)
        return rf_call_error(c, "lambda_nm must lie in [%d, %d] (the CIE 1931 table)",
                             RF_LOCUS_FIRST_NM, RF_LOCUS_LAST_NM);
    rf_out_num(c, "x", p.x);
    rf_out_num(c, "y", p.y);
    return 0;
}

static int in_xy(RfFormulaCall *c, RfVec2 *p)
{
    if (rf_in_num(c, "x", &p->x) || rf_in_num(c, "y", &p->y))
        return 1;
    return 0;
}

static int in_point2(RfFormulaCall *c, const char *name, RfVec2 *p)
{
    double a[2];
    if (rf_in_vec(c, name, 0, a, NULL))
        return 1;
    *p = rf_vec2(a[0], a[1]);
    return 0;
}

static int f_dominant_wavelength(RfFormulaCall *c)
{
    RfVec2 p, w;
    RfDominant d;
    if (in_xy(c, &p) || in_point2(c, "white", &w))
        return 1;
    RfStatus st = rf_dominant_wavelength(p, w, &d);
    if (st == RF_ERR_DEGENERATE)
        return rf_call_error(c, "the colour is the white point: no dominant wavelength");
    if (st != RF_OK)
        return rf_call_error(c, "the white point must lie inside the spectral locus");
    rf_out_num(c, "lambda_nm", d.lambda_nm);
    rf_out_num(c, "purity", d.purity);
    if (d.has_complementary)
        rf_out_num(c, "complementary_nm", d.complementary_nm);
    else
        rf_out_null(c, "complementary_nm");
    rf_out_bool(c, "on_purple_line", d.on_purple_line);
    double b[2] = {d.boundary.x, d.boundary.y};
    rf_out_vec(c, "boundary", b, 2);
    return 0;
}

static int f_mix(RfFormulaCall *c)
{
    RfVec3 a, b, r;
    if (in_rgb(c, "xyY_a", &a) || in_rgb(c, "xyY_b", &b))
        return 1;
    if (rf_mix_xyy(a, b, &r) != RF_OK)
        return rf_call_error(c, "a colour with y = 0 and Y != 0, or a sum X+Y+Z = 0 that is not black");
    rf_out_num(c, "x", r.x);
    rf_out_num(c, "y", r.y);
    rf_out_num(c, "Y", r.z);
    return 0;
}

static int in_primaries(RfFormulaCall *c, RfVec2 p[3])
{
    double v[6];
    int n = 0;
    if (rf_in_vecs(c, "primaries", 0, 3, v, &n, NULL))
        return 1;
    if (n != 3)
        return rf_call_bad_input(c, "primaries must be three xy points, not %d", n);
    for (int i = 0; i < 3; i++)
        p[i] = rf_vec2(v[2 * i], v[2 * i + 1]);
    return 0;
}

static int f_in_gamut(RfFormulaCall *c)
{
    RfVec2 p, prim[3];
    double b[3];
    if (in_xy(c, &p) || in_primaries(c, prim))
        return 1;
    if (rf_gamut_barycentric(p, prim, b) != RF_OK)
        return rf_call_error(c, "the primaries are collinear: no gamut triangle");
    rf_out_bool(c, "inside", b[0] >= 0.0 && b[1] >= 0.0 && b[2] >= 0.0);
    rf_out_vec(c, "barycentric", b, 3);
    return 0;
}

static int f_gamut_map(RfFormulaCall *c)
{
    RfVec2 p, prim[3], w, r;
    int method;
    if (in_xy(c, &p) || in_primaries(c, prim) || in_point2(c, "white", &w) ||
        rf_in_choice(c, "method", &method))
        return 1;
    RfStatus st = rf_gamut_map(p, prim, w, (RfGamutMethod)method, &r);
    if (st == RF_ERR_DEGENERATE)
        return rf_call_error(c, "the primaries are collinear: no gamut triangle");
    if (st != RF_OK)
        return rf_call_error(c, "toward-white needs the white point inside the gamut triangle");
    rf_out_num(c, "x", r.x);
    rf_out_num(c, "y", r.y);
    rf_out_num(c, "shift", hypot(r.x - p.x, r.y - p.y));
    rf_out_bool(c, "moved", r.x != p.x || r.y != p.y);
    return 0;
}

#define SPECTRUM_IN "lambda_nm:nums the wavelengths of the samples, increasing (nm); " \
                    "power:nums the spectral power at each wavelength (any unit), as many"
#define SPECTRUM_NOTE " (spectrum interpolated linearly onto the 1 nm grid, 0 outside its range, " \
                      "summed with 1 nm steps)"
#define RGB_IN(what) "rgb:rgb " what ", linear, usually in [0,1]"
#define QUANT_IN "i_min:num the smallest intensity I_min (> 0); i_max:num the largest intensity " \
                 "I_max (> I_min); step:num=0.02 the relative step (Weber fraction) that is just visible"
#define PRIMARIES_IN "primaries:vecs2=" SRGB_PRIMARIES " the xy chromaticities of the red, green " \
                     "and blue primaries (default sRGB)"
#define XY_IN "x:num the chromaticity x; y:num the chromaticity y"

const RfFormula rf_formulas_color[] = {
    {"dynamic-range", "1.1", "dynamic range R_d = (I_max + k)/(I_min + k), k: ambient light",
     "i_min:num the darkest intensity I_min (>= 0); i_max:num the brightest intensity I_max; "
     "k:num=0 the ambient light added to both (>= 0)", "r_d:num the dynamic range R_d", NULL,
     f_dynamic_range, "i_min=0.01 i_max=100 k=0.1"},
    {"linear-steps", "1.1.1", "linear quantisation: steps = (I_max - I_min)/(step I_min) (not rounded), "
     "bits = ceil(log2(steps))", QUANT_IN,
     "steps:num the number of equal steps of size step I_min (not rounded); bits:num ceil(log2(steps))",
     NULL, f_linear_steps, "i_min=0.01 i_max=1"},
    {"exp-steps", "1.1.1", "exponential quantisation: steps = ceil(ln(I_max/I_min)/ln(1+step)), "
     "bits = ceil(log2(steps)); steps_script = the script's estimate log10(R) 120", QUANT_IN,
     "steps:num the number of steps, each (1+step) times the last; bits:num ceil(log2(steps)); "
     "steps_script:num the script's estimate log10(I_max/I_min) 120 (for step = 0.02)",
     NULL, f_exp_steps, "i_min=0.01 i_max=1"},
    {"exp-level", "1.1.1", "exponential quantisation level I_n = I_min (1+step)^n",
     "i_min:num the smallest intensity I_min (> 0); n:num the level number; "
     "step:num=0.02 the relative step between levels", "i:num the intensity I_n of level n", NULL,
     f_exp_level, "i_min=0.01 n=100"},
    {"power-transfer", "1.1.1", "power-law transfer function I(n) = (n/N)^gamma I_max, n in [0, N]",
     "n:num the code value, 0 <= n <= n_max; n_max:num the largest code value N (> 0); "
     "gamma:num the exponent (> 0); i_max:num=1 the intensity at n = N",
     "i:num the intensity I(n)", NULL, f_power_transfer, "n=128 n_max=255 gamma=2.2"},
    {"gamma-encode", "1.1.2", "gamma correction per channel: a' = a^(1/gamma) (negative values -> 0)",
     RGB_IN("the linear colour") "; gamma:num=2.2 the display's exponent (> 0)",
     "rgb:rgb the encoded colour a^(1/gamma) per channel", "the script writes alpha ∝ alpha^(1/gamma); it is "
     "alpha' = alpha^(1/gamma)", f_gamma_encode, "rgb=0.5,0.25,1"},
    {"gamma-decode", "1.1.2", "inverse gamma per channel: a = a'^gamma (negative values -> 0)",
     "rgb:rgb the encoded colour, in [0,1]; gamma:num=2.2 the display's exponent (> 0)",
     "rgb:rgb the linear colour a'^gamma per channel", NULL, f_gamma_decode, "rgb=0.5"},
    {"srgb-encode", "beyond", "IEC 61966-2-1 sRGB curve per channel: 12.92 v for v <= 0.0031308, "
     "else 1.055 v^(1/2.4) - 0.055", RGB_IN("the linear colour"), "rgb:rgb the sRGB-encoded colour",
     NULL, f_srgb_encode, "rgb=0.5,0.002,1"},
    {"srgb-decode", "beyond", "inverse sRGB curve per channel: v/12.92 for v <= 0.04045, "
     "else ((v + 0.055)/1.055)^2.4", "rgb:rgb the sRGB-encoded colour, in [0,1]",
     "rgb:rgb the linear colour", NULL, f_srgb_decode, "rgb=0.5,0.04,1"},
    {"quantize", "1.1", "quantisation to n bits: round(v (2^bits - 1)), v clamped to [0, 1]",
     "value:num the value, clamped to [0,1]; bits:int=8 the number of bits, 1..16",
     "code:num the integer code round(value (2^bits - 1))", NULL, f_quantize, "value=0.5 bits=8"},
    {"alpha-over", "1.2", "Porter-Duff a over b: alpha = a_a + a_b (1 - a_a); straight colours "
     "rgb = (C_a a_a + C_b a_b (1 - a_a))/alpha (0 if alpha = 0); premultiplied C_a + C_b (1 - a_a)",
     "rgb_a:rgb the colour C_a in front; alpha_a:num its opacity a_a in [0,1]; "
     "rgb_b:rgb the colour C_b behind; alpha_b:num its opacity a_b in [0,1]; "
     "premultiplied:bool=false the colours are premultiplied by their alpha",
     "rgb:rgb the composite colour (premultiplied when the inputs are); alpha:num the composite opacity",
     NULL, f_alpha_over, "rgb_a=1,0,0 alpha_a=0.5 rgb_b=0,0,1 alpha_b=1"},
    {"frequency", "1.3", "frequency of light nu = c/lambda, c = 299792458 m/s",
     "lambda_nm:num the wavelength (nm, > 0)", "nu_hz:num the frequency (Hz)", NULL, f_frequency,
     "lambda_nm=500"},
    {"cone-response", "1.3.1", "cone responses s, m, l: sums over the CIE 2006 2-degree LMS cone "
     "fundamentals (390-830 nm)" SPECTRUM_NOTE, SPECTRUM_IN,
     "s:num the short-wave cone response; m:num the middle-wave cone response; "
     "l:num the long-wave cone response", NULL, f_cone_response,
     "lambda_nm=500,550,600 power=1,1,1"},
    {"luminance", "1.4.2", "luminance approximation Y = 0.3 r + 0.59 g + 0.11 b", RGB_IN("the colour"),
     "y:num the luminance Y", "the script writes 0.59q; q is g", f_luminance, "rgb=1,0.5,0.25"},
    {"rgb-to-cmy", "1.4.3", "CMY = 1 - RGB", RGB_IN("the colour"), "cmy:rgb the colour as c,m,y",
     NULL, f_rgb_to_cmy, "rgb=1,0.5,0.25"},
    {"cmy-to-rgb", "1.4.3", "RGB = 1 - CMY", "cmy:rgb the colour as c,m,y in [0,1] (one number: grey)",
     "rgb:rgb the colour as r,g,b", NULL, f_cmy_to_rgb, "cmy=0,0.5,0.75"},
    {"cmy-to-cmyk", "1.4.3", "K = min(C,M,Y); variant script|normalized: (C-K, M-K, Y-K, K) or "
     "((C-K)/(1-K), ..., K), black (K = 1) -> (0,0,0,1)",
     "cmy:rgb the colour as c,m,y in [0,1] (one number: grey); "
     "variant:script|normalized=script script: C-K, normalized: (C-K)/(1-K)",
     "cmyk:vec the colour as c,m,y,k", NULL, f_cmy_to_cmyk, "cmy=0.2,0.5,0.6 variant=normalized"},
    {"cmyk-to-cmy", "1.4.3", "inverse of cmy-to-cmyk: script C = C' + K; normalized C = C'(1-K) + K",
     "cmyk:vec4 the colour as c,m,y,k in [0,1]; "
     "variant:script|normalized=script how the cmyk was made (see cmy-to-cmyk)",
     "cmy:rgb the colour as c,m,y", NULL, f_cmyk_to_cmy, "cmyk=0,0.375,0.5,0.2 variant=normalized"},
    {"rgb-to-hsv", "1.4.4", "hexcone model: V = max, S = (max-min)/max, H in [0,360); grey -> H = 0, "
     "S = 0", RGB_IN("the colour"),
     "h_deg:num the hue H in [0,360) (degrees); s:num the saturation S in [0,1]; v:num the value V = max",
     NULL, f_rgb_to_hsv, "rgb=1,0.5,0.25"},
    {"hsv-to-rgb", "1.4.4", "hexcone model back to RGB (H taken modulo 360)",
     "h_deg:num the hue H (degrees, taken modulo 360); s:num the saturation S in [0,1]; "
     "v:num the value V", "rgb:rgb the colour", NULL, f_hsv_to_rgb, "h_deg=20 s=0.75 v=1"},
    {"spectrum-to-rgb", "1.4.5", "r, g, b: sums over the CIE 1931 RGB colour matching functions "
     "(5 nm table, linear to 1 nm, 380-780 nm; negative lobes kept)" SPECTRUM_NOTE, SPECTRUM_IN,
     "r:num the sum with r-bar; g:num the sum with g-bar; b:num the sum with b-bar (may be negative)",
     NULL, f_spectrum_to_rgb, "lambda_nm=500,550,600 power=1,1,1"},
    {"spectrum-to-xyz", "1.4.6", "tristimulus X, Y, Z: sums over the CIE 1931 2-degree x, y, z-bar "
     "(360-830 nm)" SPECTRUM_NOTE, SPECTRUM_IN,
     "x:num the tristimulus X; y:num the tristimulus Y; z:num the tristimulus Z", NULL,
     f_spectrum_to_xyz, "lambda_nm=500,550,600 power=1,1,1"},
    {"rgb-to-xyz", "1.4.6", "XYZ = M RGB; matrix script (the script's M) | cie1931 (exact CIE RGB, "
     "rows x 1/0.17697) | srgb (IEC 61966-2-1 primaries, D65)",
     RGB_IN("the colour") "; matrix:script|cie1931|srgb=script which M: the script's, the exact "
     "CIE 1931 RGB one, or sRGB's (D65)",
     "xyz:vec the colour X,Y,Z; matrix:mat the matrix M used", NULL, f_rgb_to_xyz,
     "rgb=1,1,1 matrix=srgb"},
    {"xyz-to-rgb", "1.4.6", "RGB = M^-1 XYZ (matrix as in rgb-to-xyz; the output matrix is M^-1)",
     "xyz:vec3 the colour X,Y,Z (3 numbers, not one: X=Y=Z is not grey in general); "
     "matrix:script|cie1931|srgb=script which M (see rgb-to-xyz)",
     "rgb:rgb the colour; matrix:mat the matrix M^-1 used", NULL, f_xyz_to_rgb,
     "xyz=0.9505,1,1.089 matrix=srgb"},
    {"xyz-to-xyy", "1.4.7", "x = X/(X+Y+Z), y = Y/(X+Y+Z), Y; black -> (1/3, 1/3, 0)",
     "xyz:vec3 the colour X,Y,Z", "x:num the chromaticity x; y:num the chromaticity y; "
     "Y:num the luminance Y (= the input's Y)", NULL, f_xyz_to_xyy, "xyz=0.25,0.5,0.25"},
    {"xyy-to-xyz", "1.4.7", "X = (Y/y) x, Z = (Y/y)(1-x-y); y = 0 with Y != 0 is an error",
     XY_IN "; Y:num the luminance Y", "xyz:vec the colour X,Y,Z", NULL, f_xyy_to_xyz,
     "x=0.25 y=0.5 Y=0.5"},
    {"locus", "1.5", "spectral locus: chromaticity of monochromatic light (x, y, z-bar interpolated "
     "linearly, then normalised), 360-830 nm", "lambda_nm:num the wavelength, 360..830 (nm)",
     "x:num the chromaticity x; y:num the chromaticity y", NULL, f_locus, "lambda_nm=520"},
    {"dominant-wavelength", "1.5", "extend white -> C to the locus (polyline at 1 nm, 360-830 nm, "
     "closed by the purple line); purity = |WC|/|W boundary|; on the purple side lambda_nm = "
     "-complementary (CIE)", XY_IN " of the colour C; white:vec2=" WHITE_THIRD " the white "
     "point's x,y (default: equal energy, 1/3, 1/3)",
     "lambda_nm:num the dominant wavelength (nm, negative: minus the complementary one, purple side); "
     "purity:num the excitation purity |WC|/|W boundary|; complementary_nm:num the complementary "
     "wavelength (nm, null when none exists); on_purple_line:bool the ray from white meets the purple line; "
     "boundary:vec the x,y where the ray meets the locus or the purple line", NULL,
     f_dominant_wavelength, "x=0.3 y=0.15"},
    {"mix", "1.5", "additive mixing: X, Y, Z add; the chromaticity lies on the segment, weighted by "
     "X+Y+Z", "xyY_a:vec3 the first colour as x,y,Y; xyY_b:vec3 the second colour as x,y,Y",
     "x:num the mixture's chromaticity x; y:num its chromaticity y; Y:num its luminance Y", NULL, f_mix,
     "xyY_a=0.64,0.33,0.2126 xyY_b=0.3,0.6,0.7152"},
    {"in-gamut", "1.5", "inside the triangle of the primaries: all barycentric coordinates >= 0",
     XY_IN "; " PRIMARIES_IN,
     "inside:bool the point lies in the gamut triangle (edges included); "
     "barycentric:vec its barycentric coordinates with respect to the primaries", NULL, f_in_gamut,
     "x=0.2 y=0.6"},
    {"gamut-map", "1.5", "map into the gamut triangle: method toward-white (along the line to the "
     "white point, hue kept) | nearest (closest point of the triangle); inside points stay",
     XY_IN "; " PRIMARIES_IN "; white:vec2=" WHITE_THIRD " the white point's x,y (toward-white); "
     "method:toward-white|nearest=toward-white along the line to white, or the nearest point",
     "x:num the mapped chromaticity x; y:num the mapped chromaticity y; shift:num the distance moved in xy; "
     "moved:bool the point was outside and has moved", NULL, f_gamut_map, "x=0.2 y=0.7"},
    {NULL, NULL, NULL, NULL, NULL, NULL, NULL, NULL},
};
