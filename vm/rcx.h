/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The state of one RCX brick and the byte-code machine's public interface.
 *
 * Everything mutable lives in one `struct rcx`: the target keeps one in .bss, the host may run several.
 * Time, sensor samples and IR bytes enter through function calls (vm_tick, vm_run, vm_direct); the machine
 * never reads a clock or a register itself.
 */
#ifndef RCX_VM_H
#define RCX_VM_H

#include "rcx_types.h"
#include "rcx_limits.h"
#include "rcx_opcodes.h"
#include "sensors.h"
#include "outputs.h"
#include "sound.h"
#include "display.h"
#include "events.h"
#include "remote.h"

/* Code objects of a program slot, in arena order: subroutines 0-7, then tasks 0-9. */
#define RCX_SLOT_OBJS (RCX_SUBS + RCX_TASKS)
#define RCX_OBJS (RCX_PROGRAMS * RCX_SLOT_OBJS)
#define rcx_obj_sub(prog, n) ((u8)((prog) * RCX_SLOT_OBJS + (n)))
#define rcx_obj_task(prog, n) ((u8)((prog) * RCX_SLOT_OBJS + RCX_SUBS + (n)))

#define RCX_NO_SUB 0xFF /* task executing its own body */

enum rcx_task_state {
    RCX_TASK_IDLE = 0,  /* not running */
    RCX_TASK_RUNNING,   /* gets one byte code per scheduler pass */
    RCX_TASK_WAITING    /* Wait in progress: costs nothing until its 10 ms tick comes */
};

#define WAIT_10MS 1
#define WAIT_MS 2

struct rcx_task {
    u8 state;
    u8 sub;         /* subroutine being executed, or RCX_NO_SUB */
    u16 pc;         /* offset of the next byte code within the current code object */
    u8 has_ret;     /* the single subroutine return address is set */
    u8 ret_sub;     /* code object to return to (a nested Gosub returns into a sub) */
    u16 ret_pc;
    u16 wake;       /* value of rcx.ticks10 at which a waiting task resumes */
    u8 priority;    /* 0 most important; decides access control only */
    u8 loop_depth;
    u8 loop[RCX_LOOP_LEVELS];
    u8 local_base;  /* variable 32-47 is global[n + local_base]: 16 x task in an RCX 2.0 program, 0 in a Swan one */
    u8 spare;       /* (ev's words are aligned) */
    struct rcx_task_events ev; /* monitoring and access control */
#if RCX_SWAN /* last: the rest is laid out the same with and without (tests/drivers/test_h8tasks.c) */
    u8 stack;       /* Swan push/pop depth (the values are readable by no source OpenRCX has) */
    u8 wait_ms;     /* the wait is WaitMS's: wake is a value of rcx.ms_now */
#endif
};

/* A task or subroutine download in progress (BeginOfTask/BeginOfSub then ContinueDL blocks). */
struct rcx_download {
    u8 active;
    u8 obj;         /* code object being written */
    u16 expect;     /* number of the next block (1, 2, ...; the last is 0) */
    u16 last;       /* number of the last accepted block, for re-acknowledging a repeat */
    u16 filled;     /* bytes written so far */
};

/* Program memory's bytes still to be moved after a resize (vm/progmem.c, RCX_MOVE_STEP): the `len` bytes at `from`
 * belong at `to`. */
struct rcx_move {
    u8 *from, *to;
    u16 len;
};

struct rcx {
    /* Program memory: code objects packed in obj order, then the datalog, then free space. */
    u16 obj_start[RCX_OBJS + 1]; /* offsets; obj_start[RCX_OBJS] is the end of code */
    u16 log_size;   /* datalog entries allocated including entry 0; 0 = no datalog */
    u16 log_count;  /* entries used including entry 0 */
    u16 arena_addr; /* address the arena has in the brick's RAM (memory map, UploadRam) */
    struct rcx_download dl;

    /* Variables and tasks of the selected program. */
    u8 prog;        /* selected program slot, source 8 */
    u8 rr;          /* next task the round-robin scheduler visits */
    u16 runmask;    /* bit n set: task n is in RCX_TASK_RUNNING */
    volatile u8 yield; /* set by the port (the brick's tick interrupt): vm_run returns at its next check */
    u8 waiting;     /* WAIT_10MS/WAIT_MS set when a task starts a Wait/WaitMS, cleared once none waits */
    u8 swan[RCX_SWAN_N(RCX_PROGRAMS)]; /* slot's code uses a Swan opcode or source 43/44 (decided when a download
                                          completes) */
    u8 message;     /* source 15 (here, in the byte the array leaves before the words) */
    s16 global[RCX_ALL_GLOBALS]; /* 0-31 RCX 2.0's globals, then task t's locals at 32 + 16 t (Swan's overlay) */
    struct rcx_task task[RCX_TASKS];

