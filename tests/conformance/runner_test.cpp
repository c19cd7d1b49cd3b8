// topconf's runner against an in-process topsim (virtual clock): the
// default matrices pass, every fault breaks what it must with the right
// class, and a silent or flooding device cannot hang it.
#include "conf/runner.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <map>
#include <sstream>

#include "conf/liveness.hpp"
#include "conf/report.hpp"
#include "run_test_util.hpp"
#include "test_matrix_util.hpp"

namespace {

using topconf::ExpectKind;
using topconf::RunResult;
using topconf::Verdict;

// Results point into their matrix: keep every matrix alive for the run.
const topconf::Matrix& matrix_of(top::Model m) {
  static std::map<top::Model, topconf::Matrix> cache;
  auto it = cache.find(m);
  if (it == cache.end()) it = cache.emplace(m, default_matrix(m)).first;
  return it->second;
}

RunResult run(top::Model m, std::string_view faults = {}, std::uint32_t retries = 0,
              topsim::Link link = topsim::Link::network, std::uint64_t seed = 1,
              top::Profile profile = top::Profile::field) {
  const topconf::Matrix& mx = matrix_of(m);
  std::string err;
  auto fc = topsim::parse_faults(faults, err);
  EXPECT_TRUE(fc) << err;
  topconf::SimTransport t(m, *fc, seed, link, profile);
  topconf::RunOptions o;
  o.retries = retries;
  return topconf::run_matrix(mx, t, o);
}

// What a case expects of the device.
bool expects_only_silence(const topconf::Case& c) {
  for (const auto& s : c.steps)
    for (const auto& e : s.expect)
      if (e.kind != ExpectKind::silence) return false;
  return true;
}
bool expects_a_frame_first(const topconf::Case& c) {
  return !c.steps.empty() && c.steps[0].expect[0].kind != ExpectKind::silence;
}
bool tolerates_silence(const topconf::Case& c) {
  for (const auto& s : c.steps)
    for (const auto& e : s.expect)
      if (e.kind == ExpectKind::silence && e.tolerated) return true;
  return false;
}

class Models : public ::testing::TestWithParam<top::Model> {};

TEST_P(Models, DefaultMatrixPassesInProcess) {
  for (auto link : {topsim::Link::network, topsim::Link::uart}) {
    RunResult r = run(GetParam(), {}, 0, link);
    EXPECT_EQ(r.exit_code(), 0);
    EXPECT_FALSE(r.cases.empty());
    for (const auto& c : r.cases) {
      // A form the field records (docs/FIELD.md) passes as non-strict with
      // its evidence in the reason; anything else must be a plain pass.
      if (c.field_form) {
        EXPECT_EQ(c.verdict, Verdict::non_strict) << c.spec->id;
        EXPECT_NE(c.reason.find("the field's form"), std::string::npos) << c.reason;
        continue;
      }
      EXPECT_EQ(c.verdict, Verdict::pass) << c.spec->id << ": " << c.reason;
    }
  }
}

TEST_P(Models, DefaultMatrixPassesInProcessUnderTheDocumentProfile) {
  for (auto link : {topsim::Link::network, topsim::Link::uart}) {
    RunResult r = run(GetParam(), {}, 0, link, 1, top::Profile::document);
    EXPECT_EQ(r.exit_code(), 0);
    for (const auto& c : r.cases)
      EXPECT_EQ(c.verdict, Verdict::pass) << c.spec->id << ": " << c.reason;
  }
}

INSTANTIATE_TEST_SUITE_P(All, Models, ::testing::ValuesIn(top::all_models()),
                         [](const auto& i) { return std::string(top::to_string(i.param)); });

// ---- faults: each must break exactly what it should, with the right class.

TEST(Faults, DropAllMakesTheTargetUnreachable) {
  RunResult r = run(top::Model::c12, "drop=1");
  EXPECT_TRUE(r.unreachable);
  EXPECT_EQ(r.exit_code(), 2);
}

TEST(Faults, DropSomeFailsCasesAndRetriesMakeThemFlaky) {
  RunResult r = run(top::Model::c12, "drop=0.1", 0);
  EXPECT_GT(r.count(Verdict::fail), 0u);
  EXPECT_EQ(r.exit_code(), 1);
  for (const auto& c : r.cases) {
    if (expects_only_silence(*c.spec)) {
      EXPECT_EQ(c.verdict, Verdict::pass) << c.spec->id << ": " << c.reason;
    }
  }
  RunResult again = run(top::Model::c12, "drop=0.1", 4);
  std::size_t flaky = 0;
  for (const auto& c : again.cases) flaky += c.flaky ? 1 : 0;
  EXPECT_GT(flaky, 0u);
  EXPECT_LT(again.count(Verdict::fail), r.count(Verdict::fail));
}

TEST(Faults, DelayBeyondTheTimeoutFailsEveryAnswer) {
  RunResult r = run(top::Model::c12, "delay=400");
  ASSERT_FALSE(r.unreachable);
  for (const auto& c : r.cases) {
    // The probe reads AWB: a late AWB answer can be taken for the probe's
    // and the probe's for the next AWB case. A late reply is ambiguous on
    // any link; the README says so. Those cases are left out here.
    if (c.spec->id.find("/AWB/") != std::string::npos) continue;
    if (expects_only_silence(*c.spec)) {
      EXPECT_EQ(c.verdict, Verdict::pass) << c.spec->id;
    } else if (tolerates_silence(*c.spec)) {
      // ERE expected, nothing within the timeout: the tolerated silence.
      EXPECT_EQ(c.verdict, Verdict::non_strict) << c.spec->id << ": " << c.reason;
    } else if (expects_a_frame_first(*c.spec)) {
      EXPECT_EQ(c.verdict, Verdict::fail) << c.spec->id << ": " << c.reason;
    }
  }
  // A delay inside the timeout is no deviation.
  EXPECT_EQ(run(top::Model::c12, "delay=100").exit_code(), 0);
}

TEST(Faults, BadChecksumAndHeaderCaseFailEveryAnswer) {
  for (const char* f : {"bad-checksum=1", "header-case=1"}) {
    RunResult r = run(top::Model::c12, f);
    ASSERT_FALSE(r.unreachable) << f;
    for (const auto& c : r.cases) {
      if (expects_only_silence(*c.spec)) {
        EXPECT_EQ(c.verdict, Verdict::pass) << f << " " << c.spec->id;
      } else if (expects_a_frame_first(*c.spec)) {
        EXPECT_EQ(c.verdict, Verdict::fail) << f << " " << c.spec->id;
      }
    }
  }
}

TEST(Faults, DuplicateRepliesAreNonStrictAndBreakTheStreamRate) {
  RunResult r = run(top::Model::c12, "duplicate=1");
  EXPECT_EQ(find_case(r, "skydroid/3.3.1/GAY/write").verdict, Verdict::non_strict);
  EXPECT_NE(find_case(r, "skydroid/3.3.1/GAY/write").reason.find("more than once"),
            std::string::npos);
  EXPECT_EQ(find_case(r, "skydroid/4.11/VER/read").verdict, Verdict::non_strict);
  EXPECT_EQ(find_case(r, "skydroid/3.3.2.1/GAA/stream").verdict, Verdict::fail);
  EXPECT_EQ(r.exit_code(), 1);
}

TEST(Faults, NoSwapMatchesOnlyTheToleratedAlternatives) {
  RunResult r = run(top::Model::c12, "no-swap");
  EXPECT_EQ(find_case(r, "skydroid/3.3.1/GAY/write").verdict, Verdict::non_strict);
  EXPECT_EQ(find_case(r, "skydroid/4.11/VER/read").verdict, Verdict::non_strict);
  EXPECT_EQ(find_case(r, "skydroid/frame/unknown-ident").verdict, Verdict::non_strict);
  EXPECT_EQ(find_case(r, "skydroid/4.9.1/IPV/state").verdict, Verdict::non_strict);
  EXPECT_EQ(find_case(r, "skydroid/2.3.2/ERE/example").verdict, Verdict::fail);
  EXPECT_EQ(r.count(Verdict::pass) + r.count(Verdict::non_strict) + r.count(Verdict::fail),
            r.cases.size());
}

TEST(Faults, LyingLengthIsRecoveredAsNonStrict) {
  RunResult r = run(top::Model::c12, "lying-length=1");
  const auto& ver = find_case(r, "skydroid/4.11/VER/read");
  EXPECT_EQ(ver.verdict, Verdict::non_strict);
  EXPECT_NE(ver.reason.find("length-mismatch"), std::string::npos) << ver.reason;
  EXPECT_EQ(find_case(r, "skydroid/3.3.1/GAY/write").verdict, Verdict::non_strict);
}

TEST(Faults, TmpQuirkAffectsOnlyTmp) {
  RunResult r = run(top::Model::c12, "tmp-quirk");
  const auto& tmp = find_case(r, "skydroid/appendix-I/TMP/read");
  EXPECT_EQ(tmp.verdict, Verdict::non_strict);
  EXPECT_NE(tmp.reason.find("tmp-quirk"), std::string::npos) << tmp.reason;
  for (const auto& c : r.cases) {
    // A form the field records (the C12 palette's byte-counting length)
    // passes as non-strict, as in DefaultMatrixPassesInProcess.
    if (c.spec->id != tmp.spec->id && !c.field_form) {
      EXPECT_EQ(c.verdict, Verdict::pass) << c.spec->id;
    }
  }
}

TEST(Faults, SplitFramesAreReassembled) {
  RunResult r = run(top::Model::c12, "split", 0, topsim::Link::uart);
  EXPECT_EQ(r.exit_code(), 0);
  for (const auto& c : r.cases)
    EXPECT_EQ(c.verdict, c.field_form ? Verdict::non_strict : Verdict::pass)
        << c.spec->id << ": " << c.reason;
}

TEST(Faults, GarbageBeforeFramesIsNonStrict) {
  RunResult r = run(top::Model::c12, "garbage=1");
  const auto& gay = find_case(r, "skydroid/3.3.1/GAY/write");
  EXPECT_EQ(gay.verdict, Verdict::non_strict);
  EXPECT_NE(gay.reason.find("garbage"), std::string::npos);
}

TEST(Faults, HangOnFailsThatCaseAndErrorsTheRest) {
  RunResult r = run(top::Model::c12, "hang-on=GAY");
  bool seen = false;
  for (const auto& c : r.cases) {
    if (c.spec->id == "skydroid/3.3.1/GAY/write") {
      EXPECT_EQ(c.verdict, Verdict::fail);
      seen = true;
    } else if (seen) {
      EXPECT_EQ(c.verdict, Verdict::error) << c.spec->id;
      EXPECT_NE(c.reason.find("stopped answering after case skydroid/3.3.1/GAY/write"),
                std::string::npos);
    } else {
      EXPECT_EQ(c.verdict, Verdict::pass) << c.spec->id;
    }
  }
  EXPECT_TRUE(seen);
  EXPECT_EQ(r.exit_code(), 1);
}

// ---- the liveness probe: the catalog's probes (top/probe.hpp), tried in
// order (conf/liveness.hpp)

std::string probe_list(top::Model m) {
  std::string s;
  for (const top::LivenessProbe& p : top::liveness_probes(m))
    s += (s.empty() ? "" : " ") + std::string(p.ident) + p.control + ">" + std::string(p.answer);
  return s;
}

TEST(Liveness, TheProbesOfEachModelComeFromTheCatalog) {
  // a read first; then the attitude stream's switch, answered by its push
  EXPECT_EQ(probe_list(top::Model::sip), "VERr>VER GIAw>GIA");
  EXPECT_EQ(probe_list(top::Model::c12), "AWBr>AWB VERr>VER GAAw>GAC");
  EXPECT_EQ(probe_list(top::Model::c13), "AWBr>AWB");  // the catalog gives it neither VER nor GAA
  EXPECT_TRUE(top::liveness_probes(top::Model::unknown).empty());
  for (top::Model m : top::all_models()) {
    const auto probes = top::liveness_probes(m);
    ASSERT_FALSE(probes.empty()) << top::to_string(m);
    EXPECT_EQ(probes.front().control, 'r') << top::to_string(m);
    for (const auto& p : probes) {
      const top::CommandSpec* c = top::find_command(top::dialect_of(m), p.ident);
      ASSERT_NE(c, nullptr) << p.ident;
      EXPECT_TRUE(c->supports(m) && c->has_control(p.control)) << p.ident;
      EXPECT_EQ(p.address, c->address) << p.ident;  // AWB to D, Topotek VER to G
      EXPECT_FALSE(p.evidence.empty()) << p.ident;
    }
  }
  // Topotek GIA switches GIC (the document) and GIA frames (the field) on.
  const top::LivenessProbe gia = top::liveness_probes(top::Model::sip).at(1);
  EXPECT_TRUE(gia.switches_push(top::Dialect::topotek, "GIC"));
  EXPECT_TRUE(gia.switches_push(top::Dialect::topotek, "GIA"));
  EXPECT_FALSE(gia.switches_push(top::Dialect::topotek, "GAC"));
}

TEST(Liveness, ChoiceTellsUnansweredFromUnreachable) {
  std::vector<topconf::Probe> probes(2);
  probes[0].ident = "VER";
  probes[1].ident = "GIA";
  auto script = [](std::vector<topconf::ProbeHeard> heard) {
    return [heard, i = std::size_t{0}](const topconf::Probe&) mutable {
      return i < heard.size() ? heard[i++] : topconf::ProbeHeard::nothing;
    };
  };
  using H = topconf::ProbeHeard;
  auto none = topconf::choose_probe(probes, 3, script({}));
  EXPECT_FALSE(none.probe);
  EXPECT_FALSE(none.heard);
  auto second =
      topconf::choose_probe(probes, 3, script({H::other, H::nothing, H::other, H::answer}));
  ASSERT_TRUE(second.probe);
  EXPECT_EQ(second.probe->ident, "GIA");
  EXPECT_TRUE(second.heard);
  EXPECT_EQ(second.note(), "probe unanswered: VER");
  auto other = topconf::choose_probe(probes, 2, script({H::other}));
  EXPECT_FALSE(other.probe);
  EXPECT_TRUE(other.heard);
  EXPECT_EQ(other.note(), "probe unanswered: VER, GIA");
  EXPECT_EQ(topconf::choose_probe(probes, 1, script({H::answer})).note(), "");
}

// A device that does not answer the first probes (ArduPilot's simulators
// answer neither VER nor AWB) is reached by the next one, and liveness holds
// between cases; one that answers none of them sends nothing: unreachable.
TEST(Liveness, ADeviceThatIgnoresAProbeIsReachedByTheNext) {
  RunResult sip = run(top::Model::sip, "ignore=VER");
  EXPECT_FALSE(sip.unreachable) << sip.unreachable_reason;
  EXPECT_EQ(sip.probe_note, "probe unanswered: VER");
  EXPECT_EQ(sip.count(Verdict::error), 0u);
  RunResult c12 = run(top::Model::c12, "ignore=AWB+VER");
  EXPECT_FALSE(c12.unreachable) << c12.unreachable_reason;
  EXPECT_EQ(c12.probe_note, "probe unanswered: AWB, VER");
  EXPECT_EQ(c12.count(Verdict::error), 0u);
  RunResult all = run(top::Model::c12, "ignore=AWB+VER+GAA");
  EXPECT_TRUE(all.unreachable);
  EXPECT_NE(all.unreachable_reason.find("no frame came back to the liveness probe AWB, VER, GAA"),
            std::string::npos)
      << all.unreachable_reason;
  EXPECT_EQ(run(top::Model::c12).probe_note, "");
}

// ---- filters, order, classes that need a matrix of their own

TEST(Runner, FiltersAndSeededOrder) {
  const topconf::Matrix& mx = matrix_of(top::Model::c12);
  topconf::SimTransport t(top::Model::c12);
  topconf::RunOptions o;
  o.cases = {"skydroid/3.3.1/*"};
  auto r = topconf::run_matrix(mx, t, o);
  ASSERT_FALSE(r.cases.empty());
  for (const auto& c : r.cases) EXPECT_EQ(c.spec->id.rfind("skydroid/3.3.1/", 0), 0u);
  o.cases.clear();
  o.tags = {"stream"};
  EXPECT_EQ(topconf::run_matrix(mx, t, o).cases.size(), 1u);
  o.tags.clear();
  o.levels = {topconf::Level::may};
  for (const auto& c : topconf::run_matrix(mx, t, o).cases)
    EXPECT_EQ(c.spec->level, topconf::Level::may);
  o.levels.clear();
  auto order = [&](std::uint64_t seed) {
    topconf::RunOptions so;
    so.seed = seed;
    std::vector<std::string> ids;
    for (const auto& c : topconf::run_matrix(mx, t, so).cases) ids.push_back(c.spec->id);
    return ids;
  };
  EXPECT_EQ(order(5), order(5));
  EXPECT_NE(order(5), order(6));
}

const char* kSmall = R"({
  "format": "topconf-matrix-1", "model": "c12",
  "defaults": {"timeout_ms": 50, "retries": 0, "probe_timeout_ms": 50},
  "probe": {"command": "AWB", "control": "r", "data": "00"},
  "cases": [
    {"id": "na", "section": "SkyDroid 3.3.5", "level": "must", "models": ["c13"],
     "steps": [{"send": {"command": "GOT", "data": "02800168"}, "expect": [{"echo": true}]}]},
    {"id": "pre", "section": "SkyDroid 4.1", "level": "must",
     "preconditions": [{"send": {"command": "ZZZ", "control": "r", "data": "00", "dst": "D"},
                        "expect": [{"echo": true}]}],
     "steps": [{"send": {"command": "REC", "data": "01"}, "expect": [{"echo": true}]}]},
    {"id": "fields", "section": "SkyDroid 4.4", "level": "must",
     "steps": [{"send": {"command": "SDC", "control": "r", "data": "00"},
                "expect": [{"reply": {"control": "r", "fields": {"free": {"min": 70000}}}}]}]},
    {"id": "fields-ok", "section": "SkyDroid 4.4", "level": "must",
     "steps": [{"send": {"command": "SDC", "control": "r", "data": "00"},
                "expect": [{"reply": {"control": "r", "fields": {"free": {"min": 1, "max": 70000},
                            "total": {"pattern": "1D4C0"}}}}]}]},
    {"id": "may-fail", "section": "SkyDroid 4.11", "level": "may",
     "steps": [{"send": {"command": "VER", "control": "r", "data": "00"},
                "expect": [{"reply": {"data_pattern": "V9.*"}}]}]}
  ]})";

