/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The world as JSON for the panel (shapes in world.h): the static scene once, and what moves as often as it likes.
 * Also the floor picture's bytes and its replacement. Numbers are printed rounded (0.1 mm, 0.1 degree).
 */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include "world_model.h"

struct out {
    char *buf;
    size_t size, n;
    int full;
};

static void put(struct out *o, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void put(struct out *o, const char *fmt, ...)
{
    va_list ap;
    int k;
    if (o->full)
        return;
    va_start(ap, fmt);
    k = vsnprintf(o->buf + o->n, o->size - o->n, fmt, ap);
    va_end(ap);
    if (k < 0 || (size_t)k >= o->size - o->n)
        o->full = 1;
    else
        o->n += (size_t)k;
}

static size_t done(struct out *o)
{
    return o->full ? 0 : o->n;
}

/* A JSON string's body: the scene's names are the user's, so quotes and control characters are escaped. */
static void put_text(struct out *o, const char *s)
{
    for (; *s; s++) {
        unsigned char ch = (unsigned char)*s;
        if (ch == '"' || ch == '\\')
            put(o, "\\%c", ch);
        else if (ch < 0x20)
            put(o, "\\u%04x", ch);
        else
            put(o, "%c", ch);
    }
}

/* Degrees counter-clockwise from +x, in [0, 360). */
static double heading_deg(cpBody *b)
{
    double d = fmod(cpBodyGetAngle(b) * 180.0 / M_PI, 360.0);
    return d < 0 ? d + 360.0 : d;
}

size_t world_scene_json(const struct world *w, char *buf, size_t size)
{
    static const char *const kind[] = { "none", "touch", "light", "rotation" };
    struct out o = { buf, size, 0, size == 0 };
    int i, k;

    put(&o, "{\"scene\":\"");
    put_text(&o, w->name);
    put(&o, "\",\"floor\":{\"w\":%g,\"h\":%g,\"version\":%u},\"walls\":[", w->floor.w_mm, w->floor.h_mm,
        w->floor.version);
    for (i = 0; i < w->nwalls; i++)
        put(&o, "%s{\"x1\":%g,\"y1\":%g,\"x2\":%g,\"y2\":%g,\"t\":%g}", i ? "," : "", w->wall[i].x1, w->wall[i].y1,
            w->wall[i].x2, w->wall[i].y2, w->wall[i].t);
    put(&o, "],\"obstacles\":[");
    for (i = 0; i < w->nobstacles; i++) {
        const struct world_obstacle *b = &w->obstacle[i];
        if (b->circle)
            put(&o, "%s{\"i\":%d,\"shape\":\"circle\",\"r\":%g", i ? "," : "", i, b->r);
        else
            put(&o, "%s{\"i\":%d,\"shape\":\"box\",\"w\":%g,\"h\":%g", i ? "," : "", i, b->w, b->h);
        put(&o, ",\"color\":\"#%06x\",\"movable\":%s}", b->color, b->movable ? "true" : "false");
    }
    put(&o, "],\"robots\":[");
    for (i = 0; i < w->nrobots; i++) {
        const struct world_robot *r = &w->robot[i];
        int first = 1;
        put(&o, "%s{\"i\":%d,\"brick\":%d,\"name\":\"", i ? "," : "", i, r->brick);
        put_text(&o, r->name);
        put(&o, "\",\"w\":%g,\"l\":%g,\"wheel_d\":%g,\"track\":%g,\"sensors\":[", r->w, r->l, r->wheel_d, r->track);
        for (k = 0; k < WORLD_MAX_SENSORS; k++) {
            const struct world_sensor *s = &r->sensor[k];
            double x = s->x, y = s->y;
            if (s->kind == SENSOR_NONE)
                continue;
            if (s->kind == SENSOR_ROTATION) { /* drawn on its wheel's axle */
                x = r->axle_x;
                y = s->wheel ? -r->track / 2 : r->track / 2;
            }
            put(&o, "%s{\"input\":%d,\"kind\":\"%s\",\"x\":%g,\"y\":%g}", first ? "" : ",", k + 1, kind[s->kind], x, y);
            first = 0;
        }
        put(&o, "]}");
    }
    put(&o, "]}");
    return done(&o);
}

size_t world_pose_json(const struct world *w, char *buf, size_t size)
{
    struct out o = { buf, size, 0, size == 0 };
    int i;

    put(&o, "{\"t\":%llu,\"robots\":[", w->ms);
    for (i = 0; i < w->nrobots; i++) {
        const struct world_robot *r = &w->robot[i];
        cpVect p = cpBodyGetPosition(r->body);
        put(&o, "%s{\"i\":%d,\"x\":%.1f,\"y\":%.1f,\"h\":%.1f,\"inputs\":[%u,%u,%u]}", i ? "," : "", i, p.x, p.y,
            heading_deg(r->body), r->raw[0], r->raw[1], r->raw[2]);
    }
    put(&o, "],\"obstacles\":[");
    for (i = 0; i < w->nobstacles; i++) {
        cpVect p = cpBodyGetPosition(w->obstacle[i].body);
        put(&o, "%s{\"i\":%d,\"x\":%.1f,\"y\":%.1f,\"h\":%.1f}", i ? "," : "", i, p.x, p.y,
            heading_deg(w->obstacle[i].body));
    }
    put(&o, "]}");
    return done(&o);
}

int world_floor_png(const struct world *w, const unsigned char **png, size_t *len)
{
    if (!w->floor.png)
        return -1;
    *png = w->floor.png;
    *len = w->floor.png_len;
    return 0;
}

int world_set_floor_png(struct world *w, const unsigned char *png, size_t len, char *err, size_t errlen)
{
    return floor_decode(&w->floor, png, len, err, errlen);
}

/* One robot's pose for the trace: {"robot":i,"x":..,"y":..,"h":..}, without braces. */
size_t world_robot_pose(const struct world *w, int i, char *buf, size_t size)
{
    struct out o = { buf, size, 0, size == 0 };
    cpVect p;
    if (i < 0 || i >= w->nrobots)
        return 0;
    p = cpBodyGetPosition(w->robot[i].body);
    put(&o, "\"robot\":%d,\"x\":%.1f,\"y\":%.1f,\"h\":%.1f", i, p.x, p.y, heading_deg(w->robot[i].body));
    return done(&o);
}
