/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Scheduling and time: round-robin shares (reference-firmware.md "Tasks and timing"), waiting tasks, the 100 ms
 * timers and their 10 ms view (spec pp. 5, 6, 8; reference-firmware.md), ClearTimer (p. 34), the watch (p. 7, 51).
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include "brick.h"

#define LO(x) ((u8)((unsigned)(x) & 0xFFu))
#define HI(x) ((u8)(((unsigned)(x) >> 8) & 0xFFu))
#define CONST 2
#define INC(v) 0x24, (u8)(v), CONST, 0x01, 0x00
#define WAIT(n) 0x43, CONST, LO(n), HI(n)

static void load(struct rcx *b, u8 n, const u8 *code, unsigned len)
{
    assert_int_equal(brick_download(b, 1, n, code, len), 0);
}

static void ticks(struct rcx *b, unsigned n)
{
    while (n--)
        vm_tick(b);
}

/* Poll (0x12, spec p. 50): the value of a source as a host sees it. */
static s16 poll(struct rcx *b, u8 src, u8 index)
{
    u8 cmd[3] = { 0x12, src, index }, reply[RCX_REPLY_MAX];
    assert_int_equal(brick_cmd(b, cmd, 3, reply), 3);
    return (s16)(u16)(reply[1] | reply[2] << 8);
}

static void set_source(struct rcx *b, u8 src, u8 index, s16 value)
{
    u8 cmd[6] = { 0x05, src, index, CONST, LO(value), HI(value) };
    assert_int_equal(brick_cmd(b, cmd, 6, NULL), 1);
}

/* ------------------------------------------------------------------------------------------------------------ */

/* Task i: SetPriority p_i, then `x_i++` forever (SumVar + SJump: 2 byte codes per round). */
static struct rcx *counting_tasks(unsigned n, const u8 *prio)
{
    struct rcx *b = brick_new();
    unsigned i;
    for (i = 0; i < n; i++) {
        const u8 code[] = { 0xD7, prio[i], INC(i), 0x27, 0x86 }; /* jmp back 6 from the field at 8: to 2 */
        load(b, (u8)i, code, sizeof code);
    }
    for (i = 0; i < n; i++)
        brick_start(b, (u8)i);
    return b;
}

/* "one byte-code per running task per pass, whatever the priorities" (reference-firmware.md). */
static void equal_shares_whatever_priorities(void **state)
{
    static const u8 prio[10] = { 1, 200, 0, 255, 7, 7, 100, 3, 250, 42 };
    unsigned n;
    (void)state;
    for (n = 1; n <= 10; n++) {
        struct rcx *b = counting_tasks(n, prio);
        unsigned i, rounds = 500;
        /* budget: the SetPriority of each task, then `rounds` iterations of 2 byte codes each */
        assert_int_equal(vm_run(b, (u16)(n * (1 + 2 * rounds))), n * (1 + 2 * rounds));
        for (i = 0; i < n; i++) {
            if (b->global[i] != (s16)rounds)
                fail_msg("%u tasks: task %u (priority %u) did %d rounds, expected %u", n, i, prio[i], b->global[i],
                         rounds);
            assert_int_equal(b->task[i].priority, prio[i]);
        }
        brick_free(b);
    }
}

/* The same through simulated time with a budget per millisecond that no task count divides. */
static void shares_stay_equal_over_time(void **state)
{
    static const u8 prio[5] = { 200, 1, 0, 9, 255 };
    struct rcx *b = counting_tasks(5, prio);
    s16 lo = 32767, hi = -32768;
    unsigned i;
    (void)state;
    brick_run_ms(b, 1000, 7);
    for (i = 0; i < 5; i++) {
        if (b->global[i] < lo) lo = b->global[i];
        if (b->global[i] > hi) hi = b->global[i];
    }
    assert_true(hi - lo <= 1);
    assert_in_range(lo, (7000 / 5 - 1) / 2 - 1, 7000 / 5 / 2);
    brick_free(b);
}

