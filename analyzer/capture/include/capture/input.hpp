// Inputs and their formats: a capture file or a serial log, opened (a
// file, or stdin and pipes) and its format told from its first bytes.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace topdump {

enum class Format : std::uint8_t { automatic, pcap, raw, socat, saleae, lines, pcapng };
std::optional<Format> format_from_string(std::string_view s);
std::string_view to_string(Format f) noexcept;

// Picks the format from the first bytes of a file.
Format detect_format(std::string_view head);

// Why a head that is no pcap/pcapng starts like one (a damaged capture,
// not a raw serial dump): the pcap version or the pcapng byte-order magic
// behind a bad magic number. nullopt otherwise.
std::optional<std::string> damaged_capture(std::string_view head);

// How many first bytes of an input open_input() reads for detection.
inline constexpr std::size_t kInputHead = 4096;

// An input opened for reading: a file, or stdin ("-"), a pipe, FIFO or
// terminal, whose first bytes are read for detection and handed out again.
struct Input {
  std::string name;                // the path, "stdin" for "-"
  std::unique_ptr<char[]> buffer;  // the FILE's buffer; outlives it
  std::FILE* file = nullptr;       // at byte 0 of the content
  std::string head;                // the first bytes (up to kInputHead)
  bool regular = false;            // a regular file (seekable, sized)
  std::uint64_t size = 0;          // regular files
  Input() = default;
  Input(const Input&) = delete;
  Input& operator=(const Input&) = delete;
  ~Input() {
    if (file) std::fclose(file);
  }
};
// Opens `path` ("-": stdin). false with `error` naming the file (cannot
// open, a directory, a read error).
bool open_input(const std::string& path, Input& in, std::string& error);
// Copies a pipe into a temporary file (for readers that scan twice).
bool make_seekable(Input& in, std::string& error);

// What was read: the format detection chose (or the one forced) and, for
// captures, the link type.
struct InputInfo {
  std::string file;
  Format format = Format::automatic;
  std::string link;  // pcap/pcapng: libpcap's name of the link type
};

}  // namespace topdump
