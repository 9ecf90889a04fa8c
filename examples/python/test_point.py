"""ballnet (ballnet.py) under pytest: the module's own checks, which need no server, and a point
played through it against a ball-server and a ball-bot on loopback (ctest's net_python).

  BALL_BIN=build/server BALL_TEST_DOMAIN=<id> BALL_NET_LIBRARY=build/server/libball-net.so \\
      python3 -m pytest -p no:cacheprovider examples/python/test_point.py

BALL_BIN names the folder of ball-server and ball-bot, BALL_TEST_DOMAIN the DDS domain
(cmake/dds_domains.cmake gives net_python its own); without BALL_BIN the networked test is
skipped (ctest fails on a skip). Every process started here is in a group of its own, dies with
this one (PR_SET_PDEATHSIG) and is stopped by its fixture, also when the test fails.
"""
import ctypes
import math
import os
import signal
import subprocess
import time

import pytest

import ballnet

LIBC = ctypes.CDLL(None, use_errno=True)
PR_SET_PDEATHSIG = 1
DOMAIN = int(os.environ.get("BALL_TEST_DOMAIN", "0"))


# ---- the module alone --------------------------------------------------------------------------

def test_layouts_are_the_librarys():
    for struct, kind in ballnet.LAYOUTS:
        assert ctypes.sizeof(struct) == ballnet._lib.ball_net_sizeof(kind), struct.__name__
    # (the sizes of x86-64 gcc's ball/net.h, so that a change there is seen here too)
    assert [ctypes.sizeof(s) for s, _ in ballnet.LAYOUTS] == [152, 184, 184, 152, 12]
    for struct, kind in ballnet.LAYOUTS:
        for field, _ in struct._fields_:
            assert getattr(struct, field).offset == ballnet._lib.ball_net_offsetof(kind, field.encode()), field


def load_module_text(text):
    """ballnet's source, as edited, run as a module of its own: what an import of it would do."""
    exec(compile(text, ballnet.__file__, "exec"), {"__name__": "ballnet_edited", "__file__": ballnet.__file__})


def test_a_layout_unlike_the_librarys_is_an_import_error():
    with open(ballnet.__file__) as f:
        text = f.read()
    dropped = '("serving_side", ctypes.c_int),'
    assert dropped in text
    with pytest.raises(ImportError, match=r"layout mismatch: Match is 184 bytes in .* but 176 here"):
        load_module_text(text.replace(dropped, ""))


def test_a_field_moved_in_padding_is_an_import_error():
    # ball_states sits in what was padding of ball_net_config: its size is the same without it
    with open(ballnet.__file__) as f:
        text = f.read()
    dropped = '("ball_states", ctypes.c_int),'
    assert dropped in text
    with pytest.raises(ImportError, match=r"layout mismatch: Config.ball_states is at byte \d+ in .* but missing here"):
        load_module_text(text.replace(dropped, ""))


def test_a_library_that_is_not_there_is_an_import_error(monkeypatch):
    monkeypatch.setenv("BALL_NET_LIBRARY", "/nonexistent/libball-net.so")
    with open(ballnet.__file__) as f:
        text = f.read()
    with pytest.raises(ImportError, match="set BALL_NET_LIBRARY .*/nonexistent/libball-net.so"):
        load_module_text(text)


def test_open_refuses_a_domain_of_300():
    with pytest.raises(ballnet.Error) as e:
        ballnet.Client(domain=300)
    assert e.value.status == ballnet.Status.BALL_ERANGE
    assert e.value.name == "BALL_ERANGE"
    assert "domain 300" in e.value.message


def test_a_push_to_a_match_not_joined_is_refused():
    with ballnet.Client(domain=DOMAIN) as c:
        with pytest.raises(ballnet.Error) as e:
            c.push(7, 0, ballnet.now(), (0.0, 1.0, 0.0), (1.0, 0.0, 0.0))
        assert e.value.name == "BALL_ENOMATCH"
        assert "slot 0" in e.value.message and "match 7" in e.value.message
        with pytest.raises(ballnet.Error) as e:
            c.join(7, 4)
        assert e.value.name == "BALL_ERANGE"
        assert c.match_info(7) is None  # no server serves it: None, not an error