    /* Time. */
    u8 ms;          /* milliseconds into the current 10 ms step */
    u8 step10;      /* 10 ms steps into the current 100 ms tick (the 10 ms view of the timers) */
    u16 ticks10;    /* free-running count of 10 ms steps; task wake times */
    u16 timer[RCX_TIMERS]; /* 100 ms timers, 0-32767 */
    u16 watch_ms;   /* milliseconds into the current minute */
    u16 watch;      /* source 14: minutes since midnight */
    u16 random;     /* generator state, never 0 */
    u16 ms_now;     /* free-running millisecond count: 1 ms timers and WaitMS */
    u16 ms_base[RCX_SWAN_N(RCX_TIMERS)]; /* source 22 index i reads (ms_now - ms_base[i]) & 0x7FFF */

    /* Values delivered by the runtime, read by sources. */
    u16 battery_mv; /* source 34 */
    s16 msg_param;  /* source 15 index 1: Swan's message parameter */
    s16 swan_power[RCX_SWAN_N(4)][RCX_MOTORS]; /* sources 5, 16, 32, 7 as last written (sources.c) */
    s16 system[RCX_SWAN_N(RCX_SYSTEM)];  /* source 24 as written: read back for the settings OpenRCX does not have */

    struct rcx_sensor sensor[RCX_SENSORS];
    struct rcx_event event[RCX_EVENTS];
    struct rcx_outputs out;
    struct rcx_sound sound;
    struct rcx_display display;
    struct rcx_remote remote;
    u8 uart[RCX_UART_BYTES]; /* source 33 */

    /* Requests the runtime acts on (power, IR range, boot mode). */
    u8 power_down_min;     /* PBPowerDownTime, 0 = never */
    u8 idle_reset;         /* set when the power-down timer must restart */
    u8 turn_off;           /* PBTurnOff accepted */
    u8 tx_range;           /* PbTXPower: 0 short, 1 long */
    u8 boot_mode;          /* GoIntoBootMode accepted */
    u8 sensors_rest;       /* sensors_at_rest() found every input steady; cleared when that may end */

    struct rcx_move move[2]; /* the move being made, then the one to make after it (a command's second resize):
                                nothing that reads or writes program memory runs while a len is not 0 */
#if RCX_SWAN
    u16 dl_scan;    /* the download's first instruction not looked at for Swan code yet (swan_block; while no Swan
                       code is found) */
    u8 dl_swan;     /* the download has Swan code */
    u8 spare2;
#endif

    void *port;     /* the hardware port's own data for this brick (host simulator); the machine never uses it */

    u8 arena[RCX_ARENA_SIZE];
};

#if RCX_SWAN
/* The clock task t's wait runs on: rcx.ms_now for Swan's WaitMS (t->wait_ms), else rcx.ticks10 (ops_wait, vm_tick).
 * Written as an if: gcc makes the conditional expression longer. */
static inline u16 wait_clock(const struct rcx *b, const struct rcx_task *t)
{
    u16 now = b->ticks10;
    if (t->wait_ms)
        now = b->ms_now;
    return now;
}
#endif

/* Power-on state: empty memory, variables zero, program slot 0, outputs braked (told to the hardware, so attach
 * rcx.port first: it is kept). `arena_addr` is the arena's address on the brick. */
void vm_init(struct rcx *b, u16 arena_addr);

/* One millisecond has passed. */
void vm_tick(struct rcx *b);
#define vm_pausing(b) ((b)->out.pause[0] || (b)->out.pause[1] || (b)->out.pause[2]) /* outputs_tick has work */
#define vm_sounding(b) ((b)->sound.count || (b)->sound.left)                        /* sound_tick has work */

/* Execute up to `budget` byte codes, one per running task in turn; returns how many were executed (a task reaching
 * the end of its code counts as one). Returns early once `yield` is set: it is checked at least every
 * RCX_RUN_CHUNK byte codes, so a port can pass a budget as large as it likes and still get its turn. */
#define RCX_RUN_CHUNK 40 /* x++ at full speed: 0.7 ms of the brick */
u16 vm_run(struct rcx *b, u16 budget);

/* Execute one direct command (`len` bytes from the opcode, toggle bit as received). Writes the reply into
 * `reply` (at least RCX_REPLY_MAX bytes) and returns its length; 0 means the command is not answered. */
u8 vm_direct(struct rcx *b, const u8 *cmd, u8 len, u8 *reply);

