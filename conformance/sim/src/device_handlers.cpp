// The commands with state behind them, as a table: (dialect, identifier,
// control) -> handler. A handler answers (true) or leaves the request to
// the catalog-driven answer of Device::handle (false); a write is echoed
// once its handler took it, where top::write_reply says so.
#include <algorithm>

#include "device_util.hpp"
#include "sim/device.hpp"

namespace topsim {

using detail::data_byte;
using detail::field;
using detail::hex_u;

struct Handlers {
  using Call = detail::HandlerCall;
  using Fn = detail::HandlerFn;

  // An axis turning at `rate` deg/s until the speed hold ends, unless refreshed.
  static void turn(const Call& c, Axis& a, double rate) {
    a.rate = rate;
    a.rate_until = c.now_us + std::uint64_t{c.dev.opts_.speed_hold_ms} * 1000;
    a.has_target = false;
  }

  static void echo(const Call& c) {
    c.out.push_back(
        c.dev.make(c.req.header, c.req, c.req.control, c.req.ident_view(), c.req.data()));
  }

  // Topotek D class (5.1, 5.2): REC and CAP answer with a file index.
  static bool topotek_file_write(const Call& c) {
    Device& d = c.dev;
    const std::string_view id = c.req.ident_view();
    const int v = data_byte(c.req.data());
    if (v < 0) return false;
    const int act = v & 0x0F;
    if (id == "REC") {
      if (act != 0 && act != 1 && act != 0x0A) return false;
      const bool rec = act == 1 ? true : act == 0 ? false : !d.recording_;
      if (rec && !d.recording_) ++d.file_index_;
      d.recording_ = rec;
    } else {
      if (act != 1 && act != 2 && act != 3 && act != 5) return false;
      ++d.file_index_;
    }
    const std::string reply =
        std::string(id == "CAP" || d.recording_ ? "11" : "00") + hex_u(d.file_index_, 8);
    c.out.push_back(d.make(top::Header::variable, c.req, 'w', id, reply));
    return true;
  }

  // Topotek REC, GIA and GAA reads: the recording state, a stream on or off.
  static bool topotek_state_read(const Call& c) {
    Device& d = c.dev;
    const std::string_view id = c.req.ident_view();
    std::string v = id == "REC" ? (d.recording_ ? "01" : "00") : "00";
    if (id != "REC") {
      // the profile's stream (field: GIA 01 pushes GIA frames)
      const top::StreamSpec* on = top::stream_enabled_by(d.dialect_, id, d.opts_.profile);
      for (const Stream& s : d.streams_)
        if (on && s.ident == on->push && s.period_us) v = "01";
    }
    c.out.push_back(d.make(top::Header::fixed, c.req, 'r', id, v));
    return true;
  }

  // SkyDroid angle and speed commands (top/motion.hpp).
  static bool motion(const Call& c) {
    Device& d = c.dev;
    const top::MotionSpec* m = top::motion_of(d.dialect_, c.req.ident_view());
    if (!m) return false;
    if (d.ignores_motion(c.req.ident_view())) return true;  // echoed; nothing moves
    for (const top::MotionAxis& x : m->fields()) {
      Axis& a = d.axes_[static_cast<std::size_t>(x.axis)];
      if (m->kind == top::MotionKind::angle) {
        const top::FieldValue* ang = field(c.dec, x.value);
        if (!ang) continue;
        const top::FieldValue* spd = field(c.dec, x.speed);
        a.target = std::clamp(ang->value, a.min, a.max);
        const double s = spd ? spd->value : 0;
        a.target_speed = s > 0 ? s : 9.9;  // 0: the document gives no meaning; full speed
        a.has_target = true;
        a.rate = 0;
        a.rate_until = 0;
      } else if (const top::FieldValue* spd = field(c.dec, x.value)) {
        turn(c, a, spd->value);
      }
      // A sign trait (or --yaw-sign/--pitch-sign) for this command: the
      // gimbal moves the other way from what the attitude reports; the
      // invert= fault turns the axis the other way from that.
      const auto axis = static_cast<std::size_t>(x.axis);
      if (d.inverted(axis, c.req.ident_view()) != d.fault_inverts(axis, m->kind)) {
        a.target = std::clamp(-a.target, a.min, a.max);
        a.rate = -a.rate;
      }
    }
    return true;
  }

  // The request's "action" field, -1 without one.
  static int action(const Call& c) {
    const auto* a = field(c.dec, "action");
    return a ? static_cast<int>(a->integer) : -1;
  }

