// A real Topotek camera on UDP, as topdump pairs it: a device that answers
// the client's host from an ephemeral port, fans each reply out to several
// ports and takes writes silently (docs/FIELD.md; captures/sip-bench for the
// recorded sessions themselves, sip_bench_test.cpp).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "findings/afindings.hpp"
#include "test_support.hpp"
#include "top/frame.hpp"

namespace topdump::test {
namespace {

// A real Topotek camera on UDP (docs/FIELD.md ephemeral-reply-port, fan-out,
// duplicate-to-client-port, silent-writes; captures/sip-bench): it answers
// the bench's requests to 9003 from an ephemeral port, to the asking port
// and twice to 9004, and takes writes without a word.
struct SipLinks {
  Recorder rec;
  std::unique_ptr<Analyzer> a;
  Endpoint cam = ep4(108, 9003), reply = ep4(108, 57707);
  std::uint64_t record = 0;
  explicit SipLinks(AnalyzerOptions o = {}) { a = std::make_unique<Analyzer>(o, rec); }
  void send(std::int64_t us, std::uint16_t port, const std::string& f) {
    a->datagram(T + us, ep4(167, port), cam, top::with_checksum(f), ++record, 28);
  }
  void recv(std::int64_t us, std::uint16_t port, const std::string& f,
            const Endpoint* from = nullptr) {
    a->datagram(T + us, from ? *from : reply, ep4(167, port), top::with_checksum(f), ++record, 28);
  }
  // a reply to 8080, then to 9004 twice, as the camera sent them
  void fanned(std::int64_t us, const std::string& f) {
    recv(us, 8080, f);
    recv(us + 40, 9004, f);
    recv(us + 60, 9004, f);
  }
  const Recorder::F& frame(std::uint64_t n) const { return rec.frames.at(n - 1); }
  // What each frame was, in order: "r1" a reply to frame 1, "c3" a copy of
  // frame 3, "-" neither.
  std::string links() const {
    std::string t;
    for (const auto& f : rec.frames)
      t += (t.empty() ? "" : " ") + (f.copy_of    ? "c" + std::to_string(f.copy_of)
                                     : f.reply_to ? "r" + std::to_string(f.reply_to)
                                                  : std::string("-"));
    return t;
  }
  const NoteEvent* note(ACode c) const {
    for (const auto& n : rec.notes)
      if (n.note.code == c) return &n;
    return nullptr;
  }
  // "from > to" of the note's JSON line
  std::string note_ends(ACode c) const {
    for (std::size_t i = 0; i < rec.notes.size(); ++i)
      if (rec.notes[i].note.code == c) {
        const auto j = nlohmann::json::parse(rec.note_json[i].first);
        return j.value("from", "") + " > " + j.value("to", "");
      }
    return "";
  }
};

TEST(RealSip, RepliesFromAnEphemeralPortToSeveralPortsAreOneReplyEach) {
  SipLinks b;
  b.send(0, 8080, "#TPPD2rTRC00");
  b.fanned(1'900, "#TPDP2rTRC00");
  b.send(120'000, 8080, "#TPPG2rGIC00");
  b.fanned(228'000, "#tpGPCrGIAFF25FFF8FFFE");
  b.a->finish();
  ASSERT_EQ(b.rec.frames.size(), 8u);
  // each read is paired with the first copy, latency to it
  // the other deliveries are copies of it, neither paired nor unsolicited
  EXPECT_EQ(b.links(), "- r1 c2 c2 - r5 c6 c6");
  EXPECT_EQ(b.frame(2).latency, 1'900);
  EXPECT_EQ(b.frame(6).latency, 108'000);
  for (const auto& f : b.rec.frames) {
    EXPECT_FALSE(has_code(f, "unsolicited")) << f.n;
    if (f.copy_of) {
      EXPECT_EQ(f.reply_to, 0u) << f.n;
    }
  }
  const Stats& s = b.a->stats();
  EXPECT_EQ(pairing_counts(s), (Counts{2, 2, 0, 0}));
  EXPECT_EQ(s.copies, 4u);
  EXPECT_EQ(s.conversations.size(), 1u);  // every port pair of the two hosts, one conversation
  // what the device did, once each, info
  const NoteEvent* rp = b.note(ACode::reply_port);
  ASSERT_NE(rp, nullptr);
  EXPECT_EQ(rp->note.severity, top::Severity::info);
  EXPECT_EQ(rp->note.count, 2u);
  EXPECT_NE(rp->note.message.find("from port 57707"), std::string::npos) << rp->note.message;
  // each note sits at the frame it names, between that frame's own ends
  // (as written when it came: the ends are the session's, gone after finish)
  EXPECT_EQ(b.note_ends(ACode::reply_port), "10.0.0.108:57707 > 10.0.0.167:8080");
  const NoteEvent* fo = b.note(ACode::fan_out);
  ASSERT_NE(fo, nullptr);
  EXPECT_EQ(fo->note.count, 4u);
  EXPECT_NE(fo->note.message.find("copies to port 9004"), std::string::npos) << fo->note.message;
  EXPECT_EQ(b.note_ends(ACode::fan_out), "10.0.0.108:57707 > 10.0.0.167:9004");
  EXPECT_EQ(b.rec.count_note(ACode::reply_port) + b.rec.count_note(ACode::fan_out), 2u);
  EXPECT_FALSE(b.rec.has_note(acode_of(top::Diagnosis::silent_device)));
}

// The deliveries of two datagrams may interleave (PixEagle bench,
// 20260918T060610Z-rotated-point 06:06:14.538870: TRC, its copy, an OFT, the
// TRC's second copy, the OFT's copy); the same bytes 30 ms later are a frame
// of their own (ODZ during zoom, 20260917T050955Z-zoom).
TEST(RealSip, InterleavedCopiesAreCopiesAndALaterSameFrameIsNot) {
  SipLinks b;
  const std::string trc = "#TPDP2rTRC02", oft = "#TPDP2rTRA11";
  b.send(0, 8080, "#TPPD2rTRC00");
  b.send(10, 8080, "#TPPD2rTRA00");
  b.recv(1'000, 8080, trc);
  b.recv(1'040, 9004, trc);
  b.recv(1'070, 8080, oft);
  b.recv(1'080, 9004, trc);
  b.recv(1'090, 9004, oft);
  b.send(200'000, 8080, "#TPPD2rTRC00");
  b.recv(201'000, 8080, trc);  // the same bytes, 200 ms later: an answer
  b.a->finish();
  EXPECT_EQ(b.links(), "- - r1 c3 r2 c3 c5 - r8");
  EXPECT_EQ(b.a->stats().unsolicited, 0u);
}

// A client that asks again within the copy window gets an answer of its
// own, the same bytes as the last (topsim on loopback answers in 0.1 ms);
// a copy that arrives while an older read the device never answered is
// pending stays a copy (PixEagle bench, 20260917T071854Z-ai-observe: the GAC
// read at 07:19:02.634 got nothing, the next one's reply went to 8080 and
// twice to 9004).
TEST(RealSip, AReadAskedAgainWithinTheWindowGetsItsOwnAnswer) {
  SipLinks b;
  b.send(0, 8080, "#TPPD2rTRC00");
  b.recv(100, 8080, "#TPDP2rTRC00");
  b.send(200, 8080, "#TPPD2rTRC00");
  b.recv(300, 8080, "#TPDP2rTRC00");
  b.recv(340, 9004, "#TPDP2rTRC00");
  b.send(400'000, 8080, "#TPPG2rGAC00");  // never answered
  b.send(800'000, 8080, "#TPPG2rGAC00");
  b.fanned(908'000, "#tpGPCrGAC01220138024F");
  b.a->finish();
  EXPECT_EQ(b.links(), "- r1 - r3 c4 - - r7 c8 c8");
  EXPECT_EQ(b.a->stats().unanswered, 1u);  // the GAC read of frame 6
}

// Topotek 2 defines w as set/control and gives these writes no reply; the
// camera echoed none of its 361 (docs/FIELD.md silent-writes): no write is
// unanswered, and one info note counts them. A camera that sent nothing at
// all is no evidence that it took them.
TEST(RealSip, WritesTakenWithoutAWordAreNotedOnceNeverUnanswered) {
  SipLinks b(unanswered_after_100ms());
  b.send(0, 8080, "#TPPG2wPTZ00");
  b.send(30'000, 8080, "#TPPM2wZMC00");
  b.send(60'000, 8080, "#TPPD2rTRC00");
  b.fanned(61'000, "#TPDP2rTRC00");
  b.send(500'000, 8080, "#TPPD2wTRC02");
  b.send(900'000, 8080, "#TPPD2rTRC00");
  b.fanned(901'000, "#TPDP2rTRC01");
  b.a->finish();
  EXPECT_FALSE(b.rec.has_note(ACode::unanswered));
  EXPECT_EQ(b.a->stats().unanswered, 0u);
  const NoteEvent* n = b.note(ACode::silent_writes);
  ASSERT_NE(n, nullptr);
  EXPECT_EQ(n->note.count, 3u);
  EXPECT_EQ(n->note.severity, top::Severity::info);
  EXPECT_NE(n->note.message.find("(PTZ, ZMC, TRC)"), std::string::npos) << n->note.message;
  // the TRC read after the TRC 02 write is answered by its own reply
  EXPECT_EQ(b.frame(9).reply_to, 8u);

  SipLinks dead(unanswered_after_100ms());
  dead.send(0, 8080, "#TPPG2wPTZ00");
  dead.send(500'000, 8080, "#TPPG2wPTZ00");
  dead.a->finish();
  EXPECT_FALSE(dead.rec.has_note(ACode::silent_writes));
}

// The bench's pan pulse names the source U (the UART) over UDP, and the
// camera moved (20260917T045437Z-pan 04:54:39.435460): the deviation is the
// client's, named whether or not the device answered.
TEST(RealSip, AUartSourceOverTheNetworkIsTheClientsWhateverTheDeviceDid) {
  SipLinks b;
  b.send(0, 8080, "#TPUG2wGSY05");
  b.send(150'000, 8080, "#TPPG2wPTZ00");
  b.send(200'000, 8080, "#TPPG2rGAC00");
  b.fanned(308'000, "#tpGPCrGACFF1306D7029E");
  b.a->finish();
  const NoteEvent* n = b.note(acode_of(top::Diagnosis::reply_interface));
  ASSERT_NE(n, nullptr);
  EXPECT_EQ(n->note.severity, top::Severity::warning);
  EXPECT_EQ(n->note.frame, 1u);
  EXPECT_NE(n->note.message.find("the client sent 1 request with source U"), std::string::npos)
      << n->note.message;
  EXPECT_NE(n->note.message.find("none that expects an answer went unanswered"), std::string::npos)
      << n->note.message;
  EXPECT_FALSE(b.rec.has_note(ACode::unanswered));
}

// On one host (a loopback capture) only the client's own ports and the
// dialect's client port (9004) are taken: an unrelated pair of the same
// address keeps its own conversation, and so does a SkyDroid device of the
// camera's host on its own port.
TEST(RealSip, OnlyTheDevicesPairsAreTaken) {
  Recorder rec;
  Analyzer a(AnalyzerOptions{}, rec);
  auto lo = [](std::uint16_t port) {
    Endpoint e = Endpoint::ipv4(0x7F000001u, port);
    return e;
  };
  std::uint64_t r = 0;
  a.datagram(T, lo(8080), lo(9003), top::with_checksum("#TPPD2rTRC00"), ++r, 28);
  a.datagram(T + 1000, lo(40000), lo(8080), top::with_checksum("#TPDP2rTRC00"), ++r, 28);
  a.datagram(T + 2000, lo(16000), lo(17000), top::with_checksum("#TPUD2rVER00"), ++r, 28);
  a.datagram(T + 3000, lo(17000), lo(16000), top::with_checksum("#tpDU6rVERV1.1.5"), ++r, 28);
  a.datagram(T + 4000, lo(5000), lo(40001), top::with_checksum("#TPGU2wPTZ05"), ++r, 28);
  a.finish();
  ASSERT_EQ(rec.frames.size(), 5u);
  EXPECT_EQ(rec.frames[1].reply_to, 1u);  // the reply port 40000 is the camera's
  EXPECT_EQ(rec.frames[3].reply_to, 3u);  // 16000 <> 17000 is a pair of its own
  const Stats& s = a.stats();
  EXPECT_EQ(s.conversations.size(), 3u);
}

// A request the capture's end cut off before its slowest answer was due is
// not unanswered (a bench that stopped listening 100 ms after a GAC read
// its camera answers in 105-112 ms); one the capture saw long enough is.
TEST(RealSip, ARequestTheEndCutOffIsNotUnanswered) {
  SipLinks b;
  b.send(0, 8080, "#TPPG2rGAC00");
  b.fanned(108'000, "#tpGPCrGACFF1306D7029E");
  b.send(400'000, 8080, "#TPPG2rGAC00");
  b.send(450'000, 8080, "#TPPG2wPTZ00");  // the last frame: 50 ms after the read
  b.a->finish();
  EXPECT_FALSE(b.rec.has_note(ACode::unanswered));

  SipLinks c;
  c.send(0, 8080, "#TPPG2rGAC00");
  c.fanned(108'000, "#tpGPCrGACFF1306D7029E");
  c.send(400'000, 8080, "#TPPG2rGAC00");
  c.send(600'000, 8080, "#TPPG2wPTZ00");  // 200 ms after: the answer was due
  c.a->finish();
  ASSERT_EQ(c.rec.count_note(ACode::unanswered), 1u);
  EXPECT_EQ(c.rec.notes.front().note.frame, 5u);
}

}  // namespace
}  // namespace topdump::test

namespace topdump::test {
namespace {

// A reply to a query is never a stream sample: a late answer of an
// identifier the device answered reads of is a late answer (unsolicited),
// not the first push of a stream that could then stall (a bench that polls
// GAC read "stream-stalled" for its pauses).
TEST(RealSipStreams, ALateAnswerIsNoStream) {
  Fixture f;
  AnalyzerOptions o;
  o.timeout_us = 200'000;
  f.reset(o);
  f.client = ep4(167, 8080);
  f.device = ep4(108, 9003);
  f.up(0, top::with_checksum("#TPPG2rGAC00"));
  f.down(108, top::with_checksum("#tpGPCrGACFF1306D7029E"));
  f.up(400, top::with_checksum("#TPPG2rGAC00"));  // answered 300 ms late
  f.down(700, top::with_checksum("#tpGPCrGACFF0A06D702A9"));
  f.up(1200, top::with_checksum("#TPPG2rGAC00"));
  f.down(1308, top::with_checksum("#tpGPCrGACFF0206D702AD"));
  f.a->finish();
  EXPECT_TRUE(f.a->stats().conversations.at(0).streams.empty());
  EXPECT_EQ(f.a->stats().unsolicited, 1u);
  EXPECT_EQ(f.a->stats().paired, 2u);
}

}  // namespace
}  // namespace topdump::test
