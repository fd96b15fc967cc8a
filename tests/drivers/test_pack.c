/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The image packer and its reference unpacker (drivers/pack/pack.c, format in pack.h): round trips of the real image
 * and of edge cases, streams the unpacker must refuse, and the in-place check on the brick's layout, which must
 * refuse a download that the unpacker would overwrite before reading it, or that is too large for it.
 * (tests/drivers/test_h8image.c runs the H8 unpacker itself on the same streams.)
 *
 * Usage: test_pack <image (COFF; image.srec, image.bin, image.unpack beside it)> <h8300 nm>
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "h8image.h"
#include "pack.h"

static const char *image_path, *nm_path;
static uint8_t in[0x8000], packed[PACK_BOUND(0x8000)], out[0x8000];

static size_t round_trip(size_t n)
{
    size_t len = pack(in, n, packed);
    memset(out, 0xA5, sizeof out);
    assert_null(unpack(packed, len, out, n));
    assert_memory_equal(out, in, n);
    assert_true(len <= PACK_BOUND(n));
    return len;
}

static uint32_t seed = 1;
static uint8_t rnd(void) /* xorshift32 */
{
    seed ^= seed << 13;
    seed ^= seed >> 17;
    seed ^= seed << 5;
    return (uint8_t)seed;
}

static void edge_cases_round_trip(void **state)
{
    size_t i;
    (void)state;
    assert_int_equal(round_trip(0), 0);             /* empty: no bytes at all */
    in[0] = 7;
    assert_int_equal(round_trip(1), 2);             /* a flag byte and the literal */
    for (i = 0; i < sizeof in; i++)
        in[i] = rnd();
    assert_true(round_trip(sizeof in) > sizeof in); /* incompressible: up to 9 bits a byte (round_trip: the bound) */
    memset(in, 0xEE, sizeof in);
    assert_true(round_trip(sizeof in) < sizeof in / 50); /* a long run: the longest matches, at offset 1 */
    for (i = 0; i < 1000; i++)
        in[i] = (uint8_t)(i % 3);
    assert_true(round_trip(257) < 10); /* 256 + 1: one longest match and one literal */
    for (i = 0; i < sizeof in; i++)
        in[i] = i < 0x100 ? rnd() : i >= 0x7F00 ? in[i - 0x7E00] : (uint8_t)(i * 13 + (i >> 9));
    round_trip(sizeof in); /* far matches: the last 256 bytes repeat ones 32 000 bytes back */
}

static void broken_streams_are_refused(void **state)
{
    size_t len;
    (void)state;
    memcpy(in, "abcabcabcabcXYZ", 15);
    len = pack(in, 15, packed);
    assert_non_null(unpack(packed, len - 1, out, 15));   /* cut short */
    packed[len] = 0;
    assert_non_null(unpack(packed, len + 1, out, 15));   /* a byte too many */
    assert_non_null(unpack(packed, len, out, 16));       /* the stream ends before the output */
    assert_non_null(unpack(packed, len, out, 5));        /* a match runs past the output's end */
    packed[0] = 0x80;                                    /* 1: a match first, before any output */
    packed[1] = 0xFF;
    assert_non_null(unpack(packed, 2, out, 4));
}

/* The real image: round trip, and the in-place check on its layout, which it must pass as the build ran it. */
static void real_image_unpacks_in_place(void **state)
{
    static struct h8 h;
    static uint8_t unpacker[256];
    char path[512];
    struct pack_layout l;
    size_t n, len, size;
    FILE *f;
    (void)state;
    assert_int_equal(h8_image_read(&h, image_path, nm_path), 0);
    l.base = (unsigned long)h8_sym("_rcx_image_base");
    l.head_end = (unsigned long)h8_sym("_rcx_head_end");
    l.packed_start = (unsigned long)h8_sym("_rcx_packed_start");
    l.image_end = (unsigned long)h8_sym("_rcx_image_end");
    l.download_end = (unsigned long)h8_sym("_rcx_download_end");
    l.ram_end = (unsigned long)h8_sym("_rcx_ram_end");
    snprintf(path, sizeof path, "%s.bin", image_path);
    f = fopen(path, "rb");
    assert_non_null(f);
    n = fread(in, 1, sizeof in, f);
    fclose(f);
    snprintf(path, sizeof path, "%s.unpack", image_path);
    f = fopen(path, "rb");
    assert_non_null(f);
    size = fread(unpacker, 1, sizeof unpacker, f);
    fclose(f);
    assert_int_equal(n, l.image_end - l.base);
    assert_int_equal(size, l.packed_start - l.head_end);

    len = round_trip(n);
    assert_true(len < n * 4 / 5); /* H8 code packs by more than a fifth (about a quarter: less as it gets denser) */
    len = pack(in + (l.head_end - l.base), n - (l.head_end - l.base), packed);
    assert_null(pack_check_in_place(&l, in, unpacker, packed, len));
    /* What the build downloads: exactly these bytes after the head (the S-records loaded at 0x8000). */
    assert_memory_equal(h.mem + l.head_end, unpacker, size);
    assert_memory_equal(h.mem + l.packed_start, packed, len);

    /* Moved up less (the largest download ending lower), the unpacker's writes reach bytes not read yet. */
    l.download_end = l.ram_end - 256;
    assert_non_null(pack_check_in_place(&l, in, unpacker, packed, len));
    /* A download past the end of what the unpacker moves up is refused. */
    l.download_end = l.packed_start + len - 1;
    assert_string_equal(pack_check_in_place(&l, in, unpacker, packed, len),
                        "download larger than the unpacker moves up (the image budget)");
}

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(edge_cases_round_trip),
        cmocka_unit_test(broken_streams_are_refused),
        cmocka_unit_test(real_image_unpacks_in_place),
    };
    if (h8_image_args(argc, argv, &image_path, &nm_path))
        return 2;
    return cmocka_run_group_tests(tests, NULL, NULL);
}
