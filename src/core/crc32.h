// bedlam — CRC-32 checksums of byte streams.
//
// The CRC-32 of zlib, PNG and gzip (reflected polynomial 0xEDB88320, initial and final value
// 0xFFFFFFFF): a checksum any tool can recompute (Python's zlib.crc32, `gzip -l`). It detects
// every error confined to 32 consecutive bits (so every changed byte); other damage passes with a
// chance of about 2^-32. Checkpoints carry one over their payload (output/checkpoint.h).
#ifndef BDL_CRC32_H
#define BDL_CRC32_H

#include <stddef.h>
#include <stdint.h>

/// The CRC-32 of `size` more bytes after a stream whose CRC-32 so far is `crc` (0 for an empty
/// stream): bdl_crc32(bdl_crc32(0, a, m), b, n) is the CRC-32 of a followed by b.
uint32_t bdl_crc32(uint32_t crc, const void *data, size_t size);

#endif
