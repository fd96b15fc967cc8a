/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The panel's side of the world (rcxsim --world), on the simulation thread: in panel_sync() it applies the requests
 * the pages queued (drag a robot or an obstacle, switch the scene, a new floor picture) and copies what the pages
 * draw: the scene (floor, walls, obstacles, robots and their sensors) whenever it may have changed, the poses at most
 * every POSE_GAP_MS of wall time (the page interpolates between them, so more would only cost the simulation).
 * The HTTP threads read only these copies (panel_world_http.c).
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "panel_server.h"
#include "world/world.h"

#define POSE_GAP_MS 20            /* poses copied at most 50 times a (wall) second */
#define JSON_FIRST_TRY 8192

/* A JSON text from the world, in a buffer that grows until it fits; newlines made spaces (one line per event). */
static char *world_text(const struct world *w, size_t (*make)(const struct world *, char *, size_t), size_t *len)
{
    size_t size = JSON_FIRST_TRY, n, i;
    char *buf = NULL, *more;

    for (;;) {
        more = realloc(buf, size);
        if (!more)
            abort();
        buf = more;
        n = make(w, buf, size);
        if (n)
            break;
        if (size >= (64u << 20)) {
            free(buf);
            *len = 0;
            return NULL;
        }
        size *= 2;
    }
    for (i = 0; i < n; i++)
        if (buf[i] == '\n' || buf[i] == '\r')
            buf[i] = ' ';
    *len = n;
    return buf;
}

static long ms_since(const struct timespec *then, const struct timespec *now)
{
    return (long)(now->tv_sec - then->tv_sec) * 1000 + (now->tv_nsec - then->tv_nsec) / 1000000;
}

/* The scene again (and the floor picture with it); under the lock only for the swap. */
static void copy_scene(struct panel *p, const struct world *w)
{
    struct panel_world *pw = &p->world;
    struct panel_world_limits lim;
    const unsigned char *png = NULL;
    unsigned char *floor = NULL;
    size_t len, png_len = 0;
    char *scene = world_text(w, world_scene_json, &len);
    int same;

    if (!scene)
        return;
    pthread_mutex_lock(&p->lock);
    same = pw->scene && pw->scene_len == len && memcmp(pw->scene, scene, len) == 0;
    pthread_mutex_unlock(&p->lock);
    if (same) {
        free(scene);
        return;
    }
    panel_world_limits_parse(scene, &lim);
    if (world_floor_png(w, &png, &png_len) == 0 && png && png_len) {
        floor = malloc(png_len);
        if (!floor)
            abort();
        memcpy(floor, png, png_len);
    }
    pthread_mutex_lock(&p->lock);
    free(pw->scene);
    free(pw->floor);
    pw->scene = scene;
    pw->scene_len = len;
    pw->floor = floor;
    pw->floor_len = floor ? png_len : 0;
    pw->lim = lim;
    pw->scene_version++;
    pw->version++;
    pthread_cond_broadcast(&p->changed);
    pthread_mutex_unlock(&p->lock);
}

static void copy_poses(struct panel *p, const struct world *w)
{
    struct panel_world *pw = &p->world;
    size_t len;
    char *pose = world_text(w, world_pose_json, &len);

    if (!pose)
        return;
    pthread_mutex_lock(&p->lock);
    if (pw->pose && pw->pose_len == len && memcmp(pw->pose, pose, len) == 0) {
        pthread_mutex_unlock(&p->lock);
        free(pose);
        return;
    }
    free(pw->pose);
    pw->pose = pose;
    pw->pose_len = len;
    pw->version++;
    pthread_cond_broadcast(&p->changed);
    pthread_mutex_unlock(&p->lock);
}

/* Another scene: the world is loaded anew from <scenes dir>/<name>.json, the old one goes only if that worked. */
static void switch_scene(struct panel *p, struct sim *s, struct world_request *r)
{
    char path[sizeof p->world.scenes_dir + PANEL_SCENE_NAME_MAX + 8], err[200];
    struct world *w;
    int i;

    snprintf(path, sizeof path, "%s/%s.json", p->world.scenes_dir, r->scene);
    w = world_load(path, err, sizeof err);
    if (!w) {
        r->status = MHD_HTTP_UNPROCESSABLE_CONTENT;
        snprintf(r->why, sizeof r->why, "scene %s: %s", r->scene, err);
        return;
    }
    for (i = 0; i < world_robots(w); i++)
        if (world_robot_brick(w, i) >= s->nbricks) {
            r->status = MHD_HTTP_CONFLICT;
            snprintf(r->why, sizeof r->why, "scene %s: robot %d needs brick %d, rcxsim runs %d (--bricks)", r->scene,
                     i, world_robot_brick(w, i), s->nbricks);
            world_free(w);
            return;
        }
    sim_world_set(s, w);
    pthread_mutex_lock(&p->lock);
    strcpy(p->world.current, r->scene);
    pthread_mutex_unlock(&p->lock);
    r->status = MHD_HTTP_NO_CONTENT;
}

