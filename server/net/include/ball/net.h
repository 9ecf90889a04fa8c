/* libball's client library: a game joins a ball server (docs/client.md).
 *
 * The paper's ball server "communicates with game clients delivering
 * positions of objects susceptible to hit the ball" (section 4). This is the
 * client side: open a client on a DDS domain, list the matches the domain's
 * servers serve, create one, join a slot, push the racket's pose at your
 * tracker's rate, and ask for the ball at any time of your clock: the
 * library evaluates it with libball from the flight segment in effect
 * (eq 3, 4), the segments written ahead of their bounces and the
 * corrections applied, as docs/protocol.md says. Events (hits, bounces,
 * points, pauses, a change of the match's server) come from ball_net_poll,
 * each once and in order. Everything a client needs comes from the wire:
 * no scene file, no QoS file.
 *
 * Threads. A client is a plain object: call its functions from one thread
 * at a time (any thread; a game calls them from its loop). Different
 * clients are independent. The library's DDS threads receive and keep
 * samples; they never touch a client's state and never call back into the
 * game. ball_net_poll takes what came in and resends what the server has
 * not answered yet (JOIN, CREATE): call it every frame, at least every
 * 0.1 s. ball_net_ball_at and ball_net_predict only read what the last poll
 * took; they are cheap (docs/client.md, "What it costs").
 *
 * Errors. Every call returns a ball_status (ball.h; ball_strerror names
 * it), and ball_net_message says why in a sentence. A call that is refused
 * changes nothing. No exception crosses this boundary, nothing is printed,
 * the library never aborts or exits. The only state shared by the clients
 * of a process is Fast DDS's own (its participant factory and the QoS
 * profiles it loaded).
 *
 * Clocks. Every time a game passes or gets is on its own clock, in
 * seconds: CLOCK_MONOTONIC unless the config names another (its `clock`).
 * Sim times are the match's sim clock (docs/protocol.md, "Time"); the
 * library maps between the two. Units are SI. */
#ifndef BALL_NET_H
#define BALL_NET_H

#include <stddef.h>
#include <stdint.h>

#include "ball/ball.h"

