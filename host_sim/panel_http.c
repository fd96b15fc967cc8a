/* SPDX-License-Identifier: MPL-2.0 */
/*
 * The panel's HTTP server (libmicrohttpd, one thread per connection):
 *   GET  /, /panel.css, /panel.js, /brick.svg   the page (host_sim/panel/)
 *   GET  /state                                  one JSON snapshot of every brick (panel_state.c)
 *   GET  /events                                 the same snapshot as a Server-Sent Event whenever it changes
 *   POST /button?brick=B&button=onoff|run|view|prgm&action=down|up
 *   POST /sensor?brick=B&input=1-3&raw=0-1023
 *   POST /battery?brick=B&mv=0-65535             (brick defaults to 0; parameters in the query, no body)
 *   /world...                                    the world, with --world (panel_world_http.c)
 * An input answers 204 once the simulation has applied it, 202 if it is still queued after a second. Anything else
 * gets a 4xx status and a one-line reason.
 */
#define _POSIX_C_SOURCE 200809L
#include <arpa/inet.h>
#include <errno.h>
#include <pthread.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include "panel_server.h"

#define PANEL_JSON_MAX 16384      /* GET /state of 8 bricks is about 6 KB */
#define PANEL_CONNECTIONS 64      /* open pages (each holds an event stream) and requests at once */
#define PANEL_FILE_MAX (1 << 20)
#define EVENT_GAP_MS 40           /* an event stream sends at most 25 snapshots a second */
#define WORLD_GAP_MS 20           /* the world's stream 50 poses a second: the page interpolates between them */
#define EVENT_KEEPALIVE_S 5       /* a comment line when nothing changed: finds closed pages */
#define INPUT_WAIT_S 1

/* The files of the page, the only paths served from disk. */
static const struct {
    const char *path, *file, *type;
} page_files[] = {
    { "/", "index.html", "text/html; charset=utf-8" },
    { "/index.html", "index.html", "text/html; charset=utf-8" },
    { "/panel.css", "panel.css", "text/css; charset=utf-8" },
    { "/panel.js", "panel.js", "text/javascript; charset=utf-8" },
    { "/world.js", "world.js", "text/javascript; charset=utf-8" },
    { "/brick.svg", "brick.svg", "image/svg+xml" },
};

/* ---- simulation thread ---- */

unsigned panel_take_inputs(struct panel *p, struct sim_event *ev)
{
    unsigned n, i;

    pthread_mutex_lock(&p->lock);
    n = p->queued;
    for (i = 0; i < n; i++) {
        memset(&ev[i], 0, sizeof ev[i]);
        ev[i].brick = p->queue[i].brick;
        ev[i].kind = p->queue[i].kind;
        ev[i].a = p->queue[i].a;
        ev[i].b = p->queue[i].b;
    }
    p->queued = 0;
    pthread_mutex_unlock(&p->lock);
    return n;
}

void panel_sync(struct panel *p, struct sim *s, unsigned n)
{
    struct panel_brick shot[SIM_MAX_BRICKS];
    unsigned i;
    int changed;

    for (i = 0; i < (unsigned)p->nbricks; i++)
        panel_snapshot(s->brick[i], &shot[i]);

    pthread_mutex_lock(&p->lock);
    p->now_ms = s->room.now / 1000;
    changed = memcmp(shot, p->shot, (size_t)p->nbricks * sizeof shot[0]) != 0;
    if (changed) {
        memcpy(p->shot, shot, (size_t)p->nbricks * sizeof shot[0]);
        p->version++;
    }
    p->applied += n;
    if (changed || n)
        pthread_cond_broadcast(&p->changed);
    pthread_mutex_unlock(&p->lock);
    if (p->world.on)
        panel_world_sync(p, s);
}

/* ---- HTTP threads ---- */

/* Queues a response (NULL: it could not be made, the connection is dropped) and lets go of it. */
static enum MHD_Result respond(struct MHD_Connection *c, unsigned status, struct MHD_Response *r, const char *type,
                               const char *cache)
{
    enum MHD_Result ok;

    if (!r)
        return MHD_NO;
    MHD_add_response_header(r, "Content-Type", type);
    MHD_add_response_header(r, "Cache-Control", cache);
    ok = MHD_queue_response(c, status, r);
    MHD_destroy_response(r);
    return ok;
}

