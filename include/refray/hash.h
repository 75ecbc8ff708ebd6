/* refray: a 64-bit content hash, to name what a render was made from (the scene's files) so
 * that tiles of different scenes are never merged. Not cryptographic: it guards against
 * mistakes, not against forgery. FNV-1a (Fowler, Noll, Vo) over little-endian 64-bit words
 * (8 bytes per multiply, about 8x the byte-wise speed), the last partial word zero-padded,
 * the length mixed in, and SplitMix64's finaliser (rng.h) at the end so that every input bit
 * reaches every output bit. */
#ifndef REFRAY_HASH_H
#define REFRAY_HASH_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define RF_HASH_INIT 0xcbf29ce484222325ULL /* FNV's 64-bit offset basis */

/* Continues hash h over n bytes; chains: rf_hash_bytes(rf_hash_bytes(RF_HASH_INIT, a), b). */
uint64_t rf_hash_bytes(uint64_t h, const void *data, size_t n);

#ifdef __cplusplus
}
#endif

#endif
