/* rf_hash_bytes (hash.h). */
#include "refray/hash.h"

#include <string.h>

#include "refray/rng.h"

#define FNV_PRIME 0x100000001b3ULL

/* Eight bytes as a little-endian word on every host (one load where the host is one). */
static uint64_t load_le64(const unsigned char *p)
{
    uint64_t w = 0;
#if defined(__BYTE_ORDER__) && defined(__ORDER_LITTLE_ENDIAN__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    memcpy(&w, p, sizeof w);
#else
    for (int k = 7; k >= 0; k--)
        w = (w << 8) | p[k];
#endif
    return w;
}

uint64_t rf_hash_bytes(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = data;
    size_t i = 0;
    for (; i + 8 <= n; i += 8)
        h = (h ^ load_le64(p + i)) * FNV_PRIME;
    uint64_t last = 0;
    for (size_t k = n; k > i; k--)
        last = (last << 8) | p[k - 1];
    h = (h ^ last) * FNV_PRIME;
    h = (h ^ (uint64_t)n) * FNV_PRIME;
    return rf_mix64(h);
}
