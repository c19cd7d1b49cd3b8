// topsim's device model: answers, state and streams, on an injected clock.
#include "sim/device.hpp"

#include <gtest/gtest.h>

#include <array>

#include "sim/intake.hpp"

namespace {

using topsim::Device;
using topsim::Link;

std::vector<std::string> ask_text(Device& d, std::string_view body, std::uint64_t t = 0,
                                  Link link = Link::network) {
  return topsim::handle_datagram(d, top::with_checksum(body), link, t);
}

top::Frame parsed(const std::string& s) {
  auto r = top::parse_exact(s);
  EXPECT_EQ(r.status, top::ParseStatus::frame) << s;
  return r.frame;
}

// A frame's identifier, header kind and addresses, checked together.
void expect_frame(const top::Frame& f, std::string_view ident, top::Header header, char src,
                  char dst) {
  EXPECT_EQ(f.ident_view(), ident);
  EXPECT_EQ(f.header, header) << ident;
  EXPECT_EQ(f.src, src) << ident;
  EXPECT_EQ(f.dst, dst) << ident;
}

TEST(Device, WriteIsEchoedWithSwappedAddresses) {
  Device d(top::Model::c12);
  auto out = ask_text(d, "#TPUG6wGAYEF0732");
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], top::with_checksum("#TPGU6wGAYEF0732"));
}

TEST(Device, ReadIsAnsweredWithData) {
  Device d(top::Model::c12);
  auto out = ask_text(d, "#TPUD2rVER00");
  ASSERT_EQ(out.size(), 1u);
  auto f = parsed(out[0]);
  EXPECT_EQ(f.src, 'D');
  EXPECT_EQ(f.dst, 'U');
  EXPECT_EQ(f.ident_view(), "VER");
  EXPECT_EQ(f.data(), "V1.0.78");  // the form ArduPilot's SkyDroid driver parses
}

TEST(Device, InvalidCommandGetsEreOnSkyDroid) {
  Device d(top::Model::c12);
  auto out = ask_text(d, "#TPUM2rZZZ00");
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], "#TPMU2wERE!!30");  // the document's own example
  // Wrong length and unsupported on the model: ERE too.
  EXPECT_EQ(parsed(ask_text(d, "#TPUG5wGAYEF073").at(0)).ident_view(), "ERE");
  Device c13(top::Model::c13);
  EXPECT_EQ(parsed(ask_text(c13, "#TPUG6wGAYEF0732").at(0)).ident_view(), "ERE");
}

TEST(Device, BadChecksumGetsSilence) {
  Device d(top::Model::c12);
  EXPECT_TRUE(topsim::handle_datagram(d, "#TPUG6wGAYEF073200", Link::network, 0).empty());
  EXPECT_TRUE(topsim::handle_datagram(d, "#TPUG6wGAYEF0732", Link::network, 0).empty());
}

TEST(Device, TopotekAnswersTheInterfaceOfTheSourceByte) {
  Device d(top::Model::sip);
  // UDP request with source U: no answer (field notes, Topotek 2).
  EXPECT_TRUE(ask_text(d, "#TPUG2rGIC00", 0, Link::network).empty());
  EXPECT_TRUE(ask_text(d, "#TPPG2rGIC00", 0, Link::uart).empty());
  auto net = ask_text(d, "#TPPG2rGIC00", 0, Link::network);
  ASSERT_EQ(net.size(), 1u);
  EXPECT_EQ(parsed(net[0]).dst, 'P');
  auto uart = ask_text(d, "#TPUG2rGIC00", 0, Link::uart);
  ASSERT_EQ(uart.size(), 1u);
  EXPECT_EQ(parsed(uart[0]).dst, 'U');
  // Unknown identifier on Topotek: silence, no ERE.
  EXPECT_TRUE(ask_text(d, "#TPPD2rZZZ00").empty());
}

TEST(Device, TopotekRecAndCapReplyWithFileIndex) {
  Device d(top::Model::sip);
  auto start = ask_text(d, "#TPPD2wREC01");
  ASSERT_EQ(start.size(), 1u);
  EXPECT_EQ(start[0], top::with_checksum("#tpDPAwREC1100000001"));
  EXPECT_TRUE(d.recording());
  EXPECT_EQ(parsed(ask_text(d, "#TPPD2rREC00").at(0)).data(), "01");
  auto stop = ask_text(d, "#TPPD2wREC0A");  // toggle
  EXPECT_EQ(stop.at(0), top::with_checksum("#tpDPAwREC0000000001"));
  EXPECT_FALSE(d.recording());
  EXPECT_EQ(ask_text(d, "#TPPD2wCAP01").at(0), top::with_checksum("#tpDPAwCAP1100000002"));
  EXPECT_EQ(d.file_index(), 2u);
}

