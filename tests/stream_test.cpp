#include "top/stream.hpp"

#include <gtest/gtest.h>

#include <random>

#include "test_util.hpp"

using namespace top;
using toptest::decode_all;
using toptest::decode_chunked;
using toptest::describe;

namespace {
std::vector<std::string> frames_of(const std::vector<StreamItem>& items) {
  std::vector<std::string> v;
  for (const auto& it : items)
    if (it.kind == ItemKind::frame) v.push_back(it.frame.raw);
  return v;
}
}  // namespace

TEST(Stream, ResyncKeepsTheFollowingFrame) {
  auto items = decode_all("#T#TPUD2wCAP013E");
  ASSERT_EQ(items.size(), 2u) << describe(items);
  EXPECT_EQ(items[0].kind, ItemKind::garbage);
  EXPECT_EQ(items[0].offset, 0u);
  EXPECT_EQ(items[0].length, 2u);
  EXPECT_EQ(items[0].finding.code, FindingCode::bad_header);
  EXPECT_EQ(items[0].finding.offset, 2u);
  ASSERT_EQ(items[1].kind, ItemKind::frame);
  EXPECT_EQ(items[1].offset, 2u);
  EXPECT_EQ(items[1].frame.raw, "#TPUD2wCAP013E");
  EXPECT_TRUE(items[1].frame.ok());
}

TEST(Stream, BackToBackWithAndWithoutCrlf) {
  auto items = decode_all("#TPUD2wCAP013E#TPUD2rREC003E\r\n#tpUM2rZOM00A3\n");
  ASSERT_EQ(frames_of(items),
            (std::vector<std::string>{"#TPUD2wCAP013E", "#TPUD2rREC003E", "#tpUM2rZOM00A3"}))
      << describe(items);
  EXPECT_EQ(items[0].frame.terminator, 0);
  EXPECT_EQ(items[1].frame.terminator, 2);
  EXPECT_TRUE(toptest::has_code(items[1].frame.findings, FindingCode::crlf));
  EXPECT_EQ(items[2].frame.terminator, 1);
  EXPECT_EQ(items[2].offset, 30u);
}

TEST(Stream, LeadingGarbageIsReported) {
  auto items = decode_all("hello#TPUD2wCAP013E");
  ASSERT_EQ(items.size(), 2u);
  EXPECT_EQ(items[0].kind, ItemKind::garbage);
  EXPECT_EQ(items[0].finding.code, FindingCode::garbage);
  EXPECT_EQ(items[0].preview, "hello");
  EXPECT_EQ(items[1].offset, 5u);
}

namespace {
std::string gps_frame_with_hash() {
  // Topotek 5.8.5: 14 raw little-endian bytes; the heading 0x2323 holds '#'.
  std::string data;
  auto le = [&](std::uint32_t v, int n) {
    for (int i = 0; i < n; ++i) data += static_cast<char>((v >> (8 * i)) & 0xFF);
  };
  le(0x2323, 2);
  le(static_cast<std::uint32_t>(1203456789), 4);
  le(static_cast<std::uint32_t>(301234567), 4);
  le(static_cast<std::uint32_t>(123456), 4);
  return build_frame({.header = Header::variable,
                      .src = 'U',
                      .dst = 'D',
                      .control = 'w',
                      .ident = "GPS",
                      .data = data});
}
}  // namespace

TEST(Stream, BinaryDataWithHashInsideAValidatedFrame) {
  std::string gps = gps_frame_with_hash();
  ASSERT_NE(gps.find('#', 1), std::string::npos);
  std::string stream = gps + "#TPUD2wCAP013E" + gps;
  auto items = decode_all(stream);
  EXPECT_EQ(frames_of(items), (std::vector<std::string>{gps, "#TPUD2wCAP013E", gps}))
      << describe(items);
  for (const auto& it : items) EXPECT_TRUE(it.frame.ok());
}

TEST(Stream, CorruptFrameYieldsToValidFrameInside) {
  // A frame whose declared length swallows the start of the next one.
  auto items = decode_all("#TPUD9wCAP#TPUD2wCAP013E");
  ASSERT_EQ(frames_of(items), (std::vector<std::string>{"#TPUD2wCAP013E"})) << describe(items);
  EXPECT_EQ(items[0].kind, ItemKind::garbage);
}

