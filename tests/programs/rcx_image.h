/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The .rcx files nqc writes (`nqc -O<file>`), read into memory and downloaded into a brick.
 *
 * Layout (host-tools.md §3), little-endian throughout:
 *   header   "RCXI", u16 version (0x0102), u16 chunk count, u16 symbol count, u8 target (0 RCX, 3 RCX2, 5 Swan), u8 0
 *   chunks   u8 type (0 task, 1 subroutine), u8 number, u16 code length, code padded with zeros to a multiple of 4
 *   symbols  u8 type (0 task, 1 subroutine, 2 variable), u8 index, u16 length, name of `length` bytes ending in 0
 *
 * The parser trusts nothing in the file: every count, length and number is checked against the bytes that are
 * actually there and against the machine's limits, and a file that breaks any rule is refused with a message.
 * Parsed chunks and names point into the caller's buffer, which must outlive the image.
 */
#ifndef TEST_RCX_IMAGE_H
#define TEST_RCX_IMAGE_H

#include <stddef.h>
#include "rcx.h"

#define RCX_IMAGE_VERSION 0x0102u
#define RCX_IMAGE_HEADER_SIZE 12u

#define RCX_IMAGE_TARGET_RCX 0u   /* nqc's default target, RCX 1.0 firmware */
#define RCX_IMAGE_TARGET_RCX2 3u  /* nqc -TRCX2 */
#define RCX_IMAGE_TARGET_SWAN 5u  /* nqc -TSwan (issue 16) */

#define RCX_CHUNK_TASK 0u
#define RCX_CHUNK_SUB 1u

#define RCX_SYMBOL_TASK 0u
#define RCX_SYMBOL_SUB 1u
#define RCX_SYMBOL_VAR 2u

/* A program slot holds at most 10 tasks and 8 subroutines, each at most once. */
#define RCX_IMAGE_MAX_CHUNKS (RCX_TASKS + RCX_SUBS)
/* Every task may name its own locals, so names can outnumber variables; this is far above what nqc produces. */
#define RCX_IMAGE_MAX_SYMBOLS 256u

struct rcx_chunk {
    u8 type;          /* RCX_CHUNK_TASK or RCX_CHUNK_SUB */
    u8 number;        /* task 0-9, subroutine 0-7 */
    u16 length;       /* code bytes, without the padding */
    const u8 *code;
};

struct rcx_symbol {
    u8 type;          /* RCX_SYMBOL_* */
    u8 index;         /* task, subroutine or variable number */
    const char *name; /* zero-terminated, inside the file buffer */
};

struct rcx_image {
    u16 version;
    u8 target;
    unsigned chunk_count;
    unsigned symbol_count;
    struct rcx_chunk chunk[RCX_IMAGE_MAX_CHUNKS];
    struct rcx_symbol symbol[RCX_IMAGE_MAX_SYMBOLS];
};

/* Parse `size` bytes of a .rcx file. Returns 0, or -1 with a message in err (may be NULL). */
int rcx_image_parse(struct rcx_image *img, const u8 *data, size_t size, char *err, size_t errlen);

/* Read a whole file into a malloc'd buffer (free it with free()). Returns 0, or -1 with a message in err. */
int rcx_image_read_file(const char *path, u8 **data, size_t *size, char *err, size_t errlen);

/* Number of the variable called `name`, or -1 if the image names no such variable. */
int rcx_image_find_var(const struct rcx_image *img, const char *name);

/*
 * Download the image through direct commands in the order `nqc -d` sends them (host-tools.md §2):
 * ping 10; SelectProgram 91 slot if slot >= 0 (what `-pgm slot+1` adds); StopAllTasks 50; DeleteAllTasks 40;
 * DeleteAllSubs 70; every subroutine, then every task, with 35/25 and 45 blocks of 20 bytes; then the
 * download-complete sound 51 05 and the battery query 30.
 * Returns 0, or -1 with a message in err when a command is not answered as nqc expects or a download is refused.
 */
int rcx_image_load(struct rcx *b, const struct rcx_image *img, int slot, char *err, size_t errlen);

#endif