// The document's signs (the C12's field sign traits: field_test.cpp).
topsim::DeviceOptions document_signs() {
  topsim::DeviceOptions o;
  o.yaw_inverted = false;
  o.pitch_inverted = false;
  return o;
}

TEST(Device, GimbalMovesTowardTargetAtCommandedSpeed) {
  Device d(top::Model::c12, document_signs());
  // GAY +10.00 deg (03E8) at 5.0 deg/s (32).
  ask_text(d, "#TPUG6wGAY03E832", 0);
  d.advance(1000000);
  EXPECT_NEAR(d.yaw().angle, 5.0, 1e-6);
  d.advance(2500000);
  EXPECT_NEAR(d.yaw().angle, 10.0, 1e-6);
  EXPECT_FALSE(d.yaw().has_target);
  // GAM: yaw -20, pitch +30 at 9.9 deg/s (63).
  ask_text(d, "#TPUGCwGAMF830630BB863", 3000000);
  d.advance(13000000);
  EXPECT_NEAR(d.yaw().angle, -20.0, 1e-6);
  EXPECT_NEAR(d.pitch().angle, 30.0, 1e-6);
}

TEST(Device, SpeedCommandsIntegrateWithinLimitsAndExpire) {
  topsim::DeviceOptions o = document_signs();
  o.speed_hold_ms = 1000;
  Device d(top::Model::c12, o);
  // GSY +20 steps = +10 deg/s.
  ask_text(d, "#TPUG2wGSY14", 0);
  d.advance(500000);
  EXPECT_NEAR(d.yaw().angle, 5.0, 1e-6);
  d.advance(3000000);  // the command held for 1 s only
  EXPECT_NEAR(d.yaw().angle, 10.0, 1e-6);
  // Refreshed at 50 Hz for 12 s at +63.5 deg/s: clamped at the +90 limit.
  for (std::uint64_t t = 3000000; t < 15000000; t += 20000) ask_text(d, "#TPUG2wGSP7F", t);
  d.advance(15000000);
  EXPECT_DOUBLE_EQ(d.pitch().angle, 90.0);
}

TEST(Device, GaaStreamsGacAtTheRequestedRate) {
  Device d(top::Model::c12);
  ask_text(d, "#TPUG2wGAA0A", 0);  // 10 Hz
  std::vector<std::string> out;
  std::uint64_t t = 0;
  int n = 0;
  while ((t = d.next_timer()) <= 1000000) {
    d.poll(t, out);
    ++n;
  }
  EXPECT_EQ(n, 10);
  ASSERT_FALSE(out.empty());
  // The field profile's C12 form (#tpUGCrGAC, client first: docs/FIELD.md);
  // field_test.cpp checks every profile's form.
  expect_frame(parsed(out[0]), "GAC", top::Header::variable, 'U', 'G');
  ask_text(d, "#TPUG2wGAA00", 1000000);
  EXPECT_EQ(d.next_timer(), std::numeric_limits<std::uint64_t>::max());
}

