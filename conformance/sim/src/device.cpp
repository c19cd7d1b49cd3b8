#include "sim/device.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace topsim {
namespace {

using top::Dialect;
using top::FindingCode;
using top::Frame;

constexpr std::uint64_t kNever = std::numeric_limits<std::uint64_t>::max();

std::string hex_s16(double deg) {
  long v = std::lround(deg * 100.0);
  v = std::clamp(v, -32768L, 32767L);
  char buf[8];
  std::snprintf(buf, sizeof buf, "%04X",
                static_cast<unsigned>(static_cast<std::uint16_t>(static_cast<std::int16_t>(v))));
  return buf;
}

std::string hex_u(std::uint64_t v, int width) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "%0*llX", width, static_cast<unsigned long long>(v));
  return buf;
}

// Commands Topotek's document defines that the simulator implements even
// while the catalog does not list them yet (catalog_topotek.cpp is being
// completed): the sim answers them from its own state.
bool topotek_builtin(std::string_view ident) noexcept {
  return ident == "REC" || ident == "CAP" || ident == "GIA" || ident == "GIC" || ident == "GAA";
}

const top::FieldValue* field(const top::Decoded& d, std::string_view name) {
  for (const auto& f : d.fields)
    if (f.name() == name && f.valid && !f.none) return &f;
  return nullptr;
}

// Two hex digits of data as a number, -1 when they are not.
int data_byte(std::string_view data) noexcept {
  if (data.size() != 2) return -1;
  int hi = top::hex_value(data[0]), lo = top::hex_value(data[1]);
  if (hi < 0 || lo < 0) return -1;
  return hi * 16 + lo;
}

bool catalog_rejects(const top::Decoded& dec) {
  for (const auto& f : dec.findings) {
    switch (f.code) {
      case FindingCode::unknown_ident:
      case FindingCode::unsupported_on_model:
      case FindingCode::unsupported_control:
      case FindingCode::data_length:
      case FindingCode::bad_field:
      case FindingCode::value_out_of_range:
        return true;
      default:
        break;
    }
  }
  return false;
}

}  // namespace

Device::Device(top::Model model, DeviceOptions opts)
    : model_(model), dialect_(top::dialect_of(model)), opts_(opts) {
  const top::Profile p = opts_.profile;
  yaw_inverted_ = opts_.yaw_inverted.value_or(
      top::find_trait(top::TraitKind::yaw_inverted, model, p) != nullptr);
  pitch_inverted_ = opts_.pitch_inverted.value_or(
      top::find_trait(top::TraitKind::pitch_inverted, model, p) != nullptr);
  field_ptz_ = opts_.field_ptz.value_or(p == top::Profile::field);
  if (dialect_ == Dialect::topotek) {
    axes_[0].min = -150;
    axes_[0].max = 150;
  }
  axes_[2].min = -45;
  axes_[2].max = 45;
  // Read-only values a real device reports.
  settings_["VER"] = dialect_ == Dialect::topotek ? "SIP0001V113TK0" : "V1.1.5";
  settings_["SDC"] = "0EA601D4C0";  // 60000 MB free of 120000 MB
  settings_["IPV"] = "192.168.144.108";
  settings_["GTW"] = "192.168.144.1";
}

std::string Device::setting(std::string_view ident) const {
  auto it = settings_.find(ident);
  return it == settings_.end() ? std::string() : it->second;
}

void Device::advance(std::uint64_t now_us) noexcept {
  if (now_us <= now_us_) return;
  const std::uint64_t from = now_us_;
  now_us_ = now_us;
  for (Axis& a : axes_) {
    std::uint64_t rate_end = std::min(now_us, std::max(a.rate_until, from));
    if (a.rate != 0 && rate_end > from) {
      a.angle += a.rate * static_cast<double>(rate_end - from) / 1e6;
      a.angle = std::clamp(a.angle, a.min, a.max);
    }
    if (a.rate_until <= now_us) a.rate = 0;
    if (a.has_target && a.rate == 0) {
      double step = a.target_speed * static_cast<double>(now_us - from) / 1e6;
      double diff = a.target - a.angle;
      if (std::fabs(diff) <= step) {
        a.angle = a.target;
        a.has_target = false;
      } else {
        a.angle += diff > 0 ? step : -step;
      }
    }
  }
}