/* Tasks and programs (vm/sched.c). */
void sched_start_task(struct rcx *b, u8 n);
struct rcx_task *sched_stop_task(struct rcx *b, u8 n); /* task n (NULL: there is none) */
struct rcx_task *sched_stop(struct rcx *b, struct rcx_task *t); /* the same for a task by its address; t */
void sched_set_state(struct rcx *b, struct rcx_task *t, u8 state); /* and t's bit of runmask: set only when RUNNING */
void sched_stop_all(struct rcx *b);
void sched_select_program(struct rcx *b, u8 prog, u8 from_program);

/* Sources (vm/sources.c). `t` is the task asking, NULL for a direct command (no locals). */
s16 source_get(struct rcx *b, const struct rcx_task *t, u8 src, u16 index);
void source_set(struct rcx *b, struct rcx_task *t, u8 src, u16 index, s16 value);
s16 source_poll(struct rcx *b, const u8 *cmd); /* direct Poll: 0x8000 for what does not exist */
s16 *var_ref(struct rcx *b, const struct rcx_task *t, u16 n); /* NULL when n is not a variable here */
#define rcx_local(b, n, k) ((b)->global[RCX_GLOBALS + RCX_LOCALS * (n) + (k)]) /* task n's variable 32 + k */

/* Program memory (vm/progmem.c). */
u16 mem_free(const struct rcx *b);
u16 mem_obj_size(const struct rcx *b, u8 obj);
static inline const u8 *mem_obj_code(const struct rcx *b, u8 obj) { return b->arena + b->obj_start[obj]; } /* (tests) */
u8 mem_obj_runnable(const struct rcx *b, u8 obj);
/* Objects obj to obj + n - 1 as one of `size` bytes (the last; the others empty), which keeps their first bytes: 0
 * when memory is short, and then nothing changed. */
u8 mem_resize(struct rcx *b, u8 obj, u8 n, u16 size);
void mem_delete(struct rcx *b, u8 id, u8 n); /* the selected slot's objects id to id + n - 1 (vm/direct.c), all
                                                 * but the one being downloaded */
#if RCX_MOVE_STEP
u8 mem_step(struct rcx *b); /* a step of the move a resize left; 0: none was left */
#else
#define mem_step(b) ((void)(b), 0)
#endif
u8 mem_memmap(const struct rcx *b, u8 *out); /* the 188 data bytes of the MemMap reply */

/* Datalog (vm/datalog.c). */
void datalog_set(struct rcx *b, u16 entries);
void datalog_add(struct rcx *b, const struct rcx_task *t, u8 src, u8 index);
s16 datalog_upload(const struct rcx *b, u16 start, u16 count, u8 *out); /* bytes written, -1 when refused */

/* Instructions shared by programs and direct commands, and the program's that do not jump (vm/ops.c); any other
 * opcode does nothing. */
void ops_exec(struct rcx *b, struct rcx_task *t, const u8 *ins);
#if RCX_SWAN
s16 ops_arith(s16 a, s16 v, u8 kind); /* a op v for kind ARITH_* (rcx_opcodes.h); static (inlined) without Swan */
#endif
void ops_set_message(struct rcx *b, u8 m); /* and tell the events */
/* Swan's opcodes (vm/swan.c): run the instruction of row r (a stack overflow or underflow stops the task). */
void swan_exec(struct rcx *b, struct rcx_task *t, const u8 *ins, const struct rcx_swan_row *r);
/* A download's block of `count` bytes at `src`, checked: written, looked at for Swan code; the last (number 0) ends the
 * download (the object's final size, then its slot's kind). */
void swan_block(struct rcx *b, const u8 *src, u16 count);

void ops_var(struct rcx *b, struct rcx_task *t, const u8 *ins); /* 0x14-0x94: v op= S */
void ops_wait(struct rcx *b, struct rcx_task *t, const u8 *ins); /* Wait, Swan's WaitMS */
/* The commonest operand: a source in ins[1], its 16-bit index (little-endian) at ins + 2. */
s16 ops_source(struct rcx *b, const struct rcx_task *t, const u8 *ins);
s16 ops_source8(struct rcx *b, const struct rcx_task *t, const u8 *ins); /* the same with an 8-bit index */

/* A new 10-bit sample of input n (vm/sensors.h). */
static inline void sensor_sample(struct rcx *b, u8 n, u16 raw)
{
    if (n < RCX_SENSORS)
        sensor_feed(b, &b->sensor[n], raw);
}
/* Input n's processed value or boolean may have changed. Inline: the sensor engine, which has the input at hand,
 * calls events_evaluate() itself (vm/sensors.c), and the image needs no function of its own for this. */
static inline void events_input(struct rcx *b, u8 n)
{
    if (n < RCX_SENSORS)
        events_evaluate(b, b->sensor[n].watched, EVENTS_KEY(n));
}

#endif
