#include "pcapio/writer.hpp"

#include <pcap/pcap.h>
#include <sys/time.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
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
bool PcapWriter::finish() {
  if (!dumper_) return false;
  bool ok = pcap_dump_flush(dumper_) == 0 && !std::ferror(pcap_dump_file(dumper_));
  // pcap_dump_close() is fclose() of this stream and returns nothing: close
  // it here to see its status
  ok = std::fclose(pcap_dump_file(dumper_)) == 0 && ok;
  dumper_ = nullptr;
  close();
  return ok;
}
void PcapWriter::write(std::int64_t ts, std::string_view bytes, std::size_t caplen,
                       std::size_t len) {
  if (!dumper_) return;
  pcap_pkthdr h{};
  h.ts.tv_sec = static_cast<time_t>(ts / 1000000);
  h.ts.tv_usec = static_cast<suseconds_t>(ts % 1000000);
  h.len = static_cast<bpf_u_int32>(std::max(len, bytes.size()));
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

namespace {

void ng_block(std::string& out, std::uint32_t type, const std::string& body) {
  const auto len = static_cast<std::uint32_t>(12 + body.size());
  le32a(out, type);
  le32a(out, len);
  out += body;
  le32a(out, len);
}

// The section header and one interface block per link type.
std::string ng_head(const std::vector<std::uint16_t>& linktypes) {
  std::string out;
  std::string shb;
  le32a(shb, 0x1A2B3C4D);  // byte-order magic
  le16a(shb, 1);           // version 1.0
  le16a(shb, 0);
  le32a(shb, 0xFFFFFFFF);  // section length: not given
  le32a(shb, 0xFFFFFFFF);
  ng_block(out, 0x0A0D0D0A, shb);
  for (std::uint16_t lt : linktypes) {
    std::string idb;
    le16a(idb, lt);
    le16a(idb, 0);
    le32a(idb, 65535);  // snap length
    ng_block(out, 1, idb);
  }
  return out;
}

// An enhanced packet block; `len` is the length on the wire.
void ng_packet(std::string& out, std::uint32_t interface, std::int64_t ts_us,
               std::string_view bytes, std::size_t len) {
  std::string epb;
  le32a(epb, interface);
  const auto ts = static_cast<std::uint64_t>(ts_us);
  le32a(epb, static_cast<std::uint32_t>(ts >> 32));
  le32a(epb, static_cast<std::uint32_t>(ts & 0xFFFFFFFF));
  le32a(epb, static_cast<std::uint32_t>(bytes.size()));
  le32a(epb, static_cast<std::uint32_t>(std::max(len, bytes.size())));
  epb += bytes;
  while (epb.size() % 4) epb += '\0';
  ng_block(out, 6, epb);
}

}  // namespace

std::string pcapng(const std::vector<std::uint16_t>& linktypes,
                   const std::vector<NgPacket>& packets) {
  std::string out = ng_head(linktypes);
  for (const NgPacket& p : packets) ng_packet(out, p.interface, p.ts_us, p.bytes, p.bytes.size());
  return out;
}

bool CaptureWriter::is_pcapng(const std::string& path) {
  constexpr std::string_view ext = ".pcapng";
  return path.size() >= ext.size() && path.compare(path.size() - ext.size(), ext.size(), ext) == 0;
}

CaptureWriter::CaptureWriter(const std::string& path, int dlt) : path_(path) {
  if (is_pcapng(path)) {
    ng_ = std::fopen(path.c_str(), "wb");
    if (!ng_) {
      error_ = path + ": " + std::strerror(errno);
      return;
    }
    const std::string head = ng_head({static_cast<std::uint16_t>(dlt)});
    if (std::fwrite(head.data(), 1, head.size(), ng_) != head.size()) failed_ = errno ? errno : EIO;
  } else {
    pcap_ = std::make_unique<PcapWriter>(path, dlt);
    if (!pcap_->ok()) error_ = path + ": " + pcap_->error();
  }
}

CaptureWriter::~CaptureWriter() { close(); }

void CaptureWriter::write(std::int64_t ts_us, std::string_view bytes, std::size_t len) {
  if (ng_) {
    buf_.clear();
    ng_packet(buf_, 0, ts_us, bytes, len);
    if (std::fwrite(buf_.data(), 1, buf_.size(), ng_) != buf_.size() && !failed_)
      failed_ = errno ? errno : EIO;
  } else if (pcap_ && pcap_->ok()) {
    pcap_->write(ts_us, bytes, SIZE_MAX, len);
  }
}

bool CaptureWriter::close() {
  if (ng_) {
    if (std::fflush(ng_) != 0 && !failed_) failed_ = errno ? errno : EIO;
    if (std::ferror(ng_) && !failed_) failed_ = EIO;
    if (std::fclose(ng_) != 0 && !failed_) failed_ = errno ? errno : EIO;
    ng_ = nullptr;
  }
  if (pcap_) {
    if (!pcap_->finish() && !failed_) failed_ = errno ? errno : EIO;
    pcap_.reset();
  }
  if (failed_ && error_.empty()) error_ = path_ + ": write error: " + std::strerror(failed_);
  return error_.empty();
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
