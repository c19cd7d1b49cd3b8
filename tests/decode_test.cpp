#include "top/decode.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "test_util.hpp"
#include "top/detail/decimal.hpp"

using namespace top;
using toptest::tmp_quirk_frame;

namespace {

Decoded dec(std::string_view bytes, Dialect d = Dialect::unknown, Model m = Model::unknown) {
  ParseResult r = parse_exact(bytes);
  EXPECT_EQ(r.status, ParseStatus::frame) << bytes;
  return decode(r.frame, {.dialect = d, .model = m});
}

const FieldValue& field(const Decoded& d, std::string_view name) {
  for (const auto& f : d.fields)
    if (f.name() == name) return f;
  static FieldValue none;
  ADD_FAILURE() << "no field " << name << " in " << d.summary();
  return none;
}

}  // namespace

TEST(Decode, AngleCommand) {
  Decoded d = dec("#tpUG6wGAYEC7832", Dialect::skydroid);
  ASSERT_NE(d.command, nullptr);
  EXPECT_EQ(d.command->ident, "GAY");
  EXPECT_EQ(d.role, Role::request);
  const FieldValue& a = field(d, "angle");
  EXPECT_DOUBLE_EQ(a.value, -50.0);
  EXPECT_EQ(a.integer, -5000);
  EXPECT_EQ(a.unit(), "deg");
  EXPECT_EQ(a.offset, 10u);
  EXPECT_EQ(a.length, 4u);
  EXPECT_EQ(format_value(a), "-50.00 deg");
  EXPECT_DOUBLE_EQ(field(d, "speed").value, 5.0);
  EXPECT_EQ(d.summary(), "angle -50.00 deg, speed 5.0 deg/s");
  std::string s = "GAY: ";  // appended after what the buffer holds, separators as summary()'s
  d.append_summary(s);
  EXPECT_EQ(s, "GAY: angle -50.00 deg, speed 5.0 deg/s");
}

TEST(Decode, TpLengthSeverityDependsOnClassAndDialect) {
  Decoded g = dec("#TPUG6wGAYEF073248", Dialect::skydroid);
  ASSERT_EQ(g.findings.size(), 1u);
  EXPECT_EQ(g.findings[0].code, FindingCode::tp_length);
  EXPECT_EQ(g.findings[0].severity, Severity::info);
  Decoded t = dec("#TPUG6wGAYEF073248", Dialect::topotek);
  ASSERT_FALSE(t.findings.empty());
  EXPECT_EQ(t.findings[0].code, FindingCode::tp_length);
  EXPECT_EQ(t.findings[0].severity, Severity::warning);
}

TEST(Decode, EnumNamesPerDialect) {
  EXPECT_EQ(field(dec("#TPUG2wPTZ0670", Dialect::skydroid), "action").enum_name, "follow");
  EXPECT_EQ(field(dec("#TPUG2wPTZ0670", Dialect::topotek), "action").enum_name, "lock");
  EXPECT_EQ(format_value(field(dec("#TPUG2wPTZ0670", Dialect::skydroid), "action")), "follow (06)");
}

TEST(Decode, UndocumentedEnumValue) {
  std::string s = with_checksum("#TPUG2wPTZ7F");
  Decoded d = dec(s, Dialect::skydroid);
  EXPECT_TRUE(toptest::has_code(d.findings, FindingCode::value_out_of_range));
}

TEST(Decode, EncodeRoundTrip) {
  const CommandSpec* c = find_command(Dialect::skydroid, "GAY");
  ASSERT_NE(c, nullptr);
  EncodeValue v[2] = {{.number = -50.0}, {.number = 5.0}};
  std::string data;
  ASSERT_TRUE(encode_fields(c->forms[0], v, data));
  EXPECT_EQ(data, "EC7832");
  EncodeValue too_big[2] = {{.number = 400.0}, {.number = 5.0}};
  EXPECT_FALSE(encode_fields(c->forms[0], too_big, data));
}

TEST(Decode, AttitudeStream) {
  // A real Topotek reply (DESIGN.md field notes): addresses swapped.
  Decoded d = dec("#tpGPCrGACFF36ED5A0048DE");
  EXPECT_EQ(d.dialect, Dialect::topotek);
  EXPECT_EQ(d.role, Role::response);
  EXPECT_NEAR(field(d, "yaw").value, -2.02, 1e-9);
  EXPECT_NEAR(field(d, "pitch").value, -47.74, 1e-9);
  EXPECT_NEAR(field(d, "roll").value, 0.72, 1e-9);
  EXPECT_TRUE(d.findings.empty());
}

