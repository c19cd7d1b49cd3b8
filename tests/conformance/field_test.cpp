// Field fidelity of topsim: the device answers as real cameras do under the
// field profile and as the documents write under the document profile, and
// a client as strict as the public ones (exact prefixes, valid checksum)
// gets attitude, palette and range over real UDP. Where the document and
// the field disagree, each test names both.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <optional>
#include <string>
#include <thread>
#include <utility>

#include "running_server.hpp"
#include "sim/device.hpp"
#include "sim/server.hpp"

namespace {

using topsim::Device;
using topsim::DeviceOptions;
using topsim::Link;

std::vector<std::string> ask(Device& d, std::string_view body, std::uint64_t t = 0) {
  return topsim::handle_datagram(d, top::with_checksum(body), Link::network, t);
}

DeviceOptions profile(top::Profile p) {
  DeviceOptions o;
  o.profile = p;
  return o;
}

// What the public clients accept: the exact prefix, then a valid checksum
// over the bytes as sent (the C12 console's parse_attitude and
// parse_thermal_palette, the C13 SDK's range parser).
bool strict(const std::string& f, std::string_view prefix) {
  if (f.size() < prefix.size() + 2 || f.compare(0, prefix.size(), prefix) != 0) return false;
  char cs[2];
  top::put_hex2(top::checksum(std::string_view(f).substr(0, f.size() - 2)), cs);
  return f.compare(f.size() - 2, 2, cs, 2) == 0;
}

std::vector<std::string> pushes(Device& d, std::uint64_t from_us, std::uint64_t to_us) {
  std::vector<std::string> out;
  for (std::uint64_t t = from_us; t <= to_us; t += 1000) d.poll(t, out);
  return out;
}

TEST(FieldProfile, C12AttitudePushIsLowercaseClientFirstAt10Hz) {
  // Field: real C12s push #tpUGCrGAC (clients accept nothing else).
  // Document (SkyDroid 3.3.2.2 example): #TPUGCrGAC.
  Device d(top::Model::c12);
  ASSERT_EQ(ask(d, "#TPUG2wGAA0A").size(), 1u);
  auto out = pushes(d, 0, 1000000);
  ASSERT_EQ(out.size(), 10u);
  for (const auto& f : out) {
    EXPECT_TRUE(strict(f, "#tpUGCrGAC")) << f;
    EXPECT_EQ(f.size(), 24u);
  }
  Device doc(top::Model::c12, profile(top::Profile::document));
  ask(doc, "#TPUG2wGAA0A");
  out = pushes(doc, 0, 1000000);
  ASSERT_EQ(out.size(), 10u);
  EXPECT_TRUE(strict(out[0], "#TPUGCrGAC")) << out[0];
}

TEST(FieldProfile, OtherSkyDroidModelsPushTheDocumentsExample) {
  // No field evidence for the C10: the 3.3.2.2 example under both profiles.
  Device d(top::Model::c10);
  ask(d, "#TPUG2wGAA0A");
  auto out = pushes(d, 0, 200000);
  ASSERT_FALSE(out.empty());
  EXPECT_TRUE(strict(out[0], "#TPUGCrGAC")) << out[0];
}

TEST(FieldProfile, C12PaletteAndVersionRepliesSwapTheAddresses) {
  // Field: #TPDU...IMG (a C12 console reads nothing else), #tpDU3rVER (a
  // real C12). Document rule 2.3.1 gives the same order.
  for (top::Profile p : {top::Profile::field, top::Profile::document}) {
    Device d(top::Model::c12, profile(p));
    auto img = ask(d, "#TPUD2rIMG00");
    ASSERT_EQ(img.size(), 1u);
    // Field: the C12 app waits for #TPDU1rIMG (the length counts bytes), the
    // console for #TPDU..IMG; the document counts chars.
    EXPECT_TRUE(strict(img[0], p == top::Profile::field ? "#TPDU1rIMG" : "#TPDU2rIMG")) << img[0];
    auto ver = ask(d, "#TPUD2rVER00");
    ASSERT_EQ(ver.size(), 1u);
    EXPECT_TRUE(strict(ver[0], "#tpDU")) << ver[0];
  }
}

TEST(FieldProfile, C13RangeIsUppercaseSwappedInTheFieldAndClientFirstInTheDocument) {
  // Field: a C13 SDK takes a range only from #TPDU...SLR.
  // Document (SkyDroid 4.22 example): #TPUD4rSLR0005BC.
  Device field(top::Model::c13);
  auto out = ask(field, "#TPUD2rSLR00");
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(strict(out[0], "#TPDU4rSLR")) << out[0];
  Device doc(top::Model::c13, profile(top::Profile::document));
  out = ask(doc, "#TPUD2rSLR00");
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(strict(out[0], "#TPUD4rSLR")) << out[0];
}

TEST(FieldProfile, C12ReportsTheOppositeYawOfTheCommand) {
  // Field: C12 clients negate yaw; the attitude reports the opposite sign of
  // the GAM input. Document (3.3.1): the attitude is the angle commanded.
  Device d(top::Model::c12);
  ask(d, "#TPUG6wGAY0BB863");
  d.advance(10'000'000);
  ask(d, "#TPUG2wGAA0A", 10'000'000);
  auto out = pushes(d, 10'000'000, 10'100'000);
  ASSERT_FALSE(out.empty());
  EXPECT_EQ(out[0].substr(10, 4), "F448") << out[0];  // -30.00
  Device doc(top::Model::c12, profile(top::Profile::document));
  ask(doc, "#TPUG6wGAY0BB863");
  doc.advance(10'000'000);
  ask(doc, "#TPUG2wGAA0A", 10'000'000);
  out = pushes(doc, 10'000'000, 10'100'000);
  ASSERT_FALSE(out.empty());
  EXPECT_EQ(out[0].substr(10, 4), "0BB8") << out[0];  // +30.00
  // The switch overrides the profile.
  DeviceOptions o;
  o.yaw_inverted = false;
  Device sw(top::Model::c12, o);
  ask(sw, "#TPUG6wGAY0BB863");
  sw.advance(10'000'000);
  ask(sw, "#TPUG2wGAA0A", 10'000'000);
  out = pushes(sw, 10'000'000, 10'100'000);
  ASSERT_FALSE(out.empty());
  EXPECT_EQ(out[0].substr(10, 4), "0BB8") << out[0];
}

TEST(FieldProfile, C13TakesThePtzCodesTheFieldReports) {
  // Field: a C13 SDK reports PTZ 02, 05, 0E-13 working. Document 3.1: PTZ
  // is not listed for the C13 (ERE), and 0E-13 are trim codes.
  Device field(top::Model::c13);
  auto out = ask(field, "#TPUG2wPTZ0E");
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0], top::with_checksum("#TPGU2wPTZ0E"));
  field.advance(500'000);
  EXPECT_GT(field.pitch().angle, 1.0);  // 0E: pitch +
  out = ask(field, "#TPUG2wPTZ10", 500'000);
  ASSERT_EQ(out.size(), 1u);
  field.advance(1'000'000);
  EXPECT_GT(field.yaw().angle, 1.0);  // 10: yaw +
  // A code no evidence covers (09 calibrate): ERE. 06/07 are ArduPilot's
  // SkyDroid driver's follow/lock (PR #34155), taken too.
  out = ask(field, "#TPUG2wPTZ09");
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NE(out[0].find("ERE"), std::string::npos) << out[0];
  Device doc(top::Model::c13, profile(top::Profile::document));
  out = ask(doc, "#TPUG2wPTZ0E");
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NE(out[0].find("ERE"), std::string::npos) << out[0];
}

TEST(FieldProfile, TraitSwitchesOverrideTheProfile) {
  DeviceOptions o;
  o.push_order = top::Order::swapped;
  o.push_header = top::Header::fixed;
  Device d(top::Model::c12, o);
  ask(d, "#TPUG2wGAA0A");
  auto out = pushes(d, 0, 200000);
  ASSERT_FALSE(out.empty());
  EXPECT_TRUE(strict(out[0], "#TPGUCrGAC")) << out[0];
  DeviceOptions r;
  r.reply_order = top::Order::request_order;
  Device c13(top::Model::c13, r);
  out = ask(c13, "#TPUD2rSLR00");
  ASSERT_EQ(out.size(), 1u);
  EXPECT_TRUE(strict(out[0], "#TPUD4rSLR")) << out[0];
}

TEST(FieldProfile, DescribeNamesEverySourceOfTheModel) {
  Device d(top::Model::c12);
  bool push = false, yaw = false, pitch = false;
  for (const auto& t : d.describe()) {
    EXPECT_FALSE(t.source.empty()) << t.name;
    EXPECT_FALSE(t.evidence.empty()) << t.name;
    if (t.name == "GAC-push-header") push = t.value == "#tp" && t.source == "field";
    if (t.name == "yaw-inverted") yaw = t.value == "on (GSY GAY GAM)" && t.source == "field";
    // The C12 pitch inversion: recorded with its sources, off (contested).
    if (t.name == "pitch-inverted") {
      pitch = t.value == "off (recorded for GAM)";
      EXPECT_EQ(t.source, "contested");
      EXPECT_NE(t.evidence.find("Against"), std::string::npos);
    }
  }
  EXPECT_TRUE(push);
  EXPECT_TRUE(yaw);
  EXPECT_TRUE(pitch);
  Device doc(top::Model::c12, profile(top::Profile::document));
  for (const auto& t : doc.describe()) {
    if (t.name == "GAC-push-header") {
      EXPECT_EQ(t.value, "#TP");
      EXPECT_EQ(t.source, "document example");
    }
    if (t.name == "yaw-inverted") {
      EXPECT_EQ(t.value, "off");
    }
  }
}

// --- signs per identifier, ArduPilot's SkyDroid driver -------------------

// The GAC push's yaw and pitch (deg) after `cmd` held for 1 s.
std::pair<double, double> after(Device& d, std::string_view cmd) {
  ask(d, cmd);
  ask(d, "#TPUG2wGAA0A");
  auto out = pushes(d, 1'000'000, 1'000'000);
  out.clear();
  for (std::uint64_t t = 0; t <= 1'000'000; t += 20'000) ask(d, cmd, t);
  out = pushes(d, 1'000'000, 1'100'000);
  if (out.empty()) return {0, 0};
  const top::ParseResult r = top::parse_exact(out.back());
  const auto v = [&](std::size_t at) {
    return static_cast<std::int16_t>(
               std::stoi(std::string(r.frame.data().substr(at, 4)), nullptr, 16)) /
           100.0;
  };
  return {v(0), v(4)};
}

TEST(FieldProfile, SignsFollowEachIdentifiersEvidence) {
  // +GSY makes GAC yaw decrease on C12 and C13 (AP_Mount_SkyDroid, C13
  // station); +GSP makes GAC pitch increase (C11 driver, C12 app, C13
  // station): the driver's -30 target settles there.
  for (top::Model m : {top::Model::c12, top::Model::c13}) {
    Device y(m);
    EXPECT_LT(after(y, "#TPUG2wGSY14").first, -5) << top::to_string(m);
    Device p(m);
    EXPECT_GT(after(p, "#TPUG2wGSP14").second, 5) << top::to_string(m);
  }
  // C12 GAM: the pitch inversion is contested and off; yaw (GAY GAM) on.
  Device gam(top::Model::c12);
  ask(gam, "#TPUGCwGAM03E8630BB863");
  gam.advance(20'000'000);
  EXPECT_NEAR(gam.pitch().angle, 30.0, 1e-6);
  EXPECT_NEAR(gam.yaw().angle, -10.0, 1e-6);
  // The switches: every command of the axis, either way.
  DeviceOptions inv;
  inv.pitch_inverted = true;
  Device p(top::Model::c12, inv);
  EXPECT_LT(after(p, "#TPUG2wGSP14").second, -5);
  DeviceOptions normal;
  normal.yaw_inverted = false;
  Device y(top::Model::c13, normal);
  EXPECT_GT(after(y, "#TPUG2wGSY14").first, 5);
  // The document's device: no trait.
  Device doc(top::Model::c12, profile(top::Profile::document));
  EXPECT_GT(after(doc, "#TPUG2wGSY14").first, 5);
}

TEST(FieldProfile, C13AnswersWhatTheSkyDroidDriverSends) {
  // The driver sends these to C11 and C13 alike (PR #34155); the
  // document's support lines leave the C13 out (ERE under its profile).
  for (const char* body :
       {"#TPUD2rVER00", "#TPUD2rMOD00", "#TPUD2rSDC00", "#TPUD2wREC01", "#TPUD2wCAP01",
        "#TPUM2wDZM0A", "#tpUDFwTIM143005.00261026", "#TPUG2wFAE01", "#TPUD2wSLR01"}) {
    Device field(top::Model::c13);
    const auto out = ask(field, body);
    ASSERT_EQ(out.size(), 1u) << body;
    EXPECT_EQ(top::parse_exact(out[0]).frame.ident_view(), std::string_view(body).substr(7, 3))
        << body << " -> " << out[0];
    Device doc(top::Model::c13, profile(top::Profile::document));
    EXPECT_EQ(top::parse_exact(ask(doc, body).at(0)).frame.ident_view(), "ERE") << body;
  }
  // FAI: 12 chars is the document's form, taken without an answer (the
  // document gives FAI no reply: top::write_reply); the 14 of ArduPilot's
  // SkyDroid driver (the attitude and a mode byte: AP_Mount_SkyDroid.cpp @
  // c5aa8452 send_attitude_to_gimbal()) is the field's form, taken without
  // an answer by default on both models and refused by the document's device.
  for (top::Model m : {top::Model::c12, top::Model::c13}) {
    Device d(m);
    EXPECT_TRUE(ask(d, "#tpUGCwFAI000000000000").empty());
    for (const char* fai : {"#tpUGEwFAI00000000000000", "#tpUGEwFAIEC78FF38000001"})
      EXPECT_TRUE(ask(d, fai).empty()) << fai;
    Device doc(m, profile(top::Profile::document));
    EXPECT_EQ(top::parse_exact(ask(doc, "#tpUGEwFAI00000000000000").at(0)).frame.ident_view(),
              "ERE");
  }
}

TEST(FieldProfile, IdentityIsPlausibleAndSettable) {
  Device c13(top::Model::c13);
  EXPECT_EQ(top::parse_exact(ask(c13, "#TPUD2rMOD00").at(0)).frame.data(), "C13");
  EXPECT_EQ(top::parse_exact(ask(c13, "#TPUD2rVER00").at(0)).frame.data(), "V1.0.78");
  DeviceOptions o;
  o.model_name = "C12S";
  o.version = "V2.1.0";
  Device c12(top::Model::c12, o);
  EXPECT_EQ(top::parse_exact(ask(c12, "#TPUD2rMOD00").at(0)).frame.data(), "C12S");
  EXPECT_EQ(top::parse_exact(ask(c12, "#TPUD2rVER00").at(0)).frame.data(), "V2.1.0");
  // MOD is the field's: the document's device does not know it.
  Device doc(top::Model::c12, profile(top::Profile::document));
  EXPECT_EQ(top::parse_exact(ask(doc, "#TPUD2rMOD00").at(0)).frame.ident_view(), "ERE");
}

// --- a strict client over real UDP --------------------------------------

struct Udp {
  int fd = -1;
  Udp(const char* host, std::uint16_t port) {
    fd = ::socket(AF_INET, SOCK_DGRAM, 0);
    int one = 1;
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    ::inet_pton(AF_INET, host, &a.sin_addr);
    ok = ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  }
  ~Udp() { ::close(fd); }
  bool ok = false;
  void send(const std::string& bytes, const char* host, std::uint16_t port) const {
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    ::inet_pton(AF_INET, host, &a.sin_addr);
    ::sendto(fd, bytes.data(), bytes.size(), 0, reinterpret_cast<sockaddr*>(&a), sizeof a);
  }
  // The first datagram that holds `prefix` and passes the strict check
  // within `ms`, as the public clients read them.
  std::optional<std::string> wait_for(std::string_view prefix, int ms) const {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
    char buf[2048];
    while (std::chrono::steady_clock::now() < end) {
      pollfd p{fd, POLLIN, 0};
      if (::poll(&p, 1, 50) <= 0) continue;
      const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
      if (n <= 0) continue;
      std::string d(buf, static_cast<std::size_t>(n));
      while (!d.empty() && (d.back() == '\r' || d.back() == '\n')) d.pop_back();
      if (strict(d, prefix)) return d;
    }
    return std::nullopt;
  }
};

void strict_client_session(const char* server_host, std::uint16_t server_port,
                           const char* client_host, std::uint16_t client_port) {
  topsim::ServerConfig cfg;
  cfg.model = top::Model::c12;
  cfg.host = server_host;
  cfg.port = server_port;
  RunningServer s(cfg);
  const std::uint16_t port = s.server.port();
  Udp c(client_host, client_port);
  ASSERT_TRUE(c.ok) << client_host << ":" << client_port;
  c.send(top::with_checksum("#TPUG2wGAA0A"), server_host, port);
  auto att = c.wait_for("#tpUGCrGAC", 2000);
  ASSERT_TRUE(att) << "no attitude push a C12 client accepts";
  c.send(top::with_checksum("#TPUD2rIMG00"), server_host, port);
  EXPECT_TRUE(c.wait_for("#TPDU1rIMG", 2000)) << "no palette reply a C12 client accepts";
  c.send(top::with_checksum("#TPUG2wGAA00"), server_host, port);

  topsim::ServerConfig c13 = cfg;
  c13.model = top::Model::c13;
  c13.port = 0;
  RunningServer s13(c13);
  c.send(top::with_checksum("#TPUD2rSLR00"), server_host, s13.server.port());
  EXPECT_TRUE(c.wait_for("#TPDU4rSLR", 2000)) << "no range reply the C13 SDK accepts";
}

TEST(StrictClient, GetsAttitudePaletteAndRangeFromAnEphemeralPort) {
  strict_client_session("127.0.0.1", 0, "127.0.0.1", 0);
}

TEST(StrictClient, GetsAttitudePaletteAndRangeFrom5000To5000) {
  // The vendor's app: UDP 5000 -> 5000. Two loopback addresses let both ends
  // bind port 5000 on one machine.
  strict_client_session("127.0.0.83", 5000, "127.0.0.84", 5000);
}

}  // namespace
