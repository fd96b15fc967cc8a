/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The access-control & event-monitoring state machine of spec p. 107, one per task (struct rcx_task_events).
 * Its states and inputs in the spec table's order; vm/access.c quotes the table and runs it.
 */
#ifndef RCX_ACCESS_H
#define RCX_ACCESS_H

#include "rcx_types.h"

struct rcx;
struct rcx_task;

/* States (rows). NONE must be 0: a task's power-on state. Bit 0 is set in the states with event monitoring, bit 1 in
 * those with an access region (one bit test each); the two nestings differ in bit 2. */
enum access_state {
    ACCESS_NONE = 0,
    ACCESS_EV = 1,      /* monitoring events */
    ACCESS_AC = 2,      /* holding resources */
    ACCESS_EV_AC = 3,   /* an access region inside event monitoring */
    ACCESS_AC_EV = 7    /* event monitoring inside an access region */
};

/* Inputs (columns) without operands. EV and AC come from the firmware, the others from the task's own byte codes.
 * The inputs with operands, ENTER EV (S/LEnterEventCheck: MON, LBL) and ENTER AC (EnterAccessControl: RES, LBL), are
 * access_enter() (vm/events.h), given the byte code. */
enum access_input {
    ACCESS_IN_EV = 0,    /* a monitored event happened */
    ACCESS_IN_AC,        /* a task of equal or higher priority took some of RC */
    ACCESS_IN_EXIT_EV,   /* ExitEventCheck */
    ACCESS_IN_EXIT_AC    /* ExitAccessControl */
};                       /* START, STOP, DELETE TASK: events_task_ended() (vm/events.h), which only ends everything */

#define ACCESS_HAS_EV(state) ((u8)((state) & ACCESS_EV)) /* EV, EV->AC, AC->EV */
#define ACCESS_HAS_AC(state) ((u8)((state) & ACCESS_AC)) /* AC, EV->AC, AC->EV */

/* Feed one input to task t's machine (vm/access.c). */
void access_input(struct rcx *b, struct rcx_task *t, u8 input);

#endif
