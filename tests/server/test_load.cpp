// The load benchmark's core (server/client/load.h): the split of the
// matches over bot processes, the sim-to-real mapping of hit-to-wire, the
// payload bytes of counted samples, the /proc figures, the parts of a run
// combined and the rounds of a point summarized, with hand-computed values.
#include <algorithm>

#include "check.hpp"
#include "load.h"

using namespace ballsrv;

TEST(matches_split_in_consecutive_ranges_differing_by_at_most_one) {
  auto r = split_matches(0, 10, 3);
  CHECK_EQ(r.size(), 3u);
  CHECK_EQ(r[0].first, 0);
  CHECK_EQ(r[0].count, 4);
  CHECK_EQ(r[1].first, 4);
  CHECK_EQ(r[1].count, 3);
  CHECK_EQ(r[2].first, 7);
  CHECK_EQ(r[2].count, 3);
  auto few = split_matches(5, 2, 4);  // no empty range
  CHECK_EQ(few.size(), 2u);
  CHECK_EQ(few[1].first, 6);
  CHECK_EQ(split_matches(0, 7, 0).size(), 1u);
  CHECK_EQ(split_matches(0, 0, 2).size(), 0u);
}

TEST(a_sim_time_maps_to_the_server_instant_by_the_info_pair) {
  MatchInfoOut info;
  info.sim_time = 10.0;
  info.server_time = 1000.0;
  info.settings.time_base = 0.5;  // sim runs at half speed
  CHECK_NEAR(server_time_of(info, 11.0), 1002.0, 1e-12);
  CHECK_NEAR(server_time_of(info, 9.75), 999.5, 1e-12);
}

namespace {
void feed(LoadMeter &m, const json &line) {
  std::string text = line.dump();
  LoadMeter::tap(&m, text.c_str(), text.size());
}
}  // namespace

// The meter over tap lines: counts by type, the hits' segments of its own
// matches timed by hand-computed values while measuring, the server's
// statuses of the window, and lines that do not read counted apart.
TEST(the_meter_times_its_own_matches_hits_from_the_tap) {
  LoadMeter m(4, 2);  // matches 4 and 5
  MatchInfoOut info;
  info.match_id = 4;
  info.sim_time = 10.0;
  info.server_time = 1000.0;
  info.settings.time_base = 1.0;
  SegmentOut hit;
  hit.match_id = 4;
  hit.cause = Cause::racket;
  hit.segment.t0 = 10.5;          // at server 1000.5
  hit.sample.source_time = 1000.48;
  hit.sample.valid = true;
  auto segment_line = [](const SegmentOut &s, double recv, double sent) {
    json j = record_line(s, recv);
    if (sent > 0.0) j["sent"] = sent;
    return j;
  };
  feed(m, record_line(info, 999.0));
  feed(m, segment_line(hit, 1000.53, 1000.51));  // not measuring yet
  CHECK(m.part.latency.empty());
  m.measuring = true;
  feed(m, segment_line(hit, 1000.53, 1000.51));
  SegmentOut other = hit;
  other.match_id = 6;  // another process's
  feed(m, segment_line(other, 1000.53, 1000.51));
  SegmentOut bounce = hit;
  bounce.cause = Cause::floor;
  feed(m, segment_line(bounce, 1000.6, 0.0));
  SegmentOut late = hit;
  late.correction = true;  // lag compensation's: its latency, no hit-to-wire
  feed(m, segment_line(late, 1000.56, 0.0));
  SegmentOut unsent = hit;  // DDS said no source timestamp: hit-to-wire only
  feed(m, segment_line(unsent, 1000.54, 0.0));
  CHECK_EQ(m.part.latency.size(), 3u);
  CHECK_NEAR(m.part.latency[0], 0.05, 1e-9);
  CHECK_NEAR(m.part.latency[1], 0.08, 1e-9);
  CHECK_EQ(m.part.hit_to_wire.size(), 2u);
  CHECK_NEAR(m.part.hit_to_wire[0], 0.03, 1e-9);
  CHECK_NEAR(m.part.hit_to_wire[1], 0.04, 1e-9);
  CHECK_EQ(m.part.hit_to_write.size(), 1u);
  CHECK_NEAR(m.part.hit_to_write[0], 0.01, 1e-9);
  CHECK_NEAR(m.part.delivery[0], 0.02, 1e-9);
  StatusOut a, b;
  a.server_id = b.server_id = 1;
  a.frame_p50 = 0.001;
  b.frame_p50 = 0.002;
  b.samples_in = 40;
  feed(m, record_line(a, 1000.0));
  feed(m, record_line(b, 1001.0));
  CHECK_EQ(m.part.frame_p50.size(), 2u);
  CHECK_EQ(m.part.first.frame_p50, 0.001);
  CHECK_EQ(m.part.last.samples_in, 40u);
  feed(m, record_line(StateOut{}, 1001.0));
  feed(m, record_line(EventOut{}, 1001.0));
  feed(m, json{{"type", "ready"}, {"recv", 1.0}});
  PortCounts c = m.counts();
  CHECK(c.infos == 1 && c.segments == 6 && c.statuses == 2 && c.states == 1 && c.events == 1);
  CHECK(m.info(4) && !m.info(5));
  CHECK_EQ(m.unreadable(), 0u);
  json bad = segment_line(hit, 1000.5, 0.0);
  bad["cause"] = "volley";
  feed(m, bad);
  LoadMeter::tap(&m, "[1, 2]", 6);
  CHECK_EQ(m.unreadable(), 2u);
  CHECK_EQ(m.part.latency.size(), 3u);
}

