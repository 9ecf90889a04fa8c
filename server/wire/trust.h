// What a client takes from the server topics, free of DDS (docs/protocol.md,
// "Clients that trust no one"): samples of the servers it chose, MatchInfo
// whose numbers are in their ranges, segment numbers that fit the stream,
// scene names that are names, never paths. What it refuses it counts and
// drops; it never exits on a value from the wire. A server takes another
// server's MatchInfo by the same rule (usable_info).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "types.h"

namespace ballsrv {

// The servers a client chose, from "1,2" ("": any server). Under DDS
// Security an id may name the identity whose certificate its server holds,
// "1=server1": samples claiming that id from any other participant are
// refused (docs/security.md, "A server's certificate").
struct ServerChoice {
  std::vector<uint32_t> ids;           // empty: any
  std::vector<std::string> identities;  // identities[i]: the certificate of ids[i] ("": any)
  bool accepts(uint32_t server_id) const;
  // (id, identity) for each id bound to a certificate
  std::vector<std::pair<uint32_t, std::string>> bound() const;
  // false with a sentence in err unless a comma-separated list of ID or
  // ID=NAME (NAME: letters, digits, '-', '_', '.', not starting with '.').
  static bool parse(const std::string &text, ServerChoice *out, std::string *err);
};

// sim s: no match's clock gets this far (31 years of play); a sim time
// beyond it is forged, and steps of a frame would vanish in its rounding
constexpr double kMaxSimTime = 1e9;
// points a side may have: a forged score must not overflow when it scores
constexpr int kMaxScore = 1 << 30;

// A MatchInfo a client can use: slots, level, the settings that travel
// (check_wire_settings), frame time and the flight model in their ranges (a
// forged level 99 once made ball-bot exit),
// the enums among the IDL's values, the sim clock and the segment's t0 in
// [0, kMaxSimTime], and its Play usable (usable_play).
bool usable_info(const MatchInfoOut &info);

// A Play from the wire (docs/protocol.md, "Segments") whose numbers are in
// the ranges a server writes: serving side, striker and bounce side 0 or 1,
// bounces 0 or 1, scores in [0, kMaxScore], the rally's start and the
// serve's time finite. The sides and counts index the rules' arrays.
bool usable_play(const PlayState &play);
// And as a server writes it at sim s `at` (a MatchInfo's sim_time, a
// Segment's t0): the rally begun by then, the serve due at most the longest
// serve_delay after it (a serve put off without end stops the match).
bool play_fits(const PlayState &play, double at);

// What a server takes of another server's MatchInfo (docs/protocol.md,
// "Several servers on one domain"): usable_info, its segment starting no
// later than its sim_time, and its Play fitting that sim time.
bool usable_other_info(const MatchInfoOut &info);
// Another server's Segment a standby may go on from: finite, its cause
// among the IDL's, its t0 in [0, kMaxSimTime] and its Play fitting that t0.
bool usable_segment(const SegmentOut &segment);

// A MatchModel a reader may use for a match whose newest usable MatchInfo
// names `info_hash` (docs/protocol.md, "The match's model"): its model
// passes ball_model_check and hashes to its model_hash, which is info_hash.
bool usable_model(const MatchModelOut &m, uint64_t info_hash);

// A segment whose numbers are all finite: a forged NaN or infinity must
// reach no evaluation (nor a JSON record, which has no such numbers).
bool finite_segment(const ball_segment &s);

// Of two owners of a match, (term, server_id), whether a is older than b
// (docs/protocol.md, "Terms"): the lower term, or of one term the higher
// server id. A client takes nothing of an older owner's than one it took.
bool owner_before(uint32_t term_a, uint32_t server_a, uint32_t term_b, uint32_t server_b);
// Terms further ahead of the one held than this are not the match's (a
// forged term 0xFFFFFFFF must not blind a client to its server): 1000
// rounds, a term being 256 x round + a server's (docs/protocol.md, "Terms").
constexpr uint32_t kMaxTermAhead = 1000u << 8;

// Segments further ahead of the newest than this are not the stream's (a
// forged seq 0xFFFFFFFF once blinded every bot): unless the newest
// MatchInfo names that seq as the one in effect.
constexpr uint32_t kMaxSeqAhead = 1000;
// Whether segment `seq` is news for a stream whose newest is `newest` (0:
// none yet) and whose newest MatchInfo names `info_seq` as in effect:
// ahead of it in serial-number arithmetic, by at most kMaxSeqAhead, or
// info_seq itself (a server that started the match anew).
bool segment_is_news(uint32_t seq, uint32_t newest, uint32_t info_seq);
// Whether segment `seq` belongs to that stream at all: within kMaxSeqAhead
// of the newest either way, without wrapping around (a late joiner gets
// older ones after the one in effect), or info_seq itself.
bool segment_fits(uint32_t seq, uint32_t newest, uint32_t info_seq);

}  // namespace ballsrv
