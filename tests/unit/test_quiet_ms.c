/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Quiet milliseconds (src/runtime.h): a brick whose port sleeps through the milliseconds rt_quiet() allows and
 * counts them with rt_skip() must be, every time it has caught up, byte for byte the brick that ran rt_tick() and
 * rt_run() every millisecond - machine, IR layer, user interface and everything told to the hardware - through
 * sound, reversing pauses, waiting tasks, IR packets, buttons and the minutes of the watch and the power-down timer.
 * The one difference allowed is the documented one: a switch-off asked for while skipping comes at most 9 ms late.
 * The brick here skips as the port's idle sleep does, while no task runs.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>
#include "brick.h"
#include "fake_hal.h"
#include "runtime.h"

#define LO(x) ((u8)((unsigned)(x) & 0xFFu))
#define HI(x) ((u8)(((unsigned)(x) >> 8) & 0xFFu))
#define CONST 2

struct side {
    struct rcx_brick *k;
    struct fake_hal *h;
};

/* `every` ticks every millisecond; `sleeper` skips what rt_quiet() allows, `pending` milliseconds behind. */
struct pair {
    struct side every, sleeper;
    u8 quiet, pending;
    unsigned skipped, now;
};

static void side_new(struct side *s)
{
    s->k = calloc(1, sizeof *s->k);
    s->h = calloc(1, sizeof *s->h);
    assert_non_null(s->k);
    assert_non_null(s->h);
    s->k->vm.port = s->h;
    rt_init(s->k, TEST_ARENA_ADDR);
}

static void side_free(struct side *s)
{
    free(s->h);
    free(s->k);
}

static struct pair *pair_new(void)
{
    struct pair *p = calloc(1, sizeof *p);
    assert_non_null(p);
    side_new(&p->every);
    side_new(&p->sleeper);
    return p;
}

static void pair_free(struct pair *p)
{
    side_free(&p->every);
    side_free(&p->sleeper);
    free(p);
}

static void same(const struct pair *p)
{
    const struct rcx_brick *a = p->every.k, *b = p->sleeper.k;
    assert_memory_equal(&a->vm, &b->vm, offsetof(struct rcx, port));
    assert_memory_equal(a->vm.arena, b->vm.arena, sizeof a->vm.arena);
    assert_memory_equal(&a->ir, &b->ir, offsetof(struct rcx_ir, tx_src)); /* then a pointer into each brick */
    assert_int_equal(a->ir.tx_src ? a->ir.tx_src - (const u8 *)a : -1, b->ir.tx_src ? b->ir.tx_src - (const u8 *)b : -1);
    assert_memory_equal(&a->ir.tx_src_len, &b->ir.tx_src_len, sizeof a->ir - offsetof(struct rcx_ir, tx_src_len));
    assert_memory_equal(&a->ui, &b->ui, sizeof a->ui);
    assert_memory_equal(p->every.h, p->sleeper.h, sizeof *p->every.h);
}

/* The sleeper catches up: all pending milliseconds but the last counted at once, the last ticked. */
static void catch_up(struct pair *p)
{
    struct rcx_brick *k = p->sleeper.k;
    u8 n = p->pending;

    if (!n)
        return;
    if (--n > p->quiet)
        n = p->quiet;
    rt_skip(k, n);
    p->skipped += n;
    for (n = (u8)(p->pending - n); n; n--)
        rt_tick(k);
    p->pending = 0;
}

/* The sleeper's main-loop pass; the other's rt_run() too when something came in (else it had its own already). */
static void main_loop(struct pair *p, int both)
{
    if (both)
        rt_run(p->every.k, 50);
    catch_up(p);
    rt_run(p->sleeper.k, 50);
    /* The port's idle sleep: it skips only while no task runs. With tasks running it lets them run on through the
     * quiet milliseconds instead (drivers/h8300/main.c), which the image's own tests check (test_h8machine.c). */
    p->quiet = p->sleeper.k->vm.runmask ? 0 : rt_quiet(p->sleeper.k);
    same(p);
}

/* `ms` milliseconds with nothing coming in. */
static void pass(struct pair *p, unsigned ms)
{
    while (ms--) {
        p->now++;
        rt_tick(p->every.k);
        rt_run(p->every.k, 50);
        if (++p->pending > p->quiet)
            main_loop(p, 0);
    }
}

/* Something comes in: the sleeper wakes and catches up first, as the port's main loop does. */
static void direct(struct pair *p, const u8 *cmd, unsigned len)
{
    catch_up(p);
    assert_int_equal(brick_cmd(&p->every.k->vm, cmd, len, NULL), brick_cmd(&p->sleeper.k->vm, cmd, len, NULL));
    main_loop(p, 1);
}

static void ir_byte(struct pair *p, u8 byte)
{
    catch_up(p);
    rt_ir_byte(p->every.k, byte, 0);
    rt_ir_byte(p->sleeper.k, byte, 0);
    main_loop(p, 1);
}

static void button(struct pair *p, u8 which, u8 down)
{
    catch_up(p);
    rt_button(p->every.k, which, down);
    rt_button(p->sleeper.k, which, down);
    main_loop(p, 1);
}

