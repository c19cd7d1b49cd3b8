#include "diagnoses/cause.hpp"

#include <iterator>

namespace topdump {

namespace {
constexpr std::string_view kCauseText[] = {
    "",
    "its checksum is bad, and devices drop such frames",
    "its checksum is in lowercase hex, which strict parsers drop",
    "a Topotek request with source U over the network; the device answers U requests on its "
    "UART only (the network client is P)",
    "the identifier is not supported on the model",
    "the request is invalid (its length or a value), which devices ignore or answer with ERE",
    "the device sent its frames to another port of this host: a client that does not listen "
    "there hears nothing",
    "the device was silent",
};
static_assert(std::size(kCauseText) == cause_count);
}  // namespace

std::string_view describe(Cause c) noexcept { return kCauseText[static_cast<std::size_t>(c)]; }

}  // namespace topdump
