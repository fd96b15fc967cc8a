/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The world's hooks in the virtual RCX (--world): each simulated millisecond, before the bricks step, the world
 * gets every brick's outputs and sensor power, advances 1 ms, and gives back the A/D values the bricks then sample.
 * Robots' poses go into the trace every SIM_WORLD_TRACE_MS and whenever their brick's outputs change.
 */
#include <stdlib.h>
#include <string.h>
#include "sim.h"
#include "world/world.h"

#define SIM_WORLD_TRACE_MS 100

static void trace_poses(struct sim *s, int changed_only, const int *changed)
{
    int i;
    for (i = 0; i < world_robots(s->world); i++) {
        int b = world_robot_brick(s->world, i);
        char pose[128];
        if (b >= s->nbricks || (changed_only && !changed[b]))
            continue;
        if (world_robot_pose(s->world, i, pose, sizeof pose))
            trace_line(s->brick[b], "%s", pose);
    }
}

void sim_world_step(struct sim *s)
{
    struct world_brick_io io[SIM_MAX_BRICKS];
    int changed[SIM_MAX_BRICKS] = { 0 }, any = 0, i, k;

    if (!s->world)
        return;
    for (i = 0; i < s->nbricks; i++) {
        struct sim_brick *b = s->brick[i];
        for (k = 0; k < 3; k++) {
            /* 0xFF: nothing driven since power-on, the outputs float */
            io[i].motor[k] = b->mode == SIM_FIRMWARE && b->motor[k] != 0xFF ? b->motor[k] : 0;
            io[i].sensor_power[k] = b->mode == SIM_FIRMWARE && b->sensor_power[k];
            io[i].raw[k] = b->raw[k];
        }
        if (memcmp(b->world_motor, io[i].motor, 3)) {
            memcpy(b->world_motor, io[i].motor, 3);
            changed[i] = any = 1;
        }
    }
    if (s->trace && (any || s->room.now / 1000 % SIM_WORLD_TRACE_MS == 0))
        trace_poses(s, s->room.now / 1000 % SIM_WORLD_TRACE_MS != 0, changed); /* and where it was at the change */
    world_step(s->world, io, s->nbricks);
    for (i = 0; i < s->nbricks; i++)
        memcpy(s->brick[i]->raw, io[i].raw, sizeof io[i].raw);
}

void sim_world_set(struct sim *s, struct world *w)
{
    int i;

    world_free(s->world);
    s->world = w;
    for (i = 0; i < s->nbricks; i++)
        memset(s->brick[i]->world_motor, 0, sizeof s->brick[i]->world_motor);
}

int sim_world_open(struct sim *s, const char *scene)
{
    char err[512], path[4096];
    int i;

    /* A bare name (no '/', no .json) is a shipped scene. */
    if (!strchr(scene, '/') && !strstr(scene, ".json"))
        snprintf(path, sizeof path, "%s/%s.json", world_scenes_dir(), scene);
    else
        snprintf(path, sizeof path, "%s", scene);
    s->world = world_load(path, err, sizeof err);
    if (!s->world) {
        fprintf(stderr, "rcxsim: --world %s\n", err);
        return -1;
    }
    for (i = 0; i < world_robots(s->world); i++)
        if (world_robot_brick(s->world, i) >= s->nbricks)
            s->nbricks = world_robot_brick(s->world, i) + 1;
    return 0;
}

/* A script's `place` line: a pose off the floor or a robot or obstacle the scene has not is said, and skipped. */
void sim_world_place(struct sim *s, const struct sim_event *ev)
{
    if (world_place(s->world, ev->a, ev->b, ev->pose[0], ev->pose[1], ev->pose[2]))
        fprintf(stderr, "rcxsim: --script: at %llu ms: no %s %d, or (%g, %g) is off the floor\n", ev->at / 1000,
                ev->a ? "robot" : "obstacle", ev->b, ev->pose[0], ev->pose[1]);
    else if (s->trace && ev->a && world_robot_brick(s->world, ev->b) < s->nbricks) {
        char pose[128];
        if (world_robot_pose(s->world, ev->b, pose, sizeof pose))
            trace_line(s->brick[world_robot_brick(s->world, ev->b)], "%s,\"placed\":true", pose);
    }
}
