#include "log_reader.hpp"

namespace topdump {

std::string line_note(const std::string& path, std::uint64_t line,
                      std::initializer_list<std::string_view> why) {
  const std::string n = std::to_string(line);
  std::size_t size = path.size() + n.size() + 9;
  for (std::string_view p : why) size += p.size();
  std::string m;
  m.reserve(size);
  m.append(path).append(": line ").append(n).append(": ");
  for (std::string_view p : why) m.append(p);
  return m;
}

}  // namespace topdump