bool Device::takes_in_field(const top::Decoded& dec) const {
  // The only rejection field evidence lifts: unsupported-on-model for a
  // value the field says the model's firmware takes (C13 PTZ).
  if (!field_ptz_ || !dec.command || dec.fields.empty() || !dec.fields[0].valid) return false;
  for (const auto& f : dec.findings)
    if (f.code != FindingCode::unsupported_on_model && f.severity != top::Severity::info)
      return false;
  return top::field_supported(dialect_, model_, dec.command->ident, dec.fields[0].integer) !=
         nullptr;
}

bool Device::accepts(const Frame& f, Link link) const noexcept {
  if (dialect_ != Dialect::topotek) return true;
  // Topotek answers to the interface the source byte names.
  return (link == Link::network && f.src == 'P') || (link == Link::uart && f.src == 'U');
}

std::string Device::make(top::Header h, const Frame& req, char control, std::string_view ident,
                         std::string_view data) const {
  top::BuildSpec spec;
  spec.header = h;
  spec.src = opts_.swap_addresses ? req.dst : req.src;
  spec.dst = opts_.swap_addresses ? req.src : req.dst;
  spec.control = control;
  spec.ident = ident;
  spec.data = data;
  return top::build_frame(spec);
}

void Device::reply_error(const Frame& req, std::vector<std::string>& out) const {
  // SkyDroid 2.3.2: #TP<dst><src>2wERE!!<cs>, addresses swapped.
  if (dialect_ == Dialect::skydroid) out.push_back(make(top::Header::fixed, req, 'w', "ERE", "!!"));
}

std::string Device::attitude_data() const {
  // C12 field trait: the attitude reports the opposite sign of the command.
  const double yaw = yaw_inverted_ ? -axes_[0].angle : axes_[0].angle;
  const double pitch = pitch_inverted_ ? -axes_[1].angle : axes_[1].angle;
  return hex_s16(yaw) + hex_s16(pitch) + hex_s16(axes_[2].angle);
}

top::DeviceForm Device::form_of(std::string_view ident, top::Sent sent, std::size_t length) const {
  top::DeviceForm f = top::device_form(model_, ident, 'r', sent, length, opts_.profile);
  const auto& order = sent == top::Sent::push ? opts_.push_order : opts_.reply_order;
  const auto& header = sent == top::Sent::push ? opts_.push_header : opts_.reply_header;
  if (order) f.order = *order;
  if (header) f.header = *header;
  if (!opts_.swap_addresses) f.order = top::Order::request_order;
  // A header the length cannot take (#TP/#tp past 15 chars) is the rule's.
  if (length > top::max_data_hex) f.header = top::choose_header(dialect_, 'G', length);
  return f;
}

std::string Device::build(const top::DeviceForm& form, char client, char device, char control,
                          std::string_view ident, std::string_view data) const {
  top::BuildSpec spec;
  spec.header = form.header;
  const bool swapped = form.order == top::Order::swapped;
  spec.src = swapped ? device : client;
  spec.dst = swapped ? client : device;
  spec.control = control;
  spec.ident = ident;
  spec.data = data;
  return top::build_frame(spec);
}

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
        {std::string(r.ident) + "-reply", header(f.header) + " " + order(f.order),
         opts_.reply_header || opts_.reply_order || !opts_.swap_addresses ? "option" : src(p),
         std::string(p.evidence)});
  }
  {
    const top::DeviceForm rule =
        top::device_form(model_, "???", 'r', top::Sent::reply, 4, opts_.profile);
    out.push_back({"reply", opts_.swap_addresses ? "swapped" : "request-order",
                   opts_.swap_addresses ? "document rule" : "option", std::string(rule.evidence)});
  }
  auto trait = [&](top::TraitKind k, const std::optional<bool>& opt, bool on) {
    const top::Trait* t = top::find_trait(k, model_, top::Profile::field);
    if (!t && !on) return;
    const bool from_profile = top::find_trait(k, model_, opts_.profile) != nullptr;
    out.push_back({std::string(top::to_string(k)), on ? "on" : "off",
                   opt            ? "option"
                   : from_profile ? std::string(top::to_string(t->source))
                                  : "document rule",
                   t ? std::string(t->evidence) : std::string()});
  };
  trait(top::TraitKind::yaw_inverted, opts_.yaw_inverted, yaw_inverted_);
  trait(top::TraitKind::pitch_inverted, opts_.pitch_inverted, pitch_inverted_);
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