/* A malloc'ed body, freed whatever happens. */
enum MHD_Result panel_send_buffer(struct MHD_Connection *c, void *data, size_t len, const char *type,
                                  const char *cache)
{
    struct MHD_Response *r = MHD_create_response_from_buffer(len, data, MHD_RESPMEM_MUST_FREE);
    if (!r)
        free(data);
    return respond(c, MHD_HTTP_OK, r, type, cache);
}

enum MHD_Result panel_send_text(struct MHD_Connection *c, unsigned status, const char *type, const char *text)
{
    struct MHD_Response *r = MHD_create_response_from_buffer(strlen(text), (void *)text, MHD_RESPMEM_MUST_COPY);
    return respond(c, status, r, type, "no-store");
}

/* A refusal: the status and a one-line reason. */
enum MHD_Result panel_refuse(struct MHD_Connection *c, unsigned status, const char *why)
{
    char line[256];
    snprintf(line, sizeof line, "%s\n", why);
    return panel_send_text(c, status, "text/plain; charset=utf-8", line);
}

static enum MHD_Result send_file(struct MHD_Connection *c, const char *name, const char *type)
{
    char path[4096];
    FILE *f;
    char *data;
    size_t n;

    snprintf(path, sizeof path, "%s/%s", panel_files_dir(), name);
    f = fopen(path, "rb");
    if (!f)
        return panel_refuse(c, MHD_HTTP_NOT_FOUND, "page file missing from the installation");
    data = malloc(PANEL_FILE_MAX);
    n = data ? fread(data, 1, PANEL_FILE_MAX, f) : 0;
    fclose(f);
    if (!data)
        return MHD_NO;
    return panel_send_buffer(c, data, n, type, "no-cache");
}

static enum MHD_Result send_state(struct panel *p, struct MHD_Connection *c)
{
    char *json = malloc(PANEL_JSON_MAX);
    size_t len;

    if (!json)
        return MHD_NO;
    pthread_mutex_lock(&p->lock);
    len = panel_json(json, PANEL_JSON_MAX, p->now_ms, p->shot, p->nbricks, p->world.on);
    pthread_mutex_unlock(&p->lock);
    if (len == 0) {
        free(json);
        return panel_refuse(c, MHD_HTTP_INTERNAL_SERVER_ERROR, "state too large");
    }
    return panel_send_buffer(c, json, len, "application/json", "no-store");
}

/* One page's event stream: a snapshot each time it changes (at most every gap), comments in between. */
struct stream {
    struct panel *p;
    int world;                    /* the world's scene and poses (GET /world/events), else the bricks (GET /events) */
    int started;
    unsigned long version;        /* of the last snapshot sent */
    unsigned long scene_version;  /* of the last scene sent (world) */
    struct timespec last;         /* when it was sent */
    size_t len, off;              /* of the event being sent */
    size_t cap;
    char *buf;
};

static void add_ms(struct timespec *t, long ms)
{
    t->tv_sec += ms / 1000;
    t->tv_nsec += ms % 1000 * 1000000L;
    if (t->tv_nsec >= 1000000000L) {
        t->tv_sec++;
        t->tv_nsec -= 1000000000L;
    }
}

static int stream_behind(const struct stream *st)
{
    const struct panel *p = st->p;
    if (st->world)
        return p->world.version != st->version || p->world.scene_version != st->scene_version;
    return p->version != st->version;
}

/* The snapshot as an event into st->buf, under the lock; its length, 0 when it cannot be made. */
static size_t fill_event(struct stream *st)
{
    struct panel *p = st->p;
    size_t n;
    char *more;

    if (!st->world) {
        memcpy(st->buf, "data: ", 6);
        n = panel_json(st->buf + 6, st->cap - 8, p->now_ms, p->shot, p->nbricks, p->world.on);
        st->version = p->version;
        if (n == 0)
            return 0;
        memcpy(st->buf + 6 + n, "\n\n", 2);
        return n + 8;
    }
    while ((n = panel_world_event(p, &st->version, &st->scene_version, st->buf, st->cap)) > st->cap) {
        more = realloc(st->buf, n);
        if (!more)
            return 0;
        st->buf = more;
        st->cap = n;
    }
    return n;
}

