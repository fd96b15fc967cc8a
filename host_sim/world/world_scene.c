/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Scene files (JSON, read with cJSON; the format is in docs/world.md): the floor picture and its size, walls,
 * obstacles, and the robots with their start poses. Robots start from the built-in Roverbot-like preset, then take
 * the keys of a robot file ("file") and of their own entry. Anything wrong - a missing picture, a size out of range,
 * an unknown key, a robot off the floor - is refused with one line naming the file and the problem.
 */
#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "world_model.h"

#define SCENE_MAX_BYTES (1u << 20)
#define FLOOR_MAX_BYTES (16u << 20)
#define FLOOR_MAX_MM 20000.0

struct ctx {
    const char *path;              /* the file being read, for the message */
    char *err;
    size_t errlen;
};

static int bad(struct ctx *c, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static int bad(struct ctx *c, const char *fmt, ...)
{
    va_list ap;
    int n = snprintf(c->err, c->errlen, "%s: ", c->path);
    va_start(ap, fmt);
    if (n >= 0 && (size_t)n < c->errlen)
        vsnprintf(c->err + n, c->errlen - (size_t)n, fmt, ap);
    va_end(ap);
    return -1;
}

static unsigned char *read_all(const char *path, size_t max, size_t *len, char *why, size_t whylen)
{
    FILE *f = fopen(path, "rb");
    unsigned char *buf;
    size_t n;

    if (!f) {
        snprintf(why, whylen, "%s", strerror(errno));
        return NULL;
    }
    buf = malloc(max + 1);
    if (!buf)
        abort();
    n = fread(buf, 1, max + 1, f);
    fclose(f);
    if (n > max) {
        snprintf(why, whylen, "larger than %zu bytes", max);
        free(buf);
        return NULL;
    }
    *len = n;
    return buf;
}

static int known_keys(struct ctx *c, const cJSON *obj, const char *where, const char *const *keys)
{
    const cJSON *item;
    if (!cJSON_IsObject(obj))
        return bad(c, "%s: expected an object {...}", where);
    cJSON_ArrayForEach(item, obj) {
        const char *const *k;
        for (k = keys; *k && strcmp(*k, item->string); k++)
            ;
        if (!*k)
            return bad(c, "%s: unknown key \"%s\"", where, item->string);
    }
    return 0;
}

/* A number within lo-hi into *out; absent keeps *out unless `required`. */
static int number(struct ctx *c, const cJSON *obj, const char *key, const char *where, double lo, double hi,
                  int required, double *out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!v) {
        if (required)
            return bad(c, "%s: \"%s\" is missing", where, key);
        return 0;
    }
    if (!cJSON_IsNumber(v) || !(v->valuedouble >= lo && v->valuedouble <= hi))
        return bad(c, "%s: \"%s\" must be a number from %g to %g", where, key, lo, hi);
    *out = v->valuedouble;
    return 0;
}

static int boolean(struct ctx *c, const cJSON *obj, const char *key, const char *where, int *out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!v)
        return 0;
    if (!cJSON_IsBool(v))
        return bad(c, "%s: \"%s\" must be true or false", where, key);
    *out = cJSON_IsTrue(v);
    return 0;
}

static int string(struct ctx *c, const cJSON *obj, const char *key, const char *where, const char **out)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!v)
        return 0;
    if (!cJSON_IsString(v))
        return bad(c, "%s: \"%s\" must be a string", where, key);
    *out = v->valuestring;
    return 0;
}

static int pick(struct ctx *c, const cJSON *obj, const char *key, const char *where, const char *const *words,
                int *out)
{
    const char *s = NULL;
    int i;
    if (string(c, obj, key, where, &s))
        return -1;
    if (!s)
        return 0;
    for (i = 0; words[i]; i++)
        if (strcmp(s, words[i]) == 0) {
            *out = i;
            return 0;
        }
    return bad(c, "%s: \"%s\" cannot be \"%s\"", where, key, s);
}

