/* Sample patterns, warps and reconstruction filters (§3.9, §3.10). Every value is a pure function
 * of its arguments: the jitter comes from the counter-based generator (rng.h), the shuffles and
 * scrambles from keys hashed out of (pixel, dimension, seed), so there is no state at all. */
#include "refray/sampling.h"
#include "refray/rng.h"

#include <math.h>
#include <string.h>

#if defined(__SSE4_1__)
#include <smmintrin.h>
#define RF_SAMPLING_SSE 1
#endif

/* The largest double below 1: where a jittered cell could round up to 1.0, the result is
 * clamped to it, so that every sample lies in [0,1). */
static const double rf_one_minus = 0x1.fffffffffffffp-1;

static double rf_below_one(double x)
{
    return x < 1.0 ? x : rf_one_minus;
}

/* ---- keys, permutations, scrambles -------------------------------------------------------- */

/* Tags that tell the keys of one (pixel, dimension, seed) apart. */
enum { RF_KEY_ORDER = 1, RF_KEY_LHS_Y, RF_KEY_SOBOL_INDEX, RF_KEY_SOBOL_X, RF_KEY_SOBOL_Y };

/* A 64-bit key for one use within a pixel and dimension. The chain differs from rng.h's (other
 * constants, add instead of xor), so keys and jitter values are unrelated. */
static uint64_t rf_key_base(uint64_t pixel, uint64_t seed)
{
    return rf_mix64(rf_mix64(seed ^ 0x5851F42D4C957F2DULL) + pixel * 0x9E3779B97F4A7C15ULL);
}

/* The key of one tag from rf_key_base: a sample that needs several keys hashes the pixel once. */
static uint64_t rf_key_tag(uint64_t base, uint32_t dimension, uint32_t tag)
{
    return rf_mix64(base ^ (((uint64_t)tag << 32) | dimension));
}

/* A keyed bijection of [0, n) for any n, cheap enough to run per sample: on the smallest
 * power of two >= n, four rounds of "xor a round key, multiply by an odd round key, xorshift"
 * (each a bijection of the b-bit words, so the chain is one), repeated while the result lies
 * outside [0, n) (cycle walking: it returns to [0, n) in fewer than 2 tries on average). It is
 * the structure of Kensler's permute() ("Correlated Multi-Jittered Sampling", 2013) with round
 * keys drawn from the key. Not every permutation is reachable (for n = 4, most of the 24 are);
 * what the sampler needs is that the strata of two dimensions are paired differently in every
 * pixel, which tests/test_sampling.c checks with chi-square tests. The swap-or-not shuffle
 * (Hoang, Morris, Rogaway 2012) reached every order evenly but cost 30 % of a soft-shadow render
 * (docs/performance.md). rf_permute_keys draws the round keys (once per pixel and dimension,
 * rf_sample_keys), rf_permute applies them. */
static RfPermuteKeys rf_permute_keys(uint64_t key)
{
    uint64_t k0 = rf_mix64(key), k1 = rf_mix64(key ^ 0x6A09E667F3BCC909ULL);
    RfPermuteKeys p = {{(uint32_t)k0, (uint32_t)(k0 >> 32), (uint32_t)k1, (uint32_t)(k1 >> 32)},
                       {(uint32_t)(k0 >> 16) | 1u, (uint32_t)(k0 >> 48) * 0x9E3779B9u | 1u, (uint32_t)(k1 >> 16) | 1u,
                        (uint32_t)(k1 >> 40) * 0x85EBCA6Bu | 1u}};
    return p;
}

static uint32_t rf_permute(uint32_t x, uint32_t n, const RfPermuteKeys *p)
{
    if (n <= 1)
        return 0;
    unsigned bits = 1;
    while (bits < 32 && ((uint64_t)1 << bits) < n)
        bits++;
    uint32_t mask = (uint32_t)(((uint64_t)1 << bits) - 1), shift = bits > 1 ? (bits + 1) / 2 : 1;
    do {
        for (int r = 0; r < 4; r++) {
            x = (x ^ p->xor_key[r]) & mask;
            x = (x * p->mul_key[r]) & mask;
            x ^= x >> shift;
        }
    } while (x >= n);
    return x;
}

