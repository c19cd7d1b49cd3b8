#include "pcapio/writer.hpp"

#include <pcap/pcap.h>
#include <sys/time.h>

#include <algorithm>
#include <fstream>
#include <stdexcept>

#include "pcapio/packet.hpp"

namespace pcapio {

PcapWriter::PcapWriter(const std::string& path, int dlt, int snaplen) {
  p_ = pcap_open_dead_with_tstamp_precision(dlt, snaplen, PCAP_TSTAMP_PRECISION_MICRO);
  if (!p_) {
    error_ = "pcap_open_dead failed";
    return;
  }
  dumper_ = pcap_dump_open(p_, path.c_str());
  if (!dumper_) error_ = pcap_geterr(p_);
}
PcapWriter::~PcapWriter() { close(); }
void PcapWriter::close() {
  if (dumper_) pcap_dump_close(dumper_);
  if (p_) pcap_close(p_);
  dumper_ = nullptr;
  p_ = nullptr;
}
void PcapWriter::flush() {
  if (dumper_) pcap_dump_flush(dumper_);
}
void PcapWriter::write(std::int64_t ts, std::string_view bytes, std::size_t caplen) {
  if (!dumper_) return;
  pcap_pkthdr h{};
  h.ts.tv_sec = static_cast<time_t>(ts / 1000000);
  h.ts.tv_usec = static_cast<suseconds_t>(ts % 1000000);
  h.len = static_cast<bpf_u_int32>(bytes.size());
  h.caplen = static_cast<bpf_u_int32>(std::min(caplen, bytes.size()));
  pcap_dump(reinterpret_cast<u_char*>(dumper_), &h, reinterpret_cast<const u_char*>(bytes.data()));
}

namespace {
void le16a(std::string& s, std::uint32_t v) {
  s += static_cast<char>(v & 0xFF);
  s += static_cast<char>((v >> 8) & 0xFF);
}
void le32a(std::string& s, std::uint32_t v) {
  le16a(s, v & 0xFFFF);
  le16a(s, v >> 16);
}
}  // namespace

std::string pcapng(const std::vector<std::uint16_t>& linktypes,
                   const std::vector<NgPacket>& packets) {
  std::string out;
  auto block = [&](std::uint32_t type, const std::string& body) {
    const auto len = static_cast<std::uint32_t>(12 + body.size());
    le32a(out, type);
    le32a(out, len);
    out += body;
    le32a(out, len);
  };
  std::string shb;
  le32a(shb, 0x1A2B3C4D);  // byte-order magic
  le16a(shb, 1);           // version 1.0
  le16a(shb, 0);
  le32a(shb, 0xFFFFFFFF);  // section length: not given
  le32a(shb, 0xFFFFFFFF);
  block(0x0A0D0D0A, shb);
  for (std::uint16_t lt : linktypes) {
    std::string idb;
    le16a(idb, lt);
    le16a(idb, 0);
    le32a(idb, 65535);  // snap length
    block(1, idb);
  }
  for (const NgPacket& p : packets) {
    std::string epb;
    le32a(epb, p.interface);
    const auto ts = static_cast<std::uint64_t>(p.ts_us);
    le32a(epb, static_cast<std::uint32_t>(ts >> 32));
    le32a(epb, static_cast<std::uint32_t>(ts & 0xFFFFFFFF));
    le32a(epb, static_cast<std::uint32_t>(p.bytes.size()));
    le32a(epb, static_cast<std::uint32_t>(p.bytes.size()));
    epb += p.bytes;
    while (epb.size() % 4) epb += '\0';
    block(6, epb);
  }
  return out;
}

bool write_file(const std::string& path, std::string_view bytes) {
  std::ofstream f(path, std::ios::binary);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return static_cast<bool>(f);
}

Recorder::Recorder(const std::string& path, bool tcp) : file_(path, DLT_EN10MB), tcp_(tcp) {
  if (!file_.ok()) throw std::runtime_error(path + ": " + file_.error());
}

void Recorder::write(const Endpoint& from, const Endpoint& to, std::string_view payload) {
  constexpr std::size_t kMax = 65000;
  do {
    const std::string_view part = payload.substr(0, std::min(kMax, payload.size()));
    packet(from, to, part);
    payload.remove_prefix(part.size());
  } while (!payload.empty());
}

void Recorder::packet(const Endpoint& from, const Endpoint& to, std::string_view payload) {
  auto ip = [](const Endpoint& e) {
    const std::uint32_t v = e.family == 4 ? e.ipv4() : 0x7F000001u;
    return Ip4{static_cast<std::uint8_t>(v >> 24), static_cast<std::uint8_t>(v >> 16),
               static_cast<std::uint8_t>(v >> 8), static_cast<std::uint8_t>(v)};
  };
  // locally administered MACs derived from the ports
  auto mac = [](const Endpoint& e) {
    return Mac{0x02,
               0,
               0,
               0,
               static_cast<std::uint8_t>(e.port >> 8),
               static_cast<std::uint8_t>(e.port & 0xFF)};
  };
  const Ip4Options o{ip_id_++, true};
  std::string l3;
  if (tcp_) {
    const bool a_side = from.port < to.port;
    std::uint32_t& seq = a_side ? seq_a_ : seq_b_;
    const std::uint32_t ack = a_side ? seq_b_ : seq_a_;
    l3 = tcp4(ip(from), ip(to), from.port, to.port, seq, ack, kPsh | kAck, payload, o);
    seq += static_cast<std::uint32_t>(payload.size());
  } else {
    l3 = udp4(ip(from), ip(to), from.port, to.port, payload, o);
  }
  timeval tv{};
  gettimeofday(&tv, nullptr);
  file_.write(std::int64_t{tv.tv_sec} * 1000000 + tv.tv_usec, eth(l3, {}, mac(to), mac(from)));
  ++packets_;
}

}  // namespace pcapio
