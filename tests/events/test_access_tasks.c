/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Access control and monitoring across tasks, with hand-assembled byte-code programs (spec pp. 26, 69, 85, 98,
 * 106-107): a higher priority seizing a motor (the loser takes its handler, its motors brake), equal priorities
 * pre-empting, refusal, user resources and several holders, release on stop, program change, ExitAccessControl and
 * EndOfSub, events reaching waiting tasks and tasks inside subroutines.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdio.h>
#include <cmocka.h>
#include "brick.h"
#include "access.h"

static s16 poll(struct rcx *b, u8 src, u8 index)
{
    u8 c[3] = { 0x12, src, index }, reply[RCX_REPLY_MAX];
    assert_int_equal(brick_cmd(b, c, 3, reply), 3);
    return (s16)(u16)(reply[1] | reply[2] << 8);
}

#define SETP(p) 0xD7, (p)
#define MONAL(res, d) 0x73, (res), (d), 0x00     /* target = pc + 2 + d */
#define MONAX 0xA0
#define MONE(mask, d) 0xB4, 0x02, (u8)(mask), (u8)((mask) >> 8), (d) /* target = pc + 4 + d */
#define MONEX 0xB0
#define SETV(v, k) 0x14, (v), 0x02, (u8)(k), (u8)((k) >> 8)
#define JMP_SELF 0x27, 0x81
#define WAIT(n) 0x43, 0x02, (u8)(n), (u8)((n) >> 8)
#define MOTOR_A_ON 0x21, 0x81
#define STOP_SELF 0x81, 0xFF

static void load(struct rcx *b, int is_task, u8 n, const u8 *code, unsigned len)
{
    assert_int_equal(brick_download(b, is_task, n, code, len), 0);
}

/*
 * Task n: priority `prio`, waits `wait` x 10 ms, takes `res`; inside the region it switches on the motors of
 * `motors` (OnOffFloat list, 0 = none), sets var `in` and spins; its handler sets var `h` and spins.
 */
static void acquirer(struct rcx *b, u8 n, u8 prio, u8 wait, u8 res, u8 motors, u8 in, u8 h)
{
    const u8 code[] = {
        SETP(prio),              /* 0 */
        WAIT(wait),              /* 2 */
        MONAL(res, 11),          /* 6: handler at 6 + 2 + 11 = 19 */
        0x21, (u8)(0x80 | motors), /* 10 */
        SETV(in, 1),             /* 12 */
        JMP_SELF,                /* 17 */
        SETV(h, 1),              /* 19: handler */
        JMP_SELF,                /* 24 */
    };
    load(b, 1, n, code, sizeof code);
}

static u8 motor(struct rcx *b, u8 m)
{
    return (u8)((u8)poll(b, 3, m) & (RCX_MOTOR_ON | RCX_MOTOR_BRAKE));
}

/* Task 1 (priority 5) holds motor A and runs it; task 0 (priority 2) asks for A. Task 1 loses it: motor A brakes
 * (p. 98), task 1 takes its handler and holds nothing, task 0 is granted A and is not sent to its handler. */
static void higher_priority_task_seizes_a_motor(void **state)
{
    struct rcx *b = brick_new();
    (void)state;
    acquirer(b, 1, 5, 0, 0x01, 0x01, 10, 11);
    acquirer(b, 0, 2, 5, 0x01, 0x00, 20, 21);
    brick_start(b, 1);
    brick_start(b, 0);
    brick_run_ms(b, 30, 4);
    assert_int_equal(b->global[10], 1);
    assert_int_equal(b->task[1].ev.rc, 0x01);
    assert_int_equal(motor(b, 0), RCX_MOTOR_ON);
    brick_run_ms(b, 40, 4);
    assert_int_equal(b->global[20], 1);
    assert_int_equal(b->global[21], 0);
    assert_int_equal(b->task[0].ev.rc, 0x01);
    assert_int_equal(b->global[11], 1);
    assert_int_equal(b->task[1].ev.rc, 0);
    assert_int_equal(b->task[1].ev.state, ACCESS_NONE);
    assert_int_equal(motor(b, 0), RCX_MOTOR_BRAKE);
    brick_free(b);
}

