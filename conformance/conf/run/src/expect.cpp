#include "expect.hpp"

#include <algorithm>

#include "top/device.hpp"

namespace topconf::detail {

using top::is_error_reply;

const top::DeviceForm* recorded_departure(const Matrix& m, const top::Frame& f) {
  const top::DeviceForm* rf = recorded_form_of(m.dialect, m.model, f);
  if (!rf) return nullptr;
  const top::CommandSpec* cmd = top::find_command(m.dialect, f.ident_view());
  const bool rule =
      rf->order == top::Order::swapped &&
      rf->header == top::choose_header(m.dialect, cmd ? cmd->address : 'G', f.data_length);
  return rule ? nullptr : rf;
}

std::string field_reply_form(const Matrix& m, const top::Frame& f) {
  top::DecodeOptions o;
  o.dialect = m.dialect;
  o.model = m.model;
  o.role = top::Role::response;
  o.detail = false;
  const top::Decoded dec = top::decode(f, o);
  if (!dec.form || !dec.form->from_field()) return {};
  return std::string(kFieldForm) + std::string(dec.form->evidence);
}

std::string field_stream(top::Dialect d, std::string_view ident) {
  if (top::stream_of(d, ident, top::Profile::document)) return {};
  const top::StreamSpec* s = top::stream_of(d, ident);
  if (!s || !s->from_field()) return {};
  return std::string(kFieldForm) + std::string(s->evidence);
}

std::string frame_deviation(const Received& r) {
  if (r.after_garbage) return "garbage preceded the frame";
  for (const auto& f : r.frame.findings) {
    // A length that counts bytes in a form recorded from real devices.
    if (f.code == top::FindingCode::length_in_bytes) return std::string(kFieldForm) + f.message;
    if (f.severity == top::Severity::error || f.severity == top::Severity::warning ||
        !f.quirk.empty() || f.code == top::FindingCode::tmp_quirk)
      return std::string(top::to_string(f.code)) + ": " + f.message;
  }
  return {};
}

std::vector<Alternative> Matcher::prepare(const std::vector<Expectation>& expect, char client) {
  compiled_.clear();
  auto regex = [&](const std::shared_ptr<const std::regex>& loaded,
                   const std::string& pattern) -> const std::regex* {
    if (pattern.empty()) return nullptr;
    if (loaded) return loaded.get();
    return &compiled_.emplace_back(pattern);
  };
  std::vector<Alternative> alts;
  alts.reserve(expect.size());
  for (const Expectation& e : expect) {
    Alternative a{e};
    if (e.kind == ExpectKind::frame) {
      std::string err;
      resolve_send(e.frame, m_.dialect, client, a.exact, err);
    }
    a.data_re = regex(e.data_re, e.data_pattern);
    for (const FieldCheck& fc : e.fields) a.field_re.push_back(regex(fc.re, fc.pattern));
    alts.push_back(std::move(a));
  }
  return alts;
}

bool Matcher::addressed(const Expectation& e, const top::Frame* req, const top::Frame& f,
                        const char* what, std::string& why) const {
  if (e.any_addresses || !req || reply_addressed(m_.dialect, m_.model, f, req->src, req->dst))
    return true;
  why = std::string(what) + " " + f.raw + " does not swap the addresses";
  return false;
}

bool Matcher::matches(const Alternative& a, const top::Frame* req, const Received& r,
                      std::string& why) const {
  const Expectation& e = a.e;
  const top::Frame& f = r.frame;
  if (!f.ok()) {
    why = "a frame arrived with errors: " +
          (f.findings.empty() ? std::string("?") : f.findings[0].message);
    return false;
  }
  switch (e.kind) {
    case ExpectKind::frame:
      if (f.raw == a.exact) return true;
      why = "got " + f.raw + ", expected " + a.exact;
      return false;
    case ExpectKind::echo:
      if (!req) return false;
      if (f.ident_view() != req->ident_view()) return false;
      if (f.control != req->control || f.data() != req->data()) {
        why = "reply " + f.raw + " is not an echo of " + req->raw;
        return false;
      }
      return addressed(e, req, f, "echo", why);
    case ExpectKind::error:
      if (!is_error_reply(f.ident_view())) {
        if (req && f.ident_view() == req->ident_view())
          why = "answered " + f.raw + " instead of ERE";
        return false;
      }
      return addressed(e, req, f, "ERE", why);
    case ExpectKind::reply:
      return reply_matches(a, req, f, why);
    default:
      return false;
  }
}

bool Matcher::reply_matches(const Alternative& a, const top::Frame* req, const top::Frame& f,
                            std::string& why) const {
  const Expectation& e = a.e;
  const std::string ident = !e.ident.empty() ? e.ident : req ? std::string(req->ident_view()) : "";
  // The identifier, or the one a recorded form answers it with (GIC -> GIA).
  if (!top::answers_query(m_.dialect, ident, f.ident_view())) {
    if (is_error_reply(f.ident_view())) why = "the device answered ERE";
    return false;
  }
  if (e.control && f.control != e.control) {
    why = "reply " + f.raw + " has control '" + std::string(1, f.control ? f.control : '?') + "'";
    return false;
  }
  if (!addressed(e, req, f, "reply", why)) return false;
  const std::string data(f.data());
  if (e.data && data != *e.data) {
    why = "data " + data + ", expected " + *e.data;
    return false;
  }
  if (a.data_re && !std::regex_match(data, *a.data_re)) {
    why = "data " + data + " does not match /" + e.data_pattern + "/";
    return false;
  }
  top::DecodeOptions dopt;
  dopt.dialect = m_.dialect;
  dopt.model = m_.model;
  dopt.role = top::Role::response;
  top::Decoded dec = top::decode(f, dopt);
  if (dec.command) {
    for (const auto& fd : dec.findings) {
      if (fd.severity != top::Severity::warning) continue;
      if (fd.code == top::FindingCode::unswapped_addresses) continue;
      why = "reply " + f.raw + ": " + std::string(top::to_string(fd.code)) + ": " + fd.message;
      return false;
    }
  }
  return fields_match(a, f, dec, why);
}

bool Matcher::fields_match(const Alternative& a, const top::Frame& f, const top::Decoded& dec,
                           std::string& why) const {
  for (std::size_t i = 0; i < a.e.fields.size(); ++i) {
    const FieldCheck& fc = a.e.fields[i];
    const top::FieldValue* fv = nullptr;
    for (const auto& x : dec.fields)
      if (x.name() == fc.name) fv = &x;
    if (!fv || !fv->valid) {
      why = "reply " + f.raw + " has no valid field " + fc.name;
      return false;
    }
    const std::string raw = f.raw.substr(fv->offset, fv->length);
    if ((fc.min && fv->value < *fc.min) || (fc.max && fv->value > *fc.max)) {
      why = "field " + fc.name + " = " + top::format_value(*fv) + " is out of range";
      return false;
    }
    if (!fc.enums.empty() &&
        std::find(fc.enums.begin(), fc.enums.end(), std::string(fv->enum_name)) == fc.enums.end()) {
      why = "field " + fc.name + " = " + top::format_value(*fv) + " is not an allowed value";
      return false;
    }
    if (a.field_re[i] && !std::regex_match(raw, *a.field_re[i])) {
      why = "field " + fc.name + " = " + raw + " does not match /" + fc.pattern + "/";
      return false;
    }
    if (fc.equals && raw != *fc.equals) {
      why = "field " + fc.name + " = " + raw + ", expected " + *fc.equals;
      return false;
    }
  }
  return true;
}

}  // namespace topconf::detail
