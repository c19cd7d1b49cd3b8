// Writes the synthetic sample captures of captures/ (see captures/README.md).
// Deterministic: the same bytes on every run. Usage: make_captures DIR
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "capture_kit.hpp"

using namespace pcapio;
using namespace capture_kit;

namespace {
void sample() {
  // SkyDroid C12 over Ethernet/IPv4/UDP 5000: the bundled sample.
  Udp u("sample.pcap", kEn10mb, 40000, 5000);
  u.echoed(0, 4, "#TPUG2wGAA0A");                              // attitude push at 10 Hz
  for (int i = 0; i < 12; ++i) u.down(100 + i * 100, gac(i));  // the stream, 10 Hz
  u.echoed(150, 12, "#tpUG6wGAYEC7832");  // yaw -50.00 deg at speed 0x32; echo after 12 ms
  u.up(300, F("#tpUG6wGAP03E832") + F("#TPUG2wPTZ05"));  // two frames in one datagram
  u.down(309, F("#tpGU6wGAP03E832") + "\r\n");           // CRLF after the frame
  u.down(311, F("#TPGU2wPTZ05"));
  u.up(400,
       "#tpUG6wGAY0000"
       "3200");                                                       // wrong checksum ("00")
  u.up(500, F("#TPUD2rVER00"));                                       // never answered
  u.up(600, F("#TPUM2wXYZ01"));                                       // unknown identifier ...
  u.down(607, F("#TPMU2wERE!!"));                                     // ... rejected with ERE
  u.down(700, F("#TPDU2wREC01"));                                     // nobody asked
  for (int i = 0; i < 3; ++i) u.up(800 + 30 * i, F("#TPUG2wPTZ00"));  // sent three times
  u.down(805, F("#TPGU2wPTZ00"));
  u.echoed(900, 10, "#tpUG6wGAYfe0c32");  // lowercase hex data
  u.up(1000, F("#tpUG6wGAY03E832"));
  u.down(1011, F("#tpUG6wGAY03E832"));  // simulator: addresses not swapped
}

void topotek_vlan() {
  // Topotek SIP over Ethernet + 802.1Q VLAN 100, UDP 9004 -> 9003.
  Udp u("topotek-vlan.pcap", kEn10mb, 9004, 9003);
  u.vlans = {100};
  u.echoed(0, 5, "#TPPG2wGIA01");
  for (int i = 0; i < 6; ++i) u.down(50 + i * 50, F(std::string("#tpGPCrGIC") + "FF36ED5A0048"));
  // GPS struct: heading 0x2323 ('##'), longitude with a '#' byte
  std::string gps = "#tpPDEwGPS";
  gps += std::string("\x23\x23\x40\x23\x5e\x45\x11\xe4\x23\x0d\xe8\x03\x00\x00", 14);
  u.up(400, F(gps));
  u.up(500, F("#TPPD2rTMP00"));
  u.down(520, F("#PDP16TMP1008001720504000FA0123"));    // the documented malformed form
  u.down(560, F("#tpDP16wTMP1008001720504000FA0123"));  // two-digit length form
  u.up(600, F("#TPPD2wREC01"));
  u.down(640, F("#tpDPAwREC0000000012"));  // file index, not an echo
}

void links() {
  {
    Udp u("sll.pcap", kSll, 40001, 5000);
    u.echoed(0, 10, "#tpUG6wGAYEC7832");
  }
  {
    Udp u("sll2.pcap", kSll2, 40002, 5000);
    u.echoed(0, 8, "#TPUG2wPTZ05");
  }
  {
    Udp u("rawip.pcap", kRaw, 40003, 12580);
    u.up(0, F("#TPUD2rVER00"));
    u.down(20, F("#tpDU6rVER010502"));
    u.v6 = true;
    u.echoed(30, 10, "#TPUG2wPTZ01");
  }
  {
    Udp u("loopback-null.pcap", kNull, 40004, 5000);
    u.echoed(0, 6, "#TPUG2wPTZ05");
    u.v6 = true;
    u.echoed(10, 6, "#TPUG2wPTZ00");
  }
  {
    Udp u("ipv6.pcap", kEn10mb, 40005, 5000);
    u.v6 = true;
    u.echoed(0, 9, "#tpUG6wGAYEC7832");
    u.echoed(20, 4, "#TPUG2wGAA05");
    // 5 Hz asked, 2 Hz sent: stream-rate finding
    for (int i = 0; i < 5; ++i) u.down(100 + i * 500, gac(i));
  }
}

void tcp() {
  // SkyDroid C10 on TCP 5000: split frames, several per segment,
  // retransmission, out of order, an overlap that disagrees.
  PcapWriter w(path("tcp-c10.pcap"), kEn10mb);
  std::uint16_t cp = 50000, sp = 5000;
  std::uint32_t cs = 1000, ss = 9000;
  auto up = [&](std::int64_t ms, std::uint32_t seq, std::uint8_t fl, const std::string& p) {
    w.write(T0 + ms * 1000, eth(tcp4(kClient, kCamera, cp, sp, seq, ss, fl, p)));
  };
  auto down = [&](std::int64_t ms, std::uint32_t seq, std::uint8_t fl, const std::string& p) {
    w.write(T0 + ms * 1000, eth(tcp4(kCamera, kClient, sp, cp, seq, cs, fl, p)));
  };
  up(0, cs - 1, kSyn, "");
  down(1, ss - 1, kSyn | kAck, "");
  up(2, cs, kAck, "");
  std::string a = F("#tpUG6wGAYEC7832"), b = F("#TPUG2wPTZ05"), c = F("#TPUD2rVER00");
  // a split in two segments
  up(10, cs, kAck | kPsh, a.substr(0, 7));
  up(11, cs + 7, kAck | kPsh, a.substr(7));
  cs += static_cast<std::uint32_t>(a.size());
  std::string ra = F("#tpGU6wGAYEC7832");
  down(20, ss, kAck | kPsh, ra);
  down(21, ss, kAck | kPsh, ra);  // retransmitted
  ss += static_cast<std::uint32_t>(ra.size());
  // b and c in one segment, sent out of order as two: second half first
  std::string bc = b + c;
  up(30, cs + 6, kAck | kPsh, bc.substr(6));
  up(31, cs, kAck | kPsh, bc.substr(0, 6));
  cs += static_cast<std::uint32_t>(bc.size());
  std::string rb = F("#TPGU2wPTZ05"), rc = F("#tpDU6rVER010502");
  down(40, ss, kAck | kPsh, rb + rc);
  // an overlapping segment whose bytes disagree with what was delivered
  std::string bad = rc;
  bad[5] = 'X';
  down(41, ss + static_cast<std::uint32_t>(rb.size()), kAck | kPsh, bad);
  ss += static_cast<std::uint32_t>(rb.size() + rc.size());
  up(50, cs, kAck | kFin, "");
}

void truncated() {
  std::string p = path("truncated.pcap");
  {
    PcapWriter w(p, kEn10mb, 65535);
    auto pkt = [&](const std::string& pl, bool upward) {
      return eth(upward ? udp4(kClient, kCamera, 40006, 5000, pl)
                        : udp4(kCamera, kClient, 5000, 40006, pl));
    };
    w.write(T0, pkt(F("#tpUG6wGAYEC7832"), true));
    w.write(T0 + 10000, pkt(F("#tpGU6wGAYEC7832"), false));
    std::string cut = pkt(F("#tpUG6wGAP03E832"), true);
    w.write(T0 + 20000, cut, cut.size() - 6);  // cut by the snap length
    w.write(T0 + 30000, pkt(F("#TPUG2wPTZ05"), true));
    w.write(T0 + 40000, pkt(F("#TPGU2wPTZ05"), false));
  }
  // cut the file inside the last record
  std::FILE* f = std::fopen(p.c_str(), "rb");
  std::string all;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) all.append(buf, n);
  std::fclose(f);
  write_file(p, all.substr(0, all.size() - 20));
}