/* "Tasks of equal priority can pre-empt each other" (p. 106; reference-firmware.md): the later request wins. */
static void equal_priority_pre_empts(void **state)
{
    struct rcx *b = brick_new();
    (void)state;
    acquirer(b, 1, 4, 0, 0x02, 0, 10, 11);
    acquirer(b, 0, 4, 5, 0x02, 0, 20, 21);
    brick_start(b, 1);
    brick_start(b, 0);
    brick_run_ms(b, 100, 4);
    assert_int_equal(b->global[10], 1);
    assert_int_equal(b->global[11], 1);
    assert_int_equal(b->global[20], 1);
    assert_int_equal(b->global[21], 0);
    assert_int_equal(b->task[0].ev.rc, 0x02);
    assert_int_equal(b->task[1].ev.rc, 0);
    brick_free(b);
}

/* A request against a holder of higher priority fails at once (JUMP LBL); the holder does not notice. */
static void lower_priority_request_is_refused(void **state)
{
    struct rcx *b = brick_new();
    (void)state;
    acquirer(b, 1, 1, 0, 0x08, 0x04, 10, 11);     /* motor C */
    acquirer(b, 0, 7, 5, 0x0C, 0, 20, 21);        /* sound and motor C */
    brick_start(b, 1);
    brick_start(b, 0);
    brick_run_ms(b, 100, 4);
    assert_int_equal(b->global[10], 1);
    assert_int_equal(b->global[11], 0);
    assert_int_equal(b->task[1].ev.rc, 0x08);
    assert_int_equal(motor(b, 2), RCX_MOTOR_ON);
    assert_int_equal(b->global[20], 0);
    assert_int_equal(b->global[21], 1);
    assert_int_equal(b->task[0].ev.rc, 0);
    assert_int_equal(b->task[0].ev.state, ACCESS_NONE);
    brick_free(b);
}

/* The user resources 0x10-0x80 are arbitrated like the others (p. 69); disjoint requests both succeed, and one
 * request may take resources from several holders at once, each getting its AC. A loser gives up everything it
 * held, and all its motors brake. */
static void user_resources_and_several_holders(void **state)
{
    struct rcx *b = brick_new();
    (void)state;
    acquirer(b, 1, 5, 0, 0x13, 0x03, 10, 11);     /* A, B, user 1; runs A and B */
    acquirer(b, 2, 6, 0, 0x80, 0, 12, 13);        /* user 4 */
    acquirer(b, 3, 6, 0, 0x40, 0, 14, 15);        /* user 3: not asked for */
    acquirer(b, 0, 3, 5, 0x90, 0, 20, 21);        /* user 1 and user 4 */
    brick_start(b, 1);
    brick_start(b, 2);
    brick_start(b, 3);
    brick_start(b, 0);
    brick_run_ms(b, 100, 4);
    assert_int_equal(b->global[20], 1);
    assert_int_equal(b->task[0].ev.rc, 0x90);
    assert_int_equal(b->global[11], 1);
    assert_int_equal(b->global[13], 1);
    assert_int_equal(b->global[15], 0);
    assert_int_equal(b->task[1].ev.rc, 0);
    assert_int_equal(b->task[2].ev.rc, 0);
    assert_int_equal(b->task[3].ev.rc, 0x40);
    assert_int_equal(motor(b, 0), RCX_MOTOR_BRAKE);
    assert_int_equal(motor(b, 1), RCX_MOTOR_BRAKE);
    brick_free(b);
}

/* All eight resource bits are defined (p. 69), so no resource operand is out of range; asking for none at all is
 * granted, takes nothing from anybody and leaves a region that holds nothing. */
