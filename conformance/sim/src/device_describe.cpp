// topsim --describe: every trait of the device with its source.
#include <algorithm>

#include "device_util.hpp"
#include "sim/device.hpp"

namespace topsim {

using detail::hex_u;

std::vector<Device::TraitLine> Device::describe() const {
  std::vector<TraitLine> out;
  auto src = [](const top::DeviceForm& f) { return std::string(top::to_string(f.source)); };
  auto header = [](top::Header h) { return std::string(top::to_string(h)); };
  auto order = [](top::Order o) {
    return o == top::Order::swapped ? std::string("swapped") : std::string("request-order");
  };
  const top::StreamSpec* push = nullptr;
  for (const top::StreamSpec& s : top::streams()) {
    const top::CommandSpec* req = top::find_command(dialect_, s.request);
    if (s.dialect == dialect_ && s.sender == top::Sender::device && req && req->supports(model_)) {
      push = &s;
      break;
    }
  }
  if (push) {
    const top::DeviceForm f = form_of(push->push, top::Sent::push, 12);
    const top::DeviceForm p =
        top::device_form(model_, push->push, 'r', top::Sent::push, 12, opts_.profile);
    out.push_back({std::string(push->push) + "-push-header", header(f.header),
                   opts_.push_header ? "option" : src(p), std::string(p.evidence)});
    out.push_back({std::string(push->push) + "-push-order", order(f.order),
                   opts_.push_order || !opts_.swap_addresses ? "option" : src(p),
                   std::string(p.evidence)});
  }
  std::vector<std::string_view> seen;
  for (const top::DeviceForm& r : top::device_forms()) {
    if (r.sent != top::Sent::reply || r.dialect != dialect_ ||
        !(r.models & top::model_bit(model_)) ||
        std::find(seen.begin(), seen.end(), r.ident) != seen.end())
      continue;
    seen.push_back(r.ident);
    std::size_t len = 4;
    if (const top::CommandSpec* c = top::find_command(dialect_, r.ident))
      for (const top::FormSpec& x : c->forms)
        if (x.control == r.control && x.role == top::Role::response) len = x.min_length;
    const top::DeviceForm p =
        top::device_form(model_, r.ident, r.control, top::Sent::reply, len, opts_.profile);
    const top::DeviceForm f = form_of(r.ident, top::Sent::reply, len);
    out.push_back(
        {std::string(r.ident) + "-reply",
         header(f.header) + " " + order(f.order) +
             (f.length_in_bytes ? ", length counts bytes" : ""),
         opts_.reply_header || opts_.reply_order || !opts_.swap_addresses ? "option" : src(p),
         std::string(p.evidence)});
  }
  {
    const top::DeviceForm rule =
        top::device_form(model_, "???", 'r', top::Sent::reply, 4, opts_.profile);
    out.push_back({"reply", opts_.swap_addresses ? "swapped" : "request-order",
                   opts_.swap_addresses ? "document rule" : "option", std::string(rule.evidence)});
  }
  // A sign trait: the identifiers it applies to, or the option's every
  // command; a contested one is shown with its sources, off.
  auto sign = [&](top::TraitKind k, const std::optional<bool>& opt) {
    const top::Trait* t = top::find_trait(k, model_, top::Profile::field, true);
    if (!t && !opt) return;
    const top::Trait* applied = top::find_trait(k, model_, opts_.profile);
    std::string value = "off", source = "document rule";
    if (opt) {
      value = *opt ? "on (every command)" : "off";
      source = "option";
    } else if (applied) {
      value =
          "on (" + std::string(applied->idents.empty() ? "every command" : applied->idents) + ")";
      source = std::string(top::to_string(applied->source));
    } else if (t->contested && opts_.profile == top::Profile::field) {
      value = "off (recorded for " + std::string(t->idents) + ")";
      source = "contested";
    }
    out.push_back({std::string(top::to_string(k)), value, source,
                   t ? std::string(t->evidence) : std::string()});
  };
  sign(top::TraitKind::yaw_inverted, opts_.yaw_inverted);
  sign(top::TraitKind::pitch_inverted, opts_.pitch_inverted);
  for (const top::FieldSupport& fs : top::field_support()) {
    if (fs.dialect != dialect_ || !(fs.models & top::model_bit(model_))) continue;
    std::string v;
    for (std::int64_t x : fs.values)
      v += (v.empty() ? "" : ",") + hex_u(static_cast<std::uint64_t>(x), 2);
    out.push_back({std::string(fs.ident) + "-field-codes", field_ptz_ ? v : "off",
                   opts_.field_ptz ? "option"
                   : field_ptz_    ? "field"
                                   : "document rule",
                   std::string(fs.evidence)});
  }
  for (top::TraitKind k : {top::TraitKind::answers_to_source, top::TraitKind::link_by_source,
                           top::TraitKind::speed_refresh}) {
    const top::Trait* t = top::find_trait(k, model_, opts_.profile);
    if (!t) continue;
    std::string value = t->value ? std::to_string(t->value) : "on";
    if (k == top::TraitKind::speed_refresh) value = std::to_string(opts_.speed_hold_ms) + " ms";
    out.push_back({std::string(top::to_string(k)), value, std::string(top::to_string(t->source)),
                   std::string(t->evidence)});
  }
  return out;
}

}  // namespace topsim