static cJSON *parse_file(struct ctx *c, const char *path)
{
    char why[128];
    size_t len;
    unsigned char *text = read_all(path, SCENE_MAX_BYTES, &len, why, sizeof why);
    cJSON *root;

    if (!text) {
        bad(c, "cannot read it (%s)", why);
        return NULL;
    }
    root = cJSON_ParseWithLength((const char *)text, len);
    if (!root) {
        const char *at = cJSON_GetErrorPtr();
        size_t i, line = 1;
        for (i = 0; at && i < len && (const char *)text + i < at; i++)
            line += text[i] == '\n';
        bad(c, "not valid JSON (line %zu)", line);
    }
    free(text);
    return root;
}

/* The built-in robot: a Roverbot-like car (docs/world.md says where each figure comes from). */
static void roverbot(struct world_robot *r)
{
    memset(r, 0, sizeof *r);
    snprintf(r->name, sizeof r->name, "roverbot");
    r->w = 120;
    r->l = 160;
    r->mass = 0.55;
    r->wheel_d = 43.2;
    r->track = 112;
    r->rpm = 360;
    r->stall_nm = 0.06;
    r->mu = 0.8;
    r->drive_share = 0.8;
    r->rolling = 0.03;
    r->wheel[0] = (struct world_wheel){ .output = 0, .gear = 3 };
    r->wheel[1] = (struct world_wheel){ .output = 2, .gear = 3 };
    /* Two bumper bars, each across half the front and 14 mm ahead of it, pressing the touch sensors on 1 and 3. */
    r->sensor[0] = (struct world_sensor){ .kind = SENSOR_TOUCH, .x = 84, .y = 30, .r = 10, .w = 60 };
    r->sensor[1] = (struct world_sensor){ .kind = SENSOR_LIGHT, .x = 60, .y = 0, .r = 6 };
    r->sensor[2] = (struct world_sensor){ .kind = SENSOR_TOUCH, .x = 84, .y = -30, .r = 10, .w = 60 };
}

static const char *const outputs[] = { "A", "B", "C", NULL };
static const char *const sides[] = { "left", "right", NULL };
static const char *const kinds[] = { "none", "touch", "light", "rotation", NULL };

static int wheel(struct ctx *c, const cJSON *obj, const char *where, struct world_wheel *wh)
{
    static const char *const keys[] = { "output", "gear", "invert", NULL };
    if (known_keys(c, obj, where, keys) || pick(c, obj, "output", where, outputs, &wh->output) ||
        number(c, obj, "gear", where, 0.01, 100, 0, &wh->gear) || boolean(c, obj, "invert", where, &wh->invert))
        return -1;
    return 0;
}

static int sensors(struct ctx *c, const cJSON *list, const char *where, struct world_robot *r)
{
    static const char *const keys[] = { "input", "kind", "x", "y", "r", "w", "axle", "gear", NULL };
    const cJSON *s;
    char at[96];
    int i = 0;

    if (!cJSON_IsArray(list))
        return bad(c, "%s: \"sensors\" must be a list [...]", where);
    memset(r->sensor, 0, sizeof r->sensor);
    cJSON_ArrayForEach(s, list) {
        double input = 0;
        struct world_sensor v = { .r = 6, .gear = 1 };
        int kind = -1;
        snprintf(at, sizeof at, "%s.sensors[%d]", where, i++);
        if (known_keys(c, s, at, keys) || number(c, s, "input", at, 1, 3, 1, &input) ||
            pick(c, s, "kind", at, kinds, &kind) || number(c, s, "x", at, -500, 500, 0, &v.x) ||
            number(c, s, "y", at, -500, 500, 0, &v.y) || number(c, s, "r", at, 0.5, 100, 0, &v.r) ||
            number(c, s, "w", at, 0, 1000, 0, &v.w) ||
            pick(c, s, "axle", at, sides, &v.wheel) || number(c, s, "gear", at, 0.01, 100, 0, &v.gear))
            return -1;
        if (kind < 0)
            return bad(c, "%s: \"kind\" is missing (touch, light or rotation)", at);
        if (input != floor(input) || r->sensor[(int)input - 1].kind != SENSOR_NONE)
            return bad(c, "%s: input %g is not a free input 1-3", at, input);
        v.kind = (enum world_sensor_kind)kind;
        r->sensor[(int)input - 1] = v;
    }
    return 0;
}

