#include "wire.hpp"

#include "top/decode.hpp"
#include "top/device.hpp"
#include "top/motion.hpp"

namespace topconf::drive::detail {
namespace {

// The motion a driver's frame commands, in the convention of docs/DRIVE.md
// (top/motion.hpp: a positive value times the axis's sign turns right or up).
void read_command(const top::Decoded& dec, std::string_view data, bool field, WireFrame& w) {
  const top::MotionSpec* m = dec.motion;
  if (!m || !dec.form) return;
  if (m->kind == top::MotionKind::ptz) {
    const top::PtzAction a = top::ptz_action(top::ptz_code(*dec.form, data));
    if (a.move == top::PtzMove::stop) {
      w.rate = true;
      w.axis = {true, true, true};
    } else if (a.move == top::PtzMove::turn) {
      w.rate = true;
      const auto i = static_cast<std::size_t>(a.axis);
      w.axis[i] = true;
      w.value[i] = a.sign;  // a turn at the device's PTZ speed
    } else if (a.move == top::PtzMove::centre) {
      w.angle = true;
      w.axis = {true, true, false};
    }
    return;
  }
  if (m->kind != top::MotionKind::rate && m->kind != top::MotionKind::angle) return;
  top::MotionReading r;
  if (!top::read_motion(*m, *dec.form, data, r)) return;
  (m->kind == top::MotionKind::rate ? w.rate : w.angle) = true;
  for (const top::MotionAxis& a : m->fields()) {
    const auto i = static_cast<std::size_t>(a.axis);
    if (!r.has[i]) continue;
    w.axis[i] = true;
    const double v = m->kind == top::MotionKind::rate
                         ? top::motion_speed(*m, r.value[i], r.raw[i], field)
                         : r.value[i];
    w.value[i] = v * a.sign_in(field);
  }
}

}  // namespace

WireTap::WireTap(top::Model model, bool datagrams, bool field)
    : model_(model), datagrams_(datagrams), field_(field) {}

void WireTap::take(double t, bool in, std::string_view bytes) {
  std::lock_guard lock(mu_);
  top::StreamDecoder& dec = in ? in_ : out_;
  dec.feed(bytes);
  if (datagrams_)
    dec.finish();
  else
    dec.flush();
  drain(t, in, dec);
  if (datagrams_) dec.reset();
}

void WireTap::drain(double t, bool in, top::StreamDecoder& decoder) {
  top::StreamItem item;
  top::DecodeOptions o;
  o.dialect = top::dialect_of(model_);
  o.model = model_;
  o.role = in ? top::Role::request : top::Role::response;
  while (decoder.next(item)) {
    if (item.kind != top::ItemKind::frame) continue;
    const top::Frame& f = item.frame;
    WireFrame w;
    w.t = t;
    w.from_driver = in;
    w.ok = f.checksum_ok;
    w.src = f.src;
    w.dst = f.dst;
    w.control = f.control;
    w.ident = std::string(f.ident_view());
    w.data = std::string(f.data());
    w.raw = f.raw;
    if (f.checksum_ok) {
      const top::Decoded dec = top::decode(f, o);
      if (in) {
        read_command(dec, w.data, field_, w);
        // The switch of a stream the device pushes (not SkyDroid FAE, which
        // switches the client's FAI).
        if (f.control == 'w' && dec.switches && dec.switches->periodic &&
            dec.switches->sender == top::Sender::device) {
          const auto v = top::switch_value(w.data);
          w.stream_on = v && !top::switches_off(*dec.switches, *v);
        }
      } else {
        // An attitude report: three angles of 4 hex chars (a 2-char echo of
        // a switch is none). Its form need not be the document's (the C12's
        // GAC under a #TP header: SkyDroid errata).
        w.attitude =
            dec.motion && dec.motion->kind == top::MotionKind::attitude && w.data.size() >= 12;
      }
    }
    frames_.push_back(std::move(w));
  }
}

std::vector<WireFrame> WireTap::frames() const {
  std::lock_guard lock(mu_);
  return frames_;
}

}  // namespace topconf::drive::detail
