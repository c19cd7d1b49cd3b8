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

bool sends_copies(top::Model m) {
  return top::find_trait(top::TraitKind::fan_out, m, top::Profile::field) ||
         top::find_trait(top::TraitKind::duplicate_to_client_port, m, top::Profile::field);
}

bool reply_addressed(top::Dialect d, top::Model m, const top::Frame& f, char src, char dst) {
  if (f.src == dst && f.dst == src) return true;
  if (f.src != src || f.dst != dst) return false;
  const top::DeviceForm* rf = recorded_form_of(d, m, f);
  return rf && rf->order == top::Order::request_order;
}

void FrameLink::send(std::string_view bytes) {
  if (copies_ && !recent_.empty()) {
    // The copies of what came last arrive before the next request leaves
    // (they leave the device together): what comes after the request may
    // answer it, and is no copy of what came before.
    const std::uint64_t until =
        recent_.back().at + static_cast<std::uint64_t>(top::fan_out_copy_window_us);
    std::string chunk;
    for (std::size_t n = 0; n < 4096 && t_.receive(until, chunk); ++n) take(chunk);
    recent_.clear();
  }
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
        collect(now());
        if (!frames_.empty()) continue;
      }
      return false;
    }
    take(chunk);
  }
}

void FrameLink::take(const std::string& chunk) {
  const std::uint64_t at = t_.arrived_us();
  if (pcap_) pcap_->write(t_.remote(), t_.local(), chunk);
  std::uint64_t after = 0;
  if (copies_ && t_.datagram() && copy_of_recent(chunk, at, after)) {
    if (on_copy) on_copy(chunk, after);
    return;
  }
  if (on_chunk) on_chunk(chunk);
  dec_.feed(chunk);
  if (t_.datagram())
    dec_.finish();
  else
    dec_.flush();
  collect(at);
  if (t_.datagram()) dec_.reset();
}

bool FrameLink::copy_of_recent(const std::string& chunk, std::uint64_t at, std::uint64_t& after) {
  const auto window = static_cast<std::uint64_t>(top::fan_out_copy_window_us);
  while (!recent_.empty() && recent_.front().at + window <= at) recent_.pop_front();
  for (const Recent& r : recent_)
    if (r.bytes == chunk && at >= r.at) {
      after = at - r.at;
      return true;
    }
  // A device that floods cannot make this list long: the window is short.
  if (recent_.size() >= 64) recent_.pop_front();
  recent_.push_back(Recent{chunk, at});
  return false;
}

void FrameLink::collect(std::uint64_t at) {
  top::StreamItem item;
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
