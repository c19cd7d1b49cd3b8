// The copies of one datagram to several ports of the client's host, sent
// together (private to sim/; sim/fanout.hpp says where they go).
#pragma once

#include <asio.hpp>
#include <string>
#include <vector>

namespace topsim {

// Sends `bytes` from socket `fd` to each of `to` by one sendmmsg(2), so
// that the copies leave together (top::fan_out_copy_window_us); a copy the
// kernel refuses (a full buffer) is lost, as a datagram may be.
void send_copies(int fd, std::vector<asio::ip::udp::endpoint>& to, const std::string& bytes);

}  // namespace topsim