// The document: GIA 01 switches GIC pushes on (Topotek 4.3.6). The field:
// GIA frames (ArduPilot's driver, a real SIP; device_topotek_test.cpp).
TEST(Device, TopotekGiaStreamsGicInTheDocument) {
  topsim::DeviceOptions o;
  o.profile = top::Profile::document;
  Device d(top::Model::sip, o);
  ask_text(d, "#TPPG2wGIA01", 0);
  std::vector<std::string> out;
  d.poll(d.next_timer(), out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(parsed(out[0]).ident_view(), "GIC");
  EXPECT_EQ(parsed(out[0]).dst, 'P');
}

TEST(Device, SettingsReadBackWhatWasSet) {
  Device d(top::Model::c12);
  ask_text(d, "#tpUDAwIPV10.0.0.9");
  EXPECT_EQ(parsed(ask_text(d, "#TPUD2rIPV00").at(0)).data(), "10.0.0.9");
  ask_text(d, "#TPUD2wAWB15");
  EXPECT_EQ(parsed(ask_text(d, "#TPUD2rAWB00").at(0)).data(), "15");
  ask_text(d, "#TPUD2wREC01");
  EXPECT_EQ(parsed(ask_text(d, "#TPUD2rREC00").at(0)).data(), "01");
  EXPECT_EQ(parsed(ask_text(d, "#TPUD2rSDC00").at(0)).data(), "0EA601D4C0");
}

TEST(Device, NoSwapAndTmpQuirkOptions) {
  topsim::DeviceOptions o;
  o.swap_addresses = false;
  o.tmp_quirk = true;
  Device d(top::Model::c12, o);
  EXPECT_EQ(ask_text(d, "#TPUG2wGAA00").at(0), top::with_checksum("#TPUG2wGAA00"));
  auto tmp = parsed(ask_text(d, "#tpUD0rTMP").at(0));
  EXPECT_TRUE(tmp.has(top::FindingCode::tmp_quirk));
}

// The Topotek 12.2 firmware form byte for byte: a two-digit length, control
// w, the addresses swapped (or not, with no-swap).
TEST(Device, TmpQuirkIsTheFirmwareFormByteForByte) {
  topsim::DeviceOptions o;
  o.tmp_quirk = true;
  Device swapped(top::Model::c12, o);
  EXPECT_EQ(ask_text(swapped, "#tpUD0rTMP").at(0), "#tpDU16wTMP0100200300400500600700AB");
  o.swap_addresses = false;
  Device kept(top::Model::c12, o);
  EXPECT_EQ(ask_text(kept, "#tpUD0rTMP").at(0), "#tpUD16wTMP0100200300400500600700AB");
}

TEST(Device, HandlerSurvivesHostileBytes) {
  Device d(top::Model::c12);
  std::string junk;
  for (int i = 0; i < 4096; ++i) junk.push_back(static_cast<char>((i * 131) & 0xFF));
  junk += "#TP#tp#tP\xFF\xFF#Tp\xFF\xFF";
  EXPECT_NO_THROW(topsim::handle_datagram(d, junk, Link::network, 0));
  topsim::Session s(d, Link::uart, false);
  std::vector<std::string> out;
  const std::string f = top::with_checksum("#TPUG2wGAA00");
  for (char c : f) s.feed(std::string_view(&c, 1), 0, out);  // split at every byte
  EXPECT_EQ(out.size(), 1u);
}

}  // namespace

namespace {

// The Topotek commands the simulator answers from its own state (its
// handler table) are all in the catalog: the simulator no longer needs a
// fallback for a catalog without them.
TEST(Device, TopotekStateCommandsAreCatalogued) {
  for (const char* id : {"REC", "CAP", "GIA", "GIC", "GAA"})
    EXPECT_NE(top::find_command(top::Dialect::topotek, id), nullptr) << id;
}

}  // namespace