TEST(Decode, ZoomPositionIsSigned) {
  Decoded d = dec("#tpMU4rZOMFFB447");
  EXPECT_EQ(field(d, "position").integer, -76);
}

TEST(Decode, GpsBinaryStructLittleEndian) {
  std::string data;
  auto le = [&](std::uint32_t v, int n) {
    for (int i = 0; i < n; ++i) data += static_cast<char>((v >> (8 * i)) & 0xFF);
  };
  le(static_cast<std::uint16_t>(-1500), 2);
  le(static_cast<std::uint32_t>(1203456789), 4);
  le(static_cast<std::uint32_t>(-301234567), 4);
  le(static_cast<std::uint32_t>(123456), 4);
  std::string s = build_frame({.header = Header::variable,
                               .src = 'P',
                               .dst = 'D',
                               .control = 'w',
                               .ident = "GPS",
                               .data = data});
  Decoded d = dec(s);
  ASSERT_NE(d.command, nullptr);
  EXPECT_NEAR(field(d, "longitude").value, 120.3456789, 1e-9);
  EXPECT_NEAR(field(d, "latitude").value, -30.1234567, 1e-9);
  EXPECT_NEAR(field(d, "altitude").value, 123.456, 1e-9);
  EXPECT_EQ(field(d, "longitude").unit(), "deg");
  for (const auto& f : d.findings) EXPECT_NE(f.severity, Severity::error) << f.message;
}

TEST(Decode, TmpQuirkTemperatures) {
  Decoded d = dec(tmp_quirk_frame());
  ASSERT_NE(d.command, nullptr);
  EXPECT_EQ(d.command->ident, "TMP");
  EXPECT_EQ(field(d, "x_high").integer, 0xA0);
  EXPECT_NEAR(field(d, "t_high").value, 50.0, 1e-9);
  EXPECT_NEAR(field(d, "t_low").value, -20.0, 1e-9);
  EXPECT_NEAR(field(d, "t_center").value, 29.1, 1e-9);
  EXPECT_EQ(field(d, "t_center").unit(), "degC");
}

TEST(Decode, IpAddressAndCardCapacity) {
  Decoded ip = dec("#tpUDDwIPV192.168.31.22D7", Dialect::skydroid);
  EXPECT_EQ(field(ip, "address").text, "192.168.31.22");
  std::string sdc = with_checksum("#tpDUArSDC0123400ABC");
  Decoded d = dec(sdc, Dialect::skydroid);
  EXPECT_EQ(field(d, "free").integer, 0x01234);
  EXPECT_EQ(field(d, "total").integer, 0x00ABC);
  EXPECT_EQ(format_value(field(d, "free")), "4660 MB");
  std::string none = with_checksum("#tpDP5rSDCNNNNN");
  Decoded n = dec(none, Dialect::topotek);
  ASSERT_FALSE(n.fields.empty());
  EXPECT_TRUE(n.fields[0].none);
}

TEST(Decode, LowercaseHexDataIsDecodedAndReported) {
  std::string s = with_checksum("#tpUG6wGAYec7832");
  Decoded d = dec(s, Dialect::topotek);
  EXPECT_DOUBLE_EQ(field(d, "angle").value, -50.0);
  EXPECT_TRUE(toptest::has_code(d.findings, FindingCode::lowercase_hex));
}

TEST(Decode, UnknownIdentKeepsTheFrame) {
  Decoded d = dec("#TPUD2wQQQ0155", Dialect::skydroid);
  EXPECT_EQ(d.command, nullptr);
  EXPECT_TRUE(toptest::has_code(d.findings, FindingCode::unknown_ident));
}

TEST(Decode, ExampleDataDecodesCleanForEveryForm) {
  for (Dialect dl : {Dialect::skydroid, Dialect::topotek})
    for (const CommandSpec& c : commands(dl))
      for (const FormSpec& f : c.forms) {
        std::string data = example_data(f);
        EXPECT_GE(data.size(), f.min_length) << c.ident;
        EXPECT_LE(data.size(), f.max_length) << c.ident;
      }
}

TEST(Decode, SkydroidNoCardIsNotZeroMegabytes) {
  std::string s = with_checksum("#tpDUArSDC0000000000");
  Decoded d = dec(s, Dialect::skydroid);
  ASSERT_EQ(d.fields.size(), 2u);
  EXPECT_TRUE(d.fields[0].none);
  EXPECT_TRUE(d.fields[1].none);
  EXPECT_EQ(d.summary(), "none (all zero: no memory card)");
  // A full card (no MB free) is not "no card".
  std::string full = with_checksum("#tpDUArSDC000001D1C0");
  Decoded f = dec(full, Dialect::skydroid);
  EXPECT_FALSE(f.fields[0].none);
  EXPECT_EQ(f.fields[0].integer, 0);
  EXPECT_EQ(f.fields[1].integer, 0x1D1C0);
}

