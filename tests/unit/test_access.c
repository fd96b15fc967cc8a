/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The access-control & event-monitoring state machine (spec p. 107), cell by cell. Multi-task scenarios (priorities,
 * equal priority pre-empting, revoked motors braking, release on stop, EndOfSub, program change) are in
 * tests/events/test_access_tasks.c.
 *
 * The cell table below is this test's own restatement of the spec table: for every state x input (and each branch
 * of IF MON<>0 / IF OK) it spells out what the spec's actions leave behind - the state, the jump taken, the
 * resources and labels held - with each SEND followed through to the cell it reaches. It does not read the
 * implementation's table. Where the spec's cell is silent (EXIT AC without RELEASE RC) the reading is marked
 * (implied); vm/access.c gives the reason.
 */
#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <cmocka.h>
#include "brick.h"
#include "access.h"

#define S_TASK 0        /* the task whose machine is tested */
#define O_TASK 1        /* another task that takes or holds resources */
#define PRIO 5          /* priority of S_TASK */

/* Set-up values: events monitored, labels, resources; and the operands of the input under test. */
#define MON0 0x0003u
#define EVL 0x0010u
#define ACL 0x0020u
#define RC0 0x01u       /* motor A */
#define MON1 0x0030u
#define LBL 0x0040u     /* label of the ENTER EV / ENTER AC under test */
#define RES1 0x02u      /* motor B */
#define PC0 0x0005u     /* where the task is when the input arrives */

enum input {
    IN_EV, IN_AC, IN_EXIT_EV, IN_EXIT_AC, IN_ENTER_EV_MON, IN_ENTER_EV_0, IN_ENTER_AC_OK, IN_ENTER_AC_REFUSED,
    IN_START, IN_STOP, IN_DELETE
};
enum jump { NO_JUMP, TO_EVL, TO_ACL, TO_LBL, ANY_PC };
enum keep { KEEP, NEW };        /* a label as set up, or as the input's LBL (EV=LBL / AC=LBL) */
enum rc { RC_SETUP, RC_NONE, RC_RES };

struct cell {
    const char *name;
    u8 state;           /* before */
    u8 input;
    u8 state_after;
    u8 jump;
    u8 rc;
    u8 ev_label;
    u8 ac_label;
    u8 revoked;         /* O took RC0 from S: S's motor A must brake */
};

#define NONE ACCESS_NONE
#define EV ACCESS_EV
#define AC ACCESS_AC
#define EV_AC ACCESS_EV_AC
#define AC_EV ACCESS_AC_EV