TEST(payload_is_counts_times_sizes) {
  PortCounts c;
  c.infos = 2;
  c.segments = 3;
  c.states = 5;
  c.events = 7;
  c.statuses = 1;
  c.samples_written = 11;
  c.controls_written = 13;
  WireSizes s{100, 10, 1000, 10000, 100000, 1000000, 10000000};
  CHECK_EQ(server_payload(c, s), 2u * 1000000 + 3u * 1000 + 5u * 100000 + 7u * 10000 + 10000000u);
  CHECK_EQ(client_payload(c, s), 11u * 100 + 13u * 10);
  PortCounts d = c - c;
  CHECK_EQ(server_payload(d, s), 0u);
}

TEST(what_the_server_wrote_is_its_own_counts_over_its_statuses) {
  WireSizes s{100, 10, 1000, 10000, 100000, 1000000, 10000000};
  StatusOut a, b;
  a.server_time = 10.0;
  b.server_time = 14.0;
  a.segments_out = 5, b.segments_out = 9;
  a.events_out = 7, b.events_out = 15;
  a.states_out = 100, b.states_out = 140;
  CHECK_NEAR(server_written_per_s(a, b, s), (4.0 * 1000 + 8.0 * 10000 + 40.0 * 100000) / 4.0, 1e-9);
  CHECK_EQ(server_written_per_s(a, a, s), -1.0);  // one status: no span
  CHECK_EQ(server_written_per_s(b, a, s), -1.0);  // the later first
  StatusOut restarted = b;
  restarted.events_out = 3;  // a count that went back (another server): not a payload
  CHECK_EQ(server_written_per_s(a, restarted, s), -1.0);
}

TEST(proc_texts_give_cpu_rss_and_loopback_bytes) {
  double cpu = 0.0, rss = 0.0;
  // comm with a space and a parenthesis; utime 250, stime 50 ticks
  std::string stat = "123 (ball (x) y) S 1 2 3 4 5 6 7 8 9 10 250 50 0 0 20 0 1";
  CHECK(parse_proc_stat(stat, 100.0, &cpu));
  CHECK_NEAR(cpu, 3.0, 1e-12);
  CHECK(!parse_proc_stat("123 no parens", 100.0, &cpu));
  CHECK(parse_proc_rss("Name:\tx\nVmRSS:\t   2048 kB\nThreads: 3\n", &rss));
  CHECK_NEAR(rss, 2048.0 * 1024.0, 1e-9);
  CHECK(!parse_proc_rss("Name:\tx\n", &rss));
  std::string dev =
      "Inter-|   Receive |  Transmit\n face |bytes packets errs drop fifo frame compressed multicast|bytes ...\n"
      "    lo: 900 9 0 0 0 0 0 0 800 8 0 0 0 0 0 0\n  eth0: 1 2 0 0 0 0 0 0 3 4 0 0 0 0 0 0\n";
  uint64_t bytes = 0, packets = 0;
  CHECK(parse_net_dev(dev, "lo", &bytes, &packets));
  CHECK_EQ(bytes, 800u);
  CHECK_EQ(packets, 8u);
  CHECK(parse_net_dev(dev, "eth0", &bytes, &packets));
  CHECK_EQ(bytes, 3u);
  CHECK(!parse_net_dev(dev, "wlan0", &bytes, &packets));
}

// Each match's two bots begin together, within the stagger of the start,
// the same whichever process plays the match; the matches spread over it.
TEST(a_loads_matches_begin_staggered_alike_however_split) {
  std::vector<double> all = bot_starts(0, 100, 7, 1.0, 50.0);
  CHECK_EQ(all.size(), 200u);
  double lo = 1e300, hi = -1e300;
  for (size_t i = 0; i < all.size(); i += 2) {
    CHECK_EQ(all[i], all[i + 1]);
    CHECK(all[i] >= 50.0 && all[i] < 51.0);
    lo = std::min(lo, all[i]);
    hi = std::max(hi, all[i]);
  }
  CHECK(hi - lo > 0.9);  // 100 draws in 1 s: spread over it
  std::vector<double> part = bot_starts(60, 40, 7, 1.0, 50.0);
  for (size_t i = 0; i < part.size(); ++i) CHECK_EQ(part[i], all[120 + i]);
  for (double t : bot_starts(0, 5, 7, 0.0, 50.0)) CHECK_EQ(t, 50.0);  // none: all at once
  CHECK(bot_starts(0, 100, 8, 1.0, 50.0)[0] != all[0]);                 // another seed, other instants
}

