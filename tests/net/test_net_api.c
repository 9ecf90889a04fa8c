/* The client library's C API with bad input (ball/net.h): every call
 * refuses NULL, a closed client, a match it does not follow or hold a slot
 * of, NaN and out-of-range values with its status and a sentence, and
 * changes nothing. With a server (argv: the ball-server program), the
 * same for racket poses of a slot it holds. A CMocka test on the DDS
 * domain its ctest case gives it (BALL_TEST_DOMAIN); it stops the server it
 * starts, also when a check fails. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include <ball/net.h>

static const char *server_program = NULL;
static pid_t server_pid = -1;

static void pause_seconds(double s) {
  struct timespec ts;
  ts.tv_sec = (time_t)s;
  ts.tv_nsec = (long)((s - (double)ts.tv_sec) * 1e9);
  nanosleep(&ts, NULL);
}

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void stop_server(void) {
  if (server_pid > 0) {
    kill(server_pid, SIGTERM);
    waitpid(server_pid, NULL, 0);
    server_pid = -1;
  }
}

static int stopped(void **state) {
  (void)state;
  stop_server();
  return 0;
}

static ball_net_client *open_client(void) {
  ball_net_config c;
  ball_net_client *client = NULL;
  char why[256] = "";
  ball_net_config_default(&c);
  c.domain = BALL_TEST_DOMAIN;
  c.max_matches = 16;
  assert_int_equal(ball_net_open(&c, &client, why, sizeof why), BALL_OK);
  assert_string_equal(why, "");
  assert_non_null(client);
  return client;
}

/* open refuses a bad config with a sentence naming what is wrong, and no client */
static void open_refuses_a_bad_config(void **state) {
  ball_net_config c;
  ball_net_client *client = (ball_net_client *)&c; /* must come back NULL */
  char why[256];
  char tiny[8];
  (void)state;
  assert_int_equal(ball_net_open(NULL, &client, why, sizeof why), BALL_EINVAL);
  assert_null(client);
  ball_net_config_default(&c);
  assert_int_equal(ball_net_open(&c, NULL, why, sizeof why), BALL_EINVAL);
  c.domain = 233;
  assert_int_equal(ball_net_open(&c, &client, why, sizeof why), BALL_ERANGE);
  assert_null(client);
  assert_non_null(strstr(why, "domain 233"));
  assert_int_equal(ball_net_open(&c, &client, tiny, sizeof tiny), BALL_ERANGE);
  assert_int_equal(strlen(tiny), sizeof tiny - 1); /* cut, NUL-terminated */
  ball_net_config_default(&c);
  c.max_matches = 5000;
  assert_int_equal(ball_net_open(&c, &client, why, sizeof why), BALL_ERANGE);
  /* the simulated network's ranges (ball/net.h), each bound and NaN */
  {
    double *const knob[] = {&c.link_delay, &c.link_jitter, &c.link_loss};
    const double beyond[] = {10.001, 1.001, 0.901};
    size_t i;
    for (i = 0; i < 3; i++) {
      ball_net_config_default(&c);
      *knob[i] = beyond[i];
      assert_int_equal(ball_net_open(&c, &client, why, sizeof why), BALL_ERANGE);
      assert_non_null(strstr(why, "link_"));
      *knob[i] = -0.001;
      assert_int_equal(ball_net_open(&c, &client, why, sizeof why), BALL_ERANGE);
      *knob[i] = NAN;
      assert_int_equal(ball_net_open(&c, &client, why, sizeof why), BALL_ERANGE);
      assert_null(client);
    }
  }
  ball_net_config_default(&c);
  c.servers = "1,x";
  assert_int_equal(ball_net_open(&c, &client, why, sizeof why), BALL_ERANGE);
  assert_non_null(strstr(why, "1,x"));
  c.servers = "1=server1";
  assert_int_equal(ball_net_open(&c, &client, why, sizeof why), BALL_EINVAL);
  ball_net_config_default(&c);
  c.identity = "player";
  assert_int_equal(ball_net_open(&c, &client, why, sizeof why), BALL_EINVAL);
  ball_net_config_default(&c);
  c.followed_only = 2;
  assert_int_equal(ball_net_open(&c, &client, why, sizeof why), BALL_ERANGE);
  assert_non_null(strstr(why, "followed_only"));
  ball_net_config_default(&c);
  c.domain = BALL_TEST_DOMAIN;
  c.qos_file = "/nonexistent/qos.xml";
  assert_int_equal(ball_net_open(&c, &client, why, sizeof why), BALL_ENETWORK);
  assert_non_null(strstr(why, "/nonexistent/qos.xml"));
  ball_net_config_default(&c);
  c.domain = BALL_TEST_DOMAIN;
  c.participant = "no_such_profile";
  assert_int_equal(ball_net_open(&c, &client, why, sizeof why), BALL_ENETWORK);
  assert_non_null(strstr(why, "no_such_profile"));
  assert_null(client);
  assert_int_equal(ball_net_open(&c, &client, NULL, 0), BALL_ENETWORK); /* no room for a sentence: fine */
}

