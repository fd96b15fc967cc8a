/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Inside the world: what a scene holds once loaded (world_scene.c), the floor picture (world_floor.c), and the
 * per-millisecond physics and sensors (world_step.c). Units inside: mm, kg, s (so a force is kg mm/s^2 = mN).
 */
#ifndef RCX_WORLD_MODEL_H
#define RCX_WORLD_MODEL_H

#include <chipmunk/chipmunk.h>
#include "world.h"

#define WORLD_MAX_OBSTACLES 64
#define WORLD_MAX_WALLS 128
#define WORLD_MAX_SENSORS 3
#define WORLD_G 9810.0             /* mm/s^2 */
#define WORLD_NAME 64

enum world_sensor_kind { SENSOR_NONE, SENSOR_TOUCH, SENSOR_LIGHT, SENSOR_ROTATION };

/* The floor picture: grey levels for the light sensors, the PNG bytes as given for the panel. */
struct world_floor {
    double w_mm, h_mm;
    unsigned px_w, px_h;
    unsigned char *grey;           /* px_w * px_h, row 0 at the top of the picture (the floor's far edge, y = h) */
    unsigned long long *sum;       /* (px_w + 1) * (px_h + 1): sums of grey above and left, for fast spot means */
    unsigned char *png;
    size_t png_len;
    unsigned version;
};

struct world_sensor {
    enum world_sensor_kind kind;
    double x, y, r;                /* robot frame, mm; r: light spot radius, or touch reach (half the bar's depth) */
    double w;                      /* touch: the bumper bar's width across the robot (0: a disc of radius r) */
    int wheel;                     /* rotation: 0 left, 1 right axle */
    double gear;                   /* rotation: sensor turns per wheel turn */
    int pressed;                   /* touch: something touches its area (this ms) */
};

struct world_wheel {
    int output;                    /* 0-2: A-C */
    double gear;                   /* motor turns per wheel turn */
    int invert;                    /* 1: the motor's "fwd" drives this wheel backwards */
    double angle;                  /* radians turned, forwards positive */
    double v0, f_stall;            /* from the motor and gearing (world_build): tyre speed at no load, push at stall */
};

struct world_robot {
    char name[WORLD_NAME];
    int brick;
    double w, l, mass, wheel_d, track, axle_x;
    double rpm, stall_nm;          /* the motors' no-load speed and stall torque at full voltage */
    double mu, drive_share, rolling;  /* tyre friction, weight share on the driven wheels, rolling resistance */
    struct world_wheel wheel[2];   /* left, right */
    struct world_sensor sensor[WORLD_MAX_SENSORS]; /* by input 1-3 */
    double x0, y0, h0;             /* the scene's start pose */
    double grip, roll;             /* per wheel, from mass and friction (world_build): most push; rolling resistance */
    cpBody *body;
    cpShape *chassis;
    unsigned short raw[3];
};

struct world_obstacle {
    int circle;
    double w, h, r, mass;
    int movable;
    unsigned color;                /* 0xRRGGBB */
    double start[3];                  /* the scene's pose: x, y, heading in degrees */
    cpBody *body;
    cpShape *shape;
};

struct world_wall {
    double x1, y1, x2, y2, t;
};

struct world {
    char name[WORLD_NAME];
    struct world_floor floor;
    int nwalls, nobstacles, nrobots;
    struct world_wall wall[WORLD_MAX_WALLS];
    struct world_obstacle obstacle[WORLD_MAX_OBSTACLES];
    struct world_robot robot[WORLD_MAX_ROBOTS];
    int light_white, light_black, light_noise; /* raw values of white and black floor; noise amplitude, raw */
    unsigned long long seed, rng;
    unsigned long long ms;
    cpSpace *space;
};

/* world_floor.c */
int floor_decode(struct world_floor *f, const unsigned char *png, size_t len, char *err, size_t errlen);
void floor_free(struct world_floor *f);
double floor_brightness(const struct world_floor *f, double x, double y, double r); /* 0 black - 1 white */

/* world_step.c */
void world_build(struct world *w);  /* the Chipmunk space from the scene */
void robot_set_pose(struct world *w, struct world_robot *r, double x, double y, double h_deg);

#endif