static inline uint32_t rf_reverse_bits(uint32_t x)
{
#if defined(__GNUC__)
    x = __builtin_bswap32(x); /* the bytes in one instruction, then the bits within them */
#else
    x = (x << 16) | (x >> 16);
    x = ((x & 0x00FF00FFu) << 8) | ((x >> 8) & 0x00FF00FFu);
#endif
    x = ((x & 0x0F0F0F0Fu) << 4) | ((x >> 4) & 0x0F0F0F0Fu);
    x = ((x & 0x33333333u) << 2) | ((x >> 2) & 0x33333333u);
    x = ((x & 0x55555555u) << 1) | ((x >> 1) & 0x55555555u);
    return x;
}

/* A keyed Laine-Karras permutation (Burley 2020, "Practical Hash-based Owen Scrambling", §3):
 * built only of addition, multiplication by an odd number and x ^= x * (even number), each of
 * which changes bit i as a function of bits 0..i alone. The key enters both an addition and a
 * multiplier, so whether the flip of bit i depends on a lower bit varies from key to key. */
static inline uint32_t rf_lk_permute(uint32_t x, uint64_t key)
{
    x += (uint32_t)key;
    x *= (uint32_t)(key >> 32) | 1u;
    x ^= x * 0xA3B195A4u;
    x += (uint32_t)(key >> 16);
    x *= 0x2C1B3C6Du;
    x ^= x * 0x297A2D38u;
    x *= (uint32_t)(key >> 40) | 1u;
    x ^= x * 0x6A09E66Cu;
    return x;
}

/* Owen's nested uniform scramble of a 32-bit fraction (Burley 2020): read with its most
 * significant bit first, the flip of each digit depends only on the digits before it, so every
 * elementary interval is mapped onto one of the same size. */
static inline uint32_t rf_owen_scramble(uint32_t x, uint64_t key)
{
    return rf_reverse_bits(rf_lk_permute(rf_reverse_bits(x), key));
}

/* rf_owen_scramble of a fraction given with its bits already reversed (least significant digit
 * first): one reversal instead of two. */
static inline uint32_t rf_owen_scramble_reversed(uint32_t reversed, uint64_t key)
{
    return rf_reverse_bits(rf_lk_permute(reversed, key));
}

/* The second component of the 2D Sobol sequence as a 32-bit fraction: the generator matrix of
 * the primitive polynomial x + 1 (direction numbers m_1 = 1, m_j = 2 m_{j-1} xor m_{j-1}, i.e.
 * Pascal's triangle mod 2), column j being v_j = m_j 2^(32-j), here with its bits reversed
 * (v_0 = 1, v_{j+1} = v_j xor 2 v_j), the form the scramble takes. The first component is the van
 * der Corput sequence, rf_reverse_bits(i).
 * Bit m of v_j is C(j, m) mod 2, which is 1 exactly when the bits of m are a subset of those of j
 * (Lucas), so bit m of the result is the parity of the set bits j of i with j a superset of m:
 * the superset-sum transform over the five bits of the index m, one shift, mask and xor per bit
 * (the loop over the set bits of i it replaces mispredicted a branch per bit: 15 % of a sobol
 * render; tests/test_sampling.c checks both against each other). */
static inline uint32_t rf_sobol_y_reversed(uint32_t i)
{
    i ^= (i >> 1) & 0x55555555u;
    i ^= (i >> 2) & 0x33333333u;
    i ^= (i >> 4) & 0x0F0F0F0Fu;
    i ^= (i >> 8) & 0x00FF00FFu;
    i ^= i >> 16;
    return i;
}

static const double rf_two_m32 = 1.0 / 4294967296.0;