// format_value writes numbers as printf("%.*f") would (it uses std::to_chars,
// which promises the same text): every numeric field of the catalog, with
// values across its range and beyond, and huge decimal numbers.
TEST(Decode, FormatValueNumbersAreThoseOfPrintf) {
  auto decimals = [](double scale) {  // as decode.cpp decides them
    int d = 0;
    double s = scale;
    while (d < 9 && scale > 0 && std::fabs(s - std::round(s)) > 1e-9) {
      s *= 10;
      ++d;
    }
    return d;
  };
  auto printf_text = [](double v, int d) {
    std::vector<char> b(static_cast<std::size_t>(std::snprintf(nullptr, 0, "%.*f", d, v)) + 1);
    std::snprintf(b.data(), b.size(), "%.*f", d, v);
    return std::string(b.data());
  };
  std::size_t checked = 0;
  std::uint64_t x = 88172645463325252ull;
  auto rnd = [&] {
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return x;
  };
  for (Dialect dl : {Dialect::skydroid, Dialect::topotek})
    for (const CommandSpec& c : commands(dl))
      for (const FormSpec& form : c.forms)
        for (const FieldSpec& s : form.fields) {
          if (s.kind != FieldKind::hex_u && s.kind != FieldKind::hex_s &&
              s.kind != FieldKind::dec_u && s.kind != FieldKind::le_i16 &&
              s.kind != FieldKind::le_u16 && s.kind != FieldKind::le_i32 &&
              s.kind != FieldKind::number)
            continue;
          for (int i = 0; i < 200; ++i) {
            FieldValue fv;
            fv.spec = &s;
            fv.valid = true;
            fv.integer = static_cast<std::int64_t>(rnd() % 2000001) - 1000000;
            if (i % 4 == 0) fv.integer = static_cast<std::int64_t>(rnd() >> (rnd() % 64));
            fv.value = static_cast<double>(fv.integer) * s.scale;
            const int d = decimals(s.scale);
            const double m = std::round(s.scale * std::pow(10.0, d));
            if (i % 2 && std::fabs(static_cast<double>(fv.integer) * m) < 1e15)
              fv.value = static_cast<double>(fv.integer) * m / std::pow(10.0, d);  // as decoded
            if (s.kind == FieldKind::number) {
              fv.text = "12.5";
              continue;  // printed as its text
            }
            std::string want = printf_text(fv.value, d);
            if (!s.unit.empty()) want += " " + std::string(s.unit);
            const std::string got = format_value(fv);
            ASSERT_EQ(got.substr(0, want.size()), want) << s.name << " " << fv.integer;
            ++checked;
          }
        }
  EXPECT_GT(checked, 5000u);
  // past the 64-character buffer: a 1e300 value in a decimal field
  static const FieldSpec big{"big", FieldKind::hex_u, 2, 0.5, "", 0, -1};
  FieldValue fv;
  fv.spec = &big;
  fv.valid = true;
  fv.value = 1e300;
  EXPECT_EQ(format_value(fv), printf_text(1e300, 1));
}

// A scaled value is the double nearest to its decimal: 70 x 0.01 is 0.7, not
// 0.7000000000000001 (what the multiplication gives, and what topdump --json
// printed for about one field in six of the benchmark capture).
TEST(Decode, ScaledValuesAreTheNearestDoubleToTheirDecimal) {
  ParseResult r = parse_exact(with_checksum("#TPGUCrGAC0046FFAD0053"));
  ASSERT_EQ(r.status, ParseStatus::frame);
  const Decoded d = decode(r.frame, {.dialect = Dialect::skydroid});
  EXPECT_EQ(field(d, "yaw").value, 0.7);
  EXPECT_EQ(field(d, "pitch").value, -0.83);
  EXPECT_EQ(field(d, "roll").value, 0.83);
  std::int64_t mant = 0;
  int dec = 0;
  ASSERT_TRUE(detail::exact_decimal(field(d, "pitch"), mant, dec));
  EXPECT_EQ(mant, -83);
  EXPECT_EQ(dec, 2);
  EXPECT_EQ(format_value(field(d, "pitch")), "-0.83 deg");
}

