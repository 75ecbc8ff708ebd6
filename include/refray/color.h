/* refray: colour science of §1 — quantisation, alpha, colour models, spectra, CIE XYZ/xyY,
 * chromaticity diagrams and gamuts. Transfer curves (gamma, sRGB) are in transfer.h.
 * Contract and conventions: FORMULAS.md, section 1 and "Pinned conventions". */
#ifndef REFRAY_COLOR_H
#define REFRAY_COLOR_H

#include "refray/mat.h"
#include "refray/status.h"
#include "refray/vec.h"

/* ---- §1.1 dynamic range and quantisation (callers check i_min > 0, step > 0) ---- */
double rf_dynamic_range(double i_min, double i_max, double k);   /* (I_max+k)/(I_min+k) */
double rf_linear_steps(double i_min, double i_max, double step); /* (I_max-I_min)/(step I_min) */
double rf_exp_steps(double i_min, double i_max, double step);    /* ceil(ln(R)/ln(1+step)) */
double rf_steps_bits(double steps);                              /* ceil(log2(steps)) */
double rf_exp_level(double i_min, double n, double step);        /* I_min (1+step)^n */
double rf_power_transfer(double n, double n_max, double gamma, double i_max); /* (n/N)^γ I_max */

/* ---- §1.2 alpha compositing: Porter–Duff "a over b" ---- */
typedef struct { RfVec3 rgb; double alpha; } RfRgba;
/* Straight colours: rgb = (a αa + b αb (1-αa)) / α (0 when α = 0); premultiplied: a + b (1-αa). */
RfRgba rf_alpha_over(RfRgba a, RfRgba b, int premultiplied);

/* ---- §1.3 light ---- */
#define RF_SPEED_OF_LIGHT 299792458.0 /* m/s, exact */
double rf_frequency_hz(double lambda_nm);

/* ---- §1.4 colour models ---- */
double rf_luminance(RfVec3 rgb);       /* §1.4.2: 0.3 r + 0.59 g + 0.11 b */
RfVec3 rf_rgb_cmy(RfVec3 v);           /* §1.4.3: 1 - v, both directions */
typedef enum { RF_CMYK_SCRIPT, RF_CMYK_NORMALIZED } RfCmykVariant;
RfVec4 rf_cmy_to_cmyk(RfVec3 cmy, RfCmykVariant variant); /* w holds K */
RfVec3 rf_cmyk_to_cmy(RfVec4 cmyk, RfCmykVariant variant);
RfVec3 rf_rgb_to_hsv(RfVec3 rgb);      /* §1.4.4 hexcone: (h_deg in [0,360), s, v) */
RfVec3 rf_hsv_to_rgb(RfVec3 hsv);

/* ---- spectra (§1.3.1, §1.4.5, §1.4.6) ---- */
typedef enum {
    RF_CMF_XYZ_1931, /* x̄ ȳ z̄, CIE 1931 2°, 360–830 nm */
    RF_CMF_RGB_1931, /* r̄ ḡ b̄, CIE 1931, 380–780 nm (5 nm table, linear to 1 nm) */
    RF_CMF_LMS_2006  /* l̄ m̄ s̄ (x = L, y = M, z = S), CIE 2006 2°, 390–830 nm */
} RfCmf;
void rf_cmf_range(RfCmf cmf, int *first_nm, int *last_nm);
const char *rf_cmf_source(RfCmf cmf); /* publication; distribution */
/* The functions at any wavelength: linear interpolation of the table, 0 outside it. */
RfVec3 rf_cmf_at(RfCmf cmf, double lambda_nm);
/* Σ cmf(λ) P(λ) Δλ over the table's 1 nm grid, Δλ = 1 nm; P is interpolated linearly from the
 * samples (lambda strictly increasing, n >= 1) and 0 outside them. RF_ERR_DOMAIN otherwise. */
RfStatus rf_spectrum_integrate(RfCmf cmf, const double *lambda, const double *power, int n,
                               RfVec3 *out);

