// topsim's device model: answers, state and streams, on an injected clock.
#include "sim/device.hpp"

#include <gtest/gtest.h>

#include "sim/intake.hpp"

namespace {

using topsim::Device;
using topsim::Link;

std::vector<std::string> ask(Device& d, std::string_view body, std::uint64_t t = 0,
                             Link link = Link::network) {
  return topsim::handle_datagram(d, top::with_checksum(body), link, t);
}

top::Frame parsed(const std::string& s) {
  auto r = top::parse_exact(s);
  EXPECT_EQ(r.status, top::ParseStatus::frame) << s;
  return r.frame;
}

TEST(Device, WriteIsEchoedWithSwappedAddresses) {
  Device d(top::Model::c12);
  auto out = ask(d, "#TPUG6wGAYEF0732");
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], top::with_checksum("#TPGU6wGAYEF0732"));
}

TEST(Device, ReadIsAnsweredWithData) {
  Device d(top::Model::c12);
  auto out = ask(d, "#TPUD2rVER00");
  ASSERT_EQ(out.size(), 1u);
  auto f = parsed(out[0]);
  EXPECT_EQ(f.src, 'D');
  EXPECT_EQ(f.dst, 'U');
  EXPECT_EQ(f.ident_view(), "VER");
  EXPECT_EQ(f.data(), "V1.0.78");  // the form ArduPilot's SkyDroid driver parses
}

TEST(Device, InvalidCommandGetsEreOnSkyDroid) {
  Device d(top::Model::c12);
  auto out = ask(d, "#TPUM2rZZZ00");
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], "#TPMU2wERE!!30");  // the document's own example
  // Wrong length and unsupported on the model: ERE too.
  EXPECT_EQ(parsed(ask(d, "#TPUG5wGAYEF073").at(0)).ident_view(), "ERE");
  Device c13(top::Model::c13);
  EXPECT_EQ(parsed(ask(c13, "#TPUG6wGAYEF0732").at(0)).ident_view(), "ERE");
}

TEST(Device, BadChecksumGetsSilence) {
  Device d(top::Model::c12);
  EXPECT_TRUE(topsim::handle_datagram(d, "#TPUG6wGAYEF073200", Link::network, 0).empty());
  EXPECT_TRUE(topsim::handle_datagram(d, "#TPUG6wGAYEF0732", Link::network, 0).empty());
}

TEST(Device, TopotekAnswersTheInterfaceOfTheSourceByte) {
  Device d(top::Model::sip);
  // UDP request with source U: no answer (field notes, Topotek 2).
  EXPECT_TRUE(ask(d, "#TPUG2rGIC00", 0, Link::network).empty());
  EXPECT_TRUE(ask(d, "#TPPG2rGIC00", 0, Link::uart).empty());
  auto net = ask(d, "#TPPG2rGIC00", 0, Link::network);
  ASSERT_EQ(net.size(), 1u);
  EXPECT_EQ(parsed(net[0]).dst, 'P');
  auto uart = ask(d, "#TPUG2rGIC00", 0, Link::uart);
  ASSERT_EQ(uart.size(), 1u);
  EXPECT_EQ(parsed(uart[0]).dst, 'U');
  // Unknown identifier on Topotek: silence, no ERE.
  EXPECT_TRUE(ask(d, "#TPPD2rZZZ00").empty());
}

TEST(Device, TopotekRecAndCapReplyWithFileIndex) {
  Device d(top::Model::sip);
  auto start = ask(d, "#TPPD2wREC01");
  ASSERT_EQ(start.size(), 1u);
  EXPECT_EQ(start[0], top::with_checksum("#tpDPAwREC1100000001"));
  EXPECT_TRUE(d.recording());
  EXPECT_EQ(parsed(ask(d, "#TPPD2rREC00").at(0)).data(), "01");
  auto stop = ask(d, "#TPPD2wREC0A");  // toggle
  EXPECT_EQ(stop.at(0), top::with_checksum("#tpDPAwREC0000000001"));
  EXPECT_FALSE(d.recording());
  EXPECT_EQ(ask(d, "#TPPD2wCAP01").at(0), top::with_checksum("#tpDPAwCAP1100000002"));
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
  ask(d, "#TPUG6wGAY03E832", 0);
  d.advance(1000000);
  EXPECT_NEAR(d.yaw().angle, 5.0, 1e-6);
  d.advance(2500000);
  EXPECT_NEAR(d.yaw().angle, 10.0, 1e-6);
  EXPECT_FALSE(d.yaw().has_target);
  // GAM: yaw -20, pitch +30 at 9.9 deg/s (63).
  ask(d, "#TPUGCwGAMF830630BB863", 3000000);
  d.advance(13000000);
  EXPECT_NEAR(d.yaw().angle, -20.0, 1e-6);
  EXPECT_NEAR(d.pitch().angle, 30.0, 1e-6);
}

