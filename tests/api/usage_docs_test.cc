// docs/usage.md shows the examples verbatim: each code block names its file in the comment
// above it (<!-- example: PATH -->) and must equal that file, which the Python and install
// tests run. So a snippet in the docs is always a tested one.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace movseg {
namespace {

struct Snippet {
  std::string file;  // "" when the block names no file
  std::string code;
  int line = 0;      // of the opening fence
};

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<Snippet> snippets(const std::string& markdown) {
  static const std::regex marker(R"(<!-- example: (\S+) -->)");
  std::vector<Snippet> found;
  std::istringstream lines(markdown);
  std::string line, previous;
  Snippet* open = nullptr;
  for (int number = 1; std::getline(lines, line); ++number) {
    if (line.rfind("```", 0) == 0) {
      if (open != nullptr) {
        open = nullptr;
      } else {
        std::smatch match;
        const bool named = std::regex_match(previous, match, marker);
        found.push_back({named ? match[1].str() : "", "", number});
        open = &found.back();
      }
    } else if (open != nullptr) {
      open->code += line + "\n";
    }
    previous = line;
  }
  return found;
}

TEST(UsageDocs, EveryCodeBlockIsATestedExampleFile) {
  const std::string source = MOVSEG_SOURCE_DIR;
  const std::vector<Snippet> blocks = snippets(readFile(source + "/docs/usage.md"));
  ASSERT_GE(blocks.size(), 6u);
  for (const Snippet& block : blocks) {
    ASSERT_FALSE(block.file.empty())
        << "docs/usage.md:" << block.line << ": code block without <!-- example: PATH --> above it";
    EXPECT_EQ(block.code, readFile(source + "/" + block.file))
        << "docs/usage.md:" << block.line << " differs from " << block.file;
  }
}

// README.md also shows command lines and output; its code blocks that name a file must equal it,
// and the C++ and Python snippets must be among them.
TEST(UsageDocs, ReadmeSnippetsAreTheTestedExampleFiles) {
  const std::string source = MOVSEG_SOURCE_DIR;
  int named = 0;
  for (const Snippet& block : snippets(readFile(source + "/README.md"))) {
    if (block.file.empty()) continue;
    ++named;
    EXPECT_EQ(block.code, readFile(source + "/" + block.file))
        << "README.md:" << block.line << " differs from " << block.file;
  }
  EXPECT_GE(named, 2) << "README.md should show examples/minimal/main.cc and a Python example";
}

}  // namespace
}  // namespace movseg
