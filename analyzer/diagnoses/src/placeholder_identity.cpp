#include "diagnoses/placeholder_identity.hpp"

#include "top/text.hpp"

namespace topdump::diag {

void IdentityWatch::placeholder(std::string_view ident, std::string_view data, std::uint64_t n,
                                std::int64_t ts, int dir) {
  if (!top::is_placeholder_identity(data)) return;
  if (!c_.any()) value_ = std::string(data.substr(0, 32));
  c_.add(n, ts, ident, dir);
}

std::optional<Found> IdentityWatch::verdict() const {
  if (!c_.any()) return std::nullopt;
  Found f{top::Diagnosis::placeholder_identity, c_, -1, {}};
  f.figure = top::escape(std::string_view(c_.ident, 3)) + " reply \"" + top::escape(value_) +
             "\" is a factory placeholder (frame " + std::to_string(c_.first_frame) +
             (c_.frames > 1 ? ", " + std::to_string(c_.frames) + " placeholder replies" : "") + ")";
  return f;
}

}  // namespace topdump::diag