/* every call refuses a NULL client or out-pointer */
static void every_call_refuses_null(void **state) {
  ball_net_client *c = open_client();
  ball_net_match m;
  ball_net_ball b;
  ball_net_event e[4];
  ball_net_status s;
  ball_prediction p;
  ball_model model;
  double t;
  int n, slot;
  ball_vec3 v = {1, 1, 1};
  (void)state;
  assert_int_equal(ball_net_matches(NULL, &m, 1, &n), BALL_EINVAL);
  assert_int_equal(ball_net_matches(c, &m, 1, NULL), BALL_EINVAL);
  assert_int_equal(ball_net_matches(c, NULL, 1, &n), BALL_EINVAL);
  assert_int_equal(ball_net_matches(c, &m, -1, &n), BALL_EINVAL);
  assert_int_equal(ball_net_matches(c, NULL, 0, &n), BALL_OK);
  assert_int_equal(n, 0);
  assert_int_equal(ball_net_match_info(NULL, 0, &m), BALL_EINVAL);
  assert_int_equal(ball_net_match_info(c, 0, NULL), BALL_EINVAL);
  assert_int_equal(ball_net_create(NULL, 0, "tennis", 2, BALL_LEVEL_EASY), BALL_EINVAL);
  assert_int_equal(ball_net_create(c, 0, NULL, 2, BALL_LEVEL_EASY), BALL_EINVAL);
  assert_int_equal(ball_net_join(NULL, 0, -1), BALL_EINVAL);
  assert_int_equal(ball_net_leave(NULL, 0, -1), BALL_EINVAL);
  assert_int_equal(ball_net_slot_of(NULL, 0, &slot), BALL_EINVAL);
  assert_int_equal(ball_net_slot_of(c, 0, NULL), BALL_EINVAL);
  assert_int_equal(ball_net_watch(NULL, 0), BALL_EINVAL);
  assert_int_equal(ball_net_unwatch(NULL, 0), BALL_EINVAL);
  assert_int_equal(ball_net_ask(NULL, 0, BALL_NET_SERVE, 0.0), BALL_EINVAL);
  assert_int_equal(ball_net_push(NULL, 0, 0, 1.0, v, v), BALL_EINVAL);
  assert_int_equal(ball_net_ball_at(NULL, 0, 1.0, &b), BALL_EINVAL);
  assert_int_equal(ball_net_ball_at(c, 0, 1.0, NULL), BALL_EINVAL);
  assert_int_equal(ball_net_predict(NULL, 0, 1.0, 1.0, 0.1, &p), BALL_EINVAL);
  assert_int_equal(ball_net_predict(c, 0, 1.0, 1.0, 0.1, NULL), BALL_EINVAL);
  assert_int_equal(ball_net_sim_time(NULL, 0, 1.0, &t), BALL_EINVAL);
  assert_int_equal(ball_net_sim_time(c, 0, 1.0, NULL), BALL_EINVAL);
  assert_int_equal(ball_net_local_time(NULL, 0, 1.0, &t), BALL_EINVAL);
  assert_int_equal(ball_net_local_time(c, 0, 1.0, NULL), BALL_EINVAL);
  assert_int_equal(ball_net_model(NULL, 0, &model), BALL_EINVAL);
  assert_int_equal(ball_net_model(c, 0, NULL), BALL_EINVAL);
  assert_int_equal(ball_net_poll(NULL, e, 4, &n), BALL_EINVAL);
  assert_int_equal(ball_net_poll(c, e, 4, NULL), BALL_EINVAL);
  assert_int_equal(ball_net_poll(c, NULL, 4, &n), BALL_EINVAL);
  assert_int_equal(ball_net_status_of(NULL, 0, &s), BALL_EINVAL);
  assert_int_equal(ball_net_status_of(c, 0, NULL), BALL_EINVAL);
  assert_int_equal(ball_net_close(NULL), BALL_EINVAL);
  assert_string_equal(ball_net_message(NULL), "");
  ball_net_free(NULL);
  ball_net_free(c);
}

