// The names and descriptions of topconf fuzz's enums (conf/fuzz.hpp), one
// array each (top/enum_names.hpp).
#include <iterator>

#include "conf/fuzz.hpp"
#include "top/enum_names.hpp"

namespace topconf {

namespace {
constexpr std::string_view kFailureClass[] = {"stopped-answering", "answered-corrupt-frame",
                                              "bad-reply", "slow-answer", "wrong-answer"};
constexpr std::string_view kFailureDescription[] = {
    "the device stopped answering the liveness probe",
    "the device answered a frame whose checksum is wrong",
    "a malformed, wrongly addressed or out-of-range reply",
    "an answer later than --slow-ms after a case",
    "ERE or silence where the document promises an answer, or an answer where it "
    "promises ERE (must and should levels)"};
static_assert(std::size(kFailureClass) == static_cast<std::size_t>(FailureClass::wrong_answer) + 1);
static_assert(std::size(kFailureDescription) == std::size(kFailureClass));
constexpr std::string_view kMinimiseHow[] = {"alone", "window", "not-reproduced", "skipped"};
static_assert(std::size(kMinimiseHow) == static_cast<std::size_t>(MinimiseHow::skipped) + 1);
}  // namespace

std::string_view to_string(FailureClass c) noexcept { return top::enum_name(kFailureClass, c); }
std::string_view describe(FailureClass c) noexcept {
  return top::enum_name(kFailureDescription, c);
}
std::string_view to_string(MinimiseHow h) noexcept { return top::enum_name(kMinimiseHow, h); }

}  // namespace topconf
