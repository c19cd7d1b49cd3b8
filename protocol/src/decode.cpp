// Decoding a frame into fields and findings: the command and form its
// shape decides (remembered by a DecodeCache without detail,
// top/detail/decode_cache.hpp), then each field (decode_fields.cpp), or
// without detail the form's plan (decode_plan.hpp).
#include "top/decode.hpp"

#include <algorithm>
#include <array>

#include "chars.hpp"
#include "decode_ctx.hpp"
#include "decode_plan.hpp"
#include "device_form.hpp"
#include "numbers.hpp"
#include "shape_slot.hpp"
#include "top/detail/decode_cache.hpp"
#include "top/detail/prefilter.hpp"
#include "top/device.hpp"
#include "top/dialect.hpp"
#include "top/motion.hpp"

namespace top {

using detail::cat;
using detail::check_fields;
using detail::Ctx;
using detail::FormPlan;
using detail::judge_planned;
using detail::plan_of;
using detail::role_fits;

namespace {

// A #TP frame whose length is not 2 (tp-length): info for a SkyDroid
// G-class command, which SkyDroid puts under #TP whatever its length.
void note_tp_length(Ctx& ctx, const Frame& frame, const CommandSpec* cmd, Dialect d, Decoded& out) {
  bool g_class = cmd && cmd->address == 'G' && d == Dialect::skydroid;
  // Every SkyDroid GAC stream frame has this finding: its 32 possible
  // messages (length 0-F, G class or not) are built once.
  auto message = [](std::uint32_t length, bool g) {
    return "#TP frame with length " + std::to_string(length) + " (the fixed header implies 2)" +
           (g ? "; SkyDroid puts every G-class command under #TP" : "");
  };
  static const std::array<std::string, 32> kMessages = [&] {
    std::array<std::string, 32> m;
    for (std::uint32_t i = 0; i < m.size(); ++i) m[i] = message(i % 16, i >= 16);
    return m;
  }();
  Finding& f = out.findings.emplace_back();
  f.code = FindingCode::tp_length;
  f.severity = g_class ? Severity::info : default_severity(FindingCode::tp_length);
  f.offset = 5;
  // (Not a ?: of the two: its result would be a copy of the kept message,
  // then assigned, two allocations instead of one.)
  if (ctx.detail && frame.declared_length < 16)  // two-digit lengths (TMP quirk) go past F
    f.message = kMessages[frame.declared_length + (g_class ? 16 : 0)];
  else if (ctx.detail)
    f.message = message(frame.declared_length, g_class);
}

// A client's frame in a length its document does not give that a form of
// the field takes (ArduPilot's 14-char SkyDroid FAI): a data-length of
// information, naming the form's source, where the document's device would
// refuse it (top::rejection takes no information as a refusal). A device's
// frames in the field's layouts (the 12-char Topotek GIA, an echo of the
// FAI) are what real devices send and get none.
void note_field_length(Ctx& ctx, const Frame& frame, const CommandSpec& cmd, const FormSpec& form,
                       Decoded& out) {
  if (!form.from_field() || cmd.from_field() || form.role == Role::response ||
      out.role == Role::response)
    return;
  const std::size_t len = frame.data_length;
  bool documented = false;
  for (const FormSpec& f : cmd.forms) {
    if (f.from_field() || f.control != form.control) continue;
    if (len >= f.min_length && len <= f.max_length) return;
    documented = true;
  }
  if (!documented) return;
  ctx.add(FindingCode::data_length, frame.data_offset, [&] {
    std::string m = cat(
        {std::to_string(len), " data byte(s); ", cmd.ident, " '", {&form.control, 1}, "' takes "});
    bool first = true;
    for (const FormSpec& f : cmd.forms) {
      if (f.from_field() || f.control != form.control) continue;
      if (!first) m += ", ";
      first = false;
      m += std::to_string(f.min_length);
      if (f.min_length != f.max_length) m.append("-").append(std::to_string(f.max_length));
    }
    return cat({m, " in ", cmd.section, "; field: ", form.evidence});
  });
  Finding& x = out.findings.back();
  x.severity = Severity::info;
  x.quirk = form.evidence;
}

// What a frame's dialect, role, identifier, header, lengths and control
// decide: the command, the form and their findings, in `out` (out.form stays
// null when no form applies: the decode ends there).
void decode_shape(Ctx& ctx, const Frame& frame, const DecodeOptions& opts, Dialect d,
                  Decoded& out) {
  const std::string_view ident = frame.ident_view();
  const auto ident_at =
      static_cast<std::uint32_t>(frame.header == Header::tmp_quirk ? 6 : frame.data_offset - 3);
  const CommandSpec* cmd = d == Dialect::unknown ? find_any(ident) : find_command(d, ident);
  if (cmd && d == Dialect::unknown) d = cmd->dialect;
  out.dialect = d;
  out.command = cmd;
  out.motion = cmd ? motion_of(*cmd) : nullptr;
  out.switches = frame.control == 'w' && out.role != Role::response
                     ? stream_enabled_by(d, ident, Profile::field)
                     : nullptr;

  if (frame.header == Header::fixed && frame.declared_length != 2)
    note_tp_length(ctx, frame, cmd, d, out);
  if (d == Dialect::skydroid && (frame.header == Header::ext8 || frame.header == Header::ext16))
    ctx.add(FindingCode::ext_header_skydroid, 0, [&] {
      return cat({to_string(frame.header),
                  " is a Topotek extended header; SkyDroid defines only #TP/#tp"});
    });

  if (!cmd) {
    ctx.add(FindingCode::unknown_ident, ident_at, [&] {
      return cat({"identifier ", ident, " is not in the ",
                  d == Dialect::unknown ? "TOP" : to_string(d), " catalog"});
    });
    return;
  }
  if (opts.model != Model::unknown && !cmd->supports(opts.model)) {
    // Not in the document for the model: information when field evidence
    // says the firmware takes it anyway (device.hpp: a healthy C13 running
    // ArduPilot's GSY/GSP/GAC/FAI is no warning), an error when nothing does.
    const FieldSupport* fs = field_supported(d, opts.model, ident, std::nullopt);
    ctx.add(FindingCode::unsupported_on_model, ident_at, [&] {
      return cat({ident, " (", cmd->section, ") is not listed for ", to_string(opts.model),
                  fs ? "; field: " : "", fs ? fs->evidence : ""});
    });
    Finding& x = out.findings.back();
    x.severity = fs ? Severity::info : Severity::error;
    if (fs) x.quirk = fs->evidence;
  }
  if (ident == "ERE")
    ctx.add(FindingCode::error_reply, ident_at, [&] {
      return cat({"the device rejected a command as invalid (",
                  {&frame.src, 1},
                  " to ",
                  {&frame.dst, 1},
                  ")"});
    });

  const std::size_t len = frame.data_length;
  const FormSpec* form = nullptr;
  bool swapped = false, control_known = false;
  for (const FormSpec& f : cmd->forms) {
    if (frame.control != 0 && f.control != frame.control) continue;
    control_known = true;
    if (len < f.min_length || len > f.max_length) continue;
    if (role_fits(f.role, out.role)) {
      form = &f;
      break;
    }
    if (!swapped && !form) swapped = true;
  }
  if (!form && swapped) {
    for (const FormSpec& f : cmd->forms) {
      if (frame.control != 0 && f.control != frame.control) continue;
      if (len < f.min_length || len > f.max_length) continue;
      form = &f;
      break;
    }
    if (form)
      ctx.add(FindingCode::unswapped_addresses, 3, [&] {
        return cat({"laid out as a ",
                    form->role == Role::response ? "response" : "request",
                    " but addressed ",
                    {&frame.src, 1},
                    " to ",
                    {&frame.dst, 1}});
      });
  }
  if (!control_known) {
    ctx.add(FindingCode::unsupported_control, 6, [&] {
      return cat({ident, " has no '", {&frame.control, 1}, "' form in ", cmd->section});
    });
    return;
  }
  if (!form) {
    ctx.add(FindingCode::data_length, frame.data_offset, [&] {
      std::string m = cat({std::to_string(len),
                           " data byte(s); ",
                           ident,
                           " '",
                           {frame.control ? &frame.control : "?", 1},
                           "' takes "});
      bool first = true;
      for (const FormSpec& f : cmd->forms) {
        if (frame.control != 0 && f.control != frame.control) continue;
        if (!first) m += ", ";
        first = false;
        m += std::to_string(f.min_length);
        if (f.min_length != f.max_length) m.append("-").append(std::to_string(f.max_length));
      }
      return m;
    });
    return;
  }
  out.form = form;
  if (form->role != Role::any && out.role == Role::any) out.role = form->role;
  note_field_length(ctx, frame, *cmd, *form, out);
}

// Among the forms of the frame's shape (control, role, length) from `form`
// on, the first whose fields validate (a document's first with
// `document_first`): LAT/LON's field echo and 5.8.7 output share a length.
// `form` when it is alone in its shape or none validates.
const FormSpec* by_content(const Frame& frame, const CommandSpec& cmd, const FormSpec* form,
                           Role role, bool document_first) {
  const std::size_t len = frame.data_length;
  const std::span<const FormSpec> rest(form, cmd.forms.data() + cmd.forms.size());
  auto same = [&](const FormSpec& f) {
    return f.control == form->control && role_fits(f.role, role) && len >= f.min_length &&
           len <= f.max_length;
  };
  if (std::count_if(rest.begin(), rest.end(), same) < 2) return form;
  Decoded trial;
  for (int pass = document_first ? 0 : 1; pass < 2; ++pass)
    for (const FormSpec& f : rest) {
      if (!same(f) || (pass == 0 && f.from_field())) continue;
      trial.findings.clear();
      Ctx t{frame, trial, false};
      check_fields(t, f, frame);
      if (trial.findings.empty()) return &f;
    }
  return form;
}

}  // namespace

// The fields of a frame whose shape has a form (`plan`: the shape's, when
// the cache knows it): the form chosen by content, its fields' findings and,
// with detail, their values.
static void decode_data(Ctx& ctx, const Frame& frame, const DecodeOptions& opts, Decoded& out,
                        const FormPlan* plan) {
  const FormSpec* shaped = out.form;
  const FormSpec* form = out.form =
      by_content(frame, *out.command, shaped, out.role, opts.document_first);
  if (form != shaped) plan = nullptr;  // the plan is the shape's form's

  std::string_view data = frame.data();
  std::size_t pos = 0;
  if (!form->none.empty() && data == form->none) {
    if (!ctx.detail) return;
    for (const FieldSpec& fs : form->fields) {
      FieldValue fv;
      fv.spec = &fs;
      fv.offset = static_cast<std::uint32_t>(frame.data_offset + pos);
      fv.length = fs.width ? fs.width : static_cast<std::uint32_t>(data.size() - pos);
      fv.valid = fv.none = true;
      fv.text = std::string(data.substr(pos, fv.length));
      pos += fv.length;
      out.fields.push_back(std::move(fv));
    }
    return;
  }
  if (!ctx.detail && frame.data_offset >= 8) {
    if (!plan) plan = &plan_of(*out.command, *form);
    if (plan->fast && plan->width == data.size() && judge_planned(ctx, *plan, frame)) return;
  }
  check_fields(ctx, *form, frame);
}

// The frame's command, form and findings, and its fields with detail;
// without detail through `cache` when there is one. The one body of both
// entry points (top::decode calls it without a cache): a call from one to
// the other costs the session's decode (docs/perf/decisions.md, "Decode
// shape cache").
bool detail::decode(const Frame& frame, const DecodeOptions& opts, DecodeCache* cache,
                    Decoded& out) {
  out.fields.clear();
  out.findings.clear();
  out.command = nullptr;
  out.form = nullptr;
  out.motion = nullptr;
  out.switches = nullptr;
  Ctx ctx{frame, out, opts.detail};
  out.role = opts.role != Role::any ? opts.role : role_from_addresses(frame);
  Dialect d = opts.dialect;
  if (d == Dialect::unknown && opts.model != Model::unknown) d = dialect_of(opts.model);
  if (d == Dialect::unknown) d = dialect_from_frame(frame);
  const FormPlan* plan = nullptr;  // the form's, when the shape cache knows it
  // The caller knows the device sent it: a recorded form of real firmware
  // (top/device.hpp) completes the shape's findings. What it reads and
  // writes is the shape's, so the shape cache remembers it too; `noted`:
  // the finding it added, if any.
  std::size_t noted = detail::kNoNote;
  bool diagnosed = false;  // the shape's, like the command
  auto shape = [&] {
    diagnosed = detail::may_matter_to_diagnoses(frame.ident);
    decode_shape(ctx, frame, opts, d, out);
    if (opts.role != Role::response) return;
    const std::size_t before = out.findings.size();
    detail::note_device_form(frame, opts.model, ctx.detail, out);
    if (out.findings.size() > before) noted = out.findings.size() - 1;
  };
  if (detail::ShapeSlot* slot =
          ctx.detail ? nullptr : detail::shape_slot(cache, opts, frame, d, out.role)) {
    if (slot->known) {
      detail::replay(*slot, out, noted, diagnosed);
    } else {
      shape();
      detail::remember(*slot, out, noted, diagnosed);  // unless the shape has too many findings
    }
    if (slot->known) plan = slot->plan;
  } else {
    shape();
  }
  if (out.form) decode_data(ctx, frame, opts, out, plan);
  // The finding the device's form added comes after the fields' own, as
  // the device's form is judged once the frame is (and the Lua dissector
  // lists them so).
  if (noted != detail::kNoNote && noted + 1 < out.findings.size())
    std::rotate(out.findings.begin() + static_cast<std::ptrdiff_t>(noted),
                out.findings.begin() + static_cast<std::ptrdiff_t>(noted) + 1, out.findings.end());
  return diagnosed;
}

void decode(const Frame& frame, const DecodeOptions& opts, Decoded& out) {
  detail::decode(frame, opts, nullptr, out);
}

Decoded decode(const Frame& frame, const DecodeOptions& opts) {
  Decoded out;
  decode(frame, opts, out);
  return out;
}

}  // namespace top
