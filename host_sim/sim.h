/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The virtual RCX: whole firmware runtimes (src/ + vm/) on simulated drivers, any number of bricks in one simulated
 * IR room (room.h) with the ways into it: serial IR towers on pseudo-terminals for the real host tools (tower.h),
 * the TCP link (net.h), and the ROM's download mode.
 *
 * Time is simulated: the main loop advances it one millisecond at a time and hands each brick rt_tick(); the wall
 * clock only paces the loop (real time, N x real time, or as fast as possible) and never reaches a brick.
 */
#ifndef RCX_SIM_H
#define RCX_SIM_H

#include <stdio.h>
#include "runtime.h"
#include "room.h"

#define SIM_MAX_BRICKS 8

/* The ROM's download mode (rcx-hardware.md §2, §4.3). */
#define ROM_RX_MAX (6 + 1024)
#define ROM_IMAGE 0x7000u          /* 8000-EFFF */
struct sim_rom {
    unsigned char rx[ROM_RX_MAX];
    unsigned rx_len, rx_need, state, quiet, echo;
    unsigned char rx_value, rx_sum;
    int have_last;
    unsigned char last_op, reply[32], reply_len;
    int active;                    /* 0x75 seen, no block 0 yet */
    int loaded;                    /* a 0x75 has been seen since the reset */
    unsigned entry, checksum, ptr, last_ptr, expect, last_block;
    int start_pending;             /* unlocked: start the firmware once the reply is out */
    unsigned image_end;            /* highest byte written, for the trace */
    unsigned char mem[ROM_IMAGE];
};

enum sim_mode { SIM_FIRMWARE, SIM_ROM, SIM_STANDBY };

struct sim;

struct sim_brick {
    struct rcx_brick k;            /* first: a hal call's struct rcx * is the start of this struct */
    struct sim *sim;
    int index;
    enum sim_mode mode;
    struct room_port port;         /* its IR LED and receiver */
    unsigned short raw[3];         /* A/D value of inputs 1-3 */
    unsigned battery_mv;
    long credit_us;                /* byte-code budget of the brick model */
    unsigned char buttons;         /* bit n: button n (enum rt_button) held down */
    unsigned long ir_in, ir_out;   /* IR bytes heard by its receiver and sent by its LED */
    /* Last state reported to the trace. */
    unsigned char motor[3], sensor_power[3], lcd[9], range;
    unsigned char world_motor[3];  /* the outputs at the last pose line of its robot (--world, sim_world.c) */
    int lcd_known;
    unsigned sound_hz;
    sim_us sound_start;
    struct sim_rom rom;
};

struct sim_event {                 /* one line of the --script file */
    sim_us at;
    int brick;
    enum { EV_SENSOR, EV_BUTTON, EV_BATTERY, EV_IR, EV_QUIT, EV_PLACE } kind;
    int a, b;
    double pose[3];                /* EV_PLACE: x, y (mm), heading (degrees) of robot (a = 1) or obstacle b */
    unsigned char bytes[256];
    int nbytes;
};

struct panel;
struct world;

struct sim {
    struct room room;              /* the IR room; its clock is the simulation's */
    int nbricks;
    struct sim_brick *brick[SIM_MAX_BRICKS];
    struct room_port script;       /* `ir` lines of the script: heard by every brick and tower */
    struct sim_event *events;
    int nevents, next_event;
    FILE *trace;
    double speed;                  /* x real time; 0 = as fast as possible */
    unsigned rate;                 /* byte codes per ms; 0 = the brick model */
    int quit;
    struct panel *panel;           /* the browser panel (--panel), or NULL */
    struct world *world;           /* the robots' world (--world), or NULL: owned here, swapped by sim_world_set */
};

/* rom.c */
void rom_reset(struct sim_brick *b);
void rom_byte(struct sim_brick *b, unsigned char byte, int error);
int rom_tick(struct sim_brick *b); /* 1: the image is unlocked and its reply out, the firmware starts now */

/* hal_sim.c */
extern const char *const sim_motor_dirs[4]; /* the trace's names of enum hal_motor_mode */

/* trace.c */
void trace_line(struct sim_brick *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void trace_lcd_number(const unsigned char *image, char *num, char *prog);
void trace_flush_sound(struct sim_brick *b);

/* script.c: the script's words, shared with the panel's requests so that both accept the same inputs. */
#define SIM_BUTTONS 4
#define SIM_BATTERY_MAX_MV 65535
extern const char *const sim_button_names[SIM_BUTTONS]; /* by enum rt_button */
int script_load(struct sim *s, const char *path);
int sim_word_index(const char *w, const char *const *list, int n);
int sim_parse_number(const char *w, long lo, long hi, long *out); /* decimal, within lo-hi; 0 = good */

/* sim_world.c: the world's hooks. Called once per simulated millisecond before the bricks step: outputs to the
 * world, one physics millisecond, A/D values back, poses into the trace. */
void sim_world_step(struct sim *s);
/* Replace the world (the panel's scene switch); the old one is freed. The bricks keep running. */
void sim_world_set(struct sim *s, struct world *w);
/* --world SCENE: a scene file, or the name of a shipped one; at least as many bricks as its robots need. 0 ok, else
 * one line on the standard error. */
int sim_world_open(struct sim *s, const char *scene);
void sim_world_place(struct sim *s, const struct sim_event *ev);

#define sim_brick_of(rcx) ((struct sim_brick *)(void *)(rcx))

#endif
