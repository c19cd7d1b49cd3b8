#include "udp_copies.hpp"

#include <sys/socket.h>
#include <sys/uio.h>

#include <cerrno>

namespace topsim {

void send_copies(int fd, std::vector<asio::ip::udp::endpoint>& to, const std::string& bytes) {
  std::vector<iovec> iov(to.size());
  std::vector<mmsghdr> msgs(to.size());
  for (std::size_t i = 0; i < to.size(); ++i) {
    iov[i].iov_base = const_cast<char*>(bytes.data());
    iov[i].iov_len = bytes.size();
    msgs[i] = mmsghdr{};
    msgs[i].msg_hdr.msg_name = to[i].data();
    msgs[i].msg_hdr.msg_namelen = static_cast<socklen_t>(to[i].size());
    msgs[i].msg_hdr.msg_iov = &iov[i];
    msgs[i].msg_hdr.msg_iovlen = 1;
  }
  for (std::size_t done = 0; done < msgs.size();) {
    const int n = ::sendmmsg(fd, msgs.data() + done, static_cast<unsigned>(msgs.size() - done), 0);
    if (n < 0 && errno == EINTR) continue;
    done += n > 0 ? static_cast<std::size_t>(n) : 1;
  }
}

}  // namespace topsim
