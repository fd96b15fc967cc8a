/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The world's millisecond: the motors' PWM as the RCX gives it, a LEGO 9 V motor's straight speed/torque line
 * through the gearing to a tyre with friction, one 1 ms step of Chipmunk2D (collisions with walls, obstacles and
 * other robots), then the sensors' A/D values. docs/world.md gives the model and its sources.
 */
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>
#include "world_model.h"

#define STEP_S 0.001
#define NM 1e6                     /* N m in kg mm^2 / s^2 */

/* RCX power 0-7: which of 8 ms the output is on, rotated one bit per ms; off ms float (rcx-hardware.md §3.2). */
static const unsigned char pwm_pattern[8] = { 0x01, 0x11, 0x49, 0x55, 0x6D, 0x77, 0x7F, 0xFF };

/* Touch sensor: a switch to ground (pressed, a few tens of raw through the rubber contact) or open (pull-up, 1023). */
#define TOUCH_PRESSED_RAW 50
#define OPEN_RAW 1023
/* Rotation sensor: the four levels of its 16 steps a turn (about 5.1, 3.8, 1.8 and 2.6 V on the 5 V A/D), in the
 * order the firmware counts up (vm/sensors.c: phase 0 960-1023, 1 768-959, 2 320-511, 3 512-767). */
static const unsigned short rotation_raw[4] = { 1023, 777, 368, 532 };


void robot_set_pose(struct world *w, struct world_robot *r, double x, double y, double h_deg)
{
    cpBodySetPosition(r->body, cpv(x, y));
    cpBodySetAngle(r->body, h_deg * M_PI / 180.0);
    cpBodySetVelocity(r->body, cpvzero);
    cpBodySetAngularVelocity(r->body, 0);
    cpSpaceReindexShapesForBody(w->space, r->body);
}

/* Where a touch sensor feels, in the robot's frame: its bumper bar (w across, 2 r deep) or its disc's square. */
static cpBB touch_area(const struct world_sensor *s)
{
    double half = s->w > 0 ? s->w / 2 : s->r;
    return cpBBNew(s->x - s->r, s->y - half, s->x + s->r, s->y + half);
}

static void add_robot(struct world *w, int i)
{
    struct world_robot *r = &w->robot[i];
    cpShapeFilter own = cpShapeFilterNew((cpGroup)(i + 1), CP_ALL_CATEGORIES, CP_ALL_CATEGORIES);
    int k;

    /* One shape: the chassis and its bumpers, which are solid - a bumper presses its switch by touching something. A
     * touch sensor is pressed while a contact point of the shape lies in its area (touch_area). */
    cpBB hull = cpBBNew(-r->l / 2, -r->w / 2, r->l / 2, r->w / 2);

    for (k = 0; k < 2; k++) {
        r->wheel[k].v0 = r->rpm * 2 * M_PI / 60 / r->wheel[k].gear * r->wheel_d / 2;  /* mm/s */
        r->wheel[k].f_stall = r->stall_nm * NM * r->wheel[k].gear / (r->wheel_d / 2); /* kg mm/s^2 */
    }
    r->grip = r->mu * r->mass * WORLD_G * r->drive_share / 2;
    r->roll = r->rolling * r->mass * WORLD_G / 2;

    for (k = 0; k < WORLD_MAX_SENSORS; k++)
        if (r->sensor[k].kind == SENSOR_TOUCH)
            hull = cpBBMerge(hull, touch_area(&r->sensor[k]));
    r->body = cpSpaceAddBody(w->space, cpBodyNew(r->mass, cpMomentForBox(r->mass, r->l, r->w)));
    r->chassis = cpSpaceAddShape(w->space, cpBoxShapeNew2(r->body, hull, 0));
    cpShapeSetFriction(r->chassis, 0.5);
    cpShapeSetFilter(r->chassis, own);
    robot_set_pose(w, r, r->x0, r->y0, r->h0);
}

/* A movable obstacle slides on the floor: a pivot and a gear joint to the static body that push back with at most
 * its sliding friction (Chipmunk's top-down friction idiom). */
