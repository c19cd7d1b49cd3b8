// Named regression inputs found while fuzzing (fuzz/regressions/<target>/).
// Each test says what is malformed about its input and what must happen;
// ctest also replays every file through its fuzz target (fuzz_<target>
// .regressions), under ASan in CI.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "../test_util.hpp"
#include "reference.hpp"
#include "top/top.hpp"

using namespace top;

namespace {

std::string regression(const std::string& target, const std::string& name) {
  const std::filesystem::path p =
      std::filesystem::path(TOPKIT_SOURCE_DIR) / "fuzz" / "regressions" / target / name;
  std::ifstream in(p, std::ios::binary);
  EXPECT_TRUE(in) << p;
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

// fuzz/regressions/stream/quadratic-wait-inside-failing-ext16-frame
//
// Malformed: a #Tp frame declaring 60000 data bytes whose checksum is "ZZ";
// 20 bytes before its end its data holds a second #Tp header declaring
// 65535 bytes, and 66000 more bytes follow; the file holds four copies.
// (The first two bytes are the stream target's chunk prefix: one chunk size,
// 1 byte.)
// The decoder must hold the failing frame while the inner one may still turn
// out valid. It used to parse the whole 60 KB frame again for every byte
// that arrived while it waited: this file fed a byte at a time took 13 s at
// -O2 (quadratic), so a serial link could stall the analyzer; now 20 ms.
// The replay test fuzz_stream.regressions has a 10 s timeout for this. It must now keep
// the parse and resume at the inner '#', and give the same items as when the
// stream comes in one piece: the failing frame (bad-checksum; "ZZ" is not a
// checksum, so the frame ends with its data) and the rest as garbage.
TEST(FuzzRegression, StreamWaitInsideFailingFrameIsNotReparsed) {
  const std::string file = regression("stream", "quadratic-wait-inside-failing-ext16-frame");
  ASSERT_GT(file.size(), 2u);
  const std::string stream = file.substr(2);

  const auto whole = toptest::decode_all(stream);
  ASSERT_GE(whole.size(), 2u);
  EXPECT_EQ(whole[0].kind, ItemKind::frame);
  EXPECT_EQ(whole[0].offset, 0u);
  EXPECT_EQ(whole[0].length, 10u + 60000u);
  EXPECT_TRUE(whole[0].frame.has(FindingCode::bad_checksum));
  std::uint64_t covered = 0;
  for (const auto& it : whole) {
    EXPECT_EQ(it.offset, covered);
    covered += it.length;
  }
  EXPECT_EQ(covered, stream.size());

  // One byte at a time.
  const auto split = toptest::decode_chunked(stream, {1});
  ASSERT_EQ(split.size(), whole.size());
  for (std::size_t i = 0; i < whole.size(); ++i) {
    EXPECT_EQ(split[i].kind, whole[i].kind) << i;
    EXPECT_EQ(split[i].offset, whole[i].offset) << i;
    EXPECT_EQ(split[i].length, whole[i].length) << i;
  }
}

// fuzz/regressions/stream/garbage-run-over-64k-in-one-chunk
//
// Malformed: 70000 bytes with no '#' at all (after the target's prefix: one
// chunk size, 7 bytes). A garbage run is reported when it reaches 64 KiB.
// Fed in one piece the whole span was added at once and came out as one
// 70000-byte item; fed in chunks it came out as 65536 + 4464: the items
// depended on the split. They must be 65536 + 4464 both ways.
TEST(FuzzRegression, GarbageRunsEndAt64KiBHoweverTheBytesArrive) {
  const std::string file = regression("stream", "garbage-run-over-64k-in-one-chunk");
  ASSERT_GT(file.size(), 2u);
  const std::string stream = file.substr(2);
  for (const auto& items : {toptest::decode_all(stream), toptest::decode_chunked(stream, {7})}) {
    ASSERT_EQ(items.size(), 2u);
    EXPECT_EQ(items[0].kind, ItemKind::garbage);
    EXPECT_EQ(items[0].offset, 0u);
    EXPECT_EQ(items[0].length, 65536u);
    EXPECT_EQ(items[1].offset, 65536u);
    EXPECT_EQ(items[1].length, 70000u - 65536u);
  }
}

// fuzz/regressions/differential/zfp-focus-placeholder-nnnn
//
// Malformed: "#tpUM8wZFP!tpUNNNNDA", a Topotek ZFP (zoom & focus position)
// whose zoom field "!tpU" is not hex and whose focus field is "NNNN". The
// fault was in the reference parser, not the library: Topotek 3.x says "if
// only zoom is set, fill focus with 'N''N''N''N'", which the catalog models
// and the reference did not. Both must now read focus as the placeholder and
// zoom as invalid, so the differential target agrees.
TEST(FuzzRegression, ZfpFocusPlaceholderIsNotAValue) {
  const std::string in = regression("differential", "zfp-focus-placeholder-nnnn");
  const auto g = topref::parse(in);
  ASSERT_TRUE(g.has_value());
  const topref::Layout* l = topref::find_layout("topotek", *g);
  ASSERT_NE(l, nullptr);
  const auto ref = topref::decode(*l, g->data);
  ASSERT_EQ(ref.size(), 2u);
  EXPECT_FALSE(ref[0].valid);
  EXPECT_TRUE(ref[1].valid && ref[1].none);

  const ParseResult r = parse_exact(in);
  ASSERT_EQ(r.status, ParseStatus::frame);
  DecodeOptions o;
  o.dialect = Dialect::topotek;
  const Decoded d = decode(r.frame, o);
  ASSERT_EQ(d.fields.size(), 2u);
  EXPECT_FALSE(d.fields[0].valid);
  EXPECT_TRUE(d.fields[1].valid && d.fields[1].none);
}
