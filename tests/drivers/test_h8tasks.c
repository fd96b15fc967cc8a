/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Several tasks in the firmware image against the host's machine: the same random and hand-written programs
 * (several tasks, subroutines, jumps in and out of the code, operands out of range, byte codes the brick's fast loop
 * drivers/h8300/runfast.S leaves to the C) downloaded into both, run with the same budgets, and after each vm_run()
 * the variables, every task whole (every field of struct rcx_task), the running tasks and the scheduler's next task
 * compared. The host runs only the C (run_task() and its scheduler); the image runs its assembler loop for one task
 * or several, so a wrong dispatcher shows here.
 *
 * Usage: test_h8tasks <image (COFF; image.srec beside it)> <h8300 nm>
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "rcx.h"
#include "sources.h"
#include "h8image.h"
#include "runfast.h"
#include "fake_hal.h"

#define CMD (H8_SCRATCH)
#define REPLY (H8_SCRATCH + 0x100)

static struct h8 h;
static uint16_t brick;
static struct rcx host;
static struct fake_hal host_hal;
static const char *image_path, *nm_path;

static uint32_t seed;
static unsigned rnd(unsigned n)
{
    seed = seed * 1103515245u + 12345u;
    return (unsigned)(seed >> 16) % n;
}

/* A direct command to both; the replies must agree. */
static uint8_t both(const uint8_t *cmd, unsigned len)
{
    uint8_t reply[RCX_REPLY_MAX];
    uint16_t at = REPLY;
    unsigned n = vm_direct(&host, cmd, (u8)len, reply), m;
    memcpy(h.mem + CMD, cmd, len);
    m = (unsigned)h8_run(&h, "_vm_direct", brick, CMD, (uint16_t)len, &at, 1) & 0xFF;
    assert_int_equal(m, n);
    assert_memory_equal(h.mem + REPLY, reply, n);
    return n > 1 ? reply[1] : 0;
}

static void download(uint8_t begin_op, uint8_t n, const uint8_t *code, unsigned size)
{
    uint8_t begin[6] = { begin_op, 0, n, 0, (uint8_t)size, (uint8_t)(size >> 8) }, block[300];
    unsigned i, sum = 0;
    assert_int_equal(both(begin, sizeof begin), 0);
    block[0] = 0x45;
    block[1] = block[2] = 0;
    block[3] = (uint8_t)size;
    block[4] = (uint8_t)(size >> 8);
    for (i = 0; i < size; i++)
        sum += block[5 + i] = code[i];
    block[5 + size] = (uint8_t)sum;
    assert_int_equal(both(block, 6 + size), 0);
}

static uint16_t img16(uint16_t a) { return (uint16_t)(h.mem[a] << 8 | h.mem[(uint16_t)(a + 1)]); }

/*
 * Every field of a task. The host lays struct rcx_task out as gcc does for the H8/300 (u8 and u16 fields only, each
 * at its natural alignment; the list must cover the struct's every byte, checked in main), but the image's words are
 * big-endian: field by field, element by element.
 */
#define TASK_FIELD(f, width) { offsetof(struct rcx_task, f), sizeof ((struct rcx_task *)0)->f, width, #f }
static const struct { unsigned at, size, width; const char *name; } task_fields[] = {
    TASK_FIELD(state, 1),     TASK_FIELD(sub, 1),       TASK_FIELD(pc, 2),         TASK_FIELD(has_ret, 1),
    TASK_FIELD(ret_sub, 1),   TASK_FIELD(ret_pc, 2),    TASK_FIELD(wake, 2),       TASK_FIELD(priority, 1),
    TASK_FIELD(loop_depth, 1), TASK_FIELD(loop, 1),     TASK_FIELD(local_base, 1), TASK_FIELD(spare, 1),
    TASK_FIELD(ev.events, 2),
    TASK_FIELD(ev.mon, 2),    TASK_FIELD(ev.ev_pc, 2),  TASK_FIELD(ev.ac_pc, 2),   TASK_FIELD(ev.ev_sub, 1),
    TASK_FIELD(ev.ac_sub, 1), TASK_FIELD(ev.rc, 1),     TASK_FIELD(ev.state, 1),
#if RCX_SWAN
    TASK_FIELD(stack, 1),     TASK_FIELD(wait_ms, 1),
#endif
};