static void add_obstacle(struct world *w, struct world_obstacle *o, double x, double y, double h_deg)
{
    const double mu = 0.4;
    cpBody *ground = cpSpaceGetStaticBody(w->space);

    if (o->movable) {
        double moment = o->circle ? cpMomentForCircle(o->mass, 0, o->r, cpvzero) : cpMomentForBox(o->mass, o->w, o->h);
        cpConstraint *c;
        o->body = cpSpaceAddBody(w->space, cpBodyNew(o->mass, moment));
        c = cpSpaceAddConstraint(w->space, cpPivotJointNew2(ground, o->body, cpvzero, cpvzero));
        cpConstraintSetMaxBias(c, 0);
        cpConstraintSetMaxForce(c, mu * o->mass * WORLD_G);
        c = cpSpaceAddConstraint(w->space, cpGearJointNew(ground, o->body, 0, 1));
        cpConstraintSetMaxBias(c, 0);
        cpConstraintSetMaxForce(c, mu * o->mass * WORLD_G * (o->circle ? o->r : (o->w + o->h) / 4) / 2);
    } else {
        o->body = cpSpaceAddBody(w->space, cpBodyNewStatic());
    }
    o->shape = cpSpaceAddShape(w->space, o->circle ? cpCircleShapeNew(o->body, o->r, cpvzero)
                                                   : cpBoxShapeNew(o->body, o->w, o->h, 0));
    cpShapeSetFriction(o->shape, 0.5);
    cpBodySetPosition(o->body, cpv(x, y));
    cpBodySetAngle(o->body, h_deg * M_PI / 180.0);
    cpSpaceReindexShapesForBody(w->space, o->body);
}

/* Debian's Chipmunk is built in debug mode and prints a banner on the standard output when the first space is made.
 * The standard output may be the trace (--trace -): make that first space with it pointed at /dev/null. */
static void quiet_first_space(void)
{
    static int done;
    int saved, null;

    if (done)
        return;
    done = 1;
    fflush(stdout);
    saved = dup(STDOUT_FILENO);
    null = open("/dev/null", O_WRONLY);
    if (saved >= 0 && null >= 0)
        dup2(null, STDOUT_FILENO);
    cpSpaceFree(cpSpaceNew());
    fflush(stdout);
    if (saved >= 0 && null >= 0)
        dup2(saved, STDOUT_FILENO);
    if (saved >= 0)
        close(saved);
    if (null >= 0)
        close(null);
}

void world_build(struct world *w)
{
    int i;

    quiet_first_space();
    w->space = cpSpaceNew();
    /* What has been still for half a second (below 1 mm/s) sleeps until something touches or drives it: obstacles
     * nobody pushes cost no constraint solving. */
    cpSpaceSetSleepTimeThreshold(w->space, 0.5);
    cpSpaceSetIdleSpeedThreshold(w->space, 1.0);
    cpSpaceSetIterations(w->space, 10);
    for (i = 0; i < w->nwalls; i++) {
        struct world_wall *l = &w->wall[i];
        cpShape *s = cpSegmentShapeNew(cpSpaceGetStaticBody(w->space), cpv(l->x1, l->y1), cpv(l->x2, l->y2), l->t / 2);
        cpShapeSetFriction(cpSpaceAddShape(w->space, s), 0.5);
    }
    for (i = 0; i < w->nobstacles; i++) {
        struct world_obstacle *o = &w->obstacle[i];
        add_obstacle(w, o, o->start[0], o->start[1], o->start[2]);
    }
    for (i = 0; i < w->nrobots; i++)
        add_robot(w, i);
}

/* The chassis this ms: its pose and speed, and the impulses of the tyres added up (applied once, after). The chassis'
 * centre is its centre of gravity. */
struct chassis {
    cpVect pos, rot, v;
    double w, m, moment;
    cpVect dv;                     /* impulse / mass */
    double dw;                     /* angular impulse / moment */
};

static cpVect point(const struct chassis *c, double x, double y) /* robot frame to floor */
{
    return cpvadd(c->pos, cpvrotate(cpv(x, y), c->rot));
}

static cpVect speed_at(const struct chassis *c, cpVect p)
{
    return cpvadd(c->v, cpvmult(cpvperp(cpvsub(p, c->pos)), c->w));
}

static void kick(struct chassis *c, cpVect j, cpVect p)
{
    c->dv = cpvadd(c->dv, cpvmult(j, 1.0 / c->m));
    c->dw += cpvcross(cpvsub(p, c->pos), j) / c->moment;
}

