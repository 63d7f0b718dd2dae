/* wp_sha256.h -- SHA-256 (FIPS 180-4), for content-addressed fixture ids. */
#ifndef WP_SHA256_H
#define WP_SHA256_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct wp_sha256 {
    uint32_t state[8];
    uint64_t length;          /* bytes hashed so far */
    unsigned char block[64];  /* pending input */
    size_t used;              /* bytes in block */
} wp_sha256;

void wp_sha256_init(wp_sha256 *hash);
void wp_sha256_update(wp_sha256 *hash, const void *data, size_t size);
void wp_sha256_final(wp_sha256 *hash, unsigned char digest[32]);

#ifdef __cplusplus
}
#endif

#endif
