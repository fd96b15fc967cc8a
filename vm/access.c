/*
 * Access control & event monitoring (spec pp. 69, 85, 96, 106-107): the state machine of p. 107 as a table with
 * one cell per state x input, run by one small interpreter. Rows and columns are the spec's, in its order; each
 * cell names the spec's actions in the spec's words.
 *
 * Where the table is silent or garbled:
 *  - EXIT AC lists only GO in rows AC, EV->AC and AC->EV. Leaving an access region must give its resources back
 *    (p. 69: "before releasing the resources"), and every other way out of an AC state releases RC, so those
 *    three cells RELEASE RC here; otherwise a task outside any access region would keep its motors for ever.
 *  - An AC input is only sent to holders when the request is granted (OK): a refused request takes nothing.
 */
#include "rcx.h"
#include "access.h"

/*
 * A cell is the set of its actions. The interpreter performs them in the order every cell of the spec lists them:
 * AC=LBL when it comes before the IF; the IF; then RELEASE RC, EV=LBL, AC=LBL, RC=RES, JUMP, GO; or, when the IF
 * fails, the ELSE action (a SEND or JUMP LBL).
 */
#define GO(state)    ((u16)((state) + 1)) /* bits 0-2; 0: the state does not change */
#define JUMP_EV      0x0008u
#define JUMP_AC      0x0010u
#define RELEASE_RC   0x0020u
#define EV_LBL       0x0040u    /* EV=LBL (and the events to monitor) */
#define AC_LBL       0x0080u    /* AC=LBL inside the IF */
#define RC_RES       0x0100u    /* RC=RES */
#define IF_MON       0x0200u    /* IF MON<>0 */
#define IF_OK        0x0400u    /* IF OK: no task of higher priority holds any of RES */
#define AC_LBL_IF    0x0800u    /* AC=LBL before the IF */
#define ELSE_SEND_EXIT_EV 0x1000u
#define ELSE_SEND_AC 0x2000u
#define ELSE_JUMP_LBL 0x4000u

#define NONE ACCESS_NONE
#define EV ACCESS_EV
#define AC ACCESS_AC
#define EV_AC ACCESS_EV_AC
#define AC_EV ACCESS_AC_EV

/* Spec p. 107. (NEW) and (ALERT) mark the transitions the spec marks; they need no action of their own. */
static const u16 access_table[ACCESS_STATES][ACCESS_INPUTS] = {
    [NONE] = {
        [ACCESS_IN_EV] = 0,
        [ACCESS_IN_AC] = 0,
        [ACCESS_IN_EXIT_EV] = 0,
        [ACCESS_IN_EXIT_AC] = 0,
        [ACCESS_IN_ENTER_EV] = IF_MON | EV_LBL | GO(EV) | ELSE_SEND_EXIT_EV,
        [ACCESS_IN_ENTER_AC] = IF_OK | AC_LBL | RC_RES | GO(AC) | ELSE_JUMP_LBL,
        [ACCESS_IN_END] = 0,
    },
    [EV] = {
        [ACCESS_IN_EV] = JUMP_EV | GO(NONE),
        [ACCESS_IN_AC] = 0,
        [ACCESS_IN_EXIT_EV] = GO(NONE),
        [ACCESS_IN_EXIT_AC] = 0,
        [ACCESS_IN_ENTER_EV] = IF_MON | EV_LBL | GO(EV) /* NEW */ | ELSE_SEND_EXIT_EV,
        [ACCESS_IN_ENTER_AC] = IF_OK | AC_LBL | RC_RES | GO(EV_AC) | ELSE_JUMP_LBL,
        [ACCESS_IN_END] = GO(NONE),
    },
    [AC] = {
        [ACCESS_IN_EV] = 0,
        [ACCESS_IN_AC] = RELEASE_RC | JUMP_AC | GO(NONE),
        [ACCESS_IN_EXIT_EV] = 0,
        [ACCESS_IN_EXIT_AC] = RELEASE_RC | GO(NONE),
        [ACCESS_IN_ENTER_EV] = IF_MON | EV_LBL | GO(AC_EV) | ELSE_SEND_EXIT_EV,
        [ACCESS_IN_ENTER_AC] = AC_LBL_IF | IF_OK | RC_RES | GO(AC) /* NEW */ | ELSE_SEND_AC,
        [ACCESS_IN_END] = RELEASE_RC | GO(NONE),
    },
    [EV_AC] = {
        [ACCESS_IN_EV] = RELEASE_RC | JUMP_EV | GO(NONE),
        [ACCESS_IN_AC] = RELEASE_RC | JUMP_AC | GO(EV),
        [ACCESS_IN_EXIT_EV] = RELEASE_RC | GO(NONE),
        [ACCESS_IN_EXIT_AC] = RELEASE_RC | GO(EV),
        [ACCESS_IN_ENTER_EV] = IF_MON | EV_LBL | GO(AC_EV) /* ALERT */ | ELSE_SEND_EXIT_EV,
        [ACCESS_IN_ENTER_AC] = AC_LBL_IF | IF_OK | RC_RES | GO(EV_AC) /* NEW */ | ELSE_SEND_AC,
        [ACCESS_IN_END] = RELEASE_RC | GO(NONE),
    },
    [AC_EV] = {
        [ACCESS_IN_EV] = JUMP_EV | GO(AC),
        [ACCESS_IN_AC] = RELEASE_RC | JUMP_AC | GO(NONE),
        [ACCESS_IN_EXIT_EV] = GO(AC),
        [ACCESS_IN_EXIT_AC] = RELEASE_RC | GO(NONE),
        [ACCESS_IN_ENTER_EV] = IF_MON | EV_LBL | GO(AC_EV) /* NEW */ | ELSE_SEND_EXIT_EV,
        [ACCESS_IN_ENTER_AC] = AC_LBL_IF | IF_OK | RC_RES | GO(EV_AC) /* ALERT */ | ELSE_SEND_AC,
        [ACCESS_IN_END] = RELEASE_RC | GO(NONE),
    },
};

