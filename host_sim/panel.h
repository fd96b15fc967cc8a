/* SPDX-License-Identifier: MPL-2.0 */
/*
 * rcxsim --panel: the bricks live in a browser. An embedded HTTP server (libmicrohttpd, in threads of its own)
 * serves the static page in host_sim/panel/, a JSON snapshot of every brick (GET /state), a stream of snapshots
 * as Server-Sent Events (GET /events), and takes inputs back (POST /button, /sensor, /battery).
 *
 * Threads: only the simulation thread touches a brick. Once per simulated millisecond it calls panel_sync(), which
 * applies the inputs the HTTP threads queued and copies what the bricks show into the snapshot; the HTTP threads
 * read only that snapshot. One mutex guards the queue and the snapshot.
 */
#ifndef RCX_PANEL_H
#define RCX_PANEL_H

#include <stddef.h>
#include "sim.h"

/* What a page shows of one brick, copied on the simulation thread (panel_state.c). */
struct panel_brick {
    unsigned char mode;            /* enum sim_mode */
    unsigned char motor[3];        /* enum hal_motor_mode << 3 | level, as hal_motor() last set it */
    unsigned char lcd[9];          /* the glass: the firmware's segment image, blank in standby and ROM mode */
    unsigned char sensor_type[3], sensor_mode[3], sensor_power[3], sensor_bool[3];
    short sensor_value[3];         /* source 9, as the program reads it */
    unsigned short raw[3];         /* what the inputs' A/D converter reads */
    unsigned short tasks;          /* bit n: task n runs or waits */
    unsigned char buttons;         /* bit n: button n held (enum rt_button) */
    unsigned char slot;            /* selected program slot 1-5 */
    unsigned char range;           /* 0 short, 1 long, 0xFF never set */
    unsigned battery_mv, sound_hz;
    unsigned long ir_in, ir_out;
};

/* panel_state.c */
void panel_snapshot(const struct sim_brick *b, struct panel_brick *out);
/* The JSON of GET /state; returns its length, or 0 when it does not fit in `size`. */
size_t panel_json(char *buf, size_t size, unsigned long long t_ms, const struct panel_brick *bricks, int n);

/* panel_files.c: the folder of the page's files (index.html, ...) */
const char *panel_files_dir(void);

/* panel_http.c */
#define PANEL_QUEUE 64            /* inputs waiting for the simulation thread */
struct panel;
struct panel *panel_start(struct sim *s, const char *bind_addr, unsigned port, char *err, size_t errlen);
/* Simulation thread, every simulated ms: takes the inputs the pages queued (at most PANEL_QUEUE) for the caller to
 * apply, then, with how many it applied, snapshots the bricks and answers the requests that wait for them. */
unsigned panel_take_inputs(struct panel *p, struct sim_event *ev);
void panel_sync(struct panel *p, const struct sim *s, unsigned applied);
void panel_stop(struct panel *p);

#endif
