/* SPDX-License-Identifier: MPL-2.0 */
/*
 * Inside the panel's server: the state its HTTP threads and the simulation thread share (struct panel), and the
 * answers panel_http.c gives, for panel_world_http.c. Not for the rest of rcxsim, which sees only panel.h.
 */
#ifndef RCX_PANEL_SERVER_H
#define RCX_PANEL_SERVER_H

#include <pthread.h>
#include <time.h>
#include <microhttpd.h>
#include "panel.h"

struct panel_input {
    int brick, kind, a, b;        /* as in struct sim_event */
};

/* A world request from a page, answered once the simulation thread has applied it (panel_world.c). */
struct world_request {
    enum { WORLD_PLACE, WORLD_SCENE, WORLD_FLOOR } kind;
    struct panel_place place;
    char scene[PANEL_SCENE_NAME_MAX + 1];
    unsigned char *png;           /* WORLD_FLOOR: the picture, malloc'ed; freed with the request */
    size_t png_len;
    int done, abandoned;          /* abandoned: the page stopped waiting, whoever finishes last frees it */
    unsigned status;              /* the HTTP status of the answer */
    char why[320];                /* its reason when it is refused */
    struct world_request *next;
};

/* What the pages see of the world: copies made on the simulation thread. */
struct panel_world {
    int on;                       /* rcxsim runs with --world */
    char *scene;                  /* world_scene_json(), malloc'ed */
    size_t scene_len;
    char *pose;                   /* world_pose_json(), malloc'ed */
    size_t pose_len;
    unsigned char *floor;         /* world_floor_png(), malloc'ed, NULL without a picture */
    size_t floor_len;
    unsigned long version;        /* counts changes of the scene and of the poses */
    unsigned long scene_version;  /* counts changes of the scene alone */
    struct panel_world_limits lim;
    char current[PANEL_SCENE_NAME_MAX + 1]; /* the scene's file name in scenes_dir, "" when not known */
    char scenes_dir[4096];        /* world_scenes_dir(), asked on the simulation thread */
    struct world_request *queue, **tail;
    /* simulation thread only */
    struct timespec pose_at;      /* when the poses were last copied */
};

struct panel {
    struct MHD_Daemon *daemon;
    pthread_mutex_t lock;         /* guards everything below */
    pthread_cond_t changed;       /* the snapshot changed, inputs were applied, or the panel closes */
    int closing;
    int nbricks;
    unsigned long version;        /* counts changes of the snapshot */
    unsigned long long now_ms;
    struct panel_brick shot[SIM_MAX_BRICKS];
    struct panel_input queue[PANEL_QUEUE];
    unsigned queued;              /* inputs in the queue */
    unsigned long posted, applied; /* inputs ever queued, and applied by the simulation */
    struct panel_world world;
};

/* panel_http.c */
enum MHD_Result panel_send_buffer(struct MHD_Connection *c, void *data, size_t len, const char *type,
                                  const char *cache);
enum MHD_Result panel_send_text(struct MHD_Connection *c, unsigned status, const char *type, const char *text);
enum MHD_Result panel_refuse(struct MHD_Connection *c, unsigned status, const char *why);
enum MHD_Result panel_send_stream(struct panel *p, struct MHD_Connection *c, int world);
const char *panel_arg(struct MHD_Connection *c, const char *name);
int panel_query_only(struct MHD_Connection *c, const char *const *names); /* 1: no other, empty or repeated name */

/* panel_world.c, simulation thread */
void panel_world_start(struct panel *p, struct sim *s);
void panel_world_sync(struct panel *p, struct sim *s);
void panel_world_stop(struct panel *p);
/* the JSON of the world's next event for a stream that has seen `*version` and `*scene_version` (under the lock) */
size_t panel_world_event(struct panel *p, unsigned long *version, unsigned long *scene_version, char *buf,
                         size_t size);

/* panel_world_http.c: GET and POST /world... */
#define PANEL_FLOOR_MAX (8u << 20) /* a floor picture's upload, bytes */
enum MHD_Result panel_world_route(struct panel *p, struct MHD_Connection *c, const char *url, int get, int post,
                                  const unsigned char *body, size_t body_len);

#endif