def test_close_twice_is_harmless():
    c = ballnet.Client(domain=DOMAIN)
    c.close()
    c.close()
    assert c.closed


def test_every_call_on_a_closed_client_raises_BALL_ECLOSED():
    with ballnet.Client(domain=DOMAIN) as c:
        pass
    calls = {
        "matches": lambda: c.matches(),
        "match_info": lambda: c.match_info(0),
        "join": lambda: c.join(0),
        "leave": lambda: c.leave(0),
        "push": lambda: c.push(0, 0, ballnet.now(), (0, 1, 0), (1, 0, 0)),
        "ball_at": lambda: c.ball_at(0, ballnet.now()),
        "poll": lambda: c.poll(),
    }
    for name, call in calls.items():
        with pytest.raises(ballnet.Error) as e:
            call()
        assert e.value.status == ballnet.Status.BALL_ECLOSED, name
        assert e.value.message == "the client is closed", name


# ---- a point against a bot ----------------------------------------------------------------------

def dds_shm():
    """Fast DDS's shared-memory files (the QoS profiles turn shared memory off: there are none)."""
    prefixes = ("fastrtps_", "fast_datasharing", "sem.fastrtps_", "sem.fast_datasharing")
    return {n for n in os.listdir("/dev/shm") if n.startswith(prefixes)}


def start(args, log):
    """A process in a group of its own that dies with this one."""
    with open(log, "w") as out:
        return subprocess.Popen(args, stdout=out, stderr=subprocess.STDOUT, start_new_session=True,
                                preexec_fn=lambda: LIBC.prctl(PR_SET_PDEATHSIG, signal.SIGKILL))


def stop(p):
    """SIGTERM to its group, SIGKILL after 10 s; its exit status."""
    if p.poll() is None:
        try:
            os.killpg(p.pid, signal.SIGTERM)
            p.wait(10)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
            p.wait()
        except ProcessLookupError:
            p.wait()
    return p.returncode


@pytest.fixture
def server_and_bot(tmp_path):
    """A ball-server of one match and a ball-bot in its slot 1, stopped whatever happens."""
    bin_dir = os.environ.get("BALL_BIN")
    if not bin_dir:
        pytest.skip("BALL_BIN is not set (the folder of ball-server and ball-bot)")
    shm_before = dds_shm()
    procs = []
    try:
        procs.append(start([os.path.join(bin_dir, "ball-server"), "--domain", str(DOMAIN), "--matches", "1",
                            "--startup-wait", "0", "--duration", "80"], tmp_path / "server.log"))
        procs.append(start([os.path.join(bin_dir, "ball-bot"), "--domain", str(DOMAIN), "--match", "0",
                            "--player", "1", "--duration", "75"], tmp_path / "bot.log"))
        yield
    finally:
        for p in reversed(procs):
            stop(p)
    assert dds_shm() <= shm_before, "Fast DDS files left in /dev/shm"


def racket_target(client, m, side, t, chase):
    """rally.c's scripted racket: onto the ball 0.05 s ahead while it comes in on this side, not yet
    2 m past the baseline or a sideline (the server refuses a racket beyond its racket_margin), else 1 m inside
    the baseline."""
    toward_net = 1.0 if side == 0 else -1.0
    ready = (m.court_x[0] + 1.0 if side == 0 else m.court_x[1] - 1.0, 1.0, 0.5 * (m.court_z[0] + m.court_z[1]))
    b = client.ball_at(m.id, t + 0.05) if chase else None
    if b is not None:
        p, v = b.state.position, b.state.velocity
        baseline = m.court_x[0] if side == 0 else m.court_x[1]
        if ((p.x - m.net_x) * toward_net < 0.0 and v.x * toward_net < 0.0 and (p.x - baseline) * toward_net > -2.0
                and m.court_z[0] - 2.0 < p.z < m.court_z[1] + 2.0 and p.y < 3.0):
            return tuple(p)
    return ready


