// Liveness probes: the requests a client sends a device of a model to learn
// that it is alive, in the order to try them, each with the identifiers of
// the frames that answer it. The identifiers are the device's rule, written
// here once with their evidence; whether a model takes one is the catalog's
// (catalog.hpp), and what answers a stream switch is the stream table's
// (device.hpp). topconf run and topconf fuzz probe with them.
#pragma once

#include <string_view>
#include <vector>

#include "top/catalog.hpp"

namespace top {

struct LivenessProbe {
  std::string_view ident;  // the request's identifier ("VER")
  char address = 0;        // its command's address class, where it is sent ('G')
  char control = 'r';      // 'r' a read, 'w' a stream switch
  std::string_view data;   // the request's data ("00"; "01" switches a stream on)
  // The identifier of the answer: the request's own for a read, the push
  // of the stream the write switches on (GAA: GAC).
  std::string_view answer;
  std::string_view evidence;  // why a device answers it (document, driver, simulator)

  // Whether a device frame of `ident` is the push of a stream of `d` this
  // probe switches on, the document's or the field's (Topotek GIA: GIC or
  // GIA frames). A read's answer is a frame of its own identifier and
  // control, which the caller checks.
  bool switches_push(Dialect d, std::string_view ident) const noexcept;
};

// The probes for a device of `model`, in the order to try them: those of its
// dialect whose command the catalog gives the model (with that control).
// Empty for Model::unknown.
std::vector<LivenessProbe> liveness_probes(Model model);

}  // namespace top
