// libball's static contact verdicts and swept racket test against FCL 0.7.
// FCL pitfalls (docs/design.md, "Pitfalls of the dependencies"): no distance to Halfspace/Plane, so the
// floor and the net are boxes; continuous collision by conservative
// advancement (the naive solver samples poses and can tunnel).
#include <fcl/fcl.h>

#include <algorithm>

#include "common.h"

namespace bv {

namespace {

// Thickness given to libball's zero-thickness net and racket disc in FCL, and
// the grazing band: where |libball distance| < kBand, a verdict may differ
// only because FCL's slab is kThin thick (its surface is kThin/2 nearer).
constexpr double kThin = 1e-9;       // m
constexpr double kBand = 1e-9;       // m
constexpr double kDistTol = 1e-12;   // m, beyond kThin/2, on separated distances
constexpr double kFloorThick = 1.0;  // m: the floor slab, far thicker than any penetration sampled
constexpr double kFloorSize = 2000;  // m: the floor slab's sides
// FCL 0.7's shape-shape conservative advancement stops when its next safe
// step is below t_err = 1e-4 of the motion (hard-coded in
// ShapeConservativeAdvancementTraversalNode): its time of contact is early by
// up to that, and it reports a hit for a near miss closer than t_err x the
// motion bound.
constexpr double kCaTErr = 1e-4;
// A gap this small is touching: FCL's closest points are then equal or a
// rounding error apart.
constexpr double kTouch = 1e-12;  // m

using Vec = fcl::Vector3d;
using Tf = fcl::Transform3d;

Vec ev(ball_vec3 v) { return Vec(v.x, v.y, v.z); }

Tf at(ball_vec3 p) {
  Tf tf = Tf::Identity();
  tf.translation() = ev(p);
  return tf;
}

// A pose whose local z axis is n (FCL's cylinder axis).
Tf axis_pose(ball_vec3 c, ball_vec3 n) {
  Tf tf = Tf::Identity();
  tf.linear() = fcl::Quaterniond::FromTwoVectors(Vec::UnitZ(), ev(n).normalized()).toRotationMatrix();
  tf.translation() = ev(c);
  return tf;
}

bool fcl_collide(const fcl::CollisionGeometryd *a, const Tf &ta, const fcl::CollisionGeometryd *b,
                 const Tf &tb) {
  fcl::CollisionRequestd req;
  fcl::CollisionResultd res;
  fcl::collide(a, ta, b, tb, req, res);
  return res.isCollision();
}

double fcl_distance(const fcl::CollisionGeometryd *a, const Tf &ta, const fcl::CollisionGeometryd *b,
                    const Tf &tb) {
  fcl::DistanceRequestd req;
  fcl::DistanceResultd res;
  fcl::distance(a, ta, b, tb, req, res);
  return res.min_distance;
}

// The FCL box standing for a net or wall rectangle (kThin thick).
void rect_box(const ball_plane &r, double *sx, double *sy, double *sz, ball_vec3 *c) {
  double mid = 0.5 * (r.lo + r.hi), ymid = 0.5 * (r.bottom + r.top);
  *sy = r.top - r.bottom;
  if (r.axis == 0) {
    *sx = kThin;
    *sz = r.hi - r.lo;
    *c = {r.position, ymid, mid};
  } else {
    *sx = r.hi - r.lo;
    *sz = kThin;
    *c = {mid, ymid, r.position};
  }
}

double clampd(double v, double lo, double hi) { return v < lo ? lo : v > hi ? hi : v; }

// Nearest point of the rectangle / disc to p (used only to place samples).
ball_vec3 rect_nearest(const ball_plane &r, ball_vec3 p) {
  if (r.axis == 0) return {r.position, clampd(p.y, r.bottom, r.top), clampd(p.z, r.lo, r.hi)};
  return {clampd(p.x, r.lo, r.hi), clampd(p.y, r.bottom, r.top), r.position};
}

ball_vec3 disc_nearest(ball_vec3 c, ball_vec3 n, double radius, ball_vec3 p) {
  ball_vec3 w = ball_v3_sub(p, c);
  ball_vec3 radial = ball_v3_sub(w, ball_v3_scale(n, ball_v3_dot(w, n)));
  double rho = ball_v3_norm(radial);
  if (rho > radius) radial = ball_v3_scale(radial, radius / rho);
  return ball_v3_add(c, radial);
}

// A unit vector perpendicular to n.
ball_vec3 perpendicular(ball_vec3 n, Rng &rng) {
  for (;;) {
    ball_vec3 u = rng.unit();
    ball_vec3 p = ball_v3_sub(u, ball_v3_scale(n, ball_v3_dot(u, n)));
    double l = ball_v3_norm(p);
    if (l > 1e-3) return ball_v3_scale(p, 1.0 / l);
  }
}

// Tallies of one obstacle kind.
struct StaticTally {
  long total = 0, in_band = 0, agree_out = 0, disagree_out = 0, agree_in = 0;
  long hits = 0;
  double max_dist_diff = 0;  // |FCL - libball| on separated pairs, beyond kThin/2
  std::vector<std::string> cases;
  void add(double d_lib, bool fcl_hit, double d_fcl, const std::string &what) {
    bool lib_hit = d_lib < 0.0;
    total++;
    hits += lib_hit;
    if (std::fabs(d_lib) < kBand) {
      in_band++;
      agree_in += lib_hit == fcl_hit;
    } else if (lib_hit == fcl_hit) {
      agree_out++;
    } else {
      disagree_out++;
      if (cases.size() < 10)
        cases.push_back(fmt("%s: libball distance %.17g (hit %d), FCL collide %d distance %.17g", what.c_str(), d_lib,
                            lib_hit, fcl_hit, d_fcl));
    }
    if (!fcl_hit) {
      // FCL's slab surface is up to kThin/2 nearer than libball's plane
      double diff = d_lib - d_fcl;
      double excess = diff < 0 ? -diff : std::max(0.0, diff - 0.5 * kThin);
      max_dist_diff = std::max(max_dist_diff, excess);
      if (excess > kDistTol && cases.size() < 10)
        cases.push_back(fmt("%s: separated distance differs: libball %.17g FCL %.17g", what.c_str(), d_lib, d_fcl));
    }
  }
  bool pass() const { return disagree_out == 0 && max_dist_diff <= kDistTol; }
  std::string line(const char *name) const {
    return fmt("%-6s %7ld configs (%ld overlapping): outside band %ld agree, %ld disagree; in band %ld (%ld agree); "
               "max separated distance difference beyond kThin/2 %.2e m",
               name, total, hits, agree_out, disagree_out, in_band, agree_in, max_dist_diff);
  }
};

// Distance offset for a sample: broad most of the time, and one sample in
// four grazing (|d| from 1e-12 to 1e-6 m, either sign) to load the band's edges.
double sample_gap(Rng &rng, double r) {
  if (rng.chance(0.25)) return (rng.chance(0.5) ? 1 : -1) * rng.log_uniform(1e-12, 1e-6);
  return rng.uniform(-r - 0.05, 0.3);
}

}  // namespace

Outcome check_static(const Options &opt) {
  Outcome out;
  out.check = "validate_static";
  Rng rng(opt.seed, 3);
  StaticTally floor_t, net_t, disc_t;
  double t_start = now_s();
  fcl::Boxd floor_box(kFloorSize, kFloorThick, kFloorSize);
  for (int i = 0; i < opt.statics; i++) {
    double r = rng.chance(0.05) ? 0.0 : rng.uniform(0.01, 0.3);
    fcl::Sphered sphere(r);
    // floor: libball's verdict is the plain height test of eq 5 on the ball's surface
    {
      double floor_level = rng.uniform(-1.0, 1.0);
      double gap = sample_gap(rng, r);
      if (r == 0.0 && gap < 0.0) gap = -gap;  // a point ball below the floor is not a sample of interest
      ball_vec3 c = {rng.uniform(-50, 50), floor_level + r + gap, rng.uniform(-50, 50)};
      double d_lib = c.y - r - floor_level;
      Tf tf_floor = at({0.0, floor_level - 0.5 * kFloorThick, 0.0});
      bool hit = fcl_collide(&sphere, at(c), &floor_box, tf_floor);
      double d_fcl = hit ? -1.0 : fcl_distance(&sphere, at(c), &floor_box, tf_floor);
      // the floor slab has no kThin: its top face is the floor itself
      floor_t.add(d_lib, hit, d_fcl, fmt("floor %d", i));
    }
    // net or wall rectangle (both plane orientations)
    {
      ball_plane rect{};
      rect.axis = rng.chance(0.5) ? 0 : 2;
      rect.position = rng.uniform(-5, 15);
      rect.lo = rng.uniform(-5, 5);
      rect.hi = rect.lo + rng.uniform(0.1, 12);
      rect.bottom = rng.uniform(-1, 1);
      rect.top = rect.bottom + rng.uniform(0.05, 3);
      rect.damping = 0.2;
      double m = r + 0.3;
      ball_vec3 c;
      double along = rng.uniform(-m, m), h = rng.uniform(rect.lo - m, rect.hi + m),
             y = rng.uniform(rect.bottom - m, rect.top + m);
      c = rect.axis == 0 ? ball_vec3{rect.position + along, y, h} : ball_vec3{h, y, rect.position + along};
      // place the surface at a chosen gap from the rectangle
      ball_vec3 q = rect_nearest(rect, c);
      ball_vec3 dir = ball_v3_sub(c, q);
      double gap = sample_gap(rng, r);
      if (ball_v3_norm(dir) > 1e-6 && r + gap > 0.0) c = ball_v3_add(q, ball_v3_scale(dir, (r + gap) / ball_v3_norm(dir)));
      double d_lib;
      ball_status st = ball_sphere_rect_distance(&rect, c, r, &d_lib);
      if (st != BALL_OK) {
        out.pass = false;
        out.lines.push_back(fmt("net %d: ball_sphere_rect_distance: %s", i, ball_strerror(st)));
        continue;
      }
      double sx, sy, sz;
      ball_vec3 bc;
      rect_box(rect, &sx, &sy, &sz, &bc);
      fcl::Boxd box(sx, sy, sz);
      bool hit = fcl_collide(&sphere, at(c), &box, at(bc));
      double d_fcl = hit ? -1.0 : fcl_distance(&sphere, at(c), &box, at(bc));
      net_t.add(d_lib, hit, d_fcl,
                fmt("net %d (axis %d pos %.17g z/x [%.17g, %.17g] y [%.17g, %.17g], centre (%.17g, %.17g, %.17g) r "
                    "%.17g)",
                    i, rect.axis, rect.position, rect.lo, rect.hi, rect.bottom, rect.top, c.x, c.y, c.z, r));
    }
    // racket disc: a thin cylinder along the normal
    {
      ball_vec3 dc = rng.box({-2, 0, -2}, {2, 2, 2});
      ball_vec3 n = rng.unit();
      ball_vec3 n_lib = ball_v3_scale(n, rng.uniform(0.5, 2.0));  // libball takes any length
      double R = rng.uniform(0.05, 0.4);
      ball_vec3 u = perpendicular(n, rng);
      double rho = rng.uniform(0.0, R + r + 0.3), hgt = rng.uniform(-r - 0.3, r + 0.3);
      ball_vec3 c = ball_v3_add(dc, ball_v3_add(ball_v3_scale(u, rho), ball_v3_scale(n, hgt)));
      ball_vec3 q = disc_nearest(dc, n, R, c);
      ball_vec3 dir = ball_v3_sub(c, q);
      double gap = sample_gap(rng, r);
      if (ball_v3_norm(dir) > 1e-6 && r + gap > 0.0) c = ball_v3_add(q, ball_v3_scale(dir, (r + gap) / ball_v3_norm(dir)));
      double d_lib;
      ball_status st = ball_sphere_disc_distance(dc, n_lib, R, c, r, &d_lib);
      if (st != BALL_OK) {
        out.pass = false;
        out.lines.push_back(fmt("disc %d: ball_sphere_disc_distance: %s", i, ball_strerror(st)));
        continue;
      }
      fcl::Cylinderd cyl(R, kThin);
      Tf tf_cyl = axis_pose(dc, n);
      bool hit = fcl_collide(&sphere, at(c), &cyl, tf_cyl);
      double d_fcl = hit ? -1.0 : fcl_distance(&sphere, at(c), &cyl, tf_cyl);
      disc_t.add(d_lib, hit, d_fcl,
                 fmt("disc %d (centre (%.17g, %.17g, %.17g) normal (%.17g, %.17g, %.17g) R %.17g, ball (%.17g, "
                     "%.17g, %.17g) r %.17g)",
                     i, dc.x, dc.y, dc.z, n.x, n.y, n.z, R, c.x, c.y, c.z, r));
    }
  }
  out.pass = out.pass && floor_t.pass() && net_t.pass() && disc_t.pass();
  out.lines.insert(out.lines.begin(),
                   {fmt("%d configurations per obstacle (%.1f s); grazing band |libball distance| < %.0e m; FCL "
                        "net box and racket cylinder %.0e m thick, floor a %.0f m slab under floor_level",
                        opt.statics, now_s() - t_start, kBand, kThin, kFloorThick),
                    floor_t.line("floor"), net_t.line("net"), disc_t.line("disc")});
  for (const StaticTally *t : {&floor_t, &net_t, &disc_t})
    for (const std::string &c : t->cases) out.lines.push_back(c);
  return out;
}

namespace {

// One swept motion, in libball's terms.
struct Motion {
  ball_swept_query q;
  bool rotating;
};

// The disc normal at u under a motion: libball's normalised lerp, or FCL's
// InterpMotion (constant angular velocity about n0 x n1: slerp).
ball_vec3 normal_at(const Motion &mo, double u, bool slerp) {
  ball_vec3 n0 = ball_v3_scale(mo.q.n0, 1.0 / ball_v3_norm(mo.q.n0)), n1 = ball_v3_scale(mo.q.n1, 1.0 / ball_v3_norm(mo.q.n1));
  if (!slerp) {
    ball_vec3 n = ball_v3_lerp(n0, n1, u);
    return ball_v3_scale(n, 1.0 / ball_v3_norm(n));
  }
  double c = std::max(-1.0, std::min(1.0, ball_v3_dot(n0, n1)));
  double th = std::acos(c);
  if (th < 1e-15) return n0;
  ball_vec3 w = ball_v3_sub(n1, ball_v3_scale(n0, c));
  w = ball_v3_scale(w, 1.0 / ball_v3_norm(w));
  return ball_v3_add(ball_v3_scale(n0, std::cos(th * u)), ball_v3_scale(w, std::sin(th * u)));
}

// Static libball distance at u along the motion (normal by lerp or slerp).
double distance_at(const Motion &mo, double u, bool slerp) {
  double d = 0;
  ball_sphere_disc_distance(ball_v3_lerp(mo.q.c0, mo.q.c1, u), normal_at(mo, u, slerp), mo.q.disc_radius,
                            ball_v3_lerp(mo.q.p0, mo.q.p1, u), mo.q.ball_radius, &d);
  return d;
}

// Smallest distance over [0, 1]: dense samples, then golden section around
// the best one. *at gets where.
double min_distance(const Motion &mo, bool slerp, double *at) {
  const int n = 4000;
  int best = 0;
  double dbest = distance_at(mo, 0.0, slerp);
  for (int i = 1; i <= n; i++) {
    double d = distance_at(mo, static_cast<double>(i) / n, slerp);
    if (d < dbest) {
      dbest = d;
      best = i;
    }
  }
  double lo = std::max(0.0, (best - 1.0) / n), hi = std::min(1.0, (best + 1.0) / n);
  const double g = 0.6180339887498949;
  for (int k = 0; k < 80; k++) {
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    if (distance_at(mo, x1, slerp) < distance_at(mo, x2, slerp))
      hi = x2;
    else
      lo = x1;
  }
  double u = 0.5 * (lo + hi), d = distance_at(mo, u, slerp);
  if (d < dbest) {
    dbest = d;
    best = -1;
  }
  if (at) *at = best >= 0 ? static_cast<double>(best) / n : u;
  return dbest;
}

// First contact on [0, 1] by dense sampling of the static distance (checked
// against FCL above) and bisection: a reference time of impact independent of
// libball's swept search and of FCL's advancement; -1 if none is seen.
double reference_toi(const Motion &mo, bool slerp) {
  const int n = 4000;
  double prev = 0.0;
  if (distance_at(mo, 0.0, slerp) <= 0.0) return 0.0;
  for (int i = 1; i <= n; i++) {
    double u = static_cast<double>(i) / n;
    if (distance_at(mo, u, slerp) <= 0.0) {
      double lo = prev, hi = u;
      for (int k = 0; k < 100 && hi - lo > 0.0; k++) {
        double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        (distance_at(mo, mid, slerp) <= 0.0 ? hi : lo) = mid;
      }
      return hi;
    }
    prev = u;
  }
  return -1.0;
}

// A random ball/racket motion over one frame, aimed so about half hit: a
// contact-ish point is chosen on the grown disc at a random time and both
// motions are laid through it.
Motion random_motion(Rng &rng, bool rotating) {
  Motion mo{};
  mo.rotating = rotating;
  ball_swept_query &q = mo.q;
  q.ball_radius = rng.chance(0.05) ? 0.0 : rng.uniform(0.02, 0.15);
  q.disc_radius = rng.uniform(0.05, 0.4);
  ball_vec3 n0 = rng.unit();
  ball_vec3 n1 = n0;
  if (rotating) {  // a turn of up to 30 degrees about an axis in the disc plane
    ball_vec3 a = perpendicular(n0, rng);
    double th = rng.uniform(0.0, 30.0) * M_PI / 180.0;
    ball_vec3 w = ball_v3_cross(a, n0);
    n1 = ball_v3_add(ball_v3_scale(n0, std::cos(th)), ball_v3_scale(w, std::sin(th)));
  }
  ball_vec3 dc = ball_v3_scale(rng.unit(), rng.uniform(0.0, 1.0));   // racket moves up to 1 m in the frame
  ball_vec3 dp = ball_v3_scale(rng.unit(), rng.uniform(0.0, 2.0));   // the ball up to 2 m
  double ts = rng.uniform(0.0, 1.0);
  ball_vec3 cs = rng.box({-2, 0, -2}, {2, 2, 2});            // disc centre at ts
  q.c0 = ball_v3_sub(cs, ball_v3_scale(dc, ts));
  q.c1 = ball_v3_add(q.c0, dc);
  Motion tmp = mo;
  tmp.q.n0 = n0;
  tmp.q.n1 = n1;
  ball_vec3 ns = normal_at(tmp, ts, false);
  ball_vec3 u = perpendicular(ns, rng);
  double rho = rng.uniform(0.0, q.disc_radius + q.ball_radius + 0.1);
  double side = (rng.chance(0.5) ? 1 : -1) * (q.ball_radius + rng.uniform(-0.05, 0.05));
  ball_vec3 ps = ball_v3_add(cs, ball_v3_add(ball_v3_scale(u, rho), ball_v3_scale(ns, side)));
  q.p0 = ball_v3_sub(ps, ball_v3_scale(dp, ts));
  q.p1 = ball_v3_add(q.p0, dp);
  q.n0 = ball_v3_scale(n0, rng.uniform(0.5, 2.0));  // libball takes any length
  q.n1 = ball_v3_scale(n1, rng.uniform(0.5, 2.0));
  return mo;
}

// The FCL poses of a motion: sphere without rotation, cylinder axis along
// n; the end rotation is the shortest turn n0 -> n1 after c0's rotation, so
// FCL turns the axis along the great circle through n0 and n1.
void fcl_poses(const Motion &mo, Tf *b0, Tf *b1, Tf *c0, Tf *c1) {
  *b0 = at(mo.q.p0);
  *b1 = at(mo.q.p1);
  *c0 = axis_pose(mo.q.c0, mo.q.n0);
  *c1 = *c0;
  c1->linear() = fcl::Quaterniond::FromTwoVectors(ev(mo.q.n0).normalized(), ev(mo.q.n1).normalized())
                     .toRotationMatrix() *
                 c0->linear();
  c1->translation() = ev(mo.q.c1);
}

// FCL's answer: sphere and thin cylinder, conservative advancement; pure
// translation as TranslationMotion, a turning racket as InterpMotion (the
// ball's InterpMotion without rotation is the same straight line).
bool fcl_swept(const Motion &mo, double *toc) {
  fcl::Sphered sphere(mo.q.ball_radius);
  fcl::Cylinderd cyl(mo.q.disc_radius, kThin);
  Tf b0, b1, c0, c1;
  fcl_poses(mo, &b0, &b1, &c0, &c1);
  fcl::ContinuousCollisionRequestd req(1000, 1e-10, mo.rotating ? fcl::CCDM_LINEAR : fcl::CCDM_TRANS,
                                       fcl::GST_LIBCCD, fcl::CCDC_CONSERVATIVE_ADVANCEMENT);
  fcl::ContinuousCollisionResultd res;
  fcl::continuousCollide(&sphere, b0, b1, &cyl, c0, c1, req, res);
  *toc = res.time_of_contact;
  return res.is_collide;
}

// FCL's shape-shape conservative advancement loop, step by step with FCL's
// own pieces (libccd solver, RSS motion bounds), to explain a disagreement:
// where it stopped, at what gap, and whether it stepped over the rest of the
// frame from a touching pose: closest points equal or within rounding of
// each other give no direction or a random one, the motion bound along it is
// 0 or negative, and the next step is the whole frame.
struct CaTrace {
  bool hit = false;
  double toc = 0;       // where it stopped
  double gap = 0;       // distance there (FCL reports -1 when overlapping)
  bool jumped = false;  // stepped on from a touching pose (gap <= kTouch)
  double jump_toc = 0;  // ... at this time
  double jump_gap = 0;  // ... with this distance
};

CaTrace ca_trace(const Motion &mo) {
  using Solver = fcl::detail::GJKSolver_libccd<double>;
  CaTrace tr;
  fcl::Sphered sphere(mo.q.ball_radius);
  fcl::Cylinderd cyl(mo.q.disc_radius, kThin);
  Tf b0, b1, c0, c1;
  fcl_poses(mo, &b0, &b1, &c0, &c1);
  // The motions live on the stack. On the heap, libfcl's deleting
  // destructors (built as C++14: Eigen's aligned operator delete) would free
  // what this C++17 code's operator new allocated, which AddressSanitizer
  // rightly reports as an alloc-dealloc mismatch.
  fcl::InterpMotion<double> turn1(b0, b1), turn2(c0, c1);
  fcl::TranslationMotion<double> shift1(b0, b1), shift2(c0, c1);
  fcl::MotionBase<double> *m1 = &shift1, *m2 = &shift2;
  if (mo.rotating) {
    m1 = &turn1;
    m2 = &turn2;
  }
  Solver solver;
  fcl::RSSd bv1, bv2;
  fcl::computeBV(sphere, Tf::Identity(), bv1);
  fcl::computeBV(cyl, Tf::Identity(), bv2);
  Tf t1, t2;
  m1->getCurrentTransform(t1);
  m2->getCurrentTransform(t2);
  if (fcl_collide(&sphere, t1, &cyl, t2)) {
    tr.hit = true;
    return tr;
  }
  double toc = 0;
  for (int it = 0; it < 100000; it++) {
    m1->getCurrentTransform(t1);
    m2->getCurrentTransform(t2);
    double d = 0;
    Vec q1 = Vec::Zero(), q2 = Vec::Zero();
    solver.shapeDistance(sphere, t1, cyl, t2, &d, &q1, &q2);
    Vec n = q2 - q1;
    if (n.squaredNorm() > 0.0) n.normalize();
    fcl::TBVMotionBoundVisitor<fcl::RSSd> v1(bv1, n), v2(bv2, -n);
    double bound = m1->computeMotionBound(v1) + m2->computeMotionBound(v2);
    double dt = bound <= d ? 1.0 : d / bound;
    tr.toc = toc;
    tr.gap = d;
    if (dt <= kCaTErr) {
      tr.hit = true;
      return tr;
    }
    if (d <= kTouch && !tr.jumped) {
      tr.jumped = true;
      tr.jump_toc = toc;
      tr.jump_gap = d;
    }
    toc += dt;
    if (toc > 1) break;
    m1->integrate(toc);
    m2->integrate(toc);
  }
  tr.hit = false;
  return tr;
}

std::string describe(const Motion &mo) {
  const ball_swept_query &q = mo.q;
  return fmt("p0 (%.17g, %.17g, %.17g) p1 (%.17g, %.17g, %.17g) r %.17g c0 (%.17g, %.17g, %.17g) c1 (%.17g, %.17g, "
             "%.17g) n0 (%.17g, %.17g, %.17g) n1 (%.17g, %.17g, %.17g) R %.17g",
             q.p0.x, q.p0.y, q.p0.z, q.p1.x, q.p1.y, q.p1.z, q.ball_radius, q.c0.x, q.c0.y, q.c0.z, q.c1.x, q.c1.y,
             q.c1.z, q.n0.x, q.n0.y, q.n0.z, q.n1.x, q.n1.y, q.n1.z, q.disc_radius);
}

}  // namespace
Outcome check_swept(const Options &opt) {
  Outcome out;
  out.check = "validate_swept";
  double t_start = now_s();
  for (int set = 0; set < 2; set++) {
    bool rotating = set == 1;
    Rng rng(opt.seed, 4 + set);
    long both = 0, neither = 0, fcl_only = 0, lib_only = 0, unexplained = 0, at_start = 0;
    long why_jump = 0, why_near = 0, why_graze = 0, why_rot = 0, fcl_late = 0;
    double max_diff = 0, sum_diff = 0, max_jump_diff = 0;
    double max_lib_ref = 0, max_fcl_ref = 0, max_interp = 0;  // against the reference roots
    long n_ref = 0;
    std::vector<std::string> notes;
    for (int i = 0; i < opt.swept; i++) {
      Motion mo = random_motion(rng, rotating);
      int hit = 0;
      double toi = -1;
      ball_vec3 point;
      ball_status st = ball_swept_disc(&mo.q, &hit, &toi, &point);
      if (st != BALL_OK) {
        out.pass = false;
        notes.push_back(fmt("motion %d: ball_swept_disc: %s", i, ball_strerror(st)));
        continue;
      }
      double toc;
      bool fhit = fcl_swept(mo, &toc);
      if (hit && fhit) {
        both++;
        if (toi == 0.0 && toc == 0.0) {
          at_start++;  // overlapping at the start: both report contact at 0
          continue;
        }
        double diff = toi - toc;  // FCL stops short of contact: diff >= 0 expected
        double ref_lib = reference_toi(mo, false), ref_fcl = rotating ? reference_toi(mo, true) : ref_lib;
        if (ref_lib >= 0.0 && ref_fcl >= 0.0) {
          n_ref++;
          max_lib_ref = std::max(max_lib_ref, std::fabs(toi - ref_lib));
          max_fcl_ref = std::max(max_fcl_ref, std::fabs(toc - ref_fcl));
          max_interp = std::max(max_interp, std::fabs(ref_lib - ref_fcl));
        }
        max_diff = std::max(max_diff, std::fabs(diff));
        sum_diff += std::fabs(diff);
        // FCL's conservative time must not be past contact on its own motion
        if (distance_at(mo, toc, rotating) < -kBand) {
          fcl_late++;
          notes.push_back(fmt("motion %d: FCL's time of contact %.17g overlaps already (libball %.17g): %s", i,
                              toc, toi, describe(mo).c_str()));
        }
        if (!rotating && diff < -kBand) {
          // libball earlier than FCL's conservative lower bound: libball wrong
          unexplained++;
          notes.push_back(fmt("motion %d: libball toi %.17g before FCL's conservative %.17g: %s", i, toi, toc,
                              describe(mo).c_str()));
        }
        continue;
      }
      if (!hit && !fhit) {
        neither++;
        continue;
      }
      double u_lib, u_fcl;
      double g_lib = min_distance(mo, false, &u_lib);  // libball's motion (lerp normal)
      double g_fcl = min_distance(mo, true, &u_fcl);   // FCL's motion (slerp normal)
      CaTrace tr = ca_trace(mo);
      std::string why;
      if (tr.hit != fhit) {
        why = "";  // the replica must reproduce FCL; if not, leave it unexplained
      } else if (fhit) {
        fcl_only++;
        if (g_lib > 0.0 && tr.gap > 0.0 && (rotating ? g_fcl : g_lib) <= tr.gap + kBand) {
          why_near++;
          why = fmt("near miss: FCL stopped at gap %.3g m (its next step under t_err = %.0e of the frame), the "
                    "closest approach is %.3g m at %.4f",
                    tr.gap, kCaTErr, rotating ? g_fcl : g_lib, rotating ? u_fcl : u_lib);
        } else if (rotating && g_lib > 0.0 && g_fcl <= kBand) {
          why_rot++;
          why = fmt("rotation interpolation: FCL's slerped disc touches (gap %.3g m at %.4f), libball's lerped "
                    "normal keeps %.3g m clear",
                    g_fcl, u_fcl, g_lib);
        }
      } else {
        lib_only++;
        // does FCL's own static test see the overlap libball found?
        fcl::Sphered sphere(mo.q.ball_radius);
        fcl::Cylinderd cyl(mo.q.disc_radius, kThin);
        bool fcl_sees = fcl_collide(&sphere, at(ball_v3_lerp(mo.q.p0, mo.q.p1, u_lib)), &cyl,
                                    axis_pose(ball_v3_lerp(mo.q.c0, mo.q.c1, u_lib), normal_at(mo, u_lib, rotating)));
        if (tr.jumped && fcl_sees && std::fabs(tr.jump_toc - toi) < 1e-6) {
          why_jump++;
          max_jump_diff = std::max(max_jump_diff, std::fabs(tr.jump_toc - toi));
          why = fmt("FCL stepped over the contact: it reached the touching pose at %.12f (gap %.2g m), where its "
                    "closest points coincide to rounding, so the direction is 0 or noise, the motion bound <= 0 "
                    "and the next step the whole frame; its own static collide sees the overlap (%.3g m deep at %.4f)",
                    tr.jump_toc, tr.jump_gap, -g_lib, u_lib);
        } else if (g_lib <= 0.0 && g_lib > -kBand) {
          why_graze++;
          why = fmt("graze: libball's deepest overlap %.3g m is inside the band", -g_lib);
        } else if (rotating && g_lib <= 0.0 && g_fcl > 0.0) {
          why_rot++;
          why = fmt("rotation interpolation: libball's lerped normal touches (overlap %.3g m at %.4f), FCL's "
                    "slerped disc keeps %.3g m clear",
                    -g_lib, u_lib, g_fcl);
        }
      }
      bool ok = !why.empty();
      unexplained += !ok;
      if (!ok || notes.size() < 6)
        notes.push_back(fmt("motion %d: %s only (libball toi %.17g, FCL toc %.17g): %s%s; %s", i,
                            fhit ? "FCL" : "libball", hit ? toi : NAN, fhit ? toc : NAN,
                            ok ? "explained, " : "UNEXPLAINED ", why.c_str(), describe(mo).c_str()));
    }
    bool pass = unexplained == 0 && fcl_late == 0;
    out.pass = out.pass && pass;
    out.lines.push_back(fmt("%s set, %d motions: both hit %ld (%ld overlapping at the start), neither %ld, FCL "
                            "only %ld, libball only %ld, unexplained %ld",
                            rotating ? "rotating (libball lerps the normal, FCL slerps; turns <= 30 deg)"
                                     : "translation",
                            opt.swept, both, at_start, neither, fcl_only, lib_only, unexplained));
    out.lines.push_back(fmt("  time of impact when both hit: max |libball - FCL| %.3e, mean %.3e (frame = 1)",
                            max_diff, both - at_start ? sum_diff / static_cast<double>(both - at_start) : 0.0));
    out.lines.push_back(fmt("  reference roots (dense sampling of the static distance + bisection, %ld motions): "
                            "|libball - ref(lerp)| <= %.3e, |FCL - ref(%s)| <= %.3e%s",
                            n_ref, max_lib_ref, rotating ? "slerp" : "same motion", max_fcl_ref,
                            rotating ? fmt(", |ref(lerp) - ref(slerp)| <= %.3e", max_interp).c_str() : ""));
    out.lines.push_back(fmt("  explained: %ld FCL steps over a touching pose (its touching time matches libball's "
                            "to %.1e), %ld near misses under FCL's stop gap, %ld grazes in the band, %ld rotation "
                            "interpolation",
                            why_jump, max_jump_diff, why_near, why_graze, why_rot));
    for (const std::string &s2 : notes) out.lines.push_back("  " + s2);
  }
  out.lines.insert(out.lines.begin(),
                   fmt("FCL continuousCollide, conservative advancement (t_err %.0e hard-coded), sphere vs %.0e m "
                       "thick cylinder (%.1f s)",
                       kCaTErr, kThin, now_s() - t_start));
  return out;
}

}  // namespace bv