TEST(parts_combine_counts_pool_latencies_and_take_the_server_once) {
  WireSizes s{100, 10, 1000, 10000, 100000, 1000000, 10000000};
  LoadPart a, b;
  a.row.matches = 3;
  a.row.bots = 6;
  a.row.ready = true;
  a.row.seconds = 2.0;
  a.row.samples_per_s = 180.0;
  a.latency = {0.010, 0.030};
  a.hit_to_wire = {0.001, 0.003};
  a.hit_to_write = {0.0005, 0.0025};  // its parts: the server's write, then the delivery
  a.delivery = {0.0005, 0.0005};
  a.counts.samples_written = 360;
  a.counts.segments = 8;  // the server's, as every process hears it
  a.frame_p50 = {0.001};
  b = a;
  b.row.matches = 1;
  b.row.bots = 2;
  b.row.samples_per_s = 60.0;
  b.row.ready = false;
  b.latency = {0.020};
  b.hit_to_wire = {0.002};
  b.hit_to_write = {-0.001};  // written ahead of the hit (hit_lead), received 3 ms after the write
  b.delivery = {0.003};
  b.counts.samples_written = 120;
  b.frame_p50 = {0.002, 0.004};  // heard more status periods: the server's figures come from b
  b.first.frames = 100;
  b.last.frames = 300;
  b.last.overruns = 3;
  b.first.server_time = 50.0;  // its statuses 2 s apart: 6 segments and 20 events written between them
  b.last.server_time = 52.0;
  b.first.segments_out = 10;
  b.last.segments_out = 16;
  b.first.events_out = 30;
  b.last.events_out = 50;
  b.counts.infos = 4;  // the MatchInfos it took (the server counts none in its status)
  LoadRow r = combine({a, b}, s);
  CHECK_EQ(r.matches, 4);
  CHECK_EQ(r.bots, 8);
  CHECK_EQ(r.bot_processes, 2);
  CHECK(!r.ready);
  CHECK_NEAR(r.samples_per_s, 240.0, 1e-12);
  CHECK_EQ(r.hits, 3u);
  CHECK_NEAR(r.latency_p50_ms, 20.0, 1e-9);
  CHECK_NEAR(r.hit_to_wire_p50_ms, 2.0, 1e-9);
  CHECK_NEAR(r.hit_to_write_p50_ms, 0.5, 1e-9);  // pooled over the processes: {-1, 0.5, 2.5} ms
  CHECK_NEAR(r.hit_to_write_p99_ms, 2.5, 1e-9);
  CHECK_NEAR(r.delivery_p50_ms, 0.5, 1e-9);
  CHECK_NEAR(r.delivery_p99_ms, 3.0, 1e-9);
  CHECK_EQ(r.server_frames, 200u);
  CHECK_NEAR(r.overrun_pct, 1.5, 1e-12);
  CHECK_NEAR(r.frame_p50_ms, 4.0, 1e-9);  // rank round(0.5 * 1) of {2, 4}
  // the server's own counts (not the 8 segments a process took: no events there), once, not per process
  CHECK_NEAR(r.server_bytes, (6.0 * 1000 + 20.0 * 10000) / 2.0 / 4 + 4.0 * 1000000 / (4 * 2.0), 1e-9);
  CHECK_NEAR(r.bots_bytes, 480.0 * 100 / (4 * 2.0), 1e-9);       // summed
}

TEST(rounds_summarize_to_min_and_lower_median_per_point) {
  std::vector<LoadRow> rows;
  double overruns[] = {0.5, 0.1, 0.3, 0.2};
  for (int i = 0; i < 4; ++i) {
    LoadRow r;
    r.matches = 100;
    r.state_rate = 0.0;
    r.overrun_pct = overruns[i];
    r.ready = i != 2;
    rows.push_back(r);
  }
  LoadRow other;
  other.matches = 100;
  other.state_rate = 60.0;
  other.overrun_pct = 9.0;
  rows.insert(rows.begin() + 1, other);
  auto points = summarize_points(rows);
  CHECK_EQ(points.size(), 2u);
  CHECK_EQ(points[0].rounds, 4);
  CHECK_NEAR(points[0].min.overrun_pct, 0.1, 1e-15);
  CHECK_NEAR(points[0].median.overrun_pct, 0.2, 1e-15);  // of 0.1 0.2 0.3 0.5, the lower middle
  CHECK(!points[0].median.ready);
  CHECK_EQ(points[1].rounds, 1);
  CHECK_NEAR(points[1].median.overrun_pct, 9.0, 1e-15);
  std::string table = load_table(points);
  CHECK(table.find("med") != std::string::npos && table.find("min") != std::string::npos);
  std::string data = load_plot_data(points);
  CHECK_EQ(std::count(data.begin(), data.end(), '\n'), 3);  // the comment and a line a point
}

CHECK_MAIN