static const struct cell cells[] = {
    /* Row NONE. Empty cells: nothing happens. */
    { "NONE x EV: -", NONE, IN_EV, NONE, NO_JUMP, RC_NONE, KEEP, KEEP, 0 },
    { "NONE x AC: -", NONE, IN_AC, NONE, NO_JUMP, RC_NONE, KEEP, KEEP, 0 },
    { "NONE x EXIT EV: -", NONE, IN_EXIT_EV, NONE, NO_JUMP, RC_NONE, KEEP, KEEP, 0 },
    { "NONE x EXIT AC: -", NONE, IN_EXIT_AC, NONE, NO_JUMP, RC_NONE, KEEP, KEEP, 0 },
    { "NONE x ENTER EV, MON<>0: EV=LBL, GO EV", NONE, IN_ENTER_EV_MON, EV, NO_JUMP, RC_NONE, NEW, KEEP, 0 },
    { "NONE x ENTER EV, MON=0: SEND EXIT EV (-)", NONE, IN_ENTER_EV_0, NONE, NO_JUMP, RC_NONE, KEEP, KEEP, 0 },
    { "NONE x ENTER AC, OK: AC=LBL, RC=RES, GO AC", NONE, IN_ENTER_AC_OK, AC, NO_JUMP, RC_RES, KEEP, NEW, 0 },
    { "NONE x ENTER AC, not OK: JUMP LBL", NONE, IN_ENTER_AC_REFUSED, NONE, TO_LBL, RC_NONE, KEEP, KEEP, 0 },
    { "NONE x START TASK: -", NONE, IN_START, NONE, ANY_PC, RC_NONE, KEEP, KEEP, 0 },
    { "NONE x STOP TASK: -", NONE, IN_STOP, NONE, ANY_PC, RC_NONE, KEEP, KEEP, 0 },
    { "NONE x DELETE TASK: -", NONE, IN_DELETE, NONE, ANY_PC, RC_NONE, KEEP, KEEP, 0 },

    /* Row EV. */
    { "EV x EV: JUMP EV, GO NONE", EV, IN_EV, NONE, TO_EVL, RC_NONE, KEEP, KEEP, 0 },
    { "EV x AC: -", EV, IN_AC, EV, NO_JUMP, RC_NONE, KEEP, KEEP, 0 },
    { "EV x EXIT EV: GO NONE", EV, IN_EXIT_EV, NONE, NO_JUMP, RC_NONE, KEEP, KEEP, 0 },
    { "EV x EXIT AC: -", EV, IN_EXIT_AC, EV, NO_JUMP, RC_NONE, KEEP, KEEP, 0 },
    { "EV x ENTER EV, MON<>0: EV=LBL, GO EV (NEW)", EV, IN_ENTER_EV_MON, EV, NO_JUMP, RC_NONE, NEW, KEEP, 0 },
    { "EV x ENTER EV, MON=0: SEND EXIT EV (GO NONE)", EV, IN_ENTER_EV_0, NONE, NO_JUMP, RC_NONE, KEEP, KEEP, 0 },
    { "EV x ENTER AC, OK: AC=LBL, RC=RES, GO EV->AC", EV, IN_ENTER_AC_OK, EV_AC, NO_JUMP, RC_RES, KEEP, NEW, 0 },
    { "EV x ENTER AC, not OK: JUMP LBL", EV, IN_ENTER_AC_REFUSED, EV, TO_LBL, RC_NONE, KEEP, KEEP, 0 },
    { "EV x START TASK: GO NONE", EV, IN_START, NONE, ANY_PC, RC_NONE, KEEP, KEEP, 0 },
    { "EV x STOP TASK: GO NONE", EV, IN_STOP, NONE, ANY_PC, RC_NONE, KEEP, KEEP, 0 },
    { "EV x DELETE TASK: GO NONE", EV, IN_DELETE, NONE, ANY_PC, RC_NONE, KEEP, KEEP, 0 },

    /* Row AC. */
    { "AC x EV: -", AC, IN_EV, AC, NO_JUMP, RC_SETUP, KEEP, KEEP, 0 },
    { "AC x AC: RELEASE RC, JUMP AC, GO NONE", AC, IN_AC, NONE, TO_ACL, RC_NONE, KEEP, KEEP, 1 },
    { "AC x EXIT EV: -", AC, IN_EXIT_EV, AC, NO_JUMP, RC_SETUP, KEEP, KEEP, 0 },
    { "AC x EXIT AC: GO NONE (RELEASE RC implied)", AC, IN_EXIT_AC, NONE, NO_JUMP, RC_NONE, KEEP, KEEP, 0 },
    { "AC x ENTER EV, MON<>0: EV=LBL, GO AC->EV", AC, IN_ENTER_EV_MON, AC_EV, NO_JUMP, RC_SETUP, NEW, KEEP, 0 },
    { "AC x ENTER EV, MON=0: SEND EXIT EV (-)", AC, IN_ENTER_EV_0, AC, NO_JUMP, RC_SETUP, KEEP, KEEP, 0 },
    { "AC x ENTER AC, OK: AC=LBL, RC=RES, GO AC (NEW)", AC, IN_ENTER_AC_OK, AC, NO_JUMP, RC_RES, KEEP, NEW, 0 },
    /* SEND AC after AC=LBL reaches AC x AC: RELEASE RC, JUMP AC (now LBL), GO NONE. */
    { "AC x ENTER AC, not OK: AC=LBL, SEND AC", AC, IN_ENTER_AC_REFUSED, NONE, TO_LBL, RC_NONE, KEEP, NEW, 0 },
    { "AC x START TASK: RELEASE RC, GO NONE", AC, IN_START, NONE, ANY_PC, RC_NONE, KEEP, KEEP, 0 },
    { "AC x STOP TASK: RELEASE RC, GO NONE", AC, IN_STOP, NONE, ANY_PC, RC_NONE, KEEP, KEEP, 0 },
    { "AC x DELETE TASK: RELEASE RC, GO NONE", AC, IN_DELETE, NONE, ANY_PC, RC_NONE, KEEP, KEEP, 0 },

    /* Row EV->AC. */
    { "EV->AC x EV: RELEASE RC, JUMP EV, GO NONE", EV_AC, IN_EV, NONE, TO_EVL, RC_NONE, KEEP, KEEP, 0 },
    { "EV->AC x AC: RELEASE RC, JUMP AC, GO EV", EV_AC, IN_AC, EV, TO_ACL, RC_NONE, KEEP, KEEP, 1 },
    { "EV->AC x EXIT EV: RELEASE RC, GO NONE", EV_AC, IN_EXIT_EV, NONE, NO_JUMP, RC_NONE, KEEP, KEEP, 0 },
    { "EV->AC x EXIT AC: GO EV (RELEASE RC implied)", EV_AC, IN_EXIT_AC, EV, NO_JUMP, RC_NONE, KEEP, KEEP, 0 },
    { "EV->AC x ENTER EV, MON<>0: EV=LBL, GO AC->EV (ALERT)", EV_AC, IN_ENTER_EV_MON, AC_EV, NO_JUMP, RC_SETUP, NEW,
      KEEP, 0 },
    /* SEND EXIT EV reaches EV->AC x EXIT EV: RELEASE RC, GO NONE. */
    { "EV->AC x ENTER EV, MON=0: SEND EXIT EV", EV_AC, IN_ENTER_EV_0, NONE, NO_JUMP, RC_NONE, KEEP, KEEP, 0 },
    { "EV->AC x ENTER AC, OK: AC=LBL, RC=RES, GO EV->AC (NEW)", EV_AC, IN_ENTER_AC_OK, EV_AC, NO_JUMP, RC_RES, KEEP,
      NEW, 0 },
    /* SEND AC after AC=LBL reaches EV->AC x AC: RELEASE RC, JUMP AC (now LBL), GO EV. */
    { "EV->AC x ENTER AC, not OK: AC=LBL, SEND AC", EV_AC, IN_ENTER_AC_REFUSED, EV, TO_LBL, RC_NONE, KEEP, NEW, 0 },
    { "EV->AC x START TASK: RELEASE RC, GO NONE", EV_AC, IN_START, NONE, ANY_PC, RC_NONE, KEEP, KEEP, 0 },
    { "EV->AC x STOP TASK: RELEASE RC, GO NONE", EV_AC, IN_STOP, NONE, ANY_PC, RC_NONE, KEEP, KEEP, 0 },
    { "EV->AC x DELETE TASK: RELEASE RC, GO NONE", EV_AC, IN_DELETE, NONE, ANY_PC, RC_NONE, KEEP, KEEP, 0 },

    /* Row AC->EV. */
    { "AC->EV x EV: JUMP EV, GO AC", AC_EV, IN_EV, AC, TO_EVL, RC_SETUP, KEEP, KEEP, 0 },
    { "AC->EV x AC: RELEASE RC, JUMP AC, GO NONE", AC_EV, IN_AC, NONE, TO_ACL, RC_NONE, KEEP, KEEP, 1 },
    { "AC->EV x EXIT EV: GO AC", AC_EV, IN_EXIT_EV, AC, NO_JUMP, RC_SETUP, KEEP, KEEP, 0 },
    { "AC->EV x EXIT AC: GO NONE (RELEASE RC implied)", AC_EV, IN_EXIT_AC, NONE, NO_JUMP, RC_NONE, KEEP, KEEP, 0 },
    { "AC->EV x ENTER EV, MON<>0: EV=LBL, GO AC->EV (NEW)", AC_EV, IN_ENTER_EV_MON, AC_EV, NO_JUMP, RC_SETUP, NEW,
      KEEP, 0 },
    /* SEND EXIT EV reaches AC->EV x EXIT EV: GO AC. */
    { "AC->EV x ENTER EV, MON=0: SEND EXIT EV", AC_EV, IN_ENTER_EV_0, AC, NO_JUMP, RC_SETUP, KEEP, KEEP, 0 },
    { "AC->EV x ENTER AC, OK: AC=LBL, RC=RES, GO EV->AC (ALERT)", AC_EV, IN_ENTER_AC_OK, EV_AC, NO_JUMP, RC_RES, KEEP,
      NEW, 0 },
    /* SEND AC after AC=LBL reaches AC->EV x AC: RELEASE RC, JUMP AC (now LBL), GO NONE. */
    { "AC->EV x ENTER AC, not OK: AC=LBL, SEND AC", AC_EV, IN_ENTER_AC_REFUSED, NONE, TO_LBL, RC_NONE, KEEP, NEW, 0 },
    { "AC->EV x START TASK: RELEASE RC, GO NONE", AC_EV, IN_START, NONE, ANY_PC, RC_NONE, KEEP, KEEP, 0 },
    { "AC->EV x STOP TASK: RELEASE RC, GO NONE", AC_EV, IN_STOP, NONE, ANY_PC, RC_NONE, KEEP, KEEP, 0 },
    { "AC->EV x DELETE TASK: RELEASE RC, GO NONE", AC_EV, IN_DELETE, NONE, ANY_PC, RC_NONE, KEEP, KEEP, 0 },
};