TEST(Stream, LyingLengthInAStream) {
  auto items = decode_all("#tpDU3rVER0105025A#TPUD2wCAP013E");
  ASSERT_EQ(frames_of(items), (std::vector<std::string>{"#tpDU3rVER0105025A", "#TPUD2wCAP013E"}))
      << describe(items);
  EXPECT_TRUE(toptest::has_code(items[0].frame.findings, FindingCode::length_mismatch));
}

TEST(Stream, TruncatedAtTheEnd) {
  auto items = decode_all("#TPUD2wCAP013E#TPUD2wC");
  ASSERT_EQ(items.size(), 2u) << describe(items);
  EXPECT_EQ(items[1].kind, ItemKind::garbage);
  EXPECT_EQ(items[1].finding.code, FindingCode::truncated);
  EXPECT_EQ(items[1].offset, 14u);
}

TEST(Stream, SameItemsHoweverSplit) {
  std::string gps = gps_frame_with_hash();
  std::string stream = std::string("xx#T#TPUD2wCAP013E\r\n") + gps + "#tpDU3rVER0105025A" +
                       "#TPUG6wGAYEF073288#TPUD2wCAP0100\n#PDP" + "#tpUM2rZOM00A3#TPUD";
  const std::string whole = describe(decode_all(stream));
  for (std::size_t a = 1; a < stream.size(); ++a) {
    ASSERT_EQ(describe(decode_chunked(stream, {a})), whole) << "chunks of " << a;
  }
  std::mt19937 rng(7);
  for (int round = 0; round < 200; ++round) {
    std::vector<std::size_t> sizes;
    for (int i = 0; i < 8; ++i) sizes.push_back(1 + rng() % 9);
    ASSERT_EQ(describe(decode_chunked(stream, sizes)), whole) << "round " << round;
  }
}

// Without messages (StreamOptions::parse.messages false, as the
// differential fuzz target decodes): the same items, findings, codes and
// offsets, however the stream is split, and no text anywhere; with them
// every finding and garbage item has its text.
TEST(Stream, WithoutMessagesTheSameItems) {
  const std::string stream = std::string("xx#T#TPUD2wCAP013E\r\n") + gps_frame_with_hash() +
                             "#tpDU3rVER0105025A" + "#TPUD9wCAP#TPUD2wCAP013E" +
                             "#TPUG6wGAYEF073288#TPUD2wCAP0100\n#PDP#tpUD5wCAP0001E4\r\n" +
                             "#tpUM2rZOM00A3#TPUD";
  StreamOptions quiet;
  quiet.parse.messages = false;
  const std::vector<StreamItem> with = decode_all(stream);
  std::size_t texts = 0, findings = 0;
  for (const StreamItem& it : with) {
    if (it.kind == ItemKind::garbage) {
      ++findings;
      texts += !it.finding.message.empty();
    }
    for (const Finding& f : it.frame.findings) {
      ++findings;
      texts += !f.message.empty();
    }
  }
  ASSERT_GT(findings, 8u) << describe(with);
  EXPECT_EQ(texts, findings);
  const std::string expected = describe(with);
  std::mt19937 rng(11);
  for (int round = 0; round < 50; ++round) {
    std::vector<std::size_t> sizes;
    for (int i = 0; i < 8; ++i) sizes.push_back(1 + rng() % 9);
    const std::vector<StreamItem> without =
        round == 0 ? decode_all(stream, quiet) : decode_chunked(stream, sizes, quiet);
    ASSERT_EQ(describe(without), expected) << "round " << round;
    for (const StreamItem& it : without) {
      EXPECT_TRUE(it.finding.message.empty()) << it.finding.message;
      for (const Finding& f : it.frame.findings) EXPECT_TRUE(f.message.empty()) << f.message;
    }
  }
}

