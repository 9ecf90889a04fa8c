# The DDS domain ids of the demo, the load benchmark and every networked
# test, stated here only: ball-demo's and ball-load's default --domain are
# compiled from this list, the tests take theirs from it
# (tests/server/tests.cmake), and the table of docs/server-reference.md ("DDS
# domains") is made from it and held to it by a test. Each user has an id
# of its own, so that runs at the same time never meet.
#   "user|id|what"
set(BALL_DDS_DOMAINS
  "ball-demo|42|`./run demo` (ball-demo's default `--domain`)"
  "ball-load|90|`./run bench-server` (ball-load's default `--domain`)"
  "bench-security|91|`./run bench-security` (its `--domain`)"
  "bench-wan|159|`./run bench-wan` (its `--domain`)"
  "bench-hit-cost|127|`./run hit-cost --server` (its `--domain`)"
  "bench-client|92|`./run bench-client` (its `--domain`)"
  "dds_rally|100|test: two bots rally"
  "dds_desync|101|test: the watcher's ball against the server's states"
  "dds_pause|102|test: a killed bot pauses its match"
  "dds_flood|103|test: 10,000 malformed samples"
  "dds_late_join|104|test: a watcher started mid-rally"
  "dds_lossy|105|test: a rally over a poor network"
  "dds_server_cli|106|test: ball-server's command line and config errors"
  "dds_busy|107|test: a second server for the same match"
  "dds_snapshots|108|test: ball-watch --snapshots"
  "dds_failover|109|test: a standby takes 10 matches over from a primary killed mid-rally"
  "dds_standby_killed|110|test: a standby killed: nothing a client sees changes"
  "dds_primary_back|111|test: the old primary restarted takes nothing back"
  "dds_claim|112|test: two claimants started together split the matches"
  "dds_standby_no_scene|130|test: a standby without the primary's scene file takes its court over from the wire"
  "dds_hosts_failover|139|test: a primary killed on one network namespace, its standby on another takes over, the watcher on a third sees nothing broken"
  "dds_hosts_standby_cut|140|test: the standby's network namespace cut off for 10 s and healed: the clients see nothing change"
  "dds_hosts_stall_4|143|test: the primary stopped for 4 s: the standby takes over at the next term, the primary yields on its return, the clients see nothing go back"
  "dds_hosts_stall_10|144|test: the primary stopped for 10 s: as for 4 s"
  "dds_hosts_cut_5|145|test: the primary's network namespace cut off for 5 s: the standby with the players takes over, the primary yields at the heal"
  "dds_hosts_cut_12|146|test: the primary's network namespace cut off for 12 s: as for 5 s"
  "dds_hosts_players_split|147|test: the players split between the primary's and the standby's namespaces for 10 s: both pause, no point decided apart, the standby's term plays on at the heal"
  "dds_hosts_claimants_meet|148|test: two claimants cut from each other claim one match, each in its own term, and when they meet the older term yields and the clients' stream does not change"
  "dds_hosts_primary_back|149|test: the old primary restarted on its namespace as a standby after the failover follows and takes nothing"
  "dds_wan_tcp|150|test: a match over the TCP profiles, the players and a watcher behind a home router's NAT"
  "dds_wan_secure|151|test: the same under DDS Security"
  "dds_wan_tls|152|test: the same over TLS, a stranger beside the players refused: no slot, no RTPS byte back, no UDP port"
  "dds_wan_udp|153|test: the same layout on UDP with a Discovery Server does not connect through the NAT"
  "dds_wan_failover|155|test: the primary killed over TCP, players behind the NAT: the standby on another host takes the match over, the rally goes on"
  "dds_wan_public_address|156|test: a server behind its data centre's port forward: announcing its own address nobody matches it, announcing the router's the players behind their NAT play"
  "dds_wan_delay|158|test: 150 ms each way (jitter 30 ms) through the test's relay between the players' LAN and the server: the match rallies, lag compensation finds the late hits, the watcher's ball is the server's"
  "dds_wan_refused|157|test: bad TCP and TLS options refused before any participant is made, each with a sentence"
  "dds_wan_bytes|160|test: what a player behind the NAT receives a second, its match alone and beside 24 more: flat within 10 % in its match's partition, growing when it reads every match"
  "dds_wan_renew|161|test: TCP clients that hear no server start anew after 5 s, then play once it comes"
  "dds_wan_stall|162|test: the primary stopped for 6 s over TCP, players behind the NAT: the standby takes over at the next term, the primary yields on its return, nothing of it reaches the watcher after"
  "dds_wan_link_cut|154|test: a player's link behind the NAT cut for 3 s: it comes back by itself, the match pauses and resumes, nothing lost or repeated"
  "dds_key_flood|113|test: a stranger floods a player's own keys: the player never vanishes"
  "dds_create_expires|114|test: a created match nobody joins goes, its MatchInfo disposed"
  "dds_secure_udp_disposal|163|test: the secure UDP domain's documented limit: one plaintext disposal datagram from a host without certificates removes a player for good"
  "dds_secure_udp_replay|164|test: 300 replayed announcements on the secure UDP domain from a host without certificates, then a certified join: the server lives, the rally goes on"
  "web_http_attack|165|test: the spectator page against hostile HTTP: header floods, slow heads, idle connections, per-address shares"
  "dds_phantom_matches|166|test: a stranger's copies of a MatchInfo as 70 made-up matches and as the match's own: the standby adopts none, the primary yields nothing"
  "dds_control_flood|167|test: a stranger's 5,000 LEAVEs a second in the bots' match: their JOINs go through at once, every control counted"
  "dds_yield_taken_back|169|test: a stranger heard as a server claims a newer term and goes quiet, then claims one and leaves: the primary yields and takes its match back both times"
  "dds_create_shares|170|test: one process of 5 participants CREATEs 2 matches each: 2 stand, a real CREATE is answered at once, a host address has its share"
  "dds_secure_own_flood|171|test: a certified player floods its own slot at 20,000 samples a second: its partner never vanishes, every sample counted once"
  "dds_secure_slots|168|test: slots bound to identities on the secure domain: a certified player JOINing another's slot is refused, the rally goes on"
  "dds_secure|115|test: DDS Security: no plaintext on the wire, strangers and other matches' players kept out"
  "demo_secure|116|test: the demo under DDS Security rallies"
  "demo_failover|138|test: `./run demo --failover`: the primary killed, the standby takes the match over, the rally goes on"
  "dds_junk_keys|117|test: 3000 made-up match ids: turned away at the door, the bots still rally"
  "dds_unreadable|129|test: samples no IDL type writes on every topic: counted at the door, everyone plays on"
  "dds_load_secure|118|test: ball-load under DDS Security: one identity granted every match plays them all"
  "dds_load_split|137|test: ball-load's bots in two processes count what one process does"
  "dds_forged_server|119|test: a stronger forged server's MatchInfo, segments and states: refused, the rally goes on"
  "dds_inbox_share|121|test: one slot's burst of 20,000 samples takes its own share of the inbox only"
  "dds_discovery_flood|122|test: 3000 made-up participant announcements: bounded memory, found again after their leases"
  "dds_lag|123|test: late-swinging bots behind 150 ms: lag compensation finds their hits, rewinds, no desync"
  "dds_lag_own|128|test: the same with rewind_own_hit: hits moved past their own racket's hit, no desync"
  "dds_create_flood|124|test: 1000 CREATEs a second under every id a CREATE may name: a real CREATE answered at once, the bots rally"
  "dds_control_share|126|test: a stranger's flood of JOINs into match 1: match 0's bots join and rally"
  "web_page|125|test: the spectator page in headless Chromium follows a rally, a server killed and a new one"
  "dds_discovery|120|test: server, bots and watcher found through a Discovery Server only"
  "test_teardown|141|test: one participant deleted within the teardown limit"
  "test_ownership|142|test: two writers of one match at once: readers take the stronger's, a strength raised while it runs included"
  "dds_net_failover|135|test: a game on the client library plays through a failover: its events go on, none twice, none skipped"
  "test_net_secure|136|test: the client library under DDS Security plays its own match, no other"
  "test_net_api|131|test: the client library's C API refuses bad input, with a server and without"
  "net_example_c|132|test: examples/c/rally.c plays 3 points against a ball-bot through libball-net"
  "net_example_cpp|133|test: examples/cpp/rally.cpp, the same game in C++17"
  "net_python|134|test: the Python binding (examples/python/ballnet.py) plays a point against a ball-bot")