/* a match the client does not follow, a slot it does not hold, values out of range */
static void calls_on_a_match_it_does_not_follow(void **state) {
  ball_net_client *c = open_client();
  ball_net_match m;
  ball_net_ball b;
  ball_net_status s;
  ball_prediction p;
  ball_model model;
  ball_vec3 center = {1, 1, 1}, normal = {1, 0, 0};
  double t;
  int slot = 77;
  (void)state;
  memset(&p, 0, sizeof p);
  assert_int_equal(ball_net_match_info(c, 3, &m), BALL_ENOMATCH);
  assert_true(strlen(ball_net_message(c)) > 0);
  assert_int_equal(ball_net_ball_at(c, 3, now(), &b), BALL_ENOMATCH);
  assert_non_null(strstr(ball_net_message(c), "match 3"));
  assert_int_equal(ball_net_predict(c, 3, now(), 1.0, 0.1, &p), BALL_ENOMATCH);
  assert_int_equal(ball_net_status_of(c, 3, &s), BALL_ENOMATCH);
  assert_int_equal(ball_net_slot_of(c, 3, &slot), BALL_ENOMATCH);
  assert_int_equal(slot, 77); /* unchanged */
  assert_int_equal(ball_net_model(c, 3, &model), BALL_ENOMATCH);
  assert_int_equal(ball_net_sim_time(c, 3, 1.0, &t), BALL_ENOMATCH);
  assert_int_equal(ball_net_local_time(c, 3, 1.0, &t), BALL_ENOMATCH);
  assert_int_equal(ball_net_leave(c, 3, -1), BALL_ENOMATCH);
  assert_int_equal(ball_net_unwatch(c, 3), BALL_ENOMATCH);
  assert_int_equal(ball_net_push(c, 3, 0, now(), center, normal), BALL_ENOMATCH);
  assert_int_equal(ball_net_ask(c, 3, BALL_NET_SERVE, 0.0), BALL_ENOMATCH);
  /* followed, no server: not yet */
  assert_int_equal(ball_net_watch(c, 3), BALL_OK);
  assert_string_equal(ball_net_message(c), "");
  assert_int_equal(ball_net_ball_at(c, 3, now(), &b), BALL_EAGAIN);
  assert_int_equal(ball_net_ball_at(c, 3, NAN, &b), BALL_ENONFINITE);
  assert_int_equal(ball_net_predict(c, 3, now(), 1.0, 0.1, &p), BALL_EAGAIN);
  assert_int_equal(ball_net_predict(c, 3, INFINITY, 1.0, 0.1, &p), BALL_ENONFINITE);
  assert_int_equal(ball_net_model(c, 3, &model), BALL_EAGAIN);
  assert_int_equal(ball_net_sim_time(c, 3, 1.0, &t), BALL_EAGAIN);
  assert_int_equal(ball_net_sim_time(c, 3, NAN, &t), BALL_ENONFINITE);
  assert_int_equal(ball_net_slot_of(c, 3, &slot), BALL_OK);
  assert_int_equal(slot, -1);
  assert_int_equal(ball_net_status_of(c, 3, &s), BALL_OK);
  assert_int_equal(s.clock_known, 0);
  assert_int_equal(ball_net_push(c, 3, 0, now(), center, normal), BALL_ENOMATCH); /* a spectator */
  assert_int_equal(ball_net_leave(c, 3, -1), BALL_ENOMATCH);
  /* values out of range */
  assert_int_equal(ball_net_join(c, 3, 4), BALL_ERANGE);
  assert_int_equal(ball_net_join(c, 3, -2), BALL_ERANGE);
  assert_int_equal(ball_net_create(c, 9, "../etc/passwd", 2, BALL_LEVEL_EASY), BALL_ERANGE);
  assert_int_equal(ball_net_create(c, 9, "", 2, BALL_LEVEL_EASY), BALL_ERANGE);
  assert_int_equal(ball_net_create(c, 9, "tennis", 0, BALL_LEVEL_EASY), BALL_ERANGE);
  assert_int_equal(ball_net_create(c, 9, "tennis", 2, (ball_level)7), BALL_ERANGE);
  assert_int_equal(ball_net_ask(c, 3, (ball_net_request)99, 0.0), BALL_EINVAL);
  assert_int_equal(ball_net_ask(c, 3, BALL_NET_LEVEL, NAN), BALL_ENONFINITE);
  assert_int_equal(ball_net_unwatch(c, 3), BALL_OK);
  assert_int_equal(ball_net_ball_at(c, 3, now(), &b), BALL_ENOMATCH);
  ball_net_free(c);
}