/* One wheel's push on the chassis this ms, and how far the wheel turns (it slips when the push would exceed the
 * tyre's grip). Motor line: torque = stall * (u - speed / no-load speed), u = +-1 while driven, 0 braked (the
 * windings shorted); floating, the wheel rolls free. */
static void drive_wheel(struct world *w, struct world_robot *r, struct chassis *c, int side, unsigned char motor)
{
    struct world_wheel *wh = &r->wheel[side];
    double radius = r->wheel_d / 2, v0 = wh->v0, f_stall = wh->f_stall, grip = r->grip;
    cpVect p = point(c, r->axle_x, side ? -r->track / 2 : r->track / 2);
    double v = cpvdot(speed_at(c, p), c->rot), spin = v, f = 0;
    unsigned mode = motor >> 3 & 3u, level = motor & 7u;
    int on = (mode == 1 || mode == 2) && (pwm_pattern[level] >> (w->ms & 7) & 1);
    double u = (mode == 2 ? 1.0 : -1.0) * (wh->invert ? -1 : 1);

    if (on || mode == 3) {
        if (!on)
            u = 0;
        f = f_stall * (u - v / v0);
        if (fabs(f) > grip) {
            f = f > 0 ? grip : -grip;
            spin = v0 * (u - f / f_stall);
        }
    }
    /* Rolling resistance, never more than stops the wheel's share of the robot. */
    {
        double roll = r->roll * STEP_S, stop = fabs(v) * r->mass / 2;
        double j = roll < stop ? roll : stop;
        f -= (v > 0 ? j : v < 0 ? -j : 0) / STEP_S;
    }
    kick(c, cpvmult(c->rot, f * STEP_S), p);
    wh->angle += spin / radius * STEP_S;
}

/* The tyres do not slide sideways while their grip holds: cancel the axle's sideways speed, within the grip. */
static void hold_sideways(struct world_robot *r, struct chassis *c)
{
    cpVect left = cpvperp(c->rot), p = point(c, r->axle_x, 0);
    double v = cpvdot(speed_at(c, p), left), arm = cpvcross(cpvsub(p, c->pos), left);
    double m_eff = 1.0 / (1.0 / c->m + arm * arm / c->moment);
    double j = -v * m_eff, most = r->mu * r->mass * WORLD_G * r->drive_share * STEP_S;

    if (j > most)
        j = most;
    if (j < -most)
        j = -most;
    kick(c, cpvmult(left, j), p);
}

static void drive(struct world *w, struct world_robot *r, const struct world_brick_io *io)
{
    struct chassis c;
    int k;

    /* A sleeping robot whose motors neither drive nor brake stays where it is; one driven wakes up. */
    if (cpBodyIsSleeping(r->body)) {
        int driven = 0;
        for (k = 0; k < 2 && io; k++)
            driven |= (io->motor[r->wheel[k].output] >> 3 & 3u) != 0;
        if (!driven)
            return;
        cpBodyActivate(r->body);
    }
    c.pos = cpBodyGetPosition(r->body);
    c.rot = cpBodyGetRotation(r->body);
    c.v = cpBodyGetVelocity(r->body);
    c.w = cpBodyGetAngularVelocity(r->body);
    c.m = r->mass;
    c.moment = cpBodyGetMoment(r->body);
    c.dv = cpvzero;
    c.dw = 0;
    for (k = 0; k < 2; k++)
        drive_wheel(w, r, &c, k, io ? io->motor[r->wheel[k].output] : 0);
    hold_sideways(r, &c);
    /* As impulses: a push through the centre and a couple (Debian's Chipmunk checks the whole body on every set
     * velocity call, which costs more than these three). */
    {
        cpVect x = cpv(1, 0);
        double a = c.dw * c.moment / 2;
        cpBodyApplyImpulseAtWorldPoint(r->body, cpvmult(c.dv, c.m), c.pos);
        cpBodyApplyImpulseAtWorldPoint(r->body, cpv(0, a), cpvadd(c.pos, x));
        cpBodyApplyImpulseAtWorldPoint(r->body, cpv(0, -a), cpvsub(c.pos, x));
    }
}

/* xorshift64*: the light sensor's seeded noise, the same every run of the same scene. */
static unsigned next_random(struct world *w)
{
    w->rng ^= w->rng >> 12;
    w->rng ^= w->rng << 25;
    w->rng ^= w->rng >> 27;
    return (unsigned)((w->rng * 2685821657736338717ull) >> 33);
}