namespace {
// Every field of an item, for exact comparisons.
std::string everything(const StreamItem& it) {
  auto finding = [](const Finding& f) {
    return std::string(to_string(f.code)) + "/" + std::to_string(static_cast<int>(f.severity)) +
           "@" + std::to_string(f.offset) + " '" + f.message + "' q'" + std::string(f.quirk) + "'";
  };
  const Frame& f = it.frame;
  std::string s = std::to_string(static_cast<int>(it.kind)) + " @" + std::to_string(it.offset) +
                  "+" + std::to_string(it.length) + " frame{" +
                  std::to_string(static_cast<int>(f.header)) + " " + std::string(1, f.src) +
                  std::string(1, f.dst) + std::string(1, f.control) + std::string(f.ident_view()) +
                  " " + std::to_string(f.declared_length) + "/" + std::to_string(f.data_offset) +
                  "/" + std::to_string(f.data_length) + " cs" + std::to_string(f.checksum) + "/" +
                  std::to_string(f.expected_checksum) + (f.checksum_present ? "p" : "") +
                  (f.checksum_ok ? "ok" : "") + " t" + std::to_string(f.terminator) + " '" + f.raw +
                  "' [";
  for (const Finding& x : f.findings) s += finding(x) + "; ";
  return s + "]} finding{" + finding(it.finding) + "} preview '" + it.preview + "'\n";
}
}  // namespace

// next() swaps an item into the caller's StreamItem and keeps the old one's
// buffers for a later item: nothing of an earlier item (a frame's findings,
// a garbage item's preview or reason) may show in a later one, whether the
// caller keeps one item or takes a new one each time.
TEST(Stream, ReusedItemsCarryNothingOver) {
  const std::string stream = std::string("xx#T#TPUD2wCAP013E\r\n") + gps_frame_with_hash() +
                             "noise that is longer than the preview of thirty-two bytes" +
                             "#tpDU3rVER0105025A#TPUD9wCAP#TPUD2wCAP013E" +
                             "#TPUG6wGAYEF073288#TPUD2wCAP0100\n#PDP#tpUD5wCAP0001E4\r\n" +
                             "#tpUM2rZOM00A3" + std::string(70000, 'z') + "#TPUD2wCAP013E#TPUD";
  for (const bool messages : {true, false}) {
    StreamOptions o;
    o.parse.messages = messages;
    std::string fresh, reused;
    StreamDecoder a(o), b(o);
    a.feed(stream);
    a.finish();
    for (StreamItem it; a.next(it); it = StreamItem{}) fresh += everything(it);
    StreamItem kept;
    b.feed(stream);
    b.finish();
    while (b.next(kept)) reused += everything(kept);
    EXPECT_EQ(reused, fresh) << "messages " << messages;
    EXPECT_NE(fresh.find("garbage"), std::string::npos);
    // and a decoder reset and used again
    b.reset();
    b.feed(stream);
    b.finish();
    std::string again;
    while (b.next(kept)) again += everything(kept);
    EXPECT_EQ(again, fresh) << "messages " << messages;
  }
}

TEST(Stream, MemoryStaysBounded) {
  StreamDecoder d;
  std::mt19937 rng(1);
  std::string chunk(4096, '\0');
  StreamItem it;
  std::size_t max_buffered = 0;
  std::uint64_t covered = 0;
  for (int i = 0; i < 2000; ++i) {
    for (char& c : chunk) {
      unsigned r = rng() % 16;
      c = r == 0 ? '#' : r == 1 ? 'T' : r == 2 ? 'p' : static_cast<char>(rng() & 0xFF);
    }
    d.feed(chunk);
    while (d.next(it))
      covered += it.length + (it.kind == ItemKind::frame ? it.frame.terminator : 0);
    max_buffered = std::max(max_buffered, d.buffered());
  }
  d.finish();
  while (d.next(it)) covered += it.length + (it.kind == ItemKind::frame ? it.frame.terminator : 0);
  EXPECT_LE(max_buffered, max_frame_size + 4096 + 64);
  EXPECT_EQ(d.buffered(), 0u);
  // Nothing is lost: every byte is in a frame, a terminator or garbage.
  EXPECT_EQ(covered, 2000u * 4096u);
}