/* Robot keys, from a robot file or a scene's entry. */
static int robot_keys(struct ctx *c, const cJSON *o, const char *where, struct world_robot *r, int in_scene)
{
    static const char *const scene_keys[] = { "name", "file", "brick", "x", "y", "heading", "w", "l", "mass",
                                              "wheel_d", "track", "axle_x", "motor", "mu", "left", "right",
                                              "sensors", NULL };
    static const char *const motor_keys[] = { "rpm", "stall_ncm", NULL };
    const cJSON *m;
    const char *name = NULL;
    double grams = r->mass * 1000, ncm = r->stall_nm * 100;
    char at[96];

    if (known_keys(c, o, where, scene_keys + (in_scene ? 0 : 6)) || string(c, o, "name", where, &name) ||
        number(c, o, "w", where, 20, 1000, 0, &r->w) || number(c, o, "l", where, 20, 1000, 0, &r->l) ||
        number(c, o, "mass", where, 10, 20000, 0, &grams) || number(c, o, "wheel_d", where, 5, 500, 0, &r->wheel_d) ||
        number(c, o, "track", where, 10, 1000, 0, &r->track) ||
        number(c, o, "axle_x", where, -500, 500, 0, &r->axle_x) || number(c, o, "mu", where, 0.01, 3, 0, &r->mu))
        return -1;
    if (name)
        snprintf(r->name, sizeof r->name, "%s", name);
    r->mass = grams / 1000;
    if ((m = cJSON_GetObjectItemCaseSensitive(o, "motor"))) {
        snprintf(at, sizeof at, "%s.motor", where);
        if (known_keys(c, m, at, motor_keys) || number(c, m, "rpm", at, 1, 100000, 0, &r->rpm) ||
            number(c, m, "stall_ncm", at, 0.01, 10000, 0, &ncm))
            return -1;
        r->stall_nm = ncm / 100;
    }
    if ((m = cJSON_GetObjectItemCaseSensitive(o, "left"))) {
        snprintf(at, sizeof at, "%s.left", where);
        if (wheel(c, m, at, &r->wheel[0]))
            return -1;
    }
    if ((m = cJSON_GetObjectItemCaseSensitive(o, "right"))) {
        snprintf(at, sizeof at, "%s.right", where);
        if (wheel(c, m, at, &r->wheel[1]))
            return -1;
    }
    if ((m = cJSON_GetObjectItemCaseSensitive(o, "sensors")) && sensors(c, m, where, r))
        return -1;
    return 0;
}

static void dir_of(const char *path, char *dir, size_t size)
{
    const char *slash = strrchr(path, '/');
    if (slash)
        snprintf(dir, size, "%.*s/", (int)(slash - path), path);
    else
        dir[0] = 0;
}