static unsigned short sensor_raw(struct world *w, struct world_robot *r, const struct world_sensor *s, int powered)
{
    switch (s->kind) {
    case SENSOR_TOUCH:
        return s->pressed ? TOUCH_PRESSED_RAW : OPEN_RAW;
    case SENSOR_LIGHT: {
        cpVect p = cpBodyLocalToWorld(r->body, cpv(s->x, s->y));
        double b = floor_brightness(&w->floor, p.x, p.y, s->r);
        long raw = (long)floor(w->light_black + (w->light_white - w->light_black) * b + 0.5);
        if (!powered)
            return OPEN_RAW;       /* its photo-transistor has no supply: nothing pulls the input down */
        if (w->light_noise)
            raw += (long)(next_random(w) % (2u * (unsigned)w->light_noise + 1)) - w->light_noise;
        return (unsigned short)(raw < 0 ? 0 : raw > 1023 ? 1023 : raw);
    }
    case SENSOR_ROTATION: {
        double steps = floor(r->wheel[s->wheel].angle * s->gear * 16 / (2 * M_PI));
        return rotation_raw[(long long)steps & 3];
    }
    default:
        return OPEN_RAW;
    }
}

/* Each contact of the robot's shape (the body's shape comes first) presses the touch sensors whose area it is in,
 * give or take Chipmunk's contact slop. */
static void press(cpBody *body, cpArbiter *arb, void *data)
{
    struct world_robot *r = data;
    cpContactPointSet set = cpArbiterGetContactPointSet(arb);
    int i, k;

    for (i = 0; i < set.count; i++) {
        cpVect p = cpBodyWorldToLocal(body, set.points[i].pointA);
        for (k = 0; k < WORLD_MAX_SENSORS; k++) {
            struct world_sensor *s = &r->sensor[k];
            cpBB area = touch_area(s);
            if (s->kind == SENSOR_TOUCH && p.x >= area.l - 1 && p.x <= area.r + 1 && p.y >= area.b - 1 &&
                p.y <= area.t + 1)
                s->pressed = 1;
        }
    }
}

void world_step(struct world *w, struct world_brick_io *io, int nbricks)
{
    int i, k;

    for (i = 0; i < w->nrobots; i++) {
        struct world_robot *r = &w->robot[i];
        drive(w, r, r->brick < nbricks ? &io[r->brick] : NULL);
    }
    cpSpaceStep(w->space, STEP_S);
    w->ms++;
    for (i = 0; i < w->nrobots; i++) {
        struct world_robot *r = &w->robot[i];
        for (k = 0; k < WORLD_MAX_SENSORS; k++)
            r->sensor[k].pressed = 0;
        cpBodyEachArbiter(r->body, press, r);
        for (k = 0; k < WORLD_MAX_SENSORS; k++) {
            int powered = r->brick < nbricks && io[r->brick].sensor_power[k];
            r->raw[k] = sensor_raw(w, r, &r->sensor[k], powered);
            if (r->brick < nbricks)
                io[r->brick].raw[k] = r->raw[k];
        }
    }
}

unsigned long long world_ms(const struct world *w)
{
    return w->ms;
}

int world_robots(const struct world *w)
{
    return w->nrobots;
}

int world_robot_brick(const struct world *w, int robot)
{
    return robot >= 0 && robot < w->nrobots ? w->robot[robot].brick : -1;
}

int world_place(struct world *w, int is_robot, int index, double x, double y, double h)
{
    if (!(x >= 0 && y >= 0 && x <= w->floor.w_mm && y <= w->floor.h_mm) || !isfinite(h))
        return -1;
    if (is_robot) {
        if (index < 0 || index >= w->nrobots)
            return -1;
        robot_set_pose(w, &w->robot[index], x, y, h);
        return 0;
    }
    if (index < 0 || index >= w->nobstacles)
        return -1;
    cpBodySetPosition(w->obstacle[index].body, cpv(x, y));
    cpBodySetAngle(w->obstacle[index].body, h * M_PI / 180.0);
    if (cpBodyGetType(w->obstacle[index].body) == CP_BODY_TYPE_DYNAMIC) {
        cpBodySetVelocity(w->obstacle[index].body, cpvzero);
        cpBodySetAngularVelocity(w->obstacle[index].body, 0);
    }
    cpSpaceReindexShapesForBody(w->space, w->obstacle[index].body);
    return 0;
}
