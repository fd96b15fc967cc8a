/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The checks of the panel's world requests, kept free of HTTP and of the simulation so that the unit tests see them
 * whole (tests/panel/test_world_args.c): a place (robot or obstacle, position, heading), a scene's name and the
 * list of scenes, a floor picture's first bytes, and what the HTTP threads must know of the scene to check them
 * (read from the scene's JSON with cJSON on the simulation thread).
 */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <cjson/cJSON.h>
#include "panel.h"

/* A decimal number as a person types it: digits, one point, a sign and an exponent; no hex, inf or nan. */
static int parse_decimal(const char *w, double lo, double hi, double *out)
{
    char *end;
    double v;

    if (!w || !*w || strspn(w, "+-0123456789.eE") != strlen(w))
        return -1;
    v = strtod(w, &end);
    if (*end || !isfinite(v) || v < lo || v > hi)
        return -1;
    *out = v;
    return 0;
}

int panel_place_parse(const char *robot, const char *obstacle, const char *x, const char *y, const char *h,
                      const struct panel_world_limits *lim, struct panel_place *out, const char **why)
{
    const char *which = robot ? robot : obstacle;
    long n = robot ? lim->robots : lim->obstacles, v;

    if (!robot == !obstacle) {
        *why = "expected robot=N or obstacle=N (one of them)";
        return -1;
    }
    if (sim_parse_number(which, 0, n - 1, &v)) {
        *why = robot ? "robot: no such robot in this scene" : "obstacle: no such obstacle in this scene";
        return -1;
    }
    if (obstacle && (v >= PANEL_WORLD_MAX_OBSTACLES || !lim->movable[v])) {
        *why = "obstacle: this one is fixed to the floor";
        return -1;
    }
    out->is_robot = robot != NULL;
    out->index = (int)v;
    if (parse_decimal(x, 0, lim->floor_w, &out->x) || parse_decimal(y, 0, lim->floor_h, &out->y)) {
        *why = "x, y: expected millimetres on the floor (0 to its width, 0 to its height)";
        return -1;
    }
    if (parse_decimal(h, -36000, 36000, &out->h)) {
        *why = "h: expected a heading in degrees";
        return -1;
    }
    out->h = fmod(out->h, 360.0);
    if (out->h < 0)
        out->h += 360.0;
    return 0;
}

int panel_scene_name_ok(const char *name)
{
    size_t n = name ? strlen(name) : 0;
    return n >= 1 && n <= PANEL_SCENE_NAME_MAX && name[0] != '-' &&
           strspn(name, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") == n;
}

const char *panel_png_problem(const unsigned char *body, size_t len)
{
    static const unsigned char signature[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n' };

    if (len == 0)
        return "no picture: send the PNG file as the request's body";
    if (len < sizeof signature || memcmp(body, signature, sizeof signature) != 0)
        return "not a PNG file (it must start with the PNG signature)";
    return NULL;
}

static int by_name(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

size_t panel_scene_list_json(const char *dir, const char *current, char *buf, size_t size)
{
    DIR *d = dir ? opendir(dir) : NULL;
    struct dirent *e;
    char *names[PANEL_SCENES_MAX];
    size_t n = 0, len = 0, i;
    int w;

    while (d && n < PANEL_SCENES_MAX && (e = readdir(d)) != NULL) {
        size_t l = strlen(e->d_name);
        if (l > 5 && strcmp(e->d_name + l - 5, ".json") == 0 && (names[n] = strndup(e->d_name, l - 5)) != NULL) {
            if (panel_scene_name_ok(names[n]))
                n++;
            else
                free(names[n]);
        }
    }
    if (d)
        closedir(d);
    qsort(names, n, sizeof names[0], by_name);
    w = snprintf(buf, size, "{\"current\":\"%s\",\"scenes\":[", panel_scene_name_ok(current) ? current : "");
    len = w < 0 ? size : (size_t)w;
    for (i = 0; i < n; i++) {
        if (len < size) {
            w = snprintf(buf + len, size - len, "%s\"%s\"", i ? "," : "", names[i]);
            len = w < 0 ? size : len + (size_t)w;
        }
        free(names[i]);
    }
    if (len < size) {
        w = snprintf(buf + len, size - len, "]}");
        len = w < 0 ? size : len + (size_t)w;
    }
    return len < size ? len : 0;
}

static double number_of(const cJSON *o, const char *key)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
    return cJSON_IsNumber(v) ? v->valuedouble : 0;
}

int panel_world_limits_parse(const char *scene_json, struct panel_world_limits *lim)
{
    cJSON *root = cJSON_Parse(scene_json), *floor, *robots, *obstacles, *o;
    const cJSON *name;
    int i = 0;

    memset(lim, 0, sizeof *lim);
    if (!root)
        return -1;
    name = cJSON_GetObjectItemCaseSensitive(root, "scene");
    if (cJSON_IsString(name) && panel_scene_name_ok(name->valuestring))
        strcpy(lim->scene, name->valuestring);
    floor = cJSON_GetObjectItemCaseSensitive(root, "floor");
    lim->floor_w = number_of(floor, "w");
    lim->floor_h = number_of(floor, "h");
    robots = cJSON_GetObjectItemCaseSensitive(root, "robots");
    obstacles = cJSON_GetObjectItemCaseSensitive(root, "obstacles");
    lim->robots = cJSON_IsArray(robots) ? cJSON_GetArraySize(robots) : 0;
    lim->obstacles = cJSON_IsArray(obstacles) ? cJSON_GetArraySize(obstacles) : 0;
    cJSON_ArrayForEach(o, obstacles) {
        if (i < PANEL_WORLD_MAX_OBSTACLES)
            lim->movable[i] = cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(o, "movable"));
        i++;
    }
    cJSON_Delete(root);
    return lim->floor_w > 0 && lim->floor_h > 0 ? 0 : -1;
}
