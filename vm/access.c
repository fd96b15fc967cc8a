/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Access control & event monitoring (spec pp. 69, 85, 96, 106-107): the state machine of p. 107, one per task.
 *
 * The spec's table, rows = states, columns = inputs (REL = RELEASE RC, (N) = NEW, (A) = ALERT, - = nothing):
 *
 *          EV                   AC                   EXIT EV        EXIT AC    START, STOP, DELETE TASK
 *  NONE    -                    -                    -              -          -
 *  EV      JUMP EV GO NONE      -                    GO NONE        -          GO NONE
 *  AC      -                    REL JUMP AC GO NONE  -              GO NONE    REL GO NONE
 *  EV->AC  REL JUMP EV GO NONE  REL JUMP AC GO EV    REL GO NONE    GO EV      REL GO NONE
 *  AC->EV  JUMP EV GO AC        REL JUMP AC GO NONE  GO AC          GO NONE    REL GO NONE
 *
 *          ENTER EV (MON, LBL):          ENTER AC (RES, LBL)
 *          IF MON<>0 EV=LBL GO ...,
 *          ELSE SEND EXIT EV
 *  NONE    GO EV                         IF OK AC=LBL RC=RES GO AC, ELSE JUMP LBL
 *  EV      GO EV (N)                     IF OK AC=LBL RC=RES GO EV->AC, ELSE JUMP LBL
 *  AC      GO AC->EV                     AC=LBL IF OK RC=RES GO AC (N), ELSE SEND AC
 *  EV->AC  GO AC->EV (A)                 AC=LBL IF OK RC=RES GO EV->AC (N), ELSE SEND AC
 *  AC->EV  GO AC->EV (N)                 AC=LBL IF OK RC=RES GO EV->AC (A), ELSE SEND AC
 *
 * Read by region, the table is three rules, which is how it is run here:
 *  - EV and EXIT EV end event monitoring, AC and EXIT AC end the access region; in a state without that region
 *    they do nothing. EV and AC also jump to the region's label. Ending the access region releases RC and leaves
 *    the event monitoring it was entered in (EV->AC goes to EV); ending event monitoring goes back to the access
 *    region it was entered in (AC->EV goes to AC) and otherwise to NONE, releasing RC (EV->AC).
 *  - ENTER EV and ENTER AC (when granted) open their region inside whatever the task is in: the new state keeps
 *    the other region. A refused ENTER AC jumps to LBL, or inside an access region ends it (SEND AC) with LBL as
 *    its label. ENTER EV without events to monitor is EXIT EV.
 *  - START, STOP and DELETE TASK end everything.
 * The states are bits (vm/access.h), so that testing for a region is one bit test.
 * RC is empty in the states without an access region, so releasing it there changes nothing.
 *
 * Where the table is silent or garbled:
 *  - EXIT AC lists only GO in rows AC, EV->AC and AC->EV. Leaving an access region must give its resources back
 *    (p. 69: "before releasing the resources"), and every other way out of an AC state releases RC, so those
 *    three cells RELEASE RC here; otherwise a task outside any access region would keep its motors for ever.
 *  - An AC input is only sent to holders when the request is granted (OK): a refused request takes nothing.
 */
#include "rcx.h"
#include "access.h"

/* A jump to `pc` (in the code object the caller has put in t->sub) reaches a task wherever it is; one asleep in Wait
 * wakes up to take it. */
static void jump(struct rcx *b, struct rcx_task *t, u16 pc)
{
    t->pc = pc;
    if (t->state == RCX_TASK_WAITING)
        sched_set_state(b, t, RCX_TASK_RUNNING);
}

/* The labels are pairs, EV's then AC's (vm/events.h), so the EV and AC inputs (0 and 1) index them. */
RCX_STATIC_ASSERT(labels_are_pairs,
                  offsetof(struct rcx_task_events, ac_pc) == offsetof(struct rcx_task_events, ev_pc) + 2 &&
                  offsetof(struct rcx_task_events, ac_sub) == offsetof(struct rcx_task_events, ev_sub) + 1 &&
                  ACCESS_IN_EV == 0 && ACCESS_IN_AC == 1);
#define label_pc(t, input) (*(const u16 *)(const void *)((const u8 *)&(t)->ev.ev_pc + 2u * (input)))
#define label_sub(t, input) (*((const u8 *)&(t)->ev.ev_sub + (input)))

