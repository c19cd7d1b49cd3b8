// The diagnoses (issue 29): the table and its device rules, each detector on
// its own, and every bundled capture through the real topdump: each
// diag-CODE capture shows exactly its diagnosis, in read, stats and report,
// and no warning or error diagnosis fires on any other bundled capture.
#include "top/diagnoses.hpp"

#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "diagnoses/placeholder_identity.hpp"
#include "diagnoses/watch.hpp"
#include "findings/afindings.hpp"
#include "test_support.hpp"
#include "test_time.hpp"
#include "top/catalog.hpp"
#include "top/decode.hpp"
#include "top/detail/decode_cache.hpp"
#include "top/detail/prefilter.hpp"
#include "top/frame.hpp"

namespace topdump {
namespace {

using test::captures_dir;
using test::run;
using test::slurp;
using test::topdump_bin;

// ---- the table ------------------------------------------------------------

TEST(DiagnosesTable, CodesAreStableDistinctAndDocumented) {
  const std::string doc = slurp(std::string(TOPKIT_SOURCE_DIR) + "/docs/DIAGNOSES.md");
  std::set<std::string_view> seen;
  for (std::size_t i = 0; i < top::diagnosis_count; ++i) {
    const auto d = static_cast<top::Diagnosis>(i);
    const std::string_view code = top::to_string(d);
    EXPECT_TRUE(seen.insert(code).second) << code;
    EXPECT_EQ(top::diagnosis_from_string(code), d);
    EXPECT_FALSE(top::title(d).empty()) << code;
    EXPECT_FALSE(top::evidence(d).empty()) << code;
    EXPECT_FALSE(top::remedy(d).empty()) << code;
    EXPECT_FALSE(top::finding_code_from_string(code)) << code << " is a frame finding's code";
    // the analyzer's code of the same name is this diagnosis
    const std::optional<ACode> a = acode_from_string(code);
    ASSERT_TRUE(a) << code;
    EXPECT_EQ(*a, acode_of(d));
    EXPECT_EQ(diagnosis_of(*a), d);
    EXPECT_EQ(default_severity(*a), top::severity(d));
    EXPECT_NE(doc.find("| `" + std::string(code) + "` |"), std::string::npos) << code;
  }
  EXPECT_FALSE(diagnosis_of(ACode::unanswered));
  EXPECT_EQ(top::diagnosis_from_string("unanswered"), std::nullopt);
}

// ---- the device rules -----------------------------------------------------

TEST(DiagnosesRules, PlaceholderIdentities) {
  for (const char* v :
       {"000000000", "0.0.0", "V0.0.0", "123", "1.2.3", "Unknown", "UNKNOWN", "", "   "})
    EXPECT_TRUE(top::is_placeholder_identity(v)) << v;
  for (const char* v : {"SIP-T1", "1.0.0", "SIM_TP", "M3326", "V1.0.0", "C13", "010502", "1230"})
    EXPECT_FALSE(top::is_placeholder_identity(v)) << v;
}

// SkyDroid MOD (the model name ArduPilot's driver reads) is an identity
// reply like VER: "Unknown" or zeros there are a placeholder (an outside
// capture's miss).
TEST(DiagnosesRules, SkyDroidModelNameIsAnIdentity) {
  EXPECT_TRUE(top::is_identity_reply(top::Dialect::skydroid, "MOD"));
  EXPECT_TRUE(top::is_identity_reply(top::Dialect::skydroid, "VER"));
  EXPECT_FALSE(top::is_identity_reply(top::Dialect::skydroid, "GAC"));
  for (const char* v : {"Unknown", "000000000"}) {
    diag::IdentityWatch w;
    w.reply(top::Dialect::skydroid, "MOD", v, 4, kT0, 1);
    const auto f = w.verdict();
    ASSERT_TRUE(f) << v;
    EXPECT_NE(f->figure.find("MOD"), std::string::npos) << f->figure;
  }
  diag::IdentityWatch ok;
  ok.reply(top::Dialect::skydroid, "MOD", "C13", 4, kT0, 1);
  EXPECT_FALSE(ok.verdict());
}

TEST(DiagnosesRules, TrackingRefusedIsState4Only) {
  EXPECT_TRUE(top::refuses_tracking(top::Dialect::topotek, "TRC", "04"));
  EXPECT_FALSE(top::refuses_tracking(top::Dialect::topotek, "TRC", "03"));  // temporarily lost
  EXPECT_FALSE(top::refuses_tracking(top::Dialect::topotek, "TRC", "02"));
  EXPECT_FALSE(top::refuses_tracking(top::Dialect::skydroid, "TRC", "04"));
}

// carries_date() names every identifier whose catalog form has a date.
TEST(DiagnosesRules, CarriesDateMatchesTheCatalog) {
  for (top::Dialect d : {top::Dialect::skydroid, top::Dialect::topotek})
    for (const top::CommandSpec& c : top::commands(d))
      for (const top::FormSpec& f : c.forms) {
        bool year = false;
        for (const top::FieldSpec& x : f.fields) year |= x.name == "year";
        if (year) {
          EXPECT_TRUE(top::carries_date(c.ident)) << c.ident;
        }
      }
}

// The session's prefilter (top/detail/prefilter.hpp) lets through every
// frame a detector's rule could take: the session's decode says so
// (top::detail::decode), with detail and without, from the shape cache too
// (topdump stats), for either sender.
TEST(DiagnosesRules, WatchPrefilterCoversTheRules) {
  top::detail::DecodeCache cache;
  std::size_t ruled_count = 0;
  for (top::Dialect d : {top::Dialect::skydroid, top::Dialect::topotek})
    for (const top::CommandSpec& c : top::commands(d)) {
      const std::string id(c.ident);
      const bool ruled = top::is_identity_reply(d, id) || top::carries_date(id) ||
                         top::refuses_tracking(d, id, "04") ||
                         top::reports_tracking(d, id, 'r', "02");
      EXPECT_EQ(top::detail::may_matter_to_diagnoses(id.c_str()), ruled) << id;
      ruled_count += ruled;
      for (top::Role role : {top::Role::request, top::Role::response}) {
        top::BuildSpec b;
        b.src = role == top::Role::request ? 'U' : c.address;
        b.dst = role == top::Role::request ? c.address : 'U';
        b.control = 'r';
        b.ident = c.ident;
        b.data = "00";
        const top::ParseResult r = top::parse_frame(top::build_frame(b), true);
        ASSERT_EQ(r.status, top::ParseStatus::frame) << id;
        for (const bool detail : {true, false}) {
          top::DecodeOptions o{d, top::Model::unknown, role};
          o.detail = detail;
          top::Decoded out;
          for (int pass = 0; pass < 2; ++pass)  // the second from the cache
            EXPECT_EQ(top::detail::decode(r.frame, o, &cache, out), ruled)
                << id << " pass " << pass;
        }
      }
    }
  EXPECT_GE(ruled_count, 7u);  // PA2, VSN, VER, MOD, TRC, TIM, UTC across the two
}

// ---- every bundled capture through topdump ---------------------------------

// The warning and error diagnoses `topdump read --json` reports, by code,
// with the exit status.
struct Seen {
  std::map<std::string, nlohmann::json> diagnoses;
  int status = 0;
};

Seen read_json(const std::string& file, const std::string& extra = "") {
  std::string out;
  Seen s;
  s.status = run("cd '" + captures_dir() + "' && '" + topdump_bin() + "' read --json " + extra +
                     " '" + file + "' 2>/dev/null",
                 out);
  std::istringstream in(out);
  std::string line;
  while (std::getline(in, line)) {
    const auto j = nlohmann::json::parse(line);
    if (j["type"] != "finding") continue;
    const std::string code = j["code"];
    if (top::diagnosis_from_string(code) && j["severity"] != "info") s.diagnoses[code] = j;
  }
  return s;
}

// Each diag-CODE capture: exactly its diagnosis, with its case.
TEST(DiagnosesCaptures, EachFiresOnItsCapture) {
  const std::map<std::string, std::string> made = {
      {"diag-stream-stalled.pcap", "stream-stalled"},
      {"diag-stream-never-started.pcap", "stream-never-started"},
      {"diag-placeholder-identity.pcap", "placeholder-identity"},
      {"diag-tracking-refused.pcap", "tracking-refused"},
      {"diag-clock-offset.pcap", "clock-offset"},
      {"diag-reply-interface.pcap", "reply-interface"},
      {"diag-silent-device.pcap", "silent-device"},
      {"diag-dropped-bad-checksum.log", "dropped-bad-checksum"},
      {"diag-dropped-checksum-case.log", "dropped-checksum-case"},
      {"diag-baud-mismatch.bin", "baud-mismatch"},
      {"diag-direction-inverted.pcap", "direction-inverted"},
      {"diag-command-ignored.log", "command-ignored"},
      {"diag-attitude-stale.pcap", "attitude-stale"},
      {"diag-axis-left-moving.log", "axis-left-moving"},
      {"diag-stream-rate.pcap", "stream-rate"},
      {"diag-refresh-gap.pcap", "refresh-gap"},
  };
  for (const auto& [file, code] : made) {
    const Seen s = read_json(file);
    ASSERT_EQ(s.diagnoses.size(), 1u) << file;
    ASSERT_TRUE(s.diagnoses.count(code)) << file << ": " << s.diagnoses.begin()->first;
    const auto& j = s.diagnoses.at(code);
    EXPECT_EQ(s.status, 1) << file;
    EXPECT_GE(j["count"].get<int>(), 1) << file;
    EXPECT_FALSE(j["evidence"].get<std::string>().empty()) << file;
    EXPECT_FALSE(j["remedy"].get<std::string>().empty()) << file;
    if (code != "baud-mismatch") {
      EXPECT_TRUE(j["frame"].is_number()) << file;
      EXPECT_TRUE(j["conversation"].is_number()) << file;
    }
    // --mute CODE takes it out, and with it the exit status it caused
    const Seen muted = read_json(file, "--mute " + code);
    EXPECT_EQ(muted.diagnoses.count(code), 0u) << file;
  }
}

// The figures the issue asks for, measured.
// The finding selection applies to diagnoses: identifier and time.
TEST(DiagnosesCaptures, SelectedByIdentAndTime) {
  EXPECT_EQ(read_json("diag-tracking-refused.pcap", "--ident TRC").diagnoses.size(), 1u);
  const Seen other = read_json("diag-tracking-refused.pcap", "--ident VSN");
  EXPECT_TRUE(other.diagnoses.empty());
  EXPECT_EQ(other.status, 0);
  // the stall began at 12:00:03
  EXPECT_EQ(read_json("diag-stream-stalled.pcap", "--to 2024-05-01T12:00:02Z").diagnoses.size(),
            0u);
  EXPECT_EQ(read_json("diag-stream-stalled.pcap", "--from 2024-05-01T12:00:02Z").diagnoses.size(),
            1u);
}

TEST(DiagnosesCaptures, CarryTheirMeasuredFigure) {
  struct Figure {
    const char* file;
    const char* code;
    const char* text;  // in its message
  };
  const Figure figures[] = {
      {"diag-clock-offset.pcap", "clock-offset",
       "camera time 2024-04-01 20:00:00, capture 2024-05-01 12:00:00: exactly one month early"},
      {"diag-placeholder-identity.pcap", "placeholder-identity", "\"000000000\""},
      {"diag-stream-stalled.pcap", "stream-stalled", "longest 2.100 s"},
      {"diag-reply-interface.pcap", "reply-interface", "5 requests"},
      // the motion diagnoses: commanded against measured
      {"diag-direction-inverted.pcap", "direction-inverted",
       "GSP 20 (10.0 deg/s up): pitch moved -9.5 deg/s (down)"},
      {"diag-command-ignored.log", "command-ignored",
       "GAY to +30.0 deg was acknowledged; yaw stayed at +0.0 deg"},
      {"diag-attitude-stale.pcap", "attitude-stale", "20 non-zero motion commands"},
      {"diag-axis-left-moving.log", "axis-left-moving",
       "yaw moved +49.0 deg in the 4.850 s to the end"},
  };
  for (const Figure& f : figures) {
    const Seen s = read_json(f.file);
    if (!s.diagnoses.count(f.code)) {  // the next captures are checked still
      ADD_FAILURE() << f.file << ": no " << f.code;
      continue;
    }
    const std::string message = s.diagnoses.at(f.code)["message"].get<std::string>();
    EXPECT_NE(message.find(f.text), std::string::npos) << f.file << ": " << message;
  }
}

// A motion diagnosis names its axis (the JSON's `axis`), and none where a
// diagnosis has no axis.
TEST(DiagnosesCaptures, MotionDiagnosesNameTheirAxis) {
  auto axis = [](const char* file, const char* code) {
    const Seen s = read_json(file);
    return s.diagnoses.count(code) ? s.diagnoses.at(code)["axis"] : nlohmann::json("missing");
  };
  EXPECT_EQ(axis("diag-direction-inverted.pcap", "direction-inverted"), "pitch");
  EXPECT_EQ(axis("diag-command-ignored.log", "command-ignored"), "yaw");
  EXPECT_EQ(axis("diag-axis-left-moving.log", "axis-left-moving"), "yaw");
  EXPECT_TRUE(axis("diag-attitude-stale.pcap", "attitude-stale").is_null());
}

// No warning or error diagnosis on any other bundled capture, except the
// ones they were made to show before diagnoses existed (sample.pcap's
// dropped bad-checksum GAY; ipv6.pcap's and the socat logs' stream-rate).
TEST(DiagnosesCaptures, SilentOnEveryOtherCapture) {
  const std::map<std::string, std::set<std::string>> known = {
      {"sample.pcap", {"dropped-bad-checksum"}},
      {"ipv6.pcap", {"stream-rate"}},
      {"serial-socat-v.log", {"stream-rate"}},
      {"serial-socat-xv.log", {"stream-rate"}},
  };
  std::string listing;
  run("cd '" + captures_dir() + "' && ls *.pcap *.pcapng *.bin *.log *.csv", listing);
  std::istringstream in(listing);
  std::string file;
  int checked = 0;
  while (std::getline(in, file)) {
    if (file.rfind("diag-", 0) == 0 && file.rfind("diag-healthy-", 0) != 0) continue;
    const Seen s = read_json(file);
    std::set<std::string> codes;
    for (const auto& [c, j] : s.diagnoses) codes.insert(c);
    const auto k = known.find(file);
    EXPECT_EQ(codes, k == known.end() ? std::set<std::string>{} : k->second) << file;
    ++checked;
  }
  EXPECT_GE(checked, 19);
}

TEST(DiagnosesCaptures, CountedByStatsAndItemsOfTheReport) {
  std::string out;
  run("cd '" + captures_dir() + "' && '" + topdump_bin() +
          "' stats --json diag-tracking-refused.pcap",
      out);
  const auto st = nlohmann::json::parse(out);
  EXPECT_EQ(st["per_finding"]["tracking-refused"], 1) << out;
  run("cd '" + captures_dir() + "' && '" + topdump_bin() + "' stats diag-stream-stalled.pcap", out);
  EXPECT_NE(out.find("stream-stalled 1"), std::string::npos) << out;

  const int rc = run("cd '" + captures_dir() + "' && '" + topdump_bin() +
                         "' report --json -o - diag-stream-stalled.pcap",
                     out);
  EXPECT_EQ(rc, 1);
  const auto r = nlohmann::json::parse(out);
  int stalled = 0, gaps = 0;
  for (const auto& w : r["overview"]["what_went_wrong"]) {
    if (w["code"] == "stream-stalled") {
      ++stalled;
      EXPECT_EQ(w["frame"], 37);  // the last push before the stall (43 resumed it)
      EXPECT_EQ(w["evidence"], std::string(top::evidence(top::Diagnosis::stream_stalled)));
      EXPECT_EQ(w["remedy"], std::string(top::remedy(top::Diagnosis::stream_stalled)));
    }
    // one cause, one item: no stream-rate for the stall, no second gap item
    EXPECT_NE(w["code"], "stream-rate") << w;
    gaps += w["text"].get<std::string>().find("push stopped") != std::string::npos;
  }
  EXPECT_EQ(stalled, 1) << out;
  EXPECT_EQ(gaps, 1) << out;
}

}  // namespace
}  // namespace topdump
