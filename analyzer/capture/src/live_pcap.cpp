// Live capture on an interface through libpcap.
#include <pcap/pcap.h>
#include <poll.h>

#include <cerrno>
#include <cstring>

#include "capture/link.hpp"
#include "capture/live.hpp"

namespace topdump {

namespace {
struct LiveCtx {
  CaptureSink* a;
  Dissector* dis;
  int dlt;
  std::uint64_t record = 0;
};
void on_packet(u_char* user, const pcap_pkthdr* h, const u_char* data) {
  auto* c = reinterpret_cast<LiveCtx*>(user);
  ++c->record;
  std::int64_t ts = static_cast<std::int64_t>(h->ts.tv_sec) * 1000000 + h->ts.tv_usec;
  c->a->record(c->dis->packet(c->dlt, ts, data, h->caplen, h->len, c->record));
}
}  // namespace

bool capture_live(const std::string& iface, const std::string& bpf, CaptureSink& a,
                  const SourceOptions& o, const std::atomic<bool>& stop, std::string& error,
                  bool& permission) {
  permission = false;
  char errbuf[PCAP_ERRBUF_SIZE] = {0};
  pcap_t* p = pcap_create(iface.c_str(), errbuf);
  if (!p) {
    error = iface + ": " + errbuf;
    return false;
  }
  pcap_set_snaplen(p, 65535);
  pcap_set_promisc(p, 0);
  pcap_set_timeout(p, 100);
  pcap_set_immediate_mode(p, 1);
  int rc = pcap_activate(p);
  if (rc < 0) {
    permission = rc == PCAP_ERROR_PERM_DENIED;
    error = iface + ": " + pcap_statustostr(rc) + ": " + pcap_geterr(p);
    pcap_close(p);
    return false;
  }
  if (!bpf.empty()) {
    bpf_program prog;
    if (pcap_compile(p, &prog, bpf.c_str(), 1, PCAP_NETMASK_UNKNOWN) != 0 ||
        pcap_setfilter(p, &prog) != 0) {
      error = "filter \"" + bpf + "\": " + pcap_geterr(p);
      pcap_close(p);
      return false;
    }
    pcap_freecode(&prog);
  }
  int dlt = pcap_datalink(p);
  if (!Dissector::supported(dlt)) {
    error = iface + ": link type " + std::to_string(dlt) + " is not dissected";
    pcap_close(p);
    return false;
  }
  Dissector dis(a, o.udp_ports, o.tcp_ports);
  LiveCtx ctx{&a, &dis, dlt};
  // Non-blocking reads behind our own poll: pcap_dispatch in immediate mode
  // may block forever on a quiet interface, and SIGINT must end the loop.
  int fd = pcap_get_selectable_fd(p);
  if (fd < 0 || pcap_setnonblock(p, 1, errbuf) != 0) {
    error = iface + ": cannot poll the capture: " + errbuf;
    pcap_close(p);
    return false;
  }
  while (!stop.load()) {
    pollfd pfd{fd, POLLIN, 0};
    if (poll(&pfd, 1, 100) < 0 && errno != EINTR) {
      error = iface + ": poll: " + std::strerror(errno);
      pcap_close(p);
      return false;
    }
    int n = pcap_dispatch(p, -1, on_packet, reinterpret_cast<u_char*>(&ctx));
    if (n == PCAP_ERROR) {
      error = iface + ": " + pcap_geterr(p);
      pcap_close(p);
      return false;
    }
    a.flush_streams();
  }
  pcap_close(p);
  return true;
}

}  // namespace topdump
