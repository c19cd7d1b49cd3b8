// The replay main linked into every fuzz target when libFuzzer is not used
// (g++ builds, ctest). Runs LLVMFuzzerTestOneInput once per input:
//
//   fuzz_<target> [--prefix HEX] [--vectors PATH]... PATH...
//
// A PATH is a file or a directory (walked recursively, files in sorted
// order). --vectors PATH takes a JSON test-vector file, or a directory of
// them, ({"vectors":[{"name","bytes",...}]}; each code point <= 0xFF of
// "bytes" is one byte) and runs each vector's bytes, after the bytes of
// --prefix HEX if given (for targets whose input starts with control bytes). Every input is copied
// into a heap block of exactly its size so ASan sees any over-read, as
// libFuzzer does. A missing path, an unreadable file or a path with no
// inputs is an error (exit 2): a replay that silently ran nothing would pass
// for the wrong reason.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "top/detail/text.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);
extern "C" __attribute__((weak)) int LLVMFuzzerInitialize(int* argc, char*** argv);

namespace fs = std::filesystem;

namespace {

void run_one(const std::string& bytes) {
  std::unique_ptr<std::uint8_t[]> copy(new std::uint8_t[bytes.size()]);
  if (!bytes.empty()) std::memcpy(copy.get(), bytes.data(), bytes.size());
  LLVMFuzzerTestOneInput(copy.get(), bytes.size());
}

bool read_file(const fs::path& p, std::string& out) {
  std::ifstream in(p, std::ios::binary);
  if (!in) return false;
  out.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return !in.bad();
}

std::vector<fs::path> files_under(const fs::path& p) {
  std::vector<fs::path> files;
  if (fs::is_directory(p)) {
    for (const auto& e : fs::recursive_directory_iterator(p))
      if (e.is_regular_file() && e.path().filename().string()[0] != '.') files.push_back(e.path());
    std::sort(files.begin(), files.end());
  } else if (fs::exists(p)) {
    files.push_back(p);
  }
  return files;
}

// Calls each(file, bytes) for every file under `p` (those whose extension
// is `ext`, if given), in order, until one returns non-zero. 2 with a
// message when there is none (`what`: what was looked for) or one cannot be
// read.
template <class Each>
int for_each_file(const fs::path& p, std::string_view ext, const char* what, Each each) {
  std::vector<fs::path> files;
  for (const fs::path& f : files_under(p))
    if (ext.empty() || f.extension() == ext) files.push_back(f);
  if (files.empty()) {
    std::fprintf(stderr, "replay: no %s at %s\n", what, p.c_str());
    return 2;
  }
  for (const fs::path& f : files) {
    std::string bytes;
    if (!read_file(f, bytes)) {
      std::fprintf(stderr, "replay: cannot read %s\n", f.c_str());
      return 2;
    }
    if (int rc = each(f, bytes)) return rc;
  }
  return 0;
}

bool unhex(const std::string& hex, std::string& out) {
  if (hex.size() % 2 != 0) return false;
  out.clear();
  for (std::size_t i = 0; i < hex.size(); i += 2) {
    const int hi = top::hex_value(hex[i]), lo = top::hex_value(hex[i + 1]);
    if (hi < 0 || lo < 0) return false;
    out += static_cast<char>(hi * 16 + lo);
  }
  return true;
}

int replay_vectors(const fs::path& p, const std::string& prefix, std::size_t& count) {
  return for_each_file(
      p, ".json", "JSON vector files", [&](const fs::path& f, const std::string& text) {
        nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
        if (doc.is_discarded() || !doc.contains("vectors") || !doc["vectors"].is_array()) {
          std::fprintf(stderr, "replay: %s is not a vector file ({\"vectors\":[...]})\n",
                       f.c_str());
          return 2;
        }
        std::size_t index = 0;
        for (const auto& v : doc["vectors"]) {
          std::optional<std::string> bytes;
          if (!v.contains("bytes") || !v["bytes"].is_string() ||
              !(bytes = top::bytes_from_utf8(v["bytes"].get<std::string>()))) {
            std::fprintf(stderr, "replay: %s: vector %zu has no byte string\n", f.c_str(), index);
            return 2;
          }
          run_one(prefix + *bytes);
          ++count;
          ++index;
        }
        return 0;
      });
}

}  // namespace

int main(int argc, char** argv) {
  if (LLVMFuzzerInitialize) LLVMFuzzerInitialize(&argc, &argv);
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s [--prefix HEX] [--vectors PATH]... PATH...\n", argv[0]);
    return 2;
  }
  std::size_t count = 0;
  std::string prefix;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--prefix") {
      if (i + 1 >= argc || !unhex(argv[++i], prefix)) {
        std::fprintf(stderr, "replay: --prefix needs hex digits\n");
        return 2;
      }
      continue;
    }
    if (arg == "--vectors") {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "replay: --vectors needs a path\n");
        return 2;
      }
      if (int rc = replay_vectors(argv[++i], prefix, count)) return rc;
      continue;
    }
    if (int rc = for_each_file(arg, "", "inputs", [&](const fs::path&, const std::string& bytes) {
          run_one(bytes);
          ++count;
          return 0;
        }))
      return rc;
  }
  std::printf("replayed %zu input(s) through %s\n", count, argv[0]);
  return 0;
}