# ball_dds_domain(USER OUT): the id of USER, a fatal error if it has none.
function(ball_dds_domain user out)
  foreach(entry ${BALL_DDS_DOMAINS})
    string(REPLACE "|" ";" fields "${entry}")
    list(GET fields 0 name)
    list(GET fields 1 id)
    if(name STREQUAL user)
      set(${out} ${id} PARENT_SCOPE)
      return()
    endif()
  endforeach()
  message(FATAL_ERROR "cmake/dds_domains.cmake: no DDS domain for ${user}")
endfunction()

# ball_dds_domain_table(FILE): the table of docs/server-reference.md, written to FILE;
# a fatal error if two users share an id.
function(ball_dds_domain_table file)
  set(text "| id | used by |\n|---|---|\n")
  set(seen "")
  foreach(entry ${BALL_DDS_DOMAINS})
    string(REPLACE "|" ";" fields "${entry}")
    list(GET fields 0 name)
    list(GET fields 1 id)
    list(GET fields 2 what)
    if(id IN_LIST seen)
      message(FATAL_ERROR "cmake/dds_domains.cmake: domain ${id} is used twice")
    endif()
    list(APPEND seen ${id})
    string(APPEND text "| ${id} | `${name}`: ${what} |\n")
  endforeach()
  file(WRITE ${file} "${text}")
endfunction()