TEST(Runner, ClassesNotApplicableInconclusiveFailAndMay) {
  auto loaded = topconf::load_matrix(kSmall, "small.json");
  ASSERT_TRUE(loaded.matrix) << loaded.errors.at(0);
  topconf::SimTransport t(top::Model::c12);
  auto r = topconf::run_matrix(*loaded.matrix, t, {});
  EXPECT_EQ(find_case(r, "na").verdict, Verdict::not_applicable);
  EXPECT_EQ(find_case(r, "pre").verdict, Verdict::inconclusive);
  EXPECT_EQ(find_case(r, "fields").verdict, Verdict::fail);
  EXPECT_NE(find_case(r, "fields").reason.find("out of range"), std::string::npos);
  EXPECT_EQ(find_case(r, "fields-ok").verdict, Verdict::pass);
  EXPECT_EQ(find_case(r, "may-fail").verdict, Verdict::fail);
  EXPECT_EQ(r.exit_code(), 1);  // inconclusive and fail at must
  // Outputs carry every case and its transcript.
  auto j = topconf::to_json(r);
  EXPECT_EQ(j["cases"].size(), 5u);
  EXPECT_EQ(j["cases"][2]["transcript"][0]["dir"], "sent");
  EXPECT_EQ(j["cases"][2]["transcript"][0]["bytes"], "#TPUD2rSDC003E") << j["cases"][2].dump();
  std::ostringstream junit, html, console;
  topconf::write_junit(junit, r);
  topconf::write_html(html, r);
  topconf::write_console(console, r, false);
  EXPECT_NE(junit.str().find("<testcase classname=\"SkyDroid 4.4\" name=\"fields\""),
            std::string::npos);
  EXPECT_NE(junit.str().find("<failure message=\"fail: "), std::string::npos);
  EXPECT_NE(junit.str().find("<skipped message=\"n/a: "), std::string::npos);
  EXPECT_NE(html.str().find("<details><summary>transcript"), std::string::npos);
  EXPECT_EQ(html.str().find("<script"), std::string::npos);  // self-contained, static
  EXPECT_NE(console.str().find("1 pass, 0 non-strict, 2 fail, 1 n/a, 1 inconclusive"),
            std::string::npos)
      << console.str();
}

