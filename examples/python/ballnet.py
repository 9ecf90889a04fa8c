"""libball's client library (ball/net.h, libball-net.so) from Python, over ctypes.

A thin binding, the way a game engine binds the library (Unity's P/Invoke,
Godot, Unreal): the header's structs mirrored as ctypes Structures, checked
against the library's own ball_net_sizeof when the module loads, and one
method per call. It adds no logic of its own; it maps:

  - a refused call to the exception Error, which carries the ball_status
    (Error.status, Error.name: "BALL_ERANGE") and ball_net_message's
    sentence (Error.message);
  - the two answers a game gets every frame before the server has said
    enough to None or False instead (ball_at: BALL_EAGAIN, no clock or
    segment yet; push: BALL_EAGAIN, the match's clock not known yet), and
    match_info's BALL_ENOMATCH (no server serves it) to None;
  - times: seconds of CLOCK_MONOTONIC, the library's default clock, which
    is what time.monotonic() reads on Linux (ballnet.now).

    import ballnet
    with ballnet.Client(domain=42) as client:
        client.join(0)
        while True:
            for e in client.poll():
                if e.kind == ballnet.EventKind.RACKET: ...
            b = client.ball_at(0, ballnet.now())  # a Ball, or None: not yet
            client.push(0, slot, ballnet.now(), (x, y, z), (1, 0, 0))

The library is found through the environment variable BALL_NET_LIBRARY (a
path), else in the project's build tree (build/server/libball-net.so beside
this checkout), else by ctypes.util.find_library("ball-net") (an installed
libball). Standard library only (Python 3.11).
"""
import ctypes
import ctypes.util
import enum
import json
import os
import time

__all__ = ["Client", "Error", "Status", "State", "Cause", "EventKind", "Reason", "Vec3", "BallState", "Segment",
           "Config", "Slot", "Match", "Ball", "Event", "MAX_PLAYERS", "NAME_LEN", "now", "library_path",
           "event_kind_name", "reason_name"]

MAX_PLAYERS = 4  # BALL_NET_MAX_PLAYERS
NAME_LEN = 32    # BALL_NET_NAME_LEN

# The library's default clock, CLOCK_MONOTONIC, in seconds.
now = time.monotonic


# ---- enums (ball/ball.h's ball_status, ball/net.h's), value for value ----------------------------

class Status(enum.IntEnum):
    BALL_OK = 0
    BALL_EINVAL = 1
    BALL_ENONFINITE = 2
    BALL_ERANGE = 3
    BALL_ENOTFOUND = 4
    BALL_ESTALE = 5
    BALL_ENOSPACE = 6
    BALL_EPARSE = 7
    BALL_EIO = 8
    BALL_ENOMEM = 9
    BALL_EDUPLICATE = 10
    BALL_ENOMATCH = 11
    BALL_EAGAIN = 12
    BALL_ENETWORK = 13
    BALL_ECLOSED = 14


class State(enum.IntEnum):  # ball_net_state
    WAITING = 0
    PLAYING = 1
    PAUSED = 2


class Cause(enum.IntEnum):  # ball_net_cause
    SERVE = 0
    FLOOR = 1
    NET = 2
    WALL = 3
    RACKET = 4


class EventKind(enum.IntEnum):  # ball_net_event_kind
    FLOOR = 0
    NET = 1
    WALL = 2
    RACKET = 3
    SOUND = 4
    SERVE = 5
    POINT = 6
    PAUSE = 7
    RESUME = 8
    JOIN = 9
    LEAVE = 10
    LEVEL = 11
    TIME_BASE = 12
    REFUSED = 13
    SERVER = 14
    SLOT = 15
    VOIDED = 16
    GAP = 17


class Reason(enum.IntEnum):  # ball_net_reason
    NONE = 0
    POINT_DOUBLE_BOUNCE = 1
    POINT_OUT = 2
    POINT_NET = 3
    POINT_OWN_SIDE = 4
    POINT_NOT_RETURNED = 5
    POINT_LET = 6
    PAUSE_VANISHED = 7
    PAUSE_LEFT = 8
    PAUSE_REQUESTED = 9
    REFUSED_SLOT_HELD = 10
    REFUSED_NOT_PLAYER = 11
    REFUSED_BAD_VALUE = 12
    REFUSED_NO_ROOM = 13
    REFUSED_STATE = 14


