// The session layer beyond pairing: TCP reassembly through the analyzer,
// statistics without detail, the ring, latency, the findings table and the
// datagram fast path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <deque>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>
#include <set>

#include "findings/afindings.hpp"
#include "output/escape.hpp"
#include "pcapio/packet.hpp"
#include "pcapio/writer.hpp"
#include "test_support.hpp"
#include "top/detail/ring.hpp"
#include "top/frame.hpp"

namespace topdump::test {
namespace {

TEST(Limits, ConversationLimitClosesTheOldest) {
  Fixture f;
  AnalyzerOptions o;
  o.max_conversations = 4;
  f.reset(o);
  for (std::uint16_t i = 0; i < 10; ++i)
    f.a->datagram(T, ep4(1, static_cast<std::uint16_t>(40000 + i)), ep4(2, 5000),
                  top::with_checksum("#TPUG2wPTZ05"), i + 1u, 42);
  f.a->finish();
  EXPECT_EQ(f.rec.count_note(ACode::conversation_limit), 6u);
  EXPECT_EQ(f.a->stats().conversations.size(), 10u);
  EXPECT_EQ(f.rec.frames.size(), 10u);
}

TEST(Positions, SeveralFramesPerDatagram) {
  Fixture f;
  std::string a = top::with_checksum("#TPUG2wPTZ05"), b = top::with_checksum("#tpUG6wGAYEC7832");
  f.up(0, a + "\r\n" + b);
  f.a->finish();
  ASSERT_EQ(f.rec.frames.size(), 2u);
  EXPECT_EQ(f.rec.frames[0].pos.record, 1u);
  EXPECT_EQ(f.rec.frames[0].pos.index, 0u);
  EXPECT_EQ(f.rec.frames[0].pos.offset, 42u);
  EXPECT_EQ(f.rec.frames[1].pos.index, 1u);
  EXPECT_EQ(f.rec.frames[1].pos.offset, 42u + a.size() + 2);
  // keys never repeat: two objects, each complete
  for (const auto& x : f.rec.frames) EXPECT_EQ(nlohmann::json::parse(x.json_fast)["record"], 1);
}

std::string tcp_stream() {
  std::string s;
  for (int i = 0; i < 20; ++i) {
    char b[32];
    std::snprintf(b, sizeof b, "#tpUG6wGAY%04X32", (i * 97) & 0xFFFF);
    s += top::with_checksum(b);
    if (i % 5 == 0) s += "\r\n";
  }
  return s;
}

std::vector<std::string> raws(const Recorder& r) {
  std::vector<std::string> v;
  for (const auto& f : r.frames) v.push_back(f.raw);
  return v;
}

TEST(Tcp, EverySplitAndShuffleGivesTheSameFrames) {
  std::string s = tcp_stream();
  Recorder ref;
  {
    Analyzer a(AnalyzerOptions{}, ref);
    a.segment(T, ep4(1, 50000), ep4(2, 5000), 100, false, s, 1, 54);
    a.finish();
  }
  ASSERT_EQ(ref.frames.size(), 20u);
  std::mt19937 rng(7);
  for (std::size_t cut = 1; cut < s.size(); cut += 3) {
    // segments of `cut` bytes, the order shuffled, one retransmitted
    std::vector<std::pair<std::uint32_t, std::string>> segs;
    for (std::size_t at = 0; at < s.size(); at += cut)
      segs.emplace_back(static_cast<std::uint32_t>(1000 + at), s.substr(at, cut));
    segs.push_back(segs[segs.size() / 2]);
    std::shuffle(segs.begin() + 1, segs.end(), rng);
    Recorder r;
    Analyzer a(AnalyzerOptions{}, r);
    a.segment(T, ep4(1, 50000), ep4(2, 5000), 999, true, "", 1, 54);  // SYN
    std::uint64_t rec = 1;
    for (const auto& [seq, bytes] : segs)
      a.segment(T, ep4(1, 50000), ep4(2, 5000), seq, false, bytes, ++rec, 54);
    a.finish();
    EXPECT_EQ(raws(r), raws(ref)) << "segments of " << cut;
    EXPECT_FALSE(r.has_note(ACode::tcp_gap)) << "segments of " << cut;
    EXPECT_TRUE(r.has_note(ACode::tcp_retransmission)) << "segments of " << cut;
  }
}

TEST(Tcp, OverlapThatDisagreesIsReported) {
  Recorder r;
  Analyzer a(AnalyzerOptions{}, r);
  std::string x = top::with_checksum("#TPUG2wPTZ05");
  a.segment(T, ep4(1, 50000), ep4(2, 5000), 10, false, x, 1, 54);
  std::string y = x;
  y[4] = 'Q';
  a.segment(T, ep4(1, 50000), ep4(2, 5000), 10, false, y, 2, 54);
  a.finish();
  EXPECT_TRUE(r.has_note(ACode::tcp_overlap_differs));
  ASSERT_EQ(r.frames.size(), 1u);
  EXPECT_EQ(r.frames[0].raw, x);
}

TEST(Tcp, MissingSegmentIsAGapAndDecodingGoesOn) {
  Recorder r;
  Analyzer a(AnalyzerOptions{}, r);
  std::string x = top::with_checksum("#TPUG2wPTZ05"), y = top::with_checksum("#TPUG2wPTZ01"),
              z = top::with_checksum("#TPUG2wPTZ00");
  a.segment(T, ep4(1, 50000), ep4(2, 5000), 0, false, x, 1, 54);
  // y never captured
  a.segment(T, ep4(1, 50000), ep4(2, 5000), static_cast<std::uint32_t>(x.size() + y.size()), false,
            z, 3, 54);
  a.finish();
  EXPECT_TRUE(r.has_note(ACode::tcp_gap));
  EXPECT_EQ(raws(r), (std::vector<std::string>{x, z}));
  EXPECT_EQ(a.worst(), top::Severity::error);
}

TEST(Tcp, HeldBytesAreBounded) {
  Recorder r;
  AnalyzerOptions o;
  o.max_tcp_held = 4096;
  Analyzer a(o, r);
  std::string chunk(1000, 'x');
  a.segment(T, ep4(1, 50000), ep4(2, 5000), 0, true, "", 1, 54);  // SYN: the stream starts at 1
  // never fill the hole before 1000: everything is held until the limit
  for (std::uint32_t i = 1; i <= 10; ++i)
    a.segment(T, ep4(1, 50000), ep4(2, 5000), i * 1000, false, chunk, i, 54);
  a.finish();
  EXPECT_TRUE(r.has_note(ACode::reassembly_limit));
}

TEST(Tcp, SequenceWrapAround) {
  std::string s = tcp_stream();
  Recorder r;
  Analyzer a(AnalyzerOptions{}, r);
  std::uint32_t isn = 0xFFFFFF00u;
  for (std::size_t at = 0; at < s.size(); at += 50)
    a.segment(T, ep4(1, 50000), ep4(2, 5000), isn + static_cast<std::uint32_t>(at), false,
              s.substr(at, 50), at + 1, 54);
  a.finish();
  EXPECT_EQ(r.frames.size(), 20u);
  EXPECT_FALSE(r.has_note(ACode::tcp_gap));
}

// Counts what stats needs of each event: codes and severities, no text.
struct VerdictSink : Sink {
  std::vector<std::string> seen;
  void frame(const FrameEvent& e) override {
    std::string s = std::to_string(e.n) + " " + std::to_string(static_cast<int>(e.worst())) + " r" +
                    std::to_string(e.reply_to) + " " +
                    std::to_string(static_cast<int>(e.entry->decoded.role));
    for (const auto* list : {&e.entry->frame->findings, &e.entry->decoded.findings})
      for (const top::Finding& x : *list) s += " " + std::string(top::to_string(x.code));
    s += e.entry->bad_checksum ? " bad" : " ok";
    for (const Note& n : e.notes) s += " " + std::string(to_string(n.code));
    seen.push_back(std::move(s));
  }
  void note(const NoteEvent& e) override {
    seen.push_back("note " + std::string(to_string(e.note.code)) + " " +
                   std::to_string(static_cast<int>(e.note.severity)) + " " +
                   std::to_string(e.note.frame));
  }
};

// topdump stats runs the analyzer without detail: every capture (and a
// generated one with every kind of session finding) gives the same
// events, the same statistics and the same exit status as with detail.
TEST(Stats, WithoutDetailEqualsWithDetail) {
  TempDir tmp;
  const std::string generated = generated_capture(tmp, "g.pcap", 20000, 3);
  ASSERT_FALSE(generated.empty());
  std::vector<std::string> inputs = {generated};
  for (const auto& e : std::filesystem::directory_iterator(captures_dir()))
    if (e.is_regular_file() && e.path().extension() != ".md" && e.path().extension() != ".sh" &&
        e.path().extension() != ".cpp" && e.path().extension() != ".txt")
      inputs.push_back(e.path().string());
  ASSERT_GT(inputs.size(), 15u);
  for (const std::string& in : inputs) {
    SCOPED_TRACE(in);
    VerdictSink sinks[2];
    std::unique_ptr<Analyzer> as[2];
    for (int detail = 0; detail < 2; ++detail) {
      AnalyzerOptions o;
      o.detail = detail == 1;
      as[detail] = std::make_unique<Analyzer>(o, sinks[detail]);
      std::string err;
      ASSERT_TRUE(read_file(in, Format::automatic, *as[detail], SourceOptions{}, err)) << err;
      as[detail]->finish();
    }
    EXPECT_EQ(sinks[0].seen, sinks[1].seen);
    std::string j[2];
    for (int i = 0; i < 2; ++i) write_stats_json(j[i], as[i]->stats(), as[i]->worst(), 2);
    EXPECT_EQ(j[0], j[1]);
    EXPECT_EQ(as[0]->worst(), as[1]->worst());
    // (diag-baud-mismatch.bin is made to hold no TOP frame)
    if (in.find("diag-baud-mismatch") == std::string::npos) {
      EXPECT_GT(as[0]->stats().frames, 0u);
    }
  }
}

// Without detail (topdump stats) the datagram path writes no finding's
// text, which stats never shows: a frame with a bad checksum and CR/LF
// after it keeps its codes, with empty messages; with detail they have
// their text (docs/perf/decisions.md, "Findings without text").
TEST(Stats, WithoutDetailTheFramesFindingsCarryNoText) {
  struct Texts : Sink {
    std::vector<std::pair<std::string, std::string>> seen;  // code, message
    void frame(const FrameEvent& e) override {
      for (const top::Finding& x : e.entry->frame->findings)
        seen.emplace_back(top::to_string(x.code), x.message);
    }
  };
  std::string bad = top::with_checksum("#TPUG2wPTZ05");
  bad.back() = bad.back() == '0' ? '1' : '0';
  const std::string payload = bad + "\r\n" + top::with_checksum("#TPUG2wPTZ00") + "\r\n";
  std::vector<std::string> codes[2];
  for (int detail = 0; detail < 2; ++detail) {
    SCOPED_TRACE(detail);
    Texts t;
    AnalyzerOptions o;
    o.detail = detail == 1;
    Analyzer a(o, t);
    a.datagram(T, ep4(1, 40000), ep4(2, 5000), payload, 1, 42);
    a.finish();
    ASSERT_GE(t.seen.size(), 3u);  // a checksum, and CR/LF after each frame
    for (const auto& [code, message] : t.seen) {
      codes[detail].push_back(code);
      EXPECT_EQ(message.empty(), detail == 0) << code << ": " << message;
    }
  }
  EXPECT_EQ(codes[0], codes[1]);
}

// The pending-request ring against a std::deque, through random pushes,
// pops and erasures anywhere, across growth and wrap-around; a slot handed
// back by push_back is reused, so the test assigns all of it as the
// analyzer does.
// clear() empties and keeps the slots; trim() drops slots only when empty
// (the stream decoder trims after a burst), and the ring works on after.
TEST(Ring, ClearAndTrim) {
  top::detail::Ring<std::string> ring;
  for (int i = 0; i < 100; ++i) ring.push_back() = "item " + std::to_string(i);
  ring.trim(8);  // not empty: nothing is dropped
  ASSERT_EQ(ring.size(), 100u);
  EXPECT_EQ(ring[99], "item 99");
  ring.pop_front();
  EXPECT_EQ(ring.front(), "item 1");
  ring.clear();
  EXPECT_TRUE(ring.empty());
  ring.trim(8);
  for (int i = 0; i < 20; ++i) ring.push_back() = "again " + std::to_string(i);
  ASSERT_EQ(ring.size(), 20u);
  for (int i = 0; i < 20; ++i)
    EXPECT_EQ(ring[static_cast<std::size_t>(i)], "again " + std::to_string(i));
}

TEST(Ring, BehavesAsADequeThroughGrowthWrapAndErase) {
  top::detail::Ring<std::string> ring;
  std::deque<std::string> model;
  std::mt19937 rng(5);
  std::size_t erased_inside = 0, erased_newest = 0, max_size = 0;
  for (int step = 0; step < 20000; ++step) {
    const auto op = rng() % 10;
    if (op < 5 || model.empty()) {
      // strings past the small-string size, so buffers are reused for real
      std::string v = "request-" + std::to_string(step) + std::string(rng() % 40, 'x');
      ring.push_back().assign(v);
      model.push_back(v);
    } else if (op < 7) {
      ring.pop_front();
      model.pop_front();
    } else {
      // op 9: the newest, as most replies erase (the ring moves nothing then)
      const std::size_t i = op == 9 ? model.size() - 1 : rng() % model.size();
      erased_inside += i + 1 < model.size();
      erased_newest += i + 1 == model.size();
      ring.erase(i);
      model.erase(model.begin() + static_cast<std::ptrdiff_t>(i));
    }
    max_size = std::max(max_size, model.size());
    ASSERT_EQ(ring.size(), model.size());
    ASSERT_EQ(ring.empty(), model.empty());
    for (std::size_t i = 0; i < model.size(); ++i) ASSERT_EQ(ring[i], model[i]) << step;
    if (!model.empty()) {
      ASSERT_EQ(ring.front(), model.front());
    }
  }
  EXPECT_GT(max_size, 40u);  // grew several times past its first 8 slots
  EXPECT_GT(erased_inside, 1000u);
  EXPECT_GT(erased_newest, 1000u);
}

// The bucket of a latency comes from small tables up to 65.536 ms (each
// slice of a power of two holds at most two bucket starts): for every value
// up to 2^17 us and values far beyond, the bucket the formula gives.
TEST(Latency, BucketTablesAgreeWithTheFormula) {
  for (std::int64_t us = -3; us < (std::int64_t{1} << 17); ++us)
    ASSERT_EQ(Latency::bucket(us), Latency::bucket_exact(us)) << us;
  std::mt19937_64 rng(7);
  for (int i = 0; i < 100000; ++i) {
    const auto us = static_cast<std::int64_t>(rng() >> (rng() % 60));
    ASSERT_EQ(Latency::bucket(us), Latency::bucket_exact(us)) << us;
  }
}

TEST(Latency, ExactThenHistogramWithinOnePercent) {
  Latency l;
  for (int i = 1; i <= 100; ++i) l.add(i * 1000);
  EXPECT_EQ(l.quantile(0.5), 50000);
  EXPECT_EQ(l.quantile(0.95), 95000);
  Latency big;
  for (int i = 1; i <= 100000; ++i) big.add(i);
  EXPECT_NEAR(static_cast<double>(big.quantile(0.5)), 50000.0, 500.0);
  EXPECT_NEAR(static_cast<double>(big.quantile(0.95)), 95000.0, 950.0);
  EXPECT_EQ(big.min(), 1);
  EXPECT_EQ(big.max(), 100000);
}

TEST(AnalyzerFindings, TableIsConsistentAndDocumented) {
  std::string doc = slurp(std::string(TOPKIT_SOURCE_DIR) + "/docs/topdump-json.md");
  // the diagnoses are documented in docs/DIAGNOSES.md (generated)
  const std::string diag = slurp(std::string(TOPKIT_SOURCE_DIR) + "/docs/DIAGNOSES.md");
  std::set<std::string> seen;
  for (std::size_t i = 0; i < acode_count; ++i) {
    auto c = static_cast<ACode>(i);
    std::string code(to_string(c));
    EXPECT_TRUE(seen.insert(code).second) << code;
    EXPECT_EQ(acode_from_string(code), c);
    EXPECT_FALSE(description(c).empty());
    EXPECT_FALSE(top::finding_code_from_string(code).has_value())
        << code << " clashes with a protocol code";
    EXPECT_NE((diagnosis_of(c) ? diag : doc).find("`" + code + "`"), std::string::npos)
        << code << " is not documented";
  }
}

}  // namespace
}  // namespace topdump::test

