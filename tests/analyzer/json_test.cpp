// The one JSON writer (analyzer/src/json_writer.hpp) against nlohmann: the
// numbers and strings it writes, and the documents whose format is
// nlohmann's dump() (stats --json, frame --json), byte by byte.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <random>

#include "json_reference.hpp"
#include "json_writer.hpp"
#include "test_support.hpp"

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
    EXPECT_EQ(pretty, ref.dump(2));
    reference::json k;
    k["type"] = "stats";
    k.update(ref);
    write_stats_json(line, a.stats(), a.worst(), -1, "stats");
    EXPECT_EQ(line, k.dump());
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

}  // namespace
}  // namespace topdump::test