# ---- structs, field for field as ball/ball.h and ball/net.h declare them ------------------------

class _Struct(ctypes.Structure):
    def __repr__(self):
        def show(v):
            if isinstance(v, ctypes.Array):
                return [show(x) for x in v]
            return v
        return "%s(%s)" % (type(self).__name__,
                           ", ".join("%s=%r" % (f[0], show(getattr(self, f[0]))) for f in self._fields_))


class Vec3(_Struct):  # ball_vec3, m or m/s
    _fields_ = [("x", ctypes.c_double), ("y", ctypes.c_double), ("z", ctypes.c_double)]

    def __iter__(self):
        return iter((self.x, self.y, self.z))


class BallState(_Struct):  # ball_state
    _fields_ = [("position", Vec3), ("velocity", Vec3), ("spin", Vec3)]


class Segment(_Struct):  # ball_segment
    _fields_ = [("t0", ctypes.c_double), ("p0", Vec3), ("v0", Vec3), ("s0", Vec3), ("grounded", ctypes.c_int)]


_Clock = ctypes.CFUNCTYPE(ctypes.c_double, ctypes.c_void_p)  # ball_net_clock
_Tap = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_char_p, ctypes.c_size_t)  # ball_net_tap


class Config(_Struct):  # ball_net_config
    _fields_ = [("domain", ctypes.c_int),
                ("participant", ctypes.c_char_p),
                ("discovery_servers", ctypes.c_char_p),
                ("qos_file", ctypes.c_char_p),
                ("security_dir", ctypes.c_char_p),
                ("identity", ctypes.c_char_p),
                ("servers", ctypes.c_char_p),
                ("name", ctypes.c_char_p),
                ("max_matches", ctypes.c_int),
                ("ball_states", ctypes.c_int),
                ("clock", _Clock),
                ("clock_user", ctypes.c_void_p),
                ("link_delay", ctypes.c_double),
                ("link_jitter", ctypes.c_double),
                ("link_loss", ctypes.c_double),
                ("link_seed", ctypes.c_uint64),
                ("rackets", ctypes.c_int),
                ("server_status", ctypes.c_int),
                ("tcp_peers", ctypes.c_char_p),
                ("tls_dir", ctypes.c_char_p),
                ("followed_only", ctypes.c_int)]


class Slot(_Struct):  # ball_net_slot
    _fields_ = [("held", ctypes.c_int), ("present", ctypes.c_int), ("mine", ctypes.c_int)]


class Match(_Struct):  # ball_net_match
    _fields_ = [("id", ctypes.c_uint32),
                ("server", ctypes.c_uint32),
                ("scene", ctypes.c_char * NAME_LEN),
                ("level", ctypes.c_int),
                ("state", ctypes.c_int),
                ("players", ctypes.c_int),
                ("slots", Slot * MAX_PLAYERS),
                ("score", ctypes.c_int * 2),
                ("rally", ctypes.c_uint32),
                ("serving_side", ctypes.c_int),
                ("time_base", ctypes.c_double),
                ("sim_time", ctypes.c_double),
                ("net_x", ctypes.c_double),
                ("court_x", ctypes.c_double * 2),
                ("court_z", ctypes.c_double * 2),
                ("model_hash", ctypes.c_uint64)]


class Ball(_Struct):  # ball_net_ball
    _fields_ = [("state", BallState),
                ("sim_time", ctypes.c_double),
                ("segment", ctypes.c_uint32),
                ("cause", ctypes.c_int),
                ("cause_index", ctypes.c_int),
                ("sound", ctypes.c_int),
                ("flight", Segment)]


class RacketPose(_Struct):  # ball_racket_pose (ball.h)
    _fields_ = [("center", Vec3), ("normal", Vec3), ("velocity", Vec3)]


