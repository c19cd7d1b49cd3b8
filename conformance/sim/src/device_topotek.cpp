// The Topotek commands with state behind them, as ArduPilot's AP_Mount_Topotek
// and a real Topotek camera (PixEagle bench) show them
// (docs/sources/ardupilot.md sections 1, 8.1, 8.3): angle and rate commands
// move the axes (top::motion_of, with the field's signs and units under the
// field profile), GIA switches the attitude stream (GIA frames in the
// field, GIC in the document), the GIC query is answered as that camera
// does, tracking is a small state machine (TRC, LOC, OFT), and a
// rangefinder measurement is answered with its range (LRF); a write gets
// the answer top::write_reply gives it (none where the document gives it
// no reply form). Asked before device_handlers.cpp's table
// (Device::dispatch).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "device_util.hpp"
#include "sim/device.hpp"

namespace topsim {

using detail::data_byte;
using detail::field;

struct TopotekHandlers {
  using Call = detail::HandlerCall;
  using Fn = detail::HandlerFn;

  // The write back, its header kept (a real Topotek camera answers #tp with
  // #tp: PixEagle session 20260917T185212Z-identity, GMS), where
  // top::write_reply gives the write an answer (Device::silent_write: the
  // same camera echoed none of the writes the document gives no reply
  // form); `always` for a fault's echo.
  static bool echo(const Call& c, bool always = false) {
    if (!always && c.dec.command && c.dev.silent_write(*c.dec.command)) return true;
    c.out.push_back(
        c.dev.make(c.req.header, c.req, c.req.control, c.req.ident_view(), c.req.data()));
    return true;
  }

  // Angle and rate commands (top/motion.hpp): the field's signs and units
  // under the field profile (GIP down positive, YPR in deg/s x 1.2207).
  static bool motion(const Call& c) {
    Device& d = c.dev;
    const top::MotionSpec* m = top::motion_of(d.dialect_, c.req.ident_view());
    if (!m || (m->kind != top::MotionKind::angle && m->kind != top::MotionKind::rate)) return false;
    // ignore-motion=: firmware that echoes a command it does not carry out
    // (the echo is the fault's, even where the healthy device is silent)
    if (d.ignores_motion(c.req.ident_view())) return echo(c, true);
    const bool fld = d.field();
    for (const top::MotionAxis& x : m->fields()) {
      const auto axis = static_cast<std::size_t>(x.axis);
      Axis& a = d.axes_[axis];
      const top::FieldValue* v = field(c.dec, x.value);
      if (!v) continue;
      // invert=: this kind of command turns the axis the other way.
      const double sign = x.sign_in(fld) * (d.fault_inverts(axis, m->kind) ? -1 : 1);
      if (m->kind == top::MotionKind::angle) {
        const top::FieldValue* spd = field(c.dec, x.speed);
        const double s = spd ? top::motion_speed(*m, spd->value, spd->integer, fld) : 0;
        a.target = std::clamp(sign * v->value, a.min, a.max);
        // 0: the document gives no meaning; the full speed (99)
        a.target_speed = s > 0 ? s : top::motion_speed(*m, 9.9, 99, fld);
        a.has_target = true;
        a.rate = 0;
        a.rate_until = 0;
      } else {
        a.rate = sign * top::motion_speed(*m, v->value, v->integer, fld);
        a.rate_until = c.now_us + std::uint64_t{d.opts_.speed_hold_ms} * 1000;
        a.has_target = false;
      }
    }
    return echo(c);
  }

  // GIA and GAA writes: the stream on (at the device's rate) or off. In the
  // field GIA 01 pushes GIA frames (top::stream_enabled_by under the profile).
  static bool stream_write(const Call& c) {
    Device& d = c.dev;
    const int v = data_byte(c.req.data());
    const top::StreamSpec* s =
        top::stream_enabled_by(d.dialect_, c.req.ident_view(), d.opts_.profile);
    if ((v != 0 && v != 1) || !s) return false;
    d.start_stream(s->push, v ? d.opts_.topotek_stream_hz : 0, c.req.src, c.now_us);
    // no-stream=: firmware that answers the switch and never streams (the
    // answer is the fault's, even where the healthy device is silent)
    return echo(c, d.opts_.faults.never_pushes(s->push));
  }

  // The GIC query: the attitude now, in the identifier top::reply_ident
  // gives (a real Topotek camera answers with a 12-char GIA, the document
  // with GIC).
  static bool attitude_read(const Call& c) {
    Device& d = c.dev;
    d.advance(c.now_us);
    const std::string_view id = top::reply_ident(d.model_, c.req.ident_view(), d.opts_.profile);
    const std::string data = d.attitude_data(id);
    c.out.push_back(
        d.build(d.reply_form(c.req, id, data.size()), c.req.src, c.req.dst, 'r', id, data));
    return true;
  }

  // TRC write: 02 prepare and 01 cancel go to waiting, 00 exits; a lens that
  // cannot track stays in state 4. A cancel while tracking pushes one OFT
  // with an all-zero box and status 1 (PixEagle bench notes).
  static bool tracking_write(const Call& c) {
    Device& d = c.dev;
    Tracking& t = d.tracking_;
    const int v = data_byte(c.req.data());
    if (v < 0 || v > 2) return false;
    if (t.state != '4') {
      if (t.state == '2' && v != 2) d.push_box(t, '1', c.out);
      t.state = v == 0 ? '0' : '1';
      t.starts_us = 0;
    }
    return echo(c);
  }

  // TRC read: 0 and the state char.
  static bool tracking_read(const Call& c) {
    Device& d = c.dev;
    const std::string data{'0', d.tracking_.state};
    const std::string_view id = c.req.ident_view();
    c.out.push_back(d.build(d.reply_form(c.req, id, 2), c.req.src, c.req.dst, 'r', id, data));
    return true;
  }