/* floor(sqrt(n)), exactly. */
static uint32_t rf_isqrt(uint32_t n)
{
    uint64_t a = (uint64_t)sqrt((double)n);
    while (a * a > n)
        a--;
    while ((a + 1) * (a + 1) <= n)
        a++;
    return (uint32_t)a;
}

/* The columns a of the uniform pattern's a x b grid with a b = n exactly: the largest divisor of
 * n not above sqrt(n) (1 for a prime n: one row of n cells). Every cell then has the area 1/n and
 * holds one sample, so the grid's mean is the midpoint rule. (The first version took
 * a = floor(sqrt n) rows of ceil(n / a) and left the last row partly empty, which weighted the
 * upper rows more: at 32 light samples a biased estimate of the light.) */
static uint32_t rf_grid_columns(uint32_t n)
{
    uint32_t a = rf_isqrt(n);
    while (n % a)
        a--;
    return a;
}

/* ---- sample patterns ----------------------------------------------------------------------- */

const char *rf_sampler_name(RfSampler s)
{
    switch (s) {
    case RF_SAMPLER_UNIFORM: return "uniform";
    case RF_SAMPLER_RANDOM: return "random";
    case RF_SAMPLER_STRATIFIED: return "stratified";
    case RF_SAMPLER_SOBOL: return "sobol";
    case RF_SAMPLER_COUNT: break;
    }
    return "sampler";
}

int rf_sampler_parse(const char *name)
{
    for (int s = 0; s < RF_SAMPLER_COUNT; s++)
        if (name && strcmp(name, rf_sampler_name((RfSampler)s)) == 0)
            return s;
    return -1;
}

RfSampleKeys rf_sample_keys(RfSampler s, uint64_t pixel, uint32_t dimension, uint64_t seed)
{
    RfSampleKeys K = {s, dimension, pixel, seed, 0, 0, {{0, 0, 0, 0}, {0, 0, 0, 0}}, 0, 0, 0};
    /* random: the counter-based generator hashes (pixel, k, dimension) per value */
    if (s == RF_SAMPLER_RANDOM || s == RF_SAMPLER_STRATIFIED || s >= RF_SAMPLER_COUNT)
        K.stream = rf_rng_stream(pixel, seed);
    if (s == RF_SAMPLER_RANDOM || s >= RF_SAMPLER_COUNT)
        return K;
    K.base = rf_key_base(pixel, seed);
    if (s == RF_SAMPLER_SOBOL) {
        K.sobol_index = rf_key_tag(K.base, dimension, RF_KEY_SOBOL_INDEX);
        K.sobol_x = rf_key_tag(K.base, dimension, RF_KEY_SOBOL_X);
        K.sobol_y = rf_key_tag(K.base, dimension, RF_KEY_SOBOL_Y);
    } else if (dimension != 0) { /* the pixel position (dimension 0) keeps its strata in order */
        K.order = rf_permute_keys(rf_key_tag(K.base, dimension, RF_KEY_ORDER));
    }
    return K;
}

/* Stratified and uniform: the cell of sample k. Dimension 0 (the pixel position) keeps the order
 * k, so that it is the renderer's historical pattern; other dimensions shuffle it, so that the
 * strata of two dimensions are not paired the same way in every pixel. */
static uint32_t rf_cell_keyed(const RfSampleKeys *K, uint32_t k, uint32_t n)
{
    return K->dimension == 0 ? k : rf_permute(k, n, &K->order);
}

/* Stratified sample k of n (side = rf_isqrt(n), which a run of samples computes once). */
static inline void stratified_2d(const RfSampleKeys *K, uint32_t k, uint32_t n, uint32_t side, double out[2])
{
    k %= n;
    double u = rf_rng_uniform_at(K->stream, k, 2 * K->dimension), v = rf_rng_uniform_at(K->stream, k, 2 * K->dimension + 1);
    uint32_t c = rf_cell_keyed(K, k, n);
    if (side * side == n) {
        /* the operations of the renderer's k x k jitter, in the same order; the clamp only
         * acts when (side - 1) + u rounds up to side, which the renderer let through as 1.0 */
        out[0] = rf_below_one(((double)(c % side) + u) / (double)side);
        out[1] = rf_below_one(((double)(c / side) + v) / (double)side);
    } else {
        /* Latin hypercube: column c, row a second permutation of c */
        RfPermuteKeys lhs = rf_permute_keys(rf_key_tag(K->base, K->dimension, RF_KEY_LHS_Y));
        uint32_t r = rf_permute(c, n, &lhs);
        out[0] = rf_below_one(((double)c + u) / (double)n);
        out[1] = rf_below_one(((double)r + v) / (double)n);
    }
}