/* The next event into st->buf; -1 when the panel closes. */
static int next_event(struct stream *st)
{
    struct panel *p = st->p;
    struct timespec until;
    size_t n;

    if (st->started) { /* keep the gap after the last snapshot */
        until = st->last;
        add_ms(&until, st->world ? WORLD_GAP_MS : EVENT_GAP_MS);
        while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &until, NULL) == EINTR)
            ;
    }
    clock_gettime(CLOCK_REALTIME, &until);
    add_ms(&until, EVENT_KEEPALIVE_S * 1000L);
    pthread_mutex_lock(&p->lock);
    while (!p->closing && st->started && !stream_behind(st))
        if (pthread_cond_timedwait(&p->changed, &p->lock, &until) == ETIMEDOUT)
            break;
    if (p->closing) {
        pthread_mutex_unlock(&p->lock);
        return -1;
    }
    if (st->started && !stream_behind(st)) {
        pthread_mutex_unlock(&p->lock);
        strcpy(st->buf, ": nothing new\n\n");
        st->len = strlen(st->buf);
        st->off = 0;
        return 0;
    }
    n = fill_event(st);
    pthread_mutex_unlock(&p->lock);
    if (n == 0)
        return -1;
    st->len = n;
    st->off = 0;
    st->started = 1;
    clock_gettime(CLOCK_MONOTONIC, &st->last);
    return 0;
}

static ssize_t stream_read(void *cls, uint64_t pos, char *out, size_t max)
{
    struct stream *st = cls;
    size_t n;

    (void)pos;
    if (st->off == st->len && next_event(st) < 0)
        return MHD_CONTENT_READER_END_OF_STREAM;
    n = st->len - st->off < max ? st->len - st->off : max;
    memcpy(out, st->buf + st->off, n);
    st->off += n;
    return (ssize_t)n;
}

static void stream_free(void *cls)
{
    struct stream *st = cls;
    free(st->buf);
    free(st);
}

enum MHD_Result panel_send_stream(struct panel *p, struct MHD_Connection *c, int world)
{
    struct stream *st = calloc(1, sizeof *st);
    struct MHD_Response *r;

    if (!st)
        return MHD_NO;
    st->p = p;
    st->world = world;
    st->cap = PANEL_JSON_MAX + 64;
    st->buf = malloc(st->cap);
    if (!st->buf) {
        free(st);
        return MHD_NO;
    }
    strcpy(st->buf, "retry: 1000\n\n"); /* a page that loses the stream comes back after a second */
    st->len = strlen(st->buf);
    r = MHD_create_response_from_callback(MHD_SIZE_UNKNOWN, 4096, stream_read, st, stream_free);
    if (!r)
        stream_free(st);
    return respond(c, MHD_HTTP_OK, r, "text/event-stream", "no-store");
}

/* The query must hold only the names given, each at most once. */
struct query_check {
    const char *const *names;
    int count[8];
    int bad;
};

static enum MHD_Result check_arg(void *cls, enum MHD_ValueKind kind, const char *key, const char *value)
{
    struct query_check *q = cls;
    int i;

    (void)kind;
    for (i = 0; q->names[i]; i++)
        if (strcmp(key, q->names[i]) == 0)
            break;
    if (!q->names[i] || !value || ++q->count[i] > 1)
        q->bad = 1;
    return MHD_YES;
}

const char *panel_arg(struct MHD_Connection *c, const char *name)
{
    return MHD_lookup_connection_value(c, MHD_GET_ARGUMENT_KIND, name);
}

int panel_query_only(struct MHD_Connection *c, const char *const *names)
{
    struct query_check q = { names, { 0 }, 0 };
    MHD_get_connection_values(c, MHD_GET_ARGUMENT_KIND, check_arg, &q);
    return q.bad;
}

