// What topsim records of its traffic (--record): a pcap of its UDP or TCP
// datagrams and segments (pcapio::Recorder), or, for a serial line or
// pseudo-terminal, topdump's line log ("<ISO-8601 time> <TX|RX> <bytes with
// C escapes>", captures/README.md): a pcap would show the line as UDP, and
// a reader would take a UART client's source U for a network client's.
#pragma once

#include <cstdio>
#include <memory>
#include <string>
#include <string_view>

#include "pcapio/endpoint.hpp"
#include "pcapio/writer.hpp"

namespace topsim {

class Recording {
 public:
  // Opens `path`: a line log when `line` (the bytes from `client` are TX),
  // else a pcap (TCP when `tcp`). Throws std::runtime_error naming the file.
  Recording(const std::string& path, bool line, bool tcp, pcapio::Endpoint client);
  ~Recording();
  Recording(const Recording&) = delete;
  Recording& operator=(const Recording&) = delete;
  void write(const pcapio::Endpoint& from, const pcapio::Endpoint& to, std::string_view bytes);
  void flush();

 private:
  std::unique_ptr<pcapio::Recorder> pcap_;
  std::FILE* log_ = nullptr;
  std::string path_;
  pcapio::Endpoint client_;
};

}  // namespace topsim
