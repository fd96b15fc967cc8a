/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The compression of the firmware image's downloaded bytes (host side: the packer, and the reference unpacker that
 * checks it). drivers/h8300/unpack.s unpacks the same stream on the brick; this file and unpack.s define the format.
 *
 * The stream is a sequence of items, until the output is complete. Bits are read one at a time from bit bytes
 * (most significant first); a bit byte is taken from the stream when its first bit is needed, so bit bytes and
 * data bytes are interleaved in the order the unpacker needs them. Items:
 *   0, byte                  a literal byte
 *   1, G(g), byte b, G(v)    a match: copy v+1 bytes (2..256) from `off` bytes back in the output, where
 *                            off = 256 * g - b (g = 1..255, b = 0..255: off = 1..65280)
 * G(x) is x >= 1 in interlaced Elias gamma: for each bit of x after its leading 1, from the top, a 0 and that bit;
 * then a 1 (1 -> "1", 2 -> "001", 3 -> "011", 4 -> "00001"). Lengths and offsets are at most 8 bits wide.
 * The packer parses optimally for this cost (dynamic programming over the bit count).
 */
#ifndef RCX_PACK_H
#define RCX_PACK_H

#include <stddef.h>
#include <stdint.h>

/* Most bytes pack() writes for n bytes of input: 9 bits per literal, and the last bit byte. */
#define PACK_BOUND(n) ((n) + (n) / 8 + 1)

/* Packs `n` bytes into `out` (PACK_BOUND(n) bytes); returns the packed size, 0 when out of memory for n > 0. */
size_t pack(const uint8_t *in, size_t n, uint8_t *out);

/* The reference unpacker: `n` bytes from the `len` bytes at `in`. NULL when the stream gave exactly n bytes and
 * was used up; otherwise what is wrong with it. */
const char *unpack(const uint8_t *in, size_t len, uint8_t *out, size_t n);

/* Where the brick unpacks (addresses; linker/openrcx.ld's symbols): the image runs from `base` to `image_end`. The
 * download holds its bytes up to `head_end` (entry, knock string) as they are, then the unpacker
 * (drivers/h8300/unpack.s), then from `packed_start` the packed bytes of the rest of the image. The unpacker, running
 * elsewhere, first moves the bytes packed_start..download_end (the end of the largest download) up so that they end
 * at `ram_end`, then unpacks forward from head_end. */
struct pack_layout {
    unsigned long base, head_end, packed_start, image_end, download_end, ram_end;
};

/* Runs that on a copy of the brick's memory: NULL when the download (the image's head, the `unpacker` bytes and the
 * `len` packed bytes) fits, and unpacks to `image` (image_end - base bytes) with the unpacker's writes never reaching
 * packed bytes it has not read yet; otherwise the reason. */
const char *pack_check_in_place(const struct pack_layout *l, const uint8_t *image, const uint8_t *unpacker,
                                const uint8_t *packed, size_t len);

#endif
