/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The datalog (spec pp. 54-55, 84): entries of 3 bytes at the end of program memory. Entry 0 is the log's own
 * header, type 0xFF, value = entries used including itself; data points follow from entry 1.
 */
#include "rcx_string.h"
#include "rcx.h"

#define LOG_ADDR(b) ((b)->arena + (b)->obj_start[RCX_OBJS])

static void put_entry(u8 *e, u8 type, u16 value)
{
    e[0] = type;
    e[1] = (u8)value;
    e[2] = (u8)(value >> 8);
}

void datalog_set(struct rcx *b, u16 entries)
{
    b->log_size = 0;
    b->log_count = 0;
    /* The spec allocates one extra element for the count: (entries + 1) x 3 bytes must fit. */
    if (entries >= mem_free(b) / 3u)
        return; /* no room: no datalog, nothing else disturbed */
    b->log_size = (u16)(entries + 1);
    b->log_count = 1;
    put_entry(LOG_ADDR(b), 0xFF, 1);
}

/* Entry type: source kind in bits 5-7 (0 variable, 1 timer, 2 sensor value, 4 watch), index in bits 0-4; 0xFF for
 * the sources that cannot be logged. */
static const u8 entry_kind[15] = { 0x00, 0x20, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0x40, 0xFF, 0xFF, 0xFF, 0xFF,
                                   0x80 };

void datalog_add(struct rcx *b, const struct rcx_task *t, u8 src, u8 index)
{
    u8 kind, *log;
    s16 value;

    /* Task locals (index >= 32) cannot be logged: their number does not fit the 5-bit index (spec p. 55). */
    if (src >= sizeof entry_kind || (kind = entry_kind[src]) == 0xFF || index >= 32 || b->log_count >= b->log_size)
        return;
    kind |= index;                    /* (the entry type now: one byte kept across the call) */
    value = source_get(b, t, src, index);
    log = LOG_ADDR(b);
    put_entry(log + b->log_count * 3u, kind, (u16)value);
    put_entry(log, 0xFF, ++b->log_count);
}

s16 datalog_upload(const struct rcx *b, u16 start, u16 count, u8 *out)
{
    /* Without a log, entry 0 still reports an empty one (and is the only entry there is to read). */
    static const u8 empty[3] = { 0xFF, 1, 0 };
    const u8 *log = empty;
    u16 used = 1;

    if (b->log_count) {
        used = b->log_count;
        log = LOG_ADDR(b);
    }
    if (count > (RCX_REPLY_MAX - 1) / 3 || start > used || count > used - start)
        return -1;
    count = (u16)(count * 3u);         /* in bytes */
    memcpy(out, log + start * 3u, count);
    return (s16)count;
}