static void asking_for_no_resources(void **state)
{
    struct rcx *b = brick_new();
    (void)state;
    acquirer(b, 1, 9, 0, 0x01, 0x01, 10, 11);
    acquirer(b, 0, 0, 5, 0x00, 0, 20, 21);
    brick_start(b, 1);
    brick_start(b, 0);
    brick_run_ms(b, 100, 4);
    assert_int_equal(b->global[20], 1);
    assert_int_equal(b->global[21], 0);
    assert_int_equal(b->task[0].ev.state, ACCESS_AC);
    assert_int_equal(b->task[0].ev.rc, 0);
    assert_int_equal(b->global[11], 0);
    assert_int_equal(b->task[1].ev.rc, 0x01);
    assert_int_equal(motor(b, 0), RCX_MOTOR_ON);
    brick_free(b);
}

/* Stopping a holder releases its resources: a lower-priority task then gets them without a fight. */
static void stop_releases(void **state)
{
    static const u8 stop1[] = { 0x81, 1 };
    struct rcx *b = brick_new();
    (void)state;
    acquirer(b, 1, 1, 0, 0x01, 0, 10, 11);
    acquirer(b, 0, 9, 20, 0x01, 0, 20, 21);
    brick_start(b, 1);
    brick_start(b, 0);
    brick_run_ms(b, 50, 4);
    assert_int_equal(b->task[1].ev.rc, 0x01);
    brick_cmd(b, stop1, sizeof stop1, NULL);
    assert_int_equal(b->task[1].ev.rc, 0);
    assert_int_equal(b->task[1].ev.state, ACCESS_NONE);
    brick_run_ms(b, 200, 4);
    assert_int_equal(b->global[20], 1);
    assert_int_equal(b->global[21], 0);
    assert_int_equal(b->global[11], 0);
    brick_free(b);
}

/* Changing the program slot stops every task, which releases everything (p. 107: STOP TASK). */
static void program_change_releases(void **state)
{
    static const u8 select1[] = { 0x91, 1 };
    struct rcx *b = brick_new();
    (void)state;
    acquirer(b, 1, 1, 0, 0xFF, 0, 10, 11);
    brick_start(b, 1);
    brick_run_ms(b, 10, 4);
    assert_int_equal(b->task[1].ev.rc, 0xFF);
    brick_cmd(b, select1, sizeof select1, NULL);
    assert_int_equal(b->task[1].ev.rc, 0);
    assert_int_equal(b->task[1].ev.state, ACCESS_NONE);
    brick_free(b);
}

/* ExitAccessControl ends the region and gives the resources back. */
static void exit_releases(void **state)
{
    static const u8 code[] = {
        MONAL(0x05, 12),         /* 0: handler at 14 */
        SETV(0, 1),              /* 4 */
        WAIT(2),                 /* 9 */
        MONAX,                   /* 13 */
        SETV(1, 1),              /* 14: reached both ways; var 2 tells which */
        JMP_SELF,                /* 19 */
    };
    struct rcx *b = brick_new();
    (void)state;
    load(b, 1, 0, code, sizeof code);
    brick_start(b, 0);
    brick_run_ms(b, 5, 4);
    assert_int_equal(b->task[0].ev.rc, 0x05);
    brick_run_ms(b, 50, 4);
    assert_int_equal(b->global[1], 1);
    assert_int_equal(b->task[0].ev.rc, 0);
    assert_int_equal(b->task[0].ev.state, ACCESS_NONE);
    brick_free(b);
}

/*
 * EndOfSub leaves the regions entered in the subroutine (p. 26, p. 107): resources taken in the subroutine are
 * released and monitoring started there ends. Here the caller monitors, the subroutine takes motor B: after the
 * return the task still monitors (EV->AC x EXIT AC: GO EV) and holds nothing.
 */