static int robot(struct ctx *c, struct world *w, const cJSON *o, int i, const char *dir)
{
    struct world_robot *r = &w->robot[i];
    const char *file = NULL;
    double brick = i;
    char where[32];

    snprintf(where, sizeof where, "robots[%d]", i);
    roverbot(r);
    if (!cJSON_IsObject(o))
        return bad(c, "%s: expected an object {...}", where);
    if (string(c, o, "file", where, &file))
        return -1;
    if (file) {
        char path[4096], label[4096 + 128];
        struct ctx fc = { label, c->err, c->errlen };
        cJSON *root;
        int status;
        snprintf(path, sizeof path, "%s%s", file[0] == '/' ? "" : dir, file);
        snprintf(label, sizeof label, "%s: %s: robot file %s", c->path, where, path); /* both files named */
        if (!(root = parse_file(&fc, path)))
            return -1;
        status = robot_keys(&fc, root, "its keys", r, 0);
        cJSON_Delete(root);
        if (status)
            return -1;
    }
    if (robot_keys(c, o, where, r, 1) || number(c, o, "brick", where, 0, WORLD_MAX_ROBOTS - 1, 0, &brick) ||
        number(c, o, "x", where, -1e9, 1e9, 1, &r->x0) || number(c, o, "y", where, -1e9, 1e9, 1, &r->y0) ||
        number(c, o, "heading", where, -3600, 3600, 0, &r->h0))
        return -1;
    if (brick != floor(brick))
        return bad(c, "%s: \"brick\" must be a whole number 0-%d", where, WORLD_MAX_ROBOTS - 1);
    r->brick = (int)brick;
    if (r->x0 < 0 || r->y0 < 0 || r->x0 > w->floor.w_mm || r->y0 > w->floor.h_mm)
        return bad(c, "%s: start (%g, %g) is outside the %g x %g mm floor", where, r->x0, r->y0, w->floor.w_mm,
                   w->floor.h_mm);
    if (r->track >= r->w + 60 || r->wheel_d > 4 * r->l)
        return bad(c, "%s: wheels that do not fit the chassis (track %g, width %g)", where, r->track, r->w);
    return 0;
}

static int obstacle(struct ctx *c, struct world *w, const cJSON *o, int i)
{
    static const char *const keys[] = { "shape", "x", "y", "heading", "w", "h", "r", "color", "mass", "movable",
                                        NULL };
    static const char *const shapes[] = { "box", "circle", NULL };
    struct world_obstacle *b = &w->obstacle[i];
    const char *color = NULL;
    double grams = 200;
    char where[32];

    snprintf(where, sizeof where, "obstacles[%d]", i);
    b->w = b->h = 100;
    b->r = 50;
    b->color = 0x8B5A2B;
    if (known_keys(c, o, where, keys) || pick(c, o, "shape", where, shapes, &b->circle) ||
        number(c, o, "x", where, 0, w->floor.w_mm, 1, &b->start[0]) ||
        number(c, o, "y", where, 0, w->floor.h_mm, 1, &b->start[1]) ||
        number(c, o, "heading", where, -3600, 3600, 0, &b->start[2]) ||
        number(c, o, "w", where, 1, FLOOR_MAX_MM, 0, &b->w) || number(c, o, "h", where, 1, FLOOR_MAX_MM, 0, &b->h) ||
        number(c, o, "r", where, 1, FLOOR_MAX_MM, 0, &b->r) || number(c, o, "mass", where, 1, 1e6, 0, &grams) ||
        boolean(c, o, "movable", where, &b->movable) || string(c, o, "color", where, &color))
        return -1;
    if (color) {
        char *end;
        unsigned long v = strtoul(color + 1, &end, 16);
        if (color[0] != '#' || strlen(color) != 7 || *end)
            return bad(c, "%s: \"color\" must be #rrggbb", where);
        b->color = (unsigned)v;
    }
    b->mass = grams / 1000;
    return 0;
}

static int wall(struct ctx *c, struct world *w, const cJSON *o, int i)
{
    static const char *const keys[] = { "x1", "y1", "x2", "y2", "t", NULL };
    struct world_wall *l = &w->wall[i];
    char where[32];

    snprintf(where, sizeof where, "walls[%d]", i);
    l->t = 20;
    if (known_keys(c, o, where, keys) || number(c, o, "x1", where, -1000, w->floor.w_mm + 1000, 1, &l->x1) ||
        number(c, o, "y1", where, -1000, w->floor.h_mm + 1000, 1, &l->y1) ||
        number(c, o, "x2", where, -1000, w->floor.w_mm + 1000, 1, &l->x2) ||
        number(c, o, "y2", where, -1000, w->floor.h_mm + 1000, 1, &l->y2) ||
        number(c, o, "t", where, 1, 1000, 0, &l->t))
        return -1;
    return 0;
}

