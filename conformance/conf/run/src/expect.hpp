// Expectation matching (private to conf/run/): does a received frame
// satisfy an alternative of a step, and how strictly.
#pragma once

#include <deque>
#include <regex>
#include <string>
#include <string_view>
#include <vector>

#include "conf/link.hpp"
#include "conf/matrix.hpp"

namespace topconf::detail {

inline constexpr std::string_view kFieldForm = "the field's form, not the document's: ";

// The recorded form (top/device.hpp) a device frame matches where it departs
// from the document's rule (the request's address order, another header),
// or nullptr.
const top::DeviceForm* recorded_departure(const Matrix& m, const top::Frame& f);

// kFieldForm and the evidence when the device frame `f` decodes as a reply
// in a form only the field gives (top/catalog.hpp from_field: a LAT/LON
// write's echo, the LRF's 5 digits, GIA answering GIC), else "".
std::string field_reply_form(const Matrix& m, const top::Frame& f);
// kFieldForm and the evidence when the pushes of `ident` are a stream only
// the field gives (top/device.hpp: Topotek GIA 01 pushing GIA), else "".
std::string field_stream(top::Dialect d, std::string_view ident);

// A deviation that a strict match must not have: a warning or error at the
// frame level, or a named firmware quirk ("" for none).
std::string frame_deviation(const Received& r);

// One alternative of a step, ready to match: its exact frame resolved and
// its regular expressions compiled (once, when the step starts; the
// loader's when it compiled them).
struct Alternative {
  const Expectation& e;
  std::string exact;                        // ExpectKind::frame: the frame
  const std::regex* data_re = nullptr;      // e.data_pattern
  std::vector<const std::regex*> field_re;  // e.fields[i].pattern
};

class Matcher {
 public:
  explicit Matcher(const Matrix& m) : m_(m) {}
  // The alternatives of `expect`, resolved for `client`.
  std::vector<Alternative> prepare(const std::vector<Expectation>& expect, char client);
  // Does `r` satisfy the frame-type alternative `a` for request `req`
  // (null: none)? `why` gets a near miss.
  bool matches(const Alternative& a, const top::Frame* req, const Received& r,
               std::string& why) const;

 private:
  // The addresses answer `req` (or "addresses": "any"); else false with
  // "WHAT FRAME does not swap the addresses" in `why`.
  bool addressed(const Expectation& e, const top::Frame* req, const top::Frame& f, const char* what,
                 std::string& why) const;
  bool reply_matches(const Alternative& a, const top::Frame* req, const top::Frame& f,
                     std::string& why) const;
  bool fields_match(const Alternative& a, const top::Frame& f, const top::Decoded& dec,
                    std::string& why) const;

  const Matrix& m_;
  std::deque<std::regex> compiled_;  // patterns a hand-built matrix left uncompiled
};

}  // namespace topconf::detail