// An enum_hex code is written as printf("%0*llX", width, value) would: the
// field's width, wider when the value needs more digits; with its name or
// "(undocumented)". append_value appends to what the buffer holds.
TEST(Decode, EnumCodesAreThoseOfPrintf) {
  static constexpr EnumValue kNames[] = {{0x06, "follow"}};
  FieldSpec spec;
  spec.name = "action";
  spec.kind = FieldKind::enum_hex;
  spec.enums = kNames;
  std::size_t checked = 0;
  for (std::uint32_t width = 0; width <= 17; ++width)
    for (std::uint64_t v : {0x0ull, 0x6ull, 0x7Full, 0x1ABull, 0xFFFFull, 0x123456789ABCDEFull,
                            0xFEDCBA9876543210ull}) {
      FieldValue f;
      f.spec = &spec;
      f.valid = true;
      f.length = width;
      f.integer = static_cast<std::int64_t>(v);
      f.enum_name = v == 0x6 ? "follow" : "";
      char b[64];
      std::snprintf(b, sizeof b, "%0*llX", static_cast<int>(width),
                    static_cast<unsigned long long>(v));
      const std::string want =
          v == 0x6 ? "follow (" + std::string(b) + ")" : std::string(b) + " (undocumented)";
      EXPECT_EQ(format_value(f), want) << width << " " << v;
      std::string appended = "x=";
      append_value(f, appended);
      EXPECT_EQ(appended, "x=" + want);
      ++checked;
    }
  EXPECT_EQ(checked, 18u * 7u);
}

namespace {

// The verdict of a decode: dialect, role, command, form and each finding's
// code, severity and offset.
std::string verdict_of(const Decoded& d) {
  std::string s = std::to_string(static_cast<int>(d.dialect)) + "/" +
                  std::to_string(static_cast<int>(d.role)) + " " +
                  (d.command ? std::string(d.command->ident) : "-") + " form " +
                  std::to_string(reinterpret_cast<std::uintptr_t>(d.form));
  for (const Finding& x : d.findings)
    s += " " + std::string(to_string(x.code)) + "/" + std::string(to_string(x.severity)) + "@" +
         std::to_string(x.offset);
  return s;
}

}  // namespace

// Without detail, forms of hex fields are judged by a lane-wise path of
// their own (integer bounds worked out from each scaled range). For every
// form of both catalogs, each field is swept through its values (all of
// them up to two chars; for wider fields, each digit through 0-F and the
// values around the range bounds and the labels), and each data byte through
// lowercase, non-hex and high bytes, with the other fields at their example
// values: the verdict is the one decoding with detail gives.
TEST(Decode, VerdictWithoutDetailAgreesOnEveryFieldValue) {
  std::size_t compared = 0, out_of_range = 0;
  Decoded lean;
  for (Dialect dl : {Dialect::skydroid, Dialect::topotek})
    for (const CommandSpec& cmd : commands(dl))
      for (const FormSpec& form : cmd.forms) {
        const std::string base = example_data(form);
        std::vector<std::string> datas;
        std::size_t at = 0;
        for (const FieldSpec& fs : form.fields) {
          const std::size_t w = fs.width ? fs.width : base.size() - at;
          auto put = [&](std::uint64_t v) {
            std::string d = base;
            for (std::size_t i = 0; i < w && i < 16; ++i)
              d[at + w - 1 - i] = "0123456789ABCDEF"[(v >> (4 * i)) & 0xF];
            datas.push_back(d);
          };
          if (w >= 1 && w <= 2) {
            for (std::uint64_t v = 0; v < (std::uint64_t{1} << (4 * w)); ++v) put(v);
          } else if (w <= 8) {
            const std::uint64_t top = (std::uint64_t{1} << (4 * w)) - 1;
            for (std::size_t i = 0; i < w; ++i)
              for (std::uint64_t n = 0; n < 16; ++n) put(n << (4 * i));
            std::vector<double> marks{0, 1, -1};
            if (fs.min <= fs.max) marks.insert(marks.end(), {fs.min, fs.max});
            for (const EnumValue& e : fs.enums) put(static_cast<std::uint64_t>(e.value));
            for (double m : marks)
              for (int delta = -3; delta <= 3; ++delta) {
                const auto iv = std::llround(m / (fs.scale > 0 ? fs.scale : 1)) + delta;
                put(static_cast<std::uint64_t>(iv) & top);
              }
            put(top);
            put(top >> 1);
            put((top >> 1) + 1);
          }
          at += w;
        }
        for (std::size_t i = 0; i < base.size(); ++i)
          for (char c : {'a', 'f', 'G', 'g', ' ', '-', '.', 'N', '\x80', '\xff', '\0'}) {
            std::string d = base;
            d[i] = c;
            datas.push_back(d);
          }
        datas.push_back(base);
        for (const std::string& data : datas) {
          BuildSpec b;
          b.header = choose_header(dl, cmd.address, data.size());
          b.src = form.role == Role::response ? cmd.address : 'U';
          b.dst = form.role == Role::response ? 'U' : cmd.address;
          b.control = form.control;
          b.ident = cmd.ident;
          b.data = data;
          const ParseResult r = parse_frame(build_frame(b), true);
          ASSERT_EQ(r.status, ParseStatus::frame) << data;
          DecodeOptions o{dl, Model::unknown, Role::any};
          const Decoded full = decode(r.frame, o);
          o.detail = false;
          decode(r.frame, o, lean);
          ASSERT_EQ(verdict_of(lean), verdict_of(full))
              << cmd.ident << " " << testing::PrintToString(data);
          ++compared;
          for (const Finding& x : full.findings)
            out_of_range += x.code == FindingCode::value_out_of_range;
        }
      }
  EXPECT_GT(compared, 20000u);
  EXPECT_GT(out_of_range, 1000u);  // the bounds were crossed, not only approached
}

