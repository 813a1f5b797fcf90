#pragma once
namespace gbl {
int runCli(int argc, char** argv);
}
