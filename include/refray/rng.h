/* refray: counter-based random numbers. The number for (pixel, sample, dimension, seed) is a
 * pure function of those four integers, so an image is bit-identical for any thread count and
 * any tile split (DESIGN.md "Determinism"). The mixer is a variant of SplitMix64's finaliser
 * (Steele, Lea, Flood 2014) applied to a combination of the counters. */
#ifndef REFRAY_RNG_H
#define REFRAY_RNG_H

#include <stdint.h>

static inline uint64_t rf_mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

/* The part of the hash that depends on (pixel, seed) alone: a caller that draws many numbers
 * of one pixel computes it once (rf_rng_uniform_at). */
static inline uint64_t rf_rng_stream(uint64_t pixel, uint64_t seed)
{
    uint64_t h = rf_mix64(seed + 0x9E3779B97F4A7C15ULL);
    return rf_mix64(h ^ (pixel * 0xD1342543DE82EF95ULL));
}

/* rf_rng_uniform from the pixel's stream. */
static inline double rf_rng_uniform_at(uint64_t stream, uint32_t sample, uint32_t dimension)
{
    uint64_t h = rf_mix64(stream ^ (((uint64_t)sample << 32) | dimension));
    return (double)(h >> 11) * (1.0 / 9007199254740992.0);
}

/* A uniform double in [0, 1) with 53 random bits. */
static inline double rf_rng_uniform(uint64_t pixel, uint32_t sample, uint32_t dimension, uint64_t seed)
{
    return rf_rng_uniform_at(rf_rng_stream(pixel, seed), sample, dimension);
}

#endif
