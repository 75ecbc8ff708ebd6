/* refray: transfer functions of §1.1 — gamma, the sRGB curve, quantisation. Per channel. */
#ifndef REFRAY_TRANSFER_H
#define REFRAY_TRANSFER_H

/* §1.1.2 gamma correction: encode v^(1/gamma), decode v^gamma (v < 0 is treated as 0).
 * Erratum: the script writes alpha ∝ alpha^(1/gamma); it is alpha' = alpha^(1/gamma). */
double rf_gamma_encode(double v, double gamma);
double rf_gamma_decode(double v, double gamma);

/* IEC 61966-2-1 sRGB curve: encode switches at v <= 0.0031308, decode at v <= 0.04045. */
double rf_srgb_encode(double v);
double rf_srgb_decode(double v);

/* §1.1 quantisation: round(v * (2^bits - 1)) with v clamped to [0,1] (bits 1..16). */
long rf_quantize(double v, int bits);

#endif
