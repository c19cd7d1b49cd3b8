#include "sim/intake.hpp"

#include <utility>

namespace topsim {

std::size_t Intake::drain(top::StreamDecoder& dec, std::uint64_t now_us,
                          std::vector<std::string>& out, std::vector<top::Frame>* received) const {
  std::size_t frames = 0;
  top::StreamItem item;
  while (dec.next(item)) {
    if (item.kind != top::ItemKind::frame) continue;
    ++frames;
    if (faults && !faults->admit(item.frame, now_us)) continue;
    device.handle(item.frame, link, now_us, out);
    if (received) received->push_back(std::move(item.frame));
  }
  return frames;
}

std::size_t Intake::take(top::StreamDecoder& dec, std::string_view bytes, bool datagram,
                         std::uint64_t now_us, std::vector<std::string>& out,
                         std::vector<top::Frame>* received) const {
  dec.feed(bytes);
  if (datagram)
    dec.finish();
  else
    dec.flush();
  const std::size_t frames = drain(dec, now_us, out, received);
  if (datagram) dec.reset();
  return frames;
}

Session::Session(Device& device, Link link, bool datagram)
    : intake_{device, link}, datagram_(datagram) {}

void Session::feed(std::string_view bytes, std::uint64_t now_us, std::vector<std::string>& out,
                   std::vector<top::Frame>* received) {
  intake_.take(decoder_, bytes, datagram_, now_us, out, received);
}

std::vector<std::string> handle_datagram(Device& device, std::string_view bytes, Link link,
                                         std::uint64_t now_us) {
  std::vector<std::string> out;
  Session s(device, link, true);
  s.feed(bytes, now_us, out);
  return out;
}

}  // namespace topsim