/* A jump reaches a task wherever it is; one asleep in Wait wakes up to take it. */
static void jump(struct rcx *b, struct rcx_task *t, u8 sub, u16 pc)
{
    t->sub = sub;
    t->pc = pc;
    if (t->state == RCX_TASK_WAITING) {
        const struct rcx_task *u = b->task;
        u16 bit = 1;
        while (u++ != t)
            bit <<= 1;
        t->state = RCX_TASK_RUNNING;
        b->runmask |= bit;
    }
}

/* The actions of cell `c` that follow a successful IF (or stand alone). */
static void perform(struct rcx *b, struct rcx_task *t, u16 c, u16 arg, u16 label)
{
    struct rcx_task_events *m = &t->ev;

    if (c & RELEASE_RC)
        m->rc = 0;
    if (c & EV_LBL) {
        m->ev_pc = label;
        m->ev_sub = t->sub;
        m->mon = arg;
    }
    if (c & AC_LBL) {
        m->ac_pc = label;
        m->ac_sub = t->sub;
    }
    if (c & RC_RES)
        m->rc = (u8)arg;
    if (c & JUMP_EV)
        jump(b, t, m->ev_sub, m->ev_pc);
    if (c & JUMP_AC)
        jump(b, t, m->ac_sub, m->ac_pc);
    if (c & 7)
        m->state = (u8)((c & 7) - 1);
}

/* OK: no other task of higher priority (lower number) holds any of `res`. */
static u8 ok(const struct rcx *b, const struct rcx_task *t, u8 res)
{
    const struct rcx_task *u;

    for (u = b->task; u < b->task + RCX_TASKS; u++)
        if (u != t && (u->ev.rc & res) && u->priority < t->priority)
            return 0;
    return 1;
}

/* The consequence of a granted request: holders of equal or lower priority lose everything they hold, their
 * motors brake (p. 98) and they take the AC input. Its cells have no IF, so no request is made from here. */
static void revoke(struct rcx *b, const struct rcx_task *t, u8 res)
{
    struct rcx_task *u;

    for (u = b->task; u < b->task + RCX_TASKS; u++)
        if (u != t && (u->ev.rc & res)) {
            outputs_revoked(b, u->ev.rc);
            perform(b, u, access_table[u->ev.state][ACCESS_IN_AC], 0, 0);
        }
}

/* No recursion (the firmware's stack check refuses it): a SEND runs the cell it reaches in the same call, and the
 * AC inputs a request causes are performed directly. */
void access_input(struct rcx *b, struct rcx_task *t, u8 input, u16 arg, u16 label)
{
    struct rcx_task_events *m = &t->ev;
    u8 sends = 0;
    u16 c;

again:
    c = access_table[m->state][input];
    if (c & AC_LBL_IF) {
        m->ac_pc = label;
        m->ac_sub = t->sub;
    }
    if (((c & IF_MON) && arg == 0) || ((c & IF_OK) && !ok(b, t, (u8)arg))) {
        if (c & ELSE_JUMP_LBL) {
            jump(b, t, t->sub, label);
        } else if ((c & (ELSE_SEND_AC | ELSE_SEND_EXIT_EV)) && !sends++) {
            /* The cells a SEND reaches (columns AC and EXIT EV) have no IF: one re-dispatch is all there is. */
            input = (c & ELSE_SEND_AC) ? ACCESS_IN_AC : ACCESS_IN_EXIT_EV;
            goto again;
        }
        return;
    }
    if (c & IF_OK)
        revoke(b, t, (u8)arg);
    perform(b, t, c, arg, label);
}

void access_enter(struct rcx *b, struct rcx_task *t, u8 resources, u16 target)
{
    access_input(b, t, ACCESS_IN_ENTER_AC, resources, target);
}

void access_exit(struct rcx *b, struct rcx_task *t)
{
    access_input(b, t, ACCESS_IN_EXIT_AC, 0, 0);
}