// A shape with more findings than a slot remembers is decoded afresh each
// time, and must not reuse anything of the shape its slot held before: here
// a PTZ write, whose planned form (one two-char field) once judged the data
// of the ERE frame after it.
TEST(Decode, CacheForgetsTheShapeItEvicts) {
  DecodeCache one(1);  // every shape in the same slot
  DecodeOptions o{Dialect::skydroid, Model::sip, Role::any};
  o.detail = false;
  BuildSpec b;
  b.header = Header::fixed;
  b.src = 'U';
  b.dst = 'G';
  b.control = 'w';
  b.ident = "PTZ";
  b.data = "FF";
  const ParseResult ptz = parse_frame(build_frame(b), true);
  // ERE under #tP from a client: extended header, not on the model, an
  // error reply, a response's form addressed as a request
  b.header = Header::ext8;
  b.dst = 'M';
  b.ident = "ERE";
  const ParseResult ere = parse_frame(build_frame(b), true);
  ASSERT_EQ(ptz.status, ParseStatus::frame);
  ASSERT_EQ(ere.status, ParseStatus::frame);
  Decoded plain, cached;
  decode(ere.frame, o, plain);
  ASSERT_GT(plain.findings.size(), 3u);  // more than a slot remembers
  ASSERT_NE(plain.form, nullptr);
  o.cache = &one;
  decode(ptz.frame, o, cached);
  for (int pass = 0; pass < 2; ++pass) {
    decode(ere.frame, o, cached);
    EXPECT_EQ(verdict_of(cached), verdict_of(plain)) << pass;
  }
}

// The shapes of a capture spread over the slots: every form of every command
// of both catalogs (about 190 shapes, in 4096 slots) is missed once and then
// found, bar a few collisions (about 9 expected; fewer than a tenth). A hash
// that took the low bits of its product put shapes that differ in their
// identifier's first chars in one slot (64 misses on the second pass here),
// and topdump stats ran 6% slower.
TEST(Decode, CacheSpreadsShapesOverItsSlots) {
  std::vector<ParseResult> frames;
  for (Dialect dl : {Dialect::skydroid, Dialect::topotek})
    for (const CommandSpec& cmd : commands(dl))
      for (const FormSpec& form : cmd.forms) {
        BuildSpec b;
        b.header = choose_header(dl, cmd.address, form.min_length);
        b.src = form.role == Role::response ? cmd.address : 'U';
        b.dst = form.role == Role::response ? 'U' : cmd.address;
        b.control = form.control;
        b.ident = cmd.ident;
        const std::string data(form.min_length, '0');
        b.data = data;
        frames.push_back(parse_frame(build_frame(b), true));
        ASSERT_EQ(frames.back().status, ParseStatus::frame);
      }
  DecodeCache cache(4096);
  DecodeOptions o;
  o.detail = false;
  o.cache = &cache;
  Decoded d;
  for (const ParseResult& r : frames) decode(r.frame, o, d);
  const std::uint64_t first = cache.misses();
  EXPECT_GT(first, frames.size() / 2);  // distinct shapes, mostly
  for (const ParseResult& r : frames) decode(r.frame, o, d);
  EXPECT_LT(cache.misses() - first, first / 10) << first << " shapes";
}