// ---- a silent device and a flooding device

class FakeTransport : public topconf::Transport {
 public:
  explicit FakeTransport(bool flood) : flood_(flood) {}
  std::uint64_t now_us() override {
    return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::microseconds>(
                                          std::chrono::steady_clock::now().time_since_epoch())
                                          .count());
  }
  bool datagram() const override { return false; }
  char client_address() const override { return 'U'; }
  void send(std::string_view) override { ++sent; }
  bool receive(std::uint64_t deadline, std::string& out) override {
    if (!flood_) {
      while (now_us() < deadline) {
      }
      return false;
    }
    ++chunks;
    // Frames, garbage and a stream that never ends.
    out = (chunks % 3 == 0) ? std::string(600, '\xAA') : "#TPDU2rAWB003E#TPGUCrGAC00000000000023";
    return true;
  }
  std::string describe() const override { return flood_ ? "flood" : "silent"; }
  std::uint64_t sent = 0, chunks = 0;

 private:
  bool flood_;
};

TEST(Runner, NeverHangsOnASilentDevice) {
  auto loaded = topconf::load_matrix(kSmall, "small.json");
  FakeTransport t(false);
  const auto t0 = std::chrono::steady_clock::now();
  auto r = topconf::run_matrix(*loaded.matrix, t, {});
  EXPECT_TRUE(r.unreachable);
  EXPECT_EQ(r.exit_code(), 2);
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(5));
}