  // LOC: a point or rectangle while waiting (or tracking: a new target)
  // starts tracking about 0.4 s later (PixEagle: the first active state
  // ~400 ms after LOC).
  static bool tracking_target(const Call& c) {
    Device& d = c.dev;
    Tracking& t = d.tracking_;
    const auto* x = field(c.dec, "x");
    const auto* y = field(c.dec, "y");
    const auto* w = field(c.dec, "width");
    const auto* h = field(c.dec, "height");
    const top::StreamSpec* s =
        top::stream_enabled_by(d.dialect_, c.req.ident_view(), d.opts_.profile);
    if (!x || !y || !w || !h || !s) return false;
    if (t.state == '1' || t.state == '2' || t.state == '3') {
      t.x = static_cast<std::int16_t>(x->integer);
      t.y = static_cast<std::int16_t>(y->integer);
      t.w = static_cast<std::uint16_t>(w->integer);
      t.h = static_cast<std::uint16_t>(h->integer);
      t.dst = c.req.src;
      t.device = c.req.dst;
      t.push = s->push;
      if (t.state != '2') t.starts_us = c.now_us + kTrackStartUs;
    }
    return echo(c);
  }

  // LRF control (Topotek 5.9 note 2: 00 stop, 01 on, 02 single, 03
  // continuous): answered with the result in the document's X1X2X3X4X5.X6,
  // metres to 0.1 m (Topotek 5.9; the form ArduPilot's AP_Mount_Topotek.cpp
  // @ d4209711 reads in gimbal_dist_info_analyse(), "12345.6"), as every
  // write of a command with a reply layout is answered in it
  // (top::write_reply); a stop too. One result per write (continuous
  // measurement is not repeated).
  static bool range_write(const Call& c) {
    if (!field(c.dec, "action") || !c.dec.command) return false;
    char data[16];
    // range-form=short: no zero padding (topconf drive 8.3).
    std::snprintf(data, sizeof data, c.dev.opts_.faults.range_short ? "%.1f" : "%07.1f",
                  std::clamp(c.dev.opts_.range_m, 0.0, 99999.9));
    const std::string_view d(data);
    c.out.push_back(c.dev.make(top::choose_header(c.dev.dialect_, c.dec.command->address, d.size()),
                               c.req, 'w', c.req.ident_view(), d));
    return true;
  }

  static constexpr std::uint64_t kTrackStartUs = 400000;
};

namespace {

struct TopotekEntry {
  std::string_view ident;
  char control;
  TopotekHandlers::Fn fn;
};

constexpr TopotekEntry kTopotekHandlers[] = {
    {"GIA", 'w', TopotekHandlers::stream_write},  {"GAA", 'w', TopotekHandlers::stream_write},
    {"GIC", 'r', TopotekHandlers::attitude_read}, {"TRC", 'w', TopotekHandlers::tracking_write},
    {"TRC", 'r', TopotekHandlers::tracking_read}, {"LOC", 'w', TopotekHandlers::tracking_target},
    {"LRF", 'w', TopotekHandlers::range_write},
};

// OFT at about video rate while tracking (PixEagle session
// 20260917T051606Z-point: 33 ms apart, ~30 Hz).
constexpr std::uint64_t kBoxPeriodUs = 1000000 / 30;

void put_le16(std::string& s, long v) {
  const auto u = static_cast<std::uint16_t>(std::clamp(v, 0L, 65535L));
  s.push_back(static_cast<char>(u & 0xFF));
  s.push_back(static_cast<char>(u >> 8));
}

}  // namespace

// One OFT: the LOC box in pixels of 1920x1080, little-endian (top left x, y,
// width, height), then the status char; '1' sends an all-zero box.
void Device::push_box(const Tracking& t, char status, std::vector<std::string>& out) const {
  std::string data;
  if (status == '2') {
    const double w = t.w * 0.96, h = t.h * 0.54;
    put_le16(data, std::lround(960 + t.x * 0.96 - w / 2));
    put_le16(data, std::lround(540 + t.y * 0.54 - h / 2));
    put_le16(data, std::lround(w));
    put_le16(data, std::lround(h));
  } else {
    data.assign(8, '\0');
  }
  data.push_back(status);
  out.push_back(
      build(form_of(t.push, top::Sent::push, data.size()), t.dst, t.device, 'w', t.push, data));
}

void Device::poll_topotek(std::uint64_t now_us, std::vector<std::string>& out) {
  Tracking& t = tracking_;
  if (t.starts_us != 0 && t.starts_us <= now_us) {
    t.starts_us = 0;
    t.state = '2';
    t.next_box_us = now_us;
    t.on_us = now_us;
  }
  if (t.state != '2' || t.next_box_us > now_us) return;
  // A stalled OFT push keeps its timing and sends nothing.
  if (!opts_.faults.muted(t.push, now_us - std::min(now_us, t.on_us))) push_box(t, '2', out);
  t.next_box_us += kBoxPeriodUs;
  if (t.next_box_us <= now_us) t.next_box_us = now_us + kBoxPeriodUs;
}

bool Device::dispatch_topotek(const top::Frame& req, const top::Decoded& dec, std::uint64_t now_us,
                              std::vector<std::string>& out) {
  const TopotekHandlers::Call call{*this, req, dec, now_us, out};
  const std::string_view id = req.ident_view();
  for (const TopotekEntry& e : kTopotekHandlers)
    if (e.control == req.control && e.ident == id) return e.fn(call);
  if (req.control == 'w' && top::motion_of(dialect_, id)) return TopotekHandlers::motion(call);
  return false;
}

}  // namespace topsim
