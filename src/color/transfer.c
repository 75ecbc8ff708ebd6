/* §1.1 transfer functions. */
#include "refray/transfer.h"

#include <math.h>

double rf_gamma_encode(double v, double gamma)
{
    return v > 0.0 ? pow(v, 1.0 / gamma) : 0.0;
}

double rf_gamma_decode(double v, double gamma)
{
    return v > 0.0 ? pow(v, gamma) : 0.0;
}

double rf_srgb_encode(double v)
{
    if (v <= 0.0031308)
        return v > 0.0 ? 12.92 * v : 0.0;
    return 1.055 * pow(v, 1.0 / 2.4) - 0.055;
}

double rf_srgb_decode(double v)
{
    if (v <= 0.04045)
        return v > 0.0 ? v / 12.92 : 0.0;
    return pow((v + 0.055) / 1.055, 2.4);
}

long rf_quantize(double v, int bits)
{
    /* 2^bits - 1 (exact either way; the shift is the fast path of every PNG row) */
    double max = bits >= 1 && bits <= 16 ? (double)((1L << bits) - 1) : ldexp(1.0, bits) - 1.0;
    if (!(v > 0.0)) /* also NaN */
        return 0;
    if (v >= 1.0)
        return (long)max;
    return (long)floor(v * max + 0.5);
}
