// The server loop's side of failover's room (server_loop.h, cluster.h):
// what the other servers of the domain wrote, claims and take-overs; the
// Cluster decides, the loop carries it out on its host and its port.
#include "server_loop.h"

#include <algorithm>
#include <cstdio>

namespace ballsrv {

// ---- the other servers of the domain ------------------------------------------

void ServerLoop::take_others() {
  ParticipantId from;
  StatusOut st;
  while (port_.take_other_status(&st, &from)) cluster_.hear_status(st, from);
  // the models before the infos: a standby follows a match with the model its info names
  MatchModelOut model;
  while (port_.take_other_model(&model, &from)) cluster_.hear_model(model);
  MatchInfoOut info;
  for (const auto &known : cluster_.known_infos()) other_info(known.first, known.second);
  while (port_.take_other_info(&info, &from)) other_info(info, from);
  SegmentOut seg;
  while (port_.take_other_segment(&seg, &from)) cluster_.hear_segment(seg, from, scheduled(seg.match_id) != nullptr);
}

// Another server's MatchInfo: the Cluster decides, the loop yields and
// follows (docs/protocol.md, "Several servers on one domain").
void ServerLoop::other_info(const MatchInfoOut &info, const ParticipantId &from) {
  uint32_t id = info.match_id;
  const Scheduled *ours = scheduled(id);
  Cluster::Heard heard = cluster_.hear_info(info, from, host_.find(id) != nullptr, ours != nullptr,
                                            ours ? ours->term : 0, clock_.realtime());
  if (heard == Cluster::Heard::refused || heard == Cluster::Heard::unknown) return;
  if (heard == Cluster::Heard::stale) {  // an older term's owner as strong as ours: outrank it
    raise_strength(cluster_.stronger_than(from, cluster_.settings().strength));
    return;
  }
  if (heard == Cluster::Heard::conflict) {
    // one this match cannot follow (another slot count or model) is not its owner's: it keeps the match
    std::string why;
    const Match *m = host_.find(id);
    if (m && !m->can_follow(info, &why)) return cluster_.refuse_other();
    if (on_conflict_) on_conflict_(info, from);
    yield(id, info, from);
  }
  const ball_model *wire = nullptr;
  Cluster::Follow plan = cluster_.follow_plan(info, clock_.mono(), &wire);
  if (plan == Cluster::Follow::none) return;
  std::string err;
  bool ok = true;
  if (plan == Cluster::Follow::begin) {
    ok = host_.follow(info, wire, &err);
  } else {
    Match *m = host_.find(id);
    ok = !m || m->follow(info, &err);
  }
  std::string line = cluster_.followed(info, from, plan, ok, err, clock_.mono());
  if (!line.empty()) say(line);
}

void ServerLoop::yield(uint32_t id, const MatchInfoOut &to, const ParticipantId &from) {
  sched_.erase(std::remove_if(sched_.begin(), sched_.end(), [id](const Scheduled &s) { return s.match->id() == id; }),
               sched_.end());
  Match *m = host_.find(id);
  std::string err;
  // it follows the match, to take it back if that owner is lost or goes silent (cluster.h)
  bool following = m && m->follow(to, &err);
  if (!following) host_.remove(id);
  cluster_.yielded(id, to, from, following, clock_.mono());
  say("yielded match " + std::to_string(id) + " to server " + std::to_string(to.server_id) + " (participant " +
      hex(from) + ")" + (following ? ", following it" : ", dropped it: " + err));
}

// ---- claims ----------------------------------------------------------------

bool ServerLoop::claim(const MatchConfig &config, double t0, std::string *err) {
  const ball_scene *sc = host_.scene(config.scene_name, err);
  if (!sc || !host_.add_match(config, *sc, err)) return false;
  Scheduled s = schedule(host_.find(config.id));
  s.firm_at = t0 + settings_.settle;
  sched_.push_back(s);
  publish_info(sched_.back());
  cluster_.claimed();
  return true;
}

void ServerLoop::claim_unplaced(double t0) {
  auto placed = [this](uint32_t id) { return scheduled(id) || host_.find(id); };
  for (const MatchConfig &c : cluster_.claims_due(t0, placed)) {
    std::string err;
    if (claim(c, t0, &err)) say("claimed match " + std::to_string(c.id));
    else say("cannot claim match " + std::to_string(c.id) + ": " + err);
  }
}

// A CREATE for a new match: the Cluster says whose it is (a claimant
// creates it when the claim rule gives it the match, a server that claims
// nothing but steps its configured matches as before; a standby alone never).
bool ServerLoop::may_create(const ControlIn &c) {
  if (c.kind != ControlKind::create || host_.find(c.match_id)) return true;
  return cluster_.may_create(c.match_id);
}

// ---- take-overs ----------------------------------------------------------------

void ServerLoop::take_over(double t0, double now) {
  auto hears = [this, now](uint32_t id) {
    const Match *m = host_.find(id);
    return m && m->hears_players(now);
  };
  for (uint32_t id : cluster_.let_go_unheld(t0)) {
    host_.remove(id);
    say("let match " + std::to_string(id) + " go: its owner is gone, and nobody held a slot of it");
  }
  // the strength of a take-over's term from the moment the owner is lost: readers learn it by
  // discovery, and one that knew the old strength when the first samples came would drop them
  if (uint32_t term = cluster_.coming_term(t0)) raise_strength(term_strength(base_strength_, term));
  for (uint32_t id : cluster_.due_takeovers(t0, hears)) take_over_match(id, t0, now);
}

void ServerLoop::take_over_match(uint32_t id, double t0, double now) {
  Match *m = host_.find(id);
  const Followed *f = cluster_.followed(id);
  if (!m || !f) return;
  Scheduled s = schedule(m);
  double first_real = s.clock.realtime_at(s.clock.deadline(s.k));
  RestorePoint p = restore_point(*f, first_real, m->frame_time());
  double lost_ago = t0 - f->lost_at;
  out_.clear();
  std::string err;
  if (!m->restore(p.info, p.has_segment ? &p.segment : nullptr, p.newest_seq, p.target, &out_, &err)) {
    cluster_.taken_over(id, false);
    say("cannot take match " + std::to_string(id) + " over: " + err);
    host_.remove(id);
    return;
  }
  cluster_.taken_over(id, true);
  s.revision = p.info.revision;
  s.term = std::max(s.term, next_term(p.info.term, settings_.server_id));
  raise_strength(term_strength(base_strength_, s.term));
  s.last_frame_real = first_real - m->frame_time();  // the instant the sim time `target` holds for
  s.taken_over = true;
  s.since = now;
  sched_.push_back(s);
  publish(out_, sched_.back(), now);
  publish_info(sched_.back());
  char line[256];
  std::snprintf(line, sizeof line,
                "took match %u over from server %u at sim time %.3f (segment %u, %zu segments caught up, owner lost "
                "%.2f s ago)",
                id, p.info.server_id, m->sim().time, p.has_segment ? p.segment.seq : 0u, out_.segments.size(),
                lost_ago);
  say(line);
}

}  // namespace ballsrv
