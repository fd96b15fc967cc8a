/*
 * The access-control & event-monitoring state machine of spec p. 107, one per task (struct rcx_task_events).
 * Its states and inputs in the spec table's order; vm/access.c quotes the table and runs it.
 */
#ifndef RCX_ACCESS_H
#define RCX_ACCESS_H

#include "rcx_types.h"

struct rcx;
struct rcx_task;

/* States (rows). NONE must be 0: a task's power-on state. */
enum access_state {
    ACCESS_NONE = 0,
    ACCESS_EV,      /* monitoring events */
    ACCESS_AC,      /* holding resources */
    ACCESS_EV_AC,   /* an access region inside event monitoring */
    ACCESS_AC_EV,   /* event monitoring inside an access region */
    ACCESS_STATES
};

/* Inputs (columns) without operands. EV and AC come from the firmware, the others from the task's own byte codes.
 * The inputs with operands, ENTER EV (S/LEnterEventCheck: MON, LBL) and ENTER AC (EnterAccessControl: RES, LBL), are
 * events_monitor_enter() and access_enter() (vm/events.h). */
enum access_input {
    ACCESS_IN_EV = 0,    /* a monitored event happened */
    ACCESS_IN_AC,        /* a task of equal or higher priority took some of RC */
    ACCESS_IN_EXIT_EV,   /* ExitEventCheck */
    ACCESS_IN_EXIT_AC,   /* ExitAccessControl */
    ACCESS_IN_END        /* START, STOP, DELETE TASK */
};

#define ACCESS_HAS_EV(state) ((state) != ACCESS_NONE && (state) != ACCESS_AC) /* EV, EV->AC, AC->EV */
#define ACCESS_HAS_AC(state) ((state) >= ACCESS_AC)                          /* AC, EV->AC, AC->EV */

/* Feed one input to task t's machine (vm/access.c). */
void access_input(struct rcx *b, struct rcx_task *t, u8 input);

#endif
