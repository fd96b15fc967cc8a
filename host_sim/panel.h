/* SPDX-License-Identifier: MPL-2.0 */
/*
 * rcxsim --panel: the bricks live in a browser. An embedded HTTP server (libmicrohttpd, in threads of its own)
 * serves the static page in host_sim/panel/, a JSON snapshot of every brick (GET /state), a stream of snapshots
 * as Server-Sent Events (GET /events), and takes inputs back (POST /button, /sensor, /battery). With --world it
 * also shows the world the robots drive in (GET /world..., panel_world.c) and takes drags, scene switches and floor
 * pictures back.
 *
 * Threads: only the simulation thread touches a brick. Once per simulated millisecond it calls panel_sync(), which
 * applies the inputs the HTTP threads queued and copies what the bricks show into the snapshot; the HTTP threads
 * read only that snapshot. One mutex guards the queue and the snapshot. The world's requests wait in a queue of
 * their own and are applied in panel_sync() too, on the simulation thread, as every world function must be.
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
/* The JSON of GET /state; returns its length, or 0 when it does not fit in `size`. `world`: rcxsim has one, the page
 * then asks for it (GET /world) and shows it. */
size_t panel_json(char *buf, size_t size, unsigned long long t_ms, const struct panel_brick *bricks, int n,
                  int world);

/* panel_files.c: the folder of the page's files (index.html, ...) */
const char *panel_files_dir(void);

/* panel_http.c */
#define PANEL_QUEUE 64            /* inputs waiting for the simulation thread */
struct panel;
struct panel *panel_start(struct sim *s, const char *bind_addr, unsigned port, char *err, size_t errlen);
/* Simulation thread, every simulated ms: takes the inputs the pages queued (at most PANEL_QUEUE) for the caller to
 * apply, then, with how many it applied, snapshots the bricks and answers the requests that wait for them. */
unsigned panel_take_inputs(struct panel *p, struct sim_event *ev);
void panel_sync(struct panel *p, struct sim *s, unsigned applied);
void panel_stop(struct panel *p);

/* panel_world_args.c: the checks of the world's requests, free of HTTP and of the simulation. */
#define PANEL_WORLD_MAX_OBSTACLES 256 /* obstacles beyond are drawn but cannot be dragged */
#define PANEL_SCENE_NAME_MAX 64
#define PANEL_SCENES_MAX 256      /* scenes listed by GET /world/scenes */
struct panel_world_limits {       /* what a request is checked against, from the scene's JSON */
    char scene[PANEL_SCENE_NAME_MAX + 1];
    double floor_w, floor_h;      /* mm */
    int robots, obstacles;
    unsigned char movable[PANEL_WORLD_MAX_OBSTACLES];
};
struct panel_place {              /* POST /world/place */
    int is_robot, index;
    double x, y, h;               /* mm from the floor's bottom-left, degrees counter-clockwise from +x, 0-360 */
};
int panel_world_limits_parse(const char *scene_json, struct panel_world_limits *lim); /* 0, or -1: no floor */
/* robot=N or obstacle=N, x, y (mm on the floor), h (degrees); 0, or -1 with a one-line reason in *why. */
int panel_place_parse(const char *robot, const char *obstacle, const char *x, const char *y, const char *h,
                      const struct panel_world_limits *lim, struct panel_place *out, const char **why);
int panel_scene_name_ok(const char *name); /* letters, digits, _ and -: it names <scenes dir>/<name>.json */
const char *panel_png_problem(const unsigned char *body, size_t len); /* NULL when it may be a PNG */
/* {"current":"<name>","scenes":["<name>",...]}: the *.json in `dir`, sorted; 0 when it does not fit. */
size_t panel_scene_list_json(const char *dir, const char *current, char *buf, size_t size);

#endif