void rf_sample_2d_keyed(const RfSampleKeys *K, uint32_t k, uint32_t n, double out[2])
{
    uint32_t du = 2 * K->dimension, dv = 2 * K->dimension + 1;
    if (n == 0)
        n = 1;
    switch (K->sampler) {
    case RF_SAMPLER_UNIFORM: {
        /* the grid's cell centres; dimensions other than the pixel position take them in a
         * shuffled order, as the stratified sampler does, or sample k would put its lens and
         * light points on the same cell as its pixel offset in every pixel (a bias that never
         * averages out) */
        uint32_t a = rf_grid_columns(n), b = n / a;
        uint32_t c = rf_cell_keyed(K, k % n, n);
        out[0] = ((double)(c % a) + 0.5) / (double)a;
        out[1] = ((double)(c / a) + 0.5) / (double)b;
        return;
    }
    case RF_SAMPLER_STRATIFIED:
        stratified_2d(K, k, n, rf_isqrt(n), out);
        return;
    case RF_SAMPLER_SOBOL: {
        /* the index of sample k in the sequence: the nested scramble applied to the integer k
         * (Burley 2020 §4, "shuffling"). Bit j of i is bit j of k flipped by a function of the
         * bits above j, so each aligned block [a 2^m, (a+1) 2^m) of samples is an aligned block of
         * the sequence in another order: again a (0,2)-sequence, any prefix a union of nets. */
        uint32_t i = rf_owen_scramble(k, K->sobol_index);
        /* the van der Corput component is i reversed, so its scramble needs one reversal */
        uint32_t x = rf_owen_scramble_reversed(i, K->sobol_x);
        uint32_t y = rf_owen_scramble_reversed(rf_sobol_y_reversed(i), K->sobol_y);
        out[0] = (double)x * rf_two_m32;
        out[1] = (double)y * rf_two_m32;
        return;
    }
    case RF_SAMPLER_RANDOM:
    case RF_SAMPLER_COUNT:
        break;
    }
    out[0] = rf_rng_uniform_at(K->stream, k, du);
    out[1] = rf_rng_uniform_at(K->stream, k, dv);
}

#if RF_SAMPLING_SSE
/* Four lanes of rf_reverse_bits: the bytes by a shuffle, the bits of each nibble by a table. */
static inline __m128i rf_reverse_bits4(__m128i x)
{
    const __m128i bytes = _mm_setr_epi8(3, 2, 1, 0, 7, 6, 5, 4, 11, 10, 9, 8, 15, 14, 13, 12);
    const __m128i nibble = _mm_setr_epi8(0x0, 0x8, 0x4, 0xC, 0x2, 0xA, 0x6, 0xE, 0x1, 0x9, 0x5, 0xD, 0x3, 0xB, 0x7, 0xF);
    const __m128i low = _mm_set1_epi8(0x0F);
    x = _mm_shuffle_epi8(x, bytes);
    __m128i lo = _mm_shuffle_epi8(nibble, _mm_and_si128(x, low));
    __m128i hi = _mm_shuffle_epi8(nibble, _mm_and_si128(_mm_srli_epi16(x, 4), low));
    return _mm_or_si128(_mm_slli_epi16(lo, 4), hi);
}

