// TcpReassembly (session/tcp_reassembly.hpp) driven directly: segments in,
// what it hands on (bytes, findings, gaps) recorded in order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "session/tcp_reassembly.hpp"

namespace topdump {
namespace {

// Every call as one line: "bytes <text> @<record>+<offset>",
// "finding <code> @<record>+<offset>: <message>", "gap <n>".
struct Recorder final : TcpOutput {
  std::vector<std::string> log;
  std::string stream;  // every byte handed on, in order
  void bytes(std::string_view b, std::uint64_t record, std::uint64_t offset,
             std::int64_t) override {
    log.push_back("bytes " + std::string(b) + " @" + std::to_string(record) + "+" +
                  std::to_string(offset));
    stream.append(b);
  }
  void finding(ACode code, std::string message, std::uint64_t record, std::uint64_t offset,
               std::int64_t) override {
    log.push_back("finding " + std::string(to_string(code)) + " @" + std::to_string(record) + "+" +
                  std::to_string(offset) + ": " + message);
  }
  void gap(std::uint64_t skipped, std::int64_t) override {
    log.push_back("gap " + std::to_string(skipped));
  }
};

constexpr std::uint32_t kIsn = 1000;

TEST(TcpReassembly, InOrderSegmentsPassStraightThrough) {
  TcpReassembly r;
  Recorder out;
  r.segment(kIsn, true, "", 1, 40, 0, out);  // SYN: the data starts at kIsn + 1
  r.segment(kIsn + 1, false, "#TPUG2", 2, 54, 0, out);
  r.segment(kIsn + 7, false, "rGAC", 3, 54, 0, out);
  EXPECT_EQ(out.log, (std::vector<std::string>{"bytes #TPUG2 @2+54", "bytes rGAC @3+54"}));
  EXPECT_EQ(r.stream_offset(), 10u);
  EXPECT_EQ(r.held_bytes(), 0u);
}

TEST(TcpReassembly, RetransmissionIsReportedAndNotDeliveredTwice) {
  TcpReassembly r;
  Recorder out;
  r.segment(kIsn, false, "abcdef", 1, 0, 0, out);
  r.segment(kIsn, false, "abcdef", 2, 0, 0, out);
  EXPECT_EQ(out.stream, "abcdef");
  ASSERT_EQ(out.log.size(), 2u);
  EXPECT_EQ(out.log[1],
            "finding tcp-retransmission @2+0: 6 bytes at stream offset 0 seen again "
            "(retransmission)");
}

TEST(TcpReassembly, OverlapKeepsTheFirstCopyAndDeliversOnlyTheNewBytes) {
  TcpReassembly r;
  Recorder out;
  r.segment(kIsn, false, "abcdef", 1, 10, 0, out);
  // bytes 4-5 again, but different, then two new bytes
  r.segment(kIsn + 4, false, "XYgh", 2, 20, 0, out);
  EXPECT_EQ(out.stream, "abcdefgh");
  EXPECT_EQ(out.log,
            (std::vector<std::string>{
                "bytes abcdef @1+10",
                "finding tcp-overlap-differs @2+20: 2 bytes at stream offset 4 seen again with "
                "different content; the first copy is kept",
                "bytes gh @2+22"}));
}

TEST(TcpReassembly, OutOfOrderSegmentIsHeldUntilTheBytesBeforeItArrive) {
  TcpReassembly r;
  Recorder out;
  r.segment(kIsn, false, "ab", 1, 0, 0, out);
  r.segment(kIsn + 4, false, "ef", 2, 0, 0, out);  // ahead by 2
  EXPECT_EQ(r.held_bytes(), 2u);
  EXPECT_EQ(r.held_segments(), 1u);
  r.segment(kIsn + 2, false, "cd", 3, 0, 0, out);
  EXPECT_EQ(out.stream, "abcdef");
  EXPECT_EQ(out.log, (std::vector<std::string>{
                         "bytes ab @1+0",
                         "finding tcp-out-of-order @2+0: 2 bytes arrived 2 bytes ahead of the "
                         "stream; held",
                         "bytes cd @3+0", "bytes ef @2+0"}));
  EXPECT_EQ(r.held_bytes(), 0u);
}

TEST(TcpReassembly, HeldCopyKeepsTheLongerOne) {
  TcpReassembly r;
  Recorder out;
  r.segment(kIsn, false, "ab", 1, 0, 0, out);
  r.segment(kIsn + 4, false, "ef", 2, 0, 0, out);
  r.segment(kIsn + 4, false, "efgh", 3, 0, 0, out);
  EXPECT_EQ(out.log.back(),
            "finding tcp-retransmission @3+0: 4 held bytes seen again (retransmission)");
  EXPECT_EQ(r.held_bytes(), 4u);
  r.segment(kIsn + 2, false, "cd", 4, 0, 0, out);
  EXPECT_EQ(out.stream, "abcdefgh");
}

TEST(TcpReassembly, GapAtTheEndSkipsTheMissingBytesAndRestarts) {
  TcpReassembly r;
  Recorder out;
  r.segment(kIsn, false, "abc", 1, 0, 0, out);
  r.segment(kIsn + 8, false, "xyz", 2, 7, 0, out);  // 5 bytes never captured
  r.finish(0, out);
  EXPECT_EQ(out.stream, "abcxyz");
  ASSERT_EQ(out.log.size(), 5u);
  EXPECT_EQ(out.log[2],
            "finding tcp-gap @2+7: 5 bytes missing at stream offset 3; decoding restarts after "
            "the gap");
  EXPECT_EQ(out.log[3], "gap 5");
  EXPECT_EQ(out.log[4], "bytes xyz @2+7");
  EXPECT_EQ(r.stream_offset(), 11u);  // 3 + 5 skipped + 3
}

TEST(TcpReassembly, HoldingPastTheLimitDropsToAGap) {
  TcpReassembly r(4);
  Recorder out;
  r.segment(kIsn, false, "ab", 1, 0, 0, out);
  r.segment(kIsn + 10, false, "abcde", 2, 0, 0, out);  // 5 held bytes > 4
  EXPECT_EQ(out.stream, "ababcde");
  EXPECT_NE(std::find(out.log.begin(), out.log.end(),
                      "finding reassembly-limit @2+0: 5 bytes in 1 segments held past the limit "
                      "of 4 bytes"),
            out.log.end());
  EXPECT_NE(std::find(out.log.begin(), out.log.end(), "gap 8"), out.log.end());
  EXPECT_EQ(r.held_bytes(), 0u);
}

TEST(TcpReassembly, SequenceNumbersWrapAround) {
  TcpReassembly r;
  Recorder out;
  r.segment(0xFFFFFFFEu, false, "ab", 1, 0, 0, out);
  r.segment(0x00000002u, false, "ef", 2, 0, 0, out);  // ahead across the wrap
  r.segment(0x00000000u, false, "cd", 3, 0, 0, out);
  EXPECT_EQ(out.stream, "abcdef");
}

TEST(TcpReassembly, SynAfterDataDoesNotMoveTheStream) {
  TcpReassembly r;
  Recorder out;
  r.segment(kIsn, false, "ab", 1, 0, 0, out);
  r.segment(kIsn - 1, true, "", 2, 0, 0, out);  // a late SYN retransmission
  r.segment(kIsn + 2, false, "cd", 3, 0, 0, out);
  EXPECT_EQ(out.stream, "abcd");
  EXPECT_EQ(out.log.size(), 2u);
}

}  // namespace
}  // namespace topdump