/* a closed client refuses every call but ball_net_message and ball_net_free */
static void a_closed_client_refuses_everything(void **state) {
  ball_net_client *c = open_client();
  ball_net_match m;
  ball_net_ball b;
  ball_net_event e[4];
  ball_net_status s;
  ball_vec3 v = {1, 1, 1};
  int n = 5, slot;
  (void)state;
  assert_int_equal(ball_net_watch(c, 1), BALL_OK);
  assert_int_equal(ball_net_close(c), BALL_OK);
  assert_int_equal(ball_net_close(c), BALL_ECLOSED);
  assert_non_null(strstr(ball_net_message(c), "closed"));
  assert_int_equal(ball_net_matches(c, &m, 1, &n), BALL_ECLOSED);
  assert_int_equal(n, 5);
  assert_int_equal(ball_net_match_info(c, 1, &m), BALL_ECLOSED);
  assert_int_equal(ball_net_create(c, 1, "tennis", 2, BALL_LEVEL_EASY), BALL_ECLOSED);
  assert_int_equal(ball_net_join(c, 1, -1), BALL_ECLOSED);
  assert_int_equal(ball_net_leave(c, 1, -1), BALL_ECLOSED);
  assert_int_equal(ball_net_slot_of(c, 1, &slot), BALL_ECLOSED);
  assert_int_equal(ball_net_watch(c, 1), BALL_ECLOSED);
  assert_int_equal(ball_net_unwatch(c, 1), BALL_ECLOSED);
  assert_int_equal(ball_net_ask(c, 1, BALL_NET_SERVE, 0.0), BALL_ECLOSED);
  assert_int_equal(ball_net_push(c, 1, 0, 1.0, v, v), BALL_ECLOSED);
  assert_int_equal(ball_net_ball_at(c, 1, 1.0, &b), BALL_ECLOSED);
  assert_int_equal(ball_net_poll(c, e, 4, &n), BALL_ECLOSED);
  assert_int_equal(ball_net_status_of(c, 1, &s), BALL_ECLOSED);
  ball_net_free(c);
}