static void apply(struct panel *p, struct sim *s, struct world_request *r)
{
    char err[200] = "";

    switch (r->kind) {
    case WORLD_PLACE:
        if (world_place(s->world, r->place.is_robot, r->place.index, r->place.x, r->place.y, r->place.h)) {
            r->status = MHD_HTTP_UNPROCESSABLE_CONTENT;
            snprintf(r->why, sizeof r->why, "the world cannot put %s %d there", r->place.is_robot ? "robot" :
                     "obstacle", r->place.index);
        } else {
            r->status = MHD_HTTP_NO_CONTENT;
        }
        break;
    case WORLD_SCENE:
        switch_scene(p, s, r);
        break;
    case WORLD_FLOOR:
        if (world_set_floor_png(s->world, r->png, r->png_len, err, sizeof err)) {
            r->status = MHD_HTTP_UNPROCESSABLE_CONTENT;
            snprintf(r->why, sizeof r->why, "floor picture: %s", err);
        } else {
            r->status = MHD_HTTP_NO_CONTENT;
        }
        break;
    }
}

/* The scene rcxsim started with was named on its command line, which the panel does not see: its name in the JSON,
 * when a shipped scene has that file name, is the best guess; else the page shows no scene of the list as current. */
static void current_guess(struct panel_world *pw)
{
    char path[sizeof pw->scenes_dir + PANEL_SCENE_NAME_MAX + 8];

    snprintf(path, sizeof path, "%s/%s.json", pw->scenes_dir, pw->lim.scene);
    if (pw->lim.scene[0] && access(path, R_OK) == 0)
        strcpy(pw->current, pw->lim.scene);
}

void panel_world_start(struct panel *p, struct sim *s)
{
    struct panel_world *pw = &p->world;

    pw->tail = &pw->queue;
    if (!s->world)
        return;
    pw->on = 1;
    snprintf(pw->scenes_dir, sizeof pw->scenes_dir, "%s", world_scenes_dir());
    copy_scene(p, s->world);
    copy_poses(p, s->world);
    current_guess(pw);
    clock_gettime(CLOCK_MONOTONIC, &pw->pose_at);
}

void panel_world_sync(struct panel *p, struct sim *s)
{
    struct panel_world *pw = &p->world;
    struct world_request *head, *r, *next;
    struct timespec now;
    int scene = 0;

    pthread_mutex_lock(&p->lock);
    head = pw->queue;
    pw->queue = NULL;
    pw->tail = &pw->queue;
    pthread_mutex_unlock(&p->lock);
    for (r = head; r; r = r->next) {
        apply(p, s, r);
        scene |= r->kind != WORLD_PLACE;
    }
    if (scene)
        copy_scene(p, s->world);
    clock_gettime(CLOCK_MONOTONIC, &now);
    if (head || ms_since(&pw->pose_at, &now) >= POSE_GAP_MS) {
        copy_poses(p, s->world);
        pw->pose_at = now;
    }
    if (!head)
        return;
    /* Answered only now: a page that reads the world after its answer sees what it asked for. */
    pthread_mutex_lock(&p->lock);
    for (r = head; r; r = next) {
        next = r->next;
        r->done = 1;
        if (r->abandoned) {
            free(r->png);
            free(r);
        }
    }
    pthread_cond_broadcast(&p->changed);
    pthread_mutex_unlock(&p->lock);
}

size_t panel_world_event(struct panel *p, unsigned long *version, unsigned long *scene_version, char *buf,
                         size_t size)
{
    struct panel_world *pw = &p->world;
    int scene = *scene_version != pw->scene_version;
    const char *head = scene ? "event: scene\ndata: " : "data: ";
    const char *json = scene ? pw->scene : pw->pose;
    size_t json_len = scene ? pw->scene_len : pw->pose_len, need = strlen(head) + json_len + 2;

    if (!json) { /* the world could not write it: a comment keeps the stream open */
        head = ": nothing yet";
        json_len = 0;
        need = strlen(head) + 2;
    }
    if (need > size)
        return need; /* the caller makes room and asks again */
    memcpy(buf, head, strlen(head));
    if (json_len)
        memcpy(buf + strlen(head), json, json_len);
    memcpy(buf + need - 2, "\n\n", 2);
    if (scene)
        *scene_version = pw->scene_version; /* the poses follow in the next event */
    else
        *version = pw->version;
    return need;
}

void panel_world_stop(struct panel *p)
{
    struct panel_world *pw = &p->world;
    struct world_request *r, *next;

    for (r = pw->queue; r; r = next) { /* nobody waits any longer: the daemon has stopped */
        next = r->next;
        free(r->png);
        free(r);
    }
    free(pw->scene);
    free(pw->pose);
    free(pw->floor);
}
