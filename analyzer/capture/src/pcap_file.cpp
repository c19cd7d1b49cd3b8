// pcap and pcapng files through libpcap: each record dissected into the
// sink, and libpcap's read errors turned into findings with their offset.
#include <pcap/pcap.h>

#include <cstdio>
#include <cstring>

#include "capture/link.hpp"
#include "readers.hpp"

namespace topdump {

namespace {

// type 2, 3 and 6), walking the block lengths; or the file size when the
// walk ends first.
std::uint64_t pcapng_block_offset(std::FILE* f, std::uint64_t record) {
  if (std::fseek(f, 0, SEEK_SET) != 0) return 0;
  std::uint64_t at = 0, packets = 0;
  bool big = false;
  unsigned char h[12];
  while (std::fread(h, 1, 8, f) == 8) {
    auto u32 = [&](const unsigned char* p) {
      return big ? std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 |
                       std::uint32_t{p[2]} << 8 | p[3]
                 : std::uint32_t{p[3]} << 24 | std::uint32_t{p[2]} << 16 |
                       std::uint32_t{p[1]} << 8 | p[0];
    };
    if (std::memcmp(h, "\x0a\x0d\x0d\x0a", 4) == 0) {
      if (std::fread(h + 8, 1, 4, f) != 4) break;
      big = h[8] == 0x1a;
    }
    std::uint32_t type = u32(h), len = u32(h + 4);
    if (type == 2 || type == 3 || type == 6) {
      if (++packets == record) return at;
    }
    if (len < 12 || len % 4 != 0) return at;
    at += len;
    if (std::fseek(f, static_cast<long>(at), SEEK_SET) != 0) break;
  }
  return at;
}

// The finding a libpcap read error stands for.
ACode code_of_pcap_error(std::string_view e) {
  if (e.find("invalid packet capture length") != std::string_view::npos) return ACode::bad_caplen;
  if (e.find("has a length of") != std::string_view::npos ||
      e.find("total length in header and trailer") != std::string_view::npos)
    return ACode::bad_block_length;
  if (e.find("a packet arrived on interface") != std::string_view::npos)
    return ACode::unknown_interface;
  if (e.find("truncated") != std::string_view::npos) return ACode::truncated_file;
  return ACode::bad_block;
}

}  // namespace

bool read_capture_file(Input& in, Format format, CaptureSink& a, const SourceOptions& o,
                       std::string& error, InputInfo what, InputInfo* info) {
  const std::string& path = in.name;
  const std::size_t header = format == Format::pcapng ? 28 : 24;
  if (in.head.size() < header) {
    error = path + ": offset 0: the " + std::string(to_string(format)) +
            " file header is cut short (" + std::to_string(in.head.size()) + " of " +
            std::to_string(header) + " bytes)";
    return false;
  }
  char errbuf[PCAP_ERRBUF_SIZE] = {0};
  // pcap_close() closes the file; the Input's buffer outlives it.
  std::FILE* file = in.file;
  pcap_t* p = pcap_fopen_offline_with_tstamp_precision(file, PCAP_TSTAMP_PRECISION_MICRO, errbuf);
  if (!p) {
    error = path + ": offset 0: " + errbuf;
    return false;
  }
  in.file = nullptr;
  int dlt = pcap_datalink(p);
  const char* dlt_name = pcap_datalink_val_to_name(dlt);
  what.link = dlt_name ? dlt_name : std::to_string(dlt);
  if (info) *info = what;
  if (o.on_input) o.on_input(what);
  if (!Dissector::supported(dlt)) {
    a.source_note(kNoTime, ACode::unsupported_link,
                  path + ": link type " + std::to_string(dlt) + " (" + (dlt_name ? dlt_name : "?") +
                      ") is not dissected",
                  0, 0);
    pcap_close(p);
    return true;
  }
  const std::uint64_t total = in.size;
  const bool ng = format == Format::pcapng;
  // pcap_loop hands each record to the callback from inside libpcap's read
  // loop (pcap_next_ex costs a call chain per record). pcap: records follow
  // a 24-byte header, each with a 16-byte header, so the file offset of a
  // record is known without asking the stream (an lseek per record).
  // pcapng: found by walking the blocks after a failure.
  struct Reader {
    Dissector dis;
    CaptureSink& a;
    const SourceOptions& o;
    int dlt;
    FILE* fp;
    std::uint64_t total;
    std::uint64_t at = 24;
    std::uint64_t record = 0;
    pcap_t* pcap = nullptr;
  } rd{Dissector(a, o.udp_ports, o.tcp_ports), a, o, dlt, in.regular ? file : nullptr, total};
  rd.pcap = p;
  const int rc = pcap_loop(
      p, -1,
      [](u_char* user, const pcap_pkthdr* h, const u_char* data) {
        auto& r = *reinterpret_cast<Reader*>(user);
        ++r.record;
        r.at += 16 + h->caplen;
        const std::int64_t ts = static_cast<std::int64_t>(h->ts.tv_sec) * 1000000 + h->ts.tv_usec;
        if (r.o.packet)
          r.o.packet(r.dlt, ts, std::string_view(reinterpret_cast<const char*>(data), h->caplen),
                     h->len, r.record);
        r.a.record(r.dis.packet(r.dlt, ts, data, h->caplen, h->len, r.record));
        if (r.a.done()) pcap_breakloop(r.pcap);  // -c: the frames asked for are in
        if (r.o.progress && (r.record & 0xFFFF) == 0 && r.fp)
          r.o.progress(static_cast<std::uint64_t>(std::ftell(r.fp)), r.total);
      },
      reinterpret_cast<u_char*>(&rd));
  if (rc == PCAP_ERROR) {
    const std::string why = pcap_geterr(p);
    std::uint64_t at = rd.at;
    std::string where;
    if (!ng) {
      where = "at file offset " + std::to_string(at);
    } else if (in.regular) {
      at = pcapng_block_offset(file, rd.record + 1);
      where = "in the block at file offset " + std::to_string(at);
    } else {
      at = 0;
      where = "(a pipe: offset unknown)";
    }
    a.source_note(kNoTime, code_of_pcap_error(why),
                  path + ": record " + std::to_string(rd.record + 1) + " " + where + ": " + why,
                  rd.record + 1, at);
  }
  pcap_close(p);
  if (o.progress) o.progress(total, total);
  return true;
}

}  // namespace topdump
