/* SPDX-License-Identifier: MPL-2.0 */
/* Reading nqc's .rcx files and downloading them as `nqc -d` does; see rcx_image.h. */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "brick.h"
#include "rcx_image.h"

static int fail(char *err, size_t errlen, const char *fmt, ...)
{
    va_list ap;
    if (err && errlen) {
        va_start(ap, fmt);
        vsnprintf(err, errlen, fmt, ap);
        va_end(ap);
    }
    return -1;
}

/* A read cursor: every take checks that the bytes are there before handing them out. */
struct cursor {
    const u8 *data;
    size_t size;
    size_t pos;
};

static size_t left(const struct cursor *c)
{
    return c->size - c->pos;
}

static const u8 *take(struct cursor *c, size_t n)
{
    const u8 *p;
    if (n > left(c))
        return NULL;
    p = c->data + c->pos;
    c->pos += n;
    return p;
}

static int parse_chunk(struct rcx_image *img, struct cursor *c, unsigned i, char *err, size_t errlen)
{
    const u8 *h = take(c, 4);
    struct rcx_chunk *ch = &img->chunk[i];
    size_t padded;
    unsigned j;

    if (!h)
        return fail(err, errlen, "chunk %u: header cut short at byte %lu", i, (unsigned long)c->pos);
    ch->type = h[0];
    ch->number = h[1];
    ch->length = RCX_LE16(h + 2);
    if (ch->type != RCX_CHUNK_TASK && ch->type != RCX_CHUNK_SUB)
        return fail(err, errlen, "chunk %u: type %u is neither task (0) nor subroutine (1)", i, ch->type);
    if (ch->number >= (ch->type == RCX_CHUNK_TASK ? RCX_TASKS : RCX_SUBS))
        return fail(err, errlen, "chunk %u: %s number %u out of range", i,
                    ch->type == RCX_CHUNK_TASK ? "task" : "subroutine", ch->number);
    for (j = 0; j < i; j++)
        if (img->chunk[j].type == ch->type && img->chunk[j].number == ch->number)
            return fail(err, errlen, "chunk %u: %s %u appears twice", i,
                        ch->type == RCX_CHUNK_TASK ? "task" : "subroutine", ch->number);
    padded = ((size_t)ch->length + 3u) & ~(size_t)3u;
    ch->code = take(c, padded);
    if (!ch->code)
        return fail(err, errlen, "chunk %u: %u code bytes (%lu padded) announced, %lu left in the file", i,
                    ch->length, (unsigned long)padded, (unsigned long)left(c));
    return 0;
}

static int parse_symbol(struct rcx_image *img, struct cursor *c, unsigned i, char *err, size_t errlen)
{
    const u8 *h = take(c, 4);
    struct rcx_symbol *s = &img->symbol[i];
    const u8 *name;
    unsigned len, limit;

    if (!h)
        return fail(err, errlen, "symbol %u: header cut short at byte %lu", i, (unsigned long)c->pos);
    s->type = h[0];
    s->index = h[1];
    len = RCX_LE16(h + 2);
    switch (s->type) {
    case RCX_SYMBOL_TASK: limit = RCX_TASKS; break;
    case RCX_SYMBOL_SUB:  limit = RCX_SUBS; break;
    case RCX_SYMBOL_VAR:  limit = img->target == RCX_IMAGE_TARGET_SWAN ? RCX_ALL_GLOBALS : RCX_VARS; break;
    default:
        return fail(err, errlen, "symbol %u: unknown type %u", i, s->type);
    }
    if (s->index >= limit)
        return fail(err, errlen, "symbol %u: index %u out of range for type %u", i, s->index, s->type);
    if (len < 2)
        return fail(err, errlen, "symbol %u: name length %u leaves no name", i, len);
    name = take(c, len);
    if (!name)
        return fail(err, errlen, "symbol %u: name of %u bytes, %lu left in the file", i, len, (unsigned long)left(c));
    /* The name must end exactly at its terminating zero: no zero inside it, one at the end. */
    if (memchr(name, 0, len) != name + len - 1)
        return fail(err, errlen, "symbol %u: name is not a single zero-terminated string", i);
    s->name = (const char *)name;
    return 0;
}