/* POST /button, /sensor, /battery: checked, queued for the simulation thread, answered once applied. */
static enum MHD_Result post_input(struct panel *p, struct MHD_Connection *c, const char *url)
{
    static const char *const button_args[] = { "brick", "button", "action", NULL };
    static const char *const sensor_args[] = { "brick", "input", "raw", NULL };
    static const char *const battery_args[] = { "brick", "mv", NULL };
    static const char *const actions[] = { "up", "down" };
    const char *const *names;
    struct panel_input in;
    struct timespec until;
    const char *brick = panel_arg(c, "brick"), *button = panel_arg(c, "button");
    unsigned long ticket;
    long v;

    memset(&in, 0, sizeof in);
    if (brick) {
        if (sim_parse_number(brick, 0, p->nbricks - 1, &v))
            return panel_refuse(c, MHD_HTTP_BAD_REQUEST, "brick: no such brick");
        in.brick = (int)v;
    }
    if (strcmp(url, "/button") == 0) {
        names = button_args;
        in.kind = EV_BUTTON;
        if (!button || (in.a = sim_word_index(button, sim_button_names, SIM_BUTTONS)) < 0)
            return panel_refuse(c, MHD_HTTP_BAD_REQUEST, "button: expected onoff, run, view or prgm");
        if (!panel_arg(c, "action") || (in.b = sim_word_index(panel_arg(c, "action"), actions, 2)) < 0)
            return panel_refuse(c, MHD_HTTP_BAD_REQUEST, "action: expected down or up");
    } else if (strcmp(url, "/sensor") == 0) {
        names = sensor_args;
        in.kind = EV_SENSOR;
        if (sim_parse_number(panel_arg(c, "input"), 1, 3, &v))
            return panel_refuse(c, MHD_HTTP_BAD_REQUEST, "input: expected 1, 2 or 3");
        in.a = (int)v - 1;
        if (sim_parse_number(panel_arg(c, "raw"), 0, 1023, &v))
            return panel_refuse(c, MHD_HTTP_BAD_REQUEST, "raw: expected 0-1023");
        in.b = (int)v;
    } else {
        names = battery_args;
        in.kind = EV_BATTERY;
        if (sim_parse_number(panel_arg(c, "mv"), 0, SIM_BATTERY_MAX_MV, &v))
            return panel_refuse(c, MHD_HTTP_BAD_REQUEST, "mv: expected millivolts 0-65535");
        in.a = (int)v;
    }
    if (panel_query_only(c, names))
        return panel_refuse(c, MHD_HTTP_BAD_REQUEST, "unknown, empty or repeated parameter");

    pthread_mutex_lock(&p->lock);
    if (p->queued == PANEL_QUEUE || p->closing) {
        pthread_mutex_unlock(&p->lock);
        return panel_refuse(c, MHD_HTTP_SERVICE_UNAVAILABLE, "input queue full, try again");
    }
    p->queue[p->queued++] = in;
    ticket = ++p->posted;
    clock_gettime(CLOCK_REALTIME, &until);
    until.tv_sec += INPUT_WAIT_S;
    while (!p->closing && (long)(p->applied - ticket) < 0)
        if (pthread_cond_timedwait(&p->changed, &p->lock, &until) == ETIMEDOUT)
            break;
    v = (long)(p->applied - ticket) >= 0;
    pthread_mutex_unlock(&p->lock);
    return panel_send_text(c, v ? MHD_HTTP_NO_CONTENT : MHD_HTTP_ACCEPTED, "text/plain", "");
}

/* Another site's page may not press the buttons: a browser names the page's origin on every POST. */
static int foreign_origin(struct MHD_Connection *c)
{
    const char *origin = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Origin");
    const char *host = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Host");
    return origin && (!host || strncmp(origin, "http://", 7) != 0 || strcmp(origin + 7, host) != 0);
}

/* A request's body, kept only for POST /world/floor; every other request has none. */
struct body {
    size_t len, cap;
    int too_large;
    unsigned char *data;
};

