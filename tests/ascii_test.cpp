// Sources are ASCII only (the documents are Chinese; our code quotes them in
// English).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;

TEST(Sources, AsciiOnly) {
  int files = 0;
  for (const char* dir :
       {"protocol", "analyzer", "conformance", "fuzz", "tests", "bench", "tools"}) {
    fs::path root = fs::path(TOPKIT_SOURCE_DIR) / dir;
    if (!fs::exists(root)) continue;
    for (const auto& e : fs::recursive_directory_iterator(root)) {
      if (!e.is_regular_file()) continue;
      auto ext = e.path().extension().string();
      if (ext != ".cpp" && ext != ".hpp" && ext != ".h" && ext != ".txt" && ext != ".lua") continue;
      std::ifstream in(e.path(), std::ios::binary);
      std::string line;
      int n = 0;
      while (std::getline(in, line)) {
        ++n;
        for (unsigned char c : line)
          ASSERT_LT(c, 0x80) << e.path().string() << ":" << n << " has a non-ASCII byte";
      }
      ++files;
    }
  }
  EXPECT_GT(files, 10);
}