class Event(_Struct):  # ball_net_event
    _fields_ = [("match", ctypes.c_uint32),
                ("seq", ctypes.c_uint32),
                ("kind", ctypes.c_int),
                ("index", ctypes.c_int),
                ("side", ctypes.c_int),
                ("in_play", ctypes.c_int),
                ("sound", ctypes.c_int),
                ("time", ctypes.c_double),
                ("local_time", ctypes.c_double),
                ("point", Vec3),
                ("velocity_in", Vec3),
                ("velocity_out", Vec3),
                ("reason", ctypes.c_int),
                ("score", ctypes.c_int * 2),
                ("value", ctypes.c_double),
                ("server", ctypes.c_uint32)]


# (struct, ball_net_type): what ball_net_sizeof and ball_net_offsetof check at load
LAYOUTS = [(Config, 0), (Match, 1), (Ball, 2), (Event, 3), (Slot, 6)]


# ---- the library --------------------------------------------------------------------------------

def _candidates():
    env = os.environ.get("BALL_NET_LIBRARY")
    if env:
        return [env]  # asked for by name: that one or none
    here = os.path.dirname(os.path.abspath(__file__))
    found = [os.path.join(here, "..", "..", "build", "server", "libball-net.so")]
    name = ctypes.util.find_library("ball-net")
    if name:
        found.append(name)
    return found


def _load():
    tried = []
    for path in _candidates():
        if os.sep in path and not os.path.exists(path):
            tried.append(path + " (no such file)")
            continue
        try:
            return ctypes.CDLL(path), os.path.normpath(path) if os.sep in path else path
        except OSError as e:
            tried.append("%s (%s)" % (path, e))
    raise ImportError("ballnet: libball-net.so not found; set BALL_NET_LIBRARY to its path (tried: %s)"
                      % "; ".join(tried or ["find_library('ball-net'): nothing"]))


_lib, library_path = _load()

_P = ctypes.c_void_p  # ball_net_client *: opaque
_ST = ctypes.c_int    # ball_status
_SIGNATURES = {
    "ball_net_sizeof": (ctypes.c_size_t, [ctypes.c_int]),
    "ball_net_offsetof": (ctypes.c_size_t, [ctypes.c_int, ctypes.c_char_p]),
    "ball_net_field": (ctypes.c_char_p, [ctypes.c_int, ctypes.c_int]),
    "ball_net_config_default": (None, [ctypes.POINTER(Config)]),
    "ball_net_open": (_ST, [ctypes.POINTER(Config), ctypes.POINTER(_P), ctypes.c_char_p, ctypes.c_size_t]),
    "ball_net_close": (_ST, [_P]),
    "ball_net_free": (None, [_P]),
    "ball_net_message": (ctypes.c_char_p, [_P]),
    "ball_net_matches": (_ST, [_P, ctypes.POINTER(Match), ctypes.c_int, ctypes.POINTER(ctypes.c_int)]),
    "ball_net_match_info": (_ST, [_P, ctypes.c_uint32, ctypes.POINTER(Match)]),
    "ball_net_join": (_ST, [_P, ctypes.c_uint32, ctypes.c_int]),
    "ball_net_leave": (_ST, [_P, ctypes.c_uint32, ctypes.c_int]),
    "ball_net_push": (_ST, [_P, ctypes.c_uint32, ctypes.c_int, ctypes.c_double, Vec3, Vec3]),
    "ball_net_ball_at": (_ST, [_P, ctypes.c_uint32, ctypes.c_double, ctypes.POINTER(Ball)]),
    "ball_net_racket": (_ST, [_P, ctypes.c_uint32, ctypes.c_int, ctypes.c_double, ctypes.POINTER(RacketPose)]),
    "ball_net_poll": (_ST, [_P, ctypes.POINTER(Event), ctypes.c_int, ctypes.POINTER(ctypes.c_int)]),
    "ball_net_set_tap": (_ST, [_P, _Tap, ctypes.c_void_p]),
    "ball_net_event_kind_name": (ctypes.c_char_p, [ctypes.c_int]),
    "ball_net_reason_name": (ctypes.c_char_p, [ctypes.c_int]),
}
for _name, (_res, _args) in _SIGNATURES.items():
    try:
        _f = getattr(_lib, _name)
    except AttributeError:
        raise ImportError("ballnet: %s has no %s: not the libball-net.so of ball/net.h" % (library_path, _name))
    _f.restype, _f.argtypes = _res, _args