/* Variables, whole tasks and the scheduler's position: the same in both. */
static void compare(const char *when)
{
    unsigned i, f, k;
    for (i = 0; i < RCX_ALL_GLOBALS; i++) /* RCX 2.0's globals and the tasks' locals (the image has no Swan) */
        if ((uint16_t)host.global[i] != img16((uint16_t)(brick + RF_GLOBAL + 2 * i)))
            fail_msg("%s: variable %u is %d on the host, %d in the image", when, i, host.global[i],
                     (int16_t)img16((uint16_t)(brick + RF_GLOBAL + 2 * i)));
    for (i = 0; i < RCX_TASKS; i++) {
        const uint8_t *mine = (const uint8_t *)&host.task[i];
        uint16_t t = (uint16_t)(brick + RF_TASK + RF_TASK_SIZE * i);
        for (f = 0; f < sizeof task_fields / sizeof task_fields[0]; f++)
            for (k = task_fields[f].at; k < task_fields[f].at + task_fields[f].size; k += task_fields[f].width) {
                uint16_t want = mine[k], got = h.mem[(uint16_t)(t + k)];
                if (task_fields[f].width == 2) {
                    uint16_t w;
                    memcpy(&w, mine + k, 2);
                    want = w;
                    got = img16((uint16_t)(t + k));
                }
                if (want != got)
                    fail_msg("%s: task %u's %s (byte %u) is %u on the host, %u in the image", when, i,
                             task_fields[f].name, k, want, got);
            }
    }
    assert_int_equal(host.runmask, img16((uint16_t)(brick + RF_RUNMASK)));
    assert_int_equal(host.rr, h.mem[brick + RF_RR]);
#if RCX_SWAN /* laid out as in the image up to rcx.port (u8 and u16 fields): offsetof serves for both */
    assert_int_equal((uint16_t)host.msg_param, img16((uint16_t)(brick + offsetof(struct rcx, msg_param))));
    assert_int_equal(host.message, h.mem[brick + offsetof(struct rcx, message)]);
    assert_int_equal(host.ms_now, img16((uint16_t)(brick + offsetof(struct rcx, ms_now))));
    assert_int_equal(host.timer[0], img16((uint16_t)(brick + offsetof(struct rcx, timer))));
    assert_int_equal(host.swan[host.prog], h.mem[brick + offsetof(struct rcx, swan) + host.prog]);
#endif
}

/* vm_run(budget) in both: the same count, then the same state. */
static void run(uint16_t budget)
{
    unsigned n = vm_run(&host, budget), m = (unsigned)h8_run(&h, "_vm_run", brick, budget, 0, NULL, 0) & 0xFFFF;
    assert_int_equal(m, n);
    compare("after vm_run");
}

static void power_on(void)
{
    assert_int_equal(h8_image_load(&h, image_path, nm_path), 0);
    brick = (uint16_t)h8_sym("_brick");
    h8_run(&h, "_rt_init", brick, brick, 0, NULL, 0);
    memset(&host, 0, sizeof host);
    memset(&host_hal, 0, sizeof host_hal);
    host.port = &host_hal;
    vm_init(&host, brick);
}