#ifdef __cplusplus
extern "C" {
#endif

#if defined(_WIN32)
#define BALL_NET_API
#elif defined(__GNUC__)
#define BALL_NET_API __attribute__((visibility("default")))
#else
#define BALL_NET_API
#endif

#define BALL_NET_MAX_PLAYERS 4  /* player slots per match (BALL_MAX_RACKETS) */
#define BALL_NET_NAME_LEN 32    /* scene names, NUL included */

typedef struct ball_net_client ball_net_client;

/* ---- opening a client ---------------------------------------------------- */

/* The caller's clock: seconds, never going back. */
typedef double (*ball_net_clock)(void *user);

typedef struct ball_net_config {
  int domain;                     /* DDS domain id, [0, 232] */
  const char *participant;        /* participant profile: "loopback" (this host only), "lan" (UDP on
                                     every interface, multicast discovery), "discovery_client" (a
                                     Discovery Server); docs/server.md, "Several hosts"; "tcp_client"
                                     (TCP out to the servers, across the internet: docs/deploy.md) */
  const char *discovery_servers;  /* HOST:PORT[;HOST:PORT...] for "discovery_client"; NULL: the profile's */
  const char *qos_file;           /* a QoS profile file; NULL: the library's own (docs/protocol.md's) */
  const char *security_dir;       /* DDS Security: the folder of ./run certs; NULL: an open domain */
  const char *identity;           /* the identity in it (NAME.pem, NAME.key); with security_dir or tls_dir */
  const char *servers;            /* the servers it takes the match topics from: "1,2"; "1=server1" binds
                                     server 1 to that certificate (with security_dir); NULL: any */
  const char *name;               /* the DDS participant's name; NULL: "ball-net" */
  int max_matches;                /* matches its readers make room for, [1, 4096]; 0: 4096 */
  int ball_states;                /* 1: also read the server's ball states (up to its frame rate: a clock pair
                                     each, and their bytes); 0: the clock from MatchInfo alone, at every change and
                                     4 s after the last one (docs/client.md, "What it costs") */
  ball_net_clock clock;           /* the caller's clock; NULL: CLOCK_MONOTONIC */
  void *clock_user;               /* passed to clock */
  /* A simulated network for this client's racket poses, to try a game behind a bad one: each pose is
     written link_delay + a uniform draw in [0, link_jitter] s after its ball_net_push (so poses may
     overtake each other), by that call or the first ball_net_push or ball_net_poll after, or lost with
     probability link_loss (its number skipped, as a network loses it); the draws from link_seed. All 0:
     none, each pose written by its ball_net_push. */
  double link_delay;              /* s, [0, 10] */
  double link_jitter;             /* s, [0, 1] */
  double link_loss;               /* [0, 0.9] */
  uint64_t link_seed;
  int rackets;                    /* 1: read the players' racket samples of the matches followed, for
                                     ball_net_racket (their samples come in too: a slot's rate times 76
                                     bytes of payload a second); 0: not */
  int server_status;              /* 1: also read the servers' status (ball/server_status, once a second
                                     each): for the tap alone (ball_net_set_tap); 0: not */
  const char *tcp_peers;          /* "tcp_client": the servers, HOST:PORT[;HOST:PORT...]; NULL: the
                                     profile's (127.0.0.1:7400) */
  const char *tls_dir;            /* "tcp_client": TLS with ca.pem and the identity in this folder (a
                                     server without a certificate of that CA is refused); NULL: plain TCP */
  int followed_only;              /* 1: read only the matches the client follows, in their own DDS partitions
                                     (what it receives does not grow with the matches on the server; while it
                                     follows none, every match's info, for ball_net_matches); 0: every match
                                     (docs/client.md, "What it costs") */
} ball_net_config;

/* Defaults: domain 0, loopback, any server, CLOCK_MONOTONIC, no simulated network. */
BALL_NET_API void ball_net_config_default(ball_net_config *config);

/* Opens a client: a DDS participant on the config's domain and its readers
 * and writers. On failure *client is NULL and `why` (if not NULL) gets a
 * sentence (at most why_size bytes, NUL included): a bad config field, a
 * domain whose ports are taken, certificates that do not fit. */
BALL_NET_API ball_status ball_net_open(const ball_net_config *config, ball_net_client **client, char *why,
                                       size_t why_size);

/* Leaves every slot the client holds (a LEAVE each, given 0.2 s to get
 * out) and deletes its DDS entities. The client stays a handle: every call
 * on it but ball_net_message and ball_net_free is refused from then on.
 * BALL_ENETWORK when Fast DDS did not finish deleting within 3 s (its
 * entities are left to it, eProsima/Fast-DDS#6193). */
BALL_NET_API ball_status ball_net_close(ball_net_client *client);

/* Closes the client if it is open and frees it. NULL is harmless. */
BALL_NET_API void ball_net_free(ball_net_client *client);

/* Why the client's last call was refused ("" after a call that succeeded).
 * Valid until the next call on the client. "" for NULL. */
BALL_NET_API const char *ball_net_message(const ball_net_client *client);

/* ---- matches ------------------------------------------------------------- */

typedef enum ball_net_state {
  BALL_NET_WAITING = 0,  /* a slot is free: nothing moves */
  BALL_NET_PLAYING,      /* the sim runs */
  BALL_NET_PAUSED,       /* a player vanished or asked: the sim clock stands still */
  BALL_NET_STATE_COUNT
} ball_net_state;

typedef struct ball_net_slot {
  int held;     /* a participant holds it */
  int present;  /* its holder's samples arrive */
  int mine;     /* this client holds it */
} ball_net_slot;

typedef struct ball_net_match {
  uint32_t id;                               /* the match */
  uint32_t server;                           /* the server that serves it now */
  char scene[BALL_NET_NAME_LEN];             /* its scene's name */
  int level;                                 /* ball_level: 0 the scene's own, 1 easy, 2 mid, 3 advanced */
  ball_net_state state;
  int players;                               /* slots, [1, BALL_NET_MAX_PLAYERS]; slot i plays on side i % 2 */
  ball_net_slot slots[BALL_NET_MAX_PLAYERS];
  int score[2];                              /* points of side 0 (x < net) and side 1 */
  uint32_t rally;                            /* points played, lets included */
  int serving_side;                          /* the side that serves next */
  double time_base;                          /* sim s per real s */
  double sim_time;                           /* sim s, now (the client's estimate) */
  double net_x;                              /* m: the net stands on the plane x = net_x */
  double court_x[2];                         /* m: the court the rules judge, baseline to baseline */
  double court_z[2];                         /* m: and sideline to sideline */
  uint64_t model_hash;                       /* ball_model_hash of the model it is stepped with: a new one (a
                                                new level) is a new model (ball_net_model) */
} ball_net_match;

/* The matches the domain's servers serve (those the client trusts, each
 * heard within the last 10 s), by id: up to cap into out, *n of them (may
 * be more than cap: then call again with room for *n). */
BALL_NET_API ball_status ball_net_matches(ball_net_client *client, ball_net_match *out, int cap, int *n);

/* One match, as ball_net_matches has it. BALL_ENOMATCH: no server serves it. */
BALL_NET_API ball_status ball_net_match_info(ball_net_client *client, uint32_t match, ball_net_match *out);

/* Asks the domain's servers for a new match `match` (an id CREATEs may name:
 * docs/server-reference.md, "Server keys", create_first and create_ids) of the
 * server's catalogue scene `scene` with `players` slots at `level` (0: the
 * scene's own). The library sends the CREATE again every 0.5 s until a
 * MatchInfo of the match appears (ball_net_match_info then finds it); a
 * server that refuses it says nothing (docs/protocol.md, "Control
 * messages"). BALL_ERANGE for players outside [1, 4], a level outside
 * [0, 3], a scene name that is not 1 to 31 letters, digits, '_' or '-';
 * BALL_ENETWORK when DDS refuses the first CREATE's writer (under DDS
 * Security: the identity is not granted the match's partition), in DDS's
 * words, and nothing is kept. */
BALL_NET_API ball_status ball_net_create(ball_net_client *client, uint32_t match, const char *scene, int players,
                                         ball_level level);

/* Joins match `match` in slot `slot` (-1: any free one, satisfied by any
 * slot this client holds there). The library sends JOIN every 0.5 s until
 * the match's MatchInfo shows the slot held by this client, and again
 * whenever it stops being so, until ball_net_leave; a BALL_NET_EVENT_SLOT
 * event says when a slot is taken or lost. A client may hold several slots
 * of a match (two players at one console: join each slot by its number).
 * Also follows the match (ball_net_watch). BALL_ERANGE for a slot outside
 * [-1, 3]; BALL_ENETWORK when DDS refuses the first JOIN's writer (under
 * DDS Security: the identity is not granted the match's partition), in DDS's
 * words, and the match is not followed (unless it was before). */
BALL_NET_API ball_status ball_net_join(ball_net_client *client, uint32_t match, int slot);

/* Gives slot `slot` of `match` up (a LEAVE; -1: every slot this client
 * holds there) and stops asking for it; the client still follows the
 * match until ball_net_unwatch. BALL_ENOMATCH: the client has not joined
 * that slot. */
BALL_NET_API ball_status ball_net_leave(ball_net_client *client, uint32_t match, int slot);

/* The lowest slot this client holds in `match`: -1 while it holds none
 * (joining, or a spectator); ball_net_match_info's slots say which it holds.
 * BALL_ENOMATCH: the client does not follow the match. */
BALL_NET_API ball_status ball_net_slot_of(ball_net_client *client, uint32_t match, int *slot);

/* Follows a match without a slot (a spectator): its ball, its events. */
BALL_NET_API ball_status ball_net_watch(ball_net_client *client, uint32_t match);
/* Stops following it (leaves its slot first, if it holds one). */
BALL_NET_API ball_status ball_net_unwatch(ball_net_client *client, uint32_t match);

/* What a player may ask of its match (docs/protocol.md, "Control messages"). */
typedef enum ball_net_request {
  BALL_NET_SERVE = 0,   /* serve now, between points */
  BALL_NET_LEVEL,       /* value: the game level, 1 easy, 2 mid, 3 advanced */
  BALL_NET_PAUSE,
  BALL_NET_RESUME,
  BALL_NET_TIME_BASE,   /* value: sim s per real s, [0.05, 20]; takes effect once every player asked for it */
  BALL_NET_REQUEST_COUNT
} ball_net_request;

/* Sends a request for a match of which this client holds a slot (it asks
 * as the holder of the lowest); the server
 * answers with an event (BALL_NET_EVENT_LEVEL, ... or BALL_NET_EVENT_REFUSED).
 * BALL_ENOMATCH: no slot held in it; BALL_ERANGE: a value out of range. */
BALL_NET_API ball_status ball_net_ask(ball_net_client *client, uint32_t match, ball_net_request request,
                                      double value);

/* ---- playing ------------------------------------------------------------- */

/* The pose of the racket of slot `slot` (one this client holds) at `time`
 * of the caller's clock: its disc's centre (m) and normal (any length in
 * [1e-6, 1e6]). The library maps the time to the
 * match's sim clock, numbers the sample and writes it; the rate is the
 * caller's (the server wants one at least every player timeout, 1 s, and
 * tests hits between samples: 10 to 60 a second play well).
 * BALL_ENOMATCH: the client does not hold that slot; BALL_EAGAIN: the match's clock
 * is not known yet (no MatchInfo); BALL_ENONFINITE, BALL_ERANGE: a bad pose;
 * BALL_ESTALE: a time not after the previous pose's; BALL_ENETWORK: DDS
 * refused the write. */
BALL_NET_API ball_status ball_net_push(ball_net_client *client, uint32_t match, int slot, double time,
                                       ball_vec3 center, ball_vec3 normal);

/* What started a flight segment (docs/protocol.md, "Segments"). */
typedef enum ball_net_cause {
  BALL_NET_CAUSE_SERVE = 0,
  BALL_NET_CAUSE_FLOOR,
  BALL_NET_CAUSE_NET,
  BALL_NET_CAUSE_WALL,    /* cause_index: the wall */
  BALL_NET_CAUSE_RACKET,  /* cause_index: the racket, which is the player slot */
  BALL_NET_CAUSE_COUNT
} ball_net_cause;

typedef struct ball_net_ball {
  ball_state state;       /* position m, velocity m/s, spin m/s at the time asked */
  double sim_time;        /* sim s: that time on the match's clock */
  uint32_t segment;       /* the segment in effect: its seq */
  ball_net_cause cause;   /* what started it */
  int cause_index;        /* the wall, or the racket's slot; -1 */
  int sound;              /* its collision made the paper's sound: play it when `segment` changes */
  ball_segment flight;    /* the segment itself: t0 sim s, p0, v0, s0, grounded (ball_segment_eval's) */
} ball_net_ball;

/* The ball of `match` at `time` of the caller's clock, from the segment in
 * effect then (written ahead or corrected, as the rules say). Reads only:
 * call it as often as you draw. BALL_ENOMATCH: the client does not follow
 * the match; BALL_EAGAIN: no segment or clock yet; BALL_ENONFINITE: a NaN
 * or infinite time. */
BALL_NET_API ball_status ball_net_ball_at(const ball_net_client *client, uint32_t match, double time,
                                          ball_net_ball *out);

/* The path ahead for aiming: ball_predict (ball.h) from the segment in
 * effect at `time` of the caller's clock to `horizon` sim s later, states
 * every dt sim s; the floor, net and wall contacts on the way (no rackets).
 * `out` as ball_predict takes it; its times are sim times
 * (ball_net_local_time maps them back). BALL_EAGAIN: the match's whole
 * model has not come yet (docs/protocol.md, "The match's model"). */
BALL_NET_API ball_status ball_net_predict(const ball_net_client *client, uint32_t match, double time,
                                          double horizon, double dt, ball_prediction *out);

/* The match's clock: the sim time at `time` of the caller's clock, and the
 * caller's time at sim time `sim` (while the match plays; paused, the sim
 * clock stands still and every time maps to the present).
 * BALL_EAGAIN: no clock yet. */
BALL_NET_API ball_status ball_net_sim_time(const ball_net_client *client, uint32_t match, double time, double *sim);
BALL_NET_API ball_status ball_net_local_time(const ball_net_client *client, uint32_t match, double sim,
                                             double *time);

/* The racket of slot `slot` of `match` at `time` of the caller's clock (a
 * player's opponent, or its own as the server sees it), from the samples its
 * holder writes (docs/protocol.md, "The other players' rackets"): between
 * two samples interpolated, past the newest extrapolated (eq 15) for at most
 * the model's extrapolation_time. Needs ball_net_config.rackets
 * (BALL_EINVAL without). BALL_ENOMATCH: the client does not follow the
 * match; BALL_EAGAIN: no clock, model or sample of the slot yet;
 * BALL_ERANGE: a slot the match does not have; BALL_ESTALE: the newest
 * sample is older than the model's stale_time; BALL_ENONFINITE: a NaN or
 * infinite time. Under DDS Security the identity must be granted reading
 * the players' topic in the match's partition (docs/security.md). */
BALL_NET_API ball_status ball_net_racket(const ball_net_client *client, uint32_t match, int slot, double time,
                                         ball_racket_pose *out);

/* The whole model the match is stepped with, from the wire (a copy).
 * BALL_EAGAIN: not come yet. */
BALL_NET_API ball_status ball_net_model(const ball_net_client *client, uint32_t match, ball_model *out);

/* ---- events -------------------------------------------------------------- */

/* The server's events (docs/protocol.md, "Events"), then the library's own. */
typedef enum ball_net_event_kind {
  BALL_NET_EVENT_FLOOR = 0,  /* a bounce (eq 5) */
  BALL_NET_EVENT_NET,        /* the net (eq 6) */
  BALL_NET_EVENT_WALL,       /* index: the wall */
  BALL_NET_EVENT_RACKET,     /* a hit; index: the racket, which is the player slot */
  BALL_NET_EVENT_SOUND,      /* the paper's sound event: the library's, right after a collision whose sound flag is set */
  BALL_NET_EVENT_SERVE,      /* index: the serving slot */
  BALL_NET_EVENT_POINT,      /* side: who won it (-1: a let); reason why; score after it */
  BALL_NET_EVENT_PAUSE,      /* index: the slot concerned or -1; reason why */
  BALL_NET_EVENT_RESUME,
  BALL_NET_EVENT_JOIN,       /* index: the slot taken (by anyone) */
  BALL_NET_EVENT_LEAVE,      /* index: the slot given up */
  BALL_NET_EVENT_LEVEL,      /* value: the new game level */
  BALL_NET_EVENT_TIME_BASE,  /* value: the new time base */
  BALL_NET_EVENT_REFUSED,    /* a request refused: index its control kind, reason why */
  /* the library's own (seq 0) */
  BALL_NET_EVENT_SERVER,     /* the match's server changed (a failover): `server` is the new one */
  BALL_NET_EVENT_SLOT,       /* this client's slot `index`: value 1 taken, 0 lost */
  BALL_NET_EVENT_VOIDED,     /* a correction, or a newer owner's other event of its seq (docs/protocol.md,
                                "Terms"), took back an event given before: value its seq, the other
                                fields that event's (its kind aside) */
  BALL_NET_EVENT_GAP,        /* events never came: value how many (seqs skipped) */
  BALL_NET_EVENT_KIND_COUNT
} ball_net_event_kind;

/* Why (docs/protocol.md, "Events" and idl/ball.idl's Reason). */
typedef enum ball_net_reason {
  BALL_NET_REASON_NONE = 0,
  BALL_NET_POINT_DOUBLE_BOUNCE,   /* the ball bounced twice on the receiver's side */
  BALL_NET_POINT_OUT,             /* the first bounce after a hit was outside the opponent's court */
  BALL_NET_POINT_NET,             /* the ball hit the net and came down on the hitter's side */
  BALL_NET_POINT_OWN_SIDE,        /* the first bounce after a hit was on the hitter's side */
  BALL_NET_POINT_NOT_RETURNED,    /* after bouncing in, the ball left the court or lay still */
  BALL_NET_POINT_LET,             /* the rally ran too long: replayed, nobody scores */
  BALL_NET_PAUSE_VANISHED,        /* a player's samples stopped or its writer died */
  BALL_NET_PAUSE_LEFT,            /* a player left its slot */
  BALL_NET_PAUSE_REQUESTED,       /* a player asked for it */
  BALL_NET_REFUSED_SLOT_HELD,     /* the slot is held by another participant that is present */
  BALL_NET_REFUSED_NOT_PLAYER,    /* only a participant holding a slot of the match may do that */
  BALL_NET_REFUSED_BAD_VALUE,     /* a field out of range */
  BALL_NET_REFUSED_NO_ROOM,       /* no free slot, or no room for another match */
  BALL_NET_REFUSED_STATE,         /* not possible in the match's state */
  BALL_NET_REASON_COUNT
} ball_net_reason;

typedef struct ball_net_event {
  uint32_t match;             /* the match */
  uint32_t seq;               /* the server's event number (docs/protocol.md); 0 for the library's own */
  ball_net_event_kind kind;
  int index;                  /* by kind, above */
  int side;                   /* collisions: 0 x < net, 1 beyond; POINT: the winner, -1 a let */
  int in_play;                /* collisions: during a rally, before its point was decided */
  int sound;                  /* collisions: loud enough for the paper's sound */
  double time;                /* sim s it happened */
  double local_time;          /* the caller's clock at that sim time (as the clock maps it now) */
  ball_vec3 point;            /* m: the ball's centre at a collision */
  ball_vec3 velocity_in;      /* m/s */
  ball_vec3 velocity_out;     /* m/s */
  ball_net_reason reason;     /* POINT, PAUSE, REFUSED */
  int score[2];               /* points of side 0 and side 1 after it */
  double value;               /* LEVEL, TIME_BASE, VOIDED, GAP: see the kind */
  uint32_t server;            /* the server that wrote it (SERVER: the new server) */
} ball_net_event;

/* Takes what came from the servers, resends what they have not answered,
 * and gives the events of every match the client follows, each once, in
 * order (by match, by seq): up to cap into out, *n of them; more wait for
 * the next call. */
BALL_NET_API ball_status ball_net_poll(ball_net_client *client, ball_net_event *out, int cap, int *n);

/* Names, for logs: "floor", "double_bounce", "playing", "racket", ... ("unknown" past the list). */
BALL_NET_API const char *ball_net_event_kind_name(ball_net_event_kind kind);
BALL_NET_API const char *ball_net_reason_name(ball_net_reason reason);
BALL_NET_API const char *ball_net_state_name(ball_net_state state);
BALL_NET_API const char *ball_net_cause_name(ball_net_cause cause);

/* ---- a tap: every sample as it came ---------------------------------------- */

/* A recorder's or a relay's hook: `line` is one sample the client took
 * from the domain, as one JSON object without a newline, `length` bytes,
 * NUL-terminated, alive during the call. The lines are those of
 * `ball-watch --record` (docs/client.md, "A tap"): "type" (match_info,
 * match_model, segment, event, state, racket_sample with the config's
 * rackets, server_status with its server_status, and "ready" once, when
 * the client first hears a server), the sample's fields, "recv", the
 * realtime clock at its reception, s, and "sent", its writer's realtime
 * clock at its writing (its DDS source timestamp; absent when not known),
 * and "trusted", the library's verdict: true when the sample passed the
 * trust rules of a match the client follows (for a MatchInfo, of one it
 * lists), with "anew": true on a MatchInfo that started a followed match
 * anew. Every sample of every match comes, the refused ones too. A match
 * the client begins to follow (ball_net_watch, ball_net_join) takes the
 * newest segments the client kept of it: each comes again, "kept": true,
 * with the match's verdict. */
typedef void (*ball_net_tap)(void *user, const char *line, size_t length);

/* Sets the client's tap (NULL: none), called with `user` from within
 * ball_net_poll (and ball_net_watch and ball_net_join, for the kept
 * segments), in the caller's thread, once per sample, in the order
 * taken. The tap may call the client's other functions but ball_net_poll,
 * ball_net_watch, ball_net_join, ball_net_close and ball_net_set_tap
 * (BALL_EINVAL) and ball_net_free (which then does nothing). */
BALL_NET_API ball_status ball_net_set_tap(ball_net_client *client, ball_net_tap tap, void *user);

/* ---- status -------------------------------------------------------------- */

typedef struct ball_net_status {
  uint32_t server;             /* the match's server */
  int clock_known;             /* 1: the match's clock is known (a MatchInfo came) */
  double clock_offset;         /* s: the caller's clock minus the server's, as estimated (it includes the
                                  smallest one-way delay: docs/protocol.md, "Time") */
  double clock_uncertainty;    /* s: the median of the offsets seen over the last couple of seconds above
                                  their minimum: how far one sample's clock reading strays */
  double delay;                /* s: the median one-way delay of the server's samples (their DDS source
                                  timestamps to their reception; needs synchronised clocks across hosts) */
  uint64_t segments;           /* segments taken */
  uint64_t events;             /* events given */
  uint64_t refused;            /* server samples not taken: another server's, numbers out of range, a clock
                                  pair or a seq that does not fit (docs/protocol.md, "Clients that trust no one") */
  uint64_t lost;               /* events that never came (gaps in their seqs) */
  uint64_t late;               /* segments that came after their t0 on this client's clock */
  uint64_t voided;             /* events a correction, or a newer owner's other event of their seq, took back */
  uint64_t samples;            /* racket poses written */
  uint64_t link_lost;          /* racket poses the simulated network lost (ball_net_config's link_loss) */
  uint64_t write_failures;     /* writes DDS refused (poses and controls) */
  uint64_t bytes_in;           /* payload bytes of the match's samples taken (CDR, without the RTPS, UDP and IP
                                  headers, acknowledgements, resends and discovery) */
  uint64_t bytes_out;          /* and of the poses and requests written for it */
  uint64_t untrusted;          /* under DDS Security, samples of any match refused because their writer lacks the
                                  certificate bound to the server id they claim (the config's servers): the
                                  client's count, the same in every match's status */
  uint64_t rackets;            /* the players' racket samples taken (ball_net_config.rackets) */
  uint64_t rackets_refused;    /* and not taken: not from the slot's holder, a slot the match lacks, not newer
                                  than the slot's newest, or come before the match's model */
  uint32_t term;               /* the term of the match's owner whose samples are taken (docs/protocol.md, "Terms") */
  uint64_t old_owner;          /* server samples of an older owner than one taken (a lower term): not taken */
} ball_net_status;

/* The status of a match the client follows. BALL_ENOMATCH: it does not. */
BALL_NET_API ball_status ball_net_status_of(const ball_net_client *client, uint32_t match, ball_net_status *out);

/* ---- for bindings ---------------------------------------------------------- */

typedef enum ball_net_type {
  BALL_NET_TYPE_CONFIG = 0,
  BALL_NET_TYPE_MATCH,
  BALL_NET_TYPE_BALL,
  BALL_NET_TYPE_EVENT,
  BALL_NET_TYPE_STATUS,
  BALL_NET_TYPE_PREDICTION,
  BALL_NET_TYPE_SLOT,
  BALL_NET_TYPE_COUNT
} ball_net_type;

/* sizeof the public struct, so that a binding can check its own layout; 0
 * past the list. */
BALL_NET_API size_t ball_net_sizeof(ball_net_type type);

/* offsetof a member of the public struct, by its name in this header
 * ("clock_user", "slots", "score"); (size_t)-1 for a name the struct has
 * not. */
BALL_NET_API size_t ball_net_offsetof(ball_net_type type, const char *field);

/* The name of the struct's member `index` (0, 1, ... in the header's
 * order); NULL past the last. A binding walks them and finds each, at its
 * ball_net_offsetof, in its own declaration: a member added in what was
 * padding changes no size and no other member's place. */
BALL_NET_API const char *ball_net_field(ball_net_type type, int index);

#ifdef __cplusplus
}
#endif

#endif /* BALL_NET_H */