/* Four lanes of rf_lk_permute, the same operations on 32-bit words. */
static inline __m128i rf_lk_permute4(__m128i x, uint64_t key)
{
    x = _mm_add_epi32(x, _mm_set1_epi32((int)(uint32_t)key));
    x = _mm_mullo_epi32(x, _mm_set1_epi32((int)((uint32_t)(key >> 32) | 1u)));
    x = _mm_xor_si128(x, _mm_mullo_epi32(x, _mm_set1_epi32((int)0xA3B195A4u)));
    x = _mm_add_epi32(x, _mm_set1_epi32((int)(uint32_t)(key >> 16)));
    x = _mm_mullo_epi32(x, _mm_set1_epi32((int)0x2C1B3C6Du));
    x = _mm_xor_si128(x, _mm_mullo_epi32(x, _mm_set1_epi32((int)0x297A2D38u)));
    x = _mm_mullo_epi32(x, _mm_set1_epi32((int)((uint32_t)(key >> 40) | 1u)));
    x = _mm_xor_si128(x, _mm_mullo_epi32(x, _mm_set1_epi32((int)0x6A09E66Cu)));
    return x;
}

/* Four lanes of rf_sobol_y_reversed. */
static inline __m128i rf_sobol_y_reversed4(__m128i i)
{
    i = _mm_xor_si128(i, _mm_and_si128(_mm_srli_epi32(i, 1), _mm_set1_epi32(0x55555555)));
    i = _mm_xor_si128(i, _mm_and_si128(_mm_srli_epi32(i, 2), _mm_set1_epi32(0x33333333)));
    i = _mm_xor_si128(i, _mm_and_si128(_mm_srli_epi32(i, 4), _mm_set1_epi32(0x0F0F0F0F)));
    i = _mm_xor_si128(i, _mm_and_si128(_mm_srli_epi32(i, 8), _mm_set1_epi32(0x00FF00FF)));
    return _mm_xor_si128(i, _mm_srli_epi32(i, 16));
}

/* Sobol samples k0 .. k0 + 3: rf_sample_2d_keyed's integer steps in four lanes. */
static void rf_sobol4(const RfSampleKeys *K, uint32_t k0, double (*out)[2])
{
    __m128i k = _mm_add_epi32(_mm_set1_epi32((int)k0), _mm_setr_epi32(0, 1, 2, 3));
    __m128i i = rf_reverse_bits4(rf_lk_permute4(rf_reverse_bits4(k), K->sobol_index));
    __m128i x = rf_reverse_bits4(rf_lk_permute4(i, K->sobol_x));
    __m128i y = rf_reverse_bits4(rf_lk_permute4(rf_sobol_y_reversed4(i), K->sobol_y));
    uint32_t xs[4], ys[4];
    _mm_storeu_si128((__m128i *)xs, x);
    _mm_storeu_si128((__m128i *)ys, y);
    for (int j = 0; j < 4; j++) {
        out[j][0] = (double)xs[j] * rf_two_m32;
        out[j][1] = (double)ys[j] * rf_two_m32;
    }
}
#endif

void rf_sample_2d_keyed_run(const RfSampleKeys *K, uint32_t k0, uint32_t count, uint32_t n, double (*out)[2])
{
    uint32_t j = 0;
#if RF_SAMPLING_SSE
    if (K->sampler == RF_SAMPLER_SOBOL)
        for (; j + 4 <= count; j += 4)
            rf_sobol4(K, k0 + j, out + j);
#endif
    if (K->sampler == RF_SAMPLER_STRATIFIED && n > 0) { /* the strata's side once for the run */
        uint32_t side = rf_isqrt(n);
        for (; j < count; j++)
            stratified_2d(K, k0 + j, n, side, out[j]);
    }
    for (; j < count; j++)
        rf_sample_2d_keyed(K, k0 + j, n, out[j]);
}

void rf_sample_2d(RfSampler s, uint32_t k, uint32_t n, uint64_t pixel, uint32_t dimension, uint64_t seed,
                  double out[2])
{
    RfSampleKeys K = rf_sample_keys(s, pixel, dimension, seed);
    rf_sample_2d_keyed(&K, k, n, out);
}