static void end_of_sub_releases_its_access_region(void **state)
{
    static const u8 sub[] = {
        MONAL(0x02, 7),          /* 0: label 9 */
        SETV(0, 1),              /* 4 */
        0xF6,                    /* 9: return from inside the region */
    };
    static const u8 task[] = {
        MONE(0x0001, 10),        /* 0: label 14 */
        0x17, 0x00,              /* 5: Gosub 0 */
        SETV(1, 1),              /* 7 */
        JMP_SELF,                /* 12 */
        SETV(2, 1),              /* 14 */
        JMP_SELF,                /* 19 */
    };
    static const u8 event0[] = { 0x03, 2, 0x01, 0x00 };
    struct rcx *b = brick_new();
    (void)state;
    load(b, 0, 0, sub, sizeof sub);
    load(b, 1, 0, task, sizeof task);
    brick_start(b, 0);
    brick_run_ms(b, 10, 4);
    assert_int_equal(b->global[0], 1);
    assert_int_equal(b->global[1], 1);
    assert_int_equal(b->task[0].sub, RCX_NO_SUB);
    assert_int_equal(b->task[0].pc, 12);
    assert_int_equal(b->task[0].ev.state, ACCESS_EV);
    assert_int_equal(b->task[0].ev.rc, 0);
    brick_cmd(b, event0, sizeof event0, NULL);   /* the caller's monitoring is still there */
    assert_int_equal(b->task[0].pc, 14);
    brick_run_ms(b, 2, 4);
    assert_int_equal(b->global[2], 1);
    brick_free(b);
}

/* Both regions entered in the subroutine: after the return the task is in neither. */
static void end_of_sub_leaves_its_monitoring(void **state)
{
    static const u8 sub[] = {
        MONAL(0x02, 13),         /* 0: label 15 */
        MONE(0x0001, 7),         /* 4: label 15 */
        SETV(0, 1),              /* 9 */
        0xF6,                    /* 14: return from inside both regions */
        0xF6,                    /* 15 */
    };
    static const u8 task[] = {
        0x17, 0x00,              /* 0: Gosub 0 */
        SETV(1, 1),              /* 2 */
        JMP_SELF,                /* 7 */
    };
    static const u8 event0[] = { 0x03, 2, 0x01, 0x00 };
    struct rcx *b = brick_new();
    (void)state;
    load(b, 0, 0, sub, sizeof sub);
    load(b, 1, 0, task, sizeof task);
    brick_start(b, 0);
    brick_run_ms(b, 10, 4);
    assert_int_equal(b->global[0], 1);
    assert_int_equal(b->global[1], 1);
    assert_int_equal(b->task[0].ev.state, ACCESS_NONE);
    assert_int_equal(b->task[0].ev.rc, 0);
    brick_cmd(b, event0, sizeof event0, NULL);
    assert_int_equal(b->task[0].sub, RCX_NO_SUB);
    assert_int_equal(b->task[0].pc, 7);
    brick_free(b);
}

/* Monitoring started in a subroutine: the event jumps to the label inside the subroutine, which can still return;
 * a subroutine that returns while monitoring leaves the monitoring behind. */
static void monitoring_inside_a_subroutine(void **state)
{
    static const u8 sub0[] = {
        MONE(0x0001, 3),         /* 0: label 7 */
        JMP_SELF,                /* 5 */
        SETV(3, 1),              /* 7 */
        0xF6,                    /* 12 */
    };
    static const u8 sub1[] = {
        MONE(0x0002, 1),         /* 0: label 5 */
        0xF6,                    /* 5: return while monitoring */
    };
    static const u8 task[] = {
        0x17, 0x00,              /* 0: Gosub 0 */
        SETV(4, 1),              /* 2 */
        0x17, 0x01,              /* 7: Gosub 1 */
        SETV(5, 1),              /* 9 */
        JMP_SELF,                /* 14 */
    };
    static const u8 event0[] = { 0x03, 2, 0x01, 0x00 }, event1[] = { 0x03, 2, 0x02, 0x00 };
    struct rcx *b = brick_new();
    (void)state;
    load(b, 0, 0, sub0, sizeof sub0);
    load(b, 0, 1, sub1, sizeof sub1);
    load(b, 1, 0, task, sizeof task);
    brick_start(b, 0);
    brick_run_ms(b, 5, 4);
    assert_int_equal(b->task[0].sub, 0);
    brick_cmd(b, event0, sizeof event0, NULL);
    assert_int_equal(b->task[0].sub, 0);
    assert_int_equal(b->task[0].pc, 7);
    brick_run_ms(b, 5, 4);
    assert_int_equal(b->global[3], 1);
    assert_int_equal(b->global[4], 1);
    assert_int_equal(b->global[5], 1);
    assert_int_equal(b->task[0].pc, 14);
    assert_int_equal(b->task[0].ev.state, ACCESS_NONE);
    brick_cmd(b, event1, sizeof event1, NULL);
    assert_int_equal(b->task[0].pc, 14);
    brick_free(b);
}