/* One byte code of the kinds the fast loop takes, with operands in and out of its range, or another one. */
static unsigned random_code(uint8_t *p)
{
    static const uint8_t ops[] = { RCX_OP_SUM_VAR, RCX_OP_SET_VAR, RCX_OP_SUB_VAR };
    static const uint8_t srcs[] = { RCX_SRC_CONST, RCX_SRC_CONST, RCX_SRC_VAR, RCX_SRC_VAR, 1, 0x0F };
    static const uint8_t edge[] = { 0, 1, 31, 32, 33, 47, 48, 49, 127, 128, 255 }; /* around the limits */
    unsigned k = rnd(20);
    if (k < 10) {
        p[0] = (uint8_t)(ops[rnd(3)] | (rnd(4) ? 0 : RCX_TOGGLE));
        p[1] = (uint8_t)(rnd(3) ? rnd(RCX_VARS) : edge[rnd(sizeof edge)]);
        p[2] = srcs[rnd(sizeof srcs)];
        p[3] = (uint8_t)(p[2] == RCX_SRC_VAR && rnd(3) ? rnd(RCX_GLOBALS) : edge[rnd(sizeof edge)]);
        p[4] = (uint8_t)(rnd(4) ? 0 : rnd(256));
        return 5;
    }
    if (k < 16) {
        p[0] = (uint8_t)(RCX_OP_SJUMP | (rnd(4) ? 0 : RCX_TOGGLE));
        p[1] = (uint8_t)(rnd(2) ? rnd(24) : 0x80 | rnd(rnd(4) ? 24 : 128));
        return 2;
    }
#if RCX_SWAN
    if (k < 16 + 4 && rnd(2)) { /* Swan's global forms the image's loop runs itself (runfast.S), and others */
        static const uint8_t swan[] = { 0x2B, 0x48, 0x49, 0x4F, 0x2C, 0x2D, 0xC8, 0xC9, 0xCA, 0x58 };
        static const uint8_t swan_srcs[] = { RCX_SRC_CONST, 43, 43, RCX_SRC_VAR, 44, 1 };
        p[0] = swan[rnd(sizeof swan)];
        p[1] = (uint8_t)(rnd(3) ? rnd(8) : rnd(256));
        p[2] = (uint8_t)rnd(256);
        p[3] = (uint8_t)rnd(256);
        if (p[0] == 0x2D || p[0] >= 0xC8) {
            p[2] = swan_srcs[rnd(sizeof swan_srcs)];
            p[3] = (uint8_t)(rnd(3) ? rnd(8) : rnd(256));
        }
        return p[0] == 0x2B || (p[0] & 0xF0) == 0x40 ? 3 : 4;
    }
#endif
    if (k < 17) {
        p[0] = RCX_OP_GOSUB;
        p[1] = (uint8_t)rnd(3);
        return 2;
    }
    if (k < 18) {
        p[0] = RCX_OP_END_OF_SUB;
        return 1;
    }
    p[0] = RCX_OP_WAIT; /* Wait 0: a byte code for run_task() that changes nothing */
    p[1] = RCX_SRC_CONST;
    p[2] = p[3] = 0;
    return 4;
}

static unsigned random_object(uint8_t *code, unsigned max)
{
    unsigned size = 0, want = 3 + rnd(max - 8);
    while (size < want)
        size += random_code(code + size);
    return size - rnd(3) * (size > 4); /* sometimes a truncated last byte code */
}

static void random_programs(void **state)
{
    unsigned round, i, step;
    (void)state;
    for (round = 0; round < 60; round++) {
        uint8_t code[80];
        uint8_t select[2] = { RCX_OP_SELECT_PROGRAM, (uint8_t)rnd(RCX_PROGRAMS) };
        seed = round * 7919u + 1;
        power_on();
        both(select, 2);
        for (i = 0; i < 2; i++)
            download(0x35, (uint8_t)i, code, random_object(code, 40));
        for (i = 0; i < RCX_TASKS; i++)
            if (rnd(5))
                download(0x25, (uint8_t)i, code, random_object(code, 70));
        for (i = 0; i < RCX_TASKS; i++) {
            uint8_t start[2] = { RCX_OP_START_TASK, (uint8_t)i };
            both(start, 2);
        }
        compare("started");
        for (step = 0; step < 80; step++) {
            if (!rnd(15)) { /* a task started again, or stopped, between runs */
                uint8_t cmd[2] = { (uint8_t)(rnd(2) ? RCX_OP_START_TASK : RCX_OP_STOP_TASK), (uint8_t)rnd(RCX_TASKS) };
                both(cmd, 2);
            }
            run((uint16_t)(rnd(4) ? 1 + rnd(40) : 1 + rnd(700)));
        }
    }
}

/* The benchmark's tasks (`while (true) x++;`), nine of them with task 0 in a subroutine doing x -= 1 and a local
 * variable, over many rounds: every task gets its byte codes in turn. */
static void busy_tasks_take_turns(void **state)
{
    static const uint8_t busy[] = { 0x24, 0x00, 0x02, 0x01, 0x00, 0x27, 0x86 };
    static const uint8_t sub[] = { 0x34, 0x00, 0x02, 0x01, 0x00, 0x14, 0x21, 0x00, 0x00, 0x00, 0x27, 0x8B };
    static const uint8_t main_task[] = { 0x17, 0x00 };
    unsigned i;
    (void)state;
    power_on();
    download(0x35, 0, sub, sizeof sub);
    download(0x25, 0, main_task, sizeof main_task);
    for (i = 1; i < RCX_TASKS; i++)
        download(0x25, (uint8_t)i, busy, sizeof busy);
    for (i = 0; i < RCX_TASKS; i++) {
        uint8_t start[2] = { RCX_OP_START_TASK, (uint8_t)i };
        both(start, 2);
    }
    for (i = 0; i < 50; i++)
        run((uint16_t)(1 + i * 37 % 300));
    run(0xFFFF);
}

