// The one JSON writer (analyzer/output/include/output/json_writer.hpp) against nlohmann: the
// numbers and strings it writes, and the documents whose format is
// nlohmann's dump() (stats --json, frame --json), byte by byte.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>
#include <set>

#include "json_reference.hpp"
#include "output/escape.hpp"
#include "output/json_writer.hpp"
#include "test_support.hpp"
#include "test_time.hpp"
#include "top/frame.hpp"

namespace topdump::test {
namespace {

std::string written(double v) {
  std::string s;
  jsonw::put_double(s, v);
  return s;
}

TEST(JsonWriter, DoublesAsNlohmannWritesThem) {
  std::vector<double> values = {0.0,
                                -0.0,
                                1.0,
                                -1.0,
                                0.5,
                                12.5,
                                100.0,
                                1e-3,
                                1e-4,
                                1e-5,
                                1.5e-5,
                                1e15,
                                1e16,
                                1.25e16,
                                1e21,
                                1e100,
                                1e-100,
                                2.5e-300,
                                0.1,
                                0.2,
                                1.0 / 3,
                                123456789012345.6,
                                999999999999999.9,
                                1714564800.123456,
                                -2.95,
                                1e308,
                                5e-324,
                                std::nan(""),
                                HUGE_VAL,
                                -HUGE_VAL};
  std::mt19937_64 rng(17);
  for (int i = 0; i < 20000; ++i) {
    // what topdump writes: microseconds as seconds, as milliseconds, rates
    const auto k = static_cast<std::int64_t>(rng() % 4'000'000'000'000'000ull);
    values.push_back(static_cast<double>(k) / 1e6);
    values.push_back(static_cast<double>(k % 100'000'000) / 1000.0);
    values.push_back(std::round(static_cast<double>(k % 1'000'000) / 7.0) / 100.0);
    // and any finite double
    double d;
    const std::uint64_t bits = rng();
    std::memcpy(&d, &bits, 8);
    if (std::isfinite(d)) values.push_back(d);
  }
  std::size_t same = 0;
  for (double v : values) {
    const std::string w = written(v), n = nlohmann::json(v).dump();
    if (!std::isfinite(v)) {
      EXPECT_EQ(w, "null");
      continue;
    }
    // the same double in nlohmann's layout, never more characters
    const double back = nlohmann::json::parse(w).get<double>();
    EXPECT_TRUE(back == v && std::signbit(back) == std::signbit(v)) << w;
    EXPECT_LE(w.size(), n.size()) << w << " " << n;
    EXPECT_EQ(w.find('e') == std::string::npos, n.find('e') == std::string::npos) << w << " " << n;
    same += w == n;
  }
  EXPECT_GT(same, values.size() * 9 / 10);
}

TEST(JsonWriter, DoublesOfFixedDecimalsAsNlohmannWritesThem) {
  // latencies (us / 1000) and rates rounded to 0.01: byte-identical to
  // nlohmann's text (times in seconds, us / 1e6, are not always: Grisu2 gives
  // 0.19323100000000001 where the shortest digits are 0.193231)
  for (std::int64_t k = -2000000; k <= 2000000; k += 7) {
    for (double v : {static_cast<double>(k) / 1000.0, static_cast<double>(k) / 100.0})
      EXPECT_EQ(written(v), nlohmann::json(v).dump()) << v;
  }
}

TEST(JsonWriter, StringsAsNlohmannWritesThem) {
  for (int c = 0; c < 0x80; ++c) {
    const std::string s = "a" + std::string(1, static_cast<char>(c)) + "bcdefghij";
    std::string w;
    jsonw::put_str(w, s);
    EXPECT_EQ(w, nlohmann::json(s).dump()) << c;
  }
}

TEST(JsonWriter, EmptyAndNestedContainersAsDumpLaysThemOut) {
  for (int indent : {-1, 2, 4}) {
    std::string out;
    jsonw::Doc d(out, indent);
    d.open_object();
    d.key("a");
    d.open_object();
    d.close_object();
    d.key("b");
    d.open_array();
    d.close_array();
    d.key("c");
    d.open_array();
    d.item();
    jsonw::put_u(out, 1);
    d.item();
    d.open_object();
    d.key("x");
    out += "null";
    d.close_object();
    d.close_array();
    d.close_object();
    nlohmann::ordered_json j;
    j["a"] = nlohmann::ordered_json::object();
    j["b"] = nlohmann::ordered_json::array();
    j["c"] = {1, {{"x", nullptr}}};
    EXPECT_EQ(out, j.dump(indent)) << indent;
  }
}

std::vector<std::string> bundled_captures() {
  std::vector<std::string> v;
  for (const auto& e : std::filesystem::directory_iterator(captures_dir())) {
    const auto x = e.path().extension();
    if (e.is_regular_file() && x != ".md" && x != ".sh" && x != ".cpp" && x != ".txt")
      v.push_back(e.path().string());
  }
  return v;
}

// stats --json and the last line of live --json, as nlohmann wrote them.
TEST(JsonWriter, StatsOfEveryCaptureAsNlohmannDumpsThem) {
  const auto inputs = bundled_captures();
  ASSERT_GT(inputs.size(), 15u);
  for (const std::string& in : inputs) {
    SCOPED_TRACE(in);
    Sink none;
    Analyzer a(AnalyzerOptions{}, none);
    std::string err;
    ASSERT_TRUE(read_file(in, Format::automatic, a, SourceOptions{}, err)) << err;
    a.finish();
    const auto ref = reference::stats_json(a.stats(), a.worst());
    std::string pretty, line;
    write_stats_json(pretty, a.stats(), a.worst(), 2);
    EXPECT_EQ(pretty, reference::dump(ref, 2));
    reference::json k;
    k["type"] = "stats";
    k.update(ref);
    write_stats_json(line, a.stats(), a.worst(), -1, "stats");
    EXPECT_EQ(line, reference::dump(k));
  }
}

// frame --json: each frame and garbage run of every bundled capture.
TEST(JsonWriter, FrameCommandLinesAsNlohmannDumpsThem) {
  std::size_t frames = 0, garbage = 0;
  for (const std::string& in : bundled_captures()) {
    struct Each : Sink {
      std::size_t *n_frames, *n_garbage;
      void frame(const FrameEvent& e) override {
        const top::Frame& f = *e.entry->frame;
        reference::json j;
        j["arg"] = 1;
        j["offset"] = e.pos.offset;
        j.update(reference::frame_json(f, e.entry->decoded));
        std::string w;
        write_frame_json(w, 1, e.pos.offset, f, e.entry->decoded);
        EXPECT_EQ(w, j.dump() + "\n");
        ++*n_frames;
      }
      void garbage(const GarbageEvent& e) override {
        reference::json j;
        j["arg"] = 2;
        j["offset"] = e.item->offset;
        j.update(reference::garbage_json(*e.item));
        std::string w;
        write_garbage_json(w, 2, *e.item);
        EXPECT_EQ(w, j.dump() + "\n");
        ++*n_garbage;
      }
    } each;
    each.n_frames = &frames;
    each.n_garbage = &garbage;
    SCOPED_TRACE(in);
    Analyzer a(AnalyzerOptions{}, each);
    std::string err;
    ASSERT_TRUE(read_file(in, Format::automatic, a, SourceOptions{}, err)) << err;
    a.finish();
  }
  EXPECT_GT(frames, 100u);
  EXPECT_GT(garbage, 0u);
}

// --- the writer against nlohmann over captures and hostile bytes ------------

constexpr std::int64_t T = 1714564800LL * 1000000;

// --- JSON fast path vs nlohmann reference ------------------------------------------

// Parses with nlohmann and fails on a key that repeats inside an object.
nlohmann::json parse_unique(const std::string& line) {
  std::vector<std::set<std::string>> stack;
  bool dup = false;
  auto cb = [&](int, nlohmann::json::parse_event_t ev, nlohmann::json& j) {
    using E = nlohmann::json::parse_event_t;
    if (ev == E::object_start)
      stack.emplace_back();
    else if (ev == E::object_end)
      stack.pop_back();
    else if (ev == E::key)
      dup |= !stack.back().insert(j.get<std::string>()).second;
    return true;
  };
  auto j = nlohmann::json::parse(line, cb);
  EXPECT_FALSE(dup) << "duplicate key in " << line;
  return j;
}

void expect_fast_equals_reference(const Recorder& r) {
  for (const auto& [line, ref] : r.garbage_json) EXPECT_EQ(line, ref);
  for (const auto& [line, ref] : r.note_json) {
    ASSERT_EQ(line.back(), '\n');
    EXPECT_EQ(std::count(line.begin(), line.end(), '\n'), 1);
    EXPECT_EQ(parse_unique(line), parse_unique(ref)) << line;
  }
  for (const auto& f : r.frames) {
    ASSERT_FALSE(f.json_fast.empty());
    ASSERT_EQ(f.json_fast.back(), '\n');
    EXPECT_EQ(std::count(f.json_fast.begin(), f.json_fast.end(), '\n'), 1);
    nlohmann::json fast = parse_unique(f.json_fast);
    nlohmann::json ref = parse_unique(f.json_ref);
    EXPECT_EQ(fast, ref) << f.json_fast << "\n" << f.json_ref;
  }
}

TEST(Json, FastWriterEqualsReferenceOverTheCaptures) {
  for (const char* cap : {"sample.pcap", "topotek-vlan.pcap", "tcp-c10.pcap", "serial-raw.bin",
                          "serial-lines.log", "serial-saleae.csv", "truncated.pcap"}) {
    Recorder r;
    Analyzer a(AnalyzerOptions{}, r);
    std::string err;
    ASSERT_TRUE(read_file(captures_dir() + "/" + cap, Format::automatic, a, SourceOptions{}, err))
        << err;
    a.finish();
    ASSERT_FALSE(r.frames.empty()) << cap;
    expect_fast_equals_reference(r);
  }
}

// A quirk is a source's evidence, which may quote it: the 14-char FAI's
// names AP_Mount_SkyDroid.cpp's format "%04X%04X%04X%02X". The writer put
// quirks between quotes as they were, and the line was no JSON.
TEST(Json, QuirkThatQuotesItsSourceIsEscaped) {
  Fixture f;
  f.up(0, top::with_checksum("#tpUGEwFAIEC78FF38000001"));
  f.a->finish();
  ASSERT_EQ(f.rec.frames.size(), 1u);
  const std::string& line = f.rec.frames[0].json_fast;
  ASSERT_NE(line.find("\\\"%04X"), std::string::npos) << line;
  const nlohmann::json j = parse_unique(line);
  ASSERT_EQ(j["quirks"].size(), 1u) << line;
  EXPECT_NE(j["quirks"][0].get<std::string>().find("\"%04X%04X%04X%02X\""), std::string::npos);
  expect_fast_equals_reference(f.rec);
}

// json_plain reads eight bytes at a time: every byte value at every
// position of strings of every length up to 24, against the byte table,
// from exact-size buffers (ASan sees a read past the end).
TEST(Json, PlainCheckAgreesWithTheByteTable) {
  std::size_t checked = 0;
  for (std::size_t n = 1; n <= 24; ++n)
    for (std::size_t at = 0; at < n; ++at)
      for (int v = 0; v < 256; ++v) {
        std::string s(n, 'A');
        s[at] = static_cast<char>(v);
        const std::unique_ptr<char[]> exact(new char[n]);
        std::memcpy(exact.get(), s.data(), n);
        const bool want = detail::kJsonPlain[static_cast<std::size_t>(v)];
        ASSERT_EQ(json_plain(std::string_view(exact.get(), n)), want) << n << " " << at << " " << v;
        ++checked;
      }
  EXPECT_EQ(checked, 256u * 300u);
  EXPECT_TRUE(json_plain(""));
  EXPECT_FALSE(detail::kJsonPlain['"']);
  EXPECT_FALSE(detail::kJsonPlain['\\']);
  EXPECT_FALSE(detail::kJsonPlain[0x7F]);
  EXPECT_TRUE(detail::kJsonPlain['~']);
}

TEST(Json, FastWriterEqualsReferenceOnHostileBytes) {
  // random bytes around frame starts, names with quotes and control bytes
  std::mt19937 rng(11);
  Recorder r;
  Analyzer a(AnalyzerOptions{}, r);
  Endpoint s, d;
  s.name = std::string("tty\"\\\x01\xff", 6);
  d.name = "host";
  for (int i = 0; i < 300; ++i) {
    std::string p = "#tp";
    int n = static_cast<int>(rng() % 24);
    for (int k = 0; k < n; ++k) p += static_cast<char>(rng() & 0xFF);
    if (i % 3 == 0)
      p = top::with_checksum("#tpUG6wGAY" + std::string(1, static_cast<char>(rng() & 0xFF)) +
                             "00032");
    if (i % 7 == 0)
      p = top::with_checksum(
          "#tPUDEwGPS" + std::string(1, '\x0e') +
          std::string("\"\\\x00\x7f\x80\xfe#\x0d\x0a\x01\x02\x03\x04\x05\x06", 15));
    a.chunk(T + i, Transport::serial, i % 2 ? s : d, i % 2 ? d : s, p,
            static_cast<std::uint64_t>(i + 1), 0);
  }
  // a frame after the timeout: what went unanswered is noted with its name
  a.chunk(T + 3'000'000, Transport::serial, d, s, top::with_checksum("#TPUG2wPTZ05"), 301, 0);
  a.finish();
  ASSERT_GT(r.frames.size(), 50u);
  ASSERT_FALSE(r.notes.empty());
  expect_fast_equals_reference(r);
}

Endpoint named_ep(const char* n) {
  Endpoint e;
  e.name = n;
  return e;
}

// Times before 1970 (a serial log's negative seconds) are written with their
// sign; the writer used to put '0' minus a digit in the fraction ("0.00000/").
TEST(Json, NegativeTimesAreNumbers) {
  Recorder r;
  Analyzer a(AnalyzerOptions{}, r);
  a.chunk(-1, Transport::serial, named_ep("a"), named_ep("b"), top::with_checksum("#TPUG2wPTZ05"),
          1, 0);
  a.chunk(-2500001, Transport::serial, named_ep("b"), named_ep("a"),
          top::with_checksum("#TPGU2wPTZ05"), 2, 0);
  a.source_note(-7, ACode::log_syntax, "a note", 3, 0);
  a.finish();
  ASSERT_EQ(r.frames.size(), 2u);
  EXPECT_EQ(nlohmann::json::parse(r.frames[0].json_fast)["time"].get<double>(), -1e-6);
  EXPECT_EQ(nlohmann::json::parse(r.frames[1].json_fast)["time"].get<double>(), -2.500001);
  expect_fast_equals_reference(r);
}

// The JSON writer puts the catalog's strings between quotes as they are: none
// may need escaping.
TEST(Json, CatalogStringsNeedNoEscaping) {
  auto plain = [](std::string_view s) {
    for (unsigned char c : s)
      if (c < 0x20 || c >= 0x7F || c == '"' || c == '\\') return false;
    return true;
  };
  std::size_t n = 0;
  for (top::Dialect dl : {top::Dialect::skydroid, top::Dialect::topotek}) {
    EXPECT_TRUE(plain(top::to_string(dl)));
    for (const top::CommandSpec& c : top::commands(dl)) {
      EXPECT_TRUE(plain(c.ident) && plain(c.title) && plain(c.section) &&
                  plain(std::string_view(&c.address, 1)))
          << c.ident;
      for (const top::FormSpec& f : c.forms)
        for (const auto& fields : {f.fields, f.record})
          for (const top::FieldSpec& fs : fields) {
            EXPECT_TRUE(plain(fs.name) && plain(fs.unit) && plain(top::to_string(fs.kind)))
                << c.ident << " " << fs.name;
            for (const top::EnumValue& e : fs.enums) EXPECT_TRUE(plain(e.name)) << e.name;
            ++n;
          }
    }
  }
  EXPECT_GT(n, 200u);
  for (std::size_t i = 0; i < top::finding_code_count; ++i)
    EXPECT_TRUE(plain(top::to_string(static_cast<top::FindingCode>(i))));
  for (top::Header h : {top::Header::fixed, top::Header::variable, top::Header::ext8,
                        top::Header::ext16, top::Header::tmp_quirk})
    EXPECT_TRUE(plain(top::to_string(h)));
}

// One writer for a push stream's keys: stats --json and report --json
// differ only where StreamKeys says.
TEST(JsonWriter, OneStreamWriterForStatsAndTheReport) {
  StreamStat t;
  t.ident = "GAC";
  t.asked_by = "GAA";
  t.asked_hz = 10;
  t.frames = 4;
  t.first = kT0;
  t.last = kT0 + 900'000;  // 3.3333 Hz
  auto write = [&](jsonw::StreamKeys k) {
    std::string out;
    jsonw::Doc j(out, -1);
    j.open_object();
    jsonw::stream_members(j, t, k);
    j.close_object();
    return out;
  };
  EXPECT_EQ(write({}),
            R"({"ident":"GAC","asked_hz":10.0,"measured_hz":3.33,"periodic":true,"frames":4})");
  EXPECT_EQ(write({.asked_by = true, .measured_per_hz = 1e4}),
            R"({"ident":"GAC","asked_by":"GAA","asked_hz":10.0,"measured_hz":3.3333,)"
            R"("periodic":true,"frames":4})");
  t.asked_hz = 0;
  t.periodic = false;
  EXPECT_EQ(write({}),
            R"({"ident":"GAC","asked_hz":null,"measured_hz":3.33,"periodic":false,"frames":4})");
}

}  // namespace
}  // namespace topdump::test
