#include "top/catalog.hpp"

#include <gtest/gtest.h>

#include <set>

#include "test_util.hpp"

using namespace top;

namespace {
// Every identifier named anywhere in the documents (appendix tables and
// body text); the catalog must hold each one.
const char* const kSkydroidIdents[] = {
    "PTZ", "GSY", "GSP", "GSR", "GSM", "GAY", "GAP", "GAR", "GAM", "GAA", "GAC",
    "SUM", "GOT", "FAE", "FAI", "REC", "CAP", "VID", "SDC", "AWB", "IQE", "TIM",
    "DZM", "IMG", "IPV", "GTW", "DNS", "BNS", "VOM", "VER", "EXT", "UID", "TSM",
    "TAS", "TDI", "TIB", "TIC", "TAR", "TTR", "TGM", "SLR", "ZMC", "FCC", "ZFP",
    "IRC", "MNU", "EVS", "LAT", "ALT", "LON", "TMP", "RST", "RTF", "ERE"};
const char* const kTopotekIdents[] = {
    "ZMC", "ZOM", "FCC", "FOC", "ZFP", "ZMP", "SWH", "IRC", "ATE", "VSN", "MUL", "APC",
    "PTZ", "GSY", "GSP", "GSR", "GSM", "RPS", "YPR", "GAY", "GAP", "GAR", "GAM", "GIY",
    "GIP", "GIR", "GIM", "GAC", "GAA", "GIC", "GIA", "GMS", "VER", "REC", "CAP", "VID",
    "BIT", "SDC", "ROT", "IPV", "GTW", "RST", "LON", "LAT", "ALT", "AZI", "GPS", "UAV",
    "LRF", "TIM", "UTC", "PIP", "TMP", "TMR", "IMG", "DZM", "DFG", "ENT"};

void check_table(Dialect d) {
  std::set<std::string_view> seen;
  for (const CommandSpec& c : commands(d)) {
    SCOPED_TRACE(std::string(c.ident));
    EXPECT_EQ(c.dialect, d);
    EXPECT_TRUE(seen.insert(c.ident).second) << "duplicate";
    EXPECT_EQ(c.ident.size(), 3u);
    EXPECT_TRUE(c.address == 'G' || c.address == 'M' || c.address == 'D' || c.address == 'E');
    EXPECT_FALSE(c.title.empty());
    // A command of the field (neither document lists it) says so and names
    // its source; one of a document gives the document's section.
    if (c.from_field())
      EXPECT_EQ(c.section.rfind("field: ", 0), 0u) << c.section;
    else
      EXPECT_EQ(c.section.rfind(d == Dialect::skydroid ? "SkyDroid " : "Topotek ", 0), 0u)
          << c.section;
    EXPECT_NE(c.models, 0);
    EXPECT_EQ(c.models & ~(d == Dialect::skydroid ? skydroid_models : topotek_models), 0);
    EXPECT_FALSE(c.forms.empty());
    EXPECT_EQ(find_command(d, c.ident), &c);
    for (const FormSpec& f : c.forms) {
      EXPECT_TRUE(f.control == 'r' || f.control == 'w');
      EXPECT_LE(f.min_length, f.max_length);
      std::size_t fixed = 0;
      bool rest = false;
      for (std::size_t i = 0; i < f.fields.size(); ++i) {
        const FieldSpec& s = f.fields[i];
        EXPECT_FALSE(s.name.empty());
        if (s.width == 0) {
          EXPECT_EQ(i + 1, f.fields.size()) << s.name << ": width 0 must be last";
          rest = true;
        }
        fixed += s.width;
        if (s.kind == FieldKind::enum_hex || s.kind == FieldKind::enum_char) {
          EXPECT_FALSE(s.enums.empty()) << s.name;
        }
        if (s.kind == FieldKind::le_i16 || s.kind == FieldKind::le_u16 ||
            s.kind == FieldKind::be_i16 || s.kind == FieldKind::be_u16) {
          EXPECT_EQ(s.width, 2) << s.name;
        }
        if (s.kind == FieldKind::le_i32) {
          EXPECT_EQ(s.width, 4) << s.name;
        }
        if (s.kind == FieldKind::u8) {
          EXPECT_EQ(s.width, 1) << s.name;
        }
      }
      if (!f.record.empty()) {
        // Records (the Topotek ODR): counted by the form's last field, an
        // integer of its own bytes, each record of fixed-width binary or
        // hex fields; the form covers no records and as many as fit.
        ASSERT_FALSE(f.fields.empty()) << "records need a count";
        EXPECT_FALSE(rest) << "records follow fixed fields";
        EXPECT_TRUE(is_integer_kind(f.fields.back().kind)) << f.fields.back().name;
        std::size_t width = 0;
        std::set<std::string_view> names;
        for (const FieldSpec& s : f.fields) names.insert(s.name);
        for (const FieldSpec& s : f.record) {
          EXPECT_GT(s.width, 0) << s.name;
          EXPECT_TRUE(names.insert(s.name).second) << s.name << ": a name twice";
          if (s.kind == FieldKind::le_i16 || s.kind == FieldKind::le_u16) {
            EXPECT_EQ(s.width, 2) << s.name;
          }
          width += s.width;
        }
        EXPECT_EQ(fixed, f.min_length) << "a form with records takes none";
        EXPECT_GE(f.max_length, fixed + width) << "a form with records takes one";
      } else if (!rest && !f.fields.empty()) {
        EXPECT_EQ(fixed, f.min_length) << "fields do not fill the form";
        EXPECT_EQ(fixed, f.max_length) << "fields do not fill the form";
      }
    }
  }
}
}  // namespace