static int takes_body(const char *url, const char *method)
{
    return strcmp(url, "/world/floor") == 0 && strcmp(method, "POST") == 0;
}

/* The first call, with the headers: a body is refused before it is read unless the request takes one. */
static int headers_seen; /* the context of a request without a body */

static enum MHD_Result begin(struct MHD_Connection *c, const char *url, const char *method, void **req)
{
    const char *length = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Content-Length");
    const char *chunked = MHD_lookup_connection_value(c, MHD_HEADER_KIND, "Transfer-Encoding");
    struct body *b;
    long n = 0;

    *req = &headers_seen;
    if (!takes_body(url, method)) {
        if ((length && strcmp(length, "0") != 0) || chunked)
            return panel_refuse(c, MHD_HTTP_CONTENT_TOO_LARGE, "no request body expected: parameters go in the query");
        return MHD_YES;
    }
    if (length && sim_parse_number(length, 0, PANEL_FLOOR_MAX, &n))
        return panel_refuse(c, MHD_HTTP_CONTENT_TOO_LARGE, "the floor picture may have at most 8 MiB");
    b = calloc(1, sizeof *b);
    if (!b)
        return MHD_NO;
    b->cap = length && n ? (size_t)n : 65536; /* sent in chunks: grows as they come */
    b->data = malloc(b->cap);
    if (!b->data) {
        free(b);
        return MHD_NO;
    }
    *req = b;
    return MHD_YES;
}

/* Takes what came of a body; a body sent in chunks is cut off at the limit and refused once it has all come. */
static void take_body(void *req, const char *data, size_t n)
{
    struct body *b = req;
    unsigned char *more;

    if (b->too_large || n > PANEL_FLOOR_MAX - b->len) {
        b->too_large = 1;
        return;
    }
    if (n > b->cap - b->len) {
        b->cap = b->len + n > PANEL_FLOOR_MAX / 2 ? PANEL_FLOOR_MAX : 2 * (b->len + n);
        more = realloc(b->data, b->cap);
        if (!more) {
            b->too_large = 1;
            return;
        }
        b->data = more;
    }
    memcpy(b->data + b->len, data, n);
    b->len += n;
}

/* The end of a request, answered or not: its body goes. */
static void finished(void *cls, struct MHD_Connection *c, void **req, enum MHD_RequestTerminationCode why)
{
    (void)cls;
    (void)c;
    (void)why;
    if (*req && *req != &headers_seen) {
        free(((struct body *)*req)->data);
        free(*req);
    }
    *req = NULL;
}

static enum MHD_Result route(void *cls, struct MHD_Connection *c, const char *url, const char *method,
                             const char *version, const char *upload_data, size_t *upload_size, void **req)
{
    struct panel *p = cls;
    int get = strcmp(method, "GET") == 0 || strcmp(method, "HEAD") == 0, post = strcmp(method, "POST") == 0;
    struct body *b;
    size_t i;

    (void)version;
    if (*req == NULL)
        return begin(c, url, method, req);
    b = takes_body(url, method) ? *req : NULL;
    if (*upload_size) {
        if (b)
            take_body(b, upload_data, *upload_size);
        *upload_size = 0;
        return MHD_YES;
    }
    for (i = 0; i < sizeof page_files / sizeof page_files[0]; i++)
        if (strcmp(url, page_files[i].path) == 0)
            return get ? send_file(c, page_files[i].file, page_files[i].type)
                       : panel_refuse(c, MHD_HTTP_METHOD_NOT_ALLOWED, "only GET here");
    if (strcmp(url, "/state") == 0 || strcmp(url, "/events") == 0) {
        if (!get)
            return panel_refuse(c, MHD_HTTP_METHOD_NOT_ALLOWED, "only GET here");
        return url[1] == 's' ? send_state(p, c) : panel_send_stream(p, c, 0);
    }
    if (strcmp(url, "/button") == 0 || strcmp(url, "/sensor") == 0 || strcmp(url, "/battery") == 0) {
        if (!post)
            return panel_refuse(c, MHD_HTTP_METHOD_NOT_ALLOWED, "only POST here");
        if (foreign_origin(c))
            return panel_refuse(c, MHD_HTTP_FORBIDDEN, "inputs only from the panel's own page");
        return post_input(p, c, url);
    }
    if (strcmp(url, "/world") == 0 || strncmp(url, "/world/", 7) == 0) {
        if (post && foreign_origin(c))
            return panel_refuse(c, MHD_HTTP_FORBIDDEN, "inputs only from the panel's own page");
        if (b && b->too_large)
            return panel_refuse(c, MHD_HTTP_CONTENT_TOO_LARGE, "the floor picture may have at most 8 MiB");
        return panel_world_route(p, c, url, get, post, b ? b->data : NULL, b ? b->len : 0);
    }
    return panel_refuse(c, MHD_HTTP_NOT_FOUND, "no such page: try / or /state");
}