double rf_sample_1d(RfSampler s, uint32_t k, uint32_t n, uint64_t pixel, uint32_t dimension, uint64_t seed)
{
    RfSampleKeys K = rf_sample_keys(s, pixel, dimension, seed);
    if (n == 0)
        n = 1;
    switch (s) {
    case RF_SAMPLER_UNIFORM:
        return ((double)rf_cell_keyed(&K, k % n, n) + 0.5) / (double)n;
    case RF_SAMPLER_STRATIFIED: {
        k %= n;
        double u = rf_rng_uniform(pixel, k, 2 * dimension, seed);
        return rf_below_one(((double)rf_cell_keyed(&K, k, n) + u) / (double)n);
    }
    case RF_SAMPLER_SOBOL: /* the first component of the 2D sample: the scrambled van der Corput sequence */
        return (double)rf_owen_scramble_reversed(rf_owen_scramble(k, K.sobol_index), K.sobol_x) * rf_two_m32;
    case RF_SAMPLER_RANDOM:
    case RF_SAMPLER_COUNT:
        break;
    }
    return rf_rng_uniform(pixel, k, 2 * dimension, seed);
}

/* ---- warps --------------------------------------------------------------------------------- */

/* Shirley and Chiu, "A Low Distortion Map Between Disk and Square" (1997): the square
 * [-1,1]^2 is cut into four triangles by its diagonals; in each, the distance from the centre
 * along the major axis becomes the radius and the position along the edge the angle, so
 * concentric squares map onto concentric circles and area is preserved. */
void rf_warp_disk(double u, double v, double *x, double *y)
{
    double a = 2.0 * u - 1.0, b = 2.0 * v - 1.0, r, phi;
    if (a == 0.0 && b == 0.0) {
        *x = 0.0;
        *y = 0.0;
        return;
    }
    if (fabs(a) > fabs(b)) {
        r = a;
        phi = (RF_PI / 4.0) * (b / a);
    } else {
        r = b;
        phi = RF_PI / 2.0 - (RF_PI / 4.0) * (a / b);
    }
    *x = r * cos(phi);
    *y = r * sin(phi);
}

/* The direction at cos(theta) = 1 - t, azimuth 2 pi v; sin^2 = t (2 - t) keeps its digits near
 * the pole, where 1 - z^2 would cancel. */
static RfVec3 rf_direction(double t, double v)
{
    double z = 1.0 - t, r = sqrt(fmax(0.0, t * (2.0 - t))), phi = 2.0 * RF_PI * v;
    return rf_vec3(r * cos(phi), r * sin(phi), z);
}

/* Archimedes: z is uniform on [-1, 1] for a uniform point on the sphere. */
RfVec3 rf_warp_sphere(double u, double v)
{
    return rf_direction(2.0 * u, v);
}

/* The solid angle of a cap is 2 pi (1 - cos_max), linear in 1 - cos(theta): that is uniform. */
RfVec3 rf_warp_cone(double u, double v, double cos_max)
{
    return rf_direction(u * (1.0 - cos_max), v);
}

double rf_warp_cone_pdf(double cos_max)
{
    return 1.0 / (2.0 * RF_PI * (1.0 - cos_max));
}

/* The density of z = cos(theta) is (n + 1) z^n on [0, 1], its distribution function z^(n+1):
 * z = u^(1/(n+1)) inverts it. */
RfVec3 rf_warp_cos_power(double u, double v, double n)
{
    double z = pow(u, 1.0 / (n + 1.0)), r = sqrt(fmax(0.0, (1.0 - z) * (1.0 + z))), phi = 2.0 * RF_PI * v;
    return rf_vec3(r * cos(phi), r * sin(phi), z);
}

double rf_warp_cos_power_pdf(RfVec3 dir, double n)
{
    return dir.z > 0.0 ? (n + 1.0) / (2.0 * RF_PI) * pow(dir.z, n) : 0.0;
}