/* ---- §1.4.6 RGB <-> XYZ ---- */
typedef enum { RF_RGB_SCRIPT, RF_RGB_CIE1931, RF_RGB_SRGB } RfRgbSpace;
RfMat3 rf_rgb_to_xyz_matrix(RfRgbSpace space);
/* RGB -> XYZ of a device from its primaries' chromaticities, scaled so that RGB = (1,1,1) is
 * the white point with Y = 1. RF_ERR_DEGENERATE for collinear primaries or y = 0. */
RfStatus rf_primaries_matrix(const RfVec2 primaries[3], RfVec2 white, RfMat3 *m);

/* ---- §1.4.7 xyY ---- */
/* Black (X = Y = Z = 0) gives the white chromaticity (1/3, 1/3) with Y = 0; X+Y+Z = 0 otherwise
 * is RF_ERR_DOMAIN. Result as (x, y, Y). */
RfStatus rf_xyz_to_xyy(RfVec3 xyz, RfVec3 *xyy);
/* y = 0 with Y != 0 is RF_ERR_DOMAIN; y = 0 with Y = 0 is black. */
RfStatus rf_xyy_to_xyz(RfVec3 xyy, RfVec3 *xyz);

/* ---- §1.5 chromaticity diagram ---- */
#define RF_LOCUS_FIRST_NM 360
#define RF_LOCUS_LAST_NM 830
/* Chromaticity of monochromatic light (x̄ȳz̄ interpolated, then normalised); RF_ERR_DOMAIN
 * outside 360–830 nm. */
RfStatus rf_locus(double lambda_nm, RfVec2 *xy);

typedef struct {
    double lambda_nm;        /* dominant wavelength; on the purple side minus the complementary */
    double purity;           /* excitation purity |W C| / |W boundary| */
    double complementary_nm; /* valid when has_complementary */
    int has_complementary;   /* 0 when the ray C -> W meets the purple line */
    int on_purple_line;      /* the ray W -> C meets the purple line */
    RfVec2 boundary;         /* where the ray W -> C meets the locus or the purple line */
    RfVec2 complementary_point;
} RfDominant;
/* The locus is the polyline of the chromaticities at 1 nm from 360 to 830 nm, closed by the
 * purple line; a ray from W meets it at its first crossing (smallest distance). RF_ERR_DEGENERATE
 * when C = W. */
RfStatus rf_dominant_wavelength(RfVec2 c, RfVec2 white, RfDominant *out);

/* Additive mixing (Grassmann): XYZ add. Inputs and result (x, y, Y). */
RfStatus rf_mix_xyy(RfVec3 a, RfVec3 b, RfVec3 *out);

/* Barycentric coordinates of c in the triangle of the primaries; RF_ERR_DEGENERATE for a
 * triangle without area. Inside iff all three >= 0. */
RfStatus rf_gamut_barycentric(RfVec2 c, const RfVec2 primaries[3], double bary[3]);
typedef enum { RF_GAMUT_TOWARD_WHITE, RF_GAMUT_NEAREST } RfGamutMethod;
/* Maps c into the triangle: a point inside stays. toward-white moves along the line to the
 * white point (which must be inside, else RF_ERR_DOMAIN); nearest takes the closest point. */
RfStatus rf_gamut_map(RfVec2 c, const RfVec2 primaries[3], RfVec2 white, RfGamutMethod method,
                      RfVec2 *out);

/* The sRGB primaries and D65 white (IEC 61966-2-1). */
extern const RfVec2 rf_srgb_primaries[3];
extern const RfVec2 rf_d65_white;

/* ---- metamerism (§1.3.1) ---- */
/* Builds, on the 1 nm grid lambda = first..first+n-1, a second spectrum p2 = p1 + s B with the
 * same XYZ (CIE 1931) and the same LMS (CIE 2006) as p1: B is the combination of the sine
 * bumps sin(k π (λ - first)/(n-1)), k = 1..7, that all six functions sum to 0, and s is
 * `fraction` of the largest scale keeping p2 >= 0. RF_ERR_DEGENERATE if no such B exists. */
RfStatus rf_metamer(int first_nm, int n, const double *p1, double fraction, double *p2);

#endif
