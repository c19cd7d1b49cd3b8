#include "conf/link.hpp"

#include <utility>

#include "top/device.hpp"

namespace topconf {

bool is_push(top::Dialect d, std::string_view ident) {
  const top::StreamSpec* s = top::stream_of(d, ident);
  return s && s->sender == top::Sender::device;
}

const top::DeviceForm* recorded_form_of(top::Dialect d, top::Model m, const top::Frame& f) {
  const top::Sent sent = is_push(d, f.ident_view()) ? top::Sent::push : top::Sent::reply;
  return top::recorded_form(d, m, f, sent);
}

bool reply_addressed(top::Dialect d, top::Model m, const top::Frame& f, char src, char dst) {
  if (f.src == dst && f.dst == src) return true;
  if (f.src != src || f.dst != dst) return false;
  const top::DeviceForm* rf = recorded_form_of(d, m, f);
  return rf && rf->order == top::Order::request_order;
}

void FrameLink::send(std::string_view bytes) {
  if (on_send) on_send(bytes);
  if (pcap_) pcap_->write(t_.local(), t_.remote(), bytes);
  t_.send(bytes);
}

bool FrameLink::next(std::uint64_t deadline, Received& out) {
  std::size_t late = 0;
  for (;;) {
    if (!frames_.empty()) {
      out = std::move(frames_.front());
      frames_.pop_front();
      return true;
    }
    // Past the deadline only what is already there is read, and a
    // flooding peer cannot keep us here.
    if (now() >= deadline && ++late > 64) return false;
    std::string chunk;
    if (!t_.receive(deadline, chunk)) {
      // A quiet stream with bytes held (a frame failing its checksum waits
      // for look-ahead): the link went quiet, so decide now.
      if (!t_.datagram() && dec_.buffered() > 0) {
        dec_.settle();
        collect();
        if (!frames_.empty()) continue;
      }
      return false;
    }
    if (on_chunk) on_chunk(chunk);
    if (pcap_) pcap_->write(t_.remote(), t_.local(), chunk);
    dec_.feed(chunk);
    if (t_.datagram())
      dec_.finish();
    else
      dec_.flush();
    collect();
    if (t_.datagram()) dec_.reset();
  }
}

void FrameLink::collect() {
  top::StreamItem item;
  const std::uint64_t at = now();
  while (dec_.next(item)) {
    if (item.kind == top::ItemKind::garbage) {
      garbage_ = true;
      if (on_garbage) on_garbage(item.length);
      continue;
    }
    if (frames_.size() >= max_queued_) frames_.pop_front();
    frames_.push_back(Received{std::move(item.frame), at, garbage_});
    garbage_ = false;
  }
}

}  // namespace topconf