  static bool ptz(const Call& c) {
    Device& d = c.dev;
    if (d.ignores_motion(c.req.ident_view())) return true;  // echoed; nothing moves
    const int act = action(c);
    constexpr double kPtzRate = 10.0;
    const top::PtzAction p = top::ptz_action(act);
    // C13 trims (0E-13) turn only where field evidence says the model takes them.
    const bool trim = act >= 0x0E;
    if (p.move == top::PtzMove::stop) {
      for (Axis& x : d.axes_) x.rate = 0, x.has_target = false;
    } else if (p.move == top::PtzMove::turn &&
               (!trim || (d.field_ptz_ &&
                          top::field_supported(d.dialect_, d.model_, c.req.ident_view(), act)))) {
      const auto axis = static_cast<std::size_t>(p.axis);
      const bool inv =
          d.inverted(axis, c.req.ident_view()) != d.fault_inverts(axis, top::MotionKind::rate);
      turn(c, d.axes_[axis], (inv ? -1 : 1) * p.sign * kPtzRate);
    } else if (p.move == top::PtzMove::centre) {
      for (Axis& x : d.axes_) x.target = 0, x.target_speed = 9.9, x.has_target = true, x.rate = 0;
    }
    return true;
  }

  // SkyDroid GAA: the attitude stream at the rate asked for (0: off).
  static bool stream_rate(const Call& c) {
    const auto* r = field(c.dec, "rate");
    c.dev.start_stream(top::stream_enabled_by(c.dev.dialect_, c.req.ident_view())->push,
                       r ? static_cast<std::uint32_t>(r->integer) : 0, c.req.src, c.now_us);
    return true;
  }

  static bool record(const Call& c) {
    Device& d = c.dev;
    const int act = action(c);
    const bool rec = act == 1 ? true : act == 0 ? false : !d.recording_;
    if (rec && !d.recording_) ++d.file_index_;
    d.recording_ = rec;
    return true;
  }

  static bool capture(const Call& c) {
    ++c.dev.file_index_;
    return true;
  }

  // SkyDroid SLR trigger: a station used on a real C13 (custom-GCS) writes
  // #TPUD2wSLR015B before each range read; the C13 SDK (skydroid_c13_miniSDK)
  // reads without one. So the trigger is taken and echoed, and every read
  // answered with the range (a measurement per read).
  static bool range_trigger(const Call&) { return true; }

  static bool zoom(const Call& c) {
    Device& d = c.dev;
    const int v = data_byte(c.req.data());
    if (v == 1) d.zoom_ = std::max(1.0, d.zoom_ - 1);
    if (v == 2) d.zoom_ = std::min(30.0, d.zoom_ + 1);
    d.settings_["ZMC"] = std::string(c.req.data());
    return true;
  }
};

namespace {

struct Entry {
  top::Dialect dialect;
  std::string_view ident;
  char control;
  Handlers::Fn fn;
  bool echo = false;  // the write is echoed once the handler took it (Device::silent_write)
};

constexpr top::Dialect kSky = top::Dialect::skydroid;
constexpr top::Dialect kTopotek = top::Dialect::topotek;

// The motion commands (top::motion_of) are looked up there.
constexpr Entry kHandlers[] = {
    {kTopotek, "REC", 'w', Handlers::topotek_file_write},
    {kTopotek, "CAP", 'w', Handlers::topotek_file_write},
    {kTopotek, "REC", 'r', Handlers::topotek_state_read},
    {kTopotek, "GIA", 'r', Handlers::topotek_state_read},
    {kTopotek, "GAA", 'r', Handlers::topotek_state_read},
    {kTopotek, "PTZ", 'w', Handlers::ptz, true},
    {kSky, "PTZ", 'w', Handlers::ptz, true},
    {kSky, "GAA", 'w', Handlers::stream_rate, true},
    {kSky, "REC", 'w', Handlers::record, true},
    {kSky, "CAP", 'w', Handlers::capture, true},
    {kSky, "ZMC", 'w', Handlers::zoom, true},
    {kSky, "SLR", 'w', Handlers::range_trigger, true},
};

}  // namespace

bool Device::dispatch(const top::Frame& req, const top::Decoded& dec, std::uint64_t now_us,
                      std::vector<std::string>& out) {
  // Topotek's motion, streams, tracking and position: device_topotek.cpp.
  if (dialect_ == kTopotek && dispatch_topotek(req, dec, now_us, out)) return true;
  const Handlers::Call call{*this, req, dec, now_us, out};
  const std::string_view id = req.ident_view();
  const Entry* entry = nullptr;
  for (const Entry& e : kHandlers)
    if (e.dialect == dialect_ && e.control == req.control && e.ident == id) {
      entry = &e;
      break;
    }
  static constexpr Entry kMotion{kSky, "", 'w', Handlers::motion, true};
  // SkyDroid angle and rate commands move the axes (Topotek's: device_topotek.cpp).
  if (!entry && dialect_ == kSky && req.control == 'w')
    if (const top::MotionSpec* m = top::motion_of(dialect_, id))
      if (m->kind == top::MotionKind::angle || m->kind == top::MotionKind::rate) entry = &kMotion;
  if (!entry || !entry->fn(call)) return false;
  // Echoed where top::write_reply says a write is (SkyDroid 2.3.1; a
  // Topotek PTZ is taken without a word), and by the ignore-motion= fault's
  // firmware, which echoes what it does not carry out.
  if (entry->echo && (!silent_write(*dec.command) || ignores_motion(id))) Handlers::echo(call);
  return true;
}

}  // namespace topsim