for _struct, _type in LAYOUTS:
    _theirs, _ours = _lib.ball_net_sizeof(_type), ctypes.sizeof(_struct)
    if _theirs != _ours:
        raise ImportError("ballnet: layout mismatch: %s is %d bytes in %s (ball_net_sizeof(%d)) but %d here: "
                          "ballnet.py does not mirror that library's ball/net.h" %
                          (_struct.__name__, _theirs, library_path, _type, _ours))
    # every member the library's struct has, here at its place (one added in what was padding
    # changes no size and moves nothing else)
    _ours = {_field: getattr(_struct, _field).offset for _field, _ in _struct._fields_}
    _k = 0
    while _lib.ball_net_field(_type, _k) is not None:
        _field = _lib.ball_net_field(_type, _k).decode()
        _at = _lib.ball_net_offsetof(_type, _field.encode())
        if _ours.get(_field) != _at:
            raise ImportError("ballnet: layout mismatch: %s.%s is at byte %d in %s (ball_net_offsetof) but %s here: "
                              "ballnet.py does not mirror that library's ball/net.h" %
                              (_struct.__name__, _field, _at, library_path,
                               "missing" if _field not in _ours else _ours[_field]))
        _k += 1
    if _k != len(_ours):
        raise ImportError("ballnet: layout mismatch: %s has %d members in %s but %d here" %
                          (_struct.__name__, _k, library_path, len(_ours)))


# ---- errors and the client ----------------------------------------------------------------------

class Error(Exception):
    """A call the library refused: status (a Status), name ("BALL_ERANGE"), message (its sentence)."""

    def __init__(self, status, message):
        self.status = Status(status)
        self.name = self.status.name
        self.message = message
        super().__init__("%s: %s" % (self.name, message))


def event_kind_name(kind):
    """ball_net_event_kind_name: "racket", "point", ..."""
    return _lib.ball_net_event_kind_name(kind).decode()


def reason_name(reason):
    """ball_net_reason_name: "double_bounce", "out", ..."""
    return _lib.ball_net_reason_name(reason).decode()


def _vec3(v):
    return v if isinstance(v, Vec3) else Vec3(*v)


def _text(s):
    return None if s is None else s.encode()