TEST(Catalog, SkydroidTableIsConsistent) { check_table(Dialect::skydroid); }
TEST(Catalog, TopotekTableIsConsistent) { check_table(Dialect::topotek); }

TEST(Catalog, EveryDocumentedIdentifierIsPresent) {
  for (const char* id : kSkydroidIdents)
    EXPECT_NE(find_command(Dialect::skydroid, id), nullptr) << "SkyDroid " << id;
  for (const char* id : kTopotekIdents)
    EXPECT_NE(find_command(Dialect::topotek, id), nullptr) << "Topotek " << id;
}

TEST(Catalog, Lookups) {
  EXPECT_EQ(find_command(Dialect::skydroid, "XYZ"), nullptr);
  EXPECT_EQ(find_command(Dialect::skydroid, "ga"), nullptr);
  EXPECT_EQ(find_command(Dialect::unknown, "GAY"), nullptr);
  ASSERT_NE(find_any("GIC"), nullptr);
  EXPECT_EQ(find_any("GIC")->dialect, Dialect::topotek);
  EXPECT_EQ(find_any("PTZ", Dialect::topotek)->dialect, Dialect::topotek);
}

TEST(Catalog, ModelsAndDialects) {
  for (Model m : all_models()) {
    auto parsed = model_from_string(to_string(m));
    ASSERT_TRUE(parsed.has_value());
    EXPECT_EQ(*parsed, m);
  }
  EXPECT_EQ(all_models().size(), 6u);
  EXPECT_EQ(dialect_of(Model::sip), Dialect::topotek);
  EXPECT_EQ(dialect_of(Model::c10pro), Dialect::skydroid);
  EXPECT_FALSE(model_from_string("c99").has_value());
  EXPECT_EQ(dialect_from_string("topotek"), Dialect::topotek);
  EXPECT_FALSE(dialect_from_string("other").has_value());
}

TEST(Catalog, ChooseHeader) {
  EXPECT_EQ(choose_header(Dialect::skydroid, 'G', 12), Header::fixed);
  EXPECT_EQ(choose_header(Dialect::skydroid, 'D', 2), Header::fixed);
  EXPECT_EQ(choose_header(Dialect::skydroid, 'D', 13), Header::variable);
  EXPECT_EQ(choose_header(Dialect::topotek, 'M', 2), Header::variable);
  EXPECT_EQ(choose_header(Dialect::topotek, 'D', 2), Header::fixed);
  EXPECT_EQ(choose_header(Dialect::topotek, 'D', 40), Header::ext8);
  EXPECT_EQ(choose_header(Dialect::topotek, 'D', 400), Header::ext16);
}

