// The spectator page (docs/bots-and-watchers.md, "The spectator page"): the messages
// of ball-watch --http arrive as server-sent events on /stream and go into
// the page's core, libball and the client library's view of each match
// compiled to WebAssembly (ballwasm.js, server/web/wasm/page_core.cpp). At
// the display's frame rate the page asks that core for the ball (the
// segment in effect, by libball), its trail and markers, the rackets (by
// libball's tracks) and the camera presets (libball's, for the window's
// shape), and draws them with three.js on the match's court, in libball's
// colours (the court message). The page itself does no arithmetic on the
// ball, the clock or a racket. window.spectator is what the tests read.
(function () {
  "use strict";
  const KEEP_EVENTS = 60; // per match, for the log
  const LOG_LINES = 40;
  const MIN_BALL_PIXELS = 2; // as the renderer: a ball never under 2 pixels of radius
  const MIN_MARKER_PIXELS = 5;
  const MARKER_RADIUS = 0.25; // m
  const TRAIL_POINTS = 256;
  const MARKERS = 64;
  const NEAR = 0.2, FAR = 400; // m, as the renderer's view.h

  const errors = [];
  window.addEventListener("error", (e) => errors.push(String(e.message)));
  window.addEventListener("unhandledrejection", (e) => errors.push(String(e.reason)));
  const nowSec = () => (performance.timeOrigin + performance.now()) / 1000; // this host's realtime, s

  // ---- what the page knows (the numbers are the core's) -------------------
  let page = null; // the page's core (ballwasm.js)
  const matches = new Map(); // id -> {id, court, info, live, events}
  let selected = null; // the match drawn
  let preset = "side"; // the camera preset, null while orbiting
  let held = null; // {match, t}: a frame held still (tests)
  let connected = false;
  let lostAt = null; // this host's realtime when ball-watch went out of reach
  let frames = 0;

  function match(id) {
    if (!matches.has(id)) matches.set(id, { id: id, court: null, info: null, live: false, events: [] });
    return matches.get(id);
  }

  function receive(m) {
    const now = nowSec();
    switch (m.type) {
      case "hello": // a stream (re)started: what follows is everything
        matches.clear();
        page.clear();
        break;
      case "restart":
        break;
      case "court": {
        const w = match(m.match);
        w.court = m;
        if (!page.court(m)) console.error("spectator: match " + m.match + ": the court's model does not hash to " + m.model_hash);
        if (selected === null) selected = m.match;
        if (selected === m.match) scene.build(w);
        break;
      }
      case "info": {
        const w = match(m.match);
        w.info = m;
        w.live = m.live;
        page.take(m, now);
        if (selected === m.match && !held && preset) scene.camera(preset, w); // the court the rules judge may have come
        break;
      }
      case "reset":
        page.reset(m.match);
        match(m.match).events = [];
        break;
      case "segment": {
        const w = match(m.match);
        if (page.take(m, now) > 0) // what the correction took back: no marker, struck out in the log
          for (const seq of page.voided()) for (const x of w.events) if (x.seq === seq) x.void = true;
        break;
      }
      case "event": {
        const w = match(m.match), taken = page.take(m, now);
        if (taken === 1 || taken === 2) { // (2: a correction that came first took it back)
          w.events.push({ seq: m.event.seq, kind: m.event.kind, time: m.event.time, text: m.text, void: taken === 2 });
          if (w.events.length > KEEP_EVENTS) w.events.shift();
        }
        break;
      }
      case "racket":
        page.racket(m);
        break;
      case "clock": {
        const w = match(m.match);
        w.live = m.live;
        page.clock(m, now);
        break;
      }
    }
    ui.dirty = true;
  }

  // The sim time a match is drawn at: its clock's (standing still while its
  // server is gone, as the clock messages say, and while ball-watch cannot
  // be reached); null without a clock.
  function simNow(w) {
    return page.simNow(w.id, lostAt === null ? nowSec() : lostAt);
  }

  // ---- the picture -------------------------------------------------------
  const canvas = document.getElementById("court");
  const renderer = new THREE.WebGLRenderer({ canvas: canvas, antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  const camera = new THREE.PerspectiveCamera(40, 1, NEAR, FAR);
  const controls = new THREE.OrbitControls(camera, canvas);
  controls.addEventListener("start", () => {
    preset = null;
    ui.dirty = true;
  });

  // the canvas fills the window, and follows it
  function fit() {
    renderer.setSize(window.innerWidth, window.innerHeight, false);
    const w = matches.get(selected);
    if (preset && w) scene.camera(preset, w);
    camera.aspect = window.innerWidth / window.innerHeight;
    camera.updateProjectionMatrix();
  }
  window.addEventListener("resize", fit);

  const v3 = (p) => new THREE.Vector3(p[0], p[1], p[2]);
  const rgb = (c) => new THREE.Color(c[0], c[1], c[2]);
  const css = (c) => "#" + rgb(c).getHexString();
  const flat = (colour, opts) => new THREE.MeshBasicMaterial(Object.assign({ color: colour, side: THREE.DoubleSide }, opts || {}));
  const lit = (colour, opts) => new THREE.MeshLambertMaterial(Object.assign({ color: colour, side: THREE.DoubleSide }, opts || {}));

  // a floor rectangle {x0, z0, x1, z1} at height y, painted in order over what is below (as the renderer)
  function floorRect(r, y, material, order) {
    const g = new THREE.PlaneGeometry(r[2] - r[0], r[3] - r[1]);
    g.rotateX(-Math.PI / 2);
    const mesh = new THREE.Mesh(g, material);
    mesh.position.set(0.5 * (r[0] + r[2]), y, 0.5 * (r[1] + r[3]));
    mesh.renderOrder = order;
    material.depthTest = false;
    material.depthWrite = false;
    return mesh;
  }

  // a net or wall rectangle between heights a and b
  function planeQuad(p, a, b, material) {
    const g = new THREE.PlaneGeometry(p.hi - p.lo, b - a);
    const mesh = new THREE.Mesh(g, material);
    if (p.axis === 0) {
      mesh.rotation.y = Math.PI / 2;
      mesh.position.set(p.position, 0.5 * (a + b), 0.5 * (p.lo + p.hi));
    } else {
      mesh.position.set(0.5 * (p.lo + p.hi), 0.5 * (a + b), p.position);
    }
    return mesh;
  }

  function planeOutline(p, colour) {
    const pts = p.axis === 0
      ? [[p.position, p.bottom, p.lo], [p.position, p.bottom, p.hi], [p.position, p.top, p.hi], [p.position, p.top, p.lo]]
      : [[p.lo, p.bottom, p.position], [p.hi, p.bottom, p.position], [p.hi, p.top, p.position], [p.lo, p.top, p.position]];
    const g = new THREE.BufferGeometry().setFromPoints(pts.map(v3));
    return new THREE.LineLoop(g, new THREE.LineBasicMaterial({ color: colour }));
  }

  function circlePoints(radius, n) {
    const pts = [];
    for (let i = 0; i < n; ++i) pts.push(new THREE.Vector3(radius * Math.cos((2 * Math.PI * i) / n), radius * Math.sin((2 * Math.PI * i) / n), 0));
    return pts;
  }

  // the world size of `pixels` pixels at point p (as the renderer's world_size)
  function worldSize(p, pixels) {
    const d = camera.position.distanceTo(p);
    return (pixels * 2 * d * Math.tan((0.5 * camera.fov * Math.PI) / 180)) / canvas.clientHeight;
  }

  const scene = {
    three: new THREE.Scene(),
    court: null, // the group of the court drawn
    courtOf: null,
    palette: null, // libball's (the court message's)
    init() {
      const s = this.three;
      s.add(new THREE.AmbientLight(0xffffff, 0.4));
      const sun = new THREE.DirectionalLight(0xffffff, 0.75);
      sun.position.set(0.35, 1, 0.55);
      s.add(sun);
      this.ball = new THREE.Mesh(new THREE.SphereGeometry(1, 24, 16), lit(0xffffff));
      this.ball.renderOrder = 10;
      this.shadow = new THREE.Mesh(new THREE.CircleGeometry(1, 32).rotateX(-Math.PI / 2),
                                   flat(0x000000, { transparent: true, depthTest: false, depthWrite: false }));
      this.shadow.renderOrder = 5;
      const trail = new THREE.BufferGeometry();
      trail.setAttribute("position", new THREE.BufferAttribute(new Float32Array(3 * TRAIL_POINTS), 3));
      this.trail = new THREE.Line(trail, new THREE.LineBasicMaterial({ color: 0xffffff }));
      this.trail.frustumCulled = false;
      this.trail.renderOrder = 10; // after the floor, which is painted without depth
      this.rackets = [];
      this.markers = new THREE.Group();
      s.add(this.ball, this.shadow, this.trail, this.markers);
      this.ball.visible = this.shadow.visible = false;
    },
    // the court of match w (docs/render.md: floor, court lines or grid, net, walls) in libball's palette
    build(w) {
      if (this.court) this.three.remove(this.court);
      const c = w.court, f = c.floor, P = c.palette, g = new THREE.Group();
      this.palette = P;
      renderer.setClearColor(rgb(P.sky));
      this.ball.material.color = rgb(P.ball);
      this.shadow.material.color = rgb(P.net);
      this.shadow.material.opacity = P.shadow_alpha;
      this.trail.material.color = rgb(P.trail);
      g.add(floorRect(f.ground, f.level, flat(rgb(P.ground)), 0));
      if (f.has_court) {
        g.add(floorRect(f.court, f.level, flat(rgb(P.court)), 1));
        for (const l of f.lines) g.add(floorRect(l, f.level, flat(rgb(P.line)), 2));
      } else {
        const h = 0.5 * f.grid_width;
        for (let x = Math.ceil(f.ground[0]); x <= f.ground[2]; x += f.grid_step) g.add(floorRect([x - h, f.ground[1], x + h, f.ground[3]], f.level, flat(rgb(P.grid)), 2));
        for (let z = Math.ceil(f.ground[1]); z <= f.ground[3]; z += f.grid_step) g.add(floorRect([f.ground[0], z - h, f.ground[2], z + h], f.level, flat(rgb(P.grid)), 2));
      }
      const seeThrough = (colour, opacity) => lit(colour, { transparent: true, opacity: opacity, depthWrite: false });
      for (const wall of c.walls) {
        g.add(planeQuad(wall, wall.bottom, wall.top, seeThrough(rgb(P.wall), P.wall_alpha)));
        g.add(planeOutline(wall, rgb(P.wall_edge)));
      }
      if (c.net) {
        const n = c.net, tape = 0.06 * (n.top - n.bottom); // the renderer's tape: the top 6 %
        g.add(planeQuad(n, n.bottom, n.top - tape, seeThrough(rgb(P.net), P.net_alpha)));
        g.add(planeQuad(n, n.top - tape, n.top, seeThrough(rgb(P.line), P.tape_alpha)));
        g.add(planeOutline(n, rgb(P.line)));
      }
      g.children.forEach((o) => (o.renderOrder = Math.max(o.renderOrder, o.isLine ? 10 : 0)));
      // the rackets: a disc and its rim per slot, in the racket colours
      for (const r of this.rackets) this.three.remove(r);
      this.rackets = P.rackets.map((colour) => {
        const d = new THREE.Group();
        d.add(new THREE.Mesh(new THREE.CircleGeometry(1, 48), lit(rgb(colour))));
        d.add(new THREE.LineLoop(new THREE.BufferGeometry().setFromPoints(circlePoints(1, 48)), new THREE.LineBasicMaterial({ color: rgb(P.net) })));
        d.visible = false;
        d.children.forEach((o) => (o.renderOrder = 10));
        this.three.add(d);
        return d;
      });
      this.markerKey = null;
      this.court = g;
      this.courtOf = w.id;
      this.three.add(g);
      this.camera(preset || "side", w);
    },
    // a preset of libball for the canvas's shape (the core's: it frames the court the rules judge)
    camera(name, w) {
      const cam = w && w.court && page.camera(w.id, name, canvas.clientWidth / canvas.clientHeight);
      if (!cam) return null;
      camera.fov = cam.fov;
      camera.aspect = canvas.clientWidth / canvas.clientHeight;
      camera.up.copy(v3(cam.up));
      camera.position.copy(v3(cam.eye));
      controls.target.copy(v3(cam.target));
      camera.lookAt(controls.target);
      camera.updateProjectionMatrix();
      controls.update();
      return cam;
    },
    // everything that moves, at sim time t: the core's numbers, drawn
    draw(w, t) {
      const b = page.ball(w.id, t);
      this.ball.visible = this.shadow.visible = b !== null;
      if (b) {
        const p = v3(b.position);
        const r = Math.max(w.court.radius, worldSize(p, MIN_BALL_PIXELS));
        this.ball.position.copy(p);
        this.ball.scale.setScalar(r);
        this.shadow.position.set(p.x, w.court.floor.level, p.z);
        this.shadow.scale.setScalar(r);
      }
      const trail = page.trail(w.id, t, w.court.trail, TRAIL_POINTS);
      const pos = this.trail.geometry.attributes.position;
      trail.forEach((q, i) => pos.setXYZ(i, q[0], q[1], q[2]));
      pos.needsUpdate = true;
      this.trail.geometry.setDrawRange(0, trail.length);
      // the markers of the collisions of the last `trail` seconds, none a correction voided
      const shown = page.markers(w.id, t, w.court.trail, MARKERS);
      const key = w.id + ":" + JSON.stringify(shown);
      if (key !== this.markerKey) { // made anew only when the markers change
        for (const o of this.markers.children.slice()) {
          this.markers.remove(o);
          o.geometry.dispose();
          o.material.dispose();
        }
        for (const m of shown) this.markers.add(marker(w, m));
        this.markers.children.forEach((o) => (o.renderOrder = 10));
        this.markerKey = key;
      }
      // the rackets where their tracks put them
      const players = w.info ? w.info.info.players : 0;
      this.rackets.forEach((g, i) => {
        const pose = i < players ? page.pose(w.id, i, t) : null;
        const r = w.court.rackets[i];
        g.visible = pose !== null && r !== undefined;
        if (!g.visible) return;
        g.position.copy(v3(pose.center));
        g.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), v3(pose.normal));
        g.scale.setScalar(r.radius);
      });
      return b;
    },
  };

  function marker(w, m) {
    const p = v3(m.point);
    const r = Math.max(MARKER_RADIUS, worldSize(p, MIN_MARKER_PIXELS));
    const material = new THREE.LineBasicMaterial({ color: rgb(w.court.palette.markers[m.kind]) });
    if (m.kind === "racket") {
      const pts = [[-r, 0, 0], [r, 0, 0], [0, -r, 0], [0, r, 0], [0, 0, -r], [0, 0, r]].map((d) => new THREE.Vector3(p.x + d[0], p.y + d[1], p.z + d[2]));
      return new THREE.LineSegments(new THREE.BufferGeometry().setFromPoints(pts), material);
    }
    const ring = new THREE.LineLoop(new THREE.BufferGeometry().setFromPoints(circlePoints(r, 48)), material);
    if (m.kind === "floor") {
      ring.rotation.x = Math.PI / 2;
      ring.position.set(p.x, w.court.floor.level + 0.01, p.z);
    } else {
      const plane = m.kind === "net" ? w.court.net : w.court.walls[m.index];
      if (!plane || plane.axis !== 2) ring.rotation.y = Math.PI / 2;
      ring.position.copy(p);
    }
    return ring;
  }

  // ---- the panels ----------------------------------------------------------
  const el = (id) => document.getElementById(id);
  const ui = {
    dirty: true,
    dead: null, // the dead ball shown: the point that decided it
    render() {
      if (!this.dirty) return;
      this.dirty = false;
      const conn = el("connection");
      conn.textContent = connected ? "connected" : "watcher unreachable, retrying";
      conn.className = connected ? "live" : "gone";
      el("matches").replaceChildren(...[...matches.keys()].filter((id) => matches.get(id).info).sort((a, b) => a - b).map((id) => {
        const b = document.createElement("button");
        b.textContent = "match " + id;
        b.className = id === selected ? "on" : "";
        b.onclick = () => select(id);
        return b;
      }));
      const w = matches.get(selected);
      const banner = el("banner");
      banner.hidden = !(w && w.info && !w.live) && connected;
      banner.textContent = !connected ? "ball-watch cannot be reached: the page keeps the last ball and retries"
                                      : "the match's server is gone: the page keeps the last ball and waits for a server";
      const cams = el("cameras");
      if (cams.childElementCount !== page.presets.length)
        cams.replaceChildren(...page.presets.map((name) => {
          const b = document.createElement("button");
          b.textContent = name;
          b.dataset.preset = name;
          b.onclick = () => setPreset(name);
          return b;
        }));
      for (const b of cams.children) b.className = b.dataset.preset === preset ? "on" : "";
      const board = el("scoreboard");
      board.hidden = !(w && w.info && w.court);
      if (!board.hidden) scoreboard(w);
      el("players").replaceChildren(...(w && w.info && w.court ? players(w) : []));
      el("log").replaceChildren(...(w ? w.events : []).filter((x) => x.text).slice(-LOG_LINES).reverse().map((x) => {
        const li = document.createElement("li");
        li.textContent = "t " + x.time.toFixed(2) + "  " + x.text + (x.void ? "  (void: corrected)" : "");
        if (x.void) li.className = "void";
        return li;
      }));
    },
  };

  // whose side each number of the score is: the side's name and its players
  function sideLabel(w, s) {
    const side = w.info.sides[s], span = document.createElement("span");
    span.className = "side";
    const who = document.createElement("span");
    who.textContent = side.name + " · " + (side.slots.length ? "player " + side.slots.join(", ") : "nobody");
    const dots = side.slots.map((i) => {
      const d = document.createElement("span");
      d.className = "dot";
      d.style.background = css(w.court.palette.rackets[i]);
      return d;
    });
    if (s === 0) span.append(who, ...dots);
    else span.append(...dots, who);
    return span;
  }

  function scoreboard(w) {
    const m = w.info, i = m.info, score = i.play.score;
    const points = document.createElement("span");
    points.className = "points";
    points.textContent = score[0] + " : " + score[1];
    el("score").replaceChildren(sideLabel(w, 0), " ", points, " ", sideLabel(w, 1));
    el("status").textContent = "level " + m.level_name + " · " + i.state + (i.state === "paused" ? " (" + i.pause_reason + ")" : "") +
      " · " + i.scene + " · server " + i.server + (w.live ? "" : " (gone)") + " · time base " + i.time_base;
    const dead = el("dead");
    dead.hidden = ui.dead === null;
    dead.textContent = ui.dead === null ? "" : "dead ball: " + ui.dead;
  }

  function players(w) {
    const i = w.info.info, rows = [];
    for (let s = 0; s < i.players; ++s) {
      const slot = i.slots[s], row = document.createElement("div"), dot = document.createElement("span");
      row.className = "slot";
      dot.className = "dot";
      dot.style.background = css(w.court.palette.rackets[s]);
      const state = !slot.held ? "free" : slot.present ? "present" : "away";
      row.append(dot, "player " + s + " (" + w.info.sides[s % 2].name + "): " + state + (slot.held ? ", " + slot.samples + " samples" : ""));
      rows.push(row);
    }
    return rows;
  }

  // A dead ball: a point decided, the ball still moving (the segment in
  // effect judged no rally on: the events' in_play false from then on),
  // told with the point that decided it.
  function deadBall(w, b) {
    if (!b || b.live || !w.info || w.info.info.state !== "playing") return null;
    const points = w.events.filter((x) => x.kind === "point" && !x.void && x.text);
    return points.length ? points[points.length - 1].text : "the point is decided";
  }

  function select(id) {
    selected = id;
    const w = matches.get(id);
    if (w && w.court) scene.build(w);
    ui.dirty = true;
  }

  function setPreset(name) {
    preset = name;
    scene.camera(name, matches.get(selected));
    ui.dirty = true;
  }

  // ---- the stream and the frame loop ----------------------------------------
  function connect() {
    const source = new EventSource("stream");
    source.onopen = () => {
      connected = true;
      lostAt = null;
      ui.dirty = true;
    };
    source.onmessage = (ev) => receive(JSON.parse(ev.data));
    source.onerror = () => {
      if (connected) lostAt = nowSec(); // the ball stands where it was; EventSource tries again by itself
      connected = false;
      ui.dirty = true;
    };
  }

  function frame() {
    const w = matches.get(held ? held.match : selected);
    let dead = null;
    if (w && w.court && w.info) {
      if (scene.courtOf !== w.id) scene.build(w);
      const t = held ? held.t : simNow(w);
      if (t !== null) dead = deadBall(w, scene.draw(w, t));
    }
    if (dead !== ui.dead) {
      ui.dead = dead;
      ui.dirty = true;
    }
    controls.update();
    renderer.render(scene.three, camera);
    frames++;
    ui.render();
    requestAnimationFrame(frame);
  }

  // ---- for the tests (docs/bots-and-watchers.md, "The spectator page") ------------------
  window.spectator = {
    errors: errors,
    frames: () => frames,
    connected: () => connected,
    matches: () => [...matches.keys()].filter((id) => matches.get(id).info),
    // a message as the stream brings it, the events a match holds, and the newest message of a type
    feed: (m) => receive(m),
    events: (id) => (matches.has(id) ? matches.get(id).events.map((x) => ({ seq: x.seq, void: x.void })) : null),
    message: (id, type) => (matches.has(id) ? matches.get(id)[type] : null),
    forget(id) {
      matches.delete(id);
      page.forget(id);
    },
    // the ball of a match at sim time t, from the segments the page holds (the core's answer)
    ballAt: (id, t) => page.ball(id, t),
    // the page's sim time now for a match, its ball then, and whether it is dead
    sample(id) {
      const w = matches.get(id);
      if (!w || !w.court || !w.info) return null;
      const t = simNow(w);
      const b = t === null ? null : page.ball(id, t);
      return { t: t, live: w.live, state: w.info.info.state, score: w.info.info.play.score, ball: b, dead: deadBall(w, b) !== null };
    },
    // holds the picture still at sim time t of a match, from a preset
    // camera, and draws it at once; release() goes live again
    hold(id, t, name) {
      held = { match: id, t: t };
      if (id !== selected) select(id);
      preset = name;
      const w = matches.get(id), cam = scene.camera(name, w);
      scene.draw(w, t);
      renderer.render(scene.three, camera);
      const r = canvas.getBoundingClientRect();
      return { x: r.left, y: r.top, width: r.width, height: r.height, ball: page.ball(id, t), camera: cam,
               floor: w.court.floor, judged: w.court.judged, rackets: scene.rackets.filter((g) => g.visible).length };
    },
    release() {
      held = null;
    },
  };

  BallWasm.load("ball.wasm").then((ball) => {
    page = ball.pageCore();
    scene.init();
    fit();
    connect();
    requestAnimationFrame(frame);
  }, (e) => {
    errors.push(String(e));
    console.error("spectator: " + e);
    el("banner").hidden = false;
    el("banner").textContent = "libball's WebAssembly module did not load: " + e;
  });
})();