/* Duff, Burgess, Christensen, Hery, Kensler, Liani, Villemin, "Building an Orthonormal Basis,
 * Revisited" (JCGT 2017): Frisvad's closed form with the sign of n.z chosen by copysign, which
 * removes its singularity at n = -z without a threshold. Right-handed: s x t = n. */
RfFrame rf_frame(RfVec3 n)
{
    double sign = copysign(1.0, n.z), a = -1.0 / (sign + n.z), b = n.x * n.y * a;
    RfFrame f;
    f.s = rf_vec3(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
    f.t = rf_vec3(b, sign + n.y * n.y * a, -n.y);
    f.n = n;
    return f;
}

RfVec3 rf_frame_to_world(const RfFrame *f, RfVec3 local)
{
    return rf_vec3_add(rf_vec3_add(rf_vec3_scale(f->s, local.x), rf_vec3_scale(f->t, local.y)),
                       rf_vec3_scale(f->n, local.z));
}

/* ---- reconstruction filters ---------------------------------------------------------------- */

RfFilter rf_filter_default(RfFilterKind kind)
{
    RfFilter f;
    f.kind = kind;
    f.sigma = 0.0;
    switch (kind) {
    case RF_FILTER_GAUSSIAN:
        f.radius = 1.5;
        f.sigma = 0.5;
        break;
    case RF_FILTER_MITCHELL:
        f.radius = 2.0;
        break;
    case RF_FILTER_BOX:
    case RF_FILTER_COUNT:
    default:
        f.radius = 0.5;
        break;
    }
    return f;
}

const char *rf_filter_name(RfFilterKind kind)
{
    switch (kind) {
    case RF_FILTER_BOX: return "box";
    case RF_FILTER_GAUSSIAN: return "gaussian";
    case RF_FILTER_MITCHELL: return "mitchell";
    case RF_FILTER_COUNT: break;
    }
    return "filter";
}

int rf_filter_parse(const char *name)
{
    for (int k = 0; k < RF_FILTER_COUNT; k++)
        if (name && strcmp(name, rf_filter_name((RfFilterKind)k)) == 0)
            return k;
    return -1;
}

/* The Gaussian shifted down by its value at the radius, so that it reaches 0 there without a
 * step (as pbrt does). */
static double rf_gaussian_1d(double x, double sigma, double radius)
{
    double s2 = 2.0 * sigma * sigma;
    return fmax(0.0, exp(-x * x / s2) - exp(-radius * radius / s2));
}

/* Mitchell and Netravali, "Reconstruction Filters in Computer Graphics" (1988), eq. 8: the
 * cubic with support [-2, 2], here B = C = 1/3 (their recommendation). It integrates to 1. */
static double rf_mitchell_1d(double x)
{
    const double B = 1.0 / 3.0, C = 1.0 / 3.0;
    x = fabs(x);
    if (x < 1.0)
        return ((12.0 - 9.0 * B - 6.0 * C) * x * x * x + (-18.0 + 12.0 * B + 6.0 * C) * x * x + (6.0 - 2.0 * B)) /
               6.0;
    if (x < 2.0)
        return ((-B - 6.0 * C) * x * x * x + (6.0 * B + 30.0 * C) * x * x + (-12.0 * B - 48.0 * C) * x +
                (8.0 * B + 24.0 * C)) /
               6.0;
    return 0.0;
}

double rf_filter_eval(const RfFilter *f, double dx, double dy)
{
    double r = f->radius;
    if (!(fabs(dx) <= r && fabs(dy) <= r))
        return 0.0;
    switch (f->kind) {
    case RF_FILTER_BOX:
        return 1.0;
    case RF_FILTER_GAUSSIAN:
        return rf_gaussian_1d(dx, f->sigma, r) * rf_gaussian_1d(dy, f->sigma, r);
    case RF_FILTER_MITCHELL:
        /* the kernel's support [-2, 2] stretched onto [-r, r] */
        return rf_mitchell_1d(2.0 * dx / r) * rf_mitchell_1d(2.0 * dy / r);
    case RF_FILTER_COUNT:
        break;
    }
    return 0.0;
}