TEST(Runner, NeverHangsOnAFloodingDeviceAndMemoryStaysBounded) {
  auto loaded = topconf::load_matrix(kSmall, "small.json");
  FakeTransport t(true);
  topconf::RunOptions o;
  o.max_transcript = 100;
  const auto t0 = std::chrono::steady_clock::now();
  auto r = topconf::run_matrix(*loaded.matrix, t, o);
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(10));
  EXPECT_FALSE(r.unreachable);
  bool dropped = false;
  for (const auto& c : r.cases) {
    EXPECT_LE(c.transcript.size(), 100u);
    dropped = dropped || c.dropped_exchanges > 0;
    for (const auto& e : c.transcript) EXPECT_LE(e.bytes.size(), 515u);
  }
  EXPECT_TRUE(dropped);
  EXPECT_GT(t.chunks, 1000u);
}

}  // namespace

// Reports show bytes as topdump does: one escape for the same byte in every
// tool (CR was \x0D here and \r in topdump).
TEST(Report, ShowsBytesAsTopdumpDoes) {
  EXPECT_EQ(topconf::printable("#TPUG2wPTZ05\r\n"), "#TPUG2wPTZ05\\r\\n");
  EXPECT_EQ(topconf::printable(std::string("a\\b\x01\xff", 5)), "a\\\\b\\x01\\xFF");
  const std::string all = [] {
    std::string s;
    for (int c = 0; c < 256; ++c) s += static_cast<char>(c);
    return s;
  }();
  EXPECT_EQ(topconf::printable(all), top::escape(all));
}
