/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Sizes of the RCX 2.0 virtual machine (spec "Virtual machine characteristics", p. 5, and
 * reference-firmware.md "limits"). A port may override RCX_ARENA_SIZE before including this header.
 */
#ifndef RCX_LIMITS_H
#define RCX_LIMITS_H

#define RCX_PROGRAMS 5      /* program slots 0-4 (shown as 1-5 on the LCD) */
#define RCX_TASKS 10        /* tasks per program */
#define RCX_SUBS 8          /* subroutines per program */
#define RCX_GLOBALS 32      /* persistent global variables 0-31 */
#define RCX_LOCALS 16       /* locals per task, variable numbers 32-47 */
#define RCX_VARS (RCX_GLOBALS + RCX_LOCALS)

/* Swan's programs (nqc -TSwan, issue 16): 1 in the host build; 0 leaves them out of a build (the firmware image, until
 * they fit its budget), which then runs RCX 2.0 code as before, with its globals and locals in one array. */
#ifndef RCX_SWAN
#define RCX_SWAN 1
#endif
/* One array of globals: 0-31 RCX 2.0's, task t's locals at 32 + 16 t (Swan's overlay, swan-target.md 4), Swan's up
 * to 255. */
#define RCX_ALL_GLOBALS (RCX_SWAN ? 256 : RCX_GLOBALS + RCX_TASKS * RCX_LOCALS)
#define RCX_SWAN_STACK 8    /* push (0xE3) entries per task before overflow stops it */
#define RCX_SYSTEM 39       /* Swan's system settings, source 24 index 0-38 */
#define RCX_SWAN_N(n) (RCX_SWAN ? (n) : 1) /* the size of an array only Swan's programs use */
#define RCX_TIMERS 4        /* 100 ms system timers */
#define RCX_LOOP_LEVELS 4   /* SetLoopCounter nesting */
#define RCX_EVENTS 16
#define RCX_COUNTERS 3      /* counters 0-2 are globals 0-2 */
#define RCX_SENSORS 3
#define RCX_MOTORS 3
#define RCX_UART_BYTES 18   /* source 33: 16 data bytes, PackConf, UartConf */

#define RCX_FIRMWARE_VERSION 328 /* source 35: version x 100, as firm0328 reports */

/* Bytes of program memory shared by the code of all slots and the datalog. */
#ifndef RCX_ARENA_SIZE
#define RCX_ARENA_SIZE 16384u
#endif

/* Bytes of program memory a pass of the main loop moves after a resize (vm/progmem.c): the firmware image's is set in
 * CMakeLists.txt; 0, the host's, moves them at once. */
#ifndef RCX_MOVE_STEP
#define RCX_MOVE_STEP 0
#endif

/* Longest reply a direct command can produce: the memory map, 1 + 94 words. */
#define RCX_REPLY_MAX 189

#endif