/* A list's items through `one`, at most `max`. */
static int list(struct ctx *c, struct world *w, const cJSON *root, const char *key, int max, int *n,
                int (*one)(struct ctx *, struct world *, const cJSON *, int))
{
    const cJSON *items = cJSON_GetObjectItemCaseSensitive(root, key), *o;
    if (!items)
        return 0;
    if (!cJSON_IsArray(items))
        return bad(c, "\"%s\" must be a list [...]", key);
    if (cJSON_GetArraySize(items) > max)
        return bad(c, "\"%s\": more than %d", key, max);
    cJSON_ArrayForEach(o, items) {
        if (one(c, w, o, *n))
            return -1;
        ++*n;
    }
    return 0;
}

static int scene_floor(struct ctx *c, struct world *w, const cJSON *root, const char *dir)
{
    static const char *const keys[] = { "image", "w", "h", NULL };
    const cJSON *f = cJSON_GetObjectItemCaseSensitive(root, "floor");
    const char *image = NULL;
    char path[4096], why[256];
    unsigned char *png;
    size_t len;
    int status;

    if (!f)
        return bad(c, "\"floor\" is missing");
    if (known_keys(c, f, "floor", keys) || number(c, f, "w", "floor", 100, FLOOR_MAX_MM, 1, &w->floor.w_mm) ||
        number(c, f, "h", "floor", 100, FLOOR_MAX_MM, 1, &w->floor.h_mm) || string(c, f, "image", "floor", &image))
        return -1;
    if (!image)
        return bad(c, "floor: \"image\" is missing");
    snprintf(path, sizeof path, "%s%s", image[0] == '/' ? "" : dir, image);
    if (!(png = read_all(path, FLOOR_MAX_BYTES, &len, why, sizeof why)))
        return bad(c, "floor image %s: %s", path, why);
    status = floor_decode(&w->floor, png, len, why, sizeof why);
    free(png);
    if (status)
        return bad(c, "floor image %s: %s", path, why);
    return 0;
}

static int light(struct ctx *c, struct world *w, const cJSON *root)
{
    static const char *const keys[] = { "white", "black", "noise", "seed", NULL };
    const cJSON *l = cJSON_GetObjectItemCaseSensitive(root, "light");
    double white = 711, black = 817, noise = 0, seed = 1;

    if (l && (known_keys(c, l, "light", keys) || number(c, l, "white", "light", 0, 1023, 0, &white) ||
              number(c, l, "black", "light", 0, 1023, 0, &black) || number(c, l, "noise", "light", 0, 200, 0, &noise) ||
              number(c, l, "seed", "light", 0, 4294967295.0, 0, &seed)))
        return -1;
    w->light_white = (int)white;
    w->light_black = (int)black;
    w->light_noise = (int)noise;
    w->seed = (unsigned long long)seed;
    w->rng = w->seed * 0x9E3779B97F4A7C15ull + 1; /* never 0: xorshift stays at 0 */
    return 0;
}

static int scene(struct ctx *c, struct world *w, const cJSON *root, const char *dir)
{
    static const char *const keys[] = { "name", "floor", "walls", "obstacles", "robots", "light", NULL };
    const char *name = NULL;
    int i, j;

    if (known_keys(c, root, "the scene", keys) || string(c, root, "name", "the scene", &name) ||
        scene_floor(c, w, root, dir) || light(c, w, root) ||
        list(c, w, root, "walls", WORLD_MAX_WALLS, &w->nwalls, wall) ||
        list(c, w, root, "obstacles", WORLD_MAX_OBSTACLES, &w->nobstacles, obstacle))
        return -1;
    snprintf(w->name, sizeof w->name, "%s", name ? name : "scene");
    {
        const cJSON *items = cJSON_GetObjectItemCaseSensitive(root, "robots"), *o;
        if (!cJSON_IsArray(items) || cJSON_GetArraySize(items) < 1)
            return bad(c, "\"robots\" must be a list of 1 to %d robots", WORLD_MAX_ROBOTS);
        if (cJSON_GetArraySize(items) > WORLD_MAX_ROBOTS)
            return bad(c, "\"robots\": more than %d", WORLD_MAX_ROBOTS);
        cJSON_ArrayForEach(o, items) {
            if (robot(c, w, o, w->nrobots, dir))
                return -1;
            w->nrobots++;
        }
    }
    for (i = 0; i < w->nrobots; i++)
        for (j = 0; j < i; j++)
            if (w->robot[i].brick == w->robot[j].brick)
                return bad(c, "robots[%d] and robots[%d] are both brick %d", j, i, w->robot[i].brick);
    return 0;
}