/* ---- helpers ----------------------------------------------------------------------------------------------- */

static const u8 spin[] = { 0x27, 0x81 }; /* SJump to itself */

static void cmd(struct rcx *b, const u8 *bytes, unsigned len)
{
    brick_cmd(b, bytes, len, NULL);
}

static s16 poll(struct rcx *b, u8 src, u8 index)
{
    u8 c[3] = { 0x12, src, index }, reply[RCX_REPLY_MAX];
    assert_int_equal(brick_cmd(b, c, 3, reply), 3);
    return (s16)(u16)(reply[1] | reply[2] << 8);
}

/* Two spinning tasks, both running. */
static struct rcx *two_tasks(void)
{
    struct rcx *b = brick_new();
    assert_int_equal(brick_download(b, 1, S_TASK, spin, sizeof spin), 0);
    assert_int_equal(brick_download(b, 1, O_TASK, spin, sizeof spin), 0);
    brick_start(b, S_TASK);
    brick_start(b, O_TASK);
    b->task[S_TASK].priority = PRIO;
    return b;
}

/* Bring S into `state` through its own byte codes' inputs. */
static void set_up(struct rcx *b, u8 state)
{
    struct rcx_task *s = &b->task[S_TASK];
    if (state == EV || state == EV_AC)
        brick_enter_ev(b, s, MON0, EVL);
    if (state == AC || state == EV_AC || state == AC_EV)
        brick_enter_ac(b, s, RC0, ACL);
    if (state == AC_EV)
        brick_enter_ev(b, s, MON0, EVL);
    assert_int_equal(s->ev.state, state);
}

