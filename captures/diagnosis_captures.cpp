// The captures of docs/DIAGNOSES.md: for each diagnosis a capture made to
// show it (diag-CODE.*), and the healthy counterparts that do the same
// things right (diag-healthy-*), SkyDroid and Topotek, UDP and serial.
// tests/analyzer/diagnoses_test.cpp checks that each fires on its capture
// and on nothing else. Deterministic: the same bytes on every run.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>

#include "capture_kit.hpp"

namespace capture_kit {

namespace {

// SkyDroid C12 on UDP 5000 (client U, gimbal G, camera D).
Udp skydroid(const char* name) { return Udp(name, 1, 40010, 5000); }
// Topotek SIP on UDP 9003 from a network client (source P).
Udp topotek(const char* name) { return Udp(name, 1, 9004, 9003); }

// Four hex digits of a value in hundredths (two's complement).
std::string hex4(double v) {
  char b[8];
  std::snprintf(b, sizeof b, "%04X", static_cast<unsigned>(std::lround(v * 100)) & 0xFFFFu);
  return b;
}
// A SkyDroid GAC push (yaw, pitch in degrees, up positive; roll 0).
std::string gac_at(double yaw, double pitch) {
  return F("#TPGUCrGAC" + hex4(yaw) + hex4(pitch) + "0000");
}
// A Topotek 12-char GIA push (attitude), as a real SIP and ArduPilot's
// SIM_Topotek send after GIA 01 (docs/FIELD.md "Streams"), to client `c` (yaw, pitch up positive:
// the wire's pitch is down positive, docs/FIELD.md).
std::string gia_at(char c, double yaw, double pitch) {
  return F(std::string("#tpG") + c + "CrGIA" + hex4(yaw) + hex4(-pitch) + "0000");
}
// A value that moves at `rate` per second from `from_ms` to `to_ms`.
double ramp(int ms, int from_ms, int to_ms, double rate) {
  return rate * (std::clamp(ms, from_ms, to_ms) - from_ms) / 1000.0;
}

// "2024-05-01T12:00:00.100Z TX frame": a line of topdump's line log at
// T0 + ms (T0 is 2024-05-01T12:00:00Z; ms < 60000).
std::string line(int ms, const char* dirn, const std::string& frame) {
  char b[64];
  std::snprintf(b, sizeof b, "2024-05-01T12:%02d:%02d.%03dZ %s ", ms / 60000, ms / 1000 % 60,
                ms % 1000, dirn);
  return b + frame + "\n";
}
const char* kLineHeader = "# topdump line log: <ISO-8601 time> <TX|RX> <frame with C escapes>\n";
// A line log written in time order, whatever order its lines are added in.
struct LineLog {
  std::vector<std::pair<int, std::string>> lines;
  void add(int ms, const char* dirn, const std::string& frame) {
    lines.emplace_back(ms, line(ms, dirn, frame));
  }
  void write(const char* name) {
    std::stable_sort(lines.begin(), lines.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::string log = kLineHeader;
    for (const auto& l : lines) log += l.second;
    write_file(path(name), log);
  }
};

// A frame with its checksum digits in lowercase (a checksum with a letter).
std::string lowercase_checksum(const std::string& f) {
  std::string o = f;
  for (std::size_t i = o.size() - 2; i < o.size(); ++i)
    o[i] = static_cast<char>(std::tolower(static_cast<unsigned char>(o[i])));
  return o;
}

// What a UART at 57600 baud reads of a line sent at 115200 (8N1): the
// sender's bits, each half a receiver bit; the receiver waits for a start
// edge, samples the middle of each of its bits, and goes on whatever the
// stop bit holds.
std::string read_at_half_speed(const std::string& sent) {
  std::vector<int> bits;  // at the sender's rate
  for (int i = 0; i < 20; ++i) bits.push_back(1);
  for (char ch : sent) {
    const auto c = static_cast<unsigned char>(ch);
    bits.push_back(0);
    for (int b = 0; b < 8; ++b) bits.push_back((c >> b) & 1);
    bits.push_back(1);
  }
  for (int i = 0; i < 40; ++i) bits.push_back(1);
  std::string got;
  std::size_t t = 1;
  while (t + 20 < bits.size()) {
    if (!(bits[t - 1] == 1 && bits[t] == 0)) {
      ++t;
      continue;
    }
    unsigned v = 0;
    for (int b = 0; b < 8; ++b)
      v |= static_cast<unsigned>(bits[t + 3 + 2 * static_cast<std::size_t>(b)]) << b;
    got += static_cast<char>(v);
    t += 3 + 2 * 8 + 2;  // past the stop bit's middle
  }
  return got;
}

void stream_captures() {
  {  // GAA asks 10 Hz (0A); the camera pushes GAC at 5 Hz, steadily
    Udp u = skydroid("diag-stream-rate.pcap");
    for (int s = 0; s < 6; ++s) u.echoed(s * 1000, 4, "#TPUG2wGAA0A");
    for (int i = 0; i < 30; ++i) u.down(100 + i * 200, gac_at(0, -20));
  }
  {  // a SkyDroid yaw rate sent once and not refreshed: yaw turns for the
     // 1 s the speed-refresh trait gives it, then stops
    Udp u = skydroid("diag-refresh-gap.pcap");
    for (int s = 0; s < 4; ++s) u.echoed(s * 1000, 4, "#TPUG2wGAA0A");
    for (int i = 0; i < 40; ++i) {
      const int ms = 50 + i * 100;
      u.down(ms, gac_at(ramp(ms, 1000, 2000, 10), -20));
    }
    u.echoed(1000, 3, "#TPUG2wGSY14");
  }
  {  // a 10 Hz GAC stream that stops for 2 s and comes back
    Udp u = skydroid("diag-stream-stalled.pcap");
    for (int s = 0; s < 8; ++s) u.echoed(s * 1000, 4, "#TPUG2wGAA0A");  // re-sent every second
    for (int i = 0; i < 80; ++i)
      if (i < 30 || i >= 50) u.down(100 + i * 100, gac(i));
  }
  {  // Topotek: GIA 01 answered every second for 6 s, no GIC ever
    Udp u = topotek("diag-stream-never-started.pcap");
    for (int s = 0; s < 6; ++s) u.echoed(s * 1000, 5, "#TPPG2wGIA01");
    u.up(200, F("#TPPD2rVSN00"));
    u.down(210, F("#TPDP2rVSN28"));
  }
}

void identity_captures() {
  {
    Udp u = topotek("diag-placeholder-identity.pcap");
    u.up(0, F("#TPPG2rPA200"));
    u.down(8, F("#tpGP9rPA2000000000"));  // model name not set at production
    u.up(100, F("#TPPD2rVSN00"));
    u.down(106, F("#TPDP2rVSN28"));
  }
  {
    Udp u = topotek("diag-tracking-refused.pcap");
    u.echoed(0, 6, "#TPPD2wTRC02");  // prepare
    u.up(50, F("#TPPD2rTRC00"));
    u.down(52, F("#TPDP2rTRC04"));  // state 4: this lens does not track
    u.up(150, F("#TPPD2rTRC00"));
    u.down(152, F("#TPDP2rTRC04"));
  }
  {  // TIM with the 0-based month: 2024-04-01 on 2024-05-01
    Udp u = topotek("diag-clock-offset.pcap");
    u.echoed(0, 7, "#tpPDEwTIM20240401200000");
  }
}

void link_captures() {
  {  // requests with source U over UDP: the answers go to the UART
    Udp u = topotek("diag-reply-interface.pcap");
    for (int i = 0; i < 4; ++i) u.up(i * 500, F("#TPUD2rVSN00"));
    u.up(2000, F("#TPUG2rPA200"));
  }
  {  // a SkyDroid camera that says nothing
    Udp u = skydroid("diag-silent-device.pcap");
    for (int s = 0; s < 6; ++s) u.up(s * 1000, F("#TPUG2wGAA0A"));  // re-sent every second
    u.up(500, F("#TPUD2rVER00"));
    u.up(1500, F("#TPUG2wPTZ05"));
  }
  {  // SkyDroid over a serial line (socat -v): GAY with a bad checksum, dropped
    std::string log;
    auto add = [&](char d, int ms, const std::string& b) {
      log += socat_header(d, ms, b.size()) + socat_text(b);
    };
    add('>', 0, F("#TPUG2wPTZ05"));
    add('<', 6, F("#TPGU2wPTZ05"));
    for (int i = 0; i < 3; ++i) add('>', 100 + i * 100, "#tpUG6wGAYEC783200");
    add('>', 4000, F("#tpUG6wGAYEC7832"));
    add('<', 4012, F("#tpGU6wGAYEC7832"));
    write_file(path("diag-dropped-bad-checksum.log"), log);
  }
  {  // SkyDroid over a serial line (line log): a checksum in lowercase, dropped
    std::string log = kLineHeader;
    log += line(0, "TX", F("#TPUD2rVER00"));
    log += line(6, "RX", F("#tpDU6rVER010502"));
    log += line(100, "TX", lowercase_checksum(F("#TPUG2wPTZ05")));
    log += line(200, "TX", lowercase_checksum(F("#TPUG2wPTZ05")));
    log += line(3000, "TX", F("#TPUG2wPTZ05"));
    log += line(3008, "RX", F("#TPGU2wPTZ05"));
    write_file(path("diag-dropped-checksum-case.log"), log);
  }
  {  // a SkyDroid GAC stream at 115200 baud recorded at 57600
    std::string sent;
    for (int i = 0; i < 600; ++i) sent += gac(i);
    write_file(path("diag-baud-mismatch.bin"), read_at_half_speed(sent));
  }
}

void motion_captures() {
  {  // SkyDroid: a pitch rate up (GSP +20) for 1 s; the gimbal turns down
    Udp u = skydroid("diag-direction-inverted.pcap");
    for (int s = 0; s < 5; ++s) u.echoed(s * 1000, 4, "#TPUG2wGAA0A");
    for (int i = 0; i < 50; ++i)
      u.down(50 + i * 100, gac_at(0, ramp(50 + i * 100, 1000, 2000, -10)));
    for (int t = 1000; t < 2000; t += 50) u.echoed(t, 3, "#TPUG2wGSP14");
    for (int k = 0; k < 3; ++k) u.echoed(2000 + k * 50, 3, "#TPUG2wGSP00");
  }
  {  // Topotek over a serial line: GAP moves pitch; GAY is echoed, yaw stays
    LineLog log;
    log.add(0, "TX", F("#TPUG2wGIA01"));
    log.add(5, "RX", F("#TPGU2wGIA01"));
    for (int i = 0; i < 50; ++i) {
      const int ms = 50 + i * 100;
      log.add(ms, "RX", gia_at('U', 0, ramp(ms, 500, 2500, 10)));
    }
    log.add(500, "TX", F("#tpUG6wGAP07D032"));  // pitch to +20.00 deg
    log.add(506, "RX", F("#tpGU6wGAP07D032"));
    log.add(2600, "TX", F("#tpUG6wGAY0BB832"));  // yaw to +30.00 deg
    log.add(2606, "RX", F("#tpGU6wGAY0BB832"));
    log.write("diag-command-ignored.log");
  }
  {  // Topotek: the GIA push stops at 1 s for good; GIP targets keep coming
    Udp u = topotek("diag-attitude-stale.pcap");
    for (int s = 0; s < 5; ++s) u.echoed(s * 1000, 5, "#TPPG2wGIA01");
    for (int i = 0; i < 10; ++i) u.down(50 + i * 100, gia_at('P', 0, -30));
    for (int t = 200; t < 4000; t += 100) u.echoed(t, 4, "#tpPG6wGIP0BB863");  // 30 deg down
  }
  {  // Topotek over a serial line: a yaw rate (GSY 20 deg/s) sent three times
     // and never stopped (Topotek records no refresh timeout: the rate holds);
     // yaw keeps turning to the end
    LineLog log;
    log.add(0, "TX", F("#TPUG2wGIA01"));
    log.add(5, "RX", F("#TPGU2wGIA01"));
    for (int i = 0; i < 60; ++i) {
      const int ms = 50 + i * 100;
      log.add(ms, "RX", gia_at('U', ramp(ms, 1000, 6000, 10), -20));
    }
    for (int k = 0; k < 3; ++k) {
      log.add(1000 + k * 50, "TX", F("#TPUG2wGSY14"));
      log.add(1003 + k * 50, "RX", F("#TPGU2wGSY14"));
    }
    log.write("diag-axis-left-moving.log");
  }
}

void healthy_captures() {
  {  // SkyDroid over UDP: a steady stream, re-sent switches, answers
    Udp u = skydroid("diag-healthy-skydroid.pcap");
    for (int s = 0; s < 8; ++s) u.echoed(s * 1000, 4, "#TPUG2wGAA0A");
    for (int i = 0; i < 80; ++i) {
      const int ms = 100 + i * 100;  // yaw to +50 at 5 deg/s, pitch up 10 deg/s for 1 s
      u.down(ms, gac_at(ramp(ms, 650, 8000, 5), ramp(ms, 3000, 4000, 10) - 20));
    }
    u.up(550, F("#TPUD2rVER00"));
    u.down(555, F("#tpDU6rVER010502"));
    u.echoed(650, 12, "#tpUG6wGAY138832");  // yaw to +50.00 deg at 5.0 deg/s
    for (int t = 3000; t < 4000; t += 50) u.echoed(t, 3, "#TPUG2wGSP14");
    for (int k = 0; k < 3; ++k) u.echoed(4000 + k * 50, 3, "#TPUG2wGSP00");
  }
  {  // Topotek over UDP with source P: the stream, identity, tracking, time
    Udp u = topotek("diag-healthy-topotek.pcap");
    for (int s = 0; s < 6; ++s) u.echoed(s * 1000, 5, "#TPPG2wGIA01");
    for (int i = 0; i < 55; ++i) {
      const int ms = 50 + i * 100;  // pitch to 30 deg down at 15 deg/s from 1 s
      u.down(ms, gia_at('P', 0, ramp(ms, 1000, 3000, -15) > -30 ? ramp(ms, 1000, 3000, -15) : -30));
    }
    for (int t = 1000; t < 5000; t += 100) u.echoed(t, 4, "#tpPG6wGIP0BB863");  // 30 deg down
    u.up(200, F("#TPPG2rPA200"));
    u.down(208, F("#tpGP6rPA2SIP-T1"));
    u.up(300, F("#TPPD2rVSN00"));
    u.down(306, F("#TPDP2rVSN28"));
    u.echoed(400, 6, "#TPPD2wTRC02");
    u.up(450, F("#TPPD2rTRC00"));
    u.down(452, F("#TPDP2rTRC02"));                // tracking
    u.echoed(500, 7, "#tpPDEwTIM20240501200000");  // Beijing time, 8 h ahead of UTC
  }
  {  // SkyDroid over a serial line: the stream, the time, an angle
    std::string log = kLineHeader;
    log += line(0, "TX", F("#TPUG2wGAA0A"));
    log += line(6, "RX", F("#TPGU2wGAA0A"));
    for (int i = 0; i < 40; ++i) {
      const int ms = 100 + i * 100;  // yaw to +50 at 5 deg/s
      log += line(ms, "RX", gac_at(ramp(ms, 250, 4100, 5), -3));
    }
    log += line(150, "TX", F("#tpUDFwTIM120000.00010524"));
    log += line(160, "RX", F("#tpDUFwTIM120000.00010524"));
    log += line(250, "TX", F("#tpUG6wGAY138832"));  // yaw to +50.00 deg at 5.0 deg/s
    log += line(262, "RX", F("#tpGU6wGAY138832"));
    write_file(path("diag-healthy-serial.log"), log);
  }
}

}  // namespace

void diagnosis_captures() {
  stream_captures();
  identity_captures();
  link_captures();
  motion_captures();
  healthy_captures();
}

}  // namespace capture_kit
