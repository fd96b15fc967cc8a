/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The panel's view of a brick: copied from the simulation (simulation thread only) and written as the JSON of
 * GET /state and of each Server-Sent Event, in the --trace vocabulary (motor directions, "lcd" as 9 hex bytes, "num"
 * and "prog" as the glass shows them, "sound" in Hz with 0 for silence).
 */
#include <stdarg.h>
#include <string.h>
#include "panel.h"
#include "hal.h"

void panel_snapshot(const struct sim_brick *b, struct panel_brick *out)
{
    const struct rcx *vm = &b->k.vm;
    int i;

    memset(out, 0, sizeof *out); /* padding too: snapshots are compared with memcmp */
    out->mode = (unsigned char)b->mode;
    out->buttons = b->buttons;
    out->battery_mv = b->battery_mv;
    out->range = b->range;
    out->ir_in = b->ir_in;
    out->ir_out = b->ir_out;
    for (i = 0; i < 3; i++) {
        /* 0xFF: hal_motor() not called yet since power-on, the outputs float */
        out->motor[i] = b->motor[i] == 0xFF ? HAL_MOTOR_FLOAT << 3 : b->motor[i];
        out->raw[i] = b->raw[i];
    }
    if (b->mode == SIM_ROM)
        return; /* no firmware: nothing of the machine is meaningful */
    out->sound_hz = b->sound_hz;
    out->slot = (unsigned char)(vm->prog + 1);
    for (i = 0; i < RCX_TASKS; i++)
        if (vm->task[i].state != RCX_TASK_IDLE)
            out->tasks |= (unsigned short)(1u << i);
    for (i = 0; i < 3; i++) {
        out->sensor_type[i] = vm->sensor[i].type;
        out->sensor_mode[i] = vm->sensor[i].mode;
        out->sensor_value[i] = vm->sensor[i].value;
        out->sensor_bool[i] = vm->sensor[i].boolean;
        out->sensor_power[i] = b->sensor_power[i];
    }
    if (b->mode == SIM_FIRMWARE && b->lcd_known)
        memcpy(out->lcd, b->lcd, sizeof out->lcd);
}

/* Appends to a bounded buffer; `*len` goes past `size` once something did not fit, and stays there. */
static void put(char *buf, size_t size, size_t *len, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
static void put(char *buf, size_t size, size_t *len, const char *fmt, ...)
{
    va_list ap;
    int n;

    if (*len >= size)
        return;
    va_start(ap, fmt);
    n = vsnprintf(buf + *len, size - *len, fmt, ap);
    va_end(ap);
    *len = n < 0 ? size : *len + (size_t)n;
}

static const char *bool_word(unsigned v)
{
    return v ? "true" : "false";
}

static void brick_json(char *buf, size_t size, size_t *len, const struct panel_brick *p, int index)
{
    static const char *const power[] = { "on", "rom", "standby" }; /* by enum sim_mode */
    static const char *const types[] = { "none", "touch", "temperature", "light", "rotation" };
    static const char *const modes[] = { "raw", "bool", "edge", "pulse", "percent", "celsius", "fahrenheit", "angle" };
    char num[16], prog[2];
    int i;

    trace_lcd_number(p->lcd, num, prog);
    put(buf, size, len, "{\"brick\":%d,\"power\":\"%s\",\"motors\":{", index, power[p->mode]);
    for (i = 0; i < 3; i++)
        put(buf, size, len, "%s\"%c\":{\"dir\":\"%s\",\"level\":%u}", i ? "," : "", 'A' + i,
            sim_motor_dirs[p->motor[i] >> 3 & 3], p->motor[i] & 7u);
    put(buf, size, len, "},\"lcd\":\"");
    for (i = 0; i < 9; i++)
        put(buf, size, len, "%02x", p->lcd[i]);
    put(buf, size, len, "\",\"num\":\"%s\",\"prog\":\"%s\",\"sound\":%u,\"sensors\":[", num, prog, p->sound_hz);
    for (i = 0; i < 3; i++)
        put(buf, size, len,
            "%s{\"input\":%d,\"raw\":%u,\"type\":\"%s\",\"mode\":\"%s\",\"slope\":%u,\"value\":%d,\"bool\":%u,"
            "\"power\":%s}",
            i ? "," : "", i + 1, p->raw[i], p->sensor_type[i] < 5 ? types[p->sensor_type[i]] : "?",
            modes[p->sensor_mode[i] >> 5], p->sensor_mode[i] & SENSOR_SLOPE, p->sensor_value[i], p->sensor_bool[i],
            bool_word(p->sensor_power[i]));
    put(buf, size, len, "],\"buttons\":{");
    for (i = 0; i < SIM_BUTTONS; i++)
        put(buf, size, len, "%s\"%s\":%s", i ? "," : "", sim_button_names[i], bool_word(p->buttons >> i & 1u));
    put(buf, size, len, "},\"battery\":%u,\"slot\":%u,\"tasks\":[", p->battery_mv, p->slot);
    for (i = 0; i < RCX_TASKS; i++)
        if (p->tasks >> i & 1u)
            put(buf, size, len, "%s%d", p->tasks & ((1u << i) - 1) ? "," : "", i);
    put(buf, size, len, "],\"ir\":{\"in\":%lu,\"out\":%lu,\"range\":\"%s\"}}", p->ir_in, p->ir_out,
        p->range == 1 ? "far" : "near");
}

size_t panel_json(char *buf, size_t size, unsigned long long t_ms, const struct panel_brick *bricks, int n,
                  int world)
{
    size_t len = 0;
    int i;

    put(buf, size, &len, "{\"t\":%llu,\"world\":%s,\"bricks\":[", t_ms, bool_word((unsigned)world));
    for (i = 0; i < n; i++) {
        if (i)
            put(buf, size, &len, ",");
        brick_json(buf, size, &len, &bricks[i], i);
    }
    put(buf, size, &len, "]}");
    return len < size ? len : 0;
}