struct panel *panel_start(struct sim *s, const char *bind_addr, unsigned port, char *err, size_t errlen)
{
    struct panel *p = calloc(1, sizeof *p);
    struct sockaddr_storage addr;
    struct sockaddr_in *v4 = (struct sockaddr_in *)&addr;
    struct sockaddr_in6 *v6 = (struct sockaddr_in6 *)&addr;
    unsigned flags = MHD_USE_THREAD_PER_CONNECTION | MHD_USE_INTERNAL_POLLING_THREAD;
    const union MHD_DaemonInfo *info;
    sigset_t block, old;
    int i;

    if (!p)
        abort();
    memset(&addr, 0, sizeof addr);
    if (inet_pton(AF_INET, bind_addr, &v4->sin_addr) == 1) {
        v4->sin_family = AF_INET;
        v4->sin_port = htons((unsigned short)port);
    } else if (inet_pton(AF_INET6, bind_addr, &v6->sin6_addr) == 1) {
        v6->sin6_family = AF_INET6;
        v6->sin6_port = htons((unsigned short)port);
        flags |= MHD_USE_IPv6;
    } else {
        snprintf(err, errlen, "--panel-bind %s: not an IPv4 or IPv6 address", bind_addr);
        free(p);
        return NULL;
    }
    pthread_mutex_init(&p->lock, NULL);
    pthread_cond_init(&p->changed, NULL);
    p->nbricks = s->nbricks;
    for (i = 0; i < s->nbricks; i++)
        panel_snapshot(s->brick[i], &p->shot[i]);
    panel_world_start(p, s);
    /* The server's threads leave the stop signals to the simulation thread. */
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    sigaddset(&block, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &block, &old);
    p->daemon = MHD_start_daemon(flags, (uint16_t)port, NULL, NULL, route, p, MHD_OPTION_SOCK_ADDR, &addr,
                                 MHD_OPTION_CONNECTION_LIMIT, (unsigned)PANEL_CONNECTIONS,
                                 MHD_OPTION_CONNECTION_TIMEOUT, (unsigned)(3 * EVENT_KEEPALIVE_S),
                                 MHD_OPTION_NOTIFY_COMPLETED, finished, NULL, MHD_OPTION_END);
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    if (!p->daemon) {
        snprintf(err, errlen, "cannot listen on %s port %u (in use?)", bind_addr, port);
        panel_world_stop(p);
        pthread_cond_destroy(&p->changed);
        pthread_mutex_destroy(&p->lock);
        free(p);
        return NULL;
    }
    info = MHD_get_daemon_info(p->daemon, MHD_DAEMON_INFO_BIND_PORT);
    fprintf(stderr, "rcxsim: panel at http://%s%s%s:%u/\n", flags & MHD_USE_IPv6 ? "[" : "", bind_addr,
            flags & MHD_USE_IPv6 ? "]" : "", info ? info->port : port);
    return p;
}

void panel_stop(struct panel *p)
{
    pthread_mutex_lock(&p->lock);
    p->closing = 1;
    pthread_cond_broadcast(&p->changed);
    pthread_mutex_unlock(&p->lock);
    MHD_stop_daemon(p->daemon);
    panel_world_stop(p);
    pthread_cond_destroy(&p->changed);
    pthread_mutex_destroy(&p->lock);
    free(p);
}