/* An idle brick sleeps through nearly all of its milliseconds, and the two minutes take it over both the watch's
 * and the power-down timer's minute (the default power-down time is 15 minutes), each set going in the middle of
 * a 10 ms step, so that a skip may count past the minute's end. */
static void an_idle_brick_skips_and_stays_the_same(void **state)
{
    struct pair *p = pair_new();
    (void)state;
    main_loop(p, 1);
    pass(p, 1003);
    direct(p, (const u8[]){ 0x22, 0x07, 0x3B }, 3);             /* SetWatch 7:59 */
    pass(p, 4);
    direct(p, (const u8[]){ 0x10 }, 1);                         /* PBAliveOrNot: the power-down timer again */
    pass(p, 125000);
    assert_int_equal(p->sleeper.k->vm.watch, 8 * 60 + 1);
    assert_int_equal(p->sleeper.k->ui.idle_min, 2);
    assert_true(p->skipped > 125000 * 7 / 10);
    pair_free(p);
}

static void sound_pauses_tasks_and_packets(void **state)
{
    static const u8 task[] = { 0x24, 0x00, CONST, 0x01, 0x00,   /* var 0 += 1 */
                               0x43, CONST, 37, 0x00,           /* Wait 370 ms */
                               0x27, 0x8A };                    /* back to the start */
    static const u8 busy[] = { 0x24, 0x01, CONST, 0x01, 0x00, 0x27, 0x86 }; /* var 1 += 1 for ever */
    static const u8 ping[] = { 0x55, 0xFF, 0x00, 0x10, 0xEF, 0x10, 0xEF };
    struct pair *p = pair_new();
    unsigned i;
    (void)state;
    main_loop(p, 1);
    pass(p, 1234);
    direct(p, (const u8[]){ 0x51, 0x03 }, 2);                   /* PlaySystemSound: a note queue */
    pass(p, 2000);
    direct(p, (const u8[]){ 0xE1, 0x81 }, 2);                   /* A forward */
    direct(p, (const u8[]){ 0x21, 0x81 }, 2);                   /* A on */
    pass(p, 7);
    direct(p, (const u8[]){ 0xE1, 0x41 }, 2);                   /* A reversed: a pause */
    pass(p, 500);
    direct(p, (const u8[]){ 0x21, 0x41 }, 2);                   /* A off */
    assert_int_equal(brick_download(&p->every.k->vm, 1, 0, task, sizeof task), 0);
    assert_int_equal(brick_download(&p->sleeper.k->vm, 1, 0, task, sizeof task), 0);
    pass(p, 3);
    direct(p, (const u8[]){ 0x71, 0x00 }, 2);                   /* StartTask 0: it waits most of the time */
    pass(p, 5003);
    assert_true(p->every.k->vm.global[0] >= 13);
    direct(p, (const u8[]){ 0x81, 0x00 }, 2);                   /* StopTask 0 */
    assert_int_equal(brick_download(&p->every.k->vm, 1, 1, busy, sizeof busy), 0);
    assert_int_equal(brick_download(&p->sleeper.k->vm, 1, 1, busy, sizeof busy), 0);
    direct(p, (const u8[]){ 0x71, 0x01 }, 2);                   /* StartTask 1: busy, never skipped */
    pass(p, 345);
    direct(p, (const u8[]){ 0x81, 0x01 }, 2);
    assert_true(p->every.k->vm.global[1] > 345);
    pass(p, 777);
    for (i = 0; i < sizeof ping; i++) {                         /* a ping from the room, no echo of the reply */
        ir_byte(p, ping[i]);
        pass(p, 4);
    }
    pass(p, 1000);
    assert_true(p->every.h->ir_len >= 7);
    button(p, RT_BUTTON_VIEW, 1);
    pass(p, 100);
    button(p, RT_BUTTON_VIEW, 0);
    pass(p, 3000);
    assert_true(p->skipped > 5000);
    pair_free(p);
}

/* Switching off by the power-down timer: the sleeper goes when the timer's minute is seen, at most 9 ms later. */
static void the_power_down_comes_at_most_9_ms_late(void **state)
{
    struct pair *p = pair_new();
    unsigned off_every = 0, off_sleeper = 0;
    (void)state;
    direct(p, (const u8[]){ 0xB1, 0x01 }, 2);                   /* PBPowerDownTime 1 minute */
    while (p->now < 62000 && !off_sleeper) {
        p->now++;
        rt_tick(p->every.k);
        rt_run(p->every.k, 50);
        if (!off_every && p->every.h->power_offs)
            off_every = p->now;
        if (++p->pending > p->quiet) {
            catch_up(p);
            rt_run(p->sleeper.k, 50);
            p->quiet = p->sleeper.k->vm.runmask ? 0 : rt_quiet(p->sleeper.k);
            if (p->sleeper.h->power_offs)
                off_sleeper = p->now;
        }
    }
    assert_true(off_every > 60000);
    assert_true(off_sleeper >= off_every && off_sleeper <= off_every + 9);
    pair_free(p);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(an_idle_brick_skips_and_stays_the_same),
        cmocka_unit_test(sound_pauses_tasks_and_packets),
        cmocka_unit_test(the_power_down_comes_at_most_9_ms_late),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
