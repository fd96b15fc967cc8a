/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The world's requests (rcxsim --world), on the panel's HTTP threads:
 *   GET  /world                the scene: floor size, walls, obstacles, robots and their sensors (JSON)
 *   GET  /world/pose           where the robots and obstacles are now, and what the robots' inputs read (JSON)
 *   GET  /world/floor.png      the floor picture
 *   GET  /world/events         Server-Sent Events: "scene" events with the scene when it changes, poses otherwise
 *   GET  /world/scenes         {"current": name, "scenes": [names]}: the scenes a page may switch to
 *   POST /world/place?robot=N|obstacle=N&x=mm&y=mm&h=deg   puts a robot or a movable obstacle there
 *   POST /world/scene?name=NAME                            switches to another scene
 *   POST /world/floor          (body: a PNG file, at most PANEL_FLOOR_MAX bytes) a new floor picture
 * The requests are checked here (panel_world_args.c) and applied by the simulation thread (panel_world.c); each is
 * answered 204 once applied, 4xx with a one-line reason when it is refused, 202 if still queued after WAIT_S.
 * Without --world every /world path answers 404.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "panel_server.h"

#define WAIT_S 5                  /* a scene loads its floor picture: give it longer than an input */
#define SCENES_JSON_MAX 32768

/* A copy of one of the world's texts, made under the lock. */
static enum MHD_Result send_copy(struct panel *p, struct MHD_Connection *c, const void *data, size_t len,
                                 const char *type, const char *missing)
{
    void *copy = len ? malloc(len) : NULL;

    if (len && !copy) {
        pthread_mutex_unlock(&p->lock);
        return MHD_NO;
    }
    if (len)
        memcpy(copy, data, len);
    pthread_mutex_unlock(&p->lock);
    if (!len)
        return panel_refuse(c, MHD_HTTP_NOT_FOUND, missing);
    return panel_send_buffer(c, copy, len, type, "no-cache");
}

static enum MHD_Result get(struct panel *p, struct MHD_Connection *c, const char *url)
{
    struct panel_world *pw = &p->world;
    char *json;
    size_t len;

    if (strcmp(url, "/world/events") == 0)
        return panel_send_stream(p, c, 1);
    if (strcmp(url, "/world/scenes") == 0) {
        json = malloc(SCENES_JSON_MAX);
        if (!json)
            return MHD_NO;
        pthread_mutex_lock(&p->lock);
        len = panel_scene_list_json(pw->scenes_dir, pw->current, json, SCENES_JSON_MAX);
        pthread_mutex_unlock(&p->lock);
        if (!len) {
            free(json);
            return panel_refuse(c, MHD_HTTP_INTERNAL_SERVER_ERROR, "too many scenes to list");
        }
        return panel_send_buffer(c, json, len, "application/json", "no-store");
    }
    pthread_mutex_lock(&p->lock);
    if (strcmp(url, "/world") == 0)
        return send_copy(p, c, pw->scene, pw->scene_len, "application/json", "the world did not write its scene");
    if (strcmp(url, "/world/pose") == 0)
        return send_copy(p, c, pw->pose, pw->pose_len, "application/json", "the world did not write its poses");
    if (strcmp(url, "/world/floor.png") == 0)
        return send_copy(p, c, pw->floor, pw->floor_len, "image/png", "this scene has no floor picture");
    pthread_mutex_unlock(&p->lock);
    return panel_refuse(c, MHD_HTTP_NOT_FOUND, "no such page under /world");
}

/* Queued for the simulation thread; the answer once it has been applied. */
static enum MHD_Result submit(struct panel *p, struct MHD_Connection *c, struct world_request *r)
{
    struct panel_world *pw = &p->world;
    struct timespec until;
    unsigned status;
    char why[sizeof r->why];

