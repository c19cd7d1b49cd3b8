// Writes the libFuzzer dictionary of the TOP protocol from the catalog, so
// the dictionary has no table of its own:
//
//   topkit_fuzz_dict OUTPUT
//
// Entries: the four headers and the TMP quirk prefix, every address pair,
// the control chars, and for every identifier of both dialects the
// identifier, its control-prefixed form ("wGAY") and a whole header through
// identifier ("#TPUG6wGAY") for each form, plus the documented placeholders
// and enum chars.
#include <algorithm>
#include <cstdio>
#include <set>
#include <string>

#include "top/top.hpp"

using namespace top;

namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c >= 0x20 && c < 0x7F) {
      out += static_cast<char>(c);
    } else {
      char b[8];
      std::snprintf(b, sizeof b, "\\x%02X", c);
      out += b;
    }
  }
  return out + "\"";
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT\n", argv[0]);
    return 2;
  }
  std::set<std::string> entries;
  for (const char* h : {"#TP", "#tp", "#tP", "#Tp", "#PDP16TMP", "#tpDP16wTMP"}) entries.insert(h);
  for (std::string_view s : {std::string_view("\r\n"), std::string_view("\n"),
                             top::error_reply_ident, top::error_reply_data})
    entries.insert(std::string(s));
  const std::string addresses = "UMDEPG";
  for (char a : addresses)
    for (char b : addresses) entries.insert(std::string{a, b});
  for (Dialect d : {Dialect::skydroid, Dialect::topotek}) {
    for (const CommandSpec& c : commands(d)) {
      const std::string ident(c.ident);
      entries.insert(ident);
      for (const FormSpec& f : c.forms) {
        entries.insert(std::string(1, f.control) + ident);
        const std::string data = example_data(f);
        const bool response = f.role == Role::response;
        const char client = top::client_address(d, top::Link::network);
        const char src = response ? c.address : client;
        const char dst = response ? client : c.address;
        BuildSpec spec;
        spec.header = choose_header(d, c.address, data.size());
        spec.src = src;
        spec.dst = dst;
        spec.control = f.control;
        spec.ident = c.ident;
        spec.data = data;
        const std::string frame = build_frame(spec);
        entries.insert(frame.substr(0, std::min<std::size_t>(frame.size(), 10)));
        for (const FieldSpec& fs : f.fields) {
          if (!fs.none.empty()) entries.insert(std::string(fs.none));
          if (fs.kind == FieldKind::enum_char)
            for (const EnumValue& e : fs.enums)
              entries.insert(std::string(1, static_cast<char>(e.value)));
        }
      }
    }
  }
  std::FILE* out = std::fopen(argv[1], "w");
  if (!out) {
    std::perror(argv[1]);
    return 1;
  }
  std::fprintf(out, "# TOP protocol dictionary, generated from the catalog by %s.\n",
               "fuzz/gen_dict.cpp");
  std::size_t n = 0;
  for (const std::string& e : entries) std::fprintf(out, "kw%zu=%s\n", n++, quoted(e).c_str());
  if (std::fclose(out) != 0) {
    std::perror(argv[1]);
    return 1;
  }
  return 0;
}