static void apply(struct rcx *b, u8 input)
{
    struct rcx_task *s = &b->task[S_TASK], *o = &b->task[O_TASK];
    static const u8 stop[] = { 0x81, S_TASK }, start[] = { 0x71, S_TASK }, del[] = { 0x61, S_TASK };
    static const u8 direct_event[] = { 0x03, 2, MON0, 0 };

    switch (input) {
    case IN_EV: cmd(b, direct_event, sizeof direct_event); break;
    case IN_AC:
        o->priority = PRIO;             /* equal priority may pre-empt (p. 106) */
        brick_enter_ac(b, o, RC0, 0x0100);
        assert_int_equal(o->ev.rc, RC0);
        break;
    case IN_EXIT_EV: access_input(b, s, ACCESS_IN_EXIT_EV); break; /* as ExitEventCheck runs it */
    case IN_EXIT_AC: access_input(b, s, ACCESS_IN_EXIT_AC); break; /* ExitAccessControl */
    case IN_ENTER_EV_MON: brick_enter_ev(b, s, MON1, LBL); break;
    case IN_ENTER_EV_0: brick_enter_ev(b, s, 0, LBL); break;
    case IN_ENTER_AC_OK: brick_enter_ac(b, s, RES1, LBL); break;
    case IN_ENTER_AC_REFUSED:
        o->priority = PRIO - 1;         /* higher than S */
        brick_enter_ac(b, o, RES1, 0x0100);
        assert_int_equal(o->ev.rc, RES1);
        brick_enter_ac(b, s, RES1, LBL);
        assert_int_equal(o->ev.rc, RES1); /* a refused request takes nothing */
        break;
    case IN_START: cmd(b, start, sizeof start); break;
    case IN_STOP: cmd(b, stop, sizeof stop); break;
    default: cmd(b, del, sizeof del); break;
    }
}