// DecodeCache replays what a frame's shape decided (command, form, role,
// shape findings) instead of looking it up again. Every command of both
// catalogs, under every header, control, a spread of data lengths (inside,
// at and past each form's bounds), both address orders, each role and
// dialect asked for and a model of each dialect (or none), plus unknown
// identifiers: decoded through one cache shared by all of them (so its slots
// are reused by other shapes), twice, the verdict is the one without it,
// quirks included.
TEST(Decode, CacheGivesTheVerdictOfEveryShapeUnchanged) {
  // The default size, and one and two slots, where every shape evicts the
  // last: nothing of a shape may outlive its slot (a shape with too many
  // findings to remember once judged its data by the plan of the shape
  // before it).
  DecodeCache caches[] = {DecodeCache(), DecodeCache(1), DecodeCache(2)};
  std::size_t compared = 0, with_findings = 0;
  Decoded plain, cached;
  auto verdict = [](const Decoded& d) {
    std::string s = verdict_of(d);
    for (const Finding& x : d.findings) s += " q:" + std::string(x.quirk);
    return s;
  };
  // the dialect and model asked for: none, each dialect, each model's, and a
  // model of the other dialect
  const std::pair<Dialect, Model> kAsked[] = {
      {Dialect::unknown, Model::unknown}, {Dialect::skydroid, Model::unknown},
      {Dialect::topotek, Model::unknown}, {Dialect::unknown, Model::c10},
      {Dialect::unknown, Model::sip},     {Dialect::skydroid, Model::sip}};
  std::vector<std::pair<std::string_view, char>> idents;  // identifier, its address class
  for (Dialect dl : {Dialect::skydroid, Dialect::topotek})
    for (const CommandSpec& cmd : commands(dl)) idents.emplace_back(cmd.ident, cmd.address);
  idents.emplace_back("ZZZ", 'G');
  idents.emplace_back("ERE", 'G');
  for (const auto& [ident, address] : idents)
    for (Header h : {Header::fixed, Header::variable, Header::ext8, Header::ext16})
      for (char control : {'r', 'w'})
        for (std::size_t len : {0, 1, 2, 4, 6, 12, 16, 40})
          for (bool reply : {false, true}) {
            BuildSpec b;
            b.header = h;
            b.src = reply ? address : 'U';
            b.dst = reply ? 'U' : address;
            b.control = control;
            b.ident = ident;
            for (char fill : {'1', 'F'}) {
              const std::string data(len, fill);
              b.data = data;
              const ParseResult r = parse_frame(build_frame(b), true);
              ASSERT_EQ(r.status, ParseStatus::frame) << ident << " " << len;
              for (auto [dl, m] : kAsked)
                for (Role role : {Role::any, Role::request, Role::response}) {
                  DecodeOptions o{dl, m, role};
                  o.detail = false;
                  decode(r.frame, o, plain);
                  for (DecodeCache& cache : caches) {
                    o.cache = &cache;
                    for (int pass = 0; pass < 2; ++pass) {
                      decode(r.frame, o, cached);
                      ASSERT_EQ(verdict(cached), verdict(plain))
                          << ident << " " << to_string(h) << " " << control << " len " << len << " "
                          << fill << " pass " << pass << " of " << &cache - caches;
                      ASSERT_TRUE(cached.fields.empty());
                    }
                  }
                  ++compared;
                  with_findings += !plain.findings.empty();
                }
            }
          }
  EXPECT_GT(compared, 500000u);
  EXPECT_GT(with_findings, compared / 4);
  // With detail the cache is not used: messages come out as without it.
  Decoded full, full_cached;
  const ParseResult r = parse_frame(std::string_view("#TPUG2wZZZ007A"), true);
  ASSERT_EQ(r.status, ParseStatus::frame);
  DecodeOptions o{Dialect::skydroid, Model::unknown, Role::any};
  decode(r.frame, o, full);
  o.cache = &caches[0];
  decode(r.frame, o, full_cached);
  ASSERT_FALSE(full.findings.empty());
  EXPECT_EQ(full_cached.findings.front().message, full.findings.front().message);
  EXPECT_FALSE(full_cached.findings.front().message.empty());
}

// ---- The field's forms (issue 28; docs/sources/ardupilot.md): each frame
// is one a real unit, ArduPilot's drivers or a station was seen to send.

namespace {

// The codes of the frame's findings.
std::vector<FindingCode> codes(const Decoded& d) {
  std::vector<FindingCode> v;
  for (const Finding& f : d.findings) v.push_back(f.code);
  return v;
}

std::string from_hex(std::string_view hex) {
  std::string out;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2)
    out += static_cast<char>(std::stoi(std::string(hex.substr(i, 2)), nullptr, 16));
  return out;
}

}  // namespace

