/* The client library on a secure domain (ball/net.h with security_dir and
 * identity; docs/security.md): a ball-server under DDS Security, the
 * client as m0-a (granted match/0 only) taking the server topics only from
 * the holder of server1's certificate. It joins match 0 and writes its
 * poses there (its writers in the partition match/0); its JOIN of match 1
 * is never written (its permissions grant no match/1: the write is
 * refused and counted); a client with an identity the CA did not sign is
 * refused at open. argv: the ball-server program, the certificates'
 * folder (./run certs). Stops the server it starts, also when a check fails. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <signal.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cmocka.h>

#include <ball/net.h>

static const char *server_program = NULL, *certs = NULL;
static pid_t server_pid = -1;

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void pause_seconds(double s) {
  struct timespec ts;
  ts.tv_sec = (time_t)s;
  ts.tv_nsec = (long)((s - (double)ts.tv_sec) * 1e9);
  nanosleep(&ts, NULL);
}

static int stopped(void **state) {
  (void)state;
  if (server_pid > 0) {
    kill(server_pid, SIGTERM);
    waitpid(server_pid, NULL, 0);
    server_pid = -1;
  }
  return 0;
}

static ball_status open_reading(const char *identity, int rackets, ball_net_client **client, char *why,
                                size_t size) {
  ball_net_config c;
  ball_net_config_default(&c);
  c.rackets = rackets;
  c.domain = BALL_TEST_DOMAIN;
  c.security_dir = certs;
  c.identity = identity;
  c.servers = "1=server1";
  c.max_matches = 16;
  return ball_net_open(&c, client, why, size);
}

static ball_status open_as(const char *identity, ball_net_client **client, char *why, size_t size) {
  return open_reading(identity, 0, client, why, size);
}

static void a_certified_player_plays_its_own_match(void **state) {
  char domain[16], why[512] = "";
  ball_net_client *c = NULL;
  ball_net_event e[32];
  ball_net_status s;
  ball_vec3 center = {1.0, 1.0, 5.0}, normal = {1, 0, 0};
  double start;
  int n, slot = -1;
  (void)state;
  snprintf(domain, sizeof domain, "%d", BALL_TEST_DOMAIN);
  server_pid = fork();
  if (server_pid == 0) {
    execl(server_program, server_program, "--domain", domain, "--matches", "2", "--startup-wait", "0", "--duration",
          "60", "--status-interval", "100", "--secure", certs, "--identity", "server1", (char *)NULL);
    _exit(127);
  }
  assert_int_equal(open_as("m0-a", &c, why, sizeof why), BALL_OK);
  assert_int_equal(ball_net_join(c, 0, 0), BALL_OK);
  for (start = now(); slot < 0 && now() - start < 30.0;) {
    assert_int_equal(ball_net_poll(c, e, 32, &n), BALL_OK);
    assert_int_equal(ball_net_slot_of(c, 0, &slot), BALL_OK);
    pause_seconds(0.05);
  }
  assert_int_equal(slot, 0);
  assert_int_equal(ball_net_push(c, 0, 0, now(), center, normal), BALL_OK);
  assert_int_equal(ball_net_status_of(c, 0, &s), BALL_OK);
  assert_int_equal(s.samples, 1);
  assert_int_equal(s.write_failures, 0);
  assert_int_equal(s.server, 1);
  /* its partner's client (m0-b) reads the rackets of match 0 in its partition, m0-a's among them;
     the rackets of match 1 it is not granted: following match 1 is refused in DDS's words */
  {
    ball_net_client *b = NULL;
    ball_racket_pose p;
    ball_status st = BALL_EAGAIN;
    assert_int_equal(open_reading("m0-b", 1, &b, why, sizeof why), BALL_OK);
    assert_int_equal(ball_net_watch(b, 0), BALL_OK);
    for (start = now(); now() - start < 30.0 && st != BALL_OK;) {
      assert_int_equal(ball_net_poll(c, e, 32, &n), BALL_OK);
      assert_int_equal(ball_net_poll(b, e, 32, &n), BALL_OK);
      ball_net_push(c, 0, 0, now(), center, normal);
      st = ball_net_racket(b, 0, 0, now(), &p);
      pause_seconds(0.05);
    }
    assert_int_equal(st, BALL_OK);
    assert_true(p.center.x == center.x && p.center.y == center.y && p.center.z == center.z);
    assert_int_equal(ball_net_watch(b, 1), BALL_ENETWORK);
    assert_non_null(strstr(ball_net_message(b), "the transport cannot follow match 1"));
    assert_non_null(strstr(ball_net_message(b), "partition match/1"));
    assert_int_equal(ball_net_status_of(b, 1, &s), BALL_ENOMATCH);
    ball_net_free(b);
  }
  /* match 1: its partition is not m0-a's; DDS itself refuses the JOIN's writer, the call says so
     in DDS's words, and the client does not follow match 1 */
  assert_int_equal(ball_net_join(c, 1, 0), BALL_ENETWORK);
  assert_non_null(strstr(ball_net_message(c), "the transport refused the join of match 1"));
  assert_non_null(strstr(ball_net_message(c), "permissions do not grant it in partition match/1"));
  assert_int_equal(ball_net_status_of(c, 1, &s), BALL_ENOMATCH);
  assert_int_equal(ball_net_join(c, 1, 0), BALL_ENETWORK); /* asked again: the same answer */
  assert_int_equal(ball_net_close(c), BALL_OK);
  ball_net_free(c);
  /* an identity the CA did not sign (no such certificate): refused at open, with the file named */
  assert_int_equal(open_as("stranger", &c, why, sizeof why), BALL_ENETWORK);
  assert_null(c);
  assert_non_null(strstr(why, "stranger"));
}

int main(int argc, char **argv) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test_teardown(a_certified_player_plays_its_own_match, stopped),
  };
  int rc;
  if (argc != 3) {
    fprintf(stderr, "usage: test_net_secure BALL_SERVER CERTS\n");
    return 2;
  }
  server_program = argv[1];
  certs = argv[2];
  rc = cmocka_run_group_tests(tests, NULL, NULL);
  stopped(NULL);
  return rc;
}
