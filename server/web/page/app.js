// The spectator page (docs/server.md, "The spectator page"): the messages
// of ball-watch --http arrive as server-sent events on /stream; each
// match's court is drawn as libball's renderer draws it (docs/render.md,
// "What is drawn"), and the ball, its trail, the markers and the rackets
// are evaluated here at the display's frame rate from the segments and the
// racket samples (protocol.js). window.spectator is what the tests read.
(function () {
  "use strict";
  const P = window.BallProtocol;
  const KEEP_SEGMENTS = 64; // per match
  const KEEP_EVENTS = 60; //   per match, for the log and the markers
  const KEEP_RACKET_SAMPLES = 8;
  const KEEP_CORRECTIONS = 16; // per match: the newest, which may void events still to come (the watcher's rule)
  const MIN_BALL_PIXELS = 2; // as the renderer: a ball never under 2 pixels of radius
  const MIN_MARKER_PIXELS = 5;
  const MARKER_RADIUS = 0.25; // m
  const TRAIL_POINTS = 2048;
  const NEAR = 0.2, FAR = 400; // m

  // the renderer's colours (docs/render.md, "What is drawn")
  const rgb = (r, g, b) => new THREE.Color(r, g, b);
  const C = {
    sky: rgb(0.8, 0.86, 0.92), ground: rgb(0.3, 0.52, 0.32), court: rgb(0.22, 0.42, 0.62), line: rgb(0.95, 0.95, 0.95),
    grid: rgb(0.24, 0.44, 0.27), net: rgb(0.12, 0.12, 0.14), wall: rgb(0.78, 0.66, 0.5), wallEdge: rgb(0.45, 0.35, 0.25),
    ball: rgb(0.95, 0.9, 0.1), trail: rgb(1, 0.55, 0.05),
    rackets: [rgb(0.85, 0.15, 0.15), rgb(0.15, 0.3, 0.85), rgb(0.85, 0.45, 0.85), rgb(0.2, 0.75, 0.75)],
    marks: { floor: rgb(1, 1, 1), net: rgb(1, 0.1, 0.8), wall: rgb(1, 0.45, 0), racket: rgb(0.95, 0.1, 0.1) },
  };

  const nowSec = () => (performance.timeOrigin + performance.now()) / 1000; // this host's realtime, s

  // ---- what the page knows ------------------------------------------------
  const matches = new Map(); // id -> match
  let selected = null; // the match drawn
  let preset = "side"; // the camera preset, null while orbiting
  let held = null; // {match, t}: a frame held still (tests)
  let connected = false;
  let lostAt = null; // this host's realtime when ball-watch went out of reach
  let frames = 0;
  const errors = [];
  window.addEventListener("error", (e) => errors.push(String(e.message)));

  function match(id) {
    if (!matches.has(id))
      matches.set(id, { id: id, court: null, info: null, live: false, segments: [], events: [], corrections: [],
                        rackets: [[], [], [], []], clock: new P.SimClock(), trail: [] });
    return matches.get(id);
  }

  function receive(m) {
    switch (m.type) {
      case "hello": // a stream (re)started: what follows is everything
        matches.clear();
        break;
      case "restart":
        break;
      case "court": {
        const w = match(m.match);
        w.court = m;
        if (selected === null) selected = m.match;
        if (selected === m.match) scene.build(w);
        break;
      }
      case "info": {
        const w = match(m.match);
        w.info = m.info;
        w.live = m.live;
        break;
      }
      case "reset": {
        const w = match(m.match);
        w.segments = [];
        w.events = [];
        w.corrections = [];
        w.trail = [];
        w.rackets = [[], [], [], []];
        break;
      }
      case "segment": {
        const w = match(m.match), s = m.segment;
        w.segments.push({ seq: s.seq, t0: s.t0, p0: s.p0, v0: s.v0, s0: s.s0, grounded: s.grounded, cause: s.cause, sound: s.sound });
        w.segments.sort((a, b) => (P.seqAfter(a.seq, b.seq) ? 1 : a.seq === b.seq ? 0 : -1));
        while (w.segments.length > KEEP_SEGMENTS) w.segments.shift();
        if (s.correction) { // what it took back is void: no marker, struck out in the log
          const c = { seq: s.seq, t0: s.t0 };
          w.corrections.push(c);
          while (w.corrections.length > KEEP_CORRECTIONS) w.corrections.shift();
          for (const x of w.events) x.void = x.void || P.voids(c, x.e);
        }
        break;
      }
      case "event": {
        if (!Number.isFinite(m.event.time)) break; // (ball-watch passes finite numbers only)
        const w = match(m.match);
        // (a correction may come first: another topic)
        w.events.push({ e: m.event, text: m.text, void: w.corrections.some((c) => P.voids(c, m.event)) });
        while (w.events.length > KEEP_EVENTS) w.events.shift();
        break;
      }
      case "racket": {
        const w = match(m.match), list = w.rackets[m.player];
        if (!list) break;
        list.push({ t: m.t, center: m.center, normal: m.normal });
        list.sort((a, b) => a.t - b.t);
        while (list.length > KEEP_RACKET_SAMPLES) list.shift();
        break;
      }
      case "clock": {
        const w = match(m.match);
        w.live = m.live;
        w.clock.observe(m.sim_time, m.real, m.time_base, m.running, nowSec());
        break;
      }
    }
    ui.dirty = true;
  }

  // The ball of match w at sim time t, and the segment it lies on.
  function ballAt(w, t) {
    if (!w || !w.info) return null;
    const s = P.inEffect(w.segments, t);
    if (!s) return null;
    const b = P.segmentEval(w.info.model, s, t);
    return { position: b.position, seq: s.seq };
  }

  // ---- the picture -------------------------------------------------------
  const canvas = document.getElementById("court");
  const renderer = new THREE.WebGLRenderer({ canvas: canvas, antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(canvas.clientWidth, canvas.clientHeight, false);
  renderer.setClearColor(C.sky);
  const camera = new THREE.PerspectiveCamera(40, canvas.clientWidth / canvas.clientHeight, NEAR, FAR);
  const controls = new THREE.OrbitControls(camera, canvas);
  controls.addEventListener("start", () => {
    preset = null;
    ui.dirty = true;
  });

  const v3 = (p) => new THREE.Vector3(p[0], p[1], p[2]);
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
    init() {
      const s = this.three;
      s.add(new THREE.AmbientLight(0xffffff, 0.4));
      const sun = new THREE.DirectionalLight(0xffffff, 0.75);
      sun.position.set(0.35, 1, 0.55);
      s.add(sun);
      this.ball = new THREE.Mesh(new THREE.SphereGeometry(1, 24, 16), lit(C.ball));
      this.ball.renderOrder = 10;
      this.shadow = new THREE.Mesh(new THREE.CircleGeometry(1, 32).rotateX(-Math.PI / 2),
                                   flat(C.net, { transparent: true, opacity: 0.45, depthTest: false, depthWrite: false }));
      this.shadow.renderOrder = 5;
      const trail = new THREE.BufferGeometry();
      trail.setAttribute("position", new THREE.BufferAttribute(new Float32Array(3 * (TRAIL_POINTS + 1)), 3));
      this.trail = new THREE.Line(trail, new THREE.LineBasicMaterial({ color: C.trail }));
      this.trail.frustumCulled = false;
      this.trail.renderOrder = 10; // after the floor, which is painted without depth
      this.rackets = C.rackets.map((colour) => {
        const g = new THREE.Group();
        g.add(new THREE.Mesh(new THREE.CircleGeometry(1, 48), lit(colour)));
        g.add(new THREE.LineLoop(new THREE.BufferGeometry().setFromPoints(circlePoints(1, 48)), new THREE.LineBasicMaterial({ color: C.net })));
        g.visible = false;
        g.children.forEach((o) => (o.renderOrder = 10));
        s.add(g);
        return g;
      });
      this.markers = new THREE.Group();
      s.add(this.ball, this.shadow, this.trail, this.markers);
    },
    // the court of match w (docs/render.md: floor, court lines or grid, net, walls)
    build(w) {
      if (this.court) this.three.remove(this.court);
      const c = w.court, f = c.floor, g = new THREE.Group();
      g.add(floorRect(f.ground, f.level, flat(C.ground), 0));
      if (f.has_court) {
        g.add(floorRect(f.court, f.level, flat(C.court), 1));
        for (const l of f.lines) g.add(floorRect(l, f.level, flat(C.line), 2));
      } else {
        const h = 0.5 * f.grid_width;
        for (let x = Math.ceil(f.ground[0]); x <= f.ground[2]; x += f.grid_step) g.add(floorRect([x - h, f.ground[1], x + h, f.ground[3]], f.level, flat(C.grid), 2));
        for (let z = Math.ceil(f.ground[1]); z <= f.ground[3]; z += f.grid_step) g.add(floorRect([f.ground[0], z - h, f.ground[2], z + h], f.level, flat(C.grid), 2));
      }
      const seeThrough = (colour, opacity) => lit(colour, { transparent: true, opacity: opacity, depthWrite: false });
      for (const wall of c.walls) {
        g.add(planeQuad(wall, wall.bottom, wall.top, seeThrough(C.wall, 0.55)));
        g.add(planeOutline(wall, C.wallEdge));
      }
      if (c.net) {
        const n = c.net, tape = 0.06 * (n.top - n.bottom);
        g.add(planeQuad(n, n.bottom, n.top - tape, seeThrough(C.net, 0.45)));
        g.add(planeQuad(n, n.top - tape, n.top, seeThrough(C.line, 0.95)));
        g.add(planeOutline(n, C.line));
      }
      g.children.forEach((o) => (o.renderOrder = Math.max(o.renderOrder, o.isLine ? 10 : 0)));
      this.court = g;
      this.courtOf = w.id;
      this.three.add(g);
      this.camera(preset || "side", w);
    },
    camera(name, w) {
      const cam = w && w.court && w.court.cameras[name];
      if (!cam) return;
      camera.fov = cam.fov;
      camera.aspect = canvas.clientWidth / canvas.clientHeight;
      camera.up.copy(v3(cam.up));
      camera.position.copy(v3(cam.eye));
      controls.target.copy(v3(cam.target));
      camera.lookAt(controls.target);
      camera.updateProjectionMatrix();
      controls.update();
    },
    // everything that moves, at sim time t
    draw(w, t) {
      const radius = w.court.radius;
      const b = ballAt(w, t);
      this.ball.visible = this.shadow.visible = b !== null;
      if (b) {
        const p = v3(b.position);
        const r = Math.max(radius, worldSize(p, MIN_BALL_PIXELS));
        this.ball.position.copy(p);
        this.ball.scale.setScalar(r);
        this.shadow.position.set(p.x, w.court.floor.level, p.z);
        this.shadow.scale.setScalar(r);
        // the trail: the centres of the last `trail` seconds, as drawn
        if (w.trail.length && t < w.trail[w.trail.length - 1].t) w.trail = [];
        if (!w.trail.length || t > w.trail[w.trail.length - 1].t) w.trail.push({ t: t, p: b.position });
        while (w.trail.length > TRAIL_POINTS || (w.trail.length && w.trail[0].t < t - w.court.trail)) w.trail.shift();
      }
      const pos = this.trail.geometry.attributes.position;
      w.trail.forEach((q, i) => pos.setXYZ(i, q.p[0], q.p[1], q.p[2]));
      pos.needsUpdate = true;
      this.trail.geometry.setDrawRange(0, w.trail.length);
      // the markers of the collisions of the last `trail` seconds
      const shown = w.events.filter(({ e, void: v }) => !v && e.kind in C.marks && e.time <= t && e.time >= t - w.court.trail);
      const key = w.id + ":" + shown.map(({ e }) => e.seq).join(",");
      if (key !== this.markerKey) { // made anew only when the markers change
        for (const o of this.markers.children.slice()) {
          this.markers.remove(o);
          o.geometry.dispose();
          o.material.dispose();
        }
        for (const { e } of shown) this.markers.add(marker(w, e));
        this.markers.children.forEach((o) => (o.renderOrder = 10));
        this.markerKey = key;
      }
      // the rackets where their tracks put them
      const model = w.info.model;
      this.rackets.forEach((g, i) => {
        const pose = i < (w.info.players || 0) ? P.racketEstimate(w.rackets[i], t, model.extrapolation_time, model.stale_time) : null;
        const r = w.court.rackets[i];
        g.visible = pose !== null && r !== undefined;
        if (!g.visible) return;
        g.position.copy(v3(pose.center));
        g.quaternion.setFromUnitVectors(new THREE.Vector3(0, 0, 1), v3(pose.normal));
        g.scale.setScalar(r.radius);
      });
    },
  };

  function marker(w, e) {
    const p = v3(e.point);
    const r = Math.max(MARKER_RADIUS, worldSize(p, MIN_MARKER_PIXELS));
    const material = new THREE.LineBasicMaterial({ color: C.marks[e.kind] });
    if (e.kind === "racket") {
      const pts = [[-r, 0, 0], [r, 0, 0], [0, -r, 0], [0, r, 0], [0, 0, -r], [0, 0, r]].map((d) => new THREE.Vector3(p.x + d[0], p.y + d[1], p.z + d[2]));
      return new THREE.LineSegments(new THREE.BufferGeometry().setFromPoints(pts), material);
    }
    const ring = new THREE.LineLoop(new THREE.BufferGeometry().setFromPoints(circlePoints(r, 48)), material);
    if (e.kind === "floor") {
      ring.rotation.x = Math.PI / 2;
      ring.position.set(p.x, w.court.floor.level + 0.01, p.z);
    } else {
      const plane = e.kind === "net" ? w.court.net : w.court.walls[e.index];
      if (!plane || plane.axis !== 2) ring.rotation.y = Math.PI / 2;
      ring.position.copy(p);
    }
    return ring;
  }

  // ---- the panels ----------------------------------------------------------
  const ui = {
    dirty: true,
    el: (id) => document.getElementById(id),
    render() {
      if (!this.dirty) return;
      this.dirty = false;
      const conn = this.el("connection");
      conn.textContent = connected ? "connected" : "watcher unreachable, retrying";
      conn.className = connected ? "live" : "gone";
      const list = this.el("matches");
      list.replaceChildren(...[...matches.keys()].sort((a, b) => a - b).map((id) => {
        const b = document.createElement("button");
        b.textContent = "match " + id;
        b.className = id === selected ? "on" : "";
        b.onclick = () => select(id);
        return b;
      }));
      const w = matches.get(selected);
      const banner = this.el("banner");
      banner.hidden = !(w && w.info && !w.live) && connected;
      banner.textContent = !connected ? "ball-watch cannot be reached: the page keeps the last ball and retries"
                                      : "the match's server is gone: the page keeps the last ball and waits for a server";
      const cams = this.el("cameras");
      if (w && w.court && cams.childElementCount !== Object.keys(w.court.cameras).length)
        cams.replaceChildren(...Object.keys(w.court.cameras).map((name) => {
          const b = document.createElement("button");
          b.textContent = name;
          b.dataset.preset = name;
          b.onclick = () => setPreset(name);
          return b;
        }));
      for (const b of cams.children) b.className = b.dataset.preset === preset ? "on" : "";
      this.el("match").innerHTML = w && w.info ? matchHtml(w) : "<p>waiting for a match</p>";
      this.el("log").replaceChildren(...(w ? w.events : []).filter((x) => x.text).slice(-40).reverse().map((x) => {
        const li = document.createElement("li");
        li.textContent = "t " + x.e.time.toFixed(2) + "  " + x.text + (x.void ? "  (void: corrected)" : "");
        if (x.void) li.className = "void";
        return li;
      }));
    },
  };

  function esc(s) {
    return String(s).replace(/[&<>"]/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;" })[c]);
  }

  function matchHtml(w) {
    const i = w.info, score = i.play.score;
    let h = '<div class="score">' + score[0] + " : " + score[1] + "</div>";
    h += "<p>" + esc(i.state) + (i.state === "paused" ? " (" + esc(i.pause_reason) + ")" : "") + ", " + esc(i.scene) +
         ", level " + i.level + ", server " + i.server + (w.live ? "" : " (gone)") + ", time base " + i.time_base + "</p>";
    for (let s = 0; s < i.players; ++s) {
      const slot = i.slots[s], colour = "#" + C.rackets[s].getHexString();
      const state = !slot.held ? "free" : slot.present ? "present" : "away";
      h += '<div class="slot"><span class="dot" style="background:' + colour + '"></span>player ' + s + ": " + state +
           (slot.held ? ", " + slot.samples + " samples" : "") + "</div>";
    }
    return h;
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

  // The sim time a match is drawn at: its clock's estimate (standing still
  // while its server is gone, as the clock messages say, and while ball-watch
  // cannot be reached).
  function simNow(w) {
    return w.clock.valid ? w.clock.simNow(lostAt === null ? nowSec() : lostAt) : null;
  }

  function frame() {
    const w = matches.get(held ? held.match : selected);
    if (w && w.court && w.info) {
      if (scene.courtOf !== w.id) scene.build(w);
      const t = held ? held.t : simNow(w);
      if (t !== null) scene.draw(w, t);
    }
    controls.update();
    renderer.render(scene.three, camera);
    frames++;
    ui.render();
    requestAnimationFrame(frame);
  }

  scene.init();
  connect();
  requestAnimationFrame(frame);

  // ---- for the tests (docs/server.md, "The spectator page") ------------------
  window.spectator = {
    errors: errors,
    frames: () => frames,
    connected: () => connected,
    matches: () => [...matches.keys()],
    // a message as the stream brings it, and the events a match holds
    feed: (m) => receive(m),
    events: (id) => (matches.has(id) ? matches.get(id).events.map((x) => ({ seq: x.e.seq, void: !!x.void })) : null),
    // the ball of a match at sim time t, from the segments the page holds
    ballAt: (id, t) => ballAt(matches.get(id), t),
    // the page's sim time now for a match, and its ball then
    sample(id) {
      const w = matches.get(id);
      if (!w || !w.court || !w.info) return null;
      const t = simNow(w);
      const b = t === null ? null : ballAt(w, t);
      return { t: t, live: w.live, state: w.info.state, score: w.info.play.score, ball: b };
    },
    // holds the picture still at sim time t of a match, from a preset
    // camera, and draws it at once; release() goes live again
    hold(id, t, name) {
      held = { match: id, t: t };
      if (id !== selected) select(id);
      setPreset(name);
      const w = matches.get(id);
      w.trail = [];
      scene.draw(w, t);
      renderer.render(scene.three, camera);
      const r = canvas.getBoundingClientRect();
      return { x: r.left, y: r.top, width: r.width, height: r.height, ball: ballAt(w, t), camera: w.court.cameras[name],
               floor: w.court.floor, rackets: scene.rackets.filter((g) => g.visible).length };
    },
    release() {
      held = null;
    },
  };
})();