void Device::start_stream(std::string_view ident, std::uint32_t hz, char dst,
                          std::uint64_t now_us) {
  auto it = std::find_if(streams_.begin(), streams_.end(),
                         [&](const Stream& s) { return s.ident == ident; });
  if (it == streams_.end()) {
    streams_.push_back(Stream{std::string(ident), 0, 0, dst});
    it = streams_.end() - 1;
  }
  it->dst = dst;
  it->period_us = hz == 0 ? 0 : 1000000u / hz;
  it->next_us = now_us + it->period_us;
}

std::uint64_t Device::next_timer() const noexcept {
  std::uint64_t t = kNever;
  for (const Stream& s : streams_)
    if (s.period_us != 0) t = std::min(t, s.next_us);
  return t;
}

void Device::poll(std::uint64_t now_us, std::vector<std::string>& out) {
  advance(now_us);
  for (Stream& s : streams_) {
    if (s.period_us == 0) continue;
    // Never emit a backlog: a late poll sends one frame and catches up.
    if (s.next_us > now_us) continue;
    const std::string data = attitude_data();
    out.push_back(
        build(form_of(s.ident, top::Sent::push, data.size()), s.dst, 'G', 'r', s.ident, data));
    s.next_us += s.period_us;
    if (s.next_us <= now_us) s.next_us = now_us + s.period_us;
  }
}

std::string Device::read_data(const top::CommandSpec& cmd, const top::FormSpec& form) const {
  const std::string_view ident = cmd.ident;
  if (ident == "REC") return recording_ ? "01" : "00";
  if (ident == "GAC" || ident == "GIC") return attitude_data();
  auto it = settings_.find(ident);
  if (it != settings_.end()) {
    const std::string& v = it->second;
    if (v.size() >= form.min_length && v.size() <= form.max_length) return v;
  }
  return top::example_data(form);
}

