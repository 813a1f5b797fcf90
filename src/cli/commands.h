#pragma once
// One function per subcommand; each takes the arguments after its name and returns the exit code.
#include <string>
#include <vector>

namespace gbl {

int runRenderCommand(const std::vector<std::string>& args);
int runCompareCommand(const std::vector<std::string>& args);
int runDevicesCommand(const std::vector<std::string>& args);
int runEncodingsCommand(const std::vector<std::string>& args);
int runLayoutsCliCommand(const std::vector<std::string>& args);
int runIblCommand(const std::vector<std::string>& args);
int runDiffCommand(const std::vector<std::string>& args);
int runCrossdiffCommand(const std::vector<std::string>& args);
int runSearchCommand(const std::vector<std::string>& args);

}  // namespace gbl