/* the names and sizes for bindings */
static void names_and_sizes(void **state) {
  int k;
  (void)state;
  for (k = 0; k < BALL_NET_EVENT_KIND_COUNT; k++)
    assert_string_not_equal(ball_net_event_kind_name((ball_net_event_kind)k), "unknown");
  assert_string_equal(ball_net_event_kind_name(BALL_NET_EVENT_KIND_COUNT), "unknown");
  assert_string_equal(ball_net_event_kind_name(BALL_NET_EVENT_RACKET), "racket");
  assert_string_equal(ball_net_event_kind_name(BALL_NET_EVENT_VOIDED), "voided");
  for (k = 0; k < BALL_NET_REASON_COUNT; k++)
    assert_string_not_equal(ball_net_reason_name((ball_net_reason)k), "unknown");
  assert_string_equal(ball_net_reason_name(BALL_NET_POINT_DOUBLE_BOUNCE), "double_bounce");
  assert_string_equal(ball_net_reason_name((ball_net_reason)-1), "unknown");
  assert_string_equal(ball_net_state_name(BALL_NET_PLAYING), "playing");
  assert_string_equal(ball_net_cause_name(BALL_NET_CAUSE_WALL), "wall");
  assert_int_equal(ball_net_sizeof(BALL_NET_TYPE_EVENT), sizeof(ball_net_event));
  assert_int_equal(ball_net_sizeof(BALL_NET_TYPE_MATCH), sizeof(ball_net_match));
  assert_int_equal(ball_net_sizeof(BALL_NET_TYPE_PREDICTION), sizeof(ball_prediction));
  assert_int_equal(ball_net_sizeof(BALL_NET_TYPE_COUNT), 0);
  assert_int_equal(ball_net_offsetof(BALL_NET_TYPE_CONFIG, "ball_states"), offsetof(ball_net_config, ball_states));
  assert_int_equal(ball_net_offsetof(BALL_NET_TYPE_CONFIG, "clock_user"), offsetof(ball_net_config, clock_user));
  assert_int_equal(ball_net_offsetof(BALL_NET_TYPE_MATCH, "court_z"), offsetof(ball_net_match, court_z));
  assert_int_equal(ball_net_offsetof(BALL_NET_TYPE_SLOT, "mine"), offsetof(ball_net_slot, mine));
  assert_int_equal(ball_net_offsetof(BALL_NET_TYPE_BALL, "flight"), offsetof(ball_net_ball, flight));
  assert_int_equal(ball_net_offsetof(BALL_NET_TYPE_EVENT, "server"), offsetof(ball_net_event, server));
  assert_int_equal(ball_net_offsetof(BALL_NET_TYPE_STATUS, "bytes_out"), offsetof(ball_net_status, bytes_out));
  assert_int_equal(ball_net_offsetof(BALL_NET_TYPE_PREDICTION, "end"), offsetof(ball_prediction, end));
  assert_true(ball_net_offsetof(BALL_NET_TYPE_MATCH, "no_such") == (size_t)-1);
  assert_true(ball_net_offsetof(BALL_NET_TYPE_MATCH, NULL) == (size_t)-1);
  assert_true(ball_net_offsetof(BALL_NET_TYPE_COUNT, "id") == (size_t)-1);
  assert_string_equal(ball_net_field(BALL_NET_TYPE_SLOT, 0), "held");
  assert_string_equal(ball_net_field(BALL_NET_TYPE_SLOT, 2), "mine");
  assert_null(ball_net_field(BALL_NET_TYPE_SLOT, 3));
  assert_null(ball_net_field(BALL_NET_TYPE_SLOT, -1));
  assert_null(ball_net_field(BALL_NET_TYPE_COUNT, 0));
  for (k = 0; ball_net_field(BALL_NET_TYPE_CONFIG, k); k++) {
  }
  assert_int_equal(k, 21); /* every member of ball_net_config */
  assert_int_equal(ball_net_offsetof(BALL_NET_TYPE_CONFIG, "followed_only"), offsetof(ball_net_config, followed_only));
  for (k = 0; k < BALL_STATUS_COUNT; k++) assert_string_not_equal(ball_strerror((ball_status)k), "unknown status");
}

