// Which server of a domain steps which match, free of DDS (docs/protocol.md,
// "Several servers on one domain"). Every server computes these rules alike
// from what it has heard (the other servers' ServerStatus, the owners'
// MatchInfo), so that servers that know the same peers decide the same
// thing without asking each other; DDS exclusive ownership settles what a
// server decided in ignorance (the weaker of two owners yields).
#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <vector>

namespace ballsrv {

// A server as the rules see it (from its ServerStatus, or oneself).
struct ServerView {
  uint32_t server_id = 0;
  uint32_t strength = 0;    // its match writers' ownership strength
  bool standby = false;     // it follows other servers' matches and takes them over
  uint32_t claim_room = 0;  // matches it may still claim
  bool alive = true;        // its status writer has its liveliness
};

// The claim rule's rank of server `server_id` for match `match_id`: a
// 64-bit mix (splitmix64's finaliser) of both ids, the same on every host.
// Rendezvous hashing: each match goes to the claimant it ranks highest, so
// the matches spread evenly and a new claimant takes only its share.
inline uint64_t claim_rank(uint32_t match_id, uint32_t server_id) {
  uint64_t z = (static_cast<uint64_t>(match_id) << 32 | server_id) + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// Who claims each unplaced match: of the live claimants with room, the one
// of the highest rank (ties: the lower id), the matches in the order of
// their ids, each taking one unit of its claimant's room. Independent of the
// order in which the matches and the claimants are listed. Matches no
// claimant has room for are left out.
inline std::map<uint32_t, uint32_t> assign_claims(std::vector<uint32_t> matches, const std::vector<ServerView> &servers) {
  std::sort(matches.begin(), matches.end());
  matches.erase(std::unique(matches.begin(), matches.end()), matches.end());
  std::map<uint32_t, uint32_t> room;  // by server id
  for (const ServerView &s : servers)
    if (s.alive && s.claim_room > 0) room[s.server_id] = std::max(room[s.server_id], s.claim_room);
  std::map<uint32_t, uint32_t> out;
  for (uint32_t m : matches) {
    uint32_t best = 0;
    uint64_t best_rank = 0;
    bool found = false;
    for (const auto &r : room) {
      if (r.second == 0) continue;
      uint64_t rank = claim_rank(m, r.first);
      if (!found || rank > best_rank || (rank == best_rank && r.first < best)) {
        best = r.first;
        best_rank = rank;
        found = true;
      }
    }
    if (!found) continue;
    out[m] = best;
    room[best]--;
  }
  return out;
}

// Which standby takes over a match whose owner `owner_id` was lost: the
// strongest live standby, then the one with the lowest id; false when there
// is none.
inline bool successor(const std::vector<ServerView> &servers, uint32_t owner_id, uint32_t *server_id) {
  const ServerView *best = nullptr;
  for (const ServerView &s : servers) {
    if (!s.alive || !s.standby || s.server_id == owner_id) continue;
    if (!best || s.strength > best->strength || (s.strength == best->strength && s.server_id < best->server_id))
      best = &s;
  }
  if (best) *server_id = best->server_id;
  return best != nullptr;
}

}  // namespace ballsrv