void multi_interface() {
  std::vector<NgPacket> pk;
  auto add = [&](std::uint32_t ifc, std::int64_t ms, const std::string& ip) {
    pk.push_back(NgPacket{ifc, T0 + ms * 1000, eth(ip)});
  };
  Ip4 c2{10, 0, 0, 2}, d2{10, 0, 0, 9};
  add(0, 0, udp4(kClient, kCamera, 40007, 5000, F("#TPUG2wPTZ05")));
  add(1, 1, udp4(c2, d2, 9004, 9003, F("#TPPG2wGIA01")));
  add(0, 7, udp4(kCamera, kClient, 5000, 40007, F("#TPGU2wPTZ05")));
  add(1, 9, udp4(d2, c2, 9003, 9004, F("#TPGP2wGIA01")));
  write_file(path("multi-if.pcapng"), pcapng({1, 1}, pk));
}

void serial_logs() {
  struct Chunk {
    char dirc;
    int ms;
    std::string bytes;
  };
  std::vector<Chunk> chunks = {
      {'>', 0, F("#TPUG2wGAA05") + "\r\n"},
      {'<', 6, F("#TPGU2wGAA05") + "\r\n"},
      {'>', 100, F("#tpUG6wGAYEC7832").substr(0, 9)},
      {'>', 101, F("#tpUG6wGAYEC7832").substr(9)},
      {'<', 112, F("#tpGU6wGAYEC7832")},
      {'<', 200, gac(0) + gac(1).substr(0, 10)},
      {'<', 300, gac(1).substr(10)},
      {'<', 400, std::string("\x01\x02", 2) + gac(2)},
  };
  std::string text, hex, lines, raw;
  for (const auto& c : chunks) {
    text += socat_header(c.dirc, c.ms, c.bytes.size()) + socat_text(c.bytes);
    hex += socat_header(c.dirc, c.ms, c.bytes.size()) + socat_hex(c.bytes);
  }
  write_file(path("serial-socat-v.log"), text);
  write_file(path("serial-socat-xv.log"), hex);

  // line log
  lines += "# topdump line log: <ISO-8601 time> <TX|RX> <frame with C escapes>\n";
  lines += "2024-05-01T12:00:00.000Z TX " + F("#TPUG2wGAA05") + "\n";
  lines += "2024-05-01T12:00:00.006Z RX " + F("#TPGU2wGAA05") + "\\r\\n\n";
  lines += "2024-05-01T12:00:00.100Z TX " + F("#tpUG6wGAYEC7832") + "\n";
  lines += "2024-05-01T12:00:00.118Z RX " + F("#tpGU6wGAYEC7832") + "\n";
  lines += "2024-05-01T12:00:00.200Z RX " + gac(0) + "\n";
  lines += "2024-05-01T12:00:00.400Z RX " + gac(1) + "\n";
  lines += "2024-05-01T12:00:00.500Z TX " + F("#TPUD2rVER00") + "\n";
  lines += "2024-05-01T12:00:00.505Z RX " + F("#tpDU6rVER010502") + "\n";
  lines += "yesterday TX #TPUG2wPTZ05\n";
  write_file(path("serial-lines.log"), lines);

  // raw: what a device sent, one direction
  raw = gac(0) + gac(1) + std::string("\x00\xff#", 3) + gac(2) + "\r\n" + F("#TPGU2wPTZ05") +
        gac(3).substr(0, 12);
  write_file(path("serial-raw.bin"), raw);

  // Saleae Logic 2 async serial export, one row per byte, two channels
  std::string csv = "name,type,start_time,duration,data,error\n";
  auto add = [&](const char* name, double t0, const std::string& bytes) {
    for (std::size_t i = 0; i < bytes.size(); ++i) {
      char b[128];
      std::snprintf(b, sizeof b, "%s,data,%.9f,8.68e-05,0x%02X,\n", name,
                    t0 + static_cast<double>(i) * 86.8e-6, static_cast<unsigned char>(bytes[i]));
      csv += b;
    }
  };
  add("TX", 0.5, F("#TPUG2wPTZ05"));
  add("RX", 0.51, F("#TPGU2wPTZ05"));
  add("TX", 0.6, F("#TPUD2rVER00"));
  add("RX", 0.62, F("#tpDU6rVER010502"));
  csv += "RX,data,0.700000000,8.68e-05,0x23,framing\n";
  write_file(path("serial-saleae.csv"), csv);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_captures DIR\n");
    return 2;
  }
  dir = argv[1];
  sample();
  topotek_vlan();
  links();
  tcp();
  truncated();
  multi_interface();
  serial_logs();
  diagnosis_captures();
  return 0;
}