TEST(Stream, ByteAccountingWithFrames) {
  std::string stream = "ab#TPUD2wCAP013E\r\n#T#tpUM2rZOM00A3zz";
  auto items = decode_all(stream);
  std::uint64_t covered = 0;
  for (const auto& it : items)
    covered += it.length + (it.kind == ItemKind::frame ? it.frame.terminator : 0);
  EXPECT_EQ(covered, stream.size()) << describe(items);
}

TEST(Stream, FlushReleasesAHeldFrame) {
  StreamDecoder d;
  d.feed("#TPUD2wCAP013E");
  StreamItem it;
  EXPECT_FALSE(d.next(it));  // held: CR/LF might follow
  d.flush();
  ASSERT_TRUE(d.next(it));
  EXPECT_EQ(it.frame.raw, "#TPUD2wCAP013E");
}

// flush() and settle() decide on the frame held last in the buffer: they
// must see every byte fed so far. They used to decode only until 64 items
// were queued, so in a chunk of more frames the frame held there was
// released before the CR/LF after it was read, and that CR/LF came out as
// garbage (a burst of 65 frames on a serial or TCP link, in topsim and in
// topdump's live and TCP paths).
TEST(Stream, FlushAndSettleSeeTheWholeChunk) {
  std::string burst;
  for (int i = 0; i < 200; ++i) burst += "#TPUD2wCAP013E\r\n";
  for (const bool settle : {false, true}) {
    StreamDecoder d;
    d.feed(burst);
    settle ? d.settle() : d.flush();
    std::vector<StreamItem> items;
    StreamItem it;
    while (d.next(it)) items.push_back(std::move(it));
    ASSERT_EQ(items.size(), 200u) << (settle ? "settle" : "flush") << describe(items);
    for (const StreamItem& x : items) {
      ASSERT_EQ(x.kind, ItemKind::frame) << describe(items);
      EXPECT_EQ(x.frame.terminator, 2);
    }
    EXPECT_EQ(d.buffered(), 0u);
  }
}

// A frame's terminator counts at most 255 CR/LF bytes; the rest are a
// garbage run after it, so every byte still belongs to one item, whether the
// bytes come at once or one at a time. (The bytes past 255 were once counted
// by no item.)
TEST(Stream, CrLfRunOver255IsGarbageAfterTheFrame) {
  const std::string frame = "#TPUD2wCAP013E";
  const std::string stream = frame + std::string(300, '\r') + frame;
  for (const bool bytewise : {false, true}) {
    StreamDecoder d;
    if (bytewise) {
      for (char c : stream) d.feed(std::string_view(&c, 1));
    } else {
      d.feed(stream);
    }
    d.finish();
    std::vector<StreamItem> items;
    StreamItem it;
    while (d.next(it)) items.push_back(std::move(it));
    ASSERT_EQ(items.size(), 3u) << describe(items);
    EXPECT_EQ(items[0].kind, ItemKind::frame);
    EXPECT_EQ(items[0].frame.terminator, 255);
    EXPECT_EQ(items[1].kind, ItemKind::garbage);
    EXPECT_EQ(items[1].offset, frame.size() + 255);
    EXPECT_EQ(items[1].length, 45u);
    EXPECT_EQ(items[2].kind, ItemKind::frame);
    EXPECT_EQ(items[2].offset, frame.size() + 300);
  }
}

TEST(Stream, LargeChunkIsDecodedLazily) {
  std::string big;
  for (int i = 0; i < 100000; ++i) big += "#TPUD2wCAP013E";
  StreamDecoder d;
  d.feed(big);
  StreamItem it;
  std::size_t n = 0;
  ASSERT_TRUE(d.next(it));
  ++n;
  // Only a bounded number of items were decoded ahead.
  EXPECT_GT(d.buffered(), big.size() / 2);
  while (d.next(it)) ++n;
  d.finish();
  while (d.next(it)) ++n;
  EXPECT_EQ(n, 100000u);
}

