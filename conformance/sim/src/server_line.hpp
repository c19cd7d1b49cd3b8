// A byte stream with a write queue, for topsim's stream transports (TCP
// socket, pty master, serial port; private to sim/).
#pragma once

#include <asio.hpp>
#include <deque>
#include <memory>
#include <string>

namespace topsim {

// A byte stream with a write queue (TCP socket, pty master, serial port).
template <class S>
class Line : public std::enable_shared_from_this<Line<S>> {
 public:
  explicit Line(S s) : s_(std::move(s)) {}
  S& stream() { return s_; }
  void write(std::string bytes) {
    // A client that never reads: bounded; new writes are dropped (the
    // front one may be in flight).
    if (q_.size() >= 4096) return;
    const bool idle = q_.empty();
    q_.push_back(std::move(bytes));
    if (idle) pump();
  }
  bool open = true;

 private:
  void pump() {
    auto self = this->shared_from_this();
    asio::async_write(s_, asio::buffer(q_.front()), [self](std::error_code ec, std::size_t) {
      if (ec) {
        self->open = false;
        self->q_.clear();
        return;
      }
      self->q_.pop_front();
      if (!self->q_.empty()) self->pump();
    });
  }
  S s_;
  std::deque<std::string> q_;
};

}  // namespace topsim