// A real SIP answers the GIC query with a 12-char GIA (issue 28 log);
// ArduPilot's driver reads yaw, pitch (down positive), roll in 0.01 deg.
TEST(DecodeField, GiaAttitudeFrame) {
  const Decoded d = dec("#tpGUCrGIA00000BB8000095", Dialect::topotek, Model::sip);
  ASSERT_NE(d.command, nullptr);
  EXPECT_EQ(d.command->ident, "GIA");
  ASSERT_NE(d.form, nullptr);
  EXPECT_TRUE(d.form->from_field());
  EXPECT_EQ(d.role, Role::response);
  EXPECT_TRUE(codes(d).empty()) << d.summary();
  EXPECT_DOUBLE_EQ(field(d, "yaw").value, 0.0);
  EXPECT_DOUBLE_EQ(field(d, "pitch").value, 30.0);  // 30 deg down on the wire
  EXPECT_DOUBLE_EQ(field(d, "roll").value, 0.0);
  // The document's switch is still the document's form.
  const Decoded on = dec("#TPUG2wGIA013E", Dialect::topotek, Model::sip);
  ASSERT_NE(on.form, nullptr);
  EXPECT_FALSE(on.form->from_field());
  EXPECT_EQ(field(on, "state").enum_name, "enable");
  // A negative yaw: FF38 = -2.00 deg.
  const Decoded neg = dec(with_checksum("#tpGPCrGIAFF38000000C8"), Dialect::topotek);
  EXPECT_DOUBLE_EQ(field(neg, "yaw").value, -2.0);
  EXPECT_DOUBLE_EQ(field(neg, "roll").value, 2.0);
}

TEST(DecodeField, TrcQueryStateAndWrites) {
  const Decoded q = dec("#TPPD2rTRC0048", Dialect::topotek, Model::sip);
  ASSERT_NE(q.command, nullptr);
  EXPECT_TRUE(q.command->from_field());
  EXPECT_EQ(q.command->section.substr(0, 7), "field: ");
  EXPECT_EQ(q.role, Role::request);
  EXPECT_TRUE(codes(q).empty());
  const Decoded r = dec("#TPDP2rTRC0048", Dialect::topotek, Model::sip);
  EXPECT_EQ(r.role, Role::response);
  EXPECT_TRUE(codes(r).empty());
  EXPECT_EQ(field(r, "state").enum_name, "stopped");
  const struct {
    const char* data;
    const char* state;
  } states[] = {{"01", "waiting"},
                {"02", "tracking"},
                {"03", "temporarily_lost"},
                {"04", "lens_unsupported"}};
  for (const auto& s : states) {
    const Decoded x =
        dec(with_checksum(std::string("#TPDU2rTRC") + s.data), Dialect::topotek, Model::sip);
    EXPECT_EQ(field(x, "state").enum_name, s.state) << s.data;
    EXPECT_TRUE(codes(x).empty()) << s.data;
  }
  // ArduPilot's driver's writes: prepare, cancel to waiting, exit.
  EXPECT_EQ(field(dec("#TPUD2wTRC0254", Dialect::topotek), "action").enum_name, "prepare");
  EXPECT_EQ(field(dec("#TPUD2wTRC0153", Dialect::topotek), "action").enum_name,
            "cancel_to_waiting");
  EXPECT_EQ(field(dec("#TPUD2wTRC0052", Dialect::topotek), "action").enum_name, "exit");
  EXPECT_TRUE(codes(dec("#TPUD2rTRC004D", Dialect::topotek)).empty());
}

TEST(DecodeField, TraReplyOfAHealthyTracker) {
  EXPECT_TRUE(codes(dec("#TPPD2rTRA0046", Dialect::topotek, Model::sip)).empty());
  const Decoded r = dec("#TPDP2rTRA1148", Dialect::topotek, Model::sip);
  ASSERT_NE(r.command, nullptr);
  EXPECT_EQ(r.command->ident, "TRA");
  EXPECT_TRUE(codes(r).empty());
  EXPECT_EQ(field(r, "fault").text, "11");  // a code whose meaning no source gives
}

TEST(DecodeField, Pa2ModelName) {
  EXPECT_TRUE(codes(dec("#TPUG2rPA2002A", Dialect::topotek, Model::sip)).empty());
  const Decoded r = dec("#TPUG6rPA2SIM_TPBA", Dialect::topotek);  // ArduPilot's SIM_Topotek
  ASSERT_NE(r.form, nullptr);
  EXPECT_EQ(field(r, "model").text, "SIM_TP");
}

