#include "sim/device.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "device_util.hpp"
#include "top/diagnoses.hpp"

namespace topsim {
namespace {

using top::Dialect;
using top::FindingCode;
using top::Frame;

constexpr std::uint64_t kNever = std::numeric_limits<std::uint64_t>::max();

using detail::hex_s16;

// `data` of a dated form (top::carries_date: TIM, UTC) one month earlier, as
// a camera whose clock was set with a 0-based month reports it (review of
// ArduPilot PR #34155): the month field less one, January the December of
// the year before. The fields are found by the form's widths, as
// top::date_time_of reads them; data it cannot read stays as it is.
std::string month_early(const top::FormSpec& form, std::string data) {
  constexpr std::size_t npos = std::string::npos;
  std::size_t at = 0, month_at = npos, month_w = 0, year_at = npos, year_w = 0;
  for (const top::FieldSpec& f : form.fields) {
    const std::size_t w = f.width ? f.width : data.size() - std::min(at, data.size());
    if (f.name == "month") month_at = at, month_w = w;
    if (f.name == "year") year_at = at, year_w = w;
    at += w;
  }
  if (month_at == npos || year_at == npos || at > data.size()) return data;
  auto number = [&](std::size_t p, std::size_t w) {
    int v = 0;
    for (std::size_t i = p; i < p + w; ++i) {
      if (data[i] < '0' || data[i] > '9') return -1;
      v = v * 10 + (data[i] - '0');
    }
    return w ? v : -1;
  };
  auto put = [&](std::size_t p, std::size_t w, int v) {
    for (std::size_t i = p + w; i-- > p; v /= 10) data[i] = static_cast<char>('0' + v % 10);
  };
  int month = number(month_at, month_w), year = number(year_at, year_w);
  if (month < 1 || year < 0) return data;
  if (--month == 0) {
    month = 12;
    year = year > 0 ? year - 1 : year_w == 2 ? 99 : 0;
  }
  put(month_at, month_w, month);
  put(year_at, year_w, year);
  return data;
}

// A factory placeholder in place of what a read that names the device
// answers (placeholder-identity; top::is_placeholder_identity is the rule):
// a model name reads 000000000, as a real Topotek unit's did (ArduPilot PR
// #27568); a version or serial number keeps its shape, every digit and
// letter 0 (a leading V kept: the version form ArduPilot's SkyDroid driver
// parses). Which reads name the device, the catalog says: the one field of
// their reply is the model, version or serial_number. Empty: not one.
std::string placeholder(top::Dialect d, std::string_view ident, const std::string& value) {
  const top::CommandSpec* c = top::find_command(d, ident);
  if (!c) return {};
  for (const top::FormSpec& f : c->forms) {
    if (f.control != 'r' || f.role != top::Role::response || f.fields.size() != 1) continue;
    const std::string_view name = f.fields[0].name;
    if (name == "model") return "000000000";
    if (name != "version" && name != "serial_number") return {};
    std::string v = value;
    for (std::size_t i = 0; i < v.size(); ++i)
      if (std::isalnum(static_cast<unsigned char>(v[i])) &&
          !(i == 0 && v[i] == 'V' && v.size() > 1))
        v[i] = '0';
    return v;
  }
  return {};
}

}  // namespace

Device::Device(top::Model model, DeviceOptions opts)
    : model_(model), dialect_(top::dialect_of(model)), opts_(opts) {
  const top::Profile p = opts_.profile;
  sign_trait_[0] = top::find_trait(top::TraitKind::yaw_inverted, model, p);
  sign_trait_[1] = top::find_trait(top::TraitKind::pitch_inverted, model, p);
  field_ptz_ = opts_.field_ptz.value_or(p == top::Profile::field);
  if (opts_.speed_hold_ms == 0) opts_.speed_hold_ms = top::speed_hold_ms(model, p);
  if (dialect_ == Dialect::topotek) {
    axes_[0].min = -150;
    axes_[0].max = 150;
  }
  axes_[2].min = -45;
  axes_[2].max = 45;
  // Read-only values a real device reports.
  // SkyDroid: the form AP_Mount_SkyDroid parses ("V1.0.78", PR #34155) and
  // the model's name, as ArduPilot's SIM_SkyDroid answers MOD (C11, C13).
  const bool sky = dialect_ == Dialect::skydroid;
  settings_["VER"] = !sky ? "SIP0001V113TK0" : opts_.version.empty() ? "V1.0.78" : opts_.version;
  if (sky) {
    std::string name(top::to_string(model));
    for (char& ch : name) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    const std::size_t pro = name.find("PRO");
    if (pro != std::string::npos) name.replace(pro, 3, "Pro");
    settings_["MOD"] = opts_.model_name.empty() ? name : opts_.model_name;
  }
  settings_["SDC"] = "0EA601D4C0";  // 60000 MB free of 120000 MB
  settings_["IPV"] = "192.168.144.108";
  settings_["GTW"] = "192.168.144.1";
  if (dialect_ == Dialect::topotek) {
    // The version a real Topotek camera answered (PixEagle session
    // 20260917T185212Z-identity 18:52:16.574300: #tpDPArVSN1.6.26.R.D62)
    // and a model name that is no placeholder (000000000 and Unknown were
    // seen: ArduPilot PRs #27568, #27053).
    settings_["VSN"] = opts_.version.empty() ? "1.6.26.R.D" : opts_.version;
    settings_["PA2"] = opts_.model_name.empty() ? "SIP" : opts_.model_name;
    // every TRA reply of a real Topotek camera (PixEagle session
    // 20260917T071854Z-ai-observe 07:18:56.511155: #TPDP2rTRA1148)
    settings_["TRA"] = "11";
    if (!opts_.tracking || opts_.faults.refuse_tracking) tracking_.state = '4';
  }
  if (opts_.faults.placeholder_identity)
    for (auto& [id, value] : settings_)
      if (std::string z = placeholder(dialect_, id, value); !z.empty()) value = std::move(z);
  keeps_header_ = !opts_.reply_header &&
                  top::find_trait(top::TraitKind::keeps_request_header, model, p) != nullptr;
}

void Device::reconfigure(DeviceOptions opts, std::uint64_t now_us) {
  advance(now_us);
  Device next(model_, std::move(opts));
  for (std::size_t i = 0; i < 3; ++i) {
    next.axes_[i].angle = std::clamp(axes_[i].angle, next.axes_[i].min, next.axes_[i].max);
    next.axes_[i].rate = 0;  // a new case starts at rest
  }
  next.streams_ = streams_;
  for (Stream& s : next.streams_) s.on_us = now_us;
  next.recording_ = recording_;
  next.file_index_ = file_index_;
  next.now_us_ = now_us_;
  next.requests_ = requests_;
  *this = std::move(next);
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

UdpTraits Device::udp_traits() const noexcept {
  auto trait = [&](top::TraitKind k, const std::optional<bool>& opt) {
    return opt ? *opt : top::find_trait(k, model_, opts_.profile) != nullptr;
  };
  UdpTraits t;
  t.ephemeral_reply_port = trait(top::TraitKind::ephemeral_reply_port, opts_.ephemeral_reply_port);
  t.fan_out = trait(top::TraitKind::fan_out, opts_.fan_out);
  t.duplicate = trait(top::TraitKind::duplicate_to_client_port, opts_.duplicate);
  return t;
}

bool Device::silent_write(const top::CommandSpec& cmd) const noexcept {
  return !opts_.write_echo.value_or(false) && top::write_reply(cmd) == top::WriteReply::nothing;
}

bool Device::inverted(std::size_t axis, std::string_view ident) const noexcept {
  const std::optional<bool>& opt = axis == 0 ? opts_.yaw_inverted : opts_.pitch_inverted;
  if (opt) return *opt;
  return axis < 2 && sign_trait_[axis] != nullptr && sign_trait_[axis]->names(ident);
}

bool Device::ignores_motion(std::string_view ident) const noexcept {
  const auto& v = opts_.faults.ignore_motion;
  return std::find(v.begin(), v.end(), ident) != v.end();
}

bool Device::fault_inverts(std::size_t axis, top::MotionKind kind) const noexcept {
  const std::uint8_t bit =
      kind == top::MotionKind::angle ? DeviceFaults::kInvertAngle : DeviceFaults::kInvertRate;
  return axis < 3 && (opts_.faults.invert[axis] & bit) != 0;
}

bool Device::accepts(const Frame& f, Link link) const noexcept {
  return top::answers_source(model_, opts_.profile, link, f.src) ||
         (opts_.any_source && top::is_client_address(f.src));
}

top::BuildSpec Device::reply_spec(top::Header h, const Frame& req, char control,
                                  std::string_view ident, std::string_view data) const {
  top::BuildSpec spec;
  spec.header = h;
  spec.src = opts_.swap_addresses ? req.dst : req.src;
  spec.dst = opts_.swap_addresses ? req.src : req.dst;
  spec.control = control;
  spec.ident = ident;
  spec.data = data;
  return spec;
}

std::string Device::make(top::Header h, const Frame& req, char control, std::string_view ident,
                         std::string_view data) const {
  return top::build_frame(reply_spec(h, req, control, ident, data));
}

void Device::reply_error(const Frame& req, std::vector<std::string>& out) const {
  if (!top::answers_error_reply(dialect_)) return;
  top::BuildSpec ere = top::error_reply(req);
  if (!opts_.swap_addresses) std::swap(ere.src, ere.dst);
  out.push_back(top::build_frame(ere));
}

std::string Device::attitude_data(std::string_view ident) const {
  // The sign traits act on the commands (Device::inverted): the attitude
  // reports where the gimbal is, in the report's own signs (Topotek GIA:
  // pitch down positive in the field).
  double yaw = axes_[0].angle, pitch = axes_[1].angle, roll = axes_[2].angle;
  if (const top::MotionSpec* m = top::motion_of(dialect_, ident))
    for (const top::MotionAxis& a : m->fields()) {
      const double s = a.sign_in(field());
      (a.axis == top::Axis::yaw ? yaw : a.axis == top::Axis::pitch ? pitch : roll) *= s;
    }
  return hex_s16(yaw) + hex_s16(pitch) + hex_s16(roll);
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

top::DeviceForm Device::reply_form(const Frame& req, std::string_view ident,
                                   std::size_t length) const {
  top::DeviceForm f = form_of(ident, top::Sent::reply, length);
  const bool fits = req.header == top::Header::fixed ? length == 2 : length <= top::max_data_hex;
  if (keeps_header_ && fits &&
      (req.header == top::Header::fixed || req.header == top::Header::variable))
    f.header = req.header;
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
  // A length that counts the bytes of the hex value (the C12 palette).
  if (form.length_in_bytes && data.size() % 2 == 0)
    spec.declared_length = static_cast<std::uint32_t>(data.size() / 2);
  return top::build_frame(spec);
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
  const std::uint32_t period = hz == 0 ? 0 : 1000000u / hz;
  // A re-sent enable keeps the stream going on its timing (ArduPilot's
  // Topotek driver re-sends GIA 01 once a second).
  if (period != 0 && it->period_us == period) return;
  if (it->period_us == 0) it->on_us = now_us;
  it->period_us = period;
  it->next_us = now_us + it->period_us;
}

std::uint64_t Device::next_timer() const noexcept {
  std::uint64_t t = kNever;
  for (const Stream& s : streams_)
    if (s.period_us != 0) t = std::min(t, s.next_us);
  if (tracking_.starts_us != 0) t = std::min(t, tracking_.starts_us);
  if (tracking_.state == '2') t = std::min(t, tracking_.next_box_us);
  return t;
}

void Device::poll(std::uint64_t now_us, std::vector<std::string>& out) {
  advance(now_us);
  for (Stream& s : streams_) {
    if (s.period_us == 0) continue;
    // Never emit a backlog: a late poll sends one frame and catches up.
    if (s.next_us > now_us) continue;
    // A stream the device switches off (stop=) waits for the client's switch.
    const std::uint64_t since_on = now_us - std::min(now_us, s.on_us);
    bool stopped = false;
    for (std::size_t i = 0; i < opts_.faults.stops.size() && i < 32; ++i) {
      const DeviceFaults::Mute& m = opts_.faults.stops[i];
      if (m.ident != s.ident || since_on < m.from_us || (stops_fired_ >> i & 1u)) continue;
      stops_fired_ |= 1u << i;
      stopped = true;
    }
    if (stopped) {
      s.period_us = 0;
      continue;
    }
    // A stalled or never-started stream keeps its timing and sends nothing.
    if (!opts_.faults.muted(s.ident, now_us - std::min(now_us, s.on_us))) {
      const std::string data = attitude_data(s.ident);
      out.push_back(
          build(form_of(s.ident, top::Sent::push, data.size()), s.dst, 'G', 'r', s.ident, data));
    }
    s.next_us += s.period_us;
    if (s.next_us <= now_us) s.next_us = now_us + s.period_us;
  }
  if (dialect_ == Dialect::topotek) poll_topotek(now_us, out);
}

std::string Device::read_data(const top::CommandSpec& cmd, const top::FormSpec& form) const {
  const std::string_view ident = cmd.ident;
  if (ident == "REC") return recording_ ? "01" : "00";
  if (ident == "GAC" || ident == "GIC") return attitude_data(ident);
  auto it = settings_.find(ident);
  if (it != settings_.end()) {
    const std::string& v = it->second;
    if (v.size() >= form.min_length && v.size() <= form.max_length) return v;
  }
  return top::example_data(form);
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

  // A request laid out as a response form (a 1-char VER read) is invalid too.
  if (!dec.command || top::rejection(dec, model_, field_ptz_) != top::Rejection::none ||
      !dec.form || dec.form->role == top::Role::response) {
    reply_error(req, out);
    return;
  }
  // ere=: this firmware refuses the command.
  for (const std::string& e : opts_.faults.ere)
    if (e == id) {
      reply_error(req, out);
      return;
    }
  if (dispatch(req, dec, now_us, out)) return;

  const top::CommandSpec& cmd = *dec.command;
  if (req.control == 'w') {
    // Settings (image, network, ...) are stored, never applied to the host;
    // a date set is answered with the camera's clock (clock=month-early).
    std::string stored(req.data());
    if (opts_.faults.clock_month_early && top::carries_date(id))
      stored = month_early(*dec.form, std::move(stored));
    settings_[std::string(id)] = stored;
    // A write with a reply layout of its own (Topotek 5.8.7 LON/LAT target
    // output) is answered in that layout; others are echoed where
    // top::write_reply says so. The field's layout first under the field
    // profile, never under the document's. (The 5.9 LRF result carries a
    // measurement: device_topotek.cpp.)
    const top::FormSpec* layout = nullptr;
    for (const auto& f : cmd.forms) {
      if (f.control != 'w' || f.role != top::Role::response || &f == dec.form) continue;
      if (f.from_field() && !field()) continue;
      if (!layout || (f.from_field() && !layout->from_field())) layout = &f;
    }
    if (layout) {
      const top::FormSpec& f = *layout;
      const std::string data = top::example_data(f);
      out.push_back(
          make(top::choose_header(dialect_, cmd.address, data.size()), req, 'w', id, data));
      return;
    }
    // A write the document gives no answer is taken without one
    // (top::write_reply); a camera whose clock is off (clock=month-early)
    // answers a date set with that clock.
    if (silent_write(cmd) && !(opts_.faults.clock_month_early && top::carries_date(id))) return;
    out.push_back(make(req.header, req, 'w', id, stored));
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
  if (opts_.tmp_quirk && id == "TMP") {
    // The Topotek 12.2 firmware form: #tp with a two-digit length, control w.
    top::BuildSpec tmp = reply_spec(top::Header::variable, req, 'w', id, "0100200300400500600700");
    tmp.two_digit_length = true;
    out.push_back(top::build_frame(tmp));
    return;
  }
  const std::string data = read_data(cmd, *resp);
  const top::DeviceForm form = reply_form(req, id, data.size());
  out.push_back(build(form, req.src, req.dst, 'r', id, data));
}

}  // namespace topsim