/* The EV, AC, EXIT EV or EXIT AC input: the first rule above (the last is events_task_ended(), vm/events.h). */
void access_input(struct rcx *b, struct rcx_task *t, u8 input)
{
    u8 s = t->ev.state, n = ACCESS_NONE;

    if (input & 1) { /* AC, EXIT AC */
        if (!ACCESS_HAS_AC(s))
            return;
        if (s == ACCESS_EV_AC)
            n = ACCESS_EV;
    } else {
        if (!ACCESS_HAS_EV(s))
            return;
        if (s == ACCESS_AC_EV)
            n = ACCESS_AC;
    }
    if (input <= ACCESS_IN_AC) { /* EV (0) or AC (1): the label of that region, one load each */
        t->sub = label_sub(t, input);
        jump(b, t, label_pc(t, input));
    }
    if (n != ACCESS_AC) /* NONE or EV: no access region left */
        t->ev.rc = 0;   /* RELEASE RC */
    t->ev.state = n;
}

/* IF OK for a request of `res` by task t: OK when no other task of higher priority (lower number) holds any of it
 * (t itself is not of higher priority than t). */
static u8 granted(const struct rcx *b, const struct rcx_task *t, u8 res)
{
    const struct rcx_task *u = b->task;
    u8 n = RCX_TASKS; /* a count: cheaper than comparing with the end of b->task */

    do {
        if ((u->ev.rc & res) && u->priority < t->priority)
            return 0;
        u++;
    } while (--n);
    return 1;
}

/* ENTER EV (SEnterEventCheck, LEnterEventCheck: MON, LBL) or ENTER AC (EnterAccessControl: RES, LBL), the byte code at
 * ins; `target` is LBL, the pc its distance leads to in the task's current code object. One function for the three,
 * so that the interpreter has one call to make. No recursion (the firmware's stack check refuses it): the AC inputs a
 * request causes are performed directly. */
#define ENTER_EV_BIT 0x80 /* set in SEnterEventCheck and LEnterEventCheck, clear in EnterAccessControl */
RCX_STATIC_ASSERT(enter_ev_bit, (RCX_OP_SENTER_EVENT & RCX_OP_LENTER_EVENT & ENTER_EV_BIT) &&
                  !(RCX_OP_ENTER_ACCESS & ENTER_EV_BIT));
void access_enter(struct rcx *b, struct rcx_task *t, const u8 *ins, u16 target)
{
    struct rcx_task *u;
    u16 mask;
    u8 resources = ins[1];

    if (!(ins[0] & ENTER_EV_BIT)) {
        if (granted(b, t, resources)) {
            /* The other holders (of equal or lower priority) lose everything they hold, their motors brake (p. 98)
             * and they take the AC input. This task's own resources go first, so that it is not one of them: it
             * holds RES in their place. */
            t->ev.rc = 0;
            u = b->task;
            do
                if (u->ev.rc & resources) {
                    outputs_revoked(b, u->ev.rc);
                    access_input(b, u, ACCESS_IN_AC);
                }
            while (++u < b->task + RCX_TASKS);
            t->ev.rc = resources;
            t->ev.state = (u8)(ACCESS_AC | (t->ev.state & ACCESS_EV)); /* EV->AC when monitoring events, else AC */
        } else {
            /* JUMP LBL (in the code object the task is in; the task runs this byte code, so it is not asleep in
             * a Wait); in an access region SEND AC, whose JUMP AC goes to the same place: what remains of it is
             * EXIT AC. */
            t->pc = target;
            if (!ACCESS_HAS_AC(t->ev.state))
                return;
            access_input(b, t, ACCESS_IN_EXIT_AC);
        }
        /* AC=LBL: after the IF OK, or before it in the states with an access region (neither JUMP nor EXIT AC reads
         * it). */
        t->ev.ac_pc = target;
        t->ev.ac_sub = t->sub;
        return;
    }
    /* ENTER EV: IF MON<>0 EV=LBL GO ..., ELSE SEND EXIT EV */
    if ((mask = (u16)ops_source(b, t, ins)) == 0) {
        access_input(b, t, ACCESS_IN_EXIT_EV);
        return;
    }
    t->ev.ev_pc = target;
    t->ev.ev_sub = t->sub;
    t->ev.mon = mask;
    t->ev.state = ACCESS_HAS_AC(t->ev.state) ? ACCESS_AC_EV : ACCESS_EV;
}