TEST(Stream, HostileNestedHeadersStayLinear) {
  // A long #Tp frame with a bad checksum whose data is full of '#Tp' headers
  // that each declare 65535 bytes: only a bounded number are tried.
  std::string unit = std::string("#TpUD\xff\xff") + "GPS";
  std::string data;
  while (data.size() + unit.size() < 60000) data += unit;
  std::string frame = std::string("#TpUD") + static_cast<char>(data.size() >> 8) +
                      static_cast<char>(data.size() & 0xFF) + "GPS" + data + "00";
  auto items = decode_all(frame + frame);
  ASSERT_FALSE(items.empty());
  std::uint64_t covered = 0;
  for (const auto& it : items) covered += it.length;
  EXPECT_EQ(covered, 2 * frame.size());
}

// A frame that fails its checksum waits for look-ahead: other data lengths
// (the length char may lie) and frames starting inside it. On a quiet live
// link that look-ahead never comes; flush() leaves the frame held (it runs
// after every chunk), so topconf and its simulated link ended the stream
// (finish, reset) when the line went quiet. settle() decides and goes on.
TEST(Stream, SettleDecidesOnAFrameWaitingForLookAhead) {
  // declared length 6, but the checksum validates with the 4 data bytes there
  const std::string lying = with_checksum("#tpUD6wCAP0000");
  StreamDecoder d;
  d.feed(lying);
  StreamItem it;
  EXPECT_FALSE(d.next(it));  // waits: 28 bytes are needed to judge other lengths
  d.flush();
  EXPECT_FALSE(d.next(it));  // flush() does not decide
  d.settle();
  ASSERT_TRUE(d.next(it));
  EXPECT_EQ(it.kind, ItemKind::frame);
  EXPECT_EQ(it.frame.raw, lying);
  EXPECT_TRUE(toptest::has_code(it.frame.findings, FindingCode::length_mismatch));

  // a frame that fails its checksum with a '#' inside whose frame needs more
  // bytes than there are
  StreamDecoder e;
  e.feed("#tpUD6wCAP00000#tpUD");
  EXPECT_FALSE(e.next(it));
  e.settle();
  ASSERT_TRUE(e.next(it));
  EXPECT_EQ(it.frame.raw, "#tpUD6wCAP00000#");  // 'tp' is no checksum: not in the frame
  EXPECT_TRUE(toptest::has_code(it.frame.findings, FindingCode::bad_checksum));
  // the stream goes on: the rest is garbage once a frame follows it
  e.feed("#TPUD2wCAP013E");
  e.settle();
  ASSERT_TRUE(e.next(it));
  EXPECT_EQ(it.kind, ItemKind::garbage);
  EXPECT_EQ(it.offset, 16u);
  ASSERT_TRUE(e.next(it));
  EXPECT_EQ(it.frame.raw, "#TPUD2wCAP013E");
  EXPECT_EQ(it.offset, 20u);

  // an incomplete frame is not judged: it waits for its rest
  StreamDecoder f;
  f.feed("#TPUD2wCA");
  f.settle();
  EXPECT_FALSE(f.next(it));
  f.feed("P013E");
  f.settle();
  ASSERT_TRUE(f.next(it));
  EXPECT_EQ(it.frame.raw, "#TPUD2wCAP013E");
}

// The C10 Pro tool's double-checksum frame is one item whose bytes are the
// stream's, second checksum included, however the stream is cut (the frame
// was two bytes short of its item: found by fuzz_stream in CI).
TEST(Stream, DoubleChecksumFrameIsTheStreamsBytes) {
  const std::string s = "#TPUD2wCAP013E#TPUG2wPTZ056FEB#TPUD2rREC003E";
  for (std::size_t chunk : {std::size_t{1}, std::size_t{3}, std::size_t{7}, s.size()}) {
    const auto items = decode_chunked(s, {chunk});
    ASSERT_EQ(frames_of(items),
              (std::vector<std::string>{"#TPUD2wCAP013E", "#TPUG2wPTZ056FEB", "#TPUD2rREC003E"}))
        << chunk << ": " << describe(items);
    EXPECT_EQ(items[1].offset, 14u);
    EXPECT_EQ(items[1].length, 16u);
    EXPECT_EQ(items[2].offset, 30u);
    EXPECT_TRUE(toptest::has_code(items[1].frame.findings, FindingCode::double_checksum));
  }
}
