// A fresh directory for the files of one test, removed with its files afterwards (engine
// and filter tests of state files and faults).
#pragma once

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <dirent.h>
#include <stdlib.h>
#include <unistd.h>

namespace dem {
namespace testing {

/// A fresh directory for the files of one test.
class TempDir {
public:
  TempDir()
  {
    char pattern[] = "/tmp/rockdem-test-XXXXXX";
    path_ = ::mkdtemp(pattern);
  }
  ~TempDir()
  {
    for (const std::string& f : files()) {
      std::remove((path_ + "/" + f).c_str());
    }
    ::rmdir(path_.c_str());
  }
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  std::vector<std::string> files() const
  {
    std::vector<std::string> names;
    if (DIR* d = ::opendir(path_.c_str())) {
      while (dirent* e = ::readdir(d)) {
        const std::string n = e->d_name;
        if (n != "." && n != "..") {
          names.push_back(n);
        }
      }
      ::closedir(d);
    }
    std::sort(names.begin(), names.end());
    return names;
  }

private:
  std::string path_;
};

} // namespace testing
} // namespace dem

