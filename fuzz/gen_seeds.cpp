// Writes the seed corpora of the protocol targets:
//
//   topkit_fuzz_seeds OUTDIR [VECTOR_DIR]
//
// OUTDIR/<target>/<fnv64 of the content> for: every form of every command of
// both dialects built as the dialect's senders build it (a request from the
// client and a response to it), the documents' own example frames with their
// errata, the firmware quirks of DESIGN.md, and the frames of the JSON test
// vectors in VECTOR_DIR. The stream target gets the same frames joined in
// groups, with separators and noise, behind a chunk-size prefix; the decode
// targets get (selector, command index, form index, data) records.
// Regenerate the checked-in corpora after the catalog grows:
//   build/default/fuzz/topkit_fuzz_seeds fuzz/corpus tests/vectors
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "top/detail/text.hpp"
#include "top/top.hpp"

using namespace top;
namespace fs = std::filesystem;

namespace {

std::string name_of(const std::string& bytes) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char b[20];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(h));
  return b;
}

bool write(const fs::path& dir, const std::string& bytes) {
  fs::create_directories(dir);
  std::ofstream out(dir / name_of(bytes), std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return static_cast<bool>(out);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: %s OUTDIR [VECTOR_DIR]\n", argv[0]);
    return 2;
  }
  const fs::path out = argv[1];
  std::vector<std::string> frames = {
      // The documents' examples, errata included.
      "#TPUG2wPTZ006A",
      "#TPUG2wGSYE276",
      "#TPUG6wGAYEF073288",
      "#tpUG6wGAYEF073288",
      "#TPMU2wERE!!30",
      "#tpUM2wZMC009C",
      "#tpMU4rZOMFFB447",
      "#tpPM5rVSNM33265D",
      "#tpUM8wZFPFFB400320F",
      "#TPUG2rGAC0032",
      "#TPUG2wGAA0136",
      "#tpUG6wGIYEF073290",
      // Field notes: a lying length, swapped reply, lowercase data, CRLF.
      "#tpDU3rVER0105025A",
      "#tpGPCrGACFF36ED5A0048DE",
      "#tpUG6wGAYef073288",
      "#TPUG2wPTZ006A\r\n",
  };
  // The TMP quirk in both forms, and the extended headers.
  const std::string tmp = "0A00B20C00D000E00F0123";
  frames.push_back(with_checksum("#PDP16TMP" + tmp));
  frames.push_back(with_checksum("#tpDP16wTMP" + tmp));
  frames.push_back(with_checksum(std::string("#tPUD") + char(20) + "wGPS" +
                                 std::string("\x10\x27\x00\x00#\x01\x02\x03\x04\x05\x06\x07\x08\x09"
                                             "\x0A\x0B\x0C\x0D\x0E\x0F",
                                             20)));
  frames.push_back(with_checksum(std::string("#TpUD") + char(0) + char(3) + "LOCABC"));

  std::vector<std::string> decode_sky, decode_topo;
  for (Dialect d : {Dialect::skydroid, Dialect::topotek}) {
    const auto table = commands(d);
    for (std::size_t i = 0; i < table.size(); ++i) {
      const CommandSpec& c = table[i];
      for (std::size_t j = 0; j < c.forms.size(); ++j) {
        const FormSpec& f = c.forms[j];
        const std::string data = example_data(f);
        const char client = top::client_address(d, top::Link::network);
        BuildSpec spec;
        spec.header = choose_header(d, c.address, data.size());
        spec.control = f.control;
        spec.ident = c.ident;
        spec.data = data;
        spec.src = f.role == Role::response ? c.address : client;
        spec.dst = f.role == Role::response ? client : c.address;
        frames.push_back(build_frame(spec));
        if (i < 256 && j < 256) {
          std::string rec{'\0', static_cast<char>(i), static_cast<char>(j)};
          (d == Dialect::skydroid ? decode_sky : decode_topo).push_back(rec + data);
        }
      }
    }
  }
  if (argc == 3) {
    for (const auto& e : fs::directory_iterator(argv[2])) {
      if (e.path().extension() != ".json") continue;
      std::ifstream in(e.path());
      const nlohmann::json doc = nlohmann::json::parse(in, nullptr, false);
      if (doc.is_discarded() || !doc.contains("vectors")) {
        std::fprintf(stderr, "%s: not a vector file\n", e.path().c_str());
        return 1;
      }
      for (const auto& v : doc["vectors"])
        if (v.contains("bytes") && v["bytes"].is_string())
          frames.push_back(top::bytes_from_utf8(v["bytes"].get<std::string>()).value_or(""));
    }
  }

  bool ok = true;
  for (const char* t : {"frame", "roundtrip", "differential"})
    for (const std::string& f : frames) ok &= write(out / t, f);
  // Streams: groups of four frames, joined three ways, behind chunk sizes
  // (byte 0 bit 3: flush() after every chunk, the third way).
  static const std::string kJoin[] = {"", "\r\n", "zz#"};
  static const std::string kPrefix[] = {std::string("\x02\x01\x07\x0D", 4),
                                        std::string("\x00\x01", 2), std::string("\x09\x20\x03", 3)};
  for (std::size_t i = 0; i < frames.size(); i += 4) {
    const std::size_t v = (i / 4) % 3;
    std::string s = kPrefix[v];
    for (std::size_t k = i; k < frames.size() && k < i + 4; ++k) s += frames[k] + kJoin[v];
    ok &= write(out / "stream", s);
  }
  for (const std::string& r : decode_sky) ok &= write(out / "decode_skydroid", r);
  for (const std::string& r : decode_topo) ok &= write(out / "decode_topotek", r);
  if (!ok) {
    std::fprintf(stderr, "cannot write under %s\n", out.c_str());
    return 1;
  }
  std::printf("%zu frames, %zu + %zu decode records under %s\n", frames.size(), decode_sky.size(),
              decode_topo.size(), out.c_str());
  return 0;
}