// ---- Topotek as ArduPilot's AP_Mount_Topotek and a real SIP show it
// (docs/sources/ardupilot.md sections 1 and 8.1; sim/src/device_topotek.cpp).
namespace {

// The frames a device pushes up to `t`, polled at every timer.
std::vector<std::string> run_until(Device& d, std::uint64_t t) {
  std::vector<std::string> out;
  while (d.next_timer() <= t) d.poll(d.next_timer(), out);
  d.advance(t);
  return out;
}

// Yaw, pitch, roll in 0.01 deg of a 12-char attitude frame.
std::array<int, 3> angles(const top::Frame& f) {
  std::array<int, 3> a{};
  for (int i = 0; i < 3; ++i)
    a[i] =
        static_cast<std::int16_t>(std::stoi(std::string(f.data().substr(i * 4, 4)), nullptr, 16));
  return a;
}

// The driver's pitch target, down positive on the wire (-30 deg AP pitch ->
// GIP +3000), speed 99: the GIA push reports it down positive within 1 s.
TEST(DeviceTopotek, GipMovesPitchAndGiaReportsItDownPositive) {
  Device d(top::Model::sip);
  // Neither write is answered (top::write_reply: the document gives them no
  // reply form; a real unit echoes none: silent_writes); both take effect.
  EXPECT_TRUE(ask_text(d, "#TPUG2wGIA01", 0, Link::uart).empty());
  EXPECT_TRUE(ask_text(d, "#tpUG6wGIP0BB863", 0, Link::uart).empty());
  const auto out = run_until(d, 1000000);
  ASSERT_GE(out.size(), 9u);
  const top::Frame last = parsed(out.back());
  expect_frame(last, "GIA", top::Header::variable, 'G', 'U');
  EXPECT_EQ(angles(last)[1], 3000);
  EXPECT_NEAR(d.pitch().angle, -30, 0.01);  // up positive inside
  // --write-echo on: every write echoed, as topsim did before silent_writes.
  topsim::DeviceOptions echo;
  echo.write_echo = true;
  Device e(top::Model::sip, echo);
  EXPECT_EQ(ask_text(e, "#TPUG2wGIA01", 0, Link::uart).at(0), top::with_checksum("#TPGU2wGIA01"));
  EXPECT_EQ(ask_text(e, "#tpUG6wGIP0BB863", 0, Link::uart).at(0),
            top::with_checksum("#tpGU6wGIP0BB863"));
  // The document: GIP is up positive, and the attitude (GIC) too.
  topsim::DeviceOptions o;
  o.profile = top::Profile::document;
  Device doc(top::Model::sip, o);
  ask_text(doc, "#tpUG6wGIP0BB863", 0, Link::uart);
  doc.advance(5000000);
  EXPECT_NEAR(doc.pitch().angle, 30, 0.01);
}

// YPR: one count is 1/1.2207 deg/s (the driver's conversion), pitch down
// positive; PTZ 00 stops the turn.
TEST(DeviceTopotek, YprTurnsInTheDriversUnitAndPtzStops) {
  Device d(top::Model::sip);
  ask_text(d, "#tpUG6wYPR0A0C00", 0, Link::uart);  // yaw +10, pitch +12 (down)
  d.advance(500000);
  EXPECT_NEAR(d.yaw().angle, 10 / 1.220740379 * 0.5, 0.01);
  EXPECT_NEAR(d.pitch().angle, -12 / 1.220740379 * 0.5, 0.01);
  EXPECT_TRUE(ask_text(d, "#TPUG2wPTZ00", 500000, Link::uart).empty());  // taken without a word
  const double stopped = d.pitch().angle;
  d.advance(900000);
  EXPECT_EQ(d.pitch().angle, stopped);
}

// The driver re-sends GIA 01 once a second: the stream keeps its timing.
TEST(DeviceTopotek, ResentGiaEnableKeepsTheStreamTiming) {
  Device d(top::Model::sip);
  ask_text(d, "#TPUG2wGIA01", 0, Link::uart);
  EXPECT_EQ(d.next_timer(), 100000u);
  ask_text(d, "#TPUG2wGIA01", 50000, Link::uart);
  EXPECT_EQ(d.next_timer(), 100000u);
  EXPECT_EQ(run_until(d, 1000000).size(), 10u);
  ask_text(d, "#TPUG2wGIA00", 1000000, Link::uart);
  EXPECT_TRUE(run_until(d, 2000000).empty());
}

// A real SIP answers the GIC query with a 12-char GIA (issue 28 log).
TEST(DeviceTopotek, GicQueryIsAnsweredWithGiaInTheField) {
  Device d(top::Model::sip);
  const top::Frame f = parsed(ask_text(d, "#TPPG2rGIC00").at(0));
  expect_frame(f, "GIA", top::Header::variable, 'G', 'P');
  EXPECT_EQ(f.data().size(), 12u);
  topsim::DeviceOptions o;
  o.profile = top::Profile::document;
  Device doc(top::Model::sip, o);
  EXPECT_EQ(parsed(ask_text(doc, "#TPPG2rGIC00").at(0)).ident_view(), "GIC");
}

TEST(DeviceTopotek, IdentityIsPlausibleAndSettable) {
  Device d(top::Model::sip);
  EXPECT_EQ(ask_text(d, "#TPPD2rVSN00").at(0), "#tpDPArVSN1.6.26.R.D62");  // the real unit's frame
  const top::Frame pa2 = parsed(ask_text(d, "#TPUG2rPA200", 0, Link::uart).at(0));
  EXPECT_EQ(pa2.data(), "SIP");
  topsim::DeviceOptions o;
  o.version = "2.1.0";
  o.model_name = "FL-30";
  Device set(top::Model::sip, o);
  EXPECT_EQ(parsed(ask_text(set, "#TPPD2rVSN00").at(0)).data(), "2.1.0");
  EXPECT_EQ(parsed(ask_text(set, "#TPPG2rPA200").at(0)).data(), "FL-30");
}

// The real unit's frames byte for byte: TRA, TRC, and #tp kept on a short reply.
TEST(DeviceTopotek, ShortRepliesAsTheRealUnit) {
  Device d(top::Model::sip);
  EXPECT_EQ(ask_text(d, "#TPPD2rTRA00").at(0), "#TPDP2rTRA1148");
  EXPECT_EQ(ask_text(d, "#TPPD2rTRC00").at(0), "#TPDP2rTRC0048");
  EXPECT_EQ(parsed(ask_text(d, "#tpPG2rGMS00").at(0)).header, top::Header::variable);
  // An option overrides the trait.
  topsim::DeviceOptions o;
  o.reply_header = top::Header::fixed;
  Device fixed(top::Model::sip, o);
  EXPECT_EQ(parsed(ask_text(fixed, "#tpPG2rGMS00").at(0)).header, top::Header::fixed);
}

std::string loc(std::int16_t x, std::int16_t y, std::uint16_t w, std::uint16_t h,
                std::uint16_t mode) {
  std::string s = "#tpUDAwLOC";
  for (std::uint16_t v :
       {static_cast<std::uint16_t>(x), static_cast<std::uint16_t>(y), w, h, mode}) {
    s.push_back(static_cast<char>(v >> 8));
    s.push_back(static_cast<char>(v & 0xFF));
  }
  return s;
}

// TRC 02 -> waiting, LOC -> tracking ~0.4 s later with OFT at ~30 Hz, TRC 01
// -> one all-zero OFT with status 1 and waiting, TRC 00 -> stopped.
TEST(DeviceTopotek, TrackingStateMachine) {
  Device d(top::Model::sip);
  auto state = [&](std::uint64_t t) {
    // A copy: the frame parsed here is gone at the end of the statement.
    return std::string(parsed(ask_text(d, "#TPUD2rTRC00", t, Link::uart).at(0)).data());
  };
  EXPECT_EQ(state(0), "00");
  ask_text(d, "#TPUD2wTRC02", 0, Link::uart);
  EXPECT_EQ(state(0), "01");
  EXPECT_TRUE(ask_text(d, loc(0, 0, 62, 111, 9), 100000, Link::uart).empty());  // no echo
  EXPECT_TRUE(run_until(d, 400000).empty());
  EXPECT_EQ(state(400000), "01");
  const auto boxes = run_until(d, 1500000);
  EXPECT_EQ(state(1500000), "02");
  EXPECT_GE(boxes.size(), 30u);
  EXPECT_LE(boxes.size(), 35u);
  const top::Frame oft = parsed(boxes.front());
  expect_frame(oft, "OFT", top::Header::variable, 'D', 'U');
  EXPECT_EQ(oft.control, 'w');
  ASSERT_EQ(oft.data().size(), 9u);
  auto le = [&](int i) {
    return static_cast<unsigned char>(oft.data()[i]) | static_cast<unsigned char>(oft.data()[i + 1])
                                                           << 8;
  };
  EXPECT_NEAR(le(0) + le(4) / 2.0, 960, 1);  // the box is centred on the LOC point
  EXPECT_NEAR(le(2) + le(6) / 2.0, 540, 1);
  EXPECT_EQ(oft.data()[8], '2');
  const auto cancel = ask_text(d, "#TPUD2wTRC01", 1500000, Link::uart);
  ASSERT_EQ(cancel.size(), 1u);  // the box, no echo
  EXPECT_EQ(parsed(cancel[0]).data(), std::string(8, '\0') + "1");
  EXPECT_EQ(state(1500000), "01");
  EXPECT_TRUE(run_until(d, 2000000).empty());
  ask_text(d, "#TPUD2wTRC00", 2000000, Link::uart);
  EXPECT_EQ(state(2000000), "00");
  // A LOC while stopped starts nothing.
  ask_text(d, loc(0, 0, 62, 111, 9), 2000000, Link::uart);
  EXPECT_TRUE(run_until(d, 3000000).empty());
}

TEST(DeviceTopotek, LensWithoutTrackingAnswersState4) {
  topsim::DeviceOptions o;
  o.tracking = false;
  Device d(top::Model::sip, o);
  ask_text(d, "#TPUD2wTRC02", 0, Link::uart);
  ask_text(d, loc(0, 0, 62, 111, 9), 0, Link::uart);
  EXPECT_TRUE(run_until(d, 1000000).empty());
  EXPECT_EQ(parsed(ask_text(d, "#TPUD2rTRC00", 1000000, Link::uart).at(0)).data(), "04");
}

// Position writes: no source records what a Topotek device answers to
// LAT/LON (the field profile echoed them on the word of our own tracker,
// which no capture bears out), so the field profile answers them as the
// document profile does: in 5.8.7's target output layout
// (top::write_reply: data). ALT, AZI and the time, which the document gives
// no reply form, get no answer in either profile, on a UART as over UDP
// (top::write_reply: nothing; a real Topotek camera echoed no write).
TEST(DeviceTopotek, PositionWritesGetTheDocumentsAnswerInEitherProfile) {
  topsim::DeviceOptions o;
  o.profile = top::Profile::document;
  Device fld(top::Model::sip), doc(top::Model::sip, o);
  for (const char* w : {"#tpUDAwLATN3520.1234", "#tpUDBwLONE13845.6789"}) {
    const std::vector<std::string> a = ask_text(fld, w, 0, Link::uart);
    ASSERT_EQ(a.size(), 1u) << w;
    EXPECT_EQ(a, ask_text(doc, w, 0, Link::uart)) << w;
    const top::Frame f = parsed(a.at(0));
    EXPECT_NE(f.data(), std::string_view(w).substr(10)) << w;  // no echo
    top::DecodeOptions dopts;
    dopts.dialect = top::Dialect::topotek;
    dopts.model = top::Model::sip;
    dopts.role = top::Role::response;
    const top::Decoded dec = top::decode(f, dopts);
    ASSERT_NE(dec.form, nullptr) << w;
    EXPECT_FALSE(dec.form->from_field()) << w;
    EXPECT_TRUE(dec.findings.empty()) << w << ": " << dec.summary();
  }
  for (const char* w : {"#tpUD8wALT000123.4", "#tpUD5wAZI045.0", "#tpUDCwUTC143005261126"}) {
    EXPECT_TRUE(ask_text(fld, w, 0, Link::uart).empty()) << w;
    EXPECT_TRUE(ask_text(doc, w, 0, Link::uart).empty()) << w;
    EXPECT_TRUE(ask_text(fld, std::string("#tpPD") + (w + 5), 0, Link::network).empty()) << w;
  }
}

// The rangefinder (Topotek 5.9): a control write (00 stop, 01 on, 02
// single, 03 continuous) is answered with the range in the document's
// X1X2X3X4X5.X6, metres, in either profile (a write of a command with a
// reply layout is answered in it: top::write_reply).
// topsim answered with 5 digits, the midpoint of the document's range
// (#tpMU5wLRF500002E), which the catalog then took for a real unit's form.
TEST(DeviceTopotek, LrfAnswersWithItsRangeInTheDocumentsForm) {
  for (top::Profile p : {top::Profile::field, top::Profile::document}) {
    topsim::DeviceOptions o;
    o.profile = p;
    Device d(top::Model::sip, o);
    for (const char* w : {"#TPUM2wLRF00", "#TPUM2wLRF01", "#TPUM2wLRF02", "#TPUM2wLRF03"}) {
      const std::vector<std::string> a = ask_text(d, w, 0, Link::uart);
      ASSERT_EQ(a.size(), 1u) << w;
      EXPECT_EQ(a.at(0), top::with_checksum("#tpMU7wLRF01234.5")) << w;
    }
    o.range_m = 12.34;
    Device near(top::Model::sip, o);
    const top::Frame f = parsed(ask_text(near, "#TPUM2wLRF03", 0, Link::uart).at(0));
    EXPECT_EQ(f.data(), "00012.3");
    top::DecodeOptions dopts;
    dopts.dialect = top::Dialect::topotek;
    dopts.model = top::Model::sip;
    dopts.role = top::Role::response;
    const top::Decoded dec = top::decode(f, dopts);
    ASSERT_NE(dec.form, nullptr);
    EXPECT_TRUE(dec.findings.empty()) << dec.summary();
    ASSERT_EQ(dec.fields.size(), 1u);
    EXPECT_DOUBLE_EQ(dec.fields[0].value, 12.3);
    EXPECT_EQ(dec.fields[0].unit(), "m");
  }
}

}  // namespace