def step_toward(at, to, reach):
    """At most `reach` m from `at` toward `to`: a racket is a body (at most 30 m/s here)."""
    d = math.dist(at, to)
    return to if d <= reach else tuple(a + (b - a) * reach / d for a, b in zip(at, to))


def test_a_point_with_a_hit_of_its_own(server_and_bot):
    hits = 1  # balls returned a rally before the next is let go: a point comes soon after a hit
    played = mine = rally_hits = 0
    slot, racket = -1, None
    seen, near = 0, []  # frames the bot's racket was known; its distance to the ball at its hits
    lines, given = [], set()  # the tap's lines; the server's events poll gave, by (match, seq)
    with ballnet.Client(domain=DOMAIN, rackets=1, server_status=1) as client:
        client.tap(lines.append)
        start_t = ballnet.now()
        m = None
        while m is None:
            client.poll()
            m = client.match_info(0)
            assert ballnet.now() - start_t < 15.0, "no server served match 0 within 15 s"
            time.sleep(0.05)
        client.join(0)
        next_pose = ballnet.now()
        while not (played >= 1 and mine >= 1) and ballnet.now() - start_t < 60.0:
            t = ballnet.now()
            for e in client.poll():
                if e.kind < ballnet.EventKind.SERVER:
                    given.add((e.match, e.seq))
                if e.kind == ballnet.EventKind.SLOT and e.value > 0:
                    slot = e.index
                elif e.kind == ballnet.EventKind.RACKET and e.in_play and e.index == slot:
                    mine += 1
                    rally_hits += 1
                elif e.kind == ballnet.EventKind.RACKET and slot >= 0:  # the bot's hit: its racket was at the ball
                    bot = client.racket(0, e.index, e.local_time)
                    if bot is not None:
                        near.append(math.dist((bot.center.x, bot.center.y, bot.center.z),
                                              (e.point.x, e.point.y, e.point.z)))
                elif e.kind == ballnet.EventKind.POINT:
                    played += 1
                    rally_hits = 0
                    print("point to side %d (%s), score %d-%d" % (e.side, ballnet.reason_name(e.reason),
                                                                  e.score[0], e.score[1]))
            if slot >= 0 and client.racket(0, 1 - slot, t) is not None:
                seen += 1
            if slot >= 0 and t >= next_pose:
                m = client.match_info(0) or m
                to = racket_target(client, m, slot % 2, t, rally_hits < hits)
                racket = to if racket is None else step_toward(racket, to, 1.0)
                client.push(0, slot, t, racket, (1.0 if slot % 2 == 0 else -1.0, 0.0, 0.0))
                next_pose += 1.0 / 30.0
                if next_pose < t:
                    next_pose = t + 1.0 / 30.0
            time.sleep(max(0.0, t + 1.0 / 60.0 - ballnet.now()))
        seconds = ballnet.now() - start_t
        client.leave(0)
    print("test_point: %d point(s) played, %d hit(s) of its own, slot %d, in %.1f s" % (played, mine, slot, seconds))
    print("test_point: the bot's racket known in %d frames; at its %d hit(s) %s m from the ball"
          % (seen, len(near), ", ".join("%.3f" % d for d in near)))
    assert slot in (0, 1)
    assert played >= 1
    assert mine >= 1
    assert seen > 0
    assert near  # the bot returns every ball at the easy level: it hit at least once
    assert all(d < 0.5 for d in near)  # within the disc's radius and the ball's, and a sample's error
    # the tap: every kind the client read, "ready" once, and every server event poll gave came through it
    kinds = [line["type"] for line in lines]
    print("test_point: the tap gave %d lines: %s" % (len(lines), ", ".join(
        "%d %s" % (kinds.count(k), k) for k in sorted(set(kinds)))))
    assert kinds.count("ready") == 1
    assert {"match_info", "match_model", "segment", "event", "racket_sample", "server_status"} <= set(kinds)
    tapped = {(line["match"], line["seq"]) for line in lines if line["type"] == "event"}
    assert given and given <= tapped
    assert all(isinstance(line["recv"], float) for line in lines)