// Build then parse every form of every command of both dialects.
TEST(Catalog, BuildParseRoundTrip) {
  int forms = 0;
  for (Dialect d : {Dialect::skydroid, Dialect::topotek}) {
    for (const CommandSpec& c : commands(d)) {
      for (const FormSpec& f : c.forms) {
        SCOPED_TRACE(std::string(to_string(d)) + " " + std::string(c.ident) + " " + f.control);
        std::string data = example_data(f);
        ASSERT_GE(data.size(), f.min_length);
        ASSERT_LE(data.size(), f.max_length);
        bool response = f.role == Role::response;
        char client = d == Dialect::topotek ? 'P' : 'U';
        std::string bytes = build_frame({.header = choose_header(d, c.address, data.size()),
                                         .src = response ? c.address : client,
                                         .dst = response ? client : c.address,
                                         .control = f.control,
                                         .ident = c.ident,
                                         .data = data});
        toptest::ExactBuffer buf(bytes);
        ParseResult r = parse_exact(buf.view());
        ASSERT_EQ(r.status, ParseStatus::frame) << bytes;
        EXPECT_TRUE(r.frame.checksum_ok) << bytes;
        EXPECT_EQ(r.frame.data(), data);
        EXPECT_EQ(build_frame({.header = r.frame.header,
                               .src = r.frame.src,
                               .dst = r.frame.dst,
                               .control = r.frame.control,
                               .ident = r.frame.ident_view(),
                               .data = r.frame.data()}),
                  bytes);
        Decoded dec = decode(r.frame, {.dialect = d});
        EXPECT_EQ(dec.command, &c) << bytes;
        ASSERT_NE(dec.form, nullptr) << bytes;
        // A field form may take what a loose document form also covers
        // (Topotek LRF: 5 digits, inside the document's 3-7 chars).
        if (dec.form != &f && dec.form->from_field() && !f.from_field()) continue;
        ASSERT_EQ(dec.form, &f) << bytes << " decoded with another form";
        for (const auto& x : dec.findings) {
          if (x.code == FindingCode::error_reply) continue;  // ERE is a rejection by design
          EXPECT_EQ(x.severity, Severity::info) << bytes << ": " << x.message;
        }
        // example_data gives a form with records one record
        EXPECT_EQ(dec.fields.size(), f.fields.size() + f.record.size()) << bytes;
        for (const auto& fv : dec.fields) EXPECT_TRUE(fv.valid) << bytes << " " << fv.name();
        ++forms;
      }
    }
  }
  EXPECT_GT(forms, 100);
}

TEST(Catalog, PtzCodeTablesDisagreePerVendor) {
  const CommandSpec* s = find_command(Dialect::skydroid, "PTZ");
  const CommandSpec* t = find_command(Dialect::topotek, "PTZ");
  ASSERT_TRUE(s && t);
  auto name = [](const CommandSpec* c, std::int64_t v) -> std::string_view {
    for (const auto& e : c->forms[0].fields[0].enums)
      if (e.value == v) return e.name;
    return "";
  };
  EXPECT_EQ(name(s, 6), "follow");
  EXPECT_EQ(name(s, 7), "lock");
  EXPECT_EQ(name(t, 6), "lock");
  EXPECT_EQ(name(t, 7), "follow");
}

// Every enum's names come from one table each (src/names.cpp): both ways,
// for every enumerator, and nothing else reads as one.
template <class E, class From>
void expect_names_round_trip(E last, From from) {
  std::set<std::string_view> names;
  for (int i = 0; i <= static_cast<int>(last); ++i) {
    const auto e = static_cast<E>(i);
    const std::string_view n = to_string(e);
    EXPECT_TRUE(names.insert(n).second) << n;
    EXPECT_EQ(from(n), e) << n;
  }
  EXPECT_FALSE(from("nonsense").has_value());
}

TEST(Catalog, EveryEnumNameReadsBack) {
  expect_names_round_trip(Dialect::topotek, dialect_from_string);
  expect_names_round_trip(Model::sip, model_from_string);
  expect_names_round_trip(Role::any, role_from_string);
  expect_names_round_trip(FieldKind::raw, field_kind_from_string);
  expect_names_round_trip(Header::tmp_quirk, header_from_string);
  EXPECT_EQ(to_string(Role::response), "response");
  EXPECT_EQ(to_string(Header::ext8), "#tP");
  EXPECT_EQ(describe(Header::fixed), "fixed, length 2");
  EXPECT_EQ(dialect_from_string("auto"), Dialect::unknown);
  EXPECT_EQ(model_from_string("auto"), Model::unknown);
  EXPECT_EQ(model_list(", ", " or "), "c10, c10pro, c12, c13, c20 or sip");
  EXPECT_EQ(all_models().size(), static_cast<std::size_t>(Model::sip));
}

// The identifier index topdump counts frames by and the catalog finds
// commands by: one numbering, read back by ident_of.
TEST(Catalog, IdentIndexReadsBack) {
  std::set<int> seen;
  for (char a : std::string_view(ident_chars))
    for (char b : {'A', 'Z', '0', '9'})
      for (char c : {'A', 'Y', '1', '8'}) {
        const char id[3] = {a, b, c};
        const int i = ident_index(id);
        ASSERT_GE(i, 0);
        ASSERT_LT(static_cast<std::size_t>(i), ident_slots);
        EXPECT_TRUE(seen.insert(i).second);
        EXPECT_EQ(ident_of(static_cast<std::size_t>(i)), std::string(id, 3));
      }
  EXPECT_EQ(ident_index("GAY"), ident_index(std::string_view("GAY")));
  EXPECT_EQ(ident_index("gay"), -1);
  EXPECT_EQ(ident_index(std::string_view("GA")), -1);
  EXPECT_EQ(ident_index("G#Y"), -1);
}
