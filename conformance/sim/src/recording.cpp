#include "recording.hpp"

#include <chrono>
#include <ctime>
#include <stdexcept>

#include "top/text.hpp"

namespace topsim {

Recording::Recording(const std::string& path, bool line, bool tcp, pcapio::Endpoint client)
    : path_(path), client_(std::move(client)) {
  if (!line) {
    pcap_ = std::make_unique<pcapio::Recorder>(path, tcp);
    return;
  }
  log_ = std::fopen(path.c_str(), "w");
  if (!log_) throw std::runtime_error("record: cannot write " + path);
  std::fputs("# topsim's serial line: <ISO-8601 time> <TX|RX> <bytes with C escapes>\n", log_);
}

Recording::~Recording() {
  if (log_) std::fclose(log_);
}

void Recording::write(const pcapio::Endpoint& from, const pcapio::Endpoint& to,
                      std::string_view bytes) {
  if (pcap_) {
    pcap_->write(from, to, bytes);
    return;
  }
  using namespace std::chrono;
  const auto us = duration_cast<microseconds>(system_clock::now().time_since_epoch()).count();
  const std::time_t s = static_cast<std::time_t>(us / 1000000);
  std::tm tm{};
  gmtime_r(&s, &tm);
  char t[48];
  std::strftime(t, sizeof t, "%Y-%m-%dT%H:%M:%S", &tm);
  std::fprintf(log_, "%s.%06lldZ %s %s\n", t, static_cast<long long>(us % 1000000),
               from == client_ ? "TX" : "RX", top::escape(bytes).c_str());
}

void Recording::flush() {
  if (pcap_) pcap_->flush();
  if (log_) std::fflush(log_);
}

}  // namespace topsim