namespace topdump::test {
namespace {

// The one-frame datagram fast path gives what the stream decoder gives.
TEST(Datagram, FastPathEqualsStreamDecoder) {
  std::mt19937 rng(3);
  std::vector<std::string> payloads = {top::with_checksum("#tpUG6wGAYEC7832"),
                                       top::with_checksum("#TPUG2wPTZ05"),
                                       "#TPUG2wPTZ0500",
                                       top::with_checksum("#TPUG2wPTZ05") + "\r\n",
                                       top::with_checksum("#PDP16TMP1008001720504000FA0123"),
                                       top::with_checksum("#tpDP16wTMP1008001720504000FA0123"),
                                       top::with_checksum("#tpUG6wGAYfe0c32"),
                                       "#tpUG6wGAY",
                                       top::with_checksum("#tpUG6wGAY#TPUG2"),
                                       top::with_checksum("#TPUG2wPTZ05").substr(0, 13)};
  for (int i = 0; i < 400; ++i) {
    std::string p = top::with_checksum("#tpUG6wGAYEC7832");
    p[static_cast<std::size_t>(rng() % p.size())] = static_cast<char>(rng() & 0xFF);
    payloads.push_back(p);
  }
  // Several frames per datagram, with CR/LF runs (one over 255 bytes), and
  // then one byte anywhere replaced: the fast path hands over to the decoder
  // at the first byte it does not take.
  const std::vector<std::string> parts = {top::with_checksum("#tpUG6wGAYEC7832"),
                                          top::with_checksum("#TPUG2wPTZ05"),
                                          top::with_checksum("#TPUD2rVER00"),
                                          top::with_checksum("#tpUG6wGAYfe0c32"),
                                          top::with_checksum("#PDP16TMP1008001720504000FA0123"),
                                          "\r\n",
                                          "\n",
                                          std::string(300, '\r'),
                                          "x",
                                          "#TPUG2wPTZ0500"};
  for (int i = 0; i < 600; ++i) {
    std::string p;
    const std::size_t n = 2 + rng() % 4;
    for (std::size_t k = 0; k < n; ++k) p += parts[rng() % (k == 0 ? 5 : parts.size())];
    if (i % 2) p[static_cast<std::size_t>(rng() % p.size())] = static_cast<char>(rng() & 0xFF);
    payloads.push_back(p);
  }
  for (const std::string& p : payloads) {
    Recorder r;
    Analyzer a(AnalyzerOptions{}, r);
    a.datagram(T, ep4(1, 40000), ep4(2, 5000), p, 1, 42);
    a.finish();
    top::StreamDecoder dec;
    dec.feed(p);
    dec.finish();
    top::StreamItem it;
    std::size_t frames = 0, garbage = 0;
    while (dec.next(it)) {
      if (it.kind == top::ItemKind::garbage) {
        ASSERT_LT(garbage, r.garbage_pos.size()) << escape(p);
        EXPECT_EQ(r.garbage_pos[garbage].offset, 42u + it.offset) << escape(p);
        EXPECT_EQ(r.garbage_pos[garbage].index, frames + garbage) << escape(p);
        ++garbage;
        continue;
      }
      ASSERT_LT(frames, r.frames.size()) << escape(p);
      const auto& got = r.frames[frames++];
      EXPECT_EQ(got.raw, it.frame.raw) << escape(p);
      EXPECT_EQ(got.pos.offset, 42u + it.offset) << escape(p);
      EXPECT_EQ(got.pos.index, frames + garbage - 1) << escape(p);
      std::vector<std::string> want;
      // in the dialect the conversation settled on (a TMP frame makes it Topotek)
      top::Decoded d = top::decode(
          it.frame, top::DecodeOptions{got.dialect, top::Model::unknown, top::Role::any});
      for (const top::Finding* x : all_findings(it.frame, d))
        want.emplace_back(top::to_string(x->code));
      std::vector<std::string> have;
      for (const auto& c : got.codes)
        if (!acode_from_string(c)) have.push_back(c);
      EXPECT_EQ(have, want) << escape(p);
    }
    EXPECT_EQ(frames, r.frames.size()) << escape(p);
    EXPECT_EQ(garbage, r.garbage_codes.size()) << escape(p);
  }
}

}  // namespace
}  // namespace topdump::test