/* A waiting task costs nothing: vm_run returns fewer than its budget when every task waits. */
static void waiting_tasks_consume_no_budget(void **state)
{
    static const u8 sleeper[] = { INC(0), WAIT(100), INC(0) };
    static const u8 counter[] = { INC(1), 0x27, 0x86 }; /* 0x86: back to 0 from the field at 6 */
    static const u8 counter2[] = { INC(2), 0x27, 0x86 };
    struct rcx *b = brick_new();
    (void)state;
    assert_int_equal(vm_run(b, 50), 0); /* nothing running at all */
    load(b, 0, sleeper, sizeof sleeper);
    brick_start(b, 0);
    assert_int_equal(vm_run(b, 50), 2); /* SumVar and Wait, then it sleeps */
    assert_int_equal(b->task[0].state, RCX_TASK_WAITING);
    assert_int_equal(vm_run(b, 50), 0);
    ticks(b, 500);
    assert_int_equal(vm_run(b, 50), 0); /* still within its 1 s */

    /* a running task next to the waiting one gets the whole budget */
    load(b, 1, counter, sizeof counter);
    load(b, 2, counter2, sizeof counter2);
    brick_start(b, 1);
    brick_start(b, 2);
    assert_int_equal(vm_run(b, 40), 40);
    assert_int_equal(b->global[1], 10);
    assert_int_equal(b->global[2], 10);
    assert_int_equal(b->global[0], 1);

    ticks(b, 500); /* the wait is over */
    assert_int_equal(vm_run(b, 1000), 1000);
    assert_int_equal(b->global[0], 2);
    assert_int_equal(b->task[0].state, RCX_TASK_IDLE);
    brick_free(b);
}

/* ------------------------------------------------------------------------------------------------------------ */

/* 4 timers, 100 ms resolution, 0-32767 then 0 again (spec p. 5). */
static void timers_count_100ms_and_wrap(void **state)
{
    struct rcx *b = brick_new();
    unsigned i;
    (void)state;
    ticks(b, 99);
    for (i = 0; i < 4; i++)
        assert_int_equal(poll(b, 1, (u8)i), 0);
    ticks(b, 1);
    for (i = 0; i < 4; i++)
        assert_int_equal(poll(b, 1, (u8)i), 1);
    ticks(b, 12345 - 100);
    assert_int_equal(poll(b, 1, 0), 123);

    set_source(b, 1, 3, 32767); /* nqc SetTimer: 05 01 n 02 lo hi */
    assert_int_equal(poll(b, 1, 3), 32767);
    ticks(b, 100);
    assert_int_equal(poll(b, 1, 3), 0);
    assert_int_equal(poll(b, 1, 0), 124);
    brick_free(b);
}

/* Source 26 = 10 x the 100 ms count + the 10 ms steps into the current 100 ms tick (reference-firmware.md). */
static void timer10_view(void **state)
{
    static const unsigned at[] = { 0, 9, 10, 99, 100, 255, 1234, 20000 };
    struct rcx *b = brick_new();
    unsigned i, now = 0;
    (void)state;
    for (i = 0; i < sizeof at / sizeof at[0]; i++) {
        ticks(b, at[i] - now);
        now = at[i];
        assert_int_equal(poll(b, 26, 0), (s16)(now / 100 * 10 + now % 100 / 10));
        assert_int_equal(poll(b, 26, 3), (s16)(now / 100 * 10 + now % 100 / 10));
    }
    brick_free(b);
}