TEST(Device, SpeedCommandsIntegrateWithinLimitsAndExpire) {
  topsim::DeviceOptions o = document_signs();
  o.speed_hold_ms = 1000;
  Device d(top::Model::c12, o);
  // GSY +20 steps = +10 deg/s.
  ask(d, "#TPUG2wGSY14", 0);
  d.advance(500000);
  EXPECT_NEAR(d.yaw().angle, 5.0, 1e-6);
  d.advance(3000000);  // the command held for 1 s only
  EXPECT_NEAR(d.yaw().angle, 10.0, 1e-6);
  // Refreshed at 50 Hz for 12 s at +63.5 deg/s: clamped at the +90 limit.
  for (std::uint64_t t = 3000000; t < 15000000; t += 20000) ask(d, "#TPUG2wGSP7F", t);
  d.advance(15000000);
  EXPECT_DOUBLE_EQ(d.pitch().angle, 90.0);
}

TEST(Device, GaaStreamsGacAtTheRequestedRate) {
  Device d(top::Model::c12);
  ask(d, "#TPUG2wGAA0A", 0);  // 10 Hz
  std::vector<std::string> out;
  std::uint64_t t = 0;
  int n = 0;
  while ((t = d.next_timer()) <= 1000000) {
    d.poll(t, out);
    ++n;
  }
  EXPECT_EQ(n, 10);
  ASSERT_FALSE(out.empty());
  auto f = parsed(out[0]);
  EXPECT_EQ(f.ident_view(), "GAC");
  // The field profile's C12 form (#tpUGCrGAC, client first: docs/FIELD.md);
  // field_test.cpp checks every profile's form.
  EXPECT_EQ(f.header, top::Header::variable);
  EXPECT_EQ(f.src, 'U');
  EXPECT_EQ(f.dst, 'G');
  ask(d, "#TPUG2wGAA00", 1000000);
  EXPECT_EQ(d.next_timer(), std::numeric_limits<std::uint64_t>::max());
}

TEST(Device, TopotekGiaStreamsGic) {
  Device d(top::Model::sip);
  ask(d, "#TPPG2wGIA01", 0);
  std::vector<std::string> out;
  d.poll(d.next_timer(), out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(parsed(out[0]).ident_view(), "GIC");
  EXPECT_EQ(parsed(out[0]).dst, 'P');
}

TEST(Device, SettingsReadBackWhatWasSet) {
  Device d(top::Model::c12);
  ask(d, "#tpUDAwIPV10.0.0.9");
  EXPECT_EQ(parsed(ask(d, "#TPUD2rIPV00").at(0)).data(), "10.0.0.9");
  ask(d, "#TPUD2wAWB15");
  EXPECT_EQ(parsed(ask(d, "#TPUD2rAWB00").at(0)).data(), "15");
  ask(d, "#TPUD2wREC01");
  EXPECT_EQ(parsed(ask(d, "#TPUD2rREC00").at(0)).data(), "01");
  EXPECT_EQ(parsed(ask(d, "#TPUD2rSDC00").at(0)).data(), "0EA601D4C0");
}

TEST(Device, NoSwapAndTmpQuirkOptions) {
  topsim::DeviceOptions o;
  o.swap_addresses = false;
  o.tmp_quirk = true;
  Device d(top::Model::c12, o);
  EXPECT_EQ(ask(d, "#TPUG2wGAA00").at(0), top::with_checksum("#TPUG2wGAA00"));
  auto tmp = parsed(ask(d, "#tpUD0rTMP").at(0));
  EXPECT_TRUE(tmp.has(top::FindingCode::tmp_quirk));
}

// The Topotek 12.2 firmware form byte for byte: a two-digit length, control
// w, the addresses swapped (or not, with no-swap).
TEST(Device, TmpQuirkIsTheFirmwareFormByteForByte) {
  topsim::DeviceOptions o;
  o.tmp_quirk = true;
  Device swapped(top::Model::c12, o);
  EXPECT_EQ(ask(swapped, "#tpUD0rTMP").at(0), "#tpDU16wTMP0100200300400500600700AB");
  o.swap_addresses = false;
  Device kept(top::Model::c12, o);
  EXPECT_EQ(ask(kept, "#tpUD0rTMP").at(0), "#tpUD16wTMP0100200300400500600700AB");
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