// PixEagle's centre-point LOC to a real SIP, byte for byte.
TEST(DecodeField, LocPointIsBigEndian) {
  const std::string bytes = from_hex("237470504441774c4f4300000000003e006f00094537");
  ASSERT_EQ(bytes.substr(0, 10), "#tpPDAwLOC");
  const Decoded d = dec(bytes, Dialect::topotek, Model::sip);
  ASSERT_NE(d.command, nullptr);
  EXPECT_EQ(d.command->ident, "LOC");
  EXPECT_TRUE(codes(d).empty()) << d.summary();
  EXPECT_EQ(field(d, "x").integer, 0);
  EXPECT_EQ(field(d, "y").integer, 0);
  EXPECT_EQ(field(d, "width").integer, 62);
  EXPECT_EQ(field(d, "height").integer, 111);
  EXPECT_EQ(field(d, "mode").integer, 9);
  EXPECT_EQ(field(d, "mode").enum_name, "point");
  EXPECT_EQ(field(d, "x").spec->kind, FieldKind::be_i16);
  // A rectangle left of and above the centre: x -405 (FE6B), y -389 (FE7B).
  const std::string rect =
      with_checksum(std::string("#tpUDAwLOC") + from_hex("FE6BFE7B00C800C80001"));
  const Decoded r = dec(rect, Dialect::topotek);
  EXPECT_TRUE(codes(r).empty()) << r.summary();
  EXPECT_EQ(field(r, "x").integer, -405);
  EXPECT_EQ(field(r, "y").integer, -389);
  EXPECT_EQ(field(r, "width").integer, 200);
  EXPECT_EQ(field(r, "mode").enum_name, "rectangle");
  // Outside the +/-1000 grid: x 1001 (03E9).
  const Decoded out =
      dec(with_checksum(std::string("#tpUDAwLOC") + from_hex("03E90000000000000001")),
          Dialect::topotek);
  EXPECT_EQ(codes(out), std::vector<FindingCode>{FindingCode::value_out_of_range});
}

// OFT: PixEagle's examples, little-endian pixels then the status char.
TEST(DecodeField, OftTrackingBoxIsLittleEndian) {
  auto oft = [](unsigned x, unsigned y, unsigned w, unsigned h, char status) {
    std::string d = "#tpDP9wOFT";
    for (unsigned v : {x, y, w, h}) {
      d += static_cast<char>(v & 0xFF);
      d += static_cast<char>(v >> 8);
    }
    d += status;
    return with_checksum(d);
  };
  const Decoded a = dec(oft(952, 536, 51, 30, '2'), Dialect::topotek, Model::sip);
  ASSERT_NE(a.command, nullptr);
  EXPECT_EQ(a.command->ident, "OFT");
  EXPECT_EQ(a.role, Role::response);
  EXPECT_TRUE(codes(a).empty()) << a.summary();
  EXPECT_EQ(field(a, "x").integer, 952);
  EXPECT_EQ(field(a, "y").integer, 536);
  EXPECT_EQ(field(a, "width").integer, 51);
  EXPECT_EQ(field(a, "height").integer, 30);
  EXPECT_EQ(field(a, "status").enum_name, "tracking");
  const Decoded b = dec(oft(1288, 590, 127, 81, '2'), Dialect::topotek, Model::sip);
  EXPECT_EQ(field(b, "x").integer, 1288);
  EXPECT_EQ(field(b, "height").integer, 81);
  const Decoded c = dec(oft(0, 0, 0, 0, '1'), Dialect::topotek, Model::sip);
  EXPECT_EQ(field(c, "status").enum_name, "stopped");
  EXPECT_EQ(field(c, "width").integer, 0);
}

TEST(DecodeField, LrfFiveCharReply) {
  const Decoded d = dec("#tpMU5wLRF500002E", Dialect::topotek, Model::sip);
  ASSERT_NE(d.form, nullptr);
  EXPECT_TRUE(d.form->from_field());
  EXPECT_TRUE(codes(d).empty()) << d.summary();
  EXPECT_DOUBLE_EQ(field(d, "distance").value, 50000);
  EXPECT_EQ(field(d, "distance").unit(), "");  // not established
  // The document's form is still the document's.
  const Decoded doc = dec(with_checksum("#tpDU7wLRF00123.4"), Dialect::topotek, Model::sip);
  ASSERT_NE(doc.form, nullptr);
  EXPECT_FALSE(doc.form->from_field());
  EXPECT_DOUBLE_EQ(field(doc, "distance").value, 123.4);
}

TEST(DecodeField, BigEndianKindsEncodeAndName) {
  EXPECT_EQ(to_string(FieldKind::be_i16), "be_i16");
  EXPECT_EQ(field_kind_from_string("be_u16"), FieldKind::be_u16);
  const CommandSpec* loc = find_command(Dialect::topotek, "LOC");
  ASSERT_NE(loc, nullptr);
  const FormSpec& form = loc->forms[0];
  const EncodeValue v[] = {{-405}, {-389}, {200}, {200}, {1}};
  std::string data;
  ASSERT_TRUE(encode_fields(form, v, data));
  EXPECT_EQ(data, from_hex("FE6BFE7B00C800C80001"));
  const EncodeValue too_big[] = {{0}, {0}, {70000}, {0}, {1}};
  EXPECT_FALSE(encode_fields(form, too_big, data));
  EXPECT_EQ(example_data(form).size(), 10u);
}