static void cleartimer(void **state)
{
    static const u8 prog[] = { 0xA1, 0x02 }; /* ClearTimer from a program */
    u8 cmd[2] = { 0xA1, 0x00 }, reply[RCX_REPLY_MAX];
    struct rcx *b = brick_new();
    (void)state;
    ticks(b, 350);
    assert_int_equal(brick_cmd(b, cmd, 2, reply), 1);
    assert_int_equal(reply[0], 0xA1 ^ 0xFF); /* 0x5E; spec p. 34 prints 0x56 with bit 3 clear */
    assert_int_equal(poll(b, 1, 0), 0);
    assert_int_equal(poll(b, 1, 1), 3);        /* the others keep counting */
    assert_int_equal(poll(b, 26, 0), 5);       /* "can read up to 10 more" right after a clear */
    ticks(b, 50);
    assert_int_equal(poll(b, 1, 0), 1);        /* the shared 100 ms tick */
    load(b, 0, prog, sizeof prog);
    brick_start(b, 0);
    vm_run(b, 10);
    assert_int_equal(poll(b, 1, 2), 0);
    assert_int_equal(poll(b, 1, 3), 4);
    cmd[1] = 4; /* timers are 0-3: nothing happens */
    assert_int_equal(brick_cmd(b, cmd, 2, NULL), 1);
    assert_int_equal(poll(b, 1, 0), 1);
    assert_int_equal(poll(b, 1, 1), 4);
    assert_int_equal(poll(b, 1, 3), 4);
    brick_free(b);
}

/* "Writing to them also affects source 26 ... and vice-versa" (spec pp. 6, 8). */
static void timers_written_through_1_and_26(void **state)
{
    struct rcx *b = brick_new();
    (void)state;
    ticks(b, 1000);                   /* on a 100 ms boundary: no steps into the current tick */
    set_source(b, 1, 2, 45);
    assert_int_equal(poll(b, 1, 2), 45);
    assert_int_equal(poll(b, 26, 2), 450);
    set_source(b, 26, 1, 1230);
    assert_int_equal(poll(b, 1, 1), 123);
    assert_int_equal(poll(b, 26, 1), 1230);
    set_source(b, 26, 3, 123);
    assert_int_equal(poll(b, 1, 3), 12);
    ticks(b, 30);
    assert_int_equal(poll(b, 26, 2), 453);
    ticks(b, 70);
    assert_int_equal(poll(b, 1, 2), 46);
    assert_int_equal(poll(b, 1, 1), 124);
    assert_int_equal(poll(b, 1, 0), 11);
    brick_free(b);
}

/* Source 14 = hours*60 + minutes, never past 23:59 (spec p. 7); one minute is 60000 ms. */
static void watch_ticks_minutes_and_wraps(void **state)
{
    u8 setw[3] = { 0x22, 23, 59 };
    struct rcx *b = brick_new();
    (void)state;
    ticks(b, 59999);
    assert_int_equal(poll(b, 14, 0), 0);
    ticks(b, 1);
    assert_int_equal(poll(b, 14, 0), 1);
    ticks(b, 60000 * 2);
    assert_int_equal(poll(b, 14, 0), 3);

    ticks(b, 1234); /* any phase within the minute */
    assert_int_equal(brick_cmd(b, setw, 3, NULL), 1);
    assert_int_equal(poll(b, 14, 0), 23 * 60 + 59);
    ticks(b, 60000);
    assert_int_equal(poll(b, 14, 0), 0); /* 24:00 is 00:00 */
    ticks(b, 60000);
    assert_int_equal(poll(b, 14, 0), 1);

    set_source(b, 14, 0, 600); /* the watch is writable (p. 7) */
    assert_int_equal(poll(b, 14, 0), 600);
    setw[1] = 24;
    setw[2] = 0;
    assert_int_equal(brick_cmd(b, setw, 3, NULL), 1);
    assert_in_range(poll(b, 14, 0), 0, 23 * 60 + 59); /* "cannot exceed 23 hrs and 59 min" */
    brick_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(equal_shares_whatever_priorities),
        cmocka_unit_test(shares_stay_equal_over_time),
        cmocka_unit_test(waiting_tasks_consume_no_budget),
        cmocka_unit_test(timers_count_100ms_and_wrap),
        cmocka_unit_test(timer10_view),
        cmocka_unit_test(cleartimer),
        cmocka_unit_test(timers_written_through_1_and_26),
        cmocka_unit_test(watch_ticks_minutes_and_wraps),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