static void one_cell(void **state)
{
    const struct cell *c = *state;
    struct rcx *b = two_tasks();
    struct rcx_task *s = &b->task[S_TASK];
    static const u8 motor_a_on[] = { 0x21, 0x81 };
    u16 ev_before, mon_before, ac_before;
    u8 rc_before;

    set_up(b, c->state);
    cmd(b, motor_a_on, sizeof motor_a_on);
    s->sub = RCX_NO_SUB;
    s->pc = PC0;
    ev_before = s->ev.ev_pc;
    mon_before = s->ev.mon;
    ac_before = s->ev.ac_pc;
    rc_before = s->ev.rc;

    apply(b, c->input);

    assert_int_equal(s->ev.state, c->state_after);
    switch (c->jump) {
    case NO_JUMP: assert_int_equal(s->pc, PC0); break;
    case TO_EVL: assert_int_equal(s->pc, EVL); break;
    case TO_ACL: assert_int_equal(s->pc, ACL); break;
    case TO_LBL: assert_int_equal(s->pc, LBL); break;
    default: break;
    }
    assert_int_equal(s->ev.rc, c->rc == RC_SETUP ? rc_before : c->rc == RC_RES ? RES1 : 0);
    if (c->ev_label == NEW) {
        assert_int_equal(s->ev.ev_pc, LBL);
        assert_int_equal(s->ev.mon, MON1);
    } else if (c->jump != ANY_PC) {
        assert_int_equal(s->ev.ev_pc, ev_before);
        assert_int_equal(s->ev.mon, mon_before);
    }
    if (c->ac_label == NEW)
        assert_int_equal(s->ev.ac_pc, LBL);
    else if (c->jump != ANY_PC)
        assert_int_equal(s->ev.ac_pc, ac_before);
    if (c->input == IN_EV && c->jump == TO_EVL)
        assert_int_equal(poll(b, 23, S_TASK), MON0); /* the events that ended the monitoring */
    if (c->revoked) {
        u8 status = (u8)poll(b, 3, 0);  /* motor A: "affected motors are BRAKE" (p. 98) */
        assert_int_equal(status & (RCX_MOTOR_ON | RCX_MOTOR_BRAKE), RCX_MOTOR_BRAKE);
    }
    brick_free(b);
}

int main(void)
{
    struct CMUnitTest tests[sizeof cells / sizeof cells[0]];
    unsigned i;

    for (i = 0; i < sizeof cells / sizeof cells[0]; i++) {
        struct CMUnitTest t = { cells[i].name, one_cell, NULL, NULL, (void *)&cells[i] };
        tests[i] = t;
    }
    return _cmocka_run_group_tests("access_cells", tests, i, NULL, NULL);
}
