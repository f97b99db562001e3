#pragma once
// Paths tests read from: the source tree, the build tree, and the shared real data beside the
// project.

#include <string>

namespace testing_support {

std::string sourceDir();
std::string binaryDir();
/// ../shared/data/<relative> from the project root (real data we did not make; never copied in).
std::string sharedData(const std::string& relative);
/// A fresh empty directory under the build tree for one test's output.
std::string freshOutputDir(const std::string& name);
/// The whole content of a file ("" when it cannot be read).
std::string readFile(const std::string& path);

}  // namespace testing_support