class Client:
    """A client of ball servers (ball_net_client): a DDS participant on `domain`.

    Keyword arguments are ball_net_config's fields (participant, discovery_servers, qos_file,
    security_dir, identity, servers, name, max_matches, ball_states, rackets, server_status, link_delay,
    link_jitter, link_loss, link_seed, tcp_peers, tls_dir, followed_only); None keeps the default. Error when
    the library refuses (a field out of range, a domain whose ports are taken, ...).
    A context manager: leaving the block closes it. Every call on a closed client raises
    Error with status BALL_ECLOSED; close() itself may be called again.
    """

    def __init__(self, domain=0, **config):
        c = Config()
        _lib.ball_net_config_default(ctypes.byref(c))
        c.domain = domain
        for key, value in config.items():
            numbers = ("max_matches", "ball_states", "rackets", "server_status", "link_delay", "link_jitter",
                       "link_loss", "link_seed", "followed_only")
            if key not in ("participant", "discovery_servers", "qos_file", "security_dir", "identity",
                           "servers", "name", "tcp_peers", "tls_dir") + numbers:
                raise TypeError("Client() got an unexpected keyword argument %r" % key)
            if value is not None:
                setattr(c, key, value if key in numbers else _text(value))
        why = ctypes.create_string_buffer(256)
        handle = _P()
        self._handle, self._closed = None, True
        st = _lib.ball_net_open(ctypes.byref(c), ctypes.byref(handle), why, len(why))
        if st != Status.BALL_OK:
            raise Error(st, why.value.decode(errors="replace"))
        self._handle, self._closed = handle, False

    # the handle lives until the Client goes (ball_net_free): a closed one answers BALL_ECLOSED
    def __del__(self):
        handle, self._handle = getattr(self, "_handle", None), None
        if handle is not None and _lib is not None:  # (_lib: None late in the interpreter's exit)
            _lib.ball_net_free(handle)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def _check(self, st):
        if st != Status.BALL_OK:
            raise Error(st, _lib.ball_net_message(self._handle).decode(errors="replace"))

    @property
    def closed(self):
        return self._closed

    def close(self):
        """Leaves every slot and deletes the DDS entities (ball_net_close); again: nothing."""
        if self._closed:
            return
        self._closed = True
        self._check(_lib.ball_net_close(self._handle))

    def matches(self):
        """The matches the domain's servers serve, a list of Match."""
        n = ctypes.c_int(0)
        cap = 16
        while True:
            out = (Match * cap)()
            self._check(_lib.ball_net_matches(self._handle, out, cap, ctypes.byref(n)))
            if n.value <= cap:
                return list(out[:n.value])
            cap = n.value

    def match_info(self, match):
        """One match, a Match; None while no server serves it."""
        out = Match()
        st = _lib.ball_net_match_info(self._handle, match, ctypes.byref(out))
        if st == Status.BALL_ENOMATCH:
            return None
        self._check(st)
        return out

    def join(self, match, slot=-1):
        """Joins `match` in `slot` (-1: any free one); a SLOT event says when it is held."""
        self._check(_lib.ball_net_join(self._handle, match, slot))

    def leave(self, match, slot=-1):
        """Gives `slot` of `match` up (-1: every slot this client holds there)."""
        self._check(_lib.ball_net_leave(self._handle, match, slot))

    def push(self, match, slot, time, center, normal):
        """The racket's pose at `time` (seconds, CLOCK_MONOTONIC): centre (m) and normal, each a Vec3
        or 3 numbers. False while the match's clock is not known yet (nothing sent)."""
        st = _lib.ball_net_push(self._handle, match, slot, time, _vec3(center), _vec3(normal))
        if st == Status.BALL_EAGAIN:
            return False
        self._check(st)
        return True

    def ball_at(self, match, time):
        """The ball at `time` (seconds, CLOCK_MONOTONIC), a Ball; None while the match has no clock
        or segment yet."""
        out = Ball()
        st = _lib.ball_net_ball_at(self._handle, match, time, ctypes.byref(out))
        if st == Status.BALL_EAGAIN:
            return None
        self._check(st)
        return out

    def racket(self, match, slot, time):
        """The racket of `slot` at `time` (seconds, CLOCK_MONOTONIC), a RacketPose, from its holder's
        samples (a client opened with rackets=1); None while there is no clock, model or sample of it
        yet, or its newest sample is stale."""
        out = RacketPose()
        st = _lib.ball_net_racket(self._handle, match, slot, time, ctypes.byref(out))
        if st in (Status.BALL_EAGAIN, Status.BALL_ESTALE):
            return None
        self._check(st)
        return out

    def tap(self, fn):
        """Calls fn(line) with every sample the client takes from now on, a dict of the record's JSON
        (ball_net_set_tap), from within poll(); None: no tap. An exception fn raises is raised by the
        poll() that called it, once the poll is done."""
        if fn is None:
            self._check(_lib.ball_net_set_tap(self._handle, _Tap(), None))
            self._tap = None
            return

        def call(_user, line, length):
            try:
                fn(json.loads(ctypes.string_at(line, length)))
            except BaseException as e:  # (it cannot cross the C library)
                self._tap_error = self._tap_error or e

        tap = _Tap(call)
        self._check(_lib.ball_net_set_tap(self._handle, tap, None))
        self._tap, self._tap_error = tap, None  # (ctypes calls it: it must live as long as the tap)

    def poll(self):
        """Takes what came in, resends what was not answered; every event that is ready, a list of
        Event in order."""
        events, n, cap = [], ctypes.c_int(0), 32
        while True:
            out = (Event * cap)()
            self._check(_lib.ball_net_poll(self._handle, out, cap, ctypes.byref(n)))
            error, self._tap_error = getattr(self, "_tap_error", None), None
            if error is not None:
                raise error
            events.extend(out[:n.value])
            if n.value < cap:
                return events
