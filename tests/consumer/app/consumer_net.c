/* An outside program using the installed client library (ball/net.h): it
 * links libball-net alone, with no Fast DDS header or library of its own,
 * and opens nothing (no network): a config, a refused open and its
 * sentence, the names of a status and an event kind. */
#include <stdio.h>

#include <ball/net.h>

int main(void) {
  ball_net_config config;
  ball_net_client *client = NULL;
  char why[128];
  ball_status st;
  ball_net_config_default(&config);
  config.domain = 300;
  st = ball_net_open(&config, &client, why, sizeof why);
  if (st != BALL_ERANGE || client != NULL) return 1;
  printf("net: %s: %s; %s; %s\n", ball_strerror(st), why, ball_strerror(BALL_EAGAIN),
         ball_net_event_kind_name(BALL_NET_EVENT_RACKET));
  return 0;
}