    pthread_mutex_lock(&p->lock);
    if (p->closing) {
        pthread_mutex_unlock(&p->lock);
        free(r->png);
        free(r);
        return panel_refuse(c, MHD_HTTP_SERVICE_UNAVAILABLE, "the simulation is stopping");
    }
    *pw->tail = r;
    pw->tail = &r->next;
    clock_gettime(CLOCK_REALTIME, &until);
    until.tv_sec += WAIT_S;
    while (!p->closing && !r->done)
        if (pthread_cond_timedwait(&p->changed, &p->lock, &until) == ETIMEDOUT)
            break;
    if (!r->done) {
        r->abandoned = 1; /* the simulation thread (or panel_stop) frees it */
        pthread_mutex_unlock(&p->lock);
        return panel_send_text(c, MHD_HTTP_ACCEPTED, "text/plain", "");
    }
    pthread_mutex_unlock(&p->lock);
    status = r->status;
    memcpy(why, r->why, sizeof why);
    free(r->png);
    free(r);
    if (status == MHD_HTTP_NO_CONTENT)
        return panel_send_text(c, status, "text/plain", "");
    return panel_refuse(c, status, why);
}

static struct world_request *new_request(int kind)
{
    struct world_request *r = calloc(1, sizeof *r);
    if (!r)
        abort();
    r->kind = kind;
    return r;
}

static enum MHD_Result post(struct panel *p, struct MHD_Connection *c, const char *url, const unsigned char *body,
                            size_t body_len)
{
    static const char *const place_args[] = { "robot", "obstacle", "x", "y", "h", NULL };
    static const char *const scene_args[] = { "name", NULL };
    static const char *const no_args[] = { NULL };
    struct panel_world_limits lim;
    struct world_request *r;
    const char *why, *name;
    char path[sizeof p->world.scenes_dir + PANEL_SCENE_NAME_MAX + 8];

    if (strcmp(url, "/world/place") == 0) {
        struct panel_place place;
        pthread_mutex_lock(&p->lock);
        lim = p->world.lim;
        pthread_mutex_unlock(&p->lock);
        if (panel_place_parse(panel_arg(c, "robot"), panel_arg(c, "obstacle"), panel_arg(c, "x"), panel_arg(c, "y"),
                              panel_arg(c, "h"), &lim, &place, &why))
            return panel_refuse(c, MHD_HTTP_BAD_REQUEST, why);
        if (panel_query_only(c, place_args))
            return panel_refuse(c, MHD_HTTP_BAD_REQUEST, "unknown, empty or repeated parameter");
        r = new_request(WORLD_PLACE);
        r->place = place;
        return submit(p, c, r);
    }
    if (strcmp(url, "/world/scene") == 0) {
        name = panel_arg(c, "name");
        if (!panel_scene_name_ok(name) || panel_query_only(c, scene_args))
            return panel_refuse(c, MHD_HTTP_BAD_REQUEST, "name: expected a scene's name (GET /world/scenes)");
        snprintf(path, sizeof path, "%s/%s.json", p->world.scenes_dir, name);
        if (access(path, R_OK) != 0)
            return panel_refuse(c, MHD_HTTP_NOT_FOUND, "name: no such scene (GET /world/scenes lists them)");
        r = new_request(WORLD_SCENE);
        strcpy(r->scene, name);
        return submit(p, c, r);
    }
    if (strcmp(url, "/world/floor") == 0) {
        if (panel_query_only(c, no_args))
            return panel_refuse(c, MHD_HTTP_BAD_REQUEST, "no parameters here: the picture is the body");
        if ((why = panel_png_problem(body, body_len)) != NULL)
            return panel_refuse(c, MHD_HTTP_BAD_REQUEST, why);
        r = new_request(WORLD_FLOOR);
        r->png = malloc(body_len);
        if (!r->png)
            abort();
        memcpy(r->png, body, body_len);
        r->png_len = body_len;
        return submit(p, c, r);
    }
    return panel_refuse(c, MHD_HTTP_NOT_FOUND, "no such page under /world");
}

enum MHD_Result panel_world_route(struct panel *p, struct MHD_Connection *c, const char *url, int is_get,
                                  int is_post, const unsigned char *body, size_t body_len)
{
    int writes = strcmp(url, "/world/place") == 0 || strcmp(url, "/world/scene") == 0 ||
                 strcmp(url, "/world/floor") == 0;

    if (!p->world.on)
        return panel_refuse(c, MHD_HTTP_NOT_FOUND, "no world: rcxsim runs without --world");
    if (writes && !is_post)
        return panel_refuse(c, MHD_HTTP_METHOD_NOT_ALLOWED, "only POST here");
    if (!writes && !is_get)
        return panel_refuse(c, MHD_HTTP_METHOD_NOT_ALLOWED, "only GET here");
    return writes ? post(p, c, url, body, body_len) : get(p, c, url);
}