int rcx_image_parse(struct rcx_image *img, const u8 *data, size_t size, char *err, size_t errlen)
{
    struct cursor c;
    const u8 *h;
    unsigned i;

    memset(img, 0, sizeof *img);
    if (!data)
        return fail(err, errlen, "no data");
    c.data = data;
    c.size = size;
    c.pos = 0;
    h = take(&c, RCX_IMAGE_HEADER_SIZE);
    if (!h)
        return fail(err, errlen, "file of %lu bytes is shorter than the %u-byte header", (unsigned long)size,
                    RCX_IMAGE_HEADER_SIZE);
    if (memcmp(h, "RCXI", 4) != 0)
        return fail(err, errlen, "not an .rcx file (no \"RCXI\" signature)");
    img->version = RCX_LE16(h + 4);
    img->chunk_count = RCX_LE16(h + 6);
    img->symbol_count = RCX_LE16(h + 8);
    img->target = h[10];
    if (img->version != RCX_IMAGE_VERSION)
        return fail(err, errlen, "format version %04x, expected %04x", img->version, RCX_IMAGE_VERSION);
    if (img->target != RCX_IMAGE_TARGET_RCX && img->target != RCX_IMAGE_TARGET_RCX2 && img->target != RCX_IMAGE_TARGET_SWAN)
        return fail(err, errlen, "target %u is not an RCX (0), RCX2 (3) or Swan (5)", img->target);
    if (h[11] != 0)
        return fail(err, errlen, "header byte 11 is %u, expected 0", h[11]);
    if (img->chunk_count > RCX_IMAGE_MAX_CHUNKS)
        return fail(err, errlen, "%u chunks; a program holds at most %u", img->chunk_count, RCX_IMAGE_MAX_CHUNKS);
    if (img->symbol_count > RCX_IMAGE_MAX_SYMBOLS)
        return fail(err, errlen, "%u symbols; at most %u are accepted", img->symbol_count, RCX_IMAGE_MAX_SYMBOLS);
    for (i = 0; i < img->chunk_count; i++)
        if (parse_chunk(img, &c, i, err, errlen))
            return -1;
    for (i = 0; i < img->symbol_count; i++)
        if (parse_symbol(img, &c, i, err, errlen))
            return -1;
    if (left(&c))
        return fail(err, errlen, "%lu bytes after the last symbol", (unsigned long)left(&c));
    return 0;
}

int rcx_image_read_file(const char *path, u8 **data, size_t *size, char *err, size_t errlen)
{
    FILE *f = fopen(path, "rb");
    u8 *buf = NULL;
    size_t n = 0, cap = 0;

    *data = NULL;
    *size = 0;
    if (!f)
        return fail(err, errlen, "%s: %s", path, strerror(errno));
    for (;;) {
        size_t got;
        if (n == cap) {
            u8 *bigger;
            cap = cap ? cap * 2 : 4096;
            bigger = realloc(buf, cap);
            if (!bigger) {
                free(buf);
                fclose(f);
                return fail(err, errlen, "%s: out of memory", path);
            }
            buf = bigger;
        }
        got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (got == 0)
            break;
    }
    if (ferror(f)) {
        free(buf);
        fclose(f);
        return fail(err, errlen, "%s: read error", path);
    }
    fclose(f);
    *data = buf;
    *size = n;
    return 0;
}

int rcx_image_find_var(const struct rcx_image *img, const char *name)
{
    unsigned i;
    for (i = 0; i < img->symbol_count; i++)
        if (img->symbol[i].type == RCX_SYMBOL_VAR && strcmp(img->symbol[i].name, name) == 0)
            return img->symbol[i].index;
    return -1;
}

/* One direct command that nqc expects a reply of `want` bytes to (host-tools.md §1). */
static int command(struct rcx *b, const u8 *cmd, unsigned len, unsigned want, char *err, size_t errlen)
{
    u8 reply[RCX_REPLY_MAX];
    unsigned got = brick_cmd(b, cmd, len, reply);
    if (got != want)
        return fail(err, errlen, "command %02x: %u reply bytes, nqc expects %u", cmd[0], got, want);
    return 0;
}

static int download(struct rcx *b, const struct rcx_image *img, u8 type, char *err, size_t errlen)
{
    unsigned i;
    for (i = 0; i < img->chunk_count; i++) {
        const struct rcx_chunk *ch = &img->chunk[i];
        int status;
        if (ch->type != type)
            continue;
        status = brick_download(b, type == RCX_CHUNK_TASK, ch->number, ch->code, ch->length);
        if (status)
            return fail(err, errlen, "%s %u (%u bytes): download status %d",
                        type == RCX_CHUNK_TASK ? "task" : "subroutine", ch->number, ch->length, status);
    }
    return 0;
}

int rcx_image_load(struct rcx *b, const struct rcx_image *img, int slot, char *err, size_t errlen)
{
    static const u8 ping[] = { 0x10 }, stop_all[] = { 0x50 }, del_tasks[] = { 0x40 }, del_subs[] = { 0x70 };
    static const u8 sound[] = { 0x51, 0x05 }, battery[] = { 0x30 };
    u8 select[2];

    if (command(b, ping, sizeof ping, 1, err, errlen))
        return -1;
    if (slot >= 0) {
        if (slot >= RCX_PROGRAMS)
            return fail(err, errlen, "program slot %d out of range", slot);
        select[0] = 0x91;
        select[1] = (u8)slot;
        if (command(b, select, sizeof select, 1, err, errlen))
            return -1;
    }
    if (command(b, stop_all, sizeof stop_all, 1, err, errlen) ||
        command(b, del_tasks, sizeof del_tasks, 1, err, errlen) ||
        command(b, del_subs, sizeof del_subs, 1, err, errlen))
        return -1;
    if (download(b, img, RCX_CHUNK_SUB, err, errlen) || download(b, img, RCX_CHUNK_TASK, err, errlen))
        return -1;
    if (command(b, sound, sizeof sound, 1, err, errlen) || command(b, battery, sizeof battery, 3, err, errlen))
        return -1;
    return 0;
}
