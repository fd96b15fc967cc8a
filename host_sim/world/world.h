/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The world: simulated robots on a floor, with walls and obstacles (Chipmunk2D), a floor picture (PNG) under the
 * light sensors, loaded from a scene file (JSON). It plugs in beside the IR room: each simulated millisecond it reads
 * every brick's outputs (direction, power level) and writes its inputs' A/D values. It knows nothing of the VM.
 *
 * Coordinates: millimetres, origin at the floor's bottom-left corner, x right, y up; heading in degrees
 * counter-clockwise from +x. Robot frame (sensor positions): x forward, y left, mm from the chassis centre.
 *
 * Every function is called on the simulation thread only. See docs/world.md for the physics and the scene format.
 */
#ifndef RCX_WORLD_H
#define RCX_WORLD_H

#include <stddef.h>

#define WORLD_MAX_ROBOTS 8

struct world;

/* What the world sees of one brick each millisecond: its outputs in, its inputs' A/D values out. */
struct world_brick_io {
    unsigned char motor[3];        /* per output: mode << 3 | level, mode as enum hal_motor_mode (0 float, 1 rev,
                                      2 fwd, 3 brake), level 0-7 */
    unsigned char sensor_power[3]; /* 1: the input is powered (active sensor: light, rotation) */
    unsigned short raw[3];         /* written by the world: A/D value 0-1023 of inputs 1-3 */
};

/* Load a scene file (also used by the panel to switch scenes: the sim swaps worlds); NULL + err on failure. err gets
 * one line naming the file and the problem. */
struct world *world_load(const char *path, char *err, size_t errlen);
void world_free(struct world *w);

/* How many robots the scene has (the bricks it needs), and which brick drives robot i. */
int world_robots(const struct world *w);
int world_robot_brick(const struct world *w, int robot);

/* One simulated millisecond: `io[b]` is brick b (nbricks of them); the world reads the motors of every brick that
 * drives a robot, advances its physics by 1 ms, and writes raw[] of those bricks. */
void world_step(struct world *w, struct world_brick_io *io, int nbricks);
unsigned long long world_ms(const struct world *w); /* simulated milliseconds stepped since the load */

/* JSON of the static scene, 0 if it does not fit:
 * {"scene":"<name>","floor":{"w":W,"h":H,"version":N},"walls":[{"x1","y1","x2","y2","t"}],
 *  "obstacles":[{"i","shape":"box","w","h","color":"#rrggbb","movable"} or {"i","shape":"circle","r",...}],
 *  "robots":[{"i","brick","name","w","l","wheel_d","track","sensors":[{"input","kind","x","y"}]}]} */
size_t world_scene_json(const struct world *w, char *buf, size_t size);
/* JSON of what moves, 0 if it does not fit:
 * {"t":ms,"robots":[{"i","x","y","h","inputs":[raw1,raw2,raw3]}],"obstacles":[{"i","x","y","h"}]} */
size_t world_pose_json(const struct world *w, char *buf, size_t size);

/* The floor picture as PNG bytes (kept by the world); 0 ok. */
int world_floor_png(const struct world *w, const unsigned char **png, size_t *len);
/* Replace the floor picture (same size in mm); 0 ok, else err filled. */
int world_set_floor_png(struct world *w, const unsigned char *png, size_t len, char *err, size_t errlen);

/* Move robot/obstacle `index` (is_robot 1/0) to a pose; 0 ok, -1 bad index or outside the floor. */
int world_place(struct world *w, int is_robot, int index, double x_mm, double y_mm, double heading_deg);

/* Robot i's pose as JSON members for the trace, "robot":i,"x":..,"y":..,"h":.. (no braces); 0 if it does not fit. */
size_t world_robot_pose(const struct world *w, int i, char *buf, size_t size);

/* The folder of the shipped scenes, found like panel_files_dir(). */
const char *world_scenes_dir(void);

#endif
