// Inputs: a file or stdin opened for reading, its first bytes kept for
// format detection.
#include "capture/input.hpp"

#include <fcntl.h>
#include <stdio_ext.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <vector>

#include "magic.hpp"

namespace topdump {

namespace {

// A pipe, FIFO or terminal as a FILE: the bytes read for detection first,
// then the rest of the descriptor.
struct PipeCookie {
  int fd;
  std::string head;
  std::size_t at = 0;
};
ssize_t pipe_read(void* c, char* buf, std::size_t n) {
  auto& k = *static_cast<PipeCookie*>(c);
  if (k.at < k.head.size()) {
    std::size_t m = std::min(n, k.head.size() - k.at);
    std::memcpy(buf, k.head.data() + k.at, m);
    k.at += m;
    if (k.at == k.head.size()) std::string().swap(k.head), k.at = 0;
    return static_cast<ssize_t>(m);
  }
  for (;;) {
    ssize_t r = ::read(k.fd, buf, n);
    if (r >= 0 || errno != EINTR) return r;
  }
}
int pipe_close(void* c) {
  auto* k = static_cast<PipeCookie*>(c);
  int r = ::close(k->fd);
  delete k;
  return r;
}

// Our own FILE buffer: libpcap reads each record with two freads, which
// stdio's default 4 KiB buffer turns into a read(2) every ~50 records. 64
// KiB, from the heap, measured best (docs/perf/decisions.md, "The read
// buffer").
constexpr std::size_t kReadBuffer = std::size_t{1} << 16;

// The buffer's first byte on a cache line (it is allocated 64 bytes
// larger): a placement that measured well, and stays the same whatever the
// allocator did before (docs/perf/decisions.md, "The read buffer").
char* line_start(char* p) noexcept {
  return p + (-reinterpret_cast<std::uintptr_t>(p) & std::uintptr_t{63});
}

// The input's FILE reads through our buffer, and without stdio's lock:
// only this thread reads it, and libpcap's two freads per record each took
// the lock (docs/perf/decisions.md, "The read buffer").
void own_reads(Input& in) {
  std::setvbuf(in.file, line_start(in.buffer.get()), _IOFBF, kReadBuffer);
  ::__fsetlocking(in.file, FSETLOCKING_BYCALLER);
}

}  // namespace

bool open_input(const std::string& path, Input& in, std::string& error) {
  in.name = path == "-" ? "stdin" : path;
  int fd = path == "-" ? ::dup(0) : ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    error = in.name + ": cannot open: " + std::strerror(errno);
    return false;
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0 || S_ISDIR(st.st_mode)) {
    error = in.name + (S_ISDIR(st.st_mode) ? ": is a directory, not a capture file"
                                           : ": cannot open: " + std::string(std::strerror(errno)));
    ::close(fd);
    return false;
  }
  in.regular = S_ISREG(st.st_mode);
  in.size = in.regular ? static_cast<std::uint64_t>(st.st_size) : 0;
  in.buffer.reset(new char[kReadBuffer + 64]);
  if (in.regular) {
    in.file = ::fdopen(fd, "rb");
    if (!in.file) {
      error = in.name + ": cannot open: " + std::strerror(errno);
      ::close(fd);
      return false;
    }
    own_reads(in);
    in.head.resize(kInputHead);
    in.head.resize(std::fread(in.head.data(), 1, kInputHead, in.file));
    if (std::ferror(in.file) || std::fseek(in.file, 0, SEEK_SET) != 0) {
      error = in.name + ": cannot read: " + std::strerror(errno);
      return false;
    }
    return true;
  }
  // Not seekable: keep what detection reads and hand it out again first.
  std::string head(kInputHead, '\0');
  std::size_t got = 0;
  while (got < kInputHead) {
    ssize_t r = ::read(fd, head.data() + got, kInputHead - got);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) {
      error = in.name + ": cannot read: " + std::strerror(errno);
      ::close(fd);
      return false;
    }
    if (r == 0) break;
    got += static_cast<std::size_t>(r);
  }
  head.resize(got);
  in.head = head;
  auto* cookie = new PipeCookie{fd, std::move(head)};
  in.file =
      ::fopencookie(cookie, "rb", cookie_io_functions_t{pipe_read, nullptr, nullptr, pipe_close});
  if (!in.file) {
    error = in.name + ": cannot open: " + std::strerror(errno);
    pipe_close(cookie);
    return false;
  }
  own_reads(in);
  return true;
}

bool make_seekable(Input& in, std::string& error) {
  if (in.regular) return true;
  std::FILE* t = std::tmpfile();
  if (!t) {
    error = in.name + ": cannot spool to a temporary file: " + std::strerror(errno);
    return false;
  }
  std::vector<char> b(kReadBuffer);
  std::size_t n;
  while ((n = std::fread(b.data(), 1, b.size(), in.file)) > 0) {
    if (std::fwrite(b.data(), 1, n, t) != n) {
      error = in.name + ": cannot spool to a temporary file: " + std::strerror(errno);
      std::fclose(t);
      return false;
    }
  }
  const bool bad = std::ferror(in.file) != 0;
  std::fclose(in.file);  // our buffer is free again
  in.file = t;
  own_reads(in);
  if (bad) {
    error = in.name + ": read error: " + std::strerror(errno);
    return false;
  }
  in.regular = true;
  in.size = static_cast<std::uint64_t>(std::ftell(t));
  std::rewind(t);
  return true;
}

std::optional<std::string> damaged_capture(std::string_view head) {
  if (head.size() < 12 || is_pcap_magic(head) || head.substr(0, 4) == "\x0a\x0d\x0d\x0a")
    return std::nullopt;
  auto at = [&](std::size_t i) { return static_cast<unsigned char>(head[i]); };
  // pcap: version 2.4 after the magic, in either byte order
  const bool pcap_version = (at(4) == 2 && at(5) == 0 && at(6) == 4 && at(7) == 0) ||
                            (at(4) == 0 && at(5) == 2 && at(6) == 0 && at(7) == 4);
  // pcapng: the section header's byte-order magic after the block length
  const bool ng_order =
      head.substr(8, 4) == "\x4d\x3c\x2b\x1a" || head.substr(8, 4) == "\x1a\x2b\x3c\x4d";
  if (!pcap_version && !ng_order) return std::nullopt;
  return "offset 0: magic number " + hex32(head) + " is not a pcap or pcapng magic, but " +
         (pcap_version ? "bytes 4-7 are a pcap file header's version 2.4"
                       : "bytes 8-11 are a pcapng section header's byte-order magic") +
         ": a damaged capture (--format raw reads it as a raw serial dump)";
}

}  // namespace topdump
