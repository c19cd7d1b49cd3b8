// Target: topsim's request handler (handle_datagram), the entry point of
// every byte a client sends the simulator. Byte 0 picks the model (and the
// TMP-quirk and no-swap options), byte 1 the link; the rest is a sequence of
// datagrams separated by "\n\n" handed to one device, with time advancing
// 50 ms per datagram, so state (streams, speed holds, settings) carries
// over. Checks: every reply is one frame that the parser accepts with a
// valid checksum; nothing crashes, leaks or hangs.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "check.hpp"
#include "sim/device.hpp"
#include "top/top.hpp"

using topfuzz::show;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  size = topfuzz::capped(size);
  if (size < 2) return 0;
  const auto models = top::all_models();
  const top::Model model = models[data[0] % models.size()];
  topsim::DeviceOptions o;
  o.tmp_quirk = (data[0] & 0x40) != 0;
  o.swap_addresses = (data[0] & 0x80) == 0;
  const topsim::Link link = (data[1] & 1) ? topsim::Link::uart : topsim::Link::network;
  topsim::Device device(model, o);
  std::string_view rest(reinterpret_cast<const char*>(data + 2), size - 2);
  std::uint64_t now = 1'000'000;
  while (true) {
    const std::size_t cut = rest.find("\n\n");
    const std::string_view datagram = rest.substr(0, cut);
    const std::vector<std::string> replies = topsim::handle_datagram(device, datagram, link, now);
    for (const std::string& r : replies) {
      const top::ParseResult p = top::parse_exact(r);
      FUZZ_CHECK(p.status == top::ParseStatus::frame && p.frame.checksum_ok,
                 "the simulator sent \"" + show(r) + "\" in answer to \"" + show(datagram) + "\"");
    }
    if (cut == std::string_view::npos) break;
    rest.remove_prefix(cut + 2);
    now += 50'000;
  }
  return 0;
}