bool Device::handle_special(const Frame& req, const top::Decoded& dec, std::uint64_t now_us,
                            std::vector<std::string>& out) {
  const std::string_view id = req.ident_view();
  const std::string_view data = req.data();
  const bool write = req.control == 'w';
  const bool topotek = dialect_ == Dialect::topotek;
  auto echo = [&] { out.push_back(make(req.header, req, req.control, id, data)); };

  // Topotek D class (5.1, 5.2): REC and CAP answer with a file index.
  if (topotek && (id == "REC" || id == "CAP") && write) {
    const int v = data_byte(data);
    if (v < 0) return false;
    if (id == "REC") {
      const int act = v & 0x0F;
      bool rec = act == 1 ? true : act == 0 ? false : act == 0x0A ? !recording_ : recording_;
      if (act != 0 && act != 1 && act != 0x0A) return false;
      if (rec && !recording_) ++file_index_;
      recording_ = rec;
    } else {
      const int act = v & 0x0F;
      if (act != 1 && act != 2 && act != 3 && act != 5) return false;
      ++file_index_;
    }
    const std::string reply =
        std::string(id == "CAP" || recording_ ? "11" : "00") + hex_u(file_index_, 8);
    out.push_back(make(top::Header::variable, req, 'w', id, reply));
    return true;
  }
  if (topotek && (id == "REC" || id == "GIA" || id == "GAA") && !write) {
    std::string v = id == "REC" ? (recording_ ? "01" : "00") : "00";
    if (id != "REC") {
      for (const Stream& s : streams_)
        if (s.ident == top::stream_enabled_by(dialect_, id)->push && s.period_us) v = "01";
    }
    out.push_back(make(top::Header::fixed, req, 'r', id, v));
    return true;
  }
  if (topotek && (id == "GIA" || id == "GAA") && write) {
    const int v = data_byte(data);
    if (v != 0 && v != 1) return false;
    start_stream(top::stream_enabled_by(dialect_, id)->push, v ? opts_.topotek_stream_hz : 0,
                 req.src, now_us);
    echo();
    return true;
  }
  if (topotek && id == "GIC" && !write) {
    advance(now_us);
    out.push_back(make(top::Header::variable, req, 'r', id, attitude_data()));
    return true;
  }
  if (topotek) return false;

  // SkyDroid state behind the catalog entries.
  if (!write) return false;
  advance(now_us);
  auto axis_of = [](std::string_view ident) -> int {
    const char c = ident[2];
    return c == 'Y' ? 0 : c == 'P' ? 1 : c == 'R' ? 2 : -1;
  };
  auto set_target = [&](int ax, const top::FieldValue* ang, const top::FieldValue* spd) {
    if (!ang) return;
    Axis& a = axes_[ax];
    a.target = std::clamp(ang->value, a.min, a.max);
    double s = spd ? spd->value : 0;
    a.target_speed = s > 0 ? s : 9.9;  // 0: the document gives no meaning; full speed
    a.has_target = true;
    a.rate = 0;
    a.rate_until = 0;
  };
  auto set_rate = [&](int ax, const top::FieldValue* spd) {
    if (!spd) return;
    Axis& a = axes_[ax];
    a.rate = spd->value;
    a.rate_until = now_us + std::uint64_t{opts_.speed_hold_ms} * 1000;
    a.has_target = false;
  };
  if (id == "GAY" || id == "GAP" || id == "GAR") {
    set_target(axis_of(id), field(dec, "angle"), field(dec, "speed"));
  } else if (id == "GAM") {
    set_target(0, field(dec, "yaw"), field(dec, "yaw_speed"));
    set_target(1, field(dec, "pitch"), field(dec, "pitch_speed"));
  } else if (id == "GSY" || id == "GSP" || id == "GSR") {
    set_rate(axis_of(id), field(dec, "speed"));
  } else if (id == "GSM") {
    set_rate(0, field(dec, "yaw_speed"));
    set_rate(1, field(dec, "pitch_speed"));
  } else if (id == "PTZ") {
    const auto* a = field(dec, "action");
    const int act = a ? static_cast<int>(a->integer) : -1;
    constexpr double kPtzRate = 10.0;
    if (act == 0) {
      for (Axis& x : axes_) x.rate = 0, x.has_target = false;
    } else if (act >= 1 && act <= 4) {
      Axis& x = axes_[act <= 2 ? 1 : 0];
      x.rate = (act == 1 || act == 4) ? kPtzRate : -kPtzRate;
      x.rate_until = now_us + std::uint64_t{opts_.speed_hold_ms} * 1000;
      x.has_target = false;
    } else if (act == 5) {
      for (Axis& x : axes_) x.target = 0, x.target_speed = 9.9, x.has_target = true, x.rate = 0;
    } else if (act >= 0x0E && act <= 0x13 && field_ptz_ &&
               top::field_supported(dialect_, model_, id, act)) {
      // C13 field evidence: 0E/0F pitch +/-, 10/11 yaw +/-, 12/13 roll +/-.
      static constexpr int kAxis[] = {1, 0, 2};
      Axis& x = axes_[kAxis[(act - 0x0E) / 2]];
      x.rate = (act % 2 == 0) ? kPtzRate : -kPtzRate;
      x.rate_until = now_us + std::uint64_t{opts_.speed_hold_ms} * 1000;
      x.has_target = false;
    }
  } else if (id == "GAA") {
    const auto* r = field(dec, "rate");
    start_stream(top::stream_enabled_by(dialect_, id)->push,
                 r ? static_cast<std::uint32_t>(r->integer) : 0, req.src, now_us);
  } else if (id == "REC") {
    const auto* a = field(dec, "action");
    const int act = a ? static_cast<int>(a->integer) : -1;
    const bool rec = act == 1 ? true : act == 0 ? false : !recording_;
    if (rec && !recording_) ++file_index_;
    recording_ = rec;
  } else if (id == "CAP") {
    ++file_index_;
  } else if (id == "ZMC") {
    const int v = data_byte(data);
    if (v == 1) zoom_ = std::max(1.0, zoom_ - 1);
    if (v == 2) zoom_ = std::min(30.0, zoom_ + 1);
    settings_["ZMC"] = std::string(data);
  } else {
    return false;
  }
  echo();
  return true;
}