struct world *world_load(const char *path, char *err, size_t errlen)
{
    struct ctx c = { path, err, errlen };
    struct world *w;
    cJSON *root;
    char dir[4096];

    if (!(root = parse_file(&c, path)))
        return NULL;
    w = calloc(1, sizeof *w);
    if (!w)
        abort();
    dir_of(path, dir, sizeof dir);
    if (scene(&c, w, root, dir)) {
        cJSON_Delete(root);
        floor_free(&w->floor);
        free(w);
        return NULL;
    }
    cJSON_Delete(root);
    world_build(w);
    return w;
}

/* cpSpaceFree() leaves the bodies, shapes and constraints: collect them first, free them after. */
struct parts {
    void *item[4 * (WORLD_MAX_ROBOTS * 5 + WORLD_MAX_OBSTACLES * 4 + WORLD_MAX_WALLS)];
    void (*free_item[4 * (WORLD_MAX_ROBOTS * 5 + WORLD_MAX_OBSTACLES * 4 + WORLD_MAX_WALLS)])(void *);
    int n;
};

static void keep(struct parts *p, void *item, void (*free_item)(void *))
{
    int i;
    for (i = 0; i < p->n; i++)
        if (p->item[i] == item)
            return; /* a static body may be listed by the space as well */
    if (p->n < (int)(sizeof p->item / sizeof p->item[0])) {
        p->item[p->n] = item;
        p->free_item[p->n++] = free_item;
    }
}

static void free_shape(void *s) { cpShapeFree(s); }
static void free_body(void *b) { cpBodyFree(b); }
static void free_constraint(void *c) { cpConstraintFree(c); }
static void each_shape(cpShape *s, void *p) { keep(p, s, free_shape); }
static void each_body(cpBody *b, void *p) { keep(p, b, free_body); }
static void each_constraint(cpConstraint *c, void *p) { keep(p, c, free_constraint); }

void world_free(struct world *w)
{
    struct parts *p;
    int i;

    if (!w)
        return;
    p = calloc(1, sizeof *p);
    if (!p)
        abort();
    /* A sleeping body's constraints are out of the space's lists until it wakes: wake them all first. */
    for (i = 0; i < w->nrobots; i++)
        cpBodyActivate(w->robot[i].body);
    for (i = 0; i < w->nobstacles; i++)
        if (cpBodyGetType(w->obstacle[i].body) == CP_BODY_TYPE_DYNAMIC)
            cpBodyActivate(w->obstacle[i].body);
    cpSpaceEachShape(w->space, each_shape, p);
    cpSpaceEachConstraint(w->space, each_constraint, p);
    cpSpaceEachBody(w->space, each_body, p); /* the dynamic ones, and the static obstacles' */
    for (i = 0; i < w->nobstacles; i++)
        if (cpBodyGetType(w->obstacle[i].body) == CP_BODY_TYPE_STATIC)
            keep(p, w->obstacle[i].body, free_body);
    cpSpaceFree(w->space);
    for (i = 0; i < p->n; i++)
        p->free_item[i](p->item[i]);
    free(p);
    floor_free(&w->floor);
    free(w);
}