#if RCX_SWAN
#include "rcx_image.h"
static const char *program_dir;

/* A code object of any size, in blocks of 200 bytes as nqc sends them. */
static void download_long(uint8_t begin_op, uint8_t n, const uint8_t *code, unsigned size)
{
    uint8_t begin[6] = { begin_op, 0, n, 0, (uint8_t)size, (uint8_t)(size >> 8) }, block[210];
    unsigned off = 0, seq = 1, i, chunk, sum;
    assert_int_equal(both(begin, sizeof begin), 0);
    do {
        chunk = size - off > 200 ? 200 : size - off;
        block[0] = 0x45;
        block[1] = (uint8_t)(off + chunk >= size ? 0 : seq);
        block[2] = 0;
        block[3] = (uint8_t)chunk;
        block[4] = 0;
        for (i = sum = 0; i < chunk; i++)
            sum += block[5 + i] = code[off + i];
        block[5 + chunk] = (uint8_t)sum;
        assert_int_equal(both(block, 6 + chunk), 0);
        off += chunk;
        seq++;
    } while (off < size);
}

/* The Swan programs of tests/programs (nqc -TSwan) in both, started as nqc -run does, with milliseconds passing
 * (WaitMS, MSTimer, the 10 ms waits) and budgets of every size: the same variables, tasks and Swan state. */
static void swan_programs(void **state)
{
    static const char *const names[] = { "swan_globals", "swan_math", "swan_time", "swan_tasks" };
    unsigned p, c, ms;
    (void)state;
    for (p = 0; p < sizeof names / sizeof names[0]; p++) {
        char path[1024], err[160];
        u8 *data;
        size_t size;
        struct rcx_image img;
        uint8_t start[2] = { RCX_OP_START_TASK, 0 };
        snprintf(path, sizeof path, "%s/%s.swan.rcx", program_dir, names[p]);
        if (rcx_image_read_file(path, &data, &size, err, sizeof err) || rcx_image_parse(&img, data, size, err, sizeof err))
            fail_msg("%s", err);
        power_on();
        seed = p * 31u + 7u;
        for (c = 0; c < img.chunk_count; c++)
            download_long(img.chunk[c].type == RCX_CHUNK_TASK ? 0x25 : 0x35, img.chunk[c].number, img.chunk[c].code,
                          img.chunk[c].length);
        both(start, 2);
        compare("started");
        for (ms = 0; ms < 1200; ms++) {
            run((uint16_t)(rnd(8) ? 1 + rnd(12) : 1 + rnd(300)));
            vm_tick(&host);
            h8_run(&h, "_vm_tick", brick, 0, 0, NULL, 0);
            if (ms % 50 == 0)
                compare("a millisecond on");
        }
        compare("the end");
        assert_int_equal(host.swan[0], 1);
        free(data);
    }
}
#endif

int main(int argc, char **argv)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(busy_tasks_take_turns),
        cmocka_unit_test(random_programs),
#if RCX_SWAN
        cmocka_unit_test(swan_programs),
#endif
    };
    if (argc != 3 + RCX_SWAN) {
        fprintf(stderr, "usage: %s <firmware image> <h8300 nm>%s\n", argv[0], RCX_SWAN ? " <Swan program images>" : "");
        return 2;
    }
#if RCX_SWAN
    program_dir = argv[3];
#endif
    {
        unsigned f, covered = 0;
        for (f = 0; f < sizeof task_fields / sizeof task_fields[0]; f++)
            covered += task_fields[f].size;
        if (covered != sizeof(struct rcx_task) || sizeof(struct rcx_task) != RF_TASK_SIZE) {
            fprintf(stderr, "test_h8tasks: task_fields covers %u of %u bytes of struct rcx_task (image: %u)\n",
                    covered, (unsigned)sizeof(struct rcx_task), RF_TASK_SIZE);
            return 1;
        }
    }
    image_path = argv[1];
    nm_path = argv[2];
    return cmocka_run_group_tests(tests, NULL, NULL);
}