void Device::handle(const Frame& req, Link link, std::uint64_t now_us,
                    std::vector<std::string>& out) {
  ++requests_;
  advance(now_us);
  // A frame we cannot trust (bad or missing checksum, bad structure) gets
  // silence: the device cannot know who sent it or what it meant.
  if (!req.ok()) return;
  if (req.control != 'r' && req.control != 'w') return;
  if (!accepts(req, link)) return;

  top::DecodeOptions dopts;
  dopts.dialect = dialect_;
  dopts.model = model_;
  dopts.role = top::Role::request;
  const top::Decoded dec = top::decode(req, dopts);
  const std::string_view id = req.ident_view();

  // Topotek commands the simulator implements that a catalog without them
  // would reject (kept so the sim does not depend on catalog completeness).
  if (dialect_ == Dialect::topotek && !dec.command && topotek_builtin(id) &&
      handle_special(req, dec, now_us, out))
    return;
  // A request laid out as a response form (a 1-char VER read) is invalid too.
  if (!dec.command || (catalog_rejects(dec) && !takes_in_field(dec)) || !dec.form ||
      dec.form->role == top::Role::response) {
    reply_error(req, out);
    return;
  }
  if (handle_special(req, dec, now_us, out)) return;

  const top::CommandSpec& cmd = *dec.command;
  if (req.control == 'w') {
    // Settings (image, network, ...) are stored, never applied to the host.
    settings_[std::string(id)] = std::string(req.data());
    // A write with a reply layout of its own (Topotek 5.8.7 LON/LAT target
    // output, 5.9 LRF result) is answered in that layout; others are echoed.
    for (const auto& f : cmd.forms) {
      if (f.control != 'w' || f.role != top::Role::response || &f == dec.form) continue;
      const std::string data = top::example_data(f);
      out.push_back(
          make(top::choose_header(dialect_, cmd.address, data.size()), req, 'w', id, data));
      return;
    }
    out.push_back(make(req.header, req, 'w', id, req.data()));
    return;
  }
  // A read: find the response form (or the request's own when the command
  // has a single 'r' form for both roles).
  const top::FormSpec* resp = nullptr;
  for (const auto& f : cmd.forms)
    if (f.control == 'r' && f.role == top::Role::response) {
      resp = &f;
      break;
    }
  if (!resp) resp = dec.form;
  std::string data = read_data(cmd, *resp);
  if (opts_.tmp_quirk && id == "TMP") {
    // The Topotek 12.2 firmware form: two-digit length, control w.
    data = "0100200300400500600700";
    std::string f = "#tp";
    f += opts_.swap_addresses ? req.dst : req.src;
    f += opts_.swap_addresses ? req.src : req.dst;
    f += "16wTMP";
    f += data;
    out.push_back(top::with_checksum(f));
    return;
  }
  const top::DeviceForm form = form_of(id, top::Sent::reply, data.size());
  out.push_back(build(form, req.src, req.dst, 'r', id, data));
}

Session::Session(Device& device, Link link, bool datagram)
    : device_(device), link_(link), datagram_(datagram) {}

void Session::feed(std::string_view bytes, std::uint64_t now_us, std::vector<std::string>& out,
                   std::vector<Frame>* received) {
  decoder_.feed(bytes);
  if (datagram_)
    decoder_.finish();
  else
    decoder_.flush();
  top::StreamItem item;
  while (decoder_.next(item)) {
    if (item.kind != top::ItemKind::frame) continue;
    device_.handle(item.frame, link_, now_us, out);
    if (received) received->push_back(std::move(item.frame));
  }
  if (datagram_) decoder_.reset();
}

std::vector<std::string> handle_datagram(Device& device, std::string_view bytes, Link link,
                                         std::uint64_t now_us) {
  std::vector<std::string> out;
  Session s(device, link, true);
  s.feed(bytes, now_us, out);
  return out;
}

}  // namespace topsim
