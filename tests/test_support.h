// Helpers shared by the tests.
#pragma once

#include <string>

namespace movseg::test {

// A fresh empty folder under the system temp dir, removed when the object dies.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }
  std::string operator/(const std::string& name) const { return path_ + "/" + name; }

 private:
  std::string path_;
};

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Runs build/movseg with `arguments` (a shell-quoted string) and captures its output.
CommandResult runCli(const std::string& arguments);

}  // namespace movseg::test