/* With a server: a slot held, then poses with NaN, a zero or huge normal, a
 * centre beyond 1e9 m and a time not after the previous one are refused and
 * count nothing; a good one is written; close leaves the slot. */
static void poses_of_a_slot_held(void **state) {
  char domain[16];
  ball_net_client *c;
  ball_net_event e[32];
  ball_net_status s;
  ball_vec3 center = {1.0, 1.0, 5.0}, normal = {1, 0, 0}, bad;
  double start, t;
  uint64_t pushed;
  int n, slot = -1;
  (void)state;
  if (!server_program) skip();
  snprintf(domain, sizeof domain, "%d", BALL_TEST_DOMAIN);
  server_pid = fork();
  if (server_pid == 0) {
    execl(server_program, server_program, "--domain", domain, "--matches", "1", "--startup-wait", "0", "--duration",
          "60", "--status-interval", "100", (char *)NULL);
    _exit(127);
  }
  c = open_client();
  assert_int_equal(ball_net_join(c, 0, 0), BALL_OK);
  for (start = now(); slot < 0 && now() - start < 15.0;) {
    assert_int_equal(ball_net_poll(c, e, 32, &n), BALL_OK);
    assert_int_equal(ball_net_slot_of(c, 0, &slot), BALL_OK);
    pause_seconds(0.02);
  }
  assert_int_equal(slot, 0);
  /* both slots held (two players at one console) and present: the match serves */
  {
    ball_net_match m;
    ball_net_ball b;
    ball_vec3 far = {20.0, 1.0, 5.0}, back = {-1, 0, 0};
    assert_int_equal(ball_net_join(c, 0, 1), BALL_OK);
    for (start = now(); now() - start < 15.0 && ball_net_ball_at(c, 0, now(), &b) != BALL_OK;) {
      assert_int_equal(ball_net_poll(c, e, 32, &n), BALL_OK);
      ball_net_push(c, 0, 1, now(), far, back);
      pause_seconds(0.05);
    }
    assert_int_equal(ball_net_match_info(c, 0, &m), BALL_OK);
    assert_true(m.slots[0].mine && m.slots[1].mine);
    assert_int_equal(ball_net_ball_at(c, 0, now(), &b), BALL_OK);
    /* a spectator that reads the rackets sees slot 1's where its holder put it; the player's
       client does not read them */
    {
      ball_net_config sc;
      ball_net_client *spec = NULL;
      ball_racket_pose p;
      ball_net_status ss;
      ball_status st = BALL_EAGAIN;
      ball_net_config_default(&sc);
      sc.domain = BALL_TEST_DOMAIN;
      sc.max_matches = 16;
      sc.rackets = 1;
      assert_int_equal(ball_net_open(&sc, &spec, NULL, 0), BALL_OK);
      assert_int_equal(ball_net_watch(spec, 0), BALL_OK);
      for (start = now(); now() - start < 15.0 && st != BALL_OK;) {
        assert_int_equal(ball_net_poll(c, e, 32, &n), BALL_OK);
        assert_int_equal(ball_net_poll(spec, e, 32, &n), BALL_OK);
        ball_net_push(c, 0, 1, now(), far, back);
        st = ball_net_racket(spec, 0, 1, now(), &p);
        pause_seconds(0.05);
      }
      assert_int_equal(st, BALL_OK);
      assert_true(p.center.x == far.x && p.center.y == far.y && p.center.z == far.z); /* one place: exact */
      assert_true(p.normal.x == -1.0 && p.normal.y == 0.0 && p.normal.z == 0.0);
      assert_int_equal(ball_net_racket(spec, 0, 2, now(), &p), BALL_ERANGE);
      assert_int_equal(ball_net_racket(spec, 0, 1, NAN, &p), BALL_ENONFINITE);
      assert_int_equal(ball_net_racket(spec, 0, 1, now(), NULL), BALL_EINVAL);
      assert_int_equal(ball_net_racket(spec, 1, 1, now(), &p), BALL_ENOMATCH);
      assert_int_equal(ball_net_status_of(spec, 0, &ss), BALL_OK);
      assert_true(ss.rackets >= 1); /* (and some refused: those that came before the match's model) */
      assert_int_equal(ball_net_racket(c, 0, 1, now(), &p), BALL_EINVAL); /* rackets not read */
      assert_non_null(strstr(ball_net_message(c), "rackets"));
      ball_net_free(spec);
    }
  }
  t = now();
  bad = center;
  bad.y = NAN;
  assert_int_equal(ball_net_push(c, 0, 0, t, bad, normal), BALL_ENONFINITE);
  assert_int_equal(ball_net_push(c, 0, 0, NAN, center, normal), BALL_ENONFINITE);
  bad.x = bad.y = bad.z = 0.0;
  assert_int_equal(ball_net_push(c, 0, 0, t, center, bad), BALL_ERANGE);
  bad.x = 2e6;
  assert_int_equal(ball_net_push(c, 0, 0, t, center, bad), BALL_ERANGE);
  bad = center;
  bad.z = 2e9;
  assert_int_equal(ball_net_push(c, 0, 0, t, bad, normal), BALL_ERANGE);
  assert_int_equal(ball_net_push(c, 0, 2, t, center, normal), BALL_ENOMATCH); /* not its slot */
  assert_int_equal(ball_net_status_of(c, 0, &s), BALL_OK);
  pushed = s.samples; /* (slot 1's poses so far: nothing refused counted) */
  assert_int_equal(ball_net_push(c, 0, 0, t, center, normal), BALL_OK);
  assert_string_equal(ball_net_message(c), "");
  assert_int_equal(ball_net_push(c, 0, 0, t, center, normal), BALL_ESTALE);
  assert_int_equal(ball_net_push(c, 0, 0, t - 1.0, center, normal), BALL_ESTALE);
  assert_int_equal(ball_net_push(c, 0, 0, t + 0.05, center, normal), BALL_OK);
  assert_int_equal(ball_net_status_of(c, 0, &s), BALL_OK);
  assert_int_equal(s.samples, pushed + 2);
  assert_int_equal(s.write_failures, 0);
  assert_int_equal(s.clock_known, 1);
  /* the server goes away: the ball still answers from what came; the
     match leaves the list 10 s after its last MatchInfo (docs/client.md) */
  {
    ball_net_match m;
    ball_net_ball b;
    double gone;
    assert_int_equal(ball_net_match_info(c, 0, &m), BALL_OK);
    stop_server();
    gone = now();
    while (now() - gone < 12.0 && ball_net_match_info(c, 0, &m) == BALL_OK) {
      assert_int_equal(ball_net_poll(c, e, 32, &n), BALL_OK);
      pause_seconds(0.05);
    }
    assert_int_equal(ball_net_match_info(c, 0, &m), BALL_ENOMATCH);
    assert_true(now() - gone > 6.0 && now() - gone < 10.2); /* its last info came up to 4 s before the stop */
    assert_int_equal(ball_net_ball_at(c, 0, now(), &b), BALL_OK);
  }
  assert_int_equal(ball_net_close(c), BALL_OK);
  ball_net_free(c);
}

int main(int argc, char **argv) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(open_refuses_a_bad_config),
      cmocka_unit_test(every_call_refuses_null),
      cmocka_unit_test(calls_on_a_match_it_does_not_follow),
      cmocka_unit_test(a_closed_client_refuses_everything),
      cmocka_unit_test(names_and_sizes),
      cmocka_unit_test_teardown(poses_of_a_slot_held, stopped),
  };
  int rc;
  if (argc > 1) server_program = argv[1];
  rc = cmocka_run_group_tests(tests, NULL, NULL);
  stop_server(); /* (a failed check longjmps out of the case) */
  return rc;
}
