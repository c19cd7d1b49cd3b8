// Library-internal: what decode() does with a frame its caller says the
// device sent (DecodeOptions::role == Role::response).
#pragma once

#include "top/decode.hpp"
#include "top/frame.hpp"

namespace top::detail {

// For a frame the device sent, decoded in `dec`: when it deviates from the
// rule (the request's address order, #TP with another length), adds or
// completes its `unswapped-addresses` finding and names the recorded form
// it matches: the evidence as the finding's quirk and, with `detail`, the
// kind of source in its message; a `tp-length` warning on a recorded form
// becomes info. A form
// nothing records stays as it is ("some simulators").
void note_device_form(const Frame& f, Model model, bool detail, Decoded& dec);

}  // namespace top::detail
