// topsim --describe: every trait of the device with its source.
#include <algorithm>
#include <cstdio>

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
  // The attitude stream the profile pushes (field: Topotek GIA frames).
  const top::StreamSpec* push = nullptr;
  for (const top::StreamSpec& s : top::streams()) {
    const top::CommandSpec* req = top::find_command(dialect_, s.request);
    const top::MotionSpec* m = top::motion_of(dialect_, s.push);
    if (s.dialect != dialect_ || s.sender != top::Sender::device || !req ||
        !req->supports(model_) || (s.from_field() && !field()) || !m ||
        m->kind != top::MotionKind::attitude)
      continue;
    if (!push || (s.from_field() && !push->from_field())) push = &s;
  }
  if (push) {
    out.push_back({std::string(push->request) + "-enables", std::string(push->push),
                   push->from_field() ? "field" : "document rule",
                   std::string(push->from_field() ? push->evidence : push->note)});
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
                           top::TraitKind::speed_refresh, top::TraitKind::keeps_request_header}) {
    const top::Trait* t = top::find_trait(k, model_, opts_.profile);
    if (!t) continue;
    std::string value = t->value ? std::to_string(t->value) : "on";
    if (k == top::TraitKind::speed_refresh) value = std::to_string(opts_.speed_hold_ms) + " ms";
    out.push_back({std::string(top::to_string(k)), value, std::string(top::to_string(t->source)),
                   std::string(t->evidence)});
  }
  describe_udp(out);
  if (dialect_ == top::Dialect::topotek) describe_topotek(out);
  return out;
}

void Device::describe_udp(std::vector<TraitLine>& out) const {
  // The ports the document gives the model (top::known_ports): what the
  // UDP traits depart from.
  std::string served_src, client_src;
  for (const top::PortSpec& p : top::known_ports()) {
    if (!(p.models & top::model_bit(model_)) || p.tcp) continue;
    if (p.client && client_src.empty()) client_src = std::string(p.source);
    if ((p.served & top::model_bit(model_)) && served_src.empty())
      served_src = std::string(p.source);
  }
  const UdpTraits on = udp_traits();
  // One switch: shown for a model with the trait in the field, or when set.
  auto line = [&](const char* name, top::TraitKind k, const std::optional<bool>& opt, bool value,
                  const char* on_text, const char* off_text, const std::string& doc) {
    const top::Trait* t = top::find_trait(k, model_, top::Profile::field);
    if (!t && !opt) return;
    const top::Trait* applied = top::find_trait(k, model_, opts_.profile);
    std::string source = opt       ? "option"
                         : applied ? std::string(top::to_string(applied->source))
                                   : "document rule";
    out.push_back({name, value ? on_text : off_text, source,
                   t && (value || opt || doc.empty()) ? std::string(t->evidence) : doc});
  };
  line("reply-from", top::TraitKind::ephemeral_reply_port, opts_.ephemeral_reply_port,
       on.ephemeral_reply_port, "ephemeral", "served", served_src);
  line("fan-out", top::TraitKind::fan_out, opts_.fan_out, on.fan_out, "on", "off", client_src);
  line("duplicate", top::TraitKind::duplicate_to_client_port, opts_.duplicate, on.duplicate, "on",
       "off", client_src);
  // Writes: answered as top::write_reply says (none where the document
  // gives no reply form), or every write echoed (--write-echo on).
  const bool echo = opts_.write_echo.value_or(false);
  line("write-echo", top::TraitKind::silent_writes, opts_.write_echo, echo, "on", "off", "");
}

void Device::describe_topotek(std::vector<TraitLine>& out) const {
  // Motion: the field's signs and units where they differ from the document.
  for (const top::MotionSpec& m : top::motions()) {
    if (m.dialect != dialect_ || m.field_evidence.empty()) continue;
    if (!field() && m.section.starts_with("field")) continue;  // a row only the field gives
    std::string v;
    for (const top::MotionAxis& a : m.fields())
      if (a.axis == top::Axis::pitch && a.sign_in(field()) < 0) v = "pitch down positive";
    if (field() && m.field_unit != 0) {
      char buf[48];
      std::snprintf(buf, sizeof buf, "%s%.4f deg/s a count", v.empty() ? "" : ", ", m.field_unit);
      v += buf;
    }
    out.push_back({std::string(m.ident) + "-motion", v.empty() ? "as the document" : v,
                   field() ? "field" : "document rule", std::string(m.field_evidence)});
  }
  out.push_back({"version", setting("VSN"), opts_.version.empty() ? "field" : "option",
                 "a real Topotek camera answered #tpDPArVSN1.6.26.R.D62 (PixEagle session "
                 "20260917T185212Z-identity 18:52:16.574300)"});
  out.push_back({"model-name", setting("PA2"), opts_.model_name.empty() ? "default" : "option",
                 "AP_Mount_Topotek reads PA2 as the model name (PR #27568); placeholders seen: "
                 "000000000 (PR #27568), Unknown (PR #27053)"});
  out.push_back({"tracking", opts_.tracking ? "on" : "off (TRC state 4)",
                 opts_.tracking ? "field" : "option",
                 "TRC 02 prepare/01 cancel -> waiting, 00 exit -> stopped, LOC -> tracking in "
                 "~0.4 s with OFT at ~30 Hz (AP_Mount_Topotek PR #27568, PR #31768: state 4; "
                 "PixEagle session 20260917T051606Z-point on a real Topotek camera)"});
}

}  // namespace topsim