/* A task asleep in Wait inside a monitored region wakes up to take its EV exit, at once. */
static void waiting_task_is_woken_by_its_event(void **state)
{
    static const u8 task[] = {
        MONE(0x0100, 12),        /* 0: label 16 */
        WAIT(1000),              /* 5: ten seconds */
        SETV(0, 1),              /* 9 */
        JMP_SELF,                /* 14 */
        SETV(1, 1),              /* 16 */
        JMP_SELF,                /* 21 */
    };
    static const u8 event8[] = { 0x03, 2, 0x00, 0x01 };
    struct rcx *b = brick_new();
    (void)state;
    load(b, 1, 0, task, sizeof task);
    brick_start(b, 0);
    brick_run_ms(b, 50, 4);
    assert_int_equal(b->task[0].state, RCX_TASK_WAITING);
    brick_cmd(b, event8, sizeof event8, NULL);
    assert_int_equal(b->task[0].state, RCX_TASK_RUNNING);
    assert_int_equal(b->task[0].pc, 16);
    brick_run_ms(b, 2, 4);
    assert_int_equal(b->global[1], 1);
    assert_int_equal(b->global[0], 0);
    assert_int_equal(poll(b, 23, 0), 0x0100);
    brick_free(b);
}

/* An event while the task is in a subroutine called from the monitored region: the task jumps back to the label in
 * its own body. */
static void event_reaches_the_body_from_a_subroutine(void **state)
{
    static const u8 sub[] = { JMP_SELF };
    static const u8 task[] = {
        MONE(0x0004, 3),         /* 0: label 7 */
        0x17, 0x00,              /* 5: Gosub 0, which never returns */
        SETV(1, 1),              /* 7 */
        JMP_SELF,                /* 12 */
    };
    static const u8 event2[] = { 0x03, 2, 0x04, 0x00 };
    struct rcx *b = brick_new();
    (void)state;
    load(b, 0, 0, sub, sizeof sub);
    load(b, 1, 0, task, sizeof task);
    brick_start(b, 0);
    brick_run_ms(b, 5, 4);
    assert_int_equal(b->task[0].sub, 0);
    brick_cmd(b, event2, sizeof event2, NULL);
    assert_int_equal(b->task[0].sub, RCX_NO_SUB);
    assert_int_equal(b->task[0].pc, 7);
    brick_run_ms(b, 2, 4);
    assert_int_equal(b->global[1], 1);
    brick_free(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(higher_priority_task_seizes_a_motor),
        cmocka_unit_test(equal_priority_pre_empts),
        cmocka_unit_test(lower_priority_request_is_refused),
        cmocka_unit_test(user_resources_and_several_holders),
        cmocka_unit_test(asking_for_no_resources),
        cmocka_unit_test(stop_releases),
        cmocka_unit_test(program_change_releases),
        cmocka_unit_test(exit_releases),
        cmocka_unit_test(end_of_sub_releases_its_access_region),
        cmocka_unit_test(end_of_sub_leaves_its_monitoring),
        cmocka_unit_test(monitoring_inside_a_subroutine),
        cmocka_unit_test(waiting_task_is_woken_by_its_event),
        cmocka_unit_test(event_reaches_the_body_from_a_subroutine),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
